"""A reference integration of an operation scene by scipy's Radau (for studies).

The same equations as the engine (`Mechanism.evaluate`) in first-order form
y = [q, q'], y' = [q', M^-1 F(t, q, q')], with the analytic Jacobian
[[0, I], [-M^-1 K, -M^-1 C]], restarted at every breakpoint of the drives; ropes keep
their initial taut/slack state (no events: use it where no rope goes slack). Returns the
peak force of each active rope from the dense output, and the cost. docs/operations.md,
"Integrator and why".
"""

import time

import numpy as np
from scipy.integrate import solve_ivp

from .mechanism import Mechanism
from .scene import parse


def radau(model, rtol=1e-8, atol=1e-9, sample=0.002):
    """(peak (nr,), static (nr,), steps, force evaluations, CPU seconds)."""
    spec = parse(model)
    mech = Mechanism(model, spec)
    n, taut = mech.n, mech.taut0
    count = [0]

    def f(t, y):
        count[0] += 1
        ev = mech.evaluate(t, y[:n], y[n:], taut)
        # the mass matrix of the state: joint coordinates carry a dense block M_J(u, t)
        return np.concatenate([y[n:], np.linalg.solve(mech.mass_matrix(ev), ev.F)])

    def jac(t, y):
        # for Newton's iteration only: d(M^-1)/dq F is left out (it changes the
        # iteration's convergence, not the solution)
        ev = mech.evaluate(t, y[:n], y[n:], taut)
        J = np.zeros((2 * n, 2 * n))
        J[:n, n:] = np.eye(n)
        Minv = np.linalg.inv(mech.mass_matrix(ev))
        J[n:, :n] = -Minv @ ev.K
        J[n:, n:] = -Minv @ ev.C
        return J

    t0 = time.process_time()
    y = np.concatenate([mech.q0, np.zeros(n)])
    peak = np.zeros(len(mech.ropes))
    steps = 0
    bps = [0.0] + [float(b) for b in spec.breakpoints] + [spec.duration]
    for a, b in zip(bps[:-1], bps[1:]):
        sol = solve_ivp(f, (a, b), y, method="Radau", jac=jac, rtol=rtol, atol=atol,
                        dense_output=True)
        steps += len(sol.t) - 1
        for tt in np.linspace(a, b, max(3, int((b - a) / sample))):
            yy = sol.sol(tt)
            ev = mech.evaluate(tt, yy[:n], yy[n:], taut)
            peak = np.maximum(peak, ev.S + ev.Sd)
        y = sol.y[:, -1]
    return peak, mech.S0, steps, count[0], time.process_time() - t0
