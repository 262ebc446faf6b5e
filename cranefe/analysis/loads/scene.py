"""The keys of a loads scene (``analysis: {type: loads, ...}``), checked, and the
defaults used when `cranefe loads` is given a plain model or a transient scene
(docs/loads.md, "Scene keys").

Every number that decides a factor is here, so that the result can say what it assumed:
the hoisting speeds (full and creep, at the hook), the drives' ramp times, the released
part of the load and its release time, the joint drives' moves, the working point
(radius, hook height) of a load chart.
"""

from dataclasses import dataclass, replace

import numpy as np

from ...errors import ModelError
from ...model.load import _Reader

KEYS = {"type", "hoist", "release", "drives", "after_lift_off", "time_step", "tolerance",
        "radius",
        "radius_nodes", "hook_height", "hoisting_class", "drive_class"}
HOIST_KEYS = {"drum", "load", "speed", "creep", "ramp", "jerk_time"}
RELEASE_KEYS = {"fraction", "time"}
DRIVE_KEYS = {"v_max", "ramp", "distance", "v_max_deg", "distance_deg", "jerk_time"}

DEFAULT_SPEED = 0.5          # m/s at the hook: full hoisting speed when nothing says
CREEP_SHARE = 0.1            # creep speed / full speed when not given
DEFAULT_RAMP = 1.0           # s from rest to full speed (hoist) when not given
DEFAULT_AFTER = 3.0          # s simulated after lift-off
JERK_SHARE = 0.25            # jerk time / ramp when not given
DEFAULT_FRACTION = 0.5       # dm/m released
SPEED_SHARES = (0.25, 0.5, 0.75, 1.0)   # phi2 curve: creep plus these x full speed
SLIDER_MOVE = {"v_max": 1.0, "ramp": 2.0, "distance": 6.0}          # m/s, s, m
HINGE_MOVE = {"v_max_deg": 0.8 * 6.0, "ramp": 5.0, "distance_deg": 45.0}  # 0.8 rpm


@dataclass(frozen=True)
class JointMove:
    """A trapezoidal move of one slider or hinge joint for phi5 (operation engine)."""

    joint: str                # joint name
    kind: str                 # slider | hinge
    v_max: float              # m/s or rad/s
    ramp: float               # s to reach v_max (and to stop)
    distance: float           # m or rad
    jerk: float = 0.0         # s over which the acceleration rises


@dataclass(frozen=True)
class LoadsSpec:
    """A checked loads analysis (docs/loads.md)."""

    drum: str                 # the hoist drum
    loads: tuple              # node names of the hoist load (resting on the ground)
    speed: float              # full steady hoisting speed v_h,max at the hook, m/s
    creep: float              # creep speed v_h,CS, m/s
    ramp: float               # s, hoist drive from rest to full speed
    jerk: float               # s, over which its acceleration rises (0: a step)
    fraction: float           # dm/m released (phi3)
    release_time: float       # s over which dm is released (0: sudden)
    moves: tuple              # JointMove
    after_lift_off: float     # s simulated after the (estimated) lift-off
    time_step: float          # s, or None: the transient core's automatic step
    radius: float = None      # working radius (m) of radius_nodes, or None: as modelled
    radius_nodes: tuple = ()
    hook_height: float = None  # height (m) of the load node(s), or None: as modelled
    hoisting_class: str = None  # declared HC1-HC4 (None: the one the crane behaves like)
    drive_class: str = "HD1"  # declared hoist drive class of phi2's `value`
    assumed: tuple = ()       # sentences: what was taken as default, and from where
    tolerance: float = None   # operation engine's tolerance (None: its default)

    @property
    def speeds(self):
        """Steady hoisting speeds of the phi2 curve: creep, then shares of full speed."""
        return tuple(sorted({self.creep, *(s * self.speed for s in SPEED_SHARES)}))


def parse(model):
    """The loads analysis of `model`: the scene's keys (type: loads), the hoist speed of
    a transient scene's drum (type: transient), or the defaults (a model)."""
    a = model.analysis or {}
    file = model.scene_file or model.file
    r = _Reader(file)
    kind = a.get("type", "modes")
    assumed = []
    if kind == "loads":
        r.keys(a, "analysis", KEYS)
        raw = a
    else:
        raw = {}
    drum = _drum(model, r, raw.get("hoist", {}), assumed)
    hoist = raw.get("hoist", {})
    if hoist:
        r.keys(hoist, "analysis.hoist", HOIST_KEYS)
    loads = _loads(model, r, hoist, assumed)
    speed, ramp = _speed(model, r, hoist, drum, kind, assumed)
    creep = r.number(hoist["creep"], "analysis.hoist.creep", positive=True) \
        if "creep" in hoist else None
    rel = raw.get("release", {})
    r.keys(rel, "analysis.release", RELEASE_KEYS)
    fraction = r.number(rel.get("fraction", DEFAULT_FRACTION), "analysis.release.fraction",
                        positive=True)
    if fraction >= 1.0:
        r.fail("analysis.release.fraction", f"{fraction:g}: the released part dm/m must "
               "be below 1 (a part of the load stays on the hook)")
    if "fraction" not in rel:
        assumed.append(f"phi3: dm/m = {DEFAULT_FRACTION:g} released (give "
                       "analysis.release.fraction)")
    rtime = r.number(rel.get("time", 0.0), "analysis.release.time", nonneg=True)
    moves = _moves(model, r, raw.get("drives"), assumed)
    after = r.number(raw.get("after_lift_off", DEFAULT_AFTER), "analysis.after_lift_off",
                     positive=True)
    step = r.number(raw["time_step"], "analysis.time_step", positive=True) \
        if "time_step" in raw else None
    jerk = r.number(hoist["jerk_time"], "analysis.hoist.jerk_time", nonneg=True) \
        if "jerk_time" in hoist else JERK_SHARE * ramp
    if jerk > 0.5 * ramp:
        r.fail("analysis.hoist.jerk_time", f"{jerk:g} s is more than half the ramp "
               f"({ramp:g} s): the acceleration must rise and fall within the ramp")
    radius = r.number(raw["radius"], "analysis.radius", positive=True) \
        if "radius" in raw else None
    rnodes = tuple(r.listing(raw.get("radius_nodes", []), "analysis.radius_nodes"))
    if radius is not None and not rnodes:
        r.fail("analysis.radius_nodes", "name the nodes that move to the radius (the "
               "trolley and the hook below it), e.g. radius_nodes: [K, HOOK]")
    for k, n in enumerate(rnodes):
        if n not in model.node_index:
            r.fail(f"analysis.radius_nodes[{k}]", f"unknown node {n!r}")
    height = r.number(raw["hook_height"], "analysis.hook_height") \
        if "hook_height" in raw else None
    hc = raw.get("hoisting_class")
    if hc is not None and hc not in ("HC1", "HC2", "HC3", "HC4"):
        r.fail("analysis.hoisting_class", f"{hc!r} is not one of HC1, HC2, HC3, HC4")
    dc = raw.get("drive_class", "HD1")
    if dc not in ("HD1", "HD2", "HD3", "HD4", "HD5"):
        r.fail("analysis.drive_class", f"{dc!r} is not one of HD1 ... HD5")
    tol = r.number(raw["tolerance"], "analysis.tolerance", positive=True) \
        if "tolerance" in raw else None
    return LoadsSpec(drum, loads, speed, creep, ramp, jerk, fraction, rtime, moves, after,
                     step, radius, rnodes, height, hc, dc, tuple(assumed), tol)


def _drum(model, r, hoist, assumed):
    names = [d.name for d in model.drums if not d.brake]
    if "drum" in hoist:
        if hoist["drum"] not in names:
            r.fail("analysis.hoist.drum", f"unknown or braked drum {hoist['drum']!r}; "
                   f"unbraked drums of the model: {', '.join(names) or 'none'}")
        return hoist["drum"]
    if not names:
        raise ModelError("cranefe loads needs a hoist drum that turns (a drum with "
                         "brake: false); the model has none", model.scene_file or
                         model.file, "drums")
    if len(names) > 1:
        r.fail("analysis.hoist.drum", f"the model has several drums ({', '.join(names)}); "
               "name the hoist drum")
    return names[0]


def _loads(model, r, hoist, assumed):
    """The hoist load's node(s): given, or the point masses with no rope hanging below
    them that hang at a node of their own (the lowest masses of each hoist)."""
    if "load" in hoist:
        names = hoist["load"] if isinstance(hoist["load"], list) else [hoist["load"]]
        for k, n in enumerate(names):
            if n not in model.node_index:
                r.fail("analysis.hoist.load", f"unknown node {n!r}")
            if model.node_index[n] not in set(model.masses.nodes.tolist()):
                r.fail("analysis.hoist.load", f"node {n!r} carries no point mass")
        return tuple(names)
    on_body = {i for b in model.bodies for i in b.nodes}
    ground = set(model.ground.tolist())
    free = [int(i) for i in model.masses.nodes if int(i) not in on_body | ground]
    up = -model.gravity / np.linalg.norm(model.gravity)
    below = set()
    for rope in model.ropes:
        for a, b in zip(rope.span_a, rope.span_b):
            za, zb = model.coords[a] @ up, model.coords[b] @ up
            if za == zb:
                continue                 # a level span: neither mass hangs below the other
            lo, hi = (a, b) if za < zb else (b, a)
            if hi in free and lo in free:
                below.add(int(hi))       # a mass hangs below this one
    loads = [i for i in free if i not in below]
    if not loads:
        raise ModelError("cranefe loads finds no hoist load (a point mass at a node of its "
                         "own hanging on the ropes); give analysis.hoist.load",
                         model.scene_file or model.file, "analysis.hoist.load")
    names = tuple(model.node_names[i] for i in loads)
    assumed.append(f"hoist load: the point mass(es) at {', '.join(names)} (the lowest "
                   "masses on the ropes; give analysis.hoist.load)")
    return names


def _speed(model, r, hoist, drum, kind, assumed):
    """Full hook speed (m/s) and ramp (s): the loads scene's, a transient scene's drum
    speed (converted to the hook later: returned negative as rad/s), or defaults."""
    ramp = r.number(hoist["ramp"], "analysis.hoist.ramp", positive=True) \
        if "ramp" in hoist else None
    if "speed" in hoist:
        speed = r.number(hoist["speed"], "analysis.hoist.speed", positive=True)
    elif kind == "transient" and drum in (model.analysis.get("drums") or {}) and \
            "speed" in model.analysis["drums"][drum]:
        spec = model.analysis["drums"][drum]
        v = spec["speed"]
        w = float(np.max(np.abs(np.asarray(v, float)[:, 1]))) if isinstance(v, list) \
            else abs(float(v))
        if w <= 0:
            r.fail(f"analysis.drums.{drum}.speed", "a zero drum speed gives no hoisting "
                   "speed; give a loads scene with analysis.hoist.speed")
        speed = -w         # rad/s of the drum: converted with the reeving (analysis)
        assumed.append(f"full hoisting speed: the transient scene's drum speed {w:.4g} "
                       f"rad/s of drum '{drum}'")
        if ramp is None and isinstance(spec.get("ramp"), (int, float)) and spec["ramp"] > 0:
            ramp = float(spec["ramp"])
            assumed.append(f"hoist ramp: the scene's {ramp:g} s")
    else:
        speed = DEFAULT_SPEED
        assumed.append(f"full hoisting speed v_h,max = {DEFAULT_SPEED:g} m/s at the hook "
                       "(the model gives no speed; give a loads scene with "
                       "analysis.hoist.speed)")
    if ramp is None:
        ramp = DEFAULT_RAMP
        assumed.append(f"hoist drive: rest to full speed in {DEFAULT_RAMP:g} s (give "
                       "analysis.hoist.ramp)")
    return speed, ramp


def _moves(model, r, raw, assumed):
    """One trapezoidal move per named slider and hinge joint (phi5 by the operation
    engine): the scene's `drives`, else defaults for every such joint."""
    joints = {j.name: j for j in model.joints if j.name and j.type in ("slider", "hinge")}
    if raw is None:
        raw = {n: {} for n in joints}
        if joints:
            assumed.append("joint drives: default moves " + "; ".join(
                f"{n}: " + (f"{SLIDER_MOVE['v_max']:g} m/s reached in "
                            f"{SLIDER_MOVE['ramp']:g} s" if j.type == "slider" else
                            f"{HINGE_MOVE['v_max_deg']:g} deg/s reached in "
                            f"{HINGE_MOVE['ramp']:g} s")
                for n, j in joints.items()) + " (give analysis.drives)")
    r.mapping(raw, "analysis.drives")
    out = []
    for name, spec in raw.items():
        e = f"analysis.drives.{name}"
        if name not in joints:
            r.fail(e, f"no slider or hinge joint named {name!r}; named ones: "
                   f"{', '.join(joints) or 'none'}")
        spec = spec or {}
        r.keys(spec, e, DRIVE_KEYS)
        j = joints[name]
        if j.type == "slider":
            d = dict(SLIDER_MOVE, **{k: v for k, v in spec.items()
                                      if not k.endswith("deg")})
            v, dist = r.number(d["v_max"], f"{e}.v_max", positive=True), \
                r.number(d["distance"], f"{e}.distance")
        else:
            d = dict(HINGE_MOVE, **spec)
            v = np.radians(r.number(d["v_max_deg"], f"{e}.v_max_deg", positive=True))
            dist = np.radians(r.number(d["distance_deg"], f"{e}.distance_deg"))
        ramp = r.number(d["ramp"], f"{e}.ramp", positive=True)
        jerk = r.number(d.get("jerk_time", JERK_SHARE * ramp), f"{e}.jerk_time",
                        nonneg=True)
        if jerk > 0.5 * ramp:
            r.fail(f"{e}.jerk_time", f"{jerk:g} s is more than half the ramp ({ramp:g} s)")
        out.append(JointMove(name, j.type, float(v), ramp, float(dist), jerk))
    return tuple(out)


def complete(spec, hook_per_drum, file):
    """The spec with its speeds in m/s at the hook: a drum speed (a transient scene's,
    stored negative in rad/s) times `hook_per_drum` (m of hook travel per rad), and the
    default creep speed CREEP_SHARE x full speed."""
    assumed = list(spec.assumed)
    speed = spec.speed if spec.speed > 0 else -spec.speed * hook_per_drum
    creep = spec.creep
    if creep is None:
        creep = CREEP_SHARE * speed
        assumed.append(f"creep speed v_h,CS = {CREEP_SHARE:g} x full speed = {creep:.4g} "
                       "m/s (give analysis.hoist.creep)")
    if creep >= speed:
        raise ModelError(f"the creep speed {creep:g} m/s is not below the full speed "
                         f"({speed:.4g} m/s)", file, "analysis.hoist.creep")
    return replace(spec, speed=float(speed), creep=float(creep), assumed=tuple(assumed))
