"""Kill tests for cranefe/analysis/damping/exact.py (tools/mutation.py damping_exact;
docs/testing.md, "Mutation testing"): the exact viscous and complex-stiffness damping of
a 3-DOF chain against its eigenvalues computed at 30 digits with mpmath, through both
the dense (QZ + refinement) and the sparse (block shift-invert, ARPACK fallback) paths.

The chain: masses (1, 2, 1.5) kg; ground springs (200, 100, 250) N/m with psi (0.3, 0,
0.1); springs 1-2 (100 N/m, psi 0.5) and 2-3 (150 N/m, psi 0). K and K_psi = sum psi_e
k_e (element stiffness) written out below. Exact answers per mode i (undamped w_i):
- viscous, B_i = K_psi / (2 pi w_i) (Heletiy eq. 12): the root lam of
  det(lam^2 M + lam B_i + K) = 0 nearest i w_i, from the eigenvalues of the companion
  matrix [[0, I], [-M^-1 K, -M^-1 B_i]]; zeta = -Re lam / |lam|, damped w = Im lam;
- complex stiffness: mu, eigenvalue of M^-1 (K + i K_psi / (2 pi)) nearest w_i^2;
  zeta = Im mu / (2 Re mu), damped w = Re sqrt(mu).
The modes (w = 10.18, 16.86, 18.81 rad/s) are damped 1.0 % to 2.0 % and the nearest root
is the mode's own (checked: the next one is more than twice as far plus 1 rad/s).
"""

from functools import lru_cache
from types import SimpleNamespace

import mpmath as mp
import numpy as np
import pytest
import scipy.linalg as sla
import scipy.sparse as sp

import cranefe.analysis.damping.exact as exact

mp.mp.dps = 30

MASS = (1.0, 2.0, 1.5)
K_G, PSI_G = (200.0, 100.0, 250.0), (0.3, 0.0, 0.1)
K_C, PSI_C = (100.0, 150.0), (0.5, 0.0)


def _chain(k_g, k_c):
    return [[k_g[0] + k_c[0], -k_c[0], 0],
            [-k_c[0], k_g[1] + k_c[0] + k_c[1], -k_c[1]],
            [0, -k_c[1], k_g[2] + k_c[1]]]


K = _chain(K_G, K_C)
KPSI = _chain([p * k for p, k in zip(PSI_G, K_G)], [p * k for p, k in zip(PSI_C, K_C)])


def _modes(scale=1.0):
    w2, V = sla.eigh(np.array(K, float), scale * np.diag(MASS))
    return np.sqrt(w2), V


@lru_cache(maxsize=1)
def _exact_by_mpmath():
    w, _ = _modes()
    Mi = mp.diag([1 / mp.mpf(m) for m in MASS])
    Km, Pm = mp.matrix(K), mp.matrix(KPSI)
    out_v, out_h = [], []
    for i in range(3):
        B = Pm / (2 * mp.pi * w[i])
        A = mp.zeros(6, 6)
        top = -Mi * Km
        bot = -Mi * B
        for a in range(3):
            A[a, 3 + a] = 1
            for b in range(3):
                A[3 + a, b] = top[a, b]
                A[3 + a, 3 + b] = bot[a, b]
        lams = sorted(mp.eig(A, left=False, right=False), key=lambda x: abs(x - 1j * w[i]))
        assert abs(lams[1] - 1j * w[i]) > 2 * abs(lams[0] - 1j * w[i]) + 1.0
        lam = lams[0]
        out_v.append((float(-mp.re(lam) / abs(lam)), float(mp.im(lam))))
        mus = sorted(mp.eig(Mi * (Km + 1j * Pm / (2 * mp.pi)), left=False, right=False),
                     key=lambda x: abs(x - w[i]**2))
        mu = mus[0]
        out_h.append((float(mp.im(mu) / (2 * mp.re(mu))), float(mp.re(mp.sqrt(mu)))))
    return np.array(out_v), np.array(out_h)


def _run(which=None, scale=1.0):
    w, V = _modes(scale)
    Kpsi = sp.csr_matrix(np.array(KPSI, float))
    system = SimpleNamespace(K=sp.csr_matrix(np.array(K, float)),
                             M=sp.csr_matrix(scale * np.diag(MASS)))
    zeta = np.diag(V.T @ np.array(KPSI) @ V) / (2 * np.pi) / (2 * w**2)
    # the coupling only picks the start block of the sparse path: use |D_ij| / |dw^2|
    H = V.T @ np.array(KPSI) @ V / (2 * np.pi)
    coupling = np.abs(H - np.diag(np.diag(H))) / (np.abs(w[:, None]**2 - w[None, :]**2)
                                                   + np.eye(3))
    v = exact.exact_viscous(system, V, w, zeta, Kpsi, coupling, which)
    h = exact.exact_hysteretic(system, V, w, zeta, Kpsi, coupling, which)
    return np.array(v).T, np.array(h).T, zeta


@pytest.mark.parametrize("path", ["dense", "sparse"])
def test_exact_damping_of_a_three_mass_chain_against_mpmath(path, monkeypatch):
    """Both exact solutions to 1e-9 relative (dense: QZ refined by inverse iteration, at
    round-off; sparse: the block iteration stops at a residual of 1e-10, which bounds the
    eigenvalue's relative error by about that). The decoupled ratios differ from the
    exact ones by 8e-7, 8e-3 and 4e-3 of themselves here (far above 1e-9), so returning
    them fails the test."""
    if path == "sparse":
        monkeypatch.setattr(exact, "DENSE_MAX", 0)
    v_ref, h_ref = _exact_by_mpmath()
    v, h, zeta = _run()
    np.testing.assert_allclose(v, v_ref, rtol=1e-9)
    np.testing.assert_allclose(h, h_ref, rtol=1e-9)
    assert np.all(np.abs(zeta / v_ref[:, 0] - 1) > 5e-7)


@pytest.mark.parametrize("path", ["dense", "sparse"])
def test_exact_damping_of_chosen_modes_in_their_order(path, monkeypatch):
    """`which` = (2, 0): the results come in that order (rows are positions)."""
    if path == "sparse":
        monkeypatch.setattr(exact, "DENSE_MAX", 0)
    v_ref, h_ref = _exact_by_mpmath()
    v, h, _ = _run(which=[2, 0])
    np.testing.assert_allclose(v, v_ref[[2, 0]], rtol=1e-9)
    np.testing.assert_allclose(h, h_ref[[2, 0]], rtol=1e-9)


def test_decoupled_lambda_and_partners_by_hand():
    """The shift: -zeta w + i w sqrt(1 - zeta^2) moved by 1e-3 w e^{0.3 i}; overdamped
    (zeta = 2): the slow root -w (2 - sqrt 3). Partners: mode i first, then the (up to 3)
    modes most coupled to it, only those with coupling > 0."""
    lam = exact._decoupled_lambda(np.array([10.0, 10.0]), np.array([0.1, 2.0]))
    off = 1e-3 * 10 * np.exp(0.3j)
    assert np.allclose(lam, [10 * (-0.1 + 1j * np.sqrt(0.99)) + off,
                             -10 * (2 - np.sqrt(3)) + off], rtol=0, atol=1e-13)
    c = np.array([[0, 0.3, 0.0, 0.1, 0.2, 0.05],
                  [0.3, 0, 0, 0, 0, 0]] + [[0] * 6] * 4)
    assert exact._partners(c, 0) == [0, 1, 4, 3]
    assert exact._partners(c, 1) == [1, 0]
    assert exact._assign(np.array([[0.1, 0.9], [0.8, 0.7]])) == [(0, 1), (1, 0)]


@pytest.mark.parametrize("path", ["dense", "sparse"])
def test_slow_modes_scale_with_the_mass(path, monkeypatch):
    """Masses times s = 1e3 (modes at 0.32 to 0.59 rad/s, like a crane's sway): with
    lam' = lam / sqrt(s) the viscous equation lam'^2 s M + lam' K_psi / (2 pi w_i / sqrt(s))
    + K = 0 is the original one, and mu' = mu / s for the complex stiffness: the damping
    ratios stay, the damped frequencies scale by 1 / sqrt(s). Tolerance 1e-9 as above
    (a damped frequency clipped at 1 rad/s, `maximum(lam.imag, 1.0)`, survived the
    10-19 rad/s case)."""
    if path == "sparse":
        monkeypatch.setattr(exact, "DENSE_MAX", 0)
    v_ref, h_ref = _exact_by_mpmath()
    v, h, _ = _run(scale=1e3)
    f = np.array([1.0, 1e-3 ** 0.5])
    np.testing.assert_allclose(v, v_ref * f, rtol=1e-9)
    np.testing.assert_allclose(h, h_ref * f, rtol=1e-9)
    assert v[:, 1].max() < 1.0


def test_arpack_fallback_against_mpmath(monkeypatch):
    """When the block iteration does not converge, `_nearest` falls back to ARPACK
    (shift-invert, 8 Ritz values, the one most like the mode). Forced here by a block
    iteration that never converges; the results are the same exact eigenvalues (1e-9:
    ARPACK's default tolerance is machine precision on a 6 x 6 operator)."""
    monkeypatch.setattr(exact, "DENSE_MAX", 0)
    monkeypatch.setattr(exact, "_block_inverse",
                        lambda apply, Z0, pick, **kw: (np.nan, None, False))
    v_ref, h_ref = _exact_by_mpmath()
    v, h, _ = _run()
    np.testing.assert_allclose(v, v_ref, rtol=1e-9)
    np.testing.assert_allclose(h, h_ref, rtol=1e-9)
