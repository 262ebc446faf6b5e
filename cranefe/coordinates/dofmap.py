"""Degrees of freedom for the effects that are on, and the one constraint transform.

Two spaces (docs/theory.md, "Coordinates"):

- *primitive* coordinates u, always 3D: three translations per node, six per body
  (translation of its centre of mass and rotation vector), one rotation per drum;
  element kernels are written in them;
- *generalised* coordinates q: what actually moves. Bodies joined by fixed joints move as
  one rigid group (6 coordinates, 3 in a plane: ux, uz, ry); a node is carried by its
  body, fixed (ground), or has its own translations (only those its elastic elements
  resist when sway is off); a drum turns only when coupled and unbraked.

``u = T q`` with ``T = T_map @ T_c``: T_map is the rigid/planar kinematics, T_c the
master-slave elimination of joint, linear-drive and inextensible-rope constraints
``G q_map = 0`` (QR with column pivoting, so redundant constraints of closed loops are
handled).
"""

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..elements import skew, span_geometry
from ..model import GROUND
from .constraints import _constraint_rows, _eliminate
from .key import VALUE_ONLY, structure_key  # noqa: F401 (part of this stage's interface)
from .layout import Layout

PLANAR_COMPONENTS = (0, 2, 4)       # ux, uz, ry of (ux, uy, uz, rx, ry, rz)
AXES = ("x", "y", "z")
COMP_NAMES = ("ux", "uy", "uz", "rx", "ry", "rz")


@dataclass(frozen=True)
class DofMap:
    """Generalised coordinates and the transform from them to primitive ones."""

    layout: Layout
    T: sp.csr_matrix          # (n_primitive, n): u = T q
    T_map: sp.csr_matrix      # (n_primitive, n_map): kinematics before constraints
    T_c: sp.csr_matrix        # (n_map, n): constraint elimination
    labels: tuple             # (n,) names of the generalised coordinates
    kinds: tuple              # (n,) 'body' | 'node' | 'drum'
    group_of_body: np.ndarray  # (nb,) rigid group index or GROUND
    group_ref: np.ndarray     # (ng, 3) reference point of each group
    group_q: np.ndarray       # (ng, 6) q_map index of each of the 6 components, -1 absent
    carrier: np.ndarray       # (nn,) group carrying each node, GROUND, or -2 = own DOFs
    constraints: tuple        # ConstraintRows used in T_c
    coords: np.ndarray        # (nn, 3) model nodes, interior rope nodes, member nodes
    ropes: object = None      # cranefe.coordinates.ropes.RopeMesh when rope mass is on
    members: object = None    # cranefe.coordinates.members.MemberMesh when the structure is flexible

    @property
    def n(self):
        return self.T.shape[1]


def _groups(model):
    """Union-find of bodies over fixed joints; a group fixed to ground is GROUND."""
    nb = len(model.bodies)
    parent = list(range(nb + 1))     # index nb stands for ground

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for k, j in enumerate(model.joints):
        if j.type == "fixed":
            a, b = (nb if x == GROUND else x for x in j.bodies)
            ra, rb = find(a), find(b)
            if ra != rb:      # the ground's root stays the root of its group
                lo, hi = (ra, rb) if ra == nb or (rb != nb and ra < rb) else (rb, ra)
                parent[hi] = lo
    roots, group_of_body = {}, np.empty(nb, dtype=int)
    for b in range(nb):
        r = find(b)
        group_of_body[b] = GROUND if r == nb else roots.setdefault(r, len(roots))
    return group_of_body, len(roots)


def direction_tensor(model, effects, n_nodes):
    """Per node, D_i = sum of e e^T over the elastic elements acting on it, (n, 3, 3): its
    eigenvectors with non-zero eigenvalue span the directions they resist (sway off).

    Ropes, axial springs and linear drives act along their spans; members only when the
    structure is flexible (trusses along their axes, beams in every direction)."""
    D = np.zeros((n_nodes, 3, 3))
    a_list, b_list = [], []
    for r in model.ropes:
        a_list.append(r.span_a)
        b_list.append(r.span_b)
    for s in model.springs:
        if s.type == "axial":
            a_list.append([s.nodes[0]])
            b_list.append([s.nodes[1]])
    for d in model.linear_drives:
        a_list.append([d.nodes[0]])
        b_list.append([d.nodes[1]])
    if effects.structure == "flexible":
        from .members import member_pairs
        for m in model.members:
            pairs = member_pairs(m)
            if m.type == "truss":
                a_list.append(pairs[:, 0])
                b_list.append(pairs[:, 1])
            else:
                np.add.at(D, pairs.ravel(), np.eye(3))
    if a_list:
        a, b = np.concatenate(a_list).astype(int), np.concatenate(b_list).astype(int)
        e, _ = span_geometry(model.coords, a, b)
        ee = (e[:, :, None] * e[:, None, :]).reshape(-1, 9)
        ends = np.concatenate([a, b])          # sums per node: bincount, not np.add.at
        D += np.stack([np.bincount(ends, np.tile(ee[:, j], 2), minlength=n_nodes)
                       for j in range(9)], axis=1).reshape(n_nodes, 3, 3)
    return D


class _Map:
    """The kinematic map T_map being built: triplets and the coordinates' names."""

    def __init__(self):
        self.rows, self.cols, self.vals = [], [], []
        self.labels, self.kinds = [], []
        self.rotations = []       # indices of rotation coordinates (drums, rx, ry, rz)

    def new(self, label, kind):
        """A new generalised coordinate; returns its index."""
        self.labels.append(label)
        self.kinds.append(kind)
        if kind == "drum" or (kind in ("body", "node") and label[-2:] in ("rx", "ry", "rz")):
            self.rotations.append(len(self.labels) - 1)
        return len(self.labels) - 1

    def translations(self, labels):
        """Many node translations at once (`new` for each, without a rotation)."""
        self.labels += labels
        self.kinds += ["node"] * len(labels)

    def add(self, rows, cols, vals):
        self.rows.append(np.ravel(rows))
        self.cols.append(np.ravel(cols))
        self.vals.append(np.ravel(vals))

    def matrix(self, size):
        if not self.rows:
            return sp.csr_matrix((size, len(self.labels)))
        return sp.coo_matrix((np.concatenate(self.vals), (np.concatenate(self.rows),
                                                          np.concatenate(self.cols))),
                             shape=(size, len(self.labels))).tocsr()


@dataclass(frozen=True)
class _Groups:
    """Rigid groups of bodies: coordinates, reference points, carried nodes."""

    of_body: np.ndarray       # (nb,) group of each body, or GROUND
    q: np.ndarray             # (ng, 6) q_map index of each component, -1 absent
    ref: np.ndarray           # (ng, 3) reference point (centre of mass or node centroid)
    carrier: np.ndarray       # (nn,) group carrying each node, GROUND, or -2 = own DOFs


def _group_coordinates(model, comps, m, n_nodes):
    """Six coordinates per rigid group (three in a plane), its reference point, and the
    carrier of every node: the ground, a group, or none (-2: the node's own DOFs)."""
    of_body, ng = _groups(model)
    q = -np.ones((ng, 6), dtype=int)
    names = [[model.bodies[b].name for b in np.flatnonzero(of_body == g)] for g in range(ng)]
    for g in range(ng):
        for c in comps:
            q[g, c] = m.new(f"body {'+'.join(names[g])} {COMP_NAMES[c]}", "body")
    ref, mass = np.zeros((ng, 3)), np.zeros(ng)
    nodes = [[] for _ in range(ng)]
    for b, body in enumerate(model.bodies):
        g = of_body[b]
        if g != GROUND:
            ref[g] += body.mass * body.com
            mass[g] += body.mass
            nodes[g] += [model.coords[list(body.nodes)]] if body.nodes else [body.com[None]]
    for g in range(ng):
        ref[g] = ref[g] / mass[g] if mass[g] > 0 else np.vstack(nodes[g]).mean(axis=0)
    carrier = np.full(n_nodes, -2, dtype=int)      # interior rope and member nodes: free
    carrier[model.ground] = GROUND
    for b, body in enumerate(model.bodies):
        for i in body.nodes:
            if carrier[i] == -2 or of_body[b] == GROUND:
                carrier[i] = of_body[b]
    for j in model.joints:                # a joint's node moves with its first body
        if carrier[j.at] == -2:
            b1 = j.bodies[0]
            carrier[j.at] = GROUND if b1 == GROUND else of_body[b1]
    return _Groups(of_body, q, ref, carrier)


def _rigid_rows(m, groups, comps, prim_rows, g, offsets):
    """Rows of points (k offsets from the group's reference) carried by group g:
    u_point = u_ref + t x c = u_ref - skew(c) t."""
    if g == GROUND:
        return
    block = np.zeros((len(offsets), 3, 6))
    block[:, :, :3] = np.eye(3)
    block[:, :, 3:] = -skew(offsets)
    for c in comps:
        nz = block[:, :, c] != 0
        m.add(prim_rows[nz], np.full(nz.sum(), groups.q[g, c]), block[:, :, c][nz])


def _carried(model, layout, groups, comps, m):
    """Nodes and bodies carried by rigid groups."""
    carried = np.flatnonzero(groups.carrier >= 0)
    for g in range(len(groups.q)):
        sel = carried[groups.carrier[carried] == g]
        _rigid_rows(m, groups, comps, layout.node(sel), g, model.coords[sel] - groups.ref[g])
    for b, body in enumerate(model.bodies):
        g = groups.of_body[b]
        if g == GROUND:
            continue
        _rigid_rows(m, groups, comps, layout.body(b)[None, :3], g,
                    (body.com - groups.ref[g])[None])
        for c in (3, 4, 5):                 # rotations are shared by the whole group
            if groups.q[g, c] >= 0:
                m.add([layout.body(b)[c]], [groups.q[g, c]], [1.0])


def _free_directions(model, effects, layout, rm, mm):
    """D (n, 3, 3) per node: the directions its elements resist (all with sway on), and
    which nodes are active (something acts on them)."""
    nn, n_int = len(model.node_names), rm.n_interior if rm else 0
    D = direction_tensor(model, effects, layout.n_nodes)
    if rm is not None:                      # interior rope nodes: along their fall
        D[nn:nn + n_int] = rm.direction[:, :, None] * rm.direction[:, None, :]
    if mm is not None:                      # interior nodes of subdivided beams
        D[nn + n_int:] = np.eye(3)
    active = np.abs(D).sum(axis=(1, 2)) > 0
    active[model.masses.nodes] = True
    active[[d.node for d in model.drums]] = True
    if effects.sway:                        # every direction (tension stiffness)
        D[active] = np.eye(3)
    if model.planar:
        D[:, 1, :] = D[:, :, 1] = 0.0
    return D, active


def _free_nodes(model, layout, D, free, node_names, m):
    """Translations of free nodes: only those something acts on get coordinates, along
    the directions their elements resist."""
    planar = model.planar
    w, v = np.linalg.eigh(D[free]) if len(free) else (np.zeros((0, 3)), None)
    keep = w > 1e-9 * np.maximum(w.max(axis=1, initial=0), 1e-300)[:, None]
    full = keep.sum(axis=1) == (2 if planar else 3)
    trans = (0, 2) if planar else (0, 1, 2)
    nodes_full = free[full]           # free in every direction: the global axes (vectorised)
    q0 = len(m.labels)
    for k, c in enumerate(trans):
        m.add(layout.node(nodes_full)[:, c], q0 + k + len(trans) * np.arange(len(nodes_full)),
              np.ones(len(nodes_full)))
    axes = [f" {AXES[c]}" for c in trans]
    m.translations([f"node {node_names[i]}{a}" for i in nodes_full.tolist() for a in axes])
    for i, wi, vi in zip(free[~full], w[~full], v[~full] if v is not None else []):
        for vec in vi[:, wi > 1e-9 * max(wi.max(), 1e-300)].T:
            vec = np.where(np.abs(vec) > 1e-15, vec, 0.0)
            vec = vec * np.sign(vec[np.argmax(np.abs(vec))])
            nz = np.flatnonzero(vec)
            axis = np.flatnonzero(np.abs(np.abs(vec) - 1) < 1e-12)
            name = AXES[axis[0]] if len(axis) else \
                "along (" + ", ".join(f"{x:.3g}" for x in vec + 0.0) + ")"
            q = m.new(f"node {node_names[i]} {name}", "node")
            m.add(layout.node(i)[nz], np.full(len(nz), q), vec[nz])


def _beam_rotations(model, layout, mm, groups, node_names, m):
    """Rotations where beams meet: a body's, none on the ground, else their own."""
    for i in (mm.rotation_nodes() if mm else ()):
        g = groups.carrier[i]
        for c in ((4,) if model.planar else (3, 4, 5)):
            if g == GROUND:
                continue
            q = groups.q[g, c] if g >= 0 else m.new(f"node {node_names[i]} {COMP_NAMES[c]}",
                                                    "node")
            m.add([layout.rot(i)[c - 3]], [q], [1.0])


def build_dofs(model, effects=None):
    """The generalised coordinates of `model` for `effects` (default: the model's)."""
    effects = effects or model.effects
    rm = mm = None
    if effects.rope_mass > 0:
        from .ropes import discretize
        rm = discretize(model, effects.rope_mass)
    n_int, n_slip = (rm.n_interior, rm.n_slips) if rm else (0, 0)
    nn, nb, nd = len(model.node_names), len(model.bodies), len(model.drums)
    if effects.structure == "flexible" and model.members:
        from .members import discretize as members_discretize
        mm = members_discretize(model, nn + n_int)
    layout = Layout(nn + n_int + (mm.n_interior if mm else 0), nb, nd, n_slip)
    coords = np.vstack([model.coords] + ([rm.coords] if rm else [])
                       + ([mm.coords] if mm else []))
    comps = PLANAR_COMPONENTS if model.planar else tuple(range(6))
    m = _Map()
    groups = _group_coordinates(model, comps, m, layout.n_nodes)
    _carried(model, layout, groups, comps, m)
    D, active = _free_directions(model, effects, layout, rm, mm)
    node_names = list(model.node_names) + ([f"rope {n}" for n in rm.names] if rm else []) \
        + (list(mm.names) if mm else [])
    _free_nodes(model, layout, D, np.flatnonzero((groups.carrier == -2) & active),
                node_names, m)
    _beam_rotations(model, layout, mm, groups, node_names, m)
    for d, drum in enumerate(model.drums):
        if effects.drive == "coupled" and not drum.brake:
            m.add([layout.drum(d)], [m.new(f"drum {drum.name}", "drum")], [1.0])
    for k, name in enumerate(rm.slip_names if rm else ()):
        m.add([layout.slip(k)], [m.new(name, "slip")], [1.0])
    T_map = m.matrix(layout.size)
    constraints = _constraint_rows(model, effects, layout, T_map, groups.of_body, groups.q,
                                   groups.ref, comps)
    rotation = np.zeros(len(m.labels), dtype=bool)
    rotation[m.rotations] = True
    T_c, keep = _eliminate(constraints, len(m.labels), rotation, model.length_scale)
    kept = len(keep) == len(m.labels)       # then keep is every coordinate, in order
    return DofMap(layout, (T_map @ T_c).tocsr(), T_map, T_c,
                  tuple(m.labels) if kept else tuple(m.labels[i] for i in keep),
                  tuple(m.kinds) if kept else tuple(m.kinds[i] for i in keep),
                  groups.of_body, groups.ref, groups.q, groups.carrier, tuple(constraints),
                  coords, rm, mm)


def entry_of(label):
    """The model entry a coordinate label belongs to: 'node B z' -> 'nodes.B'."""
    kind, _, rest = label.partition(" ")
    name = rest.split(" ")[0]
    return {"node": f"nodes.{name}", "body": f"bodies.{name.split('+')[0]}",
            "drum": f"drums.{name}"}.get(kind)
