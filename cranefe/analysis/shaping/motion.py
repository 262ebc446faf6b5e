"""Motion profiles as piecewise-constant accelerations, their shaping, and the residual
sway they leave on a pendulum or a damped oscillator, in closed form.

A profile is a(t) = sum_j da_j H(t - t_j) (``AccelSteps``): a trapezoidal speed profile
has four jumps; an S-curve is j(t) = sum_j dj_j H(t - t_j) (``JerkSteps``), whose state
is the superposition of ramp responses instead (`_responses`). Shaping convolves the command with an impulse train (t_i, A_i): the
jumps become da_j A_i at t_j + t_i, still piecewise constant, so the shaped speed is
piecewise linear and is given exactly by its values at the jump times (``table``).

Residual vibration (docs/loads.md): the mode q'' + 2 zeta w q' + w^2 q = gain a(t),
from rest, is the superposition of step responses
  s(t) = [1 - exp(-zeta w t)(cos w_d t + zeta w / w_d sin w_d t)] / w^2,
  s'(t) = h(t) = exp(-zeta w t) sin(w_d t) / w_d,
q(T) = gain sum_j da_j s(T - t_j), q'(T) = gain sum_j da_j h(T - t_j) at the end T of
the motion (sum da_j = 0), after which q swings freely with amplitude
  sqrt(q^2 + ((q' + zeta w q) / w_d)^2)  (at T; it decays as exp(-zeta w (t - T))).
The linear pendulum of length l under a trolley acceleration a: l theta'' + g theta = -a,
i.e. w = sqrt(g/l), gain -1/l.
"""

from dataclasses import dataclass
from math import factorial

import numpy as np

from ...cases import G
from ...errors import AnalysisError, ModelError


@dataclass(frozen=True)
class AccelSteps:
    """a(t) = sum_j jumps[j] H(t - times[j]); times sorted (order 0: piecewise-constant
    acceleration, a trapezoidal speed)."""
    times: np.ndarray
    jumps: np.ndarray
    order = 0

    @property
    def end(self):
        return float(self.times[-1])

    def _power(self, t, k):
        """sum_j jumps_j (t - t_j)_+^k / k!: the profile integrated k times."""
        t = np.asarray(t, float)[..., None]
        d = np.maximum(t - self.times, 0.0)
        base = (t >= self.times) if k == 0 else d**k / factorial(k)
        return np.sum(self.jumps * base, axis=-1)

    def acceleration(self, t):
        return self._power(t, self.order)

    def speed(self, t):
        return self._power(t, self.order + 1)

    def position(self, t):
        return self._power(t, self.order + 2)

    def table(self, per_piece=1):
        """The speed profile as a table for the operation engine: ``{"times", "values",
        "positions"}`` at the corners (and ``per_piece - 1`` points inside each piece).
        Exact under linear interpolation for order 0 (the speed is piecewise linear);
        for order 1 (piecewise quadratic speed) the interpolation error is at most
        j h^2 / 8, h the row spacing, j the largest jerk."""
        corners = np.unique(np.concatenate([[0.0], self.times]))
        f = np.linspace(0.0, 1.0, per_piece + 1)[:-1]
        t = np.concatenate([(a + f * (b - a)) for a, b in zip(corners[:-1], corners[1:])]
                           + [corners[-1:]])
        return {"times": t.tolist(), "values": self.speed(t).tolist(),
                "positions": self.position(t).tolist()}


@dataclass(frozen=True)
class JerkSteps(AccelSteps):
    """j(t) = sum_j jumps[j] H(t - times[j]) (order 1: piecewise-linear acceleration, an
    S-curve speed)."""
    order = 1


def _merge(times, jumps, cls=AccelSteps):
    order = np.argsort(times, kind="stable")
    t, d = times[order], jumps[order]
    keep = np.concatenate([[True], np.diff(t) > 1e-12 * max(abs(t[-1]), 1.0)])
    return cls(t[keep], np.bincount(np.cumsum(keep) - 1, weights=d))


def trapezoid(distance, v_max, a_max):
    """Trapezoidal speed (a triangle if the distance is too short to reach v_max):
    accelerate at a_max for t_a = v/a_max, coast t_c, decelerate."""
    if not (distance > 0 and v_max > 0 and a_max > 0):
        raise ModelError("a trapezoidal move needs positive distance, v_max and a_max "
                         f"(got {distance}, {v_max}, {a_max})")
    v = min(v_max, np.sqrt(distance * a_max))
    ta = v / a_max
    tc = distance / v - ta
    return _merge(np.array([0.0, ta, ta + tc, 2 * ta + tc]),
                  np.array([a_max, -a_max, -a_max, a_max]))


def shape(profile, shaper):
    """The command convolved with the shaper's impulse train (same distance and top
    speed, longer by the shaper's duration)."""
    t = (profile.times[:, None] + shaper.times[None, :]).ravel()
    d = (profile.jumps[:, None] * shaper.amplitudes[None, :]).ravel()
    return _merge(t, d, type(profile))


def s_curve(distance, v_max, a_max, j_max):
    """Jerk-limited (S-curve) move: the trapezoid convolved with a box of width
    t_j = a_max / j_max and unit area (a moving average of the acceleration). The
    acceleration ramps over t_j at jerk j_max; distance and top speed are the
    trapezoid's, the move is t_j longer. In frequency terms the box multiplies every
    residual by |sin(w t_j/2)| / (w t_j/2) (undamped): an S-curve is itself a filter."""
    if not j_max > 0:
        raise ModelError(f"an S-curve needs a positive jerk limit (got {j_max})")
    trap = trapezoid(distance, v_max, a_max)
    tj = a_max / j_max
    t = np.concatenate([trap.times, trap.times + tj])
    d = np.concatenate([trap.jumps, -trap.jumps]) / tj
    return _merge(t, d, JerkSteps)


def _responses(tau, w, zeta):
    """Unit step response s, its derivative h and the unit ramp response rho of
    q'' + 2 zeta w q' + w^2 q = f, at the delays tau >= 0 (rho' = s, s' = h):
      rho = [t - 2 zeta/w + e^(-zeta w t)(2 zeta/w cos w_d t + (2 zeta^2 - 1)/w_d sin w_d t)]/w^2
    """
    wd = w * np.sqrt(1 - zeta**2)
    e, c, sn = np.exp(-zeta * w * tau), np.cos(wd * tau), np.sin(wd * tau)
    s = (1.0 - e * (c + zeta * w / wd * sn)) / w**2
    h = e * sn / wd
    rho = (tau - 2 * zeta / w + e * (2 * zeta / w * c + (2 * zeta**2 - 1) / wd * sn)) / w**2
    return s, h, rho


def residual_amplitude(profile, omega, zeta=0.0, gain=1.0):
    """Amplitude of the free vibration left by the profile on the mode (omega, zeta)
    (module docstring), at the end of the motion. For jerk steps (S-curves) the state
    is the superposition of ramp responses: q = gain sum dj rho, q' = gain sum dj s."""
    scale = np.max(np.abs(profile.jumps)) * max(profile.end, 1.0) ** (profile.order + 1)
    after = profile.acceleration(profile.end + np.array([1.0, 2.0]))
    if np.max(np.abs(after)) > 1e-9 * scale:
        raise ModelError("the motion does not end at constant speed (its acceleration "
                         "is not zero after the last step)")
    w = float(omega)
    wd = w * np.sqrt(1 - zeta**2)
    s, h, rho = _responses(profile.end - profile.times, w, zeta)
    q, dq = (s, h) if profile.order == 0 else (rho, s)
    q = gain * np.sum(profile.jumps * q)
    dq = gain * np.sum(profile.jumps * dq)
    return float(np.hypot(q, (dq + zeta * w * q) / wd))


def pendulum_omega(length, g=G):
    return float(np.sqrt(g / length))


def residual_sway(profile, length, g=G, zeta=0.0):
    """Residual sway amplitude [rad] of the linear pendulum of length l under the
    trolley motion (gain 1/l: l theta'' + g theta = -a)."""
    return residual_amplitude(profile, pendulum_omega(length, g), zeta, 1.0 / length)


def double_pendulum_omegas(l1, l2, m1, m2, g=G):
    """The hook (m1 on rope l1) and load (m2 on sling l2) double pendulum's two
    frequencies: M = diag(m1, m2), K = g [[(m1+m2)/l1 + m2/l2, -m2/l2], [-m2/l2, m2/l2]];
    det(K - w^2 M) = 0 gives w^4 - (1+R) g (1/l1 + 1/l2) w^2 + (1+R) g^2/(l1 l2) = 0,
    R = m2/m1."""
    R = m2 / m1
    b = (1 + R) * g * (1 / l1 + 1 / l2)
    c = (1 + R) * g**2 / (l1 * l2)
    d = np.sqrt(b * b - 4 * c)
    return float(np.sqrt(2 * c / (b + d))), float(np.sqrt(0.5 * (b + d)))


def nonlinear_residual_sway(profile, length, g=G, rtol=1e-10):
    """Residual sway [rad] of the exact (nonlinear) pendulum l theta'' = -g sin(theta) -
    a cos(theta), integrated piecewise between the acceleration jumps (DOP853), the
    amplitude from the pendulum's energy: cos(theta_max) = cos(theta) - l theta'^2 / (2g).
    """
    from scipy.integrate import solve_ivp
    y = np.zeros(2)
    edges = np.unique(np.concatenate([[0.0], profile.times]))
    for t0, t1 in zip(edges[:-1], edges[1:]):
        a0 = float(profile.acceleration(t0 + 0.5 * (t1 - t0)))
        slope = 0.0 if profile.order == 0 else float(np.sum(profile.jumps[profile.times <= t0]))
        tm = t0 + 0.5 * (t1 - t0)

        def rhs(t, y, a0=a0, slope=slope, tm=tm):      # a(t) is linear on the piece
            a = a0 + slope * (t - tm)
            return [y[1], -(g * np.sin(y[0]) + a * np.cos(y[0])) / length]
        sol = solve_ivp(rhs, (t0, t1), y, method="DOP853", rtol=rtol, atol=1e-14)
        if sol.status != 0:
            raise AnalysisError(f"pendulum integration failed at t = {t0} s: {sol.message}")
        y = sol.y[:, -1]
    c = np.cos(y[0]) - length * y[1]**2 / (2 * g)
    return float(np.arccos(np.clip(c, -1.0, 1.0)))
