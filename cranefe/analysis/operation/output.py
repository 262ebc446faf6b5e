"""Presentation of an OperationResult: terminal table, CSV, PNG plots."""

import csv
import os

import numpy as np


def table(r):
    lines = [(f"{r.scene or r.model_name}: operation, {len(r.coordinates)} coordinates, "
              f"{r.steps} steps ({r.rejected} rejected) over {r.duration:g} s"),
             (f"  {'rope':<20} {'static [N]':>12} {'max [N]':>12} {'at [s]':>9} "
              f"{'dynamic factor':>15}")]
    for n, s, m, t, f in zip(r.rope_names, r.rope_force_static, r.rope_force_max,
                             r.rope_force_max_time, r.dynamic_factor):
        if np.isfinite(m):
            lines.append(f"  {n:<20} {s:>12.6g} {m:>12.6g} {t:>9.4g} {f:>15.4f}")
    for n, mx, rs in zip(r.sway_names, r.sway_max_deg, r.sway_residual_deg):
        lines.append(f"  sway of {n}: max {mx:.4g} deg, residual "
                     + (f"{rs:.4g} deg" if np.isfinite(rs) else "-"))
    for k, n in enumerate(r.drive_names):
        pu, su = r.drive_units[k]
        lines.append(f"  drive {n} ({r.drive_kind[k]}): {r.drive_position[-1, k]:.6g} {pu} "
                     f"at the end, speed up to {np.abs(r.drive_speed[:, k]).max():.4g} {su}")
    lines.append(f"  energy balance error: {r.energy_error:.2e}")
    if r.events:
        lines.append(f"  events: {len(r.events)}")
        lines += [f"    {t:.6g} s: {w}" for t, w in r.events[:8]]
    lines += [f"warning: {w}" for w in r.warnings]
    return "\n".join(lines)


def write_csv(path, r, extra=None):
    """One row per output time: t_s, NODE.x_m/y_m/z_m of every node with a mass,
    ROPE.force_N, DRIVE.position and DRIVE.speed (issue 16's contract), then the
    columns of `extra` = (names, values (time, k)) if given (the bodies, outputs/
    histories.py); written atomically (outpaths)."""
    from ...outpaths import atomic
    cols = ["t_s"]
    for n in r.mass_names:
        cols += [f"{n}.x_m", f"{n}.y_m", f"{n}.z_m"]
    cols += [f"{n}.force_N" for n in r.rope_names]
    for n in r.drive_names:
        cols += [f"{n}.position", f"{n}.speed"]
    names, more = extra if extra is not None else ((), np.zeros((len(r.times), 0)))
    with atomic(path) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(cols + list(names))
        for k, t in enumerate(r.times):
            row = [t] + list(r.mass_position[k].ravel()) + list(r.rope_force[k])
            for d in range(len(r.drive_names)):
                row += [r.drive_position[k, d], r.drive_speed[k, d]]
            w.writerow([f"{x:.9g}" for x in row + list(more[k])])
    return path


def plot(folder, r):
    """operation.png: sway angles, rope forces, drive speeds (and drum torques, dashed),
    and the loads' paths seen from above."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    os.makedirs(folder, exist_ok=True)
    fig = plt.figure(figsize=(12, 9))
    ax = fig.add_subplot(3, 2, 1)
    for k, n in enumerate(r.sway_names):
        ax.plot(r.times, r.sway_deg[:, k], label=n)
    if np.isfinite(r.motion_end):
        ax.axvline(r.motion_end, ls="--", color="k", lw=0.8)
    ax.set_ylabel("sway [deg]")
    ax.legend(fontsize=8)
    ax = fig.add_subplot(3, 2, 3)
    for k, n in enumerate(r.rope_names):
        if np.any(np.isfinite(r.rope_force[:, k])):
            line, = ax.plot(r.times, r.rope_force[:, k] / 1e3, label=n)
            ax.axhline(r.rope_force_static[k] / 1e3, ls=":", color=line.get_color())
    ax.set_ylabel("rope force [kN]")
    ax.legend(fontsize=8)
    ax = fig.add_subplot(3, 2, 5)
    for k, n in enumerate(r.drive_names):
        ax.plot(r.times, r.drive_speed[:, k], label=f"{n} [{r.drive_units[k][1]}]")
    ax.set_ylabel("drive speed")
    ax.set_xlabel("t [s]")
    if r.drive_names:
        ax.legend(fontsize=8)
    drums = [k for k in range(len(r.drive_names)) if np.any(np.isfinite(r.drive_torque[:, k]))]
    if drums:
        tw = ax.twinx()
        for k in drums:
            tw.plot(r.times, r.drive_torque[:, k] / 1e3, ls="--", lw=0.8)
        tw.set_ylabel("drum torque [kN m] (dashed)")
    ax = fig.add_subplot(1, 2, 2)
    for k, n in enumerate(r.mass_names):
        ax.plot(r.mass_position[:, k, 0], r.mass_position[:, k, 1], label=n)
        ax.plot(r.mass_position[-1, k, 0], r.mass_position[-1, k, 1], "o",
                color=ax.lines[-1].get_color())
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("paths seen from above")
    ax.legend(fontsize=8)
    for a in fig.axes:
        a.grid(alpha=0.3)
    fig.suptitle(r.scene or r.model_name)
    fig.tight_layout()
    path = os.path.join(folder, "operation.png")
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return [path]
