"""Beam elements of flexible members: elastic stiffness blocks in global axes."""

import numpy as np

from ..elements import (beam_axes, beam_geometric, beam_stiffness, release_transforms,
                        to_global, transform)
from .coo import Blocks
from .materials import element_sections, shear_parameters
from .springs import member_geometry


def beam_dofs(layout, mm, which):
    """(ne, 12) primitive indices: translations and rotations of both ends."""
    return np.hstack([6 * mm.node[which, :1] + np.arange(6), 6 * mm.node[which, 1:] +
                      np.arange(6)]) if len(which) else np.zeros((0, 12), dtype=int)


def _local_stiffness(sec, b, l):
    return beam_stiffness(sec.E[b], sec.G[b], sec.A[b], sec.Iy[b], sec.Iz[b], sec.J[b], l,
                          *shear_parameters(sec, b, l))


def release_mask(model, mm, b):
    """(len(b), 12) bool: the local end rotations of beam elements b that their member
    releases (`releases: {NODE: [rx, ry, rz]}` at the elements' ends at NODE)."""
    mask = np.zeros((len(b), 12), dtype=bool)
    for mi, mem in enumerate(model.members):
        for node, comps in mem.releases:
            for j in (0, 1):
                hit = (mm.member[b] == mi) & (mm.node[b, j] == node)
                mask[np.ix_(hit, 6 * j + 3 + np.asarray(comps, dtype=int))] = True
    return mask


def end_releases(model, layout, mm, b, sec=None, l=None):
    """T (len(b), 12, 12) condensing the released end rotations of beam elements b
    (`release_transforms`), or None when no member releases any."""
    if not any(m.releases for m in model.members):
        return None
    sec = element_sections(model, mm) if sec is None else sec
    if l is None:
        _, l = member_geometry(model, layout, mm, b)
    return release_transforms(_local_stiffness(sec, b, l), release_mask(model, mm, b))


def local_released(x, T):
    """x with the end releases T applied (unchanged without releases)."""
    return x if T is None else transform(x, T)


def axial_variation(model, layout, mm, b):
    """dN (len(b),): change of the static axial force along beam elements b from their
    first end to their second, -p l with p = rho A g . e the axial part of their own
    weight per length (consistent mass: a distributed load; lumped mass puts the weight
    on the nodes, and N is constant), or None without gravity along any of them."""
    sec = element_sections(model, mm)
    e, l = member_geometry(model, layout, mm, b)
    p = np.where(sec.lumped[b], 0.0, sec.rho[b] * sec.A[b]) * (e @ model.gravity)
    return None if not p.any() else -p * l


def beam_blocks(model, layout, mm):
    """Elastic stiffness of the beam elements in global axes, and their absorption."""
    sec = element_sections(model, mm)
    b = np.flatnonzero(mm.beam)
    e, l = member_geometry(model, layout, mm, b)
    axes = beam_axes(e, mm.orientation[b])
    k = _local_stiffness(sec, b, l)
    T = end_releases(model, layout, mm, b, sec, l)
    return Blocks(beam_dofs(layout, mm, b), to_global(local_released(k, T), axes)), sec.psi[b]


def beam_local_matrices(model, layout, mm, b):
    """Local stiffness and mass (with the end releases) and local axes of beam elements
    b: (k (nb, 12, 12), m (nb, 12, 12), axes (nb, 3, 3)), as assembled."""
    from ..elements import beam_mass
    sec = element_sections(model, mm)
    e, l = member_geometry(model, layout, mm, b)
    axes = beam_axes(e, mm.orientation[b])
    phi = shear_parameters(sec, b, l)
    m = np.where(sec.lumped[b][:, None, None],
                 beam_mass(sec.rho[b], sec.A[b], sec.Iy[b], sec.Iz[b], l, lumped=True),
                 beam_mass(sec.rho[b], sec.A[b], sec.Iy[b], sec.Iz[b], l, False, *phi,
                           rotary=sec.timoshenko[b]))
    T = end_releases(model, layout, mm, b, sec, l)
    return local_released(_local_stiffness(sec, b, l), T), local_released(m, T), axes


def beam_geometric_local(model, layout, mm, b, N, l, dN=None):
    """Local geometric stiffness (with the end releases) of beam elements b under mean
    axial forces N (len(b),) and their linear change dN: with the shear parameters of
    Timoshenko members (`beam_geometric`)."""
    sec = element_sections(model, mm)
    return local_released(beam_geometric(N, l, dN, *shear_parameters(sec, b, l)),
                          end_releases(model, layout, mm, b, sec, l))
