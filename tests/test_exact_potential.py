"""The assembled stiffness equals the second derivative of the exact nonlinear potential.

A rigid boom hinged to the ground and held by a strut or a rope that carries static
force: tension stiffness, load stiffness and joint reactions must together give
d^2V/dtheta^2 of V = 1/2 k (L(theta) - L0)^2 + m g z_com(theta) at the equilibrium
(L0 from dV/dtheta = 0), differentiated in 50-digit arithmetic (mpmath).
"""

import mpmath as mp
import numpy as np
import pytest

from cranefe.analysis.modal import modes

mp.mp.dps = 50
G = 9.81


def exact_omega(m, com, Ic, k, A, C, hinge=(0, 0)):
    """w of the boom from the exact potential; points (x, z), rotation about y at hinge."""
    ox, oz = map(mp.mpf, hinge)

    def rot(p, t):
        x, z = mp.mpf(p[0]) - ox, mp.mpf(p[1]) - oz
        # positive rotation about +y turns z into x
        return ox + x * mp.cos(t) + z * mp.sin(t), oz - x * mp.sin(t) + z * mp.cos(t)

    def L(t):
        cx, cz = rot(C, t)
        return mp.sqrt((cx - A[0]) ** 2 + (cz - A[1]) ** 2)

    def zc(t):
        return rot(com, t)[1]

    L0 = L(0) + m * G * mp.diff(zc, 0) / (k * mp.diff(L, 0))   # dV/dt = 0 at t = 0
    V = lambda t: k / 2 * (L(t) - L0) ** 2 + m * G * zc(t)
    I_O = Ic + m * ((com[0] - hinge[0]) ** 2 + (com[1] - hinge[1]) ** 2)
    return float(mp.sqrt(mp.diff(V, 0, 2) / I_O)), float(k * (L(0) - L0))


@pytest.mark.parametrize("kind", ["strut", "rope"])
@pytest.mark.parametrize("angle", [0.0, 30.0, 65.0])
def test_boom_on_strut_or_rope(model_from, kind, angle):
    m, Ic, lc, lb = 6000.0, 4.0e4, 9.0, 20.0
    a = np.radians(angle)
    u = np.array([np.cos(a), np.sin(a)])
    com, tip, mid = lc * u, lb * u, 12.0 * u
    if kind == "strut":       # compressed strut from a ground point below to mid-boom
        A, C, stiff = np.array([3.0, -6.0]), mid, 5.0e6
        element = f"""
    springs:
      - {{name: strut, type: axial, nodes: [A, C], stiffness: {stiff}}}"""
    else:                     # luffing rope from the tip to a ground point above the hinge
        A, C, stiff = np.array([-2.0, 25.0]), tip, 3.0e6
        EA = stiff * np.linalg.norm(C - A)
        element = f"""
    ropes:
      luff: {{EA: {EA}, path: [A, C]}}"""
    text = f"""
    cranefe: 1
    plane: xz
    nodes: {{O: [0, 0, 0], A: [{A[0]}, 0, {A[1]}], C: [{C[0]}, 0, {C[1]}],
            T: [{tip[0]}, 0, {tip[1]}]}}
    ground: [A]
    bodies:
      boom: {{mass: {m}, com: [{com[0]}, 0, {com[1]}], inertia: {Ic}, nodes: [O, C, T]}}
    joints:
      - {{type: hinge, bodies: [ground, boom], at: O}}""" + element
    if kind == "rope":
        text = text.replace("nodes: [O, C, T]", "nodes: [O, T]").replace(
            f", C: [{C[0]}, 0, {C[1]}]", "").replace("[A, C]", "[A, T]")
    w, force = exact_omega(m, com, Ic, stiff, A, C)
    r = modes(model_from(text))
    assert (force > 0) == (kind == "rope")       # the rope pulls, the strut pushes
    # both are exact second derivatives; the 50-digit reference leaves round-off only
    assert r.omega == pytest.approx([w], rel=1e-9)
