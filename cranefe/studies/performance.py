"""Large lattice cranes: cranefe's whole `modes` process against a bare floor script and
OpenSeesPy, measured in one run, with the frequencies compared."""

import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

from ._common import pyplot, save, write_csv

DESCRIPTION = "1e3..1e5 DOFs: cranefe vs the floor (scipy) vs OpenSeesPy, whole processes"
COUNT = 20


def _process(args, repeat):
    """Best wall time of a whole process, its JSON output and its peak memory (MB)."""
    best, out, peak = float("inf"), None, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        p = subprocess.run([sys.executable, "-m", "cranefe.studies._run", *args],
                           capture_output=True, text=True)
        wall = time.perf_counter() - t0
        if p.returncode != 0:
            raise RuntimeError(f"{' '.join(args)} failed: {p.stderr[-2000:]}")
        if wall < best:
            best, out = wall, json.loads(p.stdout)
            peak = int(p.stderr.rsplit("PEAK_RSS_KB", 1)[1].split()[0]) / 1024
    return best, out, peak


def _freqs(doc):
    return np.array(doc["frequency_hz"] if "frequency_hz" in doc else
                    [m["frequency_hz"] for m in doc["modes"]])


def _opensees_available():
    p = subprocess.run([sys.executable, "-c", "import openseespy.opensees"],
                       capture_output=True)
    return p.returncode == 0


def run(outdir, quick=False):
    from ..model.generate import panels_for, to_yaml, tower_crane, with_meshes
    sizes = (1000, 3000) if quick else (1000, 10000, 100000)
    have_ops = _opensees_available()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in sizes:
            repeat = 1 if n >= 100000 or quick else 3
            model = tower_crane(panels=panels_for(n))
            yml = to_yaml(model, os.path.join(tmp, f"crane{n}.yaml"))
            mesh_yml = os.path.join(tmp, f"crane{n}_mesh.yaml")
            to_yaml(with_meshes(model, mesh_yml), mesh_yml)
            c_t, c_doc, c_mem = _process(["cranefe", "modes", yml, "--count", str(COUNT),
                                          "--json"], repeat)
            m_t, m_doc, m_mem = _process(["cranefe", "modes", mesh_yml, "--count",
                                          str(COUNT), "--json"], repeat)
            f_t, f_doc, f_mem = _process(["cranefe.studies._floor", yml, str(COUNT)], repeat)
            row = {"dofs": c_doc["dofs"], "cranefe_s": c_t, "cranefe_mesh_s": m_t,
                   "floor_s": f_t, "floor_read_s": f_doc["timings_s"]["read"],
                   "ratio_floor": c_t / f_t,
                   "ratio_mesh_floor_without_read": m_t / (f_t - f_doc["timings_s"]["read"]),
                   "cranefe_load_s": c_doc["timings_s"]["load"],
                   "cranefe_assemble_s": c_doc["timings_s"]["assemble"],
                   "cranefe_solve_s": c_doc["timings_s"]["solve"],
                   "floor_solve_s": f_doc["timings_s"]["solve"],
                   "max_rel_diff_floor": float(np.max(np.abs(_freqs(c_doc) / _freqs(f_doc)
                                                             - 1))),
                   "max_rel_diff_mesh": float(np.max(np.abs(_freqs(m_doc) / _freqs(c_doc)
                                                            - 1))),
                   "cranefe_peak_MB": c_mem, "cranefe_mesh_peak_MB": m_mem,
                   "floor_peak_MB": f_mem}
            if have_ops:
                o_t, o_doc, o_mem = _process(["cranefe.studies._opensees", yml, str(COUNT)],
                                             repeat)
                row.update(opensees_s=o_t, ratio_opensees=c_t / o_t,
                           max_rel_diff=float(np.max(np.abs(_freqs(c_doc) / _freqs(o_doc)
                                                            - 1))),
                           opensees_solve_s=o_doc["timings_s"]["solve"],
                           opensees_peak_MB=o_mem)
            else:
                row.update(opensees_s=np.nan, ratio_opensees=np.nan, max_rel_diff=np.nan,
                           opensees_solve_s=np.nan, opensees_peak_MB=np.nan)
            rows.append(row)
    keys = ["dofs", "cranefe_s", "floor_s", "opensees_s", "ratio_floor", "ratio_opensees",
            "max_rel_diff"] + [k for k in rows[0] if k not in
                               ("dofs", "cranefe_s", "floor_s", "opensees_s", "ratio_floor",
                                "ratio_opensees", "max_rel_diff")]
    path = write_csv(outdir, "performance.csv", rows, keys)
    fig, ax = pyplot().subplots(figsize=(7, 4.5))
    d = [r["dofs"] for r in rows]
    for key, label in (("cranefe_s", "cranefe modes (YAML)"),
                       ("cranefe_mesh_s", "cranefe modes (mesh files)"),
                       ("floor_s", "floor: read + scipy assembly + eigsh"),
                       ("opensees_s", "OpenSeesPy")):
        ax.loglog(d, [r[key] for r in rows], marker="o", label=label)
    ax.set_xlabel("coordinates (DOFs)")
    ax.set_ylabel(f"whole process, {COUNT} modes [s]")
    ax.set_title("Lattice tower crane: cost of the modes, whole processes")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    return [path, save(fig, outdir, "performance.png")]
