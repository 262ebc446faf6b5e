"""The engine half of `cranefe study shaping`: shapers run through the operation engine on
the bundled tower crane (trolley and slewing; hook 250 kg and 4 t load on a 3 m sling:
the double pendulum) and a luffing-jib crane (luffing by its hinge), docs/shaping.md.

Tables (results/):
- shaping_engine.csv / .json: residual sway of every hanging mass after each motion,
  unshaped and with ZV, ZVD, ZVDD, EI (frequency auto: both pendulum modes), move time;
- shaping_varying.csv: the same motions while the hook is hoisted 20 m, shapers designed
  at the start length, the mean length and the end length, and the time-varying ZV
  (cranefe/analysis/shaping/varying.py);
- shaping_engine_robustness.csv: residual sway against the error in the assumed rope
  length (the shapers' frequencies w / sqrt(1 + e)), engine beside the linear V(w);
- shaping_swing_free.csv: the minimum-time swing-free trapezoid and the energy-optimal
  swing-free move for the trolley and slewing, through the engine.
"""

import os
import tempfile

import numpy as np

MODELS = os.path.join(os.path.dirname(__file__), "..", "..", "models", "operations")
TOWER = os.path.abspath(os.path.join(MODELS, "tower_crane.yaml"))
LUFFING = os.path.abspath(os.path.join(MODELS, "luffing_jib_crane.yaml"))
KINDS = ("unshaped", "ZV", "ZVD", "ZVDD", "EI")
OBSERVE = 40.0              # s watched after the last drive stops (> 3 periods of 12 s)

# name -> (model, drive name, drive entry (YAML flow), duration of the unshaped move)
MOTIONS = {
    "trolley 15 m": (TOWER, "trolley",
                     "{slider: trolley_travel, profile: {type: trapezoid, distance: 15.0, "
                     "v_max: 1.0, a_max: 0.5}}", 17.0),
    "slewing 90 deg": (TOWER, "slewing",
                       "{hinge: slewing, profile: {type: s_curve, distance_deg: 90, "
                       "v_max_deg: 4.8, a_max_deg: 1.2, j_max_deg: 1.2}}", 23.75),
    "luffing 60 to 45 deg": (LUFFING, "luff",
                             "{hinge: luffing, profile: {type: trapezoid, distance_deg: "
                             "15, v_max_deg: 1.0, a_max_deg: 0.5}}", 17.0),
}
# hoisting during the motion: the hook rises 20 m at 1 m/s, 0.5 m/s^2, from t = 0
HOIST = {TOWER: "{drum: hoist, profile: {type: trapezoid, distance: 266.667, v_max: "
                "13.333, a_max: 6.6667}}",          # 4 falls, r = 0.3 m: 1 m = 13.33 rad
         LUFFING: "{drum: hoist, profile: {type: trapezoid, distance: 80.0, v_max: 4.0, "
                  "a_max: 2.0}}"}                  # 1 fall, r = 0.25 m: 1 m = 4 rad
HOIST_TIME = 22.0           # s: 20 m at 1 m/s with 2 s ramps


def _scene(tmp, model, drives, duration, name, quick=False):
    """A scene file of `model` with these drives; quick runs at tolerance 1e-5 instead of
    the default 1e-7 (the quick hoisting run's residual sway moves by 2e-4 deg of 9.36,
    at a third of the time without numba)."""
    from ..model import load
    path = os.path.join(tmp, name)
    tol = "  tolerance: 1.0e-5\n" if quick else ""
    with open(path, "w") as fh:
        fh.write(f"cranefe: 1\nscene: {name}\nmodel: {model}\nanalysis:\n  type: operation\n"
                 f"  duration: {duration}\n  output_step: 0.05\n{tol}  drives:\n")
        for k, v in drives.items():
            fh.write(f"    {k}: {v}\n")
    return load(path)


def _model(tmp, motion, hoist=False, name="scene.yaml", quick=False):
    model, drive, entry, dur = MOTIONS[motion]
    drives = {drive: entry}
    if hoist:
        drives["hoist"] = HOIST[model]
        dur = max(dur, HOIST_TIME)
    return _scene(tmp, model, drives, dur + _observe(quick), name, quick), drive


def _observe(quick):
    """Seconds watched after the last drive stops: > 3 swing periods (12 s), or just one
    in quick runs (the residual then is a lower bound; the engine warns)."""
    return 14.0 if quick else OBSERVE


def _row(motion, label, out):
    by = out["residual_sway_deg_by_node"]
    return {"motion": motion, "shaper": label,
            "residual_hook_deg": float(by.get("HOOK", np.nan)),
            "residual_load_deg": float(by.get("LOAD", np.nan)),
            "max_sway_deg": out["max_sway_deg"], "move_time_s": out["move_time_s"],
            "extra_time_s": out.get("extra_time_s", np.nan),
            "frequencies_hz": " ".join(f"{f:.5g}" for f in out.get("frequencies_hz", []))}


def kinds(quick=False):
    """Every shaper kind on every motion (frequency auto) -> rows, JSON document."""
    from ..analysis.shaping.engine import compare
    rows, doc = [], {}
    with tempfile.TemporaryDirectory() as tmp:
        for motion in (list(MOTIONS)[:1] if quick else MOTIONS):
            m, drive = _model(tmp, motion, quick=quick)
            ks = ("unshaped", "ZV") if quick else KINDS
            doc[motion] = compare(m, drive, kinds=ks)
            rows += [_row(motion, k, v) for k, v in doc[motion]["shapers"].items()]
            if motion.startswith("slewing") and not quick:
                # half the slewing speed: the centrifugal tilt r Omega^2 / g a quarter
                slow = _scene(tmp, TOWER, {drive: MOTIONS[motion][2].replace(
                    "v_max_deg: 4.8", "v_max_deg: 2.4")}, 40.5 + OBSERVE, "slow.yaml")
                half = compare(slow, drive, kinds=("unshaped", "ZV"))
                doc[motion + " at 2.4 deg/s"] = half
                rows += [_row(motion + " at 2.4 deg/s", k, v)
                         for k, v in half["shapers"].items()]
            if MOTIONS[motion][0] == TOWER and not quick:
                one = compare(m, drive, kinds=("ZV",), modes=[1])["shapers"]["ZV"]
                one["extra_time_s"] = one["move_time_s"] - \
                    doc[motion]["shapers"]["unshaped"]["move_time_s"]
                rows.append(_row(motion, "ZV, mode 1 only", one))
    return rows, doc


def _pendulum_hz(model, op, drive, t):
    from ..analysis.operation.shaped import auto_omegas
    d = next(x for x in op.drives if x.name == drive)
    return [w / (2 * np.pi) for w in auto_omegas(model, op, d, t)]


def _tv_entry(model, op, drive, entry, n=4000):
    """The time-varying ZV of the drive's move for mode 1, times a ZV at mode 2's start
    frequency if the load hangs on a hook (double pendulum): a table profile in the
    drive's units. w(t) is sampled from the crane's quasi-static modes along the move,
    the gain k (horizontal speed of the node the load hangs from per unit drive speed)
    along it too; both are sampled again along the shaped move (one fixed-point pass:
    they depend on where the shaped drive is, not where the unshaped one would be)."""
    import dataclasses

    import yaml
    from scipy.interpolate import CubicSpline

    from ..analysis.operation import profiles
    from ..analysis.operation.shaped import auto_omegas, crane_modes
    from ..analysis.shaping.varying import omega2_from_samples, time_varying_zv
    k = next(i for i, x in enumerate(op.drives) if x.name == drive)
    d = op.drives[k]
    mv = d.motion
    t0, t1 = float(mv.t[0]), float(mv.t[-1])
    dist = float(mv(1e9)[0])
    w_start = auto_omegas(model, op, d, t0)
    span = t1 + 1.2 * np.pi / min(w_start) + 5.0
    ts = np.linspace(t0, span, 61)
    cur = op
    for _ in range(2):
        dd = cur.drives[k]
        w1 = [auto_omegas(model, cur, dd, float(t))[0] for t in ts]
        omega2 = omega2_from_samples(ts, w1)
        _, _, _, _, mech = crane_modes(model, cur, t0)
        node = mech.root[0]
        H = np.eye(3) - np.outer(mech.up, mech.up)
        pos = np.array([dd.motion(float(t))[0] for t in ts])
        Xh = np.array([H @ mech.kinematics(float(t))[0][node] for t in ts])
        keep = np.concatenate([[True], np.diff(pos) > 1e-9 * abs(dist)])
        if keep.sum() > 3:
            spl = CubicSpline(pos[keep], Xh[keep])
            der = spl.derivative()

            def gain(t, dd=dd, der=der, lo=pos[keep][0], hi=pos[keep][-1]):
                s = min(max(dd.motion(t)[0], lo), hi)
                return float(np.linalg.norm(der(s)))
        else:
            gain = None
        t, v = time_varying_zv(mv.t, lambda x: mv(x)[2], omega2, dist, n=n, gain=gain)
        table = profiles.speed_table(t, v)
        drives = list(cur.drives)
        drives[k] = dataclasses.replace(dd, motion=table)
        cur = dataclasses.replace(cur, drives=tuple(drives))
    spec = yaml.safe_load(entry)
    prof = {"type": "table", "speed": [[float(a), float(b)] for a, b in zip(t, v)]}
    if len(w_start) > 1:
        prof["shaper"] = {"type": "ZV", "frequency": [w / (2 * np.pi) for w in w_start[1:]]}
    spec.pop("profile")
    spec["profile"] = prof
    return spec, float(np.abs(v).max())


def varying(quick=False):
    """Each motion while hoisting 20 m: ZV, ZVD, EI designed at the start, mean and end
    rope length (the crane's modes at the start of the move, where the hoist has done
    half its travel, and at its end), and the time-varying ZV."""
    from scipy.optimize import brentq

    from ..analysis.operation.integrate import simulate
    from ..analysis.operation.scene import parse
    from ..analysis.shaping.engine import shaped_model, summary
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for motion in (list(MOTIONS)[:1] if quick else MOTIONS):
            m, drive = _model(tmp, motion, hoist=True, name="hoist.yaml", quick=quick)
            op = parse(m)
            hoist = next(x for x in op.drives if x.name == "hoist").motion
            D = hoist(1e9)[0]
            t_mid = brentq(lambda t: hoist(t)[0] - D / 2, 0.0, hoist.t[-1])
            when = {"start": 0.0, "mean": t_mid, "end": float(hoist.t[-1])}
            freqs = {k: _pendulum_hz(m, op, drive, t) for k, t in when.items()}
            res = simulate(m)
            ref = summary(res, next(x for x in op.drives if x.name == drive).motion)
            rows.append(_row(motion, "unshaped", ref))
            designs = [] if quick else \
                [(k, w) for k in ("ZV", "ZVD", "EI") for w in ("start", "mean")] + \
                [("ZV", "end")]
            for kind, at in designs:
                mm = shaped_model(m, drive, {"type": kind, "frequency": freqs[at]})
                d = next(x for x in parse(mm).drives if x.name == drive)
                out = summary(simulate(mm), d.motion)
                out["frequencies_hz"] = freqs[at]
                out["extra_time_s"] = out["move_time_s"] - ref["move_time_s"]
                rows.append(_row(motion, f"{kind} at the {at} length", out))
            entry = MOTIONS[motion][2]
            spec, vpeak = _tv_entry(m, op, drive, entry, n=600 if quick else 4000)
            import yaml
            mm = _scene(tmp, MOTIONS[motion][0],
                        {drive: yaml.safe_dump(spec, default_flow_style=True,
                                               width=1 << 30).strip(),
                         "hoist": HOIST[MOTIONS[motion][0]]},
                        max(spec["profile"]["speed"][-1][0], HOIST_TIME) + _observe(quick),
                        "tv.yaml", quick)
            d = next(x for x in parse(mm).drives if x.name == drive)
            out = summary(simulate(mm), d.motion)
            out["extra_time_s"] = out["move_time_s"] - ref["move_time_s"]
            row = _row(motion, "time-varying ZV", out)
            row["frequencies_hz"] = "w(t) along the move"
            row["peak_speed_over_command"] = vpeak / float(
                np.abs(next(x for x in op.drives if x.name == drive).motion.v).max())
            rows.append(row)
            for r in rows:
                r.setdefault("peak_speed_over_command", float("nan"))
                if r["motion"] == motion:
                    r["length_start_mean_end_hz"] = " ".join(
                        f"{freqs[k][0]:.5g}" for k in ("start", "mean", "end"))
    return rows


def robustness(quick=False):
    """Trolley 15 m on the tower crane: residual sway against the error e of the assumed
    rope length, the shapers designed for w / sqrt(1 + e) (both modes), beside the
    linear prediction V(w_true) x the unshaped residual (of the load, mode 1)."""
    from ..analysis.operation.integrate import simulate
    from ..analysis.operation.scene import parse
    from ..analysis.operation.shaped import build_shaper, parse_shaper
    from ..analysis.shaping.engine import shaped_model, summary
    from ..model.load import _Reader
    rows = []
    errors = (0.3,) if quick else tuple(np.round(np.arange(-0.4, 0.41, 0.1), 2))
    shapers = ("ZV",) if quick else ("ZV", "ZVD", "ZVDD", "EI")
    with tempfile.TemporaryDirectory() as tmp:
        m, drive = _model(tmp, "trolley 15 m", quick=quick)
        op = parse(m)
        f_true = _pendulum_hz(m, op, drive, 0.0)
        d0 = next(x for x in op.drives if x.name == drive)
        ref = summary(simulate(m), d0.motion)
        for e in errors:
            row = {"length_error": float(e)}
            for kind in shapers:
                f = [x / np.sqrt(1 + e) for x in f_true]
                mm = shaped_model(m, drive, {"type": kind, "frequency": f})
                d = next(x for x in parse(mm).drives if x.name == drive)
                out = summary(simulate(mm), d.motion)
                row[f"{kind}_load_deg"] = out["residual_sway_deg_by_node"]["LOAD"]
                row[f"{kind}_hook_deg"] = out["residual_sway_deg_by_node"]["HOOK"]
                sp = parse_shaper(_Reader(""), {"type": kind, "frequency": f}, "")
                s = build_shaper(sp, [2 * np.pi * x for x in f])
                row[f"{kind}_linear_load_deg"] = float(
                    s.residual(2 * np.pi * f_true[0]) *
                    ref["residual_sway_deg_by_node"]["LOAD"])
            row["unshaped_load_deg"] = ref["residual_sway_deg_by_node"]["LOAD"]
            rows.append(row)
    return rows, shapers


def swing_free(quick=False):
    """The minimum-time swing-free trapezoid (shaping.swingfree) and the energy-optimal
    swing-free move of 1.25 x its duration, designed for the equivalent pendulum of mode
    1 (l = g / w1^2 at the start), for the trolley and the slewing motion through the
    engine, beside the unshaped and the ZV-shaped (both modes) move."""
    from ..analysis.operation.integrate import simulate
    from ..analysis.operation.scene import parse
    from ..analysis.shaping import energy_optimal_swing_free, min_time_swing_free
    from ..analysis.shaping.engine import shaped_model, summary
    from ..cases import G
    rows = []
    radius = 10.0                  # m: the trolley's radius on the jib (slewing)
    cases = {"trolley 15 m": (15.0, 1.0, 0.5, 1.0),
             "slewing 90 deg": (np.pi / 2 * radius, np.radians(4.8) * radius,
                                np.radians(1.2) * radius, radius)}
    with tempfile.TemporaryDirectory() as tmp:
        for motion in (list(cases)[:1] if quick else cases):
            D, v, a, scale = cases[motion]
            model, drive, entry, dur = MOTIONS[motion]
            m, _ = _model(tmp, motion, quick=quick)
            op = parse(m)
            f = _pendulum_hz(m, op, drive, 0.0)
            l_eq = G / (2 * np.pi * f[0]) ** 2
            d0 = next(x for x in op.drives if x.name == drive)
            ref = summary(simulate(m), d0.motion)
            rows.append(_row(motion, "unshaped", ref))
            if not quick:
                mm = shaped_model(m, drive, {"type": "ZV"})
                d = next(x for x in parse(mm).drives if x.name == drive)
                out = summary(simulate(mm), d.motion)
                out["extra_time_s"] = out["move_time_s"] - ref["move_time_s"]
                rows.append(_row(motion, "ZV (both modes)", out))
            free = min_time_swing_free(D, v, a, l_eq)
            target = "slider: trolley_travel" if drive == "trolley" else "hinge: slewing"
            acc, vp = free["acceleration"] / scale, free["acceleration"] * free["t_acc"] / scale
            prof = (f"{{type: trapezoid, distance: {float(D / scale)!r}, v_max: "
                    f"{float(vp)!r}, a_max: {float(acc)!r}}}")
            T = free["time_s"]
            laws = [(f"min-time swing-free trapezoid ({free['family']})", prof, T)]
            # the fastest trapezoid whose ramps are each swing-free (t_a = T): it does
            # not rely on the deceleration cancelling the acceleration's swing
            Tp = free["period_s"]
            a1 = min(a, v / Tp)
            s1 = max(D / (a1 * Tp), Tp)
            a1 = D / (Tp * s1)
            laws.append(("swing-free trapezoid (acceleration: t_a = 1 T)",
                         f"{{type: trapezoid, distance: {float(D / scale)!r}, v_max: "
                         f"{float(a1 * Tp / scale)!r}, a_max: {float(a1 / scale)!r}}}",
                         Tp + s1))
            if quick:
                laws = []
            eo = energy_optimal_swing_free(D, 1.25 * T, l_eq)
            tab = eo["table"](300)
            speed = [[float(t), float(s / scale)] for t, s in zip(tab["times"], tab["values"])]
            speed[-1][1] = 0.0
            laws.append(("energy-optimal swing-free, 1.25 x", "{type: table, speed: "
                         + repr(speed) + "}", 1.25 * T))
            for label, p, T_law in laws:
                mm = _scene(tmp, model, {drive: f"{{{target}, profile: {p}}}"},
                            T_law + _observe(quick), "law.yaml", quick)
                d = next(x for x in parse(mm).drives if x.name == drive)
                out = summary(simulate(mm), d.motion)
                row = _row(motion, label, out)
                row["extra_time_s"] = out["move_time_s"] - ref["move_time_s"]
                row["frequencies_hz"] = f"{f[0]:.5g} (l = {l_eq:.4g} m)"
                rows.append(row)
    return rows
