"""Kill tests for cranefe/elements/motion.py (tools/mutation.py motion; docs/testing.md,
"Mutation testing"): the rigid motions of hinges and sliders and their composition,
with first and second time derivatives, against independent constructions at 30 digits.

Before these tests only tests/test_operation.py (about 70 s, the operation engine)
reached the module.

A hinge turned by phi(t) about the unit axis a through the point c: X -> R X + p with
R(t) = expm(phi(t) K), K = skew(a) (the matrix exponential, by mpmath, not Rodrigues'
formula), p = c - R c. Since K commutes with R: R' = phi' K R and
R'' = phi'' K R + phi'^2 K^2 R; p' = -R' c, p'' = -R'' c. A composition is checked as
the product of 4 x 4 homogeneous matrices of two time-dependent motions, differentiated
numerically at 30 digits (central differences).
"""

import mpmath as mp
import numpy as np

from cranefe.elements.motion import IDENTITY_MOTION, compose, hinge_motion, slider_motion

mp.mp.dps = 30

AXIS = np.array([2.0, -1.0, 2.0]) / 3.0            # unit
POINT = np.array([0.7, -1.2, 2.5])
PHI, DPHI, DDPHI = 0.9, -1.3, 0.4


def _skew(a):
    return mp.matrix([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])


def _np(m):
    return np.array(m.tolist(), dtype=float)


def test_hinge_motion_against_the_matrix_exponential():
    K = _skew([mp.mpf(2) / 3, mp.mpf(-1) / 3, mp.mpf(2) / 3])
    R = mp.expm(PHI * K)
    dR = DPHI * K * R
    ddR = DDPHI * K * R + DPHI**2 * K * K * R
    c = mp.matrix(POINT.tolist())
    want = [_np(R), _np(dR), _np(ddR), _np(c - R * c).ravel(), _np(-dR * c).ravel(),
            _np(-ddR * c).ravel()]
    got = hinge_motion(AXIS, POINT, PHI, DPHI, DDPHI)
    for g, w in zip(got, want):
        np.testing.assert_allclose(g, w, rtol=0, atol=1e-14)


def test_slider_motion_is_a_translation_along_its_axis():
    R, dR, ddR, p, dp, ddp = slider_motion(AXIS, 1.5, -0.25, 2.0)
    np.testing.assert_array_equal(R, np.eye(3))
    np.testing.assert_array_equal(dR, np.zeros((3, 3)))
    np.testing.assert_array_equal(ddR, np.zeros((3, 3)))
    np.testing.assert_allclose(p, 1.5 * AXIS, rtol=1e-15)
    np.testing.assert_allclose(dp, -0.25 * AXIS, rtol=1e-15)
    np.testing.assert_allclose(ddp, 2.0 * AXIS, rtol=1e-15)


def _homogeneous(axis, point, phi0, dphi, ddphi, slide=None):
    """t -> 4 x 4 matrix of the motion at time t (phi or s quadratic in t)."""
    a = [mp.mpf(x) for x in axis]
    c = mp.matrix([mp.mpf(x) for x in point])

    def at(t):
        q = phi0 + dphi * t + ddphi * t**2 / 2
        T = mp.eye(4)
        if slide:
            for i in range(3):
                T[i, 3] = q * a[i]
            return T
        R = mp.expm(q * _skew(a))
        p = c - R * c
        for i in range(3):
            for j in range(3):
                T[i, j] = R[i, j]
            T[i, 3] = p[i]
        return T
    return at


def test_composition_follows_the_product_rule_of_the_true_motion():
    """A slider (axis e_z, s = 0.3 - 0.8 t + 1.1 t^2 / 2) carrying a hinge (AXIS through
    POINT), composed again with a second hinge about e_x through (0, 1, 0): the position,
    velocity and acceleration of the composed motion equal the derivatives (central differences at 30 digits)
    of the product of the three homogeneous matrices. Tolerance 1e-11: the differences
    below are good to about 1e-12; the double-precision composition to 1e-15."""
    ez, ex = np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0])
    s = slider_motion(ez, 0.3, -0.8, 1.1)
    h1 = hinge_motion(AXIS, POINT, PHI, DPHI, DDPHI)
    h2 = hinge_motion(ex, np.array([0.0, 1.0, 0.0]), -0.4, 0.6, -0.9)
    got = compose(compose(compose(IDENTITY_MOTION, s), h1), h2)
    f_s = _homogeneous(ez, (0, 0, 0), 0.3, -0.8, 1.1, slide=True)
    f_1 = _homogeneous(AXIS, POINT, PHI, DPHI, DDPHI)
    f_2 = _homogeneous(ex, (0, 1, 0), -0.4, 0.6, -0.9)

    # central differences at 30 digits with h = 1e-9: truncation about h^2 = 1e-18,
    # round-off 1e-30 / h^2 = 1e-12 at most
    h = mp.mpf("1e-9")
    Tm, T0, Tp = [f_s(t) * f_1(t) * f_2(t) for t in (-h, 0, h)]
    derivs = (T0, (Tp - Tm) / (2 * h), (Tp - 2 * T0 + Tm) / h**2)
    for (Rg, pg), T in zip(((got[0], got[3]), (got[1], got[4]), (got[2], got[5])), derivs):
        T = _np(T)
        np.testing.assert_allclose(Rg, T[:3, :3], rtol=0, atol=1e-11)
        np.testing.assert_allclose(pg, T[:3, 3], rtol=0, atol=1e-11)
