"""Damping from absorption coefficients (Heletiy 2016, eq. 11-17; docs/damping.md).

An element with stiffness matrix K_e and absorption coefficient psi (energy absorbed per
cycle over the peak strain energy; psi = 2 delta for light damping) is given the
equivalent viscous matrix  b_e = psi c / (2 pi w)  at the frequency w of the mode
concerned (eq. 12, "p" is pi), so  B(w) = K_psi / (2 pi w)  with  K_psi = sum psi_e K_e.

- decoupled (Hasselman's weak coupling, eq. 16-17): with mass-normalised undamped modes V,
  D_ij = V_i^T K_psi V_j / (2 pi sqrt(w_i w_j)); zeta_i = D_ii / (2 w_i) (for one element:
  psi / (4 pi)), damped frequency sqrt(w_i^2 - (D_ii/2)^2);
- coupling coefficient of modes i, j: kappa_ij = |D_ij| max(w_i, w_j) / |w_i^2 - w_j^2|,
  the size of the first-order admixture of mode j in the complex mode i; the decoupled
  estimate is trusted when every kappa_ij < KAPPA;
- exact: the quadratic eigenproblem (lam^2 M + lam B(w_i) + K) x = 0 of each mode's own B,
  the eigenvalue nearest i w_i (dense for small systems, sparse shift-invert for large);
  and, for the frequency-independent absorption psi really describes, the complex
  stiffness K + i K_psi / (2 pi), whose eigenvalue w^2 (1 + i eta) gives zeta = eta / 2.
"""

import time
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

KAPPA = 0.1          # largest coupling coefficient for which the decoupled estimate is used
DENSE_MAX = 150      # coordinates up to which the exact problems are solved densely


@dataclass
class DampingResult:
    model_name: str
    effects: dict
    omega: np.ndarray             # (m,) undamped, rad/s, elastic modes only
    zeta: np.ndarray              # (m,) decoupled damping ratios
    damped_omega: np.ndarray      # (m,) decoupled damped frequencies, rad/s
    log_decrement: np.ndarray     # (m,)
    coupling: np.ndarray          # (m,) largest kappa_ij of each mode
    coupling_matrix: np.ndarray   # (m, m)
    method: str                   # modal | exact | both
    exact_zeta: np.ndarray = None          # (m,) viscous, each mode's own B
    exact_damped_omega: np.ndarray = None
    hysteretic_zeta: np.ndarray = None     # (m,) complex stiffness
    hysteretic_damped_omega: np.ndarray = None
    timings: dict = field(default_factory=dict)
    warnings: list = field(default_factory=list)

    @property
    def criterion_holds(self):
        return self.coupling < KAPPA


def psi_stiffness(system):
    """K_psi = sum psi_e K_e in generalised coordinates (spring rows and beam blocks)."""
    s = system.springs
    K = s.R.T @ sp.diags(s.c * s.psi) @ s.R
    if system.beams is not None:
        from .assemble import Blocks, sum_blocks
        b = system.beams
        K = K + sum_blocks([Blocks(b.idx, b.mat * system.beam_psi[:, None, None])],
                           K.shape[0])
    T = system.dofs.T
    K = (T.T @ K @ T).tocsr()
    return ((K + K.T) * 0.5).tocsr()


def modal_damping(system, modal):
    """Decoupled estimate: (omega, zeta, damped omega, D, kappa) of the elastic modes."""
    el = ~modal.rigid
    w = modal.omega[el]
    V = modal.shapes[:, el]
    Kpsi = psi_stiffness(system)
    D = (V.T @ (Kpsi @ V)) / (2 * np.pi * np.sqrt(np.outer(w, w)))   # Heletiy eq. 15
    D = 0.5 * (D + D.T)
    d = np.diag(D)
    zeta = d / (2 * w)                                                 # eq. 16
    with np.errstate(invalid="ignore"):
        damped = np.sqrt(np.maximum(w**2 - (d / 2) ** 2, 0.0))         # eq. 17
    sep = np.abs(w[:, None] ** 2 - w[None, :] ** 2)
    big = np.maximum(w[:, None], w[None, :])
    with np.errstate(divide="ignore", invalid="ignore"):
        kappa = np.where(sep > 0, np.abs(D) * big / np.where(sep > 0, sep, 1),
                         np.where(np.abs(D) > 0, np.inf, 0.0))
    np.fill_diagonal(kappa, 0.0)
    return w, zeta, damped, D, kappa, Kpsi


def modal_damping_ratios(system, modal):
    """Decoupled damping ratio of every mode of `modal` (0 for rigid ones): for sweeps."""
    out = np.zeros(len(modal.omega))
    out[~modal.rigid] = modal_damping(system, modal)[1]
    return out


def _nearest(lams, w):
    """The eigenvalue nearest i w (upper half plane), as (zeta, damped omega)."""
    lams = lams[np.isfinite(lams) & (lams.imag > 0)]
    lam = lams[np.argmin(np.abs(lams - 1j * w))]
    return -lam.real / abs(lam), lam.imag


def exact_viscous(system, w, Kpsi):
    """For each undamped w_i: the eigenvalue of (lam^2 M + lam B(w_i) + K) nearest i w_i."""
    K, M = system.K, system.M
    n = K.shape[0]
    zeta, damped = np.zeros(len(w)), np.zeros(len(w))
    if n <= DENSE_MAX:
        Kd, Md, Pd = K.toarray(), M.toarray(), Kpsi.toarray()
        Z = np.zeros((n, n))
        I = np.eye(n)
        for i, wi in enumerate(w):
            # first-order form [[0, I], [-K, -B]] z = lam [[I, 0], [0, M]] z
            A = np.block([[Z, I], [-Kd, -Pd / (2 * np.pi * wi)]])
            Bm = np.block([[I, Z], [Z, Md]])
            lams = sla.eig(A, Bm, right=False)
            lams = lams[np.isfinite(lams) & (lams.imag > 0)]
            lam = _refine(A, Bm, lams[np.argmin(np.abs(lams - 1j * wi))])
            zeta[i], damped[i] = -lam.real / abs(lam), lam.imag
        return zeta, damped
    I = sp.identity(n, format="csr")
    for i, wi in enumerate(w):
        A = sp.bmat([[None, I], [-K, -Kpsi / (2 * np.pi * wi)]], format="csc")
        Bm = sp.bmat([[I, None], [None, M]], format="csc")
        lams = _shift_invert(A, Bm, 1j * wi)
        zeta[i], damped[i] = _nearest(lams, wi)
    return zeta, damped


def exact_hysteretic(system, w, Kpsi):
    """Complex stiffness K + i K_psi / (2 pi): eigenvalues w^2 (1 + i eta), zeta = eta/2."""
    K, M = system.K, system.M
    Kc = K + 1j * Kpsi / (2 * np.pi)
    if K.shape[0] <= DENSE_MAX:
        Kd, Md = Kc.toarray(), M.toarray().astype(complex)
        lams = sla.eig(Kd, Md, right=False)
        lams = lams[np.isfinite(lams) & (np.abs(lams) > 0)]
        picked = [_refine(Kd, Md, lams[np.argmin(np.abs(lams - wi**2))]) for wi in w]
    else:
        picked = [_nearest_generalised(Kc.tocsc(), M.tocsc(), wi**2) for wi in w]
    lam = np.array(picked)
    eta = lam.imag / lam.real
    root = np.sqrt(lam)                    # free vibration e^{i sqrt(lam) t}
    return eta / 2, root.real


def _refine(A, Bm, lam, steps=3):
    """Inverse iteration at the eigenvalue found by QZ: its absolute error eps |A| is a
    large relative error for a slow mode among fast ones; a few steps remove it."""
    shift = lam * (1 + 1e-7)         # off the eigenvalue, so the factor is regular
    lu = sla.lu_factor(A - shift * Bm, check_finite=False)
    x = np.ones(A.shape[0], dtype=complex)
    for _ in range(steps):
        y = sla.lu_solve(lu, Bm @ x, check_finite=False)
        mu = np.vdot(x, y) / np.vdot(x, x)
        x = y / np.linalg.norm(y)
    refined = shift + 1 / mu
    return refined if np.isfinite(refined) else lam


def _shift_invert(A, Bm, sigma, k=4):
    """A few eigenvalues of A z = lam Bm z nearest sigma (complex shift-invert)."""
    lu = spla.splu((A - sigma * Bm).astype(complex).tocsc())
    op = spla.LinearOperator(A.shape, matvec=lambda x: lu.solve(Bm @ x), dtype=complex)
    mu = spla.eigs(op, k=min(k, A.shape[0] - 2), which="LM", return_eigenvectors=False,
                   v0=np.ones(A.shape[0], dtype=complex))
    return sigma + 1 / mu


def _nearest_generalised(Kc, M, sigma):
    lams = _shift_invert(Kc, M, sigma)
    return lams[np.argmin(np.abs(lams - sigma))]


def damping(model, method="auto", count=None, system=None, modal=None):
    """Damping of the elastic modes: decoupled, exact, or both (`auto`: decoupled while
    Hasselman's criterion holds, exact for the modes where it fails)."""
    from .assemble import assemble
    from .modal import modes
    t0 = time.perf_counter()
    system = system or assemble(model)
    modal = modal or modes(model, count=None if count is None else count + 6, system=system)
    t1 = time.perf_counter()
    w, zeta, damped, D, kappa, Kpsi = modal_damping(system, modal)
    if count is not None:
        w, zeta, damped = w[:count], zeta[:count], damped[:count]
        kappa = kappa[:count]
    coupling = kappa.max(axis=1) if kappa.size else np.zeros(len(w))
    t2 = time.perf_counter()
    result = DampingResult(model.name, system.effects.as_dict(), w, zeta, damped,
                           2 * np.pi * zeta / np.sqrt(np.maximum(1 - zeta**2, 1e-300)),
                           coupling, kappa[:, :len(w)] if kappa.size else kappa,
                           "modal", timings={**system.timings,
                                             "modes": t1 - t0, "modal_damping": t2 - t1})
    weak = coupling < KAPPA
    if not weak.all():
        bad = ", ".join(f"{k + 1} ({c:.2g})" for k, c in
                        zip(np.flatnonzero(~weak), coupling[~weak]))
        result.warnings.append(
            f"Hasselman's weak-coupling criterion fails for modes {bad}: kappa >= {KAPPA}; "
            "the decoupled damping is not reliable there"
            + ("; the exact solution is used" if method == "auto" else ""))
    if method in ("exact", "both") or (method == "auto" and not weak.all()):
        t3 = time.perf_counter()
        result.exact_zeta, result.exact_damped_omega = exact_viscous(system, w, Kpsi)
        result.hysteretic_zeta, result.hysteretic_damped_omega = \
            exact_hysteretic(system, w, Kpsi)
        result.timings["exact"] = time.perf_counter() - t3
        result.method = "both" if method != "exact" else "exact"
        if method == "auto":
            result.method = "auto"
    return result


def polyharmonic_k1(amplitudes, omegas):
    """Heletiy (2016) eq. 13 (its fraction bar lost in print), derived from equal
    dissipated power: for x = sum a_j sin(w_j t) an element of absorption psi dissipates
    sum psi c a_j^2 w_j / (4 pi) per second, a dashpot b dissipates b sum a_j^2 w_j^2 / 2,
    so b = psi c / (2 pi w_1 k1) with
    k1 = sum (a_j/a_1)^2 (w_j/w_1)^2 / sum (a_j/a_1)^2 (w_j/w_1)."""
    a = np.asarray(amplitudes, dtype=float) / amplitudes[0]
    r = np.asarray(omegas, dtype=float) / omegas[0]
    return float(np.sum(a**2 * r**2) / np.sum(a**2 * r))
