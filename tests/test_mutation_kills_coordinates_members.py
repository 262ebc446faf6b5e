"""Kill tests for cranefe/coordinates/members.py (tools/mutation.py coords_members;
docs/testing.md, "Mutation testing"): the finite-element mesh of members (structure:
flexible; docs/structure.md): interior nodes of subdivided beams, their names and
numbering, element orientations, pinned ends and the nodes that carry rotations, by
hand; and a clamped beam in two elements whose tip stiffness is 3 EI / L^3 exactly
(cubic Hermite elements are exact under end loads).
"""

import numpy as np

from cranefe.coordinates.members import discretize, member_pairs
from cranefe.model import load
from cranefe.system import assemble

SPATIAL = """cranefe: 1
nodes: {A: [0, 0, 0], B: [3, 0, 4], C: [3, 0, 0], E: [0, 2, 0], F: [0, 4, 0]}
ground: [A]
members:
  t: {type: truss, pairs: [[A, C], [C, E]], E: 2.0e11, A: 1.0e-3}
  bm: {type: beam, nodes: [A, B, C], E: 2.0e11, A: 1.0e-3, Iy: 1.0e-6, Iz: 1.0e-6,
       J: 1.0e-6, G: 8.0e10, orientation: [0, 1, 0], elements: 3,
       releases: {C: [rx, ry, rz], A: [rx, rz]}}
  bm2: {type: beam, nodes: [C, E, F], E: 2.0e11, A: 1.0e-3, Iy: 1.0e-6, Iz: 1.0e-6,
        J: 1.0e-6, G: 8.0e10, orientation: [0, 0, 1], elements: 2,
        releases: {C: [ry, rz], F: [rx, ry, rz]}}
  bm3: {type: beam, nodes: [E, B], E: 2.0e11, A: 1.0e-3, Iy: 1.0e-6, Iz: 1.0e-6,
        J: 1.0e-6, G: 8.0e10, orientation: [0, 0, 1], elements: 2}
effects: {structure: flexible}
"""


def test_spatial_mesh_by_hand():
    """Nodes A, B, C, E, F = 0..4. The truss (pairs A-C, C-E): one element per pair, no
    orientation. The beam A-B-C in 3 elements per piece: interior nodes at thirds,
    numbered from first_node = 10: A-B (5 m along (0.6, 0, 0.8)) 10 (1, 0, 4/3),
    11 (2, 0, 8/3); B-C (4 m down) 12 (3, 0, 8/3), 13 (3, 0, 4/3); then bm2 C-E-F in 2
    elements per piece: 14 (1.5, 1, 0), 15 (0, 3, 0); then bm3 E-B: 16 (1.5, 1, 2)
    (the third subdivided member: its numbers continue the count). Each beam's orientation is its own
    on every element. Releases: every rotation at C (bm) and at F (bm2) pins that end;
    rx, rz (bm at A) or ry, rz (bm2 at C) pin nothing in 3D."""
    m = load("s.yaml", SPATIAL)
    mm = discretize(m, 10)
    np.testing.assert_allclose(mm.coords, [[1, 0, 4 / 3], [2, 0, 8 / 3], [3, 0, 8 / 3],
                                           [3, 0, 4 / 3], [1.5, 1, 0], [0, 3, 0],
                                           [1.5, 1, 2]],
                               atol=1e-14)
    assert mm.n_interior == 7
    assert mm.names == ("bm A-B 1", "bm A-B 2", "bm B-C 1", "bm B-C 2", "bm2 C-E 1",
                        "bm2 E-F 1", "bm3 E-B 1")
    assert mm.member.tolist() == [0, 0] + [1] * 6 + [2] * 4 + [3] * 2
    assert mm.beam.tolist() == [False, False] + [True] * 12
    assert mm.node.tolist() == [[0, 2], [2, 3], [0, 10], [10, 11], [11, 1], [1, 12],
                                [12, 13], [13, 2], [2, 14], [14, 3], [3, 15], [15, 4],
                                [3, 16], [16, 1]]
    np.testing.assert_array_equal(mm.orientation,
                                  [[0, 0, 0]] * 2 + [[0, 1, 0]] * 6 + [[0, 0, 1]] * 6)
    assert mm.pinned.tolist() == ([[False, False]] * 7 + [[False, True]]
                                  + [[False, False]] * 3 + [[False, True]]
                                  + [[False, False]] * 2)
    assert mm.rotation_nodes().tolist() == [0, 1, 2, 3, 10, 11, 12, 13, 14, 15, 16]
    assert mm.node.dtype.kind == mm.member.dtype.kind == "i" and mm.beam.dtype == bool
    assert member_pairs(m.members[0]).tolist() == [[0, 2], [2, 3]]
    assert member_pairs(m.members[1]).tolist() == [[0, 1], [1, 2]]


PLANAR = """cranefe: 1
plane: xz
nodes: {A: [0, 0, 0], B: [3, 0, 4], C: [5, 0, 4]}
ground: [A]
members:
  bm: {type: beam, nodes: [A, B], E: 2.0e11, A: 1.0e-3, Iy: 1.0e-6}
  pin: {type: beam, nodes: [B, C], E: 2.0e11, A: 1.0e-3, Iy: 1.0e-6, releases: {C: [ry]}}
effects: {structure: flexible}
"""


def test_planar_beams_bend_in_the_plane_and_a_released_end_has_no_rotation():
    """Planar default orientation: local y = global y, so the local z (orientation) is
    e x (0, 1, 0): (0.6, 0, 0.8) x y = (-0.8, 0, 0.6), (1, 0, 0) x y = (0, 0, 1). One
    element per piece: no interior nodes. ry released at C pins it (planar), so the
    rotations are at A and B only."""
    m = load("p.yaml", PLANAR)
    mm = discretize(m, 3)
    assert mm.coords.shape == (0, 3) and mm.names == ()
    assert mm.node.tolist() == [[0, 1], [1, 2]]
    np.testing.assert_allclose(mm.orientation, [[-0.8, 0, 0.6], [0, 0, 1]], atol=1e-15)
    assert mm.pinned.tolist() == [[False, False], [False, True]]
    assert mm.rotation_nodes().tolist() == [0, 1]


def test_clamped_beam_in_two_elements_has_the_exact_tip_stiffness():
    """A beam from the ground node A (clamped: a ground node has no rotation) to B,
    L = 2 m along (0.6, 0, 0.8), EI = 2e5, in two elements (interior node at the middle,
    (0.6, 0, 0.8)): condensing the interior node and the tip rotation leaves, across the
    beam, 3 EI / L^3 = 75000 N/m and along it EA / L = 1e8 (exact for cubic elements);
    tolerance 1e-9 relative (a 5 x 5 solve)."""
    s = assemble(load("c.yaml", """cranefe: 1
plane: xz
nodes: {A: [0, 0, 0], B: [1.2, 0, 1.6]}
ground: [A]
members:
  bm: {type: beam, nodes: [A, B], E: 2.0e11, A: 1.0e-3, Iy: 1.0e-6, elements: 2}
effects: {structure: flexible, sway: false}
"""))
    np.testing.assert_allclose(s.dofs.members.coords, [[0.6, 0, 0.8]], atol=1e-15)
    K = s.K.toarray()
    r = [s.dofs.labels.index("node B x"), s.dofs.labels.index("node B z")]
    i = [k for k in range(len(K)) if k not in r]
    Kc = K[np.ix_(r, r)] - K[np.ix_(r, i)] @ np.linalg.solve(K[np.ix_(i, i)], K[np.ix_(i, r)])
    e, n = np.array([0.6, 0.8]), np.array([-0.8, 0.6])
    np.testing.assert_allclose(Kc, 1e8 * np.outer(e, e) + 75000.0 * np.outer(n, n),
                               rtol=1e-9, atol=1e-9 * 1e8)


def test_no_members_an_empty_mesh():
    m = load("n.yaml", """cranefe: 1
nodes: {A: [0, 0, 0]}
ground: [A]
""")
    mm = discretize(m, 1)
    assert mm.node.shape == (0, 2) and mm.orientation.shape == (0, 3)
    assert mm.coords.shape == (0, 3) and mm.rotation_nodes().size == 0
