"""`simulate(model)`: run the operation scene of a model (docs/operations.md).

The trapezoidal rule (Newmark's average acceleration, beta = 1/4, gamma = 1/2) on the
nonlinear equations `M q'' = F(t, q, q')`, each step solved by Newton's method on the
analytic tangent `4/h^2 M + 2/h C + K`; the step is chosen from the local error estimate
of Zienkiewicz & Xie (1991), `e = h^2 / 12 (a1 - a0)` (the position error of the step),
against `tolerance x model size`. Steps end at every kink of the prescribed motions; a
rope going slack or taut ends a step where its stretch ln(L/L0) crosses zero (located by
the Illinois variant of regula falsi on the step length, each trial a full step).
"""

import time

import numpy as np
from scipy.linalg.lapack import dgesv

from ...errors import AnalysisError
from .mechanism import Mechanism
from .results import Recorder
from .scene import parse

NEWTON_MAX = 12
MAX_STEPS = 2_000_000


class Stepper:
    def __init__(self, mech, spec, lscale):
        self.m, self.spec = mech, spec
        self.lscale = lscale
        n = mech.n
        self.wq = np.ones(n)                       # weights: metres of motion
        for c, k in enumerate(mech.qdrums):
            self.wq[mech.nx + c] = mech.model.drums[k].radius
        self.M = mech.M
        self.diag = np.arange(n) * (n + 1)         # flat indices of a (n, n) diagonal
        self.newton_tol = 1e-4 * spec.tolerance * lscale
        self.steps = self.rejected = self.newton_iterations = 0
        self.events = []
        self.kin_cache = {}

    def kin(self, t):
        k = self.kin_cache.get(t)
        if k is None:
            if len(self.kin_cache) > 8:
                self.kin_cache.clear()
            k = self.kin_cache[t] = self.m.kinematics(t)
        return k

    def accel(self, t, q, v, taut):
        ev = self.m.evaluate(t, q, v, taut, self.kin(t))
        return ev.F / self.M, ev

    def step(self, t0, q0, v0, a0, h, taut):
        """One trapezoidal step of length h -> (q1, v1, a1, ev1) or None."""
        t1 = t0 + h
        kin = self.kin(t1)
        M = self.M
        q1 = q0 + h * v0 + 0.5 * h * h * a0
        c1, c2 = 4.0 / (h * h), 2.0 / h
        dq_norm = np.inf
        ev = None
        for it in range(NEWTON_MAX):
            v1 = c2 * (q1 - q0) - v0
            a1 = c1 * (q1 - q0 - h * v0) - a0
            if dq_norm <= self.newton_tol:
                # quadratic convergence: the residual at q1 is O(dq^2); the forces of the
                # last iterate (dq away) serve the recorder and the event test
                return q1, v1, a1, self.m.powers(ev)
            ev = self.m.evaluate(t1, q1, v1, taut, kin, powers=False)
            self.newton_iterations += 1
            if not np.isfinite(ev.F).all():
                return None
            Rs = M * a1 - ev.F
            J = ev.K + c2 * ev.C
            J.ravel()[self.diag] += c1 * M
            # LAPACK's dgesv directly (LU with partial pivoting, as np.linalg.solve) without
            # numpy's per-call wrapping; info > 0: J singular
            _, _, dq, info = dgesv(J, -Rs, overwrite_a=True, overwrite_b=True)
            if info != 0 or not np.isfinite(dq).all():
                return None
            q1 = q1 + dq
            dq_norm = np.abs(dq * self.wq).max(initial=0.0)
        return None

    def stretch(self, ev):
        return np.log(ev.L / ev.L0)


def simulate(model, progress=None, initial=None):
    """Integrate the operation scene of `model` -> `OperationResult`.

    initial : optional dict {"q": (n,), "v": (n,)} replacing the static state (for tests
        and scripts: e.g. a load already on its steady slewing orbit); the ropes' unstretched
        lengths stay those of the static state.

    Length: the time-stepping loop with its step control and event location in one
    frame, as the transient engine's Newmark loop.
    """
    t_start = time.perf_counter()
    spec = parse(model)
    mech = Mechanism(model, spec)
    lscale = model.length_scale
    st = Stepper(mech, spec, lscale)
    T = spec.duration
    q = mech.q0.copy()
    v = np.zeros(mech.n)
    if initial is not None:
        q = np.asarray(initial.get("q", q), float).copy()
        v = np.asarray(initial.get("v", v), float).copy()
    taut = mech.taut0.copy()
    t = 0.0
    a, ev = st.accel(t, q, v, taut)
    rec = Recorder(mech, spec)
    t_setup = time.perf_counter()
    rec.start(t, q, v, a, ev, taut)
    bps = list(spec.breakpoints) + [T]
    for d in spec.drives:
        if d.motion is not None:
            for a0_, b0_ in d.motion.moves():
                if 0 < a0_ < T:
                    st.events.append((a0_, f"drive {d.name} starts"))
                if 0 < b0_ < T:
                    st.events.append((b0_, f"drive {d.name} stops"))
    h = min(spec.max_step, 1e-3 * T, 1e-2)
    tol = spec.tolerance * lscale
    hmin = 1e-12 * max(T, 1.0)
    bi = 0
    try:
        while t < T * (1 - 1e-14):
            while bi < len(bps) and bps[bi] <= t * (1 + 1e-14) + 1e-14:
                bi += 1
            t_next = bps[bi] if bi < len(bps) else T
            hh = min(h, spec.max_step, t_next - t)
            if t_next - t - hh < 1e-9 * hh:
                hh = t_next - t
            out = st.step(t, q, v, a, hh, taut)
            if out is None:
                st.rejected += 1
                h = hh * 0.25
                if h < hmin:
                    raise _blowup(t, h, "Newton's method does not converge", mech, ev, taut)
                continue
            q1, v1, a1, ev1 = out
            err = np.abs((hh * hh / 12.0) * (a1 - a) * st.wq).max(initial=0.0) / tol
            if err > 1.0:
                st.rejected += 1
                h = hh * max(0.2, 0.9 * err ** (-1 / 3))
                if h < hmin:
                    raise _blowup(t, h, "the step size collapsed", mech, ev, taut)
                continue
            # slack / taut events: the stretch ln(L/L0) of a rope changes sign
            g0, g1 = st.stretch(ev), st.stretch(ev1)
            cross = np.flatnonzero(np.where(taut, g1 < 0, g1 > 0))
            if len(cross):
                res = _locate(st, t, q, v, a, hh, taut, g0, cross)
                if res is None:
                    h = hh * 0.25
                    st.rejected += 1
                    continue
                hh, (q1, v1, a1, ev1), k = res
                rec.accept(t, q, v, a, ev, t + hh, q1, v1, a1, ev1, taut)
                t, q, v = t + hh, q1, v1
                taut = taut.copy()
                taut[k] = ~taut[k]
                name = model.ropes[mech.ropes[k]].name
                st.events.append((t, f"rope {name} {'taut' if taut[k] else 'slack'}"))
                a, ev = st.accel(t, q, v, taut)
                rec.switch(t, ev, taut)
                st.steps += 1
                continue
            rec.accept(t, q, v, a, ev, t + hh, q1, v1, a1, ev1, taut)
            t, q, v, a, ev = t + hh, q1, v1, a1, ev1
            st.steps += 1
            _two_blocking(mech, ev, t)
            mech.check_range(ev, t)
            if st.steps > MAX_STEPS:
                raise AnalysisError(f"more than {MAX_STEPS} steps at t = {t:.6g} s; raise "
                                    "analysis.tolerance")
            if progress is not None:
                progress(t, T)
            h_new = hh * min(2.0, 0.9 * err ** (-1 / 3)) if err > 0 else 2 * hh
            h = max(h, h_new) if hh < h else h_new      # a step cut at a breakpoint
    except AnalysisError as exc:
        t_end = time.perf_counter()
        exc.result = rec.result(st, {"setup": t_setup - t_start,
                                     "integrate": t_end - t_setup,
                                     "total": t_end - t_start}, status=1,
                                message=str(exc))
        raise
    t_end = time.perf_counter()
    return rec.result(st, {"setup": t_setup - t_start, "integrate": t_end - t_setup,
                           "total": t_end - t_start})


def _locate(st, t, q, v, a, h, taut, g0, cross):
    """Shortest step that ends where a rope's stretch crosses zero (Illinois)."""
    best = None
    for k in cross:
        lo, hi = 0.0, h
        glo, ghi = g0[k], None
        out = st.step(t, q, v, a, h, taut)
        if out is None:
            return None
        ghi = st.stretch(out[3])[k]
        side = 0
        cand = None
        for _ in range(60):
            x = hi - ghi * (hi - lo) / (ghi - glo) if ghi != glo else 0.5 * (lo + hi)
            x = min(max(x, lo + 1e-3 * (hi - lo)), hi - 1e-3 * (hi - lo)) \
                if hi - lo > 1e-12 * h else x
            o = st.step(t, q, v, a, x, taut)
            if o is None:
                return None
            gx = st.stretch(o[3])[k]
            cand = (x, o)
            if abs(gx) < 1e-13 or hi - lo < 1e-12 * max(h, 1e-300):
                break
            if np.sign(gx) == np.sign(ghi):
                hi, ghi = x, gx
                if side == 1:
                    glo *= 0.5
                side = 1
            else:
                lo, glo = x, gx
                if side == -1:
                    ghi *= 0.5
                side = -1
        if best is None or cand[0] < best[0]:
            best = (cand[0], cand[1], k)
    return best


def _two_blocking(mech, ev, t):
    """A span that touches a load shrinks to 1 % of its reference length: the load has
    reached its sheave (the engine has no contact model for that)."""
    if not len(mech.span_a):
        return
    l = np.linalg.norm(ev.X[mech.span_b] - ev.X[mech.span_a], axis=1)
    short = np.flatnonzero((l < 0.01 * mech.span_ref) & ~(mech.kin_a & mech.kin_b))
    if len(short):
        k = short[0]
        names = mech.model.node_names
        raise AnalysisError(
            f"at t = {t:.6g} s the span {names[mech.span_a[k]]}-{names[mech.span_b[k]]} "
            f"is down to {l[k]:.3g} m ({l[k] / mech.span_ref[k]:.1%} of its length): the "
            "load was hauled into its sheave (two-blocking); likely cause: a drive torque "
            f"far above what holds the load; the results up to t = {t:.6g} s are kept")


def _blowup(t, h, what, mech, ev, taut):
    slack = int((~taut).sum())
    cause = ("ropes switching between slack and taut (snatch loads) faster than the "
             "step can follow" if slack else
             "a drive accelerating the load harder than the ropes can transmit, or a "
             "tolerance too tight for the rope's axial frequency")
    return AnalysisError(f"{what} at t = {t:.6g} s (step {h:.3g} s): likely cause: "
                         f"{cause}; the results up to t = {t:.6g} s are kept")
