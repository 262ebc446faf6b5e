"""Assembly (pipeline stage): element values gathered from the model, element kernels
called, and one COO step to sparse matrices in primitive coordinates.

- `springs`: elongation rows of ropes, trusses and springs (K = R^T diag(c) R);
- `beams`: elastic blocks of beam elements; `stiffness`: the elastic K_u of both;
- `inertia`: M_u and gravity forces; `pattern`: which motions nothing resists;
- `materials`: element values read from the model; `coo`: the one assembly step;
- `reuse`: what a sweep's variants of one structure share.

The static state (`cranefe.statics`) and the tension stiffness of the linearised system
(`cranefe.system`) come after this stage.
"""

from .coo import Blocks, coo, sum_blocks
from .inertia import mass_and_gravity
from .pattern import null_space, pattern
from .springs import SpringRows, spring_rows
from .stiffness import elastic_stiffness

__all__ = ["Blocks", "coo", "sum_blocks", "mass_and_gravity", "null_space", "pattern",
           "SpringRows", "spring_rows", "elastic_stiffness"]
