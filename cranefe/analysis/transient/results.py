"""The result of a transient run, and the recorder that fills it while stepping.

Peak rope forces are tracked on every step, not only at the stored output times: between
the ends of a step the force of each rope row is the cubic Hermite interpolant of its
values and rates there (S = S0 + c R q, S' = c R q'), whose interior maximum is taken
where the rate changes sign. This removes the sampling error of the peak (the step's own
error remains, O(h^2) for the trapezoidal rule).
"""

from dataclasses import dataclass, field

import numpy as np

from .equations import DENSE_OPS

MAX_SAMPLES = 2000      # stored output times when no output_step is given


@dataclass
class TransientResult:
    """Time histories and peaks of one transient scene (docs/transient.md)."""

    model_name: str
    scene: str
    effects: dict
    method: str                    # direct | modal
    initial: str                   # static | grounded
    dofs: int
    labels: tuple                  # (n,) generalised coordinates
    duration: float                # s
    time_step: float               # s
    steps: int
    modes: int                     # elastic modes retained (modal), else 0
    highest_frequency_hz: float    # highest frequency the step resolves (retained)
    times: np.ndarray              # (nt,) output times
    q: np.ndarray                  # (nt, n) displacements from the reference state
    v: np.ndarray                  # (nt, n) velocities
    rope_names: tuple              # (nr,)
    rope_force: np.ndarray         # (nt, nr) N, the largest force along each rope
    rope_force_static: np.ndarray  # (nr,) N, with the load hanging at rest
    rope_force_max: np.ndarray     # (nr,) N, peak over the run (every step, interpolated)
    rope_force_max_time: np.ndarray  # (nr,) s
    dynamic_factor: np.ndarray     # (nr,) peak / static (phi2 of EN 13001-2)
    drum_names: tuple              # (nd,) drums with a rotation coordinate
    drum_drive: tuple              # (nd,) speed | torque | motor | held
    drum_angle: np.ndarray         # (nt, nd) rad
    drum_speed: np.ndarray         # (nt, nd) rad/s
    drum_torque: np.ndarray        # (nt, nd) N m at the drum (applied, or what holds the
                                   #   prescribed speed)
    load_names: tuple              # (nl,) nodes with a point mass
    load_displacement: np.ndarray  # (nt, nl, 3) m
    ground_names: tuple            # (ng,) loads resting on the ground at the start
    ground_force: np.ndarray       # (nt, ng) N, the ground's push on each
    lift_off_times: np.ndarray     # (ng,) s, nan if it never lifts
    lift_off_time: float           # s, the first lift-off, nan if none
    energy_error: float            # |dE - W + D + L| / largest term: the balance
    energy: dict                   # initial, final, work_loads, work_drives, dissipated,
                                   #   impact_loss (J)
    events: list = field(default_factory=list)     # "0.1799 s: lift-off HOOK", ...
    timings: dict = field(default_factory=dict)
    warnings: list = field(default_factory=list)
    status: int = 0
    message: str = "ok"

    def to_dict(self):
        """The JSON document of ``cranefe simulate --json`` (docs/transient.md)."""
        from .output import document
        return document(self)


def hermite_peaks(S0, S1, d0, d1, h):
    """Largest value of the cubic Hermite interpolants through (S0, d0) and (S1, d1)
    over a step h, and where (fraction of h); rows with no interior maximum keep the
    larger end value."""
    best = np.maximum(S0, S1)
    where = np.where(S1 >= S0, 1.0, 0.0)
    m0, m1 = h * d0, h * d1
    cand = np.flatnonzero((m0 > 0) & (m1 < 0))
    if len(cand):
        p0, p1, a0, a1 = S0[cand], S1[cand], m0[cand], m1[cand]
        A = 6 * (p0 - p1) + 3 * (a0 + a1)
        B = -6 * (p0 - p1) - 4 * a0 - 2 * a1
        C = a0
        with np.errstate(divide="ignore", invalid="ignore"):
            disc = np.sqrt(np.maximum(B * B - 4 * A * C, 0.0))
            r1 = np.where(np.abs(A) > 1e-14 * (np.abs(B) + np.abs(C)),
                          (-B - disc) / (2 * A), -C / B)
            r2 = np.where(np.abs(A) > 1e-14 * (np.abs(B) + np.abs(C)),
                          (-B + disc) / (2 * A), -C / B)
        for r in (r1, r2):
            ok = (r > 0) & (r < 1)
            s = np.where(ok, r, 0.0)
            val = (2 * s**3 - 3 * s**2 + 1) * p0 + (s**3 - 2 * s**2 + s) * a0 \
                + (-2 * s**3 + 3 * s**2) * p1 + (s**3 - s**2) * a1
            better = ok & (val > best[cand])
            best[cand] = np.where(better, val, best[cand])
            where[cand] = np.where(better, s, where[cand])
    return best, where


class Recorder:
    """Fills a TransientResult from the accepted steps of a `newmark.Stepper`."""

    def __init__(self, problem, eq, stride_ok=True, clip=True):
        self.p, self.eq = problem, eq
        self.clip = clip                 # tension-only ropes (direct): no negative forces
        p = problem
        self.nr = len(p.model.ropes)
        self.peak = None
        self.peak_t = None
        self.samples = []
        self.min_force = np.inf
        model = p.model
        self.load_nodes = [int(i) for i in model.masses.nodes]
        dofs = p.system.dofs
        self.load_T = [dofs.T[dofs.layout.node([i])[0]].toarray() for i in self.load_nodes]
        self.R = p.R.toarray() if p.n <= DENSE_OPS else p.R

    def _full(self, s):
        if self.eq.to_full is None:
            return s.x, s.v, s.a
        return self.eq.to_full(s.t, s.x, s.v, s.a)

    def _tension(self, q):
        return self.p.S0 + self.p.c * (self.R @ q)

    def start(self, s, stepper):
        self.stepper = stepper
        q, v, a = self._full(s)
        S = self._tension(q)
        self.peak = np.maximum(S, 0.0) if self.clip else S.copy()
        self.peak_t = np.zeros(len(S))
        self.scale = max(np.abs(self.p.hanging).max(initial=0.0), 1e-300)
        self.fell = np.zeros(len(S), dtype=bool)
        self.min_force = float(S.min(initial=np.inf))
        self._last = (s, q, v)
        self._last_a = (s.a, a)
        self._sample(s, q, v, a)

    def sample(self, s):
        """Store the state s as an output time."""
        last, q, v = self._last
        if last is s and self._last_a is not None and self._last_a[0] is s.a:
            a = self._last_a[1]
        else:
            q, v, a = self._full(s)
        self._sample(s, q, v, a)

    def accept(self, s0, s1):
        last, q0, v0 = self._last
        if last is not s0:               # the state was switched (event): recompute
            q0, v0, _ = self._full(s0)
        q1, v1, a1 = self._full(s1)
        p = self.p
        h = s1.t - s0.t
        if h > 0 and len(p.c):
            S0, S1 = self._tension(q0), self._tension(q1)
            d0, d1 = p.c * (self.R @ v0), p.c * (self.R @ v1)
            if not self.clip:
                self.min_force = min(self.min_force, float(S1.min()))
            best, where = hermite_peaks(S0, S1, d0, d1, h)
            # the time of a later peak replaces that of an earlier one only if it is
            # higher by more than 1e-4 (equal peaks of an undamped run differ by the
            # interpolation error); within one rise the time follows the maximum
            up = best > self.peak
            later = up & self.fell & (best > self.peak + 1e-4 * np.maximum(
                np.abs(self.peak), self.scale))
            move = (up & ~self.fell) | later
            self.peak_t[move] = s0.t + where[move] * h
            self.fell[move] = False
            self.peak = np.maximum(self.peak, best)
            self.fell |= d1 < 0
        self._last = (s1, q1, v1)
        self._last_a = (s1.a, a1)

    def _sample(self, s, q, v, a):
        p = self.p
        S = self._tension(q)
        if self.clip:
            S = np.where(s.taut, np.maximum(S, 0.0), 0.0) if len(s.taut) == len(S) \
                else np.maximum(S, 0.0)
        forces = np.array([S[p.rope_of_row == k].max() if np.any(p.rope_of_row == k)
                           else np.nan for k in range(self.nr)])
        taut = s.taut if len(s.taut) == len(p.c) else np.ones(len(p.c), dtype=bool)
        torque = p.drum_torque(s.t, q, v, a, taut)
        ground = np.zeros(len(p.contacts))
        if len(p.contacts) and len(s.on) == len(p.contacts):
            r = p.eq.residual(s.t, q, v, a, taut)[p.contacts] * p.up
            ground = np.where(s.on, r, 0.0)
        disp = np.array([(T @ q) for T in self.load_T]).reshape(len(self.load_T), 3)
        self.samples.append((s.t, q.copy(), v.copy(), forces, torque, ground, disp))

    def result(self, method, h, steps, modes, f_hz, stepper, timings, warnings):
        p = self.p
        model = p.model
        t = np.array([x[0] for x in self.samples])
        Q = np.array([x[1] for x in self.samples])
        V = np.array([x[2] for x in self.samples])
        forces = np.array([x[3] for x in self.samples]).reshape(len(t), self.nr)
        torque = np.array([x[4] for x in self.samples]).reshape(len(t), len(p.drum_q))
        ground = np.array([x[5] for x in self.samples]).reshape(len(t), len(p.contacts))
        disp = np.array([x[6] for x in self.samples]).reshape(len(t), len(self.load_nodes),
                                                             3)
        fmax, tmax, static = (np.full(self.nr, np.nan) for _ in range(3))
        for k in range(self.nr):
            rows = np.flatnonzero(p.rope_of_row == k)
            if len(rows):
                j = rows[np.argmax(self.peak[rows])]
                fmax[k], tmax[k] = self.peak[j], self.peak_t[j]
                static[k] = p.hanging[rows].max()
        with np.errstate(divide="ignore", invalid="ignore"):
            factor = np.where(static > 0, fmax / static, np.nan)
        drums = list(p.drum_q)
        dq = [p.drum_q[d] for d in drums]
        lift = np.full(len(p.contacts), np.nan)
        for j, tt in stepper.lift_off.items():
            lift[j] = tt
        names = {**{k: n for k, n in enumerate(f"rope {model.ropes[r].name}"
                                                for r in p.rope_of_row)}}
        m = len(p.c)
        events = []
        for tt, k, what in stepper.events:
            who = names[k] if k < m else model.node_names[p.spec.grounded[k - m]]
            events.append(f"{tt:.6g} s: {who} {what}")
        err, E1 = stepper.energy_error()
        energy = {"initial": stepper.E0, "final": E1, **stepper.energy}
        eff = model.effects.as_dict()
        return TransientResult(
            model.name, model.scene or "", eff, method, p.spec.initial, p.n, p.labels,
            p.spec.duration, h, steps, modes, f_hz, t, Q, V,
            tuple(r.name for r in model.ropes), forces, static, fmax, tmax, factor,
            tuple(model.drums[d].name for d in drums),
            tuple(p.drive_of[d][0] for d in drums),
            Q[:, dq] if dq else np.zeros((len(t), 0)),
            V[:, dq] if dq else np.zeros((len(t), 0)), torque,
            tuple(model.node_names[i] for i in self.load_nodes), disp,
            tuple(model.node_names[i] for i in p.spec.grounded), ground, lift,
            float(np.nanmin(lift)) if np.any(np.isfinite(lift)) else float("nan"),
            float(err), energy, events, timings, list(warnings))
