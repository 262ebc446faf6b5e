"""`simulate(model)`: run the transient scene of a model (docs/transient.md).

Solvers by name: ``METHODS = {"direct": ..., "modal": ...}`` build the equations the
time stepper (`newmark.Stepper`) integrates: the model's generalised coordinates with
tension-only ropes and ground contact (direct), or the retained principal coordinates
(modal, `cranefe.analysis.transient.modal`).
"""

import time

import numpy as np

from .modal import modal_equations
from .newmark import Stepper
from .problem import Problem
from .results import MAX_SAMPLES, Recorder, TransientResult  # noqa: F401 (re-export)
from .scene import parse


def _direct(problem, spec):
    w = problem.highest_omega() if spec.time_step is None else float("nan")
    return problem.eq, {"modes": 0, "omega_max": w, "warnings": []}


METHODS = {"direct": _direct, "modal": modal_equations}


def time_step(spec, omega_max):
    """The step: given, or a twentieth of the shortest period retained (and at most a
    hundredth of the duration), capped at `max_steps`; returns (h, warnings)."""
    if spec.time_step is not None:
        return spec.time_step, []
    T = spec.duration
    h = np.pi / (10 * omega_max) if omega_max > 0 else T / 100
    h = min(h, T / 100)
    warnings = []
    if T / h > spec.max_steps * (1 + 1e-9):
        h = T / spec.max_steps
        warnings.append(
            f"automatic time step capped at max_steps = {spec.max_steps}: h = {h:.3g} s "
            f"resolves frequencies up to {1 / (20 * h):.4g} Hz with 20 steps a period; the "
            f"highest is {omega_max / (2 * np.pi):.4g} Hz (the method stays stable; those "
            "modes lag in phase). Give time_step or max_steps to choose")
    return h, warnings


def simulate(model, progress=None, reuse=None):
    """Integrate the transient scene of `model` -> `TransientResult`.

    progress : callable (t, duration) or None, called after each step.
    reuse : `cranefe.assembly.reuse.Reuse` of earlier models of the same structure (sweeps).
    """
    t0 = time.perf_counter()
    spec = parse(model)
    moving = any(np.any(d.profile.values) for d in spec.drums if d.kind == "speed")
    damping = spec.method == "direct" or model.effects.damping == "exact" or \
        (model.effects.damping != "none" and moving)     # coupling of prescribed drums
    problem = Problem(model, spec, damping=damping, reuse=reuse)
    t1 = time.perf_counter()
    eq, info = METHODS[spec.method](problem, spec)
    warnings = list(problem.warnings) + list(info["warnings"])
    h, w = time_step(spec, info["omega_max"])
    warnings += w
    n_steps = int(np.ceil(spec.duration / h - 1e-9))
    stride = max(1, int(round(spec.output_step / (spec.duration / n_steps)))) \
        if spec.output_step else max(1, int(np.ceil(n_steps / MAX_SAMPLES)))
    t2 = time.perf_counter()
    recorder = Recorder(problem, eq, clip=spec.method == "direct")
    stepper = Stepper(eq, problem.force_scale, problem.length_scale, recorder, progress)
    stepper.run(spec.duration, h, spec.breakpoints, stride)
    t3 = time.perf_counter()
    warnings += stepper.warnings
    if spec.method == "modal" and recorder.min_force < 0:
        warnings.append(f"a rope's force fell to {recorder.min_force:.4g} N: it would go "
                        "slack, which modal superposition (linear) does not follow; use "
                        "method: direct")
    timings = {"assemble": t1 - t0, "setup": t2 - t1, "integrate": t3 - t2,
               "total": t3 - t0}
    f_hz = info["omega_max"] / (2 * np.pi)
    return recorder.result(spec.method, stepper.h, stepper.steps, info["modes"], f_hz,
                           stepper, timings, warnings)
