"""Kill tests for cranefe/elements/beams.py (tools/mutation.py beams; docs/testing.md,
"Mutation testing"): every local matrix of the beam kernels against an independent
construction from the element's exact displacement field.

The bending field of a uniform Timoshenko element with end values (v1, r1, v2, r2) and no
span load is the static solution, the stationary point of int EI r'^2 + G As (v' - r)^2:
G As (v' - r) = const and EI r'' + G As (v' - r) = 0, so r is quadratic
(r = b1 + b2 x + b3 x^2) and the shear strain is v' - r = -2 b3 EI / (G As), i.e.
v = c0 + b1 x + b2 x^2 / 2 + b3 x^3 / 3 - 2 b3 EI / (G As) x. Its four coefficients
follow from the end values (a 4 x 4 solve below); G As = inf is Euler-Bernoulli
(r = v'). Then, with 4-point Gauss quadrature (exact for degree 7):
  K = int EI r'^2 + G As (v' - r)^2 dx,   M = int rho A v^2 + rho I r^2 dx,
  Kg = int N(x) v'^2 dx (Hermite cubics, N(x) = N + dN (x/l - 1/2)).
In the local x-y plane r = rz; in the x-z plane r = ry = -(the x-z plane's rotation),
so the coupling terms change sign. Axial and torsion: linear fields. All tolerances
1e-12 relative to the largest entry: a 12 x 12 matrix of sums of a few products.
"""

import numpy as np
import pytest

from cranefe.elements.beams import (beam_axes, beam_geometric, beam_mass, beam_stiffness,
                                    release_transforms, shear_factors, to_global, transform)

E, G = 2.1e11, 8.1e10
A, Iy, Iz, J = 3.0e-3, 4.0e-6, 9.0e-6, 2.5e-6
RHO = 7850.0
L = 1.7
GX, GW = np.polynomial.legendre.leggauss(4)
X = (GX + 1) / 2 * L
WQ = GW / 2 * L


def _field(EI, GAs, l=L):
    """(v, v', r, r') at the quadrature points for each of the four unit end values,
    each (4 shapes, npts)."""
    s = 0.0 if GAs == np.inf else -2 * EI / GAs

    def rows(x):
        # unknowns (c0, b1, b2, b3): v and r at x
        v = np.array([1.0, x, x**2 / 2, x**3 / 3 + s * x])
        r = np.array([0.0, 1.0, x, x**2])
        return v, r
    v0, r0 = rows(0.0)
    v1, r1 = rows(l)
    C = np.linalg.inv(np.array([v0, r0, v1, r1]))       # coefficients of each shape
    x = X * l / L
    V = np.array([C[0, k] + C[1, k] * x + C[2, k] * x**2 / 2 + C[3, k] * (x**3 / 3 + s * x)
                  for k in range(4)])
    dV = np.array([C[1, k] + C[2, k] * x + C[3, k] * (x**2 + s) for k in range(4)])
    R = np.array([C[1, k] + C[2, k] * x + C[3, k] * x**2 for k in range(4)])
    dR = np.array([C[2, k] + 2 * C[3, k] * x for k in range(4)])
    return V, dV, R, dR


def _reference(As_y=np.inf, As_z=np.inf, rotary=True, l=L):
    """(K, M) 12 x 12 from the fields above."""
    w = WQ * l / L
    K = np.zeros((12, 12))
    M = np.zeros((12, 12))
    lin = np.array([1 - X * l / L / l, X * l / L / l])          # linear shapes
    dlin = np.array([-np.ones(4) / l, np.ones(4) / l])
    for (a, b), (kk, mm) in (((0, 6), (E * A, RHO * A)), ((3, 9), (G * J, RHO * (Iy + Iz)))):
        for i, p in enumerate((a, b)):
            for j, q in enumerate((a, b)):
                K[p, q] = np.sum(w * kk * dlin[i] * dlin[j])
                M[p, q] = np.sum(w * mm * lin[i] * lin[j])
    for I, GAs, cols, sign in ((Iz, G * As_y, (1, 5, 7, 11), (1, 1, 1, 1)),
                               (Iy, G * As_z, (2, 4, 8, 10), (1, -1, 1, -1))):
        V, dV, R, dR = _field(E * I, GAs, l)
        gam = dV - R
        rI = RHO * I if rotary else 0.0
        for i in range(4):
            for j in range(4):
                p, q = cols[i], cols[j]
                sh = 0.0 if GAs == np.inf else np.sum(w * GAs * gam[i] * gam[j])
                K[p, q] = sign[i] * sign[j] * (np.sum(w * E * I * dR[i] * dR[j]) + sh)
                M[p, q] = sign[i] * sign[j] * np.sum(w * (RHO * A * V[i] * V[j]
                                                          + rI * R[i] * R[j]))
    return K, M


def _close(a, b):
    return np.allclose(a, b, rtol=0, atol=1e-12 * np.max(np.abs(b)))


def _one(x):
    return np.array([x])


def test_euler_bernoulli_stiffness_and_mass_from_the_exact_field():
    K, M = _reference()
    k = beam_stiffness(E, G, A, _one(Iy), _one(Iz), J, _one(L))[0]
    m = beam_mass(RHO, A, _one(Iy), _one(Iz), _one(L))[0]
    assert _close(k, K)
    # the Euler-Bernoulli consistent mass has no rotary inertia
    _, M0 = _reference(rotary=False)
    assert _close(m, M0)


def test_timoshenko_shear_factors_stiffness_and_mass_from_the_exact_field():
    """Shear areas differ per plane (Asy with Iz, Asz with Iy) and are small enough that
    phi = 12 EI / (G As l^2) is 0.1 to 0.5: phi_y = 12 E Iz / (G Asy l^2)."""
    Asy, Asz = 6.0e-4, 3.0e-4
    py, pz = shear_factors(E, G, _one(Iy), _one(Iz), _one(Asy), _one(Asz), _one(L))
    assert np.isclose(py[0], 12 * E * Iz / (G * Asy * L**2), rtol=1e-14)
    assert np.isclose(pz[0], 12 * E * Iy / (G * Asz * L**2), rtol=1e-14)
    assert 0.1 < pz[0] < py[0] < 1.0
    K, M = _reference(Asy, Asz)
    k = beam_stiffness(E, G, A, _one(Iy), _one(Iz), J, _one(L), py, pz)[0]
    m = beam_mass(RHO, A, _one(Iy), _one(Iz), _one(L), phi_y=py, phi_z=pz)[0]
    assert _close(k, K)
    assert _close(m, M)
    # rotary inertia off: only the translational part
    _, M0 = _reference(Asy, Asz, rotary=False)
    m0 = beam_mass(RHO, A, _one(Iy), _one(Iz), _one(L), phi_y=py, phi_z=pz,
                   rotary=np.array([False]))[0]
    assert _close(m0, M0)


def test_zero_shear_area_is_euler_bernoulli_and_one_plane_may_shear():
    py, pz = shear_factors(E, G, _one(Iy), _one(Iz), _one(0.0), _one(1.5e-3), _one(L))
    assert py[0] == 0.0 and pz[0] > 0
    K, M = _reference(np.inf, 1.5e-3)
    assert _close(beam_stiffness(E, G, A, _one(Iy), _one(Iz), J, _one(L), py, pz)[0], K)
    assert _close(beam_mass(RHO, A, _one(Iy), _one(Iz), _one(L), phi_y=py, phi_z=pz)[0], M)
    # phi only for one plane given: the other is Euler-Bernoulli (phi None -> zeros)
    m = beam_mass(RHO, A, _one(Iy), _one(Iz), _one(L), phi_y=None, phi_z=pz)[0]
    assert _close(m, M)


def test_lumped_mass_is_half_at_each_end_translations_only():
    m = beam_mass(RHO, A, _one(Iy), _one(Iz), _one(L), lumped=True)[0]
    want = np.zeros((12, 12))
    for i in (0, 1, 2, 6, 7, 8):
        want[i, i] = RHO * A * L / 2
    assert _close(m, want)


@pytest.mark.parametrize("dN", [None, 3.0e4])
def test_geometric_stiffness_is_the_integral_of_n_v_prime_squared(dN):
    """Kg = int N(x) v'^2 dx with the Hermite cubics, N(x) = N + dN (x/l - 1/2)."""
    N = 2.0e5
    V, dV, R, dR = _field(1.0, np.inf)
    Nx = N + (0.0 if dN is None else dN) * (X / L - 0.5)
    Kg = np.zeros((12, 12))
    for cols, sign in (((1, 5, 7, 11), (1, 1, 1, 1)), ((2, 4, 8, 10), (1, -1, 1, -1))):
        for i in range(4):
            for j in range(4):
                Kg[cols[i], cols[j]] = sign[i] * sign[j] * np.sum(WQ * Nx * dV[i] * dV[j])
    got = beam_geometric(_one(N), _one(L), None if dN is None else _one(dN))[0]
    assert _close(got, Kg)


def test_axes_and_rotation_to_global():
    """e = (3, 4, 0)/5, orientation (1, 0, 1): z = o - (o.e) e = (0.64, -0.48, 1)/sqrt(1.64),
    y = z x e. to_global is T^T k T with T = blockdiag(R, R, R, R), built here by kron."""
    e = np.array([[0.6, 0.8, 0.0]])
    R = beam_axes(e, np.array([[1.0, 0.0, 1.0]]))[0]
    z = np.array([0.64, -0.48, 1.0]) / np.sqrt(1.64)
    assert np.allclose(R, [e[0], np.cross(z, e[0]), z], atol=1e-15)
    assert np.allclose(R @ R.T, np.eye(3), atol=1e-15) and np.isclose(np.linalg.det(R), 1)
    k = np.arange(144.0).reshape(12, 12)
    T = np.kron(np.eye(4), R)
    assert _close(to_global(k[None], R[None])[0], T.T @ k @ T)
    S = np.random.default_rng(1).normal(size=(12, 12))
    assert _close(transform(k[None], S[None])[0], S.T @ k @ S)


def test_pinned_end_condenses_to_the_propped_element():
    """Releasing rz at end 2 of an Euler-Bernoulli element: r2 = -3 (v1 - v2) / (2 l) - r1 / 2
    (its moment row 6l v1 + 2l^2 r1 - 6l v2 + 4l^2 r2 = 0), and the condensed x-y bending
    stiffness on (v1, r1, v2) is 3 EI / l^3 [[1, l, -1], [l, l^2, -l], [-1, -l, 1]]
    (pinned-fixed element). A second element without releases gets the identity, a third
    releases ry at end 1 (the x-z plane, sign-flipped coupling)."""
    k = beam_stiffness(E, G, A, np.full(3, Iy), np.full(3, Iz), J, np.full(3, L))
    rel = np.zeros((3, 12), dtype=bool)
    rel[0, 11] = True
    rel[2, 4] = True
    T = release_transforms(k, rel)
    assert np.array_equal(T[1], np.eye(12))
    t = T[0]
    assert np.allclose(t[11, [1, 5, 7]], [-3 / (2 * L), -0.5, 3 / (2 * L)], atol=1e-14)
    assert np.allclose(t[:, 11], 0.0)
    kc = (t.T @ k[0] @ t)[np.ix_([1, 5, 7], [1, 5, 7])]
    c = 3 * E * Iz / L**3
    assert _close(kc, c * np.array([[1, L, -1], [L, L**2, -L], [-1, -L, 1]]))
    # ry released at end 1: w-plane, r1y = -(3 (w2 - w1) / (2 l)) ... by symmetry of the
    # element: the condensed stiffness on (w1, w2, r2y) is 3 E Iy / l^3 with the signs of
    # the x-z plane; compare with the hand-condensed block of the full matrix
    kk = k[2]
    c_, r_ = [4], [i for i in range(12) if i != 4]
    cond = kk[np.ix_(r_, r_)] - kk[np.ix_(r_, c_)] @ np.linalg.inv(kk[np.ix_(c_, c_)]) \
        @ kk[np.ix_(c_, r_)]
    assert _close((T[2].T @ kk @ T[2])[np.ix_(r_, r_)], cond)
    assert np.isclose(cond[r_.index(2), r_.index(2)], 3 * E * Iy / L**3, rtol=1e-12)
