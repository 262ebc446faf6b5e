"""Kill tests for cranefe/analysis/operation/flexible.py (tools/mutation.py flexible;
docs/mutation.md, operation/flexible.py): the structure's setup - which springs join
it, what it refuses, the static state's rope forces and holding torques - on cases
solved by hand.

The jib is test_mutation_kills_flexible.DIRECT's (planar, one element, L = 12 m,
EI = 2.1e11 x 2e-2 = 4.2e9 N m^2, tip mass rho A L / 2 = 565.2 kg, a 1500 kg hook on a
vertical rope from the tip T). With no axial force in the jib its one cubic element is
exact for a tip load: the tip's bending stiffness, the tip slope condensed, is 3 EI / L^3
(as there).
"""

import numpy as np
import pytest
from test_mutation_kills_flexible import DIRECT
from test_mutation_kills_flexible_chain import CHAIN, DRIVES
from test_operation_flexible import write

from cranefe.analysis.operation.mechanism import Mechanism
from cranefe.analysis.operation.scene import parse
from cranefe.errors import ModelError
from cranefe.model import load

G = 9.81
EI, L = 2.1e11 * 2.0e-2, 12.0
TIP = 7850 * 0.012 * 12 / 2
JIB = dict(IYVAL=2.0e-2, NEL=1, MASS="lumped", GVAL=-G)


def _edit(text, *pairs):
    for a, b in zip(pairs[::2], pairs[1::2]):
        assert a in text, a
        text = text.replace(a, b)
    return text


def test_springs_beside_and_on_the_structure(tmp_path):
    """Two axial springs: first a buffer holding a separate 200 kg load W from the
    ground node B (it does not touch the structure: left to the mechanism), then a tie
    from the tip T up to the ground node E (4 m above T, k = 5e6 N/m: on the
    structure). The tip then carries P = (1500 + 565.2) g on the bending stiffness and
    the tie in parallel: w = P / (3 EI / L^3 + k) (to 1e-9 relative: the tie's tilt by
    the tip's 1e-7 m shortening and the Green terms are 1e-10 of it); the hook's rope
    1500 g."""
    text = _edit(DIRECT, "  HOOK: [12.0, 0.0, 12.0]\n",
                 "  HOOK: [12.0, 0.0, 12.0]\n  E: [12.0, 0.0, 24.0]\n  B: [20.0, 0.0, 12.0]\n"
                 "  W: [20.0, 0.0, 10.0]\n",
                 "ground: [A, D]", "ground: [A, D, E, B]",
                 "masses: {HOOK: 1500}", "masses: {HOOK: 1500, W: 200}")
    text += ("springs:\n  - {name: buffer, type: axial, nodes: [B, W], stiffness: 1.0e4}\n"
             "  - {name: tie, type: axial, nodes: [T, E], stiffness: 5.0e6}\n")
    model = load(write(tmp_path, text, "  duration: 1\n", **JIB))
    mech = Mechanism(model, parse(model))
    assert mech.flex.labels() == ["T.ux", "T.uz"]
    o = mech.nc + mech.nJ
    w = (1500 + TIP) * G / (3 * EI / L**3 + 5.0e6)
    np.testing.assert_allclose(mech.q0[o + 1], -w, rtol=1e-9)
    np.testing.assert_allclose(mech.S0, [1500 * G], rtol=1e-10)
    # without the tie the tip would sink 1.7 times as far
    assert (1500 + TIP) * G / (3 * EI / L**3) > 1.5 * w


def test_a_spring_to_a_massless_block_is_refused(tmp_path):
    """A spring from the tip T to a massless node Z that a rope joins to the hook (a
    massless block, not a load): refused, naming the spring and the model file."""
    text = _edit(DIRECT, "  HOOK: [12.0, 0.0, 12.0]\n",
                 "  HOOK: [12.0, 0.0, 12.0]\n  Z: [12.0, 0.0, 16.0]\n",
                 "path: [T, HOOK]}", "path: [Z, HOOK]}")
    text += "springs:\n  - {name: link, type: axial, nodes: [T, Z], stiffness: 3.0e5}\n"
    path = write(tmp_path, text, "  duration: 1\n", **JIB)
    model = load(path)
    with pytest.raises(ModelError) as exc:
        Mechanism(model, parse(model))
    msg = str(exc.value)
    assert "spring 'link' joins the elastic structure to a load or a massless node" in msg
    assert msg.startswith(f"{path.parent / ('model_' + path.name)}: springs.link: "), msg


def test_two_falls_on_one_drum_hold_a_light_hook(tmp_path):
    """Two ropes from the drum over the tip T down to one 0.1 kg hook (two falls): by
    symmetry each carries m g / 2 = 0.49 N, both taut, and the drum's holding torque is
    r (S1 + S2) = 0.2 m g (to 1e-7: S = EA (L - L0) / L0 with a stretch of 2e-7 m on
    8 m, so one ulp of the 8 m length is 4e-9 of S)."""
    text = _edit(DIRECT, "masses: {HOOK: 1500}", "masses: {HOOK: 0.1}",
                 "  hoist_rope: {EA: 2.0e7, path: [T, HOOK]}",
                 "  fall_1: {EA: 2.0e7, path: [hoist, T, HOOK]}\n"
                 "  fall_2: {EA: 2.0e7, path: [hoist, T, HOOK]}")
    model = load(write(tmp_path, text, "  duration: 1\n", **JIB))
    mech = Mechanism(model, parse(model))
    np.testing.assert_allclose(mech.S0, [0.05 * G, 0.05 * G], rtol=1e-7)
    assert mech.taut0.tolist() == [True, True]
    np.testing.assert_allclose(mech.hold_torque, [0.2 * 0.1 * G], rtol=1e-7)


def test_a_released_rotation_is_refused(tmp_path):
    """The chain scene's boom with its rotation ry released at the tip, where no other
    beam meets: that rotation has no stiffness; refused, naming the members and the
    model file."""
    text = _edit(CHAIN, "         mass: lumped}\n  hanger",
                 "         mass: lumped, releases: {T: [ry]}}\n  hanger")
    path = write(tmp_path, text, DRIVES)
    model = load(path)
    with pytest.raises(ModelError) as exc:
        Mechanism(model, parse(model))
    msg = str(exc.value)
    assert "a rotation of the elastic structure has no stiffness" in msg
    assert f"{path.parent / ('model_' + path.name)}: members:" in msg, msg


ROD = """cranefe: 1
name: a thin steel rod
plane: xz
gravity: [0, 0, 0]
nodes:
  A: [0.0, 0, 0.0]
  T: [1.0, 0, 0.0]
ground: [A]
members:
  rod: {type: beam, nodes: [A, T], E: 2.1e+11, A: 3.5e-6, Iy: 1.0e-12, rho: 7850,
        elements: 1, mass: lumped}
"""


def test_a_soft_rod_is_solved(tmp_path):
    """A 1.9 mm steel rod, 1 m long (EI = 0.21 N m^2: its tip rotation's stiffness
    4 EI / L = 0.84 N m, below 1): solved, not refused; at rest its tangent is
    diag(EA / L, 3 EI / L^3) (to 1e-12: round-off of the condensation)."""
    model = load(write(tmp_path, ROD, "  duration: 1\n"))
    mech = Mechanism(model, parse(model))
    f = mech.flex
    assert f.labels() == ["T.ux", "T.uz"]
    np.testing.assert_allclose(np.diag(f.K)[f.nu:], [4 * 0.21])
    Kt = f.strain(np.zeros(2))[2]
    np.testing.assert_allclose(Kt, np.diag([2.1e11 * 3.5e-6, 3 * 0.21]), rtol=1e-12,
                               atol=1e-12 * 0.63)


def _refusals():
    """(model text, analysis, substitutions, entry, words) of every refusal of the
    module that a scene reaches: test_mutation_kills_flexible's six on its two-bar truss,
    and the drives' and frames' three."""
    import test_mutation_kills_flexible as base
    from test_operation_flexible import ROTOR
    out = []
    for edit, words, entry in base.test_what_the_structure_refuses.pytestmark[0].args[1]:
        text = base.TRUSS2
        for a, b in zip(edit[::2], edit[1::2]):
            text = _edit(text, a, b)
        # (the support's entry, which the base test leaves out, is supports.T)
        out.append((text, "  duration: 1\n", {}, entry or "supports.T", words))
    rotor = _edit(ROTOR, "  T: [10.0, 0, 0]\n", "  T: [10.0, 0, 0]\n  K: [5.0, 0, 0]\n",
                  "joints:\n", "  trolley: {mass: 10, com: [5, 0, 0], inertia: [1, 1, 1], "
                  "nodes: [K]}\njoints:\n  - {name: travel, type: slider, bodies: [hub, "
                  "trolley], at: K, axis: [1, 0, 0], range: [0, 9]}\n")
    # the hub spun by a profile (the blade on the hub's frame) and the trolley driven
    # along it: the trolley's joint moves a body on a frame that carries the blade
    out.append((rotor, "  duration: 1\n  drives:\n    s: {hinge: spin, profile: {type: "
                "table, speed: [[0, 0], [1, 0.5]]}}\n    t: {slider: travel, profile: {type: "
                "trapezoid, distance: 1, v_max: 1, a_max: 1}}\n", dict(NEL=2),
                "analysis.drives.t", "use structure: rigid, or anchor the elastic members "
                "on the moving body"))
    out.append((rotor, "  duration: 1\n  drives:\n    s: {hinge: spin, torque: 1.0}\n",
                dict(NEL=2), "analysis.drives.s", "prescribe the joint's motion with a "
                "profile, or use structure: rigid"))
    chain = _edit(CHAIN, "nodes: [K]}", "nodes: [K, N]}", "inertia: [1, 1, 1], nodes: [N]}",
                  "inertia: [1, 1, 1], nodes: []}")
    out.append((chain, DRIVES, {}, "members.hanger", "members 'boom' and 'hanger' join "
                "nodes of bodies that move relative to each other"))
    return out


@pytest.mark.parametrize("k", range(9))
def test_every_refusal_names_the_file_and_the_entry(tmp_path, k):
    """Each refusal's message starts with the file that holds the entry (the scene's
    for a drive, the model's for members, masses, springs, supports and joints) and the
    entry ('FILE: ENTRY: ...', the ModelError contract) and says what to do."""
    text, analysis, subs, entry, words = _refusals()[k]
    path = write(tmp_path, text, analysis, **subs)
    model = load(path)
    with pytest.raises(ModelError) as exc:
        Mechanism(model, parse(model))
    msg = str(exc.value)
    file = path if entry.startswith("analysis.") else path.parent / f"model_{path.name}"
    assert msg.startswith(f"{file}: {entry + ': ' if entry else ''}"), msg
    assert words in msg, msg


LFRAME = """cranefe: 1
name: an L-shaped bracket in 3D
gravity: [0, 0, -9.81]
nodes:
  A: [0.0, 0, 0]
  B: [4.0, 0, 0]
  T: [4.0, 3.0, 0]
ground: [A]
masses: {T: 100}
members:
  arm: {type: beam, nodes: [A, B], E: 2.1e+11, G: 8.0e+10, A: 0.01, Iy: 1.0e-3,
        Iz: 1.0e-3, J: 2.0e-3, rho: 7850, orientation: [0, 0, 1], elements: 1,
        mass: lumped}
  hand: {type: beam, nodes: [B, T], E: 2.1e+11, G: 8.0e+10, A: 0.01, Iy: 1.0e-3,
         Iz: 1.0e-3, J: 2.0e-3, rho: 7850, orientation: [0, 0, 1], elements: 1,
         mass: lumped}
"""


def test_an_l_bracket_twists_its_arm(tmp_path):
    """An L-shaped bracket clamped at A (arm A-B along x, a = 4 m; hand B-T along y,
    b = 3 m), both nodes elastic, under its lumped weights P_B = rho A (a + b) / 2 g at B
    and P_T = (100 + rho A b / 2) g at T. T sinks by
        P_T (a^3 / (3 EI) + b^2 a / (GJ) + b^3 / (3 EI)) + P_B a^3 / (3 EI)
    (the arm's bending, the arm's twist by the moment P_T b, the hand's bending; the
    arm's slope at B turns the hand about its own axis: no sinking), one cubic element
    per beam being exact for end loads (to 1e-6 relative: the Green strain's quartic
    terms, (8e-4 / 3)^2 of it). Needs the torsion of the elastic nodes: the arm's twist
    is 45 % of it."""
    model = load(write(tmp_path, LFRAME, "  duration: 1\n"))
    mech = Mechanism(model, parse(model))
    assert mech.flex.labels() == ["B.ux", "B.uy", "B.uz", "T.ux", "T.uy", "T.uz"]
    EI3, GJ = 3 * 2.1e11 * 1.0e-3, 8.0e10 * 2.0e-3
    PB, PT = 7850 * 0.01 * 7 / 2 * G, (100 + 7850 * 0.01 * 3 / 2) * G
    twist = PT * 9 * 4 / GJ
    w = PT * (64 / EI3 + twist / PT + 27 / EI3) + PB * 64 / EI3
    o = mech.nc + mech.nJ
    np.testing.assert_allclose(mech.q0[o + 5], -w, rtol=1e-6)
    assert twist > 0.4 * w


def test_members_all_on_the_ground_leave_no_structure(tmp_path):
    """The jib with its tip T on the ground as well: no elastic node, so no elastic
    structure (the scene runs rigid: no elastic coordinates), the hook's rope 1500 g."""
    text = _edit(DIRECT, "ground: [A, D]", "ground: [A, D, T]")
    model = load(write(tmp_path, text, "  duration: 1\n", **JIB))
    mech = Mechanism(model, parse(model))
    assert mech.flex is None and mech.nu == 0
    np.testing.assert_allclose(mech.S0, [1500 * G], rtol=1e-10)
