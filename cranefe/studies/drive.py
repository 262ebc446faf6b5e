"""The simplified drive reduction (Heletiy 2016, eq. 10) against the coupled drive."""

import time
from dataclasses import replace

import numpy as np

from ..cases import two_mass_hoist
from ..model import load
from ..analysis.modal import drive_reduction, modes
from ._common import pyplot, save, write_csv

DESCRIPTION = "drive: reduced vs coupled: frequency error vs drive inertia, and its cost"


def run(outdir, quick=False):
    plt = pyplot()
    ratios = np.logspace(-2, 2, 5 if quick else 17)      # J / (m r^2)
    rows = []
    for q in ratios:
        m, R, n = 5000.0, 0.25, 2
        J = q * m * (R / n) ** 2
        text, exact = two_mass_hoist(falls=n, J=J, R=R, m=m)
        model = load("hoist.yaml", text)
        t0 = time.perf_counter()
        coupled = modes(model)
        t_c = time.perf_counter() - t0
        t0 = time.perf_counter()
        reduced = modes(model, replace(model.effects, drive="reduced"))
        t_r = time.perf_counter() - t0
        err = drive_reduction(model, reduced)["modes"][0]["relative_error"]
        rows.append({"J_over_m_r2": q, "error_w": err,
                     "error_w2": (1 + err) ** 2 - 1,
                     "formula_w2": -exact["error_w2"],
                     "coupled_vs_exact": coupled.omega[~coupled.rigid][0] /
                     exact["omega"][0] - 1,
                     "time_coupled_s": t_c, "time_reduced_s": t_r})
    path = write_csv(outdir, "drive_reduction.csv", rows)
    fig, ax = plt.subplots(figsize=(6.5, 4))
    ax.loglog(ratios, [-r["error_w"] for r in rows], "o-", label="reduced vs coupled, w")
    ax.loglog(ratios, [-r["formula_w2"] for r in rows], "--",
              label="m r^2 / (m r^2 + J), of w^2")
    ax.set_xlabel("J / (m r^2): drive inertia over the load's, at the drum")
    ax.set_ylabel("relative frequency error of drive: reduced")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    return [path, save(fig, outdir, "drive_reduction.png")]
