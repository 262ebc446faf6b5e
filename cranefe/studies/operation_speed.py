"""Speed of the operation engine (issue 16, "Performance"): the real-time factor of the
tower-crane working cycle (models/operations/tower_crane_cycle.yaml: sway, elastic
ropes, exact damping; 110 s) side by side with its accuracy, at several tolerances.

- real-time factor = simulated time / wall time of `simulate(model)` (scene parsing,
  setup, integration and the result arrays: everything but reading the YAML), and the
  same with the process's CPU time (what a busy machine does not inflate);
- accuracy: the dynamic factor of the hoist rope, the largest and residual sway of the
  load and the positions at the output times against a run at tolerance 1e-10
  (docs/operations.md, "Speed and accuracy");
- engines: "new", this tree with the compiled step (numba, fast.py; after a warm-up
  run that compiles it or loads its cache), "numpy", the same tree's numpy step (Lean,
  the reference path, `simulate(fast=False)`), and the engine before, if a checkout of
  it is named by the environment variable CRANEFE_BASELINE (e.g.
  `git archive <commit> | tar -x -C /tmp/old-op`): all run in fresh processes
  alternated run by run (so that a busy machine slows them alike), best wall time of
  `repeat` rounds each, ratios (speed-up) against the baseline, or against numpy
  without one, from the same round;
- "exudyn": Exudyn (cranefe study operations' peer, if installed) on the same scene at
  fixed steps in the same run, its CPU time also over the engine's at the default
  tolerance (`cpu_vs_default`).

Writes operation_speed.csv and operation_speed.png.
"""

import json
import os
import subprocess
import sys
from dataclasses import replace

import numpy as np

from ._common import pyplot, save, write_csv

DESCRIPTION = "operation engine: real-time factor of the tower-crane cycle vs tolerance " \
    "(and against a baseline checkout)"
SCENE = os.path.join("models", "operations", "tower_crane_cycle.yaml")
GOAL_RTF = 200.0
REFERENCE_TOL = 1e-10
EXUDYN_STEPS = (0.01, 0.005)

# One run in a fresh interpreter: the package of the tree on PYTHONPATH, the scene of
# this tree; prints the result document, its time histories and the times.
_SCRIPT = r"""
import dataclasses, json, sys, time
import numpy as np
from cranefe.model import load
from cranefe.analysis.operation.integrate import simulate
scene, tol, duration, out = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
fast = {"compiled": None, "numpy": False}.get(sys.argv[5] if len(sys.argv) > 5 else "")
m = load(scene)
m = dataclasses.replace(m, analysis={**m.analysis, "tolerance": tol, "duration": duration})
kw = {} if len(sys.argv) <= 5 else {"fast": fast}
if kw and fast is None:              # compile (or load the cache) outside the timing
    simulate(dataclasses.replace(m, analysis={**m.analysis, "duration": 0.01}))
w, c = time.perf_counter(), time.process_time()
r = simulate(m, **kw)
w, c = time.perf_counter() - w, time.process_time() - c
np.savez(out, t=r.times, X=r.mass_position, sway=r.sway_deg)
d = r.to_dict()
d["wall_s"], d["cpu_s"] = w, c
print(json.dumps(d))
"""


def _root():
    return os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def _one(tree, scene, tol, duration, tmp, path=None):
    """One run of the engine in `tree` -> (document, histories); path: "compiled"
    (numba, fast.py) or "numpy" (Lean) of this tree, None for a baseline tree."""
    env = {k: v for k, v in os.environ.items()}
    env["PYTHONPATH"] = tree
    out = os.path.join(tmp, "hist.npz")
    p = subprocess.run([sys.executable, "-c", _SCRIPT, scene, repr(tol), repr(duration),
                        out] + ([path] if path else []), capture_output=True, text=True,
                       env=env, cwd=tree)
    if p.returncode != 0:
        raise RuntimeError(f"the run in {tree} failed: {p.stderr[-2000:]}")
    h = np.load(out)
    return json.loads(p.stdout), {k: h[k] for k in h.files}


def _errors(doc, hist, ref, rhist):
    rope = "hoist_rope"
    load = list(doc["sway"])[-1]
    out = {"dynamic_factor": doc["dynamic_factor"][rope],
           "sway_max_deg": doc["sway"][load]["max_deg"],
           "sway_residual_deg": doc["sway"][load]["residual_deg"],
           "energy_error": doc["energy_error"]}
    if ref is not None:
        out["err_dynamic_factor"] = abs(out["dynamic_factor"] - ref["dynamic_factor"][rope])
        out["err_sway_max_deg"] = abs(out["sway_max_deg"] - ref["sway"][load]["max_deg"])
        r = ref["sway"][load]["residual_deg"]
        out["err_sway_residual_deg"] = abs(out["sway_residual_deg"] - r) \
            if r is not None and out["sway_residual_deg"] is not None else float("nan")
        same = len(hist["t"]) == len(rhist["t"])
        out["err_position_m"] = float(np.abs(hist["X"] - rhist["X"]).max()) \
            if same else float("nan")
    return out


def _exudyn_rows(scene, duration, steps, ref):
    """Exudyn (the peer of `cranefe study operations`) on the same scene at fixed
    steps, in this process: its CPU time and its errors against the same reference."""
    from .operations import _version, exudyn
    version = _version()
    if version is None:
        return []
    from ..model import load
    m = load(scene)
    m = replace(m, analysis={**m.analysis, "duration": duration})
    rope = "hoist_rope"
    load_ = list(ref["sway"])[-1]
    rows = []
    for h in steps:
        ex = exudyn(m, h)
        phi = ex["peak"][rope] / ref["rope_force_static_N"][rope]
        smax = ex["sway_max"][load_]
        rows.append({"engine": "exudyn", "tolerance": h, "duration_s": duration,
                     "wall_s": ex["wall_s"], "cpu_s": ex["cpu_s"],
                     "rtf_wall": duration / ex["wall_s"], "rtf_cpu": duration / ex["cpu_s"],
                     "steps": ex["steps"], "rejected": 0, "newton_iterations": "",
                     "dynamic_factor": phi, "sway_max_deg": smax,
                     "err_dynamic_factor": abs(phi - ref["dynamic_factor"][rope]),
                     "err_sway_max_deg": abs(smax - ref["sway"][load_]["max_deg"])})
    return rows


def run(outdir, quick=False, repeat=None):
    """The table and figure (quick: the first 5 s at two tolerances, the tree's default
    path only: no numpy run, baseline or Exudyn)."""
    import tempfile
    root = _root()
    scene = os.path.join(root, SCENE)
    base = os.environ.get("CRANEFE_BASELINE")
    duration = 5.0 if quick else 110.0
    tols = [1e-6, 1e-7] if quick else [1e-6, 1e-7, 1e-8]
    repeat = repeat or (1 if quick else 2)
    from ..analysis.operation import fast
    if quick:                    # the tree's default path (compiled if numba is there)
        engines = {"new": (root, "compiled")}
    else:
        engines = {"new": (root, "compiled")} if fast.available() else {}
        engines["numpy"] = (root, "numpy")
    if base and not quick:
        engines["baseline"] = (os.path.abspath(base), None)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        ref, rhist = _one(root, scene, 1e-8 if quick else REFERENCE_TOL, duration, tmp)
        if not quick:
            rows += _exudyn_rows(scene, duration, EXUDYN_STEPS, ref)
        for tol in tols:
            best = {}
            for _ in range(repeat):
                for name, (tree, path) in engines.items():      # alternated run by run
                    doc, hist = _one(tree, scene, tol, duration, tmp, path)
                    if name not in best or doc["wall_s"] < best[name][0]["wall_s"]:
                        best[name] = (doc, hist)
            for name, (doc, hist) in best.items():
                row = {"engine": name, "tolerance": tol, "duration_s": duration,
                       "wall_s": doc["wall_s"], "cpu_s": doc["cpu_s"],
                       "rtf_wall": duration / doc["wall_s"],
                       "rtf_cpu": duration / doc["cpu_s"], "steps": doc["steps"],
                       "rejected": doc["rejected_steps"],
                       "newton_iterations": doc["newton_iterations"]}
                row.update(_errors(doc, hist, ref, rhist))
                other = "baseline" if "baseline" in best else "numpy"
                if name != other and other in best:
                    old = best[other][0]
                    row["speedup_wall"] = old["wall_s"] / doc["wall_s"]
                    row["speedup_cpu"] = old["cpu_s"] / doc["cpu_s"]
                rows.append(row)
    default = [r for r in rows if r["tolerance"] == 1e-7 and r["engine"] in ("new", "numpy")]
    for r in rows:                    # CPU time over the engine's at the default tolerance
        if default and r["engine"] == "exudyn":
            r["cpu_vs_default"] = r["cpu_s"] / default[0]["cpu_s"]
    keys = ["engine", "tolerance", "duration_s", "wall_s", "cpu_s", "rtf_wall", "rtf_cpu",
            "steps", "rejected", "newton_iterations", "dynamic_factor", "sway_max_deg",
            "sway_residual_deg", "energy_error", "err_dynamic_factor", "err_sway_max_deg",
            "err_sway_residual_deg", "err_position_m", "speedup_wall", "speedup_cpu",
            "cpu_vs_default"]
    for r in rows:
        for k in keys:
            r.setdefault(k, "")
    paths = [write_csv(outdir, "operation_speed.csv", rows, keys)]
    plt = pyplot()
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for name, mk in (("new", "o-"), ("numpy", "^-"), ("baseline", "s--"),
                     ("exudyn", "D:")):
        rs = [r for r in rows if r["engine"] == name]
        if not rs:
            continue
        t = [r["tolerance"] for r in rs]
        ax[0].loglog(t, [r["rtf_wall"] for r in rs], mk, label=f"{name} (wall)")
        ax[0].loglog(t, [r["rtf_cpu"] for r in rs], mk, alpha=0.4, label=f"{name} (CPU)")
        ax[1].loglog([r["err_position_m"] for r in rs], [r["rtf_cpu"] for r in rs], mk,
                     label=name)
    ax[0].axhline(GOAL_RTF, color="k", lw=0.8, ls=":")
    ax[0].set_xlabel("tolerance")
    ax[0].set_ylabel("real-time factor")
    ax[0].legend(fontsize=8)
    ax[1].set_xlabel("largest position error of the loads [m]")
    ax[1].set_ylabel("real-time factor (CPU)")
    ax[1].legend(fontsize=8)
    fig.suptitle(f"Tower-crane cycle ({duration:g} s)")
    paths.append(save(fig, outdir, "operation_speed.png"))
    return paths
