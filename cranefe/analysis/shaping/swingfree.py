"""The minimum-time swing-free trolley move among trapezoidal (bang-coast-bang) speed
profiles, for a pendulum of length l (docs/loads.md, "Swing-free trapezoid").

With acceleration a for t_a, coast t_c, deceleration a for t_a, the acceleration is two
rectangular pulses of width t_a, the second opposite and delayed by s = t_a + t_c. A
pulse of width t_a leaves the undamped pendulum (w = sqrt(g/l)) a residual proportional
to |sin(w t_a / 2)|, the delayed opposite pulse the same with a phase w s, so
  residual = (4 a / (l w^2)) |sin(w t_a / 2)| |sin(w s / 2)|        (exact, linear)
which vanishes iff t_a = m T (each pulse swing-free on its own) or s = n T (the second
pulse cancels the first), T = 2 pi / w, m, n = 1, 2, ... The distance is D = a t_a s,
the time t_a + s, with a <= a_max, a t_a <= v_max, t_a <= s:
- family "s = nT": t_a = D / (a n T), fastest with a = a_max; needs D/(nT) <= v_max and
  t_a <= nT (else the coast would be negative);
- family "t_a = mT": a = min(a_max, v_max / (mT)), s = max(D / (a m T), mT) (when the
  distance is short the acceleration is lowered so that s = mT, a triangle).
The minimum over both families and all m, n is returned.
"""

import numpy as np

from ...cases import G
from ...errors import ModelError
from .motion import AccelSteps


def _candidates(D, v_max, a_max, T, n_max):
    for n in range(1, n_max + 1):
        s = n * T
        ta = D / (a_max * s)
        if D / s <= v_max * (1 + 1e-12) and ta <= s:
            yield ta + s, "coast: t_a + t_c = %d T" % n, a_max, ta, s
    for m in range(1, n_max + 1):
        ta = m * T
        a = min(a_max, v_max / ta)
        s = D / (a * ta)
        if s < ta:
            a, s = D / ta**2, ta
        yield ta + s, "acceleration: t_a = %d T" % m, a, ta, s


def min_time_swing_free(distance, v_max, a_max, length, g=G, n_max=200):
    """Fastest swing-free trapezoid: dict with ``profile`` (AccelSteps), ``time_s``,
    ``acceleration``, ``t_acc``, ``t_coast``, ``family``."""
    if not (distance > 0 and v_max > 0 and a_max > 0 and length > 0):
        raise ModelError("a swing-free move needs positive distance, v_max, a_max and "
                         f"length (got {distance}, {v_max}, {a_max}, {length})")
    T = 2 * np.pi * np.sqrt(length / g)
    best = min(_candidates(distance, v_max, a_max, T, n_max), key=lambda c: c[0])
    total, family, a, ta, s = best
    profile = AccelSteps(np.array([0.0, ta, s, s + ta]), np.array([a, -a, -a, a]))
    return {"profile": profile, "time_s": float(total), "acceleration": float(a),
            "t_acc": float(ta), "t_coast": float(s - ta), "family": family,
            "period_s": float(T)}


def _x_minus_sin(y):
    """y - sin(y) without cancellation for small y (its series to y^9 below 0.1: the
    next term is y^11 / 39916800, 1.5e-15 of the sum)."""
    if y > 0.1:
        return y - np.sin(y)
    y2 = y * y
    return y * y2 / 6 * (1 - y2 / 20 * (1 - y2 / 42 * (1 - y2 / 72)))


def _gram(w, T):
    """G_kl = int_0^T g_k g_l dt of g = (1, T - t, cos(w t), sin(w t)), integrated by hand
    (by parts for (T - t) cos and (T - t) sin; 1 - cos x = 2 sin^2(x/2), and x - sin x
    from `_x_minus_sin`, so a short move, w T << 1, keeps its digits)."""
    x = w * T
    s, omc = np.sin(x), 2 * np.sin(x / 2) ** 2
    c2 = _x_minus_sin(2 * x) / (4 * w)                 # int sin^2 = (2x - sin 2x)/(4w)
    G = np.array([
        [T, T**2 / 2, s / w, omc / w],
        [T**2 / 2, T**3 / 3, omc / w**2, _x_minus_sin(x) / w**2],
        [s / w, omc / w**2, T - c2, s**2 / (2 * w)],
        [omc / w, _x_minus_sin(x) / w**2, s**2 / (2 * w), c2]])
    return G


def energy_optimal_swing_free(distance, duration, length, g=G, swing_free=True):
    """The trolley move of a given duration with the least integral of a^2 (the drive
    force squared: the copper losses of a drive that only accelerates the mass) that
    ends at rest at the distance with the pendulum at rest (linear, undamped).

    Constraints, linear in a(t): int a = 0 (speed back to 0), int (T - t) a = D (the
    distance), int a cos(w t) = int a sin(w t) = 0 (the pendulum's Duhamel integral
    int a(t) e^(i w (T - t)) dt is zero: no residual sway). Minimising int a^2 under
    <a, g_k> = c_k gives a = sum_k lambda_k g_k with the Gram system G lambda = c,
    G_kl = <g_k, g_l> in closed form (`_gram`), and the cost int a^2 = lambda^T G lambda:
      a(t) = l1 + l2 (T - t) + l3 cos(w t) + l4 sin(w t).
    Without the sway constraints (swing_free=False) it is the classic
    a = (6 D / T^2)(1 - 2 t / T). Returns a dict with ``acceleration``, ``speed``,
    ``position`` (callables), ``coefficients``, ``cost`` (int a^2), ``peak_speed``,
    ``peak_acceleration`` and ``table(n)`` for the operation engine.
    """
    D, T = float(distance), float(duration)
    if not (D > 0 and T > 0 and length > 0):
        raise ModelError("an energy-optimal move needs positive distance, duration and "
                         f"length (got {distance}, {duration}, {length})")
    w = np.sqrt(g / length)
    k = 4 if swing_free else 2
    G = _gram(w, T)
    lam = np.zeros(4)
    lam[:k] = np.linalg.solve(G[:k, :k], np.array([0.0, D, 0.0, 0.0][:k]))

    def acceleration(s):
        s = np.asarray(s, float)
        return lam[0] + lam[1] * (T - s) + lam[2] * np.cos(w * s) + lam[3] * np.sin(w * s)

    def speed(s):
        s = np.asarray(s, float)
        return (lam[0] * s + lam[1] * (T * s - s**2 / 2) + lam[2] * np.sin(w * s) / w
                + lam[3] * (1 - np.cos(w * s)) / w)

    def position(s):
        s = np.asarray(s, float)
        return (lam[0] * s**2 / 2 + lam[1] * (T * s**2 / 2 - s**3 / 6)
                + lam[2] * (1 - np.cos(w * s)) / w**2 + lam[3] * (s / w - np.sin(w * s) / w**2))

    def table(n=200):
        s = np.linspace(0.0, T, n + 1)
        return {"times": s.tolist(), "values": speed(s).tolist(),
                "positions": position(s).tolist()}

    fine = np.linspace(0.0, T, 2001)
    return {"acceleration": acceleration, "speed": speed, "position": position,
            "table": table, "coefficients": lam, "duration_s": T,
            "cost": float(lam @ G @ lam),
            "peak_speed": float(np.max(np.abs(speed(fine)))),
            "peak_acceleration": float(np.max(np.abs(acceleration(fine))))}
