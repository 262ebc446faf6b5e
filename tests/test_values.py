"""Value tests of the formulas the results stand on (issue 20), each against numbers
derived by hand in the docstrings below and evaluated at 30 digits with mpmath.

They assert values, not thresholds, so that a plausible slip in the formula fails them
(docs/testing.md lists which slip each test catches and how far it moves the value).
"""

import mpmath as mp
import numpy as np
import pytest

from cranefe.damping import damping
from cranefe.model import load

mp.mp.dps = 30


# ------------------------------------------------------------------ Hasselman coupling

CLOSE_PAIR = """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {G1: [0, 0, 0], A: [1, 0, 0], B: [2, 0, 0], G2: [3, 0, 0]}
ground: [G1, G2]
masses: {A: 100, B: 100}
springs:
  - {name: a, type: axial, nodes: [G1, A], stiffness: 1.0e4, psi: 0.1}
  - {name: b, type: axial, nodes: [B, G2], stiffness: 1.01e4, psi: 3.0}
  - {name: c, type: axial, nodes: [A, B], stiffness: 50.0, psi: 0.0}
effects: {sway: false}
"""


def test_coupling_of_a_close_pair_from_its_closed_form():
    """Two oscillators 0.5 % apart joined by a soft spring (the close pair of
    test_damping.py), coupling written out by hand (docs/damping.md, "Coupling
    coefficient"): eps_12 = |H_12| / |w_1^2 - w_2^2 + i (H_11 - H_22)|.

    Per unit mass M^-1 K = [[100.5, -0.5], [-0.5, 101.5]] (k_a + c, -c, k_b + c over 100),
    so w^2 = 101 -+ sqrt(0.5): w_1^2 - w_2^2 = -sqrt(2). The lower mode's shape solves
    (100.5 - w_1^2) x = 0.5 y: y / x = (sqrt(0.5) - 0.5) / 0.5 = sqrt(2) - 1 = tan(pi/8),
    so the mass-normalised modes are V_1 = (c, s) / 10, V_2 = (-s, c) / 10 with
    c = cos(pi/8), s = sin(pi/8). K_psi = diag(psi_a k_a, psi_b k_b) = diag(1000, 30300)
    (spring c has psi 0), and H = V^T K_psi V / (2 pi):

        H_11 = (1000 c^2 + 30300 s^2) / (200 pi),  H_22 = (1000 s^2 + 30300 c^2) / (200 pi)
        H_22 - H_11 = 29300 cos(pi/4) / (200 pi) =: X,    |H_12| = 29300 s c / (200 pi) = X/2

    hence eps_12 = (X/2) / sqrt(2 + X^2) = 0.49954..., X = 32.974. Dropping the
    i (H_ii - H_jj) term would give (X/2) / sqrt(2) = 11.66 (23 times more), so the
    tolerance (1e-10: round-off of a 2 x 2 eigenproblem and a few products) fails it.
    The decoupled ratios zeta_i = H_ii / (2 w_i^2) (eq. 16) are checked as well.
    """
    X = mp.mpf(29300) * mp.cos(mp.pi / 4) / (200 * mp.pi)
    eps = (X / 2) / mp.sqrt(2 + X**2)
    assert float(eps) == pytest.approx(0.499540, abs=1e-6)      # the hand value quoted
    c2, s2 = mp.cos(mp.pi / 8) ** 2, mp.sin(mp.pi / 8) ** 2
    w2 = [101 - mp.sqrt(0.5), 101 + mp.sqrt(0.5)]
    H = [(1000 * c2 + 30300 * s2) / (200 * mp.pi), (1000 * s2 + 30300 * c2) / (200 * mp.pi)]
    r = damping(load("pair.yaml", CLOSE_PAIR), method="modal")
    np.testing.assert_allclose(r.omega**2, [float(x) for x in w2], rtol=1e-13)
    np.testing.assert_allclose(r.coupling_matrix, [[0, float(eps)], [float(eps), 0]],
                               rtol=1e-10, atol=0)
    np.testing.assert_allclose(r.zeta, [float(h / (2 * w)) for h, w in zip(H, w2)],
                               rtol=1e-10)


TRIPLE = """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {G0: [0, 0, 0], N0: [1, 0, 0], G1: [1.5, 0, 0], N1: [2, 0, 0], G2: [2.5, 0, 0],
        N2: [3, 0, 0]}
ground: [G0, G1, G2]
masses: {N0: 100, N1: 100, N2: 100}
springs:
  - {name: g0, type: axial, nodes: [G0, N0], stiffness: 1.0e4, psi: 0.1}
  - {name: g1, type: axial, nodes: [G1, N1], stiffness: 1.0e4, psi: 0.2}
  - {name: g2, type: axial, nodes: [G2, N2], stiffness: 1.0e4, psi: 0.5}
  - {name: c01, type: axial, nodes: [N0, N1], stiffness: 200.0, psi: 0.0}
  - {name: c12, type: axial, nodes: [N1, N2], stiffness: 200.0, psi: 0.0}
effects: {sway: false}
"""


def test_coupling_of_three_oscillators_from_their_closed_form():
    """Three equal masses m = 100 on ground springs k = 1e4 (psi p = 0.1, 0.2, 0.5) and
    joined in a line by soft springs c = 200 (psi 0): K = k I + c L, L the path
    Laplacian [[1, -1, 0], [-1, 2, -1], [0, -1, 1]], whose eigenvectors are
    u_1 = (1, 1, 1)/sqrt(3), u_2 = (1, 0, -1)/sqrt(2), u_3 = (1, -2, 1)/sqrt(6) with
    eigenvalues 0, 1, 3. So w_j^2 = (k + c lambda_j) / m = 100, 102, 106 and V = U / sqrt(m).

    Only the ground springs absorb, each stretched by its own mass's displacement:
    H_ij = (k / (2 pi m)) sum_n p_n u_ni u_nj, i.e. with h0 = k / (2 pi m):

        H_11 = h0 (p0 + p1 + p2) / 3      H_12 = h0 (p0 - p2) / sqrt(6)
        H_22 = h0 (p0 + p2) / 2           H_13 = h0 (p0 - 2 p1 + p2) / (3 sqrt(2))
        H_33 = h0 (p0 + 4 p1 + p2) / 6    H_23 = h0 (p0 - p2) / (2 sqrt(3))

    and eps_ij = |H_ij| / |w_i^2 - w_j^2 + i (H_ii - H_jj)| = 1.2561, 0.12456, 0.44408
    for (1,2), (1,3), (2,3). Without the i-term they would be 1.2995, 0.12504, 0.45944
    (3.5 %, 0.39 %, 3.5 % off): the tolerance 1e-10 (round-off of a 3 x 3 eigenproblem
    with a 6 % frequency spread) catches every pair.
    """
    k, m, c = mp.mpf(10000), mp.mpf(100), mp.mpf(200)
    p0, p1, p2 = mp.mpf("0.1"), mp.mpf("0.2"), mp.mpf("0.5")
    h0 = k / (2 * mp.pi * m)
    w2 = [(k + c * lam) / m for lam in (0, 1, 3)]
    H = mp.matrix([[(p0 + p1 + p2) / 3, (p0 - p2) / mp.sqrt(6), (p0 - 2 * p1 + p2) / (3 * mp.sqrt(2))],
                   [0, (p0 + p2) / 2, (p0 - p2) / (2 * mp.sqrt(3))],
                   [0, 0, (p0 + 4 * p1 + p2) / 6]]) * h0
    eps = np.zeros((3, 3))
    for i in range(3):
        for j in range(i + 1, 3):
            e = abs(H[i, j]) / abs(w2[i] - w2[j] + 1j * (H[i, i] - H[j, j]))
            eps[i, j] = eps[j, i] = float(e)
    np.testing.assert_allclose(eps[[0, 0, 1], [1, 2, 2]], [1.25606, 0.124558, 0.444083],
                               rtol=1e-5)                         # the values quoted
    r = damping(load("triple.yaml", TRIPLE), method="modal")
    np.testing.assert_allclose(r.omega**2, [float(x) for x in w2], rtol=1e-13)
    np.testing.assert_allclose(r.coupling_matrix, eps, rtol=1e-10, atol=0)
    np.testing.assert_allclose(r.zeta, [float(H[i, i] / (2 * w2[i])) for i in range(3)],
                               rtol=1e-10)
    # the modal damping matrix D_ij = H_ij / sqrt(w_i w_j) (docs/damping.md, eq. 15)
    w = [mp.sqrt(x) for x in w2]
    D = np.array([[float(H[min(i, j), max(i, j)] / mp.sqrt(w[i] * w[j])) for j in range(3)]
                  for i in range(3)])
    np.testing.assert_allclose(np.abs(r.D), np.abs(D), rtol=1e-10)
