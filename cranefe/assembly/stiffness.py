"""Elastic stiffness in primitive coordinates: spring rows and beam blocks."""

from dataclasses import replace

import numpy as np
import scipy.sparse as sp

from .beams import beam_blocks
from .coo import sum_blocks
from .springs import spring_rows


def elastic_stiffness(model, dofs, effects=None):
    """(K_u, springs, beams, beam_psi): K_u = R^T diag(c) R + beam blocks.

    Inextensible ropes (rope_elasticity: false) are constraints of the DOF map, so their
    rows carry no stiffness here."""
    springs = spring_rows(model, dofs.layout, dofs.ropes, dofs.members)
    if effects is not None and not effects.rope_elasticity:
        springs = replace(springs, c=np.where(springs.rope >= 0, 0.0, springs.c))
    K_u = springs.R.T @ sp.diags(springs.c) @ springs.R
    beams, beam_psi = None, None
    if dofs.members is not None and dofs.members.beam.any():
        beams, beam_psi = beam_blocks(model, dofs.layout, dofs.members)
        K_u = K_u + sum_blocks([beams], dofs.layout.size)
    return K_u.tocsr(), springs, beams, beam_psi
