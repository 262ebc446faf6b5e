"""The decoupled (Hasselman) damping estimate against the exact complex solutions:
error and time versus model size."""

import os
import time
from dataclasses import replace

import numpy as np

from ..assemble import assemble
from ..damping import exact_hysteretic, exact_viscous, modal_damping
from ..model import load
from ..modal import modes
from ._common import pyplot, save, write_csv

DESCRIPTION = "decoupled vs exact damping: error and time vs model size"
MODEL = os.path.join(os.path.dirname(__file__), "..", "..", "models",
                     "hammerhead_tower_crane.yaml")
COUNT = 6


def run(outdir, quick=False):
    base = load(os.path.abspath(MODEL))
    rows = []
    for N in ((0, 2) if quick else (0, 1, 4, 10, 25, 60, 140)):
        model = replace(base, effects=replace(base.effects, rope_mass=N))
        system = assemble(model)
        t0 = time.perf_counter()
        modal = modes(model, count=COUNT + 1, system=system)
        w, zeta, _, _, kappa, Kpsi = modal_damping(system, modal)
        w, zeta = w[:COUNT], zeta[:COUNT]
        t_modal = time.perf_counter() - t0
        t0 = time.perf_counter()
        ze, _ = exact_viscous(system, w, Kpsi)
        t_exact = time.perf_counter() - t0
        t0 = time.perf_counter()
        zh, _ = exact_hysteretic(system, w, Kpsi)
        t_hyst = time.perf_counter() - t0
        rows.append({"rope_elements": N, "dofs": system.K.shape[0],
                     "error_vs_viscous": float(np.max(np.abs(zeta / ze - 1))),
                     "error_vs_hysteretic": float(np.max(np.abs(zeta / zh - 1))),
                     "max_coupling": float(kappa[:COUNT].max()),
                     "modal_s": t_modal, "exact_viscous_s": t_exact,
                     "exact_hysteretic_s": t_hyst, "ratio_exact_modal": t_exact / t_modal})
    path = write_csv(outdir, "damping_cost.csv", rows)
    fig, axes = pyplot().subplots(1, 2, figsize=(11, 4))
    d = [r["dofs"] for r in rows]
    axes[0].loglog(d, [r["error_vs_viscous"] for r in rows], "o-", label="vs exact viscous")
    axes[0].loglog(d, [r["error_vs_hysteretic"] for r in rows], "s--",
                   label="vs complex stiffness")
    axes[0].set_ylabel(f"max relative error of zeta, first {COUNT} modes")
    for key, label in (("modal_s", "decoupled (modes + V^T B V)"),
                       ("exact_viscous_s", "exact viscous, per mode"),
                       ("exact_hysteretic_s", "exact complex stiffness")):
        axes[1].loglog(d, [r[key] for r in rows], "o-", label=label)
    axes[1].set_ylabel("time [s]")
    for ax in axes:
        ax.set_xlabel("coordinates (tower crane, rope elements per fall)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle("Damping of the hammerhead tower crane: decoupled estimate vs exact")
    return [path, save(fig, outdir, "damping_cost.png")]
