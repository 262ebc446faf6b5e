"""Kill tests for cranefe/assembly/inertia.py (tools/mutation.py assembly; docs/testing.md,
"Mutation testing"): what a body carries, by hand.

- A compound pendulum: an arm hinged to the ground at O, hanging along -z, carrying its
  own mass (m_b, I_b at the centre c_b), a point mass with rotary inertia at its tip T
  (parallel axes: `_BodyMass.add`), and, with `structure: rigid`, a member rod O-T whose
  mass joins the arm (`_rigid_members`: m_r = rho A l at the rod's middle, m_r l^2 / 12
  about it). Small swings about the hinge: w^2 = g sum(m_k d_k) / I_O with
  I_O = sum(I_k + m_k d_k^2), d_k the depth of each centre below O. The gravity load on
  the arm (its weights at their points) gives the pendulum's stiffness g sum(m_k d_k):
  with the point mass or the rod left out of either, w changes.
- A free node's point mass (`_point_masses`): its block m I and its weight m g.
- A linear drive's rotor (`_linear_drives`): the reduced mass J (i/R)^2 along the
  drive's direction, J (i/R)^2 e e^T on each end node (and -e e^T between them),
  from `mass_and_gravity` directly (a modal analysis holds the drive: the rotor does not
  turn there).

- A vertical bar with mass (a truss member with consistent or lumped mass, a rope with
  mass in one element, consistent or lumped) holding a load (`_trusses`,
  `_rope_elements`, `element_materials`): its frequency and static force by hand.

Tolerance 1e-12 relative: a one-coordinate eigenvalue and matrix entries of a few terms.
"""

import numpy as np
import pytest

from cranefe.analysis.modal import modes
from cranefe.assembly import mass_and_gravity
from cranefe.coordinates import build_dofs
from cranefe.errors import ModelError
from cranefe.model import load
from cranefe.statics import solve_static

G = 9.81

ARM = """cranefe: 1
plane: xz
nodes: {{O: [0, 0, 0], T: [0, 0, -4], Q: [0, 0, -1]}}
ground: [O]
bodies:
  arm: {{mass: 300, com: [0, 0, -2], inertia: 50, nodes: [T, Q]}}
masses: {{T: {{mass: 80, inertia: 7}}}}
joints:
  - {{type: hinge, bodies: [ground, arm], at: O}}
{members}
effects: {{sway: true}}
"""

ROD = """members:
  rod: {type: truss, nodes: [O, T], E: 2.1e11, A: 1.0e-3, rho: 7850}"""


def _pendulum_w2(rod):
    mb, Ib, db = 300.0, 50.0, 2.0
    mp, Ip, dp = 80.0, 7.0, 4.0
    num = mb * db + mp * dp
    I_O = Ib + mb * db**2 + Ip + mp * dp**2
    if rod:
        l = 4.0
        mr = 7850 * 1.0e-3 * l
        num += mr * l / 2
        I_O += mr * l**2 / 12 + mr * (l / 2) ** 2
    return G * num / I_O


@pytest.mark.parametrize("rod", [False, True])
def test_compound_pendulum_with_a_point_mass_and_a_rigid_member(rod):
    r = modes(load("arm.yaml", ARM.format(members=ROD if rod else "")))
    assert r.omega.shape == (1,)
    assert r.omega[0] ** 2 == pytest.approx(_pendulum_w2(rod), rel=1e-12)


def test_a_rigid_member_across_two_bodies_is_an_error():
    text = ARM.format(members=ROD).replace(
        "nodes: [T, Q]}", "nodes: [T, Q]}\n  box: {mass: 10, com: [0, 0, -6], inertia: 1, "
        "nodes: [U]}").replace("Q: [0, 0, -1]}", "Q: [0, 0, -1], U: [0, 0, -6]}").replace(
        "  - {type: hinge, bodies: [ground, arm], at: O}",
        "  - {type: hinge, bodies: [ground, arm], at: O}\n"
        "  - {type: hinge, bodies: [arm, box], at: T}").replace(
        "rod: {type: truss, nodes: [O, T]", "rod: {type: truss, nodes: [Q, U]")
    with pytest.raises(ModelError, match=r"^arm.yaml: members.rod: with structure: rigid a "
                                         r"member's nodes must all be carried by one body or "
                                         r"the ground \(found nodes on different carriers\); "
                                         r"put them on one body or use effects: "
                                         r"\{structure: flexible\}$"):
        modes(load("arm.yaml", text))


def test_a_rigid_member_through_a_joint_node_joins_the_body_and_one_on_the_ground_none():
    """The rod O-T: O is the hinge's node (ground and arm), T the arm's: the rod joins the
    arm (the pendulum above). A rod between two ground nodes adds nothing."""
    text = ARM.format(members=ROD.replace("nodes: [O, T]", "nodes: [O, G2]")).replace(
        "Q: [0, 0, -1]}", "Q: [0, 0, -1], G2: [3, 0, 0]}").replace("ground: [O]",
                                                                    "ground: [O, G2]")
    r = modes(load("arm.yaml", text))
    assert r.omega[0] ** 2 == pytest.approx(_pendulum_w2(False), rel=1e-12)


FREE_NODE = """cranefe: 1
plane: xz
nodes: {S: [0, 0, 10], L: [0, 0, 0], A: [-3, 0, 0], C: [2, 0, 2]}
ground: [S, A]
masses: {L: 700}
bodies:
  b: {mass: 100, com: [2, 0, 2], inertia: 5, nodes: [C]}
joints:
  - {type: hinge, bodies: [ground, b], at: S}
ropes:
  r: {EA: 1.0e8, path: [S, L]}
linear_drives:
  d: {nodes: [A, C], pinion_radius: 0.25, gear_ratio: 50, rotor_inertia: 0.4}
effects: {sway: false}
"""


def test_point_mass_on_a_free_node_and_a_linear_drive_rotor_in_the_mass_matrix():
    m = load("f.yaml", FREE_NODE)
    dofs = build_dofs(m, m.effects)
    M, f, points = mass_and_gravity(m, dofs, m.effects)
    M = M.toarray()
    lay = dofs.layout
    L = lay.node([m.node_index["L"]]).ravel()
    C = lay.node([m.node_index["C"]]).ravel()
    A = lay.node([m.node_index["A"]]).ravel()
    assert np.allclose(M[np.ix_(L, L)], 700 * np.eye(3), rtol=1e-15)
    assert np.allclose(f[L], [0, 0, -700 * G], rtol=1e-15)
    # the rotor: J (i/R)^2 = 0.4 * 200^2 = 16000 kg along e = (5, 0, 2)/sqrt 29
    e = np.array([5.0, 0.0, 2.0]) / np.sqrt(29.0)
    jm = 0.4 * (50 / 0.25) ** 2
    assert np.allclose(M[np.ix_(C, C)], jm * np.outer(e, e), rtol=1e-12, atol=1e-9)
    assert np.allclose(M[np.ix_(A, C)], -jm * np.outer(e, e), rtol=1e-12, atol=1e-9)
    assert np.allclose(M[np.ix_(A, A)], jm * np.outer(e, e), rtol=1e-12, atol=1e-9)
    # the body's weight at its centre, in the gravity points
    assert len(points) == 1
    b, p, F = points[0]
    assert b == 0 and np.allclose(p, [2, 0, 2]) and np.allclose(F, [0, 0, -100 * G])


CANTILEVER = """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {O: [0, 0, 0], T: [2, 0, 0]}
ground: [O]
masses: {T: 500}
members:
  arm: {type: beam, nodes: [O, T], E: 2.0e11, G: 8.0e10, A: 1.0e-2, Iy: 1.0e-5,
        Asz: 1.0e-4, rho: 0}
effects: {structure: flexible}
"""


def test_timoshenko_cantilever_with_a_tip_mass():
    """A massless Timoshenko cantilever (shear area 1e-4 m^2, small on purpose: the
    shear compliance L/(G As) = 2.5e-7 m/N against L^3/(3 EI) = 1.33e-6 m/N) under a tip
    mass M, gravity off: w^2 = 1 / (M (L^3/(3 EI) + L/(G As))) across, EA/(L M) along
    (one element holds the static Timoshenko solution exactly: 1e-12)."""
    L, E, G_, A, I, As, M = 2.0, 2.0e11, 8.0e10, 1.0e-2, 1.0e-5, 1.0e-4, 500.0
    r = modes(load("c.yaml", CANTILEVER))
    flex = L**3 / (3 * E * I) + L / (G_ * As)
    assert np.allclose(np.sort(r.omega**2), [1 / (M * flex), E * A / (L * M)], rtol=1e-12)


BAR = """cranefe: 1
plane: xz
nodes: {{O: [0, 0, 10], L: [0, 0, 0]}}
ground: [O]
masses: {{L: 500}}
{element}
effects: {{sway: false{extra}}}
"""


@pytest.mark.parametrize("element, extra, share", [
    ("members:\n  bar: {type: truss, nodes: [O, L], E: 2.0e11, A: 1.0e-3, rho: 7850}",
     ", structure: flexible", 1 / 3),
    ("members:\n  bar: {type: truss, nodes: [O, L], E: 2.0e11, A: 1.0e-3, rho: 7850, "
     "mass: lumped}", ", structure: flexible", 1 / 2),
    ("ropes:\n  r: {EA: 2.0e8, path: [O, L], mass_per_length: 7.85}", "", 1 / 3),
    ("ropes:\n  r: {EA: 2.0e8, path: [O, L], mass_per_length: 7.85}",
     ", rope_mass: 1, rope_mass_matrix: lumped", 1 / 2)])
def test_a_bar_with_mass_under_a_load_one_element(element, extra, share):
    """A vertical bar (truss member or rope with mass, one element, EA = 2e8 N, 78.5 kg)
    holding 500 kg: with the top fixed the element's consistent mass puts mu L / 3 on the
    free end (lumped: mu L / 2), so w^2 = (EA / L) / (M + share mu L) exactly; its
    gravity load mu L g / 2 per node (both forms), so the static force in the element is
    (M + mu L / 2) g."""
    text = BAR.format(element=element, extra=extra)
    if "rope_mass: 1" not in extra and "ropes" in element:
        text = text.replace("sway: false", "sway: false, rope_mass: 1")
    model = load("bar.yaml", text)
    mL = 7850 * 1.0e-3 * 10
    r = modes(model)
    assert r.omega[0] ** 2 == pytest.approx(2.0e8 / 10 / (500 + share * mL), rel=1e-12)
    st = solve_static(model)
    assert st.element_force == pytest.approx([(500 + mL / 2) * G], rel=1e-12)
