"""Input shaping of a trolley move: robustness of the shapers (residual vibration against
the error in the assumed frequency or rope length), the move time each costs, the
nonlinear residual beside the linear one, the minimum-time swing-free trapezoid, and a
two-mode shaper on the hook-and-load double pendulum (docs/loads.md).

Writes results/shaping_robustness.csv/.png (V(w/w_model); the plot also shows the
residual sway of the move against the rope-length error, shaping_length_error.csv) and
results/shaping_cost.csv (one row per shaper:
move time, residual sway exact and with +/-10 % / +/-20 % rope-length error, width of the
5 % insensitivity band), results/shaping_double_pendulum.csv and
results/shaping_energy_optimal.csv (least int a^2 swing-free moves).
"""

import os

import numpy as np

from ._common import pyplot, save, write_csv

DESCRIPTION = "input shaping: residual sway vs frequency / rope-length error, move-time cost"
LENGTH, DISTANCE, V_MAX, A_MAX = 20.0, 15.0, 1.0, 0.5    # m, m, m/s, m/s^2: trolley move
EI_V = 0.05
T_JERK = 1.0                     # s: the S-curve's acceleration ramp (jerk 0.5 m/s^3)
NAMES = ("unshaped", "ZV", "ZVD", "ZVDD", "EI")
DOUBLE = {"l1": 20.0, "l2": 3.0, "m1": 400.0, "m2": 2000.0}   # hook on 20 m, load on 3 m


def _shapers(omega):
    from ..analysis.shaping import make
    return {n: make(n, omega, 0.0, **({"V": EI_V} if n == "EI" else {})) for n in NAMES}


def _band(shaper, omega, level=0.05):
    """Width (in w / w_model) of the frequency interval around w_model where V <= level."""
    r = np.linspace(0.3, 1.7, 140001)
    ok = shaper.residual(r * omega) <= level * (1 + 1e-9)    # EI touches V at w_model
    i = 70000                                   # r = 1
    if not ok[i]:
        return 0.0
    lo = i - np.argmin(ok[i::-1]) + 1 if not ok[:i].all() else 0
    hi = i + np.argmin(ok[i:]) - 1 if not ok[i:].all() else len(r) - 1
    return float(r[hi] - r[lo])


def robustness(quick=False):
    """Rows of V(w / w_model) per shaper, w / w_model from 0.5 to 1.5 (undamped)."""
    from ..analysis.shaping import pendulum_omega
    w = pendulum_omega(LENGTH)
    shapers = _shapers(w)
    return [{"frequency_ratio": float(r),
             **{f"V_{n}": float(s.residual(r * w)) for n, s in shapers.items()}}
            for r in np.linspace(0.5, 1.5, 41 if quick else 401)]


def length_error(quick=False):
    """Rows of the move's residual sway [deg] per shaper (and for the swing-free
    trapezoid) when the true rope is l (1 + e) but the shapers assume l."""
    from ..analysis.shaping import (min_time_swing_free, pendulum_omega, residual_sway,
                                    shape, trapezoid)
    move = trapezoid(DISTANCE, V_MAX, A_MAX)
    profiles = {n: shape(move, s) for n, s in _shapers(pendulum_omega(LENGTH)).items()}
    profiles["swing-free"] = min_time_swing_free(DISTANCE, V_MAX, A_MAX, LENGTH)["profile"]
    return [{"length_error": float(e),
             **{f"sway_deg_{n}": float(np.degrees(residual_sway(p, LENGTH * (1 + e))))
                for n, p in profiles.items()}}
            for e in np.linspace(-0.5, 0.5, 21 if quick else 201)]


def cost():
    """One row per shaper (and the swing-free trapezoid): move time, residual sway."""
    from ..analysis.shaping import (min_time_swing_free, nonlinear_residual_sway,
                                    pendulum_omega, residual_sway, s_curve, shape,
                                    trapezoid)
    w = pendulum_omega(LENGTH)
    move = trapezoid(DISTANCE, V_MAX, A_MAX)
    rows = []
    shapers = _shapers(w)
    cases = [(n, s, shape(move, s)) for n, s in shapers.items()]
    free = min_time_swing_free(DISTANCE, V_MAX, A_MAX, LENGTH)
    cases.append(("swing-free trapezoid", None, free["profile"]))
    smooth = s_curve(DISTANCE, V_MAX, A_MAX, A_MAX / T_JERK)
    cases += [(f"S-curve t_j = {T_JERK:g} s", None, smooth),
              (f"S-curve t_j = {T_JERK:g} s + ZV", shapers["ZV"], shape(smooth, shapers["ZV"]))]
    for n, s, p in cases:
        row = {"shaper": n, "shaper_duration_s": s.duration if s else float("nan"),
               "move_time_s": p.end, "extra_time_s": p.end - move.end,
               "residual_deg": float(np.degrees(residual_sway(p, LENGTH))),
               "residual_nonlinear_deg": float(np.degrees(nonlinear_residual_sway(p, LENGTH)))}
        for e in (-0.2, -0.1, 0.1, 0.2):
            row[f"residual_deg_length{e:+.0%}"] = float(np.degrees(
                residual_sway(p, LENGTH * (1 + e))))
        row["band_5pct"] = _band(s, w) if s else float("nan")
        rows.append(row)
    return rows, free


def double_pendulum():
    """Hook and load: each mode's residual relative to the unshaped move's, with ZV on
    the low mode only and with ZV*ZV on both (modal residuals from residual_amplitude
    with the gain -phi_k^T M 1 of the trolley acceleration on mass-normalised mode k)."""
    import scipy.linalg as sl

    from ..analysis.shaping import (convolve, double_pendulum_omegas, residual_amplitude,
                                    shape, trapezoid, zv, zvd)
    from ..cases import G
    d = DOUBLE
    w1, w2 = double_pendulum_omegas(d["l1"], d["l2"], d["m1"], d["m2"])
    M = np.diag([d["m1"], d["m2"]])
    K = G * np.array([[(d["m1"] + d["m2"]) / d["l1"] + d["m2"] / d["l2"], -d["m2"] / d["l2"]],
                      [-d["m2"] / d["l2"], d["m2"] / d["l2"]]])
    _, V = sl.eigh(K, M)
    gains = -V.T @ M @ np.ones(2)
    move = trapezoid(DISTANCE, V_MAX, A_MAX)
    rows = []
    ref = [residual_amplitude(move, w, 0.0, g) for w, g in zip((w1, w2), gains)]
    for name, s in (("unshaped", None), ("ZV low mode", zv(w1)),
                    ("ZV high mode", zv(w2)), ("ZV*ZV both modes", convolve(zv(w1), zv(w2))),
                    ("ZVD low mode", zvd(w1))):
        p = shape(move, s) if s else move
        rows.append({"shaper": name, "move_time_s": p.end,
                     "mode1_hz": w1 / (2 * np.pi), "mode2_hz": w2 / (2 * np.pi),
                     "residual_mode1_rel": residual_amplitude(p, w1, 0.0, gains[0]) / ref[0],
                     "residual_mode2_rel": residual_amplitude(p, w2, 0.0, gains[1]) / ref[1]})
    return rows


def energy_optimal():
    """The energy-optimal swing-free move (least int a^2) for durations from the
    minimum-time swing-free trapezoid's up, beside the trapezoid and the optimum
    without the sway constraints."""
    from ..analysis.shaping import energy_optimal_swing_free, min_time_swing_free
    free = min_time_swing_free(DISTANCE, V_MAX, A_MAX, LENGTH)
    rows = [{"law": "swing-free trapezoid", "duration_s": free["time_s"],
             "int_a2": 2 * free["acceleration"]**2 * free["t_acc"],
             "peak_speed": V_MAX, "peak_acceleration": free["acceleration"]}]
    for f in (1.0, 1.25, 1.5):
        for sway in (True, False):
            r = energy_optimal_swing_free(DISTANCE, f * free["time_s"], LENGTH,
                                          swing_free=sway)
            rows.append({"law": "energy-optimal" + (" swing-free" if sway else
                                                    ", sway ignored"),
                         "duration_s": r["duration_s"], "int_a2": r["cost"],
                         "peak_speed": r["peak_speed"],
                         "peak_acceleration": r["peak_acceleration"]})
    return rows


def run(outdir, quick=False):
    paths = _linear(outdir, quick)
    return paths + _engine(outdir, quick)


def _engine(outdir, quick):
    """The shapers through the operation engine (studies/_shaping_engine.py)."""
    import json

    from . import _shaping_engine as se
    from ..outpaths import write_text
    rows, doc = se.kinds(quick)
    paths = [write_csv(outdir, "shaping_engine.csv", rows)]
    path = os.path.join(outdir, "shaping_engine.json")
    write_text(path, json.dumps(doc, indent=1) + "\n")
    paths.append(path)
    var = se.varying(quick)
    keys = list(dict.fromkeys(k for r in var for k in r))
    paths.append(write_csv(outdir, "shaping_varying.csv", var, keys))
    rob, shapers = se.robustness(quick)
    paths.append(write_csv(outdir, "shaping_engine_robustness.csv", rob))
    free = se.swing_free(quick)
    paths.append(write_csv(outdir, "shaping_swing_free.csv", free))
    paths.append(_engine_figure(outdir, rob, shapers, var))
    return paths


def _engine_figure(outdir, rob, shapers, var):
    """results/shaping_engine.png: robustness (engine vs linear V) and the residuals
    under hoisting, from the rows of shaping_engine_robustness.csv / shaping_varying.csv."""
    plt = pyplot()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
    e = [100 * r["length_error"] for r in rob]
    for k, c in zip(shapers, ("C0", "C1", "C2", "C3")):
        a1.plot(e, [r[f"{k}_load_deg"] for r in rob], "o-", color=c, label=f"{k} (engine)")
        a1.plot(e, [r[f"{k}_linear_load_deg"] for r in rob], ":", color=c,
                label=f"{k} (linear V)")
    a1.set(xlabel="error in the assumed rope length [%]",
           ylabel="residual sway of the load [deg]",
           title=f"tower crane, trolley 15 m (unshaped {rob[0]['unshaped_load_deg']:.2f} deg)")
    motions = list(dict.fromkeys(r["motion"] for r in var))
    labels = list(dict.fromkeys(r["shaper"] for r in var))
    wbar = 0.8 / len(motions)
    for i, mo in enumerate(motions):
        vals = {r["shaper"]: max(r["residual_hook_deg"], r["residual_load_deg"]
                                 if r["residual_load_deg"] == r["residual_load_deg"] else 0)
                for r in var if r["motion"] == mo}
        a2.bar(np.arange(len(labels)) + i * wbar, [vals.get(k, np.nan) for k in labels],
               wbar, label=mo)
    a2.set_yscale("log")
    a2.set_xticks(np.arange(len(labels)) + 0.4 - wbar / 2)
    a2.set_xticklabels(labels, rotation=60, ha="right", fontsize=7)
    a2.set(ylabel="largest residual sway [deg]", title="hoisting 20 m during the motion")
    for a in (a1, a2):
        a.grid(alpha=0.3)
        a.legend(fontsize=7)
    return save(fig, outdir, "shaping_engine.png")


def _linear(outdir, quick=False):
    rob, err = robustness(quick), length_error(quick)
    rows, _ = cost()
    paths = [write_csv(outdir, "shaping_robustness.csv", rob),
             write_csv(outdir, "shaping_length_error.csv", err),
             write_csv(outdir, "shaping_cost.csv", rows),
             write_csv(outdir, "shaping_double_pendulum.csv", double_pendulum()),
             write_csv(outdir, "shaping_energy_optimal.csv", energy_optimal())]
    plt = pyplot()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4))
    for n in NAMES:
        a1.plot([r["frequency_ratio"] for r in rob], [r[f"V_{n}"] for r in rob], label=n)
    for n in NAMES + ("swing-free",):
        a2.plot([100 * r["length_error"] for r in err], [r[f"sway_deg_{n}"] for r in err],
                label=n, ls="--" if n == "swing-free" else "-")
    a1.axhline(EI_V, color="grey", lw=0.6, ls=":")
    a1.set(xlabel="actual / assumed frequency", ylabel="residual vibration V",
           title="shaper robustness (undamped)")
    a2.set(xlabel="rope length error [%]", ylabel="residual sway [deg]",
           title=f"{DISTANCE:g} m trolley move, {V_MAX:g} m/s, {A_MAX:g} m/s², "
                 f"l = {LENGTH:g} m")
    for a in (a1, a2):
        a.grid(alpha=0.3)
        a.legend()
    paths.append(save(fig, outdir, "shaping_robustness.png"))
    return paths
