"""Kill tests for luffing configurations no other fast test builds (issue 20, mutation
testing; docs/testing.md "Not run yet, or not whole"):

- kinematics.py (tools/mutation.py luffing_kinematics): a linkage with a REDUNDANT joint,
  whose closure Jacobian has more rows than coordinates, so `Linkage` solves its linear
  systems by the pseudo-inverse. The linkage: a boom O-B and two links F1-E1, F2-E2 of the
  boom's length, parallel to it, all hinged to the ground, and a jib hinged to all three
  (B, E1, E2). One link is enough to make a parallelogram; the second adds two closure
  equations of which one is dependent (13 equations for 12 coordinates, rank 11 with the
  driver free: one degree of freedom). By hand, with theta = alpha - alpha_ref: the boom
  and both links turn by theta about their ground hinges, X = P + Rot(theta) (X0 - P),
  dX/dalpha = Rot(theta + pi/2) (X0 - P), d2X/dalpha2 = -Rot(theta) (X0 - P), and the jib
  translates with B, X = X0 + B(alpha) - B0, without turning.
"""

import math

import numpy as np
import pytest

from cranefe.analysis.luffing.kinematics import Linkage
from cranefe.model import load

# --------------------------------------------------------------- the redundant linkage
L, A_REF = 10.0, math.radians(30.0)
F1, F2 = np.array([0.0, -2.0]), np.array([1.0, -3.0])
B0 = L * np.array([math.cos(A_REF), math.sin(A_REF)])
TIP = np.array([4.0, 0.0])               # D = B + TIP on the jib


def _p(v):
    return f"[{float(v[0])!r}, 0, {float(v[1])!r}]"


# centres of mass: boom 5 u, links F + 5 u, jib B + (2, -1)
COMS = {"boom": np.zeros(2) + 5 * B0 / L, "link1": F1 + 5 * B0 / L,
        "link2": F2 + 5 * B0 / L, "jib": B0 + np.array([2.0, -1.0])}
PIVOTS = {"boom": np.zeros(2), "link1": F1, "link2": F2}

REDUNDANT = f"""cranefe: 1
name: parallelogram with a redundant link
plane: xz
nodes:
  O: [0.0, 0, 0.0]
  F1: {_p(F1)}
  F2: {_p(F2)}
  B: {_p(B0)}
  E1: {_p(B0 + F1)}
  E2: {_p(B0 + F2)}
  D: {_p(B0 + TIP)}
ground: [O, F1, F2]
bodies:
  boom: {{mass: 1000, com: {_p(COMS['boom'])}, inertia: 8000, nodes: [O, B]}}
  link1: {{mass: 200, com: {_p(COMS['link1'])}, inertia: 1500, nodes: [F1, E1]}}
  link2: {{mass: 150, com: {_p(COMS['link2'])}, inertia: 1200, nodes: [F2, E2]}}
  jib: {{mass: 500, com: {_p(COMS['jib'])}, inertia: 700, nodes: [B, E1, E2, D]}}
joints:
  - {{type: hinge, bodies: [ground, boom], at: O}}
  - {{type: hinge, bodies: [ground, link1], at: F1}}
  - {{type: hinge, bodies: [ground, link2], at: F2}}
  - {{type: hinge, bodies: [boom, jib], at: B}}
  - {{type: hinge, bodies: [link1, jib], at: E1}}
  - {{type: hinge, bodies: [link2, jib], at: E2}}
"""


def _rot(t, v):
    c, s = math.cos(t), math.sin(t)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def _hand_redundant(alpha):
    """{body: [(x, z, theta), d/dalpha, d2/dalpha2]} and the tip D's (X, X', X'')."""
    th = alpha - A_REF
    out = {}
    for name, P in PIVOTS.items():
        v = COMS[name] - P
        out[name] = [np.array([*(P + _rot(th, v)), th]),
                     np.array([*_rot(th + math.pi / 2, v), 1.0]),
                     np.array([*(-_rot(th, v)), 0.0])]
    dB = [_rot(th, B0) - B0, _rot(th + math.pi / 2, B0), -_rot(th, B0)]
    out["jib"] = [np.array([*(COMS["jib"] + dB[0]), 0.0]), np.array([*dB[1], 0.0]),
                  np.array([*dB[2], 0.0])]
    out["D"] = [B0 + TIP + dB[0], dB[1], dB[2]]
    return out


def test_a_redundant_joint_is_solved_by_the_pseudo_inverse():
    """Tolerances: poses 1e-10 (Newton stops at 1e-13 of the size, 10 m), derivatives
    1e-9 and 1e-8 (one and two more least-squares solves, condition ~10)."""
    m = load("redundant.yaml", REDUNDANT)
    lk = Linkage(m, "boom", "O", "B")
    names = [b.name for b in m.bodies]
    assert lk.n == 12 and lk.square is False
    F, J = lk.equations(lk.q_ref[None], np.array([A_REF]))
    assert J.shape == (1, 13, 12) and np.abs(F).max() < 1e-12
    degs = (12.0, 47.0, 71.0)           # below and above the model's 30 deg
    st = lk.state(np.radians(degs))
    assert np.all(st.residual <= 1e-10 * lk.scale)
    tol = (1e-10, 1e-9, 1e-8)
    for n, deg in enumerate(degs):
        hand = _hand_redundant(math.radians(deg))
        for b in lk.bodies:
            i = lk.local[b]
            for d, arr in enumerate((st.q, st.dq, st.ddq)):
                assert np.allclose(arr[n, 3 * i:3 * i + 3], hand[names[b]][d], rtol=0,
                                   atol=tol[d] * 10), (deg, names[b], d)
        X = st.point(m.node_index["D"])
        for d in range(3):
            assert np.allclose(X[d][n], hand["D"][d], rtol=0, atol=tol[d] * 10), (deg, d)
    # the continuation passed through the table both ways, at its step
    assert lk._A[0] <= math.radians(12.0) and lk._A[-1] >= math.radians(71.0)
    assert np.allclose(np.diff(lk._A), Linkage.STEP, rtol=1e-12)
    # Newton from a poor start closes the loops by least squares too
    q, res = lk.newton(lk.q_ref[None] + 0.01, np.array([math.radians(47.0)]))
    assert res[0] < 1e-10
    assert np.allclose(q[0], st.q[1], rtol=0, atol=1e-9)
    # the least-squares solve of a consistent system is its exact solution (the full
    # Jacobian, the driver's row included, has rank 12: one solution)
    y = np.linspace(-1.0, 1.0, 12)
    x = lk._lin_solve(J, np.einsum("nij,j->ni", J, y))
    assert np.allclose(x[0], y, rtol=0, atol=1e-12)
