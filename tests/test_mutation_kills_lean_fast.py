"""Value tests of cranefe/analysis/operation/fast.py (issue 20, mutation testing): one
trapezoidal step of the lean path written out in loops for numba. Without numba (CI:
the `fast` extra is not in `test`) its functions are plain Python and are tested the
same; with numba they run compiled. For the mutation run numba's JIT is disabled
(NUMBA_DISABLE_JIT=1), so that mutmut's trampolines are plain Python too.

- one step of a load on a vertical rope (sway off, n = 1) by hand: the trapezoidal
  equation z1 = z0 + h v0 + h^2/4 (a0 + a(z1)), a(z) = -g + EA ln((10 - z)/L0)/m,
  solved by scipy's brentq to 1e-15 m, and the step's error estimate
  h^2/12 max(|a1 - a0| / tol, EA/(FORCE_TOL tol) |G (a1 - a0)| / (L max(S0, |S|)))
  with G = dL/dz = -1 (integrate.py, Stepper.error);
- the LU factorisation with partial pivoting and its solve against numpy on matrices
  that need pivoting, and its refusals (singular, non-finite);
- the forces `_forces` against Lean.evaluate and the whole step `FastLean.step` against
  integrate.Stepper.step with Lean (fast=False: the numpy reference, mutation-tested
  against hand values itself: docs/mutation.md, integrate.py and lean.py) on the
  scenes of tests/test_mutation_kills_lean.py (sway on and off, a drum driven, dashpots
  on and off, a slack rope, a moving trolley and slewing jib): the same formulas, so
  equal to rounding (1e-10 of each quantity's scale), with the same Newton iteration
  and tangent counts; and the failures: too few iterations, a non-finite state, a
  singular Newton matrix.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq
from test_mutation_kills_integrate import ROPE, _scene
from test_mutation_kills_lean import PAIRS, _mech

from cranefe.analysis.operation import fast
from cranefe.analysis.operation import integrate as integ
from cranefe.analysis.operation.integrate import Stepper
from cranefe.analysis.operation.lean import Lean
from cranefe.analysis.operation.mechanism import Mechanism
from cranefe.analysis.operation.scene import parse

G = 9.81
REF = 1e-10


def test_available_says_whether_numba_is_installed():
    try:
        import numba  # noqa: F401
        have = True
    except ImportError:
        have = False
    assert fast.available() is have


# ----------------------------------------------------------------- LU

@pytest.mark.parametrize("n", [2, 3, 5])
def test_lu_with_pivoting_solves_as_numpy(n):
    """A matrix with a zero first pivot and rows out of order (partial pivoting must
    swap); the solution to 1e-13 relative (condition ~10)."""
    rng = np.random.default_rng(n)
    A = rng.uniform(-1, 1, (n, n)) + 3 * np.eye(n)[::-1]
    A[0, 0] = 0.0
    b = rng.uniform(-1, 1, n)
    J, piv = A.copy(), np.zeros(n, np.int64)
    assert fast._lu(J, piv)
    x = fast._solve(J, piv, b)
    np.testing.assert_allclose(x, np.linalg.solve(A, b), rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(A @ x, b, rtol=0, atol=1e-13)
    if n > 1:
        # the largest entry of the first column is the pivot
        assert piv[0] == int(np.argmax(np.abs(A[:, 0])))
        # L (unit lower) U reproduces the row-permuted matrix
        L = np.tril(J, -1) + np.eye(n)
        U = np.triu(J)
        P = A.copy()
        for k in range(n):
            P[[k, piv[k]]] = P[[piv[k], k]]
        np.testing.assert_allclose(L @ U, P, rtol=0, atol=1e-13)


def test_lu_refuses_singular_and_non_finite_matrices():
    piv = np.zeros(3, np.int64)
    assert not fast._lu(np.array([[1.0, 2, 3], [2, 4, 6], [1, 0, 1]]), piv)
    assert not fast._lu(np.zeros((3, 3)), piv)
    assert not fast._lu(np.array([[np.inf, 0, 0], [0, 1, 0], [0, 0, 1.0]]), piv)
    assert not fast._lu(np.array([[np.nan, 0, 0], [0, 1, 0], [0, 0, 1.0]]), piv)
    assert not fast._lu(np.array([[1.0, 0, 0], [0, 1, 0], [0, 0, 0.0]]), piv)
    assert fast._lu(np.array([[1e-300, 0, 0], [0, 1, 0], [0, 0, 1.0]]), piv)


# ----------------------------------------------------------------- one step by hand

def _rope_stepper(tol=1.0e-6):
    model = _scene("rope", ROPE, f"  duration: 1\n  tolerance: {tol}\n", "{sway: false}")
    mech = Mechanism(model, parse(model))
    return model, mech, Stepper(mech, parse(model), model.length_scale, fast=False)


@pytest.mark.parametrize("jerk", [None, 40.0])
def test_one_step_of_a_load_on_its_rope_by_hand(jerk):
    """The step's solution and error by hand (module docstring); brentq to 1e-15 m;
    Newton stops at a correction below 1e-4 tol, so q1 to 1e-12 m, a1 = 4/h^2 (...) to
    1e-12 x 4/h^2 = 2.5e-7 m/s^2 at h = 4 ms; the error estimate to 1e-6 relative."""
    model, mech, st = _rope_stepper()
    EA, m = 4.0e5, 200.0
    L0 = 5.0 * math.exp(-m * G / EA)
    fl = fast.FastLean(mech)
    q0, v0 = np.array([5.0]), np.array([0.3])
    taut = mech.taut0.copy()
    a0 = np.array([-G + EA * math.log(5.0 / L0) / m])
    h = 0.004

    def acc(z):
        return -G + EA * math.log((10.0 - z) / L0) / m
    z1 = brentq(lambda z: z - (q0[0] + h * v0[0] + h * h / 4 * (a0[0] + acc(z))),
                4.0, 6.0, xtol=1e-15, rtol=1e-15)
    a1 = acc(z1)
    v1 = v0[0] + h / 2 * (a0[0] + a1)
    out = fl.step(h, q0, v0, a0, h, taut, None if jerk is None else np.array([jerk]), st.M,
                  st.newton_tol, integ.NEWTON_MAX, st.fscale, st.sfloor, st.tol)
    status, q1, vv1, aa1, err, its, tg, ev = out
    assert status == 0
    assert q1[0] == pytest.approx(z1, abs=1e-12)
    assert vv1[0] == pytest.approx(v1, abs=1e-9)
    assert aa1[0] == pytest.approx(a1, abs=3e-7)
    tol = 1e-6 * model.length_scale
    L1 = 10.0 - z1
    S1 = EA * math.log(L1 / L0)
    e_pos = abs(a1 - a0[0]) / tol
    e_force = EA / (integ.FORCE_TOL * 1e-6) * abs(a1 - a0[0]) / (L1 * max(m * G, abs(S1)))
    assert e_force > e_pos
    assert err == pytest.approx(max(e_pos, e_force) * h * h / 12, rel=1e-6)
    # without the force part: the position error alone
    out = fl.step(h, q0, v0, a0, h, taut, None, st.M, st.newton_tol, integ.NEWTON_MAX,
                  None, st.sfloor, st.tol)
    assert out[4] == pytest.approx(e_pos * h * h / 12, rel=1e-6)
    # a slack rope: the load falls freely (exact: a = -g), no force error
    out = fl.step(h, q0, v0, a0, h, np.array([False]), None, st.M, st.newton_tol,
                  integ.NEWTON_MAX, st.fscale, st.sfloor, st.tol)
    assert out[0] == 0
    assert out[1][0] == pytest.approx(q0[0] + h * v0[0] + h * h / 4 * (a0[0] - G), abs=1e-13)
    assert out[3][0] == pytest.approx(-G, abs=1e-8)
    assert out[4] == pytest.approx(abs(-G - a0[0]) / tol * h * h / 12, rel=1e-6)
    # the returned forces are those of the last iterate (q, v before the correction)
    assert ev.F[0] == pytest.approx(m * acc(ev._q[0]), rel=1e-12)
    assert ev._v[0] == pytest.approx(2 / h * (ev._q[0] - q0[0]) - v0[0], rel=1e-12)
    # the cost: the fresh tangent's correction, then one iteration confirming it
    assert (its, tg) == (2, 1)


def test_failures_of_the_step():
    """Status 1 for: Newton not converged within newton_max iterations; a non-finite
    state; a singular Newton matrix (no mass, no stiffness: a slack rope with M = 0)."""
    model, mech, st = _rope_stepper()
    fl = fast.FastLean(mech)
    q0, v0 = np.array([5.0]), np.array([0.3])
    taut = mech.taut0.copy()
    a0 = np.array([0.0])
    args = (st.M, st.newton_tol)
    out = fl.step(0.01, q0, v0, a0, 0.01, taut, None, *args, 1, st.fscale, st.sfloor, st.tol)
    assert out[0] == 1 and out[5] == 1 and out[6] == 1
    out = fl.step(0.01, q0, v0, a0, 0.01, taut, None, *args, 2, st.fscale, st.sfloor, st.tol)
    assert out[0] == 0 and out[5] == 2 and out[6] == 1
    out = fl.step(0.01, np.array([np.nan]), v0, a0, 0.01, taut, None, *args, 12,
                  st.fscale, st.sfloor, st.tol)
    assert out[0] == 1 and out[5] == 1 and out[6] == 0
    out = fl.step(0.01, q0, v0, a0, 0.01, np.array([False]), None, np.zeros(1),
                  st.newton_tol, 12, st.fscale, st.sfloor, st.tol)
    assert out[0] == 1 and out[5] == 1 and out[6] == 1


# ----------------------------------------------------------------- the reference

def _states(mech, rng, t):
    nr = len(mech.ropes)
    for taut in (np.ones(nr, bool), np.r_[False, np.ones(nr - 1, bool)],
                 np.r_[np.ones(nr - 1, bool), False]):
        q = mech.q0 + rng.uniform(-0.05, 0.05, mech.n)
        v = rng.uniform(-0.3, 0.3, mech.n)
        yield q, v, taut


@pytest.mark.parametrize("case, eff", PAIRS)
def test_forces_equal_lean(case, eff):
    """_forces (with and without the tangent) against Lean.evaluate."""
    mech = _mech(case, eff)
    lean = Lean(mech)
    fl = fast.FastLean(mech)
    Dm, Af, extra, EA, beta, Fg, D, falls, span_rope = fl._c
    rng = np.random.default_rng(5)
    n = mech.n
    for t in (0.5, 1.5, 3.7):
        kt = lean.kin(t)
        for q, v, taut in _states(mech, rng, t):
            a = lean.evaluate(t, q, v, taut, kt)
            for tangent in (True, False):
                K, C = np.full((n, n), 7.0), np.full((n, n), 7.0)
                out = fast._forces(q, v, Dm, kt[2], np.zeros(0) if kt[3] is None else kt[3],
                                   Af, extra, kt[7], EA, kt[8], taut, beta, Fg, D,
                                   falls, span_rope, bool(lean.damped), tangent, K, C)
                F, Gm, l, e, L, lam, loglam, S, Sd, edot, cL = out
                s = np.abs(a.S).max() + np.abs(a.Sd).max() + np.abs(mech.Fg).max()
                for x, y, sc in ((F, a.F, s), (Gm, a._G, 10.0), (l, a._l, 60.0),
                                 (e, a._e, 1.0), (L, a.L, 60.0), (lam, a._lam, 1.0),
                                 (loglam, a._loglam, 1.0), (S, a.S, s), (Sd, a.Sd, s),
                                 (edot, a.edot, 10.0), (cL, a._cL, np.abs(a._cL).max())):
                    np.testing.assert_allclose(x, y, rtol=0, atol=REF * sc)
                if tangent:
                    np.testing.assert_allclose(K, a.K, rtol=0, atol=REF * np.abs(a.K).max())
                    np.testing.assert_allclose(C, a.C, rtol=0,
                                               atol=REF * (np.abs(a.C).max() + 1))
                else:
                    assert (K == 7.0).all() and (C == 7.0).all()


@pytest.mark.parametrize("case, eff", PAIRS)
def test_step_equals_the_numpy_step(case, eff):
    """FastLean.step against Stepper.step (fast=False) from the same states, with and
    without the jerk predictor, h = 10 ms and 50 ms (more Newton iterations, some fresh
    tangents): q1, v1, a1, the error, the last iterate's forces and state, its powers
    and energies; the iteration and tangent counts equal."""
    mech = _mech(case, eff)
    spec = parse(mech.model)
    ref = Stepper(mech, spec, mech.model.length_scale, fast=False)
    assert type(ref.ops) is Lean
    fl = fast.FastLean(mech)
    rng = np.random.default_rng(3)
    for t in (0.3, 1.7, 3.6):
        for q, v, taut in _states(mech, rng, t):
            a, _ = ref.accel(t, q, v, taut)
            for jerk in (None, rng.uniform(-1, 1, mech.n)):
                for h in (0.01, 0.05):
                    n0 = (ref.newton_iterations, ref.tangents)
                    x = ref.step(t, q, v, a, h, taut, jerk)
                    y = fl.step(t + h, q, v, a, h, taut, jerk, ref.M, ref.newton_tol,
                                integ.NEWTON_MAX, ref.fscale, ref.sfloor, ref.tol)
                    assert (x is None) == (y[0] != 0)
                    assert y[5] == ref.newton_iterations - n0[0]
                    assert y[6] == ref.tangents - n0[1]
                    if x is None:
                        continue
                    ev, fv = x[3], y[7]
                    s = np.abs(ev.S).max() + np.abs(ev.Sd).max() + np.abs(mech.Fg).max()
                    for u, w, sc in ((x[0], y[1], 60.0), (x[1], y[2], 1.0),
                                     (x[2], y[3], np.abs(x[2]).max() + 1.0),
                                     (ev.S, fv.S, s), (ev.Sd, fv.Sd, s), (ev.F, fv.F, s),
                                     (ev.L, fv.L, 60.0), (ev.L0, fv.L0, 60.0),
                                     (ev.edot, fv.edot, 10.0), (ev._G, fv._G, 10.0),
                                     (ev._St, fv._St, s), (ev._cL, fv._cL, 1e10),
                                     (ev._q, fv._q, 60.0), (ev._v, fv._v, 1.0),
                                     (ev.theta, fv.theta, 1.0), (ev.omega, fv.omega, 1.0),
                                     (ev._l, fv._l, 60.0), (ev._e, fv._e, 1.0),
                                     (ev._lam, fv._lam, 1.0), (ev._loglam, fv._loglam, 1.0)):
                        np.testing.assert_allclose(w, u, rtol=0, atol=REF * sc)
                    assert y[4] == pytest.approx(x[4], rel=1e-8, abs=1e-12)
                    assert fv.t == t + h and fv._taut is taut and fv._kt is fl.kin(t + h)
                    ref.ops.powers(ev)
                    fl.powers(fv)
                    P = max(abs(ev.P_drive), abs(ev.P_diss), abs(ev.P_wound), 1.0)
                    for u, w in ((ev.P_drive, fv.P_drive), (ev.P_diss, fv.P_diss),
                                 (ev.P_wound, fv.P_wound), (ev.T_guided, fv.T_guided)):
                        assert w == pytest.approx(u, rel=0, abs=REF * P)
                    Ea, Eb = ref.ops.energy(ev, taut), fl.energy(fv, taut)
                    np.testing.assert_allclose(Eb, Ea, rtol=0,
                                               atol=REF * (max(map(abs, Ea)) + 1))
