"""Exact single-degree-of-freedom references for the dynamic factors (docs/loads.md,
"Single-mass references"): the closed forms the simulations are tested against and
that explain the standard's simplified values.

Common building block: the oscillator x'' + w^2 x = f(t) from rest, f a ramp from 0 to
f0 over t_r then constant. Duhamel's integral with h(t) = sin(w t)/w gives
  x(t) = (f0/w^2) (t - sin(w t)/w) / t_r                          0 <= t <= t_r
  x(t) = (f0/w^2) [1 - (sin(w t) - sin(w (t - t_r))) / (w t_r)]   t >= t_r
and sin(w t) - sin(w (t - t_r)) = 2 sin(w t_r/2) cos(w (t - t_r/2)), so after the ramp
x swings about the static value f0/w^2 with relative amplitude
  A(w t_r) = |sin(w t_r/2)| / (w t_r/2)     (A -> 1 for a step, t_r -> 0).
During the ramp x rises monotonically (x' = f0 (1 - cos w t)/(w^2 t_r) >= 0) to
x(t_r) = (f0/w^2)(1 - sin(w t_r)/(w t_r)) <= (f0/w^2)(1 + A), so the peak over all time
is (f0/w^2)(1 + A), reached after the ramp.
"""

import numpy as np

from ...cases import G


def ramp_amplitude(omega, t_r):
    """A = |sin(w t_r/2)| / (w t_r/2): the free swing's amplitude after a ramped step,
    relative to the step's static response (1 for t_r = 0)."""
    th = 0.5 * np.asarray(omega, float) * np.asarray(t_r, float)
    return np.abs(np.sinc(th / np.pi))        # np.sinc(x) = sin(pi x)/(pi x)


def ramp_response(omega, t_r, t):
    """x(t) w^2 / f0 of the ramped step (module docstring), for t >= 0; t_r = 0 is the
    step 1 - cos(w t)."""
    t = np.asarray(t, float)
    w = float(omega)
    if t_r == 0.0:
        return 1.0 - np.cos(w * t)
    during = (t - np.sin(w * t) / w) / t_r
    after = 1.0 - (np.sin(w * t) - np.sin(w * (t - t_r))) / (w * t_r)
    return np.where(t <= t_r, during, after)


def phi2_rigid_drive(v, omega, g=G):
    """phi2 = 1 + v w / g: a grounded mass lifted on an elastic rope whose end moves at
    the constant speed v from the start (rigid drive). The rope force rises
    quasi-statically until it equals m g; from lift-off the mass starts at rest while the
    rope end moves at v, so the stretch oscillates about its static value with velocity
    amplitude v: extra force m v w (cranefe.cases.hoist_lift_off)."""
    return 1.0 + np.asarray(v, float) * np.asarray(omega, float) / g


def phi5_ramp(omega, t_r):
    """phi5 of one elastic degree of freedom under an acceleration ramped from 0 to a
    over t_r: peak elastic force / rigid-body inertia force m a = 1 + A(w t_r) =
    1 + |sin(w t_r/2)| / (w t_r/2); 2 for a sudden step (t_r = 0). The relative
    coordinate obeys x'' + w^2 x = a(t) (the module's oscillator with f0 = a)."""
    return 1.0 + ramp_amplitude(omega, t_r)


def phi3_sudden(dm_over_m):
    """Sudden release of dm from a mass m on a spring: the remaining mass m - dm starts
    at rest at the old equilibrium x0 = m g/k and swings about its new one
    x1 = (m - dm) g/k with amplitude x0 - x1 = dm g/k. The spring force therefore ranges
    over [(m - 2 dm) g, m g]: relative to the hoist load m g,
    phi3 = 1 - 2 dm/m (the standard's 1 - (dm/m)(1 + beta3) with beta3 = 1); the upper
    extreme returns to 1 (never above the load before the release)."""
    r = np.asarray(dm_over_m, float)
    return 1.0 - 2.0 * r, np.ones_like(r)


def phi3_linear_release(dm_over_m, omega_remaining, t_r):
    """Release of dm spread linearly over t_r: the force dm g carried for the released
    part falls from dm g to 0 over t_r while the remaining mass m' = m - dm (frequency
    w' = sqrt(k/m')) follows. This is the ramped step of size -dm g on m', so the spring
    force swings about m' g with amplitude A(w' t_r) dm g after the release:
      phi3 = 1 - (dm/m)(1 + A),  A = |sin(w' t_r/2)| / (w' t_r/2)
    (the standard's form with beta3 = A: 1 for t_r -> 0; 0.5 at w' t_r = 3.791, i.e.
    t_r = 0.603 periods of the remaining mass). Returns (lowest, highest) force / m g;
    the highest is 1 - (dm/m)(1 - A)."""
    r = np.asarray(dm_over_m, float)
    A = ramp_amplitude(omega_remaining, t_r)
    return 1.0 - r * (1.0 + A), 1.0 - r * (1.0 - A)


def beta3_equivalent(omega_remaining, t_r):
    """The beta3 that a linear release over t_r corresponds to: A(w' t_r)."""
    return ramp_amplitude(omega_remaining, t_r)


def buffer_peak_force(mass, speed, stiffness):
    """A rigid mass m at speed v on a linear buffer of stiffness k: peak force
    v sqrt(k m) (all kinetic energy in the spring: F^2/(2k) = m v^2/2); the rigid-body
    force of the standard's buffer case is this with xi = 0.5."""
    return float(speed) * np.sqrt(float(stiffness) * float(mass))
