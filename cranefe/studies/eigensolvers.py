"""Dense and sparse eigensolvers on a chain with exactly known discrete frequencies."""

import time

import numpy as np

from ..cases import spring_chain
from ..model import load
from ..analysis.modal import modes
from ._common import pyplot, save, write_csv

DESCRIPTION = "dense vs sparse eigensolvers: error and time vs size"
COUNT = 10


def run(outdir, quick=False):
    plt = pyplot()
    sizes = (50, 200) if quick else (50, 100, 200, 500, 1000, 1500, 3000, 10000)
    rows = []
    for N in sizes:
        text, exact = spring_chain(N)
        model = load("chain.yaml", text)
        w = exact["omega"][:COUNT]
        row = {"dofs": N}
        for solver in ("dense", "sparse"):
            if solver == "dense" and N > 3000:
                row.update(dense_error=np.nan, dense_s=np.nan)
                continue
            t0 = time.perf_counter()
            r = modes(model, count=COUNT, solver=solver)
            row[f"{solver}_s"] = time.perf_counter() - t0
            row[f"{solver}_error"] = float(np.max(np.abs(r.omega[:COUNT] / w - 1)))
        rows.append(row)
    path = write_csv(outdir, "eigensolvers.csv", rows,
                     ["dofs", "dense_error", "dense_s", "sparse_error", "sparse_s"])
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for solver in ("dense", "sparse"):
        d = [r["dofs"] for r in rows]
        axes[0].loglog(d, [r[f"{solver}_s"] for r in rows], "o-", label=solver)
        axes[1].loglog(d, [max(r[f"{solver}_error"], 1e-17) for r in rows], "o-",
                       label=solver)
    axes[0].set_ylabel(f"time of cranefe modes, {COUNT} modes [s]")
    axes[1].set_ylabel(f"max relative error, first {COUNT} frequencies")
    for ax in axes:
        ax.set_xlabel("coordinates")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle("Eigensolvers against the exact frequencies of a discrete chain")
    return [path, save(fig, outdir, "eigensolvers.png")]
