"""Speed of the operation engine (issue 16, "Performance"): the real-time factor of the
tower-crane working cycle (models/operations/tower_crane_cycle.yaml: sway, elastic
ropes, exact damping; 110 s) side by side with its accuracy, at several tolerances, and
Exudyn on the same scene in the same run.

- real-time factor = simulated time / time of `simulate(model)` (scene parsing, setup,
  integration and the result arrays: everything but reading the YAML), on the wall clock
  and in the process's CPU time (what a busy machine does not inflate);
- accuracy against a run at tolerance 1e-10 (docs/operations.md, "Cost"): the dynamic
  factor of the hoist rope, the largest relative error of a rope's peak force, the
  largest error of a load's maximum and residual sway, the positions at the output
  times and at the end;
- engines, all in fresh processes alternated run by run (so that a busy machine slows
  them alike), best wall time of `repeat` rounds each: "new", this tree's default, the
  whole loop compiled (loop.py, numba; after a warm-up call that compiles it or loads
  its cache, outside the timing); "step", the compiled step inside the Python loop
  (fast.py, `simulate(fast="step")`: the engine before the loop was compiled); "numpy",
  the numpy step (Lean, the reference path, `simulate(fast=False)`); "baseline", the
  engine of another checkout named by the environment variable CRANEFE_BASELINE (e.g.
  `git archive <commit> | tar -x -C /tmp/old-op`), if given. Speed-ups against the
  numpy step (or the baseline) of the same round;
- "exudyn": Exudyn (cranefe study operations' peer, if installed) on the same scene at
  fixed steps, with its default Newton tolerance (1e-8) and a looser one (1e-6, fewer
  Newton iterations at nearly the same accuracy: its cheapest setting found), each round
  in this process between the engine's runs; `cpu_vs_default` is its CPU time over the
  engine's at the default tolerance, and `as_accurate` says whether it is at least as
  accurate as the engine's default on both the peak forces and the sway;
- "compile": the first call of the compiled loop with an empty numba cache (a fresh
  NUMBA_CACHE_DIR): the one-off compile cost, kept out of every other row.

Writes operation_speed.csv and operation_speed.png.
"""

import json
import os
import subprocess
import sys
import tempfile
from dataclasses import replace

import numpy as np

from ._common import pyplot, rewrite_doc_blocks, save, write_csv

DESCRIPTION = "operation engine: real-time factor of the tower-crane cycle vs tolerance, " \
    "side by side with Exudyn"
SCENE = os.path.join("models", "operations", "tower_crane_cycle.yaml")
GOAL_RTF = 200.0
REFERENCE_TOL = 1e-10
DEFAULT_TOL = 1e-7
# Exudyn: (step s, Newton relative tolerance)
EXUDYN_RUNS = ((0.01, 1e-8), (0.0075, 1e-8), (0.005, 1e-8), (0.0025, 1e-8),
               (0.0075, 1e-6), (0.005, 1e-6))

# One run in a fresh interpreter: the package of the tree on PYTHONPATH, the scene of
# this tree; prints the result document and the times, saves the histories.
_SCRIPT = r"""
import dataclasses, json, sys, time
import numpy as np
from cranefe.model import load
from cranefe.analysis.operation.integrate import simulate
scene, tol, duration, out = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
path = sys.argv[5] if len(sys.argv) > 5 else ""
fast = {"compiled": None, "numpy": False, "step": "step", "compile": None}.get(path)
m = load(scene)
m = dataclasses.replace(m, analysis={**m.analysis, "tolerance": tol, "duration": duration})
kw = {} if not path else {"fast": fast}
if path in ("compiled", "step"):     # compile (or load the cache) outside the timing
    simulate(dataclasses.replace(m, analysis={**m.analysis, "duration": 0.01}), **kw)
if path == "compile":                # the first call with an empty cache: compile + run
    m = dataclasses.replace(m, analysis={**m.analysis, "duration": 0.01})
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


def _one(tree, scene, tol, duration, tmp, path=None, env_extra=None):
    """One run of the engine in `tree` -> (document, histories); path: "compiled"
    (the compiled loop), "step" (compiled step, Python loop), "numpy", "compile" (first
    call with the cache of env_extra) of this tree, None for a baseline tree."""
    env = dict(os.environ)
    env["PYTHONPATH"] = tree
    env.update(env_extra or {})
    out = os.path.join(tmp, "hist.npz")
    p = subprocess.run([sys.executable, "-c", _SCRIPT, scene, repr(tol), repr(duration),
                        out] + ([path] if path else []), capture_output=True, text=True,
                       env=env, cwd=tree)
    if p.returncode != 0:
        raise RuntimeError(f"the run in {tree} failed: {p.stderr[-2000:]}")
    h = np.load(out)
    return json.loads(p.stdout), {k: h[k] for k in h.files}


def _errors(doc, hist, ref, rhist):
    """Errors of an engine run against the reference run (module docstring)."""
    rope = "hoist_rope"
    load = list(doc["sway"])[-1]
    out = {"dynamic_factor": doc["dynamic_factor"][rope],
           "sway_max_deg": doc["sway"][load]["max_deg"],
           "sway_residual_deg": doc["sway"][load]["residual_deg"],
           "energy_error": doc["energy_error"]}
    if ref is None:
        return out
    out["err_dynamic_factor"] = abs(out["dynamic_factor"] - ref["dynamic_factor"][rope])
    out["err_peak_force"] = max(abs(doc["rope_force_max_N"][n] / v - 1)
                                for n, v in ref["rope_force_max_N"].items()
                                if v is not None)
    out["err_sway_max_deg"] = max(abs(doc["sway"][n]["max_deg"] - v["max_deg"])
                                  for n, v in ref["sway"].items())
    res = [abs(doc["sway"][n]["residual_deg"] - v["residual_deg"])
           for n, v in ref["sway"].items()
           if v["residual_deg"] is not None and doc["sway"][n]["residual_deg"] is not None]
    out["err_sway_residual_deg"] = max(res) if res else float("nan")
    same = len(hist["t"]) == len(rhist["t"])
    out["err_position_m"] = float(np.abs(hist["X"] - rhist["X"]).max()) \
        if same else float("nan")
    out["err_end_position_m"] = float(np.linalg.norm(hist["X"][-1] - rhist["X"][-1],
                                                     axis=-1).max())
    return out


def _exudyn_run(scene, duration, step, rtol, ref, rhist):
    """Exudyn (the peer of `cranefe study operations`) on the same scene at a fixed step
    and Newton tolerance, in this process: its times and errors against the same
    reference (peak forces refined by a parabola through the largest step values)."""
    from ..model import load
    from .operations import exudyn
    m = load(scene)
    m = replace(m, analysis={**m.analysis, "duration": duration})
    ex = exudyn(m, step, rtol)
    rope = "hoist_rope"
    load_ = list(ref["sway"])[-1]
    phi = ex["peak"][rope] / ref["rope_force_static_N"][rope]
    res = [abs(ex["sway_residual"][n] - v["residual_deg"]) for n, v in ref["sway"].items()
           if v["residual_deg"] is not None]
    names = list(ref["sway"])
    end = max(float(np.linalg.norm(ex["end"][n] - rhist["X"][-1][k]))
              for k, n in enumerate(names))
    return {"engine": "exudyn", "tolerance": step, "newton_rtol": rtol,
            "duration_s": duration, "wall_s": ex["wall_s"], "cpu_s": ex["cpu_s"],
            "rtf_wall": duration / ex["wall_s"], "rtf_cpu": duration / ex["cpu_s"],
            "steps": ex["steps"], "rejected": 0, "newton_iterations": "",
            "dynamic_factor": phi, "sway_max_deg": ex["sway_max"][load_],
            "sway_residual_deg": ex["sway_residual"][load_],
            "err_dynamic_factor": abs(phi - ref["dynamic_factor"][rope]),
            "err_peak_force": max(abs(ex["peak"][n] / v - 1)
                                  for n, v in ref["rope_force_max_N"].items()
                                  if v is not None),
            "err_sway_max_deg": max(abs(ex["sway_max"][n] - v["max_deg"])
                                    for n, v in ref["sway"].items()),
            "err_sway_residual_deg": max(res) if res else float("nan"),
            "err_end_position_m": end}


def _engine_row(name, tol, duration, doc, hist, ref, rhist):
    row = {"engine": name, "tolerance": tol, "duration_s": duration,
           "wall_s": doc["wall_s"], "cpu_s": doc["cpu_s"],
           "rtf_wall": duration / doc["wall_s"], "rtf_cpu": duration / doc["cpu_s"],
           "steps": doc["steps"], "rejected": doc["rejected_steps"],
           "newton_iterations": doc["newton_iterations"]}
    row.update(_errors(doc, hist, ref, rhist))
    return row


KEYS = ["engine", "tolerance", "newton_rtol", "duration_s", "wall_s", "cpu_s", "rtf_wall",
        "rtf_cpu", "steps", "rejected", "newton_iterations", "dynamic_factor",
        "sway_max_deg", "sway_residual_deg", "energy_error", "err_dynamic_factor",
        "err_peak_force", "err_sway_max_deg", "err_sway_residual_deg", "err_position_m",
        "err_end_position_m", "speedup_wall", "speedup_cpu", "cpu_vs_default",
        "as_accurate"]


def run(outdir, quick=False, repeat=None):
    """The table and figure (quick: the first 5 s at two tolerances, the tree's default
    path only: no numpy, step, baseline, compile or Exudyn runs).

    Length: the plan of the side-by-side runs (rounds alternating every engine and
    Exudyn), the derived columns and the figure in one piece."""
    root = _root()
    scene = os.path.join(root, SCENE)
    base = os.environ.get("CRANEFE_BASELINE")
    duration = 5.0 if quick else 110.0
    tols = [1e-6, 1e-7] if quick else [1e-6, 1e-7, 1e-8]
    repeat = repeat or (1 if quick else 2)
    from ..analysis.operation import fast
    from .operations import _version
    engines = {"new": (root, "compiled")}
    if not quick:
        if fast.available():
            engines["step"] = (root, "step")
        else:
            engines = {}
        engines["numpy"] = (root, "numpy")
        if base:
            engines["baseline"] = (os.path.abspath(base), None)
    peer = not quick and _version() is not None
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        ref, rhist = _one(root, scene, 1e-8 if quick else REFERENCE_TOL, duration, tmp)
        if not quick and fast.available():
            cache = os.path.join(tmp, "numba-cache")
            doc, _ = _one(root, scene, DEFAULT_TOL, duration, tmp, "compile",
                          {"NUMBA_CACHE_DIR": cache})
            rows.append({"engine": "compile", "tolerance": DEFAULT_TOL, "duration_s": 0.01,
                         "wall_s": doc["wall_s"], "cpu_s": doc["cpu_s"]})
        best, ex_best = {}, {}
        for _ in range(repeat):
            for tol in tols:
                for name, (tree, path) in engines.items():      # alternated run by run
                    doc, hist = _one(tree, scene, tol, duration, tmp, path)
                    k = (name, tol)
                    if k not in best or doc["wall_s"] < best[k][0]["wall_s"]:
                        best[k] = (doc, hist)
            for h, rtol in (EXUDYN_RUNS if peer else ()):
                r = _exudyn_run(scene, duration, h, rtol, ref, rhist)
                if (h, rtol) not in ex_best or r["wall_s"] < ex_best[(h, rtol)]["wall_s"]:
                    ex_best[(h, rtol)] = r
        for tol in tols:
            for name in engines:
                doc, hist = best[(name, tol)]
                row = _engine_row(name, tol, duration, doc, hist, ref, rhist)
                other = "baseline" if "baseline" in engines else "numpy"
                if name != other and (other, tol) in best:
                    old = best[(other, tol)][0]
                    row["speedup_wall"] = old["wall_s"] / doc["wall_s"]
                    row["speedup_cpu"] = old["cpu_s"] / doc["cpu_s"]
                rows.append(row)
        rows += list(ex_best.values())
    default = [r for r in rows if r["tolerance"] == DEFAULT_TOL and r["engine"] in
               ("new", "numpy")]
    if default:
        d = default[0]
        for r in rows:                # CPU time over the engine's at the default tolerance
            if r["engine"] in ("exudyn", "step", "numpy", "baseline"):
                r["cpu_vs_default"] = r["cpu_s"] / d["cpu_s"]
            if r["engine"] == "exudyn":
                r["as_accurate"] = "yes" if (r["err_peak_force"] <= d["err_peak_force"] and
                                             r["err_sway_max_deg"] <= d["err_sway_max_deg"]) \
                    else "no"
    for r in rows:
        for k in KEYS:
            r.setdefault(k, "")
    paths = [write_csv(outdir, "operation_speed.csv", rows, KEYS)]
    plt = pyplot()
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for name, mk in (("new", "o-"), ("step", "v-"), ("numpy", "^-"), ("baseline", "s--")):
        rs = [r for r in rows if r["engine"] == name]
        if not rs:
            continue
        t = [r["tolerance"] for r in rs]
        ax[0].loglog(t, [r["rtf_wall"] for r in rs], mk, label=f"{name} (wall)")
        ax[0].loglog(t, [r["rtf_cpu"] for r in rs], mk, alpha=0.4, label=f"{name} (CPU)")
        ax[1].loglog([r["err_peak_force"] for r in rs], [r["rtf_cpu"] for r in rs], mk,
                     label=f"cranefe {name}")
    for rtol, mk in ((1e-8, "D:"), (1e-6, "d:")):
        rs = [r for r in rows if r["engine"] == "exudyn" and r["newton_rtol"] == rtol]
        if rs:
            ax[1].loglog([r["err_peak_force"] for r in rs], [r["rtf_cpu"] for r in rs], mk,
                         label=f"Exudyn (Newton rtol {rtol:g})")
    ax[0].axhline(GOAL_RTF, color="k", lw=0.8, ls=":")
    ax[1].axhline(GOAL_RTF, color="k", lw=0.8, ls=":")
    ax[0].set_xlabel("tolerance")
    ax[0].set_ylabel("real-time factor")
    ax[0].legend(fontsize=7)
    ax[1].set_xlabel("largest relative error of a peak rope force")
    ax[1].set_ylabel("real-time factor (CPU)")
    ax[1].legend(fontsize=7)
    fig.suptitle(f"Tower-crane cycle ({duration:g} s)")
    paths.append(save(fig, outdir, "operation_speed.png"))
    if not quick:
        docs = os.path.join(os.path.dirname(os.path.abspath(outdir)), "docs", "operations.md")
        paths += rewrite_doc_blocks(docs, "operation_speed", (("table", markdown(rows)),))
    return paths


_NAMES = {"exudyn": None, "new": "compiled loop (numba)",
          "step": "compiled step, Python loop", "numpy": "numpy step (reference path)",
          "baseline": "baseline (CRANEFE_BASELINE)"}


def markdown(rows):
    """The measured table of docs/operations.md "Cost" (Exudyn's rows first, then the
    engine's by tolerance), with the machine's load at the end of the run."""
    def e(x):
        return "-" if x == "" else f"{float(x):.1e}"

    def g(x):
        return f"{float(x):,.0f}".replace(",", " ")

    lines = ["| program | tolerance / step | steps (rejected) | CPU [s] | real-time factor "
             "CPU / wall | dynamic factor | peak force error | sway max error [deg] | "
             "end position error [m] | CPU / engine default |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    from .operations import _version
    exudyn = f"Exudyn {_version() or ''}".strip()
    default = next((float(r["cpu_s"]) for r in rows if r["engine"] == "new" and
                    float(r["tolerance"]) == 1e-7), None)     # the engine's default

    def key(r):          # Exudyn by step then Newton tolerance; the engine by tolerance
        if r["engine"] == "exudyn":
            return (0, -float(r["tolerance"]), float(r["newton_rtol"]))
        return (1, -float(r["tolerance"]), list(_NAMES).index(r["engine"]))

    for r in sorted((r for r in rows if r["engine"] in _NAMES), key=key):
        if r["engine"] == "exudyn":
            name = exudyn
            if float(r["newton_rtol"]) != 1e-8:
                name += f", Newton rtol {float(r['newton_rtol']):g}"
            tol, steps = f"{float(r['tolerance']):g} s", g(r["steps"])
        else:
            name, tol = _NAMES[r["engine"]], f"{float(r['tolerance']):g}"
            steps = f"{g(r['steps'])} ({g(r['rejected'])})"
        ratio = float(r["cpu_s"]) / default if default else float("nan")
        lines.append(f"| {name} | {tol} | {steps} | {float(r['cpu_s']):.3g} | "
                     f"{g(r['rtf_cpu'])} / {g(r['rtf_wall'])} | "
                     f"{float(r['dynamic_factor']):.4f} | {e(r['err_peak_force'])} | "
                     f"{e(r['err_sway_max_deg'])} | {e(r['err_end_position_m'])} | "
                     f"{ratio:.3g} |")
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    compile_ = [float(r["cpu_s"]) for r in rows if r["engine"] == "compile"]
    cold = (f" The compiled loop's first call without a cache (compiling it) took "
            f"{compile_[0]:.0f} s of CPU, not in the table." if compile_ else "")
    return "\n".join(lines) + f"\n\nLoad average of the machine at the end of the run: " \
        f"{load:.1f} (2 cores).{cold}\n"
