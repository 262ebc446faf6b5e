"""Kill tests for configurations of cranefe/analysis/operation/mechanism.py that the other
mechanism kill tests do not build (issue 20, mutation testing; docs/mutation.md,
mechanism.py's section, "untested configurations"):

- a slider whose point is listed on no body: it moves with the joint's first body
  (docs/model-format.md, "Node kinds"), so a rope from it stays with the ground while the
  trolley travels, and moves with the trolley (by -s) when the trolley is listed first;
- bodies two levels below a joint coordinate's body (slewing jib -> trolley -> basket):
  the coordinate's length scale rho is the basket's radius, its mass I_z / rho^2 with the
  three bodies' I_zz + m r^2, its force the rope's moment about the axis over rho;
- springs between kinematic nodes (an axial spring from the ground to a moving trolley, a
  rotational one between them): no force computed, no energy, no power; a spring on a
  body a joint coordinate moves is refused (its force would not reach the coordinate);
- a joint coordinate with a drum coordinate after it (q = (x, z, u, theta)): the luffing
  arm free on its stay, the load hoisted over its tip by a torque drum; F and K by
  moments about the hinge and central differences of that hand force;
- a four-bar luffed by a linear drive (the construction in Mechanism._tree): the boom's
  tip and the load's force against the hand geometry of test_mutation_kills_linkage.py,
  the hinges' ranges checked over the scene's duration;
- a joint coordinate past its range (free with and without drums by profiles, torque,
  motor, force): the whole message, and the 1e-9 slack at either end;
- poses() of an elastic structure's nodes with their frame (a hub off the origin).

Tolerances: 1e-9 relative for closed forms (a few operations on O(1e4) numbers, the
ln(L/L0) of a 1e-4 strain loses ~4 digits of 1e-16); positions 1e-12 m (a rotation of
O(10) m vectors); central differences with step 1e-6: truncation h^2 |F'''| ~ 1e-12 of
the entries, round-off 1e-16 |F| / h ~ 1e-6 N/m against entries of 1e4-1e7: 1e-6
relative; the linkage's geometry 1e-9 m (its reference's accuracy,
test_mutation_kills_linkage.py's docstring).
"""

import numpy as np
import pytest
from test_mutation_kills_linkage import NODES as FOUR_BAR
from test_mutation_kills_linkage import _reference, drive_of
from test_mutation_kills_mechanism import (
    ARM,
    IO,
    MB,
    ML,
    SLEWING,
    SPRING,
    TROLLEY,
    TROLLEY_DRIVE,
    _count,
    _dir,
    _mech,
    _scene_mech,
    trolley_xs,
)
from test_operation_flexible import ROTOR, write

from cranefe.analysis.operation.linkage import LinkageDrive
from cranefe.errors import AnalysisError, ModelError
from cranefe.model import load

G = 9.81
RTOL = 1e-9
BASE = TROLLEY.replace("MASS", "1000").replace("EAVAL", "1.0e7")


def _names(mech, nodes):
    return [mech.model.node_names[i] for i in nodes]


# ----------------------------------------------------------------- a joint's point

@pytest.mark.parametrize("first", ["ground", "trolley"])
def test_a_slider_point_on_no_body_moves_with_the_joints_first_body(first):
    """The trolley's slider at K, K on no body's list: K moves with the joint's first
    body. [ground, trolley]: K stays at (0, 0, 10) while the trolley travels, the load
    hangs at rest (F = 0 at its reference place). [trolley, ground]: the trolley is the
    child moved by -s (the joint's motion is bodies[1]'s relative to bodies[0]) and K
    with it: the rope's force on the load at its reference place by hand."""
    text = BASE.replace("nodes: [K]}", "nodes: []}")
    if first == "trolley":
        text = text.replace("bodies: [ground, trolley]", "bodies: [trolley, ground]")
    mech = _scene_mech(text, TROLLEY_DRIVE)
    K = mech.model.node_names.index("K")
    assert mech.carrier[K] == (-1 if first == "ground" else 0)
    m, EA = 1000.0, 1.0e7
    L0 = 10.0 * np.exp(-m * G / EA)
    for t in (0.5, 1.5, 2.5):
        s, ds, dds = trolley_xs(t)
        xk, vk, ak = (0.0, 0.0, 0.0) if first == "ground" else (-s, -ds, -dds)
        X, V, A, _ = mech.kinematics(t)
        np.testing.assert_allclose([X[K], V[K], A[K]],
                                   [[xk, 0, 10], [vk, 0, 0], [ak, 0, 0]], atol=1e-12)
        ev = mech.evaluate(t, mech.q0, np.zeros(2), np.array([True]), damping=False)
        d = np.array([-xk, -10.0])                  # K -> H, H at (0, 0)
        L = np.hypot(*d)
        S = EA * np.log(L / L0)
        np.testing.assert_allclose(ev.F, np.array([0.0, -m * G]) - S * d / L,
                                   rtol=RTOL, atol=1e-9 * m * G)
        # the power the moving rope end feeds: -S e . V_K (zero on the ground)
        assert ev.P_drive == pytest.approx(-S * (d[0] / L) * vk, rel=RTOL, abs=1e-9)


# ----------------------------------------------------------------- two levels below

# slewing jib (a torque coordinate) -> trolley (held slider) -> basket (held hinge),
# the load H on the basket's node B at radius 9, beyond the trolley (6) and the jib's
# centre of mass (4)
DEEP = (SLEWING.replace("com: [10, 0, 30]", "com: [4, 0, 30]")
        .replace("H: [6, 0, 20]", "B: [9, 0, 30]\n  H: [9, 0, 20]")
        .replace("joints:", "  basket: {mass: 100, com: [9, 0, 30], inertia: [1, 1, 2], "
                 "nodes: [B]}\njoints:")
        .replace("ropes:", "  - {name: tilt, type: hinge, bodies: [trolley, basket], at: K, "
                 "axis: [0, 1, 0]}\nropes:")
        .replace("hoist: {EA: 1.0e8, path: [K, H]}", "hoist: {EA: 1.0e8, path: [B, H]}"))


def test_a_body_two_levels_below_a_joint_coordinate():
    """The slewing coordinate u = rho phi carries the trolley and, one level further, the
    basket: rho = 9 m (the basket's node and centre of mass), nodes T, K, B (O is
    the ground's);
    M_J = (I_zz + m r^2 summed: 1e5 + 5000 4^2 + 10 + 500 6^2 + 2 + 100 9^2) / rho^2;
    the load pushed 0.3 m sideways pulls B with S d / L, moment about z
    M_z = x_B f_y = 9 S 0.3 / L, F_u = M_z / rho; poses turn B with the jib."""
    mech = _scene_mech(DEEP, "  duration: 2\n  drives:\n    s: {hinge: slew, torque: 0}\n")
    assert mech.nJ == 1 and mech.n == 4
    (jc,) = mech.jc
    assert jc["rho"] == 9.0 and _names(mech, jc["nodes"]) == ["T", "K", "B"]
    B = mech.model.node_names.index("B")
    assert B in mech.jnodes
    I_z = 1e5 + 5000 * 16 + 10 + 500 * 36 + 2 + 100 * 81
    m, EA = 1000.0, 1.0e8
    q = np.array([9.0, 0.3, 20.05, 0.0])
    ev = mech.evaluate(0.0, q, np.zeros(4), mech.taut0, damping=False)
    np.testing.assert_allclose(ev.MJ, [[I_z / 81]], rtol=1e-12)
    d = np.array([0.0, 0.3, -9.95])                  # B -> H
    L = np.linalg.norm(d)
    S = EA * np.log(L / (10 * np.exp(-m * G / EA)))
    np.testing.assert_allclose(ev.F, [*(np.array([0, 0, -m * G]) - S * d / L),
                                      9 * S * 0.3 / L / 9.0], rtol=RTOL)
    phi = 0.4
    Xp = mech.poses(0.0, {"s": (phi, 0.0)})[1]
    np.testing.assert_allclose(Xp[B], [9 * np.cos(phi), 9 * np.sin(phi), 30], atol=1e-12)
    assert mech.joint_state(mech.jc[0]["drive"], 0.0, q + [0, 0, 0, 9 * phi],
                            np.array([0, 0, 0, 9 * 0.1])) == pytest.approx((phi, 0.1))
    # the basket's hinge a coordinate too: its subtree is the basket alone, rho = 3 m
    # (B and the centre of mass from the axis through K; the jib's T would be 6 m), its
    # mass (I_yy + m 3^2) / 3^2 at the reference pose
    mech = _scene_mech(DEEP, "  duration: 2\n  drives:\n    s: {hinge: slew, torque: 0}\n"
                             "    b: {hinge: tilt, torque: 0}\n")
    assert [jc["rho"] for jc in mech.jc] == [9.0, 3.0]
    assert [_names(mech, jc["nodes"]) for jc in mech.jc] == [["T", "K", "B"], ["B"]]
    ev = mech.evaluate(0.0, mech.q0, np.zeros(mech.n), mech.taut0)
    assert ev.MJ[1, 1] == pytest.approx((1 + 100 * 9) / 9, rel=1e-12)


# ----------------------------------------------------------------- springs

def test_springs_between_kinematic_nodes_carry_no_force():
    """An axial spring from a ground node to the travelling trolley and a rotational one
    between the ground and the trolley: the trolley's motion is prescribed, so neither
    has a force, an energy or a power in the load's equations (ev.N empty, U the rope's
    Hencky energy only, the power -S e . V_K of the rope alone)."""
    text = (BASE.replace("  H: [0, 0, 0]\n", "  H: [0, 0, 0]\n  A: [-5, 0, 10]\n")
            .replace("masses:", "ground: [A]\nmasses:")
            + "springs:\n  - {name: tie, type: axial, nodes: [A, K], stiffness: 1.0e6}\n"
              "  - {name: twist, type: rotational, bodies: [ground, trolley], at: K, "
              "stiffness: 1.0e6}\n")
    mech = _scene_mech(text, TROLLEY_DRIVE)
    assert len(mech.sp_k) == 0 and len(mech.N_ref) == 0
    m, EA, t = 1000.0, 1.0e7, 1.5
    L0 = 10.0 * np.exp(-m * G / EA)
    s, ds = trolley_xs(t)[:2]
    q, v = np.array([0.7, 0.9]), np.array([0.3, -0.2])
    ev = mech.evaluate(t, q, v, np.array([True]))
    assert len(ev.N) == 0
    d = np.array([q[0] - s, q[1] - 10.0])
    L = np.hypot(*d)
    S = EA * np.log(L / L0)
    np.testing.assert_allclose(ev.F, np.array([0.0, -m * G]) - S * d / L, rtol=RTOL)
    assert ev.P_drive == pytest.approx(-S * d[0] / L * ds, rel=RTOL)
    U = mech.energy(ev, np.array([True]))[2]
    assert U == pytest.approx(EA * (L * np.log(L / L0) - L + L0), rel=1e-7)


# ----------------------------------------------------------------- joint + drum coordinates

# the luffing arm (free on its stay) with the load hoisted over its tip T from the drum
# w at W, level with the hinge O and the tip (the span W-T passes through O's height:
# its pull has no moment about O at the reference pose)
ARM_DRUM = (ARM.replace("  H: [4, 0, 5]\n", "  H: [4, 0, 5]\n  W: [-2, 0, 10]\n")
            .replace("ground: [P]", "ground: [P, W]\ndrums:\n  w: {node: W, radius: 0.5, "
                     "inertia: 20}")
            .replace("hoist: {EA: 1.0e8, psi: 0.2, path: [T, H]}",
                     "hoist: {EA: 1.0e8, path: [w, T, H]}"))
EA_H, EA_S, R_W, J_W, TQ = 1.0e8, 5.0e8, 0.5, 20.0, 1000.0


def _arm_drum_force(x, z, u, th):
    """(x, z, u, theta) -> generalised force by hand. The arm turned by phi = u / 4 about
    +y through O = (0, 10) (a positive turn takes the tip down): T = O + 4 (cos, -sin);
    the stay P-T and the hoist W-T-H with L0 = L_ref exp(-S0/EA) (hoist: L_ref = 6 + 5,
    S0 = m_l g; stay: L_ref = sqrt 32 and S0 by the moment balance at rest
    4 S0 (4 / sqrt 32) = 2 m_b g + 4 m_l g, the hoist's tip force vertical there), the
    hoist's L0 less R theta / lambda_ref; F_u = (moments about O) / rho, rho = 4 (the
    tip); the drum: the torque less R S."""
    phi = u / 4.0
    T = np.array([4 * np.cos(phi), 10 - 4 * np.sin(phi)])
    P, W, H = np.array([0.0, 14.0]), np.array([-2.0, 10.0]), np.array([x, z])
    S0h = ML * G
    S0s = (2 * MB * G + 4 * ML * G) / (16 / np.sqrt(32))
    lam = np.exp(S0h / EA_H)
    l_tw, l_th, l_tp = (np.linalg.norm(a - T) for a in (W, H, P))
    Lh = l_tw + l_th
    L0h = (11.0 - R_W * th) / lam
    Sh = EA_H * np.log(Lh / L0h)
    Ss = EA_S * np.log(l_tp / (np.sqrt(32) * np.exp(-S0s / EA_S)))
    f = Ss * (P - T) / l_tp + Sh * ((W - T) / l_tw + (H - T) / l_th)   # on the tip
    r = T - np.array([0.0, 10.0])
    M = 2 * np.cos(phi) * MB * G + (r[1] * f[0] - r[0] * f[1])      # about +y
    FH = np.array([0.0, -ML * G]) - Sh * (H - T) / l_th
    return np.array([*FH, M / 4.0, TQ - R_W * Sh])


def test_a_joint_coordinate_before_a_drum_coordinate():
    """q = (x_H, z_H, u, theta): the joint block is u's row and column only (jb), the
    drum's row the torque less R S; M = diag(m_l, m_l, I_O / rho^2, J)."""
    mech = _scene_mech(ARM_DRUM, f"  duration: 2\n  drives:\n    d: {{hinge: luff, free: "
                                 f"true}}\n    h: {{drum: w, torque: {TQ}}}\n")
    assert (mech.nc, mech.nJ, mech.n) == (2, 1, 4) and mech.qdrums == [0]
    assert mech.jb == slice(2, 3)
    np.testing.assert_allclose(mech.S0, [ML * G, (2 * MB * G + 4 * ML * G)
                                         / (16 / np.sqrt(32))], rtol=RTOL)
    for state in ([4.0, 5.0, 0.0, 0.0], [4.1, 5.05, 0.0, 0.02], [4.1, 5.05, 0.08, 0.02]):
        q = np.array(state)
        v = np.zeros(4)
        ev = mech.evaluate(0.0, q, v, np.array([True, True]), damping=False)
        Fh = _arm_drum_force(*q)
        np.testing.assert_allclose(ev.F, Fh, rtol=1e-9, atol=1e-9 * ML * G)
        h = 1e-6
        Kfd = np.zeros((4, 4))
        for j in range(4):
            dq = np.zeros(4)
            dq[j] = h
            Kfd[:, j] = -(_arm_drum_force(*(q + dq)) - _arm_drum_force(*(q - dq))) / (2 * h)
        np.testing.assert_allclose(ev.K, Kfd, rtol=1e-6, atol=1e-6 * np.abs(Kfd).max())
        np.testing.assert_allclose(mech.mass_matrix(ev),
                                   np.diag([ML, ML, IO / 16, J_W]), rtol=1e-12)
        assert ev.drive_torque.tolist() == [TQ]
    # the drum's angle and speed come from q, v after the joint coordinate; the tip
    # T = O + 4 (cos, -sin) phi moves at 4 (-sin, -cos) phi', phi' = u' / rho
    v = np.array([0.1, 0.2, 0.3, 0.4])
    X, V, theta, omega = mech.place(0.0, q, v)
    phi, dphi = q[2] / 4, 0.3 / 4
    Ti = mech.model.node_index["T"]
    np.testing.assert_allclose(X[Ti], [4 * np.cos(phi), 0, 10 - 4 * np.sin(phi)], atol=1e-12)
    np.testing.assert_allclose(V[Ti], [-4 * np.sin(phi) * dphi, 0, -4 * np.cos(phi) * dphi],
                               atol=1e-12)
    assert theta.tolist() == [q[3]] and omega.tolist() == [0.4]
    assert mech.joint_state(mech.jc[0]["drive"], 0.0, q, v) == pytest.approx(
        (q[2] / 4, 0.3 / 4), rel=1e-15)


# ----------------------------------------------------------------- linear drive

def test_a_four_bar_luffed_by_a_linear_drive(tmp_path, monkeypatch):
    """The linkage test's four-bar (cylinder on the coupler) in a Mechanism: the boom's
    tip B = R B0 + p of the hand geometry at three times, the load's rope force from it
    by hand; the closing joint (tie - rocker) is the linkage's, not a loop; the hinges'
    ranges are checked over the scene's duration, 6 s (LinkageDrive.check_range, whose
    refusals test_mutation_kills_linkage.py checks: 401 linkage solves, seconds)."""
    model, drive = drive_of(tmp_path)
    seen = []
    check = LinkageDrive.check_range
    monkeypatch.setattr(LinkageDrive, "check_range",
                        lambda self, duration: seen.append(duration) or check(self, duration))
    mech = _mech(model)
    assert seen == [6.0]
    assert mech.linear is not None and mech.n == 2
    B = model.node_index["B"]
    m, EA = 1000.0, 1.0e6
    L0 = 7.0 * np.exp(-m * G / EA)
    for t in (0.0, 1.3, 3.7):
        maps = _reference(t, drive.motion)[3]
        (R, p), (dR, dp), (ddR, ddp) = maps["boom"]
        Xb = R @ FOUR_BAR["B"] + p
        X, V, A, _ = mech.kinematics(t)
        np.testing.assert_allclose(X[B][[0, 2]], Xb, atol=1e-9)
        np.testing.assert_allclose(mech.poses(t, {})[1][B][[0, 2]], Xb, atol=1e-9)
        np.testing.assert_allclose(V[B][[0, 2]], dR @ FOUR_BAR["B"] + dp, atol=1e-9)
        np.testing.assert_allclose(A[B][[0, 2]], ddR @ FOUR_BAR["B"] + ddp, atol=1e-9)
        ev = mech.evaluate(t, mech.q0, np.zeros(2), np.array([True]), damping=False)
        d = np.array([11.0, 5.0]) - Xb                  # B -> H
        L = np.hypot(*d)
        S = EA * np.log(L / L0)
        np.testing.assert_allclose(ev.F, np.array([0.0, -m * G]) - S * d / L,
                                   rtol=1e-7, atol=1e-7 * m * G)


# a spring on the luffing arm, which a free or torque drive moves as a coordinate
SPRING_ON_ARM = {
    # the load on an axial spring from the tip instead of the hoist rope (before the
    # refusal: its weight did not reach the arm, the stay carried 1387 N, not 5549 N)
    # (a rotational spring at the hinge and an axial one on the arm listed first: both
    # accepted, the search goes on)
    "load": ARM.replace("  hoist: {EA: 1.0e8, psi: 0.2, path: [T, H]}\n", "")
    + ("springs:\n  - {name: rot, type: rotational, bodies: [ground, arm], at: O, "
       "stiffness: 1.0e7}\n  - {name: arm, type: axial, nodes: [O, T], stiffness: 1.0e7}\n"
       "  - {name: sp, type: axial, nodes: [T, H], stiffness: 1.0e7}\n"),
    # between bodies: a tie from the ground beside the stay, a rotational spring at the
    # hinge (what holds the joint in the linear analyses: no force in a scene), and a
    # spring between two nodes of the arm itself
    "ground": ARM + "springs:\n  - {name: sp, type: axial, nodes: [P, T], "
                    "stiffness: 1.0e7}\n",
    "rotational": ARM + "springs:\n  - {name: sp, type: rotational, bodies: [ground, "
                        "arm], at: O, stiffness: 1.0e7}\n",
    "on the arm": ARM + "springs:\n  - {name: sp, type: axial, nodes: [O, T], "
                        "stiffness: 1.0e7}\n",
    # a second load Q (100 kg) on a spring from the ground: a spring on a load, kept
    "ground load": ARM.replace("  H: [4, 0, 5]\n", "  H: [4, 0, 5]\n  Q: [0, 0, 8]\n")
    .replace("masses: {H: 300}", "masses: {H: 300, Q: 100}")
    + "springs:\n  - {name: sp, type: axial, nodes: [P, Q], stiffness: 1.0e7}\n",
}


@pytest.mark.parametrize("drive", ["free: true", "torque: 0"])
@pytest.mark.parametrize("case", list(SPRING_ON_ARM))
def test_a_spring_from_a_load_to_a_joint_coordinates_body_is_refused(case, drive):
    """Exit 2 naming the model file and the spring's entry; springs between bodies are
    accepted and carry no force (docs/operations.md: forces of springs between bodies
    not yet) and a spring from the ground to another load Q carries its weight; the
    free arm's stay holds it by the moment balance about O without the springs between
    bodies, 4 S (4 / sqrt 32) = 2 m_b g + 4 m_l g."""
    analysis = f"  duration: 2\n  drives:\n    d: {{hinge: luff, {drive}}}\n"
    if case != "load":
        mech = _scene_mech(SPRING_ON_ARM[case], analysis)
        assert mech.nJ == 1
        if case == "ground load":             # N0 = m_Q g
            np.testing.assert_allclose(mech.N_ref, [100 * G], rtol=RTOL)
            return
        assert len(mech.sp_k) == 0
        if drive == "free: true":
            np.testing.assert_allclose(mech.S0, [ML * G, (2 * MB * G + 4 * ML * G)
                                                 / (16 / np.sqrt(32))], rtol=RTOL)
        return
    with pytest.raises(ModelError) as exc:
        _scene_mech(SPRING_ON_ARM[case], analysis)
    e = exc.value
    assert e.entry == "springs.sp"
    assert e.message == ("spring 'sp' joins a load or a massless block to body 'arm', which "
                         "drive 'd' moves as a coordinate; the spring's force on the "
                         "coordinate is not computed by operation scenes yet: hang the load "
                         "by a rope, or prescribe the joint's motion by a profile")
    assert str(e.file) == str(_dir() / f"model_s{_count[0]}.yaml")


def test_a_spring_from_a_load_to_a_trolley_coordinate_on_a_slewing_coordinate():
    """Two coordinates, the slewing jib's and the trolley's on it, both carry K; a second
    load Q on a spring from K is refused naming the innermost: the trolley's drive."""
    text = (SLEWING.replace("  H: [6, 0, 20]\n", "  H: [6, 0, 20]\n  Q: [6, 0, 25]\n")
            .replace("masses: {H: 1000}", "masses: {H: 1000, Q: 100}")
            + "springs:\n  - {name: sq, type: axial, nodes: [K, Q], stiffness: 1.0e6}\n")
    with pytest.raises(ModelError) as exc:
        _scene_mech(text, "  duration: 2\n  drives:\n    s: {hinge: slew, torque: 0}\n"
                          "    t: {slider: travel, force: 0}\n")
    assert exc.value.entry == "springs.sq"
    assert exc.value.message.startswith("spring 'sq' joins a load or a massless block to "
                                        "body 'trolley', which drive 't' moves as a "
                                        "coordinate;")


# ----------------------------------------------------------------- ranges

FREE_CAUSE = "the joint is free (free: true): the ropes and weights on it moved it there"
DEG = 180 / np.pi
RANGE_CASES = {
    # (model, drives, the coordinate's index in q, its rho, unit factor, unit, cause)
    "free": (ARM_DRUM,
             ("    d: {hinge: luff, free: true}\n"
              "    h: {drum: w, profile: {type: table, speed: [[0, 0.1]]}}\n"), 2, 4.0, DEG,
             "deg", FREE_CAUSE + (" (drives of drums by profiles: 'h': hauling in or paying "
                                  "out the rope that holds it)")),
    "free, no drum": (ARM, "    d: {hinge: luff, free: true}\n", 2, 4.0, DEG, "deg",
                      FREE_CAUSE),
    "torque": (ARM, "    d: {hinge: luff, torque: 0}\n", 2, 4.0, DEG, "deg",
               "a drive torque that does not stop it"),
    "motor": (ARM,
              ("    d: {hinge: luff, gear_ratio: 30, motor: {stall_torque: 400, "
               "synchronous_speed: 150}}\n"), 2, 4.0, DEG, "deg",
              "a motor that does not stop it"),
    "force": (BASE, "    d: {slider: travel, force: 0}\n", 2, 1.0, 1.0, "m",
              "a drive force that does not stop it"),
}


@pytest.mark.parametrize("case", list(RANGE_CASES))
def test_a_joint_coordinate_past_its_range_names_time_joint_and_cause(case):
    """The luffing arm's hinge allowed [-1, 1] rad ([-57.2958, 57.2958] deg), the trolley's
    slider [-1, 20] m: a coordinate at 1.2 x the upper end (or below the lower end) stops
    the run with the whole message; 1e-9 past either end passes (the check's slack)."""
    text, drives, i, rho, f, unit, cause = RANGE_CASES[case]
    mech = _scene_mech(text, "  duration: 2\n  drives:\n" + drives)
    (jc,) = mech.jc
    lo, hi = mech.model.joints[jc["joint"]].range
    q = np.array(mech.q0, float)
    # inside, and exactly at the 1e-9 slack (the same float operations as the check's;
    # q / rho is exact for rho = 4 and 1)
    for s in (lo + 1e-10, hi - 1e-10, lo - 1e-9, hi + 1e-9):
        q[i] = rho * s
        mech.check_range(mech.evaluate(0.25, q, np.zeros(mech.n), mech.taut0), 0.25)
    label = "'luff' (joints[0])" if unit == "deg" else "'travel' (joints[0])"
    for s in (1.2 * hi, lo - 0.2):
        q[i] = rho * s
        ev = mech.evaluate(0.25, q, np.zeros(mech.n), mech.taut0)
        with pytest.raises(AnalysisError) as exc:
            mech.check_range(ev, 0.25)
        assert str(exc.value) == (
            f"at t = 0.25 s {label} (drive 'd') reached {s * f:.6g} {unit}, past the end of "
            f"its range [{lo * f:g}, {hi * f:g}] {unit}: the engine has no end stops; "
            f"likely cause: {cause}; the results up to t = 0.25 s are kept")


# ----------------------------------------------------------------- an elastic structure

def test_poses_carry_the_elastic_nodes_with_their_frame(tmp_path):
    """The spinning cantilever (tests/test_operation_flexible.py's ROTOR, two elements)
    with its hub axis moved to O = (1, 2, 0): poses() draws the tip T undeflected with
    the hub's frame, O + R_z(phi) (10, 0, 0), phi = 0.6 t^2 / 2 (the table's speed rises
    from 0 to 1.2 rad/s over 2 s); the mid node is the structure's own (not a model
    node) and is left out; a ground node G stays where it is."""
    text = (ROTOR.replace("O: [0, 0, 0]", "O: [1, 2, 0]").replace("T: [10.0, 0, 0]",
                                                                  "T: [11.0, 2, 0]")
            .replace("com: [0, 0, 0]", "com: [1, 2, 0]")
            .replace("  T: [11.0, 2, 0]\n", "  T: [11.0, 2, 0]\n  G: [5.0, 5.0, 5.0]\n")
            .replace("ground: []", "ground: [G]"))
    model = load(write(tmp_path, text, "  duration: 3\n  drives:\n    spin: {hinge: spin, "
                       "profile: {type: table, speed: [[0, 0], [2, 1.2]]}}\n", NEL=2))
    mech = _mech(model)
    assert mech.flex is not None and mech.flex.nu == 6
    T = model.node_index["T"]
    for t in (0.0, 1.0, 1.5):
        phi = 0.3 * t * t
        X = mech.poses(t, {})[1]
        np.testing.assert_allclose(X[T], [1 + 10 * np.cos(phi), 2 + 10 * np.sin(phi), 0],
                                   atol=1e-12)
        np.testing.assert_allclose(X[model.node_index["O"]], [1, 2, 0], atol=1e-12)
        np.testing.assert_allclose(X[model.node_index["G"]], [5, 5, 5], atol=0)


# ----------------------------------------------------------------- powers and dashpots

def test_the_drive_power_of_two_joint_coordinates():
    """The slewing jib (torque 2e4 N m, rho = 10 m) and the trolley on it (force 300 N),
    both turning / running, nothing prescribed: the drives' power is T phi' + F s'
    (phi' = u' / rho) and nothing else (the trolley's rope end moves with its own
    coordinates: no rope power fed from outside)."""
    mech = _scene_mech(SLEWING, "  duration: 2\n  drives:\n    s: {hinge: slew, torque: 2.0e4}\n"
                       "    t: {slider: travel, force: 300}\n")
    assert mech.nJ == 2 and [jc["rho"] for jc in mech.jc] == pytest.approx([10.0, 1.0])
    v = np.array([0.0, 0.0, 0.0, 10 * 0.05, 0.4])
    ev = mech.evaluate(0.0, mech.q0, v, mech.taut0)
    assert ev.P_drive == pytest.approx(2.0e4 * 0.05 + 300 * 0.4, rel=1e-9)


def test_a_soft_spring_dashpot_below_one_radian_per_second():
    """k = 100 N/m under 200 kg: w^2 = k / m = 0.5 (below 1), b = psi k / (2 pi w) and
    C = b e e^T, N = N0 + b e . v along the vertical spring."""
    text = (SPRING.replace("stiffness: 4.0e5", "stiffness: 100")
            .replace("H: [0, 0, 5]", "H: [0, 0, -9.62]"))
    mech = _scene_mech(text, "  duration: 1\n", "{damping: exact}")
    m, k, psi = 200.0, 100.0, 0.4
    b = psi * k / (2 * np.pi * np.sqrt(k / m))
    v = np.array([0.0, 0.0, -0.3])
    ev = mech.evaluate(0.0, mech.q0, v, np.zeros(0, bool))
    np.testing.assert_allclose(ev.C, b * np.diag([0, 0, 1.0]), rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(ev.N, [m * G + b * 0.3], rtol=1e-12)


# ------------------------------------- three prescribed joints in one chain (a gantry)

GANTRY = """cranefe: 1
name: gantry with a slewing hook block
nodes:
  P: [0, 0, 12]
  K: [0, 0, 10]
  B: [1, 0, 10]
  H: [1, 0, 2]
masses: {H: 800}
bodies:
  bridge: {mass: 4000, com: [0, 0, 12], inertia: [100, 100, 100], nodes: [P]}
  trolley: {mass: 600, com: [0, 0, 10], inertia: [10, 10, 10], nodes: [K]}
  block: {mass: 50, com: [0.5, 0, 10], inertia: [1, 1, 1], nodes: [B]}
joints:
  - {name: run, type: slider, bodies: [ground, bridge], at: P, axis: [0, 1, 0],
     range: [-1, 10]}
  - {name: travel, type: slider, bodies: [bridge, trolley], at: K, axis: [1, 0, 0],
     range: [-1, 10]}
  - {name: turn, type: hinge, bodies: [trolley, block], at: K, axis: [0, 0, 1]}
ropes:
  hoist: {EA: 1.0e7, path: [B, H]}
"""


def test_three_prescribed_joints_in_one_chain_compose_by_hand():
    """A bridge running along y, a trolley travelling along x on it and a hook block
    turning about z on the trolley, by trapezoids of the same times scaled (2, 1 and 0.5
    x trolley_xs: 4 m, 2 m, 1 rad; distinct, so each joint must read its own state):
    the bridge moves by (0, a, 0), the trolley by (b, a, 0) (its parent's translation
    added), the block by X -> Rz(c) (X - K0) + K0 + (b, a, 0), with their
    first and second time derivatives (Rz(s)' = s' A, A = dRz/ds; Rz'' = s'' A + s'^2
    d2Rz/ds2). The block's node B and its velocity by the same map. Tolerance 1e-12
    (products of O(10) numbers)."""
    def prof(k):
        return f"{{type: trapezoid, distance: {2 * k}, v_max: {k}, a_max: {k}}}"
    mech = _scene_mech(GANTRY, "  duration: 4\n  drives:\n"
                       f"    a: {{slider: run, profile: {prof(2)}}}\n"
                       f"    b: {{slider: travel, profile: {prof(1)}}}\n"
                       f"    c: {{hinge: turn, profile: {prof(0.5)}}}\n")
    names = {b.name: i for i, b in enumerate(mech.model.bodies)}
    K0 = np.array([0.0, 0.0, 10.0])
    B0 = np.array([1.0, 0.0, 10.0])
    for t in (0.4, 1.5, 2.7, 3.5):
        a, b, s = (k * np.array(trolley_xs(t)) for k in (2.0, 1.0, 0.5))
        s, ds, dds = s
        c, n = np.cos(s), np.sin(s)
        R = np.array([[c, -n, 0], [n, c, 0], [0, 0, 1.0]])
        A = np.array([[-n, -c, 0], [c, -n, 0], [0, 0, 0.0]])
        A2 = np.array([[-c, n, 0], [-n, -c, 0], [0, 0, 0.0]])
        dR, ddR = ds * A, dds * A + ds ** 2 * A2
        d, dd, ddd = (np.array([b[k], a[k], 0.0]) for k in range(3))
        e_y = np.array([0.0, 1.0, 0.0])
        want = {"bridge": (np.eye(3), 0 * A, 0 * A, a[0] * e_y, a[1] * e_y, a[2] * e_y),
                "trolley": (np.eye(3), 0 * A, 0 * A, d, dd, ddd),
                "block": (R, dR, ddR, K0 - R @ K0 + d, -dR @ K0 + dd, -ddR @ K0 + ddd)}
        got = mech.body_motions(t)
        for body, ref in want.items():
            for g, r in zip(got[names[body]], ref):
                assert np.allclose(g, r, rtol=0, atol=1e-12), (t, body)
        X, V, _, _ = mech.kinematics(t)
        b = mech.model.node_index["B"]
        assert np.allclose(X[b], R @ (B0 - K0) + K0 + d, rtol=0, atol=1e-12), t
        assert np.allclose(V[b], dR @ (B0 - K0) + dd, rtol=0, atol=1e-12), t
