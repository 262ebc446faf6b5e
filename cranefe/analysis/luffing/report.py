"""Presentation of a luffing result: the JSON document of ``cranefe luff --json`` and the
human-readable table."""

import math

import numpy as np


def _clean(v):
    """JSON-safe copy: numpy scalars to Python, non-finite floats to None."""
    if isinstance(v, dict):
        return {str(k): _clean(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_clean(x) for x in v]
    if isinstance(v, np.ndarray):
        return _clean(v.tolist())
    if isinstance(v, (bool, np.bool_)):
        return bool(v)
    if isinstance(v, (int, np.integer)):
        return int(v)
    if isinstance(v, (float, np.floating)):
        return float(v) if math.isfinite(v) else None
    return v


def luffing_document(result):
    """``{"alpha0_rad", "alphak_rad", "t_k_s", "jib_tip_deviation_m", "optimum": {...},
    "laws": {NAME: {...}}, ...}`` (docs/luffing.md lists every key)."""
    doc = {
        "model": result.model_name,
        "scene": result.scene,
        "alpha0_rad": result.alpha0,
        "alphak_rad": result.alphak,
        "alpha0_deg": math.degrees(result.alpha0),
        "alphak_deg": math.degrees(result.alphak),
        "reach0_m": result.reach0,
        "reachk_m": result.reachk,
        "t_k_s": result.t_k,
        "load_mass_kg": result.load_mass,
        "rope_length_m": result.rope_length,
        "jib_tip_deviation_m": result.jib_tip_deviation,
        "imbalance_moment_max_Nm": result.imbalance_moment,
        "imbalance_motor_torque_max_Nm": result.imbalance_motor_torque,
        "kinematics": result.kinematics,
        "optimum": result.optimum,
        "laws": result.table,
        "collocation": result.collocation,
        "sensitivity": result.sensitivity,
        "timings_s": {k: round(v, 6) for k, v in result.timings.items()},
        "warnings": list(result.warnings),
    }
    return _clean(doc)


def luffing_table(result):
    o, k = result.optimum, result.kinematics
    lines = [
        f"{result.scene or result.model_name}: luffing alpha {math.degrees(result.alpha0):.2f}"
        f" -> {math.degrees(result.alphak):.2f} deg (reach {result.reach0:.2f} -> "
        f"{result.reachk:.2f} m) in t_k = {result.t_k:g} s; load {result.load_mass:g} kg on "
        f"{result.rope_length:g} m of rope",
        f"jib tip: {1e3 * result.jib_tip_deviation:.0f} mm from level (height "
        f"{k['tip_height_range_m'][0]:.3f}..{k['tip_height_range_m'][1]:.3f} m); drive "
        f"stroke {k['drive_stroke_m']:.3f} m; loop closure {k['loop_closure_residual']:.1e} m",
        f"counterweight: residual imbalance {result.imbalance_moment / 1e3:.1f} kN m at the "
        f"boom = {result.imbalance_motor_torque:.1f} N m at the motor; load weight on the "
        f"non-level path: up to {k['load_weight_motor_torque_max_Nm']:.1f} N m at the motor",
        "",
        f"optimum (eq. 16, {o['inertia']} inertia): T_mean = {o['T_mean_J'] / 1e3:.4f} kJ, "
        f"J alpha'^2 constant: speed jumps to {math.degrees(o['speed_start_rad_s']):.3f} "
        f"deg/s at the start and from {math.degrees(o['speed_end_rad_s']):.3f} deg/s at "
        f"the stop (motor impulse {o['motor_impulse_Nms']:.1f} N m s), coasting torque "
        f"<= {o['coasting_motor_torque_Nm']:.1f} N m",
        f"paper's eq. 3 inertia: J_paper/J = {o['J_paper_over_complete'][0]:.3f}.."
        f"{o['J_paper_over_complete'][1]:.3f}; its optimum T_mean(eq. 3) = "
        f"{o['T_mean_paper_J'] / 1e3:.4f} kJ, differs from the optimum by "
        f"{o['max_law_difference_deg']:.3f} deg and costs "
        f"{100 * o['paper_law_energy_excess']:.3f} % more",
        "",
    ]
    head = (f"{'law':<14} {'T_mean kJ':>10} {'ratio':>7} {'peak M Nm':>10} {'peak P kW':>10} "
            f"{'sway max':>9} {'residual':>9} {'lin resid':>9} {'T_load kJ':>10}")
    lines += [head, "-" * len(head)]
    for name in result.law_names:
        f = result.table[name]
        lines.append(f"{name:<14} {f['T_mean_J'] / 1e3:>10.4f} {f['T_ratio']:>7.4f} "
                     f"{f['peak_motor_torque_Nm']:>10.1f} {f['peak_power_W'] / 1e3:>10.2f} "
                     f"{f['max_sway_deg']:>8.3f}° {f['residual_sway_deg']:>8.4f}° "
                     f"{f['residual_sway_linear_deg']:>8.4f}° {f['T_load_mean_J'] / 1e3:>10.3f}")
    lines.append("(sway: nonlinear pendulum with gravity; 'lin resid': linear model; speed "
                 "jumps of optimal, linear, swing-free act as impulses, not in 'peak M')")
    c = result.collocation
    if c:
        lines.append("")
        for v in ("printed", "eq21", "corrected"):
            p = c["paper"][v]
            rho = p["spectral_radius"]
            err = math.degrees(p["error_rad"]) if p["error_rad"] is not None else math.nan
            lines.append(f"paper 3-point collocation ({v}): {p['message']}; spectral radius "
                         f"{rho:.3f}; error {err:.2e} deg")
        if "corrected_relaxed" in c["paper"]:
            p = c["paper"]["corrected_relaxed"]
            lines.append(f"  corrected, relaxed by {p['relax']:.3f}: {p['message']}")
        for kind in ("equally_spaced", "chebyshev"):
            errs = " ".join(f"{math.degrees(r['error_rad']):.1e}" for r in c[kind])
            rate = c[kind + "_rate"]
            lines.append(f"{kind.replace('_', ' ')} collocation n=2..10 error (deg): {errs}"
                         f"  [x{rate['geometric_ratio']:.3f} per point]")
        lines.append(f"solve_bvp (tol {c['solve_bvp']['tol']:g}): error "
                     f"{math.degrees(c['solve_bvp']['error_rad']):.1e} deg")
    for w in result.warnings:
        lines.append(f"warning: {w}")
    return "\n".join(lines)
