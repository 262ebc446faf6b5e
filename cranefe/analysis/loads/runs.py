"""The simulations behind the dynamic factors: scenes built from a model and a
`LoadsSpec`, run on the transient core (lift-off, hoist start, release) and on the
operation engine (joint drives). Each returns the raw result and a `Trace` saying what
was simulated (docs/loads.md, "How each factor is simulated").
"""

from dataclasses import dataclass, replace

import numpy as np

from ...errors import AnalysisError


@dataclass(frozen=True)
class Trace:
    """What one simulation was: its name, engine, scene parameters and cost."""

    name: str
    engine: str               # transient | operation
    parameters: dict
    duration: float
    steps: int
    seconds: float

    def to_dict(self):
        return {"name": self.name, "engine": self.engine, "parameters": self.parameters,
                "duration_s": self.duration, "steps": self.steps,
                "seconds": round(self.seconds, 6)}


def placed(model, spec):
    """The model at the spec's working point: `radius_nodes` moved horizontally to
    `radius` from the vertical axis through the first ground node (keeping their
    azimuth), the load node(s) to `hook_height` (their rope gets longer or shorter)."""
    if spec.radius is None and spec.hook_height is None:
        return model
    X = model.coords.copy()
    up = -model.gravity / np.linalg.norm(model.gravity)
    idx = model.node_index
    if spec.radius is not None:
        base = X[int(model.ground[0])] if len(model.ground) else np.zeros(3)
        for n in spec.radius_nodes:
            i = idx[n]
            d = X[i] - base
            h = d - (d @ up) * up
            r = np.linalg.norm(h)
            e = h / r if r > 0 else np.array([1.0, 0.0, 0.0])
            X[i] = base + (d @ up) * up + spec.radius * e
    if spec.hook_height is not None:
        for n in spec.loads:
            i = idx[n]
            X[i] = X[i] + (spec.hook_height - X[i] @ up) * up
    return replace(model, coords=X)


def lift_model(model):
    """The model with sway off and no damping: a vertical lift (a grounded load has no
    pendulum stiffness; the factors are the undamped peaks, as EN 13001-2 means them)."""
    return model.with_effects(sway=False, damping="none")


def hook_per_drum(model, drum):
    """Metres of hook travel per radian of the drum (R / falls, from the rope row that
    leaves the drum and the point mass it moves most)."""
    from ...system import assemble
    s = assemble(lift_model(model))
    d = s.dofs
    R = (s.springs.R @ d.T).tocsr()
    j = d.labels.index(f"drum {drum}")
    rows = np.flatnonzero(np.abs(R[:, j].toarray().ravel()) > 0)
    masses = [k for k, kind in enumerate(d.kinds) if kind == "node"]
    best = 0.0
    for row in rows:
        coef = np.abs(R[row, masses].toarray().ravel())
        if coef.size and coef.max() > best:
            best, ratio = coef.max(), abs(R[row, j]) / coef.max()
    if best == 0.0:
        raise AnalysisError(f"drum '{drum}' moves no point mass through its rope; cranefe "
                            "loads needs a hoist load hanging on the drum's rope")
    return float(ratio)


def _transient(model, name, analysis):
    from ...analysis.transient.integrate import simulate
    m = replace(model, analysis=dict(analysis, type="transient"),
                scene=f"loads: {name}")
    return simulate(m)


def s_curve_speeds(v_max, ramp, jerk, h):
    """Speed table [[t, v], ...] of a jerk-limited start from rest to v_max in `ramp`
    seconds, the acceleration rising linearly over `jerk` seconds to a = v_max /
    (ramp - jerk), held, and falling over `jerk` (sampled every h <= jerk/8: the
    transient core's tables are piecewise linear in speed) -> (table, a)."""
    a = v_max / (ramp - jerk)
    n = max(8, int(np.ceil(jerk / h))) if jerk > 0 else 0
    t1 = np.linspace(0.0, jerk, n + 1) if n else np.zeros(1)
    v1 = 0.5 * a * t1**2 / jerk if n else np.zeros(1)
    up = np.column_stack([t1, v1])
    down = np.column_stack([ramp - t1[::-1], v_max - v1[::-1]])
    table = np.vstack([up, down]) if ramp - jerk > jerk else np.vstack([up[:-1], down])
    return table.tolist(), a


def lift_off(model, spec, name, drum_speed, guess=None):
    """Lift the grounded load at a prescribed drum speed (rad/s, a step at t = 0: the
    rigid drive of phi2; HD5's start is `hoist_start`): -> (TransientResult, Trace).
    Runs until `after_lift_off` seconds past the lift-off (again, longer, if `guess` of
    the lift-off time was short)."""
    import time
    t0 = time.perf_counter()
    drive = {"speed": float(drum_speed)}
    guess = guess or 1.0
    res = None
    for _ in range(6):
        duration = guess + spec.after_lift_off
        a = dict(_steps(spec, model), duration=duration, initial="grounded",
                 grounded=list(spec.loads), drums={spec.drum: drive})
        res = _transient(model, name, a)
        t_lift = res.lift_off_time
        if np.isfinite(t_lift) and t_lift + spec.after_lift_off <= duration * (1 + 1e-9):
            break
        guess = t_lift * 1.05 if np.isfinite(t_lift) else 4 * guess
    else:
        raise AnalysisError(f"{name}: the load does not lift off within "
                            f"{res.duration:g} s at drum speed {drum_speed:g} rad/s")
    params = {"initial": "grounded", "loads": list(spec.loads), "drum": spec.drum,
              "drum_speed_rad_s": float(drum_speed),
              "start": "step to full speed at t = 0",
              "time_step_s": float(res.time_step),
              "effects": {"sway": False, "damping": "none"}}
    return res, Trace(name, "transient", params, float(res.duration), int(res.steps),
                      time.perf_counter() - t0)


def _table_step(spec):
    return min(spec.time_step or np.inf, spec.jerk / 16 if spec.jerk > 0 else np.inf,
               0.01)


STEPS_PER_PERIOD = 60     # default step: this many per period of the highest mode


def _steps(spec, model=None):
    """time_step: given, else STEPS_PER_PERIOD per period of the model's highest
    frequency (finer than the transient core's automatic twenty: the factors are peaks)."""
    out = {"max_steps": 10 ** 7}
    if spec.time_step:
        out["time_step"] = spec.time_step
    elif model is not None:
        from ...analysis.transient.problem import highest_omega
        from ...system import assemble
        w = highest_omega(assemble(model))
        if w > 0:
            out["time_step"] = 2 * np.pi / (STEPS_PER_PERIOD * w)
    return out


def hoist_start(model, spec, drum_speed):
    """The hanging load hoisted from rest along the jerk-limited start profile ->
    (TransientResult, Trace, rigid-body hook acceleration a)."""
    import time
    t0 = time.perf_counter()
    table, acc = s_curve_speeds(drum_speed, spec.ramp, spec.jerk, _table_step(spec))
    duration = spec.ramp + spec.after_lift_off
    a = dict(_steps(spec, model), duration=duration, initial="static",
             drums={spec.drum: {"speed": table}})
    res = _transient(model, "hoist start", a)
    params = {"initial": "static", "drum": spec.drum, "drum_speed_rad_s": float(drum_speed),
              "start": f"jerk-limited, {spec.ramp:g} s to full speed, jerk time "
                       f"{spec.jerk:g} s", "time_step_s": float(res.time_step),
              "effects": {"sway": False, "damping": "none"}}
    return res, Trace("hoist start", "transient", params, duration, int(res.steps),
                      time.perf_counter() - t0), acc


def release(model, spec):
    """Release of dm = fraction x m from the load, over `release_time` (0: sudden).

    By linearity (docs/loads.md, "phi3"): with the remaining mass m' = m - dm on the
    hook, the true rope force is S_m - (S_run(t) - S_m'), S_run the response of the
    model with m' at rest under gravity to a *downward* force dm g applied over the
    release time. The run is integrated by modal superposition with every mode (linear,
    equal to direct integration to round-off), so it never goes slack; whether the true
    rope goes slack is read from the result. -> (run, model with m', Trace)."""
    import time
    t0 = time.perf_counter()
    idx = model.node_index
    load = idx[spec.loads[0]]
    k = int(np.flatnonzero(model.masses.nodes == load)[0])
    m = float(model.masses.mass[k])
    dm = spec.fraction * m
    mass = model.masses.mass.copy()
    mass[k] = m - dm
    reduced = replace(model, masses=replace(model.masses, mass=mass))
    g = np.asarray(model.gravity, float)
    force = (dm * g).tolist()
    drive = {"force": force}
    if spec.release_time > 0:
        drive["ramp"] = spec.release_time
    from ...system import assemble
    n = assemble(reduced).dofs.n
    duration = spec.release_time + spec.after_lift_off
    a = dict(_steps(spec, reduced), duration=duration, method="modal", modes=n,
             initial="static",
             forces={spec.loads[0]: drive})
    res = _transient(reduced, "release", a)
    params = {"load": spec.loads[0], "mass_kg": m, "released_kg": dm,
              "release_time_s": spec.release_time, "method": "modal (all modes)",
              "time_step_s": float(res.time_step), "effects": {"sway": False,
                                                         "damping": "none"}}
    return res, reduced, Trace("release", "transient", params, duration, int(res.steps),
                               time.perf_counter() - t0)


def joint_move(model, spec, move, output_step=0.01, shapers=()):
    """A jerk-limited move (s-curve; trapezoid for jerk 0) of one slider or hinge on the
    operation engine (sway on, no damping): -> (OperationResult, Trace, a_max); with
    `shapers` (ZV, ZVD, ...): the move unshaped and shaped by each, frequency from the
    crane's own modes -> {NAME: {residual_sway_deg, move_time_s, ...}}."""
    import time
    from ...analysis.operation.integrate import simulate
    t0 = time.perf_counter()
    # a pendulum half-period after the move (the longest rope below the load's carrier)
    up = -model.gravity / np.linalg.norm(model.gravity)
    heights = [model.coords[model.node_index[n]] @ up for n in spec.loads]
    top = max(model.coords[:, :] @ up)
    length = max(top - min(heights), 1.0)
    period = 2 * np.pi * np.sqrt(length / np.linalg.norm(model.gravity))
    move_time = abs(move.distance) / move.v_max + move.ramp
    duration = move_time + 0.75 * period
    key = "slider" if move.kind == "slider" else "hinge"
    a_max = move.v_max / (move.ramp - move.jerk)
    prof = {"type": "trapezoid", "distance": move.distance, "v_max": move.v_max,
            "a_max": a_max} if move.jerk == 0 else \
        {"type": "s_curve", "distance": move.distance, "v_max": move.v_max,
         "a_max": a_max, "j_max": a_max / move.jerk}
    a = {"type": "operation", "duration": duration, "output_step": output_step,
         "drives": {move.joint: {key: move.joint, "profile": prof}}}
    if spec.tolerance is not None:
        a["tolerance"] = spec.tolerance
    m = replace(model.with_effects(sway=True, damping="none"), analysis=a,
                scene=f"loads: {move.joint} move")
    if shapers:             # the same move once per shaper (analysis/shaping/engine.py)
        from ..shaping.engine import compare
        return compare(m, move.joint, kinds=("unshaped",) + tuple(shapers))["shapers"]
    res = simulate(m)
    params = {"joint": move.joint, "kind": move.kind, "profile": prof,
              "tolerance": spec.tolerance, "output_step_s": output_step,
              "effects": {"sway": True, "damping": "none"}}
    return res, Trace(f"{move.joint} move", "operation", params, duration, int(res.steps),
                      time.perf_counter() - t0), a_max
