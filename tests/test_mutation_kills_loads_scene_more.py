"""More kill tests for cranefe/analysis/loads/scene.py (tools/mutation.py loads_scene;
docs/testing.md, "Mutation testing"), for the survivors of its first run: the hoist
load's search in models with a level rope between two hooks and with a mass tied down
to the ground, a named joint that is neither slider nor hinge, and the exact sentences
of `assumed` and of the messages (they go into the --json document and name what to
give). Everything by hand; parse only, no simulation.
"""

import os

import pytest

from cranefe.analysis.loads.scene import complete, parse
from cranefe.errors import ModelError
from cranefe.model import load

MODELS = os.path.join(os.path.dirname(__file__), "..", "models")

TWO_HOOKS = """cranefe: 1
name: two hooks at one level, tied by a rope
plane: xz
nodes: {D: [0, 0, 0], S: [0, 0, 30], T: [4, 0, 30], A: [0, 0, 10], B: [4, 0, 10]}
ground: [D, S, T]
masses: {A: 1000.0, B: 1000.0}
drums:
  hoist: {node: D, radius: 0.25, inertia: 500.0, brake: false}
ropes:
  hoist_rope: {EA: 1.0e7, path: [hoist, S, A]}
  second: {EA: 1.0e7, path: [T, B]}
  tie: {EA: 1.0e7, path: [A, B]}
"""


def scene(tmp_path, model, analysis):
    """A scene file (the analysis) over a model file, loaded."""
    (tmp_path / "model.yaml").write_text(model)
    path = tmp_path / "scene.yaml"
    path.write_text(f"cranefe: 1\nscene: t\nmodel: model.yaml\n{analysis}")
    return load(path)


def test_a_level_rope_between_two_hooks_leaves_both_loads():
    """A and B hang at the same height, tied by a level rope: neither hangs below the
    other, so both are the hoist load (the search used to mark the first node of a
    level span as carrying a mass below it, and lifted B alone)."""
    s = parse(load("two.yaml", TWO_HOOKS))
    assert s.loads == ("A", "B")
    assert s.assumed[0] == ("hoist load: the point mass(es) at A, B (the lowest masses "
                            "on the ropes; give analysis.hoist.load)")
    # listed the other way round: the same
    s = parse(load("two.yaml", TWO_HOOKS.replace("path: [A, B]", "path: [B, A]")))
    assert s.loads == ("A", "B")
    # B a little lower: B hangs below A through the tie, B alone is the load
    s = parse(load("two.yaml", TWO_HOOKS.replace("B: [4, 0, 10]", "B: [4, 0, 9]")))
    assert s.loads == ("B",)


def test_a_mass_tied_down_to_the_ground_is_a_load():
    """A rope from the hook down to a ground anchor G (a tag line) hangs no mass below
    it: H stays the load."""
    text = TWO_HOOKS.replace("T: [4, 0, 30]", "T: [4, 0, 30], G: [0, 0, 2]").replace(
        "ground: [D, S, T]", "ground: [D, S, T, G]").replace(
        "  tie: {EA: 1.0e7, path: [A, B]}\n", "  tag: {EA: 1.0e5, path: [A, G]}\n")
    s = parse(load("tag.yaml", text))
    assert s.loads == ("A", "B")
    s = parse(load("tag.yaml", text.replace("path: [A, G]", "path: [G, A]")))
    assert s.loads == ("A", "B")


JIBS = """cranefe: 1
name: two luffing jibs and a welded counter-jib
nodes:
  O:   [0.0, 0.0, 0.0]
  Q:   [5.0, 0.0, 0.0]
  TIP: [0.0, 0.0, 20.0]
  D:   [-1.0, 0.0, 0.5]
  L:   [0.0, 0.0, 10.0]
ground: [O, Q]
masses: {L: 2000}
bodies:
  jib: {mass: 3000, com: [0.0, 0.0, 10.0], inertia: [1.0e3, 1.0e5, 1.0e5],
        nodes: [TIP, D]}
  jib2: {mass: 300, com: [5.0, 0.0, 5.0], inertia: [1.0e3, 1.0e3, 1.0e3]}
  counter: {mass: 300, com: [-5.0, 0.0, 0.0], inertia: [1.0e3, 1.0e3, 1.0e3]}
joints:
  - {name: luff_a, type: hinge, bodies: [ground, jib], at: O, axis: [0, 1, 0]}
  - {name: luff_b, type: hinge, bodies: [ground, jib2], at: Q, axis: [0, 1, 0]}
  - {name: weld, type: fixed, bodies: [jib, counter], at: O}
springs:
  - {name: g1, type: rotational, bodies: [ground, jib], at: O, axis: [0, 1, 0],
     stiffness: 1.0e9}
  - {name: g2, type: rotational, bodies: [ground, jib2], at: Q, axis: [0, 1, 0],
     stiffness: 1.0e9}
drums:
  hoist: {node: D, radius: 0.2, inertia: 5.0, brake: false, rope_reserve: 20.0}
ropes:
  hoist_rope: {EA: 5.0e7, path: [hoist, TIP, L]}
"""


def test_named_joints_that_move_and_one_that_does_not(tmp_path):
    """The two named hinges get the default move (4.8 deg/s in 5 s); the named fixed
    joint none; the sentence lists them joined by '; '; an unknown drive name lists
    the named ones joined by ', '."""
    s = parse(load("jibs.yaml", JIBS))
    assert [(mv.joint, mv.kind) for mv in s.moves] == [("luff_a", "hinge"),
                                                       ("luff_b", "hinge")]
    assert ("joint drives: default moves luff_a: 4.8 deg/s reached in 5 s; luff_b: 4.8 "
            "deg/s reached in 5 s (give analysis.drives)") in s.assumed
    with pytest.raises(ModelError) as e:
        parse(scene(tmp_path, JIBS, "analysis: {type: loads, drives: {weld: {}}}\n"))
    assert e.value.entry == "analysis.drives.weld"
    assert e.value.message == ("no slider or hinge joint named 'weld'; named ones: "
                               "luff_a, luff_b")


def test_default_slider_move_sentence():
    s = parse(load(os.path.join(MODELS, "operations", "overhead_crane.yaml")))
    assert ("joint drives: default moves trolley_travel: 1 m/s reached in 2 s (give "
            "analysis.drives)") in s.assumed


HOIST = """cranefe: 1
name: single mass on an elastic rope
plane: xz
nodes: {D: [0, 0, 0], S: [0, 0, 30], H: [0, 0, 10]}
ground: [D, S]
masses: {H: 5000.0}
drums:
  hoist: {node: D, radius: 0.25, inertia: 500.0, brake: false}
ropes:
  hoist_rope: {EA: 3.15e6, path: [hoist, S, {node: H, falls: 2}]}
"""


def test_the_assumed_sentences_of_a_plain_model():
    """Each default said in full (the --json document's `assumed`), in order."""
    s = complete(parse(load("h.yaml", HOIST)), 0.125, "h.yaml")
    assert s.assumed == (
        "hoist load: the point mass(es) at H (the lowest masses on the ropes; give "
        "analysis.hoist.load)",
        "full hoisting speed v_h,max = 0.5 m/s at the hook (the model gives no speed; "
        "give a loads scene with analysis.hoist.speed)",
        "hoist drive: rest to full speed in 1 s (give analysis.hoist.ramp)",
        "phi3: dm/m = 0.5 released (give analysis.release.fraction)",
        "creep speed v_h,CS = 0.1 x full speed = 0.05 m/s (give analysis.hoist.creep)")


def test_the_assumed_sentences_of_a_transient_scene(tmp_path):
    """A transient scene's drum: 4 rad/s x R / n = 0.5 m/s; its ramp 0.5 s."""
    m = scene(tmp_path, HOIST, "analysis:\n  type: transient\n  drums:\n    hoist: "
              "{speed: 4.0, ramp: 0.5}\n")
    s = complete(parse(m), 0.125, "t.yaml")
    assert s.assumed == (
        "hoist load: the point mass(es) at H (the lowest masses on the ropes; give "
        "analysis.hoist.load)",
        "full hoisting speed: the transient scene's drum speed 4 rad/s of drum 'hoist'",
        "hoist ramp: the scene's 0.5 s",
        "phi3: dm/m = 0.5 released (give analysis.release.fraction)",
        "creep speed v_h,CS = 0.1 x full speed = 0.05 m/s (give analysis.hoist.creep)")
    assert (s.speed, s.creep, s.ramp) == (0.5, 0.05, 0.5)


def test_a_zero_drum_speed_names_what_to_give(tmp_path):
    m = scene(tmp_path, HOIST, "analysis:\n  type: transient\n  drums:\n    hoist: "
              "{speed: 0.0}\n")
    with pytest.raises(ModelError) as e:
        parse(m)
    assert e.value.entry == "analysis.drums.hoist.speed"
    assert e.value.message == ("a zero drum speed gives no hoisting speed; give a loads "
                               "scene with analysis.hoist.speed")


def test_a_model_without_a_turning_drum(tmp_path):
    text = HOIST.replace("brake: false", "brake: true")
    with pytest.raises(ModelError) as e:
        parse(load("b.yaml", text))
    assert e.value.entry == "drums"
    assert e.value.message == ("cranefe loads needs a hoist drum that turns (a drum with "
                               "brake: false); the model has none")
    with pytest.raises(ModelError) as e:
        parse(scene(tmp_path, text, "analysis: {type: loads, hoist: {drum: hoist}}\n"))
    assert e.value.message == ("unknown or braked drum 'hoist'; unbraked drums of the "
                               "model: none")
