"""Inertia and gravity in primitive coordinates: point masses, rigid bodies (with what
they carry), drums, rope elements, flexible members and linear-drive rotors."""

import numpy as np

from ..elements import (beam_axes, beam_mass, elongation_rows, rigid_mass, rope_mass, skew,
                        span_geometry, to_global)
from ..coordinates.members import member_pairs
from ..coordinates.ropes import endpoint_maps
from ..errors import ModelError
from ..model import GROUND
from .beams import beam_dofs, end_releases, local_released
from .coo import Triplets
from .materials import element_materials, element_sections, shear_parameters
from .springs import member_geometry


class _BodyMass:
    """The 6x6 mass of every body at its centre of mass, with what its nodes carry, and
    the weights it carries at their points (for the load stiffness)."""

    def __init__(self, model, dofs):
        self.model = model
        self.blocks = [rigid_mass(np.array([b.mass]), b.inertia[None])[0]
                       for b in model.bodies]
        self.points = [(b, body.com, body.mass * model.gravity)
                       for b, body in enumerate(model.bodies) if body.mass > 0]
        self.first_body = {}
        for b, g in enumerate(dofs.group_of_body):
            self.first_body.setdefault(g, b)

    def add(self, b, m, c, inertia):
        """A mass m with rotary inertia at offset c from body b's centre of mass
        (parallel axes: [[m I, -m C], [m C, -m C C + J]] with C = skew(c))."""
        self.points.append((b, self.model.bodies[b].com + c, m * self.model.gravity))
        C = skew(c)
        blk = np.zeros((6, 6))
        blk[:3, :3] = m * np.eye(3)
        blk[:3, 3:] = -m * C
        blk[3:, :3] = m * C
        blk[3:, 3:] = -m * C @ C + inertia
        self.blocks[b] = self.blocks[b] + blk


def _carriers_of(model, dofs, i):
    """Rigid groups (or GROUND) a node moves with: its carrier, and at a joint's node
    every group the joint connects."""
    out = {int(dofs.carrier[i])} if dofs.carrier[i] != -2 else set()
    for j in model.joints:
        if j.at == i:
            out |= {GROUND if b == GROUND else int(dofs.group_of_body[b]) for b in j.bodies}
    return out


def _point_masses(model, dofs, bodies, t, f):
    """A mass on a body adds to it exactly; a free node's mass is its own, and its
    rotary inertia goes to the node's rotations (which exist where beams meet; elsewhere
    they have no coordinates and it drops out)."""
    layout = dofs.layout
    pm = model.masses
    for i, m, J in zip(pm.nodes, pm.mass, pm.inertia):
        car = dofs.carrier[i]
        if car >= 0:
            b = bodies.first_body[car]
            bodies.add(b, m, model.coords[i] - model.bodies[b].com, J)
        else:
            idx = layout.node([i])
            t.add_blocks(idx, m * np.eye(3)[None])
            f[idx[0]] += m * model.gravity
            if np.any(J):
                t.add_blocks(layout.rot([i]), J[None])


def _rigid_members(model, dofs, bodies):
    """With structure: rigid, each member element's mass (a slender rod) joins the body
    that carries all its nodes."""
    for mem in model.members:
        pairs = member_pairs(mem)
        a, b = pairs[:, 0], pairs[:, 1]
        e, l = span_geometry(model.coords, a, b)
        # a joint's node belongs to every body the joint connects (and to the ground)
        cars = set.intersection(*(_carriers_of(model, dofs, i) for i in np.unique(pairs)))
        if not cars:
            raise ModelError("with structure: rigid a member's nodes must all be carried by "
                             "one body or the ground (found nodes on different carriers); "
                             "put them on one body or use effects: {structure: flexible}",
                             model.file, f"members.{mem.name}")
        car = GROUND if GROUND in cars else min(cars)
        if car == GROUND:
            continue
        bi = bodies.first_body[car]
        for ek, lk, ak, bk in zip(e, l, a, b):
            me = mem.rho * mem.A * lk
            mid = 0.5 * (model.coords[ak] + model.coords[bk])
            bodies.add(bi, me, mid - model.bodies[bi].com,
                       me * lk**2 / 12 * (np.eye(3) - np.outer(ek, ek)))


def _rope_elements(model, dofs, effects, t, f):
    """Rope elements: B^T M6 B on their end maps (ends that slide over sheaves)."""
    rm = dofs.ropes
    idx, B = endpoint_maps(rm, dofs.layout)
    _, mu = element_materials(model, rm)
    M6 = rope_mass(mu, rm.length, lumped=effects.rope_mass_matrix == "lumped")
    t.add_blocks(idx, np.einsum("kai,kab,kbj->kij", B, M6, B))
    np.add.at(f, idx, np.einsum("kai,kab,b->ki", B, M6, np.tile(model.gravity, 2)))


def _trusses(model, dofs, sec, tr, t, f):
    """Truss elements: lumped m/2 on the diagonal (no 6x6 blocks of zeros for big
    lattices) or the consistent rod mass."""
    layout, mm = dofs.layout, dofs.members
    _, l = member_geometry(model, layout, mm, tr)
    idx = np.hstack([layout.node(mm.node[tr, 0]), layout.node(mm.node[tr, 1])])
    lump = sec.lumped[tr]
    m_e = sec.rho[tr] * sec.A[tr] * l
    t.add(idx[lump], idx[lump], np.repeat(m_e[lump] / 2, 6))
    t.add_blocks(idx[~lump], rope_mass(sec.rho[tr][~lump] * sec.A[tr][~lump], l[~lump]))
    f += np.bincount(idx.ravel(), ((m_e / 2)[:, None] * np.tile(model.gravity, 2)).ravel(),
                     minlength=len(f))


def _beams(model, dofs, sec, b, t, f):
    layout, mm = dofs.layout, dofs.members
    e, l = member_geometry(model, layout, mm, b)
    axes = beam_axes(e, mm.orientation[b])
    mb = np.where(sec.lumped[b][:, None, None],
                  beam_mass(sec.rho[b], sec.A[b], sec.Iy[b], sec.Iz[b], l, lumped=True),
                  beam_mass(sec.rho[b], sec.A[b], sec.Iy[b], sec.Iz[b], l, False,
                            *shear_parameters(sec, b, l), rotary=sec.timoshenko[b]))
    mb = local_released(mb, end_releases(model, layout, mm, b, sec, l))
    mg = to_global(mb, axes)
    idx = beam_dofs(layout, mm, b)
    t.add_blocks(idx, mg)
    g12 = np.concatenate([model.gravity, np.zeros(3), model.gravity, np.zeros(3)])
    np.add.at(f, idx, mg @ g12)


def _linear_drives(model, layout, t):
    """The rotor turns i / R rad per metre of stroke (Loveikin et al. 2013, eq. 14)."""
    for ld in model.linear_drives:
        a, c = ld.nodes
        e, _ = span_geometry(model.coords, np.array([a]), np.array([c]))
        cc, v = elongation_rows(e, np.ones(1), layout.node([a]), layout.node([c]))
        jm = ld.rotor_inertia * (ld.gear_ratio / ld.pinion_radius) ** 2
        t.add_blocks(cc, jm * np.outer(v[0], v[0])[None])


def mass_and_gravity(model, dofs, effects):
    """Primitive inertia matrix, gravity forces, and the weights bodies carry.

    Returns (M (n_u, n_u), f (n_u,), gravity_points): gravity_points lists
    (body, point, force) for each weight on a body (its own, point masses on its nodes,
    rigid members) at its point of application, for the load stiffness.
    """
    layout = dofs.layout
    t = Triplets()
    f = np.zeros(layout.size)
    bodies = _BodyMass(model, dofs)
    _point_masses(model, dofs, bodies, t, f)
    if dofs.members is None:
        _rigid_members(model, dofs, bodies)
    g6 = np.concatenate([model.gravity, np.zeros(3)])
    for b, blk in enumerate(bodies.blocks):
        idx = layout.body(b)
        t.add_blocks(idx[None], blk[None])
        f[idx] += blk @ g6
    for d, drum in enumerate(model.drums):
        t.add([layout.drum(d)], [layout.drum(d)], [drum.reduced_inertia])
    if dofs.ropes is not None:
        _rope_elements(model, dofs, effects, t, f)
    mm = dofs.members
    if mm is not None:
        sec = element_sections(model, mm)
        tr, b = np.flatnonzero(~mm.beam), np.flatnonzero(mm.beam)
        if len(tr):
            _trusses(model, dofs, sec, tr, t, f)
        if len(b):
            _beams(model, dofs, sec, b, t, f)
    _linear_drives(model, layout, t)
    return t.csr((layout.size, layout.size)), f, tuple(bodies.points)
