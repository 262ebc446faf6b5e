"""A digest of everything the DOF map depends on, so models of one structure share it."""

import dataclasses
import hashlib

import numpy as np


# Model values that build_dofs never reads, or reads only in part: models that differ
# only in these share one DofMap (sweeps reuse it). Each maps to what of it the key
# keeps (None: nothing); a rope's mass_per_length only decides whether it is
# discretised (rope_mass: N). Everything else is structure, so a field added later
# counts as structure until it is listed here; tests/test_sweeps.py perturbs every
# number of the examples and checks that an unchanged key means an unchanged DofMap.
VALUE_ONLY = {
    "Model": {"text": None, "analysis": None},
    "Body": {"inertia": None},
    "PointMasses": {"mass": None, "inertia": None},
    "Spring": {"stiffness": None, "psi": None},
    "Drum": {"inertia": None, "rotor_inertia": None, "gear_ratio": None},
    "Rope": {"EA": None, "psi": None, "mass_per_length": lambda mu: mu > 0},
    "Member": dict.fromkeys(("E", "G", "A", "Iy", "Iz", "J", "rho", "psi", "mass", "Asy",
                             "Asz")),
    "LinearDrive": {"pinion_radius": None, "gear_ratio": None, "rotor_inertia": None},
}


def structure_key(model, effects=None):
    """A digest of everything `build_dofs(model, effects)` depends on."""
    h = hashlib.sha1()

    def feed(x):
        if dataclasses.is_dataclass(x):
            partial = VALUE_ONLY.get(type(x).__name__, {})
            h.update(type(x).__name__.encode())
            for f in dataclasses.fields(x):
                value = getattr(x, f.name)
                if f.name in partial:
                    if partial[f.name] is None:
                        continue
                    value = partial[f.name](value)
                h.update(f.name.encode())
                feed(value)
        elif isinstance(x, np.ndarray):
            h.update(f"{x.dtype}{x.shape}".encode())
            h.update(np.ascontiguousarray(x).tobytes())
        elif isinstance(x, (tuple, list)):
            h.update(f"({len(x)}".encode())
            for v in x:
                feed(v)
        else:
            h.update(repr(x).encode())

    feed(model)
    feed(effects or model.effects)
    return h.hexdigest()
