"""The result of an operation run, and the recorder that fills it step by step.

Peak rope forces are tracked on every step: between the ends of a step each rope's force
is the cubic Hermite interpolant of its values and rates (dS/dt = EA/L x elongation rate;
the dashpot's share is taken as constant over the step), whose interior maximum is taken.
Stored output times are sampled inside the steps from the cubic Hermite interpolant of
the coordinates (q, q' at both ends), so they cost one force evaluation each.
"""

import math
from dataclasses import dataclass, field

import numpy as np

from ..jsonable import num as _num
from ..jsonable import timings

MAX_EVENTS = 100


@dataclass
class _Sample:
    """What an output time stores (a subset of mechanism.Eval)."""

    t: float
    X: np.ndarray
    S: np.ndarray
    Sd: np.ndarray
    theta: np.ndarray
    omega: np.ndarray
    drive_torque: np.ndarray


@dataclass
class OperationResult:
    """Time histories and peaks of one operation scene (docs/operations.md)."""

    model_name: str
    scene: str
    effects: dict
    coordinates: tuple             # (n,) labels of the generalised coordinates
    duration: float
    steps: int
    rejected: int
    newton_iterations: int
    times: np.ndarray              # (nt,)
    mass_names: tuple              # (nm,) every node with a point mass
    mass_position: np.ndarray      # (nt, nm, 3) m, global frame
    rope_names: tuple              # (nr,) every rope of the model
    rope_force: np.ndarray         # (nt, nr) N (elastic + dashpot); nan: not computed
    rope_force_static: np.ndarray  # (nr,)
    rope_force_max: np.ndarray     # (nr,)
    rope_force_max_time: np.ndarray  # (nr,)
    drive_names: tuple             # (nv,)
    drive_units: tuple             # (nv,) ("rad", "rad/s") or ("m", "m/s")
    drive_kind: tuple              # (nv,) profile | torque | motor
    drive_position: np.ndarray     # (nt, nv)
    drive_speed: np.ndarray        # (nt, nv)
    drive_torque: np.ndarray       # (nt, nv) drums: torque at the drum (applied, or what
                                   #   holds a prescribed motion); joints: nan
    sway_names: tuple              # (ns,) point masses hanging on ropes
    sway_deg: np.ndarray           # (nt, ns) angle of the span above from the vertical
    sway_max_deg: np.ndarray       # (ns,)
    sway_residual_deg: np.ndarray  # (ns,) nan if no drive stops before the end
    motion_end: float              # s, when the last prescribed drive stops
    energy: dict                   # J
    energy_error: float
    events: list = field(default_factory=list)
    timings: dict = field(default_factory=dict)
    warnings: list = field(default_factory=list)
    status: int = 0
    message: str = "ok"
    holding: dict = field(default_factory=dict)   # drive -> N m or N at rest, t = 0

    @property
    def dynamic_factor(self):
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.rope_force_static > 0,
                            self.rope_force_max / self.rope_force_static, np.nan)

    def to_dict(self):
        """The JSON document of ``cranefe simulate --json`` for an operation scene."""
        ropes = self.rope_names
        drives = {}
        for k, n in enumerate(self.drive_names):
            pu, su = self.drive_units[k]
            tq = self.drive_torque[:, k]
            linear = pu == "m"                 # a slider's force, in N
            kind = self.drive_kind[k]
            drives[n] = {"kind": "force" if linear and kind == "torque" else kind,
                         "units": [pu, su],
                         "position_final": _num(self.drive_position[-1, k]),
                         "speed_max": _num(np.abs(self.drive_speed[:, k]).max()),
                         # the largest in magnitude, with its sign
                         ("force_max_N" if linear else "torque_max_N_m"):
                         _num(tq[np.nanargmax(np.abs(tq))])
                         if np.any(np.isfinite(tq)) else None}
            if n in self.holding:
                drives[n]["holding_" + ("force_N" if linear else "torque_N_m")] = \
                    _num(self.holding[n])
        return {
            "model": self.model_name, "scene": self.scene, "analysis": "operation",
            "effects": self.effects, "dofs": len(self.coordinates),
            "coordinates": list(self.coordinates),
            "duration_s": _num(self.duration), "steps": self.steps,
            "rejected_steps": self.rejected, "newton_iterations": self.newton_iterations,
            "rope_force_max_N": {n: _num(v) for n, v in zip(ropes, self.rope_force_max)},
            "rope_force_max_time_s": {n: _num(v) for n, v in
                                      zip(ropes, self.rope_force_max_time)},
            "rope_force_static_N": {n: _num(v) for n, v in
                                    zip(ropes, self.rope_force_static)},
            "dynamic_factor": {n: _num(v) for n, v in zip(ropes, self.dynamic_factor)},
            "sway": {n: {"max_deg": _num(m), "residual_deg": _num(r)} for n, m, r in
                     zip(self.sway_names, self.sway_max_deg, self.sway_residual_deg)},
            "motion_end_s": _num(self.motion_end),
            "drives": drives,
            "energy_error": _num(self.energy_error),
            "energy_J": {k: _num(v) for k, v in self.energy.items()},
            "events": [f"{t:.6g} s: {w}" for t, w in self.events[:MAX_EVENTS]],
            "events_total": len(self.events),
            "timings_s": timings(self.timings),
            "warnings": list(self.warnings),
            "status": self.status, "message": self.message,
        }


def _hermite_max1(S0, S1, m0, m1):
    """The largest value of one rope's force over a step and where (fraction of the
    step), in plain floats (m0, m1: the step h times the end rates).

    p(s) = (2s^3-3s^2+1) S0 + (s^3-2s^2+s) m0 + (-2s^3+3s^2) S1 + (s^3-s^2) m1 has
    p'(s) = A s^2 + B s + C with C = p'(0) = m0 and A + B + C = p'(1) = m1; its real
    roots in (0, 1) (the cancellation-free formula) are the candidates beside the ends:
    an interior maximum when m0 > 0 > m1, and also when m0 and m1 have the same sign
    (the force turning twice in the step: S0 = 0, S1 = -1, m0 = m1 = 1 peaks at 0.0443,
    s = 0.092); none when m0 <= 0 <= m1."""
    if S1 >= S0:
        best, where = S1, 1.0
    else:
        best, where = S0, 0.0
    A = 6 * (S0 - S1) + 3 * (m0 + m1)
    B = -6 * (S0 - S1) - 4 * m0 - 2 * m1
    C = m0
    r1 = r2 = -1.0                          # -1: outside (0, 1)
    if A != 0:
        disc = B * B - 4 * A * C
        if disc >= 0:
            qq = -0.5 * (B + math.copysign(math.sqrt(disc), B))
            r1 = qq / A
            if qq != 0:
                r2 = C / qq
    elif B != 0:
        r1 = -C / B
    for s in (r1, r2):                      # (a plain tuple: loop.py compiles this)
        if 0 < s < 1:
            val = (2 * s**3 - 3 * s**2 + 1) * S0 + (s**3 - 2 * s**2 + s) * m0 \
                + (-2 * s**3 + 3 * s**2) * S1 + (s**3 - s**2) * m1
            if val > best:
                best, where = val, s
    return best, where


def hermite_bound(S0, S1, m0, m1):
    """An upper bound of the cubic of `_hermite_max1` over the step: the Hermite weights
    of S0, S1 are >= 0 and sum to 1, that of m0 lies in [0, 4/27], that of m1 in
    [-4/27, 0] (their extremes at s = 1/3, 2/3). A step whose bound stays below the
    running peak cannot raise it."""
    return max(S0, S1) + (4.0 / 27.0) * (max(m0, 0.0) + max(-m1, 0.0))


class Recorder:
    def __init__(self, mech, spec, ops):
        self.m, self.spec, self.ops = mech, spec, ops
        self.samples = []
        T = spec.duration
        self.out_times = np.arange(0.0, T + 0.5 * spec.output_step, spec.output_step)
        self.out_times = self.out_times[self.out_times <= T * (1 + 1e-12)]
        if self.out_times[-1] < T * (1 - 1e-12):
            self.out_times = np.append(self.out_times, T)
        self.next_out = 1
        nr = len(mech.ropes)
        self.peak = [0.0] * nr
        self.peak_t = [0.0] * nr
        self.W = self.D = self.Wd = 0.0
        self.mass_nodes = mech.mass_nodes
        self.sway_nodes = mech.free
        self.max_terms = [0.0, 0.0, 0.0]

    def _force_rate(self, ev, taut):
        """(S + S_d, its rate EA/L e' for the ropes taut over the step) of a state, made
        once (each serves two steps; a state at an event is evaluated again with the new
        `taut` set, a new object): a rope that goes taut starts at S = 0 with its full
        rate."""
        fr = getattr(ev, "_fr", None)
        if fr is None:
            F = ev.S + ev.Sd
            fr = ev._fr = (F, np.where(taut, self.m.EA / ev.L, 0.0) * ev.edot, F.tolist())
        return fr

    def start(self, t, q, v, a, ev, taut):
        self.E0 = self.ops.energy(ev, taut)
        self.Vg0 = self.E0[1]
        self.peak = (ev.S + ev.Sd).tolist()
        self.last = ev
        self.taut = taut
        self._sample(ev, q, v)

    def _reached(self, t):
        """The time a failed run reached: its last accepted state (later than the last
        output sample)."""
        last = getattr(self.last, "t", None)
        return float(t[-1]) if last is None else max(float(t[-1]), float(last))

    def switch(self, t, ev, taut):
        self.last = ev
        self.taut = taut

    def accept(self, t0, q0, v0, a0, ev0, t1, q1, v1, a1, ev1, taut):
        h = t1 - t0
        ev0 = self.last
        self.W += 0.5 * h * (ev0.P_drive + ev1.P_drive) + ev1.T_guided - ev0.T_guided
        self.D += 0.5 * h * (ev0.P_diss + ev1.P_diss)
        self.Wd += 0.5 * h * (ev0.P_wound + ev1.P_wound)
        (_, r0, F0), (_, r1, F1) = self._force_rate(ev0, taut), self._force_rate(ev1, taut)
        peak, peak_t = self.peak, self.peak_t
        for k, (a, b, m0, m1) in enumerate(zip(F0, F1, (h * r0).tolist(),
                                               (h * r1).tolist())):
            if hermite_bound(a, b, m0, m1) > peak[k]:
                best, where = _hermite_max1(a, b, m0, m1)
                if best > peak[k]:
                    peak[k], peak_t[k] = best, t0 + where * h
        T, Vg, U = self.ops.energy(ev1, taut)
        mt = self.max_terms
        mt[0], mt[1], mt[2] = max(mt[0], T), max(mt[1], abs(Vg - self.Vg0)), max(mt[2], U)
        self.last_E = (T, Vg, U)
        self.taut = taut
        while self.next_out < len(self.out_times) and \
                self.out_times[self.next_out] <= t1 * (1 + 1e-13):
            ts = self.out_times[self.next_out]
            s = (ts - t0) / h
            # cubic Hermite of q through (q0, v0), (q1, v1); its derivative for v
            h00, h10, h01, h11 = 2*s**3 - 3*s**2 + 1, s**3 - 2*s**2 + s, \
                -2*s**3 + 3*s**2, s**3 - s**2
            qs = h00 * q0 + h10 * h * v0 + h01 * q1 + h11 * h * v1
            d00, d10, d01, d11 = 6*s**2 - 6*s, 3*s**2 - 4*s + 1, -6*s**2 + 6*s, 3*s**2 - 2*s
            vs = (d00 * q0 + d01 * q1) / h + d10 * v0 + d11 * v1
            evs = ev1 if s >= 1 - 1e-12 else self._between(ts, s, h, qs, vs, ev0, ev1,
                                                                taut)
            self._sample(evs, qs, vs)
            self.next_out += 1
        self.last = ev1

    def _between(self, ts, s, h, qs, vs, ev0, ev1, taut):
        """The state at an output time inside a step, without a force evaluation: node
        positions from the interpolated coordinates, rope forces from the cubic Hermite
        interpolant of their values and rates at the step's ends."""
        m = self.m
        X, _, theta, omega = self.ops.place(ts, qs, vs)
        (F0, d0, _), (F1, d1, _) = self._force_rate(ev0, taut), self._force_rate(ev1, taut)
        F = (2*s**3 - 3*s**2 + 1) * F0 + (s**3 - 2*s**2 + s) * h * d0 \
            + (-2*s**3 + 3*s**2) * F1 + (s**3 - s**2) * h * d1
        tq = np.zeros(m.nd)
        for k in m.qdrums:
            d = m.drum_drive[k]
            if d.kind == "torque":
                tq[k] = d.torque(ts)[0]
            else:
                tq[k] = m.gear[k] * d.motor.torque(m.gear[k] * omega[k])[0]
        return _Sample(ts, X, F, np.zeros_like(F), theta, omega, tq)

    def _sample(self, ev, q, v):
        m = self.m
        X = ev.X if ev.X is not None else self.ops.place(ev.t, q, v)[0]
        nr_all = len(m.model.ropes)
        F = np.full(nr_all, np.nan)
        F[m.ropes] = ev.S + ev.Sd
        pos, spd, tq = [], [], []
        for d in self.spec.drives:
            if d.target == "drum":
                pos.append(ev.theta[d.index])
                spd.append(ev.omega[d.index])
                tq.append(self._drum_torque(ev, d))
            else:
                s, ds = m.joint_state(d, ev.t, q, v)
                pos.append(s)
                spd.append(ds)
                tq.append(m.joint_drive_torque(d, ev.t, ds))
        # the span above each load; its angle from the vertical is taken in `result`
        self.samples.append((ev.t, X[self.mass_nodes], F, pos, spd, tq,
                             X[m.hang] - X[m.free]))

    def _drum_torque(self, ev, d):
        m = self.m
        if d.kind != "profile":
            return ev.drive_torque[d.index]
        tq = 0.0
        for j, dd, R in zip(m.rope_drum, m.drum_of_end, m.end_radius):
            if dd == d.index:
                tq += R * (ev.S[j] + ev.Sd[j])
        return tq

    def _angles(self, d):
        """(nt, ns) angles (deg) from the vertical of the spans d (nt, ns, 3) above the
        loads."""
        c = (d @ self.m.up) / np.linalg.norm(d, axis=-1)
        return np.degrees(np.arccos(np.clip(c, -1.0, 1.0)))

    def result(self, st, timings, status=0, message="ok"):
        m, spec = self.m, self.spec
        model = m.model
        t = np.array([s[0] for s in self.samples])
        nt = len(t)
        X = np.array([s[1] for s in self.samples]).reshape(nt, len(self.mass_nodes), 3)
        F = np.array([s[2] for s in self.samples]).reshape(nt, len(model.ropes))
        nv = len(spec.drives)
        pos = np.array([s[3] for s in self.samples], float).reshape(nt, nv)
        spd = np.array([s[4] for s in self.samples], float).reshape(nt, nv)
        tq = np.array([s[5] for s in self.samples], float).reshape(nt, nv)
        sw = self._angles(np.array([s[6] for s in self.samples], float).reshape(
            nt, len(m.free), 3))
        nr_all = len(model.ropes)
        fmax, tmax, static = (np.full(nr_all, np.nan) for _ in range(3))
        fmax[m.ropes], tmax[m.ropes], static[m.ropes] = self.peak, self.peak_t, m.S0
        warnings = list(m.warnings)
        if m.inactive_ropes:
            warnings.append("rope(s) " + ", ".join(m.inactive_ropes) + " join only bodies "
                            "whose motion is prescribed: their forces are not computed "
                            "(rigid structure)")
        if model.effects.damping == "modal":
            warnings.append("damping: modal is applied as element dashpots b = psi c / "
                            "(2 pi w) at each rope's current axial frequency (modes do not "
                            "exist along a large motion)")
        # a torque, force or motor drive acts to the end: no free swing after it
        active = any(d.kind in ("torque", "motor") for d in spec.drives)
        t_end = np.inf if active else spec.motion_end
        resid = np.full(len(m.free), np.nan)
        if np.isfinite(t_end) and len(t) and t_end < t[-1]:
            after = t >= t_end - 1e-9
            resid = sw[after].max(axis=0) if after.any() else resid
            ev = self.last
            Xl = ev.X if ev.X is not None else self.ops.place(ev.t, ev._q, ev._v)[0]
            for k in range(len(m.free)):
                l = np.linalg.norm(Xl[m.hang[k]] - Xl[m.free[k]])
                period = 2 * np.pi * np.sqrt(l / np.linalg.norm(m.g))
                if m.sway and t[-1] - t_end < period:
                    warnings.append(f"the run ends {t[-1] - t_end:.3g} s after the last "
                                    f"drive stops, less than the swing period of "
                                    f"{model.node_names[m.free[k]]} ({period:.3g} s): its "
                                    "residual sway is a lower bound; extend the duration")
        E1 = getattr(self, "last_E", self.E0)
        dE = sum(E1) - sum(self.E0)
        scale = max(abs(self.W), abs(self.D), *self.max_terms, 1e-300)
        err = abs(dE - self.W + self.D + self.Wd) / scale
        energy = {"kinetic_initial": self.E0[0], "kinetic_final": E1[0],
                  "gravity_change": E1[1] - self.E0[1], "elastic_initial": self.E0[2],
                  "elastic_final": E1[2], "work_drives": self.W, "dissipated": self.D,
                  "wound_on_drums": self.Wd}
        units = tuple(d.units for d in spec.drives)
        labels = []
        for k, i in enumerate(m.free):
            nm = model.node_names[i]
            if not m.sway:
                labels.append(f"{nm}.height")
            else:
                labels += [f"{nm}.{a}" for a in ("xz" if model.planar else "xyz")]
        labels += [f"joint {jc['drive'].name}" for jc in m.jc]      # m, or arc m
        labels += [] if getattr(m, "flex", None) is None else m.flex.labels()
        labels += [f"drum {model.drums[k].name}" for k in m.qdrums]
        return OperationResult(
            model.name, model.scene or "", model.effects.as_dict(), tuple(labels),
            self._reached(t) if status and len(t) else spec.duration, st.steps,
            st.rejected, st.newton_iterations, t,
            tuple(model.node_names[i] for i in self.mass_nodes), X,
            tuple(r.name for r in model.ropes), F, static, fmax, tmax,
            tuple(d.name for d in spec.drives), units,
            tuple(d.kind for d in spec.drives), pos, spd, tq,
            tuple(model.node_names[i] for i in m.free), sw,
            sw.max(axis=0) if nt else np.full(len(m.free), np.nan), resid,
            float(t_end), energy, float(err),
            sorted(e for e in st.events if not (status and len(t) and e[0] > t[-1])),
            timings, warnings, status, message,
            {jc["drive"].name: float(m.joint_hold[c]) for c, jc in enumerate(m.jc)
             if jc["drive"].kind in ("torque", "motor")})
