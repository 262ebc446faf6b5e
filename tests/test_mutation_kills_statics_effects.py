"""Kill tests for cranefe/statics.py's `solve_static` in the cases the first two rounds
left (tools/mutation.py statics; docs/testing.md, "Mutation testing"), on small models
solved by hand:

- inextensible ropes in the model (`rope_elasticity: false`): the static state still
  stretches them (statics is elastic), u = -m g L / EA;
- a `Reuse` (the cache of a sweep) with sway on in the model and inclined ropes with
  mass: the static state is solved with sway off all the same;
- a boom on a linear drive whose node C also carries a rope: C's force is the rope's
  pull plus the drive's reaction (two contributions to one node);
- a light node between two beam elements of a loaded cantilever: the equilibrium check
  at beam nodes is relative to the beam end forces, not to the node's own weight.

Tolerances: 1e-10 relative (linear solves of a few well-conditioned coordinates; the
drive's force through a least-squares solve of the constraint forces).
"""

import numpy as np
import pytest

from cranefe import statics
from cranefe.assembly.reuse import Reuse
from cranefe.model import load

G = 9.81

ROPE = """cranefe: 1
plane: xz
nodes: {{S: [0, 0, 10], A: [0, 0, 0]}}
ground: [S]
masses: {{A: 1000}}
ropes:
  r: {{EA: 1.0e8, path: [S, A]}}
effects: {{sway: false{extra}}}
"""


@pytest.mark.parametrize("extra", ["", ", rope_elasticity: false"])
def test_statics_stretches_inextensible_ropes(extra):
    """The static state is elastic whatever the model's effect (solve_static's
    docstring): a 1000 kg load on a 10 m vertical rope of EA 1e8 N drops by
    m g L / EA = 9.81e-4 m and the rope carries m g."""
    m = load("r.yaml", ROPE.format(extra=extra))
    st = statics.solve_static(m)
    assert st.element_force == pytest.approx([1000 * G], rel=1e-10)
    assert st.u.min() == pytest.approx(-1000 * G * 10 / 1e8, rel=1e-10)


TAGGED = """cranefe: 1
plane: xz
nodes: {A: [-6, 0, 8], L: [0, 0, 0], B: [4, 0, -3]}
ground: [A, B]
masses: {L: 1000}
ropes:
  hoist: {EA: 1.0e7, path: [A, L], mass_per_length: 20}
  tag: {EA: 1.0e5, path: [L, B], mass_per_length: 5}
effects: {rope_mass: 4, sway: true}
"""


def test_a_reuse_solves_the_static_state_with_sway_off():
    """A load between an inclined hoist rope and a tag line, both with mass (sway on in
    the model): with sway off the interior nodes move along their falls and each rope
    carries its tension; with sway on their lateral coordinates (no elastic stiffness)
    would take the lateral weight (an error or another state). A `Reuse` must give the
    same state as none (whose values tests/test_mutation_kills_statics_solve.py checks),
    and the load L stays in equilibrium."""
    m = load("t.yaml", TAGGED)
    st = statics.solve_static(m)
    again = statics.solve_static(m, reuse=Reuse())
    assert again.u.shape == st.u.shape
    assert np.allclose(again.u, st.u, rtol=1e-10, atol=1e-15)
    assert np.allclose(again.element_force, st.element_force, rtol=1e-10)
    assert np.allclose(again.node_force[m.node_index["L"]], 0, atol=1e-6)


BOOM_ROPE = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 0], A: [-2, 0, 0], C: [2, 0, 2], T: [10, 0, 0], W: [2, 0, -8]}
ground: [O, A]
bodies:
  boom: {mass: 1000, com: [5, 0, 0], inertia: 8000, nodes: [C, T]}
masses: {W: 300}
joints:
  - {type: hinge, bodies: [ground, boom], at: O}
linear_drives:
  luff: {nodes: [A, C], pinion_radius: 0.2, gear_ratio: 100}
ropes:
  r: {EA: 1.0e8, path: [C, W]}
effects: {sway: true}
"""


def test_a_drive_node_that_also_carries_a_rope():
    """Moments about O ((r x F)_y = z F_x - x F_z): the boom's weight 1000 g at x = 5
    gives +5000 g, the rope's pull 300 g down at C (x = 2) +600 g, the drive's tension
    P along -e at C, e = (4, 0, 2)/sqrt 20: -4 P / sqrt 20. So P = 5600 g sqrt 20 / 4.
    The force on node C is the rope's pull plus the drive's: (0, 0, -300 g) - P e."""
    m = load("b.yaml", BOOM_ROPE)
    st = statics.solve_static(m)
    e = np.array([4.0, 0.0, 2.0]) / np.sqrt(20.0)
    P = 5600 * G * np.sqrt(20.0) / 4
    assert st.drive_force == pytest.approx([P], rel=1e-10)
    C = m.node_index["C"]
    assert np.allclose(st.node_force[C], np.array([0, 0, -300 * G]) - P * e,
                       rtol=1e-10, atol=1e-9 * P)
    assert st.element_force == pytest.approx([300 * G], rel=1e-10)


CANTILEVER = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 0], M: [3.7, 0, 0], T: [7.3, 0, 0]}
ground: [O]
masses: {M: 1.0e-6, T: 1.0e6}
members:
  c1: {type: beam, nodes: [O, M], E: 2.1e11, A: 1.0e-2, Iy: 2.0e-4, rho: 0}
  c2: {type: beam, nodes: [M, T], E: 2.1e11, A: 1.0e-2, Iy: 2.0e-4, rho: 0}
effects: {structure: flexible}
"""


def test_a_light_node_between_loaded_beams_is_in_equilibrium():
    """A 1e6 kg tip load on a cantilever of two beam elements whose middle node weighs
    1e-6 kg: M's forces are sums of beam end forces of about 1e7 N, whose round-off
    (~1e-9 N) is far above 1e-7 of M's weight (1e-12 N); the check is relative to the
    end forces, so the state is accepted. Tip deflection P L^3 / (3 E I) (Euler-Bernoulli,
    exact for cubic elements under end loads), to 1e-9 (the solve's round-off)."""
    m = load("c.yaml", CANTILEVER)
    st = statics.solve_static(m)
    P, L = (1.0e6 + 1.0e-6) * G, 7.3
    tip = -P * L**3 / (3 * 2.1e11 * 2.0e-4)
    assert st.u.min() == pytest.approx(tip, rel=1e-9)
