"""Elastic structure riding on the mechanism (operation scenes with
`effects: {structure: flexible}`, cranefe/analysis/operation/flexible.py,
docs/operations.md "Elastic structure") against exact references: the linear core
(`cranefe modes`) at the static state, a cantilever spun about its root (Southwell
stiffening, against a converged Rayleigh-Ritz solution of the continuous beam), the
static tip deflection under gravity, energy conservation and the integrator's order."""

from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
from test_operation import mechanism, scene
import scipy.linalg as sla

from cranefe.analysis.modal import modes
from cranefe.analysis.operation.integrate import Stepper, simulate
from cranefe.analysis.operation.lean import Generic
from cranefe.analysis.operation.mechanism import Mechanism
from cranefe.analysis.operation.scene import parse
from cranefe.cli import main
from cranefe.model import load

G = 9.81
MODELS = Path(__file__).resolve().parents[1] / "models" / "operations"

# a planar jib (beam, lumped mass) fixed at A on the ground, a load on a rope from a
# drum over the jib's tip sheave T
JIB = """cranefe: 1
name: planar elastic jib with a hanging load
plane: xz
gravity: [0, 0, GVAL]
nodes:
  A:    [0.0, 0.0, 20.0]
  D:    [-2.0, 0.0, 20.0]
  T:    [12.0, 0.0, 20.0]
  HOOK: [12.0, 0.0, 12.0]
ground: [A, D]
masses: {HOOK: 1500}
drums:
  hoist: {node: D, radius: 0.2, inertia: 5.0}
ropes:
  hoist_rope: {EA: 2.0e7, path: [hoist, T, HOOK]}
members:
  jib: {type: beam, nodes: [A, T], E: 2.1e+11, A: 0.012, Iy: IYVAL, rho: 7850,
        elements: NEL, mass: MASS}
"""

# a cantilever along x from the hub O, the hub turning about z through O
ROTOR = """cranefe: 1
name: rotating cantilever
gravity: [0, 0, 0]
nodes:
  O: [0, 0, 0]
  T: [10.0, 0, 0]
ground: []
bodies:
  hub: {mass: 10, com: [0, 0, 0], inertia: [1, 1, 1], nodes: [O]}
joints:
  - {name: spin, type: hinge, bodies: [ground, hub], at: O, axis: [0, 0, 1]}
members:
  blade: {type: beam, nodes: [O, T], E: 2.1e+11, G: 8.0e+10, A: 0.1, Iy: 1.0e-6,
          Iz: 1.0e-6, J: 2.0e-6, rho: 78.5, orientation: [0, 0, 1], elements: NEL,
          mass: lumped}
"""
EI_ROT, RHOA_ROT, L_ROT = 2.1e5, 7.85, 10.0


def write(tmp_path, model_text, analysis, name="s.yaml", effects="{structure: flexible}",
          **subs):
    return scene(tmp_path, model_text, analysis, effects, name, **subs)


def jib(tmp_path, Iy=2.0e-2, nel=6, mass="lumped", analysis="  duration: 1\n", name="j",
        g=G):
    return load(write(tmp_path, JIB, analysis, name=f"{name}.yaml", IYVAL=Iy, NEL=nel,
                      MASS=mass, GVAL=-g))


# ----------------------------------------------------------------- linear core

def _linear_gap(model):
    mech = mechanism(model)
    ev = mech.evaluate(0.0, mech.q0, np.zeros(mech.n), mech.taut0)
    assert np.abs(ev.F).max() < 1e-8 * 1500 * G             # the static state: at rest
    w = np.sqrt(np.abs(np.sort(sla.eigvals(ev.K, np.diag(mech.M)).real)))
    lin = modes(model.with_effects(drive="held")).omega
    assert len(w) == len(lin)
    return np.abs(w / lin - 1).max(), np.abs(w / lin - 1)[1]


def test_linearisation_equals_the_linear_core(tmp_path):
    """Linearised at its static state (tangent K and the lumped masses M) the engine has
    `cranefe modes`' frequencies (drum held): the jib's bending modes with the load's
    pendulum and hoisting modes. Not to round-off: the engine linearises about the
    deflected static state, the linear core about the model's geometry. With the rope
    from the drum over the tip sheave, the span D-T tilts by (tip deflection)/14 m, which
    changes at first order how the tip's deflection stretches the rope (its row
    dL/dx_T = e_DT - e_TH): measured 8.2e-6 at a tip deflection of 2.6 mm (asserted
    1e-4), 3.9e-4 on a jib ten times softer and ten times less at a tenth of gravity
    (asserted 7-13: first order). The load hanging straight from the tip (no tilting
    span) leaves only the second-order terms of the members' strain: 3e-6 at the soft
    jib's 2.6 cm and a hundred times less at a tenth of gravity (asserted 70-130)."""
    stiff, _ = _linear_gap(jib(tmp_path, 2.0e-2, name="stiff"))
    assert stiff < 1e-4
    _, soft = _linear_gap(jib(tmp_path, 2.0e-3, name="soft"))
    _, light = _linear_gap(jib(tmp_path, 2.0e-3, name="light", g=G / 10))
    assert 7 < soft / light < 13
    direct = JIB.replace("path: [hoist, T, HOOK]", "path: [T, HOOK]")
    gaps = []
    for g in (G, G / 10):
        m = load(write(tmp_path, direct, "  duration: 1\n", name=f"d{g}.yaml", IYVAL=2e-3,
                       NEL=6, MASS="lumped", GVAL=-g))
        gaps.append(_linear_gap(m)[0])
    assert gaps[0] < 1e-5 and 70 < gaps[0] / gaps[1] < 130


TRUSS = """cranefe: 1
name: planar truss jib with a hanging load and a tie spring
plane: xz
gravity: [0, 0, GVAL]
nodes:
  A:    [0.0, 0.0, 20.0]
  B:    [0.0, 0.0, 18.0]
  C:    [6.0, 0.0, 20.0]
  E:    [6.0, 0.0, 19.0]
  T:    [12.0, 0.0, 20.0]
  HOOK: [12.0, 0.0, 12.0]
ground: [A, B]
masses: {HOOK: 1500}
ropes:
  hoist_rope: {EA: 2.0e7, path: [T, HOOK]}
members:
  chords: {type: truss, pairs: [[A, C], [C, T], [B, E], [E, T], [A, E], [C, E]],
           E: 2.1e+11, A: 0.004, rho: 7850, mass: lumped}
springs:
  - {name: tie, type: axial, nodes: [B, C], stiffness: 5.0e7}
"""


def test_truss_and_spring_structure_equals_the_linear_core(tmp_path):
    """Trusses and an axial spring between structure nodes (the truss kernel): the
    engine's frequencies at its static state against `cranefe modes`: 1.5e-4 at a tip
    deflection of 2.6 mm, ten times less at a tenth of gravity (asserted 7-13): the
    members' directions turn with the deflection (deflection / 6 m), which changes
    their axial stiffness's directions at first order (the linear core keeps the
    model's geometry)."""
    gaps = []
    for g in (G, G / 10):
        m = load(write(tmp_path, TRUSS, "  duration: 1\n", name=f"tr{g}.yaml", GVAL=-g))
        gaps.append(_linear_gap(m)[0])
    assert gaps[0] < 3e-4 and 7 < gaps[0] / gaps[1] < 13


# ----------------------------------------------------------------- spinning beam

def _ritz(W, inplane, n=12):
    """First bending frequency of the continuous uniform cantilever turning at W about
    an axis through its root normal to it (zero hub radius): EI w'''' - (N w')' -
    [rho A W^2 w in the plane of rotation] = rho A w^2 w, N(x) = rho A W^2 (L^2 - x^2)/2
    (Southwell), by Rayleigh-Ritz on xi^2 P_k(2 xi - 1), k < n (clamped root), with
    60-point Gauss quadrature (exact for these polynomials): converged to 1e-12."""
    x, wq = np.polynomial.legendre.leggauss(60)
    xi, wq = (x + 1) / 2, wq / 2
    B, B1, B2 = [], [], []
    s = np.polynomial.Polynomial([-1.0, 2.0])
    for k in range(n):
        c = np.zeros(k + 1)
        c[k] = 1.0
        q = np.polynomial.Polynomial(np.polynomial.legendre.leg2poly(c))(s) * \
            np.polynomial.Polynomial([0.0, 0.0, 1.0])
        B.append(q(xi))
        B1.append(q.deriv()(xi))
        B2.append(q.deriv(2)(xi))
    B, B1, B2 = map(np.array, (B, B1, B2))
    L = L_ROT
    K = EI_ROT / L**3 * (B2 * wq) @ B2.T
    Gm = RHOA_ROT * W**2 * L / 2 * (B1 * wq * (1 - xi**2)) @ B1.T
    M = RHOA_ROT * L * (B * wq) @ B.T
    w2 = sla.eigh(K + Gm, M, eigvals_only=True)[0] - (W**2 if inplane else 0.0)
    return float(np.sqrt(w2))


def test_southwell_coefficient_of_the_first_flapwise_mode():
    """The Southwell coefficient of the cantilever's first mode (zero hub radius),
    alpha = d(w^2)/d(W^2) at W = 0 = int (L^2 - x^2)/2 phi'^2 dx / int phi^2 dx with the
    exact mode phi = cosh bx - cos bx - s (sinh bx - sin bx), b L = 1.87510..., by mpmath
    at 30 digits: 1.193336..., the 1.193 of the literature (e.g. Wright, Smith, Thresher
    & Wang, J. Appl. Mech. 49 (1982) 197-202); the Ritz solution's slope agrees to 1e-7."""
    mp.mp.dps = 30
    b = mp.findroot(lambda x: mp.cos(x) * mp.cosh(x) + 1, mp.mpf("1.875"))
    s = (mp.cosh(b) + mp.cos(b)) / (mp.sinh(b) + mp.sin(b))

    def phi(x):
        return mp.cosh(b * x) - mp.cos(b * x) - s * (mp.sinh(b * x) - mp.sin(b * x))

    def dphi(x):
        return b * (mp.sinh(b * x) + mp.sin(b * x) - s * (mp.cosh(b * x) - mp.cos(b * x)))
    alpha = float(mp.quad(lambda x: (1 - x**2) / 2 * dphi(x) ** 2, [0, 1])
                  / mp.quad(lambda x: phi(x) ** 2, [0, 1]))
    assert abs(alpha - 1.193336) < 1e-6
    w0 = _ritz(0.0, False)
    assert abs(w0 / (float(b) ** 2 * np.sqrt(EI_ROT / (RHOA_ROT * L_ROT**4))) - 1) < 1e-10
    W = 1e-2
    assert abs((_ritz(W, False) ** 2 - w0**2) / W**2 - alpha) < 1e-5


def _spinning(tmp_path, nel, W):
    """The engine's first flapwise (out of the plane of rotation) and in-plane bending
    frequencies of the cantilever turning steadily at W: its tangent K, gyroscopic C and
    M in the steady state (Newton on F = 0 in the turning frame), the quadratic
    eigenproblem M s^2 + C s + K = 0."""
    model = load(write(tmp_path, ROTOR, "  duration: 1\n  drives:\n    spin: {hinge: spin, "
                       f"profile: {{type: table, speed: [[0, {W}], [1, {W}]]}}}}\n",
                       name=f"rot{nel}_{W}.yaml", NEL=nel))
    mech = mechanism(model)
    n, t = mech.n, 0.3
    q, v = mech.q0.copy(), np.zeros(n)
    for _ in range(30):
        ev = mech.evaluate(t, q, v, mech.taut0)
        dq = np.linalg.solve(ev.K, ev.F)
        q += dq
        if np.abs(dq).max() < 1e-14:
            break
    ev = mech.evaluate(t, q, v, mech.taut0)
    assert np.abs(ev.F).max() < 1e-6
    labels = mech.flex.labels()
    zc = np.flatnonzero([lb.endswith(".uz") for lb in labels])
    xy = np.flatnonzero([not lb.endswith(".uz") for lb in labels])
    # out of the plane of rotation (z) and in it (x, y) are uncoupled: checked
    assert np.abs(ev.K[np.ix_(zc, xy)]).max() < 1e-9 * np.abs(ev.K).max()
    assert np.abs(ev.C[np.ix_(zc, xy)]).max() == 0.0

    def lowest(idx):
        k = len(idx)
        M = np.diag(mech.M[idx])
        Z = np.zeros((k, k))
        A = np.block([[Z, np.eye(k)], [-np.linalg.solve(M, ev.K[np.ix_(idx, idx)]),
                                       -np.linalg.solve(M, ev.C[np.ix_(idx, idx)])]])
        lam = np.linalg.eigvals(A)
        assert np.abs(lam.real).max() < 1e-7 * np.abs(lam).max()   # undamped, stable
        return lam.imag[lam.imag > 1e-6].min()
    flap, lag = lowest(zc), lowest(xy)
    return flap, lag


def test_spinning_cantilever_stiffens_southwell(tmp_path):
    """A cantilever (10 m, EI = 2.1e5 N m^2, rho A = 7.85 kg/m: w0 = 5.7508 rad/s) on a
    hub turning at W = 3 rad/s about an axis through its root: the engine's flapwise and
    in-plane frequencies against the continuous beam's (Rayleigh-Ritz, converged):
    flapwise `w^2 = w0^2 + alpha W^2`, in-plane `w^2 = w0^2 + (alpha - 1) W^2` with the
    secant alpha(W = 3) = 1.18947 (the first-order coefficient 1.19334 is W -> 0; the
    Southwell line bends down by 0.3 % at W/w0 = 0.52). Compared is the coefficient
    (w^2 - w0^2)/W^2 with both frequencies of the same mesh, which removes most of
    the lumped-mass discretisation error of w0 (-1.8 % at 16 elements): what remains
    converges as h^2 (16 to 32 elements: error / 4, asserted > 3) and is below 1e-4 at
    32 elements. Without the geometric stiffness of the current axial forces the
    flapwise coefficient would be 0 and the in-plane -1 (linear floating frame)."""
    W = 3.0
    ref_f = (_ritz(W, False) ** 2 - _ritz(0.0, False) ** 2) / W**2
    ref_l = (_ritz(W, True) ** 2 - _ritz(0.0, True) ** 2) / W**2
    assert abs(ref_f - 1.189466) < 1e-5 and abs(ref_l - (ref_f - 1)) < 1e-12
    err = {}
    for nel in (16, 32):
        f0, l0 = _spinning(tmp_path, nel, 0.0)
        assert abs(f0 / l0 - 1) < 1e-10
        f, lag = _spinning(tmp_path, nel, W)
        err[nel] = (abs((f**2 - f0**2) / W**2 - ref_f), abs((lag**2 - l0**2) / W**2 - ref_l))
    assert max(err[32]) < 1e-4
    assert err[16][0] / err[32][0] > 3 and err[16][1] / err[32][1] > 3


# ----------------------------------------------------------------- statics

def test_static_tip_deflection_under_gravity(tmp_path):
    """A cantilever jib (no load, no rope) under its own weight: the engine's static
    state has the tip deflection of an Euler-Bernoulli cantilever under the lumped nodal
    weights P_j at x_j, `sum P_j x_j^2 (3 L - x_j) / (6 EI)` (cubic elements are exact
    for nodal loads), to 1e-9 (the second-order terms of the strain energy change a free
    cantilever's transverse deflection only by O(slope^2) ~ 1e-8 of it); and the
    uniform-load formula `q L^4 / (8 EI)` times the lumping's exact factor: the sum is
    the trapezoidal rule of `int q x^2 (3 L - x) / (6 EI) dx`, whose Euler-Maclaurin
    error for a cubic is `h^2/12 (f'(L) - f'(0)) = q L^2 h^2 / (24 EI)`, so the tip
    deflection is `q L^4/(8 EI) (1 + 1/(3 n^2))` (n elements) - asserted to 1e-9."""
    text = JIB.replace("GVAL", str(-G)).replace("masses: {HOOK: 1500}\n", "").replace(
        "  hoist_rope: {EA: 2.0e7, path: [hoist, T, HOOK]}\n", "").replace(
        "ropes:\n", "").replace("  HOOK: [12.0, 0.0, 12.0]\n", "").replace(
        "drums:\n  hoist: {node: D, radius: 0.2, inertia: 5.0}\n", "")
    nel = 8
    model = load(write(tmp_path, text, "  duration: 1\n", IYVAL=2.0e-3, NEL=nel,
                       MASS="lumped"))
    mech = mechanism(model)
    uz = mech.q0[mech.nc + mech.nJ + mech.flex.labels().index("T.uz")]
    L, EI, q = 12.0, 2.1e11 * 2.0e-3, 7850 * 0.012 * G
    x = np.linspace(0, L, nel + 1)
    P = np.full(nel + 1, q * L / nel)
    P[0] = P[-1] = q * L / nel / 2
    ref = -np.sum(P * x**2 * (3 * L - x)) / (6 * EI)
    assert abs(uz / ref - 1) < 1e-9
    assert abs(uz / (-q * L**4 / (8 * EI)) - (1 + 1 / (3 * nel**2))) < 1e-9


# ----------------------------------------------------------------- energy, order

def _release(tmp_path, tol, name, duration=0.1):
    model = jib(tmp_path, 2.0e-3, nel=2, name=name,
                analysis=f"  duration: {duration}\n  tolerance: {tol}\n")
    mech = mechanism(model)
    q = mech.q0.copy()
    q[mech.nc + mech.nJ + mech.flex.labels().index("T.uz")] += 0.02    # 2 cm up
    q[0] += 0.05                                                        # the load aside
    return simulate(model, initial={"q": q}), mech


def test_energy_is_conserved_and_the_integrator_is_second_order(tmp_path):
    """The jib released 2 cm up with the load 5 cm aside, no drives, no damping: the
    energy balance (kinetic + gravity + rope + strain energy of the members) closes to
    < 2e-6 at tolerance 1e-8 and falls with the tolerance (measured 8.6e-6, 2.2e-6,
    5.1e-7 over 0.1 s at 1e-6, 1e-7, 1e-8, 199, 407, 859 steps); the load's position at
    the end converges at the trapezoidal rule's order 2 in the number of steps: the
    differences of runs at 1e-6, 1e-7, 1e-8 (Richardson: the error of a run is its
    difference to the next one times 1/(1 - 2^-p) ~ 4/3 at p = 2, steps x2 per decade)
    give the observed order (asserted 1.7-2.6; measured 1.86 over 0.1 s, 1.82 over
    0.15 s, 2.2 against a run at 1e-10 over 0.5 s). 0.1 s (two periods of the rope's
    axial mode, whose ~7 ms steps cost the time) rather than 0.15 s: a third fewer
    steps. A softer rope (EA 2e6 or 5e6) would cost still fewer but its tiny end
    differences (1e-8) no longer show a clean order (measured 1.5-1.6), so the rope
    keeps its EA."""
    runs = [_release(tmp_path, tol, f"t{tol}")[0] for tol in (1e-6, 1e-7, 1e-8)]
    energy = [r.energy_error for r in runs]
    assert energy[2] < 2e-6 and energy[2] < energy[1] < energy[0]
    steps = [r.steps for r in runs]
    diff = [np.abs(runs[k].mass_position[-1] - runs[k + 1].mass_position[-1]).max()
            for k in (0, 1)]
    order = np.log(diff[0] / diff[1]) / np.log(steps[1] / steps[0])
    assert 1.7 < order < 2.6, (steps, diff)


def test_energy_balance_with_a_prescribed_slewing(tmp_path):
    """A spin-up of the cantilever hub (trapezoid, 0.5 rad/s in 1 s, then steady), the
    beam at rest and straight at t = 0: the hub's prescribed motion does work on the
    elastic beam (the power of the frame's motion `sum w . m (x'' - g)`, w the carried
    velocity) and sets it vibrating; the balance closes at order 2 in the steps
    (measured 1.1e-5, 2.3e-6, 5.2e-7, 1.1e-7 at tolerances 1e-7 .. 1e-10, 2 elements,
    2 s; asserted < 1e-6 at 1e-9 and a fall of at least 3x from 1e-8). 1.2 s (the
    spin-up and 0.2 s of the steady turning, where the error is made) instead of 2 s:
    measured 2.37e-6 and 5.28e-7 (a fall of 4.5x) against 2.35e-6 and 5.17e-7 over
    2 s, with 0.6 of the steps."""
    errs = []
    for tol in ("1.0e-8", "1.0e-9"):
        model = load(write(tmp_path, ROTOR, f"  duration: 1.2\n  tolerance: {tol}\n  drives:\n"
                           "    spin: {hinge: spin, profile: {type: trapezoid, distance: 1.0, "
                           "v_max: 0.5, a_max: 0.5}}\n", name=f"spinup{tol}.yaml", NEL=2))
        r = simulate(model)
        errs.append(r.energy_error)
        assert r.energy["work_drives"] > 0
    assert errs[1] < 1e-6 and errs[0] / errs[1] > 3


BOOM = """cranefe: 1
name: elastic boom luffed by a profile
plane: xz
nodes:
  F:    [0.0, 0.0, 2.0]
  D:    [-1.0, 0.0, 2.0]
  BT:   [14.1421, 0.0, 16.1421]
  HOOK: [14.1421, 0.0, 8.0]
ground: [D]
masses: {HOOK: 800}
bodies:
  base: {mass: 100, com: [0, 0, 2], inertia: 10, nodes: [F]}
joints:
  - {name: luff, type: hinge, bodies: [ground, base], at: F, axis: [0, -1, 0],
     range_deg: [-30, 30]}
drums:
  hoist: {node: D, radius: 0.2, inertia: 5.0}
ropes:
  hoist_rope: {EA: 1.0e6, path: [hoist, BT, HOOK]}
members:
  boom: {type: beam, nodes: [F, BT], E: 2.1e+11, A: 0.006, Iy: 4.0e-3, rho: 7850,
         elements: 3, mass: lumped}
"""


def test_energy_balance_of_an_elastic_boom_luffed_by_a_profile(tmp_path):
    """A 20 m elastic boom at 45 deg on a hinge luffed up by an S-curve (10 deg), a
    load on a rope over its tip: the frame turns about a horizontal axis, so gravity
    turns in it (R^T g) and the frame's Euler and centrifugal terms act with the
    rope's pull. The energy balance (the luffing's work on the boom and through the
    ropes) closes to < 1e-6 at tolerance 1e-8 and falls about four times at 1e-9
    (twice the steps: second order; measured 3.2e-7 and 7.1e-8 over 4 s, 790 and
    1646 steps). The rope's EA is 1e6 (a 0.2 m stretch; the balance does not depend
    on it) and the boom's Iy 4e-3 (still bent by the luffing and the rope's pull at
    its tip, its bare cantilever frequency 5.9 Hz instead of 1.9 Hz): with the former EA 1e7 and Iy 4e-4 the same check took 1342 and 2843
    steps (measured 5.2e-7, 1.3e-7, asserted < 1.5e-6); EA 1e6 with Iy 4e-4 measured
    1.43e-6, too near that bound, hence the stiffer boom and the bound 1e-6."""
    err = []
    for tol in (1e-8, 1e-9):
        model = load(write(tmp_path, BOOM, f"  duration: 4\n  tolerance: {tol}\n  drives:\n"
                           "    luff: {hinge: luff, profile: {type: s_curve, distance_deg: "
                           "10, v_max_deg: 5, a_max_deg: 5, j_max_deg: 10}}\n",
                           name=f"boom{tol}.yaml"))
        r = simulate(model)
        assert r.energy["work_drives"] > 0
        err.append(r.energy_error)
    assert err[0] < 1e-6 and err[1] < err[0] / 2.5


# ----------------------------------------------------------------- refusals, example

def test_lean_does_not_claim_an_elastic_structure(tmp_path):
    model = jib(tmp_path)
    mech = mechanism(model)
    st = Stepper(mech, parse(model), model.length_scale)
    assert isinstance(st.ops, Generic) and not st.fast


@pytest.mark.parametrize("case, words", [
    ("consistent", "mass: lumped"),
    ("trolley", "trolley travelling along an elastic jib"),
    ("torque", "joint coordinate"),
])
def test_refused_cases_exit_2(tmp_path, capsys, case, words):
    if case == "consistent":
        path = write(tmp_path, JIB, "  duration: 1\n", IYVAL=2e-2, NEL=2, MASS="consistent",
                     GVAL=-G)
    else:
        text = ROTOR.replace("  T: [10.0, 0, 0]\n", "  T: [10.0, 0, 0]\n  K: [5.0, 0, 0]\n")
        text = text.replace("joints:\n", "  trolley: {mass: 10, com: [5, 0, 0], inertia: "
                            "[1, 1, 1], nodes: [K]}\njoints:\n  - {name: travel, type: "
                            "slider, bodies: [hub, trolley], at: K, axis: [1, 0, 0], "
                            "range: [0, 9]}\n")
        drive = ("    t: {slider: travel, profile: {type: trapezoid, distance: 1, v_max: 1,"
                 " a_max: 1}}\n" if case == "trolley" else "    s: {hinge: spin, torque: 1.0}\n")
        path = write(tmp_path, text, "  duration: 1\n  drives:\n" + drive, NEL=2)
    assert main(["simulate", str(path)]) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err


def test_example_elastic_jib_crane(tmp_path):
    """models/operations/elastic_jib_crane_cycle.yaml, its first 3 s (the hoist start,
    where the largest rope force of the cycle is; the whole cycle runs in `cranefe study
    operation_flexible`): the coordinates, the energy balance, the hoist rope's dynamic
    factor (pinned: 1.1005, at 0.9 s)."""
    import dataclasses
    model = load(MODELS / "elastic_jib_crane_cycle.yaml")
    model = dataclasses.replace(model, analysis={**model.analysis, "duration": 3.0})
    r = simulate(model)
    d = r.to_dict()
    assert d["dofs"] == 2 * 3 + 8 * 3 - 3
    assert r.energy_error < 1e-6
    assert d["dynamic_factor"]["hoist_rope"] == pytest.approx(1.0998, abs=2e-3)


def test_study_operation_flexible_quick(tmp_path, capsys):
    """`cranefe study operation_flexible --quick` (the example's first 3 s, rigid and
    elastic jib): one row per structure, the elastic run has the jib's coordinates, both
    energy balances close, the CSV's ratio is the two CPU times'."""
    import csv
    assert main(["study", "operation_flexible", "--quick", "--out", str(tmp_path)]) == 0
    rows = list(csv.DictReader(open(tmp_path / "operation_flexible.csv")))
    assert [r["structure"] for r in rows] == ["rigid", "elastic"]
    rigid, elastic = rows
    assert int(rigid["dofs"]) == 3 and int(elastic["dofs"]) == 27
    assert all(float(r["energy_error"]) < 1e-6 for r in rows)
    ratio = float(elastic["cpu_s"]) / float(rigid["cpu_s"])
    assert float(elastic["cpu_vs_rigid"]) == pytest.approx(ratio, rel=1e-5)
    assert abs(float(elastic["dynamic_factor"]) / float(rigid["dynamic_factor"]) - 1) < 0.01


def test_stiff_structure_tends_to_the_rigid_engine(tmp_path):
    """The example's first 3 s (the hoist start) with the jib 100 times stiffer (E and
    G x 100) against the same crane made rigid (the jib's nodes on the superstructure,
    `rigid_variant`, run by the rigid engine): the hoist rope's peak force and the
    load's travel over the 3 s agree to the jib's remaining compliance: peak force
    5.1e-5 (asserted 2e-4; 5e-5 also over the first 22 s, hoist and slew; the example's
    own jib differs by 1.5e-3), travel 1.0e-3 of its 1 m (asserted 2e-3: the jib, even
    100 times stiffer, is in series with the 2-fall rope (~8 % of its stiffness), which
    shifts the phase of the hoisting mode's ringing at the end)."""
    import dataclasses
    from cranefe.studies.operation_flexible import rigid_variant
    model = load(MODELS / "elastic_jib_crane_cycle.yaml")
    model = dataclasses.replace(model, analysis={**model.analysis, "duration": 3.0})
    stiff = dataclasses.replace(model, members=tuple(
        dataclasses.replace(m, E=100 * m.E, G=100 * m.G) for m in model.members))
    rig, el = simulate(rigid_variant(model)), simulate(stiff)
    k = list(rig.rope_names).index("hoist_rope")
    assert abs(el.rope_force_max[k] / rig.rope_force_max[k] - 1) < 2e-4
    move = [r.mass_position[-1] - r.mass_position[0] for r in (el, rig)]
    assert np.abs(move[0] - move[1]).max() < 2e-3 * np.abs(move[1]).max()


ARM = """cranefe: 1
name: spun arm with an elastic tip beam
plane: xz
gravity: [0, 0, 0]
nodes:
  O: [0, 0, 0]
  A: [3.0, 0, 0]
  N: [5.0, 0, 0]
ground: []
masses: {N: 100.0}
bodies:
  arm: {mass: 50, com: [1.5, 0, 0], inertia: 40, nodes: [O, A]}
joints:
  - {name: spin, type: hinge, bodies: [ground, arm], at: O, axis: [0, 1, 0]}
members:
  tip: {type: beam, nodes: [A, N], E: 2.0e7, A: 0.01, Iy: 1.0e-4, rho: 1.0, elements: 1,
        mass: lumped}
"""


def test_static_state_is_at_rest_before_a_move_that_starts_at_once(tmp_path):
    """A soft beam (tip mass 100 kg, k = 3 EI / l^3 = 750 N/m) at the end of an arm
    turned by a trapezoid (a_max 0.5 rad/s^2) that starts at t = 0 and, in a second run,
    at 0.5 s: both start from rest, undeflected, so the tip's deflection across the arm
    is the same history shifted by 0.5 s (to the integration's accuracy: measured 9.1e-7
    m at tolerance 1e-8, 6e-8 m at 1e-9, asserted 1e-5 m of a 0.74 m peak reached at
    2.42 s; 3 s of the move instead of 4 s and tolerance 1e-8 instead of 1e-9: a third
    of the steps, the bound still 10x the measured shift). Before the fix the static
    state of the run starting at 0 was solved with the arm's acceleration just after 0
    and began bent by the Euler load m a R / k = 0.33 m, its peak 0.42 m instead of 0.74."""
    out = {}
    for start in (0.0, 0.5):
        (tmp_path / "arm.yaml").write_text(ARM)
        (tmp_path / f"s{start}.yaml").write_text(
            "cranefe: 1\nscene: t\nmodel: arm.yaml\neffects: {structure: flexible}\n"
            f"analysis:\n  type: operation\n  duration: {3.0 + start}\n  tolerance: 1e-8\n"
            "  output_step: 0.01\n  drives:\n    s: {hinge: spin, profile: {type: "
            f"trapezoid, distance: 1.0, v_max: 0.5, a_max: 0.5, start: {start}}}}}\n")
        model = load(tmp_path / f"s{start}.yaml")
        assert np.abs(Mechanism(model, parse(model)).q0).max() == 0.0
        res = simulate(model)
        P, th = res.mass_position[:, 0], res.drive_position[:, 0]
        out[start] = (res.times, np.sin(th) * P[:, 0] + np.cos(th) * P[:, 2])
    (t0, z0), (t1, z1) = out[0.0], out[0.5]
    assert np.abs(z0).max() == pytest.approx(0.743, abs=2e-3)
    assert np.abs(z0 - np.interp(t0 + 0.5, t1, z1)).max() < 1e-5
