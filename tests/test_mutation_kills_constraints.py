"""Kill tests for cranefe/analysis/operation/constraints.py (tools/mutation.py
constraints; docs/testing.md, "Mutation testing"): the inextensible ropes' stepper and
the massless blocks' helpers, on states small enough to write out by hand, in seconds.

Before these tests only tests/test_operation_inextensible.py and
tests/test_operation_massless.py reached the module (the pendulum and slewing runs take
tens of seconds together). References, none computed by the module:

* the planar pendulum of length l on an inextensible rope from S: constraint
  g = |x - S| - L0, its row G = e^T (e the unit vector S -> load), g' = e . v, and
  gamma = (|v|^2 - (e . v)^2) / l (d^2 |x - S| / dt^2 with x'' = 0); the rope force of a
  consistent state S = -m g . e + m |v_perp|^2 / l (W = 1/m in (1), (2)); tension
  stiffness S / l (I - e e^T); the M-orthogonal projection of an equal-mass point is
  radial; a jerk removes the radial velocity with the impulse m e . v and dissipates
  m (e . v)^2 / 2;
* along the released pendulum's circle S = m g (3 cos th - 2 cos th0) (energy) and its
  rate dS/dt = -3 m g sin(th) th';
* a load on a drum hauling in at R w: a jerk gives the load the rope's speed, impulse
  m (R w - v), dissipated m (R w - v)^2 / 2, the drum's work P R w;
* a massless block on two falls above a sling: equilibrium 2 S_hoist = S_sling with the
  Hencky tension EA ln(L / L0), solved with brentq; its velocity when the drum reels
  in, from differentiating that equilibrium by hand.
"""

import math
import types

import numpy as np
import pytest
from test_operation_massless import BLOCK
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from test_operation import WINCH, mechanism, scene

from cranefe.analysis.operation import constraints as C
from cranefe.analysis.operation.integrate import Stepper, simulate
from cranefe.analysis.operation.scene import parse
from cranefe.errors import AnalysisError
from cranefe.model import load

G = 9.81
M = 100.0
PENDULUM = """cranefe: 1
name: pendulum on an inextensible rope
plane: xz
nodes:
  S: [0, 0, 10]
  H: [0, 0, 0]
ground: [S]
masses: {H: 100}
ropes:
  r: {EA: 1.0e9, path: [S, H]}
"""
INEXT = "{rope_elasticity: false}"


def stepper(tmp_path, text, analysis, effects=INEXT, name="s.yaml", **subs):
    model = load(scene(tmp_path, text, analysis, effects=effects, name=name, **subs))
    mech = mechanism(model)
    spec = parse(model)
    cls = C.ConstrainedStepper if mech.inextensible else Stepper
    return cls(mech, spec, model.length_scale), mech


@pytest.fixture
def pend(tmp_path):
    return stepper(tmp_path, PENDULUM, "  duration: 2\n  tolerance: 1.0e-6\n")


# a state off the constraint (l = 9 m, not 10), moving
Q = np.array([9 * math.sin(0.7), 10 - 9 * math.cos(0.7)])
V = np.array([1.3, -0.4])
E = np.array([math.sin(0.7), -math.cos(0.7)])          # S -> load, unit


def test_pendulum_geometry_and_rates_by_hand(pend):
    """g = l - 10, G = e, g' = e . v, gamma = (|v|^2 - (e . v)^2) / l (fixed pivot)."""
    st, mech = pend
    assert st.nJ == 0 and st.ops is st and not st.fast
    geo = st.geometry(0.3, Q, V, st.kin(0.3))
    np.testing.assert_allclose(geo["l"], [9.0], rtol=1e-14)
    np.testing.assert_allclose(geo["e"][0][[0, 2]], E, atol=1e-15)
    np.testing.assert_allclose(geo["L"] - geo["L0"], [-1.0], atol=1e-13)
    np.testing.assert_allclose(geo["G"], [E], atol=1e-15)
    ev_ = E @ V
    np.testing.assert_allclose(geo["gdot"], [ev_], rtol=1e-14)
    np.testing.assert_allclose(geo["gamma"], [(V @ V - ev_ ** 2) / 9.0], rtol=1e-13)
    np.testing.assert_allclose(geo["X"][mech.free[0]][[0, 2]], Q, rtol=1e-15)
    np.testing.assert_allclose(geo["V"][mech.free[0]][[0, 2]], V, rtol=1e-15)
    # the recorder's view: span lengths and places
    ev = st.evaluate(0.3, Q, V, np.array([True]))
    np.testing.assert_allclose(st.span_lengths(ev), [9.0], rtol=1e-14)
    vp2 = V @ V - ev_ ** 2                     # the recorder's state: the multiplier
    np.testing.assert_allclose(ev.S, [M * G * math.cos(0.7) + M * vp2 / 9.0], rtol=1e-13)
    X = st.place(0.3, Q, V)[0]
    np.testing.assert_allclose(X[mech.free[0]][[0, 2]], Q, rtol=1e-15)
    # the tension stiffness d(G^T S)/dq = S / l (I - e e^T)
    S = np.array([500.0])
    np.testing.assert_allclose(st._tension_stiffness(geo, S),
                               500.0 / 9.0 * (np.eye(2) - np.outer(E, E)), atol=1e-12)


def test_multipliers_and_acceleration_by_hand(pend):
    """S = m g cos th + m |v_perp|^2 / l at any state, a = (F - G^T S) / m; a slack rope
    (no active row) leaves the free fall; its event function is the strain l / L0 - 1,
    a taut rope's S / S_scale (S_scale = m g, the static force)."""
    st, _ = pend
    vp2 = V @ V - (E @ V) ** 2
    S = M * G * math.cos(0.7) + M * vp2 / 9.0
    ev = st.state(0.3, Q, V, np.array([True]))
    np.testing.assert_allclose(ev.S, [S], rtol=1e-13)
    np.testing.assert_allclose(ev._a, (np.array([0.0, -M * G]) - E * S) / M, atol=1e-13)
    np.testing.assert_allclose(st.stretch(ev), [S / (M * G)], rtol=1e-13)
    free = st.state(0.3, Q, V, np.array([False]))
    np.testing.assert_array_equal(free.S, [0.0])
    np.testing.assert_allclose(free._a, [0.0, -G], rtol=1e-15)
    np.testing.assert_allclose(st.stretch(free), [9.0 / 10.0 - 1.0], rtol=1e-14)
    a, ev2 = st.accel(0.3, Q, V, np.array([True]))
    np.testing.assert_allclose(a, ev._a, rtol=1e-15)
    T, Vg, U = st.energy(ev2, np.array([True]))
    np.testing.assert_allclose([T, Vg, U], [0.5 * M * V @ V, M * G * Q[1], 0.0],
                               rtol=1e-14)


def test_force_rate_along_the_circle(pend):
    """On the circle at th with th' from the energy of a release at 60 deg:
    dS/dt = -3 m g sin(th) th' (forward difference over 2e-7 s: truncation
    delta S'' / 2 ~ 1e-7 of S', rtol 1e-5)."""
    st, _ = pend
    th, th0 = 0.4, math.radians(60)
    w = -math.sqrt(2 * G / 10 * (math.cos(th) - math.cos(th0)))     # swinging down
    q = np.array([10 * math.sin(th), 10 - 10 * math.cos(th)])
    v = 10 * w * np.array([math.cos(th), math.sin(th)])
    _, ev = st.accel(0.0, q, v, np.array([True]))
    np.testing.assert_allclose(ev.S, [M * G * (3 * math.cos(th) - 2 * math.cos(th0))],
                               rtol=1e-12)
    F, dS, lst = ev._fr
    np.testing.assert_allclose(dS, [-3 * M * G * math.sin(th) * w], rtol=1e-5)
    np.testing.assert_allclose(F, ev.S, rtol=1e-15)
    assert lst == list(F)
    assert st.powers(ev) is ev and ev._fr[1] is dS          # computed once


def test_projection_is_radial_and_removes_the_radial_velocity(pend):
    """Equal masses: the M-orthogonal projection onto |x - S| = 10 is the radial point;
    g' = 0 removes e . v."""
    st, _ = pend
    q, v = st.consistent(0.0, Q, V, np.array([True]))
    np.testing.assert_allclose(q, [10 * E[0], 10 + 10 * E[1]], atol=1e-12)
    np.testing.assert_allclose(v, V - (E @ V) * E, atol=1e-14)
    q1, v1 = st.project(0.0, Q, V, np.array([0]), st.kin(0.0), once=True)
    np.testing.assert_allclose(q1, [10 * E[0], 10 + 10 * E[1]], atol=1e-12)  # radial
    np.testing.assert_allclose(v1, V - (E @ V) * E, atol=1e-14)
    # nothing taut: unchanged
    q3, v3 = st.project(0.0, Q, V, np.array([], int), st.kin(0.0))
    assert q3 is Q and v3 is V
    with pytest.raises(AnalysisError, match="cannot be projected"), \
            np.errstate(invalid="ignore", divide="ignore"):
        st.consistent(0.0, np.array([0.0, 10.0]), V, np.array([True]))


VEE = """cranefe: 1
name: a load held by two inextensible ropes in a V
plane: xz
nodes:
  A: [-5, 0, 10]
  B: [5, 0, 10]
  H: [0, 0, 0]
ground: [A, B]
masses: {H: 100}
ropes:
  a: {EA: 1.0e9, path: [A, H]}
  b: {EA: 1.0e9, path: [B, H]}
"""


def test_projection_onto_two_ropes(tmp_path):
    """Two ropes in a V hold the load at H = (0, 10 below): from 0.3 m, 0.2 m off, Newton
    projects back onto H (the circles' intersection) to 1e-12 m; `once` makes a single
    correction, which leaves the second-order residual of the curved constraints
    (|g| ~ 0.3^2 / 11 ~ 1e-2: between 1e-6 and 0.1 m)."""
    st, _ = stepper(tmp_path, VEE, "  duration: 1\n")
    act = np.array([0, 1])
    q0 = np.array([0.3, 0.2])
    q, _ = st.project(0.0, q0, np.zeros(2), act, st.kin(0.0))
    np.testing.assert_allclose(q, [0.0, 0.0], atol=1e-12)
    q1, _ = st.project(0.0, q0, np.zeros(2), act, st.kin(0.0), once=True)
    g = st.geometry(0.0, q1, np.zeros(2), st.kin(0.0))
    r = np.abs(g["L"] - g["L0"]).max()
    assert 1e-6 < r < 0.1, r


def test_jerk_of_a_pendulum_rope(pend):
    """A slack rope come tight with the load moving outwards: impulse P = m e . v, the
    radial velocity removed, m (e . v)^2 / 2 dissipated, no work (fixed pivot); with
    the load above the pivot (th = 150 deg, v tangential after the jerk) the rope's
    force m g cos th < 0: it separates again; a rope gone slack: nothing."""
    st, _ = pend
    q = np.array([10 * E[0], 10 + 10 * E[1]])
    taut = np.array([True])
    v1, note, W, D = st.switch(0.0, q, V, taut, 0)
    P = M * (E @ V)
    np.testing.assert_allclose(v1, V - (E @ V) * E, atol=1e-14)
    assert note == f": jerk, impulse {P:.7g} N s"
    assert W == 0.0
    np.testing.assert_allclose(D, 0.5 * M * (E @ V) ** 2, rtol=1e-12)
    assert taut[0]
    th = math.radians(150)
    e = np.array([math.sin(th), -math.cos(th)])
    qa = np.array([10 * e[0], 10 + 10 * e[1]])
    va = 0.1 * np.array([math.cos(th), math.sin(th)]) + 2.0 * e
    taut = np.array([True])
    v1, note, W, D = st.switch(0.0, qa, va, taut, 0)
    assert not taut[0] and note == f": jerk, impulse {M * 2.0:.7g} N s (separates again)"
    np.testing.assert_allclose(v1, va - 2.0 * e, atol=1e-14)
    # horizontal rope (th = 90 deg), tangential speed with m v^2 / l = 0.5 N: after the
    # jerk the rope holds 0.5 N (> 0): it stays taut
    e = np.array([1.0, 0.0])
    vt = math.sqrt(0.5 * 10 / M)
    taut = np.array([True])
    v1, note, W, D = st.switch(0.0, np.array([10.0, 10.0]), np.array([1.0, vt]), taut, 0)
    assert taut[0] and note == f": jerk, impulse {M * 1.0:.7g} N s", note
    np.testing.assert_allclose(st.state(0.0, np.array([10.0, 10.0]), v1, taut).S, [0.5],
                               rtol=1e-12)
    slack = np.array([False])
    assert st.switch(0.0, q, V, slack, 0) == (V, "", 0.0, 0.0)


def test_crossing_and_error_estimate(pend):
    """Events: a taut rope with S < 0, a slack one stretched by more than 1e-10 (not by
    1e-11, the projection's rounding); the error h^2/12 |a1 - a0| / (tol l_scale)."""
    st, _ = pend
    mk = lambda taut, S, L: types.SimpleNamespace(_taut=np.array(taut), S=np.array(S),
                                                  L=np.array(L), L0=np.array([10.0]))
    assert st.crossing(mk([True], [1.0], [10.0]), np.array([True])) is None
    assert list(st.crossing(mk([True], [-1e-3], [10.0]), np.array([True]))) == [0]
    assert st.crossing(mk([False], [0.0], [10.0 + 1e-10]), np.array([False])) is None
    assert list(st.crossing(mk([False], [0.0], [10.0 + 1e-8]), np.array([False]))) == [0]
    assert st.crossing(mk([False], [0.0], [9.0]), np.array([False])) is None
    assert st.m_alltaut(np.array([True])) and not st.m_alltaut(np.array([True, False]))
    a0, a1 = np.array([0.0, 1.0]), np.array([0.5, -2.0])
    h = 0.01
    ls = st.lscale
    np.testing.assert_allclose(st.error(h, a0, a1), 3.0 / (1e-6 * ls) * h * h / 12.0,
                               rtol=1e-14)
    assert st.tol == 1e-6 * ls and st.newton_tol == 1e-4 * st.tol
    assert st.gtol == 1e-13 * ls


def _short_pendulum():
    """The run (not cached: mutmut's forked runs must integrate with the mutant)."""
    import tempfile
    from pathlib import Path
    tmp = Path(tempfile.mkdtemp(prefix="kill-constraints-"))
    model = load(scene(tmp, PENDULUM, "  duration: 2.0\n  tolerance: 1.0e-7\n"
                       "  output_step: 0.05\n", effects=INEXT))
    th0 = math.radians(60)
    return simulate(model, initial={"q": np.array([10 * math.sin(th0),
                                                   10 - 10 * math.cos(th0)]),
                                    "v": np.zeros(2)})


def test_short_pendulum_run_rope_force():
    """2 s of the 60 deg pendulum released from rest at tolerance 1e-7 (through the
    bottom at ~1.7 s): S = m g (3 cos th - 2 cos th0) at every sample to 1e-4 m g
    (measured 1.7e-5: the trapezoidal rule's second order, docs/operations.md), th
    against th'' = -(g/l) sin th by solve_ivp (rtol 1e-12) to 1e-4 rad (measured
    2.7e-5), on the circle to 1e-7 l, the energy balance to 1e-4 (measured 1.5e-5), no rope event."""
    res = _short_pendulum()
    th0 = math.radians(60)
    P = res.mass_position[:, 0]
    th = np.arctan2(P[:, 0], 10.0 - P[:, 2])
    S = res.rope_force[:, 0]
    err = np.abs(S - M * G * (3 * np.cos(th) - 2 * math.cos(th0))).max() / (M * G)
    assert err < 1e-4, err
    assert np.abs(np.hypot(P[:, 0], 10 - P[:, 2]) - 10).max() < 1e-6
    ref = solve_ivp(lambda t, y: [y[1], -G / 10 * math.sin(y[0])], (0, 2.0), [th0, 0.0],
                    rtol=1e-12, atol=1e-14, dense_output=True).sol(res.times)[0]
    assert np.abs(th - ref).max() < 1e-4, np.abs(th - ref).max()
    assert th[-1] < -0.1                        # it has swung through the bottom
    assert res.energy_error < 1e-4
    assert not [e for e in res.events if "rope" in e[1]]
    # the cost, a deterministic count (no timing): Newton converges in 2-3 iterations
    # per step and no step is rejected (measured 223 steps, 0 rejected, 617
    # iterations); a crippled Newton (wrong sign, tangent or stop) still reaches the
    # accuracy above through tiny steps, so only these counts show it. The iterations
    # are reported (`newton_iterations` of the JSON document).
    assert res.steps < 300 and res.rejected <= 5, (res.steps, res.rejected)
    assert 2.0 <= res.newton_iterations / (res.steps + res.rejected) <= 4.0


def test_jerk_by_a_hauling_drum(tmp_path):
    """The load (no sway) moving up at 0.5 m/s below a drum (R = 0.5 m) hauling in at
    2 rad/s, 1 m/s of rope: a jerk gives it the rope's speed 1 m/s, impulse
    m (R w - v) = 500 N s, the drum's work P R w, dissipated m (R w - v)^2 / 2; the
    force limits at the table's breakpoint t = 1 from the left (m (g + 1)) and the
    right (m g)."""
    st, mech = stepper(tmp_path, WINCH, "  duration: 3\n  drives:\n    hoist: {drum: hoist, "
                       "profile: {type: table, speed: [[0, 0], [1, 2], [3, 2]]}}\n",
                       effects="{rope_elasticity: false, sway: false}", Z=20.0,
                       MASS=1000, EAVAL=1.0e9)
    m, t = 1000.0, 2.0
    # the load where the rope is at its length at t (drum at 3 rad: 1.5 m hauled in;
    # dg/dz = -1 for the vertical rope above the load)
    geo = st.geometry(t, mech.q0, np.zeros(1), st.kin(t))
    q = mech.q0 + (geo["L"] - geo["L0"])
    np.testing.assert_allclose(q, [21.5], rtol=1e-14)
    taut = np.array([True])
    v1, note, W, D = st.switch(t, q, np.array([0.5]), taut, 0)
    np.testing.assert_allclose(v1, [1.0], rtol=1e-13)
    P = m * (1.0 - 0.5)
    assert note == f": jerk, impulse {P:.7g} N s", note
    np.testing.assert_allclose(W, P * 1.0, rtol=1e-13)
    np.testing.assert_allclose(D, 0.5 * m * 0.5 ** 2, rtol=1e-12)
    ev = st.evaluate(t, q, np.array([1.0]), taut)
    np.testing.assert_allclose(st.span_lengths(ev), [2.0, 40 - 21.5], rtol=1e-13)
    # breakpoint at t = 1: acceleration 2 rad/s^2 * R = 1 m/s^2 before, 0 after
    geo = st.geometry(1.0, mech.q0, np.zeros(1), st.kin(1.0))
    q1 = mech.q0 + (geo["L"] - geo["L0"])
    v1 = np.array([0.5])
    left = st.state(1.0, q1, v1, taut, side=-1)
    np.testing.assert_allclose(left.S, [m * (G + 1.0)], rtol=1e-7)
    right = st.state(1.0, q1, v1, taut)
    np.testing.assert_allclose(right.S, [m * G], rtol=1e-7)
    a, ev, jumped = st.limit(1.0, q1, v1, left._a, left, taut)
    assert jumped and ev._side == 1
    np.testing.assert_allclose(ev.S, [m * G], rtol=1e-7)
    np.testing.assert_allclose(a, [0.0], atol=1e-6)
    a, ev, jumped = st.limit(1.5, q1, v1, left._a, left, taut)
    assert not jumped and ev is left
    # the left-limit kinematics only at a breakpoint
    k = st.kin_side(1.5, -1)
    assert k is st.kin(1.5)


# ------------------------------------------------------------------ massless blocks
EA_H, EA_S, R_DRUM, W_DRUM = 1.0e7, 5.0e6, 0.5, 0.4


def _block_equilibrium(zL, L0h, L0s):
    """zB with 2 EA_h ln(L_h / L0h) = EA_s ln(l_s / L0s), L_h = 5 + 2 (20 - zB),
    l_s = zB - zL (the block on the vertical through S: falls and sling vertical)."""
    f = lambda zB: 2 * EA_H * math.log((5 + 2 * (20 - zB)) / L0h) \
        - EA_S * math.log((zB - zL) / L0s)
    return brentq(f, zL + 1.0, 19.0, xtol=1e-14, rtol=1e-15)


def test_massless_block_static_split_and_velocity(tmp_path):
    """The block moved into equilibrium from 5 cm off (the load 1 cm below its static
    place): zB by brentq on the Hencky tensions (to 1e-10 m: Newton's 1e-14 stop), the
    block's x on the vertical; its velocity with the drum reeling in at w = 0.4 rad/s,
    L0h' = -R w / lambda_ref, the load held: differentiating the equilibrium,
    zB' = -2 EA_h (L0h'/L0h) / (4 EA_h / L_h + EA_s / l_s) (to 1e-6: the forward
    difference over 1e-7 of the duration); the predictor's acceleration (v - v0) / h."""
    st, mech = stepper(tmp_path, BLOCK, f"  duration: 4\n  drives:\n    hoist: {{drum: "
                       f"hoist, profile: {{type: table, speed: [[0, {W_DRUM}]]}}}}\n",
                       effects="{}")
    assert list(mech.qy) == [2, 3]
    L0h, L0s = mech.L0_ref
    t = 0.5
    lam = 25.0 / L0h              # the drum winds rope at the reference stretch:
    L0h_t = L0h - R_DRUM * W_DRUM * t / lam        # L0 = L0_ref - R theta / lambda_ref
    q = mech.q0.copy()
    q[1] -= 0.01
    q[2] += 0.03
    q[3] -= 0.05
    taut = np.array([True, True])
    qe, ve = C.algebraic_state(st, t, q, np.zeros(4), taut)
    # the load moving up at 0.2 m/s as well (the drum's and the load's parts add):
    # zB' = (EA_s / l_s) zL' / (4 EA_h / L_h + EA_s / l_s) from the load
    _, ve2 = C.algebraic_state(st, t, q, np.array([0.0, 0.2, 0.0, 0.0]), taut)
    zB = _block_equilibrium(q[1], L0h_t, L0s)
    np.testing.assert_allclose(qe[3], zB, atol=1e-10)
    np.testing.assert_allclose(qe[2], 0.0, atol=1e-10)
    np.testing.assert_array_equal(qe[:2], q[:2])
    Lh, ls = 5 + 2 * (20 - zB), zB - q[1]
    vz = -2 * EA_H * (-R_DRUM * W_DRUM / lam / L0h_t) / (4 * EA_H / Lh + EA_S / ls)
    np.testing.assert_allclose(ve[3], vz, rtol=1e-6)
    assert abs(ve[2]) < 1e-9 * abs(vz)
    vz_load = EA_S / ls * 0.2 / (4 * EA_H / Lh + EA_S / ls)
    np.testing.assert_allclose(ve2[3], vz + vz_load, rtol=1e-6)
    np.testing.assert_array_equal(ve2[:2], [0.0, 0.2])
    np.testing.assert_array_equal(ve[:2], 0.0)
    # algebraic_velocity directly: the other coordinates' v and a kept
    ev = st.ops.evaluate(t, qe, np.zeros(4), taut, st.ops.kin(t))
    v0 = np.array([0.0, 0.0, 0.0, 0.01])
    a_in = np.array([1.0, 2.0, 3.0, 4.0])
    v, a = C.algebraic_velocity(st, t, qe, np.zeros(4), a_in, v0, 0.1, ev, taut)
    np.testing.assert_allclose(v[3], vz, rtol=1e-6)
    np.testing.assert_allclose(a[3], (v[3] - 0.01) / 0.1, rtol=1e-12)
    np.testing.assert_array_equal(a[:2], a_in[:2])
    np.testing.assert_array_equal(a_in, [1.0, 2.0, 3.0, 4.0])     # not written
    # a block held by nothing: exit 1 naming it and the time
    with pytest.raises(AnalysisError, match=r"at t = 1\.25 s the massless block\(s\) B "):
        C._solve_blocks(st, 1.25, np.zeros((2, 2)), np.zeros(2))
    # both ropes slack: nothing holds the block (through the helpers)
    for call in (lambda: C.algebraic_state(st, t, qe, np.zeros(4), np.array([False, False])),
                 lambda: C.algebraic_velocity(st, t, qe, np.zeros(4), a_in, v0, 0.1,
                                              st.ops.evaluate(t, qe, np.zeros(4),
                                                              np.array([False, False]),
                                                              st.ops.kin(t)),
                                              np.array([False, False]))):
        with pytest.raises(AnalysisError, match=r"at t = 0\.5 s the massless block\(s\) B "):
            call()


# ------------------------------------------------------------ geometry, second round
def test_extra_length_enters_both_lengths(tmp_path):
    """A rope with 5 m of extra length (on the drum, terminations): L = l + 5 and
    L0 = L_ref = 10 + 5, so g = l - 10 as without it."""
    st, _ = stepper(tmp_path, PENDULUM.replace("path: [S, H]", "extra_length: 5.0, "
                                               "path: [S, H]"), "  duration: 1\n")
    geo = st.geometry(0.3, Q, V, st.kin(0.3))
    np.testing.assert_allclose(geo["L"], [14.0], rtol=1e-14)
    np.testing.assert_allclose(geo["L0"], [15.0], rtol=1e-14)


SLING = """cranefe: 1
name: hook and load on a sling
plane: xz
nodes:
  S: [0, 0, 30]
  H: [0, 0, 20]
  B: [0, 0, 17]
ground: [S]
masses: {H: 200, B: 2000}
ropes:
  hoist: {EA: 1.0e7, path: [S, H]}
  sling: {EA: 5.0e6, path: [H, B]}
"""


def test_rates_of_a_span_whose_both_ends_move(tmp_path):
    """The sling between two moving loads H and B: g' = e . (v_B - v_H),
    gamma = (|dv|^2 - (e . dv)^2) / l with dv = v_B - v_H (no prescribed motion)."""
    st, _ = stepper(tmp_path, SLING, "  duration: 1\n")
    q = np.array([0.5, 20.0, 1.5, 17.2])          # (x_H, z_H, x_B, z_B)
    v = np.array([0.3, -0.2, -0.4, 0.6])
    geo = st.geometry(0.0, q, v, st.kin(0.0))
    d = q[2:] - q[:2]
    l = np.linalg.norm(d)
    e = d / l
    dv = v[2:] - v[:2]
    np.testing.assert_allclose(geo["l"][1], l, rtol=1e-14)
    np.testing.assert_allclose(geo["gdot"][1], e @ dv, rtol=1e-13)
    np.testing.assert_allclose(geo["gamma"][1], (dv @ dv - (e @ dv) ** 2) / l, rtol=1e-12)
    np.testing.assert_allclose(geo["G"][1], np.r_[-e, e], atol=1e-15)


TROLLEY = """cranefe: 1
name: a load below a travelling trolley
nodes:
  O: [0, 0, 0]
  K: [5, 0, 20]
  H: [5, 0, 16]
ground: [O]
masses: {H: 1000}
bodies:
  trolley: {mass: 500, com: [5, 0, 20], inertia: [10, 10, 10], nodes: [K]}
joints:
  - {name: travel, type: slider, bodies: [ground, trolley], at: K, axis: [1, 0, 0],
     range: [-20, 20]}
ropes:
  hoist: {EA: 1.0e9, path: [K, H]}
"""


def test_gamma_with_an_accelerating_trolley(tmp_path):
    """The trolley K accelerates at 0.5 m/s^2 along x (a speed table; at t = 1 s it is
    at x = 5.25 m moving at 0.5 m/s), the load (sway on) 3 m aside and 4 m below it
    (e = (3, 0, -4)/5 from the trolley) moving with it: gamma = e . (A_load -
    A_trolley) with dV = 0, and the load's acceleration is the unknown (0 in gamma):
    gamma = -0.3. (With sway off a load hangs vertically below its carrier and is
    carried horizontally, so e . (A_load - A_carrier) = 0 either way.)"""
    st, _ = stepper(tmp_path, TROLLEY, "  duration: 4\n  drives:\n    travel: {slider: "
                       "travel, profile: {type: table, speed: [[0, 0], [4, 2.0]]}}\n")
    t = 1.0
    kin = st.kin(t)
    np.testing.assert_allclose(kin[0][1], [5.25, 0, 20], atol=1e-12)
    np.testing.assert_allclose(kin[1][1], [0.5, 0, 0], atol=1e-12)
    geo = st.geometry(t, np.array([8.25, 0.0, 16.0]), np.array([0.5, 0.0, 0.0]), kin)
    np.testing.assert_allclose(geo["e"][0], [0.6, 0.0, -0.8], atol=1e-12)
    np.testing.assert_allclose(geo["gamma"], [-0.3], atol=1e-12)


TWO_DRUMS = """cranefe: 1
name: two loads on two torque-driven drums
plane: xz
nodes:
  W1: [-2, 0, 40]
  S1: [0, 0, 40]
  H1: [0, 0, 20]
  W2: [8, 0, 40]
  S2: [10, 0, 40]
  H2: [10, 0, 25]
ground: [W1, S1, W2, S2]
masses: {H1: 1000, H2: 500}
drums:
  d1: {node: W1, radius: 0.5, inertia: 10}
  d2: {node: W2, radius: 0.25, inertia: 4}
ropes:
  r1: {EA: 1.0e9, path: [d1, S1, H1]}
  r2: {EA: 1.0e9, path: [d2, S2, H2]}
"""


def test_rows_of_two_drum_coordinates(tmp_path):
    """Two drums under torques (their angles coordinates 2 and 3 after the loads'
    heights): G = [[-1, 0, R1, 0], [0, -1, 0, R2]] (the vertical falls above the loads,
    dL/dz = -1; dg/dtheta = R)."""
    st, mech = stepper(tmp_path, TWO_DRUMS, "  duration: 1\n  drives:\n"
                       "    a: {drum: d1, torque: 5000}\n    b: {drum: d2, torque: 1300}\n",
                       effects="{rope_elasticity: false, sway: false}")
    assert mech.n == 4 and mech.nx == 2
    geo = st.geometry(0.0, mech.q0, np.zeros(4), st.kin(0.0))
    np.testing.assert_allclose(geo["G"], [[-1, 0, 0.5, 0], [0, -1, 0, 0.25]], atol=1e-15)
    np.testing.assert_array_equal(st.wq, [1, 1, 0.5, 0.25])


def test_kinematics_at_a_breakpoint_of_a_travelling_trolley(tmp_path):
    """The trolley's speed table bends at t = 1 s (0.5 m/s reached, then constant): at
    the breakpoint the left limit has the trolley's acceleration 0.5 m/s^2, the right
    limit 0, both with its position 5.25 m and velocity 0.5 m/s; off the breakpoint the
    kinematics unchanged."""
    st, _ = stepper(tmp_path, TROLLEY, "  duration: 4\n  drives:\n    travel: {slider: "
                       "travel, profile: {type: table, speed: [[0, 0], [1, 0.5], [4, 0.5]]}}\n")
    for side, acc in ((-1, 0.5), (1, 0.0)):
        X, Vk, A, _ = st.kin_side(1.0, side)
        np.testing.assert_allclose(X[1], [5.25, 0, 20], atol=1e-12)
        np.testing.assert_allclose(Vk[1], [0.5, 0, 0], atol=1e-12)
        np.testing.assert_allclose(A[1], [acc, 0, 0], atol=1e-6)
    assert st.kin_side(0.5, -1) is st.kin(0.5)
