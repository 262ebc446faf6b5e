"""The decoupled (Hasselman) damping estimate against the exact complex solutions:
error and time versus model size, and error versus the coupling coefficient.

Three families, measured in one run (docs/damping.md):

- ``hoist_chain``: a multi-mass hoist built here, a free drum (quasi-cyclic) hauling a
  rope of n lumped masses with absorption rising from 0.12 to 0.30 along it (the part
  running over the sheaves works hardest), a hook-block buffer with psi = 0.5 and the
  load; 10 to 3002 coordinates;
- ``tower_crane``: models/hammerhead_tower_crane.yaml with 0 to 140 rope elements per
  fall (7 to 2 933 coordinates), where lateral rope modes come close to the hoist mode;
- ``close_pair``: two oscillators joined by a soft spring, psi 0.1 and 1.0, their
  frequencies a relative gap apart from 1 down to 1e-3: the coupling coefficient
  sweeps through Hasselman's limit.

Per case: the first modes' largest relative error of the decoupled damping ratio
against the exact viscous (each mode's own B) and complex-stiffness answers, the
largest coupling coefficient and predicted error, and the best of a few timings of
the undamped modes (as `cranefe damping` computes them, with coupling partners), the
decoupled estimate, and the two exact solutions of the same modes.
"""

import os
import time
from dataclasses import replace

import numpy as np

from ..system import assemble
from ..analysis.damping import (exact_hysteretic, exact_viscous, modal_damping, partner_modes)
from ..model import load
from ._common import pyplot, save, write_csv

DESCRIPTION = "decoupled vs exact damping: error and time vs model size and coupling"
MODEL = os.path.join(os.path.dirname(__file__), "..", "..", "models",
                     "hammerhead_tower_crane.yaml")
COUNT = 7            # modes compared (rigid ones included)
REPEAT = 5           # timings: best of at least this many (3 above 500 coordinates;
                     # up to 30 while under 0.3 s in all): the shortest are ~1 ms

KEYS = ["case", "dofs", "frequency_gap", "modes", "max_coupling", "max_error_viscous",
        "max_error_hysteretic", "max_predicted_error", "modes_s", "decoupled_s",
        "exact_viscous_s", "hysteretic_s", "ratio_exact_modal", "ratio_damping_step"]


def hoist_chain(n, load_mass=5000.0, length=60.0, EA=1.7e7, mu=1.5):
    """YAML text of a vertical hoist: drum (free) - rope of n lumped masses - buffer -
    load. Rope segments are axial springs EA/l with psi rising 0.12 -> 0.30 towards the
    drum; the first segment is a rope from the drum (its rotation hauls it in)."""
    l = length / n
    z = length + 2.0 - l * np.arange(n + 1)           # N0 (drum) ... Nn
    psi = np.linspace(0.30, 0.12, n)                  # segment k: N_k -> N_{k+1}
    nodes = ", ".join(f"N{k}: [0, 0, {zk:.6f}]" for k, zk in enumerate(z))
    masses = ", ".join(f"N{k}: {mu * l:.6g}" for k in range(1, n + 1))
    springs = "\n".join(
        f"  - {{name: s{k}, type: axial, nodes: [N{k}, N{k + 1}], stiffness: {EA / l:.8g}, "
        f"psi: {psi[k]:.4f}}}" for k in range(1, n))
    return f"""cranefe: 1
name: hoist chain ({n} rope masses)
plane: xz
nodes: {{{nodes}, H: [0, 0, 0]}}
ground: [N0]
masses: {{{masses}, H: {load_mass}}}
drums:
  hoist: {{node: N0, radius: 0.25, inertia: 961.0, brake: false}}
ropes:
  top: {{EA: {EA}, psi: {psi[0]:.4f}, path: [hoist, N1]}}
springs:
{springs}
  - {{name: buffer, type: axial, nodes: [N{n}, H], stiffness: 2.0e7, psi: 0.5}}
effects: {{sway: false}}
"""


def close_pair(gap):
    """Two 100 kg oscillators, k = 1e4 and 1e4 (1 + gap)^2 N/m (psi 0.1 and 1.0), joined
    by a 200 N/m spring without absorption."""
    return f"""cranefe: 1
name: close pair (gap {gap:g})
plane: xz
gravity: [0, 0, 0]
nodes: {{G1: [0, 0, 0], A: [1, 0, 0], B: [2, 0, 0], G2: [3, 0, 0]}}
ground: [G1, G2]
masses: {{A: 100, B: 100}}
springs:
  - {{name: a, type: axial, nodes: [G1, A], stiffness: 1.0e4, psi: 0.1}}
  - {{name: b, type: axial, nodes: [B, G2], stiffness: {1.0e4 * (1 + gap) ** 2:.10g}, psi: 1.0}}
  - {{name: c, type: axial, nodes: [A, B], stiffness: 200.0, psi: 0.0}}
effects: {{sway: false}}
"""


def _best(fn, repeat, budget=0.3, most=30):
    """Best time of `repeat` runs, more (up to `most`) while they take under `budget`
    seconds in all: millisecond timings on a busy machine need many samples."""
    best, out, spent, k = np.inf, None, 0.0, 0
    while k < repeat or (spent < budget and k < most):
        t0 = time.perf_counter()
        out = fn()
        t = time.perf_counter() - t0
        best, spent, k = min(best, t), spent + t, k + 1
    return best, out


def measure(model, case, repeat=None, count=COUNT, gap=np.nan):
    """One row: errors of the decoupled estimate and the time of each method."""
    system = assemble(model)
    if repeat is None:
        repeat = REPEAT if system.K.shape[0] <= 500 else 3
    t_modes, (modal, shown) = _best(lambda: partner_modes(model, system, count), repeat)
    el = np.flatnonzero(~modal.rigid)
    t_dec, md = _best(lambda: modal_damping(system, modal, np.flatnonzero(el < shown)),
                      repeat)
    which = np.flatnonzero((el < shown) & (md.zeta > 0))
    V = modal.shapes[:, el]
    args = (system, V, md.omega, md.zeta, md.Kpsi, md.coupling, which)
    t_v, (zv, _) = _best(lambda: exact_viscous(*args), repeat)
    t_h, (zh, _) = _best(lambda: exact_hysteretic(*args), repeat)
    z = md.zeta[which]
    return {"case": case, "dofs": system.K.shape[0], "frequency_gap": float(gap),
            "modes": len(which),
            "max_coupling": float(md.coupling[which].max()),
            "max_error_viscous": float(np.max(np.abs(z / zv - 1))),
            "max_error_hysteretic": float(np.max(np.abs(z / zh - 1))),
            "max_predicted_error": float(np.max(np.abs(md.predicted_error[which]))),
            "modes_s": t_modes, "decoupled_s": t_dec, "exact_viscous_s": t_v,
            "hysteretic_s": t_h,
            "ratio_exact_modal": (t_modes + t_v) / (t_modes + t_dec),
            "ratio_damping_step": t_v / t_dec}


def run(outdir, quick=False):
    rows = []
    for n in ((8, 30) if quick else (8, 30, 100, 300, 1000, 3000)):
        rows.append(measure(load(f"chain{n}.yaml", hoist_chain(n)), "hoist_chain",
                            repeat=1 if quick else None))
    base = load(os.path.abspath(MODEL))
    for N in ((0,) if quick else (0, 1, 4, 10, 25, 60, 140)):
        model = replace(base, effects=replace(base.effects, rope_mass=N))
        rows.append(measure(model, "tower_crane", repeat=1 if quick else None))
    for gap in ((1.0, 0.1, 0.01) if quick else np.logspace(0, -3, 13)):
        rows.append(measure(load("pair.yaml", close_pair(gap)), "close_pair",
                            repeat=1 if quick else None, count=2, gap=gap))
    path = write_csv(outdir, "damping_cost.csv", rows, KEYS)
    return [path, _plot(rows, outdir)]


def _plot(rows, outdir):
    from ..analysis.damping import ERROR_TOL, KAPPA
    plt = pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.6))
    styles = {"hoist_chain": "o", "tower_crane": "s"}
    for case, mk in styles.items():
        r = [x for x in rows if x["case"] == case]
        d = [x["dofs"] for x in r]
        for key, ls, label in (("max_error_viscous", "-", "vs exact viscous"),
                               ("max_error_hysteretic", "--", "vs complex stiffness")):
            axes[0].loglog(d, [max(x[key], 1e-16) for x in r], mk + ls,
                           label=f"{case}: {label}")
        for key, ls, label in (("modes_s", ":", "undamped modes"),
                               ("decoupled_s", "-", "decoupled (V^T B V)"),
                               ("exact_viscous_s", "--", "exact viscous"),
                               ("hysteretic_s", "-.", "complex stiffness")):
            axes[1].loglog(d, [x[key] for x in r], mk + ls, label=f"{case}: {label}")
    axes[0].set_ylabel(f"max |relative error| of zeta, first {COUNT} modes (rigid incl.)")
    axes[1].set_ylabel("time [s] (best of a few)")
    for ax in axes[:2]:
        ax.set_xlabel("coordinates")
    r = [x for x in rows if x["case"] == "close_pair"]
    c = [x["max_coupling"] for x in r]
    axes[2].loglog(c, [max(x["max_error_viscous"], 1e-16) for x in r], "o-",
                   label="actual, vs exact viscous")
    axes[2].loglog(c, [max(x["max_error_hysteretic"], 1e-16) for x in r], "s--",
                   label="actual, vs complex stiffness")
    axes[2].loglog(c, [max(x["max_predicted_error"], 1e-16) for x in r], "k:",
                   label="predicted (perturbation, docs/damping.md)")
    axes[2].axvline(KAPPA, color="r", lw=1, label=f"coupling limit {KAPPA:g}")
    axes[2].axhline(ERROR_TOL, color="m", lw=1, ls="--",
                    label=f"predicted-error limit {ERROR_TOL:g}")
    axes[2].set_xlabel("largest coupling coefficient eps_ij (close pair, gap 1 to 1e-3)")
    axes[2].set_ylabel("max |relative error| of zeta")
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Decoupled (Hasselman) damping estimate against the exact complex "
                 "solutions: error and cost")
    return save(fig, outdir, "damping_cost.png")
