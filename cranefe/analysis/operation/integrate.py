"""`simulate(model)`: run the operation scene of a model (docs/operations.md).

The trapezoidal rule (Newmark's average acceleration, beta = 1/4, gamma = 1/2) on the
nonlinear equations `M q'' = F(t, q, q')`, each step solved by Newton's method on the
analytic tangent `4/h^2 M + 2/h C + K` (M diagonal, or block-diagonal with the joint
coordinates' dense M_J(u, t) and its derivative dM_J/du u'' in the tangent); the step is chosen from the local error estimate
of Zienkiewicz & Xie (1991), `e = h^2 / 12 (a1 - a0)` (the position error of the step),
against `tolerance x model size`, and from the error it makes in each rope's force,
`EA/L G e` (G = dL/dq), against `FORCE_TOL x tolerance x` the rope's force (the larger
of its static and its current force). Steps end at every kink of the prescribed motions; a
rope going slack or taut ends a step where its stretch ln(L/L0) crosses zero (located by
the Illinois variant of regula falsi on the step length, each trial a full step).
"""

import math
import time

import numpy as np
from scipy.linalg.lapack import dgetrf, dgetri

from ...errors import AnalysisError
from . import fast as _fast
from . import loop as _loop
from .constraints import ConstrainedStepper, algebraic_state, algebraic_velocity
from .lean import Generic, Lean, ops as _ops
from .mechanism import Mechanism
from .results import Recorder
from .scene import parse

NEWTON_MAX = 12
# the local error of the rope forces is held below FORCE_TOL x tolerance x the rope's
# static force (docs/operations.md "Integrator": chosen so that the default tolerance
# gives the peak forces of the bundled scenes to ~1e-3 or better (measured 1.2e-4 on
# the tower-crane cycle, 9.6e-4 on its lowering alone); 100 leaves 1.7e-3 on the
# cycle, 10 halves the error at 1.25x the steps)
FORCE_TOL = 20.0
MAX_STEPS = 2_000_000


class StepControl:
    """The next step length from the local error estimate err (relative to the
    tolerance; the trapezoidal rule's estimate is O(h^3), so err ~ C h^3).

    Accepted steps: Gustafsson's predictive controller (Gustafsson 1994; Hairer & Wanner,
    Solving ODEs II, IV.8 eq. 8.21, as in their Radau5): the smaller of the elementary
    `h safe err^(-1/3)` and `h safe (h / h_prev) (err_prev / err)^(1/3) err^(-1/3)`, which
    follows the trend of C instead of assuming it constant (the elementary rule overshoots
    where the error constant falls and is rejected where it rises: an oscillation of the
    rope's force moves the estimate by its phase). Rejected steps: `h safe err^(-1/3)`,
    and the step after a rejection does not grow. Factors bounded to [0.2, 2].
    """

    SAFE, LO, HI = 0.9, 0.2, 2.0

    def __init__(self):
        self.h_acc = self.err_acc = None
        self.after_reject = False

    def reset(self):
        """Forget the history (after an event or a step cut short at a breakpoint)."""
        self.h_acc = self.err_acc = None

    def accepted(self, h, err):
        err = max(err, 1e-10)
        fac = self.SAFE * err ** (-1 / 3)
        if self.h_acc is not None:
            fac = min(fac, self.SAFE * (h / self.h_acc) *
                      (self.err_acc / err) ** (1 / 3) * err ** (-1 / 3))
        fac = min(max(fac, self.LO), 1.0 if self.after_reject else self.HI)
        self.h_acc, self.err_acc = h, max(err, 1e-2)
        self.after_reject = False
        return h * fac

    def rejected(self, h, err):
        self.after_reject = True
        return h * max(self.LO, self.SAFE * err ** (-1 / 3))


class _FlexOps(Generic):
    """`Generic` for a mechanism with an elastic structure (flexible.py): the ropes'
    rows G = dL/dq of the step's force error include the elastic coordinates (their
    span columns R(t) depend on the time)."""

    def evaluate(self, t, q, v, taut, kin, tangent=True, full=True):
        ev = super().evaluate(t, q, v, taut, kin, tangent, full)
        nx = self.m.nx
        ev._G[:, :nx] = ev._flex_G
        return ev


class Stepper:
    def __init__(self, mech, spec, lscale, fast=None):
        self.m, self.spec = mech, spec
        # an elastic structure (flexible.py) is evaluated by Mechanism itself: Lean's
        # span vectors have no elastic columns; massless blocks (algebraic rows, M = 0)
        # likewise: Lean does not cover them
        self.qy = mech.qy if len(getattr(mech, "qy", ())) else None
        if getattr(mech, "flex", None) is not None:
            self.ops = _FlexOps(mech)
        else:
            self.ops = _ops(mech) if self.qy is None else Generic(mech)
        # the compiled step (fast.py) where Lean covers the mechanism and numba is
        # installed (fast=None), or as asked (fast=False: numpy, the reference)
        if fast is None:
            fast = _fast.available()
        self.fast = bool(fast) and type(self.ops) is Lean and _fast.available()
        if self.fast:
            self.ops = _fast.FastLean(mech)
        self.lscale = lscale
        n = mech.n
        self.wq = np.ones(n)                       # weights: metres of motion
        for c, k in enumerate(mech.qdrums):
            self.wq[mech.nx + c] = mech.model.drums[k].radius
        self.wq = None if (self.wq == 1.0).all() else self.wq     # None: all metres
        self._taut = None
        self.M = mech.M
        self.diag = np.arange(n) * (n + 1)         # flat indices of a (n, n) diagonal
        # joint coordinates: the mass matrix is block-diagonal, the loads' and drums'
        # diagonal (constant, self.M) and the joint coordinates' dense block M_J(u, t)
        # (ev.MJ, with its derivatives ev.dMJ); self.M has zeros there
        self.nJ = getattr(mech, "nJ", 0)
        if self.nJ:
            self.jd = mech.jb
            self.M = mech.M.copy()
            self.M[self.jd] = 0.0
        self.newton_tol = 1e-4 * spec.tolerance * lscale
        self.tol = spec.tolerance * lscale
        self.steps = self.rejected = self.newton_iterations = 0
        self.tangents = 0
        self.events = []
        # rope force error: the scale of each rope's force is the larger of its
        # current force and its static force (at least 1 % of the largest static
        # force); none if no rope carries a static force. fscale = EA / ftol
        S0 = np.abs(np.asarray(mech.S0, float)) if len(mech.ropes) else np.zeros(0)
        smax = float(S0.max(initial=0.0))
        self.ftol = FORCE_TOL * spec.tolerance
        self.fscale = (None if smax <= 0 or self.ftol <= 0 else
                       np.asarray(mech.EA, float) / self.ftol)
        self.sfloor = np.maximum(S0, 1e-2 * smax)

    def kin(self, t):
        return self.ops.kin(t)

    def accel(self, t, q, v, taut):
        ev = self.ops.evaluate(t, q, v, taut, self.kin(t), tangent=False)
        if self.nJ or self.qy is not None:
            # joint coordinates: their block solved; massless rows: no acceleration
            a = np.divide(ev.F, self.M, out=np.zeros_like(ev.F), where=self.M > 0)
            if self.nJ:
                a[self.jd] = np.linalg.solve(ev.MJ, ev.F[self.jd])
            return a, self.ops.powers(ev)
        return ev.F / self.M, self.ops.powers(ev)

    def inertia(self, ev, a):
        """M a with the mass matrix of the state `ev` (block-diagonal with joints)."""
        Ma = self.M * a
        if self.nJ:
            Ma[self.jd] += ev.MJ @ a[self.jd]
        return Ma

    def consistent(self, t, q, v, taut):
        """A massless block's position in equilibrium and its velocity by the implicit
        function (a given initial state; the static state already is)."""
        if self.qy is None:
            return q, v
        return algebraic_state(self, t, q, v, taut)

    def _factor(self, ev, c1, c2, a1=None):
        J = ev.K + c2 * ev.C
        J.ravel()[self.diag] += c1 * self.M
        if self.nJ:
            # d(F - M(q) a)/dq: c1 M_J + dM_J/du . a on the joint block (Kane's terms'
            # own derivatives are in ev.K and ev.C)
            jd = self.jd
            J[jd, jd] += c1 * ev.MJ
            if a1 is not None:
                J[jd, jd] += np.einsum("ijk,j->ik", ev.dMJ, a1[jd])
        # LAPACK's LU (partial pivoting, as np.linalg.solve) without numpy's wrapping,
        # then the inverse for the following iterations (modified Newton): for the few,
        # well-conditioned coordinates (4/h^2 M dominates) one product per iteration;
        # info > 0: J singular
        lu, piv, info = dgetrf(J, overwrite_a=True)
        self.tangents += 1
        if info != 0:
            return None
        inv, info = dgetri(lu, piv, overwrite_lu=True)
        return inv if info == 0 else None

    def error(self, h, a0, a1, ev1, taut):
        """The step's local error relative to the tolerances: the larger of the
        position error `h^2/12 |a1 - a0|` (Zienkiewicz & Xie 1991) over
        `tolerance x model size` (drum angles weighted by their radius), and the
        error it makes in each taut rope's force, `EA/L |G h^2/12 (a1 - a0)|`
        (G = dL/dq: the elongation error times the axial stiffness), over
        `FORCE_TOL x tolerance x` the larger of its static and its current force."""
        da = a1 - a0
        if self.qy is not None:         # massless blocks follow the others' positions
            da = da.copy()
            da[self.qy] = 0.0
        err = float(np.abs(da if self.wq is None else da * self.wq).max(initial=0.0))
        err /= self.tol
        if self.fscale is not None:
            ef = self.fscale * (ev1._G @ da) / (ev1.L * np.maximum(self.sfloor,
                                                                   np.abs(ev1.S)))
            ef = float(np.abs(ef if self.m_alltaut(taut) else
                              np.where(taut, ef, 0.0)).max(initial=0.0))
            err = max(err, ef)
        return err * (h * h / 12.0)

    def step(self, t0, q0, v0, a0, h, taut, jerk=None, left=False):
        """One trapezoidal step of length h -> (q1, v1, a1, ev1, err) or None.

        Newton's method from a predictor, on the tangent `4/h^2 M + 2/h C + K` made and
        factorised at the predictor and kept while the iteration contracts fast
        (modified Newton: every later iteration costs a residual and a back-substitution);
        made afresh at the current iterate when a correction shrinks by less than 10x.
        Converged when the last correction is below 1e-4 of the tolerance; the forces of
        that iterate (the correction away) serve the recorder and the event test (their
        power terms by `ops.powers`, for accepted steps only).
        Predictor: the trapezoidal rule's own q1 = q0 + h v0 + h^2/4 (a0 + a1) with a1
        extrapolated as a0 + h jerk (jerk: the last step's (a0 - a_prev) / h_prev), so
        that the first correction is the extrapolation's O(h^4) error.
        left: the step ends at a breakpoint of the prescribed motions and its end is
        evaluated there from the left (the motions' accelerations before their jump:
        a frame carrying an elastic structure, flexible.py, feeds them into the forces).
        """
        t1 = t0 + h
        if left:
            t1 = math.nextafter(t1, -math.inf)
        if self.fast:
            st, q1, v1, a1, err, its, tg, ev = self.ops.step(
                t1, q0, v0, a0, h, taut, jerk, self.M, self.newton_tol, NEWTON_MAX,
                self.fscale, self.sfloor, self.tol)
            self.newton_iterations += its
            self.tangents += tg
            return None if st else (q1, v1, a1, ev, err)
        kt = self.ops.kin(t1)
        M, wq = self.M, self.wq
        c1, c2 = 4.0 / (h * h), 2.0 / h
        q1 = q0 + h * v0 + (0.5 * h * h) * a0
        if jerk is not None:
            q1 = q1 + (0.25 * h * h * h) * jerk
        qb = q0 + h * v0            # a1 = c1 (q1 - q0 - h v0) - a0 (trapezoidal rule)
        Jinv = None
        prev = np.inf
        for it in range(NEWTON_MAX):
            v1 = c2 * (q1 - q0) - v0
            a1 = c1 * (q1 - qb) - a0
            fresh = Jinv is None
            ev = self.ops.evaluate(t1, q1, v1, taut, kt, tangent=fresh, full=False)
            self.newton_iterations += 1
            R = ev.F - (M * a1 if not self.nJ else self.inertia(ev, a1))
            if fresh:
                if not math.isfinite(R.sum()):
                    return None
                Jinv = self._factor(ev, c1, c2, a1)
                if Jinv is None:
                    return None
            dq = Jinv @ R
            dq_norm = float(np.abs(dq if wq is None else dq * wq).max(initial=0.0))
            if not math.isfinite(dq_norm):
                return None
            if not fresh and dq_norm <= self.newton_tol:
                # quadratic (or fast linear) convergence: the residual at q1 + dq is
                # O(dq^2); the forces of this iterate serve the recorder
                q1 = q1 + dq
                a1 = c1 * (q1 - qb) - a0
                v1 = c2 * (q1 - q0) - v0
                if self.qy is not None:     # massless blocks: v by the implicit function
                    v1, a1 = algebraic_velocity(self, t1, q1, v1, a1, v0, h, ev, taut)
                return q1, v1, a1, ev, self.error(h, a0, a1, ev, taut)
            if not fresh and dq_norm > 0.1 * prev:
                Jinv = None                      # slow: a fresh tangent next iteration
            prev = dq_norm
            q1 = q1 + dq
        return None

    def crossing(self, ev1, taut):
        """Ropes whose stretch ln(L/L0) changed sign over the step (slack / taut)."""
        lam = ev1.L / ev1.L0
        if self.m_alltaut(taut):
            return None if (lam >= 1.0).all() else np.flatnonzero(lam < 1.0)
        cross = np.flatnonzero(np.where(taut, lam < 1.0, lam > 1.0))
        return cross if len(cross) else None

    def m_alltaut(self, taut):
        if taut is not self._taut:
            self._taut, self._alltaut = taut, bool(taut.all())
        return self._alltaut

    def stretch(self, ev):
        return np.log(ev.L / ev.L0)

    def limit(self, t, q, v, a, ev, taut):
        """At a breakpoint of the drives: the state's limit from the right (a, ev,
        jumped); elastic ropes: continuous."""
        return a, ev, False

    def switch(self, t, q, v, taut, k):
        """After rope k went slack or taut: (v, note, work, dissipated) of a jump
        (none for elastic ropes; ConstrainedStepper jerks an inextensible rope taut)."""
        return v, "", 0.0, 0.0


def simulate(model, progress=None, initial=None, fast=None):
    """Integrate the operation scene of `model` -> `OperationResult`.

    initial : optional dict {"q": (n,), "v": (n,)} replacing the static state (for tests
        and scripts: e.g. a load already on its steady slewing orbit); the ropes' unstretched
        lengths stay those of the static state.
    fast : None (default): the whole loop compiled (loop.py) when numba is installed and
        the mechanism is one `Lean` covers; False: the numpy step (the reference);
        "step": the compiled step of fast.py in the Python loop (for measurements).

    Length: the time-stepping loop with its step control and event location in one
    frame, as the transient engine's Newmark loop.
    """
    t_start = time.perf_counter()
    spec = parse(model)
    mech = Mechanism(model, spec)
    lscale = model.length_scale
    st = (ConstrainedStepper if mech.inextensible else Stepper)(mech, spec, lscale, fast)
    T = spec.duration
    flex = getattr(mech, "flex", None) is not None
    q = mech.q0.copy()
    v = np.zeros(mech.n)
    if initial is not None:
        q = np.asarray(initial.get("q", q), float).copy()
        v = np.asarray(initial.get("v", v), float).copy()
    taut = mech.taut0.copy()
    if initial is not None and not mech.inextensible and len(taut):
        # an elastic rope is taut where the given state stretches it (L > L0), not as in
        # the static state: else a rope given slack starts "taut", the first step finds
        # its crossing at t ~ 0 and that step of ~1e-17 s, shorter than the positions'
        # round-off, reverses the given velocity (v1 = 2 (q1 - q0)/h - v0 with q1 = q0)
        ev0 = mech.evaluate(0.0, q, v, taut, damping=False, powers=False)
        taut = np.where(ev0.L != ev0.L0, ev0.L > ev0.L0, taut)
    t = 0.0
    if mech.inextensible or initial is not None:    # a given state made consistent
        q, v = st.consistent(t, q, v, taut)           # (ropes, massless blocks)
    a, ev = st.accel(t, q, v, taut)
    rec = Recorder(mech, spec, st.ops)
    t_setup = time.perf_counter()
    rec.start(t, q, v, a, ev, taut)
    bps = list(spec.breakpoints) + [T]
    for d in spec.drives:
        if d.motion is not None:
            for a0_, b0_ in d.motion.moves():
                if 0 <= a0_ < T:
                    st.events.append((a0_, f"drive {d.name} starts"))
                if 0 < b0_ < T:
                    st.events.append((b0_, f"drive {d.name} stops"))
    h = min(spec.max_step, 1e-3 * T, 1e-2)
    hmin = 1e-12 * max(T, 1.0)
    ctl = StepControl()
    jerk = None                  # (a0 - a_prev) / h_prev of the last accepted step
    bi = 0
    try:
        prep = _loop.prepare(st, spec) if st.fast and fast != "step" else None
        if prep is not None:            # the whole loop compiled (loop.py), same steps
            t = _loop.run(st, rec, spec, prep, t, q, v, ev, taut, progress, hmin,
                          NEWTON_MAX, MAX_STEPS, lambda *a: _fail(mech, *a))
        while t < T * (1 - 1e-14):
            while bi < len(bps) and bps[bi] <= t * (1 + 1e-14) + 1e-14:
                bi += 1
            t_next = bps[bi] if bi < len(bps) else T
            hh = min(h, spec.max_step, t_next - t)
            if t_next - t - hh < 1e-9 * hh:
                hh = t_next - t
            # a step ending at a breakpoint sees the prescribed accelerations from the
            # left (they act on joint coordinates through Kane's carried term, and on an
            # elastic structure through its frame's acceleration); the next step starts
            # from their right limits (below); the end of the run counts as a
            # breakpoint (a motion may change its segment there)
            at_bp = (bool(st.nJ) or flex) and hh == t_next - t
            mech.left_at = t + hh if at_bp else None
            out = st.step(t, q, v, a, hh, taut, jerk, at_bp and flex)
            if out is None:
                st.rejected += 1
                h = hh * 0.25
                ctl.after_reject = True
                if h < hmin:
                    raise _blowup(t, h, "Newton's method does not converge", mech, ev, taut)
                continue
            q1, v1, a1, ev1, err = out
            if err > 1.0:
                st.rejected += 1
                h = ctl.rejected(hh, err)
                if h < hmin:
                    raise _blowup(t, h, "the step size collapsed", mech, ev, taut)
                continue
            # slack / taut events: the stretch ln(L/L0) of a rope changes sign
            cross = st.crossing(ev1, taut)
            if cross is not None:
                res = _locate(st, t, q, v, a, hh, taut, st.stretch(ev), cross)
                if res is None:
                    h = hh * 0.25
                    st.rejected += 1
                    continue
                hh, (q1, v1, a1, ev1, _), k = res
                st.ops.powers(ev1)
                rec.accept(t, q, v, a, ev, t + hh, q1, v1, a1, ev1, taut)
                t, q, v = t + hh, q1, v1
                taut = taut.copy()
                taut[k] = ~taut[k]
                name = model.ropes[mech.ropes[k]].name
                tight = taut[k]
                v, note, dW, dD = st.switch(t, q, v, taut, k)
                rec.W, rec.D = rec.W + dW, rec.D + dD
                st.events.append((t, f"rope {name} {'taut' if tight else 'slack'}{note}"))
                a, ev = st.accel(t, q, v, taut)
                rec.switch(t, ev, taut)
                st.steps += 1
                jerk = None
                ctl.reset()
                continue
            st.ops.powers(ev1)          # the energy terms: for accepted steps only
            rec.accept(t, q, v, a, ev, t + hh, q1, v1, a1, ev1, taut)
            jerk = (a1 - a) / hh
            t, q, v, a, ev = t + hh, q1, v1, a1, ev1
            if at_bp:
                mech.left_at = None
                a, ev = st.accel(t, q, v, taut)       # the right limits
                jumped = True
            else:       # inextensible ropes: the force jumps with a drive's acceleration
                a, ev, jumped = st.limit(t, q, v, a, ev, taut)
            if jumped:
                rec.switch(t, ev, taut)
                jerk = None
            st.steps += 1
            _two_blocking(mech, st.ops.span_lengths(ev), t)
            mech.check_range(ev, t)
            if st.steps > MAX_STEPS:
                raise AnalysisError(f"more than {MAX_STEPS} steps at t = {t:.6g} s; raise "
                                    "analysis.tolerance")
            if progress is not None:
                progress(t, T)
            h_new = ctl.accepted(hh, err)
            if hh < h:                  # a step cut at a breakpoint: keep the longer one
                h = max(h, h_new)
                ctl.reset()
            else:
                h = h_new
        t_end = time.perf_counter()
        res = rec.result(st, {"setup": t_setup - t_start, "integrate": t_end - t_setup,
                              "total": t_end - t_start})
    except AnalysisError as exc:
        t_end = time.perf_counter()
        exc.result = rec.result(st, {"setup": t_setup - t_start,
                                     "integrate": t_end - t_setup,
                                     "total": t_end - t_start}, status=1,
                                message=str(exc))
        raise
    t_res = time.perf_counter()
    res.timings["results"] = t_res - t_end
    res.timings["total"] = t_res - t_start
    return res


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


def _two_blocking(mech, l, t):
    """A span that touches a load shrinks to 1 % of its reference length (l: the span
    lengths): the load has reached its sheave (the engine has no contact model)."""
    if not len(mech.span_a) or (l >= 0.01 * mech.span_ref).all():
        return
    short = np.flatnonzero((l < 0.01 * mech.span_ref) & ~(mech.kin_a & mech.kin_b))
    if len(short):
        k = short[0]
        names = mech.model.node_names
        raise AnalysisError(
            f"at t = {t:.6g} s the span {names[mech.span_a[k]]}-{names[mech.span_b[k]]} "
            f"is down to {l[k]:.3g} m ({l[k] / mech.span_ref[k]:.1%} of its length): the "
            "load was hauled into its sheave (two-blocking); likely cause: a drive torque "
            f"far above what holds the load; the results up to t = {t:.6g} s are kept")


def _fail(mech, status, t, h, taut, l):
    """The Python loop's AnalysisError for a failed status of the compiled loop."""
    if status == _loop.NEWTON:
        raise _blowup(t, h, "Newton's method does not converge", mech, None, taut)
    if status == _loop.COLLAPSE:
        raise _blowup(t, h, "the step size collapsed", mech, None, taut)
    if status == _loop.TWO_BLOCK:
        _two_blocking(mech, l, t)
    raise AnalysisError(f"more than {MAX_STEPS} steps at t = {t:.6g} s; raise "
                        "analysis.tolerance")


def _blowup(t, h, what, mech, ev, taut):
    slack = int((~taut).sum())
    cause = ("ropes switching between slack and taut (snatch loads) faster than the "
             "step can follow" if slack else
             "a drive accelerating the load harder than the ropes can transmit, or a "
             "tolerance too tight for the rope's axial frequency")
    return AnalysisError(f"{what} at t = {t:.6g} s (step {h:.3g} s): likely cause: "
                         f"{cause}; the results up to t = {t:.6g} s are kept")
