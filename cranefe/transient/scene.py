"""The keys of a transient scene (`analysis: {type: transient, ...}`; docs/transient.md)."""

from dataclasses import dataclass

import numpy as np

from ..model.load import _Reader

KEYS = {"type", "duration", "time_step", "method", "modes", "initial", "drums",
        "output_step"}


@dataclass(frozen=True)
class DrumLoad:
    drum: int                 # index in model.drums
    kind: str                 # speed | torque | table | motor
    value: float = 0.0        # speed (rad/s) or torque (N m) at the drum
    table: np.ndarray = None  # (k, 2) times and torques
    stall_torque: float = 0.0     # motor: N m at the motor shaft, at standstill
    synchronous_speed: float = 0.0  # motor: rad/s at the motor shaft, no torque

    def torque(self, t, speed, gear_ratio):
        """Drum torque at time t and drum speed (kinds torque, table, motor)."""
        if self.kind == "torque":
            return self.value
        if self.kind == "table":
            return float(np.interp(t, self.table[:, 0], self.table[:, 1]))
        motor_speed = gear_ratio * speed     # linear characteristic stall -> synchronous
        return gear_ratio * self.stall_torque * (1 - motor_speed / self.synchronous_speed)


@dataclass(frozen=True)
class Transient:
    duration: float
    time_step: float          # None: automatic
    method: str               # direct | modal
    modes: int
    initial: str              # static | grounded
    drums: tuple              # DrumLoad
    output_step: float        # None: every step


def parse(model):
    """The transient analysis of a scene, checked (errors name the scene entry)."""
    a = model.analysis
    r = _Reader(model.scene_file or model.file)
    r.keys(a, "analysis", KEYS)
    duration = r.number(a.get("duration", 2.0), "analysis.duration", positive=True)
    dt = r.number(a["time_step"], "analysis.time_step", positive=True) \
        if "time_step" in a else None
    method = a.get("method", "direct")
    if method not in ("direct", "modal"):
        r.fail("analysis.method", f"{method!r} is not direct or modal")
    modes = r.integer(a.get("modes", 20), "analysis.modes", minimum=1)
    initial = a.get("initial", "static")
    if initial not in ("static", "grounded"):
        r.fail("analysis.initial", f"{initial!r} is not static or grounded")
    if initial == "grounded" and model.effects.sway:
        r.fail("analysis.initial", "a load resting on the ground has no pendulum stiffness: "
               "use initial: grounded with effects: {sway: false}")
    if initial == "grounded" and method == "modal":
        r.fail("analysis.method", "lift-off is an event of the direct integration; use "
               "method: direct with initial: grounded")
    names = {d.name: i for i, d in enumerate(model.drums)}
    drums = []
    for name, spec in r.mapping(a.get("drums"), "analysis.drums").items():
        e = f"analysis.drums.{name}"
        if name not in names:
            r.fail(e, f"unknown drum '{name}'; drums: {', '.join(names) or 'none'}")
        r.keys(spec, e, {"speed", "torque", "motor"})
        if len(spec) != 1:
            r.fail(e, "give one of speed (rad/s), torque (N m or a table [[t, M], ...]) or "
                   "motor {stall_torque, synchronous_speed}")
        d = names[name]
        if "speed" in spec:
            drums.append(DrumLoad(d, "speed", r.number(spec["speed"], f"{e}.speed")))
        elif "torque" in spec and isinstance(spec["torque"], list):
            rows = r.listing(spec["torque"], f"{e}.torque", min_len=1)
            table = np.array([r.vector(p, f"{e}.torque[{k}]", 2) for k, p in enumerate(rows)])
            if np.any(np.diff(table[:, 0]) <= 0):
                r.fail(f"{e}.torque", "times must increase")
            drums.append(DrumLoad(d, "table", table=table))
        elif "torque" in spec:
            drums.append(DrumLoad(d, "torque", r.number(spec["torque"], f"{e}.torque")))
        else:
            m = spec["motor"]
            r.keys(m, f"{e}.motor", {"stall_torque", "synchronous_speed"},
                   required=("stall_torque", "synchronous_speed"))
            drums.append(DrumLoad(d, "motor", stall_torque=r.number(
                m["stall_torque"], f"{e}.motor.stall_torque", positive=True),
                synchronous_speed=r.number(m["synchronous_speed"],
                                           f"{e}.motor.synchronous_speed", positive=True)))
        if model.drums[d].brake or model.effects.drive != "coupled":
            r.fail(e, "a driven drum must turn: brake: false and effects: {drive: coupled}")
    out = r.number(a["output_step"], "analysis.output_step", positive=True) \
        if "output_step" in a else None
    return Transient(duration, dt, method, modes, initial, tuple(drums), out)
