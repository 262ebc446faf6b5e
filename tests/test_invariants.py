"""Invariants of the 3D formulation: rigid motions of a whole model, mass scaling,
the load stiffness of bodies hanging on ropes (bifilar pendulum)."""

import os
from dataclasses import replace

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from cranefe.model import load
from cranefe.analysis.modal import modes

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TOWER = os.path.join(ROOT, "models", "hammerhead_tower_crane.yaml")


def moved(model, R, shift):
    """The same crane rotated by R and shifted (gravity turns with it)."""
    rot = lambda v: None if v is None else v @ R.T
    return replace(
        model,
        coords=model.coords @ R.T + shift,
        gravity=R @ model.gravity,
        bodies=tuple(replace(b, com=R @ b.com + shift, inertia=R @ b.inertia @ R.T)
                     for b in model.bodies),
        joints=tuple(replace(j, axis=rot(j.axis)) for j in model.joints),
        springs=tuple(replace(s, axis=rot(s.axis)) for s in model.springs),
        masses=replace(model.masses, inertia=R @ model.masses.inertia @ R.T))


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_rigid_motion_of_the_whole_crane(seed):
    model = load(TOWER)
    R = Rotation.random(random_state=seed).as_matrix()
    base = modes(model)
    turned = modes(moved(model, R, np.array([1e3, -250.0, 40.0])))
    # the same physics in other coordinates: agreement to round-off of the assembly
    assert turned.omega == pytest.approx(base.omega, rel=1e-9, abs=1e-9)
    # node motion turns with the crane (compare a non-degenerate mode's magnitudes)
    k = int(np.flatnonzero(~base.rigid)[2])
    assert np.linalg.norm(turned.node_shapes[k], axis=1) == pytest.approx(
        np.linalg.norm(base.node_shapes[k], axis=1), rel=1e-6, abs=1e-9)


def test_bifilar_pendulum(model_from):
    # A beam hanging on two vertical ropes at +-a: sway sqrt(g/l) along it, torsion
    # about the vertical w^2 = m g a^2 / (I_z l) from tension and load stiffness together.
    m, a, l, Iz = 1200.0, 1.5, 6.0, 900.0
    text = f"""
    cranefe: 1
    nodes: {{S1: [{a}, 0, {l}], S2: [{-a}, 0, {l}], P1: [{a}, 0, 0], P2: [{-a}, 0, 0]}}
    # rope points 0.5 m above the com: stable about the beam axis too
    ground: [S1, S2]
    bodies:
      beam: {{mass: {m}, com: [0, 0, -0.5], inertia: [300, {Iz + 50}, {Iz}], nodes: [P1, P2]}}
    ropes:
      r1: {{EA: 4.0e7, path: [S1, P1]}}
      r2: {{EA: 4.0e7, path: [S2, P2]}}
    effects: {{rope_elasticity: false}}   # elastic ropes would let the beam pitch a little
    """
    r = modes(model_from(text))
    g = 9.81
    # sway along the beam (a parallelogram: no tilt) is the simple pendulum; sway across
    # it tilts the body about x and couples, so it is not checked here
    for expected in (np.sqrt(g / l), np.sqrt(m * g * a**2 / (Iz * l))):
        assert r.omega[np.argmin(abs(r.omega - expected))] == pytest.approx(expected,
                                                                           rel=1e-10)


def test_body_hung_below_its_rope_point_swings_as_physical_pendulum(model_from):
    # a body hanging on one rope, attached at a point h above its com: the double
    # pendulum of a rope (length l) and a rigid body (I_c, h): quartic
    # I_c l w^4 ... checked against the generic linearisation of Lagrange's equations
    m, Ic, l, h = 900.0, 400.0, 5.0, 1.2
    text = f"""
    cranefe: 1
    plane: xz
    nodes: {{S: [0, 0, 10], P: [0, 0, {10 - l}]}}
    ground: [S]
    bodies:
      hook: {{mass: {m}, com: [0, 0, {10 - l - h}], inertia: {Ic}, nodes: [P]}}
    ropes:
      r: {{EA: 1.0e12, path: [S, P]}}
    """
    r = modes(model_from(text))
    g = 9.81
    # coordinates: rope angle a, body angle b; T = m/2 (l a' + h b')^2 + Ic/2 b'^2,
    # V = m g (l a^2 + h b^2) / 2
    M = np.array([[m * l * l, m * l * h], [m * l * h, m * h * h + Ic]])
    K = np.diag([m * g * l, m * g * h])
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(M, K)).real)
    assert np.sort(r.omega)[:2] == pytest.approx(np.sqrt(w2), rel=1e-9)
