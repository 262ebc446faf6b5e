"""Kill tests for cranefe/analysis/loads/scene.py and the pure parts of runs.py
(tools/mutation.py loads_scene, loads_runs; docs/testing.md, "Mutation testing"): the
loads scene's keys, defaults and errors (each ModelError names the scene file and the
entry), the working point, the reeving ratio, the jerk-limited speed table and the
default time step, each against values written out by hand. No simulation runs here
except the lift-off guesses (one small model, a few hundred steps)."""

import os

import numpy as np
import pytest

from cranefe.analysis.loads import runs
from cranefe.analysis.loads.scene import JointMove, complete, parse
from cranefe.errors import AnalysisError, ModelError
from cranefe.model import load

G = 9.81
MODELS = os.path.join(os.path.dirname(__file__), "..", "models")
M, R, J, EA = 5000.0, 0.25, 500.0, 3.15e6

MODEL = f"""cranefe: 1
name: single mass on an elastic rope
plane: xz
nodes: {{D: [0, 0, 0], S: [0, 0, 30], H: [0, 0, 10]}}
ground: [D, S]
masses: {{H: {M}}}
drums:
  hoist: {{node: D, radius: {R}, inertia: {J}, brake: false}}
ropes:
  hoist_rope: {{EA: {EA}, path: [hoist, S, {{node: H, falls: 2}}]}}
"""

HINGE = """cranefe: 1
name: luffing jib
nodes:
  O:   [0.0, 0.0, 0.0]
  TIP: [0.0, 0.0, 20.0]
  D:   [-1.0, 0.0, 0.5]
  L:   [0.0, 0.0, 10.0]
ground: [O]
masses:
  L: 2000
bodies:
  jib: {mass: 3000, com: [0.0, 0.0, 10.0], inertia: [1.0e3, 1.0e5, 1.0e5],
        nodes: [TIP, D]}
joints:
  - {name: luffing, type: hinge, bodies: [ground, jib], at: O, axis: [0, 1, 0]}
springs:
  - {name: luffing_gear, type: rotational, bodies: [ground, jib], at: O, axis: [0, 1, 0],
     stiffness: 1.0e9}
drums:
  hoist: {node: D, radius: 0.2, inertia: 5.0, brake: false, rope_reserve: 20.0}
ropes:
  hoist_rope: {EA: 5.0e7, path: [hoist, TIP, L]}
"""


def scene(tmp_path, analysis, model=MODEL, name="s.yaml"):
    (tmp_path / "model.yaml").write_text(model)
    path = tmp_path / name
    path.write_text(f"cranefe: 1\nscene: t\nmodel: model.yaml\n{analysis}")
    return path, load(path)


def error(tmp_path, analysis, entry, *words, model=MODEL):
    path, m = scene(tmp_path, analysis, model)
    with pytest.raises(ModelError) as e:
        complete(parse(m), R / 2, str(path))
    assert e.value.entry == entry
    assert os.path.samefile(e.value.file, path)
    for w in words:
        assert w in e.value.message, (w, e.value.message)
    return e.value.message


def test_defaults_of_a_plain_model(tmp_path):
    """A model without a loads scene: the unbraked drum, the lowest point mass, 0.5 m/s
    at the hook, 1 s ramp, jerk time 1/4 of it, dm/m = 0.5 suddenly, 3 s after lift-off,
    creep 0.1 x full speed; each default said in `assumed`."""
    (tmp_path / "model.yaml").write_text(MODEL)
    m = load(tmp_path / "model.yaml")
    s = parse(m)
    assert (s.drum, s.loads, s.speed, s.creep, s.ramp, s.jerk) == \
        ("hoist", ("H",), 0.5, None, 1.0, 0.25)
    assert (s.fraction, s.release_time, s.moves, s.after_lift_off, s.time_step) == \
        (0.5, 0.0, (), 3.0, None)
    assert (s.radius, s.radius_nodes, s.hook_height, s.hoisting_class, s.drive_class,
            s.tolerance) == (None, (), None, None, "HD1", None)
    c = complete(s, R / 2, "f")
    assert c.creep == pytest.approx(0.05) and c.speed == 0.5
    assert c.speeds == pytest.approx((0.05, 0.125, 0.25, 0.375, 0.5))
    text = " | ".join(c.assumed)
    for words in ("hoist load: the point mass(es) at H", "phi3: dm/m = 0.5",
                  "full hoisting speed v_h,max = 0.5 m/s",
                  "rest to full speed in 1 s", "creep speed v_h,CS = 0.1 x full speed = 0.05"):
        assert words in text, words
    assert len(c.assumed) == 5


def test_every_key_of_a_loads_scene(tmp_path):
    _, m = scene(tmp_path, "analysis:\n  type: loads\n  hoist: {drum: hoist, load: [H], "
                 "speed: 0.8, creep: 0.2, ramp: 2.0, jerk_time: 0.5}\n"
                 "  release: {fraction: 0.3, time: 0.2}\n  after_lift_off: 1.5\n"
                 "  time_step: 0.002\n  tolerance: 1.0e-7\n  radius: 7.0\n"
                 "  radius_nodes: [H]\n  hook_height: 4.0\n  hoisting_class: HC2\n"
                 "  drive_class: HD3\n")
    s = parse(m)
    assert (s.drum, s.loads, s.speed, s.creep, s.ramp, s.jerk) == \
        ("hoist", ("H",), 0.8, 0.2, 2.0, 0.5)
    assert (s.fraction, s.release_time, s.after_lift_off, s.time_step, s.tolerance) == \
        (0.3, 0.2, 1.5, 0.002, 1.0e-7)
    assert (s.radius, s.radius_nodes, s.hook_height, s.hoisting_class, s.drive_class) == \
        (7.0, ("H",), 4.0, "HC2", "HD3")
    assert s.assumed == ()
    assert s.speeds == pytest.approx((0.2, 0.4, 0.6, 0.8))
    # the working point: H moved to radius 7 (its azimuth: +x when on the axis) and to
    # height 4
    X = runs.placed(m, s).coords
    assert X[m.node_index["H"]] == pytest.approx([7.0, 0.0, 4.0], abs=1e-12)
    assert X[m.node_index["S"]] == pytest.approx([0.0, 0.0, 30.0], abs=1e-12)
    assert runs.placed(m, parse(load(tmp_path / "model.yaml"))) is not None


def test_working_point_keeps_the_azimuth(tmp_path):
    """radius_nodes move horizontally from the vertical axis through the first ground
    node (1, 2, 0): a node at (4, 6, 10) is 5 m off it at azimuth (3, 4)/5, so radius 10
    puts it at (7, 10, 10); hook_height only moves the load vertically."""
    text = MODEL.replace("D: [0, 0, 0], S: [0, 0, 30], H: [0, 0, 10]",
                         "D: [1, 2, 0], S: [4, 6, 30], H: [4, 6, 10]").replace(
                             "plane: xz\n", "")
    _, m = scene(tmp_path, "analysis:\n  type: loads\n  radius: 10.0\n"
                 "  radius_nodes: [S, H]\n  hook_height: 3.0\n", model=text)
    X = runs.placed(m, parse(m)).coords
    assert X[m.node_index["S"]] == pytest.approx([7.0, 10.0, 30.0], abs=1e-12)
    assert X[m.node_index["H"]] == pytest.approx([7.0, 10.0, 3.0], abs=1e-12)
    assert X[m.node_index["D"]] == pytest.approx([1.0, 2.0, 0.0], abs=1e-12)
    # only the height
    _, m = scene(tmp_path, "analysis:\n  type: loads\n  hook_height: 3.0\n", model=text,
                 name="h.yaml")
    X = runs.placed(m, parse(m)).coords
    assert X[m.node_index["H"]] == pytest.approx([4.0, 6.0, 3.0], abs=1e-12)
    assert X[m.node_index["S"]] == pytest.approx([4.0, 6.0, 30.0], abs=1e-12)


def test_speed_from_a_transient_scene(tmp_path):
    """A transient scene's drum speed (rad/s, a number or the largest of a table) is the
    full speed, converted at the hook by the reeving: 4 rad/s x R/2 = 0.5 m/s; its ramp
    is the hoist's."""
    _, m = scene(tmp_path, "analysis:\n  type: transient\n  drums:\n"
                 "    hoist: {speed: 4.0, ramp: 0.5}\n")
    s = parse(m)
    assert s.speed == -4.0 and s.ramp == 0.5 and s.jerk == 0.125
    assert any("drum speed 4 rad/s of drum 'hoist'" in a for a in s.assumed)
    assert any("hoist ramp: the scene's 0.5 s" in a for a in s.assumed)
    c = complete(s, R / 2, "f")
    assert c.speed == pytest.approx(0.5) and c.creep == pytest.approx(0.05)
    _, m = scene(tmp_path, "analysis:\n  type: transient\n  drums:\n"
                 "    hoist: {speed: [[0, 0], [0.5, -4.0], [1.0, 3.0]]}\n", name="t.yaml")
    s = parse(m)
    assert s.speed == -4.0 and s.ramp == 1.0
    _, m = scene(tmp_path, "analysis:\n  type: transient\n  drums:\n"
                 "    hoist: {torque: 1000}\n", name="q.yaml")
    assert parse(m).speed == 0.5
    # a slow drum (0.8 rad/s) is a speed; a ramp of 0 is no ramp (the default 1 s)
    _, m = scene(tmp_path, "analysis:\n  type: transient\n  drums:\n"
                 "    hoist: {speed: 0.8, ramp: 0}\n", name="slow.yaml")
    s = parse(m)
    assert s.speed == -0.8 and s.ramp == 1.0


def test_the_lowest_mass_is_the_load(tmp_path):
    """Masses in a chain (A hangs B): B is the hoist load; a mass on the ground is not."""
    text = MODEL.replace("H: [0, 0, 10]", "H: [0, 0, 10], B: [0, 0, 6]").replace(
        "masses: {H: 5000.0}", "masses: {H: 5000.0, B: 1000.0, S: 10.0}") + \
        "  lower: {EA: 1.0e7, path: [H, B]}\n"
    _, m = scene(tmp_path, "analysis:\n  type: loads\n", model=text)
    assert parse(m).loads == ("B",)
    # the rope listed from the bottom up
    _, m = scene(tmp_path, "analysis:\n  type: loads\n",
                 model=text.replace("path: [H, B]", "path: [B, H]"), name="up.yaml")
    assert parse(m).loads == ("B",)


def test_default_joint_moves(tmp_path):
    """Every named hinge gets 0.8 rpm (4.8 deg/s) reached in 5 s over 45 deg, jerk time
    1/4 of the ramp; given keys override."""
    _, m = scene(tmp_path, "analysis:\n  type: loads\n", model=HINGE)
    s = parse(m)
    assert s.moves == (JointMove("luffing", "hinge", pytest.approx(np.radians(4.8)), 5.0,
                                 pytest.approx(np.radians(45.0)), 1.25),)
    assert any("luffing: 4.8 deg/s reached in 5 s" in a for a in s.assumed)
    _, m = scene(tmp_path, "analysis:\n  type: loads\n  drives:\n    luffing: "
                 "{v_max_deg: 2.0, ramp: 3.0, distance_deg: -10, jerk_time: 0.5}\n",
                 model=HINGE, name="g.yaml")
    mv = parse(m).moves[0]
    assert (mv.v_max, mv.ramp, mv.distance, mv.jerk) == pytest.approx(
        (np.radians(2.0), 3.0, np.radians(-10.0), 0.5))
    _, m = scene(tmp_path, "analysis:\n  type: loads\n  drives:\n    luffing: "
                 "{ramp: 3.0, jerk_time: 1.5}\n", model=HINGE, name="half.yaml")
    assert parse(m).moves[0].jerk == 1.5


def test_default_slider_move():
    m = load(os.path.join(MODELS, "operations", "overhead_crane.yaml"))
    s = parse(m)
    sliders = [mv for mv in s.moves if mv.kind == "slider"]
    assert sliders
    for mv in sliders:
        assert (mv.v_max, mv.ramp, mv.distance, mv.jerk) == (1.0, 2.0, 6.0, 0.5)
    assert any("1 m/s reached in 2 s" in a for a in s.assumed)


@pytest.mark.parametrize("analysis, entry, words", [
    ("  release: {fraction: 1.5}\n", "analysis.release.fraction", ["1.5", "below 1"]),
    ("  hoist: {ramp: 1.0, jerk_time: 0.6}\n", "analysis.hoist.jerk_time",
     ["0.6 s is more than half the ramp (1 s)"]),
    ("  radius: 5.0\n", "analysis.radius_nodes", ["radius_nodes: [K, HOOK]"]),
    ("  radius: 5.0\n  radius_nodes: [H, X]\n", "analysis.radius_nodes[1]",
     ["unknown node 'X'"]),
    ("  hoisting_class: HC9\n", "analysis.hoisting_class", ["'HC9'", "HC1, HC2, HC3, HC4"]),
    ("  drive_class: HD9\n", "analysis.drive_class", ["'HD9'", "HD1 ... HD5"]),
    ("  hoist: {drum: winch}\n", "analysis.hoist.drum",
     ["'winch'", "unbraked drums of the model: hoist"]),
    ("  hoist: {load: X}\n", "analysis.hoist.load", ["unknown node 'X'"]),
    ("  hoist: {load: [H, S]}\n", "analysis.hoist.load", ["node 'S' carries no point mass"]),
    ("  hoist: {speed: 0.5, creep: 0.5}\n", "analysis.hoist.creep",
     ["creep speed 0.5 m/s is not below the full speed (0.5 m/s)"]),
    ("  hoist: {sped: 1}\n", "analysis.hoist.sped", ["speed"]),
    ("  release: {fractio: 0.2}\n", "analysis.release.fractio", ["fraction"]),
    ("  drives: {trolley: {}}\n", "analysis.drives.trolley",
     ["no slider or hinge joint named 'trolley'; named ones: none"]),
    ("  drives: [trolley]\n", "analysis.drives", ["mapping"]),
    ("  hoist: {load: HX}\n", "analysis.hoist.load", ["unknown node 'HX'"]),
    ("  hoist: {speed: -0.5}\n", "analysis.hoist.speed", []),
    ("  hoist: {ramp: 0}\n", "analysis.hoist.ramp", []),
    ("  hoist: {speed: fast}\n", "analysis.hoist.speed", []),
    ("  hoist: {ramp: slow}\n", "analysis.hoist.ramp", []),
])
def test_errors_name_the_file_and_entry(tmp_path, analysis, entry, words):
    error(tmp_path, "analysis:\n  type: loads\n" + analysis, entry, *words)


@pytest.mark.parametrize("drive, entry", [
    ("{v_max_deg: -1}", "analysis.drives.luffing.v_max_deg"),
    ("{v_max_deg: x}", "analysis.drives.luffing.v_max_deg"),
    ("{distance_deg: x}", "analysis.drives.luffing.distance_deg"),
    ("{ramp: -2}", "analysis.drives.luffing.ramp"),
    ("{ramp: x}", "analysis.drives.luffing.ramp"),
    ("{jerk_time: -0.5}", "analysis.drives.luffing.jerk_time"),
    ("{jerk_time: x}", "analysis.drives.luffing.jerk_time"),
])
def test_bad_hinge_moves_name_the_entry(tmp_path, drive, entry):
    error(tmp_path, f"analysis:\n  type: loads\n  drives:\n    luffing: {drive}\n", entry,
          model=HINGE)


@pytest.mark.parametrize("drive, entry", [
    ("{v_max: -1}", "analysis.drives.trolley_travel.v_max"),
    ("{v_max: x}", "analysis.drives.trolley_travel.v_max"),
    ("{distance: x}", "analysis.drives.trolley_travel.distance"),
])
def test_bad_slider_moves_name_the_entry(tmp_path, drive, entry):
    crane = os.path.abspath(os.path.join(MODELS, "operations", "overhead_crane.yaml"))
    path = tmp_path / "s.yaml"
    path.write_text(f"cranefe: 1\nscene: t\nmodel: {crane}\nanalysis:\n  type: loads\n"
                    f"  drives:\n    trolley_travel: {drive}\n")
    with pytest.raises(ModelError) as e:
        parse(load(path))
    assert e.value.entry == entry and os.path.samefile(e.value.file, path)


def test_given_slider_move(tmp_path):
    """A slider's given keys replace the defaults (its *_deg keys are a hinge's and are
    ignored); a jerk time of exactly half the ramp is allowed."""
    crane = os.path.abspath(os.path.join(MODELS, "operations", "overhead_crane.yaml"))
    path = tmp_path / "s.yaml"
    path.write_text(f"cranefe: 1\nscene: t\nmodel: {crane}\nanalysis:\n  type: loads\n"
                    "  drives:\n    trolley_travel: {v_max: 0.3, ramp: 3.0, distance: -4.0, "
                    "jerk_time: 1.5, v_max_deg: 9}\n")
    mv = parse(load(path)).moves
    assert mv == (JointMove("trolley_travel", "slider", 0.3, 3.0, -4.0, 1.5),)


def test_more_errors_name_the_file_and_entry(tmp_path):
    error(tmp_path, "analysis:\n  type: loads\n  drives:\n    luffing: {ramp: 2, "
          "jerk_time: 1.5}\n", "analysis.drives.luffing.jerk_time",
          "1.5 s is more than half the ramp (2 s)", model=HINGE)
    error(tmp_path, "analysis:\n  type: loads\n  drives:\n    luffing: {rmp: 2}\n",
          "analysis.drives.luffing.rmp", "ramp", model=HINGE)
    error(tmp_path, "analysis:\n  type: transient\n  drums:\n    hoist: {speed: 0.0}\n",
          "analysis.drums.hoist.speed", "zero drum speed")
    error(tmp_path, "analysis:\n  type: loads\n", "drums", "brake: false",
          model=MODEL.replace("brake: false", "brake: true"))
    two = MODEL.replace("ground: [D, S]", "ground: [D, S, E]").replace(
        "S: [0, 0, 30]", "S: [0, 0, 30], E: [5, 0, 0]").replace(
        "drums:\n", "drums:\n  aux: {node: E, radius: 0.2, inertia: 10, brake: false}\n")
    error(tmp_path, "analysis:\n  type: loads\n", "analysis.hoist.drum",
          "several drums (aux, hoist); name the hoist drum", model=two)
    grounded = MODEL.replace("masses: {H: 5000.0}", "masses: {S: 5000.0}")
    error(tmp_path, "analysis:\n  type: loads\n", "analysis.hoist.load",
          "finds no hoist load", model=grounded)


def test_hook_travel_per_drum_radian(tmp_path):
    """R / falls from the rope row leaving the drum: 0.25 / 2; a drum whose rope reaches
    no point mass is an AnalysisError."""
    _, m = scene(tmp_path, "analysis:\n  type: loads\n")
    assert runs.hook_per_drum(m, "hoist") == pytest.approx(R / 2, rel=1e-12)
    three = MODEL.replace("falls: 2", "falls: 3")
    _, m = scene(tmp_path, "analysis:\n  type: loads\n", model=three, name="3.yaml")
    assert runs.hook_per_drum(m, "hoist") == pytest.approx(R / 3, rel=1e-12)
    bare = MODEL.replace("[hoist, S, {node: H, falls: 2}]", "[hoist, S]") + \
        "  other: {EA: 1.0e7, path: [S, H]}\n"
    _, m = scene(tmp_path, "analysis:\n  type: loads\n", model=bare, name="b.yaml")
    with pytest.raises(AnalysisError, match="drum 'hoist' moves no point mass"):
        runs.hook_per_drum(m, "hoist")


@pytest.mark.parametrize("ramp, jerk, h", [(2.0, 0.5, 0.01), (1.0, 0.5, 0.2),
                                           (1.0, 0.0, 0.01)])
def test_s_curve_speed_table(ramp, jerk, h):
    """The jerk-limited start: a = v / (ramp - jerk); v = a t^2 / (2 t_j) up to t_j,
    then a (t - t_j / 2), then v_max - a (ramp - t)^2 / (2 t_j); sampled at
    max(8, ceil(t_j / h)) + 1 points on each rounded part; jerk 0: a straight ramp."""
    v = 3.0
    table, a = runs.s_curve_speeds(v, ramp, jerk, h)
    assert a == pytest.approx(v / (ramp - jerk), rel=1e-14)
    t, s = np.array(table).T
    if jerk == 0:
        assert table == [[0.0, 0.0], [ramp, v]]
        return
    n = max(8, int(np.ceil(jerk / h)))
    exact = np.where(t <= jerk, a * t**2 / (2 * jerk),
                     np.where(t <= ramp - jerk, a * (t - jerk / 2),
                              v - a * (ramp - t) ** 2 / (2 * jerk)))
    np.testing.assert_allclose(s, exact, rtol=0, atol=1e-12)
    assert np.all(np.diff(t) > 0)                    # no repeated time
    assert t[0] == 0 and t[-1] == pytest.approx(ramp) and s[-1] == pytest.approx(v)
    middle = 1 if ramp - jerk > jerk else 0          # a shared point is kept once
    assert len(t) == 2 * (n + 1) - (1 - middle)
    np.testing.assert_allclose(t[:n + 1], np.linspace(0, jerk, n + 1), atol=1e-12)


def test_default_time_step_and_the_lift_off_guesses(tmp_path):
    """No time_step: 60 steps a period of the highest frequency of the lift model (drum
    free: w^2 = k (n^2 / m + R^2 / J)). A guess of the lift-off time that is too short
    is retried: unlifted at the end (4 x the guess), then lifted too late for the time
    after it (1.05 x the lift-off time): lift-off at g / (w^2 v), w^2 = n^2 k / m."""
    _, m = scene(tmp_path, "analysis:\n  type: loads\n  hoist: {speed: 0.5}\n"
                 "  after_lift_off: 0.6\n")
    s = complete(parse(m), R / 2, "f")
    lift = runs.lift_model(m)
    k = EA / 70
    w_max = np.sqrt(k * (4 / M + R**2 / J))
    st = runs._steps(s, lift)
    assert st["max_steps"] == 10**7
    assert st["time_step"] == pytest.approx(2 * np.pi / (60 * w_max), rel=1e-9)
    assert runs._steps(s) == {"max_steps": 10**7}
    s = complete(parse(m), R / 2, "f")
    from dataclasses import replace
    s = replace(s, time_step=0.01)
    w2 = 4 * k / M
    t_lift = G / (w2 * 0.125)                                    # 2.18 s at 0.125 m/s
    res, tr = runs.lift_off(lift, s, "slow", 0.125 / (R / 2), guess=0.5)
    assert res.lift_off_time == pytest.approx(t_lift, rel=1e-6)
    # 0.5 + 0.6 s: not lifted -> guess 2 s: 2.6 s, lifted at 2.18 but 0.6 s after it is
    # not in -> guess 1.05 x 2.18
    assert tr.duration == pytest.approx(1.05 * res.lift_off_time + 0.6, rel=1e-9)
    assert tr.parameters["start"] == "step to full speed at t = 0"
    assert tr.engine == "transient" and tr.steps == res.steps
    d = tr.to_dict()
    assert d["duration_s"] == tr.duration and d["name"] == "slow"
