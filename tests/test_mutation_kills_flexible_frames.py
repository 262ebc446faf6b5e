"""Kill tests for cranefe/analysis/operation/flexible.py (tools/mutation.py flexible;
docs/testing.md, "Mutation testing"): frames that translate, and several frames.

tests/test_mutation_kills_flexible.py turns its rotor about the origin (p = 0) and has
one frame. Here two one-element blades ride on two bodies: blade K-T1 on a trolley that
travels along x (a slider: R = I, p = s e_x) and blade N-T2 on a hub turned about z
through O = (2, 1, 0), off the origin (a hinge: p = O - R O, p' = -R' O, p'' = -R'' O);
N = O + (0, 2, 0), so the blade's axial force has a moment about the hinge (the frame
does work on it).
Every value is written out by hand from the frame's motion (none computed by the
module):

* the speed tables: trolley v = 0 up to t = 1 s, then 0.5 (t - 1) (s = 0.25 (t - 1)^2,
  s'' = 0.5); hub w = 0.6 t (phi = 0.3 t^2, w' = 0.6); R = Rz(phi), R' = w R S,
  R'' = R (w' S + w^2 S^2), S = skew(e_z);
* each tip displaced only along its blade (u = (d, 0, 0) in the frame's axes): no
  bending, so the condensed slopes are zero and the Green elongation is d exactly:
  U = EA/(2 L) d^2, dU/du = (EA/L) d e_x;
* per tip (lumped mass m = rho A L / 2, Y = X + u): x = R Y + p, x' = R' Y + R u' + p',
  F = -dU/du + m R^T g - m (R^T R'' Y + 2 R^T R' u' + R^T p'') (module docstring),
  T = m |x'|^2 / 2, V = -m x . g, the frame's power m w . (x'' - g) with the carried
  velocity w = R' Y + p' and x'' = R'' Y + 2 R' u' + R u'' + p'', u'' = F / m.
"""

import math

import numpy as np
from test_operation_flexible import write

from cranefe.analysis.operation.mechanism import Mechanism
from cranefe.analysis.operation.scene import parse
from cranefe.model import load

TWO = """cranefe: 1
name: two blades on a trolley and on a hub hinged off the origin
gravity: [-3.0, 1.5, -9.81]
nodes:
  K:  [0.0, -3.0, 1.0]
  T1: [6.0, -3.0, 1.0]
  O:  [2.0, 1.0, 0.0]
  N:  [2.0, 3.0, 0.0]
  T2: [12.0, 3.0, 0.0]
ground: []
bodies:
  trolley: {mass: 10, com: [0, -3, 1], inertia: [1, 1, 1], nodes: [K]}
  hub: {mass: 10, com: [2, 1, 0], inertia: [1, 1, 1], nodes: [O, N]}
joints:
  - {name: travel, type: slider, bodies: [ground, trolley], at: K, axis: [1, 0, 0],
     range: [-1, 5]}
  - {name: spin, type: hinge, bodies: [ground, hub], at: O, axis: [0, 0, 1]}
members:
  b1: {type: beam, nodes: [K, T1], E: 2.1e+11, G: 8.0e+10, A: 0.1, Iy: 1.0e-6,
       Iz: 1.0e-6, J: 2.0e-6, rho: 78.5, orientation: [0, 0, 1], elements: 1,
       mass: lumped}
  b2: {type: beam, nodes: [N, T2], E: 2.1e+11, G: 8.0e+10, A: 0.1, Iy: 1.0e-6,
       Iz: 1.0e-6, J: 2.0e-6, rho: 78.5, orientation: [0, 0, 1], elements: 1,
       mass: lumped}
"""
DRIVES = ("  duration: 3\n  drives:\n"
          "    tr: {slider: travel, profile: {type: table, speed: [[0, 0], [1, 0], [3, 1.0]]}}\n"
          "    sp: {hinge: spin, profile: {type: table, speed: [[0, 0], [2, 1.2]]}}\n")

GRAV = np.array([-3.0, 1.5, -9.81])
EA = 2.1e11 * 0.1
S = np.array([[0, -1.0, 0], [1.0, 0, 0], [0, 0, 0]])
X1, X2, O = np.array([6.0, -3.0, 1.0]), np.array([12.0, 3.0, 0.0]), np.array([2.0, 1, 0])
L1, L2 = 6.0, 10.0
M1, M2 = 78.5 * 0.1 * L1 / 2, 78.5 * 0.1 * L2 / 2
D1, D2 = 1e-7, -2e-7                   # axial tip displacements (forces 350 N, 420 N)
V1, V2 = np.array([0.7, -0.4, 0.2]), np.array([-0.3, 0.5, 0.9])


def _mechanism(tmp_path):
    """A fresh mechanism in every test (mutmut's forks must build it with the mutant)."""
    model = load(write(tmp_path, TWO, DRIVES))
    mech = Mechanism(model, parse(model))
    f = mech.flex
    assert f.labels() == ["T1.ux", "T1.uy", "T1.uz", "T2.ux", "T2.uy", "T2.uz"]
    assert [b for b, _ in f.frames] == [0, 1]          # the trolley's frame first
    f._last = f._theta = None                          # slopes from the linear start
    return mech


def _motions(t):
    """(R, R', R'', p, p', p'') of the trolley and of the hub at t, by hand."""
    s = 0.25 * (t - 1) ** 2 if t > 1 else 0.0
    ds = 0.5 * (t - 1) if t > 1 else 0.0
    dds = 0.5 if t > 1 else 0.0
    ex, Z = np.array([1.0, 0, 0]), np.zeros((3, 3))
    trolley = (np.eye(3), Z, Z, s * ex, ds * ex, dds * ex)
    phi, w, dw = 0.3 * t * t, 0.6 * t, 0.6
    c, sn = math.cos(phi), math.sin(phi)
    R = np.array([[c, -sn, 0], [sn, c, 0], [0, 0, 1.0]])
    dR, ddR = w * R @ S, R @ (dw * S + w * w * S @ S)
    hub = (R, dR, ddR, O - R @ O, -dR @ O, -ddR @ O)
    return trolley, hub


def _hand(t):
    """Per tip: x, x', F (frame axes), T, V, U, the frame's power."""
    out = []
    for (R, dR, ddR, p, dp, ddp), X, m, L, d, ud in zip(_motions(t), (X1, X2), (M1, M2),
                                                       (L1, L2), (D1, D2), (V1, V2)):
        Y = X + np.array([d, 0.0, 0.0])
        x, xd = R @ Y + p, dR @ Y + R @ ud + dp
        F = (-EA / L * d * np.array([1.0, 0, 0]) + m * R.T @ GRAV
             - m * (R.T @ ddR @ Y + 2 * R.T @ dR @ ud + R.T @ ddp))
        acc = ddR @ Y + 2 * dR @ ud + R @ (F / m) + ddp
        w = dR @ Y + dp
        out.append(dict(x=x, xd=xd, F=F, T=0.5 * m * xd @ xd, V=-m * x @ GRAV,
                        U=0.5 * EA / L * d * d, P=m * w @ (acc - GRAV)))
    return out


Q = np.array([D1, 0, 0, D2, 0, 0])
VQ = np.r_[V1, V2]


def test_place_and_forces_of_translating_frames(tmp_path):
    """At t = 1.5 s (trolley at s = 1/16 m, 0.25 m/s, 0.5 m/s^2; hub at phi = 0.675,
    w = 0.9, w' = 0.6; between the tables' points): the tips' positions and velocities (to 1e-13 m: round-off of
    12 m), and the forces on u, whose largest term is the axial 420 N (to 1e-9 of it:
    EA/L d is 2.1e9 N/m times 2e-7 m, the d's round-off 1e-16 relative of 12 m in Y
    does not enter; the slopes' Newton stops at round-off)."""
    mech = _mechanism(tmp_path)
    h = _hand(1.5)
    X, Vn = mech.place(1.5, Q, VQ)[:2]
    names = mech.model.node_names
    for k, tip in enumerate(("T1", "T2")):
        np.testing.assert_allclose(X[names.index(tip)], h[k]["x"], rtol=0, atol=1e-13)
        np.testing.assert_allclose(Vn[names.index(tip)], h[k]["xd"], rtol=0, atol=1e-13)
    ev = mech.evaluate(1.5, Q, VQ, mech.taut0)
    F = np.r_[h[0]["F"], h[1]["F"]]
    np.testing.assert_allclose(ev.F, F, rtol=0, atol=1e-9 * np.abs(F).max())


def test_energy_of_two_translating_frames(tmp_path):
    """T = sum m |x'|^2 / 2 and V = -sum m x . g over both tips (to 1e-12 relative:
    round-off), U = sum EA/(2 L) d^2 (to 1e-9: the slopes' Newton at round-off)."""
    mech = _mechanism(tmp_path)
    h = _hand(1.5)
    T, Vg, U = mech.flex.energy(mech, 1.5, Q, VQ)
    np.testing.assert_allclose(T, h[0]["T"] + h[1]["T"], rtol=1e-12)
    np.testing.assert_allclose(Vg, h[0]["V"] + h[1]["V"], rtol=1e-12)
    np.testing.assert_allclose(U, h[0]["U"] + h[1]["U"], rtol=1e-9)
    # each frame's share is far above the tolerance: dropping either would show
    assert min(h[0]["T"], h[1]["T"]) > 1e-3 * T and abs(h[0]["V"]) > 1e-3 * abs(Vg)


def test_power_of_two_translating_frames(tmp_path):
    """The frames' power sum m w . (x'' - g) at t = 1.5 s (both frames moving) and at
    t = 0.5 s (the trolley at rest: its frame adds nothing, the hub's still does), to
    1e-9 relative (the forces' tolerance; no rope)."""
    mech = _mechanism(tmp_path)
    for t in (1.5, 0.5):
        h = _hand(t)
        ev = mech.evaluate(t, Q, VQ, mech.taut0)
        P = mech.flex.power(mech, ev, Q, VQ)
        scale = abs(h[0]["P"]) + abs(h[1]["P"])
        np.testing.assert_allclose(P, h[0]["P"] + h[1]["P"], rtol=0, atol=1e-9 * scale)
        if t == 1.5:
            assert min(abs(h[0]["P"]), abs(h[1]["P"])) > 1e-3 * scale
        else:
            assert h[0]["P"] == 0.0 and abs(h[1]["P"]) > 1.0


def test_static_state_with_a_rope_slack_at_rest(tmp_path):
    """settle() with a tie from the jib's tip T down to a ground point B (1 m out, 6 m
    below): the reference geometry has it at its unstretched length (no load on it:
    S0 = 0), the tip's weight bends the jib down and shortens it, so it is slack in the
    static state and the tip deflects as without it, P L^3 / (3 EI) with
    P = (1500 + rho A L / 2) g (to 1e-10 relative, as the jib test of
    test_mutation_kills_flexible.py); the tie's force 0 and slack, the load rope's
    1500 g. (A tie held taut would push the tip up: 2.5e6 N/m against the jib's
    7.3e6 N/m.)"""
    from test_mutation_kills_flexible import DIRECT
    text = (DIRECT.replace("  HOOK: [12.0, 0.0, 12.0]\n",
                           "  HOOK: [12.0, 0.0, 12.0]\n  B:    [13.0, 0.0, 14.0]\n")
            .replace("ground: [A, D]", "ground: [A, D, B]")
            .replace("path: [T, HOOK]}", "path: [T, HOOK]}\n  tie: {EA: 2.0e7, path: [T, B]}"))
    assert text.count("B:") == 1 and "tie:" in text
    model = load(write(tmp_path, text, "  duration: 1\n", IYVAL=2.0e-2, NEL=1,
                       MASS="lumped", GVAL=-9.81))
    mech = Mechanism(model, parse(model))
    assert mech.flex.labels() == ["T.ux", "T.uz"]
    o = mech.nc + mech.nJ
    P = (1500 + 7850 * 0.012 * 12 / 2) * 9.81
    w = P * 12**3 / (3 * 2.1e11 * 2.0e-2)
    np.testing.assert_allclose(mech.q0[o + 1], -w, rtol=1e-10)
    np.testing.assert_allclose(mech.S0, [1500 * 9.81, 0.0], rtol=1e-12, atol=0)
    assert mech.taut0.tolist() == [True, False]



ARM = """cranefe: 1
name: a blade on a hub and a free arm beside it
gravity: [0, 0, -9.81]
nodes:
  O: [0, 0, 0]
  T: [10.0, 0, 0]
  P: [-5.0, 0, 0]
  Q: [-5.0, 0, -2.0]
ground: [P]
bodies:
  hub: {mass: 10, com: [0, 0, 0], inertia: [1, 1, 1], nodes: [O]}
  arm: {mass: 50, com: [-5, 0, -2], inertia: [1, 1, 1], nodes: [Q]}
joints:
  - {name: spin, type: hinge, bodies: [ground, hub], at: O, axis: [0, 0, 1]}
  - {name: swing, type: hinge, bodies: [ground, arm], at: P, axis: [0, 1, 0]}
members:
  blade: {type: beam, nodes: [O, T], E: 2.1e+11, G: 8.0e+10, A: 0.1, Iy: 1.0e-2,
          Iz: 1.0e-2, J: 2.0e-2, rho: 78.5, orientation: [0, 0, 1], elements: 1,
          mass: lumped}
"""


def test_static_state_beside_a_joint_coordinate(tmp_path):
    """A free hinge beside the elastic blade (an arm hanging at rest below its pivot P:
    a joint coordinate, before the elastic ones) leaves the blade's static state as
    without it: the tip's deflection m g L^3 / (3 EI), m = rho A L / 2, and its axial
    shortening 0.6 w^2 / L (to 1e-8 of w: the Green strain's higher terms are
    (w / L)^2 = 4e-11 relative)."""
    model = load(write(tmp_path, ARM, "  duration: 1\n  drives:\n    sp: {hinge: spin, "
                       "profile: {type: table, speed: [[0, 0], [2, 1.2]]}}\n"
                       "    sw: {hinge: swing, free: true}\n"))
    mech = Mechanism(model, parse(model))
    assert mech.nJ == 1 and mech.nc == 0 and mech.n == 1 + 3
    assert mech.flex.labels() == ["T.ux", "T.uy", "T.uz"]
    w = 78.5 * 0.1 * 10 / 2 * 9.81 * 10**3 / (3 * 2.1e11 * 1.0e-2)
    u = [-0.6 * w * w / 10, 0.0, -w]          # shortened by 0.6 w^2 / L (delta = 0)
    np.testing.assert_allclose(mech.q0[1:], u, rtol=1e-8, atol=1e-8 * w)
    np.testing.assert_allclose(mech.flex.u0, u, rtol=1e-8, atol=1e-8 * w)
