"""The keys of an operation scene, checked (`analysis: {type: operation, ...}`).

The model loader accepts `type: operation` and forwards its keys; every check and every
message about them lives here (docs/operations.md lists the keys). Errors are
`ModelError(message, scene file, entry)` with entries such as
``analysis.drives.trolley.profile.v_max``.
"""

from dataclasses import dataclass

import numpy as np

from ...errors import ModelError
from ...model import units
from ...model.load import _Reader
from ..transient.scene import Motor, Profile, _motor, _profile
from . import profiles

KEYS = {"type", "duration", "tolerance", "max_step", "output_step", "drives", "initial"}
DEFAULT_TOLERANCE = 1e-7       # local error per step, relative to the model's size
PROFILE_KEYS = {
    "trapezoid": ({"distance", "v_max"}, {"a_max", "ramp", "start"}),
    "s_curve": ({"distance", "v_max", "a_max", "j_max"}, {"start"}),
    "table": ({"speed"}, set()),
}
ANGLE_KEYS = {"distance", "v_max", "a_max", "j_max", "speed"}   # _deg variants on hinges
UNITS = {"drum": ("rad", "rad/s"), "hinge": ("rad", "rad/s"), "slider": ("m", "m/s"),
         "linear": ("m", "m/s")}


@dataclass(frozen=True)
class Drive:
    """What moves one drum or joint (docs/operations.md, "Drives")."""

    name: str
    target: str               # drum | hinge | slider
    index: int                # into model.drums or model.joints
    kind: str                 # profile | torque | motor
    motion: profiles.Motion = None   # profile: position (rad or m) against time
    torque: Profile = None    # torque: N m at the drum against time
    motor: Motor = None
    entry: str = ""
    gear_ratio: float = 1.0   # joint motor: motor speed per joint speed (rad/rad, rad/m)
    rotor_inertia: float = 0.0  # joint motor: kg m^2 at motor speed

    @property
    def coordinate(self):
        """The joint's position is a coordinate of the equations of motion (a torque,
        force, motor or free joint; drums: torque or motor)."""
        return self.kind != "profile"

    @property
    def units(self):
        return UNITS[self.target]


@dataclass(frozen=True)
class Operation:
    duration: float
    tolerance: float          # local position error per step, relative to the model size
    max_step: float
    output_step: float
    drives: tuple             # Drive

    @property
    def breakpoints(self):
        """Times where a prescribed motion's acceleration or jerk jumps (steps end
        there), and where torque tables have kinks."""
        ts = [d.motion.breakpoints for d in self.drives if d.motion is not None]
        ts += [d.torque.breakpoints for d in self.drives if d.torque is not None]
        t = np.unique(np.concatenate(ts)) if ts else np.zeros(0)
        return t[(t > 0) & (t < self.duration)]

    @property
    def motion_end(self):
        """When the last prescribed drive stops (0 if none moves; inf if one never stops)."""
        ends = [d.motion.end for d in self.drives if d.motion is not None]
        return max(ends) if ends else 0.0

    def late_drives(self):
        """Warnings for prescribed drives whose every move starts at or after the end of
        the run (a shortened cycle: they do nothing in it)."""
        out = []
        for d in self.drives:
            moves = d.motion.moves() if d.motion is not None else []
            if moves and all(a >= self.duration for a, _ in moves):
                out.append(f"drive '{d.name}' starts moving at t = {moves[0][0]:g} s, at "
                           f"or after the end of the run ({self.duration:g} s): it does "
                           "nothing in this run")
        return out


def parse(model):
    """The operation analysis of a scene `model`, checked."""
    a = model.analysis
    file = model.scene_file or model.file
    r = _Reader(file)
    r.keys(a, "analysis", KEYS, required=("duration",))
    if a.get("type") != "operation":
        r.fail("analysis.type", "this is not an operation scene: give analysis: {type: "
               "operation, duration: ..., drives: {...}} (docs/operations.md)")
    duration = r.number(a["duration"], "analysis.duration", positive=True)
    tol = r.number(a.get("tolerance", DEFAULT_TOLERANCE), "analysis.tolerance",
                   positive=True)
    if tol >= 1e-2:
        r.fail("analysis.tolerance", f"{tol:g} is not a small relative error; give e.g. "
               "1e-7 (the default)")
    max_step = r.number(a.get("max_step", min(duration / 50, 0.5)), "analysis.max_step",
                        positive=True)
    out = r.number(a.get("output_step", duration / 1000), "analysis.output_step",
                   positive=True)
    if a.get("initial", "static") != "static":
        r.fail("analysis.initial", f"{a['initial']!r}: an operation starts from the static "
               "state of the model's geometry (initial: static)")
    raw = a.get("drives", {}) or {}
    if not isinstance(raw, dict):
        r.fail("analysis.drives", "must be a mapping: drive name -> {drum: NAME, profile: "
               "{...}} or {slider: JOINT, profile: {...}} or {hinge: JOINT, profile: {...}}")
    drives = tuple(_drive(model, r, str(name), spec, duration)
                   for name, spec in raw.items())
    seen = {}
    for d in drives:
        key = (d.target if d.target in ("drum", "linear") else "joint", d.index)
        if key in seen:
            r.fail(d.entry, f"drives the same {d.target} as drive '{seen[key]}'; give one "
                   "drive per drum or joint")
        seen[key] = d.name
    from .shaped import apply      # shaped moves (docs/shaping.md)
    return apply(model, r, raw, Operation(duration, tol, max_step, out, drives), _motion,
                 _check_travel)


def _joint_by_name(model, r, name, e):
    for k, j in enumerate(model.joints):
        if j.name == name or j.entry == name:
            return k, j
    names = [j.name or j.entry for j in model.joints]
    r.fail(e, f"unknown joint '{name}'; joints of the model: {', '.join(names) or 'none'} "
           "(name a joint in the model with name: ...)")


def _drive(model, r, name, spec, duration):
    """One entry of `drives`. Drums: profile | torque | motor; hinges: profile | torque |
    motor | free; sliders: profile | force | motor | free (docs/operations.md).

    Length: one check per key of the three kinds of target, in the order of the docs.
    """
    e = f"analysis.drives.{name}"
    if not isinstance(spec, dict):
        r.fail(e, "must be a mapping such as {drum: NAME, profile: {...}} or {hinge: "
               "JOINT, torque: ...}")
    r.keys(spec, e, {"drum", "hinge", "slider", "linear", "profile", "torque", "force",
                     "motor", "ramp", "free", "gear_ratio", "rotor_inertia"})
    targets = [k for k in ("drum", "hinge", "slider", "linear") if k in spec]
    if len(targets) != 1:
        r.fail(e, "say what the drive moves: exactly one of drum: NAME, hinge: JOINT "
               "(slewing, luffing), slider: JOINT (trolley travel) or linear: NAME (a "
               "luffing cylinder or rack of the model's linear_drives)")
    target = targets[0]
    if target == "linear":
        return _linear(model, r, name, spec, e)
    load_key = "force" if target == "slider" else "torque"
    wrong = "torque" if target == "slider" else "force"
    if wrong in spec:
        r.fail(f"{e}.{wrong}", f"a {target} is driven by a {load_key} ({'N' if target == 'slider' else 'N m'}); "
               f"write {load_key}: ...")
    if "free" in spec and (target == "drum" or spec["free"] is not True):
        r.fail(f"{e}.free", "free: true (a joint turned or moved only by the forces on "
               "it, e.g. a jib held by its luffing rope) belongs to a hinge or a slider")
    kinds = [k for k in ("profile", load_key, "motor", "free") if k in spec]
    if len(kinds) != 1:
        r.fail(e, f"give exactly one of profile: {{type: trapezoid|s_curve|table, ...}}, "
               f"{load_key}: ..., motor: {{...}}" + (" or free: true" if target != "drum"
                                                    else "") + " (docs/operations.md)")
    kind = kinds[0]
    if "ramp" in spec and kind != load_key:
        r.fail(f"{e}.ramp", f"ramp belongs to a {load_key}; a profile has its own ramps")
    for k in ("gear_ratio", "rotor_inertia"):
        if k in spec and (kind != "motor" or target == "drum"):
            r.fail(f"{e}.{k}", f"{k} belongs to the motor of a joint drive (a drum's "
                   "gear and rotor are in the model's drums entry)")
    if target == "drum":
        names = {d.name: i for i, d in enumerate(model.drums)}
        dname = spec["drum"]
        if dname not in names:
            r.fail(f"{e}.drum", f"unknown drum '{dname}'; drums of the model: "
                   f"{', '.join(names) or 'none'}")
        index = names[dname]
    else:
        index, joint = _joint_by_name(model, r, spec[target], f"{e}.{target}")
        if joint.type != target:
            what = "turns (slewing, luffing)" if target == "hinge" else \
                "slides (trolley travel)"
            r.fail(f"{e}.{target}", f"joint '{spec[target]}' ({joint.entry}) is a "
                   f"{joint.type} joint, not a {target}: a {target} drive {what}; name a "
                   f"{target} joint or use {joint.type if joint.type in ('hinge', 'slider') else 'another'}: ...")
    if kind == load_key:
        ramp = r.number(spec["ramp"], f"{e}.ramp", nonneg=True) if "ramp" in spec else None
        return Drive(name, target, index, "torque",
                     torque=_profile(r, spec[load_key], f"{e}.{load_key}", 1, ramp),
                     entry=e)
    if kind == "free":
        return Drive(name, target, index, "free", entry=e)
    if kind == "motor":
        gear = r.number(spec.get("gear_ratio", 1.0), f"{e}.gear_ratio", positive=True)
        rotor = r.number(spec.get("rotor_inertia", 0.0), f"{e}.rotor_inertia",
                         nonneg=True)
        return Drive(name, target, index, "motor",
                     motor=_motor(r, spec["motor"], f"{e}.motor"), entry=e,
                     gear_ratio=gear, rotor_inertia=rotor)
    radius = model.drums[index].radius if target == "drum" else None
    motion = _moves(r, spec["profile"], f"{e}.profile", target, radius)
    drive = Drive(name, target, index, "profile", motion=motion, entry=e)
    _check_travel(model, r, drive, duration)
    return drive


def _moves(r, raw, e, target, radius=None):
    """The motion of a prescribed drive: one profile, or a list of trapezoid and s_curve
    moves one after the other (each starting when the previous one has ended)."""
    if not isinstance(raw, list):
        return _motion(r, raw, e, target, radius)
    if not raw:
        r.fail(e, "an empty list of moves; give one or more profiles")
    moves = [_motion(r, p, f"{e}[{k}]", target, radius) for k, p in enumerate(raw)]
    for k, mv in enumerate(moves):
        if mv.kind == "table" and len(moves) > 1:
            r.fail(f"{e}[{k}]", "a speed table gives the whole history; list only "
                   "trapezoid and s_curve moves, or give one table")
    for k in range(1, len(moves)):
        if moves[k].t[0] < moves[k - 1].t[-1] - 1e-12:
            r.fail(f"{e}[{k}].start", f"starts at {moves[k].t[0]:g} s, before the "
                   f"previous move ends ({moves[k - 1].t[-1]:.6g} s); start it later")
    return profiles.combine(moves)


def _linear(model, r, name, spec, e):
    """A linear drive (luffing cylinder, rack) whose length follows a profile (m)."""
    names = [d.name for d in model.linear_drives]
    if spec["linear"] not in names:
        r.fail(f"{e}.linear", f"unknown linear drive '{spec['linear']}'; linear_drives of "
               f"the model: {', '.join(names) or 'none'}")
    extra = set(spec) - {"linear", "profile"}
    if extra or "profile" not in spec:
        r.fail(f"{e}.{sorted(extra)[0]}" if extra else e, "a linear drive follows a "
               "profile of its length change (m): give profile: {...} only")
    motion = _moves(r, spec["profile"], f"{e}.profile", "linear")
    drive = Drive(name, "linear", names.index(spec["linear"]), "profile", motion=motion,
                  entry=e)
    return drive


# the SI unit of each profile key by the order of its derivative, for targets moved in
# metres (slider, linear drive) or radians (hinge, drum); a drum also takes rope units,
# turned into drum angles by its radius (docs/operations.md, "Units of profile numbers")
ORDER = {"distance": 0, "v_max": 1, "speed": 1, "a_max": 2, "j_max": 3}
LINEAR_UNITS = ("m", "m/s", "m/s^2", "m/s^3")
ANGLE_UNITS = ("rad", "rad/s", "rad/s^2", "rad/s^3")
_WHAT = {("m", 0): "a length", ("m", 1): "a speed", ("m", 2): "an acceleration",
         ("m", 3): "a jerk", ("rad", 0): "an angle", ("rad", 1): "an angular speed",
         ("rad", 2): "an angular acceleration", ("rad", 3): "an angular jerk",
         ("s", 0): "a time"}


def _value(r, v, e, key, target, radius=None, scale=1.0, **kw):
    """One profile number at entry `e`: a plain number (SI, times `scale` for the _deg
    keys) or a quantity of the dimension the target needs (a slider's distance a length,
    a hinge's an angle, a drum's an angle or a rope length by its radius, ...); a
    quantity of another dimension is a ModelError naming both."""
    if not (isinstance(v, str) and units.has_unit(v)):
        return r.number(v, e, **kw) * scale
    order = ORDER[key]
    metres = target in ("slider", "linear")
    want = (LINEAR_UNITS if metres else ANGLE_UNITS)[order]
    x = first = None
    try:
        x = units.convert(v, e, r.file, unit=want)
    except ModelError as exc:
        first = exc
    if x is None and radius is not None:    # a drum: rope length (rate) over the radius
        try:
            x = units.convert(v, e, r.file, unit=LINEAR_UNITS[order]) / radius
        except ModelError:
            pass
    if x is not None:
        return r.number(x, e, **kw)
    found = None
    for u, k in [(LINEAR_UNITS[k], k) for k in range(4)] + \
            [(ANGLE_UNITS[k], k) for k in range(4)] + [("s", 0)]:
        try:
            units.convert(v, e, r.file, unit=u)
        except ModelError:
            continue
        found = _WHAT[(u.split("/")[0] if "/" in u else u, k)]
        break
    if found is None:                   # what else it is, for the message
        found = units.what(v, e, r.file)
    if found is None:
        raise first
    need = _WHAT[("m" if metres else "rad", order)]
    also = f" or a rope {_WHAT[('m', order)].split(' ', 1)[1]} ({LINEAR_UNITS[order]}, " \
        "turned into the drum's by its radius)" if radius is not None else ""
    r.fail(e, f"{v.strip()} is {found}, but {key} of a {target} drive is {need} "
           f"({want}){also}; give it in such a unit (docs/operations.md)")


def _motion(r, p, e, target, radius=None):
    """One move of a prescribed drive (metres for a slider or linear drive, radians for
    a hinge or drum); every number may carry a unit of the target's dimension."""
    if not isinstance(p, dict):
        r.fail(e, "must be a mapping such as {type: trapezoid, distance: 15, v_max: 0.5, "
               "a_max: 0.25}")
    angles = target == "hinge"
    kind = p.get("type")
    if kind not in PROFILE_KEYS:
        r.fail(f"{e}.type", f"{kind!r} is not one of {', '.join(PROFILE_KEYS)}")
    need, optional = PROFILE_KEYS[kind]
    allowed = {"type", "shaper"} | need | optional     # shaper: analysis/operation/shaped.py
    if angles:
        allowed |= {f"{k}_deg" for k in (need | optional) & ANGLE_KEYS}
    r.keys(p, e, allowed)
    v = {}
    for k in need | optional:
        given = [x for x in (k, f"{k}_deg") if x in p]
        if len(given) > 1:
            r.fail(f"{e}.{k}", f"give {k} or {k}_deg, not both")
        if not given:
            if k in need:
                r.fail(e, f"missing required key '{k}'" + (f" (or '{k}_deg')"
                                                           if angles and k in ANGLE_KEYS
                                                           else "") + "; add it")
            continue
        key = given[0]
        scale = np.pi / 180 if key.endswith("_deg") else 1.0
        if k == "speed":
            rows = r.listing(p[key], f"{e}.{key}", min_len=1)
            table = []
            for i, x in enumerate(rows):
                ei = f"{e}.{key}[{i}]"
                if not isinstance(x, (list, tuple)) or len(x) != 2:
                    r.fail(ei, f"must be a row [time, speed], not {x!r}")
                table.append((r.number(x[0], f"{ei}[0]", unit="s"),
                              _value(r, x[1], f"{ei}[1]", "speed", target, radius, scale)))
            table = np.array(table)
            if np.any(np.diff(table[:, 0]) <= 0):
                r.fail(f"{e}.{key}", "the times (first column) must increase from row to row")
            if table[0, 0] < 0:
                r.fail(f"{e}.{key}[0]", "times start at t >= 0")
            v[k] = table
        elif k in ("start", "ramp"):
            v[k] = r.number(p[key], f"{e}.{key}", unit="s", positive=k == "ramp",
                            nonneg=k == "start")
        else:
            v[k] = _value(r, p[key], f"{e}.{key}", k, target, radius, scale,
                          positive=k != "distance")
    if kind == "trapezoid":
        if ("a_max" in v) == ("ramp" in v):
            r.fail(e, "give the acceleration a_max or the ramp time ramp (s), one of them")
        a = v["a_max"] if "a_max" in v else v["v_max"] / v["ramp"]
        return profiles.trapezoid(v["distance"], v["v_max"], a, v.get("start", 0.0))
    if kind == "s_curve":
        return profiles.s_curve(v["distance"], v["v_max"], v["a_max"], v["j_max"],
                                v.get("start", 0.0))
    return profiles.speed_table(v["speed"][:, 0], v["speed"][:, 1])


def _rope_rate(model, drum_index):
    """Rope paid out per drum radian (m/rad) for each rope on the drum: the radius once
    per rope end wound on it (a rope with both ends on the drum counts twice), as in
    Mechanism's L0 = L0_ref - sum over ends R theta / lambda_ref. {rope index: m/rad}."""
    R = model.drums[drum_index].radius
    return {k: R * rope.end_drums.count(drum_index) for k, rope in enumerate(model.ropes)
            if drum_index in rope.end_drums}


def _check_travel(model, r, d, duration):
    """The prescribed travel stays in the slider's or hinge's range, and a drum neither
    pays out more rope than it holds nor hauls the hook block into its sheaves."""
    lo, hi = d.motion.extremes(duration)
    e = f"{d.entry}.profile"
    if d.target in ("slider", "hinge"):
        j = model.joints[d.index]
        u = "m" if d.target == "slider" else "deg"
        f = 1.0 if d.target == "slider" else 180 / np.pi
        if j.range is None:
            if d.target == "slider":
                r.fail(d.entry, f"the slider {j.label} has no range: add range: "
                       f"[min, max] (m along its axis from the model's position) to "
                       f"{j.entry} in the model file ({model.file}), so the travel can "
                       "be checked")
            return
        if lo < j.range[0] - 1e-12 or hi > j.range[1] + 1e-12:
            r.fail(e, f"the drive moves {j.label} over [{lo * f:.6g}, {hi * f:.6g}]"
                   f" {u} within {duration:g} s, past the end of its range "
                   f"[{j.range[0] * f:g}, {j.range[1] * f:g}] {u} ({model.file}, "
                   f"{j.range_entry}); shorten the move or extend the range")
        return
    drum = model.drums[d.index]
    rates = _rope_rate(model, d.index)
    rate = sum(rates.values()) or drum.radius
    ends = round(rate / drum.radius)
    how = f"radius {drum.radius:g} m x {ends} rope end{'s' if ends > 1 else ''} x"
    payout = -lo * rate
    if payout > drum.rope_reserve:
        r.fail(e, f"the drum pays out {payout:.6g} m of rope ({how} {-lo:.6g} rad), more "
               f"than it holds (rope_reserve {drum.rope_reserve:g} m of drums.{drum.name});"
               " haul in, shorten the move or add rope_reserve")
    on_body = {i for b in model.bodies for i in b.nodes} | set(model.ground.tolist())
    free = {int(i) for i in model.masses.nodes} - on_body
    for k, rate in rates.items():
        rope = model.ropes[k]
        haul = hi * rate
        xs = model.coords
        hanging = [(a, b, f) for a, b, f in zip(rope.span_a, rope.span_b, rope.falls)
                   if a in free or b in free]
        room = sum(f * np.linalg.norm(xs[b] - xs[a]) for a, b, f in hanging)
        n = rope.end_drums.count(d.index)
        if hanging and haul >= room:
            r.fail(e, f"the drum hauls in {haul:.6g} m of rope (radius {drum.radius:g} m x "
                   f"{n} rope end{'s' if n > 1 else ''} x {hi:.6g} rad) but rope "
                   f"'{rope.name}' has only {room:.6g} m in the falls above its load: the "
                   "hook block would be pulled into its sheaves; shorten the move")
