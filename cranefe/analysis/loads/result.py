"""The result of `cranefe loads`: the factors, the simulations they came from, and
their presentation as a load table (docs/loads.md, "Output")."""

from dataclasses import dataclass, field

import numpy as np

from ..jsonable import num, timings


def _clean(x):
    """JSON-ready copy: finite floats or None, tuples as lists."""
    if isinstance(x, dict):
        return {str(k): _clean(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_clean(v) for v in x]
    if isinstance(x, (bool, str)) or x is None:
        return x
    if isinstance(x, (int, np.integer)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        return num(x)
    return x


def _deg(x):
    return "      --" if x is None else f"{x:8.4f}"


@dataclass
class LoadsResult:
    """Dynamic factors of EN 13001-2 computed from simulations of one crane."""

    model_name: str
    scene: str
    file: str
    spec: object                   # the checked LoadsSpec
    hook_per_drum: float           # m of hook travel per rad of the hoist drum
    factors: dict                  # phi1 ... phi7 (docs/loads.md, "Output")
    simulations: tuple             # runs.Trace
    assumed: tuple                 # what was taken as default
    warnings: tuple = ()
    timings: dict = field(default_factory=dict)
    status: int = 0
    message: str = "ok"
    shapers: dict = field(default_factory=dict)   # JOINT -> {NAME: {...}} (--shapers)

    def to_dict(self):
        """The JSON document of ``cranefe loads --json``."""
        s = self.spec
        return _clean({
            "model": self.model_name, "scene": self.scene, "analysis": "loads",
            "hoist": {"drum": s.drum, "loads": list(s.loads), "speed_m_s": s.speed,
                      "creep_m_s": s.creep, "ramp_s": s.ramp,
                      "hook_per_drum_m_rad": self.hook_per_drum},
            "working_point": {"radius_m": s.radius, "radius_nodes": list(s.radius_nodes),
                              "hook_height_m": s.hook_height},
            "factors": self.factors,
            **({"shapers": self.shapers} if self.shapers else {}),
            "simulations": [t.to_dict() for t in self.simulations],
            "assumed": list(self.assumed), "warnings": list(self.warnings),
            "timings_s": timings(self.timings), "status": self.status,
            "message": self.message})

    def rows(self):
        """(factor, case, computed, standard, from) rows of the load table (the factors
        present: `only=` reports a part)."""
        f = self.factors
        out = []
        if "phi2" in f:
            p2 = f["phi2"]
            for hd, p in p2["drive_classes"].items():
                out.append(("phi2", f"{hd}, v_h = {p['v_h_m_s']:.3g} m/s", p["value"],
                            p["standard"][p2["hoisting_class"]],
                            f"{p['simulation']} (peak {p['peak_time_s']:.3f} s)"))
            out.append(("phi2 class", "behaves like", None, None,
                        f"within {p2['behaves_like']['within'] or 'none (above HC4)'}, "
                        f"closest {p2['behaves_like']['closest']}"))
        if "phi1" in f:
            p1 = f["phi1"]
            out.append(("phi1", f"lift-off, {p1.get('mass', 'rigid crane')}", p1["value"],
                        p1["standard"], p1["simulation"] +
                        (f" (peak {p1['peak_time_s']:.3f} s)" if "peak_time_s" in p1
                         else "")))
        if "phi3" in f:
            p3 = f["phi3"]
            out.append(("phi3", f"dm/m = {p3['dm_over_m']:g}, release in "
                        f"{p3['release_time_s']:g} s", p3["value"], p3["standard"],
                        f"{p3['simulation']} (lowest {p3['peak_time_s']:.3f} s), "
                        f"beta3 = {p3['beta3_equivalent']:.3f}"))
        for name, p in f.get("phi5", {}).items():
            out.append(("phi5", f"{name}, ramp {p['ramp_s']:g} s", p["value"],
                        "{:g}-{:g}".format(*p["standard"]),
                        f"{p['simulation']} (peak {p['peak_time_s']:.3f} s)"))
        if "phi6" in f:
            p6 = f["phi6"]
            out.append(("phi6", "dynamic test", p6["value"], p6["standard"],
                        "0.5 (1 + phi2)"))
        if "phi4" in f:
            out.append(("phi4", "uneven track", None, None, "not in the model"))
        if "phi7" in f:
            out.append(("phi7", "buffer", None, "1.25-1.6", "not in the model"))
        return out

    def table(self):
        """Human-readable load table."""
        s = self.spec
        lines = [f"{self.scene or self.model_name}: dynamic factors (EN 13001-2) from "
                 f"{len(self.simulations)} simulations",
                 f"  hoist drum {s.drum}, load {', '.join(s.loads)}: full speed "
                 f"{s.speed:.4g} m/s, creep {s.creep:.4g} m/s, ramp {s.ramp:g} s",
                 f"  {'factor':<10} {'case':<34} {'computed':>9} {'EN 13001-2':>11}  from",
                 "  " + "-" * 100]
        for name, case, val, std, src in self.rows():
            v = "" if val is None else f"{val:9.4f}"
            st = "" if std is None else (f"{std:11.4f}" if isinstance(std, float)
                                         else f"{std:>11}")
            lines.append(f"  {name:<10} {case:<34} {v:>9} {st:>11}  {src}")
        for joint, rows in self.shapers.items():
            lines.append(f"  shapers on the {joint} move: residual sway, move time")
            lines += [f"    {k:<9} {_deg(r['residual_sway_deg'])} deg  "
                      f"{r['move_time_s']:8.3f} s" for k, r in rows.items()]
        lines += [f"  assumed: {a}" for a in self.assumed]
        lines += [f"  warning: {w}" for w in self.warnings]
        return "\n".join(lines)
