"""Damping from absorption coefficients (Heletiy 2016, eq. 11-17; docs/damping.md).

An element of stiffness c and absorption coefficient psi (energy absorbed per cycle over
the peak strain energy; psi = 2 delta for light damping) gets the equivalent viscous
coefficient ``b = psi c / (2 pi w)`` at the frequency w of the mode concerned (eq. 12),
so ``B(w) = K_psi / (2 pi w)`` with ``K_psi = (R T)^T diag(psi c) (R T) + sum psi_e K_e``
(beams). With the mass-normalised undamped modes V (eq. 14, corrected) everything
follows from ``H = V^T K_psi V / (2 pi)``:

- modal damping matrix ``D_ij = H_ij / sqrt(w_i w_j)`` (eq. 15; its diagonal is
  ``V_i^T B(w_i) V_i``, the off-diagonal terms take the geometric mean of the two
  frequencies, which keeps D symmetric and positive semi-definite);
- decoupled estimate (eq. 16-17): ``zeta_i = d_ii / (2 w_i) = H_ii / (2 w_i^2)``, damped
  frequency ``sqrt(w_i^2 - (d_ii/2)^2)``, log decrement ``2 pi zeta / sqrt(1 - zeta^2)``;
- Hasselman coupling coefficient of modes i, j: the off-diagonal element of the modal
  complex dynamic matrix ``diag(w^2) + i H`` over the difference of its diagonal ones,
  ``eps_ij = |H_ij| / |w_i^2 - w_j^2 + i (H_ii - H_jj)|`` (the size of mode j in the
  complex mode i);
- perturbation estimates (third order) of the exact eigenvalues, hence of the error of
  the decoupled zeta (to leading order ``-sum_j eps_ij^2 [(1 - H_jj/H_ii) +
  (1 - w_j^2/w_i^2)]`` against the complex-stiffness answer for two coupled modes);
  the estimate is trusted while every eps_ij < KAPPA and that error < ERROR_TOL.

Exact answers, per elastic mode: the quadratic eigenproblem
``(lam^2 M + lam B(w_i) + K) x = 0`` with the mode's own B, in first-order form, and the
frequency-independent complex-stiffness problem ``(K + i K_psi / (2 pi)) x = mu M x``
(loss factor psi / (2 pi)): QZ for small systems, else one sparse n x n factorisation
per mode at the decoupled eigenvalue and a block shift-invert iteration started from
the undamped modes concerned. Eigenvalues are assigned to modes by their participation
``|V_i^T M x|^2 / x^H M x``.
"""

import time
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..errors import AnalysisError, ModelError

METHODS = ("modal", "exact", "both", "auto")
KAPPA = 0.1          # Hasselman's criterion: every coupling coefficient below this
ERROR_TOL = 0.02     # and the predicted relative error of zeta below this
DENSE_MAX = 40       # coordinates up to which the exact problems are solved by QZ
EXTRA_MODES = 4      # modes computed beyond --count, as coupling partners, and at least
PARTNER_SPAN = 2.0   # up to this multiple of the highest reported frequency
UNDAMPED = 1e-10     # H_ii below this fraction of psi_max w_i^2 / (2 pi): round-off


# ---------------------------------------------------------------- element level

def equivalent_viscous(psi, c, omega, k1=1.0):
    """Equivalent viscous coefficient of elements in harmonic motion at `omega`.

    Heletiy (2016) eq. 12 (k1 = 1; the paper's "p" is pi) and eq. 13 (poly-harmonic
    motion, k1 from `polyharmonic_k1`): ``b = psi c / (2 pi omega k1)``. Broadcasts.
    """
    return np.asarray(psi) * np.asarray(c) / (2 * np.pi * np.asarray(omega) * k1)


def polyharmonic_k1(amplitudes, omegas):
    """k1 of Heletiy (2016) eq. 13, from equal dissipated power (docs/damping.md).

    For an element elongation ``x = sum_j a_j sin(w_j t)`` the absorbing element
    dissipates ``sum_j psi c a_j^2 w_j / (4 pi)`` per second, a dashpot b dissipates
    ``b sum_j a_j^2 w_j^2 / 2``; equal power gives ``b = psi c / (2 pi w_1 k1)`` with
    ``k1 = sum (a_j/a_1)^2 (w_j/w_1)^2 / sum (a_j/a_1)^2 (w_j/w_1)`` (the printed
    formula has numerator and denominator swapped). a_1 cancels, so a_1 = 0 is allowed.

    amplitudes : (..., nh) elongation amplitudes of the harmonics (e.g. per element)
    omegas : (nh,) their frequencies; omegas[0] is the reference w_1
    Returns k1 with the leading shape of `amplitudes`.
    """
    a2 = np.asarray(amplitudes, dtype=float) ** 2
    r = np.asarray(omegas, dtype=float) / omegas[0]
    num, den = (a2 * r**2).sum(axis=-1), (a2 * r).sum(axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(den > 0, num / np.where(den > 0, den, 1.0), 1.0)


def _weighted_stiffness(system, row_weight, beam_weight):
    """T^T (R^T diag(c w) R + sum w_e K_e) T: element stiffnesses weighted per element."""
    s = system.springs
    K = s.R.T @ sp.diags(s.c * row_weight) @ s.R
    if system.beams is not None:
        from ..assembly import Blocks, sum_blocks
        b = system.beams
        w = np.broadcast_to(beam_weight, (len(b.mat),))
        K = K + sum_blocks([Blocks(b.idx, b.mat * w[:, None, None])], K.shape[0])
    T = system.dofs.T
    K = (T.T @ K @ T).tocsr()
    return ((K + K.T) * 0.5).tocsr()


def psi_stiffness(system):
    """K_psi = sum_e psi_e K_e in generalised coordinates, (n, n) CSR: B(w) = K_psi/(2 pi w)."""
    return _weighted_stiffness(system, system.springs.psi,
                               system.beam_psi if system.beams is not None else 0.0)


def damping_matrix(system, omega, k1=1.0, k1_beams=1.0, omega_beams=None):
    """Viscous matrix B = (R T)^T diag(b) (R T) + beams, with b of eq. 12-13 at `omega`.

    omega : scalar or (n_rows,) per spring row; omega_beams : the beams' (default omega).
    k1 : scalar or (n_rows,) per spring row (poly-harmonic weighting, eq. 13).
    """
    s = system.springs
    beam_psi = system.beam_psi if system.beams is not None else 0.0
    omega_beams = omega if omega_beams is None else omega_beams
    return _weighted_stiffness(system, equivalent_viscous(s.psi, 1.0, omega, k1),
                               equivalent_viscous(beam_psi, 1.0, omega_beams, k1_beams))


def element_frequencies(system, V, omega):
    """The frequency each element mostly vibrates at, for eq. 12 in one viscous matrix.

    Per spring row and per beam element: the frequency of the mode (columns of V,
    mass-normalised, generalised coordinates; omega (m,)) that stores the largest share
    of its strain energy, c (r v_j)^2 / w_j^2, in that element. An element no mode
    strains gets the lowest frequency. Returns (rows (n_rows,), beams (n_beams,)).
    """
    T = system.dofs.T
    s = system.springs
    E = np.asarray((s.R @ T) @ V)                          # (ne, m) elongations
    rows = omega[np.argmax(s.c[:, None] * E**2 / omega**2, axis=1)]
    beams = np.zeros(0)
    if system.beams is not None and len(system.beams.mat):
        b = system.beams
        TV = np.asarray(T @ V)[b.idx]                      # (nb, 12, m)
        energy = np.einsum("eam,eab,ebm->em", TV, b.mat, TV)
        beams = omega[np.argmax(energy / omega**2, axis=1)]
    return rows, beams


# ---------------------------------------------------------------- modal level

class ModalDamping(NamedTuple):
    """Decoupled damping of the elastic modes (indexable as the former tuple)."""

    omega: np.ndarray            # (m,) undamped, rad/s
    zeta: np.ndarray             # (m,) decoupled damping ratios, eq. 16
    damped_omega: np.ndarray     # (m,) eq. 17
    D: np.ndarray                # (m, m) modal damping matrix, eq. 15
    coupling: np.ndarray         # (m, m) Hasselman coupling coefficients eps_ij
    Kpsi: sp.csr_matrix          # (n, n) sum psi_e K_e
    H: np.ndarray                # (m, m) V^T K_psi V / (2 pi)
    predicted_error: np.ndarray  # (m,) estimated relative error of zeta (NaN: not asked)
    shares: np.ndarray           # (m, ne_names) share of each element in H_ii
    element_names: tuple         # (ne_names,)


def _modal_absorption(system, V):
    """V^T K_psi V (m, m) and each element's part of its diagonal (names, (m, k)).

    Summed as sum_e psi_e c_e (r_e V)^2 (non-negative terms), so a mode that stretches
    no absorbing element gets zero to round-off, not eps * |K_psi|.
    """
    s = system.springs
    T = system.dofs.T
    E = np.asarray((s.R @ T) @ V)                 # (ne, m) elongation of each row
    w = s.c * s.psi
    P = E.T @ (E * w[:, None])
    parts = [(E**2 * w[:, None])]
    names = list(s.names)
    if system.beams is not None and len(system.beams.mat):
        b = system.beams
        TV = np.asarray(T @ V)[b.idx]             # (nb, 12, m)
        KV = np.einsum("eab,ebm->eam", b.mat * system.beam_psi[:, None, None], TV)
        P = P + np.einsum("eam,eak->mk", TV, KV)
        parts.append(np.einsum("eam,eam->em", TV, KV))
        mm = system.dofs.members
        names += [f"member {system.model.members[k].name}"
                  for k in mm.member[np.flatnonzero(mm.beam)]]
    uniq, inv = np.unique(np.array(names, dtype=object), return_inverse=True)
    diag = np.zeros((V.shape[1], len(uniq)))
    np.add.at(diag.T, inv, np.vstack(parts))
    return 0.5 * (P + P.T), tuple(str(u) for u in uniq), diag


def modal_damping(system, modal, predict=()):
    """Decoupled estimate for the elastic modes of `modal` -> `ModalDamping`.

    Heletiy (2016) eq. 12, 14-17 with the errata of docs/theory.md; the coupling
    coefficients and the error estimate are defined in docs/damping.md. predict:
    positions among the elastic modes whose error is estimated (it costs O(m^2) each;
    the others get NaN).
    """
    el = ~modal.rigid
    w = modal.omega[el]
    V = modal.shapes[:, el]
    Kpsi = psi_stiffness(system)
    P, names, parts = _modal_absorption(system, V)
    H = P / (2 * np.pi)                                     # eq. 12: b = psi c/(2 pi w)
    psi_max = max(np.max(system.springs.psi, initial=0.0),
                  np.max(system.beam_psi, initial=0.0) if system.beams is not None else 0)
    dead = np.diag(H) <= UNDAMPED * psi_max * w**2 / (2 * np.pi)
    H[dead, :] = 0.0
    H[:, dead] = 0.0
    h = np.diag(H)
    root = np.sqrt(w)
    D = H / np.outer(root, root)                            # eq. 15, D = V^T B V
    zeta = h / (2 * w**2)                                   # eq. 16: d_ii / (2 w_i)
    damped = w * np.sqrt(np.maximum(1 - zeta**2, 0.0))      # eq. 17
    # Hasselman: off-diagonal of diag(w^2) + i H over the difference of its diagonal
    S = w**2 + 1j * h
    off = H - np.diag(h)
    with np.errstate(divide="ignore", invalid="ignore"):
        eps = np.where(off != 0, np.abs(off) / np.abs(S[:, None] - S[None, :]), 0.0)
    predicted = np.full(len(w), np.nan)
    rows = np.asarray(predict, dtype=int)
    if rows.size:
        predicted[rows] = _predicted_error(w, h, zeta, off, rows)
    total = parts.sum(axis=1, keepdims=True)
    shares = np.where(total > 0, parts / np.where(total > 0, total, 1), 0.0)
    return ModalDamping(w, zeta, damped, D, eps, Kpsi, H, predicted, shares, names)


def _perturbed(w, h, off, c, rows):
    """Eigenvalues mu_i (i in rows) of diag(w^2) + i c_i H near w_i^2 + i c_i H_ii, to
    third order in the off-diagonal part (Rayleigh-Schroedinger; the third-order term
    is of the same order as the second-order change of Im mu, which is proportional to
    a damping difference). c : (len(rows),) complex scale of each row's H."""
    wr, hr, offr, cc = w[rows], h[rows], off[rows], c[:, None]
    g = (wr**2)[:, None] - (w**2)[None, :] + 1j * cc * (hr[:, None] - h[None, :])
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        A = np.where(offr != 0, 1j * cc * offr / g, 0.0)    # V_ij / (S_ii - S_jj)
        second = (1j * cc * offr * A).sum(axis=1)
        AV = A.real @ off + 1j * (A.imag @ off)              # off is real, symmetric
        third = 1j * c * (A * AV).sum(axis=1)
    return wr**2 + 1j * c * hr + second + third


def _predicted_error(w, h, zeta, off, rows):
    """Perturbation estimate of zeta_decoupled / zeta_exact - 1 against both exact
    answers for the modes `rows`; the larger in magnitude (docs/damping.md).

    Complex stiffness: mu_i of diag(w^2) + i H (`_perturbed`, c = 1), zeta = Im mu /
    (2 Re mu). Viscous with B(w_i) = K_psi / (2 pi w_i): with lam = i w_i c_i, the modal
    equation (lam^2 + lam H / w_i + diag(w^2)) q = 0 says mu = w_i^2 c_i^2 is an
    eigenvalue of diag(w^2) + i c_i H: a fixed point c = sqrt(mu(c)) / w_i, iterated
    from c = 1 (exact for one mode: lam = -zeta w + i w sqrt(1 - zeta^2)).
    """
    one = np.ones(len(rows), dtype=complex)
    mu = _perturbed(w, h, off, one, rows)
    c = one
    for _ in range(60):                  # contracts by about zeta per step
        c, last = np.sqrt(_perturbed(w, h, off, c, rows)) / w[rows], c
        if np.max(np.abs(c - last)) <= 1e-12:
            break
    lam = 1j * w[rows] * c
    z = zeta[rows]
    with np.errstate(divide="ignore", invalid="ignore"):
        e_h = z / (mu.imag / (2 * mu.real)) - 1
        e_v = z / (-lam.real / np.abs(lam)) - 1
    e = np.where(np.abs(e_v) > np.abs(e_h), e_v, e_h)
    return np.where(h[rows] > 0, np.where(np.isnan(e), np.inf, e), 0.0)


def modal_damping_ratios(system, modal):
    """Decoupled damping ratio of every mode of `modal` (0 for rigid ones): for sweeps."""
    out = np.zeros(len(modal.omega))
    out[~modal.rigid] = modal_damping(system, modal).zeta
    return out


# ---------------------------------------------------------------- exact solutions

def _participation(v, M, X):
    """|v^T M x|^2 / (x^H M x) for the columns x of X: the share of mode v in each."""
    MX = M @ X
    den = np.real(np.einsum("ij,ij->j", X.conj(), MX))
    return np.abs(v @ MX) ** 2 / np.where(den > 0, den, np.inf)


def _quadratic_op(K, B, M, sigma):
    """Z -> (A - sigma E)^-1 E Z for the first-order form of (lam^2 M + lam B + K) x = 0,
    A = [[0, I], [-K, -B]], E = [[I, 0], [0, M]] (M may be singular: massless
    coordinates), with one n x n factorisation of Q(sigma) = K + sigma B + sigma^2 M:
    x = -Q^-1 (M v0 + (B + sigma M) x0), v = x0 + sigma x. Z is (2n,) or (2n, p)."""
    n = K.shape[0]
    lu = spla.splu((K + sigma * B + sigma**2 * M).astype(complex).tocsc())
    G = (B + sigma * M).astype(complex).tocsr()

    def apply(Z):
        x0 = Z[:n]
        x = -lu.solve(np.asarray(M @ Z[n:] + G @ x0))
        return np.concatenate([x, x0 + sigma * x])
    return apply


def _linear_op(A, M, sigma):
    """Z -> (A - sigma M)^-1 M Z for A z = mu M z."""
    lu = spla.splu((A - sigma * M).astype(complex).tocsc())
    return lambda Z: lu.solve(np.asarray(M @ Z))


def _block_inverse(apply, Z0, pick, tol=1e-10, maxit=40):
    """Shift-invert subspace iteration with Rayleigh-Ritz, started from Z0 (size, p).

    Converges to the p eigenvalues nu of largest |nu| (eigenvalues nearest the shift);
    started from the undamped modes concerned it needs a few steps. `pick(nu, X)` says
    which Ritz pair is wanted; returns (nu, x, converged) once its relative residual
    |op x - nu x| / (|nu| |x|) is below tol, or below 1e-7 and no longer falling (the
    round-off floor of the factorisation; the eigenvalue lam = sigma + 1/nu is then
    accurate to about that fraction of |lam - sigma|, i.e. ~1e-3 of it relative to lam).
    """
    Z = np.linalg.qr(Z0)[0]
    last = np.inf
    for _ in range(maxit):
        W = apply(Z)
        nu, Y = np.linalg.eig(Z.conj().T @ W)
        X = Z @ Y
        k = pick(nu, X)
        res = np.linalg.norm(W @ Y[:, k] - nu[k] * X[:, k]) / (
            abs(nu[k]) * np.linalg.norm(X[:, k]))
        if res <= tol or (res < 1e-7 and res > 0.3 * last):
            return nu[k], X[:, k], True
        last = res
        Z = np.linalg.qr(W)[0]
    return nu[k], X[:, k], False


def _refine(apply, lam, shift, z, steps=3):
    """Inverse iteration with an operator factorised at `shift` next to an eigenvalue
    found by QZ, whose absolute error eps |A| is a large relative error for a slow mode
    among fast ones."""
    z = z / np.linalg.norm(z)
    for _ in range(steps):
        y = apply(z)
        nu = np.vdot(z, y)
        z = y / np.linalg.norm(y)
    out = shift + 1 / nu
    return out if np.isfinite(out) else lam


def _arpack(apply, size, k):
    op = spla.LinearOperator((size, size), matvec=apply, dtype=complex)
    rng = np.random.default_rng(0)               # the same digits on every run
    v0 = rng.standard_normal(size) + 1j * rng.standard_normal(size)
    try:
        nu, Z = spla.eigs(op, k=min(k, size - 2), which="LM", v0=v0)
    except spla.ArpackNoConvergence as exc:
        raise AnalysisError("the complex eigenvalue solver (ARPACK shift-invert) did not "
                            f"converge: {exc}; try --method modal") from None
    return nu, Z


def _nearest(apply, Z0, sigma, v, M, n, upper):
    """The eigenvalue near sigma whose vector (first n entries) is most like mode v:
    block iteration from Z0, ARPACK if that does not converge."""
    def pick(nu, X):
        lam = sigma + 1 / nu
        ok = (lam.imag >= -1e-9 * np.abs(lam)) if upper else np.ones(len(nu), bool)
        return int(np.argmax(_participation(v, M, X[:n]) * ok + ok * 1e-300))
    nu, _, done = _block_inverse(apply, Z0, pick)
    if not done:
        nus, Z = _arpack(apply, Z0.shape[0], max(8, Z0.shape[1] + 4))
        nu = nus[pick(nus, Z)]
    return sigma + 1 / nu


def _assign(part):
    """One-to-one (row, column) pairs, greedily by the largest participation."""
    part = part.copy()
    pairs = []
    for _ in range(min(part.shape)):
        r, c = np.unravel_index(np.argmax(part), part.shape)
        pairs.append((r, c))
        part[r, :] = -1.0
        part[:, c] = -1.0
    return pairs


def _partners(coupling, i, p=3):
    """Mode i and the p modes most coupled to it (the start block)."""
    order = np.argsort(-coupling[i])
    return [i] + [j for j in order[:p] if j != i and coupling[i, j] > 0]


def _decoupled_lambda(w, zeta, offset=1e-3):
    """The decoupled eigenvalue -zeta w + i w sqrt(1 - zeta^2) (the slow root if
    overdamped), moved off by offset * w so that a shift there is never singular."""
    lam = np.where(zeta < 1, w * (-zeta + 1j * np.sqrt(np.abs(1 - zeta**2))),
                   -w * (zeta - np.sqrt(np.abs(zeta**2 - 1))))
    return lam + offset * w * np.exp(0.3j)


def _setup(system, V, omega, Kpsi, coupling, which):
    Kpsi = psi_stiffness(system) if Kpsi is None else Kpsi
    coupling = np.zeros((len(omega),) * 2) if coupling is None else coupling
    which = np.arange(len(omega)) if which is None else np.asarray(which, dtype=int)
    return Kpsi, coupling, which, system.K.tocsr(), system.M.tocsr(), system.K.shape[0]


def exact_viscous(system, V, omega, zeta, Kpsi=None, coupling=None, which=None):
    """Exact viscous damping of each mode with its own B(w_i) = K_psi / (2 pi w_i).

    V : (n, m) mass-normalised undamped elastic modes; omega, zeta : (m,) their
    frequencies and decoupled ratios; coupling : (m, m) (partners for the start block);
    which : modes to solve (default all). Per mode: the eigenvalue lam of
    (lam^2 M + lam B(w_i) + K) x = 0 most like the mode (QZ for small systems, else
    block shift-invert from the decoupled estimate); zeta = -Re lam / |lam|, damped
    omega = Im lam. Returns (zeta, damped omega), (len(which),) each.
    """
    Kpsi, coupling, which, K, M, n = _setup(system, V, omega, Kpsi, coupling, which)
    sigma = _decoupled_lambda(omega, zeta)
    lam = np.empty(len(which), dtype=complex)
    if n <= DENSE_MAX:
        Z0, I = np.zeros((n, n)), np.eye(n)
        E = np.block([[I, Z0], [Z0, M.toarray()]])
        Kd, Pd = K.toarray(), Kpsi.toarray()
    for out, i in enumerate(which):                 # one eigenproblem per mode: B(w_i)
        B = Kpsi / (2 * np.pi * omega[i])           # Heletiy (2016) eq. 12
        if n <= DENSE_MAX:                         # QZ on the first-order form
            A = np.block([[Z0, I], [-Kd, -Pd / (2 * np.pi * omega[i])]])
            ev, Z = sla.eig(A, E)
            ok = np.isfinite(ev) & (ev.imag >= -1e-9 * np.abs(ev))
            ev, Z = ev[ok], Z[:, ok]
            # participation decides; a near-tie goes to the root nearest the decoupled
            # estimate: a massless coordinate beside a dashpot adds a real relaxation
            # root whose shape on the masses can be the mode's own (participation 1)
            part = _participation(V[:, i], M, Z[:n])
            near = np.flatnonzero(part >= (1 - 1e-3) * part.max())
            best = near[np.argmin(np.abs(ev[near] - sigma[i]))]
            shift = ev[best] + 1e-6 * abs(ev[best])
            lam[out] = _refine(_quadratic_op(K, B, M, shift), ev[best], shift, Z[:, best])
        else:
            group = _partners(coupling, i)
            Z0 = np.vstack([V[:, group], sigma[i] * V[:, group]]).astype(complex)
            lam[out] = _nearest(_quadratic_op(K, B, M, sigma[i]), Z0, sigma[i], V[:, i],
                                M, n, upper=True)
    return -lam.real / np.abs(lam), np.maximum(lam.imag, 0.0)


def exact_hysteretic(system, V, omega, zeta, Kpsi=None, coupling=None, which=None):
    """Complex stiffness (K + i K_psi / (2 pi)) x = mu M x: loss factor psi / (2 pi) per
    element, independent of frequency (what psi describes). mu = w^2 (1 + i eta),
    zeta = eta / 2 = Im mu / (2 Re mu), damped omega = Re sqrt(mu). Small systems: QZ
    once, modes matched to eigenvectors one-to-one (greedily) by participation; large
    ones: block
    shift-invert per mode from the decoupled estimate. Arguments as `exact_viscous`.
    """
    Kpsi, coupling, which, K, M, n = _setup(system, V, omega, Kpsi, coupling, which)
    Kc = (K + 1j * Kpsi / (2 * np.pi)).tocsr()
    sigma = omega**2 * (1 + 2j * zeta) + 1e-3 * omega**2 * np.exp(0.3j)
    mu = np.empty(len(which), dtype=complex)
    if n <= DENSE_MAX:
        ev, X = sla.eig(Kc.toarray(), M.toarray())
        ok = np.isfinite(ev)
        ev, X = ev[ok], X[:, ok]
        part = np.array([_participation(V[:, i], M, X) for i in which])
        for r, c in _assign(part):
            shift = ev[c] + 1e-6 * abs(ev[c])
            mu[r] = _refine(_linear_op(Kc, M, shift), ev[c], shift, X[:, c])
    else:
        for out, i in enumerate(which):
            Z0 = V[:, _partners(coupling, i)].astype(complex)
            mu[out] = _nearest(_linear_op(Kc, M, sigma[i]), Z0, sigma[i], V[:, i], M, n,
                               upper=False)
    return mu.imag / (2 * mu.real), np.sqrt(mu).real


# ---------------------------------------------------------------- the analysis

@dataclass
class DampingResult:
    """Damping of the modes of one model; rigid (quasi-cyclic) modes first, undamped.

    Arrays are per mode (m,) in the order of `cranefe modes`; the exact ones are NaN
    where not computed (all None with method modal)."""

    model_name: str
    effects: dict
    method: str                   # modal | exact | both | auto
    omega: np.ndarray             # (m,) undamped, rad/s
    rigid: np.ndarray             # (m,) quasi-cyclic: no element deforms, no damping
    zeta: np.ndarray              # (m,) decoupled damping ratios (Hasselman), eq. 16
    damped_omega: np.ndarray      # (m,) decoupled damped frequencies, eq. 17
    log_decrement: np.ndarray     # (m,) 2 pi zeta / sqrt(1 - zeta^2); NaN for rigid
    coupling: np.ndarray          # (m,) largest coupling coefficient eps_ij of the mode
    coupled_with: np.ndarray      # (m,) 0-based mode index of that partner, -1 if none
    coupling_matrix: np.ndarray   # (m, m) eps_ij among the reported modes
    predicted_error: np.ndarray   # (m,) estimated relative error of zeta (perturbation)
    D: np.ndarray                 # (m, m) modal damping matrix V^T B V (eq. 15)
    dominant_element: tuple       # (m,) element absorbing most in each mode ("" if none)
    dominant_share: np.ndarray    # (m,) its share of the mode's absorption
    exact_zeta: np.ndarray = None              # (m,) viscous, each mode's own B
    exact_damped_omega: np.ndarray = None
    hysteretic_zeta: np.ndarray = None         # (m,) complex stiffness
    hysteretic_damped_omega: np.ndarray = None
    dofs: int = 0
    quasi_cyclic: tuple = ()
    timings: dict = field(default_factory=dict)
    warnings: list = field(default_factory=list)
    status: int = 0
    message: str = "ok"

    @property
    def frequency_hz(self):
        return self.omega / (2 * np.pi)

    @property
    def criterion_holds(self):
        """Hasselman's weak coupling: every coupling coefficient of the mode < KAPPA."""
        return self.coupling < KAPPA

    @property
    def trusted(self):
        """Weak coupling and a predicted error of zeta below ERROR_TOL."""
        return self.criterion_holds & (np.abs(self.predicted_error) < ERROR_TOL)

    @property
    def exact_log_decrement(self):
        return None if self.exact_zeta is None else _log_decrement(self.exact_zeta)

    @property
    def hysteretic_log_decrement(self):
        """Free vibration e^{i sqrt(mu) t}: 2 pi Im sqrt(mu) / Re sqrt(mu)
        = 2 pi tan(atan(2 zeta) / 2)."""
        if self.hysteretic_zeta is None:
            return None
        return 2 * np.pi * np.tan(np.arctan(2 * self.hysteretic_zeta) / 2)

    @property
    def error_viscous(self):
        """Relative error of the decoupled zeta against the exact viscous one."""
        return None if self.exact_zeta is None else _rel(self.zeta, self.exact_zeta)

    @property
    def error_hysteretic(self):
        """Relative error of the decoupled zeta against the complex-stiffness one."""
        return None if self.hysteretic_zeta is None else _rel(self.zeta,
                                                             self.hysteretic_zeta)


def _log_decrement(zeta):
    """Log decrement over one damped period, 2 pi zeta / sqrt(1 - zeta^2) (inf if
    overdamped); psi = 2 delta sqrt(1 - zeta^2) exactly for one degree of freedom."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(zeta < 1, 2 * np.pi * zeta / np.sqrt(np.abs(1 - zeta**2)), np.inf)


def _rel(estimate, exact):
    """(estimate - exact) / exact; 0 where both are zero to round-off, NaN if unknown."""
    floor = 1e-9 * max(np.nanmax(np.abs(exact), initial=0.0), 1e-300)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(np.abs(exact) > floor, (estimate - exact) / exact,
                        np.where(np.abs(estimate - exact) <= floor, 0.0, np.nan))


def _check_method(method, count):
    if method not in METHODS:
        raise ModelError(f"damping method {method!r}: use one of {', '.join(METHODS)}",
                         None, "method")
    if count is not None and count < 1:
        raise ModelError(f"count {count}: ask for at least one mode", None, "count")


def damping(model, method="auto", count=None, system=None, modal=None):
    """Damping of the modes of `model` from its elements' absorption coefficients.

    method : 'modal' (decoupled estimate only), 'exact' or 'both' (also the exact
        viscous and complex-stiffness solutions of every damped mode), 'auto' (the
        estimate, and the exact solutions of the modes it cannot be trusted for).
    count : modes to report (rigid ones included, as `cranefe modes --count`); more
        are computed as coupling partners (`partner_modes`).
    system, modal : an assembled System and its ModalResult, if already at hand (then
        the first `count` of its modes are reported, all if None).
    """
    from ..system import assemble
    _check_method(method, count)
    t0 = time.perf_counter()
    system = system or assemble(model)
    t1 = time.perf_counter()
    if modal is None:
        modal, shown = partner_modes(model, system, count)
    else:
        shown = len(modal.omega) if count is None else count
    t2 = time.perf_counter()
    mtot = len(modal.omega)
    m = min(shown, mtot)
    el = np.flatnonzero(~modal.rigid)             # elastic positions among all modes
    md = modal_damping(system, modal, predict=np.flatnonzero(el < m))
    t3 = time.perf_counter()

    def full(values, fill=0.0):
        out = np.full(mtot, fill, dtype=float)
        out[el] = values
        return out[:m]

    eps = np.zeros((mtot, mtot))
    eps[np.ix_(el, el)] = md.coupling
    partner = np.where(eps.max(axis=1) > 0, np.argmax(eps, axis=1), -1)[:m]
    Dfull = np.zeros((mtot, mtot))
    Dfull[np.ix_(el, el)] = md.D
    zeta = full(md.zeta)
    top = np.argmax(md.shares, axis=1) if md.shares.size else np.zeros(len(el), int)
    share = md.shares[np.arange(len(el)), top] if md.shares.size else np.zeros(len(el))
    names = np.full(mtot, "", dtype=object)
    names[el] = [md.element_names[t] if s > 0 else "" for t, s in zip(top, share)]
    rigid = modal.rigid[:m].copy()
    result = DampingResult(
        model.name, system.effects.as_dict(), method, modal.omega[:m].copy(), rigid,
        zeta, full(md.damped_omega), np.where(rigid, np.nan, _log_decrement(zeta)),
        eps.max(axis=1)[:m], partner, eps[:m, :m], full(md.predicted_error),
        Dfull[:m, :m], tuple(str(x) for x in names[:m]), full(share),
        dofs=modal.dofs, quasi_cyclic=tuple(modal.quasi_cyclic),
        timings={"assemble": t1 - t0, "modes": t2 - t1, "decoupled": t3 - t2},
        warnings=list(modal.warnings))

    psi_any = np.any(system.springs.psi * system.springs.c > 0) or (
        system.beams is not None and np.any(system.beam_psi > 0))
    if not psi_any:
        result.warnings.append("no element has an absorption coefficient psi > 0: every "
                               "damping ratio is zero (give psi on ropes, springs or "
                               "members)")
    over = np.flatnonzero(zeta >= 1)
    if over.size:
        result.warnings.append("decoupled estimate overdamped (zeta >= 1) for mode(s) "
                               + ", ".join(str(i + 1) for i in over))
    _criterion_warnings(result, method)

    damped = ~rigid & (zeta > 0)
    if method in ("exact", "both"):
        want = damped
    elif method == "auto":
        want = damped & ~result.trusted
    else:
        want = np.zeros(m, dtype=bool)
    if method in ("exact", "both") or want.any():
        result.exact_zeta, result.exact_damped_omega = _exact_fill(result, rigid)
        result.hysteretic_zeta, result.hysteretic_damped_omega = _exact_fill(result, rigid)
    if want.any():
        idx = np.flatnonzero(want)                 # positions among all modes
        which = np.searchsorted(el, idx)          # the same modes among the elastic ones
        V = modal.shapes[:, el]
        args = (system, V, md.omega, md.zeta, md.Kpsi, md.coupling, which)
        t4 = time.perf_counter()
        ze, wd = exact_viscous(*args)
        t5 = time.perf_counter()
        zh, wh = exact_hysteretic(*args)
        t6 = time.perf_counter()
        result.exact_zeta[idx], result.exact_damped_omega[idx] = ze, wd
        result.hysteretic_zeta[idx], result.hysteretic_damped_omega[idx] = zh, wh
        result.timings.update(exact_viscous=t5 - t4, hysteretic=t6 - t5)
    return result


def partner_modes(model, system, count=None):
    """Modes for the damping analysis and how many of them to report.

    Coupling partners matter near the reported modes, so modes are kept up to
    PARTNER_SPAN times the highest reported frequency (at least EXTRA_MODES more): from
    all modes on the dense path, doubling the count on the sparse one. Reported:
    `count`, else what `cranefe modes` reports (all modes of a dense model, else 10).
    """
    from ..condense import DENSE_MAX as MODAL_DENSE_MAX
    from .modal import SMALL, modes
    n = system.K.shape[0]
    if n <= SMALL or (count is None and n <= MODAL_DENSE_MAX):
        modal = modes(model, count=None, system=system)       # dense: all modes anyway
        if count is None or count >= len(modal.omega):
            return modal, len(modal.omega)
        w = modal.omega
        keep = max(count + EXTRA_MODES, int(np.sum(w <= PARTNER_SPAN * w[count - 1])))
        return first_modes(modal, keep), count
    want = count or 10
    k = want + EXTRA_MODES
    while True:
        modal = modes(model, count=min(k, n - 2), system=system)
        w = modal.omega
        if len(w) <= want or w[-1] >= PARTNER_SPAN * w[want - 1] or k >= n - 2:
            return modal, want
        k *= 2


def first_modes(modal, k):
    """The ModalResult of the first k modes."""
    from dataclasses import replace
    return replace(modal, omega=modal.omega[:k], shapes=modal.shapes[:, :k],
                   node_shapes=modal.node_shapes[:k], rigid=modal.rigid[:k])


def _exact_fill(result, rigid):
    """Exact arrays before solving: the decoupled values where they are exact (rigid
    and undamped modes: no element deforms, so B V_i = 0), NaN elsewhere."""
    z = np.where(rigid | (result.zeta == 0), result.zeta, np.nan)
    w = np.where(rigid | (result.zeta == 0), result.damped_omega, np.nan)
    return z, w


def _criterion_warnings(result, method):
    """Warn where Hasselman's criterion fails or the predicted error is large."""
    m = len(result.omega)
    eps = result.coupling_matrix
    pairs = [(i, j) for i, j in zip(*np.nonzero(np.triu(eps >= KAPPA))) if i < j]
    outside = [i for i in range(m) if result.coupling[i] >= KAPPA
               and result.coupled_with[i] >= m]
    then = {"auto": "; they are solved exactly",
            "modal": "; use --method exact"}.get(method, "")
    if pairs or outside:
        text = ", ".join([f"{i + 1}-{j + 1} ({eps[i, j]:.2g})" for i, j in pairs] +
                         [f"{i + 1}-{result.coupled_with[i] + 1} "
                          f"({result.coupling[i]:.2g})" for i in outside])
        result.warnings.append(
            f"Hasselman's weak-coupling criterion fails (coupling >= {KAPPA}) for modes "
            f"{text}: their decoupled damping ratios are not reliable{then}")
    loose = np.flatnonzero(result.criterion_holds &
                           (np.abs(result.predicted_error) >= ERROR_TOL))
    if loose.size:
        text = ", ".join(f"{i + 1} ({100 * result.predicted_error[i]:+.1f} %)"
                         for i in loose)
        result.warnings.append(
            f"weakly coupled, but the predicted error of the decoupled damping ratio "
            f"exceeds {100 * ERROR_TOL:g} % for mode(s) {text}{then}")
