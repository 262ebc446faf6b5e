"""The integrator's view of a mechanism: forces, tangents, powers and energies at a
state, with the work that depends on the time only done once per time.

`ops(mech)` returns `Lean(mech)` when the mechanism has only what it covers - point
masses (sway on or off) on elastic ropes, drums held or driven by a profile, dashpot
damping - else `Generic(mech)`, which calls `Mechanism.evaluate/powers/energy/place`
(the reference implementation; torque and motor drums, axial springs on loads and joint
coordinates go there). Both answer the same questions with the same numbers (to
rounding; tests/test_operation_speed.py evaluates both on the example scenes).

Why a second path: for the 2-8 coordinates of a crane each numpy call costs more than
its arithmetic, so `Lean` (i) splits every span vector into a part linear in q,
`d = D q + d_kin(t)`, with `d_kin(t)` and everything else that depends on t alone (the
kinematic nodes, the prescribed drums' L0, `R omega`) made once per time and shared by
the Newton iterations, the joints' part only when a joint drive's state changes;
(ii) forms the ropes' rows `G = dL/dq` in one product with the flattened unit vectors;
(iii) builds the tangent only when asked (the integrator keeps the factorised one
within a step) and the node arrays only for states it accepts; (iv) replaces the energy
integrals by their closed forms in the coordinates (`T = 1/2 v.M v + T_guided`,
`V_g = -F_g.q`: the free nodes move as `E q` plus a kinematic part that is zero, or
horizontal without sway).
"""

import math

import numpy as np

from .mechanism import Eval


def ops(mech):
    """The fastest evaluator that covers `mech`."""
    return Lean(mech) if Lean.covers(mech) else Generic(mech)


class _TimeCache:
    """The last few time-dependent records, by time (a step's trial times repeat)."""

    def __init__(self, make):
        self.make, self.store = make, {}

    def __call__(self, t):
        k = self.store.get(t)
        if k is None:
            if len(self.store) > 8:
                self.store.clear()
            k = self.store[t] = self.make(t)
        return k


class Generic:
    """`Mechanism`'s own methods behind the integrator's interface."""

    def __init__(self, mech):
        self.m = mech
        self.kin = _TimeCache(mech.kinematics)

    def evaluate(self, t, q, v, taut, kin, tangent=True, full=True):
        m = self.m
        ev = self.m.evaluate(t, q, v, taut, kin, powers=False)
        ev._q, ev._v = q, v
        # G = dL/dq (the rope lengths' rows; Mechanism.evaluate's eD products) for the
        # step control's force error; drum coordinates: dL0/dtheta = -R, i.e. +R on
        # the elongation; joint coordinates (if any) left out
        d = ev.X[m.span_b] - ev.X[m.span_a]
        e = d / np.linalg.norm(d, axis=1)[:, None]
        G = np.zeros((len(ev.L), m.n))
        Gx = m.A @ (m.falls[:, None] * np.einsum("si,sij->sj", e, m.D))
        G[:, :Gx.shape[1]] = Gx
        for c, k in enumerate(m.qdrums):
            if m.nx + c < m.n:
                G[:, m.nx + c] = m.Rd[:, k]
        ev._G = G
        return ev

    def powers(self, ev):
        return self.m.powers(ev)

    def energy(self, ev, taut):
        return self.m.energy(ev, taut)

    def place(self, t, q, v):
        return self.m.place(t, q, v, self.kin(t))

    def span_lengths(self, ev):
        m = self.m
        return np.linalg.norm(ev.X[m.span_b] - ev.X[m.span_a], axis=1)


class Lean:
    """Point masses on elastic ropes, drums held or prescribed (see the module)."""

    @staticmethod
    def covers(mech):
        return (len(mech.ropes) > 0 and not mech.qdrums and not len(mech.sp_k)
                and not getattr(mech, "nJ", 0) and len(mech.free) > 0
                and getattr(mech, "linear", None) is None)   # linkages: Mechanism

    def __init__(self, mech):
        m = self.m = mech
        self.nx = nx = m.nx
        ns = self.ns = len(m.span_a)
        nr = self.nr = len(m.ropes)
        self.Dm = m.D.reshape(3 * ns, nx)                # span vectors <- q
        self.D = m.D
        self.Af = m.A * m.falls                           # rope length <- span lengths
        # G = dL/dq = sum_s f_s e_s . D_s = (e.ravel() @ Gbig).reshape(nr, nx); the
        # elongation rate of kinematic span ends: (e.ravel() * dv_kin) @ Bsum
        Gbig = np.einsum("rs,sic->sirc", self.Af, m.D).reshape(3 * ns, nr * nx)
        self.Gbig = np.ascontiguousarray(Gbig)
        self.Bsum = np.repeat(self.Af.T, 3, axis=0)      # (3 ns, nr)
        self.DtD = m.DtD
        self.nf = len(m.free)
        self.damped = m.damped
        self.kin = _TimeCache(self._kin)
        # L0 = L0_ref - W theta (docs/operations.md "Unstretched length and drums")
        self.W = np.zeros((nr, m.nd))
        if len(m.rope_drum):
            np.add.at(self.W, (m.rope_drum, m.drum_of_end),
                      m.end_radius / m.lam_ref[m.rope_drum])
        self.wound = bool(len(m.rope_drum))
        self._states = self._jk = self._X0 = None
        # span vectors' kinematic part: dk = Pk @ X.ravel() (the free nodes' rows hold
        # their kinematic part); Pkin: the kinematic ends only (moving sheaves)
        a3 = 3 * m.span_a[:, None] + np.arange(3)
        b3 = 3 * m.span_b[:, None] + np.arange(3)
        rows = np.arange(3 * ns).reshape(ns, 3)
        self.Pk = np.zeros((3 * ns, 3 * m.nn))
        self.Pkin = np.zeros((3 * ns, 3 * m.nn))
        np.add.at(self.Pk, (rows, b3), 1.0)
        np.add.at(self.Pk, (rows, a3), -1.0)
        np.add.at(self.Pkin, (rows[m.kin_b], b3[m.kin_b]), 1.0)
        np.add.at(self.Pkin, (rows[m.kin_a], a3[m.kin_a]), -1.0)
        self._taut, self._alltaut = None, False
        self._z0, self._znd = np.zeros(0), np.zeros(m.nd)

    def _kin(self, t):
        """Everything at time t that does not depend on q: (X, V) of the kinematic
        nodes with the free rows holding their kinematic part (zero; with sway off the
        horizontal position of the carrier), the span vectors' kinematic part, L0,
        R omega of the drums, the guided loads' kinetic energy. The joints' part is
        made again only when a joint drive's state changes."""
        m = self.m
        states = tuple(d.motion(t) for d in m._chain_drives)
        if self._jk is None or states != self._states:
            X, V = self._joints(states)          # free rows zero
            if m.sway:
                Xk, Vk, T_guided = X, V, 0.0
            else:
                H = m._H
                Xk, Vk = X.copy(), V.copy()
                Xk[m.free] = (m._X0_free + X[m.root] - m._X0_root) @ H.T
                Vh = V[m.root] @ H.T
                Vk[m.free] = Vh
                T_guided = 0.5 * float(m.free_mass @ (Vh * Vh).sum(1))
            dk = self.Pk @ Xk.ravel()
            dvk = self.Pk @ Vk.ravel()
            # velocity of the kinematic span ends only (the power fed by moving sheaves)
            vkin = dvk if m.sway else self.Pkin @ V.ravel()
            self._states = states
            self._jk = (Xk, Vk, dk, dvk if np.count_nonzero(dvk) else None,
                        vkin if np.count_nonzero(vkin) else None, T_guided)
        Xk, Vk, dk, dvk, vkin, T_guided = self._jk
        theta, omega = np.zeros(m.nd), np.zeros(m.nd)
        for k, d in m._profile_drums:
            theta[k], omega[k], _ = d.motion(t)
        L0 = m.L0_ref - self.W @ theta
        return (Xk, Vk, dk, dvk, vkin, theta, omega, L0, m.Rd @ omega, T_guided)

    def _joints(self, states):
        """(X, V) of the kinematic nodes for the joint drives' (s, s', s''): the body
        motions of Mechanism.body_motions and kinematics (same formulas, Rodrigues'
        rotation and the product rule along the tree) without the accelerations,
        which the forces do not use."""
        m = self.m
        if self._X0 is None:
            self._X0 = np.zeros((m.nn, 3))
            for b, idx, Xr in m._groups:                   # bodies at rest: X = Xr
                self._X0[idx] = Xr
        X, V = self._X0.copy(), np.zeros_like(self._X0)
        out = {}
        c = 0
        for b, p, d, sign, hinge, K, K2, point, axis in m._chain:
            par = out.get(p)                               # None: the ground (identity)
            if d is None:
                if par is not None:
                    out[b] = par
                continue
            s, ds, _ = states[c]
            c += 1
            s, ds = sign * s, sign * ds
            if hinge:
                sn, cs = math.sin(s), math.cos(s)
                R = m._I3 + sn * K + (1 - cs) * K2
                dR = ds * (cs * K + sn * K2)
                pj, dpj = point - R @ point, -(dR @ point)
                if par is None:
                    out[b] = (R, dR, pj, dpj)
                else:
                    Rp, dRp, pp, dpp = par
                    out[b] = (Rp @ R, dRp @ R + Rp @ dR, Rp @ pj + pp,
                              dRp @ pj + Rp @ dpj + dpp)
            else:
                pj, dpj = s * axis, ds * axis
                if par is None:
                    out[b] = (m._I3, np.zeros((3, 3)), pj, dpj)
                else:
                    Rp, dRp, pp, dpp = par
                    out[b] = (Rp, dRp, Rp @ pj + pp, dRp @ pj + Rp @ dpj + dpp)
        for b, idx, Xr in m._groups:
            mo = out.get(b)
            if mo is None:
                continue
            R, dR, p, dp = mo
            X[idx] = Xr @ R.T + p
            V[idx] = Xr @ dR.T + dp
        return X, V

    def evaluate(self, t, q, v, taut, kt, tangent=True, full=True):
        """Mechanism.evaluate's numbers; K, C only with `tangent`, X, V only with
        `full` (None otherwise)."""
        m = self.m
        ns, nx = self.ns, self.nx
        Xk, Vk, dk, dvk, vkin, theta, omega, L0, romega, _ = kt
        if taut is not self._taut:
            self._taut, self._alltaut = taut, bool(taut.all())
        d = (self.Dm @ q + dk).reshape(ns, 3)
        l = np.sqrt(np.add.reduce(d * d, 1))   # (no ndarray.sum wrapper)
        e = d / l[:, None]
        ef = e.ravel()
        L = self.Af @ l + m.extra
        lam = L / L0
        EA = m.EA
        G = (ef @ self.Gbig).reshape(self.nr, nx)          # dL/dq
        edot = G @ v + romega                               # elongation rate
        if dvk is not None:
            edot = edot + (ef * dvk) @ self.Bsum
        loglam = np.log(lam)
        if self._alltaut:
            S = EA * loglam
            cL = EA / L
        else:
            S = np.where(taut, EA * loglam, 0.0)
            cL = np.where(taut, EA / L, 0.0)
        if self.damped:
            # b = psi c / (2 pi w0 sqrt(c / c0)) = beta sqrt(c) (Mechanism.evaluate)
            b = m.beta * np.sqrt(cL)
            Sd = b * edot
            St = S + Sd
        else:
            b = Sd = np.zeros(len(L))
            St = S
        F = m.Fg - St @ G
        K = C = None
        if tangent:
            eD = np.matmul(e[:, None, :], self.D)[:, 0, :]   # (ns, nx) e_s . D_s
            wg = m.falls * S[m.span_rope] / l
            K = (G.T * cL) @ G + (wg @ self.DtD).reshape(nx, nx) - (eD.T * wg) @ eD
            C = (G.T * b) @ G
        X = V = None
        if full:
            nf = self.nf
            X, V = Xk.copy(), Vk.copy()
            X[m.free] += (m.E @ q).reshape(nf, 3)
            V[m.free] += (m.E @ v).reshape(nf, 3)
        ev = Eval(t, F, K, C, X, V, L, L0, S, Sd, edot, self._z0, theta, omega,
                  self._znd, None, None, None)
        ev._q, ev._v, ev._l, ev._e, ev._lam, ev._kt, ev._taut = q, v, l, ef, lam, kt, taut
        ev._loglam, ev._St, ev._cL, ev._G = loglam, St, cL, G
        return ev

    def powers(self, ev):
        """Mechanism.powers: drives, dashpots, rope wound on the drums (W)."""
        if ev.P_drive is not None:
            return ev
        m = self.m
        S, Sd, lam, taut, kt = ev.S, ev.Sd, ev._lam, ev._taut, ev._kt
        vkin, romega, T_guided = kt[4], kt[8], kt[9]
        if self.wound:
            wden = m.EA * (lam * ev._loglam - lam + 1)
            if not self._alltaut_of(taut):
                wden = np.where(taut, wden, 0.0)
            P_wound = float(((S - (S * lam - wden) / m.lam_ref) @ romega))
        else:
            P_wound = 0.0
        # moving sheaves and prescribed drums (held drums turn at omega = 0)
        rate = romega if vkin is None else (ev._e * vkin) @ self.Bsum + romega
        ev.P_drive = float(ev._St @ rate)
        ev.P_diss = float(Sd @ ev.edot)
        ev.P_wound, ev.T_guided = P_wound, T_guided
        return ev

    def energy(self, ev, taut):
        """(T, V_gravity, U_elastic) of Mechanism.energy in closed form (module)."""
        m = self.m
        v = ev._v
        T = 0.5 * float(m.M @ (v * v)) + ev._kt[9]
        Vg = -float(m.Fg @ ev._q)
        # U = EA (L ln(L/L0) - L + L0) = S L - EA (L - L0) on taut ropes
        L = ev.L
        u = ev.S * L - m.EA * (L - ev.L0)
        U = float((u if taut is ev._taut and self._alltaut_of(taut) else
                   np.where(taut, u, 0.0)).sum())
        return T, Vg, U

    def _alltaut_of(self, taut):
        if taut is not self._taut:
            self._taut, self._alltaut = taut, bool(taut.all())
        return self._alltaut

    def place(self, t, q, v):
        """(X, V, theta, omega) as Mechanism.place."""
        kt = self.kin(t)
        m = self.m
        X, V = kt[0].copy(), kt[1].copy()
        X[m.free] += (m.E @ q).reshape(self.nf, 3)
        V[m.free] += (m.E @ v).reshape(self.nf, 3)
        return X, V, kt[5], kt[6]

    def span_lengths(self, ev):
        return ev._l
