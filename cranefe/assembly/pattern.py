"""The pattern matrix and its null space: which motions no element resists.

The pattern is the sum of the element matrices each scaled to unit size: positive
semi-definite with the null space of K but none of its stiffness contrasts.
"""

import numpy as np
import scipy.sparse as sp

from .coo import sum_blocks

NULL_TOL = 1e-10       # relative eigenvalue of the unit-scaled pattern matrix


def pattern(springs, dofs, elastic_blocks=(), geometric=()):
    """Sum of element matrices each scaled to unit size, in generalised coordinates."""
    R = springs.R
    norms = np.sqrt(np.asarray(R.multiply(R).sum(axis=1)).ravel())
    Rn = sp.diags(np.where((norms > 0) & (springs.c != 0), 1 / np.where(norms > 0, norms, 1),
                           0.0)) @ R
    P = Rn.T @ Rn
    blocks = [b.unit_abs() for b in (*elastic_blocks, *geometric)]
    if blocks:
        P = P + sum_blocks(blocks, R.shape[1])
    T = dofs.T
    return (T.T @ P @ T).tocsr()


def null_space(P, tol=NULL_TOL):
    """Null space (n, k) of a PSD pattern matrix (dense).

    Jacobi scaling removes the contrast between rotations and translations. Columns are
    orthonormal in the scaled metric, mapped back and normalised to unit max-norm.
    """
    d = np.diag(P).copy()
    untouched = d <= 0
    s = 1 / np.sqrt(np.where(untouched, 1.0, d))
    S = s[:, None] * P * s[None, :]
    w, v = np.linalg.eigh(S)
    top = max(w[-1], 1.0) if len(w) else 1.0
    N = s[:, None] * v[:, w < tol * top]
    if N.shape[1]:
        N = N / np.abs(N).max(axis=0)
    return N
