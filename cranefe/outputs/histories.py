"""Time histories of the rigid bodies (a trolley, a girder, a boom) in the CSVs: of a
transient run, each body's centre-of-mass displacement and small rotation recovered from
the generalised coordinates (u = T q), also plotted; of an operation run, each body's
centre-of-mass position and rotation vector as its joints move it."""

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
    from ..analysis.transient.output import write_csv
    if not model.bodies:
        return write_csv(path, result)
    u, r = body_histories(dofs, result.q)
    extra = np.concatenate([u, r], axis=2).reshape(len(result.q), -1)  # body-major
    return write_csv(path, result, (body_columns(model), extra))


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


def joint_positions(mech, result, i):
    """The joint coordinates (torque-, force-, motor-driven and free joints) of an
    operation run at its sample i: drive name -> (position, speed)."""
    names = list(result.drive_names)
    return {d.name: (result.drive_position[i, names.index(d.name)],
                     result.drive_speed[i, names.index(d.name)])
            for d in mech.spec.drives if d.coordinate}


def operation_body_histories(model, result):
    """(centre-of-mass positions (nt, nb, 3) m in the global frame, rotation vectors
    (nt, nb, 3) rad: axis times angle of each body's rotation from the reference) of
    an operation run at its sample times. Bodies move with their joints: as the drives
    prescribe them, or as the run computed the joint coordinates (`drive_position`),
    through the operation engine's `Mechanism.body_motions`."""
    from scipy.spatial.transform import Rotation

    from ..analysis.operation.mechanism import Mechanism
    from ..analysis.operation.scene import parse
    mech = Mechanism(model, parse(model))
    nb, nt = len(model.bodies), len(result.times)
    com0 = np.array([b.com for b in model.bodies], dtype=float).reshape(nb, 3)
    pos, rot = np.zeros((nt, nb, 3)), np.zeros((nt, nb, 3))
    for i, t in enumerate(result.times):
        motions = mech.poses(float(t), joint_positions(mech, result, i))[0]
        for b in range(nb):
            R, p = motions[b][0], motions[b][3]
            pos[i, b] = R @ com0[b] + p
            rot[i, b] = Rotation.from_matrix(R).as_rotvec()
    return pos, rot


def write_operation_csv(path, result, model):
    """The operation CSV (`analysis.operation.output.write_csv`) followed by six columns
    per body: body_BODY.x_m, .y_m, .z_m (its centre of mass) and body_BODY.rx_rad, .ry_rad,
    .rz_rad (its rotation vector); written atomically. Returns the path."""
    from ..analysis.operation.output import write_csv
    if not model.bodies:
        return write_csv(path, result)
    pos, rot = operation_body_histories(model, result)
    cols = []
    for b in model.bodies:
        cols += [f"body_{b.name}.{a}_m" for a in "xyz"] + \
            [f"body_{b.name}.r{a}_rad" for a in "xyz"]
    extra = np.concatenate([pos, rot], axis=2).reshape(len(result.times), -1)
    return write_csv(path, result, (cols, extra))
