"""Element kernels (pipeline stage 1): pure, batched functions of the current geometry and
element arrays. Nothing here sees a `Model`, a DOF map or a global index: assembly
(`cranefe.assembly`) gathers the arrays from the model and scatters the element arrays.

- `ropes`: spans of ropes, axial springs and trusses (length, direction, elongation
  rows, tension stiffness, rope element mass, whole-rope force at any geometry);
- `bodies`: rigid bodies (cross-product matrices, rigid mass, load stiffness);
- `motion`: rigid motions of hinges and sliders at any angle, with their derivatives;
- `beams`: 3D Euler-Bernoulli and Timoshenko beams (elastic, mass and geometric stiffness,
  rotations).
"""

from .beams import (beam_axes, beam_geometric, beam_mass, beam_stiffness, release_transforms,
                    shear_factors, to_global, transform)
from .bodies import load_stiffness, rigid_mass, skew
from .motion import IDENTITY_MOTION, compose, hinge_motion, slider_motion
from .ropes import (RopeForce, elongation_rows, hencky_energy, hencky_tension,
                    projected_tangent, rope_force, rope_mass, rope_spans, rope_state,
                    span_geometry, spring_state, string_stiffness)

__all__ = ["beam_axes", "beam_geometric", "beam_mass", "beam_stiffness", "shear_factors",
           "to_global", "release_transforms", "transform",
           "load_stiffness", "rigid_mass", "skew", "elongation_rows", "rope_mass",
           "span_geometry", "string_stiffness", "rope_force", "RopeForce",
           "hencky_tension", "hencky_energy", "rope_spans", "rope_state", "spring_state",
           "projected_tangent", "IDENTITY_MOTION", "compose", "hinge_motion",
           "slider_motion"]
