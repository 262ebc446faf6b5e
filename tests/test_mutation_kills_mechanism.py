"""Value tests of cranefe/analysis/operation/mechanism.py (issue 20, mutation testing).

The operation engine's equations at a given (t, q, q') are checked against forces,
kinematics and energies written out by hand for small scenes (docs/operations.md,
"Mechanics"), never against the engine itself:

- a pendulum hanging from a trolley on a slider moved by a trapezoid: the trolley's
  position, speed and acceleration (s = a t^2/2, ...), the load's force
  F = m g - S e with S = EA ln(L/L0), L0 = L_ref exp(-m g/EA), the tangent K = -dF/dq by
  central differences of that hand force, the rope's dashpot b = psi c / (2 pi w) with
  c = EA/L, w^2 = c/m (one fall, e . M^-1 e = 1/m), the energies
  (1/2 m v^2, m g z, Hencky EA (L ln(L/L0) - L + L0)) and the trolley's power
  -(S + S_d) e . V_K (the force the trolley puts on the rope end times its speed);
- a hoisting drum: the unstretched length L0 = L0_ref - R theta / lambda_ref with the
  drum angle of its profile (theta = omega t), the elongation rate, the drum's power
  R (S + S_d) omega and the energy the wound rope carries onto it,
  S R omega - dU/dt|winding with U(L0) = EA (L ln(L/L0) - L + L0) at fixed L,
  dU/dL0 = EA (1 - L/L0);
  a torque or linear-motor drum as a coordinate (F = M_drive - R S, the drum's row of K
  and its inertia, the motor's C);
- slewing with a trolley running along the jib: X = R_z(phi) (r + s, 0, z),
  V and A by the product rule (centripetal, Coriolis, tangential terms) by hand;
- a torque-, motor-driven or free luffing arm (a joint coordinate u = rho phi): its
  static holding torque and the luffing rope's tension from the moment balance about
  the hinge, its inertia I_O / rho^2 (+ rotor gear^2 / rho^2), F by moments;
- an axial spring with its dashpot, sway off (the load follows its trolley), and the
  errors and warnings that name the entry.

Tolerances: 1e-9 relative for closed forms evaluated in double precision (a few
operations on O(1-1e7) numbers, ln(L/L0) of a 1e-3 strain loses ~3 digits: 1e-13
becomes 1e-10); central differences with step 1e-6 m: truncation h^2 |F'''| ~ 1e-12 of
EA/L, round-off 1e-16 |F| / h ~ 1e-6 N/m against entries of 1e4-1e6 N/m: bound 1e-6
relative.
"""

import functools
import tempfile
from pathlib import Path

import numpy as np
import pytest
from test_operation import scene
from test_operation_flexible import JIB as FLEX_JIB
from test_operation_massless import BLOCK

from cranefe.analysis.operation.mechanism import Mechanism
from cranefe.analysis.operation.scene import parse
from cranefe.errors import AnalysisError, ModelError
from cranefe.model import load

G = 9.81
RTOL = 1e-9


@functools.lru_cache(maxsize=None)
def _dir():
    return Path(tempfile.mkdtemp(prefix="mutkill-mech-"))


_count = [0]


def _scene(model_text, analysis, effects="{}"):
    _count[0] += 1
    return load(scene(_dir(), model_text, analysis, effects, name=f"s{_count[0]}.yaml"))


def _mech(model):
    return Mechanism(model, parse(model))


TROLLEY = """cranefe: 1
name: trolley pendulum
plane: xz
nodes:
  K: [0, 0, 10]
  H: [0, 0, 0]
masses: {H: MASS}
bodies:
  trolley: {mass: 500, com: [0, 0, 10], inertia: [10, 10, 10], nodes: [K]}
joints:
  - {name: travel, type: slider, bodies: [ground, trolley], at: K, axis: [1, 0, 0],
     range: [-1, 20]}
ropes:
  hoist: {EA: EAVAL, psi: 0.3, path: [K, H]}
"""
TROLLEY_DRIVE = ("  duration: 4\n  drives:\n    trolley: {slider: travel, profile: "
                 "{type: trapezoid, distance: 2, v_max: 1, a_max: 1}}\n")


def trolley_xs(t):
    """The trapezoid of distance 2, v_max 1, a_max 1 by hand: (s, s', s'')."""
    if t < 1:
        return 0.5 * t * t, t, 1.0
    if t < 2:
        return 0.5 + (t - 1), 1.0, 0.0
    if t < 3:
        u = t - 2
        return 1.5 + u - 0.5 * u * u, 1 - u, -1.0
    return 2.0, 0.0, 0.0


def _trolley(m=1000.0, EA=1.0e7, effects="{}"):
    return _mech(_scene(TROLLEY.replace("MASS", str(m)).replace("EAVAL", str(EA)),
                        TROLLEY_DRIVE, effects))


def _pendulum_force(t, x, z, m, EA, L0):
    """Hand force on the load (x, z) of the trolley pendulum (no damping)."""
    xs = trolley_xs(t)[0]
    d = np.array([x - xs, z - 10.0])
    L = np.hypot(*d)
    S = EA * np.log(L / L0)
    return np.array([0.0, -m * G]) - S * d / L, L, S


def test_trolley_static_state_and_kinematics():
    m, EA = 1000.0, 1.0e7
    mech = _trolley(m, EA)
    assert mech.n == 2 and mech.nc == 2 and mech.nJ == 0
    np.testing.assert_allclose(mech.S0, [m * G], rtol=RTOL)
    np.testing.assert_allclose(mech.L_ref, [10.0], rtol=RTOL)
    np.testing.assert_allclose(mech.lam_ref, [np.exp(m * G / EA)], rtol=RTOL)
    np.testing.assert_allclose(mech.L0_ref, [10.0 * np.exp(-m * G / EA)], rtol=RTOL)
    np.testing.assert_allclose(mech.q0, [0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(mech.M, [m, m], rtol=0)
    assert mech.taut0.tolist() == [True]
    assert mech.free.tolist() == [1] and mech.kin.tolist() == [0]
    for t in (0.0, 0.5, 1.5, 2.5, 3.5):
        X, V, A, th = mech.kinematics(t)
        s, ds, dds = trolley_xs(t)
        np.testing.assert_allclose(X[0], [s, 0, 10], atol=1e-12)
        np.testing.assert_allclose(V[0], [ds, 0, 0], atol=1e-12)
        np.testing.assert_allclose(A[0], [dds, 0, 0], atol=1e-12)
        # a second call in the same state returns the same (cached) arrays
        X2 = mech.kinematics(t)[0]
        np.testing.assert_allclose(X2[0], [s, 0, 10], atol=1e-12)
        mot, Xp = mech.poses(t, {})
        np.testing.assert_allclose(Xp[0], [s, 0, 10], atol=1e-12)
        R, dR, ddR, p, dp, ddp = mech.body_motions(t)[0]
        np.testing.assert_allclose(R, np.eye(3), atol=0)
        np.testing.assert_allclose([p, dp, ddp], [[s, 0, 0], [ds, 0, 0], [dds, 0, 0]],
                                   atol=1e-12)


@pytest.mark.parametrize("t", [0.5, 2.5])
def test_trolley_pendulum_forces_and_tangent_by_hand(t):
    m, EA = 1000.0, 1.0e7
    mech = _trolley(m, EA)
    L0 = 10.0 * np.exp(-m * G / EA)
    q = np.array([0.7, 0.9])           # the load off the vertical, rope stretched
    v = np.array([0.3, -0.2])
    taut = np.array([True])
    ev = mech.evaluate(t, q, v, taut, damping=False)
    F, L, S = _pendulum_force(t, *q, m, EA, L0)
    np.testing.assert_allclose(ev.F, F, rtol=RTOL)
    np.testing.assert_allclose([ev.L[0], ev.L0[0], ev.S[0]], [L, L0, S], rtol=RTOL)
    h = 1e-6
    Kfd = np.zeros((2, 2))
    for j in range(2):
        dq = np.zeros(2)
        dq[j] = h
        Kfd[:, j] = -(_pendulum_force(t, *(q + dq), m, EA, L0)[0]
                      - _pendulum_force(t, *(q - dq), m, EA, L0)[0]) / (2 * h)
    np.testing.assert_allclose(ev.K, Kfd, rtol=1e-6, atol=1e-6 * np.abs(Kfd).max())
    np.testing.assert_allclose(ev.C, 0.0, atol=0)
    xs, vs = trolley_xs(t)[:2]
    e = np.array([q[0] - xs, 0, q[1] - 10.0]) / L
    edot = e @ (np.array([v[0], 0, v[1]]) - np.array([vs, 0, 0]))
    np.testing.assert_allclose(ev.edot, [edot], rtol=RTOL)
    np.testing.assert_allclose(ev.X[1], [q[0], 0, q[1]], atol=0)
    np.testing.assert_allclose(ev.V[1], [v[0], 0, v[1]], atol=0)
    # powers: the trolley feeds -(S) e . V_K; no dashpot, nothing wound
    assert ev.P_drive == pytest.approx(-S * e[0] * vs, rel=RTOL, abs=1e-9)
    assert ev.P_diss == 0.0 and ev.P_wound == 0.0 and ev.T_guided == 0.0
    # energies: 1/2 m v^2, m g z, Hencky
    T, Vg, U = mech.energy(ev, taut)
    assert T == pytest.approx(0.5 * m * (v @ v), rel=RTOL)
    assert Vg == pytest.approx(m * G * q[1], rel=RTOL)
    assert U == pytest.approx(EA * (L * np.log(L / L0) - L + L0), rel=1e-7)
    # slack: no force, no energy
    evs = mech.evaluate(t, q, v, np.array([False]))
    np.testing.assert_allclose(evs.F, [0, -m * G], atol=0)
    np.testing.assert_allclose(evs.K, 0.0, atol=0)
    assert mech.energy(evs, np.array([False]))[2] == 0.0
    # mass matrix
    np.testing.assert_allclose(mech.mass_matrix(ev), np.diag([m, m]), atol=0)


def test_trolley_rope_dashpot_by_hand():
    """damping: exact: b = psi c / (2 pi w), c = EA/L, w^2 = c / m (one fall)."""
    m, EA, psi, t = 1000.0, 1.0e7, 0.3, 0.5
    mech = _trolley(m, EA, effects="{damping: exact}")
    L0 = 10.0 * np.exp(-m * G / EA)
    q, v = np.array([0.7, 0.9]), np.array([0.3, -0.2])
    taut = np.array([True])
    ev = mech.evaluate(t, q, v, taut)
    F, L, S = _pendulum_force(t, *q, m, EA, L0)
    c = EA / L
    b = psi * c / (2 * np.pi * np.sqrt(c / m))
    xs, vs = trolley_xs(t)[:2]
    e2 = np.array([q[0] - xs, q[1] - 10.0]) / L
    edot = e2 @ (v - [vs, 0])
    Sd = b * edot
    np.testing.assert_allclose(ev.Sd, [Sd], rtol=RTOL)
    np.testing.assert_allclose(ev.F, F - Sd * e2, rtol=RTOL)
    np.testing.assert_allclose(ev.C, b * np.outer(e2, e2), rtol=RTOL, atol=1e-9 * b)
    assert ev.P_diss == pytest.approx(Sd * edot, rel=RTOL)
    assert ev.P_drive == pytest.approx(-(S + Sd) * e2[0] * vs, rel=RTOL)
    # without damping asked for: none
    ev0 = mech.evaluate(t, q, v, taut, damping=False)
    np.testing.assert_allclose(ev0.Sd, [0.0], atol=0)
    # a slack rope has no dashpot
    evs = mech.evaluate(t, q, v, np.array([False]))
    np.testing.assert_allclose(evs.Sd, [0.0], atol=0)
    np.testing.assert_allclose(evs.F, [0, -m * G], atol=0)
    np.testing.assert_allclose(evs.C, 0.0, atol=0)


def test_soft_rope_dashpot_below_one_radian_per_second():
    """A 1e4 kg load on 100 m of a soft rope (EA 5e5 N): w^2 = c/m = 0.5 / s^2 < 1, so
    b = psi c / (2 pi w) with w = 0.707 (no floor at 1 rad/s)."""
    text = ("cranefe: 1\nname: soft\nplane: xz\nnodes:\n  A: [0, 0, 100]\n  H: [0, 0, 0]\n"
            "ground: [A]\nmasses: {H: 1.0e4}\nropes:\n  r: {EA: 5.0e5, psi: 0.3, path: [A, H]}\n")
    mech = _scene_mech(text, "  duration: 1\n", "{damping: exact}")
    q, v = np.array([0.0, 0.5]), np.array([0.0, -0.2])
    ev = mech.evaluate(0.0, q, v, np.array([True]))
    L = 99.5
    c = 5.0e5 / L
    w = np.sqrt(c / 1.0e4)
    assert w < 1
    b = 0.3 * c / (2 * np.pi * w)
    np.testing.assert_allclose(ev.Sd, [b * 0.2], rtol=RTOL)      # e = (0, -1): e.v = 0.2


def test_sway_off_the_load_follows_its_trolley():
    m, EA, t = 1000.0, 1.0e7, 1.5
    mech = _trolley(m, EA, effects="{sway: false}")
    assert mech.n == 1
    assert mech.root.tolist() == [0] and mech.hang.tolist() == [0]
    L0 = 10.0 * np.exp(-m * G / EA)
    z, vz = 0.05, 0.1
    ev = mech.evaluate(t, np.array([z]), np.array([vz]), np.array([True]), damping=False)
    xs, vs = trolley_xs(t)[:2]
    L = 10.0 - z
    S = EA * np.log(L / L0)
    np.testing.assert_allclose(ev.X[1], [xs, 0, z], atol=1e-12)
    np.testing.assert_allclose(ev.V[1], [vs, 0, vz], atol=1e-12)
    np.testing.assert_allclose(ev.F, [S - m * G], rtol=RTOL)
    np.testing.assert_allclose(ev.K, [[EA / L]], rtol=RTOL)
    assert ev.T_guided == pytest.approx(0.5 * m * vs * vs, rel=RTOL)
    T, Vg, U = mech.energy(ev, np.array([True]))
    assert T == pytest.approx(0.5 * m * (vs * vs + vz * vz), rel=RTOL)


def test_a_load_off_the_vertical_without_sway_is_refused():
    text = TROLLEY.replace("H: [0, 0, 0]", "H: [1, 0, 0]").replace(
        "MASS", "1000").replace("EAVAL", "1.0e7")
    with pytest.raises(ModelError) as exc:
        _scene_mech(text, TROLLEY_DRIVE, "{sway: false}")
    assert exc.value.entry == "nodes.H" and "hang vertically below 'K'" in str(exc.value)


def _scene_mech(text, analysis, effects="{}"):
    return _mech(_scene(text, analysis, effects))


# ----------------------------------------------------------------- drums

WINCH = """cranefe: 1
name: winch
plane: xz
nodes:
  W: [-2, 0, 40]
  S: [0, 0, 40]
  H: [0, 0, 30]
ground: [W, S]
masses: {H: 1000}
drums:
  hoist: {node: W, radius: 0.5, inertia: 10, rope_reserve: 100}
ropes:
  r: {EA: 2.0e6, psi: 0.2, extra_length: 1.5, path: [hoist, S, {node: H, falls: 2}]}
"""


def test_drum_profile_winds_rope_by_hand():
    """L0 = L0_ref - R theta / lambda_ref, theta = omega t; L = |WS| + 2 l + extra."""
    m, EA, R, om = 1000.0, 2.0e6, 0.5, 0.4
    mech = _scene_mech(WINCH, f"  duration: 5\n  drives:\n    h: {{drum: hoist, profile: "
                       f"{{type: table, speed: [[0, {om}]]}}}}\n", "{damping: exact}")
    S0 = m * G / 2
    Lr = 2.0 + 2 * 10.0 + 1.5
    lam = np.exp(S0 / EA)
    np.testing.assert_allclose(mech.S0, [S0], rtol=RTOL)
    np.testing.assert_allclose(mech.L_ref, [Lr], rtol=RTOL)
    np.testing.assert_allclose(mech.hold_torque, [R * S0], rtol=RTOL)
    assert mech.n == 2 and not mech.qdrums
    t = 1.5
    theta = om * t
    L0 = Lr / lam - R * theta / lam
    np.testing.assert_allclose(mech.unstretched(np.array([theta])), [L0], rtol=RTOL)
    q, v = np.array([0.2, 30.1]), np.array([0.05, 0.3])
    ev = mech.evaluate(t, q, v, np.array([True]))
    l = np.hypot(q[0], 40 - q[1])
    L = 2.0 + 2 * l + 1.5
    S = EA * np.log(L / L0)
    e = np.array([q[0], q[1] - 40]) / l          # from S to H
    edot = 2 * e @ v + R * om
    c = EA / L
    w = np.sqrt(c * 4 / m)                         # two falls: (2 e) . M^-1 (2 e)
    b = 0.2 * c / (2 * np.pi * w)
    Sd = b * edot
    np.testing.assert_allclose([ev.L[0], ev.L0[0], ev.S[0]], [L, L0, S], rtol=RTOL)
    np.testing.assert_allclose(ev.theta, [theta], rtol=RTOL)
    np.testing.assert_allclose(ev.omega, [om], rtol=RTOL)
    np.testing.assert_allclose(ev.edot, [edot], rtol=RTOL)
    np.testing.assert_allclose(ev.Sd, [Sd], rtol=RTOL)
    np.testing.assert_allclose(ev.F, np.array([0, -m * G]) - 2 * (S + Sd) * e, rtol=RTOL)
    # powers: the drum R (S + Sd) omega; the wound energy S R omega - dU/dt|winding
    # with U(L0) = EA (L ln(L/L0) - L + L0) at fixed L, dL0/dt = -R omega / lambda_ref
    assert ev.P_drive == pytest.approx(R * (S + Sd) * om, rel=RTOL)
    assert ev.P_diss == pytest.approx(Sd * edot, rel=RTOL)

    def U(L0_):
        return EA * (L * np.log(L / L0_) - L + L0_)
    dU = EA * (1 - L / L0) * (-R * om / lam)       # dU/dL0 = EA (1 - L/L0)
    assert ev.P_wound == pytest.approx(S * R * om - dU, rel=1e-7)
    T, Vg, Ue = mech.energy(ev, np.array([True]))
    assert Ue == pytest.approx(U(L0), rel=1e-7)
    evs = mech.evaluate(t, q, v, np.array([False]))
    assert evs.P_wound == 0.0 and evs.P_drive == 0.0
    assert T == pytest.approx(0.5 * m * (v @ v), rel=RTOL)
    # the drum's rope paid out past its reserve: AnalysisError only for coordinates
    mech.check_range(ev, t)


def test_damped_rope_on_a_torque_drum_by_hand():
    """damping: exact with the drum a coordinate: the rope's row g = (2 e, R) (two falls
    and the drum), w^2 = c (4/m + R^2/J), b = psi c / (2 pi w), S_d = b g . v,
    F = -(S + S_d) g + gravity + torque, C = b g g^T."""
    m, EA, R, J, psi = 1000.0, 2.0e6, 0.5, 10.0, 0.2
    mech = _scene_mech(WINCH, "  duration: 5\n  drives:\n    h: {drum: hoist, torque: 3000}\n",
                       "{damping: exact}")
    lam = np.exp(m * G / 2 / EA)
    q, v = np.array([0.2, 30.1, 0.3]), np.array([0.05, 0.3, 0.7])
    ev = mech.evaluate(1.0, q, v, np.array([True]))
    l = np.hypot(q[0], 40 - q[1])
    L = 23.5 - 20 + 2 * l
    L0 = (23.5 - R * q[2]) / lam
    S = EA * np.log(L / L0)
    g = np.array([2 * q[0] / l, 2 * (q[1] - 40) / l, R])
    c = EA / L
    b = psi * c / (2 * np.pi * np.sqrt(c * (4 / m + R * R / J)))
    Sd = b * (g @ v)
    np.testing.assert_allclose(ev.Sd, [Sd], rtol=RTOL)
    np.testing.assert_allclose(ev.F, np.array([0, -m * G, 3000.0]) - (S + Sd) * g, rtol=RTOL)
    np.testing.assert_allclose(ev.C, b * np.outer(g, g), rtol=RTOL, atol=1e-12 * b)


def test_a_drum_winds_only_its_own_rope():
    """Two ropes, the first on the drum: the second's L0 does not change with theta."""
    text = WINCH.replace("  H: [0, 0, 30]\n", "  H: [0, 0, 30]\n  B: [0, 0, 25]\n").replace(
        "masses: {H: 1000}", "masses: {H: 1000, B: 500}") + \
        "  sling: {EA: 1.0e6, path: [H, B]}\n"
    mech = _scene_mech(text, "  duration: 5\n  drives:\n    h: {drum: hoist, profile: "
                       "{type: table, speed: [[0, 0.4]]}}\n")
    S0 = np.array([1500 * G / 2, 500 * G])
    np.testing.assert_allclose(mech.S0, S0, rtol=RTOL)
    lam = np.exp(S0 / np.array([2.0e6, 1.0e6]))
    L0 = mech.unstretched(np.array([0.6]))
    np.testing.assert_allclose(L0, [(23.5 - 0.5 * 0.6) / lam[0], 5.0 / lam[1]], rtol=RTOL)
    # forces at a displaced state: H on two falls and the sling, B on the sling
    t = 1.5
    q = np.array([0.1, 29.9, -0.2, 24.8])        # H (x, z), B (x, z)
    ev = mech.evaluate(t, q, np.zeros(4), np.array([True, True]))
    H, B = q[:2], q[2:]
    l1 = np.hypot(*H - [0, 40])
    e1 = (H - [0, 40]) / l1
    S1 = 2.0e6 * np.log((3.5 + 2 * l1) / ((23.5 - 0.5 * 0.4 * t) / lam[0]))
    l2 = np.hypot(*B - H)
    e2 = (B - H) / l2
    S2 = 1.0e6 * np.log(l2 / (5.0 / lam[1]))
    F = np.concatenate([[0, -1000 * G] - 2 * S1 * e1 + S2 * e2, [0, -500 * G] - S2 * e2])
    np.testing.assert_allclose(ev.F, F, rtol=1e-9, atol=1e-9 * 1000 * G)
    # only the drum feeds power (the loads at rest): R S1 omega
    assert ev.P_drive == pytest.approx(0.5 * S1 * 0.4, rel=1e-9)


def test_without_gravity_the_vertical_is_z():
    """gravity [0, 0, 0]: 'up' falls back to +z (a sway-off load's coordinate)."""
    text = SPRING.replace("name: spring\n", "name: spring\ngravity: [0, 0, 0]\n")
    mech = _scene_mech(text, "  duration: 1\n", "{sway: false}")
    np.testing.assert_allclose(mech.up, [0, 0, 1], atol=0)
    np.testing.assert_allclose(mech.E[:, 0], [0, 0, 1], atol=0)
    np.testing.assert_allclose(mech.N_ref, [0.0], atol=0)


@pytest.mark.parametrize("kind", ["torque", "motor"])
def test_torque_and_motor_drums_as_coordinates(kind):
    m, EA, R, J = 1000.0, 2.0e6, 0.5, 10.0
    drive = "torque: [[0, 2000], [2, 4000]]" if kind == "torque" else \
        "motor: {stall_torque: 400, synchronous_speed: 157}"
    gear = "" if kind == "torque" else ", motor: {rotor_inertia: 0.2, gear_ratio: 20}"
    text = WINCH.replace("rope_reserve: 100", "rope_reserve: 100" + gear)
    J = J if kind == "torque" else J + 0.2 * 20 ** 2     # reduced to the drum
    mech = _scene_mech(text, f"  duration: 5\n  drives:\n    h: {{drum: hoist, {drive}}}\n")
    assert mech.n == 3 and mech.qdrums == [0]
    np.testing.assert_allclose(mech.M, [m, m, J], rtol=0)
    S0 = m * G / 2
    Lr = 23.5
    lam = np.exp(S0 / EA)

    def hand(qv):
        x, z, th, om = qv
        l = np.hypot(x, 40 - z)
        L = 2.0 + 2 * l + 1.5
        L0 = (Lr - R * th) / lam
        S = EA * np.log(L / L0)
        e = np.array([x, z - 40]) / l
        if kind == "torque":
            tq = 3000.0                  # the table at t = 1 s
        else:
            tq = 20 * 400 * (1 - 20 * om / 157)
        return np.array([*(np.array([0, -m * G]) - 2 * S * e), tq - R * S]), tq
    q, v = np.array([0.2, 30.1, 0.3]), np.array([0.05, 0.3, 0.7])
    ev = mech.evaluate(1.0, q, v, np.array([True]))
    F, tq = hand([*q, v[2]])
    np.testing.assert_allclose(ev.F, F, rtol=RTOL)
    np.testing.assert_allclose(ev.drive_torque, [tq], rtol=RTOL)
    h = 1e-6
    Kfd = np.zeros((3, 3))
    for j in range(3):
        dq = np.zeros(4)
        dq[j] = h
        Kfd[:, j] = -(hand(np.r_[q, v[2]] + dq)[0] - hand(np.r_[q, v[2]] - dq)[0]) / (2 * h)
    np.testing.assert_allclose(ev.K, Kfd, rtol=1e-6, atol=1e-6 * np.abs(Kfd).max())
    C = np.zeros((3, 3))
    if kind == "motor":
        C[2, 2] = 20 * 20 * 400 / 157
    np.testing.assert_allclose(ev.C, C, rtol=RTOL, atol=1e-9)
    # energy: the drum's 1/2 J omega^2; power: the drive's torque times omega
    T = mech.energy(ev, np.array([True]))[0]
    assert T == pytest.approx(0.5 * m * (v[:2] @ v[:2]) + 0.5 * J * v[2] ** 2, rel=RTOL)
    assert ev.P_drive == pytest.approx(tq * v[2], rel=RTOL)
    # a slack rope: no force on the drum, no stiffness
    evs = mech.evaluate(1.0, q, v, np.array([False]))
    np.testing.assert_allclose(evs.F, [0, -m * G, tq], rtol=RTOL)
    np.testing.assert_allclose(evs.K, 0.0, atol=0)
    # paying out past the reserve (theta R per radian, 100 m) stops the run
    mech.check_range(ev, 1.0)
    for th in (-190.0, -200.0):          # 95 m, exactly 100 m paid out: still inside
        ev.theta[0] = th
        mech.check_range(ev, 1.0)
    ev.theta[0] = -100.0 / R - 1.0
    with pytest.raises(AnalysisError) as exc:
        mech.check_range(ev, 2.5)
    assert "drum 'hoist'" in str(exc.value) and "t = 2.5 s" in str(exc.value)
    assert "rope_reserve 100 m" in str(exc.value) and "paid out 100.5 m" in str(exc.value)
    assert f"drive {kind} too weak" in str(exc.value)


# ----------------------------------------------------------------- slewing

SLEWING = """cranefe: 1
name: slewing test crane
nodes:
  O: [0, 0, 0]
  T: [0, 0, 30]
  K: [6, 0, 30]
  H: [6, 0, 20]
ground: [O]
masses: {H: 1000}
bodies:
  jib: {mass: 5000, com: [10, 0, 30], inertia: [1.0e3, 1.0e5, 1.0e5], nodes: [O, T]}
  trolley: {mass: 500, com: [6, 0, 30], inertia: [10, 10, 10], nodes: [K]}
joints:
  - {name: slew, type: hinge, bodies: [ground, jib], at: O, axis: [0, 0, 1]}
  - {name: travel, type: slider, bodies: [jib, trolley], at: K, axis: [1, 0, 0],
     range: [-2, 20]}
ropes:
  hoist: {EA: 1.0e8, path: [K, H]}
"""


def test_slewing_with_a_running_trolley_by_hand():
    """K = R_z(phi) (6 + s, 0, 30), phi = w t + a t^2/2 (a table from w0 to w1):
    V = R' r + R r', A = R'' r + 2 R' r' + R r'' by hand."""
    w0, w1, T1 = 0.2, 0.5, 2.0
    mech = _scene_mech(SLEWING, f"  duration: 4\n  drives:\n    s: {{hinge: slew, profile: "
                       f"{{type: table, speed: [[0, {w0}], [{T1}, {w1}]]}}}}\n"
                       "    t: {slider: travel, profile: {type: trapezoid, distance: 2, "
                       "v_max: 1, a_max: 1}}\n")
    al = (w1 - w0) / T1
    for t in (0.5, 1.5):
        ph, dph, ddph = w0 * t + al * t * t / 2, w0 + al * t, al
        s, ds, dds = trolley_xs(t)
        c, sn = np.cos(ph), np.sin(ph)
        r = 6 + s
        X = np.array([r * c, r * sn, 30])
        V = np.array([ds * c - r * sn * dph, ds * sn + r * c * dph, 0])
        A = np.array([dds * c - 2 * ds * sn * dph - r * c * dph ** 2 - r * sn * ddph,
                      dds * sn + 2 * ds * c * dph - r * sn * dph ** 2 + r * c * ddph, 0])
        Xk, Vk, Ak, _ = mech.kinematics(t)
        np.testing.assert_allclose(Xk[2], X, atol=1e-12)
        np.testing.assert_allclose(Vk[2], V, atol=1e-12)
        np.testing.assert_allclose(Ak[2], A, atol=1e-12)
        np.testing.assert_allclose(Xk[1], [0, 0, 30], atol=1e-12)
        Xp = mech.poses(t, {})[1]
        np.testing.assert_allclose(Xp[2], X, atol=1e-12)
        # the load's rope from the moving trolley: force by hand
        q = np.array([X[0] + 0.1, X[1] - 0.2, 20.05])
        ev = mech.evaluate(t, q, np.zeros(3), np.array([True]))
        d = q - X
        L = np.linalg.norm(d)
        S = 1.0e8 * np.log(L / (10 * np.exp(-1000 * G / 1.0e8)))
        np.testing.assert_allclose(ev.F, [0, 0, -1000 * G] - S * d / L, rtol=1e-8)
        # power fed by the moving trolley: -S e . V_K
        assert ev.P_drive == pytest.approx(-S * (d / L) @ V, rel=1e-8)


# ----------------------------------------------------------------- springs

SPRING = """cranefe: 1
name: spring
nodes:
  A: [0, 0, 10]
  H: [0, 0, 5]
ground: [A]
masses: {H: 200}
springs:
  - {name: s, type: axial, nodes: [A, H], stiffness: 4.0e5, psi: 0.4}
"""


def test_axial_spring_and_its_dashpot_by_hand():
    m, k, psi = 200.0, 4.0e5, 0.4
    mech = _scene_mech(SPRING, "  duration: 1\n", "{damping: exact}")
    np.testing.assert_allclose(mech.N_ref, [m * G], rtol=RTOL)
    np.testing.assert_allclose(mech.sp_dref, [5.0], rtol=RTOL)
    q = np.array([0.3, -0.2, 4.9])
    v = np.array([0.1, 0.2, -0.3])
    ev = mech.evaluate(0.0, q, v, np.zeros(0, bool))
    d = q - [0, 0, 10]
    dl = np.linalg.norm(d)
    e = d / dl
    N = m * G + k * (dl - 5.0)
    w = np.sqrt(k / m)
    b = psi * k / (2 * np.pi * w)
    Nd = b * (e @ v)
    np.testing.assert_allclose(ev.N, [N + Nd], rtol=RTOL)
    np.testing.assert_allclose(ev.F, [0, 0, -m * G] - (N + Nd) * e, rtol=RTOL)
    Kh = k * np.outer(e, e) + N / dl * (np.eye(3) - np.outer(e, e))
    np.testing.assert_allclose(ev.K, Kh, rtol=1e-9, atol=1e-9 * k)
    np.testing.assert_allclose(ev.C, b * np.outer(e, e), rtol=1e-9, atol=1e-9 * b)
    assert ev.P_diss == pytest.approx(Nd * (e @ v), rel=RTOL)
    assert ev.P_drive == 0.0
    T, Vg, U = mech.energy(ev, np.zeros(0, bool))
    assert U == pytest.approx(m * G * (dl - 5) + 0.5 * k * (dl - 5) ** 2, rel=RTOL)
    assert Vg == pytest.approx(m * G * q[2], rel=RTOL)
    ev0 = mech.evaluate(0.0, q, v, np.zeros(0, bool), damping=False)
    np.testing.assert_allclose(ev0.N, [N], rtol=RTOL)
    assert ev0.P_diss == 0.0


# ----------------------------------------------------------------- joint coordinates

ARM = """cranefe: 1
name: luffing arm
plane: xz
nodes:
  O: [0, 0, 10]
  T: [4, 0, 10]
  P: [0, 0, 14]
  H: [4, 0, 5]
ground: [P]
masses: {H: 300}
bodies:
  arm: {mass: 200, com: [2, 0, 10], inertia: [1, 50, 50], nodes: [O, T]}
joints:
  - {name: luff, type: hinge, bodies: [ground, arm], at: O, axis: [0, 1, 0],
     range: [-1, 1]}
ropes:
  hoist: {EA: 1.0e8, psi: 0.2, path: [T, H]}
  stay: {EA: 5.0e8, path: [P, T]}
"""
MB, ML, IO = 200.0, 300.0, 50.0 + 200.0 * 4.0     # arm mass, load, inertia about O


def _arm(drive):
    return _scene_mech(ARM, f"  duration: 2\n  drives:\n    d: {{hinge: luff, {drive}}}\n")


def test_free_arm_hangs_on_its_stay_by_the_moment_balance():
    """Moments about O (y axis, a positive turn takes the tip down): gravity
    2 m_b g + 4 m_l g against the stay P-T, whose force S e (e = (-4, 0, 4)/sqrt 32)
    at T = (4, 0, 10) has the moment -4 S 4 / sqrt 32."""
    mech = _arm("free: true")
    assert mech.nJ == 1 and mech.n == 3
    assert not [w for w in mech.warnings if "held like a drum" in w]
    stay = (2 * MB * G + 4 * ML * G) / (16 / np.sqrt(32))
    np.testing.assert_allclose(mech.S0, [ML * G, stay], rtol=1e-9)
    np.testing.assert_allclose(mech.joint_hold, [0.0], atol=1e-6)
    assert mech.jc[0]["rho"] == pytest.approx(4.0)
    np.testing.assert_allclose(mech.M, [ML, ML, IO / 16], rtol=1e-12)


def _arm_force(mech, q, v, taut, tq_of):
    """Hand generalised forces of the arm scene at (q, v): the load (x, z) on its rope
    from the tip T, the arm's coordinate u = rho phi by moments about O (y axis):
    gravity 2 cos(phi) m_b g, the ropes' forces at T (r_z F_x - r_x F_z, r = T - O),
    the drive's torque tq_of(phi') - all over rho."""
    rho = 4.0
    phi, dphi = q[2] / rho, v[2] / rho
    c, s = np.cos(phi), np.sin(phi)
    Tn = np.array([4 * c, 10 - 4 * s])
    EA = np.array([1.0e8, 5.0e8])
    out = np.zeros(3)
    Mu = 2 * c * MB * G + tq_of(dphi)
    out[1] -= ML * G
    for k, (a, b) in enumerate([(Tn, q[:2]), (np.array([0.0, 14.0]), Tn)]):
        d = b - a
        l = np.linalg.norm(d)
        S = EA[k] * np.log(l / mech.L0_ref[k]) if taut[k] else 0.0
        e = d / l
        if k == 0:
            out[:2] -= S * e                      # on the load (b = H)
            Ft = S * e                            # on T (its a end)
        else:
            Ft = -S * e                           # on T (its b end)
        Mu += (-4 * s) * Ft[0] - (4 * c) * Ft[1]
    out[2] = Mu / rho
    return out


def _arm_tangents(mech, q, v, taut, tq_of, h=1e-6):
    K = np.zeros((3, 3))
    for j in range(3):
        dq = np.zeros(3)
        dq[j] = h
        K[:, j] = -(_arm_force(mech, q + dq, v, taut, tq_of)
                    - _arm_force(mech, q - dq, v, taut, tq_of)) / (2 * h)
    dv = np.array([0.0, 0.0, h])
    C = np.zeros((3, 3))
    C[:, 2] = -(_arm_force(mech, q, v + dv, taut, tq_of)
                - _arm_force(mech, q, v - dv, taut, tq_of)) / (2 * h)
    return K, C


def test_free_arm_forces_by_moments():
    mech = _arm("free: true")
    rho = 4.0
    np.testing.assert_allclose(mech.L0_ref, [5.0 * np.exp(-ML * G / 1.0e8),
                                             np.sqrt(32) * np.exp(-mech.S0[1] / 5.0e8)],
                               rtol=1e-12)
    q = np.array([4.0, 5.0, rho * 0.05])
    v = np.array([0.1, 0.0, rho * 0.3])
    taut = np.array([True, True])
    ev = mech.evaluate(0.0, q, v, taut)
    F = _arm_force(mech, q, v, taut, lambda w: 0.0)
    np.testing.assert_allclose(ev.F, F, rtol=1e-9, atol=1e-9 * np.abs(F).max())
    K, C = _arm_tangents(mech, q, v, taut, lambda w: 0.0)
    np.testing.assert_allclose(ev.K, K, rtol=1e-6, atol=1e-6 * np.abs(K).max())
    np.testing.assert_allclose(ev.C, 0.0, atol=1e-9)
    np.testing.assert_allclose(ev.joint_torque, [0.0], atol=0)
    d_ = mech.spec.drives[0]
    assert mech.joint_drive_torque(d_, 0.0, 0.3) == 0.0


@pytest.mark.parametrize("kind", ["torque", "motor"])
def test_held_arm_torque_motor_and_its_warning(kind):
    """A torque- or motor-driven arm is held at rest: it carries the whole moment
    (joint_hold = -(2 m_b + 4 m_l) g), the stay is at 0 N and the run warns. The
    torque is a table (-5000 N m at t = 0 to -3000 at t = 1: -4000 at 0.5 s)."""
    drive = "torque: [[0, -5000], [1, -3000]]" if kind == "torque" else \
        "gear_ratio: 30, rotor_inertia: 0.2, motor: {stall_torque: 400, synchronous_speed: 150}"
    mech = _arm(drive)
    hold = -(2 * MB + 4 * ML) * G
    np.testing.assert_allclose(mech.joint_hold, [hold], rtol=1e-9)
    np.testing.assert_allclose(mech.S0, [ML * G, 0.0], atol=1e-6)
    warn = [w for w in mech.warnings if "held like a drum" in w]
    assert len(warn) == 1 and "drive 'd'" in warn[0] and f"{hold:.6g} N m" in warn[0]
    assert "rope(s) stay, which" in warn[0], warn      # the loaded hoist rope not listed
    given = -5000.0 if kind == "torque" else 30 * 400.0          # the drive at t = 0
    assert f"the drive gives {given:.6g} N m at t = 0" in warn[0]
    rot = 0.0 if kind == "torque" else 0.2 * 30 ** 2
    np.testing.assert_allclose(mech.M, [ML, ML, (IO + rot) / 16], rtol=1e-12)
    # a state: the arm turned by phi, turning at dphi; the load at rest
    rho, phi, dphi, t = 4.0, 0.1, 0.3, 0.5
    q = np.array([4.0, 5.0, rho * phi])
    v = np.array([0.0, 0.0, rho * dphi])
    taut = mech.taut0.copy()
    assert taut.tolist() == [True, False]
    ev = mech.evaluate(t, q, v, taut)

    def tq_of(w):
        return -4000.0 if kind == "torque" else 30 * 400 * (1 - 30 * w / 150)
    tq = tq_of(dphi)
    F = _arm_force(mech, q, v, taut, tq_of)
    np.testing.assert_allclose(ev.F, F, rtol=1e-9, atol=1e-9 * np.abs(F).max())
    K, C = _arm_tangents(mech, q, v, taut, tq_of)
    np.testing.assert_allclose(ev.K, K, rtol=1e-6, atol=1e-6 * np.abs(K).max())
    # (C by differences in u' of a force of 1e5 N: round-off 1e-16 1e5 / 1e-6 ~ 1e-5 each)
    np.testing.assert_allclose(ev.C, C, rtol=1e-5, atol=1e-9)
    np.testing.assert_allclose(ev.joint_torque, [tq], rtol=1e-12)
    np.testing.assert_allclose(ev.MJ, [[(IO + rot) / 16]], rtol=1e-12)
    np.testing.assert_allclose(mech.mass_matrix(ev)[2, 2], (IO + rot) / 16, rtol=1e-12)
    np.testing.assert_allclose(mech.joint_accel(ev), [F[2] / ((IO + rot) / 16)], rtol=1e-9)
    if kind == "motor":
        # dF_u/du' = tq'(dphi) / rho^2 = -30^2 400/150 / 16
        assert ev.C[2, 2] == pytest.approx(30 * 30 * 400 / 150 / 16, rel=1e-9)
    # energy: 1/2 (I_O + rotor) dphi^2, the arm's weight at its com
    T, Vg, U = mech.energy(ev, taut)
    assert T == pytest.approx(0.5 * (IO + rot) * dphi ** 2, rel=1e-9)
    assert Vg == pytest.approx(MB * G * (10 - 2 * np.sin(phi)) + ML * G * 5.0, rel=1e-9)
    # power: the drive's torque times dphi (the load at rest, no prescribed motion)
    assert ev.P_drive == pytest.approx(tq * dphi, rel=1e-9)
    d_ = mech.spec.drives[0]
    assert mech.joint_drive_torque(d_, t, dphi) == pytest.approx(tq, rel=1e-12)
    np.testing.assert_allclose(mech.joint_state(d_, t, q, v), [phi, dphi], rtol=1e-12)
    # past its range [-1, 1] rad: AnalysisError naming the drive and time
    mech.check_range(ev, 0.0)
    q2 = q.copy()
    q2[2] = rho * 1.2
    ev2 = mech.evaluate(0.5, q2, v, taut)
    with pytest.raises(AnalysisError) as exc:
        mech.check_range(ev2, 0.5)
    assert "drive 'd'" in str(exc.value) and "68.7549 deg" in str(exc.value)


def test_inextensible_ropes_with_a_joint_coordinate_are_refused():
    with pytest.raises(ModelError) as exc:
        _scene_mech(ARM, "  duration: 2\n  drives:\n    d: {hinge: luff, free: true}\n",
                    "{rope_elasticity: false}")
    assert exc.value.entry == "effects.rope_elasticity"
    assert str(exc.value.file) == str(_dir() / f"s{_count[0]}.yaml")     # the scene file
    assert "drive 'd'" in exc.value.message


JIB = (FLEX_JIB.replace("GVAL", "-9.81").replace("IYVAL", "2.0e-2").replace("NEL", "2")
       .replace("MASS", "lumped"))


def test_an_elastic_structure_with_inextensible_ropes_is_refused():
    with pytest.raises(ModelError) as exc:
        _scene_mech(JIB, "  duration: 1\n", "{structure: flexible, rope_elasticity: false}")
    assert exc.value.entry == "effects.rope_elasticity"
    assert str(exc.value.file) == str(_dir() / f"s{_count[0]}.yaml")
    assert "elastic structure" in exc.value.message


# ----------------------------------------------------------------- errors

def test_errors_name_their_entries():
    # a load that no rope holds in the geometry: not a static equilibrium
    off = WINCH.replace("H: [0, 0, 30]", "H: [3, 0, 30]")
    with pytest.raises(ModelError) as exc:
        _scene_mech(off, "  duration: 1\n")
    assert exc.value.entry == "nodes.H" and "static equilibrium" in str(exc.value)
    # a free arm whose stay runs along it (no moment about the hinge)
    loose = ARM.replace("P: [0, 0, 14]", "P: [8, 0, 10]").replace(
        "masses: {H: 300}\n", "").replace("  hoist: {EA: 1.0e8, psi: 0.2, path: [T, H]}\n", "")
    with pytest.raises(ModelError) as exc:
        _scene_mech(loose, "  duration: 2\n  drives:\n    d: {hinge: luff, free: true}\n")
    assert exc.value.entry == "analysis.drives.d" and "luff" in str(exc.value)
    # a mass on no rope
    lone = SPRING.replace("springs:\n  - {name: s, type: axial, nodes: [A, H], "
                          "stiffness: 4.0e5, psi: 0.4}\n",
                          "ropes:\n  r: {EA: 1.0e6, path: [A, B]}\n").replace(
        "  H: [0, 0, 5]\n", "  H: [0, 0, 5]\n  B: [0, 0, 3]\n").replace(
        "masses: {H: 200}", "masses: {H: 200, B: 10}")
    with pytest.raises(ModelError) as exc:
        _scene_mech(lone, "  duration: 1\n")
    assert exc.value.entry == "masses.H"


def test_two_joint_coordinates_slewing_torque_and_trolley_motor():
    """A slewing torque and a trolley motor (two coordinates after the load's three):
    at rest at t = 0 the load hangs in equilibrium, the vertical axis and the horizontal
    slider see no weight, so F = (0, 0, 0, M / rho_1, F_t), F_t = gear x stall = 500 N;
    rho_1 = 10 m (the jib's com, the farthest point from the axis); the inertias about
    the axis I_zz + m r^2 (jib 1e5 + 5000 10^2, trolley 10 + 500 6^2) over rho_1^2, the
    trolley's 500 kg + the rotor's 0.01 x 50^2 along its slider."""
    mech = _scene_mech(SLEWING, "  duration: 2\n  drives:\n    s: {hinge: slew, torque: 2.0e4}\n"
                       "    t: {slider: travel, gear_ratio: 50, rotor_inertia: 0.01, "
                       "motor: {stall_torque: 10, synchronous_speed: 100}}\n")
    assert mech.nJ == 2 and mech.nc == 3 and mech.n == 5
    assert [jc["rho"] for jc in mech.jc] == pytest.approx([10.0, 1.0])
    np.testing.assert_allclose(mech.joint_hold, [0.0, 0.0], atol=1e-6)
    I_ax = 1e5 + 5000 * 100 + 10 + 500 * 36
    ev = mech.evaluate(0.0, mech.q0, np.zeros(5), mech.taut0)
    np.testing.assert_allclose(ev.F, [0, 0, 0, 2.0e4 / 10, 500.0], atol=1e-6)
    np.testing.assert_allclose(ev.joint_torque, [2.0e4, 500.0], rtol=1e-12)
    np.testing.assert_allclose(ev.MJ, np.diag([I_ax / 100, 525.0]), rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(mech.M[:3], [1000.0] * 3, rtol=0)
    # speeds: the motor's force 500 (1 - 50 s'/100); kinetic energy
    # 1/2 I_ax phi'^2 + 1/2 (500 + rotor) s'^2 + 1/2 m_load |v|^2 (the trolley's radial
    # speed is orthogonal to its slewing speed)
    v = np.array([0.1, -0.2, 0.05, 10 * 0.1, 0.4])
    ev = mech.evaluate(0.0, mech.q0, v, mech.taut0)
    # along the slider: the motor and the centrifugal force m_t r phi'^2 (r = 6 m)
    assert ev.F[4] == pytest.approx(500.0 * (1 - 50 * 0.4 / 100) + 500 * 6 * 0.1 ** 2,
                                    rel=1e-9)
    T = mech.energy(ev, mech.taut0)[0]
    assert T == pytest.approx(0.5 * I_ax * 0.01 + 0.5 * 525.0 * 0.16
                              + 0.5 * 1000 * (v[:3] @ v[:3]), rel=1e-9)
    q = mech.q0.copy()
    q[3:] = [10 * 0.2, 0.7]
    ds, dt = mech.spec.drives
    np.testing.assert_allclose(mech.joint_state(ds, 0.0, q, v), [0.2, 0.1], rtol=1e-12)
    np.testing.assert_allclose(mech.joint_state(dt, 0.0, q, v), [0.7, 0.4], rtol=1e-12)
    X = mech.place(0.0, q, v)[0]
    np.testing.assert_allclose(X[2], [6.7 * np.cos(0.2), 6.7 * np.sin(0.2), 30], atol=1e-12)
    # the trolley's range [-2, 20] m (the slewing joint has none): inside by less than
    # 1e-9 passes, beyond stops the run naming it
    for s_ in (20 + 0.5e-9, -2 - 0.5e-9, 20.0, -2.0):
        q[4] = s_
        mech.check_range(mech.evaluate(0.0, q, v, mech.taut0), 0.0)
    for s_, where in ((25.0, "reached 25 m"), (-2.5, "reached -2.5 m")):
        q[4] = s_
        with pytest.raises(AnalysisError) as exc:
            mech.check_range(mech.evaluate(0.0, q, v, mech.taut0), 0.75)
        msg = str(exc.value)
        assert where in msg and "[-2, 20] m" in msg and "drive 't'" in msg
        assert "a motor that does not stop it" in msg and "t = 0.75 s" in msg


def test_a_prescribed_slewing_feeds_power_into_a_trolley_coordinate():
    """Slewing at w (a profile) with the trolley a force coordinate: the drives' power is
    the force times s' plus what the slewing does on the trolley, int (x'' - g) . x_t dm
    with x_t = w x r the velocity with the coordinate held: the Coriolis acceleration
    2 w s' (tangential) times r w, so 2 m_t r w^2 s' (the centripetal and radial terms
    are orthogonal to x_t, the trolley's own rotation at constant w does no work).
    The load hangs vertically below the trolley: its rope does no work on x_t."""
    w = 0.3
    mech = _scene_mech(SLEWING, f"  duration: 2\n  drives:\n    s: {{hinge: slew, profile: "
                       f"{{type: table, speed: [[0, {w}]]}}}}\n"
                       "    t: {slider: travel, force: 300}\n")
    assert mech.nJ == 1
    t, s_, ds_ = 1.0, 0.5, 0.4
    ph = w * t
    r = 6.0 + s_
    K = np.array([r * np.cos(ph), r * np.sin(ph), 30.0])
    q = np.array([K[0], K[1], 20.0, s_])
    v = np.array([0.0, 0.0, 0.0, ds_])
    ev = mech.evaluate(t, q, v, mech.taut0)
    assert ev.P_drive == pytest.approx(300 * ds_ + 2 * 500 * r * w * w * ds_, rel=1e-9)
    np.testing.assert_allclose(ev.X[2], K, atol=1e-12)
    # a prescribed drive's state and torque: its motion, nan
    d_ = mech.spec.drives[0]
    np.testing.assert_allclose(mech.joint_state(d_, t, q, v), [ph, w], rtol=1e-12)
    assert np.isnan(mech.joint_drive_torque(d_, t, w))


def test_inextensible_ropes_take_the_reference_length():
    """rope_elasticity: false: L0_ref = L_ref and lambda_ref = 1 (a drum winds R theta)."""
    mech = _scene_mech(TROLLEY.replace("MASS", "1000").replace("EAVAL", "1.0e7"),
                       TROLLEY_DRIVE, "{rope_elasticity: false}")
    assert mech.inextensible
    np.testing.assert_allclose(mech.lam_ref, [1.0], rtol=0)
    np.testing.assert_allclose(mech.L0_ref, [10.0], rtol=1e-12)
    np.testing.assert_allclose(mech.S0, [1000 * G], rtol=1e-9)


def test_damped_motor_arm_and_its_poses():
    """damping: exact on the arm's load rope T-H: its row G = (e_x, e_z, -e . dT/du) with
    dT/du = (-sin phi, -cos phi) (u = 4 phi), b = psi sqrt(c c0) / (2 pi w0) (w0 the
    mode at rest that most strains it: test_hook_and_sling_dashpots_take_their_modes);
    the motor's C and the dashpot's b G G^T add. poses(t, {drive: (phi, phi')}) puts the tip at
    (4 cos phi, 10 - 4 sin phi) and its acceleration (phi'' = 0) is centripetal."""
    mech = _scene_mech(ARM, "  duration: 2\n  drives:\n    d: {hinge: luff, gear_ratio: 30, "
                       "rotor_inertia: 0.2, motor: {stall_torque: 400, "
                       "synchronous_speed: 150}}\n", "{damping: exact}")
    rho, phi, dphi = 4.0, 0.1, 0.3
    q = np.array([4.2, 5.0, rho * phi])
    v = np.array([0.1, -0.2, rho * dphi])
    taut = mech.taut0.copy()
    ev = mech.evaluate(0.0, q, v, taut)
    c_, s_ = np.cos(phi), np.sin(phi)
    Tn = np.array([4 * c_, 10 - 4 * s_])
    d = q[:2] - Tn
    l = np.linalg.norm(d)
    e = d / l
    Gr = np.array([e[0], e[1], -(e @ np.array([-s_, -c_]))])
    c = 1.0e8 / l
    b = 0.2 * np.sqrt(c * 1.0e8 / mech.L_ref[0]) / (2 * np.pi * mech.dashpot_w0[0])
    Sd = b * (Gr @ v)
    np.testing.assert_allclose(ev.Sd, [Sd, 0.0], rtol=1e-9, atol=1e-12)
    F = _arm_force(mech, q, v, taut, lambda w: 30 * 400 * (1 - 30 * w / 150)) - Sd * Gr
    np.testing.assert_allclose(ev.F, F, rtol=1e-9, atol=1e-9 * np.abs(F).max())
    C = b * np.outer(Gr, Gr)
    C[2, 2] += 30 * 30 * 400 / 150 / 16
    np.testing.assert_allclose(ev.C, C, rtol=1e-9, atol=1e-9 * np.abs(C).max())
    mot, X = mech.poses(0.0, {"d": (phi, dphi)})
    np.testing.assert_allclose(X[1], [4 * c_, 0, 10 - 4 * s_], atol=1e-12)
    arm = [b.name for b in mech.model.bodies].index("arm")
    R, dR, ddR, p, dp, ddp = mot[arm]
    X1 = np.array([4.0, 0, 10])
    np.testing.assert_allclose(dR @ X1 + dp, dphi * 4 * np.array([-s_, 0, -c_]), atol=1e-12)
    np.testing.assert_allclose(ddR @ X1 + ddp, -dphi ** 2 * 4 * np.array([c_, 0, -s_]),
                               atol=1e-12)


def test_two_springs_and_a_rope_share_the_load():
    """A load on a vertical rope (c = EA/L) and two springs at 45 deg (k each): the static
    state shares the weight by stiffness, u = m g / (c + 2 k cos^2), S0 = c u,
    N0 = k cos u; at a displaced state each spring's N = N0 + k (d - d_ref), the energy
    the rope's Hencky energy plus sum N0 (d - d_ref) + k (d - d_ref)^2 / 2."""
    m, k, EA = 500.0, 2.0e5, 1.0e6
    text = ("cranefe: 1\nname: shared\nnodes:\n  A: [-5, 0, 10]\n  B: [5, 0, 10]\n"
            "  C: [0, 0, 10]\n  H: [0, 0, 5]\nground: [A, B, C]\nmasses: {H: 500}\n"
            "springs:\n  - {name: a, type: axial, nodes: [A, H], stiffness: 2.0e5}\n"
            "  - {name: b, type: axial, nodes: [B, H], stiffness: 2.0e5}\n"
            "ropes:\n  r: {EA: 1.0e6, path: [C, H]}\n")
    text = text.replace("stiffness: 2.0e5}", "stiffness: 2.0e5, psi: 0.4}").replace(
        "path: [C, H]}", "psi: 0.2, path: [C, H]}")
    mech = _scene_mech(text, "  duration: 1\n", "{damping: exact}")
    cs = 1 / np.sqrt(2)
    u = m * G / (EA / 5 + 2 * k * cs * cs)
    np.testing.assert_allclose(mech.S0, [EA / 5 * u], rtol=1e-9)
    np.testing.assert_allclose(mech.N_ref, [k * cs * u] * 2, rtol=1e-9)
    q = np.array([0.3, 0.1, 4.9])
    ev = mech.evaluate(0.0, q, np.zeros(3), mech.taut0)
    F = np.array([0, 0, -m * G])
    Ue = 0.0
    for a in ([-5, 0, 10], [5, 0, 10]):
        dv = q - a
        dl = np.linalg.norm(dv)
        N = k * cs * u + k * (dl - np.sqrt(50))
        F -= N * dv / dl
        Ue += k * cs * u * (dl - np.sqrt(50)) + 0.5 * k * (dl - np.sqrt(50)) ** 2
    dv = q - [0, 0, 10]
    L = np.linalg.norm(dv)
    L0 = 5 * np.exp(-EA / 5 * u / EA)
    F -= EA * np.log(L / L0) * dv / L
    Ue += EA * (L * np.log(L / L0) - L + L0)
    np.testing.assert_allclose(ev.F, F, rtol=1e-9, atol=1e-9 * m * G)
    assert mech.energy(ev, mech.taut0)[2] == pytest.approx(Ue, rel=1e-7)
    # tangent: each element's k e e^T + N/d (I - e e^T) (rope: EA/L, S/L);
    # dashpots: each b e e^T, b = psi k / (2 pi w0) (the rope: psi sqrt(c c0) / (2 pi
    # w0)), w0 the mode at rest that most strains it. At rest (H at [0, 0, 5]) the
    # tangent is diagonal by symmetry: K_xx = k + N0/d + S0/5 (springs at 45 deg, their
    # and the rope's geometric terms), K_zz = k + N0/d + EA/5; the springs' rows
    # (+-cs, 0, -cs) strain x and z alike, so they take the softer, x (K_xx < K_zz);
    # the vertical rope only z
    S0, N0, d0 = EA / 5 * u, k * cs * u, np.sqrt(50)
    w_x = np.sqrt((k + N0 / d0 + S0 / 5) / m)
    w_z = np.sqrt((k + N0 / d0 + EA / 5) / m)
    Kh = np.zeros((3, 3))
    Ch = np.zeros((3, 3))
    for a, kk, psi in (([-5, 0, 10], k, 0.4), ([5, 0, 10], k, 0.4),
                       ([0, 0, 10], None, 0.2)):
        dv = q - a
        dl = np.linalg.norm(dv)
        e = dv / dl
        if kk is None:
            kk, N = EA / dl, EA * np.log(dl / L0)
            b = psi * np.sqrt(kk * EA / 5) / (2 * np.pi * w_z)
        else:
            N = N0 + kk * (dl - d0)
            b = psi * kk / (2 * np.pi * w_x)
        Kh += kk * np.outer(e, e) + N / dl * (np.eye(3) - np.outer(e, e))
        Ch += b * np.outer(e, e)
    np.testing.assert_allclose(ev.K, Kh, rtol=1e-9, atol=1e-9 * np.abs(Kh).max())
    np.testing.assert_allclose(ev.C, Ch, rtol=1e-9, atol=1e-9 * np.abs(Ch).max())


def test_a_joint_listed_child_first_moves_the_other_way():
    """bodies: [trolley, ground]: the drive moves bodies[1] relative to bodies[0], so the
    trolley (the child in the tree) moves by -s."""
    text = TROLLEY.replace("bodies: [ground, trolley]", "bodies: [trolley, ground]").replace(
        "MASS", "1000").replace("EAVAL", "1.0e7")
    mech = _scene_mech(text, TROLLEY_DRIVE)
    for t in (0.5, 2.5):
        X, V, A, _ = mech.kinematics(t)
        s, ds, dds = trolley_xs(t)
        np.testing.assert_allclose([X[0, 0], V[0, 0], A[0, 0]], [-s, -ds, -dds], atol=1e-12)


LUFF_ON_SLEW = """cranefe: 1
name: boom on a slewing tower
nodes:
  O: [0, 0, 0]
  P: [1, 0, 20]
  T: [21, 0, 20]
  H: [21, 0, 10]
ground: [O]
masses: {H: 1000}
bodies:
  tower: {mass: 1000, com: [0, 0, 10], inertia: [10, 10, 10], nodes: [O]}
  boom: {mass: 500, com: [11, 0, 20], inertia: [10, 10, 10], nodes: [P, T]}
joints:
  - {name: slew, type: hinge, bodies: [ground, tower], at: O, axis: [0, 0, 1]}
  - {name: luff, type: hinge, bodies: [tower, boom], at: P, axis: [0, -1, 0]}
ropes:
  hoist: {EA: 1.0e8, path: [T, H]}
"""


def test_a_hinge_on_a_slewing_body_composes_by_hand():
    """The boom tip T = Rz(phi) [P + R_(-y)(theta) (T0 - P)] (luffing about the tower's
    -y axis through P, which turns with the tower); its velocity and acceleration by
    central differences of that hand position (h = 1e-4 s: truncation h^2/6 |x'''|
    ~ 1e-8 m/s, round-off 1e-16 x 20 / h^2 ~ 2e-7 m/s^2; bounds 1e-6 and 1e-5)."""
    w_s, w_l = 0.2, 0.1
    mech = _scene_mech(LUFF_ON_SLEW, "  duration: 3\n  drives:\n    s: {hinge: slew, profile: "
                       f"{{type: table, speed: [[0, {w_s}]]}}}}\n    l: {{hinge: luff, profile: "
                       f"{{type: table, speed: [[0, {w_l}], [2, {2 * w_l}]]}}}}\n")

    def tip(t):
        ph = w_s * t
        th = w_l * t + (w_l / 2) * t * t / 2 if t < 2 else None
        c, s = np.cos(th), np.sin(th)
        # rotation by th about -y: x -> (x c, 0, x s) for a point along +x
        d = np.array([20 * c, 0, 20 * s])
        p = np.array([1.0, 0, 20]) + d
        Rz = np.array([[np.cos(ph), -np.sin(ph), 0], [np.sin(ph), np.cos(ph), 0], [0, 0, 1]])
        return Rz @ p
    h = 1e-4
    for t in (0.5, 1.5):
        X, V, A, _ = mech.kinematics(t)
        np.testing.assert_allclose(X[2], tip(t), atol=1e-12)
        np.testing.assert_allclose(V[2], (tip(t + h) - tip(t - h)) / (2 * h), atol=1e-6)
        np.testing.assert_allclose(A[2], (tip(t + h) - 2 * tip(t) + tip(t - h)) / h ** 2,
                                   atol=1e-5)


def test_sway_off_load_under_a_luffing_tip():
    """sway: false under the arm's tip, the arm luffed by a profile: the load's horizontal
    position follows the tip (x = 4 cos phi) and its height is its own coordinate."""
    mech = _scene_mech(ARM, "  duration: 2\n  drives:\n    d: {hinge: luff, profile: "
                       "{type: table, speed: [[0, 0.2]]}}\n", "{sway: false}")
    t = 1.0
    ph = 0.2 * t
    X, V, th, om = mech.place(t, np.array([4.5]), np.array([0.3]))
    np.testing.assert_allclose(X[3], [4 * np.cos(ph), 0, 4.5], atol=1e-12)
    np.testing.assert_allclose(V[3], [-4 * np.sin(ph) * 0.2, 0, 0.3], atol=1e-12)


def test_sway_off_load_rides_on_a_trolley_coordinate():
    """sway: false under a trolley driven by a force: the load's horizontal inertia is
    carried by the trolley's coordinate (M_J = 500 + 1000 kg), its height its own; the
    kinetic energy 1/2 (m_t + m) s'^2 + 1/2 m z'^2, no separate guided energy."""
    text = TROLLEY.replace("MASS", "1000").replace("EAVAL", "1.0e7")
    mech = _scene_mech(text, "  duration: 2\n  drives:\n    f: {slider: travel, force: 300}\n",
                       "{sway: false}")
    assert mech.n == 2 and mech.guided_joint.tolist() == [True]
    q, v = np.array([0.01, 0.4]), np.array([0.2, 0.3])
    ev = mech.evaluate(0.0, q, v, mech.taut0)
    np.testing.assert_allclose(ev.MJ, [[1500.0]], rtol=1e-12)
    np.testing.assert_allclose(mech.M, [1000.0, 1500.0], rtol=1e-12)
    np.testing.assert_allclose(ev.X[1], [0.4, 0, 0.01], atol=1e-12)
    np.testing.assert_allclose(ev.V[1], [0.3, 0, 0.2], atol=1e-12)
    assert ev.F[1] == pytest.approx(300.0, rel=1e-12)
    T = mech.energy(ev, mech.taut0)[0]
    assert T == pytest.approx(0.5 * 1500 * 0.09 + 0.5 * 1000 * 0.04, rel=1e-12)
    assert ev.T_guided == 0.0


BRIDGE = """cranefe: 1
name: trolley on a travelling bridge
plane: xz
nodes:
  B: [0, 0, 10]
  K: [1, 0, 10]
  H: [1, 0, 0]
masses: {H: 1000}
bodies:
  bridge: {mass: 2000, com: [0, 0, 10], inertia: [10, 10, 10], nodes: [B]}
  trolley: {mass: 500, com: [1, 0, 10], inertia: [10, 10, 10], nodes: [K]}
joints:
  - {name: run, type: slider, bodies: [ground, bridge], at: B, axis: [1, 0, 0],
     range: [-1, 20]}
  - {name: travel, type: slider, bodies: [bridge, trolley], at: K, axis: [1, 0, 0],
     range: [-5, 5]}
ropes:
  hoist: {EA: 1.0e7, path: [K, H]}
"""


def test_a_breakpoint_seen_from_the_left_by_a_trolley_coordinate():
    """The bridge runs a trapezoid (acceleration 1 m/s^2 until t = 1 s, then 0); the
    trolley on it is a force coordinate (300 N): along its slider F = 300 - m_t a_bridge
    (the carried acceleration), so at t = 1 s from the left (left_at = 1) -200 N, from
    the right 300 N. The load hangs straight below the trolley (no force along x)."""
    mech = _scene_mech(BRIDGE, "  duration: 4\n  drives:\n    r: {slider: run, profile: "
                       "{type: trapezoid, distance: 2, v_max: 1, a_max: 1}}\n"
                       "    t: {slider: travel, force: 300}\n")
    assert mech.nJ == 1 and mech.nc == 2
    q = np.array([1.5, mech.q0[1], 0.0])            # the load below K at x = 0.5 + 1
    v = np.array([1.0, 0.0, 0.0])                   # moving with the bridge
    mech.left_at = 1.0
    ev = mech.evaluate(1.0, q, v, mech.taut0)
    assert ev.F[2] == pytest.approx(300 - 500 * 1.0, rel=1e-12)
    mech.left_at = None
    ev = mech.evaluate(1.0, q, v, mech.taut0)
    assert ev.F[2] == pytest.approx(300.0, rel=1e-12)
    ev = mech.evaluate(0.5, np.array([1.125, mech.q0[1], 0.0]), np.array([0.5, 0, 0]),
                       mech.taut0)
    assert ev.F[2] == pytest.approx(300 - 500 * 1.0, rel=1e-12)
    np.testing.assert_allclose(ev.F[:2], 0.0, atol=1e-6)
    # the load 0.3 m ahead of the trolley: the drives' power is the rope's pull on the
    # prescribed motion of K, -S e . V_K (V_K = 0.5 m/s along x), plus the bridge's work
    # on the trolley, m_t (a_b + s'') v_b with s'' = (300 - m_t a_b + S e_x) / m_t
    q = np.array([1.425, mech.q0[1], 0.0])
    ev = mech.evaluate(0.5, q, np.array([0.5, 0, 0]), mech.taut0)
    d = np.array([0.3, q[1] - 10.0])
    L = np.linalg.norm(d)
    S = 1.0e7 * np.log(L / mech.L0_ref[0])
    ex = d[0] / L
    s2 = (300 - 500 * 1.0 + S * ex) / 500
    assert ev.F[2] == pytest.approx(300 - 500 + S * ex, rel=1e-9)
    assert ev.P_drive == pytest.approx(-S * ex * 0.5 + 500 * (1 + s2) * 0.5, rel=1e-9)


HOIST_TROLLEY = """cranefe: 1
name: hoist rope over a moving trolley
plane: xz
nodes:
  W: [-2, 0, 10]
  K: [0, 0, 10]
  H: [0, 0, 0]
ground: [W]
masses: {H: 1000}
drums:
  hoist: {node: W, radius: 0.5, inertia: 10, rope_reserve: 100}
bodies:
  trolley: {mass: 500, com: [0, 0, 10], inertia: [10, 10, 10], nodes: [K]}
joints:
  - {name: travel, type: slider, bodies: [ground, trolley], at: K, axis: [1, 0, 0],
     range: [-1, 20]}
ropes:
  hoist: {EA: 1.2e6, path: [hoist, K, H]}
springs:
  - {name: s, type: axial, nodes: [K, H], stiffness: 5.0e4}
"""


def test_power_of_a_hoist_drum_and_a_trolley_on_a_rope_and_a_spring():
    """The rope W-K-H (drum at W, profile omega = 0.4) and a spring K-H share the load
    by stiffness (u = m g / (EA/12 + k)); the drives feed S (e_WK - e_KH) . V_K (the
    trolley pulls both spans), R S omega (the drum) and N (-e_KH) . V_K (the spring's
    end on the trolley)."""
    m, EA, k, R, om = 1000.0, 1.2e6, 5.0e4, 0.5, 0.4
    mech = _scene_mech(HOIST_TROLLEY, "  duration: 4\n  drives:\n    trolley: {slider: travel, "
                       "profile: {type: trapezoid, distance: 2, v_max: 1, a_max: 1}}\n"
                       f"    h: {{drum: hoist, profile: {{type: table, speed: [[0, {om}]]}}}}\n")
    u = m * G / (EA / 12 + k)
    np.testing.assert_allclose(mech.S0, [EA / 12 * u], rtol=1e-9)
    np.testing.assert_allclose(mech.N_ref, [k * u], rtol=1e-9)
    t = 1.5
    xs, vs = trolley_xs(t)[:2]
    q = np.array([xs + 0.4, 0.1])
    ev = mech.evaluate(t, q, np.zeros(2), mech.taut0)
    K = np.array([xs, 10.0])
    d1 = K - [-2, 10]
    d2 = q - K
    l1, l2 = np.linalg.norm(d1), np.linalg.norm(d2)
    e1, e2 = d1 / l1, d2 / l2
    lam = np.exp(mech.S0[0] / EA)
    L0 = (12.0 - R * om * t) / lam
    S = EA * np.log((l1 + l2) / L0)
    N = k * u + k * (l2 - 10.0)
    VK = np.array([vs, 0.0])
    P = S * (e1 - e2) @ VK + R * S * om + N * (-e2 @ VK)
    assert ev.P_drive == pytest.approx(P, rel=1e-9)
    np.testing.assert_allclose(ev.F, [0, -m * G] - (S + N) * e2, rtol=1e-9)




def test_a_massless_block_by_hand():
    """The block B (no mass) is a coordinate with M = 0 after the load L; statics: the
    two falls carry m g / 2 each, the sling m g; forces at a displaced state:
    F_B = -2 S_1 e_1 + S_2 e_2, F_L = m g - S_2 e_2 (e_1 = (B - S)/l_1, e_2 = (L - B)/l_2)."""
    m = 1000.0
    mech = _scene_mech(BLOCK, "  duration: 1\n")
    assert mech.free.tolist() == [3, 2] and mech.qy.tolist() == [2, 3]
    np.testing.assert_allclose(mech.M, [m, m, 0, 0], atol=0)
    np.testing.assert_allclose(mech.S0, [m * G / 2, m * G], rtol=1e-9)
    q = np.array([0.2, 6.9, 0.1, 9.95])
    ev = mech.evaluate(0.0, q, np.zeros(4), mech.taut0)
    L_, B = q[:2], q[2:]
    l1 = np.linalg.norm(B - [0, 20])
    e1 = (B - [0, 20]) / l1
    l2 = np.linalg.norm(L_ - B)
    e2 = (L_ - B) / l2
    S1 = 1.0e7 * np.log((5 + 2 * l1) / (25 * np.exp(-m * G / 2 / 1.0e7)))
    S2 = 5.0e6 * np.log(l2 / (3 * np.exp(-m * G / 5.0e6)))
    F = np.concatenate([[0, -m * G] - S2 * e2, -2 * S1 * e1 + S2 * e2])
    np.testing.assert_allclose(ev.F, F, rtol=1e-9, atol=1e-9 * m * G)
    for eff, entry in (("{damping: exact}", "effects.damping"),
                       ("{rope_elasticity: false}", "effects.rope_elasticity")):
        with pytest.raises(ModelError) as exc:
            _scene_mech(BLOCK, "  duration: 1\n", eff)
        assert exc.value.entry == entry and "node(s) B with" in exc.value.message


def test_loops_and_free_bodies_are_refused():
    # a second joint between the ground and the driven trolley closes a loop
    text = TROLLEY.replace("MASS", "1000").replace("EAVAL", "1.0e7").replace(
        "ropes:", "  - {name: extra, type: hinge, bodies: [ground, trolley], at: K, "
        "axis: [0, 1, 0]}\nropes:")
    with pytest.raises(ModelError) as exc:
        _scene_mech(text, TROLLEY_DRIVE)
    assert exc.value.entry == "analysis.drives.trolley" and "extra" in exc.value.message
    # a body without a joint
    text = TROLLEY.replace("MASS", "1000").replace("EAVAL", "1.0e7").replace(
        "joints:", "  crate: {mass: 50, com: [5, 0, 0], inertia: [1, 1, 1], nodes: []}\n"
        "joints:")
    with pytest.raises(ModelError) as exc:
        _scene_mech(text, TROLLEY_DRIVE)
    assert exc.value.entry == "bodies.crate"
    # a joint coordinate that carries no mass
    text = ARM.replace("arm: {mass: 200,", "arm: {mass: 0,")
    with pytest.raises(ModelError) as exc:
        _scene_mech(text, "  duration: 2\n  drives:\n    d: {hinge: luff, torque: 100}\n")
    assert exc.value.entry == "analysis.drives.d" and "no mass" in exc.value.message


def test_two_damped_ropes_on_a_guided_load_damp_it_at_psi_over_4pi():
    """A guided load (sway off: its height z the one coordinate) on a vertical rope and a
    slanted one of another stiffness, at rest: the one mode has w0^2 = (c_a g_a^2 +
    c_b g_b^2 + S_b (1 - g_b^2) / L_b) / m (g = dL/dz, c = EA / L; the static forces
    S = c g u, u = -m g / sum c g^2; the slanted rope's geometric stiffness). Both
    dashpots take it (b = psi c / (2 pi w0)), so C = psi / (2 pi w0) sum c g^2 and the
    damping ratio C / (2 m w0) is psi / (4 pi) times the ropes' share of the stiffness
    (0.9999 here), as for one rope. Each rope's own frequency (c g^2 / m) gave C 38 %
    higher."""
    m, psi = 800.0, 0.3
    text = ("cranefe: 1\nname: two ropes\nplane: xz\nnodes:\n  A: [0, 0, 10]\n"
            "  B: [3, 0, 8]\n  H: [0, 0, 0]\nground: [A, B]\nmasses: {H: 800}\nropes:\n"
            "  a: {EA: 2.0e6, psi: 0.3, path: [A, H]}\n"
            "  b: {EA: 5.0e6, psi: 0.3, path: [B, H]}\n")
    mech = _scene_mech(text, "  duration: 1\n", "{sway: false, damping: exact}")
    assert mech.nx == 1
    ev = mech.evaluate(0.0, mech.q0, np.zeros(1), mech.taut0)
    c, g, Ls = [], [], []
    for (x, h), EA in (((0.0, 10.0), 2.0e6), ((3.0, 8.0), 5.0e6)):
        L = np.hypot(x, h)
        c.append(EA / L)
        g.append(-h / L)
        Ls.append(L)
    c, g = np.array(c), np.array(g)
    ka = c @ g ** 2
    u = -m * G / ka                                    # the static sag (down), S = c g u
    Sb = c[1] * g[1] * u
    w0 = np.sqrt((ka + Sb * (1 - g[1] ** 2) / Ls[1]) / m)
    assert Sb > 100.0                                  # the geometric term is there
    assert ev.C[0, 0] == pytest.approx(psi / (2 * np.pi * w0) * ka, rel=1e-10)
    share = ka / (m * w0 ** 2)
    assert ev.C[0, 0] / (2 * m * w0) == pytest.approx(psi / (4 * np.pi) * share, rel=1e-10)


def test_hook_and_sling_dashpots_take_their_modes():
    """A light hook (200 kg) on a hoist rope (c_h = 1e6 N/m, psi 0.2) carries a heavy
    load (5000 kg) on a stiff sling (c_s = 2e7 N/m, psi 0.1), sway off: at rest K =
    [[c_h + c_s, -c_s], [-c_s, c_s]], M = diag(200, 5000) (heights of hook and load),
    whose two modes (closed form of the 2x2 problem) are the hoisting mode (hook and
    load together on the hoist rope) and the hook's own between the ropes. Each rope's
    dashpot takes the mode that stores the most of its strain energy (r phi)^2 / w^2:
    the hoist rope the hoisting mode, the sling the hook's. So the hoisting mode's
    damping ratio phi^T C phi / (2 w) is psi_h / (4 pi) times the hoist rope's share of
    its energy (0.957) plus the sling's small part: 0.0152 of psi_h / (4 pi) = 0.0159.
    The hook's own frequency (sqrt((c_h + c_s) / m_h), the Rayleigh quotient along
    M^-1 r) would give 0.0007, the hoist rope's own (sqrt(c_h / m_h)) 0.0029."""
    mh, ml, ch, cs = 200.0, 5000.0, 1.0e6, 2.0e7
    text = ("cranefe: 1\nname: hook and sling\nplane: xz\nnodes:\n  S: [0, 0, 30]\n"
            "  K: [0, 0, 20]\n  H: [0, 0, 15]\nground: [S]\nmasses: {K: 200, H: 5000}\n"
            "ropes:\n  hoist: {EA: 1.0e7, psi: 0.2, path: [S, K]}\n"
            "  sling: {EA: 1.0e8, psi: 0.1, path: [K, H]}\n")
    mech = _scene_mech(text, "  duration: 1\n", "{sway: false, damping: exact}")
    assert mech.n == 2
    # det(K - w^2 M) = 0: mh ml w^4 - (mh cs + ml (ch + cs)) w^2 + ch cs = 0
    a, b_, c = mh * ml, -(mh * cs + ml * (ch + cs)), ch * cs
    lam = np.array([(-b_ - s * np.sqrt(b_ * b_ - 4 * a * c)) / (2 * a) for s in (1, -1)])
    w = np.sqrt(lam)
    # mode shapes (hook, load): (c_s, c_s - ml w^2)... normalised to phi^T M phi = 1
    phi = np.array([[cs, ch + cs - mh * x] for x in lam])       # rows: modes
    phi /= np.sqrt(mh * phi[:, 0] ** 2 + ml * phi[:, 1] ** 2)[:, None]
    strain_h = phi[:, 0]                      # hoist rope: L = 30 - z_K, |dL/dz_K| = 1
    strain_s = phi[:, 0] - phi[:, 1]          # sling: L = z_K - z_H
    kh = int(np.argmax(strain_h ** 2 / lam))
    ks = int(np.argmax(strain_s ** 2 / lam))
    assert (kh, ks) == (0, 1)
    np.testing.assert_allclose(mech.dashpot_w0, [w[kh], w[ks]], rtol=1e-10)
    ev = mech.evaluate(0.0, mech.q0, np.zeros(2), mech.taut0)
    zeta = phi[0] @ ev.C @ phi[0] / (2 * w[0])
    hand = 0.2 / (4 * np.pi) * ch * strain_h[0] ** 2 / lam[0] + \
        0.1 * cs * strain_s[0] ** 2 / (4 * np.pi * w[0] * w[1])
    assert zeta == pytest.approx(hand, rel=1e-10)
    assert 0.95 * 0.2 / (4 * np.pi) < zeta < 0.2 / (4 * np.pi)


def _pick(K, M, R):
    """The linear core's rule written out: the modes of (K, M) from the symmetric
    problem L^-1 K L^-T y = w^2 y (M = L L^T; phi = L^-T y, mass-normalised), each row's
    w of max (r phi)^2 / w^2."""
    L = np.linalg.cholesky(M)
    A = np.linalg.solve(L, np.linalg.solve(L, K).T)
    lam, y = np.linalg.eigh(A)
    E = R @ np.linalg.solve(L.T, y)
    return np.sqrt(lam[np.argmax(E * E / lam, axis=1)])


def test_two_torque_drums_and_two_springs_pick_their_modes_by_hand():
    """A guided load (sway off, height z) on two vertical ropes, each from its own torque
    drum (coordinates theta_1, theta_2; J_1 = 0.5 kg m^2, light, J_2 = 40), and two
    vertical springs to the ground below it: at rest K = sum c r r^T + sum k s s^T with
    the rows r_1 = (-1, R_1, 0), r_2 = (-1, 0, R_2) (L = top - z, the drum hauls R theta
    in), s = (1, 0, 0), M = diag(m, J_1, J_2); each element's w0 picked from those modes by
    hand, and the static state's C = sum b r r^T (b = psi c / (2 pi w0), the spring's
    psi k / (2 pi w0)) on every coordinate: the drums' columns where they belong."""
    m, R1, R2, J1, J2 = 2000.0, 0.3, 0.5, 0.5, 40.0
    c1, c2, k, k2 = 4.0e6 / 10, 6.0e6 / 12, 2.0e5, 1.0e5
    text = ("cranefe: 1\nname: two drums\nplane: xz\nnodes:\n  A: [0, 0, 10]\n"
            "  B: [0, 0, 12]\n  H: [0, 0, 0]\n  F: [0, 0, -5]\n  E: [0, 0, -8]\n"
            "ground: [A, B, F, E]\n"
            "masses: {H: 2000}\ndrums:\n  d1: {node: A, radius: 0.3, inertia: 0.5}\n"
            "  d2: {node: B, radius: 0.5, inertia: 40}\nropes:\n"
            "  r1: {EA: 4.0e6, psi: 0.2, path: [d1, H]}\n"
            "  r2: {EA: 6.0e6, psi: 0.3, path: [d2, H]}\n"
            "springs:\n  - {name: s, type: axial, nodes: [H, F], stiffness: 2.0e5, psi: 0.1}\n"
            "  - {name: s2, type: axial, nodes: [H, E], stiffness: 1.0e5, psi: 0.05}\n")
    mech = _scene_mech(text, "  duration: 1\n  drives:\n    t1: {drum: d1, torque: 1000}\n"
                       "    t2: {drum: d2, torque: 2000}\n", "{sway: false, damping: exact}")
    assert mech.n == 3 and len(mech.qdrums) == 2
    rows = np.array([[-1.0, R1, 0.0], [-1.0, 0.0, R2], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    stiff = np.array([c1, c2, k, k2])
    K = (rows.T * stiff) @ rows
    M = np.diag([m, J1, J2])
    w0 = _pick(K, M, rows)
    np.testing.assert_allclose(mech.dashpot_w0, w0, rtol=1e-9)
    assert len(set(np.round(w0, 6))) >= 2                 # the picks differ
    b = np.array([0.2, 0.3, 0.1, 0.05]) * stiff / (2 * np.pi * w0)
    ev = mech.evaluate(0.0, mech.q0, np.zeros(3), mech.taut0)
    C = sum(bi * np.outer(r, r) for bi, r in zip(b, rows))
    np.testing.assert_allclose(ev.C, C, rtol=1e-9, atol=1e-12 * np.abs(C).max())


def test_the_pick_is_at_rest_before_the_drives_move():
    """The trolley runs from t = 0: the modes are those of the static state (rope
    vertical: the hoisting mode w0 = sqrt(c / m), c = EA / 10 m, decoupled from the
    pendulum), not of the pose a second later (the load 0.5 m behind its trolley)."""
    mech = _scene_mech(TROLLEY.replace("MASS", "1000").replace("EAVAL", "1.0e7"),
                       TROLLEY_DRIVE, "{damping: exact}")
    np.testing.assert_allclose(mech.dashpot_w0, [np.sqrt(1.0e7 / 10 / 1000)], rtol=1e-12)
