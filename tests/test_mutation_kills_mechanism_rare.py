"""Kill tests for five configurations of cranefe/analysis/operation/mechanism.py that no
other fast test builds (issue 20, mutation testing; docs/mutation.md, mechanism.py's
section, "result-changing, configurations no fast test builds yet"):

- two drum coordinates (two winches, each drum driven by a torque: q = (x1, z1, x2, z2,
  theta1, theta2)): each drum's row F = M_drive - R (S + S_d) at its own index nx + c,
  K by central differences of that hand force, the dashpots b = psi c / (2 pi w) with
  w^2 = c (1/m + R^2/J), C = b g g^T with g = dL/dq + R on the drum's column, the drums'
  1/2 J omega^2 and the drives' power M omega (evaluate's `i = nx + cc`);
- an elastic structure with a damped rope (the one-element jib of
  test_mutation_kills_flexible.py, its tip T holding the hook on a vertical rope, the
  ground frame): the power fed by the drives is zero (nothing outside the system moves:
  the rope's pull on the moving tip and the tip's on the rope cancel), the dashpot's
  dissipation S_d e', the energies 1/2 m v^2 of hook and tip, m g z, the rope's Hencky
  energy plus the jib's strain energy EA d^2 / (2 L) (a tip displaced along the jib's
  axis: Green's strain d / L with the slopes zero), and the rows G = dL/dq = (e, -e)
  the step's force error uses (integrate's _FlexOps);
- an elastic structure beside a joint coordinate (the spinning cantilever on its hub,
  a force-driven trolley on the ground): the elastic coordinates after the joint's, the
  power fed the force's alone, the energies by hand (the structure is refused only on
  the bodies a coordinate moves or on a frame a driven joint moves on);
- three joint coordinates in one chain (the gantry's bridge, trolley and hook block on
  forces and a torque): every node's place by hand, also without the joints' motions
  (place(t, q, v): the positions the results record);
- sway off with a joint coordinate and a load the coordinate does not guide: trolley A
  on a force (a coordinate) carries its load's horizontal inertia, trolley B on a
  trapezoid guides its load, whose horizontal kinetic energy the guidance feeds
  (T_guided = 1/2 m_B s_B'^2).

Tolerances: 1e-9 relative for closed forms (a few operations on O(1e4) numbers, the
ln(L/L0) of a 1e-3 strain loses ~3 digits of 1e-16); central differences with step
1e-6: truncation h^2 |F'''| ~ 1e-12 of the entries, round-off 1e-16 |F| / h ~ 1e-6 N
against entries of 1e5-1e6: 1e-6 relative; a power that is zero: 1e-9 of S |u'| (the
two cancelling terms' size); energies of O(1e5) J: 1e-9 relative; the Hencky energy
EA (L ln(L/L0) - L + L0) of a 1e-3 strain cancels ~6 digits: 1e-7 relative (as
test_mutation_kills_mechanism.py); positions and velocities 1e-12 m (rotations of O(10)
m vectors); the unit rows dL/dq 1e-14.
"""

import numpy as np
import pytest
from test_mutation_kills_flexible import DIRECT, mechanism
from test_mutation_kills_mechanism import _scene_mech, trolley_xs
from test_mutation_kills_mechanism_configs import GANTRY
from test_operation_flexible import ROTOR, write

from cranefe.analysis.operation.integrate import _FlexOps
from cranefe.model import load

G = 9.81
RTOL = 1e-9

# ----------------------------------------------------------------- two drum coordinates

WINCHES = """cranefe: 1
name: two winches
plane: xz
nodes:
  W1: [-2, 0, 40]
  S1: [0, 0, 40]
  H1: [0, 0, 30]
  W2: [18, 0, 40]
  S2: [20, 0, 40]
  H2: [20, 0, 32]
ground: [W1, S1, W2, S2]
masses: {H1: 1000, H2: 600}
drums:
  d1: {node: W1, radius: 0.5, inertia: 10, rope_reserve: 100}
  d2: {node: W2, radius: 0.4, inertia: 6, rope_reserve: 100}
ropes:
  r1: {EA: 2.0e6, psi: 0.2, path: [d1, S1, H1]}
  r2: {EA: 1.5e6, psi: 0.3, path: [d2, S2, H2]}
"""
WINCH_DRIVES = ("  duration: 5\n  drives:\n    h1: {drum: d1, torque: 3000}\n"
                "    h2: {drum: d2, torque: 2500}\n")
# per winch: mass, EA, psi, R, J, reference length (drum-sheave 2 m + the fall), sheave
WINCH = [(1000.0, 2.0e6, 0.2, 0.5, 10.0, 12.0, np.array([0.0, 40.0]), 3000.0),
         (600.0, 1.5e6, 0.3, 0.4, 6.0, 10.0, np.array([20.0, 40.0]), 2500.0)]


def _winches_by_hand(q):
    """F (no damping), and per rope (S, e, L) at q = (x1, z1, x2, z2, th1, th2):
    L = 2 + |H - S|, L0 = (L_ref - R theta) / lambda_ref, S = EA ln(L/L0),
    F_load = m g - S e, F_drum = M - R S."""
    F = np.zeros(6)
    out = []
    for k, (m, EA, _, R, _, Lr, sheave, tq) in enumerate(WINCH):
        lam = np.exp(m * G / EA)
        d = q[2 * k:2 * k + 2] - sheave
        l = np.hypot(*d)
        L = 2.0 + l
        S = EA * np.log(L / ((Lr - R * q[4 + k]) / lam))
        e = d / l
        F[2 * k:2 * k + 2] = np.array([0.0, -m * G]) - S * e
        F[4 + k] = tq - R * S
        out.append((S, e, L))
    return F, out


def test_two_drum_coordinates_by_hand():
    mech = _scene_mech(WINCHES, WINCH_DRIVES, "{damping: exact}")
    assert mech.nx == 4 and mech.n == 6 and mech.qdrums == [0, 1]
    np.testing.assert_allclose(mech.M, [1000, 1000, 600, 600, 10, 6], rtol=0)
    q = np.array([0.2, 30.1, 19.7, 32.05, 0.3, -0.2])
    v = np.array([0.05, 0.3, -0.1, 0.2, 0.7, -0.4])
    taut = np.array([True, True])
    ev = mech.evaluate(1.0, q, v, taut, damping=False)
    F, ropes = _winches_by_hand(q)
    np.testing.assert_allclose(ev.F, F, rtol=RTOL, atol=RTOL * 1000 * G)
    np.testing.assert_allclose(ev.drive_torque, [3000.0, 2500.0], rtol=RTOL)
    h = 1e-6
    Kfd = np.zeros((6, 6))
    for j in range(6):
        dq = np.zeros(6)
        dq[j] = h
        Kfd[:, j] = -(_winches_by_hand(q + dq)[0] - _winches_by_hand(q - dq)[0]) / (2 * h)
    np.testing.assert_allclose(ev.K, Kfd, rtol=1e-6, atol=1e-6 * np.abs(Kfd).max())
    # the dashpots: rope k's row g_k = (e_k on its load, R_k on its drum), one fall:
    # g M^-1 g = 1/m + R^2/J; S_d = b g . v; F = F_hand - S_d g; C = sum b g g^T
    ev = mech.evaluate(1.0, q, v, taut)
    Fd, C, Sd, edots = F.copy(), np.zeros((6, 6)), [], []
    for k, ((m, EA, psi, R, J, *_), (S, e, L)) in enumerate(zip(WINCH, ropes)):
        g = np.zeros(6)
        g[2 * k:2 * k + 2] = e
        g[4 + k] = R
        c = EA / L
        b = psi * c / (2 * np.pi * np.sqrt(c * (1 / m + R * R / J)))
        edots.append(g @ v)
        Sd.append(b * edots[-1])
        Fd -= Sd[-1] * g
        C += b * np.outer(g, g)
    np.testing.assert_allclose(ev.Sd, Sd, rtol=RTOL)
    np.testing.assert_allclose(ev.F, Fd, rtol=RTOL, atol=RTOL * 1000 * G)
    np.testing.assert_allclose(ev.C, C, rtol=RTOL, atol=RTOL * np.abs(C).max())
    # energies and powers: the drums' 1/2 J omega^2, the drives' M omega (the sheaves
    # and drums' nodes are fixed: no rope end moves)
    T = mech.energy(ev, taut)[0]
    assert T == pytest.approx(0.5 * 1000 * (v[:2] @ v[:2]) + 0.5 * 600 * (v[2:4] @ v[2:4])
                              + 0.5 * 10 * v[4] ** 2 + 0.5 * 6 * v[5] ** 2, rel=RTOL)
    assert ev.P_drive == pytest.approx(3000 * v[4] + 2500 * v[5], rel=RTOL)
    assert ev.P_diss == pytest.approx(float(np.dot(Sd, edots)), rel=RTOL)


# ----------------------------------------------------------------- an elastic structure

def _damped_jib(tmp_path):
    text = DIRECT.replace("EA: 2.0e7,", "EA: 2.0e7, psi: 0.2,")
    model = load(write(tmp_path, text, "  duration: 1\n",
                       effects="{structure: flexible, damping: exact}",
                       IYVAL=2.0e-2, NEL=1, MASS="lumped", GVAL=-9.81))
    return mechanism(model)


def test_an_elastic_jib_with_a_damped_rope_energy_and_power(tmp_path):
    """The one-element jib (A fixed at (0, 20), tip T at (12, 20), EA_b = 2.52e9 N,
    lumped tip mass rho A L / 2 = 565.2 kg) holds the 1500 kg hook on a vertical rope
    (EA 2e7, psi 0.2, L_ref 8 m, S0 = 1500 g). State: the tip pulled d = 2e-4 m along the
    jib (Green's strain d/L, slopes zero: U_b = EA_b d^2 / (2 L)), the hook 1 cm off and
    2 cm below; velocities hook (0.1, -0.2), tip (0.3, -0.05) m/s."""
    mech = _damped_jib(tmp_path)
    m, mt, EA, psi = 1500.0, 7850 * 0.012 * 12 / 2, 2.0e7, 0.2
    assert mech.nc == 2 and mech.nJ == 0 and mech.flex.nu == 2 and mech.n == 4
    np.testing.assert_allclose(mech.M, [m, m, mt, mt], rtol=1e-14)
    np.testing.assert_allclose(mech.S0, [m * G], rtol=1e-12)
    np.testing.assert_allclose(mech.L_ref, [8.0], rtol=1e-12)
    d = 2e-4
    tip = np.array([12.0 + d, 20.0])
    hook = tip + [0.01, -8.02]
    q = np.array([*hook, d, 0.0])
    vh, vt = np.array([0.1, -0.2]), np.array([0.3, -0.05])
    v = np.r_[vh, vt]
    taut = np.array([True])
    ev = mech.evaluate(0.0, q, v, taut)
    r = hook - tip
    L = np.hypot(*r)
    e = r / L
    L0 = 8.0 * np.exp(-m * G / EA)
    S = EA * np.log(L / L0)
    edot = e @ (vh - vt)
    c = EA / L
    # b = psi sqrt(c c0) / (2 pi w0): w0 the mode at rest that most strains the rope
    # (picked in test_mutation_kills_mechanism.py's hook-and-sling test), c0 = EA / 8 m
    b = psi * np.sqrt(c * EA / 8.0) / (2 * np.pi * mech.dashpot_w0[0])
    Sd = b * edot
    np.testing.assert_allclose([ev.L[0], ev.S[0], ev.edot[0], ev.Sd[0]], [L, S, edot, Sd],
                               rtol=RTOL)
    np.testing.assert_allclose(ev.F[:2], [0.0, -m * G] - (S + Sd) * e, rtol=RTOL)
    # nothing outside the system moves: no power fed (the rope's work on the moving
    # tip, -(S + S_d) e . u', is the tip's on the rope with the other sign)
    assert abs(ev.P_drive) <= 1e-9 * S * np.hypot(*vt)
    assert abs((S + Sd) * (e @ vt)) > 1e3             # the two terms are not small
    assert ev.P_diss == pytest.approx(Sd * edot, rel=RTOL)
    assert ev.P_wound == 0.0 and ev.T_guided == 0.0
    # energies: hook and tip 1/2 m v^2, m g z (the fixed root's mass left out), the
    # rope's Hencky energy and the jib's strain energy
    T, Vg, U = mech.energy(ev, taut)
    assert T == pytest.approx(0.5 * m * (vh @ vh) + 0.5 * mt * (vt @ vt), rel=RTOL)
    assert Vg == pytest.approx(m * G * hook[1] + mt * G * tip[1], rel=RTOL)
    Ub = 2.1e11 * 0.012 * d * d / (2 * 12.0)
    assert U == pytest.approx(EA * (L * np.log(L / L0) - L + L0) + Ub, rel=1e-7)
    # the integrator's rows of the step's force error: dL/dq = (e, -e) (ground frame)
    evo = _FlexOps(mech).evaluate(0.0, q, v, taut, mech.kinematics(0.0))
    np.testing.assert_allclose(evo._G, [[*e, *(-e)]], rtol=0, atol=1e-14)


# ----------------------------------------------------------------- sway off, two trolleys

TWO_TROLLEYS = """cranefe: 1
name: two trolleys
plane: xz
nodes:
  KA: [0, 0, 10]
  HA: [0, 0, 0]
  KB: [20, 0, 10]
  HB: [20, 0, 0]
masses: {HA: 1000, HB: 800}
bodies:
  ta: {mass: 500, com: [0, 0, 10], inertia: [10, 10, 10], nodes: [KA]}
  tb: {mass: 400, com: [20, 0, 10], inertia: [10, 10, 10], nodes: [KB]}
joints:
  - {name: a, type: slider, bodies: [ground, ta], at: KA, axis: [1, 0, 0], range: [-1, 20]}
  - {name: b, type: slider, bodies: [ground, tb], at: KB, axis: [1, 0, 0], range: [-1, 20]}
ropes:
  ra: {EA: 1.0e7, path: [KA, HA]}
  rb: {EA: 1.0e7, path: [KB, HB]}
"""
TWO_DRIVES = ("  duration: 4\n  drives:\n    fa: {slider: a, force: 300}\n"
              "    pb: {slider: b, profile: {type: trapezoid, distance: 2, v_max: 1, "
              "a_max: 1}}\n")


@pytest.mark.parametrize("t", [0.5, 1.5])
def test_sway_off_a_joint_coordinate_and_a_load_it_does_not_guide(t):
    """Sway off: load A rides on trolley A's coordinate (its horizontal inertia in
    M_J = 500 + 1000 kg), load B follows trolley B's trapezoid (x = 20 + s_B(t)); q =
    (z_A, z_B, s_A). The guidance of B feeds its horizontal kinetic energy
    T_guided = 1/2 800 s_B'^2; the drives' power is the force's 300 s_A' (both ropes
    vertical: the trolleys do no work on them)."""
    mech = _scene_mech(TWO_TROLLEYS, TWO_DRIVES, "{sway: false}")
    assert mech.n == 3 and mech.nJ == 1
    assert mech.guided_joint.tolist() == [True, False]
    q, v = np.array([0.01, 0.02, 0.4]), np.array([0.2, -0.1, 0.3])
    ev = mech.evaluate(t, q, v, mech.taut0)
    s, ds, _ = trolley_xs(t)
    np.testing.assert_allclose(ev.MJ, [[1500.0]], rtol=1e-12)
    np.testing.assert_allclose(ev.X[mech.free], [[0.4, 0, 0.01], [20 + s, 0, 0.02]],
                               atol=1e-12)
    np.testing.assert_allclose(ev.V[mech.free], [[0.3, 0, 0.2], [ds, 0, -0.1]], atol=1e-12)
    L0 = [10 * np.exp(-1000 * G / 1.0e7), 10 * np.exp(-800 * G / 1.0e7)]
    S = 1.0e7 * np.log((10 - q[:2]) / L0)
    np.testing.assert_allclose(ev.F, [S[0] - 1000 * G, S[1] - 800 * G, 300.0], rtol=RTOL)
    assert ev.T_guided == pytest.approx(0.5 * 800 * ds * ds, rel=RTOL)
    assert ev.P_drive == pytest.approx(300 * 0.3, rel=RTOL)
    T = mech.energy(ev, mech.taut0)[0]
    assert T == pytest.approx(0.5 * 1500 * 0.09 + 0.5 * 1000 * 0.04
                              + 0.5 * 800 * (ds * ds + 0.01), rel=RTOL)


# ----------------------------------------------------------------- an elastic structure and
# a joint coordinate

def _rotor_and_trolley(tmp_path):
    """The spinning cantilever of test_operation_flexible.py (hub at the origin turned
    about z by phi = 0.3 t^2, gravity -9.81 z, one element) and, on the ground beside
    it, a trolley on a force of 300 N (a joint coordinate) carrying an 800 kg load on a
    10 m rope: the structure rides on the hub's frame, which no driven joint moves
    anything on, so both are accepted together."""
    text = ROTOR.replace("gravity: [0, 0, 0]", "gravity: [0, 0, -9.81]")
    text = text.replace("  T: [10.0, 0, 0]\n", "  T: [10.0, 0, 0]\n  K: [30, 0, 10]\n"
                        "  H2: [30, 0, 0]\nmasses: {H2: 800}\n")
    text = text.replace("joints:\n", "  trolley: {mass: 500, com: [30, 0, 10], inertia: "
                        "[10, 10, 10], nodes: [K]}\njoints:\n  - {name: travel, type: slider, "
                        "bodies: [ground, trolley], at: K, axis: [1, 0, 0], range: [-5, 5]}\n")
    text += "ropes:\n  r2: {EA: 1.0e7, path: [K, H2]}\n"
    model = load(write(tmp_path, text, "  duration: 3\n  drives:\n    spin: {hinge: spin, "
                       "profile: {type: table, speed: [[0, 0], [2, 1.2]]}}\n"
                       "    f: {slider: travel, force: 300}\n", NEL=1))
    return mechanism(model)


def test_an_elastic_structure_beside_a_joint_coordinate(tmp_path):
    """q = (the load's x, y, z; the trolley's s; the tip's u in the hub's axes): the
    elastic coordinates come after the joint's. At t = 1 s (phi = 0.3, omega = 0.6) with
    the tip at its static deflection u0 and moving at u' = (0.1, -0.05, 0.02) in the
    hub's axes: the tip at R_z(phi) (X_T + u0); the power fed is the force's 300 s'
    alone: the rope is on no elastic node (no rope power through the tip), the trolley's
    rope end moves with its own coordinate, and the hub's frame feeds
    w . m (x'' - g) = -w . R grad U = 0 (x'' from the forces; the blade's force at the
    static deflection is the tip's weight, vertical, w horizontal). The rope force on
    the load by hand, F_s = 300 (the rope vertical)."""
    mech = _rotor_and_trolley(tmp_path)
    assert (mech.nc, mech.nJ, mech.flex.nu, mech.n) == (3, 1, 3, 7)
    assert mech.flex.labels() == ["T.ux", "T.uy", "T.uz"]
    q = mech.q0.copy()
    u0 = q[4:7]
    q[2] -= 0.01                                      # the load 1 cm down
    v = np.array([0.0, 0.0, 0.1, 0.2, 0.1, -0.05, 0.02])
    t, phi = 1.0, 0.3
    ev = mech.evaluate(t, q, v, mech.taut0)
    c, s = np.cos(phi), np.sin(phi)
    Rz = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
    T = mech.model.node_names.index("T")
    np.testing.assert_allclose(ev.X[T], Rz @ (np.array([10.0, 0, 0]) + u0), atol=1e-12)
    L0 = 10 * np.exp(-800 * G / 1.0e7)
    S = 1.0e7 * np.log((10 - q[2]) / L0)
    np.testing.assert_allclose(ev.F[:4], [0, 0, S - 800 * G, 300.0], rtol=RTOL,
                               atol=RTOL * 800 * G)
    assert abs(ev.P_drive - 300 * 0.2) <= 1e-9 * (60 + S * 0.1)
    # energies: the load, the trolley (M_J = 500 kg), the tip (rho A L / 2 = 39.25 kg) at
    # velocity omega e_z x R Y + R u' (the hub at the origin), their weights' m g z
    mt = 7.85 * 10 / 2
    np.testing.assert_allclose(mech.flex.me, [mt], rtol=1e-14)
    Y = np.array([10.0, 0, 0]) + u0
    w = np.cross([0, 0, 0.6], Rz @ Y) + Rz @ v[4:7]
    Tk, Vg, _ = mech.energy(ev, mech.taut0)
    assert Tk == pytest.approx(0.5 * 800 * 0.01 + 0.5 * 500 * 0.04 + 0.5 * mt * (w @ w),
                               rel=RTOL)
    assert Vg == pytest.approx(800 * G * q[2] + 500 * G * 10 + mt * G * (Rz @ Y)[2],
                               rel=RTOL)


# ----------------------------------------------------------------- three joint coordinates

def test_three_joint_coordinates_in_one_chain_place_by_hand():
    """The gantry of test_mutation_kills_mechanism_configs.py with its three joints as
    coordinates (the bridge and the trolley on forces, the hook block on a torque): q =
    (the load's x, y, z; s_a, s_b, rho phi) with rho = 1 m (the block's node B from the
    axis through K). P moves by (0, s_a, 0), K by (s_b, s_a, 0), B to
    Rz(phi) (B0 - K0) + K0 + (s_b, s_a, 0), its velocity omega e_z x Rz(phi) (B0 - K0)
    + (s_b', s_a', 0): from place() without the joints' motions (the positions the
    results record, integrate's Generic.place) and from evaluate (with them)."""
    mech = _scene_mech(GANTRY, "  duration: 4\n  drives:\n    a: {slider: run, force: 100}\n"
                       "    b: {slider: travel, force: 50}\n    c: {hinge: turn, torque: 10}\n")
    assert (mech.nc, mech.nJ) == (3, 3) and [jc["rho"] for jc in mech.jc] == [1, 1, 1]
    q = mech.q0.copy()
    q[3:6] = [0.7, 0.4, 0.3]
    v = np.zeros(6)
    v[3:6] = [0.1, 0.2, 0.3]
    c, s = np.cos(0.3), np.sin(0.3)
    want = {"P": ([0, 0.7, 12], [0, 0.1, 0]), "K": ([0.4, 0.7, 10], [0.2, 0.1, 0]),
            "B": ([c + 0.4, s + 0.7, 10], [-0.3 * s + 0.2, 0.3 * c + 0.1, 0])}
    X, V, _, _ = mech.place(1.0, q, v)
    ev = mech.evaluate(1.0, q, v, mech.taut0)
    for name, (x, w) in want.items():
        i = mech.model.node_index[name]
        for XX, VV in ((X, V), (ev.X, ev.V)):
            np.testing.assert_allclose(XX[i], x, rtol=0, atol=1e-12)
            np.testing.assert_allclose(VV[i], w, rtol=0, atol=1e-12)
