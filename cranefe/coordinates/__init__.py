"""Coordinates (pipeline stage): which degrees of freedom exist for the effects that are
on, and the one constraint transform u = T q (docs/theory.md, "Coordinates").

- `dofmap`: the generalised coordinates and `build_dofs`;
- `ropes`, `members`: the meshes of ropes with mass and of flexible members.
"""

from .dofmap import DofMap, Layout, build_dofs, entry_of, structure_key

__all__ = ["DofMap", "Layout", "build_dofs", "entry_of", "structure_key"]
