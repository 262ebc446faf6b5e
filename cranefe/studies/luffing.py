"""Energy-optimal luffing (Loveikin et al. 2013): error of each way of solving eq. 16
against the exact law, and its cost; the comparison of laws for the example crane.

Every method gets f(alpha) = J'/(2J) from the kinematics itself (Newton on the loop
closure, transfer functions by implicit differentiation), so its time includes the
kinematics it asks for. The reference is the exact law by quadrature on a Chebyshev
interpolant of sqrt(J) converged to round-off (checked against scipy's adaptive quad).
"""

import os
import time

import numpy as np

from ._common import pyplot, save, write_csv

DESCRIPTION = "luffing optimum: paper's collocation, n-point collocation, solve_bvp, " \
              "quadrature: error vs time"
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "models", "portal_crane_luffing_scene.yaml")


def _best_time(run, repeat):
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = run()
        best = min(best, time.perf_counter() - t0)
    return out, best


def measure(quick=False, scene=SCENE):
    """Rows of (method, parameter, error, time) and the analysis' objects."""
    from ..analysis.luffing.analysis import Luffing, read_scene
    from ..analysis.luffing.optimum import (GRID, bvp, chebyshev_points, collocation,
                                   equally_spaced, law_error, paper_collocation,
                                   quadrature_law)
    from ..model import load
    model = load(scene)
    lf = Luffing(model, read_scene(model, scene), scene)
    exact = lf.optimal()
    a0, ak = lf.alpha0, lf.alphak
    T_exact = exact.info["S"] ** 2 / 2
    red = lf.reduced

    def f(alpha):                               # the kinematics, every call
        v = red.evaluate(alpha)
        return 0.5 * v["dJ"] / v["J"]

    def T_error(law):
        tau = np.polynomial.legendre.leggauss(64)
        al, d1, _ = law.evaluate(0.5 + 0.5 * tau[0])
        T = 0.5 * np.sum(tau[1] * 0.5 * lf.proxy("J", al) * d1**2)
        return abs(T / T_exact - 1)

    repeat = 1 if quick else 3
    rows = []

    def add(family, method, param, law, t):
        rows.append({"family": family, "method": method, "parameter": param,
                     "error_rad": law_error(law, exact, GRID),
                     "T_mean_rel_error": T_error(law), "time_s": t,
                     "f_evaluations": law.evaluations, "status": law.status,
                     "iterations": law.iterations})

    for variant, relax in (("printed", 1.0), ("eq21", 1.0), ("corrected", None)):
        if relax is None:           # the corrected iteration diverges: relax it
            probe = paper_collocation(f, a0, ak, variant)
            relax = probe.info["relax_best"]
        law, t = _best_time(lambda: paper_collocation(f, a0, ak, variant, relax=relax),
                            repeat)
        add("paper 3-point fixed point", f"paper {variant} (relax {relax:.3f})", 3, law, t)
    ns = range(2, 7) if quick else range(2, 11)
    for family, points in (("collocation, equally spaced", equally_spaced),
                           ("collocation, Chebyshev", chebyshev_points)):
        for n in ns:
            law, t = _best_time(lambda: collocation(f, a0, ak, points(n)), repeat)
            add(family, f"{family} n={n}", n, law, t)
    tols = (1e-2, 1e-4, 1e-6) if quick else (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8,
                                             1e-9, 1e-10)
    for tol in tols:
        law, t = _best_time(lambda: bvp(f, a0, ak, tol=tol), repeat)
        add("solve_bvp", f"solve_bvp tol={tol:g}", tol, law, t)
    ms = (2, 4, 8, 16) if quick else (2, 3, 4, 6, 8, 12, 16, 24, 32, 48)
    for m in ms:
        law, t = _best_time(lambda: quadrature_law(red.evaluate, a0, ak, m), repeat)
        add("quadrature", f"quadrature m={m}", m, law, t)
    return rows, lf, exact


def check_reference(lf, exact, points=(0.25, 0.5, 0.75)):
    """tau(alpha) of the reference against scipy's adaptive quad of sqrt(J) evaluated
    by the kinematics: largest |difference| in tau."""
    from scipy.integrate import quad
    red = lf.reduced
    S = exact.info["S"]
    worst = 0.0
    for tau in points:
        al = exact.evaluate(tau)[0][0]
        val, _ = quad(lambda a: np.sqrt(red.evaluate(np.array([a]))["J"][0]), lf.alpha0,
                      al, epsabs=1e-13, epsrel=1e-13, limit=200)
        worst = max(worst, abs(val / S - tau))
    return worst


def run(outdir, quick=False):
    rows, lf, exact = measure(quick)
    paths = [write_csv(outdir, "luffing_cost.csv", rows)]
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 5))
    markers = {"paper 3-point fixed point": "s", "collocation, equally spaced": "o",
               "collocation, Chebyshev": "^", "solve_bvp": "D", "quadrature": "v"}
    for family, mk in markers.items():
        sel = [r for r in rows if r["family"] == family]
        err = np.maximum([r["error_rad"] for r in sel], 1e-17)
        ax.loglog([r["time_s"] for r in sel], err, marker=mk, ls="-" if len(sel) > 3
                  else "none", label=family)
        if family.startswith("paper"):
            for r, e in zip(sel, err):
                ax.annotate(r["method"].split(" (")[0].replace("paper ", ""),
                            (r["time_s"], e), fontsize=7, xytext=(4, 2),
                            textcoords="offset points")
    ax.set_xlabel("time (s), kinematics included")
    ax.set_ylabel("max |alpha - alpha_exact| (rad)")
    ax.set_title("Optimum of eq. 16 (Loveikin et al. 2013), portal crane 30 -> 8 m",
                 fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    paths.append(save(fig, outdir, "luffing_cost.png"))
    if not quick:
        from ..analysis.luffing.analysis import analyse
        from ..analysis.luffing.plots import write_plots
        from ..model import load
        result = analyse(load(SCENE), file=SCENE)
        keys = ["T_mean_J", "T_ratio", "peak_motor_torque_Nm", "peak_power_W",
                "motor_impulse_Nms", "max_sway_deg", "residual_sway_deg",
                "max_sway_linear_deg", "residual_sway_linear_deg", "T_load_mean_J"]
        paths.append(write_csv(outdir, "luffing_laws.csv",
                               [{"law": n, **{k: result.table[n][k] for k in keys}}
                                for n in result.law_names], ["law"] + keys))
        orders = []
        for kind in ("equally_spaced", "chebyshev"):
            for r in result.collocation[kind]:
                orders.append({"points": kind, "n": r["n"], "error_rad": r["error_rad"]})
        paths.append(write_csv(outdir, "luffing_collocation_order.csv", orders))
        paths += write_plots(result, outdir)
    return paths
