"""Off-screen mode-shape images (PNG) and animations (GIF, MP4) with pyvista.

One `ModeScene` per model: the ground and what stands on it (supports, the floor,
drums), the undeformed crane, the deformed crane and an axes triad are built once; a
mode or a phase of its animation only moves the deformed points in place, and one
camera, fitted to every mode's extreme shapes, frames all of them.

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

from ..errors import AnalysisError, ModelError
from .mesh import KINDS, line_mesh, point_displacements

_PROBE = ("import pyvista as pv\n"
          "p = pv.Plotter(off_screen=True, window_size=(16, 16))\n"
          "p.add_mesh(pv.Line((0, 0, 0), (1, 1, 1)))\n"
          "img = p.screenshot(return_img=True)\n"
          "p.close()\n"
          "print('ok', img.shape)\n")
_WINDOWS = ("vtkEGLRenderWindow", "vtkOSOpenGLRenderWindow")
_chosen = None

VIEWS = ("iso", "xy", "xz", "yz")
# view: (direction from the focal point to the camera, view up)
_DIRECTIONS = {"iso": ((1.0, -1.0, 0.8), (0.0, 0.0, 1.0)), "xy": ((0.0, 0.0, 1.0),
               (0.0, 1.0, 0.0)), "xz": ((0.0, -1.0, 0.0), (0.0, 0.0, 1.0)),
               "yz": ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0))}
BACKGROUND = (255, 255, 255)
GROUND_COLOUR = "#5a4a3a"      # supports, posts, drums: what stands on the ground
FLOOR_COLOUR = "#e4dfd6"
SCALE = 0.12                   # largest displacement drawn: 12 % of the model size
BAR_TITLE = "relative displacement"
COLOURS = ("displacement", "stress")
STRESS_MAP = "viridis"         # |sigma| of the members: 0 at the low end, the mode's peak
STRESS_TITLE = "stress MPa"    # at the top of the colour bar
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
    return pv.PolyData(np.array(points, dtype=float), lines=cells)


def _up(model):
    g = np.asarray(model.gravity, dtype=float)
    n = np.linalg.norm(g)
    return -g / n if n > 0 else np.array([0.0, 0.0, 1.0])


def _ground_nodes(model):
    """Nodes fixed to the ground: the model's ground list and structural supports."""
    nodes = [int(i) for i in model.ground]
    for s in getattr(model, "supports", ()) or ():
        i = getattr(s, "node", None)
        if i is not None and int(i) not in nodes:
            nodes.append(int(i))
    return nodes


def _drum_axis(model, drum):
    """A drum's axis: normal to a plane model's plane, else horizontal and normal to the
    first rope span leaving the drum's node."""
    if model.planar:
        return np.array([0.0, 1.0, 0.0])
    up = _up(model)
    for r in model.ropes:
        for a, b in zip(r.span_a, r.span_b):
            if drum.node in (a, b):
                e = model.coords[b] - model.coords[a]
                axis = np.cross(e, up)
                if np.linalg.norm(axis) > 1e-9 * np.linalg.norm(e):
                    return axis / np.linalg.norm(axis)
    return np.array([0.0, 1.0, 0.0])


def add_ground(p, model, points):
    """The floor, a post from every ground node above it down to the floor with a base
    block, and each drum as a short cylinder at its node, into plotter p.

    Returns (floor height, the floor slab's 8 corners, [(drum actor, node)])."""
    import pyvista as pv
    L = model.length_scale
    up = _up(model)
    floor = (points @ up).min()
    for i in _ground_nodes(model):
        x = model.coords[i]
        foot = x - (x @ up - floor) * up
        if x @ up - floor > 0.02 * L:
            p.add_mesh(pv.Line(x, foot), color=GROUND_COLOUR, line_width=7)
        p.add_mesh(pv.Cube(center=x, x_length=0.025 * L, y_length=0.025 * L,
                           z_length=0.025 * L), color=GROUND_COLOUR)
    # the floor: a thin slab under the whole crane
    lo, hi = points.min(axis=0), points.max(axis=0)
    centre = 0.5 * (lo + hi)
    centre = centre - (centre @ up - floor) * up - 0.004 * L * up
    span = np.maximum(hi - lo, 0.3 * L) * 1.15
    sizes = np.where(np.abs(up) > 0.9, 0.008 * L, span)
    p.add_mesh(pv.Cube(center=centre, x_length=sizes[0], y_length=sizes[1],
                       z_length=sizes[2]), color=FLOOR_COLOUR)
    signs = np.array([[a, b, c] for a in (-1, 1) for b in (-1, 1) for c in (-1, 1)])
    drums = []
    for d in model.drums:
        r = max(d.radius, 0.02 * L)
        cyl = pv.Cylinder(center=model.coords[d.node], direction=_drum_axis(model, d),
                          radius=r, height=r, resolution=32)
        drums.append((p.add_mesh(cyl, color=GROUND_COLOUR), d.node))
    return floor, centre + 0.5 * signs * sizes, drums


def fit_camera(p, view, cloud, up, floor, length):
    """Set one parallel-projection camera of `view` on plotter p that sees every point
    of `cloud` (k, 3) and its foot on the floor, with room for the title (above), the
    colour bar (right) and the triad (left); returns p.camera_position."""
    direction, view_up = (np.array(v, dtype=float) for v in _DIRECTIONS[view])
    direction /= np.linalg.norm(direction)
    cloud = np.vstack([cloud, cloud - ((cloud @ up) - floor)[:, None] * up])
    right = np.cross(view_up, direction)
    right /= np.linalg.norm(right)
    true_up = np.cross(direction, right)
    u, v = cloud @ right, cloud @ true_up
    w, h = p.window_size
    # the crane in the middle 70 % of the width and 80 % of the height
    half_h = max((v.max() - v.min()) / 2 / 0.80, (u.max() - u.min()) / 2 / 0.70 / (w / h),
                 1e-3 * length)
    mid = right * (u.max() + u.min()) / 2 + true_up * ((v.max() + v.min()) / 2
                                                        + 0.05 * half_h)
    depth = cloud @ direction
    mid = mid + direction * (depth.max() + depth.min()) / 2
    dist = 4.0 * max(np.ptp(cloud, axis=0).max(), length)
    cam = p.camera
    p.enable_parallel_projection()
    cam.focal_point = tuple(mid)
    cam.position = tuple(mid + dist * direction)
    cam.up = tuple(true_up)
    cam.parallel_scale = half_h
    p.renderer.ResetCameraClippingRange()
    return p.camera_position


def pixels(p, points):
    """(row, column) in plotter p's image of world points (k, 3)."""
    from vtkmodules.vtkRenderingCore import vtkCoordinate
    coord = vtkCoordinate()
    coord.SetCoordinateSystemToWorld()
    h = p.window_size[1]
    out = []
    for x in np.atleast_2d(points):
        coord.SetValue(*map(float, x))
        c, r = coord.GetComputedDoubleDisplayValue(p.renderer)
        out.append((int(round(h - 1 - r)), int(round(c))))
    return np.array(out)


def check_view(view):
    if view is not None and view not in VIEWS:
        raise ModelError(f"--view {view!r}: give one of {', '.join(VIEWS)}")


class ModeScene:
    """The crane of one model in one off-screen plotter, for all its modes.

    `show(k, phase)` draws mode k at phase (the displacement times `phase`): it only
    moves the deformed points and the drums and sets the title; nothing is rebuilt.
    The camera is fitted once to the undeformed crane and every mode at +-1.

    With `member_forces` (the modes' `MemberForces`) the members are coloured by the
    extreme-fibre stress of the mode, max(|sigma_max|, |sigma_min|) at each element end
    and linear along the element, from 0 to the mode's largest value (MPa on the colour
    bar; the other elements are drawn in their own colours)."""

    def __init__(self, model, dofs, result, size=(1024, 768), view=None,
                 member_forces=None):
        backend()
        import pyvista as pv
        check_view(view)
        self.view = view or ("xz" if model.planar else "iso")
        self.model, self.result = model, result
        self.mesh = mesh = line_mesh(model, dofs)
        self.stress = None
        if member_forces is not None:
            # (m, ne, 2): the larger |sigma| of the two fibres at each element end
            self.stress = np.fmax(np.abs(member_forces.stress[..., 0]),
                                  np.abs(member_forces.stress[..., 1]))
            self.stress_scale = member_forces.scale
        disp = point_displacements(dofs, result.shapes)            # (m, np, 3)
        L = model.length_scale
        peak = np.linalg.norm(disp, axis=2).max(axis=1)             # (m,)
        self.scale = np.where(peak > 0, SCALE * L / np.where(peak > 0, peak, 1), 0.0)
        self.disp = disp * self.scale[:, None, None]                # drawn displacements
        self.relative = np.linalg.norm(disp, axis=2) / np.where(peak > 0, peak, 1)[:, None]
        self.p = p = pv.Plotter(off_screen=True, window_size=size)
        p.set_background([c / 255 for c in BACKGROUND])
        self._ground(pv)
        self.deformed = []
        first = True
        for kind in np.unique(mesh.kind):
            name = KINDS[kind]
            colour, width = STYLE[name]
            lines = mesh.lines[mesh.kind == kind]
            p.add_mesh(_polydata(mesh.points, lines), color=colour, line_width=width,
                       opacity=0.5)
            if self.stress is not None:
                self._add_stressed(pv, name, lines, colour, width)
                continue
            d = _polydata(mesh.points, lines)
            d.point_data["relative displacement"] = np.zeros(len(mesh.points))
            p.add_mesh(d, scalars="relative displacement", cmap="viridis", clim=(0.0, 1.0),
                       line_width=width, render_lines_as_tubes=name != "rope",
                       show_scalar_bar=first,
                       scalar_bar_args={"title": BAR_TITLE, "vertical": True,
                                        "position_x": 0.84, "position_y": 0.12,
                                        "height": 0.6, "color": "black",
                                        "title_font_size": 14, "n_labels": 3,
                                        "fmt": "%.1f"})
            first = False
            self.deformed.append(d)
        self.nodes = pv.PolyData(np.array(mesh.points, dtype=float))
        p.add_mesh(self.nodes, color="black", point_size=6, render_points_as_spheres=True)
        self.title = p.add_text("", font_size=12, color="black", position="upper_left")
        p.add_axes(line_width=3, color="black", viewport=(0.0, 0.0, 0.18, 0.22))
        self.camera = self._fit_camera()
        p.show(auto_close=False)            # the first render: later ones only redraw
        p.camera_position = self.camera

    def _add_stressed(self, pv, name, lines, colour, width):
        """With stress colours: the members as separate two-point lines (each element
        end its own value), the other kinds deformed in their own colours."""
        if name != "member":
            d = _polydata(self.mesh.points, lines)
            self.p.add_mesh(d, color=colour, line_width=width,
                            render_lines_as_tubes=name != "rope")
            self.deformed.append(d)
            return
        if len(lines) != self.stress.shape[1]:
            raise AnalysisError(f"{len(lines)} member lines for {self.stress.shape[1]} "
                                "member elements")
        self.member_points = lines.ravel()               # (2 ne,): end a, end b, ...
        d = _polydata(np.asarray(self.mesh.points, dtype=float)[self.member_points],
                      np.arange(2 * len(lines)).reshape(-1, 2))
        d.point_data["stress"] = np.zeros(2 * len(lines))
        self.stress_actor = self.p.add_mesh(
            d, scalars="stress", cmap=STRESS_MAP, clim=(0.0, 1.0), line_width=width,
            render_lines_as_tubes=True, lighting=False, nan_color="#b0b0b0",
            scalar_bar_args={"title": STRESS_TITLE, "vertical": True,
                             "position_x": 0.84, "position_y": 0.12, "height": 0.6,
                             "color": "black", "title_font_size": 14, "n_labels": 3,
                             "fmt": "%.3g"})
        self.stressed = d

    def stress_note(self):
        """The title's line on the stress colours: how the mode is scaled."""
        sc = self.stress_scale
        at = f"largest node translation {sc['amplitude_m']:g} m" if "amplitude_m" in sc \
            else "mass-normalised mode"
        return f"members: extreme-fibre stress, {at}"

    def _ground(self, pv):
        self.floor, self.floor_corners, self.drums = add_ground(
            self.p, self.model, np.asarray(self.mesh.points, dtype=float))

    def _fit_camera(self):
        """One camera for every mode: it sees the undeformed crane, the floor and every
        mode's extreme shapes (+-1)."""
        pts = np.asarray(self.mesh.points, dtype=float)
        cloud = np.vstack([pts] + [pts + s * d for d in self.disp for s in (1, -1)])
        return fit_camera(self.p, self.view, cloud, _up(self.model), self.floor,
                          self.model.length_scale)

    def show(self, k, phase=1.0):
        """Draw mode k with its displacement times `phase`."""
        pts = np.asarray(self.mesh.points, dtype=float) + phase * self.disp[k]
        rel = np.abs(phase) * self.relative[k]
        for d in self.deformed:
            d.points[:] = pts
            if "relative displacement" in d.point_data:
                d.point_data["relative displacement"][:] = rel
            d.Modified()
        if self.stress is not None:
            sigma = self.stress[k] / 1e6                     # MPa, (ne, 2)
            top = np.nanmax(sigma) if np.isfinite(sigma).any() else 0.0
            self.stressed.points[:] = pts[self.member_points]
            self.stressed.point_data["stress"][:] = np.abs(phase) * sigma.ravel()
            self.stressed.Modified()
            self.stress_actor.mapper.scalar_range = (0.0, top if top > 0 else 1.0)
        self.nodes.points[:] = pts
        self.nodes.Modified()
        for actor, node in self.drums:
            actor.position = tuple(phase * self.disp[k][node])
        self.title.set_text("upper_left", self.title_text(k))
        self.p.camera_position = self.camera
        self.p.render()

    def title_text(self, k):
        r = self.result
        f = r.omega[k] / (2 * np.pi)
        kind = "rigid (quasi-cyclic)" if r.rigid[k] else f"{f:.4g} Hz (T = {1 / f:.4g} s)"
        text = f"{r.model_name}\nmode {k + 1}: {kind}    view {self.view}"
        return text + "\n" + self.stress_note() if self.stress is not None else text

    def screenshot(self, path):
        from ..outpaths import atomic
        with atomic(path, os.path.splitext(path)[1]) as tmp:
            self.p.screenshot(tmp)
        return path

    def image(self):
        """The current frame as an (h, w, 3) uint8 array."""
        return self.p.screenshot(return_img=True)

    def pixels(self, points):
        """(row, column) in the image of world points (k, 3), for tests and labels."""
        return pixels(self.p, points)

    def close(self):
        self.p.close()


def render_modes(folder, model, dofs, result, size=(1024, 768), animate=None, frames=24,
                 view=None, member_forces=None):
    """One PNG per mode into `folder` and with animate="gif" (or True) / "mp4" one
    animation per mode; returns the paths written. `member_forces` (of the modes):
    colour the members by their stress (`ModeScene`)."""
    from ..outpaths import make_folder
    if animate is True:
        animate = "gif"
    if animate not in (None, False, "gif", "mp4"):
        raise ModelError(f"animation format {animate!r}: give gif or mp4")
    if animate == "mp4":
        _need_ffmpeg()
    make_folder(folder, "--images")
    scene = ModeScene(model, dofs, result, size=size, view=view,
                      member_forces=member_forces)
    paths = []
    try:
        for k in range(len(result.omega)):
            scene.show(k)
            paths.append(scene.screenshot(os.path.join(folder, f"mode_{k + 1:02d}.png")))
            if animate:
                path = os.path.join(folder, f"mode_{k + 1:02d}.{animate}")
                phases = np.sin(np.linspace(0, 2 * np.pi, frames, endpoint=False))
                paths.append(write_animation(path, (_frame(scene, k, s) for s in phases),
                                             fps=max(frames // 2, 1)))
    finally:
        scene.close()
    return paths


def _frame(scene, k, phase):
    scene.show(k, phase)
    return scene.image()


# ---------------------------------------------------------------- animation files

def _need_ffmpeg():
    try:
        import imageio_ffmpeg  # noqa: F401
    except ImportError:
        raise ModelError("MP4 needs the optional package imageio-ffmpeg (pip install "
                         "'cranefe[video]' or pip install imageio-ffmpeg); or write a "
                         ".gif instead") from None


def write_animation(path, frames, fps=12):
    """Write frames ((h, w, 3) uint8 arrays, an iterable) as a GIF or, for a path ending
    in .mp4, an H.264 MP4 (needs imageio-ffmpeg); atomically. Returns the path.

    GIF: one 256-colour palette, taken from a few frames, serves every frame (the
    scene's colours do not change between frames), so each frame is mapped, not
    re-quantised."""
    from ..outpaths import atomic
    ext = os.path.splitext(path)[1].lower()
    if ext not in (".gif", ".mp4"):
        raise ModelError(f"animation {path!r}: give a file name ending in .gif or .mp4")
    if ext == ".mp4":
        _need_ffmpeg()
        import imageio.v2 as imageio
        with atomic(path, ext) as tmp:
            writer = imageio.get_writer(tmp, format="FFMPEG", mode="I", fps=fps,
                                        codec="libx264", quality=7, macro_block_size=2,
                                        ffmpeg_log_level="error")
            try:
                for f in frames:
                    writer.append_data(np.asarray(f)[:, :, :3])
            finally:
                writer.close()
        return path
    from PIL import Image
    frames = [np.asarray(f)[:, :, :3] for f in frames]
    if not frames:
        raise AnalysisError(f"animation {path!r}: no frames")
    sample = np.concatenate(frames[::max(1, len(frames) // 4)], axis=0)[::2, ::2]
    palette = Image.fromarray(np.ascontiguousarray(sample)).quantize(
        colors=256, method=Image.Quantize.MEDIANCUT)
    images = [Image.fromarray(f).quantize(palette=palette, dither=Image.Dither.NONE)
              for f in frames]
    with atomic(path, ext) as tmp:
        images[0].save(tmp, format="GIF", save_all=True, append_images=images[1:],
                       duration=int(round(1000 / fps)), loop=0, optimize=False)
    return path
