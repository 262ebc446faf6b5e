"""The keys of a transient scene, checked (`analysis: {type: transient, ...}`).

The model loader accepts `type: transient` without looking at its other keys; every
check and every message about them lives here (docs/transient.md lists the keys). Errors
are `ModelError(message, scene file, entry)` with entries such as
``analysis.drums.hoist.torque``.
"""

from dataclasses import dataclass

import numpy as np

from ...errors import ModelError
from ...model.load import _Reader

KEYS = {"type", "duration", "time_step", "max_steps", "method", "modes",
        "static_correction", "initial", "grounded", "output_step", "drums", "forces"}
METHODS = ("direct", "modal")
INITIAL = ("static", "grounded")
DEFAULT_DURATION = 2.0        # s
DEFAULT_MODES = 20            # elastic modes retained by method: modal
DEFAULT_MAX_STEPS = 20000     # cap on the number of steps of an automatic time step


# ------------------------------------------------------------------- time functions

@dataclass(frozen=True)
class Profile:
    """A piecewise-linear function of time, constant outside its table.

    `times` (k,) strictly increasing, `values` (k, m). One point is a constant from
    t = 0 (a step at t = 0); ``ramp(v, r)`` rises linearly from 0 to v over r seconds.
    """

    times: np.ndarray
    values: np.ndarray

    @classmethod
    def constant(cls, value, ramp=0.0):
        value = np.atleast_1d(np.asarray(value, dtype=float))
        if ramp > 0:
            return cls(np.array([0.0, ramp]), np.vstack([np.zeros_like(value), value]))
        return cls(np.array([0.0]), value[None, :])

    @property
    def breakpoints(self):
        return self.times

    def __call__(self, t):
        """(m,) value at t."""
        if len(self.times) == 1:
            return self.values[0].copy()
        return np.array([np.interp(t, self.times, self.values[:, j])
                         for j in range(self.values.shape[1])])

    def rate(self, t, left=False):
        """(m,) slope at t (its right limit, or the left one with left=True)."""
        tt, vv = self.times, self.values
        if len(tt) < 2:
            return np.zeros(vv.shape[1])
        k = np.searchsorted(tt, t, side="left" if left else "right") - 1
        if k < 0 or k >= len(tt) - 1:
            return np.zeros(vv.shape[1])
        return (vv[k + 1] - vv[k]) / (tt[k + 1] - tt[k])

    def integral(self, t):
        """(m,) integral of the function from 0 to t (exact for the piecewise-linear
        function; the first value holds before the first time)."""
        tt, vv = self.times, self.values
        if t <= 0:
            return np.zeros(vv.shape[1])
        # the function on [0, t]: knots 0, the table times inside, t
        knots = np.concatenate([[0.0], tt[(tt > 0) & (tt < t)], [t]])
        vals = np.array([self(x) for x in knots])
        return (0.5 * (vals[1:] + vals[:-1]) * np.diff(knots)[:, None]).sum(axis=0)


@dataclass(frozen=True)
class Motor:
    """A motor's torque-speed characteristic at the motor shaft (N m, rad/s).

    kind 'linear': M = M_s (1 - n / n_s); 'kloss': M = 2 M_k / (s / s_k + s_k / s) with
    the slip s = 1 - n / n_s (Kloss's formula of the induction motor); 'table':
    piecewise-linear through [[n, M], ...], constant beyond the ends.
    """

    kind: str
    synchronous_speed: float = 0.0
    stall_torque: float = 0.0
    breakdown_torque: float = 0.0
    breakdown_slip: float = 0.0
    table: np.ndarray = None

    def torque(self, n):
        """Torque (N m) and its slope dM/dn at motor speed n (rad/s)."""
        if self.kind == "linear":
            return self.stall_torque * (1 - n / self.synchronous_speed), \
                -self.stall_torque / self.synchronous_speed
        if self.kind == "kloss":
            ns, mk, sk = self.synchronous_speed, self.breakdown_torque, self.breakdown_slip
            s = 1 - n / ns
            den = s * s + sk * sk
            # M = 2 M_k s_k s / (s^2 + s_k^2); dM/ds = 2 M_k s_k (s_k^2 - s^2) / den^2
            return 2 * mk * sk * s / den, -2 * mk * sk * (sk * sk - s * s) / den**2 / ns
        x, y = self.table[:, 0], self.table[:, 1]
        k = np.clip(np.searchsorted(x, n) - 1, 0, len(x) - 2)
        slope = (y[k + 1] - y[k]) / (x[k + 1] - x[k]) if x[0] <= n <= x[-1] else 0.0
        return float(np.interp(n, x, y)), slope


# ------------------------------------------------------------------- scene objects

@dataclass(frozen=True)
class DrumDrive:
    """What drives one drum from t = 0 (its brake opens)."""

    drum: int                 # index in model.drums
    name: str
    kind: str                 # speed | torque | motor
    profile: Profile = None   # speed (rad/s) or torque (N m at the drum)
    motor: Motor = None


@dataclass(frozen=True)
class NodeForce:
    node: int
    name: str
    profile: Profile          # values (k, 3): N


@dataclass(frozen=True)
class Transient:
    """A checked transient analysis (docs/transient.md)."""

    duration: float
    time_step: float          # None: automatic
    max_steps: int
    method: str               # direct | modal
    modes: int                # elastic modes retained (modal)
    static_correction: bool   # modal: quasi-static part of the modes left out
    initial: str              # static | grounded
    grounded: tuple           # node indices resting on the ground (initial: grounded)
    output_step: float        # None: automatic
    drums: tuple              # DrumDrive
    forces: tuple             # NodeForce

    @property
    def breakpoints(self):
        """Times where a load or a prescribed speed has a kink: steps end there."""
        ts = [p.profile.breakpoints for p in self.drums if p.profile is not None]
        ts += [f.profile.breakpoints for f in self.forces]
        t = np.unique(np.concatenate(ts)) if ts else np.zeros(0)
        return t[(t > 0) & (t < self.duration)]


def parse(model):
    """The transient analysis of a scene `model`, checked."""
    a = model.analysis
    file = model.scene_file or model.file
    r = _Reader(file, drums={d.name: d.radius for d in model.drums})
    r.keys(a, "analysis", KEYS)
    if a.get("type") != "transient":
        raise ModelError("this is not a transient scene: give analysis: {type: transient, "
                         "...} (docs/transient.md)", file, "analysis.type")
    duration = r.number(a.get("duration", DEFAULT_DURATION), "analysis.duration",
                        positive=True)
    dt = r.number(a["time_step"], "analysis.time_step", positive=True) \
        if "time_step" in a else None
    if dt is not None and dt > duration:
        r.fail("analysis.time_step", f"{dt:g} s is longer than the duration "
               f"({duration:g} s); give a shorter step or leave it out (automatic)")
    max_steps = r.integer(a.get("max_steps", DEFAULT_MAX_STEPS), "analysis.max_steps",
                          minimum=1)
    method = a.get("method", "direct")
    if method not in METHODS:
        r.fail("analysis.method", f"{method!r} is not one of {', '.join(METHODS)}")
    modes = r.integer(a.get("modes", DEFAULT_MODES), "analysis.modes", minimum=1)
    if "modes" in a and method != "modal":
        r.fail("analysis.modes", "modes is the number of modes of method: modal; add "
               "method: modal or remove it")
    correction = r.boolean(a.get("static_correction", True), "analysis.static_correction")
    initial = a.get("initial", "static")
    if initial not in INITIAL:
        r.fail("analysis.initial", f"{initial!r} is not one of {', '.join(INITIAL)}")
    if initial == "grounded" and model.effects.sway:
        r.fail("analysis.initial", "a load resting on the ground has no pendulum "
               "stiffness: use initial: grounded with effects: {sway: false}")
    if initial == "grounded" and method == "modal":
        r.fail("analysis.method", "lift-off changes the equations (the ground lets go), "
               "which modal superposition cannot follow; use method: direct with "
               "initial: grounded")
    grounded = _grounded(model, a, r, initial)
    out = r.number(a["output_step"], "analysis.output_step", positive=True) \
        if "output_step" in a else None
    drums = _drums(model, a, r)
    forces = _forces(model, a, r)
    return Transient(duration, dt, max_steps, method, modes, correction, initial,
                     grounded, out, drums, forces)


def _profile(r, v, entry, width, ramp):
    """A number (or `width` numbers) as a constant with an optional ramp, or a table
    [[t, v...], ...] -> Profile."""
    if isinstance(v, list) and v and isinstance(v[0], list):
        if ramp is not None:
            r.fail(f"{entry}", "a table gives the whole history; remove 'ramp'")
        rows = [r.vector(p, f"{entry}[{k}]", width + 1) for k, p in enumerate(v)]
        table = np.array(rows)
        if np.any(np.diff(table[:, 0]) <= 0):
            r.fail(entry, "the times (first column) must increase from row to row")
        if table[0, 0] < 0:
            r.fail(f"{entry}[0]", "times start at t >= 0")
        return Profile(table[:, 0], table[:, 1:])
    value = r.vector(v, entry, width) if width > 1 else \
        np.array([r.number(v, entry)])
    return Profile.constant(value, ramp or 0.0)


def _drums(model, a, r):
    names = {d.name: i for i, d in enumerate(model.drums)}
    out = []
    raw = a.get("drums", {})
    if not isinstance(raw, dict):
        r.fail("analysis.drums", "must be a mapping: drum name -> {speed: ...}, "
               "{torque: ...} or {motor: {...}}")
    for name, spec in raw.items():
        e = f"analysis.drums.{name}"
        if name not in names:
            r.fail(e, f"unknown drum '{name}'; drums of the model: "
                   f"{', '.join(names) or 'none'}")
        r.keys(spec, e, {"speed", "torque", "motor", "ramp"})
        given = [k for k in ("speed", "torque", "motor") if k in spec]
        if len(given) != 1:
            r.fail(e, "give exactly one of speed (rad/s), torque (N m at the drum, or a "
                   "table [[t, M], ...]) or motor {...} (docs/transient.md)")
        d = names[name]
        drum = model.drums[d]
        if drum.brake:
            r.fail(e, f"drum '{name}' is braked in the model (brake: true), so it has no "
                   "rotation to drive; set brake: false in the model")
        if model.effects.drive != "coupled":
            r.fail(e, f"with effects: {{drive: {model.effects.drive}}} the drum has no "
                   "rotation coordinate; a driven drum needs drive: coupled")
        ramp = r.number(spec["ramp"], f"{e}.ramp", nonneg=True) if "ramp" in spec else None
        kind = given[0]
        if kind == "speed":
            out.append(DrumDrive(d, name, "speed", _profile(r, spec["speed"], f"{e}.speed",
                                                            1, ramp)))
        elif kind == "torque":
            out.append(DrumDrive(d, name, "torque",
                                 _profile(r, spec["torque"], f"{e}.torque", 1, ramp)))
        else:
            if ramp is not None:
                r.fail(f"{e}.ramp", "a motor follows its characteristic; remove 'ramp'")
            out.append(DrumDrive(d, name, "motor", motor=_motor(r, spec["motor"],
                                                                 f"{e}.motor")))
    return tuple(out)


def _motor(r, m, e):
    kinds = {"linear": {"stall_torque", "synchronous_speed"},
             "kloss": {"breakdown_torque", "breakdown_slip", "synchronous_speed"},
             "table": {"characteristic"}}
    r.keys(m, e, set().union(*kinds.values()))
    match = [k for k, keys in kinds.items() if set(m) == keys]
    if not match:
        r.fail(e, "give one characteristic: {stall_torque, synchronous_speed} (linear), "
               "{breakdown_torque, breakdown_slip, synchronous_speed} (Kloss) or "
               "{characteristic: [[n, M], ...]} (N m against rad/s at the motor shaft)")
    kind = match[0]
    if kind == "table":
        rows = r.listing(m["characteristic"], f"{e}.characteristic", min_len=2)
        t = np.array([r.vector(p, f"{e}.characteristic[{k}]", 2)
                      for k, p in enumerate(rows)])
        if np.any(np.diff(t[:, 0]) <= 0):
            r.fail(f"{e}.characteristic", "the speeds (first column) must increase")
        return Motor("table", table=t)
    ns = r.number(m["synchronous_speed"], f"{e}.synchronous_speed", positive=True)
    if kind == "linear":
        return Motor("linear", ns, stall_torque=r.number(m["stall_torque"],
                                                         f"{e}.stall_torque"))
    sk = r.number(m["breakdown_slip"], f"{e}.breakdown_slip", positive=True)
    if sk >= 1:
        r.fail(f"{e}.breakdown_slip", f"{sk:g} is not a slip below 1 (typically 0.1-0.4)")
    return Motor("kloss", ns, breakdown_torque=r.number(
        m["breakdown_torque"], f"{e}.breakdown_torque", positive=True), breakdown_slip=sk)


def _forces(model, a, r):
    raw = a.get("forces", {})
    if not isinstance(raw, dict):
        r.fail("analysis.forces", "must be a mapping: node name -> {force: [fx, fy, fz]}")
    index = model.node_index
    out = []
    for name, spec in raw.items():
        e = f"analysis.forces.{name}"
        if name not in index:
            r.fail(e, f"unknown node '{name}'")
        if index[name] in set(model.ground.tolist()):
            r.fail(e, f"node '{name}' is fixed (ground): a force on it does nothing")
        r.keys(spec, e, {"force", "ramp"}, required=("force",))
        ramp = r.number(spec["ramp"], f"{e}.ramp", nonneg=True) if "ramp" in spec else None
        p = _profile(r, spec["force"], f"{e}.force", 3, ramp)
        if model.planar and np.any(p.values[:, 1] != 0):
            r.fail(f"{e}.force", "a plane: xz model moves in x and z only; give fy = 0")
        out.append(NodeForce(index[name], name, p))
    return tuple(out)


def _grounded(model, a, r, initial):
    """Nodes of the loads that rest on the ground (initial: grounded)."""
    if "grounded" in a and initial != "grounded":
        r.fail("analysis.grounded", "the loads on the ground are for initial: grounded")
    if initial != "grounded":
        return ()
    index = model.node_index
    if "grounded" in a:
        names = r.listing(a["grounded"], "analysis.grounded", min_len=1)
        out = []
        for k, n in enumerate(names):
            if n not in index:
                r.fail(f"analysis.grounded[{k}]", f"unknown node {n!r}")
            if index[n] not in set(model.masses.nodes.tolist()):
                r.fail(f"analysis.grounded[{k}]", f"node '{n}' carries no point mass "
                       "(masses:); only a load resting on the ground can lift off")
            out.append(index[n])
        return tuple(out)
    # default: every point mass at a node of its own that hangs on ropes or springs
    # (not on a body, not fixed, not a node of a member)
    on_body = {i for b in model.bodies for i in b.nodes}
    members = {i for m in model.members for i in _member_nodes(m)}
    out = tuple(int(i) for i in model.masses.nodes
                if i not in on_body and i not in members and i not in set(model.ground))
    if not out:
        r.fail("analysis.initial", "initial: grounded needs a load hanging on ropes (a point "
               "mass at a node of its own); the model has none")
    return out


def _member_nodes(m):
    if m.pairs is not None:
        return [int(i) for i in np.asarray(m.pairs).ravel()]
    return [int(i) for i in m.nodes]
