"""The linearised system about the static state (pipeline stage after `statics`).

Elastic stiffness and inertia come from `cranefe.assembly`; with sway on, the static
state (`cranefe.statics`) gives the tensions whose stiffness is added here: tension
stiffness of spans and beams and the load stiffness of rigid groups (docs/theory.md).
Everything is in primitive coordinates and mapped once, ``K_q = T^T K_u T``.
"""

import time
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from .assembly import Blocks, elastic_stiffness, mass_and_gravity, pattern, sum_blocks
from .assembly.beams import axial_variation, beam_dofs, beam_geometric_local
from .assembly.springs import SpringRows
from .coordinates import build_dofs
from .elements import (beam_axes, load_stiffness, span_geometry,
                       string_stiffness, to_global)
from .statics import solve_static


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


def geometric_stiffness(dofs, static):
    """Tension stiffness of spans and beams and the load stiffness of rigid groups, as a
    tuple of Blocks (primitive coordinates)."""
    layout = dofs.layout
    out = []
    for a, b, falls, N in static.spans():
        e, l = span_geometry(dofs.coords, a, b)
        out.append(Blocks(np.hstack([layout.node(a), layout.node(b)]),
                          string_stiffness(N, falls, e, l)))
    mm = dofs.members
    if mm is not None and mm.beam.any():
        bi = np.flatnonzero(mm.beam)
        e, l = span_geometry(dofs.coords, mm.node[bi, 0], mm.node[bi, 1])
        dN = axial_variation(static.model, layout, mm, bi)
        kg = beam_geometric_local(static.model, layout, mm, bi, static.beam_force, l, dN)
        out.append(Blocks(beam_dofs(layout, mm, bi),
                          to_global(kg, beam_axes(e, mm.orientation[bi]))))
    first_body = {}
    for b, g in enumerate(dofs.group_of_body):
        first_body.setdefault(g, b)
    for g, point, F in static.point_forces(dofs):
        H = load_stiffness(F, point - dofs.group_ref[g]).sum(axis=0)
        out.append(Blocks(layout.body(first_body[g])[None, 3:], H[None]))
    return tuple(out)


def assemble(model, effects=None, reuse=None):
    """Assemble K, M, f for `model` with `effects` (default: the model's own).

    `reuse`: a `cranefe.assembly.reuse.Reuse` holding work of earlier models of the same
    structure (the DOF maps, the static null space), as a sweep's variants share it."""
    t0 = time.perf_counter()
    effects = effects or model.effects
    dofs = reuse.dofs(model, effects) if reuse else build_dofs(model, effects)
    K_u, springs, beams, beam_psi = elastic_stiffness(model, dofs, effects)
    M_u, f_u, _ = mass_and_gravity(model, dofs, effects)
    static, geometric = None, ()
    if effects.sway:
        static = solve_static(model, effects, reuse)
        geometric = geometric_stiffness(dofs, static)
        K_u = K_u + sum_blocks(geometric, dofs.layout.size)
    T = dofs.T
    K = (T.T @ K_u @ T).tocsr()
    K = ((K + K.T) * 0.5).tocsr()
    M = (T.T @ M_u @ T).tocsr()
    M = ((M + M.T) * 0.5).tocsr()
    return System(model, effects, dofs, K, M, T.T @ f_u, springs, beams, beam_psi,
                  geometric, static, {"assemble": time.perf_counter() - t0})
