"""The elastic structure of operation scenes (docs/operations.md "Elastic structure"):
what it changes and what it costs.

The bundled scene with an elastic jib (models/operations/elastic_jib_crane_cycle.yaml:
hoist start and stop, a 60 degree slew) is run twice in this process, one after the
other: with `structure: flexible` (the jib's nodes bend in the superstructure's frame)
and with the same model made rigid (the jib's nodes carried by the superstructure,
`rigid_variant`). Per run: the peak force and dynamic factor of every rope, the load's
largest and residual sway, steps, the energy balance error, CPU time and the real-time
factor (simulated / CPU time); the elastic run's CPU time over the rigid one's from the
same run. `--quick`: the first 3 s (the hoist start). Writes operation_flexible.csv and
operation_flexible.png (the hoist rope's force of both runs), and the measured table of
docs/operations.md "Elastic structure" (between this study's markers) when a docs/
folder sits beside the output folder. The compiled step (numba, if installed) is warmed
up before the timings, so that neither run pays its import or cache load.
"""

import csv
import dataclasses
import os
import time

import numpy as np

from ..analysis.operation.integrate import simulate
from ..analysis.operation.mechanism import Mechanism
from ..analysis.operation.scene import parse
from ..model import load
from ._common import pyplot, rewrite_doc_blocks, save, write_csv

DESCRIPTION = "operation scenes with an elastic structure: rope peak forces and cost " \
    "against the rigid structure"
SCENES = (os.path.join("models", "operations", "elastic_jib_crane_cycle.yaml"),)
QUICK_DURATION = 3.0


def rigid_variant(model):
    """The model with every elastic node carried rigidly by the body (or the ground)
    its members are anchored to, and `structure: rigid`: the same crane with a rigid
    structure."""
    mech = Mechanism(model, parse(model))
    fl = mech.flex
    if fl is None:
        return model.with_effects(structure="rigid")
    nn = len(model.node_names)
    bodies, ground = list(model.bodies), list(model.ground)
    for f, k in fl.frames:
        nodes = tuple(int(i) for i in fl.en[k] if i < nn)
        if f < 0:
            ground += list(nodes)
        else:
            bodies[f] = dataclasses.replace(bodies[f], nodes=tuple(bodies[f].nodes) + nodes)
    out = dataclasses.replace(model, bodies=tuple(bodies),
                              ground=np.array(ground, dtype=int))
    return out.with_effects(structure="rigid")


def _num(x):
    return np.nan if x is None else float(x)


def _row(name, structure, res, cpu):
    d = res.to_dict()
    rows = []
    for rope, peak in d["rope_force_max_N"].items():
        if peak is None:
            continue
        sway = next(iter(d["sway"].values()), {})
        rows.append({"scene": name, "structure": structure, "rope": rope,
                     "peak_force_N": float(peak),
                     "dynamic_factor": float(d["dynamic_factor"][rope]),
                     "sway_max_deg": _num(sway.get("max_deg")),
                     "sway_residual_deg": _num(sway.get("residual_deg")),
                     "duration_s": float(d["duration_s"]), "dofs": int(d["dofs"]),
                     "steps": int(d["steps"]), "energy_error": float(d["energy_error"]),
                     "cpu_s": float(cpu), "rtf_cpu": float(d["duration_s"]) / cpu,
                     "cpu_vs_rigid": np.nan})
    return rows


def markdown(rows):
    """The measured table of docs/operations.md: the first rope of each run."""
    lines = ["| structure | coordinates | rope | peak [N] | dynamic factor | sway max / "
             "residual [deg] | steps | energy error | CPU [s] | real-time factor | CPU / "
             "rigid |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    first = rows[0]["rope"] if rows else None
    for r in rows:
        if r["rope"] != first:
            continue
        ratio = float(r["cpu_vs_rigid"])
        lines.append(f"| {r['structure']} | {int(r['dofs'])} | {r['rope']} | "
                     f"{float(r['peak_force_N']):,.0f} | {float(r['dynamic_factor']):.4f} | "
                     f"{float(r['sway_max_deg']):.2f} / {float(r['sway_residual_deg']):.2f} | "
                     f"{int(r['steps'])} | {float(r['energy_error']):.1e} | "
                     f"{float(r['cpu_s']):.3g} | {float(r['rtf_cpu']):.3g} | "
                     f"{'1' if np.isnan(ratio) else f'{ratio:.3g}'} |")
    return "\n".join(lines).replace(",", " ") + "\n"


def run(outdir, quick=False):
    rows, curves = [], {}
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    for rel in SCENES:
        model = load(os.path.join(root, rel))
        if quick:
            model = dataclasses.replace(model, analysis={**model.analysis,
                                                         "duration": QUICK_DURATION})
        name = os.path.splitext(os.path.basename(rel))[0]
        simulate(dataclasses.replace(rigid_variant(model), analysis={      # warm-up
            **model.analysis, "duration": 0.1}))
        runs = {}
        for structure, m in (("rigid", rigid_variant(model)), ("elastic", model)):
            c = time.process_time()
            res = simulate(m)
            cpu = time.process_time() - c
            runs[structure] = cpu
            rows += _row(name, structure, res, cpu)
            curves[(name, structure)] = (res.times, res.rope_force[:, 0], res.rope_names[0])
        for r in rows:
            if r["scene"] == name and r["structure"] == "elastic":
                r["cpu_vs_rigid"] = runs["elastic"] / runs["rigid"]
    paths = [write_csv(outdir, "operation_flexible.csv", rows)]
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8, 4))
    for (name, structure), (t, f, rope) in curves.items():
        ax.plot(t, np.asarray(f) / 1e3, lw=0.8, label=f"{name}: {structure} ({rope})")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("rope force [kN]")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    paths.append(save(fig, outdir, "operation_flexible.png"))
    if not quick:
        docs = os.path.join(os.path.dirname(os.path.abspath(outdir)), "docs", "operations.md")
        with open(paths[0]) as fh:                  # the page quotes the CSV as written
            table = markdown(list(csv.DictReader(fh)))
        paths += rewrite_doc_blocks(docs, "operation_flexible", (("table", table),))
    return paths
