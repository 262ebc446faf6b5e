"""The stiffness as element factors, K = F^T diag(s) F, never formed (docs/theory.md,
"The graded factor").

Spring-like rows give `sqrt(c_e) r_e T` (K = R^T diag(c) R, Heletiy 2016 eq. 5); every
element block (beams, tension and load stiffness) gives `sqrt(|w_j|) v_j^T` from its own
eigen-decomposition, with the sign of w_j in s. The factor serves two purposes:

- `graded_eigen`: the frequencies of a graded problem as singular values of
  `G = F1 L_A^-T` (preconditioned one-sided Jacobi SVD, LAPACK dgejsv with full
  pivoting), with relative accuracy whatever the stiffness contrasts between elements,
  the order of the coordinates or where the stiff element sits (Demmel and Veselic 1992;
  Drmac and Veselic 2008). The assembled K already carries the cancellation: a link of
  1e12 N/m next to a rope of 1 N/m keeps only 4 digits of the rope in K_ii = 1e12 + 1.
- `element_energy`: the stiffness a mode meets element by element, to decide when a
  computed w^2 is zero to round-off (a mechanism whose positive and negative tension
  stiffnesses cancel).
"""

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

NULL_BLOCK = 1e-10     # relative eigenvalue of a Jacobi-scaled element block: a null motion
ROUNDOFF = 1e-12       # |w^2| below this part of the element terms a mode meets: zero
UNDEFORMED = 1e-10     # an element row with |r.u| below this part of |r| |u| does not deform


@dataclass(frozen=True)
class ElementFactor:
    """K = F^T diag(sign) F in generalised coordinates, F = Fu T."""

    Fu: sp.csr_matrix         # (rows, n_u) element rows in primitive coordinates
    T: sp.csr_matrix          # (n_u, n) u = T q
    sign: np.ndarray          # (rows,) +1 or -1
    indefinite: tuple         # names of the element kinds with negative rows

    @cached_property
    def F(self):
        return (self.Fu @ self.T).tocsr()

    def spread(self):
        """Largest over smallest squared row norm: the stiffness contrast of elements."""
        s2 = np.asarray(self.F.multiply(self.F).sum(axis=1)).ravel()
        s2 = s2[s2 > 0]
        return s2.max() / s2.min() if len(s2) else 1.0


def _block_rows(blocks):
    """Rows (k, size) and signs of Blocks: each element's eigen-decomposition after Jacobi
    scaling (rotations and translations alike), its null motions dropped."""
    mat, idx = blocks.mat, blocks.idx
    d = np.abs(np.einsum("kii->ki", mat))
    s = np.where(d > 0, np.sqrt(np.where(d > 0, d, 1.0)), 1.0)       # D^1/2
    w, v = np.linalg.eigh(mat / (s[:, :, None] * s[:, None, :]))
    top = np.abs(w).max(axis=1, keepdims=True)
    keep = np.abs(w) > NULL_BLOCK * np.where(top > 0, top, 1.0)
    # K_e = D^1/2 V diag(w) V^T D^1/2: row j is sqrt(|w_j|) (D^1/2 v_j)^T
    rows = np.sqrt(np.abs(w))[:, None, :] * s[:, :, None] * v          # (ne, k, j)
    e, j = np.nonzero(keep)
    vals = rows[e, :, j]                                               # (r, k)
    cols = idx[e]
    r = np.repeat(np.arange(len(e)), idx.shape[1])
    return (r, cols.ravel(), vals.ravel(), len(e)), np.sign(w[e, j])


def element_factor(system):
    """`ElementFactor` of an assembled `System` (primitive element data mapped by T)."""
    s = system.springs
    on = s.c != 0
    parts = [sp.diags(np.sqrt(np.abs(s.c[on]))) @ s.R[on]]
    signs = [np.sign(s.c[on])]
    kinds = [("beam elastic stiffness", system.beams)] if system.beams is not None else []
    kinds += [("tension and load stiffness", g) for g in system.geometric]
    indefinite = []
    n_u = s.R.shape[1]
    for name, blocks in kinds:
        if not len(blocks.mat):
            continue
        (r, c, v, m), sg = _block_rows(blocks)
        parts.append(sp.coo_matrix((v, (r, c)), shape=(m, n_u)).tocsr())
        signs.append(sg)
        if np.any(sg < 0) and name not in indefinite:
            indefinite.append(name)
    return ElementFactor(sp.vstack(parts).tocsr(), system.dofs.T.tocsr(),
                         np.concatenate(signs), tuple(indefinite))


def element_energy(factor, shapes):
    """Per mode (columns of `shapes`, (n, m)): w^2 = y^T K y summed element row by row,
    and whether it is zero to round-off: the rows cancel (|w^2| <= ROUNDOFF sum of
    |row energies|, e.g. tension stiffness against the load stiffness of a body), or no
    row is deformed beyond UNDEFORMED of |row|_1 max|u| (a drum turning a hook along its
    vertical rope: every r.u is round-off of the constraint map T, the motion is free).
    -> (w2 (m,), zero (m,) bool)"""
    u = np.asarray(factor.T @ shapes)
    E = np.asarray(factor.Fu @ u)
    A = np.asarray(abs(factor.Fu).sum(axis=1)).ravel()[:, None] * np.abs(u).max(axis=0)
    E2 = E * E
    w2 = factor.sign @ E2
    cancel = np.abs(w2) <= ROUNDOFF * E2.sum(axis=0)
    still = np.all(E2 <= UNDEFORMED**2 * A * A, axis=0)
    return w2, cancel | still


def _massless_condensed(F, a, b):
    """Rows of F* with K* = K_aa - K_ab K_bb^-1 K_ba = F*^T F* (F positive rows only).

    With F = [F_a F_b], K* = F_a^T (I - P_b) F_a, P_b the projector on range(F_b): the
    rows of Q^T F_a below the first nb, Q from Householder QR of F_b with the rows sorted
    by decreasing size and column pivoting, which is row-wise backward stable for graded
    rows (Cox and Higham 1998)."""
    if not len(b):
        return F[:, a]
    Fb = F[:, b]
    order = np.argsort(-np.abs(Fb).max(axis=1), kind="stable")
    (qr, tau) = sla.qr(Fb[order], pivoting=True, mode="raw")[0]
    Fa = F[np.ix_(order, a)]
    ormqr = sla.get_lapack_funcs("ormqr", (qr,))
    lwork = max(1, Fa.shape[1]) * 64
    out, _, info = ormqr("L", "T", qr, tau, Fa, lwork)
    if info != 0:
        raise np.linalg.LinAlgError(f"ormqr info {info}")
    return out[len(b):]


def _psd_rows(K):
    """Rows F (r, k) with K = F^T F of a symmetric (k, k) matrix, or None if K has a
    negative eigenvalue beyond NULL_BLOCK (Jacobi-scaled, as `_block_rows`)."""
    d = np.abs(np.diag(K))
    s = np.where(d > 0, np.sqrt(np.where(d > 0, d, 1.0)), 1.0)
    w, v = np.linalg.eigh(K / np.outer(s, s))
    top = max(np.abs(w).max(initial=0.0), 1e-300)
    if w.min(initial=0.0) < -NULL_BLOCK * top:
        return None
    keep = w > NULL_BLOCK * top
    return np.sqrt(w[keep])[:, None] * (s[:, None] * v[:, keep]).T


def _merge_negative(F, sign, grow=3):
    """F (rows, n) with its negative rows merged into positive ones, or None.

    The negative rows (a body's load stiffness on its rotations, a compressed beam) are
    summed with the positive rows that share coordinates with them, K_loc = sum s_e
    F_e^T F_e over that local set, grown by one ring of rows at a time until K_loc is
    positive semi-definite; K_loc is then factorised on its own (`_psd_rows`). Only the
    rows of the set are added together, so the contrasts between elements elsewhere
    stay in separate rows. None when the set would grow to all rows (that is assembling
    K) or stays indefinite."""
    rows = sign < 0
    for _ in range(grow):
        rows = rows | np.any(F[:, np.any(F[rows] != 0, axis=0)] != 0, axis=1)
        if rows.all():
            return None
        cols = np.flatnonzero(np.any(F[rows] != 0, axis=0))
        local = F[np.ix_(rows, cols)]
        new = _psd_rows(local.T @ (local * sign[rows, None]))
        if new is not None:
            merged = np.zeros((len(new), F.shape[1]))
            merged[:, cols] = new
            return np.vstack([F[~rows], merged])
    return None


def graded_eigen(factor, massless, kept_in_a, a, A1, E=None):
    """Eigenpairs (lam, Y) of the condensed pair (K1, A1) from the element factor, or
    None with the reason when it cannot be used.

    K1 = F1^T F1 with F1 = F*[:, p] (quasi-cyclic coordinates removed: K1 = K*_pp,
    docs/theory.md section 8), A1 = L L^T; then L^-1 K1 L^-T = G^T G with
    G = F1 L^-T, so w_i are the singular values of G and y = L^-T v_i (v_i its right
    singular vectors): A1-normalised. G is graded by rows (one per element); dgejsv with
    JOBA='F' (full pivoting: rows sorted, QR with column pivoting, then one-sided Jacobi)
    gives each singular value to a relative error of order eps times the condition of
    G with its rows scaled, whatever the row scaling (Drmac and Veselic 2008, sec. 2).
    """
    F = factor.F.toarray()
    how = "element factor, Jacobi SVD"
    if factor.indefinite:
        F = _merge_negative(F, factor.sign)
        if F is None:
            return None, ("the element factor has negative parts (" + ", ".join(
                factor.indefinite) + ", e.g. a compressed member or a body above its "
                "hinge) that the elements around them do not outweigh: graded factor not "
                "used, assembled K factorised instead")
        how = ("element factor (negative parts of " + ", ".join(factor.indefinite) +
               " merged with the elements sharing their coordinates), Jacobi SVD")
    if E is not None:                  # massless motions as coordinates (condense.py)
        F = F @ E
    F = F[np.any(F != 0, axis=1)]
    F1 = _massless_condensed(F, a, massless)[:, kept_in_a]
    n = F1.shape[1]
    if F1.shape[0] < n:
        return None, "fewer element rows than coordinates: assembled K factorised instead"
    try:
        L = np.linalg.cholesky(A1)
    except np.linalg.LinAlgError:
        return None, "the condensed inertia is not positive definite"
    G = sla.solve_triangular(L, F1.T, lower=True).T                 # F1 L^-T, row by row
    from scipy.linalg.lapack import dgejsv
    # joba=2 'F' (full pivoting), jobu=3 'N', jobv=0 'V', jobr=0 'N', jobt=0, jobp=0
    sva, _, V, work, _, info = dgejsv(G, joba=2, jobu=3, jobv=0, jobr=0, jobt=0, jobp=0)
    if info != 0:
        return None, f"Jacobi SVD failed (dgejsv info {info})"
    lam = (sva * (work[0] / work[1])) ** 2
    order = np.argsort(lam)
    Y = sla.solve_triangular(L, V[:, order], lower=True, trans="T")
    return (lam[order], Y), how
