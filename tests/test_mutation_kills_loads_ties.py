"""Kill tests for cranefe/analysis/loads/analysis.py (tools/mutation.py loads_analysis;
docs/mutation.md, its section): two choices the other kill tests never put to the
test, each on a small configuration with values by hand:

- phi1's worst mass is the one with the largest swing either way, max(upper - 1,
  1 - lower), not the largest upward or downward peak alone: a balanced arm (a jib and
  its counterweight on either side of the pivot) whose angular acceleration peaks
  unequally up and down, so that the two ends' worst sides differ;
- the suspension node of phi5 of a hinge: the node with the most falls to the hanging
  masses, never a ground node (a tag line's anchor), the falls of several ropes to one
  node added; two nodes with the most falls are refused (ModelError);
- and the refusal of unknown `only=` names, two of them on a scene with two drives (the
  separators of both lists).
"""

from types import SimpleNamespace

import numpy as np
import pytest

import cranefe
from cranefe.analysis.loads.analysis import _phi1, crane_masses, suspension_node
from cranefe.errors import ModelError
from cranefe.model.load import load
from cranefe.system import assemble

G = 9.81

# ------------------------------------------------------------- phi1's worst mass

ARM = """cranefe: 1
name: a balanced arm
plane: xz
nodes:
  O: [0.0, 0.0, 0.0]
  A: [10.0, 0.0, 0.0]
  B: [-8.0, 0.0, 0.0]
ground: [O]
masses: {A: 1000, B: 3000}
bodies:
  arm: {mass: 0.0, com: [0.0, 0.0, 0.0], inertia: [1.0e3, 1.0e3, 1.0e3], nodes: [A, B]}
joints:
  - {name: pivot, type: hinge, bodies: [ground, arm], at: O, axis: [0, 1, 0]}
springs:
  - {name: arm_spring, type: rotational, bodies: [ground, arm], at: O, axis: [0, 1, 0],
     stiffness: 1.0e7}
"""

# the arm's angular velocity (rad/s) every 0.1 s; np.gradient's differences (central
# inside, one-sided at the ends) give its angular acceleration c [0, 10, 5, -5, 0, 0]:
# the largest G / 100 at t = 0.1 s, the lowest -G / 200 at t = 0.3 s
TIMES = np.arange(6) * 0.1
C = G / 1000
THETA_DOT = C * np.array([0.0, 0.0, 2.0, 1.0, 1.0, 1.0])


def test_phi1_worst_mass_is_the_largest_swing_either_way(tmp_path):
    """A massless arm turning about the y axis through O with 1 t at A (x = 10 m) and
    3 t at B (x = -8 m): a point at x rises at -x theta' (omega x r = (0, theta', 0) x
    (x, 0, 0) = (0, 0, -x theta')), so A's upward acceleration is -10 theta'' and B's
    +8 theta''. With theta'' between -G/200 and G/100 (TIMES, THETA_DOT):
    A: upper 1 + 10/200 = 1.05 (at 0.3 s), lower 1 - 10/100 = 0.90: swings 0.10 down;
    B: upper 1 + 8/100 = 1.08 (at 0.1 s), lower 1 - 8/200 = 0.96: swings 0.08 up.
    The worst mass is A (0.10 > 0.08) and phi1 its upper 1.05, though B's upward peak
    is the larger; with the motion reversed (theta'' between -G/100 and G/200) A swings
    0.10 up (upper 1.10, lower 0.95) and B 0.08 down (1.04, 0.92): A again, though B's
    downward peak is the larger. The whole crane: (1 t (-10) + 3 t (8)) / 4 t = 3.5
    theta''. Exact but for rounding (1e-12)."""
    (tmp_path / "arm.yaml").write_text(ARM)
    model = load(str(tmp_path / "arm.yaml"))
    names, mass, rows = crane_masses(model, assemble(model).dofs)
    assert names == ["A", "B"] and list(mass) == [1000.0, 3000.0]
    np.testing.assert_allclose(rows[0][:, 0], [0.0, 0.0, -10.0], atol=1e-12)
    np.testing.assert_allclose(rows[1][:, 0], [0.0, 0.0, 8.0], atol=1e-12)
    for sign, a, b, whole in ((1, (1.05, 0.90, 0.3), (1.08, 0.96, 0.1), (1.035, 0.9825)),
                              (-1, (1.10, 0.95, 0.1), (1.04, 0.92, 0.3), (1.0175, 0.965))):
        res = SimpleNamespace(times=TIMES, v=sign * THETA_DOT[:, None])
        p = _phi1(model, res, G, "lift-off")
        for name, (up, low, when), m in (("A", a, 1000.0), ("B", b, 3000.0)):
            got = p["by_mass"][name]
            assert got["upper"] == pytest.approx(up, rel=1e-12), (sign, name)
            assert got["lower"] == pytest.approx(low, rel=1e-12), (sign, name)
            assert got["time_upper_s"] == pytest.approx(when, abs=1e-12)
            assert got["mass_kg"] == m
        assert p["mass"] == "A", sign
        assert p["value"] == pytest.approx(a[0], rel=1e-12)
        assert p["lower"] == pytest.approx(a[1], rel=1e-12)
        assert p["peak_time_s"] == pytest.approx(a[2], abs=1e-12)
        assert p["whole_crane"]["upper"] == pytest.approx(whole[0], rel=1e-12)
        assert p["whole_crane"]["lower"] == pytest.approx(whole[1], rel=1e-12)


# --------------------------------------------------------- the suspension node

JIB = """cranefe: 1
name: a slewing jib
nodes:
  O: [0.0, 0.0, 0.0]
  W: [-5.0, 0.0, 0.0]
  M: [5.0, 0.0, 15.0]
  TIP: [10.0, 0.0, 15.0]
  L: [10.0, 0.0, 5.0]
ground: [O, W]
masses: {L: 2000}
bodies:
  jib: {mass: 3000, com: [5.0, 0.0, 7.5], inertia: [1.0e5, 1.0e5, 1.0e5], nodes: [M, TIP]}
joints:
  - {name: slewing, type: hinge, bodies: [ground, jib], at: O, axis: [0, 0, 1]}
springs:
  - {name: slewing_gear, type: rotational, bodies: [ground, jib], at: O,
     axis: [0, 0, 1], stiffness: 1.0e9}
ropes:
"""


def jib(tmp_path, *ropes):
    path = tmp_path / "jib.yaml"
    path.write_text(JIB + "".join(f"  {r}\n" for r in ropes))
    return load(str(path)), str(path)


TAG = "tag: {EA: 1.0, path: [W, L]}"                  # to the ground anchor W
HOIST1 = "hoist: {EA: 5.0e7, path: [TIP, L]}"
HOIST2 = "hoist: {EA: 5.0e7, path: [TIP, {node: L, falls: 2}]}"
AUX1 = "aux: {EA: 5.0e7, path: [M, L]}"


def test_the_suspension_node_is_never_a_ground_anchor(tmp_path):
    """A tag line from the load L to the ground anchor W, listed first, beside a hoist
    rope of as many falls (one) from the tip: the load hangs from the tip (W cannot
    move with the slew; taken as the suspension point it made phi5's lever W's radius,
    5 m, instead of the tip's 10 m)."""
    model, _ = jib(tmp_path, TAG, HOIST1)
    assert suspension_node(model, ["L"]) == model.node_index["TIP"]
    model, _ = jib(tmp_path, TAG)                     # held by the tag line alone
    assert suspension_node(model, ["L"]) is None


@pytest.mark.parametrize("ropes", [(AUX1, HOIST2), (HOIST2, AUX1)])
def test_the_suspension_node_has_the_most_falls(tmp_path, ropes):
    """An auxiliary rope of one fall from M and the hoist rope of two falls from the
    tip, in either order: the tip (2 falls against 1)."""
    model, _ = jib(tmp_path, *ropes)
    assert suspension_node(model, ["L"]) == model.node_index["TIP"]


def test_the_falls_of_several_ropes_to_one_node_add_up(tmp_path):
    """Two ropes of one fall each from the tip and one fall from M: the tip (2 falls
    against 1; counted per span, the two nodes would tie and be refused)."""
    model, _ = jib(tmp_path, AUX1, HOIST1, "hoist_b: {EA: 5.0e7, path: [TIP, L]}")
    assert suspension_node(model, ["L"]) == model.node_index["TIP"]


def test_two_suspension_nodes_with_the_most_falls_are_refused(tmp_path):
    """One fall from M and one from the tip: the suspension point (phi5's lever) is
    ambiguous, refused with the model file, its ropes entry, both nodes and ropes."""
    model, path = jib(tmp_path, AUX1, HOIST1)
    with pytest.raises(ModelError) as err:
        suspension_node(model, ["L"])
    e = err.value
    assert e.file == path and e.entry == "ropes"
    assert e.message == (
        "the hanging masses hang from M and TIP by 1 falls each (ropes aux, hoist), so "
        "phi5 of a hinge has no single suspension point; reeve the load to one node "
        "(e.g. a path ending [.., TIP, {node: LOAD, falls: 2}]) or give one node more "
        "falls")


def test_phi5_of_a_slew_with_a_tag_line_uses_the_tip(tmp_path):
    """The slewing jib of tests/test_mutation_kills_loads_configs.py (the load 10 m
    below the tip at radius 10 m, one fall) with a tag line from the load to a ground
    anchor 5 m from the slewing axis, listed first: phi5's rigid-body acceleration is
    the tip's radius x the angular acceleration, 10 m x 0.05 rad/s^2 = 0.5 m/s^2, and
    the rigid-body force 2 t x 0.5 (exact: 1e-12). The anchor was taken for the
    suspension point (0.25 m/s^2, phi5 doubled)."""
    from test_mutation_kills_loads_configs import HUB, RADIUS, SLEW
    anchor = HUB + [-5.0, 0.0, 0.0]
    text = (SLEW.replace("ground: [O]", "ground: [O, W]")
            .replace("  O:   ", f"  W:   {anchor.tolist()}\n  O:   ")
            .replace("ropes:\n", "ropes:\n  tag: {EA: 1.0, path: [W, L]}\n"))
    (tmp_path / "slew.yaml").write_text(text)
    omega, ramp = 0.1, 2.0
    path = tmp_path / "s.yaml"
    path.write_text("cranefe: 1\nscene: t\nmodel: slew.yaml\nanalysis:\n  type: loads\n"
                    "  hoist: {speed: 0.2}\n  drives:\n"
                    f"    slewing: {{v_max_deg: {float(np.degrees(omega))!r}, "
                    f"ramp: {ramp!r}, jerk_time: 0, distance_deg: 20.0}}\n")
    p = cranefe.loads(str(path), only=["slewing"]).factors["phi5"]["slewing"]
    assert p["acceleration"] == pytest.approx(RADIUS * omega / ramp, rel=1e-12)
    assert p["rigid_body_force_N"] == pytest.approx(2000 * RADIUS * omega / ramp,
                                                    rel=1e-12)


def test_two_unknown_only_names_on_a_scene_with_two_drives(tmp_path):
    """The cart (hoist drum and a travel move) asked for phi9 and a slewing it does not
    have: both names and both drives listed, each list comma-separated; refused before
    any run."""
    from test_mutation_kills_loads_analysis import CART
    (tmp_path / "cart.yaml").write_text(CART)
    path = tmp_path / "s.yaml"
    path.write_text("cranefe: 1\nscene: t\nmodel: cart.yaml\nanalysis:\n  type: loads\n"
                    "  hoist: {speed: 0.2}\n  drives:\n"
                    "    travel: {v_max: 0.5, ramp: 2.0, jerk_time: 0, distance: 6.0}\n")
    with pytest.raises(ModelError) as err:
        cranefe.loads(str(path), only=["slewing", "phi2", "phi9"])
    assert err.value.message == ("unknown factor or drive 'phi9', 'slewing' in only=; use "
                                 "phi1-phi7 or a drive: hoist, travel")
    assert err.value.entry == "only" and err.value.file == str(path)
