"""Condensation: massless coordinates (static) and quasi-cyclic coordinates (inertial).

Both return the reduced matrices and what recovers full vectors (style: "constraints
are one transform"). Formulas in docs/theory.md:

- massless coordinates b (zero inertia): K* = K_aa - K_ab K_bb^-1 K_ba, q_b = -K_bb^-1 K_ba q_a;
- quasi-cyclic coordinates: with the null space N of K and chosen coordinates c
  (N_c nonsingular), q = T' [y1; y2] with q_p = y1 + N_p N_c^-1 y2, q_c = y2 turns K into
  [[K_pp, 0], [0, 0]]; then A1 = A'11 - A'12 A'22^-1 A'21 (Heletiy 2016, eq. 7-8) or,
  one coordinate at a time, a1_ij = a_ij - a_in a_nj / a_nn (eq. 9).
"""

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from .assembly import null_space
from .assembly.pattern import NULL_TOL
from .coordinates import entry_of
from .errors import ModelError

DENSE_MAX = 1500       # up to this many coordinates the dense eigen-solution is used


@dataclass(frozen=True)
class Condensed:
    """Positive-definite positional problem K1 y1'' ... and its recovery to q."""

    K: np.ndarray             # (np, np) positional stiffness (C1 = C11)
    M: np.ndarray             # (np, np) condensed inertia A1
    recover: np.ndarray       # (n, np) q = recover @ y1 (momentum-free, massless solved)
    rigid: np.ndarray         # (n, k) quasi-cyclic motions, mass-normalised
    quasi_cyclic: tuple       # labels of the chosen quasi-cyclic coordinates
    massless: tuple           # labels of the statically condensed coordinates
    warnings: tuple = ()
    inertial: np.ndarray = None   # (na,) coordinates with inertia (a), indices into q
    positional: np.ndarray = None  # (np,) y1 = q_a[positional] (quasi-cyclic ones removed)
    massless_map: np.ndarray = None  # (n, n) E of `massless_motions`, None if identity


def no_inertia(model):
    return ModelError("nothing that moves has inertia, so there is nothing to vibrate; give "
                      "a node a mass (masses:) or a body a mass", model.file)


def massless_split(M):
    """Indices (a, b) of coordinates with and without inertia (exact zero diagonal)."""
    d = M.diagonal()
    return np.flatnonzero(d > 0), np.flatnonzero(d <= 0)


def massless_motions(M, kinds):
    """(a, b, E): coordinates with inertia, massless ones, and E (n, n) or None.

    The massless motions are the null space of M. Usually they are coordinates (a zero
    diagonal: a massless node, a body rotation with zero inertia about its centre of
    mass) and E is None. A massless body carrying a point mass off its centre has a
    massless rotation about that point instead, a combination of coordinates: then
    q = E [q_a; s] with E[:, b] = Z Z_b^-1 (Z the null space, b coordinates chosen as
    for quasi-cyclic motions), so that E^T M E has zero rows and columns b and s is
    condensed statically like a massless node (docs/theory.md section 6).
    """
    a, b = massless_split(M)
    if not len(a):
        return a, b, None
    Ma = M[np.ix_(a, a)]
    try:               # positive definite: every Cholesky pivot a fair part of M_ii
        if np.min(np.diag(np.linalg.cholesky(Ma)) ** 2 / np.diag(Ma)) > NULL_TOL:
            return a, b, None
    except np.linalg.LinAlgError:
        pass
    Z = null_space(M)
    b = choose_quasi_cyclic(Z, kinds)
    E = np.eye(len(M))
    E[:, b] = Z @ np.linalg.inv(Z[b])
    return np.setdiff1d(np.arange(len(M)), b), b, E


def check_mechanisms(N, M, labels, model):
    """Raise if a stiffness-free motion has no inertia either (massless mechanism)."""
    if not N.shape[1]:
        return
    MN = N.T @ (M @ N)
    w, z = np.linalg.eigh(MN)
    scale = np.abs(np.diag(MN)).max() if MN.size else 1.0
    bad = w <= 1e-12 * max(scale, 1e-300)
    if bad.any():
        v = N @ z[:, np.argmax(bad)]
        top = np.argsort(-np.abs(v))
        names = [labels[i] for i in top[:4] if abs(v[i]) > 0.05 * abs(v).max()]
        raise ModelError(
            f"massless and unrestrained: {', '.join(names)} can move with no stiffness and "
            "no inertia; attach a rope or spring in that direction, give it mass, or add it "
            "to ground", model.file, entry_of(names[0]))


def choose_quasi_cyclic(N, kinds):
    """Coordinates c (k,) that parametrise the null space N (n, k): pivoted QR on N^T.

    Drum rotations are preferred, then body coordinates, as the seed chooses the drum
    angle; any choice with N_c nonsingular gives the same frequencies.
    """
    weight = np.array([{"drum": 4.0, "body": 2.0}.get(k, 1.0) for k in kinds])
    _, _, piv = sla.qr((N * weight[:, None]).T, pivoting=True, mode="economic")
    return np.sort(piv[:N.shape[1]])


def schur(A, c):
    """Heletiy (2016) eq. 8: A1 = A11 - A12 A22^-1 A21 for the coordinates c removed."""
    p = np.setdiff1d(np.arange(len(A)), c)
    A12 = A[np.ix_(p, c)]
    return A[np.ix_(p, p)] - A12 @ np.linalg.solve(A[np.ix_(c, c)], A12.T)


def sequential(A, c):
    """Heletiy (2016) eq. 9 applied once per coordinate: a_ij - a_in a_nj / a_nn."""
    A = np.array(A, dtype=float)
    keep = np.ones(len(A), dtype=bool)
    for n in c:
        A = A - np.outer(A[:, n], A[n, :]) / A[n, n]
        keep[n] = False
    return A[np.ix_(keep, keep)]


def condense(system, method="schur"):
    """Dense condensation of an assembled `System` -> `Condensed`."""
    K = system.K.toarray()
    M = system.M.toarray()
    labels, kinds = system.dofs.labels, system.dofs.kinds
    n = len(K)
    N = null_space(system.K_pattern.toarray())
    check_mechanisms(N, M, labels, system.model)
    K0, M0, N0 = K, M, N
    a, b, E = massless_motions(M, kinds)
    if not len(a):
        raise no_inertia(system.model)
    if E is not None:                # massless motions as coordinates s: q = E [q_a; s]
        K, M, N = E.T @ K @ E, E.T @ M @ E, np.linalg.solve(E, N)
        M[b, :] = 0.0
        M[:, b] = 0.0

    # massless: q_b = -K_bb^-1 K_ba q_a
    rec_b = -np.linalg.solve(K[np.ix_(b, b)], K[np.ix_(b, a)]) if len(b) else \
        np.zeros((0, len(a)))
    Ks = K[np.ix_(a, a)] + K[np.ix_(a, b)] @ rec_b
    Ma = M[np.ix_(a, a)]

    # quasi-cyclic: null space restricted to a (full column rank: no massless mechanism)
    Na = N[a]
    c = choose_quasi_cyclic(Na, [kinds[i] for i in a]) if Na.shape[1] else np.zeros(0, int)
    p = np.setdiff1d(np.arange(len(a)), c)
    W = Na[p] @ np.linalg.inv(Na[c]) if len(c) else np.zeros((len(p), 0))
    Tq = np.zeros((len(a), len(a)))                  # q_a = Tq [y1; y2]
    Tq[p, :len(p)] = np.eye(len(p))
    Tq[np.ix_(p, len(p) + np.arange(len(c)))] = W
    Tq[np.ix_(c, len(p) + np.arange(len(c)))] = np.eye(len(c))
    A = Tq.T @ Ma @ Tq
    cc = len(p) + np.arange(len(c))
    A1 = schur(A, cc) if method == "schur" else sequential(A, cc)
    # y2 = -A22^-1 A21 y1 (no rigid-body momentum), eq. 5 of the seed with F = 0
    y2 = -np.linalg.solve(A[np.ix_(cc, cc)], A[np.ix_(cc, np.arange(len(p)))]) if len(c) \
        else np.zeros((0, len(p)))
    rec_a = Tq @ np.vstack([np.eye(len(p)), y2])
    recover = np.zeros((n, len(p)))
    recover[a] = rec_a
    recover[b] = rec_b @ rec_a
    if E is not None:
        recover = E @ recover
    K1 = Ks[np.ix_(p, p)]

    K, M, N = K0, M0, N0
    rigid, warnings = N, []
    if N.shape[1]:
        L = np.linalg.cholesky(N.T @ M @ N)
        rigid = np.linalg.solve(L, N.T).T            # N L^-T: rigid^T M rigid = I
        # a motion the elements resist by less than the resolution of the pattern
        # (NULL_TOL) is treated as free; say so when K itself still sees it
        w2 = np.einsum("ij,ij->j", rigid, K @ rigid)
        # relative to the stiffness the motion meets on the diagonal: round-off gives
        # ~1e-20, a weak restraint below the pattern's resolution (1e-10) far more
        touched = np.einsum("ij,ij->j", rigid, np.abs(np.diag(K))[:, None] * rigid)
        weak = w2 > 1e-15 * np.maximum(touched, 1e-300)
        for k in np.flatnonzero(weak):
            v = np.abs(rigid[:, k])
            names = ", ".join(labels[i] for i in np.argsort(-v)[:2])
            warnings.append(f"{names}: nearly unrestrained (its stiffness is below 1e-10 of "
                            "its elements'), treated as free; its true frequency is about "
                            f"{np.sqrt(max(w2[k], 0.0)):.3g} rad/s")
    return Condensed(0.5 * (K1 + K1.T), 0.5 * (A1 + A1.T), recover, rigid,
                     tuple(labels[a[i]] for i in c), tuple(labels[i] for i in b),
                     tuple(warnings), a, p, E)
