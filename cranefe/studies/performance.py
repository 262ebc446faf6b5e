"""Large lattice cranes: cranefe against a bare floor script and OpenSeesPy, measured side
by side in one run (issue 14's goals):

- assembly: cranefe from the read YAML document to K and M (model build with its checks,
  DOF map, element assembly, u = T q) against the floor's few lines of numpy/scipy from the
  same document (`_floor.assemble`), in this process, alternated, best of several; goal
  at most 2x;
- whole `cranefe modes` process (interpreter, imports, reading, assembly, 20 modes)
  against the floor's process (goal at most 1.05x) and OpenSeesPy's (goal: faster),
  alternated run by run so that a busy machine slows all alike; best wall time of each.

OpenSeesPy is optional: without it its columns say "missing" and the rows stay.
"""

import json
import os
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

from ._common import pyplot, save, write_csv

DESCRIPTION = "1e3..1e5 DOFs: cranefe vs the floor (scipy) vs OpenSeesPy, assembly and " \
    "whole processes"
COUNT = 20
GOALS = {"ratio_assembly": 2.0, "ratio_floor": 1.05, "ratio_opensees": 1.0}
MISSING = "missing"


HERE = os.path.dirname(os.path.abspath(__file__))


def _environment(tmp):
    """The processes' environment: Python's default bytecode cache (kept in `tmp`, not in
    the source tree) even where PYTHONDONTWRITEBYTECODE is set, so that no process is
    charged the compilation of its modules on every start (an installed package has its
    bytecode; numpy's and scipy's have theirs)."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env["PYTHONPYCACHEPREFIX"] = os.path.join(tmp, "pycache")
    return env


def _process(args, env):
    """Wall time, CPU time (user + system) and JSON output of one whole process, and its
    peak memory (MB). args[0]: a module, or a script file of this folder."""
    run = [os.path.join(HERE, "_run.py"), os.path.join(HERE, args[0])] \
        if args[0].endswith(".py") else ["-m", "cranefe.studies._run", args[0]]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, *run, *args[1:]], capture_output=True, text=True,
                       env=env)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(args)} failed: {p.stderr[-2000:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    peak = int(p.stderr.rsplit("PEAK_RSS_KB", 1)[1].split()[0]) / 1024
    return wall, cpu, json.loads(p.stdout), peak


def _processes(commands, repeat, env, warm_up=False):
    """Each command's best run (least wall time) over `repeat` rounds; the commands
    alternate within a round (after one untimed round that fills the bytecode cache, if
    `warm_up`). Returns {name: (wall, cpu, doc, peak)}."""
    for args in commands.values() if warm_up else ():
        _process(args, env)
    best = {}
    for _ in range(repeat):
        for name, args in commands.items():
            out = _process(args, env)
            if name not in best or out[0] < best[name][0]:
                best[name] = out
    return best


def _best(f, repeat):
    t = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = f()
        t = min(t, time.perf_counter() - t0)
    return t, out


def _assembly(yml, repeat):
    """cranefe's assembly from the read document to K, M (and without the model build)
    against the floor's from the same file, alternated in this process."""
    from ..model.load import build, read_raw
    from ..system import assemble
    from . import _floor
    raw, doc = read_raw(yml), _floor.read(yml)
    t = {"floor": float("inf"), "cranefe": float("inf"), "assemble": float("inf")}
    for _ in range(repeat):
        t["floor"] = min(t["floor"], _best(lambda: _floor.assemble(doc), 1)[0])
        dt, system = _best(lambda: assemble(build(*raw)), 1)
        t["cranefe"] = min(t["cranefe"], dt)
        t["assemble"] = min(t["assemble"], _best(lambda: assemble(system.model), 1)[0])
    K_floor, _ = _floor.assemble(doc)
    if K_floor.shape != system.K.shape:
        raise RuntimeError(f"the floor assembles {K_floor.shape[0]} coordinates, cranefe "
                           f"{system.K.shape[0]}: not the same matrices")
    return {"assembly_cranefe_s": t["cranefe"], "assembly_floor_s": t["floor"],
            "ratio_assembly": t["cranefe"] / t["floor"],
            "assemble_only_s": t["assemble"],
            "ratio_assemble_only": t["assemble"] / t["floor"]}


def _freqs(doc):
    return np.array(doc["frequency_hz"] if "frequency_hz" in doc else
                    [m["frequency_hz"] for m in doc["modes"]])


def _diff(a, b):
    return float(np.max(np.abs(_freqs(a) / _freqs(b) - 1)))


def _opensees_available():
    p = subprocess.run([sys.executable, "-c", "import openseespy.opensees"],
                       capture_output=True)
    return p.returncode == 0


def _row(n, tmp, repeat, have_ops, warm_up):
    """One size: the assembly and whole-process comparisons."""
    from ..model.generate import panels_for, to_yaml, tower_crane, with_meshes
    model = tower_crane(panels=panels_for(n))
    yml = to_yaml(model, os.path.join(tmp, f"crane{n}.yaml"))
    mesh_yml = os.path.join(tmp, f"crane{n}_mesh.yaml")
    to_yaml(with_meshes(model, mesh_yml), mesh_yml)
    modes = ["cranefe", "modes", "--count", str(COUNT), "--json"]
    commands = {"cranefe": modes[:2] + [yml] + modes[2:],
                "mesh": modes[:2] + [mesh_yml] + modes[2:],
                "floor": ["_floor.py", yml, str(COUNT)]}
    if have_ops:
        commands["opensees"] = ["_opensees.py", yml, str(COUNT)]
    p = _processes(commands, repeat, _environment(tmp), warm_up)
    (c_t, c_cpu, c_doc, c_mem), (f_t, f_cpu, f_doc, f_mem) = p["cranefe"], p["floor"]
    m_t, _, m_doc, m_mem = p["mesh"]
    row = {"dofs": c_doc["dofs"], "cranefe_s": c_t, "floor_s": f_t,
           "ratio_floor": c_t / f_t, "ratio_floor_cpu": c_cpu / f_cpu,
           **_assembly(yml, max(repeat, 3)),
           "cranefe_mesh_s": m_t, "floor_read_s": f_doc["timings_s"]["read"],
           "ratio_mesh_floor_without_read": m_t / (f_t - f_doc["timings_s"]["read"]),
           "cranefe_load_s": c_doc["timings_s"]["load"],
           "cranefe_assemble_s": c_doc["timings_s"]["assemble"],
           "cranefe_solve_s": c_doc["timings_s"]["solve"],
           "floor_solve_s": f_doc["timings_s"]["solve"],
           "max_rel_diff_floor": _diff(c_doc, f_doc), "max_rel_diff_mesh": _diff(m_doc, c_doc),
           "cranefe_peak_MB": c_mem, "cranefe_mesh_peak_MB": m_mem, "floor_peak_MB": f_mem}
    if have_ops:
        o_t, o_cpu, o_doc, o_mem = p["opensees"]
        row.update(opensees_s=o_t, ratio_opensees=c_t / o_t,
                   ratio_opensees_cpu=c_cpu / o_cpu, max_rel_diff=_diff(c_doc, o_doc),
                   opensees_solve_s=o_doc["timings_s"]["solve"], opensees_peak_MB=o_mem)
    else:
        row.update(dict.fromkeys(("opensees_s", "ratio_opensees", "ratio_opensees_cpu",
                                  "max_rel_diff", "opensees_solve_s", "opensees_peak_MB"),
                                 MISSING))
    return row


def _number(v):
    return np.nan if v == MISSING else v


def _plot(rows, outdir):
    """Whole-process times (left) and the three ratios with their goals (right)."""
    fig, (ax, bx) = pyplot().subplots(1, 2, figsize=(12, 4.5))
    d = [r["dofs"] for r in rows]
    for key, label in (("cranefe_s", "cranefe modes (YAML)"),
                       ("cranefe_mesh_s", "cranefe modes (mesh files)"),
                       ("floor_s", "floor: read + scipy assembly + eigsh"),
                       ("opensees_s", "OpenSeesPy")):
        y = [_number(r[key]) for r in rows]
        ax.loglog(d, y, marker="o", label=label + (" (missing)" if np.all(np.isnan(y))
                                                   else ""))
    ax.set_xlabel("coordinates (DOFs)")
    ax.set_ylabel(f"whole process, {COUNT} modes [s]")
    ax.set_title("Lattice tower crane: whole processes")
    for key, label, colour in (("ratio_assembly", "assembly / floor's", "C0"),
                               ("ratio_floor", "process / floor's", "C1"),
                               ("ratio_opensees", "process / OpenSeesPy's", "C2")):
        y = [_number(r[key]) for r in rows]
        bx.semilogx(d, y, marker="o", color=colour,
                    label=label + (" (missing)" if np.all(np.isnan(y)) else ""))
        bx.axhline(GOALS[key], color=colour, ls="--", lw=0.8)
    bx.set_xlabel("coordinates (DOFs)")
    bx.set_ylabel("cranefe / reference (dashed: goal)")
    bx.set_title("Ratios, measured side by side")
    for a in (ax, bx):
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=8)
    return save(fig, outdir, "performance.png")


def run(outdir, quick=False):
    sizes = (1000, 3000) if quick else (1000, 10000, 100000)
    have_ops = _opensees_available()
    with tempfile.TemporaryDirectory() as tmp:
        rows = [_row(n, tmp, 1 if quick else (2 if n >= 100000 else 3), have_ops, k == 0)
                for k, n in enumerate(sizes)]
    first = ["dofs", "ratio_assembly", "ratio_floor", "ratio_opensees", "cranefe_s",
             "floor_s", "opensees_s", "assembly_cranefe_s", "assembly_floor_s",
             "max_rel_diff"]
    path = write_csv(outdir, "performance.csv", rows,
                     first + [k for k in rows[0] if k not in first])
    return [path, _plot(rows, outdir)]
