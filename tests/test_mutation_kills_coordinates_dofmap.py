"""Kill tests for cranefe/coordinates/dofmap.py (tools/mutation.py coords_dofmap;
docs/testing.md, "Mutation testing"): which generalised coordinates exist and the
kinematic map T_map (docs/theory.md section 1, "Generalised coordinates and the kinematic
map"), on small models whose groups, references, carried points, free directions, beam
rotations and drums are worked out by hand.

Every carried point's rows are computed here from u_p = u_g + t x (p - x_g) with
np.cross (theory.md section 1), not with the module's skew matrices.
"""

import numpy as np

from cranefe.coordinates import build_dofs, entry_of
from cranefe.coordinates.dofmap import direction_tensor
from cranefe.model import load

GROUPS = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 10], A: [0, 0, 4], B: [4, 0, 0], P: [2, 0, 2], J: [6, 0, 0],
        Q: [6, 0, -2], R: [8, 0, -2], K: [0, 0, 12], H: [-2, 0, 4], S: [10, 0, -2],
        V: [12, 0, 0], L1: [0, 0, -6], L2: [2, 0, -6]}
ground: [O]
bodies:
  d: {mass: 50, com: K, inertia: 5, nodes: [K]}
  a: {mass: 100, com: A, inertia: 10, nodes: [A, P, H]}
  b: {mass: 300, com: B, inertia: 30, nodes: [B]}
  c: {mass: 0, nodes: [Q, R]}
  c2: {mass: 0, nodes: [S]}
  e: {mass: 20, com: [1, 0, 12], inertia: 2, nodes: [H]}
  g: {mass: 0.5, com: [0.5, 0, -6], inertia: 0.1, nodes: [L1, L2]}
  f: {mass: 0}
joints:
  - {type: fixed, bodies: [e, d], at: K}
  - {type: fixed, bodies: [ground, d], at: O}
  - {type: fixed, bodies: [b, a], at: B}
  - {type: fixed, bodies: [c, c2], at: S}
  - {type: hinge, bodies: [b, c], at: J}
  - {type: hinge, bodies: [a, e], at: H}
  - {type: hinge, bodies: [ground, c], at: V}
"""


def _rows(points, ref, cols, planar=True):
    """Hand rows of u_p = u_g + t x (p - ref) for the group's columns cols (ux, uz, ry
    in a plane): (len(points), 3, n) blocks as a dict point index -> (3, n_cols)."""
    out = []
    for p in points:
        c = np.asarray(p, float) - ref
        blk = np.zeros((3, 6))
        blk[:, :3] = np.eye(3)
        for k in range(3):                      # column of t_k: e_k x c
            blk[:, 3 + k] = np.cross(np.eye(3)[k], c)
        out.append(blk[:, [0, 2, 4]] if planar else blk)
    return out


def test_rigid_groups_their_references_and_what_they_carry():
    """Fixed joints merge a+b (reference the mass centre (100 A + 300 B) / 400 =
    (3, 0, 1)), c+c2 (massless: the centroid of their nodes Q, R, S, (8, 0, -2)) and
    d+e+ground (grounded: d is fixed to ground, listed first in its joint, after e was
    fixed to d, so the ground stays the root); g alone (0.5 kg: its centre of mass
    (0.5, 0, -6), not its nodes' centroid (1, 0, -6)); f alone (massless, no nodes: its
    default centre, the origin). Carriers: P, A, B by a+b; J (the hinge b-c's node, listed
    by no body) by b, its first body; V (hinge ground-c, listed by no body) by the ground;
    Q, R, S by c+c2; K and H by the ground (H is listed by a and by the grounded e).
    Rows of T_map: u_p = u_g + t x (p - x_g), the bodies' centres of mass likewise and
    their rotation the group's."""
    m = load("g.yaml", GROUPS)
    d = build_dofs(m)
    assert d.group_of_body.tolist() == [-1, 0, 0, 1, 1, -1, 2, 3]
    refs = [[3, 0, 1], [8, 0, -2], [0.5, 0, -6], [0, 0, 0]]
    np.testing.assert_allclose(d.group_ref, refs, atol=1e-15)
    assert d.group_q.tolist() == [[3 * g, -1, 3 * g + 1, -1, 3 * g + 2, -1]
                                  for g in range(4)]
    idx = {n: i for i, n in enumerate(m.node_names)}
    carriers = {"O": -1, "A": 0, "B": 0, "P": 0, "J": 0, "Q": 1, "R": 1, "K": -1,
                "H": -1, "S": 1, "V": -1, "L1": 2, "L2": 2}
    assert {n: d.carrier[i] for n, i in idx.items()} == carriers
    T = d.T_map.toarray()
    assert T.shape == (d.layout.size, 12)
    lay = d.layout
    for name, g in carriers.items():
        rows = T[lay.node(idx[name])]
        if g < 0:
            assert not rows.any()
            continue
        cols = [3 * g, 3 * g + 1, 3 * g + 2]
        (want,) = _rows([m.coords[idx[name]]], np.array(refs[g], float), cols)
        np.testing.assert_allclose(rows[:, cols], want, atol=1e-14)
        np.testing.assert_allclose(np.delete(rows, cols, axis=1), 0)
    coms = {1: [0, 0, 4], 2: [4, 0, 0], 3: [7, 0, -2], 4: [10, 0, -2], 6: [0.5, 0, -6],
            7: [0, 0, 0]}
    for b, com in coms.items():
        g = d.group_of_body[b]
        cols = [3 * g, 3 * g + 1, 3 * g + 2]
        (want,) = _rows([com], np.array(refs[g], float), cols)
        np.testing.assert_allclose(T[lay.body(b)[:3]][:, cols], want, atol=1e-14)
        np.testing.assert_allclose(T[lay.body(b)[3:]][:, cols], [[0, 0, 0], [0, 0, 1],
                                                                 [0, 0, 0]], atol=0)
    for b in (0, 5):                            # grounded bodies do not move
        assert not T[lay.body(b)].any()
    assert d.kinds == ("body",) * d.n and d.n == d.T.shape[1] == len(d.labels)
    assert d.labels == ("body g ux", "body g uz", "body g ry", "body f ux", "body f uz",
                        "body f ry")
    np.testing.assert_allclose((d.T_map @ d.T_c).toarray(), d.T.toarray())


FREE = """cranefe: 1
nodes: {X1: [5, 0, 0], Z1: [0, 0, 5], N1: [0, 0, 0], N2: [10, 0, 0], W: [13, 0, -4],
        N3: [20, 0, 0], X3: [21, 0, 0], Y3: [20, 1, 0], Z3: [20.6, 0, 0.8], N4: [30, 0, 0],
        N5: [40, 0, 0], N6: [50, 0, 0], X6: [51, 0, 0],
        N7: [60, 0, 0], G7: [60.8, 0, 0.6], N8: [70, 0, 0], G8: [70, 0.6, 0.8],
        N9: [80, 0, 0], G9: [80.6, 0.8, 0], N10: [90, 0, 0], G10: [89.2, 0, 0.6],
        N11: [100, 0, 0], G11: [100.6, 0, 0.8], N12: [110, 0, 0], G12: [110.8, 0.6, 0]}
ground: [X1, Z1, W, X3, Y3, Z3, X6, G7, G8, G9, G10, G11, G12]
masses: {N1: 1, N2: 2, N3: 3, N4: 4, N7: 1, N8: 1, N9: 1, N10: 1, N11: 1, N12: 1}
ropes:
  r1: {EA: 1.0e6, path: [X1, N1]}
  r2: {EA: 1.0e6, path: [Z1, N1]}
  r3: {EA: 1.0e6, path: [N2, W]}
  r4: {EA: 1.0e6, path: [X3, N3]}
  r5: {EA: 1.0e6, path: [Y3, N3]}
  r6: {EA: 1.0e6, path: [Z3, N3]}
  r7: {EA: 1.0e6, path: [X6, N6]}
  r8: {EA: 1.0e6, path: [G7, N7]}
  r9: {EA: 1.0e6, path: [G8, N8]}
  r10: {EA: 1.0e6, path: [G9, N9]}
  r11: {EA: 1.0e6, path: [G10, N10]}
  r12: {EA: 1.0e6, path: [G11, N11]}
  r13: {EA: 1.0e6, path: [G12, N12]}
effects: {sway: false}
"""


def test_free_nodes_keep_the_directions_their_ropes_act_in():
    """Sway off (theory.md section 1, "Free nodes"): N1 between ropes along x and z keeps
    x and z; N2 on one rope along (0.6, 0, -0.8) keeps that direction, signed so its
    largest component is positive: (-0.6, 0, 0.8) (likewise N7..N12 along (0.8, 0, 0.6),
    (0, 0.6, 0.8), (0.6, 0.8, 0), (0.8, 0, -0.6), (0.6, 0, 0.8), (0.8, 0.6, 0), a zero
    printed as 0 also where the eigenvector came with the other sign); N3 with ropes along
    x, y and (0.6, 0, 0.8) is free in every direction: the global axes; N6, massless on
    one rope along x, keeps x; N4 (a mass nothing acts on) and N5 (nothing) get none.
    Sway on: every active node (all but N5) moves in x, y, z."""
    m = load("f.yaml", FREE)
    d = build_dofs(m)
    idx = {n: i for i, n in enumerate(m.node_names)}
    cases = (("node N1 x", "N1", [1, 0, 0]), ("node N1 z", "N1", [0, 0, 1]),
             ("node N3 x", "N3", [1, 0, 0]), ("node N3 y", "N3", [0, 1, 0]),
             ("node N3 z", "N3", [0, 0, 1]), ("node N6 x", "N6", [1, 0, 0]),
             ("node N2 along (-0.6, 0, 0.8)", "N2", [-0.6, 0, 0.8]),
             ("node N7 along (0.8, 0, 0.6)", "N7", [0.8, 0, 0.6]),
             ("node N8 along (0, 0.6, 0.8)", "N8", [0, 0.6, 0.8]),
             ("node N9 along (0.6, 0.8, 0)", "N9", [0.6, 0.8, 0]),
             ("node N10 along (0.8, 0, -0.6)", "N10", [0.8, 0, -0.6]),
             ("node N11 along (0.6, 0, 0.8)", "N11", [0.6, 0, 0.8]),
             ("node N12 along (0.8, 0.6, 0)", "N12", [0.8, 0.6, 0]))
    assert sorted(d.labels) == sorted(c[0] for c in cases)
    T = d.T.toarray()
    col = {lab: T[:, k] for k, lab in enumerate(d.labels)}
    lay = d.layout
    for lab, node, vec in cases:
        want = np.zeros(lay.size)
        want[lay.node(idx[node])] = vec
        np.testing.assert_allclose(col[lab], want, atol=1e-14)
    assert d.kinds == ("node",) * len(cases)
    d = build_dofs(m, m.effects.__class__(**{**vars(m.effects), "sway": True}))
    assert sorted(d.labels) == sorted(f"node N{i} {a}" for i in (1, 2, 3, 4, 6, 7, 8, 9, 10, 11, 12)
                                      for a in "xyz")
    np.testing.assert_allclose(abs(d.T.toarray()).sum(axis=0), 1)


def test_a_planar_node_between_two_ropes_uses_the_axes():
    """Planar, sway off: B on a rope to A along (-0.6, 0, 0.8) and one up to T: D is
    full in the plane (not diagonal), so B moves in x and z, the global axes; a drum on
    a free node N that nothing else acts on makes it active: with sway on it gets x, z."""
    text = """cranefe: 1
plane: xz
nodes: {A: [0, 0, 8], B: [6, 0, 0], T: [6, 0, 10], N: [9, 0, 0]}
ground: [A, T]
masses: {B: 10}
drums: {d: {node: N, radius: 0.5, inertia: 1}}
ropes:
  r1: {EA: 1.0e6, path: [A, B]}
  r2: {EA: 1.0e6, path: [B, T]}
effects: {sway: false, drive: held}
"""
    m = load("v.yaml", text)
    d = build_dofs(m)
    assert d.labels == ("node B x", "node B z")
    np.testing.assert_array_equal(d.T.toarray()[d.layout.node(1)], [[1, 0], [0, 0], [0, 1]])
    d = build_dofs(m, m.effects.__class__(**{**vars(m.effects), "sway": True}))
    assert d.labels == ("node B x", "node B z", "node N x", "node N z")


def test_direction_tensor_sums_the_spans_springs_drives_and_members():
    """D_i = sum of e e^T over rope spans (each span once, whatever its falls), axial
    springs and linear drives at node i, + truss members along their axes and I per beam
    end when the structure is flexible; rotational springs and members of a rigid
    structure add nothing."""
    text = """cranefe: 1
nodes: {A: [0, 0, 0], B: [3, 0, 4], C: [3, 0, 0], E: [0, 2, 0], F: [0, 0, 5]}
ground: [A]
bodies:
  k: {mass: 1, com: F, inertia: [1, 1, 1], nodes: [F]}
  l: {mass: 1, com: F, inertia: [1, 1, 1]}
masses: {B: 1}
ropes:
  r: {EA: 1.0e6, path: [A, B, {node: C, falls: 3}]}
springs:
  - {type: axial, nodes: [A, E], stiffness: 1.0e5}
  - {type: rotational, bodies: [k, l], axis: [0, 0, 1], stiffness: 1.0e5}
linear_drives:
  cyl: {nodes: [C, E], pinion_radius: 0.1, gear_ratio: 10}
members:
  t: {type: truss, nodes: [A, C], E: 2.0e11, A: 1.0e-3}
  bm: {type: beam, nodes: [E, F], E: 2.0e11, A: 1.0e-3, Iy: 1.0e-6, Iz: 1.0e-6,
       J: 1.0e-6, G: 8.0e10, orientation: [1, 0, 0]}
"""
    m = load("t.yaml", text)
    ab = np.outer([0.6, 0, 0.8], [0.6, 0, 0.8])      # A-B
    bc = np.diag([0.0, 0.0, 1.0])                   # B-C (3 falls: once)
    ae = np.diag([0.0, 1.0, 0.0])                   # spring A-E
    ce = np.outer([-3, 2, 0], [-3, 2, 0]) / 13.0    # drive C-E
    rigid = np.array([ab + ae, ab + bc, bc + ce, ae + ce, np.zeros((3, 3))])
    np.testing.assert_allclose(direction_tensor(m, m.effects, 5), rigid, atol=1e-15)
    flex = m.effects.__class__(**{**vars(m.effects), "structure": "flexible"})
    add = np.array([np.diag([1.0, 0, 0]), np.zeros((3, 3)), np.diag([1.0, 0, 0]),
                    np.eye(3), np.eye(3)])
    np.testing.assert_allclose(direction_tensor(m, flex, 7)[:5], rigid + add, atol=1e-15)
    assert not direction_tensor(m, flex, 7)[5:].any()


BEAMS = """cranefe: 1
plane: xz
nodes: {A: [0, 0, 0], B: [2, 0, 0], C: [4, 0, 0], E: [4, 0, 2]}
ground: [A]
bodies: {k: {mass: 10, com: C, inertia: 1, nodes: [C]}}
members:
  bar: {type: beam, nodes: [A, B, C], E: 2.0e11, A: 1.0e-3, Iy: 1.0e-6, elements: 2}
  post: {type: beam, nodes: [C, E], E: 2.0e11, A: 1.0e-3, Iy: 1.0e-6, releases: {E: [ry]}}
effects: {structure: flexible}
"""


def test_rotations_where_beams_meet():
    """Beam A-B-C (two elements per piece: interior nodes 'bar A-B 1' at (1, 0, 0) and
    'bar B-C 1' at (3, 0, 0)) and a post C-E pinned at E. Rotations: none at the ground
    node A, body k's at C (it carries C), none at the pinned E, an own 'ry' at B and at the
    two interior nodes. Translations: B, E and the interior nodes in x and z (planar)."""
    m = load("b.yaml", BEAMS)
    d = build_dofs(m)
    assert d.labels == (
        "body k ux", "body k uz", "body k ry", "node B x", "node B z", "node E x",
        "node E z", "node bar A-B 1 x", "node bar A-B 1 z", "node bar B-C 1 x",
        "node bar B-C 1 z", "node B ry", "node bar A-B 1 ry", "node bar B-C 1 ry")
    assert d.kinds == ("body",) * 3 + ("node",) * 11
    np.testing.assert_allclose(d.coords[4:], [[1, 0, 0], [3, 0, 0]], atol=1e-15)
    T = d.T_map.toarray()
    lay = d.layout
    want = {0: None, 1: 11, 2: 2, 3: None, 4: 12, 5: 13}
    for i, q in want.items():
        rot = T[lay.rot(i)]
        if q is None:
            assert not rot.any()
        else:
            e = np.zeros((3, 14))
            e[1, q] = 1.0
            np.testing.assert_array_equal(rot, e)


def test_a_3d_beam_end_has_three_rotations():
    d = build_dofs(load("c.yaml", """cranefe: 1
nodes: {A: [0, 0, 0], B: [2, 0, 0]}
ground: [A]
members:
  bar: {type: beam, nodes: [A, B], E: 2.0e11, A: 1.0e-3, Iy: 1.0e-6, Iz: 1.0e-6,
        J: 1.0e-6, G: 8.0e10, orientation: [0, 0, 1]}
effects: {structure: flexible}
"""))
    assert d.labels == tuple(f"node B {c}" for c in ("x", "y", "z", "rx", "ry", "rz"))
    np.testing.assert_array_equal(d.T.toarray()[d.layout.rot(1)], np.eye(6)[3:])
    np.testing.assert_array_equal(d.T.toarray()[d.layout.node(1)], np.eye(6)[:3])


DRUMS = """cranefe: 1
plane: xz
nodes: {D: [0, 0, 0], E: [0, 0, 1], S: [0, 0, 10], B: [0, 0, 4]}
ground: [D, E, S]
masses: {B: 1000}
drums:
  d1: {node: D, radius: 0.5, inertia: 10}
  d2: {node: E, radius: 0.5, inertia: 10, brake: true}
  d3: {node: E, radius: 0.5, inertia: 10}
ropes:
  r: {EA: 1.0e8, path: [d1, S, B]}
  r2: {EA: 1.0e8, path: [d3, S, B]}
effects: {sway: false}
"""


def test_a_drum_turns_when_coupled_and_unbraked():
    """drive: coupled: d1 and d3 are coordinates (kind 'drum', T = 1 on their rotation),
    the braked d2 is held; drive: held: no drum turns."""
    m = load("d.yaml", DRUMS)
    d = build_dofs(m)
    assert d.labels == ("node B z", "drum d1", "drum d3")
    assert d.kinds == ("node", "drum", "drum")
    T = d.T.toarray()
    np.testing.assert_array_equal(T[d.layout.drum([0, 1, 2])], [[0, 1, 0], [0, 0, 0],
                                                                [0, 0, 1]])
    held = m.effects.__class__(**{**vars(m.effects), "drive": "held"})
    assert build_dofs(m, held).labels == ("node B z",)


def test_nothing_moves_no_coordinates():
    d = build_dofs(load("n.yaml", """cranefe: 1
nodes: {A: [0, 0, 0], B: [0, 0, 1]}
ground: [A, B]
ropes:
  r: {EA: 1.0e6, path: [A, B]}
"""))
    assert d.n == 0 and d.T.shape == (d.layout.size, 0) and d.labels == ()


def test_entry_of_names_the_model_entry():
    assert entry_of("node B z") == "nodes.B"
    assert entry_of("node N2 along (-0.6, 0, 0.8)") == "nodes.N2"
    assert entry_of("body a+b ux") == "bodies.a"
    assert entry_of("drum hoist") == "drums.hoist"
    assert entry_of("slip r over S (pass 1)") is None


def test_rope_mass_zero_meshes_nothing_and_a_rigid_structure_no_members():
    """rope_mass: 0 leaves a rope with mass a massless spring (no slips, no mesh); a
    rigid structure ignores the members' elements (only body k moves)."""
    from test_mutation_kills_coordinates_ropes import V_ROPE
    d = build_dofs(load("v.yaml", V_ROPE.replace("rope_mass: 1", "rope_mass: 0")))
    assert d.labels == ("node B x", "node B z", "drum hoist") and d.ropes is None
    m = load("b.yaml", BEAMS)
    d = build_dofs(m, m.effects.__class__(**{**vars(m.effects), "structure": "rigid"}))
    assert d.labels == ("body k ux", "body k uz", "body k ry") and d.members is None


def test_rope_elements_and_member_elements_together():
    """Rope mass and flexible members in one model: nodes A, B, S, then the rope's
    interior node (2, 0, 2.5) (index 3, along the fall: z only, sway off), then the
    beam's interior node (1, 0, 0) (index 4: x, z, ry). Nodes free in every direction
    are listed first, then the others, then the rotations."""
    d = build_dofs(load("rb.yaml", """cranefe: 1
plane: xz
nodes: {A: [0, 0, 0], B: [2, 0, 0], S: [2, 0, 5]}
ground: [A, S]
masses: {B: 10}
ropes:
  r: {EA: 1.0e6, path: [S, B], mass_per_length: 1}
members:
  bm: {type: beam, nodes: [A, B], E: 2.0e11, A: 1.0e-3, Iy: 1.0e-6, elements: 2}
effects: {rope_mass: 2, structure: flexible, sway: false}
"""))
    assert d.layout.n_nodes == 5
    np.testing.assert_allclose(d.coords[3:], [[2, 0, 2.5], [1, 0, 0]], atol=1e-15)
    assert d.members.node.tolist() == [[0, 4], [4, 1]]
    assert d.labels == ("node B x", "node B z", "node bm A-B 1 x", "node bm A-B 1 z",
                        "node rope r fall 1 node 1 z", "node B ry", "node bm A-B 1 ry")
