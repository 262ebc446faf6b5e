"""PNG plots of a luffing result (matplotlib, off-screen): alpha(t), speed, motor torque,
kinetic energy, sway and the jib-tip path."""

import os

import numpy as np

from ...outpaths import make_folder, save_figure

SHOWN = ("optimal", "linear", "cubic", "quintic", "cycloidal", "trapezoidal",
         "rest_to_rest", "swing_free")


def _pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def write_plots(result, folder):
    """Write luffing_*.png into folder (created if missing); returns the paths."""
    plt = _pyplot()
    make_folder(folder, "--plots")
    names = list(result.law_names)
    rows = [(n, names.index(n)) for n in SHOWN if n in names]
    panels = (("alpha", "boom angle alpha (deg)", np.degrees(result.alpha)),
              ("speed", "boom speed (deg/s)", np.degrees(result.speed)),
              ("torque", "motor torque (N m)", result.motor_torque),
              ("energy", "kinetic energy of the links (kJ)", result.kinetic_energy / 1e3),
              ("sway", "load sway, nonlinear with gravity (deg)", np.degrees(result.sway)))
    paths = []
    for tag, label, data in panels:
        fig, ax = plt.subplots(figsize=(7.5, 4.5))
        for name, k in rows:
            style = dict(lw=2.2) if name == "optimal" else dict(lw=1.2)
            ax.plot(result.t, data[k], label=name.replace("_", "-"), **style)
        ax.set_xlabel("time t (s)")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, ncol=2)
        ax.set_title(f"{result.scene or result.model_name}: {label.split(' (')[0]}",
                     fontsize=10)
        fig.tight_layout()
        path = os.path.join(folder, f"luffing_{tag}.png")
        save_figure(fig, path, dpi=110)
        plt.close(fig)
        paths.append(path)
    fig, ax = plt.subplots(figsize=(7.5, 4.0))
    ax.plot(result.tip_x, result.tip_z, "k-")
    ax.plot(result.tip_x[[0, -1]], result.tip_z[[0, -1]], "ko")
    ax.set_xlabel("reach x (m)")
    ax.set_ylabel("jib-tip height z (m)")
    ax.set_title(f"jib-tip path: {result.jib_tip_deviation * 1e3:.0f} mm from level over "
                 f"{min(result.reach0, result.reachk):.1f}-"
                 f"{max(result.reach0, result.reachk):.1f} m", fontsize=10)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    path = os.path.join(folder, "luffing_tip_path.png")
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    paths.append(path)
    return paths
