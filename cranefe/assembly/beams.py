"""Beam elements of flexible members: elastic stiffness blocks in global axes."""

import numpy as np

from ..elements import beam_axes, beam_stiffness, to_global
from .coo import Blocks
from .materials import element_sections, shear_parameters
from .springs import member_geometry


def beam_dofs(layout, mm, which):
    """(ne, 12) primitive indices: translations and rotations of both ends."""
    return np.hstack([6 * mm.node[which, :1] + np.arange(6), 6 * mm.node[which, 1:] +
                      np.arange(6)]) if len(which) else np.zeros((0, 12), dtype=int)


def beam_blocks(model, layout, mm):
    """Elastic stiffness of the beam elements in global axes, and their absorption."""
    sec = element_sections(model, mm)
    b = np.flatnonzero(mm.beam)
    e, l = member_geometry(model, layout, mm, b)
    axes = beam_axes(e, mm.orientation[b])
    k = beam_stiffness(sec.E[b], sec.G[b], sec.A[b], sec.Iy[b], sec.Iz[b], sec.J[b], l,
                       *shear_parameters(sec, b, l))
    return Blocks(beam_dofs(layout, mm, b), to_global(k, axes)), sec.psi[b]
