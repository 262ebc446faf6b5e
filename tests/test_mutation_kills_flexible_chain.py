"""Kill tests for cranefe/analysis/operation/flexible.py (tools/mutation.py flexible;
docs/mutation.md, operation/flexible.py): the frame search `_frame_of` through a chain
of bodies.

An elastic structure rides on the body its anchors move with: the nearest body up the
tree whose joint is driven (an undriven joint holds: the body has its parent's motion).
tests/test_mutation_kills_flexible*.py anchor every member on a body that is driven
directly or on the ground, so the search never climbs. Here a jib is fixed to a slewing
tower that stands on a travelling portal:

    portal: slider along x from the ground (s = 0.25 (t - 1)^2 after t = 1 s),
    tower:  hinge about z through O = (2, 1, 0) on the portal (w = 0.6 t),
    jib:    `type: fixed` to the tower at N (undriven: the tower's motion),

and a structure is anchored on both: a beam from the jib's node N = (2, 3, 0) to the tip
T = (12, 3, 0) and a truss from the tower's node M = (12, 3, 4) down to T. Its frame is
the tower's (the jib's joint is not driven), so the two anchors agree. The joints are
listed fixed, travel, slew so that the jib's joint has index 0 = the portal's body index
(a search that stepped to the joint's index instead of the parent body would land on
the portal: a frame without the slew).

Every value by hand, from the frame's motion (none computed by the module):

* the tower's motion: R = Rz(phi), phi = 0.3 t^2, w = 0.6 t, w' = 0.6, R' = w R S,
  R'' = R (w' S + w^2 S^2), S = skew(e_z), composed with the portal's translation
  (R = I, p = s e_x): p = O - R O + s e_x, p' = -R' O + s' e_x, p'' = -R'' O + s'' e_x;
* the tip displaced along the beam, u = (d, 0, 0): no bending (the condensed slopes are
  zero), the beam's Green elongation is d, the truss's (its direction e = -e_z, length
  l = 4) is e . u + |u - (e . u) e|^2 / (2 l) = d^2 / 8 (Green's strain of a bar):
  U = EA/(2 L) d^2 + (EA/l)_t delta_t^2 / 2,
  dU/du = (EA/L) d e_x + N_t (e + (u - (e . u) e) / l), N_t = (EA/l)_t delta_t;
* the tip's lumped mass m = rho A L / 2 + rho_t A_t l / 2; x = R (X + u) + p,
  x' = R' (X + u) + R u' + p', F = -dU/du + m R^T g - m (R^T R'' Y + 2 R^T R' u' +
  R^T p'') (the module docstring's floating-frame equation), T = m |x'|^2 / 2,
  V = -m x . g.
"""

import math

import numpy as np
from test_operation_flexible import write

from cranefe.analysis.operation.mechanism import Mechanism
from cranefe.analysis.operation.scene import parse
from cranefe.model import load

CHAIN = """cranefe: 1
name: a jib fixed to a slewing tower on a travelling portal, elastic tip on both
gravity: [-3.0, 1.5, -9.81]
nodes:
  K: [0.0, -3.0, 1.0]
  O: [2.0, 1.0, 0.0]
  M: [12.0, 3.0, 4.0]
  N: [2.0, 3.0, 0.0]
  T: [12.0, 3.0, 0.0]
ground: []
bodies:
  portal: {mass: 10, com: [0, -3, 1], inertia: [1, 1, 1], nodes: [K]}
  tower: {mass: 10, com: [2, 1, 0], inertia: [1, 1, 1], nodes: [O, M]}
  jib: {mass: 10, com: [2, 3, 0], inertia: [1, 1, 1], nodes: [N]}
joints:
  - {name: fix, type: fixed, bodies: [tower, jib], at: N}
  - {name: travel, type: slider, bodies: [ground, portal], at: K, axis: [1, 0, 0],
     range: [-1, 5]}
  - {name: slew, type: hinge, bodies: [portal, tower], at: O, axis: [0, 0, 1]}
members:
  boom: {type: beam, nodes: [N, T], E: 2.1e+11, G: 8.0e+10, A: 0.1, Iy: 1.0e-6,
         Iz: 1.0e-6, J: 2.0e-6, rho: 78.5, orientation: [0, 0, 1], elements: 1,
         mass: lumped}
  hanger: {type: truss, nodes: [M, T], E: 2.1e+11, A: 0.01, rho: 78.5, mass: lumped}
"""
DRIVES = ("  duration: 3\n  drives:\n"
          "    tr: {slider: travel, profile: {type: table, speed: [[0, 0], [1, 0], [3, 1.0]]}}\n"
          "    sl: {hinge: slew, profile: {type: table, speed: [[0, 0], [2, 1.2]]}}\n")

GRAV = np.array([-3.0, 1.5, -9.81])
S = np.array([[0, -1.0, 0], [1.0, 0, 0], [0, 0, 0]])
O, X = np.array([2.0, 1.0, 0.0]), np.array([12.0, 3.0, 0.0])
EA, L = 2.1e11 * 0.1, 10.0                        # the beam N-T
EAT, LT, ET = 2.1e11 * 0.01, 4.0, np.array([0.0, 0.0, -1.0])   # the truss M-T
MASS = 78.5 * 0.1 * L / 2 + 78.5 * 0.01 * LT / 2
D = -2e-7                                         # the tip's axial displacement (420 N)
UD = np.array([-0.3, 0.5, 0.9])                   # its velocity in the frame's axes


def _tower(t):
    """(R, R', R'', p, p', p'') of the tower (and of the jib fixed to it) at t."""
    s = 0.25 * (t - 1) ** 2 if t > 1 else 0.0
    ds = 0.5 * (t - 1) if t > 1 else 0.0
    dds = 0.5 if t > 1 else 0.0
    ex = np.array([1.0, 0, 0])
    phi, w, dw = 0.3 * t * t, 0.6 * t, 0.6
    c, sn = math.cos(phi), math.sin(phi)
    R = np.array([[c, -sn, 0], [sn, c, 0], [0, 0, 1.0]])
    dR, ddR = w * R @ S, R @ (dw * S + w * w * S @ S)
    return R, dR, ddR, O - R @ O + s * ex, -dR @ O + ds * ex, -ddR @ O + dds * ex


def _hand(t):
    """The tip's x, x', F (frame axes), T, V, U at t."""
    R, dR, ddR, p, dp, ddp = _tower(t)
    u = np.array([D, 0.0, 0.0])
    Y = X + u
    dt = ET @ u + (u - (ET @ u) * ET) @ (u - (ET @ u) * ET) / (2 * LT)
    Nt = EAT / LT * dt
    dU = EA / L * D * np.array([1.0, 0, 0]) + Nt * (ET + (u - (ET @ u) * ET) / LT)
    F = (-dU + MASS * R.T @ GRAV
         - MASS * (R.T @ ddR @ Y + 2 * R.T @ dR @ UD + R.T @ ddp))
    x, xd = R @ Y + p, dR @ Y + R @ UD + dp
    return dict(x=x, xd=xd, F=F, T=0.5 * MASS * xd @ xd, V=-MASS * x @ GRAV,
                U=0.5 * EA / L * D * D + 0.5 * EAT / LT * dt * dt)


def _mechanism(tmp_path):
    """A fresh mechanism in every test (mutmut's forks must build it with the mutant)."""
    model = load(write(tmp_path, CHAIN, DRIVES))
    mech = Mechanism(model, parse(model))
    f = mech.flex
    assert f.labels() == ["T.ux", "T.uy", "T.uz"]
    tower = [b.name for b in model.bodies].index("tower")
    assert [b for b, _ in f.frames] == [tower]      # the tower's frame, not the jib's
    f._last = f._theta = None                       # slopes from the linear start
    return mech


def test_structure_on_a_body_fixed_to_a_slewing_tower(tmp_path):
    """At t = 1.5 s (portal at s = 1/16 m, 0.25 m/s, 0.5 m/s^2; tower at phi = 0.675,
    w = 0.9, w' = 0.6): the tip's position and velocity (to 1e-13 m: round-off of
    12 m), the forces on u, whose largest term is the beam's axial 420 N (to 1e-9 of
    it: EA/L d is 2.1e9 N/m times 2e-7 m; the slopes' Newton stops at round-off), T and
    V (1e-12 relative: round-off) and U (1e-9: the slopes' Newton)."""
    mech = _mechanism(tmp_path)
    t = 1.5
    h = _hand(t)
    q = np.array([D, 0.0, 0.0])
    X_, V_ = mech.place(t, q, UD)[:2]
    tip = mech.model.node_names.index("T")
    np.testing.assert_allclose(X_[tip], h["x"], rtol=0, atol=1e-13)
    np.testing.assert_allclose(V_[tip], h["xd"], rtol=0, atol=1e-13)
    ev = mech.evaluate(t, q, UD, mech.taut0)
    np.testing.assert_allclose(ev.F, h["F"], rtol=0, atol=1e-9 * np.abs(h["F"]).max())
    T, Vg, U = mech.flex.energy(mech, t, q, UD)
    np.testing.assert_allclose(T, h["T"], rtol=1e-12)
    np.testing.assert_allclose(Vg, h["V"], rtol=1e-12)
    np.testing.assert_allclose(U, h["U"], rtol=1e-9)
    # the slew's share of the tip's acceleration is far above the tolerance: a frame
    # without it (the portal's) would show
    R, dR, ddR, *_ = _tower(t)
    assert MASS * np.abs(R.T @ ddR @ (X - O)).max() > 1e6 * 1e-9 * np.abs(h["F"]).max()


# ------------------------------------------------------------------ a linkage body
# A boom hinged to the ground at O, luffed by a cylinder from the ground node A to the
# boom's node C (a linkage of one body: operation/linkage.py); a one-element blade from
# the boom's node N out to the elastic tip T, along the boom. The boom's joint is in the
# linkage, not driven: its frame is the boom's because the boom is a linkage body.
#
# Hand kinematics (x-z plane, theta turning x toward z about O): with a = A - O = (4, -3)
# and c0 = C - O = (4, 0), a . Rot(theta) c0 = 16 cos - 12 sin =
# k cos(beta + theta), k = |a| |c0| = 20, beta = atan2(3, 4), so the cylinder's length
# d^2 = |a|^2 + |c0|^2 - 2 k cos(beta + theta) gives
#     theta = acos((41 - d^2) / 40) - beta          (theta = 0 at d = d0 = 3),
# and differentiating k cos(beta + theta) = (41 - d^2) / 2 twice in t:
#     theta' = d d' / (k sin(beta + theta)),
#     theta'' = (d'^2 + d d'' - k cos(beta + theta) theta'^2) / (k sin(beta + theta)),
# d = 3 + s, s = 0.05 t^2 (the speed table s' = 0.1 t). The boom's motion:
# R = Rot(theta), R' = theta' R_th, R'' = theta'' R_th + theta'^2 R_thth, p = O - R O.

LUFF = """cranefe: 1
name: an elastic blade on a boom luffed by a cylinder
plane: xz
gravity: [0, 0, -9.81]
nodes:
  O: [1.0, 0, 2.0]
  C: [5.0, 0, 2.0]
  A: [5.0, 0, -1.0]
  N: [9.0, 0, 2.0]
  T: [15.0, 0, 2.0]
ground: [O, A]
bodies:
  boom: {mass: 500, com: [5, 0, 2], inertia: 1000, nodes: [O, C, N]}
joints:
  - {name: foot, type: hinge, bodies: [ground, boom], at: O, axis: [0, 1, 0]}
linear_drives:
  cyl: {nodes: [A, C], pinion_radius: 0.1, gear_ratio: 10}
members:
  blade: {type: beam, nodes: [N, T], E: 2.1e+11, A: 0.1, Iy: 1.0e-4, rho: 78.5,
          elements: 1, mass: lumped}
"""
LUFF_DRIVES = ("  duration: 3\n  drives:\n"
               "    c: {linear: cyl, profile: {type: table, speed: [[0, 0], [2, 0.2]]}}\n")
OL, XL, LL = np.array([1.0, 0, 2.0]), np.array([15.0, 0, 2.0]), 6.0
ML = 78.5 * 0.1 * LL / 2
G3 = np.array([0.0, 0.0, -9.81])


def _boom(t):
    """(R, R', R'', p, p', p'') of the luffed boom at t, by hand (above)."""
    s, ds, dds = 0.05 * t * t, 0.1 * t, 0.1
    d, k, beta = 3.0 + s, 20.0, math.atan2(3.0, 4.0)
    th = math.acos((41.0 - d * d) / 40.0) - beta
    sn, cs = math.sin(beta + th), math.cos(beta + th)
    dth = d * ds / (k * sn)
    ddth = (ds * ds + d * dds - k * cs * dth * dth) / (k * sn)
    c, s_ = math.cos(th), math.sin(th)
    R = np.array([[c, 0, -s_], [0, 1.0, 0], [s_, 0, c]])
    Rt = np.array([[-s_, 0, -c], [0, 0.0, 0], [c, 0, -s_]])
    Rtt = np.array([[-c, 0, s_], [0, 0.0, 0], [-s_, 0, -c]])
    dR, ddR = dth * Rt, ddth * Rt + dth * dth * Rtt
    return th, (R, dR, ddR, OL - R @ OL, -dR @ OL, -ddR @ OL)


def test_structure_on_a_linkage_body(tmp_path):
    """At t = 1.5 s (s = 0.1125 m, the boom turned up by 0.0281 rad): the tip's
    position and velocity with u = (d, 0, 0), u' = (0.4, 0, -0.7) (to 1e-12 m: the
    linkage's Newton stops 1e-13 of its size), and the forces on u: the blade's axial
    EA/L d, gravity and the frame's terms m (R^T R'' Y + 2 R^T R' u' + R^T p'') (to
    1e-9 of the largest: the linkage's rates to ~1e-11)."""
    model = load(write(tmp_path, LUFF, LUFF_DRIVES))
    mech = Mechanism(model, parse(model))
    f = mech.flex
    assert f.labels() == ["T.ux", "T.uz"]
    assert [b for b, _ in f.frames] == [0]               # the boom's frame
    f._last = f._theta = None
    t, d = 1.5, 1e-7
    th, (R, dR, ddR, p, dp, ddp) = _boom(t)
    assert th > 0.02                                     # far from the ground's frame
    u, ud = np.array([d, 0.0, 0.0]), np.array([0.4, 0.0, -0.7])
    Y = XL + u
    q = np.zeros(mech.n)
    o = mech.nc + mech.nJ
    q[o:o + 2], v = u[[0, 2]], np.zeros(mech.n)
    v[o:o + 2] = ud[[0, 2]]
    X_, V_ = mech.place(t, q, v)[:2]
    tip = model.node_names.index("T")
    np.testing.assert_allclose(X_[tip], R @ Y + p, rtol=0, atol=1e-12)
    np.testing.assert_allclose(V_[tip], dR @ Y + R @ ud + dp, rtol=0, atol=1e-12)
    F = (-2.1e11 * 0.1 / LL * d * np.array([1.0, 0, 0]) + ML * R.T @ G3
         - ML * (R.T @ ddR @ Y + 2 * R.T @ dR @ ud + R.T @ ddp))
    ev = mech.evaluate(t, q, v, mech.taut0)
    np.testing.assert_allclose(ev.F[o:o + 2], F[[0, 2]], rtol=0,
                               atol=1e-9 * np.abs(F).max())
