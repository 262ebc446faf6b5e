"""The static state under gravity in the reference geometry (model-format.md, "Static state").

Linear static solution with every drum held and only elastic stiffness; it gives the rope
tensions, spring forces, joint and drive reactions from which the tension stiffness of
spans and the load stiffness of rigid bodies are formed (docs/theory.md).
"""

from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .assembly import elastic_stiffness, mass_and_gravity, null_space, pattern
from .assembly.materials import element_sections
from .coordinates import build_dofs, entry_of
from .elements import span_geometry
from .errors import ModelError
from .model import GROUND

STATIC_DENSE_MAX = 400  # up to this many coordinates, statics finds its null space densely


@dataclass(frozen=True)
class StaticState:
    model: object
    u: np.ndarray              # (n_primitive,) static displacement from the unstressed state
    element_force: np.ndarray  # (ne,) per spring row: rope tension / spring force / moment
    springs: object            # the SpringRows the forces belong to
    ropes_fe: object           # RopeMesh of ropes with mass, or None
    drive_force: np.ndarray    # (nld,) axial force of linear drives (tension positive)
    node_force: np.ndarray     # (nn, 3) force of elements and drives on each node
    joint_forces: tuple        # (g1, g2, point, F): F acts on g1, -F on g2
    gravity_points: tuple      # (body, point, force) of every weight a body carries
    beam_force: np.ndarray = None  # (nbeam,) axial force of beam elements (tension +)
    members_fe: object = None  # MemberMesh when the structure is flexible

    @property
    def element_names(self):
        return self.springs.names

    def rope_tension(self):
        """(nr, 2): smallest and largest static tension of each rope."""
        out = np.full((len(self.model.ropes), 2), np.nan)
        for k in range(len(self.model.ropes)):
            S = self.element_force[self.springs.rope == k]
            out[k] = S.min(), S.max()
        return out

    def spans(self):
        """(a, b, falls, N) of every straight tension-carrying span (node indices)."""
        m, sp_ = self.model, self.springs
        fe = set(self.ropes_fe.ropes) if self.ropes_fe is not None else set()
        for k, r in enumerate(m.ropes):
            if k not in fe:
                S = self.element_force[sp_.rope == k][0]
                yield r.span_a, r.span_b, r.falls.astype(float), np.full(len(r.falls), S)
        if fe:
            rm = self.ropes_fe
            S = self.element_force[np.isin(sp_.rope, list(fe))]
            span = rm.fall >= 0            # not the massless extra-length pieces
            yield rm.node[span, 0], rm.node[span, 1], np.ones(span.sum()), S[span]
        trusses = np.flatnonzero(sp_.member >= 0)
        if len(trusses):
            mm_nodes = self.members_fe.node[sp_.member[trusses]]
            yield mm_nodes[:, 0], mm_nodes[:, 1], np.ones(len(trusses)), \
                self.element_force[trusses]
        for k, s in enumerate(m.springs):
            if s.type == "axial":
                N = self.element_force[sp_.spring == k][0]
                yield np.array(s.nodes[:1]), np.array(s.nodes[1:]), np.ones(1), np.array([N])
        for d, N in zip(m.linear_drives, self.drive_force):
            yield np.array(d.nodes[:1]), np.array(d.nodes[1:]), np.ones(1), np.array([N])

    def point_forces(self, dofs):
        """Per rigid group g: (g, points (k, 3), forces (k, 3)) acting on it."""
        m = self.model
        per = {}

        def add(g, p, F):
            if g != GROUND and g >= 0:
                per.setdefault(g, ([], []))
                per[g][0].append(p)
                per[g][1].append(F)

        for b, p, F in self.gravity_points:
            add(dofs.group_of_body[b], p, F)
        for i in np.flatnonzero(dofs.carrier >= 0):
            add(dofs.carrier[i], m.coords[i], self.node_force[i])
        for g1, g2, p, F in self.joint_forces:
            add(g1, p, F)
            add(g2, p, -F)
        for g, (p, F) in per.items():
            yield g, np.array(p), np.array(F)


def solve_static(model, effects=None, reuse=None):
    """Linear static solution under gravity, drums held, elastic stiffness only.

    Interior nodes of ropes with mass move only along their falls here, so a span's own
    weight loads it along the rope (tension varying with height); its lateral weight,
    which makes a real span sag, is not in the straight reference geometry.
    """
    effects = replace(effects or model.effects, sway=False, drive="held",
                      rope_elasticity=True)
    dofs = reuse.dofs(model, effects) if reuse else build_dofs(model, effects)
    layout = dofs.layout
    K_u, springs, beams, _ = elastic_stiffness(model, dofs)
    _, f_u, gravity_points = mass_and_gravity(model, dofs, effects)
    T = dofs.T
    K = (T.T @ K_u @ T).tocsr()
    f = T.T @ f_u
    q = _solve(K, f, lambda: pattern(springs, dofs, [beams] if beams else []), dofs, model,
               reuse)
    u = T @ q
    element_force = springs.c * (springs.R @ u)
    beam_force = np.zeros(0)
    mm = dofs.members
    if mm is not None and mm.beam.any():       # axial force N = EA/l e.(u_b - u_a)
        bi = np.flatnonzero(mm.beam)
        e, l = span_geometry(dofs.coords, mm.node[bi, 0], mm.node[bi, 1])
        du = u[layout.node(mm.node[bi, 1])] - u[layout.node(mm.node[bi, 0])]
        sec = element_sections(model, mm)
        beam_force = sec.E[bi] * sec.A[bi] / l * np.einsum("ki,ki->k", e, du)
    nn = layout.n_nodes
    # point masses on bodies are in gravity_points, not in f_u's node rows
    tr = layout.translations()
    node_force = (f_u[tr] - (K_u @ u)[tr]).reshape(nn, 3)

    # reactions of constraints: G^T lam = K_map u_map - f_map
    joint_forces, drive_force = [], np.zeros(len(model.linear_drives))
    if dofs.constraints:
        u_map = dofs.T_c @ q
        res = dofs.T_map.T @ (K_u @ (dofs.T_map @ u_map)) - dofs.T_map.T @ f_u
        G = np.vstack([c.rows for c in dofs.constraints])
        lam = sla.lstsq(G.T, res)[0]
        k = 0
        for c in dofs.constraints:
            lc = lam[k:k + len(c.rows)]
            k += len(c.rows)
            kind, i = c.owner
            if kind == "joint":
                joint_forces.append((*c.groups, c.point, c.directions.T @ lc))
            elif kind == "drive":
                a, cc = model.linear_drives[i].nodes
                e, _ = span_geometry(model.coords, np.array([a]), np.array([cc]))
                drive_force[i] = -lc[0]            # pushes C away from A: compression
                node_force[cc] += lc[0] * e[0]
                node_force[a] -= lc[0] * e[0]
            elif kind == "support":                # the reaction on the node
                node_force[model.supports[i].node] += c.directions.T @ lc
    scale = _force_scale(f_u, u, springs, element_force, beams, layout.size)[tr]
    _check_free_nodes(model, dofs, node_force, f_u[tr].reshape(nn, 3),
                      scale.reshape(nn, 3), _kinds_at(springs, beams, layout))
    return StaticState(model, u, element_force, springs, dofs.ropes, drive_force,
                       node_force, tuple(joint_forces), tuple(gravity_points), beam_force, mm)


def _solve(K, f, P, dofs, model, reuse=None):
    """Solve K q = f; directions no element resists must carry no load. P() forms the
    pattern matrix, whose null space `reuse` may hold from a model of the same
    structure."""
    n = K.shape[0]
    if n == 0:
        return np.zeros(0)
    if n > STATIC_DENSE_MAX:
        try:
            return spla.splu(K.tocsc()).solve(f)
        except RuntimeError:
            pass
        # free motions (a free body, an unrestrained slewing axis): a relative shift of
        # 1e-10 of the diagonal leaves them unloaded if gravity does not load them
        d = np.abs(K.diagonal())
        q = spla.splu((K + sp.diags(1e-10 * np.where(d > 0, d, d.max()))).tocsc()).solve(f)
        if np.linalg.norm(K @ q - f) > 1e-6 * (np.linalg.norm(f) or 1.0):
            raise ModelError("not in static equilibrium: gravity moves a part that nothing "
                             "restrains; support it with a joint, rope or spring", model.file)
        return q
    N = reuse.null_space(P()) if reuse else null_space(P().toarray())
    Kd = K.toarray()
    if N.shape[1]:
        load = N.T @ f
        scale = np.linalg.norm(f) or 1.0
        if np.abs(load).max() > 1e-8 * scale:
            k = int(np.argmax(np.abs(load)))
            v = N[:, k]
            top = np.argsort(-np.abs(v))[:3]
            moved = [dofs.labels[i] for i in top if abs(v[i]) > 0.1 * abs(v).max()]
            raise ModelError(
                f"not in static equilibrium: gravity moves {', '.join(moved)} with nothing "
                f"to resist it (unbalanced {abs(load[k]):.4g} N); support it with a joint, "
                "rope or spring, or fix it", model.file, entry_of(moved[0]))
        alpha = np.abs(np.diag(Kd)).max() or 1.0
        Kd = Kd + alpha * N @ N.T
    return sla.solve(Kd, f, assume_a="sym")


def _force_scale(f_u, u, springs, element_force, beams, size):
    """(n_u,) size of the forces meeting at each primitive coordinate: its weight plus
    |every element force on it| (spring rows |r_e| |N_e|, beam end forces |K_e u_e|), so
    the equilibrium test is relative to what the node carries, not to its own weight
    (a light member node under a 2e5 N load balances to ~1e-7 N of round-off), and to
    the size of the terms of K u, whose round-off that is."""
    # |K_e| |u_e| rather than |K_e u_e|: the round-off of f - K u (a 1e17 N/m link
    # stretched by 1e-13 m carries 1e4 N, computed as a difference of 1e16 N terms)
    absR = abs(springs.R)
    scale = np.abs(f_u) + absR.T @ np.maximum(np.abs(element_force),
                                              np.abs(springs.c) * (absR @ np.abs(u)))
    if beams is not None and len(beams.mat):
        end = np.einsum("kij,kj->ki", np.abs(beams.mat), np.abs(u[beams.idx]))
        np.add.at(scale, beams.idx, end)
    return scale


def _kinds_at(springs, beams, layout):
    """(nn,) the kinds of element attached to each node, e.g. 'ropes and members'."""
    nn = layout.n_nodes
    touched = {k: np.zeros(nn, bool) for k in ("ropes", "springs", "members")}
    R = springs.R.tocoo()
    node_of = np.full(layout.size, -1)
    node_of[layout.translations()] = np.repeat(np.arange(nn), 3)
    for kind, rows in (("ropes", springs.rope >= 0), ("springs", springs.spring >= 0),
                       ("members", springs.member >= 0)):
        hit = node_of[R.col[rows[R.row] & (node_of[R.col] >= 0)]]
        touched[kind][hit] = True
    if beams is not None and len(beams.mat):
        hit = node_of[beams.idx.ravel()]
        touched["members"][hit[hit >= 0]] = True
    names = [[k for k, t in touched.items() if t[i]] for i in range(nn)]
    return [" and ".join(x) if x else "elements" for x in names]


def _check_free_nodes(model, dofs, node_force, weight_force, scale, kinds):
    """Free model nodes must be in equilibrium in every direction, not only along their
    ropes (interior rope nodes are exempt: see solve_static). The test is relative to
    the forces meeting at the node (`_force_scale`)."""
    nn = len(model.node_names)
    for i in np.flatnonzero(dofs.carrier[:nn] == -2):
        F = node_force[i]
        weight = np.linalg.norm(weight_force[i])
        if weight > 0 and np.linalg.norm(F) > 1e-7 * np.linalg.norm(scale[i]):
            hint = "so that its ropes hang along gravity " if "ropes" in kinds[i] else ""
            raise ModelError(
                f"node '{model.node_names[i]}' is not in static equilibrium in the reference "
                f"geometry: its {kinds[i]} cannot balance a force of "
                f"{np.array2string(F, precision=4)} N (its weight is {weight:.4g} N); move "
                f"it {hint}(the reference geometry is the static equilibrium)", model.file,
                f"nodes.{model.node_names[i]}")
