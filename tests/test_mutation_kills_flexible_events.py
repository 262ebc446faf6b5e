"""Kill tests for cranefe/analysis/operation/flexible.py (tools/mutation.py flexible;
docs/testing.md, "Mutation testing"): two ropes going slack within one step below an
elastic tip.

The event search (integrate.py's `_locate`) locates each rope's crossing in turn and
keeps the earliest; when that is not the last one it evaluated, the power terms of the
accepted state are asked for at a time the structure's motions cache does not hold
(`ElasticStructure.power` must then compute them from the mechanism).
"""

import math

import numpy as np
from scipy.integrate import solve_ivp
from test_operation_flexible import write

from cranefe.analysis.operation.integrate import simulate
from cranefe.analysis.operation.mechanism import Mechanism
from cranefe.analysis.operation.scene import parse
from cranefe.model import load

G = 9.81
EA, M, L = 1.0e6, 100.0, 5.0
# a 2 m cantilever arm A-T on the ground, two 100-kg loads on two 5 m ropes from its
# tip T (both vertical)
TWO = """cranefe: 1
name: two loads on two ropes below an elastic tip
plane: xz
gravity: [0, 0, -9.81]
nodes:
  A:  [0.0, 0.0, 10.0]
  T:  [2.0, 0.0, 10.0]
  H1: [2.0, 0.0, 5.0]
  H2: [2.0, 0.0, 5.0]
ground: [A]
masses: {H1: 100, H2: 100}
ropes:
  r1: {EA: 1.0e6, path: [T, H1]}
  r2: {EA: 1.0e6, path: [T, H2]}
members:
  arm: {type: beam, nodes: [A, T], E: 2.1e+11, A: 0.01, Iy: 1.0e-2, rho: 7850,
        elements: 1, mass: lumped}
"""
M_TIP = 7850 * 0.01 * 2.0 / 2                      # half the arm's rho A l
K_TIP = 3 * 2.1e11 * 1.0e-2 / 2.0**3               # 3 EI / l^3 (tip slope condensed)
L0 = L * math.exp(-M * G / EA)                     # EA ln(L / L0) = m g at rest
V1, V2 = 2.001, 2.0                                # the loads thrown up (m/s)


def _reference():
    """Slack times of r1 and r2 by DOP853 on the vertical motions from the static state:
    tip up w, loads up u_i, L_i = 5 + w - u_i, S_i = EA ln(L_i / L0) while L_i > L0:
    m_t w'' = -k w - (S_1 + S_2 - 2 m g), m u_i'' = S_i - m g (the arm along x: the
    tip's vertical is its bending, stiffness 3 EI / l^3 with the slope condensed; the
    ropes stay vertical)."""
    def f(t, y):
        w, u1, u2, dw, du1, du2 = y
        S = [EA * math.log((L + w - u) / L0) for u in (u1, u2)]
        return [dw, du1, du2, (-K_TIP * w - (S[0] + S[1] - 2 * M * G)) / M_TIP,
                (S[0] - M * G) / M, (S[1] - M * G) / M]
    events = [lambda t, y, i=i: L + y[0] - y[i] - L0 for i in (1, 2)]
    sol = solve_ivp(f, (0.0, 0.004), [0, 0, 0, 0, V1, V2], events=events,
                    method="DOP853", rtol=1e-12, atol=1e-15)
    return sol.t_events[0][0], sol.t_events[1][0]


def test_two_ropes_going_slack_in_one_step_below_an_elastic_tip(tmp_path):
    """Both loads thrown up from their static state at 2.001 and 2.0 m/s: the ropes go
    slack 2.456 ms later, 1.2 microseconds apart (within one step; r1, the first in
    the search, is the earlier one). The two event times against the reference to 1e-4
    (measured 3.8e-5 at tolerance 1e-6, 1.0e-5 at 1e-7, 2.4e-6 at 1e-8: converging as
    tolerance^(2/3)), their spacing to 1e-3 (measured 3e-4: the errors of both times
    nearly equal)."""
    model = load(write(tmp_path, TWO, "  duration: 0.02\n  tolerance: 1.0e-6\n",
                       name="two.yaml"))
    mech = Mechanism(model, parse(model))
    assert mech.flex.labels() == ["T.ux", "T.uz"]
    v = np.zeros(mech.n)
    v[1], v[3] = V1, V2                            # H1.z, H2.z
    res = simulate(model, initial={"q": mech.q0.copy(), "v": v}, fast=False)
    slack = [(t, e) for t, e in res.events if e.startswith("rope")]
    assert [e for _, e in slack] == ["rope r1 slack", "rope r2 slack"], slack
    t1, t2 = _reference()
    assert abs(slack[0][0] / t1 - 1) < 1e-4 and abs(slack[1][0] / t2 - 1) < 1e-4, slack
    assert abs((slack[1][0] - slack[0][0]) / (t2 - t1) - 1) < 1e-3
