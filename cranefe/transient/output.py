"""Time histories of a transient result: CSV and PNG plots."""

import csv
import os

import numpy as np


def write_csv(path, result):
    """Columns: t, each rope's force, each drum's speed (written then renamed)."""
    tmp = f"{path}.{os.getpid()}.tmp"
    with open(tmp, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["t_s"] + [f"rope_{n}_N" for n in result.rope_names]
                   + [f"drum_{n}_rad_s" for n in result.drum_names])
        for k, t in enumerate(result.times):
            w.writerow([f"{t:.6g}"] + [f"{x:.6g}" for x in result.rope_force[k]]
                       + [f"{x:.6g}" for x in result.drum_speed[k]])
    os.replace(tmp, path)
    return path


def plot(folder, result):
    from ..studies._common import pyplot, save
    plt = pyplot()
    os.makedirs(folder, exist_ok=True)
    fig, axes = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for k, name in enumerate(result.rope_names):
        axes[0].plot(result.times, result.rope_force[:, k] / 1e3, label=f"rope {name}")
        axes[0].axhline(result.rope_force_static[k] / 1e3, ls=":", color="grey")
    axes[0].set_ylabel("rope force [kN]")
    if not np.isnan(result.lift_off_time):
        axes[0].axvline(result.lift_off_time, ls="--", color="k", label="lift-off")
    axes[0].legend()
    for k, name in enumerate(result.drum_names):
        axes[1].plot(result.times, result.drum_speed[:, k], label=f"drum {name}")
    axes[1].set_ylabel("drum speed [rad/s]")
    axes[1].set_xlabel("t [s]")
    if result.drum_names:
        axes[1].legend()
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.suptitle(f"{result.model_name}: dynamic factor "
                 + ", ".join(f"{n} {f:.3f}" for n, f in zip(result.rope_names,
                                                            result.dynamic_factor)))
    return [save(fig, folder, "transient.png")]
