"""Kill tests for the eigen-search of cranefe/analysis/damping/exact.py (tools/mutation.py
damping_exact; docs/testing.md, "Mutation testing"): repeated frequencies, strong
damping, a massless coordinate, and the search's parts (participation, block
shift-invert iteration, refinement, ARPACK fallback, decoupled shift) on operators whose
eigenvalues are known. tests/test_mutation_kills_exact.py checks a well-separated 3-DOF
chain against mpmath; there every root is nearest its own estimate, so a wrong shift,
start block, partner list or convergence test could not change a result.

Exact answers used below (derived here, no code under test):
- Repeated frequency w (M = I, K = w^2 I on two coordinates, four uncoupled ones far
  above) with a coupling K_psi: every vector of the pair's plane is an undamped mode;
  take V = the two unit vectors. With B = K_psi / (2 pi w) (the same for both modes, eq. 12
  at w) and K_psi u_k = kappa_k u_k, the viscous roots are
  lam_k = -beta_k / 2 + i sqrt(w^2 - beta_k^2 / 4), beta_k = kappa_k / (2 pi w), so
  |lam_k| = w, zeta_k = beta_k / (2 w) = kappa_k / (4 pi w^2), damped w = Im lam_k; the
  complex stiffness gives mu_k = w^2 + i kappa_k / (2 pi), zeta_k = kappa_k / (4 pi w^2)
  (the same), damped w = Re sqrt(mu_k). For K_psi = s [[8, 2], [2, 6]]:
  kappa_(+/-) = s (7 +/- sqrt 5); u_+ = (1, (sqrt 5 - 1) / 2) holds 1 / (1 + 0.382) =
  72.4 % of mode e_1 (|u_1|^2 / |u|^2), so mode 1's own root is kappa_+ and mode 2's is
  kappa_-.
- Uncoupled coordinates (M = I, K, K_psi diagonal): lam^2 + lam psi w_j^2 / (2 pi w_i)
  + w_j^2 = 0 for coordinate j under mode i's B; the own root (j = i) has
  zeta = psi / (4 pi); psi > 4 pi makes it overdamped: two real roots, both with
  zeta = -Re lam / |lam| = 1 and damped w = 0.
"""

from functools import lru_cache
from types import SimpleNamespace

import mpmath as mp
import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

import cranefe.analysis.damping.exact as exact
from cranefe.errors import AnalysisError

mp.mp.dps = 30
PATHS = ["dense", "sparse"]


def _solve(K, M, P, V, w, zeta, coupling=None, which=None, path="dense", monkeypatch=None):
    if path == "sparse":
        monkeypatch.setattr(exact, "DENSE_MAX", 0)
    system = SimpleNamespace(K=sp.csr_matrix(np.asarray(K, float)),
                             M=sp.csr_matrix(np.asarray(M, float)))
    args = (system, np.asarray(V, float), np.asarray(w, float), np.asarray(zeta, float),
            sp.csr_matrix(np.asarray(P, float)), coupling, which)
    return np.array(exact.exact_viscous(*args)).T, np.array(exact.exact_hysteretic(*args)).T


# ---------------------------------------------------------------- repeated frequency
def _kappa(w):
    """K_psi = (w^2 / 100) [[8, 2], [2, 6]] (psi ~ 0.06-0.09): kappa_(+/-) of mode 1, 2."""
    return w**2 / 100 * (7 + np.sqrt(5) * np.array([1.0, -1.0]))


def _repeated(w=100.0):
    """The pair, plus four uncoupled coordinates at 3w to 6w (psi 0.05, not asked for) so
    that the operators are big enough for ARPACK's fallback (k <= size - 2 Ritz values)
    to see both roots of the pair, as it does in the models that take this path
    (n > DENSE_MAX)."""
    K = w**2 * np.diag([1.0, 1.0, 9.0, 16.0, 25.0, 36.0])
    P = 0.05 * K
    P[:2, :2] = w**2 / 100 * np.array([[8.0, 2.0], [2.0, 6.0]])
    zeta = np.diag(P)[:2] / (4 * np.pi * w**2)          # H_ii / (2 w^2), H = P / (2 pi)
    return K, np.eye(6), P, np.eye(6)[:, :2], np.full(2, w), zeta


def _repeated_exact(w=100.0, scale=1.0):
    kappa = scale * _kappa(w)
    beta = kappa / (2 * np.pi * w)
    z = kappa / (4 * np.pi * w**2)
    viscous = np.column_stack([z, np.sqrt(w**2 - beta**2 / 4)])
    hyst = np.column_stack([z, np.sqrt(w**2 + 1j * kappa / (2 * np.pi)).real])
    return viscous, hyst


@pytest.mark.parametrize("w", [100.0, 0.25, 0.05])
@pytest.mark.parametrize("path", PATHS)
def test_repeated_frequency_pair_without_partners(path, w, monkeypatch):
    """Two modes at one frequency coupled by K_psi (zeta 0.0073 and 0.0038): each mode's
    own root (participation 72 % against 28 %) from the decoupled estimate, with no
    coupling given (`coupling=None`, so no partners: the block iteration starts from the
    mode alone and converges to the root nearest the shift). The roots lie 0.36 apart in
    Re lam (7.1 in Im mu), far more than the shift's offset (0.1, resp. 10), so the
    decoupled estimate (-zeta w + i w sqrt(1 - zeta^2) moved
    by 1e-3 w, resp. w^2 (1 + 2 i zeta) moved by 1e-3 w^2) is nearest the own root; a
    shift mirrored (1 - 2 i zeta), scaled (3 i zeta, w^2 / (1 + 2 i zeta)) or moved by
    1e-3 w^3 is nearer the other root. At w = 0.25 rad/s (a crane's sway) the pair is
    7.1e-3 |mu| apart in Im mu: a shift offset not scaled as w^2 (1e-3 / w^2 = 0.26 |mu|,
    2e-3 w = 8e-3 |mu|) lands nearer the other root; a mode heading for its partner's
    root is then sent to ARPACK (participation below 1/2), whose 4 roots nearest the
    shift hold it, except at w = 0.05 rad/s, where 1e-3 / w^2 = 160 |mu| puts the shift
    among the four far coordinates. Tolerance 1e-9 relative: the sparse iteration
    stops at a relative residual of 1e-10, or below 1e-7 when it falls by less than 0.3
    per step, and these pencils are normal (K, M multiples of I), so the eigenvalue errs
    by about the residual squared; QZ + refinement are at round-off."""
    v_ref, h_ref = _repeated_exact(w)
    v, h = _solve(*_repeated(w), coupling=None, path=path, monkeypatch=monkeypatch)
    np.testing.assert_allclose(v, v_ref, rtol=1e-9)
    np.testing.assert_allclose(h, h_ref, rtol=1e-9)


@pytest.mark.parametrize("path", PATHS)
def test_repeated_frequency_pair_needs_its_partner(path, monkeypatch):
    """The same pair with the undamped estimate zeta = 0: the shift (i w, w^2) is then
    nearer the LESS damped root (kappa_-) for both modes, so mode 1 alone heads for mode
    2's root; with the coupling given (Hasselman's eps_12 = |H_12| / |H_11 - H_22| =
    2 / 2 = 1, any value > 0 makes them partners) the start block holds both modes, the
    Rayleigh-Ritz step yields both roots and participation picks mode 1's own (without
    partners the participation check sends mode 1 to ARPACK). Results in the order of
    `which` = (1, 0). Tolerance 1e-8 on the sparse viscous zeta: a Ritz
    value from a 2-vector block of the (non-normal) first-order operator errs by about
    50 times its residual (measured 3e-10 at the residual 6e-12); elsewhere 1e-9."""
    v_ref, h_ref = _repeated_exact()
    K, M, P, V, w, _ = _repeated()
    coupling = np.array([[0.0, 1.0], [1.0, 0.0]])
    v, h = _solve(K, M, P, V, w, np.zeros(2), coupling, [1, 0], path, monkeypatch)
    np.testing.assert_allclose(v[:, 0], v_ref[[1, 0], 0], rtol=1e-8)
    np.testing.assert_allclose(v[:, 1], v_ref[[1, 0], 1], rtol=1e-9)
    np.testing.assert_allclose(h, h_ref[[1, 0]], rtol=1e-9)


@pytest.mark.parametrize("path", PATHS)
def test_close_root_nearer_the_estimate_without_partners(path, monkeypatch):
    """The repeated pair with half the absorption (K_psi / 2: Re lam -0.367 and -0.190)
    and no partners: mode 1's decoupled estimate moved by its offset 1e-3 w e^(0.3 i)
    (Re -0.223) is nearer mode 2's root (0.04 away) than its own (0.15), so the block
    iteration from mode 1 alone converged to mode 2's root and returned its zeta 0.00190
    for mode 1 (a bug until 2026-11-24: the found vector holds 28 % of mode 1); now a
    vector with participation below 1/2 sends the search to ARPACK's nearest roots,
    picked by participation. Closed forms with kappa halved; tolerance as above."""
    K, M, P, V, w, zeta = _repeated()
    P[:2, :2] /= 2
    v_ref, h_ref = _repeated_exact(scale=0.5)
    v, h = _solve(K, M, P, V, w, zeta / 2, coupling=None, path=path,
                  monkeypatch=monkeypatch)
    np.testing.assert_allclose(v, v_ref, rtol=1e-9)
    np.testing.assert_allclose(h, h_ref, rtol=1e-9)


def test_psi_stiffness_by_default(monkeypatch):
    """`Kpsi=None`: the system's own K_psi (element.psi_stiffness(system))."""
    K, M, P, V, w, zeta = _repeated()
    system = SimpleNamespace(K=sp.csr_matrix(K), M=sp.csr_matrix(M))
    asked = []
    monkeypatch.setattr(exact, "psi_stiffness",
                        lambda s: asked.append(s) or sp.csr_matrix(P))
    v_ref, h_ref = _repeated_exact()
    v = np.array(exact.exact_viscous(system, V, w, zeta)).T
    h = np.array(exact.exact_hysteretic(system, V, w, zeta)).T
    assert asked == [system, system]
    np.testing.assert_allclose(v, v_ref, rtol=1e-9)
    np.testing.assert_allclose(h, h_ref, rtol=1e-9)


def test_dense_max_coordinates_take_qz(monkeypatch):
    """DENSE_MAX is the largest size solved by QZ (constants.py): a system of exactly
    DENSE_MAX coordinates must not reach the iterative search."""
    monkeypatch.setattr(exact, "DENSE_MAX", 6)

    def no_search(*a, **k):
        raise AssertionError("the iterative search was used at n = DENSE_MAX")
    monkeypatch.setattr(exact, "_nearest", no_search)
    v_ref, h_ref = _repeated_exact()
    v, h = _solve(*_repeated())
    np.testing.assert_allclose(v, v_ref, rtol=1e-9)
    np.testing.assert_allclose(h, h_ref, rtol=1e-9)


# ---------------------------------------------------------------- a root near the shift
def _rotated_pair(k, p):
    """M = I, K = Q diag(k) Q^T, K_psi = Q diag(p) Q^T (Q a rotation by 0.3 rad): the
    modes are Q's columns, uncoupled (H diagonal), but no coordinate is a mode, so QZ's
    eigenvectors carry round-off in the other mode's direction."""
    c, s = np.cos(0.3), np.sin(0.3)
    Q = np.array([[c, -s], [s, c]])
    k, p = np.asarray(k, float), np.asarray(p, float)
    w = np.sqrt(k)
    return (Q @ np.diag(k) @ Q.T, np.eye(2), Q @ np.diag(p) @ Q.T, Q, w,
            p / (4 * np.pi * k))


def _rotated_exact(k, p):
    """Per mode j: viscous lam^2 + lam p_j / (2 pi w_j) + k_j = 0, zeta = p_j / (4 pi k_j),
    damped w = w_j sqrt(1 - zeta^2); complex stiffness mu_j = k_j + i p_j / (2 pi)."""
    k, p = np.asarray(k, float), np.asarray(p, float)
    z = p / (4 * np.pi * k)
    mu = k + 1j * p / (2 * np.pi)
    return (np.column_stack([z, np.sqrt(k * (1 - z**2))]),
            np.column_stack([mu.imag / (2 * mu.real), np.sqrt(mu).real]))


def _pair_case(case):
    if case == "mu2 = mu1 + |mu1|":                  # w = 10 and 14.2 rad/s, eta 0.1, 0.05
        mu1 = 100 * (1 + 0.1j)
        mu2 = mu1 + abs(mu1)
        return [mu1.real, mu2.real], [2 * np.pi * mu1.imag, 2 * np.pi * mu2.imag]
    if case == "mu2 = mu1 + 1e-6 / |mu1|":          # w = 0.1 rad/s, 0.5 % apart
        mu1 = 0.01 * (1 + 0.1j)
        mu2 = mu1 + 1e-6 / abs(mu1)
        return [mu1.real, mu2.real], [2 * np.pi * mu1.imag, 2 * np.pi * mu2.imag]
    # viscous: under mode 1's B = K_psi / (2 pi w1), mode 2's root at lam1 + 1e-6 / |lam1|
    # (|lam1| = w1): its roots sum to -p2 / (2 pi w1) and multiply to k2
    w1, z1 = 0.1, 0.05
    lam1 = w1 * (-z1 + 1j * np.sqrt(1 - z1**2))
    r = lam1 + 1e-6 / w1
    return [w1**2, abs(r)**2], [4 * np.pi * w1**2 * z1, -2 * r.real * 2 * np.pi * w1]


@pytest.mark.parametrize("case", ["mu2 = mu1 + |mu1|", "mu2 = mu1 + 1e-6 / |mu1|",
                                  "lam2 = lam1 + 1e-6 / |lam1|"])
def test_a_root_where_a_misplaced_refinement_shift_would_fall(case):
    """QZ's eigenvalue is refined by inverse iteration at a shift 1e-6 |ev| beside it; a
    second mode's root lying where a shift |ev| or 1e-6 / |ev| away would fall (exactly
    at mu1 + |mu1|, 42 % higher in frequency; or 1e-4 of a slow mode's |ev| away) must
    not attract the refinement: the iteration from QZ's vector multiplies its round-off
    component along that root by (distance ratio)^3. Both modes against their closed
    forms to 1e-9 relative (QZ + refinement at round-off; the slow pair is 1e-4 apart,
    still 100 times the offset 1e-6 |ev|)."""
    k, p = _pair_case(case)
    v_ref, h_ref = _rotated_exact(k, p)
    v, h = _solve(*_rotated_pair(k, p), coupling=np.zeros((2, 2)))
    np.testing.assert_allclose(v, v_ref, rtol=1e-9)
    np.testing.assert_allclose(h, h_ref, rtol=1e-9)


# ---------------------------------------------------------------- strong damping
W_OD = np.array([10.0, 12.0, 14.0, 16.0, 18.0])
PSI_OD = np.array([15.0, 0.5, 0.5, 0.5, 0.5])    # 15 > 4 pi: coordinate 1 overdamped


def _overdamped():
    """Five uncoupled modes and a sixth, free one (a rigid-body root lam = 0, like
    slewing), which the elastic modes V (6 x 5) leave out; the coordinates are the modes
    turned by 0.3 rad in the plane of modes 1 and 6 (M = I stays), so that no coordinate
    is a mode and QZ's vectors carry round-off along the rigid one."""
    w = W_OD
    R = np.eye(6)
    R[np.ix_([0, 5], [0, 5])] = [[np.cos(0.3), -np.sin(0.3)], [np.sin(0.3), np.cos(0.3)]]
    return (R @ np.diag(np.append(w**2, 0.0)) @ R.T, np.eye(6),
            R @ np.diag(np.append(PSI_OD * w**2, 0.0)) @ R.T, R[:, :5], w,
            PSI_OD / (4 * np.pi))


def _overdamped_exact():
    w = W_OD
    z = PSI_OD / (4 * np.pi)
    viscous = np.column_stack([np.minimum(z, 1.0),
                               np.where(z < 1, w * np.sqrt(np.abs(1 - z**2)), 0.0)])
    mu = w**2 * (1 + 1j * PSI_OD / (2 * np.pi))
    hyst = np.column_stack([z, np.sqrt(mu).real])
    return viscous, hyst


@pytest.mark.parametrize("path", PATHS + ["arpack"])
def test_overdamped_mode_among_light_ones(path, monkeypatch):
    """psi = 15 on coordinate 1 (zeta = 15 / (4 pi) = 1.19): its roots are real, zeta = 1
    and damped w = 0 exactly; the complex stiffness gives mu = w^2 (1 + 2.39 i), zeta 1.19.
    The four other coordinates (psi 0.5, zeta 0.0398) keep their closed forms. A filter
    that drops real roots (`Im lam >= +1e-9 |lam|`) leaves mode 1 a root of another
    coordinate; a refinement shift |ev| to the right of the slow root -5.46 (at ~5e-6)
    would converge to the free coordinate's root 0. "arpack": the block iteration forced
    not to converge, so ARPACK's 8 Ritz values (real roots among complex ones) are
    picked from. Tolerance 1e-9 relative, 1e-9
    rad/s absolute for the damped w = 0 (the iterative paths' real root carries round-off
    in Im lam, ~1e-15 of |lam| = 5.5)."""
    if path == "arpack":
        monkeypatch.setattr(exact, "_block_inverse",
                            lambda apply, Z0, pick, **kw: (np.nan, None, False))
    v_ref, h_ref = _overdamped_exact()
    v, h = _solve(*_overdamped(), path="dense" if path == "dense" else "sparse",
                  monkeypatch=monkeypatch)
    np.testing.assert_allclose(v, v_ref, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(h, h_ref, rtol=1e-9)


# ---------------------------------------------------------------- massless coordinate
# A mass m on a ground spring k0, tied to a massless node by k_a (psi 8) that a spring
# k_b holds to the ground: the node relaxes through the dashpot b = psi k_a / (2 pi w).
M1, K0, KA, KB, PSI_A = 1.0, 75.0, 50.0, 50.0, 8.0
W_ML = np.sqrt((K0 + KA * KB / (KA + KB)) / M1)          # 10 rad/s (the node condensed)
V_ML = np.array([[1.0], [KA / (KA + KB)]]) / np.sqrt(M1)   # the condensed mode


def _massless():
    K = np.array([[K0 + KA, -KA], [-KA, KA + KB]])
    P = PSI_A * np.array([[KA, -KA], [-KA, KA]])
    zeta = (V_ML.T @ P @ V_ML)[0, 0] / (2 * np.pi) / (2 * W_ML**2)
    return K, np.diag([M1, 0.0]), P, V_ML, np.array([W_ML]), np.array([zeta])


@lru_cache(maxsize=1)
def _massless_exact():
    """det(lam^2 M + lam B + K) = (lam^2 m + lam b + k0 + k_a)(lam b + k_a + k_b)
    - (lam b + k_a)^2 = m b lam^3 + m (k_a + k_b) lam^2 + b (k0 + k_b) lam
    + (k0 + k_a)(k_a + k_b) - k_a^2 (a cubic: the pair and one real relaxation root);
    complex stiffness, node condensed: mu m = k0 + c_a - c_a^2 / (c_a + k_b),
    c_a = k_a (1 + i psi / (2 pi))."""
    b = PSI_A * KA / (2 * mp.pi * mp.mpf(W_ML))
    coeffs = [M1 * b, M1 * (KA + KB), b * (K0 + KB), (K0 + KA) * (KA + KB) - KA**2]
    try:    # mpmath >= 1.4 deprecates the descending order
        roots = mp.polyroots(coeffs[::-1], maxsteps=200, extraprec=100, asc=True)
    except TypeError:   # mpmath 1.3: descending only, no `asc`
        roots = mp.polyroots(coeffs, maxsteps=200, extraprec=100)
    lam = [r for r in roots if mp.im(r) > 0][0]
    relax = [r for r in roots if abs(mp.im(r)) < 1e-20][0]
    ca = KA * (1 + 1j * PSI_A / (2 * mp.pi))
    mu = (K0 + ca - ca**2 / (ca + KB)) / M1
    return (np.array([[float(-mp.re(lam) / abs(lam)), float(mp.im(lam))]]),
            np.array([[float(mp.im(mu) / (2 * mp.re(mu))), float(mp.re(mp.sqrt(mu)))]]),
            float(mp.re(relax)), complex(lam))


@pytest.mark.parametrize("path", PATHS)
def test_massless_node_beside_a_dashpot(path, monkeypatch):
    """All three viscous roots have participation 1 (one mass), so the near-tie rule
    decides: the root nearest the decoupled estimate, the oscillating one
    (-0.584 + 10.38 i), not the relaxation root (-14.5, strong damping puts it near).
    QZ also returns an infinite eigenvalue (singular M). Tolerance 1e-9 as above."""
    v_ref, h_ref, relax, lam = _massless_exact()
    assert abs(relax) < 1.5 * abs(lam) and abs(relax - lam) > 10
    v, h = _solve(*_massless(), coupling=np.zeros((1, 1)), path=path,
                  monkeypatch=monkeypatch)
    np.testing.assert_allclose(v, v_ref, rtol=1e-9)
    np.testing.assert_allclose(h, h_ref, rtol=1e-9)


# ---------------------------------------------------------------- the search's parts
def test_participation_by_hand():
    """|v^T M x|^2 / (x^H M x) with M = diag(1, 2), v = (1, 1) / sqrt 3 (v^T M v = 1):
    x = (1, 0): (1/3) / 1; (0.5, 0.5): 0.75 / 0.75 = 1 (x^H M x < 1); (0, 0): 0, not
    0/0 (a column with no mass, e.g. on massless coordinates); (i, -1): |i - 2|^2 / 3 / 3
    = 5/9."""
    M = np.diag([1.0, 2.0])
    v = np.ones(2) / np.sqrt(3)
    X = np.array([[1, 0.5, 0, 1j], [0, 0.5, 0, -1]])
    np.testing.assert_allclose(exact._participation(v, M, X), [1 / 3, 1, 0, 5 / 9],
                               rtol=1e-14, atol=0)


def _diag_op(d):
    d = np.asarray(d, complex)
    return lambda Z: d[:, None] * Z if Z.ndim == 2 else d * Z


def _largest(nu, X):
    return int(np.argmax(np.abs(nu)))


def _true_residual(d, nu, x):
    return np.linalg.norm(np.asarray(d) * x - nu * x) / (abs(nu) * np.linalg.norm(x))


def _eig_op(lam, X, sigma):
    """Z -> X diag(1 / (lam - sigma)) X^-1 Z: a shift-invert operator whose roots lam and
    vectors X are given (the first-order space, 2n rows)."""
    A = X @ np.diag(1 / (np.asarray(lam) - sigma)) @ np.linalg.inv(X)
    return lambda Z: A @ Z


def test_nearest_takes_the_upper_root_and_a_real_root_with_round_off():
    """n = 2, M = I, mode v = e_1. (a) An underdamped pair -1 +/- 5 i in the start block, the
    lower root's vector (1, 0, lam, 0) even a little more like v than the upper one's
    (1, 0.01, lam, 0): the search must return the upper root. (b) An overdamped (real) root
    -2000 whose computed Im is a round-off -1e-9 (5e-13 of |lam|, what a complex
    factorisation leaves) and whose vector is mode v's: it is the mode's root and must be
    taken; a threshold that scaled the round-off as 1e-9 / |lam| (5e-13 here, below the
    round-off) would drop it and return a root of another mode (-2100 + 20 i, whose
    vector holds none of v)."""
    # (a) the conjugate pair, and two roots of the other coordinate far off
    lam = np.array([-1 + 5j, -1 - 5j, -3 + 40j, -3 - 40j])
    X = np.array([[1, 1, 0, 0], [0.01, 0, 1, 1], lam[:2].tolist() + [0, 0],
                  [0, 0, lam[2], lam[3]]], complex)
    sigma = -1 + 4.9j
    Z0 = X[:, :2]
    got = exact._nearest(_eig_op(lam, X, sigma), Z0, sigma, np.array([1.0, 0.0]),
                         sp.identity(2, format="csr"), 2, upper=True)
    assert abs(got - lam[0]) < 1e-8 * abs(lam[0])
    # (b) the real root with a negative round-off Im, beside another mode's real root
    lam = np.array([-2000 - 1e-9j, -2100 + 20j, -1e4, -1.1e4])
    X = np.eye(4, dtype=complex)
    X[:, 1] = [0, 1, 0, 0.5]
    sigma = -2050 + 30j
    Z0 = np.eye(4, dtype=complex)[:, :2]
    got = exact._nearest(_eig_op(lam, X, sigma), Z0, sigma, np.array([1.0, 0.0]),
                         sp.identity(2, format="csr"), 2, upper=True)
    assert abs(got - lam[0]) < 1e-8 * abs(lam[0])


def test_block_iteration_converges_to_its_tolerance():
    """Operator diag(0.05, 0.005, 0.002 i) from (1, 1, 1): the dominant pair converges by a
    factor 0.1 per step, so the iteration stops at a relative residual <= 1e-10 (checked
    here from the returned pair, with |nu| = 0.05 so that a residual not divided by |nu|
    stops 400 times too early) and nu = 0.05 to 1e-12 (a Ritz value of a normal operator
    errs by about the residual squared)."""
    d = [0.05, 0.005, 0.002j]
    nu, x, done = exact._block_inverse(_diag_op(d), np.ones((3, 1), complex), _largest)
    assert done
    assert abs(nu - 0.05) < 1e-12 * 0.05
    assert _true_residual(d, nu, x) <= 1e-10


def test_block_iteration_started_near_convergence():
    """Started at a residual of ~3e-8 (between the tolerance and the stagnation level):
    the first step has no previous residual, so it must go on to 1e-10, not stop there."""
    d = [1.0, 0.1]
    Z0 = np.array([[1.0], [3e-8]], complex)
    nu, x, done = exact._block_inverse(_diag_op(d), Z0, _largest)
    assert done and _true_residual(d, nu, x) <= 1e-10


def test_block_iteration_stops_when_stagnating():
    """diag(1, 0.5): the residual falls by only 0.5 per step (> 0.3: 'no longer
    falling'), so the iteration may stop once it is below 1e-7; the eigenvalue is then
    right to 1e-7 relative (residual squared for a normal operator), not stopped at the
    second step's residual ~0.25."""
    d = [1.0, 0.5]
    nu, x, done = exact._block_inverse(_diag_op(d), np.ones((2, 1), complex), _largest)
    assert done
    assert abs(nu - 1.0) < 1e-7
    assert _true_residual(d, nu, x) < 1e-7


def test_block_iteration_reports_no_convergence():
    """diag(1, i): two eigenvalues of equal modulus, so one vector never settles (the
    residual stays |1 - i| / 2); after maxit steps the iteration must say so (its caller
    then asks ARPACK)."""
    nu, x, done = exact._block_inverse(_diag_op([1.0, 1j]), np.ones((2, 1), complex),
                                       _largest)
    assert not done


def test_refine_reaches_the_slow_root_and_keeps_a_breakdown():
    """A slow eigenvalue 1e-3 among fast ones (2, 5 + 1 i) given with QZ-like errors
    (1e-9 on the value and on the vector): three steps of inverse iteration at a shift
    1e-6 of it give 1e-3 to 1e-12 relative. An operator that fails (NaN, a singular
    factorisation) leaves the given value."""
    A = sp.diags([1e-3, 2.0, 5 + 1j]).tocsr()
    lam0 = 1e-3 + 1e-9
    shift = lam0 + 1e-6 * abs(lam0)
    z = np.array([1.0, 1e-9, -1e-9], complex)
    out = exact._refine(exact._linear_op(A, sp.identity(3, format="csr"), shift), lam0,
                        shift, z)
    assert abs(out - 1e-3) < 1e-12 * 1e-3
    with np.errstate(invalid="ignore"):
        assert exact._refine(lambda z: np.full_like(z, np.nan), lam0, shift, z) == lam0


def test_linear_and_quadratic_operators():
    """(A - s M)^-1 M z and (A - s E)^-1 E z of the first-order form, against dense
    solves; the quadratic one with a massless coordinate (E singular)."""
    rng = np.random.default_rng(3)
    K = np.array([[3.0, -1.0], [-1.0, 2.0]])
    B = np.array([[0.2, 0.0], [0.0, 0.1]])
    M = np.diag([1.0, 0.0])
    s = 0.3 + 1.1j
    Z = rng.standard_normal((4, 2)) + 1j * rng.standard_normal((4, 2))
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-K, -B]])
    E = np.block([[np.eye(2), np.zeros((2, 2))], [np.zeros((2, 2)), M]])
    q = exact._quadratic_op(sp.csr_matrix(K), sp.csr_matrix(B), sp.csr_matrix(M), s)
    np.testing.assert_allclose(q(Z), np.linalg.solve(A - s * E, E @ Z), rtol=1e-12)
    np.testing.assert_allclose(q(Z[:, 0]), np.linalg.solve(A - s * E, E @ Z[:, 0]),
                               rtol=1e-12)
    Mf = np.diag([1.0, 2.0])
    lin = exact._linear_op(sp.csr_matrix(K), sp.csr_matrix(Mf), s)
    np.testing.assert_allclose(lin(Z[:2]), np.linalg.solve(K - s * Mf, Mf @ Z[:2]),
                               rtol=1e-12)


def test_decoupled_lambda_between_one_and_two():
    """zeta = 1.5 (overdamped): the slow root -w (1.5 - sqrt(1.25)); zeta = 1: -w from
    either formula; both moved by 1e-3 w e^(0.3 i)."""
    w = np.array([10.0, 10.0])
    lam = exact._decoupled_lambda(w, np.array([1.5, 1.0]))
    off = 1e-3 * 10 * np.exp(0.3j)
    np.testing.assert_allclose(lam, [-10 * (1.5 - np.sqrt(1.25)) + off, -10 + off],
                               rtol=0, atol=1e-13)


def test_arpack_is_reproducible_and_its_failure_is_an_analysis_error(monkeypatch):
    """The fallback starts from a fixed vector, so two calls give the same digits; the 8
    largest eigenvalues of diag(1, ..., 10)^-1 (shift-invert at 0) are 1, 1/2, ..., 1/8
    (to 1e-12: ARPACK's tolerance is machine precision). If ARPACK does not converge:
    AnalysisError naming it and the way out."""
    d = np.arange(1.0, 11.0)
    op = exact._linear_op(sp.diags(d).tocsr(), sp.identity(10, format="csr"), 0.0)
    nu1, Z1 = exact._arpack(op, 10, 8)
    nu2, Z2 = exact._arpack(op, 10, 8)
    assert np.array_equal(nu1, nu2) and np.array_equal(Z1, Z2)
    np.testing.assert_allclose(np.sort(np.abs(nu1)), np.sort(1 / d[:8]), rtol=1e-12)

    def fail(*a, **k):
        raise spla.ArpackNoConvergence("no luck", np.zeros(0), np.zeros((10, 0)))
    monkeypatch.setattr(exact.spla, "eigs", fail)
    with pytest.raises(AnalysisError, match=r"^the complex eigenvalue solver \(ARPACK "
                       r"shift-invert\) did not converge: .*no luck.*; try --method modal$"):
        exact._arpack(op, 10, 8)
