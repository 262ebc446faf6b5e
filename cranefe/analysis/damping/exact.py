"""Exact damped eigenvalues per mode: the viscous quadratic eigenproblem with the mode's
own B and the complex-stiffness problem (QZ for small systems, sparse shift-invert
iteration otherwise)."""


import numpy as np
import scipy.linalg as sla
import scipy.sparse.linalg as spla

from ...errors import AnalysisError

from .constants import DENSE_MAX
from .element import psi_stiffness


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
    block iteration from Z0, ARPACK if that does not converge or finds a vector that is
    mostly another mode's (participation below 1/2)."""
    def pick(nu, X):
        lam = sigma + 1 / nu
        ok = (lam.imag >= -1e-9 * np.abs(lam)) if upper else np.ones(len(nu), bool)
        return int(np.argmax(_participation(v, M, X[:n]) * ok + ok * 1e-300))
    nu, x, done = _block_inverse(apply, Z0, pick)
    # The block converges to the roots nearest sigma. If the mode's own root is not among
    # them (a close root nearer the estimate and no partner in the block), the best Ritz
    # vector belongs to another mode. The participations of a mode in all roots sum to 1
    # (M-orthonormal vectors, nearly so for the viscous roots), so one above 1/2 is the
    # largest; below it, ARPACK's 8 nearest roots are searched.
    if not done or _participation(v, M, x[:n, None])[0] < 0.5:
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
