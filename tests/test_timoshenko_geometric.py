"""Geometric stiffness of Timoshenko members (cranefe/elements/beams.py, `_geometric4`):
the element's own shape functions, the Euler-Bernoulli limit, and the buckling load of a
shear-flexible column (Engesser)."""

import math

import numpy as np
import pytest

from cranefe.elements import beam_geometric


def _shape_slopes(xi, l, phi):
    """v'(x) of the Timoshenko element's static shape functions (nodal v1, psi1, v2,
    psi2), xi = x / l; from EI psi'' + kGA (v' - psi) = 0, v'' = psi' (the same
    solution as the consistent mass's, Przemieniecki eq. 11.41-11.42):
    N1 = (1 - 3 xi^2 + 2 xi^3 + phi (1 - xi)) / (1 + phi),
    N2 = l (xi^3 - (2 + phi/2) xi^2 + (1 + phi/2) xi) / (1 + phi),
    N3 = (3 xi^2 - 2 xi^3 + phi xi) / (1 + phi),
    N4 = l (xi^3 - (1 - phi/2) xi^2 - phi/2 xi) / (1 + phi)."""
    d = 1 + phi
    return np.array([(-6 * xi + 6 * xi**2 - phi) / d / l,
                     (3 * xi**2 - (4 + phi) * xi + (1 + phi / 2)) / d,
                     (6 * xi - 6 * xi**2 + phi) / d / l,
                     (3 * xi**2 - (2 - phi) * xi - phi / 2) / d])


def test_geometric_stiffness_is_that_of_the_shape_functions():
    # int (N + dN (x/l - 1/2)) v' v'^T dx by 8-point Gauss-Legendre (exact for these
    # polynomials of degree 5): round-off
    l, N, dN = 1.7, -3.0e5, 4.0e4
    xg, wg = np.polynomial.legendre.leggauss(8)
    xi, w = (xg + 1) / 2, wg / 2 * l
    for phi in (0.0, 0.37, 4.0):
        B = _shape_slopes(xi, l, phi)
        ref = np.einsum("q,iq,jq->ij", w * (N + dN * (xi - 0.5)), B, B)
        kg = beam_geometric(np.array([N]), np.array([l]), np.array([dN]),
                            np.array([phi]), np.array([phi]))[0]
        xy = [1, 5, 7, 11]
        assert kg[np.ix_(xy, xy)] == pytest.approx(ref, rel=1e-12, abs=1e-12 * abs(ref).max())
        # the x-z plane: the same with rotation -dw/dx (signs of the couplings)
        s = np.array([1, -1, 1, -1])
        xz = [2, 4, 8, 10]
        assert kg[np.ix_(xz, xz)] == pytest.approx(ref * np.outer(s, s), rel=1e-12,
                                                   abs=1e-12 * abs(ref).max())
    # phi = 0 is the cubic Euler-Bernoulli matrix, bit for bit
    a = beam_geometric(np.array([N]), np.array([l]), np.array([dN]))
    b = beam_geometric(np.array([N]), np.array([l]), np.array([dN]), np.zeros(1), np.zeros(1))
    assert np.array_equal(a, b)


def _column(elements, Asz, L=3.0, E=2.1e11, G=8.1e10, A=0.01, I=2.0e-4, M=1.0e5):
    """A massless clamped column (plane xz) with a top mass M: P = M g at the factor 1."""
    return f"""
    cranefe: 1
    plane: xz
    nodes: {{O: [0, 0, 0], T: [0, 0, {L}]}}
    ground: [O]
    masses: {{T: {M}}}
    members:
      col: {{type: beam, nodes: [O, T], E: {E}, G: {G}, A: {A}, Iy: {I}, Asz: {Asz},
            rho: 0, elements: {elements}}}
    effects: {{structure: flexible}}
    """


def test_shear_flexible_column_buckles_at_engesser(model_from):
    # clamped-free column, bending stiffness EI, shear stiffness kGA = G Asz: Engesser's
    # P_cr = P_E / (1 + P_E / (G As)), P_E = pi^2 EI / (4 L^2) (Timoshenko & Gere, Theory
    # of Elastic Stability, sec. 2.17: the axial force works on the total slope v', as
    # here; Haringx's, with the force on the bending rotation, would be larger). A laced
    # column's low shear stiffness: P_E / (G As) = 0.43 here
    from cranefe.analysis.buckling import gravity_buckling
    E, G, I, L, M, g = 2.1e11, 8.1e10, 2.0e-4, 3.0, 1.0e5, 9.81
    Asz = 3.3e-4
    PE = math.pi**2 * E * I / (4 * L**2)
    Pcr = PE / (1 + PE / (G * Asz))
    haringx = (math.sqrt(1 + 4 * PE / (G * Asz)) - 1) / (2 / (G * Asz))
    assert PE / (G * Asz) == pytest.approx(0.431, abs=1e-3) and haringx > 1.03 * Pcr
    Ns = [2, 4, 8, 16]
    err = np.array([gravity_buckling(model_from(_column(n, Asz), f"c{n}.yaml")).factor
                    * M * g / Pcr - 1 for n in Ns])
    # from above (a stiff approximation), at order 2 (measured 2.0): 16 elements 1.7e-4
    assert np.all(err > 0), err
    slope = -np.polyfit(np.log(Ns[1:]), np.log(err[1:]), 1)[0]
    assert slope == pytest.approx(2.0, abs=0.1), (err, slope)
    assert err[-1] < 2e-4, err
