"""What images cost: `cranefe modes` of the tower crane with and without --images."""

import os
import subprocess
import sys
import tempfile
import time

from ._common import pyplot, save, write_csv

DESCRIPTION = "time of rendering the tower crane's mode images vs. the modes alone"
MODEL = os.path.join(os.path.dirname(__file__), "..", "..", "models",
                     "hammerhead_tower_crane.yaml")


def _wall(args, repeat):
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "cranefe", *args], check=True,
                       capture_output=True)
        best = min(best, time.perf_counter() - t0)
    return best


def run(outdir, quick=False):
    """The hammerhead crane has 7 rigid-rope modes; with 4 elements per fall of its hoist
    rope (a scene) it has plenty, and eight are rendered."""
    plt = pyplot()
    repeat = 1 if quick else 3
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
    csv_path = write_csv(outdir, "rendering.csv",
                         [{"case": c, "wall_time_s": t, "images": n} for c, t, n in rows])
    fig, ax = plt.subplots(figsize=(8, 3.5))
    ax.barh([r[0] for r in rows][::-1], [r[1] for r in rows][::-1], color="#4c72b0")
    ax.set_xlabel("wall time [s] (best of %d)" % repeat)
    ax.set_title("Hammerhead tower crane: cost of mode images (off-screen pyvista)")
    return [csv_path, save(fig, outdir, "rendering.png")]
