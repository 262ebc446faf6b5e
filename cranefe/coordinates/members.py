"""Members as finite elements (effects.structure: flexible): trusses and beams.

A member is a chain of nodes; each node-to-node piece of a beam is divided into
``elements`` beam elements with interior nodes (translations and rotations). Trusses are
one element per piece and act like springs (one elongation row, stiffness EA/l).
"""

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class MemberMesh:
    """The elements of the members: structure only (their sections: `element_sections`)."""

    coords: np.ndarray        # (ni, 3) interior nodes of subdivided beams
    names: tuple              # (ni,)
    # elements (ne,)
    member: np.ndarray        # index in model.members
    beam: np.ndarray          # bool: beam (else truss)
    node: np.ndarray          # (ne, 2) expanded node indices (offset applied by caller)
    orientation: np.ndarray   # (ne, 3)
    pinned: np.ndarray = None  # (ne, 2) bool: end with every rotation released

    @property
    def n_interior(self):
        return len(self.coords)

    def rotation_nodes(self):
        """Nodes (expanded indices) where beams meet: they carry rotations, unless every
        beam end there is pinned (its rotations released: they would have no stiffness)."""
        ends = self.node[self.beam]
        if self.pinned is not None:
            ends = ends[~self.pinned[self.beam]]
        return np.unique(ends.ravel())


def discretize(model, first_node):
    """MemberMesh of the model's members; interior nodes are numbered from first_node.

    Vectorised per member (a lattice of 1e5 bars is one or a few members)."""
    coords, names = [], []
    parts = {k: [] for k in ("member", "beam", "node", "orientation")}
    n_new = 0
    for mi, m in enumerate(model.members):
        beam = m.type == "beam"
        pairs = member_pairs(m)
        pa, pb = model.coords[pairs[:, 0]], model.coords[pairs[:, 1]]
        e = (pb - pa) / np.linalg.norm(pb - pa, axis=1)[:, None]
        if m.orientation is not None:
            orient = np.broadcast_to(m.orientation, e.shape)
        elif model.planar:                    # local y = global y: bending in x-z uses Iy
            orient = np.cross(e, [0.0, 1.0, 0.0])
        else:
            orient = np.zeros_like(e)         # trusses need none
        n = m.elements if beam else 1
        if n == 1:
            nodes = pairs
        else:                                 # interior nodes j = 1..n-1 of every piece
            j = np.arange(1, n)
            inner = pa[:, None, :] + (pb - pa)[:, None, :] * (j / n)[None, :, None]
            ids = first_node + n_new + np.arange(len(pairs) * (n - 1)).reshape(-1, n - 1)
            coords.append(inner.reshape(-1, 3))
            names += [f"{m.name} {model.node_names[a]}-{model.node_names[b]} {k}"
                      for a, b in pairs for k in j]
            n_new += ids.size
            chain = np.hstack([pairs[:, :1], ids, pairs[:, 1:]])
            nodes = np.stack([chain[:, :-1], chain[:, 1:]], axis=-1).reshape(-1, 2)
            orient = np.repeat(orient, n, axis=0)
        ne = len(nodes)
        parts["member"].append(np.full(ne, mi))
        parts["beam"].append(np.full(ne, beam))
        parts["node"].append(nodes)
        parts["orientation"].append(np.asarray(orient, dtype=float))
    cat = {k: (np.concatenate(v) if v else np.zeros(0)) for k, v in parts.items()}
    cat["node"] = cat["node"].astype(int).reshape(-1, 2)
    cat["orientation"] = cat["orientation"].reshape(-1, 3)
    cat["member"] = cat["member"].astype(int)
    cat["beam"] = cat["beam"].astype(bool)
    return MemberMesh(np.vstack(coords) if coords else np.zeros((0, 3)), tuple(names), **cat,
                      pinned=_pinned_ends(model, cat["member"], cat["node"]))


def _pinned_ends(model, member, node):
    """(ne, 2) bool: element ends where their member releases every rotation (ry in a
    plane), from the members' `releases`."""
    pinned = np.zeros(node.shape, dtype=bool)
    for mi, m in enumerate(model.members):
        for i, comps in getattr(m, "releases", ()):
            if set(comps) >= ({1} if model.planar else {0, 1, 2}):
                pinned |= (member == mi)[:, None] & (node == i)
    return pinned


def member_pairs(member):
    """(k, 2) node pairs of a member: its chain's consecutive nodes, or its pairs."""
    pairs = getattr(member, "pairs", None)
    if pairs is not None and len(pairs):
        return np.asarray(pairs, dtype=int).reshape(-1, 2)
    chain = np.asarray(member.nodes, dtype=int)
    return np.stack([chain[:-1], chain[1:]], axis=1)
