"""Presentation of a TransientResult: JSON document, terminal table, CSV, PNG plots."""

import csv
import os

import numpy as np

from ..jsonable import num


def document(result):
    """The JSON document of ``cranefe simulate --json`` (docs/transient.md)."""
    r = result
    ropes = r.rope_names
    drums = {}
    for k, name in enumerate(r.drum_names):
        drums[name] = {"drive": r.drum_drive[k],
                       "speed_final_rad_s": num(r.drum_speed[-1, k]),
                       "speed_max_rad_s": num(np.abs(r.drum_speed[:, k]).max()),
                       "torque_max_N_m": num(r.drum_torque[:, k].max()),
                       "torque_min_N_m": num(r.drum_torque[:, k].min())}
    return {
        "model": r.model_name, "scene": r.scene, "method": r.method,
        "initial": r.initial, "effects": r.effects, "dofs": r.dofs,
        "duration_s": num(r.duration), "time_step_s": num(r.time_step),
        "steps": r.steps, "modes": r.modes if r.method == "modal" else None,
        "highest_frequency_hz": num(r.highest_frequency_hz),
        "dynamic_factor": {n: num(v) for n, v in zip(ropes, r.dynamic_factor)},
        "rope_force_max_N": {n: num(v) for n, v in zip(ropes, r.rope_force_max)},
        "rope_force_max_time_s": {n: num(v) for n, v in zip(ropes, r.rope_force_max_time)},
        "rope_force_static_N": {n: num(v) for n, v in zip(ropes, r.rope_force_static)},
        "lift_off_time_s": num(r.lift_off_time),
        "lift_off_times_s": {n: num(v) for n, v in zip(r.ground_names, r.lift_off_times)},
        "drums": drums,
        "energy_error": num(r.energy_error),
        "energy_J": {k: num(v) for k, v in r.energy.items()},
        "events": r.events[:100], "events_total": len(r.events),
        "timings_s": {k: round(v, 6) for k, v in r.timings.items()},
        "warnings": list(r.warnings),
    }


def table(result):
    r = result
    eff = ", ".join(f"{k} {({True: 'on', False: 'off'}).get(v, v)}"
                    for k, v in r.effects.items())
    how = f"modal superposition, {r.modes} elastic modes" if r.method == "modal" \
        else "direct integration"
    lines = [f"{r.scene or r.model_name}: {how}, {r.dofs} coordinates ({eff})",
             f"  {r.steps} steps of {r.time_step:.4g} s over {r.duration:g} s, initial "
             f"state {r.initial}"]
    head = (f"  {'rope':<20} {'static [N]':>12} {'max [N]':>12} {'at [s]':>9} "
            f"{'dynamic factor':>15}")
    lines += [head, "  " + "-" * (len(head) - 2)]
    for n, s, m, t, f in zip(r.rope_names, r.rope_force_static, r.rope_force_max,
                             r.rope_force_max_time, r.dynamic_factor):
        lines.append(f"  {n:<20} {s:>12.6g} {m:>12.6g} {t:>9.4g} {f:>15.4f}")
    for k, name in enumerate(r.drum_names):
        lines.append(f"  drum {name} ({r.drum_drive[k]}): speed {r.drum_speed[-1, k]:.4g} "
                     f"rad/s at the end, torque {r.drum_torque[:, k].min():.4g} .. "
                     f"{r.drum_torque[:, k].max():.4g} N m")
    for n, t in zip(r.ground_names, r.lift_off_times):
        lines.append(f"  {n}: " + (f"lift-off at t = {t:.6g} s" if np.isfinite(t)
                                   else "stays on the ground"))
    if np.isfinite(r.energy_error):
        lines.append(f"  energy balance error: {r.energy_error:.2e}")
    if r.events:
        lines.append(f"  events: {len(r.events)}" + (", the first ones:"
                                                      if len(r.events) > 8 else ""))
        lines += [f"    {e}" for e in r.events[:8]]
    lines += [f"warning: {w}" for w in r.warnings]
    return "\n".join(lines)


def write_csv(path, result, extra=None):
    """Time histories: t, rope forces, drum angle/speed/torque, load displacements and
    ground forces, then the columns of `extra` = (names, values (time, k)) if given (the
    bodies, outputs/histories.py); written to a temporary file, then renamed."""
    r = result
    from ...outpaths import atomic
    cols = ["t_s"] + [f"rope_{n}_N" for n in r.rope_names]
    for n in r.drum_names:
        cols += [f"drum_{n}_rad", f"drum_{n}_rad_s", f"drum_{n}_N_m"]
    for n in r.load_names:
        cols += [f"{n}_u{a}_m" for a in "xyz"]
    cols += [f"ground_{n}_N" for n in r.ground_names]
    names, more = extra if extra is not None else ((), np.zeros((len(r.times), 0)))
    with atomic(path) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(cols + list(names))
        for k, t in enumerate(r.times):
            row = [t] + list(r.rope_force[k])
            for d in range(len(r.drum_names)):
                row += [r.drum_angle[k, d], r.drum_speed[k, d], r.drum_torque[k, d]]
            row += list(r.load_displacement[k].ravel()) + list(r.ground_force[k])
            w.writerow([f"{x:.9g}" for x in row + list(more[k])])
    return path


def plot(folder, result):
    """transient.png: rope forces (static level dotted, peaks marked), drum speeds and
    torques, load displacements."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    r = result
    from ...outpaths import make_folder, save_figure
    make_folder(folder, "--plots")
    fig, axes = plt.subplots(3, 1, figsize=(9, 9), sharex=True)
    ax = axes[0]
    for k, name in enumerate(r.rope_names):
        line, = ax.plot(r.times, r.rope_force[:, k] / 1e3, label=f"{name}: "
                        f"phi = {r.dynamic_factor[k]:.3f}")
        ax.axhline(r.rope_force_static[k] / 1e3, ls=":", color=line.get_color())
        ax.plot([r.rope_force_max_time[k]], [r.rope_force_max[k] / 1e3], "v",
                color=line.get_color())
    for t in r.lift_off_times[np.isfinite(r.lift_off_times)]:
        ax.axvline(t, ls="--", color="k", lw=0.8)
    ax.set_ylabel("rope force [kN]")
    ax.legend(fontsize=8)
    ax = axes[1]
    for k, name in enumerate(r.drum_names):
        ax.plot(r.times, r.drum_speed[:, k], label=f"drum {name} ({r.drum_drive[k]})")
    ax.set_ylabel("drum speed [rad/s]")
    if r.drum_names:
        ax.legend(fontsize=8)
        tw = ax.twinx()
        for k in range(len(r.drum_names)):
            tw.plot(r.times, r.drum_torque[:, k] / 1e3, ls="--", lw=0.8)
        tw.set_ylabel("drum torque [kN m] (dashed)")
    ax = axes[2]
    for k, name in enumerate(r.load_names):
        ax.plot(r.times, r.load_displacement[:, k, 2] * 1e3, label=f"{name} z")
    ax.set_ylabel("displacement [mm]")
    ax.set_xlabel("t [s]")
    if r.load_names:
        ax.legend(fontsize=8)
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.suptitle(f"{r.scene or r.model_name} ({r.method}, h = {r.time_step:.3g} s)")
    fig.tight_layout()
    path = os.path.join(folder, "transient.png")
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return [path]
