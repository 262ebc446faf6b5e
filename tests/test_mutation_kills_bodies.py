"""Value tests that kill the mutants of cranefe/elements/bodies.py that the fast tests left
alive (tools/mutation.py bodies; docs/testing.md, "Mutation testing"): sign and index
errors of the cross-product matrix and of the load stiffness passed every fast test (the
load stiffness is compared with a peer program only in the optional Exudyn study).
Tolerances: exact or 1e-12, a few roundings of numbers of order 10-100.
"""

import numpy as np

from cranefe.elements.bodies import load_stiffness, rigid_mass, skew


def test_skew_is_the_cross_product_matrix():
    """skew(c) @ v == c x v (numpy's cross as the reference) for a c with three distinct
    components, so any swapped index or sign shows; and skew(c) is antisymmetric."""
    c = np.array([1.0, -2.0, 3.0])
    S = skew(c)
    assert np.array_equal(S, [[0.0, -3.0, -2.0], [3.0, 0.0, -1.0], [2.0, 1.0, 0.0]])
    for v in np.eye(3).tolist() + [[0.3, 0.7, -1.1]]:
        assert np.allclose(S @ v, np.cross(c, v), rtol=0.0, atol=1e-15)
    batch = skew(np.array([c, 2.0 * c]))
    assert batch.shape == (2, 3, 3) and np.array_equal(batch[1], 2.0 * S)


def test_load_stiffness_by_hand_and_from_the_exact_rotation():
    """H = (F.c) I - (F c^T + c F^T) / 2 (docs/theory.md). F = (0, 0, -10) N at
    c = (1, 2, 3) m: F.c = -30, (F c^T + c F^T)/2 = [[0,0,-5],[0,0,-10],[-5,-10,-30]], so
    H = [[-30,0,5],[0,-30,10],[5,10,0]], symmetric. Independently: with the exact rotation
    R(s t) = exp(s skew(t)), d^2/ds^2 of -F.R(s t) c at s = 0 is -F.(t x (t x c)), which must
    equal t^T H t for every t (computed with numpy's cross, not with skew)."""
    F = np.array([[0.0, 0.0, -10.0]])
    c = np.array([[1.0, 2.0, 3.0]])
    H = load_stiffness(F, c)[0]
    assert np.allclose(H, [[-30.0, 0.0, 5.0], [0.0, -30.0, 10.0], [5.0, 10.0, 0.0]],
                       rtol=0.0, atol=1e-12)
    assert np.array_equal(H, H.T)
    F2, c2 = np.array([1.5, -0.5, 2.0]), np.array([-0.7, 0.4, 1.3])
    H2 = load_stiffness(F2[None], c2[None])[0]
    for t in np.eye(3).tolist() + [[0.2, -0.9, 0.4], [1.0, 1.0, 1.0]]:
        t = np.array(t)
        ref = -F2 @ np.cross(t, np.cross(t, c2))
        assert np.isclose(t @ H2 @ t, ref, rtol=1e-12, atol=1e-14)
    assert np.allclose(H2, H2.T, rtol=0.0, atol=1e-15)


def test_rigid_mass_is_diag_m_and_inertia():
    I = np.array([[[2.0, 0.1, 0.0], [0.1, 3.0, 0.2], [0.0, 0.2, 4.0]]])
    M = rigid_mass(np.array([5.0]), I)[0]
    assert np.array_equal(M[:3, :3], 5.0 * np.eye(3)) and np.array_equal(M[3:, 3:], I[0])
    assert not M[:3, 3:].any() and not M[3:, :3].any()
