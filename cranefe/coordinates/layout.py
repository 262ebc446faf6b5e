"""Primitive coordinates: where each node, body, drum and rope slip has its entries."""

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Layout:
    """Primitive coordinate offsets: six per node (translations, then rotations, which
    exist only where beams meet), six per body, one per drum, one per rope slip."""

    n_nodes: int             # model nodes, then interior rope nodes
    n_bodies: int
    n_drums: int
    n_slips: int = 0         # rope slip coordinates (sheave passes of ropes with mass)

    @property
    def body0(self):
        return 6 * self.n_nodes

    @property
    def drum0(self):
        return 6 * self.n_nodes + 6 * self.n_bodies

    @property
    def size(self):
        return self.drum0 + self.n_drums + self.n_slips

    def node(self, i):
        """(k, 3) translation indices of nodes i."""
        return 6 * np.asarray(i)[..., None] + np.arange(3)

    def rot(self, i):
        """(k, 3) rotation indices of nodes i."""
        return 6 * np.asarray(i)[..., None] + 3 + np.arange(3)

    def translations(self, n=None):
        """Translation indices of the first n nodes (all), node-major: (3 n,)."""
        return self.node(np.arange(self.n_nodes if n is None else n)).ravel()

    def body(self, b):
        return self.body0 + 6 * np.asarray(b)[..., None] + np.arange(6)

    def drum(self, d):
        return self.drum0 + np.asarray(d)

    def slip(self, k):
        return self.drum0 + self.n_drums + np.asarray(k)
