"""Sway of the load on its rope under the moving jib tip, for a luffing law.

The load hangs a rope length H below the jib tip D(t) = (x, z); psi is the rope's angle
from the vertical. Three models (docs/luffing.md):

- ``paper``: Loveikin et al. (2013) eq. 9, H psi'' = -(x_a alpha'' + x_aa alpha'^2)
  = -x''. It has no gravity term (the paper's criterion is kinetic energy only), so the
  load keeps its horizontal speed and psi = -(x - x0)/H grows without bound;
- ``linear``: the pendulum with gravity, H psi'' + g psi = -x'';
- ``nonlinear``: H psi'' = -x'' cos(psi) - (g + z'') sin(psi).

A law that starts (stops) with a jump in speed moves the tip impulsively while the load
stays put: psi' jumps by -(jump of the tip's velocity along the rope's normal)/H, i.e.
-(jump of x')/H in the linear model (model-format.md). Maximum sway is over 0 <= t <= t_k,
residual sway the amplitude of the free swing after t_k: sqrt(psi^2 + (psi'/w)^2),
w = sqrt(g/H), in the linear model and from the pendulum's energy in the nonlinear one.

For the linear model the residual swing has the closed form |int_0^t_k x'(t) e^(-i w t)
dt| / H (integrate by parts, the jumps included): `residual_linear_exact`.
"""

import numpy as np

KINDS = ("linear", "nonlinear", "paper")


class TipMotion:
    """The jib tip's velocity and acceleration (m/s, m/s^2) along a law, as Chebyshev
    interpolants per smooth piece of the law (exact to ~1e-13)."""

    def __init__(self, law, proxy, t_k, points=129):
        from numpy.polynomial import chebyshev as C
        self.t_k = t_k
        edges = [0.0, *law.info.get("breaks", []), 1.0]
        self.pieces = []
        x = np.cos(np.pi * (np.arange(points) + 0.5) / points)
        for a, b in zip(edges[:-1], edges[1:]):
            tau = 0.5 * (a + b) + 0.5 * (b - a) * x
            al, d1, d2 = law.evaluate(tau)
            vals = np.vstack([proxy("dx", al) * d1 / t_k,
                              proxy("dz", al) * d1 / t_k,
                              (proxy("dx", al) * d2 + proxy("ddx", al) * d1**2) / t_k**2,
                              (proxy("dz", al) * d2 + proxy("ddz", al) * d1**2) / t_k**2])
            coef = C.chebfit(x, vals.T, points - 1)              # (points, 4)
            self.pieces.append((a * t_k, b * t_k, coef))
        self.k = np.arange(points)
        self.edges = [p[0] for p in self.pieces] + [t_k]
        self.v_start = self(0.0)[:2]
        self.v_end = self(t_k)[:2]

    def __call__(self, t):
        """(vx, vz, ax, az) at time t (s) (a scalar)."""
        for a, b, coef in self.pieces:
            if t <= b or b == self.pieces[-1][1]:
                u = min(max((2 * t - a - b) / (b - a), -1.0), 1.0)
                # T_k(u) = cos(k arccos u): one vector operation instead of Clenshaw's loop
                return np.cos(self.k * np.arccos(u)) @ coef
        raise ValueError(t)

    def sample(self, t):
        return np.array([self(tt) for tt in np.atleast_1d(t)])


def _rhs(kind, H, g, tip):
    def rhs(t, y):
        _, _, ax, az = tip(t)
        if kind == "linear":
            return [y[1], -(g * y[0] + ax) / H]
        if kind == "nonlinear":
            return [y[1], -(ax * np.cos(y[0]) + (g + az) * np.sin(y[0])) / H]
        return [y[1], -ax / H]
    return rhs


def simulate(tip, H, g, kind, samples=801, rtol=1e-11, atol=1e-13):
    """psi(t) over [0, t_k] and the residual swing: dict with t, psi, dpsi (samples,),
    max (rad), residual (rad), end (psi, psi' after the stop)."""
    from scipy.integrate import solve_ivp
    t_k = tip.t_k
    w = np.sqrt(g / H)
    vx0, _ = tip.v_start
    y = np.array([0.0, -vx0 / H])               # the start's jump (psi = 0: cos = 1)
    ts = np.linspace(0, t_k, samples)
    psi, dpsi = np.empty(samples), np.empty(samples)
    rhs = _rhs(kind, H, g, tip)
    for a, b in zip(tip.edges[:-1], tip.edges[1:]):
        sel = (ts >= a) & (ts < b)
        sol = solve_ivp(rhs, (a, b), y, method="DOP853", rtol=rtol, atol=atol,
                        t_eval=np.append(ts[sel], b))
        psi[sel], dpsi[sel] = sol.y[0, :-1], sol.y[1, :-1]
        y = sol.y[:, -1]
    psi[-1], dpsi[-1] = y
    vx, vz = tip.v_end
    p, dp = y
    if kind == "linear":
        dp = dp + vx / H
        residual = float(np.hypot(p, dp / w))
    elif kind == "nonlinear":
        dp = dp + (vx * np.cos(p) + vz * np.sin(p)) / H
        E = 0.5 * (dp / w) ** 2 + (1 - np.cos(p))            # energy / (m g H)
        residual = float(np.arccos(1 - E)) if E < 2 else float(np.pi)
    else:
        dp = dp + vx / H
        residual = float("nan")                             # no restoring force
    return {"t": ts, "psi": psi, "dpsi": dpsi, "max": float(np.abs(psi).max()),
            "residual": residual, "end": (float(p), float(dp))}


def residual_linear_exact(law, proxy, t_k, H, g, nodes=200):
    """|int_0^t_k x'(t) e^(-i w t) dt| / H: the residual swing of the linear model."""
    w = np.sqrt(g / H)
    edges = [0.0, *law.info.get("breaks", []), 1.0]
    xg, wg = np.polynomial.legendre.leggauss(nodes)
    total = 0.0 + 0.0j
    for a, b in zip(edges[:-1], edges[1:]):
        tau = 0.5 * (a + b) + 0.5 * (b - a) * xg
        al, d1, _ = law.evaluate(tau)
        v = proxy("dx", al) * d1                            # dx/dtau
        total += 0.5 * (b - a) * np.sum(wg * v * np.exp(-1j * w * t_k * tau))
    return float(abs(total) / H)


def swing_free_law(proxy, alpha0, alphak, t_k, H, g, guess, tol=1e-9, which="complete"):
    """The energy-optimal law with zero residual sway of the linear model (beyond the
    paper; docs/luffing.md).

    Minimise int_0^1 1/2 J alpha.^2 dtau subject to alpha(0) = alpha0, alpha(1) = alphak
    and int_0^1 x_alpha alpha. e^(-i W tau) dtau = 0 (W = w t_k: no free swing after the
    stop, the speed jumps included). With mu(tau) = l1 cos(W tau) + l2 sin(W tau) the
    Euler-Lagrange equation is

        J alpha.. + 1/2 J' alpha.^2 = mu.(tau) x_alpha(alpha),

    solved with solve_bvp for (alpha, alpha., I_c, I_s) and the parameters (l1, l2),
    I_c, I_s the running cosine and sine integrals (zero at both ends)."""
    from scipy.integrate import solve_bvp
    from .optimum import LawSolution
    import time
    t0 = time.perf_counter()
    j = "J" if which == "complete" else "Jp"
    W = np.sqrt(g / H) * t_k
    tau = np.linspace(0, 1, 81)
    al, d1, _ = guess.evaluate(tau)
    Jbar = float(np.mean(proxy(j, al)))

    def fun(x, y, p):
        a, w = y[0], y[1]
        Jn, dJn, xp = proxy(j, a) / Jbar, proxy("d" + j, a) / Jbar, proxy("dx", a)
        c, s = np.cos(W * x), np.sin(W * x)
        dmu = W * (-p[0] * s + p[1] * c)
        return np.vstack([w, (dmu * xp - 0.5 * dJn * w**2) / Jn, xp * w * c, xp * w * s])

    def bc(ya, yb, p):
        return np.array([ya[0] - alpha0, yb[0] - alphak, ya[2], ya[3], yb[2], yb[3]])

    from scipy.integrate import cumulative_trapezoid
    v = proxy("dx", al) * d1
    y0 = np.vstack([al, d1, cumulative_trapezoid(v * np.cos(W * tau), tau, initial=0),
                    cumulative_trapezoid(v * np.sin(W * tau), tau, initial=0)])
    sol = solve_bvp(fun, bc, tau, y0, p=np.zeros(2), tol=tol, max_nodes=200000)

    def evaluate(t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        y = sol.sol(t)
        return y[0], y[1], fun(t, y, sol.p)[1]

    return LawSolution("swing-free", evaluate, sol.status, sol.message, sol.niter, 0,
                       time.perf_counter() - t0,
                       {"multipliers": [float(v) for v in sol.p * Jbar],
                        "nodes": int(sol.x.size), "W": float(W)})
