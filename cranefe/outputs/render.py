"""Off-screen mode-shape images (PNG) and animations (GIF) with pyvista.

VTK picks its OpenGL back end at run time; with no display it needs Mesa's EGL (present
on a fresh machine here) or OSMesa (Debian libosmesa6 with
VTK_DEFAULT_OPENGL_WINDOW=vtkOSOpenGLRenderWindow). A missing back end crashes the
process instead of raising, so the back end is probed once in a subprocess and chosen
before pyvista is imported; if none works the error says what to install.
"""

import os
import subprocess
import sys

import numpy as np

from ..errors import AnalysisError
from .mesh import KINDS, line_mesh, point_displacements

_PROBE = ("import pyvista as pv\n"
          "p = pv.Plotter(off_screen=True, window_size=(16, 16))\n"
          "p.add_mesh(pv.Line((0, 0, 0), (1, 1, 1)))\n"
          "img = p.screenshot(return_img=True)\n"
          "p.close()\n"
          "print('ok', img.shape)\n")
_WINDOWS = ("vtkEGLRenderWindow", "vtkOSOpenGLRenderWindow")
_chosen = None

STYLE = {  # kind: (colour of the undeformed shape, line width)
    "rope": ("#9a9a9a", 2.0), "body": ("#6f6f6f", 6.0), "spring": ("#b0a080", 3.0),
    "member": ("#7f7f7f", 4.0), "drive": ("#8080b0", 5.0),
}


def backend():
    """Choose a working off-screen OpenGL window class (probed in a subprocess, once)."""
    global _chosen
    if _chosen is not None:
        return _chosen
    candidates = []
    if os.environ.get("VTK_DEFAULT_OPENGL_WINDOW"):
        candidates.append(os.environ["VTK_DEFAULT_OPENGL_WINDOW"])
    if os.environ.get("DISPLAY"):
        candidates.append(None)               # VTK's own choice (X window)
    candidates += [w for w in _WINDOWS if w not in candidates]
    errors = []
    for window in candidates:
        env = dict(os.environ)
        if window:
            env["VTK_DEFAULT_OPENGL_WINDOW"] = window
        try:
            out = subprocess.run([sys.executable, "-c", _PROBE], env=env, timeout=120,
                                 capture_output=True, text=True)
        except subprocess.TimeoutExpired:
            errors.append(f"{window}: timed out")
            continue
        if out.returncode == 0 and out.stdout.startswith("ok"):
            if window:
                os.environ["VTK_DEFAULT_OPENGL_WINDOW"] = window
            _chosen = window or "default"
            return _chosen
        errors.append(f"{window or 'default'}: exit {out.returncode}")
    raise AnalysisError(
        "no off-screen OpenGL back end works here (" + "; ".join(errors) + "). Install "
        "Mesa's EGL (Debian: libegl1 libegl-mesa0) or OSMesa (Debian: libosmesa6, then "
        "set VTK_DEFAULT_OPENGL_WINDOW=vtkOSOpenGLRenderWindow)")


def _polydata(points, lines):
    import pyvista as pv
    cells = np.hstack([np.full((len(lines), 1), 2), lines]).ravel()
    return pv.PolyData(points, lines=cells)


def _scale(model, disp):
    peak = np.abs(disp).max()
    return 0.12 * model.length_scale / peak if peak > 0 else 1.0


def _title(result, k):
    f = result.frequency_hz[k]
    kind = "rigid (quasi-cyclic)" if result.rigid[k] else f"{f:.4g} Hz"
    return f"{result.model_name}\nmode {k + 1}: {kind}"


def _scene(plotter, model, mesh, disp, scale, clim):
    import pyvista as pv
    deformed = mesh.points + scale * disp
    mag = np.linalg.norm(disp, axis=1) * scale
    for kind in np.unique(mesh.kind):
        name = KINDS[kind]
        colour, width = STYLE[name]
        lines = mesh.lines[mesh.kind == kind]
        plotter.add_mesh(_polydata(mesh.points, lines), color=colour, line_width=width,
                         opacity=0.6)
        d = _polydata(deformed, lines)
        d.point_data["displacement"] = mag
        plotter.add_mesh(d, scalars="displacement", cmap="viridis", clim=clim,
                         line_width=width, render_lines_as_tubes=name != "rope",
                         show_scalar_bar=bool(kind == mesh.kind.min()),
                         scalar_bar_args={"title": "|u| scaled [m]",
                                          "vertical": True, "position_x": 0.86,
                                          "position_y": 0.1, "height": 0.6,
                                          "color": "black"})
    pts = pv.PolyData(deformed)
    plotter.add_mesh(pts, color="black", point_size=6, render_points_as_spheres=True)


def _camera(plotter, model):
    if model.planar:
        plotter.view_xz()
    else:
        plotter.view_isometric()
    plotter.reset_camera()


def render_modes(folder, model, dofs, result, size=(1024, 768), animate=False, frames=24):
    """One PNG (and with animate=True one GIF) per mode into `folder`; returns paths."""
    backend()
    import pyvista as pv
    from ..outpaths import atomic, make_folder
    make_folder(folder, "--images")
    mesh = line_mesh(model, dofs)
    disp = point_displacements(dofs, result.shapes)
    paths = []
    for k in range(len(disp)):
        scale = _scale(model, disp[k])
        clim = (0.0, max(float(np.linalg.norm(disp[k], axis=1).max() * scale), 1e-12))
        p = pv.Plotter(off_screen=True, window_size=size)
        p.set_background("white")
        _scene(p, model, mesh, disp[k], scale, clim)
        p.add_text(_title(result, k), font_size=12, color="black")
        _camera(p, model)
        path = os.path.join(folder, f"mode_{k + 1:02d}.png")
        with atomic(path, ".png") as tmp:
            p.screenshot(tmp)
        paths.append(path)
        if animate:
            gif = os.path.join(folder, f"mode_{k + 1:02d}.gif")
            p.clear_actors()
            with atomic(gif, ".gif") as tmp:
                p.open_gif(tmp, fps=frames // 2)
                cam = p.camera_position
                for phase in np.linspace(0, 2 * np.pi, frames, endpoint=False):
                    p.clear_actors()
                    _scene(p, model, mesh, disp[k] * np.sin(phase), scale, clim)
                    p.add_text(_title(result, k), font_size=12, color="black")
                    p.camera_position = cam
                    p.write_frame()
                p.mwriter.close()
                p.mwriter = None
            paths.append(gif)
        p.close()
    return paths
