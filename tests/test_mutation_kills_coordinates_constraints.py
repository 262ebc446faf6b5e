"""Kill tests for cranefe/coordinates/constraints.py (tools/mutation.py coords_constraints;
docs/testing.md, "Mutation testing"): the rows G of joints, linear drives, supports and
inextensible ropes and their master-slave elimination T_c (docs/theory.md section 1,
"Constraints and the master-slave transform"), against small models done by hand.

A point p of a rigid group moves by u_p = u_g + t x c, c = p - x_g (theory.md section 1);
a joint keeps the relative motion its type leaves free; the elimination keeps rotations
(a hinge is described by its angle) and drops redundant rows of closed loops. Where the
kept coordinate is a pivoting choice among equals (which rotation component of an
inclined hinge), the test normalises by it instead of fixing it.
"""

import math

import numpy as np
import pytest

from cranefe.analysis.modal import modes
from cranefe.coordinates import build_dofs
from cranefe.coordinates.constraints import _eliminate, _perp
from cranefe.errors import ModelError
from cranefe.model import load
from cranefe.system import assemble

G = 9.81

PENDULUM = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 10], C: [0, 0, 6]}
ground: [O]
bodies: {bob: {mass: 100, com: C, inertia: 2, nodes: [O, C]}}
joints:
  - {type: hinge, bodies: [ground, bob], at: O}
"""


def test_planar_hinge_keeps_the_angle_and_swings_at_the_compound_pendulum_frequency():
    """c = C - O = (0, 0, -4): u_C = t x c = (-4 theta, 0, 0), so T_c = [-4, 0, 1] on
    (ux, uz, ry) with ry the coordinate. The compound pendulum: w^2 = m g l / (I + m l^2)
    = 100 g 4 / 1602. The hinge's rows: relative translation of O (3, the y row empty in
    the plane) and rotation normal to y (2, empty in the plane). Tolerance 1e-12 (a 1 x 1
    problem)."""
    m = load("p.yaml", PENDULUM)
    d = build_dofs(m)
    assert d.labels == ("body bob ry",)
    np.testing.assert_allclose(d.T_c.toarray(), [[-4.0], [0.0], [1.0]], atol=1e-14)
    (c,) = d.constraints
    assert (c.name, c.owner, c.groups) == ("hinge joint at O", ("joint", 0), (-1, 0))
    np.testing.assert_array_equal(c.point, [0, 0, 10])
    np.testing.assert_array_equal(c.directions, np.vstack([np.eye(3), np.zeros((2, 3))]))
    # rows: -(u_g + t x (O - x_g)) with O - x_g = (0, 0, 4): x: -(ux + 4 ry), z: -uz;
    # rotation rows normal to y (its perp: x and z) are zero in the plane
    rows = c.rows[np.abs(c.rows).sum(axis=1) > 0]
    np.testing.assert_allclose(np.abs(rows), [[1, 0, 4], [0, 1, 0]], atol=1e-14)
    assert c.rows.shape == (5, 3)
    np.testing.assert_allclose(modes(m).omega ** 2, [100 * G * 4 / 1602], rtol=1e-12)


def test_a_long_pendulum_still_keeps_its_angle():
    """Rotations are weighed in length units (theta x model size) before the pivoting,
    so a 20 m pendulum (|c| = 20 m, model size 20 m) keeps its angle too, as a 4 m one:
    T_c = [-20, 0, 1] on (ux, uz, ry), with ry the coordinate (unscaled, the rotation's
    column of norm 20 would outweigh the translations' 10 and become the slave)."""
    d = build_dofs(load("l.yaml", PENDULUM.replace("O: [0, 0, 10], C: [0, 0, 6]",
                                                   "O: [0, 0, 20], C: [0, 0, 0]")))
    assert d.labels == ("body bob ry",)
    np.testing.assert_allclose(d.T_c.toarray(), [[-20.0], [0.0], [1.0]], atol=1e-13)


def test_joints_after_a_fixed_joint_and_after_a_joint_inside_a_group_still_count():
    """A cap fixed to the bob (listed first), a hinge between bob and cap (one rigid
    group: nothing to constrain), then the hinge to ground: the group bob+cap (reference
    the mass centre (100 (0, 0, 6) + 100 (0, 0, 8)) / 200 = (0, 0, 7), 3 m below O) is a
    pendulum: T_c = [-3, 0, 1]."""
    text = PENDULUM.replace("nodes: {O: [0, 0, 10], C: [0, 0, 6]}",
                            "nodes: {O: [0, 0, 10], C: [0, 0, 6], E: [0, 0, 8]}").replace(
        "bodies: {bob: {mass: 100, com: C, inertia: 2, nodes: [O, C]}}",
        "bodies:\n  bob: {mass: 100, com: C, inertia: 2, nodes: [O, C]}\n"
        "  cap: {mass: 100, com: E, inertia: 1, nodes: [E]}").replace(
        "joints:\n", "joints:\n  - {type: fixed, bodies: [bob, cap], at: C}\n"
        "  - {type: hinge, bodies: [bob, cap], at: E}\n")
    d = build_dofs(load("c.yaml", text))
    assert d.labels == ("body bob+cap ry",)
    assert [c.name for c in d.constraints] == ["hinge joint at O"]
    np.testing.assert_allclose(d.T_c.toarray(), [[-3.0], [0.0], [1.0]], atol=1e-14)


def test_double_pendulum_hinges_between_two_bodies():
    """3D: a hinged to ground at O (0, 0, 10) about y, b hinged to a at P (0, 0, 6) about
    y; centres of mass A (0, 0, 8), B (0, 0, 4). With the two angles as coordinates:
    u_A = ta y x (A - O) = (-2 ta, 0, 0), u_B = ta y x (P - O) + tb y x (B - P) =
    (-4 ta - 2 tb, 0, 0), the rotations (0, ta, 0) and (0, tb, 0). The hinge a-b's rows
    use both groups' rotations (a ball there would leave b three rotations)."""
    d = build_dofs(load("dp.yaml", """cranefe: 1
nodes: {O: [0, 0, 10], A: [0, 0, 8], P: [0, 0, 6], B: [0, 0, 4]}
ground: [O]
bodies:
  a: {mass: 10, com: A, inertia: [1, 1, 1], nodes: [A]}
  b: {mass: 10, com: B, inertia: [1, 1, 1], nodes: [B]}
joints:
  - {type: hinge, bodies: [ground, a], at: O, axis: [0, 1, 0]}
  - {type: hinge, bodies: [a, b], at: P, axis: [0, 1, 0]}
"""))
    assert d.labels == ("body a ry", "body b ry")
    want = np.zeros((12, 2))
    want[[0, 4], 0] = [-2, 1]
    want[6, 0] = -4
    want[[6, 10], 1] = [-2, 1]
    np.testing.assert_allclose(d.T_c.toarray(), want, atol=1e-13)
    assert [c.groups for c in d.constraints] == [(-1, 0), (0, 1)]


def test_hinge_on_a_body_hung_on_a_ball_turns_relative_to_it():
    """a hangs on a ball at O, b on a hinge about y at P on a: four coordinates, spanning
    a's three rotations t_a (b follows rigidly: u = t_a x (p - O) for every point) and
    b's turn about y relative to a (u_B = y x (B - P), t_b = y). The hinge's rotation rows
    are those of t_b - t_a (with t_b + t_a, b would follow a's turns mirrored). The
    space is compared (rank of [T_c, hand basis] = 4 to 1e-9 of the entries), not the
    pivoting's choice of the four rotations kept."""
    O, A, P, B = (np.array(v, float) for v in ([0, 0, 10], [1, 0, 8], [0, 0, 6], [1, 1, 4]))
    d = build_dofs(load("bh.yaml", """cranefe: 1
nodes: {O: [0, 0, 10], A: [1, 0, 8], P: [0, 0, 6], B: [1, 1, 4]}
ground: [O]
bodies:
  a: {mass: 10, com: A, inertia: [1, 1, 1], nodes: [A]}
  b: {mass: 10, com: B, inertia: [1, 1, 1], nodes: [B]}
joints:
  - {type: ball, bodies: [ground, a], at: O}
  - {type: hinge, bodies: [a, b], at: P, axis: [0, 1, 0]}
"""))
    H = np.zeros((12, 4))
    for k, t in enumerate(np.eye(3)):
        H[:, k] = np.concatenate([np.cross(t, A - O), t, np.cross(t, B - O), t])
    y = np.array([0.0, 1.0, 0.0])
    H[6:, 3] = np.concatenate([np.cross(y, B - P), y])
    T = d.T_c.toarray()
    assert T.shape == (12, 4)
    assert np.linalg.matrix_rank(np.hstack([T, H]), tol=1e-9 * abs(H).max()) == 4


def test_ball_joint_leaves_the_three_rotations():
    """3D ball at O: c = C - O = (1, 2, -4), u_C = t x c = (-4 ty - 2 tz, 4 tx + tz,
    2 tx - ty), the rotations t the coordinates (exact integers)."""
    d = build_dofs(load("b.yaml", """cranefe: 1
nodes: {O: [0, 0, 10], C: [1, 2, 6]}
ground: [O]
bodies: {bob: {mass: 100, com: C, inertia: [2, 3, 4], nodes: [C]}}
joints:
  - {type: ball, bodies: [ground, bob], at: O}
"""))
    assert d.labels == ("body bob rx", "body bob ry", "body bob rz")
    np.testing.assert_allclose(d.T_c.toarray(), [[0, -4, -2], [4, 0, 1], [2, -1, 0],
                                                 [1, 0, 0], [0, 1, 0], [0, 0, 1]],
                               atol=1e-13)
    (c,) = d.constraints
    assert c.rows.shape == (3, 6) and c.directions.shape == (3, 3)


def test_two_coaxial_hinges_are_one_hinge_redundant_rows_drop_out():
    """Hinges at O and at P = O + 5 a on the same axis a = (0.6, 0, 0.8): 10 rows on 6
    coordinates of rank 5; one rotation about a is left: t = a / a_k with k the kept
    rotation component, u_C = t x (C - O), C - O = (1, 2, -4)."""
    d = build_dofs(load("h.yaml", """cranefe: 1
nodes: {O: [0, 0, 10], C: [1, 2, 6], P: [3, 0, 14]}
ground: [O, P]
bodies: {bob: {mass: 100, com: C, inertia: [2, 3, 4], nodes: [C]}}
joints:
  - {type: hinge, bodies: [ground, bob], at: O, axis: [0.6, 0, 0.8]}
  - {type: hinge, bodies: [ground, bob], at: P, axis: [0.6, 0, 0.8]}
"""))
    assert len(d.labels) == 1 and d.labels[0][:-1] == "body bob r"
    a = np.array([0.6, 0.0, 0.8])
    t = a / a["xyz".index(d.labels[0][-1])]
    np.testing.assert_allclose(d.T_c.toarray()[:, 0],
                               np.concatenate([np.cross(t, [1, 2, -4]), t]), atol=1e-12)
    assert [c.rows.shape for c in d.constraints] == [(5, 6), (5, 6)]
    for c in d.constraints:           # the rotation rows: normal to a, on (rx, ry, rz)
        np.testing.assert_allclose(c.rows[3:, 3:] @ a, 0, atol=1e-15)
        np.testing.assert_allclose(np.abs(np.linalg.det(np.vstack([c.rows[3:, 3:], a]))),
                                   1, rtol=1e-12)


def test_perp_gives_two_orthonormal_directions_normal_to_the_axis():
    for axis in ([0.6, 0.0, 0.8], [0.0, 1.0, 0.0], [2 / 3, -1 / 3, 2 / 3]):
        p = _perp(np.array(axis))
        assert p.shape == (2, 3)
        np.testing.assert_allclose(p @ axis, 0, atol=1e-15)
        np.testing.assert_allclose(p @ p.T, np.eye(2), atol=1e-15)


SLIDER = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 10], C: [0, 0, 6]}
ground: [O]
bodies: {bob: {mass: 100, com: C, inertia: 2, nodes: [C]}}
joints:
  - {type: slider, bodies: [ground, bob], at: O, axis: [0.6, 0, 0.8]}
springs:
  - {type: axial, nodes: [O, C], stiffness: 1.0e5}
effects: {sway: false}
"""


def test_slider_leaves_the_translation_along_its_axis():
    """Slider on a = (0.6, 0, 0.8): u = s a, no rotation: T_c on (ux, uz, ry) is
    (0.6, 0.8, 0) / a_k for the kept translation k. A vertical spring k = 1e5 resists
    0.8^2 of it: w^2 = 0.64 k / m = 640 (sway off). Rows: relative translation normal to a
    (the perp: y, empty in the plane, and (-0.8, 0, 0.6)), and the rotation (3 rows, rx
    and rz empty)."""
    m = load("s.yaml", SLIDER)
    d = build_dofs(m)
    assert d.labels in (("body bob ux",), ("body bob uz",))
    a = np.array([0.6, 0.8, 0.0])
    np.testing.assert_allclose(d.T_c.toarray()[:, 0], a / a[0 if d.labels[0][-1] == "x" else 1],
                               atol=1e-14)
    (c,) = d.constraints
    assert c.rows.shape == (5, 3) and c.directions.shape == (5, 3)
    np.testing.assert_allclose(np.abs(c.directions[:2] @ [0.6, 0, 0.8]), 0, atol=1e-15)
    assert not c.directions[2:].any()
    # the translation row normal to a in the plane: +-(0.8 ux - 0.6 uz + 3.2 ry)
    # (O - x_g = (0, 0, 4): u_O = (ux + 4 ry, uz)); the ry row: +-1
    nz = c.rows[np.abs(c.rows).sum(axis=1) > 0]
    np.testing.assert_allclose(np.abs(nz), [[0.8, 0.6, 3.2], [0, 0, 1]], atol=1e-14)
    np.testing.assert_allclose(modes(m).omega ** 2, [640.0], rtol=1e-12)


def test_linear_drive_holds_the_distance_of_two_masses():
    """Masses 10 and 30 kg on a line (0.6, 0, 0.8) between springs 1e5 and 3e5 to ground,
    a drive A-B between them (sway off): each node keeps its coordinate along the line,
    the drive's row is e . (u_B - u_A) = s_B - s_A, T_c = [1, 1], and the pair moves as
    one mass: w^2 = (1e5 + 3e5) / 40 = 1e4."""
    m = load("d.yaml", """cranefe: 1
plane: xz
nodes: {G1: [-3, 0, -4], A: [0, 0, 0], B: [3, 0, 4], G2: [6, 0, 8]}
ground: [G1, G2]
masses: {A: 10, B: 30}
springs:
  - {type: axial, nodes: [G1, A], stiffness: 1.0e5}
  - {type: axial, nodes: [B, G2], stiffness: 3.0e5}
linear_drives:
  cyl: {nodes: [A, B], pinion_radius: 0.1, gear_ratio: 10}
effects: {sway: false}
""")
    d = build_dofs(m)
    (c,) = d.constraints
    assert (c.name, c.owner, c.groups, c.point) == ("linear drive cyl", ("drive", 0), (),
                                                     None)
    np.testing.assert_allclose(c.rows, [[-1.0, 1.0]], atol=1e-15)
    np.testing.assert_array_equal(c.directions, [[0, 0, 0]])
    np.testing.assert_allclose(d.T_c.toarray(), [[1.0], [1.0]], atol=1e-15)
    np.testing.assert_allclose(modes(m).omega ** 2, [1.0e4], rtol=1e-12)


INEXTENSIBLE = """cranefe: 1
plane: xz
nodes: {D: [0, 0, 0], S: [0, 0, 10], B: [0, 0, 4]}
ground: [D, S]
masses: {B: 1000}
drums: {hoist: {node: D, radius: 0.5, inertia: 10}}
ropes:
  r: {EA: 1.0e8, path: [hoist, S, {node: B, falls: 2}]}
effects: {rope_elasticity: false}
"""


def test_inextensible_rope_ties_the_hook_to_the_drum():
    """Delta = -2 u_Bz + R theta = 0 (R = 0.5): u_Bz = theta / 4, the drum's rotation the
    coordinate (translations are preferred as slaves). The row r T_map = (0, -2, 0.5) on
    (B x, B z, drum). Sway on: the hook swings on its two 6 m falls at tension m g / 2
    each: w^2 = 2 (m g / 2) / 6 / m = g / 6; the drive is quasi-cyclic (w = 0)."""
    m = load("i.yaml", INEXTENSIBLE)
    d = build_dofs(m)
    assert d.labels == ("node B x", "drum hoist")
    np.testing.assert_allclose(d.T_c.toarray(), [[1, 0], [0, 0.25], [0, 1]], atol=1e-15)
    (c,) = d.constraints
    assert (c.name, c.owner) == ("rope r (inextensible)", ("rope", 0))
    np.testing.assert_allclose(c.rows, [[0, -2, 0.5]], atol=1e-15)
    np.testing.assert_allclose(modes(m).omega, [0.0, math.sqrt(G / 6)], rtol=1e-12,
                               atol=1e-6)


def test_a_large_drum_still_keeps_its_rotation():
    """One fall from S to B on a drum of radius 1.5 m: u_Bz = 1.5 theta; the drum's
    rotation is weighed as a rotation (in model lengths), so it stays the coordinate
    although its column (1.5) outweighs the hook's (1) unweighted."""
    text = INEXTENSIBLE.replace("radius: 0.5", "radius: 1.5").replace(
        "{node: B, falls: 2}", "B")
    d = build_dofs(load("i.yaml", text))
    assert d.labels == ("node B x", "drum hoist")
    np.testing.assert_allclose(d.T_c.toarray(), [[1, 0], [0, 1.5], [0, 1]], atol=1e-15)


def test_inextensible_ropes_refuse_rope_mass():
    text = INEXTENSIBLE.replace("EA: 1.0e8,", "EA: 1.0e8, mass_per_length: 5,").replace(
        "rope_elasticity: false", "rope_elasticity: false, rope_mass: 1")
    with pytest.raises(ModelError) as err:
        build_dofs(load("i.yaml", text))
    e = err.value
    assert (e.file, e.entry) == ("i.yaml", "effects.rope_elasticity")
    assert e.message == ("inextensible ropes (rope_elasticity: false) cannot carry rope "
                         "mass elements; set rope_mass: 0")


ROLLER = """cranefe: 1
plane: xz
nodes: {GX: [-4, 0, 0], GZ: [0, 0, -4], N: [0, 0, 0]}
ground: [GX, GZ]
masses: {N: 10}
springs:
  - {type: axial, nodes: [GX, N], stiffness: 1.0e4}
  - {type: axial, nodes: [GZ, N], stiffness: 4.0e4}
supports: {N: {fix: [uz], axes: [[0.6, 0, 0.8], [0, 1, 0], [-0.8, 0, 0.6]]}}
effects: {sway: false}
"""


def test_roller_on_a_slope_moves_along_it():
    """The support fixes z' = (-0.8, 0, 0.6): N moves along x' = (0.6, 0, 0.8) only;
    w^2 = (1e4 0.36 + 4e4 0.64) / 10 = 2920 (sway off). Row: z' . u_N."""
    m = load("r.yaml", ROLLER)
    d = build_dofs(m)
    (c,) = d.constraints
    assert (c.name, c.owner) == ("support at N", ("support", 0))
    np.testing.assert_allclose(c.rows, [[-0.8, 0.6]], atol=1e-15)
    np.testing.assert_allclose(c.directions, [[-0.8, 0, 0.6]], atol=1e-15)
    np.testing.assert_array_equal(c.point, [0, 0, 0])
    x = np.array([0.6, 0.8])
    np.testing.assert_allclose(d.T_c.toarray()[:, 0], x / x[int(d.labels[0][-1] == "z")],
                               atol=1e-15)
    np.testing.assert_allclose(modes(m).omega ** 2, [2920.0], rtol=1e-12)


def test_a_clamped_support_makes_a_cantilever():
    """A beam A-B (L = 2 m, EI = 2e5, EA = 2e8) with A restrained in ux, uz, ry: the tip's
    stiffness on (x, z, ry) is EA/L and the Euler-Bernoulli end block
    EI/L^3 [[12, 6L], [6L, 4L^2]] (ry = -w'): 1e8; 3e5, 3e5, 4e5. Tolerance 1e-12."""
    m = load("c.yaml", """cranefe: 1
plane: xz
nodes: {A: [0, 0, 0], B: [2, 0, 0]}
supports: {A: [ux, uz, ry]}
members:
  bar: {type: beam, nodes: [A, B], E: 2.0e11, A: 1.0e-3, Iy: 1.0e-6}
effects: {structure: flexible, sway: false}
""")
    s = assemble(m)
    assert s.dofs.labels == ("node B x", "node B z", "node B ry")
    (c,) = s.dofs.constraints
    assert c.rows.shape == (3, 6) and c.directions.shape == (3, 3)
    np.testing.assert_allclose(s.K.toarray(), [[1e8, 0, 0], [0, 3e5, 3e5], [0, 3e5, 4e5]],
                               rtol=1e-12, atol=1e-4)


def test_no_constraint_or_only_empty_rows_leave_the_coordinates_alone():
    """A hinge between two bodies of one rigid group (fixed together) constrains nothing;
    a planar support along y (the plane's normal) gives an empty row: both leave T_c the
    identity, in order."""
    d = build_dofs(load("f.yaml", """cranefe: 1
plane: xz
nodes: {O: [0, 0, 10], C: [0, 0, 6]}
ground: [O]
bodies:
  a: {mass: 100, com: C, inertia: 2}
  b: {mass: 10, com: O, inertia: 1}
joints:
  - {type: fixed, bodies: [a, b], at: C}
  - {type: hinge, bodies: [a, b], at: O}
springs:
  - {type: axial, nodes: [O, C], stiffness: 1.0e5}
"""))
    assert d.constraints == ()
    assert len(d.labels) == 3
    np.testing.assert_array_equal(d.T_c.toarray(), np.eye(3))
    d = build_dofs(load("r.yaml", ROLLER.replace(
        "{fix: [uz], axes: [[0.6, 0, 0.8], [0, 1, 0], [-0.8, 0, 0.6]]}", "[uy]")))
    assert len(d.constraints) == 1 and d.labels == ("node N x", "node N z")
    np.testing.assert_array_equal(d.T_c.toarray(), np.eye(2))
    # a support along x on N (x, z): one column in G, eliminated
    d = build_dofs(load("r.yaml", ROLLER.replace(
        "{fix: [uz], axes: [[0.6, 0, 0.8], [0, 1, 0], [-0.8, 0, 0.6]]}", "[ux]")))
    assert d.labels == ("node N z",)
    np.testing.assert_array_equal(d.T_c.toarray(), [[0], [1]])
    T, keep = _eliminate([], 4, np.zeros(4, bool), 1.0)
    np.testing.assert_array_equal(T.toarray(), np.eye(4))
    np.testing.assert_array_equal(keep, np.arange(4))
