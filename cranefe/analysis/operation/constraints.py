"""Inextensible ropes (effect `rope_elasticity: false`) in operation scenes.

Every taut rope r is a constraint `g_r(q, t) = L_r(q, t) - L0_r(t) = 0` (L through all
falls at the current geometry, L0 following the drums: `L0 = L_ref - sum R theta`), its
multiplier the rope force S_r >= 0:

    M q'' = F(t, q, q') - G^T S,    G = dg/dq                         (1)
    g(q, t) = 0,   g' = G q' + g_t = 0,   g'' = G q'' + gamma = 0     (2)

with `gamma = sum_spans f [e . (A_b - A_a) + (|dV|^2 - (e . dV)^2) / l] + sum R alpha`
(A the prescribed accelerations of span ends, dV the relative velocity of a span's ends,
alpha the prescribed drums' angular accelerations): the second time derivative of
`sum f |x_b - x_a| - L0(t)` with q'' set to zero.

The step (docs/operations.md "Inextensible ropes"): the trapezoidal rule on the index-1
form - (1) with the acceleration constraint g'' = 0 - solved by Newton's method on the
saddle-point system in (q1, S1),

    [ 4/h^2 M + 2/h C + K + K_S   G^T ] [dq]   [ F - G^T S - M a1   ]
    [ G                            0  ] [dS] = [ -(G a1 + gamma) h^2/4 ]

(K_S = sum f S / l (I - e e^T) on the span ends: the ropes' tension stiffness), then
the end state projected onto g = 0 and g' = 0 (M-orthogonally) and its acceleration
and rope forces taken from (1), (2) at the projected state. The rope force is thus the
exact multiplier of a consistent state at every step end: a smooth function of the
state, converging with it at second order (the trapezoidal rule on the index-3 or
index-2 form gives multipliers oscillating from step to step).

Slack: a rope whose multiplier would go negative becomes inactive (event located where
S = 0); a slack rope that comes tight again (L = L0, located) is jerked taut: the
velocities jump by the impulse P (N s) that makes g' = 0 for every active rope,
`v+ = v- - M^-1 G^T P`, `P = (G M^-1 G^T)^-1 g'(v-)`; the kinetic energy it takes,
`P . g'(v-) / 2`, is booked as dissipated.
"""

import math

import numpy as np

from ...errors import AnalysisError, ModelError
from .lean import _TimeCache

NEWTON_MAX = 12
SLACK_STRAIN = 1e-10     # a slack rope is taut again when L / L0 - 1 exceeds this
                         # (above the projection's residual, 1e-13 of the length)


class ConstrainedStepper:
    """The trapezoidal step with inextensible ropes (module docstring): the integrator's
    interface of `integrate.Stepper` (step, accel, error, crossing, stretch, switch) and
    the recorder's (`ops`: evaluate, powers, energy, place, span_lengths)."""

    def __init__(self, mech, spec, lscale, fast=None):
        self.m, self.spec = mech, spec
        self.ops = self
        self.fast = False
        self.nJ = 0                  # joint coordinates are refused with these ropes
        self.kin = _TimeCache(mech.kinematics)
        n = mech.n
        self.M = np.asarray(mech.M, float)
        if (self.M <= 0).any():
            raise ModelError("a coordinate without mass cannot be solved with inextensible "
                             "ropes", mech.model.scene_file or mech.model.file,
                             "effects.rope_elasticity")
        self.Minv = 1.0 / self.M
        self.wq = np.ones(n)
        for c, k in enumerate(mech.qdrums):
            self.wq[mech.nx + c] = mech.model.drums[k].radius
        self.lscale = lscale
        self.tol = spec.tolerance * lscale
        self.newton_tol = 1e-4 * self.tol
        self.gtol = 1e-13 * lscale
        self.steps = self.rejected = self.newton_iterations = 0
        self.tangents = 0
        self.events = []
        nr = len(mech.ropes)
        self.none = np.zeros(nr, bool)
        S0 = np.abs(np.asarray(mech.S0, float))
        self.sscale = np.maximum(S0, 1e-2 * max(float(S0.max(initial=0.0)), 1e-300))
        self.delta = 1e-7 * max(spec.duration, 1.0)   # the rope forces' rate
        self._Sguess = np.asarray(mech.S0, float).copy()
        # where a prescribed acceleration jumps, so do the loads' acceleration and the
        # rope forces: a step ending there uses the limit from the left, the next one
        # starts from the limit from the right (`limit`)
        self.bps = np.concatenate([[0.0], spec.breakpoints])
        self.dbp = 1e-9 * max(spec.duration, 1.0)
        self._check_rank(mech)

    def _check_rank(self, mech):
        """The taut ropes' constraints must be independent (G M^-1 G^T regular): ropes
        that hold one load twice over are statically indeterminate when inextensible."""
        act = np.flatnonzero(mech.taut0)
        if not len(act):
            return
        geo = self.geometry(0.0, mech.q0, np.zeros(mech.n), self.kin(0.0))
        Ga = geo["G"][act]
        s = np.linalg.svd(Ga * np.sqrt(self.Minv), compute_uv=False)
        if s.min() <= 1e-10 * s.max():
            names = ", ".join(mech.model.ropes[mech.ropes[j]].name for j in act)
            raise ModelError(f"the inextensible ropes {names} hold the loads more than once "
                             "over (statically indeterminate: their forces are not defined "
                             "without their elasticity); use elastic ropes", mech.model.scene_file
                             or mech.model.file, "effects.rope_elasticity")

    # ------------------------------------------------------------ constraint kinematics
    def geometry(self, t, q, v, kin, ev=None):
        """g = L - L0, its rows G = dg/dq (nr, n), rate g' = G v + g_t and gamma (2),
        with the node positions and velocities, at (t, q, v) (those of `ev`, the
        Mechanism's Eval at that state, if given)."""
        m = self.m
        if ev is None:
            X, V, theta, omega = m.place(t, q, v, kin)
        else:
            X, V, theta, omega = ev.X, ev.V, ev.theta, ev.omega
        d = X[m.span_b] - X[m.span_a]
        l = np.sqrt(np.einsum("ij,ij->i", d, d))
        e = d / l[:, None]
        L = m.A @ (m.falls * l) + m.extra
        L0 = m.unstretched(theta)
        eD = np.einsum("si,sij->sj", e, m.D)
        G = np.zeros((len(L), m.n))
        G[:, :m.nx] = m.A @ (m.falls[:, None] * eD)
        for c, k in enumerate(m.qdrums):          # dg/dtheta = -dL0/dtheta = R
            G[:, m.nx + c] = m.Rd[:, k]
        dV = V[m.span_b] - V[m.span_a]
        edV = np.einsum("si,si->s", e, dV)
        gdot = m.A @ (m.falls * edV) + m.Rd @ omega
        A = kin[2]
        if not m.sway and len(m.free):           # loads guided with their carrier
            A = A.copy()
            A[m.free] = A[m.root] @ m._H.T
        dA = A[m.span_b] - A[m.span_a]
        gs = m.falls * (np.einsum("si,si->s", e, dA) + (np.einsum("si,si->s", dV, dV)
                                                         - edV ** 2) / l)
        gamma = m.A @ gs + m.Rd @ kin[3][:, 2]
        return {"X": X, "V": V, "theta": theta, "omega": omega, "l": l, "e": e, "eD": eD,
                "L": L, "L0": L0, "G": G, "gdot": gdot, "gamma": gamma}

    def _tension_stiffness(self, geo, S):
        """d(G^T S)/dq = sum f S / l D^T (I - e e^T) D (drum columns: constant R)."""
        m = self.m
        K = np.zeros((m.n, m.n))
        if not len(m.span_a):
            return K
        w = m.falls * S[m.span_rope] / geo["l"]
        eD, nx = geo["eD"], m.nx
        K[:nx, :nx] = (w @ m.DtD).reshape(nx, nx) - (eD.T * w) @ eD
        return K

    def _multipliers(self, F, geo, act):
        """Acceleration and rope forces of a consistent state from (1), (2)."""
        S = np.zeros(len(geo["L"]))
        if len(act):
            Ga = geo["G"][act]
            W = (Ga * self.Minv) @ Ga.T
            S[act] = np.linalg.solve(W, Ga @ (self.Minv * F) + geo["gamma"][act])
        return self.Minv * (F - geo["G"].T @ S), S

    def kin_side(self, t, side):
        """The kinematics at t, the prescribed accelerations taken from the left
        (side -1) or right (+1) of t when t is a breakpoint of the drives."""
        kin = self.kin(t)
        if not len(self.bps) or np.abs(self.bps - t).min() > 1e-12 * max(t, 1.0):
            return kin
        k2 = self.kin(t + side * self.dbp)
        th = kin[3].copy()
        th[:, 2] = k2[3][:, 2]
        return (kin[0], kin[1], k2[2], th)

    def state(self, t, q, v, taut, kin=None, side=1):
        """The Eval of a state (forces of gravity, springs and drives; the ropes' as
        multipliers), with its acceleration `ev._a` (at a breakpoint: the limit from
        `side`)."""
        m = self.m
        kin = self.kin_side(t, side) if kin is None else kin
        ev = m.evaluate(t, q, v, self.none, kin, powers=False)
        geo = self.geometry(t, q, v, kin, ev)
        act = np.flatnonzero(taut)
        a, S = self._multipliers(ev.F, geo, act)
        ev._side = side
        return self._fill(ev, geo, S, a, q, v, taut)

    def limit(self, t, q, v, a, ev, taut):
        """After a step that ended at a breakpoint: the limit from the right of the
        acceleration and rope forces, from which the next step starts; (a, ev, jumped)."""
        if np.abs(self.bps - t).min() > 1e-12 * max(t, 1.0):
            return a, ev, False
        ev = self.state(t, q, v, taut, side=1)
        return ev._a, self.powers(ev), True

    def _fill(self, ev, geo, S, a, q, v, taut):
        ev.S, ev.Sd = S, np.zeros_like(S)
        ev.L, ev.L0, ev.edot = geo["L"], geo["L0"], geo["gdot"]
        fe, _, tt, spring, rest = ev._ctx
        ev._ctx = (fe, np.ones_like(S), tt, spring, rest)   # no stretch: no wound energy
        ev._a, ev._q, ev._v, ev._taut, ev._geo = a, q, v, taut, geo
        return ev

    def accel(self, t, q, v, taut):
        ev = self.state(t, q, v, taut)
        return ev._a, self.powers(ev)

    def consistent(self, t, q, v, taut):
        """(q, v) projected onto the taut ropes' constraints (a given initial state)."""
        out = self.project(t, q, v, np.flatnonzero(taut), self.kin(t))
        if out is None:
            raise AnalysisError("the initial state cannot be projected onto the ropes' "
                                "lengths (Newton did not converge): start nearer to them")
        return out

    def project(self, t, q, v, act, kin, once=False):
        """M-orthogonal projection onto g = 0 (Newton, G at each iterate) and g' = 0.
        once: one Newton correction (after a step, whose drift g is O(h^3), the next
        correction would be O(g^2)), and g' made zero with G before it (the change
        of G over the correction is O(g))."""
        if not len(act):
            return q, v
        for it in range(10):
            geo = self.geometry(t, q, v, kin)
            g = (geo["L"] - geo["L0"])[act]
            Ga = geo["G"][act]
            W = (Ga * self.Minv) @ Ga.T
            if np.abs(g).max() <= self.gtol:
                break
            if once:
                v = v - self.Minv * (Ga.T @ np.linalg.solve(W, geo["gdot"][act]))
                return q - self.Minv * (Ga.T @ np.linalg.solve(W, g)), v
            q = q - self.Minv * (Ga.T @ np.linalg.solve(W, g))
        else:
            return None
        v = v - self.Minv * (Ga.T @ np.linalg.solve(W, geo["gdot"][act]))
        return q, v

    # ------------------------------------------------------------ the step
    def step(self, t0, q0, v0, a0, h, taut, jerk=None, left=False):
        """One trapezoidal step of the index-1 form (module docstring) -> (q1, v1, a1,
        ev1, err) at the projected end state, or None (Newton failed). `left` (an
        elastic frame's side of a breakpoint, Stepper.step) is unused: an elastic
        structure is refused with inextensible ropes; breakpoints: `limit`."""
        m = self.m
        t1 = t0 + h
        kt = self.kin_side(t1, -1)
        M, wq = self.M, self.wq
        c1, c2 = 4.0 / (h * h), 2.0 / h
        q1 = q0 + h * v0 + (0.5 * h * h) * a0
        if jerk is not None:
            q1 = q1 + (0.25 * h * h * h) * jerk
        qb = q0 + h * v0
        act = np.flatnonzero(taut)
        na, n = len(act), m.n
        S = np.zeros(len(taut))
        S[act] = self._Sguess[act]
        lu = None
        prev = np.inf
        for it in range(NEWTON_MAX):
            v1 = c2 * (q1 - q0) - v0
            a1 = c1 * (q1 - qb) - a0
            ev = m.evaluate(t1, q1, v1, self.none, kt, powers=False)
            geo = self.geometry(t1, q1, v1, kt, ev)
            self.newton_iterations += 1
            Ga = geo["G"][act]
            R = np.concatenate([ev.F - geo["G"].T @ S - M * a1,
                                -(Ga @ a1 + geo["gamma"][act]) / c1])
            if not math.isfinite(R.sum()):
                return None
            if lu is None:
                Z = np.zeros((n + na, n + na))
                Z[:n, :n] = ev.K + c2 * ev.C + self._tension_stiffness(geo, S)
                Z[np.arange(n), np.arange(n)] += c1 * M
                Z[:n, n:] = Ga.T
                Z[n:, :n] = Ga
                try:        # a few coordinates: the inverse, one product per iteration
                    lu = np.linalg.inv(Z)
                except np.linalg.LinAlgError:
                    return None
                self.tangents += 1
            sol = lu @ R
            dq = sol[:n]
            S[act] += sol[n:]
            dq_norm = float(np.abs(dq * wq).max(initial=0.0))
            if not math.isfinite(dq_norm):
                return None
            q1 = q1 + dq
            if it > 0 and dq_norm <= self.newton_tol:
                break
            if it > 0 and dq_norm > 0.1 * prev:
                lu = None
            prev = dq_norm
        else:
            return None
        a1 = c1 * (q1 - qb) - a0
        err = self.error(h, a0, a1)
        try:                    # constraints become dependent: a shorter step, or stop
            pr = self.project(t1, q1, c2 * (q1 - q0) - v0, act, kt, once=True)
            if pr is None:
                return None
            q1, v1 = pr
            ev1 = self.state(t1, q1, v1, taut, kt, side=-1)
        except np.linalg.LinAlgError:
            return None
        self._Sguess = ev1.S
        return q1, v1, ev1._a, ev1, err

    def error(self, h, a0, a1):
        """Zienkiewicz & Xie's local position error h^2/12 |a1 - a0| (the trapezoidal
        a1 of the step, before the projection) over tolerance x model size."""
        return float(np.abs((a1 - a0) * self.wq).max(initial=0.0)) / self.tol \
            * (h * h / 12.0)

    # ------------------------------------------------------------ events
    def stretch(self, ev):
        """The event functions: S / S_scale for taut ropes (slack where < 0), the strain
        L / L0 - 1 for slack ones (taut where > 0)."""
        return np.where(ev._taut, ev.S / self.sscale, ev.L / ev.L0 - 1.0)

    def crossing(self, ev1, taut):
        """Taut ropes whose force went negative, slack ones stretched by more than
        SLACK_STRAIN (not by the rounding of a rope just gone slack at L = L0)."""
        g = self.stretch(ev1)
        cross = np.flatnonzero(np.where(taut, g < 0, g > SLACK_STRAIN))
        return cross if len(cross) else None

    def m_alltaut(self, taut):
        return bool(taut.all())

    def switch(self, t, q, v, taut, k):
        """After rope k changed state at t: a rope come tight is jerked taut (module
        docstring). Returns (v, note for the event, work of the drives, dissipated)."""
        if not taut[k]:
            return v, "", 0.0, 0.0
        act = np.flatnonzero(taut)
        geo = self.geometry(t, q, v, self.kin(t))
        Ga = geo["G"][act]
        gd = geo["gdot"][act]
        P = np.linalg.solve((Ga * self.Minv) @ Ga.T, gd)
        v1 = v - self.Minv * (Ga.T @ P)
        g_t = gd - Ga @ v                       # the prescribed part of g'
        W = float(P @ g_t)                      # work of the prescribed motions
        dT = 0.5 * float(self.M @ (v1 * v1) - self.M @ (v * v))
        Pk = float(P[list(act).index(k)])
        note = f": jerk, impulse {Pk:.7g} N s"
        if self.state(t, q, v1, taut).S[k] < 0:
            taut[k] = False                     # jerked and separating again
            note += " (separates again)"
        return v1, note, W, W - dT

    # ------------------------------------------------------------ the recorder's view
    def evaluate(self, t, q, v, taut, kin=None, tangent=True, full=True):
        return self.state(t, q, v, taut, kin)

    def powers(self, ev):
        """Mechanism.powers with the multipliers as rope forces (the drives' power
        through the ropes S . g_t), and the forces' rate dS/dt for the recorder's
        Hermite interpolation (a difference along the state's motion over delta = 1e-7
        of the duration, on the side of the state's limit: truncation delta S''/2 and
        rounding 1e-13 S / delta, both below 1e-6 S per second)."""
        m = self.m
        if ev.P_drive is None:
            m.powers(ev)
        if getattr(ev, "_fr", None) is None:
            dl = self.delta * ev._side
            t, q, v, a = ev.t, ev._q, ev._v, ev._a
            Sp = self._S_at(t + dl, q + dl * v + 0.5 * dl * dl * a, v + dl * a, ev._taut)
            F = ev.S + ev.Sd
            ev._fr = (F, (Sp - ev.S) / dl, F.tolist())
        return ev

    def _S_at(self, t, q, v, taut):
        m = self.m
        kin = m.kinematics(t)                 # not cached: a time used once
        ev = m.evaluate(t, q, v, self.none, kin, powers=False)
        return self._multipliers(ev.F, self.geometry(t, q, v, kin, ev),
                                 np.flatnonzero(taut))[1]

    def energy(self, ev, taut):
        return self.m.energy(ev, self.none)

    def place(self, t, q, v):
        return self.m.place(t, q, v, self.kin(t))

    def span_lengths(self, ev):
        return ev._geo["l"]


# ------------------------------------------------------------------ massless blocks
# A free node without mass (a hook block whose mass is neglected, a free sheave) is a
# coordinate y with M = 0: its rows of the trapezoidal Newton system are the equilibrium
# F_y(t, q) = 0 of the falls and springs on it (algebraic), solved with the others. Its
# velocity is not the trapezoidal rule's v1 = 2 (q1 - q0) / h - v0, which for an algebraic
# unknown alternates from step to step, but the implicit function's: d/dt F_y = 0 gives
# K_yy v_y = dF_y/dt along (t, q_x, v_x) with y held (docs/operations.md "Massless
# blocks").

def algebraic_velocity(st, t, q, v, a, v0, h, ev, taut):
    """(v, a) with the massless blocks' velocities from the implicit function at (t, q)
    (K_yy v_y = D, D the forward difference of F_y along (1, v_x, 0) over 1e-7 of the
    duration; F has no velocity terms on those rows: damping is refused with them) and
    their accelerations as the difference of the velocities (for the predictor only)."""
    y = st.qy
    dl = 1e-7 * max(st.spec.duration, 1.0)
    vh = v.copy()
    vh[y] = 0.0
    e2 = st.ops.evaluate(t + dl, q + dl * vh, vh, taut, st.ops.kin(t + dl))
    D = (e2.F[y] - ev.F[y]) / dl
    v = v.copy()
    v[y] = _solve_blocks(st, t, ev.K[np.ix_(y, y)], D)
    a = a.copy()
    a[y] = (v[y] - v0[y]) / h
    return v, a


def _solve_blocks(st, t, Kyy, rhs):
    """K_yy^-1 rhs; a singular K_yy (a massless block whose ropes and springs went
    slack: nothing holds it, so it has no position) stops the run (exit 1, results
    kept) naming the blocks."""
    try:
        return np.linalg.solve(Kyy, rhs)
    except np.linalg.LinAlgError:
        m = st.m
        ks = sorted({int(np.flatnonzero(m.E[:, c])[0]) // 3 for c in st.qy})
        names = ", ".join(m.model.node_names[m.free[k]] for k in ks)
        raise AnalysisError(f"at t = {t:.6g} s the massless block(s) {names} lost the "
                            "tension of the ropes and springs that hold them (a rope went "
                            "slack): a block without mass has then no position; give it "
                            "a mass (masses) to follow it through slack ropes") from None


def algebraic_state(st, t, q, v, taut):
    """The massless blocks moved into equilibrium (Newton on F_y = 0 with K_yy) and
    their velocities by the implicit function, at a given (t, q, v)."""
    y = st.qy
    q = q.copy()
    kin = st.ops.kin(t)
    for _ in range(50):
        ev = st.ops.evaluate(t, q, v, taut, kin)
        dy = _solve_blocks(st, t, ev.K[np.ix_(y, y)], ev.F[y])
        q[y] += dy
        if np.abs(dy).max() <= 1e-14 * st.lscale:
            break
    ev = st.ops.evaluate(t, q, v, taut, kin)
    return q, algebraic_velocity(st, t, q, v, np.zeros_like(v), v, 1.0, ev, taut)[0]

