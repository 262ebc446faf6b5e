"""What the effects of an operation scene cost and change (`cranefe study
operation_effects`; docs/operations.md "Inextensible ropes: cost and error").

Every bundled operation scene the constraint formulation covers is run with its own
effects (elastic ropes, sway: the reference) and with one effect switched: inextensible
ropes (`rope_elasticity: false`), no sway (`sway: false`), and both. Measured against
the reference, at the same output times: the largest distance of a hanging mass from
its reference position over the run (m), the largest difference of its sway angle
(deg), of its maximum and residual sway, the relative difference of each rope's peak
force (the elastic ropes' axial ringing is what inextensible ropes leave out), the
steps and the CPU time of each run (setup included, one process, the runs side by
side). And the formulation itself: the 60 deg pendulum at fixed steps, the rope force
of the trapezoidal rule on the index-3 form (its multiplier) against this engine's
(the projected index-1 form), both against m g (3 cos th - 2 cos th0). Writes
results/operation_effects.csv, operation_effects_formulation.csv and
operation_effects.png, and the measured blocks of docs/operations.md (between the
markers of this study) when a docs/ folder sits beside the output folder.
"""

import os
import time
from dataclasses import replace

import numpy as np

from ._common import pyplot, rewrite_doc_blocks, save, write_csv

DESCRIPTION = "operation scenes with inextensible ropes and without sway against the " \
              "elastic, swaying reference: error and cost"
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = {"overhead_crane_estop": os.path.join(ROOT, "models", "operations",
                                               "overhead_crane_estop.yaml"),
          "tower_crane_cycle": os.path.join(ROOT, "models", "operations",
                                            "tower_crane_cycle.yaml")}
# quick (tests): the emergency stop to 8 s (the stop at 6.4 s included), the tower
# crane's first 3 s (hoist start)
QUICK = {"overhead_crane_estop": 8.0, "tower_crane_cycle": 3.0}
VARIANTS = (("elastic, sway (reference)", {}),
            ("inextensible", {"rope_elasticity": False}),
            ("no sway", {"sway": False}),
            ("inextensible, no sway", {"rope_elasticity": False, "sway": False}))
KEYS = ["scene", "duration_s", "variant", "steps", "rejected", "cpu_s", "real_time_factor",
        "cpu_ratio", "position_error_m", "sway_error_deg", "sway_max_error_deg",
        "sway_residual_error_deg", "peak_force_difference", "dynamic_factor"]


def scene_model(name, effects, duration=None):
    """The bundled scene with some effects switched (and another duration)."""
    from ..model import load
    model = load(SCENES[name])
    a = dict(model.analysis)
    if duration is not None:
        a["duration"] = duration
    return replace(model, analysis=a, effects=replace(model.effects, **effects))


def run_one(model):
    """(result, CPU seconds) of one run."""
    from ..analysis.operation.integrate import simulate
    c0 = time.process_time()
    res = simulate(model)
    return res, time.process_time() - c0


def compare(res, ref):
    """The variant's differences from the reference run at the same output times."""
    k = min(len(res.times), len(ref.times))
    assert np.allclose(res.times[:k], ref.times[:k], atol=1e-9)
    dx = np.linalg.norm(res.mass_position[:k] - ref.mass_position[:k], axis=2)
    sw = np.abs(res.sway_deg[:k] - ref.sway_deg[:k])
    ok = np.isfinite(ref.rope_force_max) & (ref.rope_force_max > 0)
    peak = np.abs(res.rope_force_max[ok] / ref.rope_force_max[ok] - 1)
    res_d = np.abs(res.sway_residual_deg - ref.sway_residual_deg)
    return {"position_error_m": float(dx.max()), "sway_error_deg": float(sw.max()),
            "sway_max_error_deg": float(np.abs(res.sway_max_deg - ref.sway_max_deg).max()),
            "sway_residual_error_deg": float(res_d.max()) if np.isfinite(res_d).any()
            else np.nan,
            "peak_force_difference": float(peak.max()) if len(peak) else np.nan}


PENDULUM = """cranefe: 1
name: pendulum on an inextensible rope
plane: xz
nodes: {S: [0, 0, 10], H: [0, 0, 0]}
ground: [S]
masses: {H: 100}
ropes: {r: {EA: 1.0e9, path: [S, H]}}
"""
TH0, G = np.radians(60.0), 9.81


def _pendulum_exact_force(x, z):
    """S / (m g) = 3 cos(th) - 2 cos(th0) of the pendulum at (x, z) (10 m below S)."""
    return 3 * np.cos(np.arctan2(x, 10.0 - z)) - 2 * np.cos(TH0)


def index3_pendulum(h, duration):
    """The trapezoidal rule on the index-3 form of the 60 deg pendulum (the constraint
    g(q1) = |q1 - s| - l = 0 and M a1 = F - G1^T lambda1 at each step's end, Newton on
    (q1, lambda1)): the errors of lambda = S / (m g) at the steps' ends (n,)."""
    m, l, s = 100.0, 10.0, np.array([0.0, 10.0])
    q = s + l * np.array([np.sin(TH0), -np.cos(TH0)])
    v = np.zeros(2)
    F = np.array([0.0, -m * G])
    e = (q - s) / l
    lam = m * G * np.cos(TH0)
    a = (F - lam * e) / m
    err = []
    for _ in range(round(duration / h)):
        q1, lam1 = q + h * v + 0.5 * h * h * a, lam
        for _ in range(50):
            a1 = 4 / h ** 2 * (q1 - q - h * v) - a
            d = q1 - s
            ln = np.linalg.norm(d)
            e1 = d / ln
            R = np.concatenate([m * a1 - F + lam1 * e1, [ln - l]])
            J = np.zeros((3, 3))
            J[:2, :2] = 4 * m / h ** 2 * np.eye(2) + lam1 / ln * (np.eye(2) - np.outer(e1, e1))
            J[:2, 2] = e1
            J[2, :2] = e1
            dx = np.linalg.solve(J, -R)
            q1, lam1 = q1 + dx[:2], lam1 + dx[2]
            if np.abs(dx[:2]).max() < 1e-13:
                break
        a1 = 4 / h ** 2 * (q1 - q - h * v) - a
        v = 2 / h * (q1 - q) - v
        q, a, lam = q1, a1, lam1
        err.append(lam / (m * G) - _pendulum_exact_force(q[0], q[1]))
    return np.array(err)


def oscillation(d):
    """The step-to-step oscillating part of a sequence: max |d[n+1] - 2 d[n] + d[n-1]| / 4
    (a (-1)^n component of amplitude c gives c; a smooth one O(h^2) of it)."""
    return float(np.abs(d[2:] - 2 * d[1:-1] + d[:-2]).max() / 4) if len(d) > 2 else 0.0


def formulation_rows(outdir, quick=False):
    """Fixed steps h on the 60 deg pendulum: the index-3 trapezoidal multiplier against
    this engine's (projected index-1) rope force (tolerance 0.009, so that max_step = h
    sets every step); largest error / (m g) over the run and its oscillating part."""
    import tempfile

    from ..analysis.operation.integrate import simulate
    from ..model import load
    dur = 7.0          # one period and a bit (6.8 s)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        mp = os.path.join(tmp, "pendulum.yaml")
        with open(mp, "w") as fh:
            fh.write(PENDULUM)
        for h in ((0.02, 0.01) if quick else (0.04, 0.02, 0.01, 0.005)):
            sp = os.path.join(tmp, f"scene_{h}.yaml")
            with open(sp, "w") as fh:
                fh.write(f"cranefe: 1\nscene: fixed step\nmodel: {mp}\neffects: "
                         f"{{rope_elasticity: false}}\nanalysis: {{type: operation, "
                         f"duration: {dur}, tolerance: 0.009, max_step: {h}, "
                         f"output_step: {h}}}\n")
            l = 10.0
            q0 = np.array([l * np.sin(TH0), 10.0 - l * np.cos(TH0)])
            res = simulate(load(sp), initial={"q": q0, "v": np.zeros(2)})
            P = res.mass_position[:, 0]
            eng = res.rope_force[:, 0] / (100.0 * G) - _pendulum_exact_force(P[:, 0], P[:, 2])
            i3 = index3_pendulum(h, dur)
            rows.append({"step_s": h, "index3_error": float(np.abs(i3).max()),
                         "index3_oscillation": oscillation(i3),
                         "engine_error": float(np.abs(eng).max()),
                         "engine_oscillation": oscillation(eng),
                         "engine_steps": int(res.steps)})
    return rows


def measure(quick=False):
    rows, hist = [], {}
    # warm-up: the compiled loop's import and cache load (numba, if installed) is not
    # part of the first scene's reference time
    run_one(scene_model(next(iter(SCENES)), VARIANTS[0][1], 0.1))
    for name in SCENES:
        dur = QUICK[name] if quick else None
        runs = []
        for label, eff in VARIANTS:
            res, cpu = run_one(scene_model(name, eff, dur))
            runs.append((label, res, cpu))
        ref, ref_cpu = runs[0][1], runs[0][2]
        for label, res, cpu in runs:
            row = {"scene": name, "duration_s": float(res.duration), "variant": label,
                   "steps": int(res.steps), "rejected": int(res.rejected),
                   "cpu_s": float(cpu), "real_time_factor": float(res.duration / cpu),
                   "cpu_ratio": float(cpu / ref_cpu),
                   "dynamic_factor": float(np.nanmax(res.dynamic_factor))}
            row.update(compare(res, ref))
            rows.append(row)
        hist[name] = runs
    return rows, hist


def _plot(outdir, hist):
    plt = pyplot()
    fig, axes = plt.subplots(len(hist), 2, figsize=(11, 3.4 * len(hist)), squeeze=False)
    for (name, runs), (a1, a2) in zip(hist.items(), axes):
        for label, res, _ in runs:
            a1.plot(res.times, res.sway_deg[:, -1], lw=1, label=label)
            ok = np.flatnonzero(np.isfinite(res.rope_force[0]))
            a2.plot(res.times, res.rope_force[:, ok[0]] / 1e3, lw=1, label=label)
        a1.set(title=f"{name}: sway of {runs[0][1].sway_names[-1]}", xlabel="t [s]",
               ylabel="deg")
        a2.set(title=f"{name}: force of {runs[0][1].rope_names[ok[0]]}", xlabel="t [s]",
               ylabel="kN")
        a1.legend(fontsize=7)
    return save(fig, outdir, "operation_effects.png")


def markdown(rows):
    """The measured table of docs/operations.md (from the CSV's rows)."""
    lines = [("| scene | variant | steps (rejected) | CPU [s] | CPU / reference | "
              "position [m] | sway [deg] | sway residual [deg] | peak force | "
              "dynamic factor |"), "|---|---|---|---|---|---|---|---|---|---|"]

    def e(x):
        x = float(x)
        return "-" if not np.isfinite(x) else ("0" if x == 0 else f"{x:.1e}")
    for r in rows:
        lines.append(f"| {r['scene']} ({float(r['duration_s']):g} s) | {r['variant']} | "
                     f"{int(r['steps'])} ({int(r['rejected'])}) | "
                     f"{float(r['cpu_s']):.3g} | {float(r['cpu_ratio']):.2f} | "
                     f"{e(r['position_error_m'])} | {e(r['sway_error_deg'])} | "
                     f"{e(r['sway_residual_error_deg'])} | {e(r['peak_force_difference'])} | "
                     f"{float(r['dynamic_factor']):.4f} |")
    return "\n".join(lines) + "\n"


def formulation_markdown(rows):
    lines = [("| step [s] | index-3 trapezoidal: error | its oscillating part | this "
              "engine: error | its oscillating part |"), "|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {float(r['step_s']):g} | {float(r['index3_error']):.1e} | "
                     f"{float(r['index3_oscillation']):.1e} | "
                     f"{float(r['engine_error']):.1e} | "
                     f"{float(r['engine_oscillation']):.1e} |")
    return "\n".join(lines) + "\n"


def run(outdir, quick=False):
    import csv
    rows, hist = measure(quick)
    form = formulation_rows(outdir, quick)
    written = [write_csv(outdir, "operation_effects.csv", rows, KEYS),
               write_csv(outdir, "operation_effects_formulation.csv", form),
               _plot(outdir, hist)]
    docs = os.path.join(os.path.dirname(os.path.abspath(outdir)), "docs", "operations.md")
    if not quick:
        tables = []
        for p in written[:2]:                   # the page quotes the CSVs as written
            with open(p) as fh:
                tables.append(list(csv.DictReader(fh)))
        written += rewrite_doc_blocks(docs, "operation_effects", (
            ("table", markdown(tables[0])), ("formulation", formulation_markdown(tables[1]))))
    return written
