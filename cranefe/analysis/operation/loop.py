"""The whole integration loop of the lean path compiled by numba (optional extra `fast`).

`integrate.simulate` runs a Python loop around one step: step control, breakpoints of
the drive profiles, slack/taut event location, the time-dependent kinematics (drive
profiles, the bodies' motions through the prescribed hinges and sliders, the drums'
unstretched lengths), the energy balance's power terms and the recorder (Hermite peak of
the rope forces, samples at the output times). With the compiled step (fast.py) that
loop was ~70 % of the run. Here the same loop is one compiled function, `_run`, working
on arrays made once by `prepare`:

- drive profiles as tables of their constant-jerk segments (profiles.Motion: times and
  (s, v, a, j) per segment), evaluated by bisection and `s + v tau + a tau^2/2 +
  j tau^3/6` (profiles.py);
- the chain of bodies (mechanism.Mechanism._chain): per entry its parent entry, drive,
  sign, hinge (skew matrices K, K^2 of its axis, Rodrigues' `R = I + sin s K +
  (1 - cos s) K^2`, `R' = s' (cos s K + sin s K^2)`) or slider (axis), composed along
  the tree as `Lean._joints` (R = R_p R_j, p = R_p p_j + p_p and their rates);
- the kinematic span parts `d_kin = X_b - X_a` and `v_kin` (Lean._kin), the drums'
  `L0 = L0_ref - W theta` and `R omega`, the guided loads' kinetic energy (sway off);
- the step: fast._step (forces, tangent, modified Newton, error estimate);
- step control (integrate.StepControl: Gustafsson's predictive rule), breakpoints,
  Newton failure and error rejections, event location (integrate._locate: Illinois on
  the stretch ln(L/L0), each trial a full step), two-blocking (integrate._two_blocking);
- the recorder (results.Recorder.accept): trapezoidal integrals of the drive, dashpot and
  wound powers (Lean.powers), energies (Lean.energy), peak forces by the closed-form
  Hermite maximum (results._hermite_max1), samples at the output times from the cubic
  Hermite interpolants of q and of the rope forces, node positions there (Lean.place).

Every formula is the numpy path's in the same order; what differs is rounding (a few
ulps: products summed in another order), so the runs are the same step for step until
a decision (accept/reject, Newton's stop) sits within rounding of its threshold, which
over thousands of steps happens (tests/test_operation_speed.py compares whole runs). The
numpy path (`simulate(model, fast=False)`) stays the reference.

The Python side (`run`) makes the arrays, calls `_run` once (or once per 1/200 of the
duration when a progress callback is given: the loop stops after the step that passes
the chunk's end, so chunks do not change the steps), and fills the Recorder and the
Stepper's counters as the Python loop would, so that `Recorder.result` builds the same
OperationResult; a failure (Newton or the step collapsing, two-blocking, too many
steps) raises the AnalysisError of the Python loop, with the results up to it kept.

Compiled with `cache=True`: the first call compiles for ~50 s of CPU, later processes load
the cache. numba's cache of this module's functions does not notice an edit of fast.py
or results.py, whose `_step`, `_forces` and `_hermite_max1` they compile in: after
editing those (or switching versions, e.g. `git stash`), delete the `*.nbi` and `*.nbc`
files in this folder's __pycache__ so that all are compiled afresh (touching this file was
seen not to be enough after a `git stash`).
"""

import math
from types import SimpleNamespace

import numpy as np

from . import fast as _fast
from . import results as _results

SAFE, LO, HI = 0.9, 0.2, 2.0                 # integrate.StepControl

# fs: the loop's float state
(F_T, F_H, F_HACC, F_EACC, F_W, F_D, F_WD, F_MT0, F_MT1, F_MT2, F_ET, F_EV, F_EU,
 F_PDR, F_PDI, F_PW, F_TG, F_VG0, F_FAILH, F_TWOL, NF) = range(21)
# ist: the loop's integer state
(I_HASACC, I_AFTERREJ, I_HASJERK, I_BI, I_STEPS, I_REJ, I_ITS, I_TG, I_NEXT, I_NEV,
 I_STATUS, I_TWOK, I_HASE, NI) = range(14)
# status
OK, NEWTON, COLLAPSE, TWO_BLOCK, TOO_MANY = 0, 1, 2, 3, 4


def _jit(f):
    return _fast.numba.njit(cache=True, nogil=True)(f) if _fast.numba is not None else f


@_jit
def _motion(mt, mseg, o0, o1, t):
    """(s, s') of the motion whose segments are rows o0..o1-1 (profiles.Motion.__call__)."""
    if t < mt[o0]:
        v = mseg[o0, 1]
        return v * t, v
    lo, hi = o0, o1                       # bisect_right(t[o0:o1], t) - 1
    while lo < hi:
        mid = (lo + hi) // 2
        if t < mt[mid]:
            hi = mid
        else:
            lo = mid + 1
    k = lo - 1
    s, v, a, jk = mseg[k, 0], mseg[k, 1], mseg[k, 2], mseg[k, 3]
    tau = t - mt[k]
    return (s + v * tau + a * tau * tau / 2 + jk * math.pow(tau, 3.0) / 6,
            v + a * tau + jk * tau * tau / 2)


@_jit
def _kin(t, kd):
    """Lean._kin and Lean._joints at t -> (X, V, dk, dvk, vkin, theta, omega, L0,
    R omega, T_guided, motion states (nmot, 2)). Length: the body chain, the guided
    loads and the drums written out in loops for the compiler (one block each)."""
    (mt, mseg, moff, ch_par, ch_drv, ch_sign, ch_hinge, ch_K, ch_K2, ch_point, ch_axis,
     g_ent, g_off, g_idx, g_Xr, X0, sway, free, root, X0f, X0r, H, free_mass, span_a,
     span_b, kin_a, kin_b, pd_k, pd_mot, nd, L0_ref, W, Rd, _E) = kd
    nmot = moff.shape[0] - 1
    ms = np.empty((nmot, 2))
    for i in range(nmot):
        ms[i, 0], ms[i, 1] = _motion(mt, mseg, moff[i], moff[i + 1], t)
    nch = ch_par.shape[0]
    has = np.zeros(nch, np.bool_)
    R = np.zeros((nch, 3, 3))
    dR = np.zeros((nch, 3, 3))
    P = np.zeros((nch, 3))
    dP = np.zeros((nch, 3))
    for i in range(nch):
        pe = ch_par[i]
        hp = pe >= 0 and has[pe]
        c = ch_drv[i]
        if c < 0:
            if hp:
                R[i], dR[i], P[i], dP[i] = R[pe], dR[pe], P[pe], dP[pe]
                has[i] = True
            continue
        s, ds = ch_sign[i] * ms[c, 0], ch_sign[i] * ms[c, 1]
        Rj = np.zeros((3, 3))
        dRj = np.zeros((3, 3))
        pj = np.zeros(3)
        dpj = np.zeros(3)
        if ch_hinge[i]:
            sn, cs = math.sin(s), math.cos(s)
            for x in range(3):
                for y in range(3):
                    Rj[x, y] = (1.0 if x == y else 0.0) + sn * ch_K[i, x, y] + \
                        (1 - cs) * ch_K2[i, x, y]
                    dRj[x, y] = ds * (cs * ch_K[i, x, y] + sn * ch_K2[i, x, y])
            for x in range(3):
                acc = 0.0
                dacc = 0.0
                for y in range(3):
                    acc += Rj[x, y] * ch_point[i, y]
                    dacc += dRj[x, y] * ch_point[i, y]
                pj[x] = ch_point[i, x] - acc
                dpj[x] = -dacc
        else:
            for x in range(3):
                Rj[x, x] = 1.0
                pj[x] = s * ch_axis[i, x]
                dpj[x] = ds * ch_axis[i, x]
        if not hp:
            R[i], dR[i], P[i], dP[i] = Rj, dRj, pj, dpj
        else:
            Rp, dRp, pp, dpp = R[pe], dR[pe], P[pe], dP[pe]
            if ch_hinge[i]:                       # R_p R_j, R_p' R_j + R_p R_j'
                for x in range(3):
                    for y in range(3):
                        a1 = 0.0
                        a2 = 0.0
                        for z in range(3):
                            a1 += Rp[x, z] * Rj[z, y]
                            a2 += dRp[x, z] * Rj[z, y] + Rp[x, z] * dRj[z, y]
                        R[i, x, y] = a1
                        dR[i, x, y] = a2
            else:
                R[i], dR[i] = Rp, dRp
            for x in range(3):
                a1 = 0.0
                a2 = 0.0
                for y in range(3):
                    a1 += Rp[x, y] * pj[y]
                    a2 += dRp[x, y] * pj[y] + Rp[x, y] * dpj[y]
                P[i, x] = a1 + pp[x]
                dP[i, x] = a2 + dpp[x]
        has[i] = True
    X = X0.copy()
    V = np.zeros_like(X0)
    for g in range(g_ent.shape[0]):
        ge = g_ent[g]
        if ge < 0 or not has[ge]:
            continue
        for r in range(g_off[g], g_off[g + 1]):
            n = g_idx[r]
            for x in range(3):
                a1 = P[ge, x]
                a2 = dP[ge, x]
                for y in range(3):
                    a1 += g_Xr[r, y] * R[ge, x, y]
                    a2 += g_Xr[r, y] * dR[ge, x, y]
                X[n, x] = a1
                V[n, x] = a2
    Tg = 0.0
    if sway:
        Xk, Vk = X, V
    else:
        Xk, Vk = X.copy(), V.copy()
        for k in range(free.shape[0]):
            f, rt = free[k], root[k]
            vh2 = 0.0
            for x in range(3):
                a1 = 0.0
                a2 = 0.0
                for y in range(3):
                    a1 += (X0f[k, y] + X[rt, y] - X0r[k, y]) * H[x, y]
                    a2 += V[rt, y] * H[x, y]
                Xk[f, x] = a1
                Vk[f, x] = a2
                vh2 += a2 * a2
            Tg += free_mass[k] * vh2
        Tg *= 0.5
    ns = span_a.shape[0]
    dk = np.empty(3 * ns)
    dvk = np.empty(3 * ns)
    vkin = np.empty(3 * ns)
    for s in range(ns):
        a, b = span_a[s], span_b[s]
        for x in range(3):
            dk[3 * s + x] = Xk[b, x] - Xk[a, x]
            dvk[3 * s + x] = Vk[b, x] - Vk[a, x]
            if sway:
                vkin[3 * s + x] = dvk[3 * s + x]
            else:
                vkin[3 * s + x] = (V[b, x] if kin_b[s] else 0.0) - \
                    (V[a, x] if kin_a[s] else 0.0)
    theta = np.zeros(nd)
    omega = np.zeros(nd)
    for i in range(pd_k.shape[0]):
        theta[pd_k[i]] = ms[pd_mot[i], 0]
        omega[pd_k[i]] = ms[pd_mot[i], 1]
    nr = L0_ref.shape[0]
    L0 = L0_ref.copy()
    romega = np.zeros(nr)
    for r in range(nr):
        a1 = 0.0
        a2 = 0.0
        for k in range(nd):
            a1 += W[r, k] * theta[k]
            a2 += Rd[r, k] * omega[k]
        L0[r] -= a1
        romega[r] = a2
    return Xk, Vk, dk, dvk, vkin, theta, omega, L0, romega, Tg, ms


@_jit
def _trial(t, q, v, a, h, taut, jerk, has_jerk, kd, fd, M, newton_tol, newton_max,
           fscale, sfloor, tol):
    """fast._step at t + h with the kinematics there."""
    Dm, Af, extra, EA, beta, Fg, D, falls, span_rope, damped = fd[:10]
    kt = _kin(t + h, kd)
    return _fast._step(q, v, a, h, jerk, has_jerk, Dm, kt[2], kt[3], Af, extra, kt[7],
                       EA, kt[8], taut, beta, Fg, D, falls, span_rope, damped, M,
                       newton_tol, newton_max, fscale, sfloor, tol) + (kt,)


@_jit
def _powers(out, kt, taut, fd):
    """Lean.powers -> (P_drive, P_diss, P_wound)."""
    Af, EA, lam_ref, wound = fd[1], fd[3], fd[10], fd[11]
    e, lam, loglam, S, Sd, edot = out[3], out[5], out[6], out[7], out[8], out[9]
    vkin, romega = kt[4], kt[8]
    nr = S.shape[0]
    Pw = 0.0
    if wound:
        for r in range(nr):
            wden = EA[r] * (lam[r] * loglam[r] - lam[r] + 1) if taut[r] else 0.0
            Pw += (S[r] - (S[r] * lam[r] - wden) / lam_ref[r]) * romega[r]
    Pdr = 0.0
    Pdi = 0.0
    ns = e.shape[0] // 3
    for r in range(nr):
        rate = 0.0
        for s in range(ns):
            for x in range(3):
                rate += e[3 * s + x] * vkin[3 * s + x] * Af[r, s]
        rate += romega[r]
        Pdr += (S[r] + Sd[r]) * rate
        Pdi += Sd[r] * edot[r]
    return Pdr, Pdi, Pw


@_jit
def _energy(out, kt, q, v, taut, fd, M):
    """Lean.energy -> (T, V_gravity, U_elastic)."""
    Fg, EA = fd[5], fd[3]
    L, S, L0 = out[4], out[7], kt[7]
    T = 0.0
    Vg = 0.0
    for i in range(q.shape[0]):
        T += M[i] * (v[i] * v[i])
        Vg += Fg[i] * q[i]
    U = 0.0
    for r in range(L.shape[0]):
        if taut[r]:
            U += S[r] * L[r] - EA[r] * (L[r] - L0[r])
    return 0.5 * T + kt[9], -Vg, U


# the Hermite peak of one rope (results._hermite_max1 derives it), compiled
_hermite_max1 = _jit(_results._hermite_max1)
_hermite_bound = _jit(_results.hermite_bound)


@_jit
def _force_rate(out, EA, taut):
    """Recorder._force_rate: (S + S_d, EA/L e' where taut)."""
    S, Sd, L, edot = out[7], out[8], out[4], out[9]
    nr = S.shape[0]
    F = np.empty(nr)
    r = np.empty(nr)
    for k in range(nr):
        F[k] = S[k] + Sd[k]
        r[k] = (EA[k] / L[k] if taut[k] else 0.0) * edot[k]
    return F, r


@_jit
def _accept(t0, q0, v0, t1, q1, v1, out1, kt1, qi, vi, taut, fs, ist, F0, r0, peak,
            peak_t, out_times, s_t, s_X, s_F, s_mot, kd, fd, M):
    """Recorder.accept of a step t0 -> t1 whose last Newton iterate gave out1 (at qi,
    vi); F0, r0, fs[F_PDR..F_TG]: the state at t0 (updated to t1 on return).
    Length: the recorder's four parts (powers, peaks, energy, samples) in one frame."""
    h = t1 - t0
    EA = fd[3]
    Pdr, Pdi, Pw = _powers(out1, kt1, taut, fd)
    Tg1 = kt1[9]
    fs[F_W] += 0.5 * h * (fs[F_PDR] + Pdr) + Tg1 - fs[F_TG]
    fs[F_D] += 0.5 * h * (fs[F_PDI] + Pdi)
    fs[F_WD] += 0.5 * h * (fs[F_PW] + Pw)
    F1, r1 = _force_rate(out1, EA, taut)
    for k in range(F1.shape[0]):
        a, b, m0, m1 = F0[k], F1[k], h * r0[k], h * r1[k]
        if _hermite_bound(a, b, m0, m1) > peak[k]:
            best, where = _hermite_max1(a, b, m0, m1)
            if best > peak[k]:
                peak[k], peak_t[k] = best, t0 + where * h
    T, Vg, U = _energy(out1, kt1, qi, vi, taut, fd, M)
    fs[F_MT0] = max(fs[F_MT0], T)
    fs[F_MT1] = max(fs[F_MT1], abs(Vg - fs[F_VG0]))
    fs[F_MT2] = max(fs[F_MT2], U)
    fs[F_ET], fs[F_EV], fs[F_EU] = T, Vg, U
    ist[I_HASE] = 1
    E, free = kd[33], kd[17]
    nf = free.shape[0]
    while ist[I_NEXT] < out_times.shape[0] and \
            out_times[ist[I_NEXT]] <= t1 * (1 + 1e-13):
        i = ist[I_NEXT]
        ts = out_times[i]
        s = (ts - t0) / h
        s2, s3 = math.pow(s, 2.0), math.pow(s, 3.0)
        h00, h10, h01, h11 = 2*s3 - 3*s2 + 1, s3 - 2*s2 + s, -2*s3 + 3*s2, s3 - s2
        qs = h00 * q0 + h10 * h * v0 + h01 * q1 + h11 * h * v1
        if s >= 1 - 1e-12:
            tsamp = t1
            Fs = F1
            kts = kt1
        else:
            tsamp = ts
            Fs = h00 * F0 + h10 * h * r0 + h01 * F1 + h11 * h * r1
            kts = _kin(ts, kd)
        X = kts[0].copy()
        Eq = E @ qs
        for k in range(nf):
            for x in range(3):
                X[free[k], x] += Eq[3 * k + x]
        s_t[i] = tsamp
        s_X[i] = X
        s_F[i] = Fs
        s_mot[i] = kts[10]
        ist[I_NEXT] += 1
    F0[:] = F1
    r0[:] = r1
    fs[F_PDR], fs[F_PDI], fs[F_PW], fs[F_TG] = Pdr, Pdi, Pw, Tg1


@_jit
def _stretch_k(out, k):
    return out[6][k]


@_jit
def _sign(x):
    return 1.0 if x > 0 else (-1.0 if x < 0 else 0.0)


@_jit
def _locate(t, q, v, a, h, taut, g0, cross, ncross, kd, fd, M, newton_tol,
            newton_max, fscale, sfloor, tol, ist, best):
    """integrate._locate: the shortest step ending where a crossing rope's stretch is
    zero (Illinois) -> (found, x, trial result of that step, rope); `best`: any trial
    result (its type; replaced)."""
    empty = np.zeros(0)
    best_x = -1.0
    best_k = -1
    for ic in range(ncross):
        k = cross[ic]
        lo, hi = 0.0, h
        glo = g0[k]
        o = _trial(t, q, v, a, h, taut, empty, False, kd, fd, M, newton_tol,
                   newton_max, fscale, sfloor, tol)
        ist[I_ITS] += o[5]
        ist[I_TG] += o[6]
        if o[0] != 0:
            return False, 0.0, o, -1
        ghi = _stretch_k(o[7], k)
        side = 0
        cand_x = -1.0
        cand = o
        for _ in range(60):
            x = hi - ghi * (hi - lo) / (ghi - glo) if ghi != glo else 0.5 * (lo + hi)
            if hi - lo > 1e-12 * h:
                x = min(max(x, lo + 1e-3 * (hi - lo)), hi - 1e-3 * (hi - lo))
            o = _trial(t, q, v, a, x, taut, empty, False, kd, fd, M, newton_tol,
                       newton_max, fscale, sfloor, tol)
            ist[I_ITS] += o[5]
            ist[I_TG] += o[6]
            if o[0] != 0:
                return False, 0.0, o, -1
            gx = _stretch_k(o[7], k)
            cand_x, cand = x, o
            if abs(gx) < 1e-13 or hi - lo < 1e-12 * max(h, 1e-300):
                break
            if _sign(gx) == _sign(ghi):
                hi, ghi = x, gx
                if side == 1:
                    glo *= 0.5
                side = 1
            else:
                lo, glo = x, gx
                if side == -1:
                    ghi *= 0.5
                side = -1
        if best_k < 0 or cand_x < best_x:
            best_x, best, best_k = cand_x, cand, k
    return True, best_x, best, best_k


@_jit
def _run(t_stop, T, bps, max_step, hmin, max_steps, newton_tol, newton_max, tol, fscale,
         sfloor, M, kd, fd, q, v, a, jerk, taut, loglam0, fs, ist, F0, r0, peak, peak_t,
         out_times, s_t, s_X, s_F, s_mot, ev_t, ev_k, ev_s, span_ref, span_guard, lq, lv,
         lfail):
    """integrate.simulate's loop from the state (fs, ist, q, v, a, jerk, taut, ...) until
    t >= t_stop or the end, in place. Length: the loop of integrate.simulate (step,
    rejections, event, acceptance, step control) in one frame, as there."""
    t, h = fs[F_T], fs[F_H]
    nb = bps.shape[0]
    nr = taut.shape[0]
    n = q.shape[0]
    while t < T * (1 - 1e-14):
        if t >= t_stop:
            break
        bi = ist[I_BI]
        while bi < nb and bps[bi] <= t * (1 + 1e-14) + 1e-14:
            bi += 1
        ist[I_BI] = bi
        t_next = bps[bi] if bi < nb else T
        hh = min(h, max_step, t_next - t)
        if t_next - t - hh < 1e-9 * hh:
            hh = t_next - t
        res = _trial(t, q, v, a, hh, taut, jerk, ist[I_HASJERK] == 1, kd, fd, M,
                     newton_tol, newton_max, fscale, sfloor, tol)
        st, q1, v1, a1, err, its, tg, out1, qi, vi, kt1 = res
        ist[I_ITS] += its
        ist[I_TG] += tg
        if st != 0:
            ist[I_REJ] += 1
            h = hh * 0.25
            ist[I_AFTERREJ] = 1
            if h < hmin:
                ist[I_STATUS], fs[F_FAILH] = NEWTON, h
                break
            continue
        if err > 1.0:
            ist[I_REJ] += 1
            ist[I_AFTERREJ] = 1
            h = hh * max(LO, SAFE * err ** (-1 / 3))
            if h < hmin:
                ist[I_STATUS], fs[F_FAILH] = COLLAPSE, h
                break
            continue
        # slack / taut events (Stepper.crossing)
        lam = out1[5]
        cross = np.empty(nr, np.int64)
        nc = 0
        for k in range(nr):
            if (lam[k] < 1.0) if taut[k] else (lam[k] > 1.0):
                cross[nc] = k
                nc += 1
        if nc:
            found, x, o, k = _locate(t, q, v, a, hh, taut, loglam0, cross, nc, kd, fd,
                                     M, newton_tol, newton_max, fscale, sfloor, tol, ist,
                                     res)
            if not found:
                h = hh * 0.25
                ist[I_REJ] += 1
                continue
            hh = x
            q1, v1, a1, out1, qi, vi, kt1 = o[1], o[2], o[3], o[7], o[8], o[9], o[10]
            _accept(t, q, v, t + hh, q1, v1, out1, kt1, qi, vi, taut, fs, ist, F0, r0,
                    peak, peak_t, out_times, s_t, s_X, s_F, s_mot, kd, fd, M)
            t = t + hh
            q[:] = q1
            v[:] = v1
            taut[k] = not taut[k]
            ne = ist[I_NEV]
            if ne < ev_t.shape[0]:
                ev_t[ne], ev_k[ne], ev_s[ne] = t, k, taut[k]
            ist[I_NEV] = ne + 1
            # a, ev = Stepper.accel(t, q, v, taut): the forces with the new taut set
            Dm, Af, extra, EA, beta, Fgv, D, falls, span_rope, damped = fd[:10]
            kt = _kin(t, kd)
            K0 = np.zeros((0, 0))
            ev = _fast._forces(q, v, Dm, kt[2], kt[3], Af, extra, kt[7], EA, kt[8], taut,
                               beta, Fgv, D, falls, span_rope, damped, False, K0, K0)
            for i in range(n):
                a[i] = ev[0][i] / M[i]
            Fn, rn = _force_rate(ev, EA, taut)
            F0[:] = Fn
            r0[:] = rn
            fs[F_PDR], fs[F_PDI], fs[F_PW] = _powers(ev, kt, taut, fd)
            fs[F_TG] = kt[9]
            loglam0[:] = ev[6]
            lq[:] = q
            lv[:] = v
            ist[I_STEPS] += 1
            ist[I_HASJERK] = 0
            ist[I_HASACC] = 0
            continue
        _accept(t, q, v, t + hh, q1, v1, out1, kt1, qi, vi, taut, fs, ist, F0, r0,
                peak, peak_t, out_times, s_t, s_X, s_F, s_mot, kd, fd, M)
        for i in range(n):
            jerk[i] = (a1[i] - a[i]) / hh
        ist[I_HASJERK] = 1
        t = t + hh
        q[:] = q1
        v[:] = v1
        a[:] = a1
        loglam0[:] = out1[6]
        lq[:] = qi
        lv[:] = vi
        ist[I_STEPS] += 1
        # two-blocking (integrate._two_blocking) on the spans' lengths
        l = out1[2]
        for s in range(l.shape[0]):
            if l[s] < 0.01 * span_ref[s] and span_guard[s]:
                ist[I_STATUS] = TWO_BLOCK
                lfail[:] = l
                break
        if ist[I_STATUS] != OK:
            break
        if ist[I_STEPS] > max_steps:
            ist[I_STATUS] = TOO_MANY
            break
        # StepControl.accepted
        e = max(err, 1e-10)
        fac = SAFE * e ** (-1 / 3)
        if ist[I_HASACC]:
            fac = min(fac, SAFE * (hh / fs[F_HACC]) * (fs[F_EACC] / e) ** (1 / 3) *
                      e ** (-1 / 3))
        fac = min(max(fac, LO), 1.0 if ist[I_AFTERREJ] else HI)
        fs[F_HACC], fs[F_EACC] = hh, max(e, 1e-2)
        ist[I_HASACC] = 1
        ist[I_AFTERREJ] = 0
        h_new = hh * fac
        if hh < h:                  # a step cut at a breakpoint: keep the longer one
            h = max(h, h_new)
            ist[I_HASACC] = 0
        else:
            h = h_new
    fs[F_T], fs[F_H] = t, h


def _motions_table(motions):
    """Stack profiles.Motion segments -> (times, (s, v, a, j) rows, offsets)."""
    ts, segs, off = [], [], [0]
    for mo in motions:
        ts += list(mo._tl)
        segs += [list(x) for x in mo._segs]
        off.append(len(ts))
    return (np.array(ts, float), np.array(segs, float).reshape(len(ts), 4),
            np.array(off, np.int64))


def prepare(st, spec):
    """The arrays of `_run` for the Stepper `st` (fast.FastLean ops) -> (kd, fd, drive
    map) or None when the loop does not cover the scene (then the Python loop runs)."""
    if not _fast.available() or not isinstance(st.ops, _fast.FastLean) or st.wq is not None:
        return None
    m, lean = st.m, st.ops
    if len(m.qdrums) or getattr(m, "nJ", 0) or getattr(m, "linear", None) is not None:
        return None
    chain_drives = list(m._chain_drives)
    motions = [d.motion for d in chain_drives] + [d.motion for _, d in m._profile_drums]
    if any(mo is None for mo in motions):
        return None
    # every drive of the scene read from a motion of the table (Recorder._sample)
    dmap = []
    for d in spec.drives:
        if d.target == "drum":
            k = [i for i, (kk, _) in enumerate(m._profile_drums) if kk == d.index]
            if not k or d.kind != "profile":
                return None
            dmap.append(("drum", len(chain_drives) + k[0], d))
        else:
            k = [i for i, x in enumerate(chain_drives) if x is d]
            if not k:
                return None
            dmap.append(("joint", k[0], d))
    mt, mseg, moff = _motions_table(motions)
    entry = {c[0]: i for i, c in enumerate(m._chain)}
    nch = len(m._chain)
    ch_par = np.array([entry.get(c[1], -1) for c in m._chain], np.int64)
    drv, c = [], 0
    for ch in m._chain:
        drv.append(-1 if ch[2] is None else c)
        c += ch[2] is not None
    ch_drv = np.array(drv, np.int64).reshape(nch)
    ch_sign = np.array([c[3] for c in m._chain], float).reshape(nch)
    ch_hinge = np.array([bool(c[4]) for c in m._chain], np.bool_).reshape(nch)
    z3 = np.zeros((3, 3))
    ch_K = np.array([z3 if c[5] is None else c[5] for c in m._chain], float).reshape(
        nch, 3, 3)
    ch_K2 = np.array([z3 if c[6] is None else c[6] for c in m._chain], float).reshape(
        nch, 3, 3)
    ch_point = np.array([c[7] for c in m._chain], float).reshape(nch, 3)
    ch_axis = np.array([np.zeros(3) if c[8] is None else c[8] for c in m._chain],
                       float).reshape(nch, 3)
    X0 = np.zeros((m.nn, 3))
    g_ent, g_off, g_idx, g_Xr = [], [0], [], []
    for b, idx, Xr in m._groups:
        X0[idx] = Xr
        g_ent.append(entry.get(b, -1))
        g_idx += list(idx)
        g_Xr += [list(x) for x in np.asarray(Xr, float)]
        g_off.append(len(g_idx))
    nf = len(m.free)
    pd_k = np.array([k for k, _ in m._profile_drums], np.int64)
    pd_mot = np.arange(len(chain_drives), len(motions), dtype=np.int64)
    kd = (mt, mseg, moff, ch_par, ch_drv, ch_sign, ch_hinge, ch_K, ch_K2, ch_point,
          ch_axis, np.array(g_ent, np.int64), np.array(g_off, np.int64),
          np.array(g_idx, np.int64), np.array(g_Xr, float).reshape(len(g_idx), 3), X0,
          bool(m.sway), np.asarray(m.free, np.int64), np.asarray(m.root, np.int64),
          np.asarray(m._X0_free, float).reshape(nf, 3),
          np.asarray(m._X0_root, float).reshape(nf, 3), np.asarray(m._H, float),
          np.asarray(m.free_mass, float), np.asarray(m.span_a, np.int64),
          np.asarray(m.span_b, np.int64), np.asarray(m.kin_a, np.bool_),
          np.asarray(m.kin_b, np.bool_), pd_k, pd_mot, int(m.nd),
          np.asarray(m.L0_ref, float), np.ascontiguousarray(lean.W, float),
          np.ascontiguousarray(m.Rd, float), np.ascontiguousarray(m.E, float))
    fd = (*lean._c, bool(lean.damped),
          np.asarray(m.lam_ref, float), bool(lean.wound))
    return kd, fd, dmap


def run(st, rec, spec, prep, t, q, v, ev, taut, progress, hmin, newton_max, max_steps,
        fail):
    """integrate.simulate's loop by `_run` from the state after `rec.start`; fills `rec`
    and `st` as the Python loop does -> t at the end. `fail(status, t, h, taut, l)`
    raises the Python loop's AnalysisError for a failed status."""
    kd, fd, dmap = prep
    m = st.m
    T = spec.duration
    n, nr = m.n, len(m.ropes)
    q, v = np.array(q, float), np.array(v, float)
    a = np.asarray(ev.F, float) / st.M
    taut = np.array(taut, np.bool_)
    jerk = np.zeros(n)
    F0, r0, _ = rec._force_rate(ev, taut)
    F0, r0 = np.array(F0, float), np.array(r0, float)
    loglam0 = np.array(ev._loglam, float)
    fs = np.zeros(NF)
    ist = np.zeros(NI, np.int64)
    fs[F_T], fs[F_H] = t, min(spec.max_step, 1e-3 * T, 1e-2)
    fs[F_PDR], fs[F_PDI], fs[F_PW], fs[F_TG] = ev.P_drive, ev.P_diss, ev.P_wound, \
        ev.T_guided
    fs[F_VG0] = rec.Vg0
    ist[I_NEXT] = rec.next_out
    peak = np.array(rec.peak, float)
    peak_t = np.array(rec.peak_t, float)
    out_times = np.asarray(rec.out_times, float)
    nout = len(out_times)
    s_t = np.zeros(nout)
    s_X = np.zeros((nout, m.nn, 3))
    s_F = np.zeros((nout, nr))
    s_mot = np.zeros((nout, len(kd[2]) - 1, 2))
    cap = max_steps // 4 + 1
    ev_t, ev_k, ev_s = np.empty(cap), np.empty(cap, np.int64), np.empty(cap, np.bool_)
    span_guard = ~(np.asarray(m.kin_a) & np.asarray(m.kin_b))
    lq, lv = q.copy(), v.copy()
    lfail = np.zeros(len(m.span_a))
    bps = np.array(list(spec.breakpoints) + [T], float)
    fscale = np.zeros(0) if st.fscale is None else np.asarray(st.fscale, float)
    args = (T, bps, float(spec.max_step), float(hmin), int(max_steps),
            float(st.newton_tol), int(newton_max), float(st.tol), fscale,
            np.asarray(st.sfloor, float), np.asarray(st.M, float), kd, fd, q, v, a, jerk,
            taut, loglam0, fs, ist, F0, r0, peak, peak_t, out_times, s_t, s_X, s_F, s_mot,
            ev_t, ev_k, ev_s, np.asarray(m.span_ref, float), span_guard, lq, lv, lfail)
    chunks = 200 if progress is not None else 1
    try:
        for j in range(chunks):
            _run(T * (j + 1) / chunks if j < chunks - 1 else np.inf, *args)
            if progress is not None:
                progress(float(fs[F_T]), T)
            if ist[I_STATUS] != OK or fs[F_T] >= T * (1 - 1e-14):
                break
    finally:
        _fill(st, rec, m, dmap, fs, ist, peak, peak_t, s_t, s_X, s_F, s_mot, ev_t,
              ev_k, ev_s, taut, lq, lv)
    if ist[I_STATUS] != OK:
        fail(int(ist[I_STATUS]), float(fs[F_T]), float(fs[F_FAILH]), taut, lfail)
    return float(fs[F_T])


def _fill(st, rec, m, dmap, fs, ist, peak, peak_t, s_t, s_X, s_F, s_mot, ev_t, ev_k,
          ev_s, taut, lq, lv):
    """The Recorder's and Stepper's fields as the Python loop leaves them."""
    st.steps += int(ist[I_STEPS])
    st.rejected += int(ist[I_REJ])
    st.newton_iterations += int(ist[I_ITS])
    st.tangents += int(ist[I_TG])
    names = m.model.ropes
    for i in range(min(int(ist[I_NEV]), len(ev_t))):
        k = int(ev_k[i])
        state = "taut" if ev_s[i] else "slack"
        st.events.append((float(ev_t[i]), f"rope {names[m.ropes[k]].name} {state}"))
    rec.peak, rec.peak_t = peak.tolist(), peak_t.tolist()
    rec.W, rec.D, rec.Wd = float(fs[F_W]), float(fs[F_D]), float(fs[F_WD])
    rec.max_terms = [max(rec.max_terms[0], fs[F_MT0]), max(rec.max_terms[1], fs[F_MT1]),
                     max(rec.max_terms[2], fs[F_MT2])]
    if ist[I_HASE]:
        rec.last_E = (float(fs[F_ET]), float(fs[F_EV]), float(fs[F_EU]))
    rec.taut = taut
    if ist[I_STEPS]:
        rec.last = SimpleNamespace(t=float(fs[F_T]), X=None, _q=lq.copy(), _v=lv.copy())
    i0, i1 = rec.next_out, int(ist[I_NEXT])
    rec.next_out = i1
    if i1 <= i0:
        return
    tt, X, F = s_t[i0:i1], s_X[i0:i1], s_F[i0:i1]
    nt = i1 - i0
    Fall = np.full((nt, len(m.model.ropes)), np.nan)
    Fall[:, m.ropes] = F
    pos = np.empty((nt, len(dmap)))
    spd = np.empty((nt, len(dmap)))
    tq = np.empty((nt, len(dmap)))
    for c, (kind, k, d) in enumerate(dmap):
        pos[:, c], spd[:, c] = s_mot[i0:i1, k, 0], s_mot[i0:i1, k, 1]
        if kind == "drum":            # Recorder._drum_torque of a profile drum
            acc = np.zeros(nt)
            for j, dd, R in zip(m.rope_drum, m.drum_of_end, m.end_radius):
                if dd == d.index:
                    acc = acc + R * F[:, j]
            tq[:, c] = acc
        else:
            tq[:, c] = [m.joint_drive_torque(d, x, y) for x, y in zip(tt, spd[:, c])]
    Xm = X[:, m.mass_nodes]
    span = X[:, m.hang] - X[:, m.free]
    rec.samples += [(float(tt[i]), Xm[i], Fall[i], pos[i], spd[i], tq[i], span[i])
                    for i in range(nt)]
