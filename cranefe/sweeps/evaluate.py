"""One variant of a sweep, computed in whatever process runs it.

Work that depends only on the model's structure is reused across variants of one
process: the DOF map (coordinates, constraints, the transform u = T q) is kept under a key
of everything it depends on, so a sweep over stiffnesses, loads or drive inertias builds
it once per worker (`cranefe study sweeps` measures the gain).
"""

import hashlib
import time

import numpy as np

_DOFS = {}


def structure_key(model, effects):
    """Everything the DOF map depends on."""
    h = hashlib.sha1()
    for a in (model.coords, model.ground, model.masses.nodes):
        h.update(np.ascontiguousarray(a).tobytes())
    h.update(repr((model.node_names, model.planar, effects,
                   [(b.nodes, b.mass, b.com.tobytes()) for b in model.bodies],
                   [(j.type, j.bodies, j.at, None if j.axis is None else j.axis.tobytes())
                    for j in model.joints],
                   [(d.node, d.brake) for d in model.drums],
                   [(r.span_a.tobytes(), r.span_b.tobytes(), r.falls.tobytes(), r.points)
                    for r in model.ropes],
                   [(s.type, s.nodes, s.bodies) for s in model.springs],
                   [(m.type, m.nodes, None if m.pairs is None else m.pairs.tobytes(),
                     m.elements) for m in model.members],
                   [d.nodes for d in model.linear_drives])).encode())
    return h.hexdigest()


def evaluate(job):
    """job = (raw, parameters, outputs, modes, reuse, index, values) -> result dict."""
    from ..assemble import assemble
    from ..dofs import build_dofs
    from ..errors import AnalysisError, ModelError
    from ..model import build
    from ..modal import modes
    from .spec import apply
    raw, parameters, outputs, count, reuse, index, values = job
    t0 = time.perf_counter()
    try:
        model = build(apply(raw[0], parameters, values), *raw[1:])
        dofs = None
        if reuse:
            key = structure_key(model, model.effects)
            dofs = _DOFS.get(key)
            if dofs is None:
                dofs = _DOFS.setdefault(key, build_dofs(model, model.effects))
        system = assemble(model, dofs=dofs)
        r = modes(model, count=min(count + 6, system.K.shape[0]), system=system)
        elastic = r.omega[~r.rigid]
        damping, transient = None, None
        out = []
        for name in outputs:
            if name.startswith(("phi2.", "rope_force_max.")):
                if transient is None:                 # the base is a transient scene
                    from ..transient.integrate import simulate
                    transient = simulate(model)
                rope = name.split(".", 1)[1]
                k = transient.rope_names.index(rope)
                out.append(float(transient.dynamic_factor[k] if name.startswith("phi2")
                                 else transient.rope_force_max[k]))
                continue
            if name == "dofs":
                out.append(float(r.dofs))
                continue
            kind, k = name.split(".")
            k = int(k) - 1
            if kind == "damping_ratio":
                if damping is None:
                    from ..damping import modal_damping_ratios
                    damping = modal_damping_ratios(system, r)[~r.rigid]
                out.append(float(damping[k]) if k < len(damping) else np.nan)
                continue
            w = elastic[k] if k < len(elastic) else np.nan
            out.append(float({"omega": w, "frequency_hz": w / (2 * np.pi),
                              "period_s": 2 * np.pi / w}[kind]))
        return {"index": index, "values": list(map(float, values)), "outputs": out,
                "status": "ok", "error": "", "seconds": time.perf_counter() - t0}
    except (ModelError, AnalysisError) as exc:
        message = str(exc)
    except Exception as exc:            # a variant's failure is recorded, not fatal
        message = f"{type(exc).__name__}: {exc}"
    return {"index": index, "values": list(map(float, values)),
            "outputs": [np.nan] * len(outputs), "status": "error", "error": message,
            "seconds": time.perf_counter() - t0}
