"""Rope elements per fall: frequency error against exact solutions, and its cost."""

import time
from dataclasses import replace

import numpy as np

from ..cases import ROPE_CASES, matched
from ..model import load
from ..analysis.modal import modes
from ._common import pyplot, save, write_csv

DESCRIPTION = "rope elements per fall (N): error vs exact solutions and time"
MODES = 3


def _timed(model, effects, repeat):
    best, result = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        result = modes(model, effects, count=10)
        best = min(best, time.perf_counter() - t0)
    return result, best


def measure(quick=False):
    Ns = (2, 4, 8, 16) if quick else (2, 4, 8, 16, 32, 64, 128, 256)
    rows = []
    for case, make in ROPE_CASES.items():
        text, exact = make()
        model = load(f"{case}.yaml", text)
        w = exact["omega"][:MODES]
        for matrix in ("consistent", "lumped"):
            for N in Ns:
                eff = replace(model.effects, rope_mass=N, rope_mass_matrix=matrix)
                r, t = _timed(model, eff, 1 if quick else 3)
                err = matched(r.omega, w) / w - 1
                rows.append({"case": case, "mass": matrix, "N": N, "dofs": r.dofs,
                             "time_s": t, **{f"error_mode{k + 1}": e
                                             for k, e in enumerate(err)}})
    return rows


def fitted_orders(rows):
    """Slope of log|error| against log N over the finest three N, per case/mass/mode."""
    out = {}
    for case in dict.fromkeys(r["case"] for r in rows):
        for mass in ("consistent", "lumped"):
            sel = [r for r in rows if r["case"] == case and r["mass"] == mass][-3:]
            N = np.log([r["N"] for r in sel])
            out[case, mass] = [-np.polyfit(N, np.log(np.abs([r[f"error_mode{k}"]
                                                                for r in sel])), 1)[0]
                               for k in range(1, MODES + 1)]
    return out


def run(outdir, quick=False):
    rows = measure(quick)
    orders = fitted_orders(rows)
    path = write_csv(outdir, "rope_convergence.csv", rows)
    opath = write_csv(outdir, "rope_convergence_orders.csv", [
        {"case": case, "mass": mass, **{f"order_mode{k + 1}": round(float(x), 3)
                                        for k, x in enumerate(o)}}
        for (case, mass), o in orders.items()])
    fig, axes = pyplot().subplots(1, 2, figsize=(11, 4.2))
    for case in ROPE_CASES:
        for mass, ls in (("consistent", "-"), ("lumped", "--")):
            sel = [r for r in rows if r["case"] == case and r["mass"] == mass]
            e = [abs(r["error_mode1"]) for r in sel]
            label = f"{case}, {mass} (order {orders[case, mass][0]:.2f})"
            axes[0].loglog([r["N"] for r in sel], e, ls, marker="o", label=label)
            axes[1].loglog([r["time_s"] for r in sel], e, ls, marker="o", label=label)
    axes[0].set_xlabel("elements per fall N")
    axes[1].set_xlabel("time of cranefe modes (assembly + solve) [s]")
    for ax in axes:
        ax.set_ylabel("relative error of the first frequency")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("Rope elements: error against exact solutions, and what it costs")
    return [path, opath, save(fig, outdir, "rope_convergence.png")]
