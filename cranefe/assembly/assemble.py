"""Assembly: element kernels -> one COO step -> K, M, f in generalised coordinates.

Spring-like elements (massless ropes over their whole reeving, axial and rotational
springs) are rows r of elongation coefficients, ``K = R^T diag(c) R`` (Heletiy 2016,
eq. 5: C_ij = sum_m C_m r_mi r_mj). Tension (geometric) stiffness of spans and the load
stiffness of rigid bodies come from the static state (`cranefe.statics`) when sway is on.
Everything is assembled in primitive coordinates and mapped once, ``K_q = T^T K_u T``.
"""

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from ..coordinates.dofmap import build_dofs
from ..elements.kernels import (elongation_rows, load_stiffness, rigid_mass, rope_mass, skew,
                       span_geometry, string_stiffness)
from ..errors import ModelError
from ..model import GROUND


@dataclass(frozen=True)
class SpringRows:
    """All spring-like elements: K = R^T diag(c) R (primitive coordinates)."""

    R: sp.csr_matrix          # (ne, n_primitive) elongation rows
    c: np.ndarray             # (ne,) stiffness of each row
    psi: np.ndarray           # (ne,) absorption coefficient
    names: tuple              # (ne,) "rope hoist", "spring tower_bend", ...
    length: np.ndarray        # (ne,) deformable length (ropes, axial springs), else nan
    rope: np.ndarray          # (ne,) index of the rope a row belongs to, else -1
    spring: np.ndarray        # (ne,) index of the spring a row is, else -1
    member: np.ndarray        # (ne,) index of the truss member element a row is, else -1


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


def sum_blocks(blocks, size):
    """One COO assembly of several Blocks -> CSR (size, size)."""
    rows, cols, vals = [], [], []
    for b in blocks:
        k = b.idx.shape[1]
        rows.append(np.repeat(b.idx, k, axis=1).ravel())
        cols.append(np.tile(b.idx, (1, k)).ravel())
        vals.append(b.mat.ravel())
    return _coo(rows, cols, vals, (size, size))


@dataclass(frozen=True)
class System:
    """Assembled matrices in generalised coordinates q (u = dofs.T q)."""

    model: object
    effects: object
    dofs: object
    K: sp.csr_matrix          # (n, n) stiffness: elastic + tension + load
    M: sp.csr_matrix          # (n, n) inertia
    f: np.ndarray             # (n,) gravity forces
    springs: SpringRows
    beams: Blocks = None      # elastic stiffness of beam elements (primitive), if any
    beam_psi: np.ndarray = None
    geometric: tuple = ()     # Blocks of tension and load stiffness (sway)
    static: object = None     # StaticState when sway is on
    timings: dict = field(default_factory=dict)

    @cached_property
    def K_pattern(self):
        """(n, n) sum of unit-scaled |element matrices|: the null space of K without its
        stiffness contrasts (formed only when asked: the dense path)."""
        return pattern(self.springs, self.dofs, [self.beams] if self.beams else [],
                       self.geometric)


def _coo(rows, cols, vals, shape):
    if not rows:
        return sp.csr_matrix(shape)
    return sp.coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=shape).tocsr()


def rope_rows(model, layout, which=None):
    """Massless ropes: one elongation row per rope over its whole path (seed eq. 2-3).

    Returns (R (len(which), n_primitive), deformable lengths L): rows for the ropes
    `which` (default all). A drum at an end hauls in ``radius * rotation``, which
    stretches the rope: coefficient +radius on the drum's rotation.
    """
    which = range(len(model.ropes)) if which is None else which
    rows, cols, vals, lengths = [], [], [], []
    for k, ri in enumerate(which):
        r = model.ropes[ri]
        e, l = span_geometry(model.coords, r.span_a, r.span_b)
        c, v = elongation_rows(e, r.falls.astype(float), layout.node(r.span_a),
                               layout.node(r.span_b))
        rows.append(np.full(c.size, k))
        cols.append(c.ravel())
        vals.append(v.ravel())
        for d in r.end_drums:
            rows.append([k])
            cols.append([layout.drum(d)])
            vals.append([model.drums[d].radius])
        lengths.append(float(r.falls @ l) + r.extra_length)
    return _coo(rows, cols, vals, (len(which), layout.size)), np.array(lengths)


def _member_geometry(model, layout, mm, which):
    """Unit vectors and lengths of member elements `which`."""
    coords = _all_coords(model, layout, mm)
    return span_geometry(coords, mm.node[which, 0], mm.node[which, 1])


def _all_coords(model, layout, mm):
    """Coordinates of model nodes, then interior rope nodes, then member nodes."""
    n_mem = mm.n_interior if mm is not None else 0
    out = np.full((layout.n_nodes, 3), np.nan)
    out[:len(model.coords)] = model.coords
    if n_mem:
        out[layout.n_nodes - n_mem:] = mm.coords
    return out


def spring_rows(model, layout, ropes_fe=None, members=None):
    """Rows of ropes, axial springs and rotational springs, with stiffness and psi.

    A massless rope is one row over its whole reeving (stiffness EA / L); a rope with
    mass (`ropes_fe`, a RopeMesh) contributes one row per element (EA / l_e).
    """
    fe = set(ropes_fe.ropes) if ropes_fe is not None else set()
    massless = [k for k in range(len(model.ropes)) if k not in fe]
    R_rope, L = rope_rows(model, layout, massless)
    blocks = [R_rope]
    c = [model.ropes[k].EA / l for k, l in zip(massless, L)]
    psi = [model.ropes[k].psi for k in massless]
    names = [f"rope {model.ropes[k].name}" for k in massless]
    lengths = list(L)
    rope_of = list(massless)
    if fe:
        from ..coordinates.ropes import element_materials, endpoint_maps
        rm = ropes_fe
        dofs, B = endpoint_maps(rm, layout)
        EA, _ = element_materials(model, rm)
        # elongation e . (u_end - u_start) of each element
        v = np.einsum("ki,kij->kj", rm.e, B[:, 3:] - B[:, :3])
        ne = len(rm.length)
        blocks.append(_coo([np.repeat(np.arange(ne), 8)], [dofs.ravel()], [v.ravel()],
                           (ne, layout.size)))
        c += list(EA / rm.length)
        psi += [model.ropes[k].psi for k in rm.rope]
        names += [f"rope {model.ropes[k].name}" for k in rm.rope]
        lengths += list(rm.length)
        rope_of += list(rm.rope)
    n_rope_rows = len(c)
    member_of = []
    mm = members
    if mm is not None and (~mm.beam).any():    # trusses: one row each, EA / l
        from ..coordinates.members import element_sections
        sec = element_sections(model, mm)
        t = np.flatnonzero(~mm.beam)
        e, l = _member_geometry(model, layout, mm, t)
        cc, v = elongation_rows(e, np.ones(len(t)), layout.node(mm.node[t, 0]),
                                layout.node(mm.node[t, 1]))
        blocks.append(_coo([np.repeat(np.arange(len(t)), 6)], [cc.ravel()], [v.ravel()],
                           (len(t), layout.size)))
        c += list(sec.E[t] * sec.A[t] / l)
        psi += list(sec.psi[t])
        names += [f"member {model.members[k].name}" for k in mm.member[t]]
        lengths += list(l)
        rope_of += [-1] * len(t)
        member_of = list(t)
    n_rope_rows = len(c)
    rows, cols, vals = [], [], []
    for k, s in enumerate(model.springs):
        if s.type == "axial":
            e, l = span_geometry(model.coords, np.array(s.nodes[:1]), np.array(s.nodes[1:]))
            cc, v = elongation_rows(e, np.ones(1), layout.node([s.nodes[0]]),
                                    layout.node([s.nodes[1]]))
            rows.append(np.full(6, k))
            cols.append(cc[0])
            vals.append(v[0])
            lengths.append(float(l[0]))
        else:                               # relative rotation about the axis
            for sign, b in ((-1.0, s.bodies[0]), (1.0, s.bodies[1])):
                if b != GROUND:
                    rows.append(np.full(3, k))
                    cols.append(layout.body(b)[3:])
                    vals.append(sign * s.axis)
            lengths.append(np.nan)
        c.append(s.stiffness)
        psi.append(s.psi)
        names.append(f"spring {s.name}")
    blocks.append(_coo(rows, cols, vals, (len(model.springs), layout.size)))
    ns = len(model.springs)
    n_member = len(member_of)
    return SpringRows(sp.vstack(blocks).tocsr(), np.array(c, dtype=float),
                      np.array(psi, dtype=float), tuple(names), np.array(lengths),
                      np.array(rope_of + [-1] * ns, dtype=int),
                      np.concatenate([-np.ones(n_rope_rows, dtype=int), np.arange(ns)]),
                      np.array([-1] * (n_rope_rows - n_member) + member_of + [-1] * ns,
                               dtype=int))


def beam_dofs(layout, mm, which):
    """(ne, 12) primitive indices: translations and rotations of both ends."""
    return np.hstack([6 * mm.node[which, :1] + np.arange(6), 6 * mm.node[which, 1:] +
                      np.arange(6)]) if len(which) else np.zeros((0, 12), dtype=int)


def beam_blocks(model, layout, mm):
    """Elastic stiffness of the beam elements in global axes, and their absorption."""
    from ..elements.kernels import beam_axes, beam_stiffness, to_global
    from ..coordinates.members import element_sections
    sec = element_sections(model, mm)
    b = np.flatnonzero(mm.beam)
    e, l = _member_geometry(model, layout, mm, b)
    axes = beam_axes(e, mm.orientation[b])
    k = beam_stiffness(sec.E[b], sec.G[b], sec.A[b], sec.Iy[b], sec.Iz[b], sec.J[b], l)
    return Blocks(beam_dofs(layout, mm, b), to_global(k, axes)), sec.psi[b]


def _carriers_of(model, dofs, i):
    """Rigid groups (or GROUND) a node moves with: its carrier, and at a joint's node
    every group the joint connects."""
    out = {int(dofs.carrier[i])} if dofs.carrier[i] != -2 else set()
    for j in model.joints:
        if j.at == i:
            out |= {GROUND if b == GROUND else int(dofs.group_of_body[b]) for b in j.bodies}
    return out


def mass_and_gravity(model, dofs, effects):
    """Primitive inertia matrix, gravity forces, and the weights bodies carry.

    Returns (M (n_u, n_u), f (n_u,), gravity_points): gravity_points lists
    (body, point, force) for each weight on a body (its own, point masses on its nodes,
    rigid members) at its point of application, for the load stiffness.
    """
    layout = dofs.layout
    g6 = np.concatenate([model.gravity, np.zeros(3)])
    rows, cols, vals = [], [], []

    def block(idx, m):
        rows.append(np.repeat(idx, len(idx)))
        cols.append(np.tile(idx, len(idx)))
        vals.append(np.asarray(m).ravel())

    f = np.zeros(layout.size)
    points = [(b, body.com, body.mass * model.gravity) for b, body in enumerate(model.bodies)
              if body.mass > 0]
    body_blocks = [rigid_mass(np.array([b.mass]), b.inertia[None])[0] for b in model.bodies]
    first_body = {}
    for b, g in enumerate(dofs.group_of_body):
        first_body.setdefault(g, b)

    def add_to_body(b, m, c, inertia):
        """A mass m with rotary inertia at offset c from body b's centre of mass."""
        points.append((b, model.bodies[b].com + c, m * model.gravity))
        C = skew(c)
        blk = np.zeros((6, 6))
        blk[:3, :3] = m * np.eye(3)
        blk[:3, 3:] = -m * C
        blk[3:, :3] = m * C
        blk[3:, 3:] = -m * C @ C + inertia
        body_blocks[b] = body_blocks[b] + blk

    pm = model.masses
    for i, m, J in zip(pm.nodes, pm.mass, pm.inertia):
        car = dofs.carrier[i]
        if car >= 0:        # on a body: exact rigid contribution (parallel axes included)
            b = first_body[car]
            add_to_body(b, m, model.coords[i] - model.bodies[b].com, J)
        else:
            block(layout.node([i])[0], m * np.eye(3))
            f[layout.node([i])[0]] += m * model.gravity

    for mem in (model.members if dofs.members is None else ()):   # structure: rigid
        from ..coordinates.members import member_pairs
        pairs = member_pairs(mem)
        a, b = pairs[:, 0], pairs[:, 1]
        e, l = span_geometry(model.coords, a, b)
        # a joint's node belongs to every body the joint connects (and to the ground)
        cars = set.intersection(*(_carriers_of(model, dofs, i) for i in np.unique(pairs)))
        if not cars:
            raise ModelError("with structure: rigid a member's nodes must all be carried by "
                             "one body or the ground (found nodes on "
                             "different carriers); put them on one body or "
                             "use effects: {structure: flexible}", model.file,
                             f"members.{mem.name}")
        car = GROUND if GROUND in cars else min(cars)
        if car == GROUND:
            continue
        bi = first_body[car]
        for ek, lk, ak, bk in zip(e, l, a, b):
            me = mem.rho * mem.A * lk
            mid = 0.5 * (model.coords[ak] + model.coords[bk])
            add_to_body(bi, me, mid - model.bodies[bi].com,
                        me * lk**2 / 12 * (np.eye(3) - np.outer(ek, ek)))

    for b, blk in enumerate(body_blocks):
        idx = layout.body(b)
        block(idx, blk)
        f[idx] += blk @ g6

    for d, drum in enumerate(model.drums):
        block([layout.drum(d)], [[drum.reduced_inertia]])

    rm = dofs.ropes
    if rm is not None:          # rope elements: B^T M6 B on their end maps
        from ..coordinates.ropes import element_materials, endpoint_maps
        idx, B = endpoint_maps(rm, layout)
        _, mu = element_materials(model, rm)
        M6 = rope_mass(mu, rm.length, lumped=effects.rope_mass_matrix == "lumped")
        Me = np.einsum("kai,kab,kbj->kij", B, M6, B)
        rows.append(np.repeat(idx, 8, axis=1).ravel())
        cols.append(np.tile(idx, (1, 8)).ravel())
        vals.append(Me.ravel())
        g2 = np.tile(model.gravity, 2)
        np.add.at(f, idx, np.einsum("kai,kab,b->ki", B, M6, g2))

    mm = dofs.members
    if mm is not None:          # flexible members: truss and beam element masses
        from ..elements.kernels import beam_axes, beam_mass, to_global
        from ..coordinates.members import element_sections
        sec = element_sections(model, mm)
        t, b = np.flatnonzero(~mm.beam), np.flatnonzero(mm.beam)
        g12 = np.concatenate([model.gravity, np.zeros(3), model.gravity, np.zeros(3)])
        if len(t):
            _, l = _member_geometry(model, layout, mm, t)
            idx = np.hstack([layout.node(mm.node[t, 0]), layout.node(mm.node[t, 1])])
            lump = sec.lumped[t]
            m_e = sec.rho[t] * sec.A[t] * l
            # lumped: m/2 on the diagonal (no 6x6 blocks of zeros for big lattices)
            rows.append(idx[lump].ravel())
            cols.append(idx[lump].ravel())
            vals.append(np.repeat(m_e[lump] / 2, 6))
            mt = rope_mass(sec.rho[t][~lump] * sec.A[t][~lump], l[~lump])
            rows.append(np.repeat(idx[~lump], 6, axis=1).ravel())
            cols.append(np.tile(idx[~lump], (1, 6)).ravel())
            vals.append(mt.ravel())
            np.add.at(f, idx, (m_e / 2)[:, None] * np.tile(model.gravity, 2))
        if len(b):
            e, l = _member_geometry(model, layout, mm, b)
            axes = beam_axes(e, mm.orientation[b])
            mb = np.where(sec.lumped[b][:, None, None],
                          beam_mass(sec.rho[b], sec.A[b], sec.Iy[b], sec.Iz[b], l,
                                    lumped=True),
                          beam_mass(sec.rho[b], sec.A[b], sec.Iy[b], sec.Iz[b], l))
            mg = to_global(mb, axes)
            idx = beam_dofs(layout, mm, b)
            rows.append(np.repeat(idx, 12, axis=1).ravel())
            cols.append(np.tile(idx, (1, 12)).ravel())
            vals.append(mg.ravel())
            np.add.at(f, idx, mg @ g12)

    for ld in model.linear_drives:      # rotor turns i/R rad per metre of stroke (eq. 14)
        a, c = ld.nodes
        e, _ = span_geometry(model.coords, np.array([a]), np.array([c]))
        cc, v = elongation_rows(e, np.ones(1), layout.node([a]), layout.node([c]))
        jm = ld.rotor_inertia * (ld.gear_ratio / ld.pinion_radius) ** 2
        block(cc[0], jm * np.outer(v[0], v[0]))
    M = _coo(rows, cols, vals, (layout.size, layout.size))
    return M, f, tuple(points)


def geometric_stiffness(model, dofs, static):
    """Tension stiffness of spans, beams and the load stiffness of rigid groups, as a
    tuple of Blocks (primitive coordinates)."""
    layout = dofs.layout
    out = []
    for a, b, falls, N in static.spans():
        e, l = span_geometry(dofs.coords, a, b)
        out.append(Blocks(np.hstack([layout.node(a), layout.node(b)]),
                          string_stiffness(N, falls, e, l)))
    mm = dofs.members
    if mm is not None and mm.beam.any():
        from ..elements.kernels import beam_axes, beam_geometric, to_global
        bi = np.flatnonzero(mm.beam)
        e, l = span_geometry(dofs.coords, mm.node[bi, 0], mm.node[bi, 1])
        out.append(Blocks(beam_dofs(layout, mm, bi),
                          to_global(beam_geometric(static.beam_force, l),
                                    beam_axes(e, mm.orientation[bi]))))
    first_body = {}
    for b, g in enumerate(dofs.group_of_body):
        first_body.setdefault(g, b)
    for g, point, F in static.point_forces(dofs):
        H = load_stiffness(F, point - dofs.group_ref[g]).sum(axis=0)
        out.append(Blocks(layout.body(first_body[g])[None, 3:], H[None]))
    return tuple(out)


def pattern(springs, dofs, elastic_blocks=(), geometric=()):
    """Sum of element matrices each scaled to unit size (PSD, null space of K)."""
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


def elastic_stiffness(model, dofs, effects=None):
    """Primitive elastic stiffness: spring rows and beam blocks -> (K_u, springs, beams,
    beam_psi). Inextensible ropes (rope_elasticity: false) are constraints of the DOF
    map, so their rows carry no stiffness here."""
    springs = spring_rows(model, dofs.layout, dofs.ropes, dofs.members)
    if effects is not None and not effects.rope_elasticity:
        from dataclasses import replace
        springs = replace(springs, c=np.where(springs.rope >= 0, 0.0, springs.c))
    K_u = springs.R.T @ sp.diags(springs.c) @ springs.R
    beams, beam_psi = None, None
    if dofs.members is not None and dofs.members.beam.any():
        beams, beam_psi = beam_blocks(model, dofs.layout, dofs.members)
        K_u = K_u + sum_blocks([beams], dofs.layout.size)
    return K_u.tocsr(), springs, beams, beam_psi


def assemble(model, effects=None, reuse=None):
    """Assemble K, M, f for `model` with `effects` (default: the model's own).

    `reuse`: a `cranefe.assembly.reuse.Reuse` holding work of earlier models of the same
    structure (the DOF maps, the static null space), as a sweep's variants share it."""
    import time
    t0 = time.perf_counter()
    effects = effects or model.effects
    dofs = reuse.dofs(model, effects) if reuse else build_dofs(model, effects)
    K_u, springs, beams, beam_psi = elastic_stiffness(model, dofs, effects)
    M_u, f_u, _ = mass_and_gravity(model, dofs, effects)
    static, geometric = None, ()
    if effects.sway:
        from ..statics import solve_static
        static = solve_static(model, effects, reuse)
        geometric = geometric_stiffness(model, dofs, static)
        K_u = K_u + sum_blocks(geometric, dofs.layout.size)
    T = dofs.T
    K = (T.T @ K_u @ T).tocsr()
    K = ((K + K.T) * 0.5).tocsr()
    M = (T.T @ M_u @ T).tocsr()
    M = ((M + M.T) * 0.5).tocsr()
    return System(model, effects, dofs, K, M, T.T @ f_u, springs, beams, beam_psi,
                  geometric, static, {"assemble": time.perf_counter() - t0})
