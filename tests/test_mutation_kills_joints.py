"""Value tests of cranefe/analysis/operation/joints.py (issue 20, mutation testing).

The operation engine's joint coordinates stand on three kernels: the mass properties
(m, s = int X dm, Theta = int X X^T dm) of a rigid subtree, the integral of a product of
two affine fields over it, and the derivatives of a child's motion in its joint's drive
variable. Each is checked here against an independent computation:

- a rigid body is represented by a cloud of point masses; its com and its inertia about
  the com follow by their definitions (I_c = sum m_k (|r_k|^2 I - r_k r_k^T)) and Theta
  and the pair integral by direct sums sum m_k X_k X_k^T, sum m_k (A X_k + a).(B X_k + b),
  not by the identity Theta = tr(I_c)/2 I - I_c + m c c^T the code uses;
- a hinge's rotation as the matrix exponential expm(theta K) (scipy), whose derivatives
  in the angle are exactly K^k expm(theta K), instead of the code's Rodrigues form
  (`hinge_series`); p = a - R a, so p^(k) = -R^(k) a; a slider's (`slider_series`).

Tolerances: 1e-12 relative, sums of a few products of O(1)-O(100) numbers in double
precision (round-off about 1e-14 relative).
"""

from types import SimpleNamespace

import numpy as np
from scipy.linalg import expm

from cranefe.analysis.operation.joints import (
    hinge_series,
    pair,
    slider_series,
    subtree_mass,
)

RNG = np.random.default_rng(20)


def _cloud(n, centre):
    X = centre + RNG.normal(size=(n, 3))
    m = RNG.uniform(1.0, 5.0, size=n)
    return X, m


def _body_of(X, m):
    """Mass, com and inertia about the com (global axes) of a point cloud, by definition."""
    M = m.sum()
    c = (m[:, None] * X).sum(0) / M
    r = X - c
    Ic = sum(mk * (rk @ rk * np.eye(3) - np.outer(rk, rk)) for mk, rk in zip(m, r))
    return SimpleNamespace(mass=float(M), com=c, inertia=Ic)


def _model():
    """Two bodies (clouds; the second of 0.5 kg, lighter than a kilogram), a massless
    body with an inertia that must not count, and three point masses: two carried
    (node 1 with rotary inertia, node 2), one not (node 3, listed first)."""
    X1, m1 = _cloud(7, np.array([1.0, -2.0, 0.5]))
    X2, m2 = _cloud(5, np.array([-3.0, 1.0, 2.0]))
    m2 = 0.5 * m2 / m2.sum()
    # a point mass with rotary inertia: itself a small cloud about its node
    Xp, mp = _cloud(4, np.zeros(3))
    pm = _body_of(0.3 * Xp, mp)
    nodes_xyz = np.array([[0.0, 0.0, 0.0], [2.0, 1.0, -1.0], [0.5, 4.0, 3.0],
                          [9.0, 9.0, 9.0]])
    bodies = [_body_of(X1, m1),
              SimpleNamespace(mass=0.0, com=np.array([5.0, 5.0, 5.0]),
                              inertia=np.diag([7.0, 8.0, 9.0])),
              _body_of(X2, m2)]
    ms = SimpleNamespace(nodes=np.array([3, 1, 2]), mass=np.array([11.0, pm.mass, 3.0]),
                         inertia=np.array([np.diag([1.0, 2.0, 3.0]), pm.inertia,
                                           np.zeros((3, 3))]))
    model = SimpleNamespace(bodies=bodies, masses=ms, coords=nodes_xyz)
    # the carried points, as one cloud: bodies 0 and 2, the point mass at node 1 (its
    # cloud moved to the node, com exactly there since _body_of centres it), node 2
    Xpm = 0.3 * Xp - bodies_com(0.3 * Xp, mp) + nodes_xyz[1]
    cloud_X = np.vstack([X1, X2, Xpm, nodes_xyz[2][None]])
    cloud_m = np.concatenate([m1, m2, mp, [3.0]])
    return model, cloud_X, cloud_m


def bodies_com(X, m):
    return (m[:, None] * X).sum(0) / m.sum()


def test_subtree_mass_is_the_sums_over_the_points():
    model, X, m = _model()
    M, s, Th = subtree_mass(model, [0, 1, 2], [1, 2])
    assert np.isclose(M, m.sum(), rtol=1e-13, atol=0)
    assert np.allclose(s, (m[:, None] * X).sum(0), rtol=1e-12, atol=1e-12)
    Th_ref = np.einsum("k,ki,kj->ij", m, X, X)
    assert np.allclose(Th, Th_ref, rtol=1e-12, atol=1e-11)


def test_subtree_mass_without_rotary_inertia_of_the_point_masses():
    """ms.inertia None: the point masses count as points; body 1 (massless) is skipped
    even though it has an inertia; node 3 is not carried."""
    model, X, m = _model()
    model.masses.inertia = None
    model.masses.mass = np.array([11.0, 2.0, 3.0])
    M, s, Th = subtree_mass(model, [2, 1], [2, 1])
    X2 = np.vstack([model.coords[1], model.coords[2]])
    m2 = np.array([2.0, 3.0])
    b = model.bodies[2]
    assert np.isclose(M, b.mass + 5.0, rtol=1e-13, atol=0)
    assert np.allclose(s, b.mass * b.com + m2 @ X2, rtol=1e-12, atol=1e-12)
    # body 2's Theta from its own com and inertia by the parallel-axis theorem, computed
    # here from I_c's definition: int r r^T dm = tr(I_c)/2 I - I_c
    Th_b = 0.5 * np.trace(b.inertia) * np.eye(3) - b.inertia + b.mass * np.outer(b.com, b.com)
    assert np.allclose(Th, Th_b + np.einsum("k,ki,kj->ij", m2, X2, X2), rtol=1e-12,
                       atol=1e-11)


def test_nothing_carried_is_zero():
    model, _, _ = _model()
    M, s, Th = subtree_mass(model, [1], [0])
    assert M == 0.0 and not s.any() and not Th.any()


def test_pair_is_the_integral_of_the_product_of_two_affine_fields():
    model, X, m = _model()
    M, s, Th = subtree_mass(model, [0, 2], [1, 2])
    A, B = RNG.normal(size=(3, 3)), RNG.normal(size=(3, 3))
    a, b = RNG.normal(size=3), RNG.normal(size=3)
    ref = float(np.sum(m * np.einsum("ki,ki->k", X @ A.T + a, X @ B.T + b)))
    assert np.isclose(pair(A, a, B, b, M, s, Th), ref, rtol=1e-12, atol=0)
    # the kinetic energy of a rigid turn: |R' X + p'|^2 summed over the points
    assert np.isclose(pair(A, a, A, a, M, s, Th),
                      float(np.sum(m * np.sum((X @ A.T + a) ** 2, axis=1))), rtol=1e-12)


def _skew(n):
    return np.array([[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]])


def test_hinge_series_against_the_matrix_exponential():
    """Rodrigues' R(ang) and its angle derivatives against expm(ang K): R^(k) = K^k R
    (K, the axis' skew matrix, commutes with expm(ang K)); p = a - R a, so p^(k) =
    -R^(k) a."""
    n = np.array([1.0, 2.0, -2.0]) / 3.0
    K = _skew(n)
    a = np.array([0.4, -1.3, 2.2])
    for ang in (0.83, -2.4, 3.9):
        E = expm(ang * K)
        refs = [E, K @ E, K @ K @ E, K @ K @ K @ E]
        Rs, ps = hinge_series(K, K @ K, a, ang)
        for k in range(4):
            assert np.allclose(Rs[k], refs[k], rtol=0, atol=1e-13)
        assert np.allclose(ps[0], a - E @ a, rtol=0, atol=1e-13)
        for k in range(1, 4):
            assert np.allclose(ps[k], -refs[k] @ a, rtol=0, atol=1e-12)


def test_hinge_series_against_central_differences_of_the_motion():
    """The motion x = R X + a - R a differenced in the angle (h = 1e-4: truncation
    h^2/6 |x'''| ~ 1e-8, round-off 1e-16 / h ~ 1e-12; the second difference: round-off
    1e-16 / h^2 ~ 1e-8)."""
    n = np.array([0.0, 0.6, 0.8])
    K = _skew(n)
    a = np.array([1.0, -0.5, 0.25])
    X = np.array([2.0, 1.0, -3.0])
    ang, h = 0.4, 1e-4

    def x(t):
        R = expm(t * K)
        return R @ X + a - R @ a
    (R, R1, R2, _), (p, p1, p2, _) = hinge_series(K, K @ K, a, ang)
    assert np.allclose(R @ X + p, x(ang), rtol=0, atol=1e-13)
    assert np.allclose(R1 @ X + p1, (x(ang + h) - x(ang - h)) / (2 * h), rtol=0, atol=1e-7)
    assert np.allclose(R2 @ X + p2, (x(ang + h) - 2 * x(ang) + x(ang - h)) / h ** 2,
                       rtol=0, atol=1e-6)


def test_slider_series():
    n = np.array([0.0, 0.6, 0.8])
    Rs, ps = slider_series(n, 3.0)
    assert np.array_equal(Rs[0], np.eye(3)) and not any(R.any() for R in Rs[1:])
    assert np.allclose(ps[0], 3.0 * n, rtol=0, atol=1e-15)
    assert np.allclose(ps[1], n, rtol=0, atol=1e-15)
    assert not ps[2].any() and not ps[3].any()
