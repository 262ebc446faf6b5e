"""Presentation of results: JSON documents (design.md, "Command-line contract") and tables."""

import json
import math

import numpy as np

from ..analysis.jsonable import num as _num
from ..analysis.jsonable import timings


def modes_document(result, comparison=None):
    """The JSON document of ``cranefe modes --json``: `ModalResult.to_dict`."""
    return result.to_dict(comparison)


def dumps(doc):
    return json.dumps(doc, indent=2, allow_nan=False)


def modes_table(result, comparison=None):
    eff = ", ".join(f"{k} {_fmt_effect(v)}" for k, v in result.effects.items())
    lines = [f"{result.model_name}: {result.dofs} coordinates ({eff})"]
    if result.quasi_cyclic:
        lines.append(f"quasi-cyclic (zero-frequency) coordinates: "
                     f"{', '.join(result.quasi_cyclic)}")
    if result.massless:
        lines.append(f"massless coordinates condensed statically: {len(result.massless)}")
    head = f"{'mode':>5} {'f [Hz]':>12} {'w [rad/s]':>12} {'T [s]':>10}"
    red = {c['index']: c for c in (comparison or {}).get("modes", [])}
    if red:
        head += f" {'f coupled [Hz]':>15} {'error':>9}"
    lines += [head, "-" * len(head)]
    for i, (f, w, t, r) in enumerate(zip(result.frequency_hz, result.omega, result.period_s,
                                         result.rigid)):
        row = f"{i + 1:>5} {f:>12.5g} {w:>12.5g} {t:>10.4g}" if not r else \
            f"{i + 1:>5} {0:>12.5g} {0:>12.5g} {'inf':>10}  rigid (quasi-cyclic)"
        if i + 1 in red:
            c = red[i + 1]
            row += f" {c['frequency_hz_coupled']:>15.5g} {100 * c['relative_error']:>8.3f}%"
        lines.append(row)
    for w in result.warnings:
        lines.append(f"warning: {w}")
    return "\n".join(lines)


def _fmt_effect(v):
    return {True: "on", False: "off"}.get(v, v) if isinstance(v, bool) else str(v)


def damping_document(result, modal=None):
    """The JSON document of ``cranefe damping --json`` (design.md, command-line contract)."""
    modes = []
    for k in range(len(result.omega)):
        m = {"index": k + 1, "frequency_hz": _num(result.omega[k] / (2 * math.pi)),
             "omega_rad_s": _num(result.omega[k]),
             "damping_ratio": _num(result.zeta[k]),
             "damped_frequency_hz": _num(result.damped_omega[k] / (2 * math.pi)),
             "log_decrement": _num(result.log_decrement[k]),
             "coupling": _num(result.coupling[k]),
             "weak_coupling": bool(result.criterion_holds[k])}
        if result.exact_zeta is not None:
            m["exact"] = {"damping_ratio": _num(result.exact_zeta[k]),
                          "damped_frequency_hz":
                              _num(result.exact_damped_omega[k] / (2 * math.pi))}
            m["hysteretic"] = {"damping_ratio": _num(result.hysteretic_zeta[k]),
                               "damped_frequency_hz":
                                   _num(result.hysteretic_damped_omega[k] / (2 * math.pi))}
        modes.append(m)
    return {"model": result.model_name, "effects": result.effects, "method": result.method,
            "dofs": modal.dofs if modal is not None else None,
            "quasi_cyclic": list(modal.quasi_cyclic) if modal is not None else [],
            "modes": modes, "timings_s": timings(result.timings),
            "warnings": list(result.warnings)}


def damping_table(result):
    exact = result.exact_zeta is not None
    head = (f"{'mode':>5} {'f [Hz]':>10} {'zeta':>9} {'f_d [Hz]':>10} {'log dec':>8} "
            f"{'coupling':>9}")
    if exact:
        head += f" {'zeta exact':>11} {'error':>8} {'zeta hyst.':>11} {'error':>8}"
    lines = [f"{result.model_name}: damping from absorption coefficients "
             f"(method {result.method}; decoupled estimate, Hasselman)", head,
             "-" * len(head)]
    for k in range(len(result.omega)):
        row = (f"{k + 1:>5} {result.omega[k] / (2 * math.pi):>10.5g} {result.zeta[k]:>9.4g} "
               f"{result.damped_omega[k] / (2 * math.pi):>10.5g} "
               f"{result.log_decrement[k]:>8.4g} {result.coupling[k]:>9.2g}")
        if exact:
            ze, zh = result.exact_zeta[k], result.hysteretic_zeta[k]
            rel = (lambda a, b: (a / b - 1) if b else 0.0)
            row += (f" {ze:>11.4g} {100 * rel(result.zeta[k], ze):>7.2f}% {zh:>11.4g} "
                    f"{100 * rel(result.zeta[k], zh):>7.2f}%")
        lines.append(row)
    lines += [f"warning: {w}" for w in result.warnings]
    return "\n".join(lines)



def damping_modes_document(result):
    """The JSON document of ``cranefe damping --json``: `DampingResult.to_dict`."""
    return result.to_dict()


def damping_modes_table(result):
    """The table of ``cranefe damping``: per mode the decoupled estimate, the coupling
    figure and, where solved, the exact ratios and the estimate's error against them."""
    from ..analysis.damping import KAPPA
    exact = result.exact_zeta is not None
    eff = ", ".join(f"{k} {_fmt_effect(v)}" for k, v in result.effects.items())
    lines = [f"{result.model_name}: {result.dofs} coordinates ({eff})",
             f"damping from absorption coefficients, method {result.method}: decoupled "
             f"estimate (Heletiy eq. 16-17), Hasselman coupling (limit {KAPPA:g})"]
    if result.quasi_cyclic:
        lines.append("quasi-cyclic (zero-frequency) coordinates: "
                     + ", ".join(result.quasi_cyclic))
    head = (f"{'mode':>5} {'f [Hz]':>10} {'zeta':>10} {'f_d [Hz]':>10} {'log dec':>9} "
            f"{'coupling':>13}")
    if exact:
        head += f" {'zeta exact':>11} {'error':>8} {'zeta hyst.':>11} {'error':>8}"
    lines += [head, "-" * len(head)]
    err_v, err_h = result.error_viscous, result.error_hysteretic

    def pct(e):
        return f"{'-':>8}" if e is None or not np.isfinite(e) else f"{100 * e:>7.2f}%"
    for k in range(len(result.omega)):
        f = result.omega[k] / (2 * math.pi)
        if result.rigid[k]:
            lines.append(f"{k + 1:>5} {0:>10.5g} {'-':>10} {'-':>10} {'-':>9} {'-':>13}  "
                         "rigid (quasi-cyclic): no element deforms, no damping")
            continue
        j = result.coupled_with[k]
        cpl = f"{result.coupling[k]:.2g}" + (f" ({j + 1})" if j >= 0 else "")
        flag = "" if result.criterion_holds[k] else " !"
        row = (f"{k + 1:>5} {f:>10.5g} {result.zeta[k]:>10.4g} "
               f"{result.damped_omega[k] / (2 * math.pi):>10.5g} "
               f"{result.log_decrement[k]:>9.4g} {cpl + flag:>13}")
        if exact and not np.isnan(result.exact_zeta[k]):
            row += (f" {result.exact_zeta[k]:>11.4g} {pct(err_v[k])} "
                    f"{result.hysteretic_zeta[k]:>11.4g} {pct(err_h[k])}")
        lines.append(row)
    t = result.timings
    cost = f"time: modes {t.get('modes', 0):.3g} s, decoupled {t.get('decoupled', 0):.3g} s"
    if "exact_viscous" in t:
        cost += (f", exact viscous {t['exact_viscous']:.3g} s, complex stiffness "
                 f"{t['hysteretic']:.3g} s")
    lines.append(cost)
    lines += [f"warning: {w}" for w in result.warnings]
    return "\n".join(lines)
