"""Large motions of cranes: operation scenes (docs/operations.md).

- `kernels`: pure batched kernels (rope and spring states at any geometry, rigid joint
  motions);
- `profiles`: motion profiles of prescribed drives (trapezoid, S-curve, speed tables);
- `scene`: the keys of ``analysis: {type: operation, ...}``, checked;
- `mechanism`: the scene's coordinates, static reference state and forces;
- `integrate`: the implicit integrator with step control and events (`simulate`);
- `results`, `output`: the result dataclass and its presentation.
"""
