"""What images cost: `cranefe modes` of the tower crane with and without --images, and
one mode's animation the way cranefe 0.1 made it (every frame rebuilt) against today's
(one scene, points moved in place), side by side in one run."""

import os
import subprocess
import sys
import tempfile
import time

import numpy as np

from ._common import pyplot, save, write_csv

DESCRIPTION = ("time of rendering the tower crane's mode images vs. the modes alone, and "
               "of an animation: rebuilt per frame (0.1) vs. moved in place (now)")
MODEL = os.path.join(os.path.dirname(__file__), "..", "..", "models",
                     "hammerhead_tower_crane.yaml")
FRAMES = 24                    # one period, as `--animate` draws it
SIZE = (1024, 768)             # the default --image-size


def _wall(args, repeat):
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "cranefe", *args], check=True,
                       capture_output=True)
        best = min(best, time.perf_counter() - t0)
    return best


def animation_before(path, model, dofs, result, k, size=SIZE, frames=FRAMES):
    """One mode's GIF as cranefe 0.1 made it (its render.py, kept here as the reference
    of the speed-up): a new plotter per mode, every frame's actors cleared and rebuilt,
    pyvista's GIF writer (imageio, a palette per frame)."""
    import pyvista as pv

    from ..outputs.mesh import KINDS, line_mesh, point_displacements
    from ..outputs.render import STYLE, _polydata
    mesh = line_mesh(model, dofs)
    disp = point_displacements(dofs, result.shapes)[k]
    peak = np.abs(disp).max()
    scale = 0.12 * model.length_scale / peak if peak > 0 else 1.0
    clim = (0.0, max(float(np.linalg.norm(disp, axis=1).max() * scale), 1e-12))
    title = f"{result.model_name}\nmode {k + 1}"

    def scene(p, d):
        deformed = mesh.points + scale * d
        mag = np.linalg.norm(d, axis=1) * scale
        for kind in np.unique(mesh.kind):
            name = KINDS[kind]
            colour, width = STYLE[name]
            lines = mesh.lines[mesh.kind == kind]
            p.add_mesh(_polydata(mesh.points, lines), color=colour, line_width=width,
                       opacity=0.6)
            poly = _polydata(deformed, lines)
            poly.point_data["displacement"] = mag
            p.add_mesh(poly, scalars="displacement", cmap="viridis", clim=clim,
                       line_width=width, render_lines_as_tubes=name != "rope",
                       show_scalar_bar=bool(kind == mesh.kind.min()),
                       scalar_bar_args={"title": "|u| scaled [m]", "vertical": True,
                                        "position_x": 0.86, "position_y": 0.1,
                                        "height": 0.6, "color": "black"})
        p.add_mesh(pv.PolyData(deformed), color="black", point_size=6,
                   render_points_as_spheres=True)

    p = pv.Plotter(off_screen=True, window_size=size)
    p.set_background("white")
    scene(p, disp)
    p.add_text(title, font_size=12, color="black")
    p.view_isometric()
    p.reset_camera()
    p.screenshot(return_img=True)
    p.clear_actors()
    p.open_gif(path, fps=frames // 2)
    cam = p.camera_position
    for phase in np.linspace(0, 2 * np.pi, frames, endpoint=False):
        p.clear_actors()
        scene(p, disp * np.sin(phase))
        p.add_text(title, font_size=12, color="black")
        p.camera_position = cam
        p.write_frame()
    p.mwriter.close()
    p.mwriter = None
    p.close()


def animation_now(path, model, dofs, result, k, size=SIZE, frames=FRAMES):
    """The same mode's GIF as `cranefe modes --images DIR --animate` makes it now, the
    scene (ground, triad, camera fitted to every mode) included."""
    from ..outputs.render import ModeScene, write_animation
    scene = ModeScene(model, dofs, result, size=size)
    try:
        shots = []
        for s in np.sin(np.linspace(0, 2 * np.pi, frames, endpoint=False)):
            scene.show(k, s)
            shots.append(scene.image())
        write_animation(path, shots, fps=frames // 2)
    finally:
        scene.close()


def run(outdir, quick=False):
    """The hammerhead crane has 7 rigid-rope modes; with 4 elements per fall of its hoist
    rope (a scene) it has plenty, and eight are rendered. The animation is of its
    second elastic mode, at the default image size, both ways in this one process
    (alternating, best of `repeat`; the back end is probed before either)."""
    plt = pyplot()
    repeat = 1 if quick else 2
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "tower_rope_mass.yaml")
        with open(scene, "w") as fh:
            fh.write(f"cranefe: 1\nscene: tower crane, rope mass\nmodel: "
                     f"{os.path.abspath(MODEL)}\neffects: {{rope_mass: 4}}\n")
        rows.append(("modes only, 8 modes (whole process)",
                     _wall(["modes", scene, "--count", "8"], repeat), 0))
        for n in ((1,) if quick else (1, 4, 8)):
            t = _wall(["modes", scene, "--count", str(n), "--images",
                       os.path.join(tmp, f"i{n}")], repeat)
            rows.append((f"modes + {n} images (whole process)", t, n))
        # in one process: the first image pays the back-end probe and the pyvista import
        from ..system import assemble
        from ..model import load
        from ..analysis.modal import modes
        from ..outputs.render import render_modes
        m = load(scene)
        s = assemble(m)
        r = modes(m, count=8, system=s)
        t0 = time.perf_counter()
        render_modes(os.path.join(tmp, "a"), m, s.dofs, r)
        t_all = time.perf_counter() - t0
        rows.append((f"{len(r.omega)} images in one process, first call", t_all, len(r.omega)))
        t0 = time.perf_counter()
        render_modes(os.path.join(tmp, "b"), m, s.dofs, r)
        t_warm = time.perf_counter() - t0
        rows.append((f"{len(r.omega)} images in one process, warm", t_warm, len(r.omega)))
        k = int(np.flatnonzero(~r.rigid)[1])
        times = {"before": [], "now": []}
        size, frames = ((480, 360), 12) if quick else (SIZE, FRAMES)
        for attempt in range(repeat):
            for name, fn in (("before", animation_before), ("now", animation_now)):
                t0 = time.perf_counter()
                fn(os.path.join(tmp, f"{name}{attempt}.gif"), m, s.dofs, r, k, size, frames)
                times[name].append(time.perf_counter() - t0)
        before, now = min(times["before"]), min(times["now"])
        label = f"mode {k + 1} GIF, {frames} frames {size[0]}x{size[1]}"
        rows.append((f"{label}: 0.1, rebuilt per frame", before, frames))
        rows.append((f"{label}: now, moved in place", now, frames))
        speedup = before / now
    csv_path = write_csv(outdir, "rendering.csv",
                         [{"case": c, "wall_time_s": t, "images": n} for c, t, n in rows])
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.barh([r[0] for r in rows][::-1], [r[1] for r in rows][::-1], color="#4c72b0")
    ax.set_xlabel("wall time [s] (best of %d)" % repeat)
    ax.set_title(f"Hammerhead tower crane: cost of images; animation {speedup:.1f}x "
                 "faster than 0.1")
    return [csv_path, save(fig, outdir, "rendering.png")]
