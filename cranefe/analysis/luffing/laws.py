"""Luffing laws alpha(tau), tau = t / t_k: the standard laws of model-format.md and the
practical rest-to-rest energy law.

Standard laws: alpha = alpha0 + (alphak - alpha0) s(tau) with linear s = tau, cubic
3 tau^2 - 2 tau^3, quintic 10 tau^3 - 15 tau^4 + 6 tau^5, cycloidal
tau - sin(2 pi tau)/(2 pi), trapezoidal speed with 20 % of t_k accelerating and 20 %
decelerating.

Practical law (docs/luffing.md): with the energy coordinate sigma(alpha) = int sqrt(J),
T = 1/2 (d sigma/dt)^2 and the inertial drive force on alpha is
Q = J alpha'' + J' alpha'^2 / 2 = sqrt(J) sigma''. Minimising

    int_0^t_k [ 1/2 sigma'^2 + 1/2 tau_c^2 sigma''^2 ] dt    (= energy + tau_c^2 Q^2 / J)

from rest to rest (sigma' = 0 at both ends) is a strictly convex problem whose
Euler-Lagrange equation sigma'' = tau_c^2 sigma'''' has the closed-form solution
sigma = S/2 + B (u - 1/2) + C sinh((u - 1/2)/eps), u = t/t_k, eps = tau_c/t_k. As
tau_c -> 0 it tends to the coasting optimum of eq. 16 with boundary layers of width
~tau_c in which the drive accelerates and brakes.
"""

import numpy as np

from .optimum import LawSolution

STANDARD = ("linear", "cubic", "quintic", "cycloidal", "trapezoidal")
BREAKS = {"trapezoidal": (0.2, 0.8)}


def standard_s(name, tau):
    """s(tau), s.(tau), s..(tau) of a standard law (model-format.md, luffing)."""
    tau = np.asarray(tau, dtype=float)
    one = np.ones_like(tau)
    if name == "linear":
        return tau, one, 0 * tau
    if name == "cubic":
        return 3 * tau**2 - 2 * tau**3, 6 * tau - 6 * tau**2, 6 - 12 * tau
    if name == "quintic":
        return (10 * tau**3 - 15 * tau**4 + 6 * tau**5,
                30 * tau**2 - 60 * tau**3 + 30 * tau**4,
                60 * tau - 180 * tau**2 + 120 * tau**3)
    if name == "cycloidal":
        w = 2 * np.pi
        return tau - np.sin(w * tau) / w, 1 - np.cos(w * tau), w * np.sin(w * tau)
    if name == "trapezoidal":
        ta = 0.2
        v = 1 / (1 - ta)                    # top speed: v (1 - ta) = 1
        acc = v / ta
        s = np.where(tau < ta, 0.5 * acc * tau**2,
                     np.where(tau <= 1 - ta, 0.5 * acc * ta**2 + v * (tau - ta),
                              1 - 0.5 * acc * (1 - tau) ** 2))
        ds = np.where(tau < ta, acc * tau, np.where(tau <= 1 - ta, v, acc * (1 - tau)))
        dds = np.where(tau < ta, acc, np.where(tau <= 1 - ta, 0.0, -acc))
        return s, ds, dds
    raise ValueError(f"unknown law {name!r}")


def standard_law(name, alpha0, alphak):
    D = alphak - alpha0

    def evaluate(tau):
        s, ds, dds = standard_s(name, np.atleast_1d(tau))
        return alpha0 + D * s, D * ds, D * dds

    return LawSolution(name, evaluate, info={"breaks": list(BREAKS.get(name, ()))})


def rest_to_rest_sigma(u, eps):
    """sigma(u)/S, its derivatives in u: the practical law in the energy coordinate."""
    u = np.asarray(u, dtype=float)
    Y = 0.5 / eps
    y = (u - 0.5) / eps
    # sinh(y)/cosh(Y) and cosh(y)/cosh(Y) without overflow (|y| <= Y)
    e = np.exp(-2 * Y)
    sh = (np.exp(y - Y) - np.exp(-y - Y)) / (1 + e)
    ch = (np.exp(y - Y) + np.exp(-y - Y)) / (1 + e)
    th = (1 - e) / (1 + e)                      # tanh(Y)
    Cc = 0.5 / (th - Y)                         # C cosh(Y) with sigma(1) = 1
    B = -Cc / eps                               # sigma.(1) = 0
    return (0.5 + B * (u - 0.5) + Cc * sh, B + Cc / eps * ch, Cc / eps**2 * sh)


def rest_to_rest_law(proxy, alpha0, alphak, tau_c, t_k, which="complete"):
    """The practical rest-to-rest law (module docstring) for time constant tau_c (s)."""
    key = "sqrtJ" if which == "complete" else "sqrtJp"
    j = "J" if which == "complete" else "Jp"
    S = float(proxy.antiderivative(key, alphak, alpha0))
    eps = tau_c / t_k
    lo, hi = min(alpha0, alphak), max(alpha0, alphak)
    D = alphak - alpha0

    def evaluate(tau):
        tau = np.atleast_1d(np.asarray(tau, dtype=float))
        sg, dsg, ddsg = rest_to_rest_sigma(tau, eps)
        a = alpha0 + D * sg
        for _ in range(60):                     # invert sigma(alpha) = S sg by Newton
            step = (proxy.antiderivative(key, a, alpha0) - S * sg) / proxy(key, a)
            a = np.clip(a - step, lo, hi)
            if np.abs(step).max() < 1e-15:
                break
        r = proxy(key, a)
        da = S * dsg / r
        dda = (S * ddsg - 0.5 * proxy("d" + j, a) / r * da**2) / r
        return a, da, dda

    return LawSolution("rest-to-rest", evaluate, info={"tau_c_s": tau_c, "eps": eps})
