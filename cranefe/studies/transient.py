"""Transient accuracy: peak rope force of a hoist start against a converged reference,
versus retained modes (modal superposition) and time step (direct integration)."""

import os
import tempfile
import time

from ..model import load
from ..transient.integrate import simulate
from ._common import pyplot, save, write_csv

DESCRIPTION = "hoist start with rope mass: peak-force error vs modes and time step, and cost"
MODEL = os.path.join(os.path.dirname(__file__), "..", "..", "models", "two_mass_hoist.yaml")


def _scene(folder, name, analysis):
    path = os.path.join(folder, f"{name}.yaml")
    with open(path, "w") as fh:
        fh.write(f"cranefe: 1\nscene: {name}\nmodel: {os.path.abspath(MODEL)}\n"
                 "effects: {sway: false, rope_mass: 16}\nanalysis:\n  type: transient\n"
                 "  duration: 1.0\n  drums:\n    hoist: {torque: 10200}\n" + analysis)
    return load(path)


def _run(model):
    t0 = time.perf_counter()
    r = simulate(model)
    return r.rope_force_max[0], time.perf_counter() - t0, r.dofs


def run(outdir, quick=False):
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        ref, _, dofs = _run(_scene(tmp, "ref", f"  time_step: {1e-5 if not quick else 1e-4}\n"))
        for dt in ((1e-2, 1e-3) if quick else (2e-2, 1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4)):
            f, t, _ = _run(_scene(tmp, f"dt{dt}", f"  time_step: {dt}\n"))
            rows.append({"method": "direct", "modes": dofs, "time_step_s": dt,
                         "peak_force_N": f, "error": abs(f / ref - 1), "time_s": t})
        for k in ((1, 3) if quick else (1, 2, 3, 5, 8, 12, 20, dofs)):
            f, t, _ = _run(_scene(tmp, f"m{k}", f"  method: modal\n  modes: {k}\n"
                                                f"  time_step: {1e-4}\n"))
            rows.append({"method": "modal", "modes": k, "time_step_s": 1e-4,
                         "peak_force_N": f, "error": abs(f / ref - 1), "time_s": t})
    path = write_csv(outdir, "transient_cost.csv", rows)
    fig, axes = pyplot().subplots(1, 2, figsize=(11, 4))
    d = [r for r in rows if r["method"] == "direct"]
    m = [r for r in rows if r["method"] == "modal"]
    axes[0].loglog([r["time_step_s"] for r in d], [max(r["error"], 1e-12) for r in d], "o-",
                   label="direct, all coordinates")
    axes[0].set_xlabel("time step [s]")
    axes[1].semilogy([r["modes"] for r in m], [max(r["error"], 1e-12) for r in m], "s-",
                     label="modal superposition, dt = 1e-4 s")
    axes[1].set_xlabel("retained modes (rigid one included)")
    for ax in axes:
        ax.set_ylabel("relative error of the peak rope force")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle("Hoist start, rope with 16 elements per fall: against a converged reference")
    return [path, save(fig, outdir, "transient_cost.png")]
