"""Convergence in the mesh of a heavy beam tower crane, cranefe and OpenSeesPy against a
fine-mesh reference: results/structure_convergence.csv and .png (docs/structure.md).

The crane (planar, sway on): a mast, a jib and a counter-jib as Euler-Bernoulli beams
whose own weight is a large part of what the mast carries (lattice members smeared into
equivalent beams: their mass per length in rho A), a counterweight and a load at the
ends. The first `COUNT` frequencies (the crane's sway and bending modes, where the
weight matters) with k elements per member, k = 1 .. 32, against cranefe's with 64
(its own error, by the observed order, below 1e-9; finer meshes lose digits to the
conditioning of the stiffness: with 256 elements the first modes move by 7e-7). cranefe's members carry the
consistent geometric stiffness of a linearly varying axial force; OpenSeesPy's
elasticBeamColumn with the P-Delta transformation the string stiffness N/l, exact only as
the elements shrink. OpenSeesPy is optional (pip install 'cranefe[bench]'): without it
its columns say "missing".
"""

import json
import os
import subprocess
import sys
import tempfile

import numpy as np

from ..analysis.modal import modes
from ..model import load
from ._common import pyplot, save, write_csv

DESCRIPTION = "convergence of a heavy beam tower crane, cranefe and OpenSeesPy"
COUNT = 3
REFERENCE = 64


def heavy_tower_crane(elements=1):
    """The model file text: mast 40 m, jib 50 m, counter-jib 15 m (E = 210 GPa; mass per
    length 1500, 500, 600 kg/m), counterweight 30 t, load 5 t at the jib tip; `elements`
    beam elements per member."""
    return f"""cranefe: 1
name: heavy beam tower crane
plane: xz
nodes: {{O: [0, 0, 0], T: [0, 0, 40], J: [50, 0, 40], C: [-15, 0, 40]}}
ground: [O]
members:
  mast: {{type: beam, nodes: [O, T], E: 2.1e+11, A: 0.05, Iy: 0.05, rho: 30000,
         elements: {elements}}}
  jib: {{type: beam, nodes: [T, J], E: 2.1e+11, A: 0.02, Iy: 0.01, rho: 25000,
        elements: {elements}}}
  counter_jib: {{type: beam, nodes: [T, C], E: 2.1e+11, A: 0.02, Iy: 0.01, rho: 30000,
                elements: {elements}}}
masses: {{C: 30000, J: 5000}}
effects: {{structure: flexible, sway: true}}
"""


def cranefe_hz(elements, count=COUNT):
    return modes(load("crane.yaml", heavy_tower_crane(elements)), count=count).frequency_hz


def opensees_version():
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version("openseespy")
    except PackageNotFoundError:
        return None


def opensees_hz(elements, count=COUNT):
    """OpenSeesPy's first `count` frequencies in its own process, or None (missing or
    failed; the reason as a second value)."""
    if opensees_version() is None:
        return None, "missing (openseespy not installed)"
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "crane.yaml")
        with open(path, "w") as fh:
            fh.write(heavy_tower_crane(elements))
        p = subprocess.run([sys.executable, "-m", "cranefe.studies._opensees_beams", path,
                            str(count)], capture_output=True, text=True)
    if p.returncode:
        last = (p.stderr.strip().splitlines() or ["no output"])[-1]
        return None, f"failed: {last}"
    out = p.stdout
    return np.array(json.loads(out[out.index("{"):])["frequency_hz"]), ""


def convergence(sizes, reference=REFERENCE, count=COUNT):
    """Rows: elements per member, the largest relative error of the first `count`
    frequencies of cranefe and of OpenSeesPy against cranefe's with `reference` elements,
    their largest relative difference, and the observed orders between sizes."""
    ref = cranefe_hz(reference, count)
    rows = []
    for k in sizes:
        c = cranefe_hz(k, count)
        o, why = opensees_hz(k, count)
        row = {"elements_per_member": k, "cranefe_error": float(np.max(np.abs(c / ref - 1)))}
        if o is None:
            row.update(opensees_error=why, difference=why)
        else:
            row.update(opensees_error=float(np.max(np.abs(o / ref - 1))),
                       difference=float(np.max(np.abs(o / c - 1))))
        rows.append(row)
    for prev, row in zip([None] + rows[:-1], rows):
        for who in ("cranefe", "opensees"):
            e1, e0 = row[f"{who}_error"], prev[f"{who}_error"] if prev else None
            ok = isinstance(e1, float) and isinstance(e0, float) and e1 > 0 and e0 > 0
            row[f"{who}_order"] = float(np.log(e0 / e1) / np.log(
                row["elements_per_member"] / prev["elements_per_member"])) if ok else ""
    return rows, ref


def run(outdir, quick=False):
    plt = pyplot()
    sizes = (1, 2, 4) if quick else (1, 2, 4, 8, 16, 32)
    rows, ref = convergence(sizes, 16 if quick else REFERENCE)
    keys = ["elements_per_member", "cranefe_error", "cranefe_order", "opensees_error",
            "opensees_order", "difference"]
    path = write_csv(outdir, "structure_convergence.csv", rows, keys)
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    k = [r["elements_per_member"] for r in rows]
    ax.loglog(k, [r["cranefe_error"] for r in rows], "o-", label="cranefe")
    if all(isinstance(r["opensees_error"], float) for r in rows):
        ax.loglog(k, [r["opensees_error"] for r in rows], "s-",
                  label=f"OpenSeesPy {opensees_version()} (P-Delta)")
    else:
        ax.text(0.05, 0.05, "OpenSeesPy: missing", transform=ax.transAxes)
    ax.set_xlabel("beam elements per member")
    ax.set_ylabel(f"max relative error, first {COUNT} frequencies")
    ax.set_title(f"heavy beam tower crane (reference: cranefe, "
                 f"{16 if quick else REFERENCE} elements; f1 = {ref[0]:.5g} Hz)",
                 fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    return [path, save(fig, outdir, "structure_convergence.png")]
