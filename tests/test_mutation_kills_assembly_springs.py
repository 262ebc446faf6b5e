"""Kill tests for cranefe/assembly/springs.py, pattern.py, coo.py, stiffness.py and
reuse.py (tools/mutation.py assembly; docs/testing.md, "Mutation testing"): every field
of the spring rows, the unit pattern, its null space, the one COO step and the reuse
stores, written out by hand.

- One 3D model with every kind of spring-like row (`spring_rows`): a rope with mass in
  two elements listed FIRST (rope index 0), a massless rope over a sheave (rope index 1,
  one row over its reeving), a beam member before a truss member (the truss is member
  element 1, not 0), an axial spring, a rotational spring to the ground and one between
  two bodies. Each row's coefficients (the elongation e . (u_b - u_a) of each span, the
  relative rotation a . (theta_2 - theta_1)), stiffness (EA / L, EA / l_e, E A / l, k),
  absorption psi, name, deformable length and rope / spring / member index are written
  out from the geometry.
- `elastic_stiffness`: K_u = sum_i c_i r_i r_i^T of those rows plus the beam block;
  with `rope_elasticity: false` the rope rows carry no stiffness.
- `pattern`: rows scaled to unit length (a row of zero stiffness or zero length left
  out), element blocks replaced by |block| / max |eigenvalue|, mapped by T^T P T.
- `null_space`: Jacobi scaling, the threshold, a coordinate nothing touches, the
  columns normalised to unit max-norm.
- `Blocks.unit_abs`, `Triplets.add_blocks`, `coo`, `sum_blocks` on small blocks.
- `Reuse`: hits, misses, least-recently-used eviction, `clear`, and that a kept null
  space or DOF map is the one computed for the same input.

Tolerances: the rows are sums of two or three products of unit vectors whose entries
are exact to the last bit or square roots (1e-14 relative / absolute); stiffness values
are single quotients (1e-14); matrices of products of those, 1e-12 of their largest
entry; the null spaces come from `eigh` of matrices of size <= 4, 1e-12.
"""

import math
from types import SimpleNamespace

import numpy as np
import pytest
import scipy.sparse as sp

from cranefe.assembly.coo import Blocks, Triplets, coo, sum_blocks
from cranefe.assembly.pattern import NULL_TOL, null_space, pattern
from cranefe.assembly.reuse import Reuse
from cranefe.assembly.springs import spring_rows
from cranefe.assembly.stiffness import elastic_stiffness
from cranefe.coordinates import build_dofs
from cranefe.model import load

MODEL = """cranefe: 1
nodes: {{O: [0, 0, 0], P: [6, 0, 8], S: [0, 0, 3], K: [3, 0, 4], B: [6, 0, 4],
        L: [3, 0, 0], C: [6, 0, 0]}}
ground: [O, P]
bodies:
  box: {{mass: 100, com: [3, 0, 4], inertia: [1, 2, 3], nodes: [K, S]}}
  cab: {{mass: 50, com: [6, 0, 4], inertia: [1, 1, 1], nodes: [B]}}
masses: {{L: 10, C: 5}}
ropes:
  fall: {{EA: 1.0e6, mass_per_length: 2.0, path: [K, L], psi: 0.4}}
  tag: {{EA: 2.0e6, path: [O, S, K], psi: 0.3}}
members:
  post: {{type: beam, nodes: [P, B], E: 2.0e11, G: 8.0e10, A: 1.0e-3, Iy: 1.0e-6,
         Iz: 1.0e-6, J: 2.0e-6, rho: 0, orientation: [0, 1, 0]}}
  bar: {{type: truss, nodes: [B, C], E: 1.0e11, A: 2.0e-4, rho: 0, psi: 0.05}}
springs:
  - {{name: sling, type: axial, nodes: [L, C], stiffness: 3.0e4, psi: 0.2}}
  - {{name: bend, type: rotational, bodies: [ground, box], axis: [0, 1, 0],
     stiffness: 5.0e6, psi: 0.1}}
  - {{name: twist, type: rotational, bodies: [box, cab], axis: [0, 0, 1],
     stiffness: 7.0e5}}
effects: {{structure: flexible, {effects}}}
"""

# primitive coordinates (Layout: 6 per node, model nodes O P S K B L C then the rope's
# interior node M; then 6 per body box, cab)
NODE = {n: 6 * i for i, n in enumerate("O P S K B L C M".split())}
BODY_ROT = {"box": 48 + 3, "cab": 54 + 3}
SIZE = 60


def _model(effects="rope_mass: 2"):
    return load("springs.yaml", MODEL.format(effects=effects))


def _row(**parts):
    """A dense elongation row: node -> vector on its translations, body -> on its
    rotations."""
    r = np.zeros(SIZE)
    for key, vec in parts.items():
        i = BODY_ROT[key] if key in BODY_ROT else NODE[key]
        r[i:i + 3] += vec
    return r


def _without_m(R):
    """Rows of the layout without the rope's interior node M (7 nodes, size 54)."""
    keep = np.r_[0:NODE["M"], NODE["M"] + 6:SIZE]
    return R[:, keep]


def _hand_rows():
    """Rows in the order spring_rows gives them: the massless ropes, ropes with mass (per
    element), trusses, springs."""
    down = np.array([0.0, 0.0, -1.0])
    e_sk = np.array([3.0, 0.0, 1.0]) / math.sqrt(10.0)     # S -> K, the tag's 2nd span
    up = np.array([0.0, 0.0, 1.0])                          # O -> S, the tag's 1st span
    return np.array([
        _row(O=-up, S=up - e_sk, K=e_sk),     # tag over the sheave S: both spans
        _row(K=-down, M=down),                # fall, element K -> M (M at z = 2)
        _row(M=-down, L=down),                # fall, element M -> L
        _row(B=-down, C=down),                # bar B -> C (truss member element 1)
        _row(L=-np.array([1.0, 0, 0]), C=np.array([1.0, 0, 0])),     # sling L -> C
        _row(box=np.array([0.0, 1.0, 0.0])),                          # bend: ground-box
        _row(box=-np.array([0.0, 0, 1.0]), cab=np.array([0.0, 0, 1.0])),  # twist
    ])


L_TAG = 3.0 + math.sqrt(10.0)
C_HAND = np.array([2.0e6 / L_TAG, 1.0e6 / 2, 1.0e6 / 2, 1.0e11 * 2.0e-4 / 4, 3.0e4, 5.0e6,
                   7.0e5])


def test_every_field_of_the_spring_rows_by_hand():
    m = _model()
    d = build_dofs(m)
    assert (d.layout.n_nodes, d.layout.n_bodies, d.layout.size) == (8, 2, SIZE)
    assert np.allclose(d.coords[7], [3.0, 0.0, 2.0])       # the rope's interior node M
    s = spring_rows(m, d.layout, d.ropes, d.members)
    assert isinstance(s.R, sp.csr_matrix)
    np.testing.assert_allclose(s.R.toarray(), _hand_rows(), rtol=0, atol=1e-14)
    np.testing.assert_allclose(s.c, C_HAND, rtol=1e-14)
    np.testing.assert_array_equal(s.psi, [0.3, 0.4, 0.4, 0.05, 0.2, 0.1, 0.0])
    assert s.names == ("rope tag", "rope fall", "rope fall", "member bar", "spring sling",
                       "spring bend", "spring twist")
    np.testing.assert_allclose(s.length, [L_TAG, 2.0, 2.0, 4.0, 3.0, np.nan, np.nan],
                               rtol=1e-14)
    np.testing.assert_array_equal(s.rope, [1, 0, 0, -1, -1, -1, -1])
    np.testing.assert_array_equal(s.spring, [-1, -1, -1, -1, 0, 1, 2])
    np.testing.assert_array_equal(s.member, [-1, -1, -1, 1, -1, -1, -1])
    for f in (s.c, s.psi, s.length):
        assert f.dtype == float
    for f in (s.rope, s.spring, s.member):
        assert f.dtype.kind == "i"


def test_spring_rows_without_meshes_one_row_per_rope():
    """The same model without the meshes (no `ropes_fe`, no `members`): each rope is one
    row over its reeving, EA / L, in model order; no truss rows."""
    m = _model()
    d = build_dofs(m)
    s = spring_rows(m, d.layout)
    R = _hand_rows()
    fall = R[1] + R[2]                        # K -> L as one span (M's entries cancel)
    np.testing.assert_allclose(s.R.toarray(), np.vstack([fall, R[0], R[4:]]), atol=1e-14)
    np.testing.assert_allclose(s.c, [1.0e6 / 4, 2.0e6 / L_TAG, 3.0e4, 5.0e6, 7.0e5],
                               rtol=1e-14)
    assert s.names == ("rope fall", "rope tag", "spring sling", "spring bend",
                       "spring twist")
    np.testing.assert_array_equal(s.rope, [0, 1, -1, -1, -1])
    np.testing.assert_array_equal(s.member, [-1] * 5)
    np.testing.assert_allclose(s.length, [4.0, L_TAG, 3.0, np.nan, np.nan], rtol=1e-14)


DRUM = """cranefe: 1
plane: xz
nodes: {S: [0, 0, 4], L: [0, 0, 0], D: [2, 0, 4]}
ground: [S, D]
masses: {L: 500}
drums: {hoist: {node: D, radius: 0.25, inertia: 10}}
ropes: {r: {EA: 1.0e6, path: [hoist, L], psi: 0.1}}
members: {tie: {type: truss, nodes: [S, L], E: 1.0e11, A: 2.0e-4, rho: 0}}
effects: {structure: flexible}
"""


def test_spring_rows_of_a_model_without_springs_or_beams():
    """A drum's rope D -> L and a truss S -> L, no springs, no beams (layout: nodes S, L,
    D, then the drum: 19 coordinates). The rope's elongation is e . (u_L - u_D) plus
    radius * drum rotation (hauling in stretches it, model-format.md), e = (-2, 0, -4) /
    sqrt 20; the truss's -e_t on S, e_t on L with e_t = (0, 0, -1). The empty parts
    (no springs, no rope elements) leave the index fields integer."""
    m = load("drum.yaml", DRUM)
    d = build_dofs(m)
    assert d.layout.size == 19
    s = spring_rows(m, d.layout, d.ropes, d.members)
    e = np.array([-2.0, 0.0, -4.0]) / math.sqrt(20.0)
    R = np.zeros((2, 19))
    R[0, 6:9], R[0, 12:15], R[0, 18] = e, -e, 0.25
    R[1, 0:3], R[1, 6:9] = [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]
    assert s.R.shape == (2, 19)
    np.testing.assert_allclose(s.R.toarray(), R, rtol=0, atol=1e-15)
    np.testing.assert_allclose(s.c, [1.0e6 / math.sqrt(20.0), 1.0e11 * 2.0e-4 / 4],
                               rtol=1e-14)
    np.testing.assert_array_equal(s.psi, [0.1, 0.0])
    assert s.names == ("rope r", "member tie")
    np.testing.assert_allclose(s.length, [math.sqrt(20.0), 4.0], rtol=1e-14)
    np.testing.assert_array_equal(s.rope, [0, -1])
    np.testing.assert_array_equal(s.spring, [-1, -1])
    np.testing.assert_array_equal(s.member, [-1, 0])
    for f in (s.rope, s.spring, s.member):
        assert f.dtype.kind == "i"
    for f in (s.c, s.psi, s.length):
        assert f.dtype == float


def _beam_part(K_u, rows, c, node):
    """K_u minus the rows' part; it must be the beam post's one element P -> B alone
    (B 4 m below P): EA / l = 2e11 * 1e-3 / 4 = 5e7 N/m on the z translations,
    12 EI / l^3 = 12 * 2e11 * 1e-6 / 64 = 37500 N/m on x and y, nothing elsewhere."""
    beam = K_u.toarray() - rows.T @ np.diag(c) @ rows
    P, B = node["P"], node["B"]
    for comp, k in ((2, 5.0e7), (0, 37500.0), (1, 37500.0)):
        assert beam[P + comp, P + comp] == pytest.approx(k, rel=1e-12)
        assert beam[B + comp, B + comp] == pytest.approx(k, rel=1e-12)
        assert beam[P + comp, B + comp] == pytest.approx(-k, rel=1e-12)
    outside = np.ones(len(beam), bool)
    outside[np.r_[P:P + 6, B:B + 6]] = False
    assert np.abs(beam[outside]).max() <= 1e-12 * np.abs(K_u).max()
    return beam


def test_elastic_stiffness_is_the_rows_and_the_beam_block():
    """K_u = sum_i c_i r_i r_i^T + the beam block (the post, one element)."""
    m = _model()
    d = build_dofs(m)
    K_u, s, beams, beam_psi = elastic_stiffness(m, d, m.effects)
    assert isinstance(K_u, sp.csr_matrix)
    np.testing.assert_allclose(s.c, C_HAND, rtol=1e-14)
    _beam_part(K_u, _hand_rows(), C_HAND, NODE)
    assert beams.idx.shape == (1, 12)
    np.testing.assert_array_equal(beam_psi, [0.0])


def test_inextensible_ropes_carry_no_stiffness():
    """`rope_elasticity: false` (no rope mass: the ropes are constraints): both rope rows
    have c = 0, the truss and the springs keep theirs; without the effects argument the
    ropes are springs (EA / L; the fall K -> L one row of 4 m). Without rope mass the
    massless ropes come in model order (fall, then tag)."""
    m = _model("rope_elasticity: false")
    d = build_dofs(m)
    assert d.layout.size == SIZE - 6
    node = {k: v - 6 * (v > NODE["M"]) for k, v in NODE.items()}
    R = _hand_rows()
    rows = _without_m(np.vstack([R[1] + R[2], R[0], R[3:]]))    # model order: fall, tag
    K_u, s, _, _ = elastic_stiffness(m, d, m.effects)
    c = np.r_[0.0, 0.0, C_HAND[3:]]
    np.testing.assert_allclose(s.c, c, rtol=1e-14)
    np.testing.assert_array_equal(s.rope, [0, 1, -1, -1, -1, -1])
    _beam_part(K_u, rows, c, node)
    K_u, s, _, _ = elastic_stiffness(m, d)
    c = np.r_[1.0e6 / 4, 2.0e6 / L_TAG, C_HAND[3:]]
    np.testing.assert_allclose(s.c, c, rtol=1e-14)
    _beam_part(K_u, rows, c, node)


def test_elastic_stiffness_without_beams():
    """Rigid structure (no member mesh): K_u = R^T diag(c) R of the ropes and springs
    only, no beam blocks."""
    m = load("springs.yaml", MODEL.format(effects="rope_mass: 2").replace(
        "structure: flexible, ", ""))
    d = build_dofs(m)
    K_u, s, beams, beam_psi = elastic_stiffness(m, d)
    assert beams is None and beam_psi is None
    R = _hand_rows()
    r = np.vstack([R[:3], R[4:]])
    c = np.r_[C_HAND[:3], C_HAND[4:]]
    K = r.T @ np.diag(c) @ r
    np.testing.assert_allclose(K_u.toarray(), K, rtol=0, atol=1e-12 * np.abs(K).max())


def test_pattern_scales_rows_and_blocks_to_unit_size():
    """R rows (3, 4, 0) (norm 5, c = 1), (0, 0, 0) (norm 0: left out), (0, 2, 0) with
    c = 0 (left out) and (0.3, 0, 0.4) (norm 0.5: scaled up to (0.6, 0, 0.8)); one
    elastic block [[1, 2], [2, 1]] on (1, 2), eigenvalues 3 and -1:
    |B| / 3 = [[2/3, 1/3], [1/3, 2/3]]; one geometric block [[0, 0], [0, -5]] on (0, 2):
    |B| / 5 = diag(0, 1). P = sum of the scaled rows' outer products + both blocks;
    then T^T P T."""
    R = sp.csr_matrix(np.array([[3.0, 4.0, 0.0], [0.0, 0.0, 0.0], [0.0, 2.0, 0.0],
                                [0.3, 0.0, 0.4]]))
    springs = SimpleNamespace(R=R, c=np.array([1.0, 7.0, 0.0, 2.0]))
    T = np.array([[1.0, 0.0], [2.0, 1.0], [0.0, 3.0]])
    dofs = SimpleNamespace(T=sp.csr_matrix(T))
    el = Blocks(np.array([[1, 2]]), np.array([[[1.0, 2.0], [2.0, 1.0]]]))
    geo = Blocks(np.array([[0, 2]]), np.array([[[0.0, 0.0], [0.0, -5.0]]]))
    P0 = np.array([[0.36, 0.48, 0.0], [0.48, 0.64, 0.0], [0.0, 0.0, 0.0]]) \
        + np.array([[0.36, 0.0, 0.48], [0.0, 0.0, 0.0], [0.48, 0.0, 0.64]])
    P = P0.copy()
    P[1:, 1:] += np.array([[2.0, 1.0], [1.0, 2.0]]) / 3
    P[2, 2] += 1.0
    got = pattern(springs, dofs, [el], [geo])
    assert isinstance(got, sp.csr_matrix)
    np.testing.assert_allclose(got.toarray(), T.T @ P @ T, rtol=0, atol=1e-14)
    # without blocks: the rows only
    np.testing.assert_allclose(pattern(springs, dofs).toarray(), T.T @ P0 @ T, atol=1e-14)
    # elastic blocks only, geometric only
    np.testing.assert_allclose(pattern(springs, dofs, [el]).toarray(),
                               T.T @ (P - np.diag([0, 0, 1.0])) @ T, atol=1e-14)
    np.testing.assert_allclose(pattern(springs, dofs, (), [geo]).toarray(),
                               T.T @ (P0 + np.diag([0, 0, 1.0])) @ T, atol=1e-14)


def _same_columns(N, expected):
    """N equals `expected` up to the sign of each column (each has a max-norm of 1)."""
    assert N.shape == expected.shape
    for j in range(N.shape[1]):
        s = np.sign(N[np.argmax(np.abs(N[:, j])), j])
        np.testing.assert_allclose(s * N[:, j], expected[:, j], rtol=0, atol=1e-12)


def test_null_space_of_a_pattern_with_contrast_and_an_untouched_coordinate():
    """A bar between coordinates 0 and 1 of scales 1 and 1e4 (P = r r^T with
    r = (1, -1e4), diagonal 1 and 1e8: the motion (1, 1e-4) is free), coordinate 2 with
    stiffness 4 (not free), coordinate 3 untouched (P_33 = 0: free). Null space:
    (1, 1e-4, 0, 0) and (0, 0, 0, 1), each normalised to a max-norm of 1. The Jacobi
    scaling makes the 1e8 contrast harmless (the threshold is relative to the scaled
    matrix's largest eigenvalue, 2)."""
    r = np.array([1.0, -1.0e4, 0.0, 0.0])
    P = np.outer(r, r)
    P[2, 2] = 4.0
    N = null_space(P)
    _same_columns(N[:, np.argsort(np.abs(N[3]))],
                  np.array([[1.0, 1e-4, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]]).T)
    # nothing free: an empty (n, 0) array
    N = null_space(np.diag([1.0, 2.0, 3.0]))
    assert N.shape == (3, 0)
    # a zero-size pattern
    assert null_space(np.zeros((0, 0))).shape == (0, 0)


def test_null_space_threshold_is_relative_to_the_largest_scaled_eigenvalue():
    """Two unit-diagonal coordinates coupled by a correlation rho: the scaled matrix
    [[1, rho], [rho, 1]] has eigenvalues 1 - rho and 1 + rho (about 2, so the threshold
    NULL_TOL * top is about 2 NULL_TOL), eigenvector (1, -1) for 1 - rho: a gap
    1 - rho = 1.5 NULL_TOL is null (it would not be against NULL_TOL * 1), 4 NULL_TOL is
    not. With the diagonal scaled by (1, 100) (d = 1, 1e4) the null vector is
    (1, -1e-2) up to scale: the scaling is undone on the way back (s = 1 / sqrt(d)).
    Three unit vectors nearly at 120 degrees (Gram matrix with off-diagonal
    c = -1/2 + delta): eigenvalues 2 delta along (1, 1, 1) and 3/2 - delta twice, so the
    threshold is 1.5 NULL_TOL: 2 delta = 1.75 NULL_TOL is not null (it would be against
    max(top, 2)), 1.25 NULL_TOL is. The margins (12-25 %) are far above the eigenvalues'
    round-off (1e-16)."""
    for gap, free in ((1.5 * NULL_TOL, True), (4 * NULL_TOL, False)):
        rho = 1 - gap
        A = np.array([[1.0, rho], [rho, 1.0]])
        D = np.diag([1.0, 100.0])
        N = null_space(D @ A @ D)
        if free:
            _same_columns(N, np.array([[1.0, -0.01]]).T)
        else:
            assert N.shape == (2, 0)
    for w_min, free in ((1.75 * NULL_TOL, False), (1.25 * NULL_TOL, True)):
        c = -0.5 + w_min / 2
        A = np.full((3, 3), c) + (1 - c) * np.eye(3)
        N = null_space(A)
        if free:
            _same_columns(N, np.ones((3, 1)))
        else:
            assert N.shape == (3, 0)
    # tiny diagonal entries: the scaled matrix is the identity, nothing is free whatever
    # the size of P
    assert null_space(np.diag([1e-30, 1e-20])).shape == (2, 0)
    # the explicit tolerance argument: eigenvalues 1 - rho = 1e-6 free with tol 1e-5
    A = np.array([[1.0, 1 - 1e-6], [1 - 1e-6, 1.0]])
    _same_columns(null_space(A, tol=1e-5), np.array([[1.0, -1.0]]).T)
    assert null_space(A).shape == (2, 0)


def test_unit_abs_of_blocks_by_hand():
    """[[1, 2], [2, 1]]: eigenvalues 3 (1, 1)/sqrt 2 and -1 (1, -1)/sqrt 2: |B| / 3 =
    [[2/3, 1/3], [1/3, 2/3]]; diag(-4, 2) -> diag(1, 0.5); a zero block stays zero;
    diag(0.5, -0.125), largest |eigenvalue| below 1, -> diag(1, 0.25)."""
    b = Blocks(np.array([[0, 1], [1, 2], [2, 3], [3, 0]]),
               np.array([[[1.0, 2.0], [2.0, 1.0]], [[-4.0, 0.0], [0.0, 2.0]],
                         np.zeros((2, 2)), [[0.5, 0.0], [0.0, -0.125]]]))
    u = b.unit_abs()
    np.testing.assert_array_equal(u.idx, b.idx)
    np.testing.assert_allclose(u.mat, [[[2 / 3, 1 / 3], [1 / 3, 2 / 3]],
                                       [[1.0, 0.0], [0.0, 0.5]], np.zeros((2, 2)),
                                       [[1.0, 0.0], [0.0, 0.25]]],
                               rtol=0, atol=1e-15)


def test_triplets_blocks_and_coo_sum_duplicates():
    """Blocks [[1, 2], [3, 4]] on (0, 2) and [[10, 20], [30, 40]] on (2, 1): entry (2, 2)
    gets 4 + 10; the block's row index is its first index."""
    t = Triplets()
    t.add_blocks(np.array([[0, 2], [2, 1]]),
                 np.array([[[1.0, 2.0], [3.0, 4.0]], [[10.0, 20.0], [30.0, 40.0]]]))
    expected = np.array([[1.0, 0.0, 2.0], [0.0, 40.0, 30.0], [3.0, 20.0, 14.0]])
    K = t.csr((3, 3))
    assert isinstance(K, sp.csr_matrix)
    np.testing.assert_array_equal(K.toarray(), expected)
    # one block given with a 1-D index
    t = Triplets()
    t.add_blocks([2, 0], np.array([[1.0, 2.0], [3.0, 4.0]]))
    np.testing.assert_array_equal(t.csr((3, 3)).toarray(),
                                  [[4.0, 0.0, 3.0], [0.0, 0.0, 0.0], [2.0, 0.0, 1.0]])
    # sum_blocks: the same two blocks as two Blocks
    S = sum_blocks([Blocks(np.array([[0, 2]]), np.array([[[1.0, 2.0], [3.0, 4.0]]])),
                    Blocks(np.array([[2, 1]]), np.array([[[10.0, 20.0], [30.0, 40.0]]]))], 3)
    np.testing.assert_array_equal(S.toarray(), expected)
    assert S.shape == (3, 3)
    # coo: lists of arrays, duplicates summed; no arrays -> an empty matrix of the shape
    A = coo([np.array([0, 1]), np.array([1])], [np.array([2, 0]), np.array([0])],
            [np.array([1.5, 2.0]), np.array([0.25])], (2, 4))
    assert isinstance(A, sp.csr_matrix)
    np.testing.assert_array_equal(A.toarray(), [[0, 0, 1.5, 0], [2.25, 0, 0, 0]])
    E = coo([], [], [], (2, 5))
    assert isinstance(E, sp.csr_matrix) and E.shape == (2, 5) and E.nnz == 0


def test_reuse_keeps_null_spaces_and_dof_maps_least_recently_used():
    r = Reuse(size=2)
    assert r.size == 2
    P1 = sp.csr_matrix(np.array([[1.0, -1.0], [-1.0, 1.0]]))
    P2 = sp.csr_matrix(np.diag([1.0, 0.0]))
    P3 = sp.csr_matrix(np.diag([0.0, 1.0]))
    N1 = r.null_space(P1)
    _same_columns(N1, np.array([[1.0, 1.0]]).T)
    assert (r.hits["null_space"], r.misses["null_space"]) == (0, 1)
    # the same matrix, built in another way (unsorted indices, a COO): a hit, the same array
    P1b = sp.coo_matrix(([1.0, -1.0, 1.0, -1.0], ([1, 1, 0, 0], [1, 0, 0, 1])), (2, 2))
    assert r.null_space(P1b) is N1
    assert (r.hits["null_space"], r.misses["null_space"]) == (1, 1)
    # another matrix: a miss, and its own null space
    _same_columns(r.null_space(P2), np.array([[0.0, 1.0]]).T)
    _same_columns(r.null_space(P3), np.array([[1.0, 0.0]]).T)
    assert r.misses["null_space"] == 3
    # size 2: P1 (used least recently) is gone, P2 and P3 are kept
    assert len(r._stores["null_space"]) == 2
    r.null_space(P2)
    r.null_space(P3)
    assert (r.hits["null_space"], r.misses["null_space"]) == (3, 3)
    r.null_space(P1)                              # computed again, evicts P2
    assert (r.hits["null_space"], r.misses["null_space"]) == (3, 4)
    r.null_space(P3)                              # still kept: a hit
    assert r.hits["null_space"] == 4
    r.null_space(P2)
    assert r.misses["null_space"] == 5
    # P1 zero-padded to (3, 3): another key (its indptr is longer), its own null space
    P1c = sp.csr_matrix((P1.data, P1.indices, np.r_[P1.indptr, P1.indptr[-1]]), (3, 3))
    assert r.null_space(P1c).shape == (3, 2)
    assert r.misses["null_space"] == 6
    # a different value at the same places: another key
    P2v = sp.csr_matrix(np.diag([2.0, 0.0]))
    r.null_space(P2v)
    assert r.misses["null_space"] == 7
    # the DOF maps: one per structure; the recency of a hit keeps it
    m = _model()
    d1 = r.dofs(m, m.effects)
    assert r.dofs(m, m.effects) is d1
    assert (r.hits["dofs"], r.misses["dofs"]) == (1, 1)
    assert d1.n == build_dofs(m).n and d1.labels == build_dofs(m).labels
    # another model with the same effects: its own DOF map
    other = load("other.yaml", "cranefe: 1\nplane: xz\nnodes: {S: [0, 0, 4], L: [0, 0, 0]}\n"
                 "ground: [S]\nmasses: {L: 500}\nsprings:\n  - {type: axial, nodes: [S, L], "
                 "stiffness: 2.0e5}\n")
    d_other = r.dofs(other, m.effects)
    assert d_other.labels == ("node L x", "node L z")
    assert r.misses["dofs"] == 2
    rigid = m.effects.__class__(**{**m.effects.__dict__, "structure": "rigid"})
    d2 = r.dofs(m, rigid)
    assert d2 is not d1 and d2.members is None
    assert r.misses["dofs"] == 3
    r.clear()
    assert r.size == 2 and not r.hits and not r.misses
    assert not r._stores["dofs"] and not r._stores["null_space"]
    assert r.dofs(m, m.effects) is not d1


def test_reuse_default_size_keeps_sixteen():
    r = Reuse()
    mats = [sp.csr_matrix(np.diag([float(k + 1), 0.0])) for k in range(17)]
    for P in mats[:16]:
        r.null_space(P)
    r.null_space(mats[0])
    assert r.hits["null_space"] == 1               # 16 kept: the first is still there
    r.null_space(mats[16])                         # the 17th evicts the least recent (1)
    r.null_space(mats[0])
    assert r.hits["null_space"] == 2
    r.null_space(mats[1])
    assert r.misses["null_space"] == 18
