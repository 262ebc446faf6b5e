"""Joints, fixed groups and linear drives against closed forms."""

import numpy as np
import pytest

from cranefe.analysis.modal import modes

G = 9.81


@pytest.mark.parametrize("planar", [True, False])
def test_slider_with_spring(model_from, planar):
    m, k = 1500.0, 3.0e5
    text = f"""
    cranefe: 1
    {"plane: xz" if planar else ""}
    nodes: {{A: [0, 0, 5], K: [4, 0, 5]}}
    ground: [A]
    bodies:
      trolley: {{mass: {m}, com: [4, 0, 5], inertia: {200 if planar else [150, 200, 250]},
                nodes: [K]}}
    joints:
      - {{type: slider, bodies: [ground, trolley], at: K, axis: [1, 0, 0]}}
    springs:
      - {{name: rope, type: axial, nodes: [A, K], stiffness: {k}}}
    """
    r = modes(model_from(text))
    assert r.omega == pytest.approx([np.sqrt(k / m)], rel=1e-12)
    assert r.labels == ("body trolley ux",)


def test_inclined_3d_hinge(model_from):
    # rotation about axis a through O: w^2 = k / (a^T I_O a), I_O = I_c + m (|c|^2 I - c c^T)
    m, k = 700.0, 4.0e6
    Ic = np.diag([120.0, 340.0, 410.0])
    com = np.array([1.0, 2.0, -0.5])
    a = np.array([1.0, 1.0, 1.0]) / np.sqrt(3)
    text = f"""
    cranefe: 1
    gravity: [0, 0, 0]
    nodes: {{O: [0, 0, 0]}}
    bodies:
      b: {{mass: {m}, com: {com.tolist()}, inertia: {np.diag(Ic).tolist()}, nodes: [O]}}
    joints:
      - {{type: hinge, bodies: [ground, b], at: O, axis: [1, 1, 1]}}
    springs:
      - {{name: s, type: rotational, bodies: [ground, b], axis: [1, 1, 1], stiffness: {k}}}
    """
    I_O = Ic + m * (com @ com * np.eye(3) - np.outer(com, com))
    r = modes(model_from(text))
    assert r.omega == pytest.approx([np.sqrt(k / (a @ I_O @ a))], rel=1e-12)


def test_ball_joint_spherical_pendulum(model_from):
    # a rigid bob on a ball joint: two equal physical-pendulum frequencies, and free spin
    # about the vertical through the joint (a quasi-cyclic coordinate)
    m, l, Ic = 400.0, 3.0, 50.0
    text = f"""
    cranefe: 1
    nodes: {{O: [0, 0, 10]}}
    bodies:
      bob: {{mass: {m}, com: [0, 0, {10 - l}], inertia: [{Ic}, {Ic}, 20], nodes: [O]}}
    joints:
      - {{type: ball, bodies: [ground, bob], at: O}}
    """
    r = modes(model_from(text))
    w = np.sqrt(m * G * l / (Ic + m * l * l))
    assert r.omega == pytest.approx([0, w, w], abs=1e-12, rel=1e-12)
    assert r.rigid.tolist() == [True, False, False]
    assert r.quasi_cyclic == ("body bob rz",)


def test_fixed_joint_makes_one_rigid_body(model_from):
    # two bodies fixed together equal one body with the combined mass properties
    m1, m2, k = 500.0, 300.0, 2.0e5
    c1, c2 = np.array([2.0, 0, 0]), np.array([5.0, 0, 1.0])
    I1, I2 = 100.0, 60.0
    two = f"""
    cranefe: 1
    plane: xz
    nodes: {{O: [0, 0, 0], J: [3, 0, 0]}}
    bodies:
      a: {{mass: {m1}, com: {c1.tolist()}, inertia: {I1}, nodes: [O, J]}}
      b: {{mass: {m2}, com: {c2.tolist()}, inertia: {I2}, nodes: [J]}}
    joints:
      - {{type: hinge, bodies: [ground, a], at: O}}
      - {{type: fixed, bodies: [a, b], at: J}}
    springs:
      - {{name: s, type: rotational, bodies: [ground, a], stiffness: {k}}}
    """
    r = modes(model_from(two, "two.yaml"))
    mt = m1 + m2
    ct = (m1 * c1 + m2 * c2) / mt
    It = I1 + I2 + m1 * np.sum((c1 - ct)[[0, 2]] ** 2) + m2 * np.sum((c2 - ct)[[0, 2]] ** 2)
    one = f"""
    cranefe: 1
    plane: xz
    nodes: {{O: [0, 0, 0]}}
    bodies:
      ab: {{mass: {mt}, com: {ct.tolist()}, inertia: {It}, nodes: [O]}}
    joints:
      - {{type: hinge, bodies: [ground, ab], at: O}}
    springs:
      - {{name: s, type: rotational, bodies: [ground, ab], stiffness: {k}}}
    """
    assert r.omega == pytest.approx(modes(model_from(one, "one.yaml")).omega, rel=1e-12)


def test_linear_drive_holds_the_boom(model_from):
    # a boom hinged at O and held by a rack drive: the boom cannot move, the load on its
    # tip swings as a simple pendulum and bounces on its rope
    l, m, EA = 8.0, 3000.0, 1.0e7
    text = f"""
    cranefe: 1
    plane: xz
    nodes: {{O: [0, 0, 0], A: [-3, 0, -2], C: [6, 0, 6], T: [12, 0, 12],
            L: [12, 0, {12 - l}]}}
    ground: [A]
    masses: {{L: {m}}}
    bodies:
      boom: {{mass: 5000, com: [6, 0, 6], inertia: 6.0e4, nodes: [O, C, T]}}
    joints:
      - {{type: hinge, bodies: [ground, boom], at: O}}
    linear_drives:
      luffing: {{nodes: [A, C], pinion_radius: 0.2, gear_ratio: 160, rotor_inertia: 2.0}}
    ropes:
      hoist: {{EA: {EA}, path: [T, L]}}
    """
    r = modes(model_from(text))
    assert r.omega == pytest.approx([np.sqrt(G / l), np.sqrt(EA / l / m)], rel=1e-12)
