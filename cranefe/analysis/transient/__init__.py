"""Transient simulation of scenes: hoist start, lifting a load off the ground, slack
ropes (docs/transient.md).

- `scene`: the keys of ``analysis: {type: transient, ...}``, checked;
- `problem`: the scene's equations in the model's generalised coordinates (tension-only
  ropes, ground contact, drum drives);
- `modal`: the same in principal coordinates (Heletiy 2016, eq. 7-9 and 14-17);
- `newmark`: average-acceleration stepping with event location;
- `results`, `output`: the result dataclass and its presentation.

``simulate(model)`` (in `integrate`) runs a scene.
"""
