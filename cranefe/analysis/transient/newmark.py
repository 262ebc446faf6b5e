"""Newmark's average-acceleration method with events (docs/transient.md, "Method").

The trapezoidal rule (Newmark beta = 1/4, gamma = 1/2) is unconditionally stable and, for
a linear system, conserves the discrete energy exactly: over a step
``E1 - E0 = (F0 + F1)/2 . (x1 - x0) - h v_avg . C v_avg``. Tension-only rows and ground
contacts make the system piecewise linear; within a step the set of taut rows and of
contacts that are on is held fixed, so the step is linear (Newton on it converges in one
iteration; iterations are only needed for a motor's nonlinear characteristic). When the
set changes during a step - a rope goes slack or taut again, a load lifts off or lands -
the step is cut at the event: the step length at which the first event function
(tension, ground reaction, height) crosses zero is found by the Illinois variant of
regula falsi on the step length (each trial a Newmark step of that length), the set is
switched there and the step continues. Energy is thus kept across events (the balance is
exact up to the event tolerance), and nothing depends on a step being small.

Steps end on the grid k h, on every breakpoint of the loads (ends of ramps, table
times) and on events; at breakpoints and events the accelerations are recomputed from
the equations (right-hand limits).
"""

import numpy as np

from ...errors import AnalysisError
from .equations import Factor

EVENT_TOL = 1e-9       # event functions, relative to their force / length scale
MAX_ITER = 60          # Illinois iterations per event
CHATTER = 25           # zero-length events in a row at one time before giving up


OVERFLOW = 1e100       # |x| / length scale beyond which the response has overflowed


def _bounded(s1, t, ls):
    """An AnalysisError naming the time if a step's response is not finite or beyond
    OVERFLOW times the model's length scale (squares of it would overflow doubles)."""
    big = np.abs(s1.x).max(initial=0.0), np.abs(s1.v).max(initial=0.0)
    if not (np.isfinite(big).all() and big[0] < OVERFLOW * ls):
        raise AnalysisError(f"the response grows without bound (overflows) in the step "
                            f"from t = {t:.6g} s to {s1.t:.6g} s; check the loads, drive "
                            "torques and speeds, the duration and the time step")


class State:
    __slots__ = ("t", "x", "v", "a", "taut", "on")

    def __init__(self, t, x, v, a, taut, on):
        self.t, self.x, self.v, self.a, self.taut, self.on = t, x, v, a, taut, on


class Stepper:
    """Integrates `Equations` from rest (x = 0, x' from the prescribed speeds)."""

    def __init__(self, eq, force_scale, length_scale, recorder=None, progress=None):
        self.eq = eq
        self.fs, self.ls = force_scale, length_scale
        self.recorder = recorder
        self.progress = progress
        self._factors = {}
        self._mass_lu = {}
        self.energy = {"work_loads": 0.0, "work_drives": 0.0, "dissipated": 0.0,
                       "impact_loss": 0.0}
        self.events = []            # (t, index in the event vector, what)
        self.lift_off = {}          # contact index -> first lift-off time
        self.warnings = []
        self.n_factor = 0
        self.h_grid = np.inf

    # ------------------------------------------------------------ one step
    def _factor(self, h, taut, on):
        """The step matrix's factorisation; kept for the grid step (one per active
        set), made afresh for the one-off lengths of event location and breakpoints."""
        eq = self.eq
        key = (h, taut.tobytes(), on.tobytes())
        fac = self._factors.get(key)
        if fac is None:
            keep = abs(h - self.h_grid) <= 1e-12 * self.h_grid
            if keep and len(self._factors) > 64:
                self._factors.clear()
            idx, *_ = eq.known(0.0, on)
            free = np.setdiff1d(np.arange(eq.n), idx)
            A = eq.matrix(h, taut, 4.0 / h**2)
            V = D = None
            if eq.U is not None:
                V, D = eq.U[free], (2.0 / h) * eq.W
            fac = Factor(A, free, V, D)
            fac.motor_E = np.column_stack([m.e[free] for m in eq.motors]) \
                if eq.motors else None
            if keep:
                self._factors[key] = fac
            self.n_factor += 1
        return fac

    def trial(self, s, h):
        """The state after a step of length h from s with s's active set."""
        eq = self.eq
        t1 = s.t + h
        alpha = 4.0 / h**2
        fac = self._factor(h, s.taut, s.on)
        free = fac.free
        idx, kq, kv, ka = eq.known(t1, s.on, left=True)
        # incremental form (less cancellation): unknown dx = x1 - x0 on free rows
        z = (4.0 / h) * s.v + s.a
        y = s.v.copy()
        z[idx] = 0.0
        y[idx] = 0.0
        D, Vk, Ak = np.zeros(eq.n), np.zeros(eq.n), np.zeros(eq.n)
        D[idx], Vk[idx], Ak[idx] = kq - s.x[idx], kv, ka
        b = eq.force(t1, left=True) - eq.internal(s.x, s.taut) - eq.K @ D \
            + eq.M @ (z - Ak) + eq.damp(y - Vk)
        if len(eq.c) and s.taut.any():
            b -= eq.RT @ np.where(s.taut, eq.c * (eq.R @ D), 0.0)
        bf = b[free]

        def complete(dxf):
            dx = D.copy()
            dx[free] = dxf
            a1 = alpha * (dx - h * s.v) - s.a
            v1 = s.v + 0.5 * h * (s.a + a1)
            a1[idx], v1[idx] = ka, kv
            return s.x + dx, v1, a1

        if not eq.motors:
            x1, v1, a1 = complete(fac.solve(bf))
        else:                   # Newton on the motors' speed-dependent torques
            xf = fac.solve(bf + eq.motor_force(s.v)[free])
            E = fac.motor_E
            for it in range(50):
                x1, v1, a1 = complete(xf)
                Fm = np.zeros(eq.n)
                d = np.zeros(len(eq.motors))
                for k, m in enumerate(eq.motors):
                    f, _, d[k] = m.force(v1)
                    Fm += f
                dk = -(2.0 / h) * d
                new = fac.solve(bf + Fm[free] + E @ (dk * (E.T @ xf)), extra=(E, dk))
                step = np.abs(new - xf).max()
                xf = new
                if step <= 1e-13 * (np.abs(xf).max() + h * np.abs(v1[free]).max() + 1e-300):
                    break
            else:
                raise AnalysisError(f"the motor characteristic did not converge at "
                                    f"t = {t1:.6g} s; give a smaller time_step")
            x1, v1, a1 = complete(xf)
        return State(t1, x1, v1, a1, s.taut, s.on)

    # ------------------------------------------------------------ events
    def event_values(self, s, left=True):
        """Event functions, scaled: >= 0 while the active set is right (left=False at
        the start of a step: right-hand limits of the loads)."""
        eq = self.eq
        g_rows = np.zeros(0)
        if len(eq.c):
            S = eq.tension(s.x)
            g_rows = np.where(s.taut, S, -S) / self.fs
        g_c = np.zeros(0)
        if len(eq.contacts):
            react = eq.residual(s.t, s.x, s.v, s.a, s.taut, left)[eq.contacts] * eq.up
            g_c = np.where(s.on, react / self.fs, eq.up * s.x[eq.contacts] / self.ls)
        return np.concatenate([g_rows, g_c])

    def _switch(self, s, which):
        """Switch the rows/contacts `which` (indices into the event vector) at state s."""
        eq = self.eq
        m = len(eq.c)
        taut, on = s.taut.copy(), s.on.copy()
        texts = []
        for k in which:
            if k < m:
                taut[k] = not taut[k]
                texts.append((k, "taut" if taut[k] else "slack"))
            else:
                j = k - m
                on[j] = not on[j]
                ci = eq.contacts[j]
                if not on[j]:
                    self.lift_off.setdefault(j, s.t)
                    texts.append((k, "lift-off"))
                else:               # landing: plastic impact, the load stops
                    e0 = 0.5 * s.v @ (eq.M @ s.v)
                    s.v = s.v.copy()
                    s.v[ci] = 0.0
                    self.energy["impact_loss"] += e0 - 0.5 * s.v @ (eq.M @ s.v)
                    texts.append((k, "landing"))
        s2 = State(s.t, s.x, s.v, s.a, taut, on)
        s2.a = self.accelerations(s2, left=False)
        return s2, texts

    def accelerations(self, s, left=False):
        """Accelerations from the equations at state s (right-hand limits at kinks);
        coordinates without inertia keep theirs (they never enter a step)."""
        eq = self.eq
        idx, _, _, ka = eq.known(s.t, s.on, left=left)
        a = s.a.copy() if s.a is not None else np.zeros(eq.n)
        a[idx] = ka
        fm = np.setdiff1d(np.flatnonzero(eq.mass), idx)
        if not len(fm):
            return a
        Ak = np.zeros(eq.n)
        Ak[idx] = ka
        rhs = eq.force(s.t, left) + eq.motor_force(s.v) - eq.damp(s.v) \
            - eq.internal(s.x, s.taut) - eq.M @ Ak
        key = fm.tobytes()
        lu = self._mass_lu.get(key)
        if lu is None:
            lu = Factor(eq.M, fm)
            self._mass_lu[key] = lu
        a[fm] = lu.solve(rhs[fm])
        return a

    def _locate(self, s, H, s1, cand, g0):
        """Illinois regula falsi on the step length: the first crossing of the
        candidates' event functions. Returns the state at (just past) it."""
        ha, fa = 0.0, float(np.min(g0[cand]))
        hb, fb = H, float(np.min(self.event_values(s1)[cand]))
        sb, side = s1, 0
        for _ in range(MAX_ITER):
            hc = hb - fb * (hb - ha) / (fb - fa) if fb != fa else 0.5 * (ha + hb)
            if not ha < hc < hb:
                hc = 0.5 * (ha + hb)
            sc = self.trial(s, hc)
            fc = float(np.min(self.event_values(sc)[cand]))
            if abs(fc) <= EVENT_TOL:
                return sc
            if fc < 0:
                hb, fb, sb = hc, fc, sc
                if side == -1:
                    fa *= 0.5
                side = -1
            else:
                ha, fa = hc, fc
                if side == 1:
                    fb *= 0.5
                side = 1
            if hb - ha <= 1e-13 * H:
                return sb
        return sb

    # ------------------------------------------------------------ the run
    def run(self, duration, h, breakpoints=(), stride=1):
        """Step from 0 to `duration` on a grid of about `h`, landing on `breakpoints`,
        locating events and recording every `stride`-th step.

        Length: the time-stepping loop with its event handling; the hot loop is kept in
        one frame for speed.
        """
        eq = self.eq
        n_grid = int(np.ceil(duration / h - 1e-9))
        h = duration / n_grid
        self.h_grid = h
        grid = h * np.arange(1, n_grid + 1)
        bps = np.asarray([b for b in breakpoints if 0 < b < duration])
        targets = np.unique(np.concatenate([grid, bps]))
        # merge targets closer than 1e-9 h to a grid time
        keep = np.ones(len(targets), dtype=bool)
        keep[1:] = np.diff(targets) > 1e-9 * h
        targets = targets[keep]
        is_bp = np.array([np.any(np.abs(bps - t) <= 1e-9 * h) for t in targets]) \
            if len(bps) else np.zeros(len(targets), dtype=bool)
        out_every = {int(round(t / h)) for t in grid[stride - 1::stride]} | {n_grid}

        x = np.zeros(eq.n)
        v = np.zeros(eq.n)
        on = np.ones(len(eq.contacts), dtype=bool)
        idx, _, kv, _ = eq.known(0.0, on)
        v[idx] = kv
        taut = eq.S0 >= 0
        if np.any(~taut):
            self.warnings.append(f"{int(np.sum(~taut))} rope element(s) start in "
                                 "compression, i.e. slack")
        s = State(0.0, x, v, None, taut, on)
        s.a = self.accelerations(s, left=False)
        self.E0 = eq.energy(s.x, s.v)
        if self.recorder:
            self.recorder.start(s, self)
        chatter = 0
        k_target = 0
        while k_target < len(targets):
            t_end = targets[k_target]
            H = t_end - s.t
            if abs(H - h) <= 1e-9 * h:
                H = h                 # the grid step (float noise of k h - t)
            with np.errstate(all="ignore"):     # an overflow is reported just below
                s1 = self.trial(s, H)
            _bounded(s1, s.t, self.ls)
            g1 = self.event_values(s1) if (len(eq.c) or len(eq.contacts)) else np.zeros(0)
            cand = np.flatnonzero(g1 < -EVENT_TOL)
            switched = []
            if len(cand):
                g0 = self.event_values(s, left=False)
                if np.min(g0[cand]) <= EVENT_TOL:       # already at the boundary
                    chatter += 1
                    if chatter > CHATTER:
                        self.warnings.append(f"chattering at t = {s.t:.6g} s: the active "
                                             "set keeps switching; kept as it is")
                        chatter = 0
                    else:
                        zero = cand[g0[cand] <= EVENT_TOL]
                        s, texts = self._switch(s, zero)
                        self._log(s.t, texts)
                        continue
                else:
                    s1 = self._locate(s, H, s1, cand, g0)
                    g1 = self.event_values(s1)
                    switched = cand[g1[cand] <= EVENT_TOL]
            chatter = 0
            self._account(s, s1)
            reached = abs(s1.t - t_end) <= 1e-12 * max(h, 1.0) or s1.t >= t_end
            if reached:
                s1.t = t_end
            if self.recorder:
                self.recorder.accept(s, s1)
            s = s1
            if len(switched):
                s, texts = self._switch(s, switched)
                self._log(s.t, texts)
            if reached:
                if is_bp[k_target]:
                    s.a = self.accelerations(s, left=False)
                k = int(round(s.t / h))
                if self.recorder and k in out_every and abs(s.t - k * h) <= 1e-9 * h:
                    self.recorder.sample(s)
                k_target += 1
                if self.progress:
                    self.progress(s.t, duration)
        self.final = s
        self.h = h
        self.steps = n_grid
        return s

    def _account(self, s0, s1):
        """Energy bookkeeping of one accepted step (exact for the trapezoidal rule)."""
        eq = self.eq
        dx = s1.x - s0.x
        F = 0.5 * (eq.force(s0.t) + eq.motor_force(s0.v) + eq.force(s1.t, left=True)
                   + eq.motor_force(s1.v))
        self.energy["work_loads"] += float(F @ dx)
        if eq.prescribed:
            pk = np.array(list(eq.prescribed))
            r0 = eq.residual(s0.t, s0.x, s0.v, s0.a, s0.taut)[pk]
            r1 = eq.residual(s1.t, s1.x, s1.v, s1.a, s1.taut, left=True)[pk]
            self.energy["work_drives"] += float(0.5 * (r0 + r1) @ dx[pk])
        if eq.has_damping:
            va = 0.5 * (s0.v + s1.v)
            self.energy["dissipated"] += float((s1.t - s0.t) * va @ eq.damp(va))

    def _log(self, t, texts):
        for k, what in texts:
            self.events.append((t, k, what))

    def energy_error(self):
        """|E1 - E0 - W + D + L| over the largest term of the balance."""
        e = self.energy
        E1 = self.eq.energy(self.final.x, self.final.v)
        lhs = E1 - self.E0
        rhs = e["work_loads"] + e["work_drives"] - e["dissipated"] - e["impact_loss"]
        scale = max(abs(self.E0), abs(E1), abs(e["work_loads"]), abs(e["work_drives"]),
                    e["dissipated"], e["impact_loss"], 1e-300)
        return abs(lhs - rhs) / scale, E1
