"""Kill tests for cranefe/assembly/ (issue 20, mutation testing; tools/mutation.py
assembly): two configurations the other assembly tests do not build.

- A rigid member (`structure: rigid`) on a 3D pendulum whose rod is NOT perpendicular
  to the hinge axis (`_rigid_members`): a thin rod has no inertia about its own axis,
  so about the hinge axis a (through O, the rod's end) its points s e (0 <= s <= l) give
  I = (m_r / l) int_0^l s^2 (1 - (a.e)^2) ds = m_r l^2 (1 - (a.e)^2) / 3, written here
  directly (the module adds m_r l^2 / 12 (1 - e e^T) at the midpoint and the parallel
  axes); in the planar pendulum of tests/test_mutation_kills_assembly.py a.e = 0, where
  an error in the own-axis term cannot show.
- A rope with mass and `extra_length` (the rope on the drum or in its terminations): the
  extra piece is one element of that length between the rope's anchor and a slip
  coordinate where the fall begins, elastic but massless (`element_materials`: mu = 0
  for it; docs/theory.md "Ropes with mass"). One fall element holding a load: the
  coordinates (s, u), the slip at the top and the load's displacement along the fall,
  K = EA/L_x [[1, 0], [0, 0]] + EA/L [[1, -1], [-1, 1]], M = mu L [[1/3, 1/6], [1/6,
  1/3]] + diag(0, M_load): det(K - w^2 M) = 0 by the quadratic formula; statics: the fall
  carries (M_load + mu L / 2) g, the extra piece that plus the fall's upper half, (M_load
  + mu L) g (its own weight zero).
- A light body (0.5 kg, a laboratory model's hook) welded to a hinged arm: its own
  weight enters the gravity points, i.e. the load stiffness of the rigid group (whose
  reference is the arm's centre), whatever its size (`_BodyMass`): the compound
  pendulum's w^2 = g sum(m_k d_k) / sum(I_k + m_k d_k^2).

Tolerance 1e-12 relative: eigenvalues of one or two coordinates and a linear solve.
"""

import numpy as np
import pytest

from cranefe.analysis.modal import modes
from cranefe.model import load
from cranefe.statics import solve_static

G = 9.81

PENDULUM_3D = """cranefe: 1
nodes: {O: [0, 0, 0], T: [0, 2, -4]}
ground: [O]
bodies:
  arm: {mass: 300, com: [0, 0, -2], inertia: [50, 60, 70], nodes: [T]}
joints:
  - {type: hinge, bodies: [ground, arm], at: O, axis: [0, 1, 0]}
members:
  rod: {type: truss, nodes: [O, T], E: 2.1e11, A: 1.0e-3, rho: 7850}
effects: {sway: true}
"""


def test_rigid_rod_oblique_to_the_hinge_axis():
    """w^2 = g sum(m_k d_k) / I_O about the hinge axis y: the arm (300 kg, I_yy = 60,
    centre 2 m below O: I = 60 + 300 * 4), the rod O-T (T = (0, 2, -4): l^2 = 20, e_y^2 =
    4/20, midpoint 2 m below O): I = m_r * 20 * (1 - 0.2) / 3, d = 2."""
    l2 = 20.0
    mr = 7850 * 1.0e-3 * np.sqrt(l2)
    I_O = 60 + 300 * 2.0**2 + mr * l2 * (1 - 4 / l2) / 3
    w2 = G * (300 * 2.0 + mr * 2.0) / I_O
    r = modes(load("p3.yaml", PENDULUM_3D))
    assert r.omega.shape == (1,)
    assert r.omega[0] ** 2 == pytest.approx(w2, rel=1e-12)


EXTRA = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 10], L: [0, 0, 0]}
ground: [O]
masses: {L: 500}
ropes:
  r: {EA: 2.0e8, path: [O, L], mass_per_length: 7.85, extra_length: 4}
effects: {sway: false, rope_mass: 1}
"""


def test_the_extra_length_piece_of_a_rope_with_mass_is_massless():
    EA, L, Lx, mu, M = 2.0e8, 10.0, 4.0, 7.85, 500.0
    K = EA / Lx * np.array([[1.0, 0], [0, 0]]) + EA / L * np.array([[1.0, -1], [-1, 1]])
    Mm = mu * L * np.array([[1 / 3, 1 / 6], [1 / 6, 1 / 3]]) + np.diag([0.0, M])
    a = np.linalg.det(Mm)
    b = K[0, 0] * Mm[1, 1] + K[1, 1] * Mm[0, 0] - 2 * K[0, 1] * Mm[0, 1]
    c = np.linalg.det(K)
    w2 = (b + np.array([-1.0, 1.0]) * np.sqrt(b * b - 4 * a * c)) / (2 * a)
    model = load("x.yaml", EXTRA)
    r = modes(model)
    assert np.sort(r.omega**2) == pytest.approx(w2, rel=1e-12)
    st = solve_static(model)
    assert sorted(st.element_force) == pytest.approx(
        [(M + mu * L / 2) * G, (M + mu * L) * G], rel=1e-12)


LIGHT = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 0], W: [0, 0, -1.5]}
ground: [O]
bodies:
  arm: {mass: 3, com: [0, 0, -1], inertia: 0.2, nodes: [W]}
  hook: {mass: 0.5, com: [0, 0, -2], inertia: 0.01}
joints:
  - {type: hinge, bodies: [ground, arm], at: O}
  - {type: fixed, bodies: [arm, hook], at: W}
"""


def test_a_light_body_swings_by_its_own_weight():
    r = modes(load("light.yaml", LIGHT))
    assert r.omega.shape == (1,)
    w2 = G * (3 * 1.0 + 0.5 * 2.0) / (0.2 + 3 * 1.0**2 + 0.01 + 0.5 * 2.0**2)
    assert r.omega[0] ** 2 == pytest.approx(w2, rel=1e-12)
