"""Animation of an operation run (`cranefe simulate SCENE --animate OUT.gif|OUT.mp4`):
the crane moving off-screen, with the trail of every point mass.

Positions: the point masses' from the run's samples (`OperationResult.mass_position`);
the bodies and the nodes they carry moved by their joints, as the run's drives prescribe
them (`Mechanism.kinematics` / `body_motions` of the operation engine, evaluated at the
sample times). The scene is built once and its points moved in place, frame by frame,
under one camera fitted to the whole run (`render.fit_camera`)."""

import numpy as np

from .histories import joint_positions
from .mesh import KINDS, line_mesh
from .render import (BACKGROUND, STYLE, _polydata, _up, add_ground, backend, check_view,
                     fit_camera, write_animation)

MAX_FRAMES = 150          # frames of one animation at most (samples are picked evenly)
TRAIL_COLOUR = "#e07b00"
FPS = (5, 25)             # frames per second: the run in real time, within these bounds


def operation_positions(model, result, frames=MAX_FRAMES):
    """(sample indices (nf,), positions of the line mesh's points (nf, np, 3)).

    Mesh points are the model's nodes, then the bodies' centres of mass
    (`mesh.line_mesh`); nodes on bodies and on the ground follow the joints, point
    masses come from the samples."""
    from ..analysis.operation.mechanism import Mechanism
    from ..analysis.operation.scene import parse
    mesh = line_mesh(model)
    nt = len(result.times)
    idx = np.unique(np.round(np.linspace(0, nt - 1, min(nt, frames))).astype(int))
    mech = Mechanism(model, parse(model))
    nn = len(model.node_names)
    masses = [(model.node_index[n], k) for k, n in enumerate(result.mass_names)]
    com0 = np.array([b.com for b in model.bodies], dtype=float).reshape(-1, 3)
    out = np.repeat(np.asarray(mesh.points, dtype=float)[None], len(idx), axis=0)
    for f, i in enumerate(idx):
        t = float(result.times[i])
        motions, X = mech.poses(t, joint_positions(mech, result, i))
        out[f, mech.kin] = X[mech.kin]
        for node, k in masses:
            out[f, node] = result.mass_position[i, k]
        for b in range(len(model.bodies)):
            R, p = motions[b][0], motions[b][3]
            out[f, nn + b] = R @ com0[b] + p
    return idx, out


class OperationScene:
    """The crane of an operation run in one off-screen plotter: ground, the crane at
    its start (faint), the moving crane, the loads' trails, an axes triad, a title
    with the time. `show(f)` moves everything to frame f in place."""

    def __init__(self, model, result, size=(1024, 768), view=None, frames=MAX_FRAMES):
        backend()
        import pyvista as pv
        check_view(view)
        self.view = view or ("xz" if model.planar else "iso")
        self.model, self.result = model, result
        self.mesh = mesh = line_mesh(model)
        self.index, self.P = operation_positions(model, result, frames)
        self.p = p = pv.Plotter(off_screen=True, window_size=size)
        p.set_background([c / 255 for c in BACKGROUND])
        cloud = self.P.reshape(-1, 3)
        self.floor, self.floor_corners, self.drums = add_ground(p, model, cloud)
        self.moving = []
        for kind in np.unique(mesh.kind):
            name = KINDS[kind]
            colour, width = STYLE[name]
            lines = mesh.lines[mesh.kind == kind]
            p.add_mesh(_polydata(self.P[0], lines), color=colour, line_width=width,
                       opacity=0.25)
            d = _polydata(self.P[0], lines)
            p.add_mesh(d, color="#1f3b73" if name != "rope" else "#333333",
                       line_width=width, render_lines_as_tubes=name != "rope")
            self.moving.append(d)
        self.nodes = pv.PolyData(self.P[0].copy())
        p.add_mesh(self.nodes, color="black", point_size=6, render_points_as_spheres=True)
        nf = len(self.index)
        self.trail_nodes = [model.node_index[n] for n in result.mass_names
                            if model.node_index[n] not in self._carried()]
        self.trails = []
        for node in self.trail_nodes:
            trail = _polydata(self.P[:, node], np.c_[np.arange(nf - 1), np.arange(1, nf)])
            p.add_mesh(trail, color=TRAIL_COLOUR, line_width=3)
            self.trails.append((trail, node))
        self.title = p.add_text("", font_size=12, color="black", position="upper_left")
        p.add_axes(line_width=3, color="black", viewport=(0.0, 0.0, 0.18, 0.22))
        self.camera = fit_camera(p, self.view, cloud, _up(model), self.floor,
                                 model.length_scale)
        p.show(auto_close=False)
        p.camera_position = self.camera

    def _carried(self):
        """Nodes carried by bodies or the ground (their paths are the joints')."""
        nodes = set(int(i) for i in self.model.ground)
        for b in self.model.bodies:
            nodes.update(int(i) for i in b.nodes)
        return nodes

    def show(self, f):
        """Draw frame f (sample `index[f]`)."""
        pts = self.P[f]
        for d in self.moving:
            d.points[:] = pts
            d.Modified()
        self.nodes.points[:] = pts
        self.nodes.Modified()
        for trail, node in self.trails:
            path = self.P[:, node].copy()
            path[f + 1:] = path[f]                # the future collapsed onto now
            trail.points[:] = path
            trail.Modified()
        for actor, node in self.drums:
            actor.position = tuple(pts[node] - self.model.coords[node])
        t = self.result.times[self.index[f]]
        self.title.set_text("upper_left", f"{self.result.scene or self.result.model_name}"
                            f"\nt = {t:.2f} s    view {self.view}")
        self.p.camera_position = self.camera
        self.p.render()

    def image(self):
        return self.p.screenshot(return_img=True)

    def close(self):
        self.p.close()


def animate_operation(path, model, result, size=(1024, 768), view=None,
                      frames=MAX_FRAMES):
    """Write the run as an animation (GIF, or MP4 for a path ending in .mp4); returns
    the path. Frames are samples picked evenly over the run, played in real time
    within FPS."""
    import os
    if os.path.splitext(path)[1].lower() == ".mp4":
        from .render import _need_ffmpeg
        _need_ffmpeg()
    scene = OperationScene(model, result, size=size, view=view, frames=frames)
    try:
        shots = []
        for f in range(len(scene.index)):
            scene.show(f)
            shots.append(scene.image())
        span = float(result.times[scene.index[-1]] - result.times[scene.index[0]])
        fps = int(np.clip(round(len(shots) / span) if span > 0 else FPS[1], *FPS))
        return write_animation(path, shots, fps=fps)
    finally:
        scene.close()
