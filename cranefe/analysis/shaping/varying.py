"""A zero-vibration shaper for a pendulum whose length changes during the move (hoisting
or lowering while the trolley travels, slews or luffs): docs/shaping.md, "Time-varying
ZV". Derivation (ours; the linear theory of Singhose et al. 2000, "Effects of hoisting
on the input shaping control of gantry cranes", Control Eng. Practice 8, with the
shaper's delay and amplitudes following the length instead of being fixed):

A pendulum of length l(t) under a suspension acceleration a(t): l th'' + 2 l' th' +
g th = -a (linear). In the load's offset u = l th (u'' = l th'' + 2 l' th' + l'' th):

    u'' + w(t)^2 u = -a(t),      w(t)^2 = (g - l'') / l                       (1)

no first-derivative term, so the Wronskian of two free solutions is constant (Abel).
A velocity increment dv = a(tau) dtau of the command at tau starts the free swing
-dv y_tau(t), y_tau(tau) = 0, y_tau'(tau) = 1. Split it into A1 dv at tau and A2 dv at
tau + D(tau), D the time to the next zero of y_tau (the half period of (1), a Sturm
conjugate point): there y_tau = 0 and y_tau' = rho(tau), so y_tau = rho y_{tau+D} from
then on, and the two swings cancel iff A1 rho + A2 = 0; with A1 + A2 = 1 (the speed is
kept):

    A1 = 1 / (1 - rho),   A2 = -rho / (1 - rho)                               (2)

(constant w: D = pi / w, rho = -1, A1 = A2 = 1/2: the ZV shaper). Every increment is
cancelled on its own, so the shaped command leaves no residual in (1), for any l(t).
D and rho come from one pair of free solutions y1, y2 (y1 + i y2 = r e^(i phi), phi
increasing): D(tau) solves phi(tau + D) = phi(tau) + pi, and rho = y'(tau + D) with
y = (y1(tau) y2 - y2(tau) y1) / W.

The shaped speed v_s(t) = int_0^t A1 a dtau + int_{tau + D(tau) <= t} A2 a dtau. The
delays D vary, so the distance changes by -int a A2 D dtau; the command is scaled to
keep the distance (a scaled command is cancelled as well: (1) is linear).
"""

import numpy as np
from scipy.integrate import solve_ivp
from scipy.interpolate import CubicSpline

from ...cases import G
from ...errors import AnalysisError, ModelError


def half_periods(omega2, t0, t1, rtol=1e-10):
    """D(tau), rho(tau) of eq. (1) for tau on [t0, t1] (callables), from two free
    solutions integrated once (DOP853) until half a period after t1."""
    w2min, t_min = min((omega2(t), t) for t in np.linspace(t0, t1, 50))
    if not w2min > 0:           # no swing (l'' >= g); nan or inf would never end below
        raise AnalysisError(f"time-varying shaper: w(t)^2 = {w2min:.6g} 1/s^2 at t = "
                            f"{t_min:.6g} s, not positive (the length accelerates at g "
                            f"or more, l'' >= g): there is no swing to shape")
    w0 = np.sqrt(omega2(t0))
    span = t1 - t0 + 4 * np.pi / np.sqrt(w2min)

    def rhs(t, y):
        w2 = omega2(t)
        return [y[1], -w2 * y[0], y[3], -w2 * y[2]]
    sol = solve_ivp(rhs, (t0, t0 + span), [1.0, 0.0, 0.0, w0], method="DOP853",
                    rtol=rtol, atol=1e-12, dense_output=True)
    if sol.status != 0:
        raise AnalysisError(f"time-varying shaper: the free swing did not integrate "
                            f"({sol.message})")
    tt = np.linspace(t0, t0 + span, 20001)
    y = sol.sol(tt)
    phi = np.unwrap(np.arctan2(y[2], y[0]))
    W = w0                                       # y1 y2' - y1' y2 at t0 (constant)

    def at(tau):
        p = np.interp(tau, tt, phi)
        t2 = np.interp(p + np.pi, phi, tt)
        # refine t2 by Newton on y(t2) = 0 (phase interpolation is only linear)
        a = sol.sol(tau)
        for _ in range(4):
            b = sol.sol(t2)
            yv = (a[0] * b[2] - a[2] * b[0]) / W
            dy = (a[0] * b[3] - a[2] * b[1]) / W
            t2 -= yv / dy
        b = sol.sol(t2)
        return t2 - tau, (a[0] * b[3] - a[2] * b[1]) / W
    return at


def time_varying_zv(times, accel, omega2, distance, n=4000, step=0.1, gain=None):
    """The command a(t) (``accel`` callable, zero outside [times[0], times[-1]], the
    corners ``times`` where it jumps) shaped by eq. (2) for the free frequency
    ``omega2(t)`` = w(t)^2 of eq. (1). Returns (t, v): the shaped speed, linear between
    the points, every `step` s and at the kinks: a table for the operation engine),
    scaled so it travels ``distance``.

    gain : optional callable k(t): the suspension's horizontal acceleration per unit
        drive acceleration at time t of the shaped move (1 for a trolley, the radius for
        slewing, the tip's horizontal lever for luffing). The swings then cancel iff
        A1 k(tau) rho + A2 k(tau + D) = 0 (eq. 2 with the gains):
        A1 = k2 / (k2 - rho k1), A2 = -rho k1 / (k2 - rho k1).
    """
    t0, t1 = float(times[0]), float(times[-1])
    at = half_periods(omega2, t0, t1)
    tau = np.unique(np.concatenate([np.linspace(t0, t1, n + 1), times]))
    D, rho = np.array([at(x) for x in tau]).T
    if np.any(rho >= 0):
        raise AnalysisError("time-varying shaper: no half swing found (rho >= 0)")
    arrive = tau + D
    if gain is None:
        A1, A2 = 1.0 / (1.0 - rho), -rho / (1.0 - rho)
    else:
        k1 = np.array([gain(x) for x in tau])
        k2 = np.array([gain(x) for x in arrive])
        A1, A2 = k2 / (k2 - rho * k1), -rho * k1 / (k2 - rho * k1)
    if np.any(np.diff(arrive) <= 0):
        raise AnalysisError("time-varying shaper: the delayed increments arrive out of "
                            "order (the length changes too fast for eq. 2)")
    # int A(tau) a(tau) dtau piecewise: a is constant between the corners (mid value)
    mid = 0.5 * (tau[:-1] + tau[1:])
    a = np.array([accel(x) for x in mid])
    h = np.diff(tau)
    C1 = np.concatenate([[0.0], np.cumsum(a * h * 0.5 * (A1[:-1] + A1[1:]))])
    C2 = np.concatenate([[0.0], np.cumsum(a * h * 0.5 * (A2[:-1] + A2[1:]))])
    fine = np.unique(np.concatenate([tau, arrive]))
    vf = np.interp(fine, tau, C1) + np.interp(fine, arrive, C2, left=0.0)
    # the table: every `step` s and at the kinks (the command's corners and their
    # delayed arrivals); v is smooth between them, so linear interpolation errs by
    # h^2/8 |v''| only
    kinks = np.concatenate([times, np.interp(times, tau, arrive)])
    t = np.unique(np.concatenate([np.arange(fine[0], fine[-1], step), kinks, fine[-1:]]))
    v = np.interp(t, fine, vf)
    x = float(np.sum(0.5 * (v[1:] + v[:-1]) * np.diff(t)))     # exact for the table
    if not abs(x) > 0:
        raise ModelError("time-varying shaper: the command travels no distance")
    v = v * distance / x
    v[-1] = 0.0
    return t, v


def omega2_from_samples(times, omegas, g=G):
    """w(t)^2 of eq. (1) for a pendulum mode sampled along the move: the equivalent
    length l = g / w_mode^2 (a spline through the samples), w^2 = (g - l'') / l."""
    lsp = CubicSpline(times, g / np.asarray(omegas) ** 2)
    d2 = lsp.derivative(2)
    lo, hi = float(times[0]), float(times[-1])

    def omega2(t):
        t = min(max(t, lo), hi)
        return (g - float(d2(t))) / float(lsp(t))
    return omega2
