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


POSITIVE = "must be positive (found {}); give a value > 0"
NONNEG = "must not be negative (found {}); give a value >= 0"


@pytest.mark.parametrize("analysis, entry, message", [
    ("hoist: {creep: 0}", "analysis.hoist.creep", POSITIVE.format(0)),
    ("release: {fraction: 0}", "analysis.release.fraction", POSITIVE.format(0)),
    ("release: {fraction: 1.0}", "analysis.release.fraction",
     "1: the released part dm/m must be below 1 (a part of the load stays on the hook)"),
    ("release: {time: -0.1}", "analysis.release.time", NONNEG.format(-0.1)),
    ("after_lift_off: 0", "analysis.after_lift_off", POSITIVE.format(0)),
    ("time_step: 0", "analysis.time_step", POSITIVE.format(0)),
    ("hoist: {jerk_time: -0.1}", "analysis.hoist.jerk_time", NONNEG.format(-0.1)),
    ("radius: 0", "analysis.radius", POSITIVE.format(0)),
    ("radius: 5.0", "analysis.radius_nodes",
     "name the nodes that move to the radius (the trolley and the hook below it), e.g. "
     "radius_nodes: [K, HOOK]"),
    ("radius_nodes: {H: 1}", "analysis.radius_nodes", "must be a list, not a mapping"),
    ("hook_height: high", "analysis.hook_height", None),
    ("tolerance: 0", "analysis.tolerance", POSITIVE.format(0)),
    ("radiuss: 5.0", "analysis.radiuss", None),
])
def test_every_key_names_its_entry(tmp_path, analysis, entry, message):
    """Each number of a loads scene is checked under its own entry, positive or not
    negative as it means (a time step, a radius: > 0; a release or jerk time: >= 0, 0
    being sudden); misspelt keys are named."""
    m = scene(tmp_path, HOIST, f"analysis:\n  type: loads\n  {analysis}\n")
    with pytest.raises(ModelError) as e:
        parse(m)
    assert e.value.entry == entry
    if message:
        assert e.value.message == message


@pytest.mark.parametrize("hc", ["HC1", "HC2", "HC3", "HC4"])
@pytest.mark.parametrize("hd", ["HD1", "HD2", "HD3", "HD4", "HD5"])
def test_every_class_is_accepted(tmp_path, hc, hd):
    m = scene(tmp_path, HOIST, f"analysis: {{type: loads, hoisting_class: {hc}, "
              f"drive_class: {hd}}}\n")
    s = parse(m)
    assert (s.hoisting_class, s.drive_class) == (hc, hd)


def test_zero_values_that_mean_sudden(tmp_path):
    """A jerk time of exactly half the hoist's ramp, a release time of 0 and a jerk
    time of 0 are allowed."""
    m = scene(tmp_path, HOIST, "analysis:\n  type: loads\n  hoist: {ramp: 1.0, "
              "jerk_time: 0.5}\n  release: {fraction: 0.9, time: 0}\n")
    s = parse(m)
    assert (s.ramp, s.jerk, s.fraction, s.release_time) == (1.0, 0.5, 0.9, 0.0)
    m = scene(tmp_path, HOIST, "analysis:\n  type: loads\n  hoist: {jerk_time: 0}\n")
    assert parse(m).jerk == 0.0


def test_several_drums_named_in_the_message(tmp_path):
    two = HOIST.replace("ground: [D, S]", "ground: [D, S, E]").replace(
        "S: [0, 0, 30]", "S: [0, 0, 30], E: [5, 0, 0]").replace(
        "drums:\n", "drums:\n  aux: {node: E, radius: 0.2, inertia: 10, brake: false}\n")
    m = scene(tmp_path, two, "analysis: {type: loads, hoist: {drum: winch}}\n")
    with pytest.raises(ModelError) as e:
        parse(m)
    assert e.value.message == ("unknown or braked drum 'winch'; unbraked drums of the "
                               "model: aux, hoist")


def test_no_hoist_load_message(tmp_path):
    m = scene(tmp_path, HOIST.replace("masses: {H: 5000.0}", "masses: {S: 5000.0}"),
              "analysis: {type: loads}\n")
    with pytest.raises(ModelError) as e:
        parse(m)
    assert e.value.message == ("cranefe loads finds no hoist load (a point mass at a "
                               "node of its own hanging on the ropes); give "
                               "analysis.hoist.load")


def test_a_level_span_does_not_end_the_search_along_its_rope():
    """The tie A - B - C: level from A to B, then down to C (a mass hanging below B):
    B is not a load, A and C are."""
    text = TWO_HOOKS.replace("B: [4, 0, 10]}", "B: [4, 0, 10], C: [4, 0, 5]}").replace(
        "B: 1000.0}", "B: 1000.0, C: 500.0}").replace("path: [A, B]", "path: [A, B, C]")
    assert parse(load("abc.yaml", text)).loads == ("A", "C")
