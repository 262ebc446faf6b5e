"""Motion profiles of prescribed drives: trapezoidal speed, S-curve (jerk-limited) and
speed tables, all compiled into one piecewise form with constant jerk per segment.

Position s(t) = s_k + v_k tau + a_k tau^2/2 + j_k tau^3/6 on segment k (tau = t - t_k);
before the first segment the drive rests at s = 0, after the last it keeps the last
speed (zero for trapezoid and S-curve). docs/operations.md, "Drive profiles".
"""

from bisect import bisect_right
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq


@dataclass(frozen=True)
class Motion:
    """Piecewise constant-jerk motion: segment k starts at t[k] with state
    (s[k], v[k], a[k]) and has jerk j[k]; t[-1] ends the last segment."""

    t: np.ndarray
    s: np.ndarray
    v: np.ndarray
    a: np.ndarray
    j: np.ndarray
    kind: str = "table"

    @classmethod
    def build(cls, t0, pieces, kind, v0=0.0):
        """From (duration, a_start, jerk) pieces after a rest (or speed v0) until t0."""
        t, s, v, a, j = [t0], [v0 * t0], [v0], [], []
        for dur, a0, jk in pieces:
            a.append(a0)
            j.append(jk)
            s.append(s[-1] + v[-1] * dur + a0 * dur**2 / 2 + jk * dur**3 / 6)
            v.append(v[-1] + a0 * dur + jk * dur**2 / 2)
            t.append(t[-1] + dur)
        return cls(np.array(t), np.array(s), np.array(v), np.array(a + [0.0]),
                   np.array(j + [0.0]), kind)

    def __post_init__(self):
        # the segments as plain floats: __call__ runs at every step of the integrator,
        # where numpy's scalar indexing and searchsorted cost more than the arithmetic
        last = len(self.t) - 1
        segs = tuple((float(self.s[k]), float(self.v[k]),
                      0.0 if k == last else float(self.a[k]),
                      0.0 if k == last else float(self.j[k])) for k in range(last + 1))
        object.__setattr__(self, "_tl", tuple(float(x) for x in self.t))
        object.__setattr__(self, "_segs", segs)

    def __call__(self, t):
        """(position, speed, acceleration) at t."""
        tl = self._tl
        if t < tl[0]:
            v = self._segs[0][1]
            return v * t, v, 0.0
        k = bisect_right(tl, t) - 1          # = searchsorted(t, side="right") - 1
        s, v, a, jk = self._segs[k]
        tau = t - tl[k]
        return s + v * tau + a * tau * tau / 2 + jk * tau**3 / 6, \
            v + a * tau + jk * tau * tau / 2, a + jk * tau

    @property
    def breakpoints(self):
        return self.t

    @property
    def end(self):
        """End of the motion: the last segment boundary if the drive then rests, else inf."""
        return float(self.t[-1]) if abs(self.v[-1]) <= 1e-12 * max(
            1.0, np.abs(self.v).max()) else float("inf")

    def moves(self):
        """(start, stop) times of each motion between rests (stop inf if it never
        rests again)."""
        tt = self.t
        scale = max(1.0, np.abs(self.v).max(), np.abs(self.a).max())

        def moving(k):          # segment k (the last one: constant speed v[-1])
            if k == len(tt) - 1:
                return abs(self.v[k]) > 1e-12 * scale
            return abs(self.v[k]) > 1e-12 * scale or abs(self.a[k]) > 1e-12 * scale \
                or abs(self.j[k]) > 1e-12 * scale
        out, start = [], None
        if abs(self.v[0]) > 1e-12 * scale:          # moving from t = 0 (a table)
            start = 0.0
        for k in range(len(tt)):
            if moving(k) and start is None:
                start = float(tt[k])
            elif not moving(k) and start is not None:
                out.append((start, float(tt[k])))
                start = None
        if start is not None:
            out.append((start, float("inf")))
        return out

    def extremes(self, T):
        """(min, max) of the position over 0 <= t <= T."""
        cand = [0.0, T] + [x for x in self.t if 0 <= x <= T]
        for k in range(len(self.t) - 1):
            t0, t1 = self.t[k], self.t[k + 1]
            # v + a tau + j tau^2 / 2 = 0
            roots = np.roots([self.j[k] / 2, self.a[k], self.v[k]]) \
                if self.j[k] != 0 else ([-self.v[k] / self.a[k]] if self.a[k] != 0 else [])
            for rt in np.atleast_1d(roots):
                if np.isreal(rt) and 0 < rt.real < t1 - t0 and t0 + rt.real <= T:
                    cand.append(t0 + rt.real)
        vals = [self(x)[0] for x in cand]
        return min(vals), max(vals)


def trapezoid(distance, v_max, a_max, start=0.0):
    """Trapezoidal speed: accelerate at a_max to v_max, cruise, decelerate; triangular
    (peak sqrt(|d| a_max)) when |d| < v_max^2 / a_max."""
    D, sg = abs(distance), np.sign(distance)
    if D == 0:
        return Motion.build(start, [], "trapezoid")
    vp = min(v_max, np.sqrt(D * a_max))
    ta = vp / a_max
    tc = max(D / vp - ta, 0.0)
    pieces = [(ta, sg * a_max, 0.0)] + ([(tc, 0.0, 0.0)] if tc > 0 else []) + \
        [(ta, -sg * a_max, 0.0)]
    return Motion.build(start, pieces, "trapezoid")


def s_curve(distance, v_max, a_max, j_max, start=0.0):
    """Jerk-limited (7-segment) profile: jerk +-j_max for T_j = a_p / j_max, constant
    acceleration a_p for T_a, cruise at v_p; the peak speed is lowered (and a_p with it)
    until the acceleration and deceleration fit in the distance."""
    D, sg = abs(distance), np.sign(distance)
    if D == 0:
        return Motion.build(start, [], "s_curve")

    def phase(v):
        if v >= a_max**2 / j_max:
            tj = a_max / j_max
            return tj, v / a_max - tj, a_max
        tj = np.sqrt(v / j_max)
        return tj, 0.0, tj * j_max

    def dist(v):          # accelerating + decelerating: average speed v/2 over each
        tj, ta, _ = phase(v)
        return v * (ta + 2 * tj)

    vp = v_max if dist(v_max) <= D else brentq(lambda v: dist(v) - D, 1e-12 * v_max,
                                               v_max, xtol=1e-14 * v_max, rtol=1e-15)
    tj, ta, ap = phase(vp)
    tc = max(D / vp - (ta + 2 * tj), 0.0)
    a, j = sg * ap, sg * j_max
    pieces = [(tj, 0.0, j)] + ([(ta, a, 0.0)] if ta > 0 else []) + [(tj, a, -j)]
    pieces += [(tc, 0.0, 0.0)] if tc > 0 else []
    pieces += [(tj, 0.0, -j)] + ([(ta, -a, 0.0)] if ta > 0 else []) + [(tj, -a, j)]
    return Motion.build(start, pieces, "s_curve")


def speed_table(times, speeds):
    """Speed linear between the points of a table [[t, v], ...]; the first speed holds
    from t = 0 to the first time, the last after the last time; position from 0."""
    times, speeds = np.asarray(times, float), np.asarray(speeds, float)
    pieces = [(times[k + 1] - times[k], (speeds[k + 1] - speeds[k]) /
               (times[k + 1] - times[k]), 0.0) for k in range(len(times) - 1)]
    return Motion.build(times[0], pieces, "table", v0=speeds[0])


def combine(motions):
    """The sum of several moves of one drive (e.g. hoisting, then lowering later): a
    piecewise constant-jerk motion on the union of their breakpoints."""
    if len(motions) == 1:
        return motions[0]
    t = np.unique(np.concatenate([m.t for m in motions]))
    s, v, a, j = (np.zeros(len(t)) for _ in range(4))
    for m in motions:
        for k, tk in enumerate(t):
            sk, vk, ak = m(tk)
            s[k] += sk
            v[k] += vk
            a[k] += ak
            i = int(np.searchsorted(m.t, tk, side="right")) - 1
            if 0 <= i < len(m.t) - 1:
                j[k] += m.j[i]
    v0 = sum(m.v[0] if m.t[0] > 0 else 0.0 for m in motions)
    if t[0] > 0 and v0 != 0:
        raise ValueError("moves with a speed before their first time cannot be combined")
    return Motion(t, s, v, np.append(a[:-1], 0.0), np.append(j[:-1], 0.0), "combined")
