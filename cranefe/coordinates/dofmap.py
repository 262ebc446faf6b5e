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

import dataclasses
import hashlib
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from ..elements.kernels import elongation_rows, skew, span_geometry
from ..errors import ModelError
from ..model import GROUND

PLANAR_COMPONENTS = (0, 2, 4)       # ux, uz, ry of (ux, uy, uz, rx, ry, rz)
AXES = ("x", "y", "z")
COMP_NAMES = ("ux", "uy", "uz", "rx", "ry", "rz")


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


@dataclass(frozen=True)
class ConstraintRows:
    """Rows of G (in q_map) of one constraint, with how its reaction acts on points."""

    name: str
    owner: tuple              # ("joint" | "drive" | "rope", index in the model)
    rows: np.ndarray          # (k, n_map) dense
    groups: tuple             # (g1, g2) rigid groups a joint connects, else ()
    point: np.ndarray         # (3,) point where the reaction acts (joints), or None
    directions: np.ndarray    # (k, 3) force direction of each row at the point (joint
                              # translations) or zeros (rotations, ropes, drives)


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
        ee = e[:, :, None] * e[:, None, :]
        np.add.at(D, a, ee)
        np.add.at(D, b, ee)
    return D


# Model values that build_dofs never reads, or reads only in part: models that differ
# only in these share one DofMap (sweeps reuse it). Each maps to what of it the key
# keeps (None: nothing); a rope's mass_per_length only decides whether it is
# discretised (rope_mass: N). Everything else is structure, so a field added later
# counts as structure until it is listed here; tests/test_sweeps.py perturbs every
# number of the examples and checks that an unchanged key means an unchanged DofMap.
VALUE_ONLY = {
    "Model": {"text": None, "analysis": None},
    "Body": {"inertia": None},
    "PointMasses": {"mass": None, "inertia": None},
    "Spring": {"stiffness": None, "psi": None},
    "Drum": {"inertia": None, "rotor_inertia": None, "gear_ratio": None},
    "Rope": {"EA": None, "psi": None, "mass_per_length": lambda mu: mu > 0},
    "Member": dict.fromkeys(("E", "G", "A", "Iy", "Iz", "J", "rho", "psi", "mass")),
    "LinearDrive": {"pinion_radius": None, "gear_ratio": None, "rotor_inertia": None},
}


def structure_key(model, effects=None):
    """A digest of everything `build_dofs(model, effects)` depends on."""
    h = hashlib.sha1()

    def feed(x):
        if dataclasses.is_dataclass(x):
            partial = VALUE_ONLY.get(type(x).__name__, {})
            h.update(type(x).__name__.encode())
            for f in dataclasses.fields(x):
                value = getattr(x, f.name)
                if f.name in partial:
                    if partial[f.name] is None:
                        continue
                    value = partial[f.name](value)
                h.update(f.name.encode())
                feed(value)
        elif isinstance(x, np.ndarray):
            h.update(f"{x.dtype}{x.shape}".encode())
            h.update(np.ascontiguousarray(x).tobytes())
        elif isinstance(x, (tuple, list)):
            h.update(f"({len(x)}".encode())
            for v in x:
                feed(v)
        else:
            h.update(repr(x).encode())

    feed(model)
    feed(effects or model.effects)
    return h.hexdigest()


def build_dofs(model, effects=None):
    """The generalised coordinates of `model` for `effects` (default: the model's)."""
    effects = effects or model.effects
    planar = model.planar
    rm = None
    if effects.rope_mass > 0:
        from .ropes import discretize
        rm = discretize(model, effects.rope_mass)
    n_int, n_slip = (rm.n_interior, rm.n_slips) if rm else (0, 0)
    nn, nb, nd = len(model.node_names), len(model.bodies), len(model.drums)
    mm = None
    if effects.structure == "flexible" and model.members:
        from .members import discretize as members_discretize
        mm = members_discretize(model, nn + n_int)
    n_mem = mm.n_interior if mm else 0
    layout = Layout(nn + n_int + n_mem, nb, nd, n_slip)
    coords = np.vstack([model.coords] + ([rm.coords] if rm else [])
                       + ([mm.coords] if mm else []))
    comps = PLANAR_COMPONENTS if planar else tuple(range(6))
    group_of_body, ng = _groups(model)

    labels, kinds = [], []
    group_q = -np.ones((ng, 6), dtype=int)
    group_names = [[] for _ in range(ng)]
    for b, g in enumerate(group_of_body):
        if g != GROUND:
            group_names[g].append(model.bodies[b].name)
    for g in range(ng):
        for c in comps:
            group_q[g, c] = len(labels)
            labels.append(f"body {'+'.join(group_names[g])} {COMP_NAMES[c]}")
            kinds.append("body")

    # reference point of each group: its centre of mass, or the centroid of its nodes
    group_ref = np.zeros((ng, 3))
    gmass = np.zeros(ng)
    gnodes = [[] for _ in range(ng)]
    for b, body in enumerate(model.bodies):
        g = group_of_body[b]
        if g != GROUND:
            group_ref[g] += body.mass * body.com
            gmass[g] += body.mass
            gnodes[g] += [model.coords[list(body.nodes)]] if body.nodes else [body.com[None]]
    for g in range(ng):
        group_ref[g] = group_ref[g] / gmass[g] if gmass[g] > 0 \
            else np.vstack(gnodes[g]).mean(axis=0)

    # carrier of every node (interior rope and member nodes are free)
    carrier = np.full(nn + n_int + n_mem, -2, dtype=int)
    carrier[model.ground] = GROUND
    for b, body in enumerate(model.bodies):
        for i in body.nodes:
            if carrier[i] == -2 or group_of_body[b] == GROUND:
                carrier[i] = group_of_body[b]
    for j in model.joints:                # a joint's node moves with its first body
        if carrier[j.at] == -2:
            b1 = j.bodies[0]
            carrier[j.at] = GROUND if b1 == GROUND else group_of_body[b1]

    rows, cols, vals = [], [], []

    def rigid(prim_rows, g, offsets):
        """Rows of points (k offsets from the group's reference) carried by group g."""
        if g == GROUND:
            return
        # u_point = u_ref + t x c = u_ref - skew(c) t
        k = len(offsets)
        block = np.zeros((k, 3, 6))
        block[:, :, :3] = np.eye(3)
        block[:, :, 3:] = -skew(offsets)
        for c in comps:
            q = group_q[g, c]
            nz = block[:, :, c] != 0
            rows.append(prim_rows[nz])
            cols.append(np.full(nz.sum(), q))
            vals.append(block[:, :, c][nz])

    carried = np.flatnonzero(carrier >= 0)
    for g in range(ng):
        sel = carried[carrier[carried] == g]
        rigid(layout.node(sel), g, model.coords[sel] - group_ref[g])
    for b, body in enumerate(model.bodies):
        g = group_of_body[b]
        if g == GROUND:
            continue
        rigid(layout.body(b)[None, :3], g, (body.com - group_ref[g])[None])
        for c in (3, 4, 5):                 # rotations are shared by the whole group
            if group_q[g, c] >= 0:
                rows.append([layout.body(b)[c]])
                cols.append([group_q[g, c]])
                vals.append([1.0])

    # free nodes: only those something acts on get coordinates
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
    if planar:
        D[:, 1, :] = D[:, :, 1] = 0.0
    free = np.flatnonzero((carrier == -2) & active)
    w, v = np.linalg.eigh(D[free]) if len(free) else (np.zeros((0, 3)), None)
    keep = w > 1e-9 * np.maximum(w.max(axis=1, initial=0), 1e-300)[:, None]
    full = keep.sum(axis=1) == (2 if planar else 3)
    trans = (0, 2) if planar else (0, 1, 2)
    node_names = list(model.node_names) + ([f"rope {n}" for n in rm.names] if rm else []) \
        + (list(mm.names) if mm else [])
    # nodes free in every direction: the global axes (vectorised: big lattices)
    nodes_full = free[full]
    q0 = len(labels)
    for k, c in enumerate(trans):
        rows.append(layout.node(nodes_full)[:, c])
        cols.append(q0 + k + len(trans) * np.arange(len(nodes_full)))
        vals.append(np.ones(len(nodes_full)))
    labels += [f"node {node_names[i]} {AXES[c]}" for i in nodes_full for c in trans]
    kinds += ["node"] * (len(trans) * len(nodes_full))
    # the others: the directions their elements resist
    for i, wi, vi in zip(free[~full], w[~full], v[~full] if v is not None else []):
        for vec in vi[:, wi > 1e-9 * max(wi.max(), 1e-300)].T:
            vec = np.where(np.abs(vec) > 1e-15, vec, 0.0)
            vec = vec * np.sign(vec[np.argmax(np.abs(vec))])
            nz = np.flatnonzero(vec)
            rows.append(layout.node(i)[nz])
            cols.append(np.full(len(nz), len(labels)))
            vals.append(vec[nz])
            axis = np.flatnonzero(np.abs(np.abs(vec) - 1) < 1e-12)
            name = AXES[axis[0]] if len(axis) else \
                "along (" + ", ".join(f"{x:.3g}" for x in vec + 0.0) + ")"
            labels.append(f"node {node_names[i]} {name}")
            kinds.append("node")

    # rotations where beams meet: a body's, none on the ground, else their own
    rot_comps = (4,) if planar else (3, 4, 5)
    for i in (mm.rotation_nodes() if mm else ()):
        g = carrier[i]
        for c in rot_comps:
            if g == GROUND:
                continue
            rows.append([layout.rot(i)[c - 3]])
            vals.append([1.0])
            if g >= 0:
                cols.append([group_q[g, c]])
            else:
                cols.append([len(labels)])
                labels.append(f"node {node_names[i]} {COMP_NAMES[c]}")
                kinds.append("node")

    for d, drum in enumerate(model.drums):
        if effects.drive == "coupled" and not drum.brake:
            rows.append([layout.drum(d)])
            cols.append([len(labels)])
            vals.append([1.0])
            labels.append(f"drum {drum.name}")
            kinds.append("drum")

    for k, name in enumerate(rm.slip_names if rm else ()):
        rows.append([layout.slip(k)])
        cols.append([len(labels)])
        vals.append([1.0])
        labels.append(name)
        kinds.append("slip")

    n_map = len(labels)
    T_map = sp.coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                          shape=(layout.size, n_map)).tocsr() if rows else \
        sp.csr_matrix((layout.size, 0))

    constraints = _constraint_rows(model, effects, layout, T_map, group_of_body, group_q,
                                   group_ref, comps)
    rotation = np.array([k == "drum" or (k in ("body", "node") and lab[-2:] in
                                          ("rx", "ry", "rz"))
                         for k, lab in zip(kinds, labels)], dtype=bool)
    T_c, keep = _eliminate(constraints, n_map, rotation, model.length_scale)
    return DofMap(layout, (T_map @ T_c).tocsr(), T_map, T_c,
                  tuple(labels[i] for i in keep), tuple(kinds[i] for i in keep),
                  group_of_body, group_ref, group_q, carrier, tuple(constraints), coords, rm,
                  mm)


def _constraint_rows(model, effects, layout, T_map, group_of_body, group_q, group_ref,
                     comps):
    out = []
    n_map = T_map.shape[1]

    def point_rows(g, p):
        """(3, n_map): translation of point p carried by group g."""
        m = np.zeros((3, n_map))
        if g == GROUND:
            return m
        c = p - group_ref[g]
        block = np.hstack([np.eye(3), -skew(c)])
        for k in comps:
            m[:, group_q[g, k]] += block[:, k]
        return m

    def rot_rows(g):
        m = np.zeros((3, n_map))
        if g != GROUND:
            for k in (3, 4, 5):
                if group_q[g, k] >= 0:
                    m[k - 3, group_q[g, k]] = 1.0
        return m

    for k, j in enumerate(model.joints):
        if j.type == "fixed":
            continue
        g1, g2 = (GROUND if b == GROUND else group_of_body[b] for b in j.bodies)
        if g1 == g2:
            continue                      # both in one rigid group: nothing to constrain
        p = model.coords[j.at]
        trans = point_rows(g1, p) - point_rows(g2, p)
        rot = rot_rows(g1) - rot_rows(g2)
        if j.type == "slider":
            tdirs = _perp(j.axis)
            rdirs = np.eye(3)
        else:
            tdirs = np.eye(3)
            rdirs = _perp(j.axis) if j.type == "hinge" else np.zeros((0, 3))
        rows = np.vstack([tdirs @ trans, rdirs @ rot])
        dirs = np.vstack([tdirs, np.zeros((len(rdirs), 3))])
        out.append(ConstraintRows(f"{j.type} joint at {model.node_names[j.at]}",
                                  ("joint", k), rows, (g1, g2), p, dirs))

    for k, d in enumerate(model.linear_drives):
        a, c = d.nodes
        e, _ = span_geometry(model.coords, np.array([a]), np.array([c]))
        cols, vals = elongation_rows(e, np.ones(1), layout.node([a]), layout.node([c]))
        row = np.zeros(layout.size)
        np.add.at(row, cols[0], vals[0])
        out.append(ConstraintRows(f"linear drive {d.name}", ("drive", k),
                                  (row @ T_map)[None], (), None, np.zeros((1, 3))))
    if not effects.rope_elasticity:
        if effects.rope_mass > 0:
            from ..errors import ModelError
            raise ModelError("inextensible ropes (rope_elasticity: false) cannot carry "
                             "rope mass elements; set rope_mass: 0", model.file,
                             "effects.rope_elasticity")
        from ..assembly.assemble import rope_rows
        R, _ = rope_rows(model, layout)
        RT = (R @ T_map).toarray()
        for k, r in enumerate(model.ropes):
            out.append(ConstraintRows(f"rope {r.name} (inextensible)", ("rope", k),
                                      RT[k:k + 1], (), None, np.zeros((1, 3))))
    return out


def _perp(axis):
    """(2, 3) orthonormal directions perpendicular to a unit axis."""
    _, _, vt = np.linalg.svd(axis[None])
    return vt[1:]


def _eliminate(constraints, n_map, rotation, length_scale):
    """Master-slave elimination of G q_map = 0 -> (T_c (n_map, n), kept master indices)."""
    if not constraints:
        return sp.identity(n_map, format="csr"), np.arange(n_map)
    G = np.vstack([c.rows for c in constraints])
    involved = np.flatnonzero(np.abs(G).sum(axis=0) > 0)
    if len(involved) == 0:
        return sp.identity(n_map, format="csr"), np.arange(n_map)
    GJ = G[:, involved]
    # rotations in length units (theta * model size) so pivoting compares like with like
    scale = np.where(rotation[involved], 1.0 / length_scale, 1.0)   # theta = x~ / L
    # translations are preferred as slaves, so joint rotations stay as the coordinates
    # (a hinge is described by its angle); the rank decision is unaffected by the weight
    prefer = np.where(rotation[involved], 1.0, 10.0)
    Q, R, piv = sla.qr(GJ * scale * prefer, pivoting=True, mode="economic")
    diag = np.abs(np.diag(R))
    rank = int(np.sum(diag > 1e-10 * diag[0])) if len(diag) else 0
    slaves, masters = piv[:rank], piv[rank:]
    # in scaled unknowns x~ = x / scale: R11 x~_s + R12 x~_m = 0
    W = -sla.solve_triangular(R[:rank, :rank], R[:rank, rank:])
    w = scale * prefer
    W = W * w[slaves][:, None] / w[masters][None, :]
    slave_global = involved[slaves]
    keep = np.setdiff1d(np.arange(n_map), slave_global)
    col_of = {q: k for k, q in enumerate(keep)}
    rows = list(keep)
    cols = list(range(len(keep)))
    vals = [1.0] * len(keep)
    for si, s in enumerate(slave_global):
        for mi, m in enumerate(involved[masters]):
            if W[si, mi] != 0:
                rows.append(s)
                cols.append(col_of[m])
                vals.append(W[si, mi])
    T_c = sp.coo_matrix((vals, (rows, cols)), shape=(n_map, len(keep))).tocsr()
    return T_c, keep
