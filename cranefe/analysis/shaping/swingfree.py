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
