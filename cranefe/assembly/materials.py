"""Element values gathered from the model into arrays for the kernels.

The rope and member meshes (`cranefe.coordinates`) are structure only, so one mesh
serves models that differ only in these values (the variants of a sweep).
"""

from dataclasses import dataclass

import numpy as np

from ..elements import shear_factors


def element_materials(model, rm):
    """(EA, mu), each (ne,), of the rope elements of the RopeMesh `rm`; the extra-length
    piece of a rope is massless."""
    EA = np.array([r.EA for r in model.ropes], dtype=float)
    mu = np.array([r.mass_per_length for r in model.ropes], dtype=float)
    return EA[rm.rope], np.where(rm.fall >= 0, mu[rm.rope], 0.0)


@dataclass(frozen=True)
class Sections:
    """Material and section of each member element (ne,), from its member."""

    E: np.ndarray
    G: np.ndarray
    A: np.ndarray
    Iy: np.ndarray
    Iz: np.ndarray
    J: np.ndarray
    rho: np.ndarray
    psi: np.ndarray
    lumped: np.ndarray        # bool: lumped mass matrix
    Asy: np.ndarray = None    # shear areas (0: no shear deformation)
    Asz: np.ndarray = None
    timoshenko: np.ndarray = None   # bool: shear deformation and rotary inertia


def element_sections(model, mm):
    """`Sections` of the elements of the MemberMesh `mm`, read from the model's members."""
    per = {k: np.array([float(getattr(m, k)) for m in model.members])
           for k in ("E", "G", "A", "Iy", "Iz", "J", "rho", "psi")}
    lumped = np.array([m.mass == "lumped" for m in model.members], dtype=bool)
    timo = np.array([m.timoshenko for m in model.members], dtype=bool)
    shear = {k: np.array([float(getattr(m, k)) for m in model.members])[mm.member]
             for k in ("Asy", "Asz")}
    return Sections(**{k: v[mm.member] for k, v in per.items()}, lumped=lumped[mm.member],
                    timoshenko=timo[mm.member], **shear)


def shear_parameters(sec, b, l):
    """(phi_y, phi_z) of beam elements b with lengths l, or (None, None) when none of
    them is a Timoshenko beam (the Euler-Bernoulli kernels unchanged)."""
    if not sec.timoshenko[b].any():
        return None, None
    return shear_factors(sec.E[b], sec.G[b], sec.Iy[b], sec.Iz[b], sec.Asy[b], sec.Asz[b], l)
