"""Kill tests for cranefe/statics.py's solution and reactions (`solve_static`, `_solve`,
`_force_scale`, `_kinds_at`, `_check_free_nodes`, `point_forces`; tools/mutation.py
statics; docs/testing.md, "Mutation testing"), on small models solved by hand:

- a boom hinged at O, held by a linear drive from the ground at A to C on the boom:
  moments about O give the drive's tension, force balance the hinge's reaction, and every
  rigid group's points and forces (`point_forces`) are in force and moment equilibrium;
- a point mass on a support restraining z only: the support's reaction is its weight,
  its x direction is free and unloaded (the null-space path of `_solve`); with gravity
  tilted the free direction is loaded: the error names it and the unbalanced force;
- a load on an inclined rope (or spring) with sway off: the rope balances only its own
  direction, the rest of the weight is left: the error names the node, its kind of
  element and the force;
- a column of two beam elements under a top load: axial force -P in each;
- the same on the sparse path (`STATIC_DENSE_MAX` patched to 0).

Tolerances: 1e-10 relative (a linear solve of a few well-conditioned coordinates;
the hinge reaction through a least-squares solve of the constraint forces).
"""

import numpy as np
import pytest

from cranefe import statics
from cranefe.assembly.reuse import Reuse
from cranefe.errors import ModelError
from cranefe.model import load
from cranefe.system import assemble

# (sway off: `assemble` forms no static state; solve_static is called directly)

G = 9.81

BOOM = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 0], A: [-2, 0, 0], C: [2, 0, 2], T: [10, 0, 0], H: [20, 0, 0],
        N: [20, 0, -3], K: [25, 0, -3]}
ground: [O, A, H, K]
bodies:
  boom: {mass: 1000, com: [5, 0, 0], inertia: 8000, nodes: [C, T]}
  bob: {mass: 500, com: [20, 0, -3], inertia: 10, nodes: [N]}
masses: {T: 200}
joints:
  - {type: hinge, bodies: [ground, boom], at: O}
  - {type: hinge, bodies: [bob, ground], at: H}
linear_drives:
  luff: {nodes: [A, C], pinion_radius: 0.2, gear_ratio: 100}
springs:
  - {type: axial, nodes: [N, K], stiffness: 1.0e4}
effects: {sway: true}
"""


def _boom_by_hand():
    """(The bob, a second body hanging from H, has a horizontal spring that it does not
    stretch, so that its turn is not a free motion.) Moments about O (y components, r x F)_y = z F_x - x F_z: the weights 1000 g at
    x = 5 and 200 g at x = 10 give +5000 g + 2000 g; a tension P of the drive pulls C
    toward A, force -P e on C with e = (4, 0, 2)/sqrt 20: 2 (-4P) / sqrt 20 - 2 (-2P) /
    sqrt 20 = -4 P / sqrt 20. So P = 7000 g sqrt 20 / 4 (tension), and the hinge takes
    R = (0, 0, 1200 g) + P e."""
    e = np.array([4.0, 0.0, 2.0]) / np.sqrt(20.0)
    P = 7000 * G * np.sqrt(20.0) / 4
    return P, e, np.array([0.0, 0.0, 1200 * G]) + P * e


def _check_boom(s):
    st = s.static
    P, e, R = _boom_by_hand()
    assert st.drive_force == pytest.approx([P], rel=1e-10)
    assert len(st.joint_forces) == 2
    on = {}
    for g1, g2, point, F in st.joint_forces:   # F acts on g1 and -F on g2
        on[tuple(point)] = F if g1 >= 0 else -F
    # the boom gets R at O; the bob (a pendulum hanging from H) its weight, upwards
    assert np.allclose(on[(0.0, 0.0, 0.0)], R, rtol=1e-10, atol=1e-9 * P)
    assert np.allclose(on[(20.0, 0.0, 0.0)], [0, 0, 500 * G], rtol=1e-10, atol=1e-9 * P)
    # the drive pulls the ground at A toward C
    assert np.allclose(st.node_force[s.model.node_index["A"]], P * e, rtol=1e-10)
    # the weights the boom carries, at their points: its own at the com, T's at T
    pts = sorted((tuple(p), tuple(f)) for _, p, f in st.gravity_points)
    assert np.allclose(np.array([p for p, _ in pts]), [[5, 0, 0], [10, 0, 0], [20, 0, -3]])
    assert np.allclose(np.array([f for _, f in pts]),
                       [[0, 0, -1000 * G], [0, 0, -200 * G], [0, 0, -500 * G]])
    # the drive's reaction on C (the node's force), -P e
    C = s.model.node_index["C"]
    assert np.allclose(st.node_force[C], -P * e, rtol=1e-10, atol=1e-9 * P)
    groups = list(st.point_forces(s.dofs))
    assert len(groups) == 2
    for _, p, f in groups:                     # each rigid group is in equilibrium
        assert np.allclose(f.sum(0), 0, atol=1e-9 * P)
        assert np.allclose(np.cross(p, f).sum(0), 0, atol=1e-8 * P)
    # the tension-carrying members: the bob's spring (horizontal, unloaded), and the
    # drive as a strut of force P between A and C
    spans = list(st.spans())
    assert len(spans) == 2
    assert spans[0][3] == pytest.approx([0.0], abs=1e-9 * P)
    a, b, falls, N = spans[1]
    assert (a.tolist(), b.tolist(), falls.tolist()) == (
        [s.model.node_index["A"]], [C], [1.0])
    assert N == pytest.approx([P], rel=1e-10)
    assert st.beam_force.shape == (0,)
    # a Reuse (the cache of a sweep) gives the same state
    again = statics.solve_static(s.model, reuse=Reuse())
    assert np.allclose(again.u, st.u, rtol=1e-12, atol=1e-15)
    assert again.drive_force == pytest.approx(st.drive_force, rel=1e-12)


def test_boom_on_a_linear_drive_by_hand():
    _check_boom(assemble(load("boom.yaml", BOOM)))


def test_boom_on_a_linear_drive_on_the_sparse_path(monkeypatch):
    monkeypatch.setattr(statics, "STATIC_DENSE_MAX", 0)
    _check_boom(assemble(load("boom.yaml", BOOM)))


SUPPORTED = """cranefe: 1
plane: xz
nodes: {L: [0, 0, 0], H: [4, 0, 3]}
ground: [H]
masses: {L: 1000}
supports: {L: [uz]}
springs:
  - {type: axial, nodes: [L, H], stiffness: 1.0e6}
effects: {sway: false}
"""


@pytest.mark.parametrize("dense_max", [400, 0])
def test_support_reaction_is_the_weight(monkeypatch, dense_max):
    """L moves only along its spring (sway off), e = (0.8, 0, 0.6), and the support
    u_z = 0 stops that: u = 0, the spring carries nothing, and the support's reaction
    (0, 0, 1000 g) balances the weight: the node's force is zero."""
    monkeypatch.setattr(statics, "STATIC_DENSE_MAX", dense_max)
    st = statics.solve_static(load("s.yaml", SUPPORTED))
    assert np.allclose(st.node_force, 0, atol=1e-9)
    assert np.allclose(st.u, 0, atol=1e-15)
    assert st.element_force == pytest.approx([0.0], abs=1e-9)


PAIR = """cranefe: 1
plane: xz
gravity: [{gx}, 0, -9.81]
nodes: {{SA: [0, 0, 10], SB: [2, 0, 10], A: [0, 0, 0], B: [2, 0, 0]}}
ground: [SA, SB]
masses: {{A: 1000, B: 3000}}
ropes:
  ra: {{EA: 1.0e8, path: [SA, A]}}
  rb: {{EA: 1.0e8, path: [SB, B]}}
springs:
  - {{type: axial, nodes: [A, B], stiffness: 1.0e6}}
effects: {{sway: false}}
"""


@pytest.mark.parametrize("dense_max, rtol", [(400, 1e-12), (0, 1e-9)])
def test_a_free_unloaded_direction_stays_unloaded(monkeypatch, dense_max, rtol):
    """Two loads on vertical ropes, tied by a horizontal spring: their common x motion is
    free (sway off: the ropes act along z only) and gravity does not load it. Tensions
    m g, stretch m g L / EA, the spring unloaded. (The sparse path shifts K by 1e-10 of
    its diagonal: tensions to 1e-9.)"""
    monkeypatch.setattr(statics, "STATIC_DENSE_MAX", dense_max)
    m = load("p.yaml", PAIR.format(gx=0))
    st = statics.solve_static(m)
    assert st.element_force == pytest.approx([1000 * G, 3000 * G, 0.0], rel=rtol,
                                             abs=1e-9)
    assert np.allclose(st.rope_tension(), [[1000 * G] * 2, [3000 * G] * 2], rtol=rtol)
    A, B = m.node_index["A"], m.node_index["B"]
    assert np.allclose(st.node_force[[A, B]], 0, atol=1e-5)
    assert np.sort(st.u)[[0, 1]] == pytest.approx([-3000 * G * 10 / 1e8, -1000 * G * 10 / 1e8],
                                                  rel=rtol)


def test_a_loaded_free_direction_is_named_with_its_force():
    """Gravity tilted by 3 m/s^2 along x pushes the pair's free x motion: (1000 + 3000) 3
    N along a unit translation of both."""
    with pytest.raises(ModelError, match=r"^p.yaml: nodes.A: not in static equilibrium: "
                                         r"gravity moves node A x, node B x with nothing to "
                                         r"resist it \(unbalanced 1.2e\+04 N\); support it "
                                         r"with a joint, rope or spring, or fix it$"):
        statics.solve_static(load("p.yaml", PAIR.format(gx=3)))


def test_a_loaded_free_direction_on_the_sparse_path(monkeypatch):
    monkeypatch.setattr(statics, "STATIC_DENSE_MAX", 0)
    with pytest.raises(ModelError, match=r"^p.yaml: not in static equilibrium: gravity "
                                         r"moves a part that nothing restrains; support it "
                                         r"with a joint, rope or spring$"):
        statics.solve_static(load("p.yaml", PAIR.format(gx=3)))


INCLINED = """cranefe: 1
plane: xz
nodes: {{L: [0, 0, 0], S: [2, 0, 10]}}
ground: [S]
masses: {{L: {mass}}}
{element}
effects: {{sway: false}}
"""


@pytest.mark.parametrize("mass", [1000.0, 0.05])
@pytest.mark.parametrize("element, kind, hint", [
    ("ropes:\n  r: {EA: 1.0e8, path: [S, L]}", "ropes", "so that its ropes hang along "
                                                       "gravity "),
    ("springs:\n  - {type: axial, nodes: [L, S], stiffness: 1.0e6}", "springs", "")])
def test_a_node_its_element_cannot_balance_is_named(element, kind, hint, mass):
    """The element along e = (2, 0, 10)/sqrt 104 takes the weight's component along it;
    left: w - (w.e) e = m g (20, 0, -4)/104 (a 50 g load too: every weight counts)."""
    with pytest.raises(ModelError) as err:
        statics.solve_static(load("i.yaml", INCLINED.format(element=element, mass=mass)))
    e = err.value
    assert e.file == "i.yaml" and e.entry == "nodes.L"
    F = mass * G * np.array([20.0, 0.0, -4.0]) / 104
    assert e.message == (f"node 'L' is not in static equilibrium in the reference "
                         f"geometry: its {kind} cannot balance a force of "
                         f"{np.array2string(F, precision=4)} N (its weight is "
                         f"{mass * G:.4g} N); move it {hint}(the reference geometry is the "
                         f"static equilibrium)")
    if mass == 1000.0:
        assert "1886.5385" in e.message             # 4 decimals


def test_a_node_on_a_spring_across_gravity_is_not_in_equilibrium():
    """A horizontal spring cannot carry a weight: nothing moves (u = 0) and the whole
    weight is left."""
    text = INCLINED.format(element="springs:\n  - {type: axial, nodes: [L, S], "
                           "stiffness: 1.0e6}", mass=1000).replace("S: [2, 0, 10]",
                                                                   "S: [2, 0, 0]")
    with pytest.raises(ModelError, match=r"its springs cannot balance a force of "
                                         r"\[    0\.     0\. -9810\.\] N"):
        statics.solve_static(load("i.yaml", text))


SPATIAL = """cranefe: 1
nodes: {L: [0, 0, 0], S: [2, 0, 10], Y: [0, 5, 0]}
ground: [S, Y]
masses: {L: 1000}
ropes:
  r: {EA: 1.0e8, path: [S, L]}
springs:
  - {type: axial, nodes: [L, Y], stiffness: 1.0e6}
effects: {sway: false}
"""


def test_a_node_with_ropes_and_springs_names_both():
    with pytest.raises(ModelError, match=r"^i.yaml: nodes.L: node 'L' is not in static "
                                         r"equilibrium in the reference geometry: its ropes "
                                         r"and springs cannot balance"):
        statics.solve_static(load("i.yaml", SPATIAL))


def test_interior_nodes_of_inclined_ropes_with_mass_are_exempt():
    """A load between a hoist rope and a tag line, both with mass (4 elements each): the
    interior nodes of the inclined ropes carry lateral weight that the straight
    reference cannot balance (sway off: they move along their falls); they are exempt,
    the load itself is in equilibrium."""
    text = """cranefe: 1
plane: xz
nodes: {A: [-6, 0, 8], L: [0, 0, 0], B: [4, 0, -3]}
ground: [A, B]
masses: {L: 1000}
ropes:
  hoist: {EA: 1.0e7, path: [A, L], mass_per_length: 20}
  tag: {EA: 1.0e5, path: [L, B], mass_per_length: 5}
effects: {rope_mass: 4}
"""
    m = load("t.yaml", text)
    st = statics.solve_static(m)
    assert np.allclose(st.node_force[m.node_index["L"]], 0, atol=1e-6)
    assert (st.element_force > 0).all()
COLUMN = """cranefe: 1
plane: xz
nodes: {O: [0, 0, 0], M: [0, 0, 5], T: [0, 0, 10], S: [5, 0, 10]}
ground: [O, S]
masses: {T: 2000}
members:
  c1: {type: beam, nodes: [O, M], E: 2.1e11, A: 1.0e-2, Iy: 2.0e-4, rho: 0}
  c2: {type: beam, nodes: [M, T], E: 2.1e11, A: 1.0e-2, Iy: 2.0e-4, rho: 0}
springs:
  - {type: axial, nodes: [T, S], stiffness: 5.0e4}
effects: {structure: flexible}
"""


@pytest.mark.parametrize("dense_max", [400, 0])
def test_column_axial_force_is_the_load(monkeypatch, dense_max):
    """Each element of the clamped column carries -2000 g (compression); the spring at
    T stays unstretched (its direction is horizontal, the load vertical); the top moves
    down by P L / EA."""
    monkeypatch.setattr(statics, "STATIC_DENSE_MAX", dense_max)
    s = assemble(load("c.yaml", COLUMN))
    st = s.static
    P = 2000 * G
    assert st.beam_force == pytest.approx([-P, -P], rel=1e-10)
    assert st.element_force == pytest.approx([0.0], abs=1e-9 * P)
    T = s.model.node_index["T"]
    uz = st.u[s.dofs.layout.node([T])].ravel()[2]
    assert uz == pytest.approx(-P * 10 / (2.1e11 * 1e-2), rel=1e-10)
    O = s.model.node_index["O"]
    assert np.allclose(st.node_force[T], 0, atol=1e-9 * P)
    assert st.node_force.shape == (4, 3) and O == 0


@pytest.mark.parametrize("dense_max, rtol", [(400, 1e-12), (0, 1e-9)])
def test_massless_ropes_spans_and_a_gravity_tilt_of_round_off_size(monkeypatch, dense_max,
                                                                   rtol):
    """The spans of the two ropes carry m g each, the spring nothing; a tilt of gravity
    of 1e-10 m/s^2 along the free x motion (4e-7 N against 4e4 N of weights) is
    round-off, not a loaded mechanism."""
    monkeypatch.setattr(statics, "STATIC_DENSE_MAX", dense_max)
    m = load("p.yaml", PAIR.format(gx=1e-10))
    st = statics.solve_static(m)
    spans = list(st.spans())
    assert len(spans) == 3
    idx = m.node_index
    for (a, b, falls, N), ends, S in zip(spans, (("SA", "A"), ("SB", "B"), ("A", "B")),
                                         (1000 * G, 3000 * G, 0.0)):
        assert [int(x) for x in a] == [idx[ends[0]]] and [int(x) for x in b] == [idx[ends[1]]]
        assert falls.tolist() == [1.0] and falls.dtype == float
        assert N == pytest.approx([S], rel=rtol, abs=1e-6)
    assert st.beam_force.shape == (0,)


HOIST = """cranefe: 1
plane: xz
nodes: {D: [0, 0, 0], S: [0, 0, 30], B: [0, 0, 10]}
ground: [D, S]
masses: {B: 5000}
drums:
  hoist: {node: D, radius: 0.25, inertia: 100, brake: false,
          motor: {rotor_inertia: 1.0, gear_ratio: 20}}
ropes:
  hoist: {EA: 2.0e7, path: [hoist, S, {node: B, falls: 2}]}
effects: {sway: true}
"""


def test_the_drum_is_held_in_the_static_state():
    """An unbraked drum (drive coupled in the model's effects) is held for statics:
    each of the 2 falls carries m g / 2, and the drum takes the line pull."""
    s = assemble(load("h.yaml", HOIST))
    assert np.allclose(s.static.rope_tension(), [[5000 * G / 2] * 2], rtol=1e-12)
