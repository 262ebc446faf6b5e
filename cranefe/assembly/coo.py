"""The one COO assembly step: element arrays on primitive indices -> sparse matrices."""

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp


@dataclass(frozen=True)
class Blocks:
    """Element matrices mat (ne, k, k) on primitive indices idx (ne, k)."""

    idx: np.ndarray
    mat: np.ndarray

    def unit_abs(self):
        """Each block replaced by its matrix absolute value V |L| V^T scaled to unit size."""
        w, v = np.linalg.eigh(self.mat)
        top = np.abs(w).max(axis=1)
        scaled = np.abs(w) / np.where(top > 0, top, 1)[:, None]
        return Blocks(self.idx, np.einsum("kij,kj,klj->kil", v, scaled, v))


class Triplets:
    """Rows, columns and values gathered from several element kinds, assembled once."""

    def __init__(self):
        self.rows, self.cols, self.vals = [], [], []

    def add(self, rows, cols, vals):
        self.rows.append(np.ravel(rows))
        self.cols.append(np.ravel(cols))
        self.vals.append(np.ravel(vals))

    def add_blocks(self, idx, mat):
        """Square blocks mat (ne, k, k) on indices idx (ne, k)."""
        idx = np.asarray(idx)
        k = idx.shape[-1]
        self.add(np.repeat(idx, k, axis=-1), np.tile(idx, (1,) * (idx.ndim - 1) + (k,)),
                 mat)

    def csr(self, shape):
        return coo(self.rows, self.cols, self.vals, shape)


def coo(rows, cols, vals, shape):
    """One COO -> CSR conversion of lists of index and value arrays (duplicates summed)."""
    if not rows:
        return sp.csr_matrix(shape)
    return sp.coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=shape).tocsr()


def sum_blocks(blocks, size):
    """One COO assembly of several Blocks -> CSR (size, size)."""
    t = Triplets()
    for b in blocks:
        t.add_blocks(b.idx, b.mat)
    return t.csr((size, size))
