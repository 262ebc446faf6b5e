"""Modal level: the decoupled estimate (Heletiy 2016, eq. 14-17, corrected) and
Hasselman's coupling coefficients with the predicted error of the estimate."""

from typing import NamedTuple

import numpy as np
import scipy.sparse as sp


from .constants import UNDAMPED
from .element import psi_stiffness


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
