"""The crane as a line mesh: points (nodes and body centres of mass) and line cells
(rope spans, body edges, springs, members, linear drives), with mode displacements at
every point. Used by the VTU/XDMF writers, the images and the archive."""

from dataclasses import dataclass

import numpy as np

KINDS = ("rope", "body", "spring", "member", "drive")


@dataclass(frozen=True)
class LineMesh:
    points: np.ndarray        # (np, 3): the model's nodes, then one point per body com
    point_names: tuple        # (np,)
    lines: np.ndarray         # (nl, 2) point indices
    kind: np.ndarray          # (nl,) index into KINDS
    element: tuple            # (nl,) "rope hoist", "body jib", ...


def line_mesh(model, dofs=None):
    """The line mesh; with `dofs`, ropes with mass and subdivided members run through
    their interior nodes (which follow the model's nodes in the point list)."""
    rm = dofs.ropes if dofs is not None else None
    mm = dofs.members if dofs is not None else None
    coords = dofs.coords if dofs is not None else model.coords
    nn = len(coords)
    points = [coords] + [b.com[None] for b in model.bodies]
    names = list(model.node_names) + (list(rm.names) if rm is not None else []) + \
        (list(mm.names) if mm is not None else []) + [f"{b.name} (com)" for b in model.bodies]
    lines, kind, element = [], [], []

    def add(a, b, k, name):
        if a != b:
            lines.append((a, b))
            kind.append(KINDS.index(k))
            element.append(name)

    fe = set(rm.ropes) if rm is not None else set()
    for k, r in enumerate(model.ropes):
        pairs = zip(rm.node[rm.rope == k, 0], rm.node[rm.rope == k, 1]) if k in fe \
            else zip(r.span_a, r.span_b)
        for a, b in sorted({tuple(sorted(p)) for p in pairs}):
            add(int(a), int(b), "rope", f"rope {r.name}")
    for k, body in enumerate(model.bodies):
        for i in body.nodes:        # a star from the centre of mass to each node
            add(nn + k, int(i), "body", f"body {body.name}")
    for s in model.springs:
        if s.type == "axial":
            add(*s.nodes, "spring", f"spring {s.name}")
    if mm is not None:
        for (a, b), k in zip(mm.node, mm.member):
            add(int(a), int(b), "member", f"member {model.members[k].name}")
    else:
        from ..coordinates.members import member_pairs
        for m in model.members:
            for a, b in member_pairs(m):
                add(int(a), int(b), "member", f"member {m.name}")
    for d in model.linear_drives:
        add(*d.nodes, "drive", f"drive {d.name}")
    return LineMesh(np.vstack(points), tuple(names),
                    np.array(lines, dtype=int).reshape(-1, 2), np.array(kind, dtype=int),
                    tuple(element))


def point_displacements(dofs, shapes):
    """(m, np, 3) displacements of the mesh points for q-space shapes (n, m)."""
    layout = dofs.layout
    nodes = dofs.T[layout.translations()] @ shapes
    body_rows = (layout.body0 + 6 * np.arange(layout.n_bodies)[:, None]
                 + np.arange(3)).ravel()
    coms = dofs.T[body_rows] @ shapes
    m = shapes.shape[1]
    return np.concatenate([nodes.T.reshape(m, -1, 3), coms.T.reshape(m, -1, 3)], axis=1)
