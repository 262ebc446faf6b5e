"""One trapezoidal step of the lean path compiled by numba (optional extra `fast`).

`Stepper.step` (integrate.py) with `Lean.evaluate` (lean.py) spends its time in ~100
numpy calls per step on a system of 2-8 coordinates, each costing more than its
arithmetic. `FastLean` does the same step - the forces, their tangent, the Newton
iteration and the local error estimate of the step - in one compiled function
(`_step`), the same formulas as `Lean.evaluate` written out in loops:

- span vectors `d = D q + d_kin(t)`, lengths l, unit vectors e, rope lengths
  `L = sum_s f_s l_s + extra`, stretch `ln(L/L0)`, Hencky force `S = EA ln(L/L0)`
  (taut ropes), rows `G = dL/dq = sum_s f_s e_s . D_s`, elongation rate
  `G v + R omega + (e . v_kin) B`, dashpot `b = beta sqrt(c)` with `c = EA/L`
  (Mechanism._dashpot_frequencies; docs/operations.md "Damping"), `F = F_g - (S + S_d) G`;
- tangent `K = c G^T G + sum_s f_s S/l (D_s^T D_s - (e.D_s)^T (e.D_s))`,
  `C = b G^T G`, Newton matrix `4/h^2 M + 2/h C + K`, LU with partial pivoting kept
  for the modified Newton iterations, made afresh when a correction shrinks by less
  than 10x (as `Stepper.step`);
- the error of the step `h^2/12 |a1 - a0|` against the position tolerance and
  `h^2/12 |EA/L G (a1 - a0)|` relative to the rope's force (integrate.py,
  `Stepper.error`).

`Lean` stays the reference: tests/test_operation_speed.py steps both from the same
states and asserts the same q1, a1, forces and error to 1e-12. Without numba
(`pip install 'cranefe[fast]'`) the integrator uses `Lean` and `Stepper.step`. With
numba the integrator runs the whole loop compiled (loop.py, which calls `_step`); this
step inside the Python loop remains as `simulate(model, fast="step")`.
"""

import math

import numpy as np

from .lean import Lean
from .mechanism import Eval

try:                                     # optional: pip install 'cranefe[fast]'
    import numba
except ImportError:                      # pragma: no cover - depends on the install
    numba = None


def available():
    """True when numba is installed (the compiled step can be used)."""
    return numba is not None


def _jit(f):
    return numba.njit(cache=True, nogil=True)(f) if numba is not None else f


@_jit
def _forces(q, v, Dm, dk, dvk, Af, extra, L0, EA, romega, taut, beta, Fg,
            D, falls, span_rope, damped, tangent, K, C):
    """Lean.evaluate's forces (and with `tangent` K, C in place) at (q, v).

    Returns (F, G, l, e, L, lam, loglam, S, Sd, edot, cL). Length: written out in
    loops for the compiler (one formula per block, see the module docstring)."""
    ns = Dm.shape[0] // 3
    nx = Dm.shape[1]
    nr = Af.shape[0]
    d = dk.copy()
    for i in range(3 * ns):
        acc = 0.0
        for c in range(nx):
            acc += Dm[i, c] * q[c]
        d[i] += acc
    l = np.empty(ns)
    e = np.empty(3 * ns)
    for s in range(ns):
        x, y, z = d[3 * s], d[3 * s + 1], d[3 * s + 2]
        ls = math.sqrt(x * x + y * y + z * z)
        l[s] = ls
        e[3 * s], e[3 * s + 1], e[3 * s + 2] = x / ls, y / ls, z / ls
    L = extra.copy()
    for r in range(nr):
        for s in range(ns):
            L[r] += Af[r, s] * l[s]
    lam = L / L0
    loglam = np.log(lam)
    # eD[s] = e_s . D_s (nx); G[r] = sum_s f_s Af[r, s] eD[s]
    eD = np.zeros((ns, nx))
    for s in range(ns):
        for c in range(nx):
            eD[s, c] = e[3 * s] * D[s, 0, c] + e[3 * s + 1] * D[s, 1, c] + \
                e[3 * s + 2] * D[s, 2, c]
    G = np.zeros((nr, nx))
    for r in range(nr):
        for s in range(ns):
            a = Af[r, s]
            if a != 0.0:
                for c in range(nx):
                    G[r, c] += a * eD[s, c]
    edot = romega.copy()
    for r in range(nr):
        for c in range(nx):
            edot[r] += G[r, c] * v[c]
    if dvk.shape[0]:
        for r in range(nr):
            acc = 0.0
            for i in range(3 * ns):
                acc += e[i] * dvk[i] * Af[r, i // 3]
            edot[r] += acc
    S = np.zeros(nr)
    cL = np.zeros(nr)
    for r in range(nr):
        if taut[r]:
            S[r] = EA[r] * loglam[r]
            cL[r] = EA[r] / L[r]
    Sd = np.zeros(nr)
    b = np.zeros(nr)
    if damped:
        for r in range(nr):
            b[r] = beta[r] * math.sqrt(cL[r])     # Mechanism.evaluate: beta sqrt(c)
            Sd[r] = b[r] * edot[r]
    F = Fg.copy()
    for r in range(nr):
        st = S[r] + Sd[r]
        for c in range(nx):
            F[c] -= st * G[r, c]
    if tangent:
        for i in range(nx):
            for j in range(nx):
                k = 0.0
                cc = 0.0
                for r in range(nr):
                    gg = G[r, i] * G[r, j]
                    k += cL[r] * gg
                    cc += b[r] * gg
                for s in range(ns):
                    wg = falls[s] * S[span_rope[s]] / l[s]
                    dd = 0.0
                    for x in range(3):
                        dd += D[s, x, i] * D[s, x, j]
                    k += wg * (dd - eD[s, i] * eD[s, j])
                K[i, j] = k
                C[i, j] = cc
    return F, G, l, e, L, lam, loglam, S, Sd, edot, cL


@_jit
def _lu(J, piv):
    """In-place LU with partial pivoting; False if J is singular."""
    n = J.shape[0]
    for k in range(n):
        p = k
        big = abs(J[k, k])
        for i in range(k + 1, n):
            if abs(J[i, k]) > big:
                big, p = abs(J[i, k]), i
        piv[k] = p
        if big == 0.0 or not math.isfinite(big):
            return False
        if p != k:
            for j in range(n):
                J[k, j], J[p, j] = J[p, j], J[k, j]
        for i in range(k + 1, n):
            f = J[i, k] / J[k, k]
            J[i, k] = f
            for j in range(k + 1, n):
                J[i, j] -= f * J[k, j]
    return True


@_jit
def _solve(LU, piv, b):
    n = LU.shape[0]
    x = b.copy()
    for k in range(n):
        p = piv[k]
        if p != k:
            x[k], x[p] = x[p], x[k]
    for i in range(n):
        for j in range(i):
            x[i] -= LU[i, j] * x[j]
    for i in range(n - 1, -1, -1):
        for j in range(i + 1, n):
            x[i] -= LU[i, j] * x[j]
        x[i] /= LU[i, i]
    return x


@_jit
def _step(q0, v0, a0, h, jerk, has_jerk, Dm, dk, dvk, Af, extra, L0, EA, romega, taut,
          beta, Fg, D, falls, span_rope, damped, M, newton_tol, newton_max,
          fscale, sfloor, tol):
    """One trapezoidal step (Stepper.step with Lean.evaluate) and its error.

    Returns (status, q1, v1, a1, err, iterations, tangents, forces of the last
    iterate, that iterate's q and v): status 0 converged, 1 not (non-finite, singular or too many
    iterations). err: the step's local error relative to the tolerances (the larger
    of position and rope force; integrate.py)."""
    n = q0.shape[0]
    c1, c2 = 4.0 / (h * h), 2.0 / h
    q1 = q0 + h * v0 + (0.5 * h * h) * a0
    if has_jerk:
        q1 = q1 + (0.25 * h * h * h) * jerk
    qb = q0 + h * v0
    K = np.zeros((n, n))
    C = np.zeros((n, n))
    J = np.zeros((n, n))
    piv = np.zeros(n, np.int64)
    fresh = True
    prev = np.inf
    its = 0
    tangents = 0
    for _ in range(newton_max):
        v1 = c2 * (q1 - q0) - v0
        a1 = c1 * (q1 - qb) - a0
        out = _forces(q1, v1, Dm, dk, dvk, Af, extra, L0, EA, romega, taut, beta,
                      Fg, D, falls, span_rope, damped, fresh, K, C)
        F = out[0]
        its += 1
        R = F - M * a1
        if fresh:
            if not math.isfinite(R.sum()):
                return 1, q1, v1, a1, 0.0, its, tangents, out, q1, v1
            for i in range(n):
                for j in range(n):
                    J[i, j] = K[i, j] + c2 * C[i, j]
                J[i, i] += c1 * M[i]
            tangents += 1
            if not _lu(J, piv):
                return 1, q1, v1, a1, 0.0, its, tangents, out, q1, v1
        dq = _solve(J, piv, R)
        dq_norm = 0.0
        for i in range(n):
            dq_norm = max(dq_norm, abs(dq[i]))
        if not math.isfinite(dq_norm):
            return 1, q1, v1, a1, 0.0, its, tangents, out, q1, v1
        if not fresh and dq_norm <= newton_tol:
            qi, vi = q1, v1
            q1 = q1 + dq
            v1 = c2 * (q1 - q0) - v0
            a1 = c1 * (q1 - qb) - a0
            da = a1 - a0
            err = 0.0
            for i in range(n):
                err = max(err, abs(da[i]))
            err /= tol
            if fscale.shape[0]:
                G, L, S = out[1], out[4], out[7]
                for r in range(G.shape[0]):
                    if taut[r]:
                        x = 0.0
                        for c in range(G.shape[1]):
                            x += G[r, c] * da[c]
                        err = max(err, abs(fscale[r] * x /
                                           (L[r] * max(sfloor[r], abs(S[r])))))
            err *= h * h / 12.0
            return 0, q1, v1, a1, err, its, tangents, out, qi, vi
        fresh = (not fresh) and dq_norm > 0.1 * prev
        prev = dq_norm
        q1 = q1 + dq
    v1 = c2 * (q1 - q0) - v0
    return 1, q1, v1, c1 * (q1 - qb) - a0, 0.0, its, tangents, out, q1, v1


@_jit
def _step_packed(q0, v0, a0, h, jerk, has_jerk, Dm, dk, dvk, Af, extra, L0, EA, romega,
                 taut, beta, Fg, D, falls, span_rope, damped, M, newton_tol,
                 newton_max, fscale, sfloor, tol):
    """`_step` with its arrays packed into one (a returned array costs a boxing each):
    (status, err, iterations, tangents, [q1 v1 a1 q v F | G | l | e | L lam loglam S
    Sd edot cL])."""
    st, q1, v1, a1, err, its, tg, out, qi, vi = _step(
        q0, v0, a0, h, jerk, has_jerk, Dm, dk, dvk, Af, extra, L0, EA, romega, taut,
        beta, Fg, D, falls, span_rope, damped, M, newton_tol, newton_max, fscale,
        sfloor, tol)
    F, G, l, e, L, lam, loglam, S, Sd, edot, cL = out
    n, nr, ns = q0.shape[0], L.shape[0], l.shape[0]
    buf = np.empty(6 * n + G.size + 4 * ns + 7 * nr)
    k = 0
    for x in (q1, v1, a1, qi, vi, F, G.ravel(), l, e, L, lam, loglam, S, Sd, edot, cL):
        buf[k:k + x.size] = x
        k += x.size
    return st, err, its, tg, buf


class FastLean(Lean):
    """`Lean` with `step`: the whole trapezoidal step compiled (module docstring)."""

    def __init__(self, mech):
        super().__init__(mech)
        m = mech
        self._c = (self.Dm, self.Af, m.extra.astype(float), m.EA.astype(float),
                   m.beta.astype(float),
                   np.ascontiguousarray(m.Fg, float), np.ascontiguousarray(m.D, float),
                   m.falls.astype(float), np.asarray(m.span_rope, np.int64))
        self._empty = np.zeros(0)
        n, nr, ns = m.n, self.nr, self.ns
        cuts = np.cumsum([n] * 6 + [nr * self.nx, ns, 3 * ns] + [nr] * 7)
        self._cuts = [(int(a), int(b)) for a, b in zip(np.r_[0, cuts], cuts)]
        self._Gshape = (nr, self.nx)

    def step(self, t1, q0, v0, a0, h, taut, jerk, M, newton_tol, newton_max, fscale,
             sfloor, tol):
        """-> (status, q1, v1, a1, err, iterations, tangents, ev of the last iterate)."""
        kt = self.kin(t1)
        dk, dvk, L0, romega = kt[2], kt[3], kt[7], kt[8]
        Dm, Af, extra, EA, beta, Fg, D, falls, span_rope = self._c
        st, err, its, tg, buf = _step_packed(
            q0, v0, a0, h, self._empty if jerk is None else jerk, jerk is not None,
            Dm, dk, self._empty if dvk is None else dvk, Af, extra, L0, EA, romega,
            taut, beta, Fg, D, falls, span_rope, bool(self.damped), M,
            newton_tol, newton_max, self._empty if fscale is None else fscale, sfloor,
            tol)
        q1, v1, a1, qi, vi, F, G, l, e, L, lam, loglam, S, Sd, edot, cL = (
            buf[a:b] for a, b in self._cuts)
        G = G.reshape(self._Gshape)
        if taut is not self._taut:
            self._taut, self._alltaut = taut, bool(taut.all())
        ev = Eval(t1, F, None, None, None, None, L, L0, S, Sd, edot, self._z0, kt[5],
                  kt[6], self._znd, None, None, None)
        ev._l, ev._e, ev._lam, ev._kt, ev._taut = l, e, lam, kt, taut
        ev._loglam, ev._St, ev._cL, ev._G = loglam, S + Sd, cL, G
        ev._q, ev._v = qi, vi
        return st, q1, v1, a1, err, its, tg, ev
