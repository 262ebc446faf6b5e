"""Kill tests for cranefe/coordinates/ropes.py (tools/mutation.py coords_ropes;
docs/testing.md, "Mutation testing"): the finite-element rope mesh (falls, interior
nodes, slip coordinates, drum ends, the extra-length element), its end maps and the
massless ropes' elongation rows, on two small hoists written out by hand from the
kinematics of docs/ropes.md ("Formulation") and docs/theory.md section 2.

The physics check: every fall, the extra length and the sheave slips are springs in
series along the rope material, so condensing the rope's own coordinates (interior nodes
and slips, a Schur complement done here in numpy) must give exactly the massless rope,
K = (EA / L) r r^T with r the rope's elongation row (seed eq. 2-3).
"""

import numpy as np

from cranefe.coordinates.ropes import discretize, endpoint_maps, falls_of, rope_rows
from cranefe.model import load
from cranefe.system import assemble

# 3D: drum D at the start, lead D -> S = (2, 4, 4) (6 m, e = (1, 2, 2) / 3), a 2-fall
# tackle S-B (6 m), extra_length 2 at the drum, 2 elements per fall, sway off
TACKLE = """cranefe: 1
nodes: {D: [-2, -4, 6], S: [0, 0, 10], B: [0, 0, 4]}
ground: [D, S]
masses: {B: 1000}
drums: {hoist: {node: D, radius: 0.5, inertia: 10}}
ropes:
  r: {EA: 1.0e8, path: [hoist, S, {node: B, falls: 2}], mass_per_length: 5, extra_length: 2}
effects: {rope_mass: 2, sway: false}
"""

# planar: anchor A, sheave block B (V of two 3-4-5 falls), sheave S, drum D at the END of
# the path (extra length 2 at the drum), one element per fall; r2 a massless rope B-C
V_ROPE = """cranefe: 1
plane: xz
nodes: {A: [0, 0, 8], B: [3, 0, 4], S: [6, 0, 8], D: [6, 0, 0], C: [3, 0, 0]}
ground: [A, S, D, C]
masses: {B: 1000}
drums: {hoist: {node: D, radius: 0.5, inertia: 10}}
ropes:
  r: {EA: 1.0e8, path: [A, B, S, hoist], mass_per_length: 5, extra_length: 2}
  r2: {EA: 2.0e7, path: [B, C]}
effects: {rope_mass: 1, sway: false}
"""

E_DS = np.array([1.0, 2.0, 2.0]) / 3.0
UP, DOWN = np.array([0.0, 0.0, 1.0]), np.array([0.0, 0.0, -1.0])


def _condensed(s, keep):
    """K on the coordinates `keep` with every other coordinate condensed statically
    (K_rr - K_ri K_ii^-1 K_ir), computed here from the assembled K."""
    K = s.K.toarray()
    r = [s.dofs.labels.index(k) for k in keep]
    i = [k for k in range(len(K)) if k not in r]
    return K[np.ix_(r, r)] - K[np.ix_(r, i)] @ np.linalg.solve(K[np.ix_(i, i)],
                                                               K[np.ix_(i, r)])


def test_falls_of_a_tackle_alternate():
    """[hoist, S, {B, falls: 3}] is hoist-S, S-B, B-S, S-B (model-format.md, the path)."""
    m = load("t.yaml", TACKLE.replace("falls: 2", "falls: 3"))
    D, S, B = (m.node_names.index(n) for n in "DSB")
    assert falls_of(m.ropes[0]) == [(D, S), (S, B), (B, S), (S, B)]


def test_tackle_mesh_with_a_drum_at_the_start_by_hand():
    """Nodes D, S, B = 0, 1, 2; interior nodes 3 (fall 1, at the lead's middle
    (-1, -2, 8)), 4 (fall 2, (0, 0, 7)), 5 (fall 3, (0, 0, 7)). Path points: the drum
    (xi = -R theta: coefficient -0.5 on drum 0), pass 1 over S (slip 0), pass 2 over B
    (slip 1), the dead end at S (xi = 0). The extra length sits between the drum and a
    new slip 2 where the first fall begins, along the lead. Element lengths: 6 / 2 = 3."""
    s = assemble(load("t.yaml", TACKLE))
    rm = s.dofs.ropes
    assert rm.ropes == (0,)
    np.testing.assert_allclose(rm.coords, [[-1, -2, 8], [0, 0, 7], [0, 0, 7]], atol=1e-14)
    assert rm.names == ("r fall 1 node 1", "r fall 2 node 1", "r fall 3 node 1")
    np.testing.assert_allclose(rm.direction, [E_DS, DOWN, UP], atol=1e-15)
    assert rm.slip_names == ("slip r over S (pass 1)", "slip r over B (pass 2)",
                             "slip r (extra length)")
    assert (rm.n_interior, rm.n_slips) == (3, 3)
    assert rm.rope.tolist() == [0] * 7
    assert rm.fall.tolist() == [-1, 0, 0, 1, 1, 2, 2]
    assert rm.node.tolist() == [[0, 0], [0, 3], [3, 1], [1, 4], [4, 2], [2, 5], [5, 1]]
    assert rm.slip.tolist() == [[-1, 2], [2, -1], [-1, 0], [0, -1], [-1, 1], [1, -1],
                                [-1, -1]]
    assert rm.drum.tolist() == [[0, -1]] + [[-1, -1]] * 6
    assert rm.coef.tolist() == [[-0.5, 1], [1, 0], [0, 1], [1, 0], [0, 1], [1, 0], [0, 0]]
    np.testing.assert_allclose(rm.e, [E_DS, E_DS, E_DS, DOWN, DOWN, UP, UP], atol=1e-15)
    np.testing.assert_allclose(rm.length, [2, 3, 3, 3, 3, 3, 3], rtol=1e-15)
    assert rm.node.dtype.kind == rm.slip.dtype.kind == rm.drum.dtype.kind == "i"
    assert s.dofs.labels == (
        "node B z", "node rope r fall 1 node 1 along (0.333, 0.667, 0.667)",
        "node rope r fall 2 node 1 z", "node rope r fall 3 node 1 z", "drum hoist",
        "slip r over S (pass 1)", "slip r over B (pass 2)", "slip r (extra length)")
    assert s.dofs.kinds == ("node",) * 4 + ("drum",) + ("slip",) * 3
    # a slip coordinate is the slip itself, in metres (T = 1 on its primitive entry)
    np.testing.assert_array_equal(s.dofs.T.toarray()[s.dofs.layout.slip([0, 1, 2])][:, 5:],
                                  np.eye(3))


def test_tackle_elements_condense_to_the_massless_rope():
    """Massless rope: Delta = 2 e_SB . u_B + R theta = -2 u_Bz + 0.5 theta (D, S fixed),
    L = 6 + 2 x 6 + 2 = 20 m, c = EA / L = 5e6 N/m: K = c [[4, -1], [-1, 0.25]] on
    (B z, drum). The elements are springs in series, so condensing interior nodes and
    slips gives it exactly; tolerance 1e-9 relative (a 6 x 6 solve of entries ~ 1e8)."""
    s = assemble(load("t.yaml", TACKLE))
    c = 1.0e8 / 20.0
    np.testing.assert_allclose(_condensed(s, ["node B z", "drum hoist"]),
                               c * np.array([[4.0, -1.0], [-1.0, 0.25]]), rtol=1e-9,
                               atol=1e-9 * c)


def test_drum_at_the_end_mesh_and_condensed_stiffness_by_hand():
    """Nodes A, B, S, D, C = 0..4; falls A-B (5 m, (0.6, 0, -0.8)), B-S (5 m,
    (0.6, 0, 0.8)), S-D (8 m, down). The drum at the END: xi = +R theta; the extra length
    is between a new slip 2 where the last fall ends and the drum, along the last fall.
    Condensed: r = e_AB . u_B - e_BS . u_B + R theta = (0, -1.6, 0.5) on (B x, B z,
    theta) (the material slides over the frictionless block B, so B x has no stiffness),
    L = 5 + 5 + 8 + 2 = 20 m, c = 5e6; the massless r2 below B adds 2e7 / 4 on B z.
    Tolerance as above."""
    s = assemble(load("v.yaml", V_ROPE))
    rm = s.dofs.ropes
    assert rm.ropes == (0,)                     # r2 has no mass: no elements
    assert rm.n_interior == 0 and rm.coords.shape == (0, 3) and rm.direction.shape == (0, 3)
    assert rm.slip_names == ("slip r over B (pass 1)", "slip r over S (pass 2)",
                             "slip r (extra length)")
    assert rm.node.tolist() == [[3, 3], [0, 1], [1, 2], [2, 3]]
    assert rm.slip.tolist() == [[2, -1], [-1, 0], [0, 1], [1, 2]]
    assert rm.drum.tolist() == [[-1, 0], [-1, -1], [-1, -1], [-1, -1]]
    assert rm.coef.tolist() == [[1, 0.5], [0, 1], [1, 1], [1, 1]]
    assert rm.fall.tolist() == [-1, 0, 1, 2]
    np.testing.assert_allclose(rm.e, [DOWN, [0.6, 0, -0.8], [0.6, 0, 0.8], DOWN],
                               atol=1e-15)
    np.testing.assert_allclose(rm.length, [2, 5, 5, 8], rtol=1e-15)
    r = np.array([0.0, -1.6, 0.5])
    K = 5.0e6 * np.outer(r, r) + np.diag([0.0, 5.0e6, 0.0])
    np.testing.assert_allclose(_condensed(s, ["node B x", "node B z", "drum hoist"]), K,
                               rtol=1e-9, atol=1e-9 * 5.0e6)


def test_massless_ropes_are_meshed_when_asked():
    """include_massless: r2 (B-C, 4 m down, one element) joins the mesh as rope 1, dead
    ends at both ends (no slip, no drum, coefficient 0)."""
    m = load("v.yaml", V_ROPE)
    rm = discretize(m, 1, include_massless=True)
    assert rm.ropes == (0, 1)
    assert rm.rope.tolist() == [0, 0, 0, 0, 1]
    assert rm.node[-1].tolist() == [1, 4]
    assert rm.slip[-1].tolist() == [-1, -1] and rm.drum[-1].tolist() == [-1, -1]
    assert rm.coef[-1].tolist() == [0, 0] and rm.fall[-1] == 0
    np.testing.assert_allclose(rm.e[-1], DOWN, atol=1e-15)
    assert rm.length[-1] == 4.0
    assert discretize(m, 1).ropes == (0,)


def test_end_maps_put_the_material_on_its_node_plus_its_slip_along_the_fall():
    """[u_start; u_end] = B u[dofs] with each end u(node) + coef xi e (docs/ropes.md),
    computed here per element from the layout for a random primitive vector u; unused
    slots (dead ends) point at dof 0 with zero coefficients."""
    for text, n in ((TACKLE, 2), (V_ROPE, 1)):
        s = assemble(load("m.yaml", text))
        rm, lay = s.dofs.ropes, s.dofs.layout
        u = np.random.default_rng(3).standard_normal(lay.size)
        dofs, B = endpoint_maps(rm, lay)
        assert dofs.shape == (len(rm.length), 8) and B.shape == (len(rm.length), 6, 8)
        got = np.einsum("eij,ej->ei", B, u[dofs])
        for k in range(len(rm.length)):
            for end in (0, 1):
                want = u[lay.node(rm.node[k, end])].copy()
                if rm.slip[k, end] >= 0:
                    want += rm.coef[k, end] * u[lay.slip(rm.slip[k, end])] * rm.e[k]
                    assert dofs[k, 4 * end + 3] == lay.slip(rm.slip[k, end])
                elif rm.drum[k, end] >= 0:
                    want += rm.coef[k, end] * u[lay.drum(rm.drum[k, end])] * rm.e[k]
                    assert dofs[k, 4 * end + 3] == lay.drum(rm.drum[k, end])
                else:
                    assert dofs[k, 4 * end + 3] == 0
                    assert not B[k, :, 4 * end + 3].any()
                np.testing.assert_allclose(got[k, 3 * end:3 * end + 3], want, atol=1e-14)
    # the drum end of the tackle: coefficient -R on the drum's column, along the lead
    s = assemble(load("t.yaml", TACKLE))
    dofs, B = endpoint_maps(s.dofs.ropes, s.dofs.layout)
    np.testing.assert_allclose(B[0, :3, 3], -0.5 * E_DS, atol=1e-15)


def test_massless_rope_rows_by_hand_at_the_reference_and_at_other_positions():
    """rope_rows (seed eq. 2-3): per rope sum_s f_s e_s . (u_b - u_a) + R theta at a drum
    end, and L = sum f_s l_s + extra. r: A-B-S-D gives on B (0.6 - 0.6, -0.8 - 0.8) =
    (0, -1.6), on A (-0.6, 0.8), on S (0.6 + 0, 0.8 + 1), on D (0, -1), drum +0.5;
    L = 20. r2 (B -> C down): +1 on B z, -1 on C z, L = 4. At positions with B moved to
    (6, 0, 0): A-B = (6, 0, -8) (10 m), B-S = (0, 0, 8) (8 m): B (0.6, -1.8), L = 28."""
    m = load("v.yaml", V_ROPE)
    lay = assemble(m).dofs.layout
    A, B, S, D, C = (lay.node(m.node_names.index(n)) for n in "ABSDC")
    drum = lay.drum(0)
    R, L = rope_rows(m, lay)
    assert R.shape == (2, lay.size)
    want = np.zeros((2, lay.size))
    want[0, A] = [-0.6, 0, 0.8]
    want[0, B] = [0, 0, -1.6]
    want[0, S] = [0.6, 0, 1.8]
    want[0, D] = [0, 0, -1]
    want[0, drum] = 0.5
    want[1, B] = [0, 0, 1]
    want[1, C] = [0, 0, -1]
    np.testing.assert_allclose(R.toarray(), want, atol=1e-15)
    np.testing.assert_allclose(L, [20, 4], rtol=1e-15)
    R1, L1 = rope_rows(m, lay, which=[1])
    np.testing.assert_allclose(R1.toarray(), want[1:], atol=1e-15)
    np.testing.assert_allclose(L1, [4], rtol=1e-15)
    moved = m.coords.copy()
    moved[m.node_names.index("B")] = [6, 0, 0]
    Rm, Lm = rope_rows(m, lay, which=[0], coords=moved)
    np.testing.assert_allclose(Rm.toarray()[0, B], [0.6, 0, -1.8], atol=1e-15)
    np.testing.assert_allclose(Rm.toarray()[0, drum], 0.5, atol=1e-15)
    np.testing.assert_allclose(Lm, [28], rtol=1e-15)
    R0, L0 = rope_rows(m, lay, which=[])
    assert R0.shape == (0, lay.size) and L0.shape == (0,)


# a rope between two drums over a sheave S: falls D0 -> S (3, 0, 4) and S -> D1
# (3, 0, -4), 5 m each, three elements per fall; a light rope (0.5 kg/m) with a short
# extra length (0.5 m), which sits at the START (the first end is a drum)
TWO_DRUMS = """cranefe: 1
plane: xz
nodes: {D0: [0, 0, 0], S: [3, 0, 4], D1: [6, 0, 0]}
ground: [D0, S, D1]
drums:
  d0: {node: D0, radius: 0.5, inertia: 10}
  d1: {node: D1, radius: 0.25, inertia: 5}
ropes:
  r: {EA: 1.0e7, path: [d0, S, d1], mass_per_length: 0.5, extra_length: 0.5}
effects: {rope_mass: 3, sway: false}
"""


def test_rope_between_two_drums_mesh_and_condensed_stiffness_by_hand():
    """Nodes D0, S, D1 = 0, 1, 2; interior nodes at thirds of each fall: 3 (1, 0, 4/3),
    4 (2, 0, 8/3), 5 (4, 0, 8/3), 6 (5, 0, 4/3); slip 0 over S, slip 1 the extra length,
    which goes to the start (drums at both ends), between drum d0 (xi = -0.5 theta0) and
    slip 1. The last end is drum d1: xi = +0.25 theta1. Condensed (docs/theory.md
    section 2): Delta = R0 theta0 + R1 theta1, L = 5 + 5 + 0.5 = 10.5 m,
    K = EA / L [[R0^2, R0 R1], [R0 R1, R1^2]] on (d0, d1); tolerance as above."""
    s = assemble(load("d.yaml", TWO_DRUMS))
    rm = s.dofs.ropes
    up, down = [0.6, 0, 0.8], [0.6, 0, -0.8]
    np.testing.assert_allclose(rm.coords, [[1, 0, 4 / 3], [2, 0, 8 / 3], [4, 0, 8 / 3],
                                           [5, 0, 4 / 3]], atol=1e-14)
    assert rm.slip_names == ("slip r over S (pass 1)", "slip r (extra length)")
    assert rm.node.tolist() == [[0, 0], [0, 3], [3, 4], [4, 1], [1, 5], [5, 6], [6, 2]]
    assert rm.slip.tolist() == [[-1, 1], [1, -1], [-1, -1], [-1, 0], [0, -1], [-1, -1],
                                [-1, -1]]
    assert rm.drum.tolist() == [[0, -1]] + [[-1, -1]] * 5 + [[-1, 1]]
    assert rm.coef.tolist() == [[-0.5, 1], [1, 0], [0, 0], [0, 1], [1, 0], [0, 0],
                                [0, 0.25]]
    np.testing.assert_allclose(rm.e, [up] * 4 + [down] * 3, atol=1e-15)
    np.testing.assert_allclose(rm.length, [0.5] + [5 / 3] * 6, rtol=1e-15)
    R = np.array([0.5, 0.25])
    np.testing.assert_allclose(_condensed(s, ["drum d0", "drum d1"]),
                               1.0e7 / 10.5 * np.outer(R, R), rtol=1e-9, atol=1e-9 * 1e6)


def test_a_light_rope_listed_after_a_massless_one_is_meshed():
    """Ropes are chosen by mass > 0, whatever their order and however light: r2 first
    (massless, skipped), then r; and r2 at 0.5 kg/m with 0.5 m of extra length (dead ends
    at both ends: the extra piece goes where its first fall begins, at B)."""
    first = V_ROPE.replace("  r: {EA: 1.0e8, path: [A, B, S, hoist], mass_per_length: 5, "
                           "extra_length: 2}\n  r2: {EA: 2.0e7, path: [B, C]}\n",
                           "  r2: {EA: 2.0e7, path: [B, C]}\n  r: {EA: 1.0e8, path: "
                           "[A, B, S, hoist], mass_per_length: 5, extra_length: 2}\n")
    rm = discretize(load("v.yaml", first), 1)
    assert rm.ropes == (1,) and rm.rope.tolist() == [1, 1, 1, 1]
    light = V_ROPE.replace("r2: {EA: 2.0e7, path: [B, C]}",
                           "r2: {EA: 2.0e7, path: [B, C], mass_per_length: 0.5, "
                           "extra_length: 0.5}")
    rm = discretize(load("v.yaml", light), 1)
    assert rm.ropes == (0, 1)
    assert rm.node[4:].tolist() == [[1, 1], [1, 4]]
    assert rm.slip[4:].tolist() == [[-1, 3], [3, -1]]
    assert rm.fall[4:].tolist() == [-1, 0]
    np.testing.assert_allclose(rm.length[4:], [0.5, 4.0], rtol=1e-15)


def test_no_rope_with_mass_leaves_the_massless_rope():
    """rope_mass: 1 with no rope carrying mass: an empty mesh, and K is the massless
    rope's (r = (0, -1.6, 0.5), c = 1e8 / 20) plus r2 (2e7 / 4 on B z), exactly."""
    s = assemble(load("v.yaml", V_ROPE.replace("mass_per_length: 5, ", "")))
    rm = s.dofs.ropes
    assert rm.ropes == () and rm.node.shape == (0, 2) and rm.e.shape == (0, 3)
    assert s.dofs.labels == ("node B x", "node B z", "drum hoist")
    r = np.array([0.0, -1.6, 0.5])
    np.testing.assert_allclose(s.K.toarray(), 5.0e6 * np.outer(r, r)
                               + np.diag([0.0, 5.0e6, 0.0]), rtol=1e-12, atol=1e-3)
