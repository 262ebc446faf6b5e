"""What a transient's accuracy costs: the error of the peak rope force against time step
and retained modes, with the computing time of each run (docs/transient.md, "Cost").

Two cases with exact answers:

- ``hoist_start``: models/two_mass_hoist.yaml started from its static state by a step
  drum torque of 1.6 x the holding torque, the rope with ELEMENTS elements per fall
  (axial waves), decoupled modal damping. For a step load the principal coordinates have
  closed-form responses (rigid: F t^2/2; elastic: F/w^2 (1 - e^(-zeta w t) (cos w_d t +
  zeta w / w_d sin w_d t))), and the modal damping makes the direct equations decouple in
  the same coordinates, so the superposition of all of them is the exact answer of the
  discrete model; its peak over time is found by dense sampling and Brent's method.
  Runs: direct integration at fixed steps; modal superposition with k modes at a fine
  step (truncation alone), with and without the static correction, and with the
  automatic step of the k retained modes (what a user gets).
- ``lift_off``: the massless two-mass hoist of cranefe.cases.hoist_lift_off, lifted at
  constant drum speed: dynamic factor and lift-off time against the closed form.

Writes results/transient_cost.csv and transient_cost.png, and results/transient_phi2.csv:
the dynamic factor of lifting the example cranes' rated loads off the ground at hook
speeds v_h, with a rigid drive (the drum at full speed from t = 0) and with the speed
ramped up over RAMP seconds, beside EN 13001-2's phi2 = phi2,min + beta2 v_h.
"""

import os
import tempfile
import time

import numpy as np
import scipy.optimize as so

from .. import cases
from ..analysis.loads.standard import HOISTING_CLASSES  # EN 13001-2 Table 2
from ..model import load
from ._common import pyplot, save, write_csv

DESCRIPTION = "transients: peak rope force error vs time step and retained modes, with times"
MODEL = os.path.join(os.path.dirname(__file__), "..", "..", "models", "two_mass_hoist.yaml")
TORQUE = 10200.0          # N m at the drum, 1.6 x the holding torque
RAMP = 0.5               # s, run-up of the "ramped" drive in the phi2 table
CRANES = (("two_mass_hoist.yaml", "H"), ("hammerhead_tower_crane.yaml", "HOOK"),
          ("luffing_tower_crane.yaml", "HOOK"))
KEYS = ["case", "method", "static_correction", "modes", "time_step_s", "dofs",
        "peak_force_N", "reference_N", "error", "lift_off_error", "time_s"]


def _scene(folder, name, model, effects, analysis):
    path = os.path.join(folder, f"{name}.yaml")
    with open(path, "w") as fh:
        fh.write(f"cranefe: 1\nscene: {name}\nmodel: {os.path.abspath(model)}\n"
                 f"effects: {effects}\nanalysis:\n  type: transient\n{analysis}")
    return load(path)


def _timed(model, repeat=1):
    from ..analysis.transient.integrate import simulate
    best, r = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        r = simulate(model)
        best = min(best, time.perf_counter() - t0)
    return r, best


def exact_peak(model, duration):
    """Peak rope force of a step-loaded, modally damped scene from the closed-form
    responses of all its principal coordinates (module docstring)."""
    from ..analysis.damping import modal_damping_ratios
    from ..analysis.modal import modes
    from ..analysis.transient.problem import Problem
    from ..analysis.transient.scene import parse
    p = Problem(model, parse(model))
    if p.prescribed and any(np.any(pr.values) for pr in p.prescribed.values()):
        raise ValueError("exact_peak takes drum torques, not prescribed speeds")
    modal = modes(model, system=p.sub)
    if modal.massless:
        raise ValueError("exact_peak needs every coordinate with inertia")
    zeta = modal_damping_ratios(p.sub, modal) if model.effects.damping == "modal" else \
        np.zeros(len(modal.omega))
    Phi = np.zeros((p.n, len(modal.omega)))
    Phi[p.free] = modal.shapes
    F = Phi.T @ p.eq.force(0.0)                   # constant: a step from t = 0
    w, rigid = modal.omega, modal.rigid
    Rc = (p.R @ Phi) * p.c[:, None]               # rope force per unit principal coord.

    def forces(t):
        t = np.atleast_1d(t)[:, None]
        eta = np.zeros((t.shape[0], len(w)))
        eta[:, rigid] = F[rigid] * t**2 / 2
        e = ~rigid
        we, ze = w[e], zeta[e]
        wd = we * np.sqrt(1 - ze**2)
        decay = np.exp(-ze * we * t)
        eta[:, e] = F[e] / we**2 * (1 - decay * (np.cos(wd * t) + ze * we / wd *
                                                 np.sin(wd * t)))
        return p.S0 + eta @ Rc.T                    # (nt, rows)

    t = np.linspace(0.0, duration, 40001)
    S = forces(t)
    k, row = np.unravel_index(np.argmax(S), S.shape)
    dt = t[1] - t[0]
    res = so.minimize_scalar(lambda x: -forces(x)[0, row],
                             bounds=(max(t[k] - dt, 0.0), min(t[k] + dt, duration)),
                             method="bounded", options={"xatol": 1e-12})
    return max(-res.fun, S[k, row]), p.n


def run(outdir, quick=False):
    elements = 4 if quick else 16
    duration = 0.4
    effects = f"{{sway: false, rope_mass: {elements}, damping: modal}}"
    steps = (1e-2, 2e-3) if quick else (2e-2, 1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4)
    fine = 1e-4 if not quick else 5e-4
    counts = (1, 3) if quick else (1, 2, 3, 5, 8, 12, 20, 30, 50)
    repeat = 1 if quick else 3
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        base = f"  duration: {duration}\n  drums:\n    hoist: {{torque: {TORQUE}}}\n"
        ref, dofs = exact_peak(_scene(tmp, "ref", MODEL, effects, base), duration)

        def add(method, corr, k, h_text, name):
            model = _scene(tmp, name, MODEL, effects, base + h_text)
            r, sec = _timed(model, repeat)
            rows.append({"case": "hoist_start", "method": method, "static_correction":
                         corr, "modes": k, "time_step_s": r.time_step, "dofs": r.dofs,
                         "peak_force_N": float(r.rope_force_max[0]), "reference_N": ref,
                         "error": abs(float(r.rope_force_max[0]) / ref - 1),
                         "lift_off_error": "", "time_s": sec})

        for h in steps:
            add("direct", "", dofs, f"  time_step: {h}\n", f"d{h}")
        add("direct auto step", "", dofs, "", "dauto")
        for k in counts:
            for corr in ("true", "false"):
                add("modal", corr, k, f"  method: modal\n  modes: {k}\n  time_step: {fine}\n"
                    f"  static_correction: {corr}\n", f"m{k}{corr}")
            add("modal auto step", "true", k, f"  method: modal\n  modes: {k}\n",
                f"a{k}")

        text, ex = cases.hoist_lift_off(drum_speed=2.0)
        mpath = os.path.join(tmp, "case.yaml")
        with open(mpath, "w") as fh:
            fh.write(text)
        for h in ((0.02, 0.005) if quick else (0.05, 0.02, 0.01, 0.005, 0.002, 0.001)):
            model = _scene(tmp, f"l{h}", mpath, "{sway: false}",
                           f"  duration: 0.8\n  time_step: {h}\n  initial: grounded\n"
                           "  drums:\n    hoist: {speed: 2.0}\n")
            r, sec = _timed(model, repeat)
            rows.append({"case": "lift_off", "method": "direct", "static_correction": "",
                         "modes": r.dofs, "time_step_s": h, "dofs": r.dofs,
                         "peak_force_N": float(r.rope_force_max[0]),
                         "reference_N": float(ex["peak"]),
                         "error": abs(float(r.dynamic_factor[0]) / ex["dynamic_factor"] - 1),
                         "lift_off_error": abs(r.lift_off_time / ex["lift_off_time"] - 1),
                         "time_s": sec})
    path = write_csv(outdir, "transient_cost.csv", rows, KEYS)
    return [path, _plot(outdir, rows, elements, dofs), phi2_table(outdir, quick)]


def _falls(model, hook):
    """Drum radius over hook falls: hook speed per drum speed (from the rope row)."""
    from ..system import assemble
    s = assemble(model)
    d = s.dofs
    R = s.springs.R @ d.T
    z = d.labels.index(f"node {hook} z")
    drum = d.labels.index("drum hoist")
    row = int(np.argmax(np.abs(R[:, z].toarray().ravel())))
    return abs(R[row, drum] / R[row, z])


def phi2_table(outdir, quick=False):
    """results/transient_phi2.csv: computed phi2 of the example cranes and EN 13001-2's
    for the four hoisting classes."""
    speeds = (0.5,) if quick else (0.125, 0.25, 0.5, 1.0)
    root = os.path.dirname(MODEL)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, hook in CRANES[:1] if quick else CRANES:
            path = os.path.join(root, name)
            ratio = None
            for v in speeds:
                row = {"crane": name[:-5], "hook_speed_m_s": v}
                for drive, ramp in (("rigid", ""), ("ramped", f", ramp: {RAMP}")):
                    if ratio is None:
                        ratio = _falls(_scene(tmp, "probe", path, "{sway: false}",
                                              "  duration: 1\n"), hook)
                    w = v / ratio
                    model = _scene(tmp, f"{name}{v}{drive}", path, "{sway: false}",
                                   f"  duration: {6.0 + RAMP}\n  time_step: 0.002\n"
                                   f"  initial: grounded\n  drums:\n"
                                   f"    hoist: {{speed: {w:.9g}{ramp}}}\n")
                    r, _ = _timed(model)
                    k = list(r.rope_names).index(next(
                        n for n in r.rope_names if "hoist" in n))
                    row[f"phi2_{drive}"] = float(r.dynamic_factor[k])
                    row["lift_off_s" if drive == "rigid" else "lift_off_ramped_s"] = \
                        float(r.lift_off_time)
                for c, (b, p0) in HOISTING_CLASSES.items():   # beta2, phi2,min
                    row[f"EN_{c}"] = p0 + b * v
                rows.append(row)
    return write_csv(outdir, "transient_phi2.csv", rows)


def _plot(outdir, rows, elements, dofs):
    plt = pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.8))
    floor = 1e-14

    def pick(**kw):
        return [r for r in rows if all(r[k] == v for k, v in kw.items())]

    d = pick(case="hoist_start", method="direct")
    lo = pick(case="lift_off")
    ax = axes[0]
    h = np.array([r["time_step_s"] for r in d])
    ax.loglog(h, [max(r["error"], floor) for r in d], "o-",
              label=f"hoist start, direct ({dofs} coordinates)")
    ax.loglog([r["time_step_s"] for r in lo], [max(r["error"], floor) for r in lo], "s-",
              label="lift-off, dynamic factor (closed form)")
    a = pick(case="hoist_start", method="direct auto step")
    ax.loglog([r["time_step_s"] for r in a], [max(r["error"], floor) for r in a], "*",
              ms=12, label="hoist start, direct, automatic step")
    if len(h) > 1:
        ax.loglog(h, d[-1]["error"] * (h / h[-1]) ** 2, "k:", lw=0.8, label="slope 2")
    hl = np.array([r["time_step_s"] for r in lo])
    if len(hl) > 1:
        ax.loglog(hl, lo[0]["error"] * (hl / hl[0]) ** 4, "k--", lw=0.8, label="slope 4")
    ax.set_xlabel("time step [s]")
    ax.set_title("direct integration (Newmark, average acceleration)")
    ax = axes[1]
    for method, corr, style, lab in (("modal", "true", "o-", "static correction, fine step"),
                                     ("modal", "false", "s--", "no correction, fine step"),
                                     ("modal auto step", "true", "^-",
                                      "static correction, automatic step")):
        m = pick(case="hoist_start", method=method, static_correction=corr)
        ax.semilogy([r["modes"] for r in m], [max(r["error"], floor) for r in m], style,
                    label=lab)
    ax.set_xlabel("retained elastic modes (the rigid drive motion always kept)")
    ax.set_title(f"modal superposition, rope with {elements} elements per fall")
    ax = axes[2]
    for method, corr, style, lab in (("direct", "", "o", "direct, fixed steps"),
                                     ("direct auto step", "", "*", "direct, automatic step"),
                                     ("modal", "true", "s", "modal, fine step"),
                                     ("modal auto step", "true", "^", "modal, automatic step")):
        m = pick(case="hoist_start", method=method, static_correction=corr)
        ax.loglog([r["time_s"] for r in m], [max(r["error"], floor) for r in m], style,
                  label=lab)
    ax.set_xlabel("computing time [s]")
    ax.set_title("error against cost (hoist start)")
    for ax in axes:
        ax.set_ylabel("relative error of the peak rope force")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Transient accuracy against exact answers (closed-form principal "
                 "coordinates; closed-form lift-off)")
    return save(fig, outdir, "transient_cost.png")
