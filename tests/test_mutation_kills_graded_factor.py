"""Fast value tests that kill mutants of cranefe/analysis/graded.py left by the model
tests of tools/mutation.py graded (docs/testing.md, "Mutation testing"): the element
factor's contract K = F^T diag(sign) F on element blocks and merged blocks written by
hand whose diagonals span 14 orders (the Jacobi scaling decides which motions are null),
`element_energy`'s zero test (scale-free, per row, per mode) on a spring written by hand,
and graded models whose element factor must hold every element: a cantilever beam with
two springs at its tip (closed form) and one coordinate held by a 1 N/m spring beside a
2e6 N/m one.
"""

import numpy as np
import pytest
import scipy.sparse as sp

from cranefe.analysis.graded import ElementFactor, _block_rows, _psd_rows, element_energy
from cranefe.analysis.modal import modes
from cranefe.assembly import Blocks
from cranefe.model import load

# K = D^1/2 C D^1/2 with C = [[1, 1/2], [1/2, 1]] (eigenvalues 1/2, 3/2) and
# D = diag(1e4, 1e-10): positive definite, but its eigenvalues unscaled are 1e4 and
# 7.5e-11 (det 7.5e-7 / 1e4), a ratio 7.5e-15 below NULL_BLOCK: only after the Jacobi
# scaling (unit diagonal: C itself) is its second motion seen not to be null.
GRADED_BLOCK = np.array([[1.0e4, 0.5e-3], [0.5e-3, 1.0e-10]])


def _entrywise(got, want, rtol):
    """Each entry to rtol of itself (the entries span 14 orders); zeros to rtol of the
    largest entry of its row."""
    scale = np.maximum(np.abs(want), rtol * np.abs(want).max(axis=1, keepdims=True))
    assert np.all(np.abs(got - want) <= rtol * scale), (got, want)


def test_block_rows_keep_the_motions_of_a_graded_block_and_drop_null_ones():
    # Three 2 x 2 element blocks on coordinates (0, 1), (1, 2), (0, 2): GRADED_BLOCK,
    # the indefinite diag(1, -2) (one negative row) and the rank-1 [[1, 1], [1, 1]]
    # (one null motion, dropped): 2 + 2 + 1 rows, signs (+, +, +, -, +) in some order
    # with one minus, and F^T diag(sign) F = sum of the blocks (assembled by hand).
    # Tolerance 1e-12 per entry: 2 x 2 eigen-decompositions of unit-diagonal blocks.
    mats = np.array([GRADED_BLOCK, [[1.0, 0.0], [0.0, -2.0]], [[1.0, 1.0], [1.0, 1.0]]])
    idx = np.array([[0, 1], [1, 2], [0, 2]])
    (r, c, v, m), sign = _block_rows(Blocks(idx, mats))
    assert m == 5 and sorted(sign) == [-1, 1, 1, 1, 1]
    F = sp.coo_matrix((v, (r, c)), shape=(m, 3)).toarray()
    K = np.array([[1.0e4 + 1.0, 0.5e-3, 1.0],
                  [0.5e-3, 1.0e-10 + 1.0, 0.0],
                  [1.0, 0.0, -2.0 + 1.0]])
    _entrywise(F.T @ (sign[:, None] * F), K, 1e-12)


def test_psd_rows_of_a_graded_block_a_null_motion_and_an_indefinite_block():
    # GRADED_BLOCK: two rows with F^T F = K (1e-12 per entry, as above); a rank-1 block:
    # one row (the null motion dropped); diag(1, -1e-3): a negative eigenvalue 1e-3 of
    # the largest, beyond NULL_BLOCK -> None.
    F = _psd_rows(GRADED_BLOCK)
    assert F.shape == (2, 2)
    _entrywise(F.T @ F, GRADED_BLOCK, 1e-12)
    F = _psd_rows(np.array([[4.0, 2.0], [2.0, 1.0]]))
    assert F.shape == (1, 2)
    np.testing.assert_allclose(np.abs(F[0]), [2.0, 1.0], rtol=1e-14)
    assert _psd_rows(np.array([[1.0, 0.0], [0.0, -1.0e-3]])) is None


def _spring(Fu):
    """An ElementFactor of positive rows Fu on coordinates that are the primitive ones."""
    Fu = sp.csr_matrix(np.asarray(Fu, dtype=float))
    return ElementFactor(Fu, sp.identity(Fu.shape[1], format="csr"),
                         np.ones(Fu.shape[0]), ())


def test_element_energy_zero_test_is_scale_free_per_row_and_per_mode():
    # One spring row (1, -1). Columns: (1) (1, 0) scaled by 1e-12, 1, 1e12: deformed,
    # w^2 = a^2 exactly, never zero (the test must not depend on the mode's scale);
    # (2) (1, 1 + 2^-40): the row deforms by 2^-40 ~ 9e-13 of |row|_1 max|u| = 2, below
    # UNDEFORMED = 1e-10 -> zero (round-off of a free motion, as a drum turning a hook);
    # (3) (1, 1 + 2^-23): 1.2e-7 of it, above -> not zero (w^2 = 2^-46).
    a = np.array([1.0e-12, 1.0, 1.0e12])
    w2, zero = element_energy(_spring([[1.0, -1.0]]), np.vstack([a, 0 * a]))
    assert w2.tolist() == (a * a).tolist() and not zero.any()
    u = np.array([[1.0, 1.0], [1.0 + 2.0**-40, 1.0 + 2.0**-23]])
    w2, zero = element_energy(_spring([[1.0, -1.0]]), u)
    assert w2.tolist() == [2.0**-80, 2.0**-46]
    assert zero.tolist() == [True, False]
    # per mode: a round-off column beside a deformed one keeps its own verdict, and a
    # deformed column 1e-6 (1, 0.999) is not judged against another column's 1e6 (1, 0)
    u = np.array([[1.0, 1.0e-6, 1.0e6], [1.0 + 2.0**-40, 0.999e-6, 0.0]])
    _, zero = element_energy(_spring([[1.0, -1.0]]), u)
    assert zero.tolist() == [True, False, False]
    # per row: a stiff row (1e8, -1e8, 0) undeformed beside a soft row (0, 1, -1)
    # deformed by 2^-23 of its own size: deformed (each row against its own |row|_1)
    u = np.array([[1.0], [1.0], [1.0 - 2.0**-23]])
    w2, zero = element_energy(_spring([[1.0e8, -1.0e8, 0.0], [0.0, 1.0, -1.0]]), u)
    assert w2.tolist() == [2.0**-46] and zero.tolist() == [False]


def test_graded_cantilever_with_springs_keeps_the_beam_in_the_factor():
    # Planar cantilever O-T along x (one Euler-Bernoulli element, EA/L = 2e10 N/m,
    # 3 EI / L^3 = 3 N/m at the tip once the massless tip rotation is condensed: the
    # cubic element is exact for a tip load), a 100 kg mass at T, an axial spring
    # kx = 1e3 along x and kz = 1.0 N/m along z at T. The tip's two translations are
    # uncoupled (beam along x): w^2 = (EA/L + kx) / m and (3 EI / L^3 + kz) / m exactly.
    # K_xx / K_zz ~ 1.5e9 > GRADED: the element factor path, with the beam's rows (also
    # when sway adds the beam's tension-stiffness blocks, zero here: no gravity) and the
    # 1 N/m spring's row. Tolerance 1e-10: round-off of the graded path (~5e-16 seen).
    E, A, I, L, m, kx, kz = 2.0e11, 1.0, 5.0e-9, 10.0, 100.0, 1.0e3, 1.0
    want = [(3 * E * I / L**3 + kz) / m, (E * A / L + kx) / m]
    for sway in ("false", "true"):
        model = load("cantilever.yaml", f"""cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {{O: [0, 0, 0], T: [{L}, 0, 0], W: [20, 0, 0], V: [{L}, 0, -5]}}
ground: [O, W, V]
masses: {{T: {m}}}
members:
  b: {{type: beam, nodes: [O, T], E: {E}, A: {A}, Iy: {I}, rho: 0}}
springs:
  - {{name: x, type: axial, nodes: [T, W], stiffness: {kx}}}
  - {{name: z, type: axial, nodes: [T, V], stiffness: {kz}}}
effects: {{structure: flexible, sway: {sway}}}
""")
        r = modes(model)
        assert r.graded == "element factor, Jacobi SVD"
        assert r.omega**2 == pytest.approx(want, rel=1e-10)


def test_graded_one_coordinate_with_a_unit_spring_row():
    # A 2 kg mass at N restrained to x, springs of 1.0 and 2e6 N/m in line to the
    # ground: element rows (1) and (sqrt(2e6)), spread 2e6 > GRADED -> element factor.
    # w^2 = (2e6 + 1) / 2 exactly; the 1 N/m row is 5e-7 of it, tolerance 1e-12
    # (round-off of a one-column SVD).
    model = load("unit.yaml", """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {G: [0, 0, 0], N: [1, 0, 0], H: [3, 0, 0]}
ground: [G, H]
supports: {N: [uz]}
masses: {N: 2.0}
springs:
  - {name: soft, type: axial, nodes: [G, N], stiffness: 1.0}
  - {name: stiff, type: axial, nodes: [N, H], stiffness: 2.0e6}
""")
    r = modes(model)
    assert r.graded == "element factor, Jacobi SVD"
    assert r.omega**2 == pytest.approx([(2.0e6 + 1.0) / 2.0], rel=1e-12)
