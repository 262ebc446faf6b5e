"""Members as finite elements (effects.structure: flexible): trusses and beams.

A member is a chain of nodes; each node-to-node piece of a beam is divided into
``elements`` beam elements with interior nodes (translations and rotations). Trusses are
one element per piece and act like springs (one elongation row, stiffness EA/l).
"""

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class MemberMesh:
    coords: np.ndarray        # (ni, 3) interior nodes of subdivided beams
    names: tuple              # (ni,)
    # elements (ne,)
    member: np.ndarray        # index in model.members
    beam: np.ndarray          # bool: beam (else truss)
    node: np.ndarray          # (ne, 2) expanded node indices (offset applied by caller)
    E: np.ndarray
    G: np.ndarray
    A: np.ndarray
    Iy: np.ndarray
    Iz: np.ndarray
    J: np.ndarray
    rho: np.ndarray
    lumped: np.ndarray        # bool
    psi: np.ndarray
    orientation: np.ndarray   # (ne, 3)

    @property
    def n_interior(self):
        return len(self.coords)

    def rotation_nodes(self):
        """Nodes (expanded indices) where beams meet: they carry rotations."""
        return np.unique(self.node[self.beam].ravel())


def discretize(model, first_node):
    """MemberMesh of the model's members; interior nodes are numbered from first_node."""
    coords, names = [], []
    el = {k: [] for k in ("member", "beam", "node", "E", "G", "A", "Iy", "Iz", "J", "rho",
                          "lumped", "psi", "orientation")}
    for mi, m in enumerate(model.members):
        beam = m.type == "beam"
        n = m.elements if beam else 1
        for a, b in zip(m.nodes[:-1], m.nodes[1:]):
            pa, pb = model.coords[a], model.coords[b]
            e = (pb - pa) / np.linalg.norm(pb - pa)
            if m.orientation is not None:
                orient = m.orientation
            elif model.planar:                 # local y = global y: bending in x-z uses Iy
                orient = np.cross(e, [0.0, 1.0, 0.0])
            else:
                orient = np.zeros(3)           # trusses need none
            chain = [a]
            for j in range(1, n):
                chain.append(first_node + len(coords))
                coords.append(pa + (pb - pa) * j / n)
                names.append(f"{m.name} {model.node_names[a]}-{model.node_names[b]} {j}")
            chain.append(b)
            for j in range(n):
                for key, val in (("member", mi), ("beam", beam),
                                 ("node", (chain[j], chain[j + 1])), ("E", m.E),
                                 ("G", m.G), ("A", m.A), ("Iy", m.Iy), ("Iz", m.Iz),
                                 ("J", m.J), ("rho", m.rho),
                                 ("lumped", m.mass == "lumped"), ("psi", m.psi),
                                 ("orientation", orient)):
                    el[key].append(val)
    arr = {k: np.array(v) for k, v in el.items()}
    arr["node"] = arr["node"].astype(int).reshape(-1, 2)
    arr["orientation"] = arr["orientation"].astype(float).reshape(-1, 3)
    arr["member"] = arr["member"].astype(int)
    for k in ("beam", "lumped"):
        arr[k] = arr[k].astype(bool)
    for k in ("E", "G", "A", "Iy", "Iz", "J", "rho", "psi"):
        arr[k] = arr[k].astype(float)
    return MemberMesh(np.array(coords, dtype=float).reshape(-1, 3), tuple(names), **arr)
