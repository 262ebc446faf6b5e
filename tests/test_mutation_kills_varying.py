"""Kill test for cranefe/analysis/shaping/varying.py's half periods (tools/mutation.py
varying; docs/testing.md, "Mutation testing"): D(tau) and rho(tau) of a pendulum whose
length grows at 2 m/s, l = 10 + 2 t, w(t)^2 = g / l (eq. 1 of the module, l'' = 0).

Reference, independent of the module's pair of free solutions and phase: the free swing
started at tau with y = 0, y' = 1, integrated on its own (DOP853, rtol 1e-13, atol 1e-15)
to tau + D: there y must vanish and y' equal rho. Tolerance: |y(tau + D)| < 1e-9 s (the
swing's size is about 1/w = 1 s: D to about 1e-9 s, far finer than the module's phase
grid of span / 20000 = 2e-3 s, so the Newton refinement of the crossing is what is
checked), rho to 1e-8 (the module integrates at rtol 1e-10).
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from cranefe.analysis.shaping.varying import half_periods

G = 9.81


def omega2(t):
    return G / (10.0 + 2.0 * t)


@pytest.mark.parametrize("tau", [0.0, 1.3, 4.0])
def test_half_period_ends_at_the_next_zero_of_the_free_swing(tau):
    at = half_periods(omega2, 0.0, 5.0)
    D, rho = at(tau)
    sol = solve_ivp(lambda t, y: [y[1], -omega2(t) * y[0]], (tau, tau + D), [0.0, 1.0],
                    method="DOP853", rtol=1e-13, atol=1e-15)
    y, dy = sol.y[:, -1]
    assert abs(y) < 1e-9
    assert rho == pytest.approx(dy, rel=1e-8)
    # a longer pendulum swings slower: D above the half period at tau's own length
    assert D > np.pi / np.sqrt(omega2(tau))
    assert -1.0 < rho < 0.0            # the swing's amplitude grows as the rope pays out
