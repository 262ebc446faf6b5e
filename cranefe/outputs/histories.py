"""Time histories of the rigid bodies of a transient run (a trolley, a girder, a boom):
the displacement of each body's centre of mass and its rotation, recovered from the
generalised coordinates (u = T q), added to the transient CSV and plotted."""

import csv
import os

import numpy as np


def body_histories(dofs, q):
    """(displacement (nt, nb, 3) m of the centres of mass, rotation (nt, nb, 3) rad
    about x, y, z) of the bodies in model order, for coordinates q (nt, n) from the
    reference state.

    A body's primitive coordinates are its centre's translation and its rotation
    (`coordinates.layout.Layout.body`); T maps the generalised ones to them."""
    layout = dofs.layout
    nb = layout.n_bodies
    if nb == 0:
        return np.zeros((len(q), 0, 3)), np.zeros((len(q), 0, 3))
    rows = layout.body(np.arange(nb)).ravel()                 # (6 nb,)
    u = (dofs.T[rows] @ np.asarray(q).T).T.reshape(len(q), nb, 6)
    return u[:, :, :3], u[:, :, 3:]


def _names(model):
    return tuple(b.name for b in model.bodies)


def body_columns(model):
    cols = []
    for n in _names(model):
        cols += [f"body_{n}_u{a}_m" for a in "xyz"] + [f"body_{n}_r{a}_rad" for a in "xyz"]
    return cols


def write_transient_csv(path, result, model, dofs):
    """The transient CSV (`analysis.transient.output.write_csv`: time, rope forces,
    drums, point masses, ground forces) followed by six columns per body:
    body_NAME_ux_m, _uy_m, _uz_m (centre of mass) and body_NAME_rx_rad, _ry_rad, _rz_rad;
    written atomically. Returns the path."""
    import tempfile

    from ..analysis.transient.output import write_csv
    from ..outpaths import atomic
    if not model.bodies:
        return write_csv(path, result)
    u, r = body_histories(dofs, result.q)
    with tempfile.TemporaryDirectory() as d:
        with open(write_csv(os.path.join(d, "base.csv"), result), newline="") as fh:
            rows = list(csv.reader(fh))
    extra = np.concatenate([u, r], axis=2).reshape(len(result.q), -1)  # body-major
    with atomic(path) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(rows[0] + body_columns(model))
        for row, x in zip(rows[1:], extra):
            w.writerow(row + [f"{v:.9g}" for v in x])
    return path


def plot_bodies(folder, result, model, dofs):
    """transient_bodies.png: the centres of mass' displacements and the rotations of
    every body over time. Returns [path] ([] without bodies)."""
    if not model.bodies:
        return []
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..outpaths import make_folder, save_figure
    make_folder(folder, "--plots")
    u, r = body_histories(dofs, result.q)
    fig, axes = plt.subplots(2, 1, figsize=(9, 6.5), sharex=True)
    for k, n in enumerate(_names(model)):
        for a, axis in enumerate("xyz"):
            if np.any(u[:, k, a]):
                axes[0].plot(result.times, u[:, k, a] * 1e3, label=f"{n} u{axis}")
            if np.any(r[:, k, a]):
                axes[1].plot(result.times, np.degrees(r[:, k, a]), label=f"{n} r{axis}")
    axes[0].set_ylabel("centre of mass [mm]")
    axes[1].set_ylabel("rotation [deg]")
    axes[1].set_xlabel("t [s]")
    for ax in axes:
        ax.grid(alpha=0.3)
        if ax.lines:
            ax.legend(fontsize=8, ncol=2)
    fig.suptitle(f"{result.scene or result.model_name}: bodies")
    fig.tight_layout()
    path = os.path.join(folder, "transient_bodies.png")
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return [path]
