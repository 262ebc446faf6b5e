"""ParaView files written with meshio: VTU (every mode as point data) and XDMF time
series (one step per mode, or per output time of a transient). Both are written to a
temporary name in the target folder and renamed, so a failed write loses nothing."""

import os
import shutil

import numpy as np

from ..errors import ModelError
from ..outpaths import atomic
from .mesh import KINDS, line_mesh, point_displacements


def _target(path):
    path = os.fspath(path)
    folder = os.path.dirname(os.path.realpath(path))
    if not os.path.isdir(folder):
        raise ModelError(f"folder {folder} does not exist; create it first", path)
    return path, folder


def _mesh_and_fields(model, dofs, result):
    mesh = line_mesh(model, dofs)
    disp = point_displacements(dofs, result.shapes)
    names = [f"mode_{k + 1}_{f:.6g}Hz" for k, f in enumerate(result.frequency_hz)]
    return mesh, disp, names


def _cell_data(mesh):
    elements = sorted(set(mesh.element))
    return {"kind": [mesh.kind], "element_id": [np.array(
        [elements.index(e) for e in mesh.element], dtype=int)]}


MEMBER_CELL_FIELDS = ("N", "Vy", "Vz", "T", "My", "Mz", "sigma_max", "sigma_min")


def member_cell_data(mesh, member_forces, state, prefix=""):
    """Cell arrays (one value per line cell, nan off the members) of the member forces of
    `state` (`MemberForces.cell_values`): the member cells of `line_mesh` are the member
    elements in the order of `dofs.members` (kind 'member')."""
    cells = np.flatnonzero(mesh.kind == KINDS.index("member"))
    values = member_forces.cell_values(state)
    out = {}
    for j, name in enumerate(MEMBER_CELL_FIELDS):
        col = np.full(len(mesh.lines), np.nan)
        col[cells] = values[:, j]
        out[prefix + name] = [col]
    return out


def write_vtu(path, model, dofs, result, member_forces=None):
    """A line mesh of the crane with one displacement array per mode (mass-normalised);
    with `member_forces` (of the modes) cell arrays mode_K_N .. mode_K_sigma_min: per
    member element the end value of larger magnitude (the stresses: the larger maximum
    and the smaller minimum of its two ends)."""
    import meshio
    path, folder = _target(path)
    mesh, disp, names = _mesh_and_fields(model, dofs, result)
    point_data = {n: d for n, d in zip(names, disp)}
    point_data["magnitude_mode_1"] = np.linalg.norm(disp[0], axis=1) if len(disp) else \
        np.zeros(len(mesh.points))
    cell_data = _cell_data(mesh)
    if member_forces is not None:
        for k in range(len(member_forces.forces)):
            cell_data.update(member_cell_data(mesh, member_forces, k, f"mode_{k + 1}_"))
    m = meshio.Mesh(mesh.points, [("line", mesh.lines)], point_data=point_data,
                    cell_data=cell_data)
    with atomic(path, ".vtu") as tmp:
        meshio.write(tmp, m, file_format="vtu")
    return path


def write_xdmf_series(path, model, dofs, times, fields, member_forces=None):
    """XDMF time series: fields is a dict name -> (nt, np, 3 or 1) arrays over `times`;
    `member_forces` (a `MemberForces` with one state per time) adds the member cell
    arrays N .. sigma_min of `member_cell_data` at every step.

    meshio's TimeSeriesWriter puts its heavy data in BASE.h5 in the current directory;
    it writes in a temporary folder, the data file is renamed BASE.xdmf.h5 (so it never
    overwrites an archive BASE.h5) and both are moved next to `path` at the end.
    """
    import meshio
    path, folder = _target(path)
    mesh = line_mesh(model, dofs)
    base = os.path.splitext(os.path.basename(path))[0]
    heavy = os.path.join(os.path.dirname(path), f"{base}.xdmf.h5")
    cwd = os.getcwd()
    # the series is written in a temporary folder beside `path` (.NAME.PID.tmp.d), then
    # its two files are renamed: the data file first, so the .xdmf never names a
    # missing one
    with atomic(path) as tmp_xdmf, atomic(heavy) as tmp_h5:
        work = tmp_xdmf + ".d"
        os.mkdir(work)
        try:
            os.chdir(work)
            with meshio.xdmf.TimeSeriesWriter(f"{base}.xdmf") as w:
                w.write_points_cells(mesh.points, [("line", mesh.lines)])
                for k, t in enumerate(times):
                    cells = {} if member_forces is None else \
                        member_cell_data(mesh, member_forces, k)
                    w.write_data(float(t), point_data={n: v[k] for n, v in fields.items()},
                                 cell_data=cells)
            os.chdir(cwd)
            with open(os.path.join(work, f"{base}.xdmf")) as fh:
                text = fh.read().replace(f">{base}.h5:", f">{base}.xdmf.h5:")
            os.replace(os.path.join(work, f"{base}.h5"), tmp_h5)
            with open(tmp_xdmf, "w") as fh:
                fh.write(text)
        finally:
            os.chdir(cwd)
            shutil.rmtree(work, ignore_errors=True)
    return path


def write_xdmf_modes(path, model, dofs, result, member_forces=None):
    """Modes as an XDMF series: step k (time = k) is mode k, field 'displacement'; with
    `member_forces` (of the modes) the member cell arrays N .. sigma_min of each mode."""
    disp = point_displacements(dofs, result.shapes)
    return write_xdmf_series(path, model, dofs, np.arange(1, len(disp) + 1),
                             {"displacement": disp}, member_forces=member_forces)


__all__ = ["write_vtu", "write_xdmf_series", "write_xdmf_modes", "KINDS"]
