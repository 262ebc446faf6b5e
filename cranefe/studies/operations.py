"""The operation engine's accuracy against its cost, and Exudyn on the same scenes
(`cranefe study operations`; docs/operations.md "Accuracy and cost", "Comparison with
Exudyn").

1. Accuracy versus cost: every bundled operation scene run by the engine at a range of
   tolerances and compared with a reference, the engine at a far tighter tolerance;
   that reference is cross-checked once against scipy's Radau IIA (on the same
   equations, `Mechanism.evaluate`, at a tight rtol) on the overhead crane's emergency
   stop. Measured: the relative error of each rope's peak force, the sway (max and
   residual) of every hanging mass, the position of the masses at the end, the run's own
   energy balance error, steps, wall time and real-time factor; the observed order is
   the slope of log(error) over log(steps).
2. Exudyn (an independent multibody program, optional) builds the same scenes
   (`_exudyn_operations`) and runs them at a few fixed steps; its peak forces, sway and
   end positions are compared with the same reference, and its wall time with the
   engine's in the same run. Without Exudyn its rows say so (never dropped).

Writes results/operation_cost.csv, operation_cost_orders.csv, operation_cost.png,
operation_peers.csv, operation_peers.png, and regenerates the measured blocks of
docs/operations.md and docs/accuracy.md (between the markers `cranefe study operations:
NAME` of this study)
when a docs/ folder sits beside the output folder.
"""

import csv
import os
import time
from dataclasses import replace

import numpy as np

from ._common import doc_block, pyplot, rewrite_doc_blocks, save, write_csv

DESCRIPTION = "operation engine: error vs tolerance and cost (reference: tighter " \
              "tolerance, cross-checked by Radau); Exudyn on the same scenes"
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = {"overhead_crane_estop": os.path.join(ROOT, "models", "operations",
                                               "overhead_crane_estop.yaml"),
          "tower_crane_cycle": os.path.join(ROOT, "models", "operations",
                                            "tower_crane_cycle.yaml")}
# per scene: duration (None: the scene's), engine tolerances, the reference tolerance,
# Radau's rtol for the cross-check (None: none), Exudyn's steps (s; or (step, Newton
# relative tolerance): its default 1e-8, or 1e-6, its cheapest setting at nearly the same
# accuracy, cranefe study operation_speed)
FULL = {"overhead_crane_estop": (None, (1e-5, 1e-6, 1e-7, 1e-8, 1e-9), 1e-11, 1e-9,
                                 (0.01, 0.005, 0.002, (0.01, 1e-6))),
        "tower_crane_cycle": (None, (1e-5, 1e-6, 1e-7, 1e-8, 1e-9), 1e-10, None,
                              (0.01, 0.005, 0.0025, (0.005, 1e-6)))}
# quick (tests): the emergency stop shortened to 12 s (the trolley stops at 6.4 s; 5.6 s
# of free swing, more than one 4.9 s period), the tower crane's first 3 s (hoist start)
QUICK = {"overhead_crane_estop": (12.0, (1e-5, 1e-6, 1e-7), 1e-9, 1e-8, (0.005,)),
         "tower_crane_cycle": (3.0, (1e-6, 1e-7), 1e-9, None, (0.0025,))}
DEFAULT_TOLERANCE = 1e-7
COST_KEYS = ["scene", "duration_s", "method", "tolerance", "steps", "rejected",
             "newton_iterations", "wall_s", "cpu_s", "integrate_s", "real_time_factor",
             "peak_force_error", "sway_max_error_deg", "sway_residual_error_deg",
             "end_position_error_m", "energy_error"]
ORDER_QUANTITIES = ("peak_force_error", "sway_max_error_deg", "sway_residual_error_deg",
                    "end_position_error_m", "energy_error")
PEER_KEYS = ["scene", "program", "setting", "quantity", "value", "reference", "difference"]


def scene_model(name, duration=None, tolerance=None, output_step=None):
    """The bundled scene `name`, optionally with another duration/tolerance."""
    from ..model import load
    model = load(SCENES[name])
    a = dict(model.analysis)
    if duration is not None:
        a["duration"] = duration
    if tolerance is not None:
        a["tolerance"] = tolerance
    if output_step is not None:
        a["output_step"] = output_step
    return replace(model, analysis=a)


def _summary_of_result(r, wall, cpu):
    ok = np.isfinite(r.rope_force_max)
    return {"peak": {n: float(v) for n, v, o in zip(r.rope_names, r.rope_force_max, ok) if o},
            "sway_max": dict(zip(r.sway_names, map(float, r.sway_max_deg))),
            "sway_residual": dict(zip(r.sway_names, map(float, r.sway_residual_deg))),
            "end": {n: r.mass_position[-1, k] for k, n in enumerate(r.mass_names)
                    if n in r.sway_names},
            "steps": r.steps, "rejected": r.rejected, "newton": r.newton_iterations,
            "wall_s": wall, "cpu_s": cpu, "integrate_s": r.timings.get("integrate", np.nan),
            "energy_error": r.energy_error, "duration": r.duration,
            "history": (r.times, {n: r.sway_deg[:, k] for k, n in enumerate(r.sway_names)},
                        {n: r.rope_force[:, k] for k, n in enumerate(r.rope_names) if ok[k]})}


def engine(model):
    """Run the engine; (summary, result)."""
    from ..analysis.operation.integrate import simulate
    t0, c0 = time.perf_counter(), time.process_time()
    r = simulate(model)
    return _summary_of_result(r, time.perf_counter() - t0, time.process_time() - c0), r


def _sway(mech, X, k):
    d = X[mech.hang[k]] - X[mech.free[k]]
    return float(np.degrees(np.arccos(np.clip(d @ mech.up / np.linalg.norm(d), -1, 1))))


def radau(model, rtol, atol=None, sample=2e-3):
    """scipy's Radau IIA on the engine's equations in first-order form y = [q, q'],
    y' = [q', M^-1 F] with the analytic Jacobian [[0, I], [-M^-1 K, -M^-1 C]], restarted
    at every breakpoint of the drives (ropes keep their initial taut state: no events;
    the scenes here have none). Sway and positions at the engine's output times from the
    dense output; peak forces from it every `sample` s. -> summary dict."""
    from scipy.integrate import solve_ivp

    from ..analysis.operation.mechanism import Mechanism
    from ..analysis.operation.scene import parse
    spec = parse(model)
    mech = Mechanism(model, spec)
    n, M, taut = mech.n, mech.M, mech.taut0
    atol = rtol * 1e-2 if atol is None else atol

    def f(t, y):
        return np.concatenate([y[n:], mech.evaluate(t, y[:n], y[n:], taut,
                                                    powers=False).F / M])

    def jac(t, y):
        ev = mech.evaluate(t, y[:n], y[n:], taut, powers=False)
        J = np.zeros((2 * n, 2 * n))
        J[:n, n:] = np.eye(n)
        J[n:, :n] = -ev.K / M[:, None]
        J[n:, n:] = -ev.C / M[:, None]
        return J

    T, dt = spec.duration, spec.output_step
    out = np.arange(0.0, T + 0.5 * dt, dt)
    out = out[out <= T * (1 + 1e-12)]
    if out[-1] < T * (1 - 1e-12):
        out = np.append(out, T)
    t0, c0 = time.perf_counter(), time.process_time()
    y = np.concatenate([mech.q0, np.zeros(n)])
    peak = mech.S0.copy()
    steps = 0
    sway, end = [], None
    names = mech.model.node_names
    bps = [0.0] + [float(b) for b in spec.breakpoints] + [T]
    for k, (a, b) in enumerate(zip(bps[:-1], bps[1:])):
        sol = solve_ivp(f, (a, b), y, method="Radau", jac=jac, rtol=rtol, atol=atol,
                        dense_output=True)
        steps += len(sol.t) - 1
        mine = out[((out > a) | (k == 0)) & (out <= b)]
        fine = np.union1d(np.linspace(a, b, max(3, int(np.ceil((b - a) / sample)) + 1)),
                          mine)
        Y = sol.sol(fine)
        for tt, yy in zip(fine, Y.T):
            ev = mech.evaluate(tt, yy[:n], yy[n:], taut, powers=False)
            peak = np.maximum(peak, ev.S + ev.Sd)
            if np.isin(tt, mine):
                sway.append((tt, [_sway(mech, ev.X, j) for j in range(len(mech.free))]))
                end = ev.X
        y = sol.y[:, -1]
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    ts = np.array([s[0] for s in sway])
    sw = np.array([s[1] for s in sway])
    after = ts >= spec.motion_end - 1e-9
    free = [names[i] for i in mech.free]
    return {"peak": {model.ropes[k].name: float(p) for k, p in zip(mech.ropes, peak)},
            "sway_max": dict(zip(free, map(float, sw.max(axis=0)))),
            "sway_residual": dict(zip(free, map(float, sw[after].max(axis=0)
                                                 if after.any() else [np.nan] * len(free)))),
            "end": {names[i]: end[i] for i in mech.free},
            "steps": steps, "rejected": 0, "newton": 0, "wall_s": wall, "cpu_s": cpu,
            "integrate_s": wall, "energy_error": np.nan, "duration": T}


def peak_of_samples(t, F):
    """Largest value of a sampled history, refined by the parabola through the largest
    sample and its neighbours (Exudyn's forces are known at the steps only)."""
    k = int(np.argmax(F))
    if 0 < k < len(F) - 1:
        a, b, c = F[k - 1], F[k], F[k + 1]
        den = a - 2 * b + c
        if den < 0:
            return float(b - (a - c) ** 2 / (8 * den))
    return float(F[k])


def exudyn(model, step, newton_rtol=None):
    """Run the scene in Exudyn at a fixed step (and Newton relative tolerance, default
    its own); summary dict (raises ImportError)."""
    from ..analysis.operation.scene import parse
    from . import _exudyn_operations as peer
    spec = parse(model)
    T, dt = spec.duration, spec.output_step
    out = np.arange(0.0, T + 0.5 * dt, dt)
    out = out[out <= T * (1 + 1e-12)]
    old = peer.NEWTON_RTOL
    peer.NEWTON_RTOL = old if newton_rtol is None else newton_rtol
    try:
        r = peer.simulate(model, spec, step, out)
    finally:
        peer.NEWTON_RTOL = old
    idx = r["samples"]
    ts = r["times"][idx]
    after = ts >= spec.motion_end - 1e-9
    return {"peak": {n: peak_of_samples(r["times"], F) for n, F in r["rope_force"].items()},
            "sway_max": {n: float(s[idx].max()) for n, s in r["sway_deg"].items()},
            "sway_residual": {n: float(s[idx][after].max()) if after.any() else np.nan
                              for n, s in r["sway_deg"].items()},
            "end": {n: p[-1] for n, p in r["positions"].items()},
            "steps": r["steps"], "rejected": 0, "newton": 0,
            "wall_s": r["wall_s"] + r["setup_s"], "cpu_s": r["cpu_s"],
            "integrate_s": r["wall_s"],
            "energy_error": np.nan, "duration": T,
            "history": (r["times"], r["sway_deg"], r["rope_force"])}


def errors(s, ref):
    """Errors of a summary against the reference's: largest relative peak-force error,
    largest sway differences (deg), largest distance of a mass at the end (m)."""
    def worst(vals):
        vals = [v for v in vals if np.isfinite(v)]
        return max(vals) if vals else np.nan
    return {
        "peak_force_error": worst(abs(s["peak"][n] / ref["peak"][n] - 1) for n in ref["peak"]),
        "sway_max_error_deg": worst(abs(s["sway_max"][n] - ref["sway_max"][n])
                                    for n in ref["sway_max"]),
        "sway_residual_error_deg": worst(abs(s["sway_residual"][n] - ref["sway_residual"][n])
                                         for n in ref["sway_residual"]),
        "end_position_error_m": worst(float(np.linalg.norm(s["end"][n] - ref["end"][n]))
                                      for n in ref["end"])}


def _cost_row(scene, method, tol, s, ref):
    row = {"scene": scene, "duration_s": float(s["duration"]), "method": method,
           "tolerance": tol, "steps": int(s["steps"]), "rejected": int(s["rejected"]),
           "newton_iterations": int(s["newton"]), "wall_s": float(s["wall_s"]),
           "cpu_s": float(s["cpu_s"]), "integrate_s": float(s["integrate_s"]),
           "real_time_factor": float(s["duration"] / s["cpu_s"]),
           "energy_error": float(s["energy_error"])}
    row.update({k: float(v) for k, v in errors(s, ref).items()})
    return row


def orders(rows):
    """Observed order per scene and quantity: -slope of log(error) over log(steps) of
    the engine's runs (errors that are zero or not finite left out; nan below 3)."""
    out = []
    for scene in dict.fromkeys(r["scene"] for r in rows):
        runs = [r for r in rows if r["scene"] == scene and r["method"] == "engine"]
        for q in ORDER_QUANTITIES:
            pts = [(r["steps"], r[q]) for r in runs if np.isfinite(r[q]) and r[q] > 0]
            order = -np.polyfit(np.log([p[0] for p in pts]), np.log([p[1] for p in pts]),
                                1)[0] if len(pts) >= 3 else np.nan
            out.append({"scene": scene, "quantity": q, "order": float(order),
                        "runs": len(pts)})
    return out


def _version():
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version("exudyn")
    except PackageNotFoundError:
        return None


def _peer_rows(scene, program, setting, s, ref, default_cpu):
    rows = []

    def add(q, v, r=None):
        rows.append({"scene": scene, "program": program, "setting": setting, "quantity": q,
                     "value": float(v), "reference": "" if r is None else float(r),
                     "difference": "" if r is None else float(v - r)})
    for n in ref["peak"]:
        add(f"peak force {n} [N]", s["peak"][n], ref["peak"][n])
    for n in ref["sway_max"]:
        add(f"sway max {n} [deg]", s["sway_max"][n], ref["sway_max"][n])
        if np.isfinite(ref["sway_residual"][n]):
            add(f"sway residual {n} [deg]", s["sway_residual"][n], ref["sway_residual"][n])
    add("end position error [m]", errors(s, ref)["end_position_error_m"])
    add("steps", s["steps"])
    add("wall time [s]", s["wall_s"])
    add("CPU time [s]", s["cpu_s"])
    add("CPU time / cranefe default", s["cpu_s"] / default_cpu)
    add("real-time factor (CPU)", s["duration"] / s["cpu_s"])
    return rows


def measure(quick=False, progress=None):
    """(cost rows, peer rows, histories for the plots)."""
    plan = QUICK if quick else FULL
    cost, peers, hist = [], [], {}
    version = _version()
    from ..analysis.operation.integrate import simulate
    for scene, (duration, tols, ref_tol, radau_rtol, steps) in plan.items():
        say = progress or (lambda text: None)
        # the compiled loop (numba) compiled or its cache loaded outside the timings
        simulate(scene_model(scene, 0.01))
        say(f"{scene}: reference (tolerance {ref_tol:g})")
        ref, _ = engine(scene_model(scene, duration, ref_tol))
        cost.append(_cost_row(scene, "reference", ref_tol, ref, ref))
        runs = {}
        for tol in tols:
            say(f"{scene}: tolerance {tol:g}")
            runs[tol], _ = engine(scene_model(scene, duration, tol))
            cost.append(_cost_row(scene, "engine", tol, runs[tol], ref))
        if radau_rtol is not None:
            say(f"{scene}: scipy Radau (rtol {radau_rtol:g})")
            cost.append(_cost_row(scene, "scipy Radau", radau_rtol,
                                  radau(scene_model(scene, duration), radau_rtol), ref))
        default = runs.get(DEFAULT_TOLERANCE) or runs[min(tols, key=lambda t: abs(
            np.log(t / DEFAULT_TOLERANCE)))]
        hist[scene] = {"cranefe": default["history"]}
        for tol in tols:
            if tol >= DEFAULT_TOLERANCE / 10 and tol <= DEFAULT_TOLERANCE * 10:
                peers += _peer_rows(scene, "cranefe", f"tolerance {tol:g}", runs[tol], ref,
                                    default["cpu_s"])
        if version is None:
            peers.append({"scene": scene, "program": "Exudyn", "setting": "-",
                          "quantity": "all", "value": "missing (Exudyn not installed)",
                          "reference": "", "difference": ""})
            continue
        for h in steps:
            h, rtol = (h, None) if np.isscalar(h) else h
            setting = f"step {h:g} s" + ("" if rtol is None else f", Newton rtol {rtol:g}")
            say(f"{scene}: Exudyn {version} ({setting})")
            ex = exudyn(scene_model(scene, duration), h, rtol)
            peers += _peer_rows(scene, f"Exudyn {version}", setting, ex, ref,
                                default["cpu_s"])
            if rtol is None:
                hist[scene]["exudyn"] = (h, ex["history"])
    return cost, peers, hist


def _plot_cost(outdir, cost, order_rows):
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    marks = {"peak_force_error": "o", "sway_residual_error_deg": "s",
             "end_position_error_m": "^", "energy_error": "x"}
    for scene, ls in zip(dict.fromkeys(r["scene"] for r in cost), ("-", "--")):
        runs = [r for r in cost if r["scene"] == scene and r["method"] == "engine"]
        for q, m in marks.items():
            y = [r[q] for r in runs]
            if not np.any(np.isfinite(y)):
                continue
            axes[0].loglog([r["steps"] for r in runs], y, ls=ls, marker=m,
                           label=f"{scene}: {q}")
            axes[1].loglog([r["cpu_s"] for r in runs], y, ls=ls, marker=m)
    axes[0].set_xlabel("steps")
    axes[0].set_ylabel("error against the reference (relative, deg, m)")
    axes[0].set_title("error vs steps (second order: slope -2)")
    axes[1].set_xlabel("CPU time [s]")
    axes[1].set_title("error vs CPU time of the run")
    axes[0].legend(fontsize=7)
    for a in axes:
        a.grid(alpha=0.3, which="both")
    return save(fig, outdir, "operation_cost.png")


def _plot_peers(outdir, hist):
    plt = pyplot()
    scenes = list(hist)
    fig, axes = plt.subplots(2, len(scenes), figsize=(6 * len(scenes), 7), squeeze=False)
    for c, scene in enumerate(scenes):
        t, sway, force = hist[scene]["cranefe"]
        for n, s in sway.items():
            axes[0, c].plot(t, s, lw=1.2, label=f"cranefe {n}")
        for n, F in force.items():
            axes[1, c].plot(t, F / 1e3, lw=1.2, label=f"cranefe {n}")
        if "exudyn" in hist[scene]:
            h, (te, swe, fe) = hist[scene]["exudyn"]
            for n, s in swe.items():
                axes[0, c].plot(te, s, ls="--", lw=0.9, label=f"Exudyn {n} (h {h:g} s)")
            for n, F in fe.items():
                axes[1, c].plot(te, F / 1e3, ls="--", lw=0.9, label=f"Exudyn {n}")
        axes[0, c].set_title(scene)
        axes[0, c].set_ylabel("sway [deg]")
        axes[1, c].set_ylabel("rope force [kN]")
        axes[1, c].set_xlabel("t [s]")
        for a in axes[:, c]:
            a.legend(fontsize=7)
            a.grid(alpha=0.3)
    return save(fig, outdir, "operation_peers.png")


# ---------------------------------------------------------------- docs blocks

def _e(x, digits=1):
    x = float(x)
    return "-" if not np.isfinite(x) else "0" if x == 0 else f"{x:.{digits}e}"


def cost_markdown(cost, order_rows):
    """The measured block of docs/operations.md "Accuracy and cost", from the CSV rows
    (strings or numbers)."""
    lines = []
    for scene in dict.fromkeys(r["scene"] for r in cost):
        rows = [r for r in cost if r["scene"] == scene]
        ref = next(r for r in rows if r["method"] == "reference")
        lines += [f"**{scene}** ({float(ref['duration_s']):g} s simulated; reference: the "
                  f"engine at tolerance {float(ref['tolerance']):g}, {int(ref['steps'])} "
                  f"steps, {float(ref['cpu_s']):.3g} s CPU):", "",
                  "| method | tolerance | steps (rejected) | CPU [s] | real-time factor | "
                  "peak force | sway max [deg] | sway residual [deg] | end position [m] | "
                  "energy error |", "|---|---|---|---|---|---|---|---|---|---|"]
        for r in rows:
            if r["method"] == "reference":
                continue
            lines.append(
                f"| {r['method']} | {float(r['tolerance']):g} | {int(r['steps'])} "
                f"({int(r['rejected'])}) | {float(r['cpu_s']):.3g} | "
                f"{float(r['real_time_factor']):.3g} | {_e(r['peak_force_error'])} | "
                f"{_e(r['sway_max_error_deg'])} | {_e(r['sway_residual_error_deg'])} | "
                f"{_e(r['end_position_error_m'])} | {_e(r['energy_error'])} |")
        ords = [o for o in order_rows if o["scene"] == scene and np.isfinite(float(o["order"]))]
        lines += ["", "Observed order (-slope of log error over log steps): " +
                  ", ".join(f"{o['quantity']} {float(o['order']):.2f}" for o in ords) + ".",
                  ""]
    return "\n".join(lines)


def peers_markdown(peers):
    """The measured block of docs/operations.md "Comparison with Exudyn": per scene, the
    quantities (rows) of cranefe and Exudyn runs (columns), from the CSV rows."""
    lines = []
    for scene in dict.fromkeys(r["scene"] for r in peers):
        rows = [r for r in peers if r["scene"] == scene]
        runs = list(dict.fromkeys((r["program"], r["setting"]) for r in rows))
        missing = [r for r in rows if r["quantity"] == "all"]
        quantities = list(dict.fromkeys(r["quantity"] for r in rows if r["quantity"] != "all"))
        cell = {(r["program"], r["setting"], r["quantity"]): r for r in rows}
        ref = {r["quantity"]: r["reference"] for r in rows if r["reference"] not in ("", None)}
        runs = [k for k in runs if k not in {(m["program"], m["setting"]) for m in missing}]
        lines += [f"**{scene}**" + "".join(f" ({m['program']}: {m['value']})"
                                           for m in missing) + ":", "",
                  "| quantity | reference | " + " | ".join(f"{p}, {s}" for p, s in runs) + " |",
                  "|---|---|" + "---|" * len(runs)]
        for q in quantities:
            vals = []
            for p, s in runs:
                r = cell.get((p, s, q))
                vals.append("-" if r is None else f"{float(r['value']):.6g}")
            rv = f"{float(ref[q]):.6g}" if q in ref else ""
            lines.append(f"| {q} | {rv} | " + " | ".join(vals) + " |")
        worst = {k: _worst(rows, *k) for k in runs}
        lines.append("| largest peak force difference (relative) | | " + " | ".join(
            _e(worst[k][0]) for k in runs) + " |")
        lines.append("| largest sway difference [deg] | | " + " | ".join(
            _e(worst[k][1]) for k in runs) + " |")
        lines += ["", _matched(rows, runs, worst), ""]
    return "\n".join(lines)


def _worst(rows, program, setting):
    """(largest relative peak-force difference, largest sway difference in deg) of a run
    against the reference, from its rows."""
    mine = [r for r in rows if (r["program"], r["setting"]) == (program, setting)]
    force = [abs(float(r["difference"]) / float(r["reference"])) for r in mine
             if r["quantity"].startswith("peak force")]
    sway = [abs(float(r["difference"])) for r in mine if r["quantity"].startswith("sway")]
    return max(force, default=np.nan), max(sway, default=np.nan)


def _matched(rows, runs, worst):
    """One sentence: the cheapest Exudyn run at least as accurate as the engine at its
    default tolerance on both forces and sway, and its CPU time against the engine's."""
    default = ("cranefe", f"tolerance {DEFAULT_TOLERANCE:g}")
    if default not in worst:
        return ""
    f0, s0 = worst[default]
    cpu = {(r["program"], r["setting"]): float(r["value"]) for r in rows
           if r["quantity"] == "CPU time / cranefe default"}
    better = [k for k in runs if k[0].startswith("Exudyn") and worst[k][0] <= f0
              and worst[k][1] <= s0]
    head = (f"At the default tolerance {DEFAULT_TOLERANCE:g} the engine is within "
            f"{_e(f0)} of the reference's peak forces and {_e(s0)} deg of its sway; ")
    if not any(k[0].startswith("Exudyn") for k in runs):
        return head + "Exudyn was not run."
    if not better:
        return head + "no Exudyn step tried is as accurate on both."
    k = min(better, key=lambda k: cpu[k])
    return head + (f"{k[0]} at {k[1]} is as accurate on both ({_e(worst[k][0])}, "
                   f"{_e(worst[k][1])} deg) at {cpu[k]:.2g} times the engine's CPU time.")


def accuracy_markdown(cost):
    """The measured block of docs/accuracy.md "Operation engine": the engine's runs."""
    lines = ["| scene | tolerance | steps | real-time factor | peak force | sway residual "
             "[deg] | end position [m] |", "|---|---|---|---|---|---|---|"]
    for r in cost:
        if r["method"] == "engine":
            lines.append(f"| {r['scene']} | {float(r['tolerance']):g} | {int(r['steps'])} | "
                         f"{float(r['real_time_factor']):.3g} | {_e(r['peak_force_error'])} | "
                         f"{_e(r['sway_residual_error_deg'])} | "
                         f"{_e(r['end_position_error_m'])} |")
    return "\n".join(lines) + "\n"


def block(text, name):
    """A measured block of this study on a docs page (tests/test_docs_tables.py)."""
    return doc_block(text, "operations", name)


def write_docs(docs, cost, order_rows, peers):
    """Regenerate the measured blocks of docs/operations.md and docs/accuracy.md."""
    written = []
    for page, parts in (("operations.md", (("cost", cost_markdown(cost, order_rows)),
                                           ("peers", peers_markdown(peers)))),
                        ("accuracy.md", (("engine", accuracy_markdown(cost)),))):
        written += rewrite_doc_blocks(os.path.join(docs, page), "operations", parts)
    return written


def run(outdir, quick=False):
    cost, peers, hist = measure(quick)
    order_rows = orders(cost)
    written = [write_csv(outdir, "operation_cost.csv", cost, COST_KEYS),
               write_csv(outdir, "operation_cost_orders.csv", order_rows),
               write_csv(outdir, "operation_peers.csv", peers, PEER_KEYS),
               _plot_cost(outdir, cost, order_rows), _plot_peers(outdir, hist)]
    docs = os.path.join(os.path.dirname(os.path.abspath(outdir)), "docs")
    if os.path.isdir(docs):
        # the pages quote the CSVs as written (6 digits), as tests/test_docs_tables.py
        # renders them
        written += write_docs(docs, *(read_csv(p) for p in written[:3]))
    return written


def read_csv(path):
    with open(path) as fh:
        return list(csv.DictReader(fh))
