"""Kill tests for the setup of cranefe/analysis/operation/mechanism.py (issue 20, mutation
testing; docs/mutation.md, mechanism.py's section): which node each point mass hangs
from, the spans' reference lengths, the coordinate directions of several masses, which
body carries a node listed on two bodies, and every refusal's whole text with the file
and entry it names (an entry of the model, such as nodes.H, names the model file; one of
the scene, such as analysis.drives.d or effects.damping, the scene file).

Hand values: the hanging node is the other end of the mass's span most nearly against
gravity (largest cosine d . up / |d|); span lengths from the coordinates; with sway on
in a plane xz each mass has the coordinates x and z, E = blocks of [[1, 0], [0, 0],
[0, 1]].
"""

import numpy as np
import pytest
from test_mutation_kills_mechanism import (ARM, BRIDGE, SLEWING, TROLLEY, TROLLEY_DRIVE,
                                           _count, _dir, _scene_mech)
from test_operation_massless import BLOCK

from cranefe.errors import ModelError

# Three masses below the ground node P: H (1000 kg) on a short vertical rope and a
# symmetric V of two long ones (one written from the mass upwards), I (500 kg) on a rope
# written from I up to H, J (200 kg) below I. Every node below z = 0, so that a sum of
# two positions instead of a difference points elsewhere.
CHAIN = """cranefe: 1
name: three masses
plane: xz
nodes:
  P: [0, 0, -2]
  L: [-3, 0, 6]
  R: [3, 0, 6]
  H: [0, 0, -4]
  I: [0, 0, -6]
  J: [0, 0, -7]
ground: [P, L, R]
masses: {H: 1000, I: 500, J: 200}
ropes:
  v: {EA: 1.0e8, path: [P, H]}
  left: {EA: 1.0e7, path: [H, L]}
  right: {EA: 1.0e7, path: [R, H]}
  a: {EA: 1.0e8, path: [I, H]}
  b: {EA: 1.0e8, path: [I, J]}
"""


def _names(mech, nodes):
    return [mech.model.node_names[i] for i in nodes]


def test_three_masses_hang_from_the_node_most_nearly_above():
    """H hangs from P (cosine 1; the V's ropes 10 / sqrt(109) = 0.958, I below: -1),
    I from H (up) not J (down), J from I; spans in the ropes' order with their lengths;
    E maps each mass's (x, z) into its (x, y, z) block."""
    mech = _scene_mech(CHAIN, "  duration: 1\n")
    assert _names(mech, mech.free) == ["H", "I", "J"]
    assert _names(mech, mech.hang) == ["P", "H", "I"]
    assert _names(mech, mech.span_a) == ["P", "H", "R", "I", "I"]
    assert _names(mech, mech.span_b) == ["H", "L", "H", "H", "J"]
    np.testing.assert_allclose(mech.span_ref, [2, np.sqrt(109), np.sqrt(109), 2, 1],
                               rtol=1e-15)
    block = np.array([[1.0, 0.0], [0.0, 0.0], [0.0, 1.0]])
    E = np.zeros((9, 6))
    for k in range(3):
        E[3 * k:3 * k + 3, 2 * k:2 * k + 2] = block
    assert mech.nc == 6 and np.array_equal(mech.E, E)
    np.testing.assert_allclose(mech.M, [1000, 1000, 500, 500, 200, 200], rtol=0)
    assert mech.qx_ref.tolist() == [0, -4, 0, -6, 0, -7]


def test_a_node_on_two_bodies_rides_on_the_deeper_one():
    """The trolley's rope node K listed on the bridge too (the bridge given after the
    trolley): it is carried by the trolley (deeper in the tree: ground - bridge -
    trolley), so it moves with the trolley's travel, not with the bridge."""
    bridge = "  bridge: {mass: 2000, com: [0, 0, 10], inertia: [10, 10, 10], nodes: [B]}\n"
    assert bridge in BRIDGE
    # the trolley listed first, so that the deeper body wins, not the later one
    text = BRIDGE.replace(bridge, "").replace(
        "joints:", bridge.replace("nodes: [B]}", "nodes: [B, K]}") + "joints:")
    mech = _scene_mech(text, "  duration: 2\n  drives:\n    t: {slider: travel, profile: "
                             "{type: table, speed: [[0, 0.5], [2, 0.5]]}}\n")
    bridge, trolley = ([b.name for b in mech.model.bodies].index(n)
                       for n in ("bridge", "trolley"))
    K = mech.model.node_names.index("K")
    assert mech.carrier[K] == trolley != bridge
    X = mech.kinematics(1.0)[0]
    np.testing.assert_allclose(X[K], [1.5, 0, 10], rtol=0, atol=1e-12)


def _refusal(text, analysis, effects="{}"):
    with pytest.raises(ModelError) as exc:
        _scene_mech(text, analysis, effects)
    n = _count[0]
    return exc.value, _dir() / f"s{n}.yaml", _dir() / f"model_s{n}.yaml"


BASE = TROLLEY.replace("MASS", "1000").replace("EAVAL", "1.0e7")
LOOP = BASE.replace("ropes:", "  - {name: extra, type: hinge, bodies: [ground, trolley], "
                    "at: K, axis: [0, 1, 0]}\nropes:")


@pytest.mark.parametrize("case", ["loop", "driven loop", "free body", "no mass",
                                  "off vertical", "damped block", "inextensible block",
                                  "no rope"])
def test_refusals_name_file_entry_and_fix(case):
    """Each refusal's whole message, its entry and the file that holds the entry."""
    if case == "loop":            # a second joint to the driven trolley closes a loop
        e, scene, model = _refusal(LOOP, TROLLEY_DRIVE)
        want = (scene, "analysis.drives.trolley",
                "'extra' (joints[1]) closes a loop of bodies that the drives move; closed "
                "linkages are not solved by operation scenes yet (drive a joint outside "
                "the loop)")
    elif case == "driven loop":   # driving the joint that closes the loop
        e, scene, model = _refusal(LOOP, "  duration: 4\n  drives:\n    e: {hinge: extra, "
                                   "profile: {type: table, speed: [[0, 0.1]]}}\n")
        want = (scene, "analysis.drives.e",
                "'extra' (joints[1]) closes a loop of bodies: driving it is not supported")
    elif case == "free body":
        e, scene, model = _refusal(BASE.replace(
            "joints:", "  crate: {mass: 50, com: [5, 0, 0], inertia: [1, 1, 1], "
            "nodes: []}\njoints:"), TROLLEY_DRIVE)
        want = (model, "bodies.crate", "body 'crate' has no joint to the ground or to "
                "other bodies: free bodies are not solved by operation scenes yet")
    elif case == "no mass":
        e, scene, model = _refusal(ARM.replace("arm: {mass: 200,", "arm: {mass: 0,"),
                                   "  duration: 2\n  drives:\n    d: {hinge: luff, "
                                   "torque: 100}\n")
        want = (scene, "analysis.drives.d",
                "drive 'd' moves 'luff' (joints[0]) as a coordinate, but the bodies it "
                "carries have no mass; give them mass (bodies.NAME.mass) or prescribe a "
                "profile")
    elif case == "off vertical":
        e, scene, model = _refusal(BASE.replace("H: [0, 0, 0]", "H: [1, 0, 0]"),
                                   TROLLEY_DRIVE, "{sway: false}")
        want = (model, "nodes.H", "with sway: false the load at node 'H' must hang "
                "vertically below 'K' (it is off by 1 m); move it or turn sway on")
    elif case == "damped block":
        e, scene, model = _refusal(BLOCK, "  duration: 1\n", "{damping: exact}")
        want = (scene, "effects.damping",
                "the massless node(s) B with damping: a dashpot on a massless block makes "
                "its velocity a differential, not an algebraic, unknown; not solved yet: "
                "give the block a mass (masses) or set damping: none")
    elif case == "inextensible block":
        e, scene, model = _refusal(BLOCK, "  duration: 1\n", "{rope_elasticity: false}")
        want = (scene, "effects.rope_elasticity",
                "the massless node(s) B with inextensible ropes: not solved yet; give the "
                "block a mass (masses) or use elastic ropes")
    else:                         # a point mass that no rope or spring holds
        e, scene, model = _refusal(
            CHAIN.replace("masses: {H: 1000, I: 500, J: 200}",
                          "masses: {H: 1000, I: 500, J: 200, Q: 5}").replace(
                "  J: [0, 0, -7]\n", "  J: [0, 0, -7]\n  Q: [5, 0, -7]\n"),
            "  duration: 1\n")
        want = (model, "masses.Q", "the point mass at node 'Q' hangs on no rope or axial "
                "spring; an operation scene moves masses on ropes")
    assert (str(e.file), e.entry, e.message) == (str(want[0]),) + want[1:]


def test_a_rope_between_bodies_only_is_inactive():
    """The luffing arm moved by a profile (no joint coordinate): its stay joins the ground
    and the arm only, so it carries no computed force (listed as inactive, warned); the
    hoist rope holds the load and is active."""
    mech = _scene_mech(ARM, "  duration: 2\n  drives:\n    d: {hinge: luff, profile: "
                            "{type: table, speed: [[0, 0.0]]}}\n")
    assert mech.inactive_ropes == ["stay"]
    assert [mech.model.ropes[k].name for k in mech.ropes] == ["hoist"]


def test_a_slewing_coordinate_carries_the_trolley_beyond_its_jib():
    """The slewing test crane with the jib's centre of mass at 4 m and the trolley (its
    node K, centre of mass and load) at 12 m: the slewing coordinate's subtree is the jib
    and the trolley riding on it, so its nodes are T and K, its length scale rho = 12 m
    (the farthest point from the axis: the trolley's) and its inertia about the axis
    (I_zz + m r^2 of jib and trolley) / rho^2; the trolley's own profile is prescribed."""
    text = (SLEWING.replace("com: [10, 0, 30]", "com: [4, 0, 30]")
            .replace("K: [6, 0, 30]", "K: [12, 0, 30]").replace("H: [6, 0, 20]", "H: [12, 0, 20]")
            .replace("com: [6, 0, 30]", "com: [12, 0, 30]"))
    mech = _scene_mech(text, "  duration: 2\n  drives:\n    s: {hinge: slew, torque: 0}\n"
                             "    t: {slider: travel, profile: {type: table, "
                             "speed: [[0, 0.0]]}}\n")
    assert mech.nJ == 1
    (jc,) = mech.jc
    assert _names(mech, jc["nodes"]) == ["T", "K"] and jc["rho"] == 12.0 and jc["hinge"]
    ev = mech.evaluate(0.0, mech.q0, np.zeros(mech.n), mech.taut0)
    I_ax = 1e5 + 5000 * 16 + 10 + 500 * 144
    np.testing.assert_allclose(ev.MJ, [[I_ax / 144]], rtol=1e-12)


def test_massless_blocks_found_through_a_chain():
    """The massless block B on two falls with a second massless node C on the sling
    below it (B - C - L): both are found from the load L outwards (C first, then B, one
    more pass), appended to the point masses with mass 0, and the statics carry m g in
    both sling parts and m g / 2 in each fall."""
    text = (BLOCK.replace("  L: [0, 0, 7]\n", "  C: [0, 0, 8.5]\n  L: [0, 0, 7]\n")
            .replace("  sling: {EA: 5.0e6, path: [B, L]}\n",
                     "  sling: {EA: 5.0e6, path: [B, C]}\n"
                     "  sling2: {EA: 5.0e6, path: [C, L]}\n"))
    mech = _scene_mech(text, "  duration: 1\n")
    assert _names(mech, mech.free) == ["L", "C", "B"]
    np.testing.assert_allclose(mech.M, [1000, 1000, 0, 0, 0, 0], atol=0)
    np.testing.assert_allclose(mech.S0, [1000 * 9.81 / 2, 1000 * 9.81, 1000 * 9.81],
                               rtol=1e-9)
