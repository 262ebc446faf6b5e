"""Kill tests for cranefe/analysis/transient/scene.py (tools/mutation.py transient_scene;
docs/testing.md, "Mutation testing"): the transient scene's keys and their defaults
(docs/transient.md: duration 2 s, automatic step, max_steps 20 000, method direct,
modes 20, static correction on, initial static), the drives (speed, torque, motor) and
node forces as time functions (`Profile`: value, slope, integral of a ramp and a table
by hand), the motors' characteristics (linear, Kloss, table: torque and slope by hand),
the loads resting on the ground (initial: grounded, the start of a lift-off), and every
error's file, entry and message. Parsing only (no analysis runs): about 0.5 s.
"""

import numpy as np
import pytest

from cranefe import cases
from cranefe.analysis.transient.scene import Motor, Profile, Transient, parse
from cranefe.errors import ModelError
from cranefe.model import load

# cases.two_mass_hoist: drum `hoist` (radius 0.25) at D, head sheave S, load B (5000 kg)
HOIST = cases.two_mass_hoist()[0]
TOL = 1e-12                     # a few roundings of exact binary numbers


def scene(tmp_path, analysis, effects="{sway: false}", model=HOIST):
    """Write the model and a scene `analysis: {type: transient, ANALYSIS}`; load it."""
    (tmp_path / "model.yaml").write_text(model)
    path = tmp_path / "s.yaml"
    body = f", {analysis}" if analysis else ""
    path.write_text(f"cranefe: 1\nmodel: model.yaml\neffects: {effects}\n"
                    f"analysis: {{type: transient{body}}}\n")
    return load(path), str(path)


def parsed(tmp_path, analysis, **kw):
    return parse(scene(tmp_path, analysis, **kw)[0])


def error(tmp_path, analysis, **kw):
    """(file is the scene, entry, message) of the ModelError parse raises."""
    model, path = scene(tmp_path, analysis, **kw)
    with pytest.raises(ModelError) as e:
        parse(model)
    assert str(e.value.file) == path
    return e.value.entry, e.value.message


# ------------------------------------------------------------------ time functions

def test_constant_profile_is_a_step_at_zero():
    p = Profile.constant(5.0)
    assert list(p.times) == [0.0] and p.values.tolist() == [[5.0]]
    assert p(-1.0).tolist() == [5.0] and p(7.0).tolist() == [5.0]
    assert p.rate(1.0).tolist() == [0.0]
    assert p.integral(3.0) == pytest.approx([15.0], rel=TOL)
    assert p.integral(0.0).tolist() == [0.0] and p.integral(-1.0).tolist() == [0.0]
    v = Profile.constant([1.0, 2.0, 3.0])
    assert v(0.5).tolist() == [1.0, 2.0, 3.0] and v.rate(0.5).tolist() == [0, 0, 0]
    assert Profile.constant(5.0, ramp=0.0).times.tolist() == [0.0]


def test_ramp_profile_value_slope_and_integral_by_hand():
    """ramp(4, 2): 2 t up to t = 2, then 4. Slope 2 on (0, 2): at t = 2 its right limit 0
    and its left limit 2; at 0 the right limit 2 and the left 0. Integral t^2 below 2,
    4 + 4 (t - 2) above."""
    p = Profile.constant(4.0, ramp=2.0)
    assert p.times.tolist() == [0.0, 2.0] and p.values.tolist() == [[0.0], [4.0]]
    assert p.breakpoints.tolist() == [0.0, 2.0]
    assert p(1.0).tolist() == [2.0] and p(3.0).tolist() == [4.0] and p(-1).tolist() == [0.0]
    assert p.rate(1.0).tolist() == [2.0]
    assert p.rate(2.0).tolist() == [0.0] and p.rate(2.0, left=True).tolist() == [2.0]
    assert p.rate(0.0).tolist() == [2.0] and p.rate(0.0, left=True).tolist() == [0.0]
    assert p.rate(5.0).tolist() == [0.0] and p.rate(-1.0).tolist() == [0.0]
    assert p.integral(1.0) == pytest.approx([1.0], rel=TOL)
    assert p.integral(2.0) == pytest.approx([4.0], rel=TOL)
    assert p.integral(3.0) == pytest.approx([8.0], rel=TOL)


def test_table_profile_holds_its_first_value_before_its_first_time():
    """[[0.5, 1], [1.5, 3], [2.5, 0]]: 1 before 0.5, 1 + 2 (t - 0.5) up to 1.5, down by 3 a
    second to 0, then 0. Integral to 1: 0.5 + (1 + 2) / 2 x 0.5 = 1.25; to 3: 0.5 + 2 +
    1.5 = 4."""
    p = Profile(np.array([0.5, 1.5, 2.5]), np.array([[1.0], [3.0], [0.0]]))
    assert p(0.0).tolist() == [1.0] and p(1.0).tolist() == [2.0] and p(2.0).tolist() == [1.5]
    assert p.rate(1.0).tolist() == [2.0] and p.rate(2.0).tolist() == [-3.0]
    assert p.rate(1.5).tolist() == [-3.0] and p.rate(1.5, left=True).tolist() == [2.0]
    assert p.rate(0.2).tolist() == [0.0]
    assert p.integral(1.0) == pytest.approx([1.25], rel=TOL)
    assert p.integral(3.0) == pytest.approx([4.0], rel=TOL)
    assert p.integral(0.25) == pytest.approx([0.25], rel=TOL)


def test_linear_motor():
    """M = M_s (1 - n / n_s), dM/dn = -M_s / n_s."""
    m = Motor("linear", 157.0, stall_torque=480.0)
    M, dM = m.torque(100.0)
    assert M == pytest.approx(480.0 * (1 - 100.0 / 157.0), rel=TOL)
    assert dM == pytest.approx(-480.0 / 157.0, rel=TOL)


def test_kloss_motor_torque_and_slope():
    """M = 2 M_k / (s / s_k + s_k / s), s = 1 - n / n_s: M = M_k at the breakdown slip (its
    peak: slope 0), 0 at synchronous speed, the slope by a central difference of this
    formula (step 1e-4 rad/s: error ~1e-8 relative)."""
    m = Motor("kloss", 157.0, breakdown_torque=480.0, breakdown_slip=0.3)

    def hand(n):
        s = 1 - n / 157.0
        return 2 * 480.0 / (s / 0.3 + 0.3 / s)
    M, dM = m.torque(157.0 * 0.7)
    assert M == pytest.approx(480.0, rel=TOL) and abs(dM) < 1e-12
    for n in (20.0, 80.0, 140.0, 160.0):
        M, dM = m.torque(n)
        assert M == pytest.approx(hand(n), rel=1e-12)
        assert dM == pytest.approx((hand(n + 1e-4) - hand(n - 1e-4)) / 2e-4, rel=1e-6)
    assert m.torque(157.0)[0] == 0.0


def test_table_motor_interpolates_and_is_flat_beyond_its_ends():
    """[[0, 260], [110, 480], [157, 0]]: slope 2 then -480/47; constant outside."""
    m = Motor("table", table=np.array([[0.0, 260.0], [110.0, 480.0], [157.0, 0.0]]))
    assert m.torque(55.0) == pytest.approx((370.0, 2.0), rel=TOL)
    assert m.torque(130.0) == pytest.approx((480.0 - 480.0 * 20 / 47, -480.0 / 47), rel=TOL)
    assert m.torque(110.0) == pytest.approx((480.0, 2.0), rel=TOL)
    assert m.torque(0.0) == pytest.approx((260.0, 2.0), rel=TOL)
    assert m.torque(157.0) == pytest.approx((0.0, -480.0 / 47), abs=1e-12)
    assert m.torque(200.0) == (0.0, 0.0) and m.torque(-5.0) == (260.0, 0.0)


# ------------------------------------------------------------------ the scene's keys

def test_defaults_of_docs_transient(tmp_path):
    t = parsed(tmp_path, "")
    assert t == Transient(2.0, None, 20000, "direct", 20, True, "static", (), None, (), ())
    assert t.breakpoints.tolist() == []


def test_every_key_given(tmp_path):
    """A speed drive ramped over 0.5 s (given as a rope speed 0.5 m/s: 0.5 / 0.25 = 2
    rad/s), a node force ramped over 0.1 s: steps end at 0.1 and 0.5 (0 and the ends of
    ramps beyond the duration are not breakpoints)."""
    t = parsed(tmp_path, "duration: 1.5, time_step: 0.0005, max_steps: 100, method: modal, "
               "modes: 5, static_correction: false, output_step: 0.01, "
               "drums: {hoist: {speed: 0.5 m/s, ramp: 0.5}}, "
               "forces: {B: {force: [0, 0, -5000], ramp: 0.1}}")
    assert (t.duration, t.time_step, t.max_steps, t.method, t.modes, t.static_correction,
            t.initial, t.grounded, t.output_step) == \
        (1.5, 0.0005, 100, "modal", 5, False, "static", (), 0.01)
    (d,), (f,) = t.drums, t.forces
    assert (d.drum, d.name, d.kind, d.motor) == (0, "hoist", "speed", None)
    assert d.profile.times.tolist() == [0.0, 0.5]
    assert d.profile.values == pytest.approx(np.array([[0.0], [2.0]]), rel=TOL)
    assert (f.node, f.name) == (load(tmp_path / "model.yaml").node_index["B"], "B")
    assert f.profile.times.tolist() == [0.0, 0.1]
    assert f.profile.values.tolist() == [[0, 0, 0], [0, 0, -5000]]
    assert t.breakpoints.tolist() == [0.1, 0.5]
    t = parsed(tmp_path, "duration: 0.3, drums: {hoist: {torque: [[0, 1], [0.2, 2], "
               "[0.4, 3]]}}")
    assert t.breakpoints.tolist() == [0.2]
    assert parsed(tmp_path, "time_step: 2.0").time_step == 2.0     # = duration: allowed


def test_drives(tmp_path):
    t = parsed(tmp_path, "drums: {hoist: {torque: 10200, ramp: 0.2}}")
    (d,) = t.drums
    assert (d.drum, d.name, d.kind, d.motor) == (0, "hoist", "torque", None)
    assert d.profile.times.tolist() == [0.0, 0.2]
    assert d.profile.values.tolist() == [[0.0], [10200.0]]
    d = parsed(tmp_path, "drums: {hoist: {speed: [[0, 0], [1, 3]]}}").drums[0]
    assert d.kind == "speed" and d.profile.values.tolist() == [[0.0], [3.0]]
    d = parsed(tmp_path, "drums: {hoist: {speed: 2.0}}").drums[0]
    assert d.profile.times.tolist() == [0.0] and d.profile.values.tolist() == [[2.0]]
    d = parsed(tmp_path, "drums: {hoist: {motor: {stall_torque: 480, "
               "synchronous_speed: 157}}}").drums[0]
    assert (d.drum, d.name, d.kind, d.profile, d.motor) == (
        0, "hoist", "motor", None, Motor("linear", 157.0, stall_torque=480.0))
    # the second of two drums: its index in model.drums
    two = HOIST.replace("  hoist: {node: D, radius: 0.25, inertia: 500.0}",
                        "  aux: {node: D, radius: 0.2, inertia: 10.0}\n"
                        "  hoist: {node: D, radius: 0.25, inertia: 500.0}")
    assert two != HOIST
    for drive in ("speed: 1", "torque: 2", "motor: {stall_torque: 1, synchronous_speed: 2}"):
        d = parsed(tmp_path, f"drums: {{hoist: {{{drive}}}}}", model=two).drums[0]
        assert (d.drum, d.name) == (1, "hoist"), drive
    assert error(tmp_path, "drums: {winch: {speed: 1}}", model=two) == (
        "analysis.drums.winch", "unknown drum 'winch'; drums of the model: aux, hoist")
    d = parsed(tmp_path, "drums: {hoist: {motor: {breakdown_torque: 480, "
               "breakdown_slip: 0.3, synchronous_speed: 157}}}").drums[0]
    assert d.motor == Motor("kloss", 157.0, breakdown_torque=480.0, breakdown_slip=0.3)
    d = parsed(tmp_path, "drums: {hoist: {motor: {characteristic: [[0, 260], [110, 480], "
               "[157, 0]]}}}").drums[0]
    assert d.motor.kind == "table"
    assert d.motor.table.tolist() == [[0, 260], [110, 480], [157, 0]]
    assert parsed(tmp_path, "drums: {}, forces: {}").drums == ()


GROUND2 = HOIST.replace(
    "masses: {B: 5000.0}", "masses: {B: 5000.0, C: 100.0, X: 10.0, S: 1.0, Y: 3.0, Z: 2.0}"
).replace(
    "nodes: {D: [0, 0, 0], S: [0, 0, 30], B: [0, 0, 10]}",
    "nodes: {D: [0, 0, 0], S: [0, 0, 30], B: [0, 0, 10], C: [1, 0, 5], X: [3, 0, 30], "
    "Y: [5, 0, 30], Z: [7, 0, 30], P: [9, 0, 30]}") + """springs:
  - {name: s, type: axial, nodes: [B, C], stiffness: 1.0e5}
  - {name: t, type: axial, nodes: [P, Y], stiffness: 1.0e5}
members:
  bar: {type: truss, pairs: [[S, X]], E: 2.1e11, A: 1.0e-3}
bodies:
  box: {mass: 10, com: [8, 0, 30], inertia: 1.0, nodes: [Z, P]}
"""


def test_grounded_loads(tmp_path):
    """initial: grounded (lift-off): by default every point mass at a node of its own
    hanging on ropes or springs (B, C, and Y on a spring below a body), not one on a
    member given by pairs (X), on a body (Z) or at a fixed node (S); or the listed ones."""
    model, _ = scene(tmp_path, "initial: grounded", model=GROUND2)
    idx = model.node_index
    t = parse(model)
    assert t.initial == "grounded" and t.grounded == (idx["B"], idx["C"], idx["Y"])
    t = parsed(tmp_path, "initial: grounded, grounded: [C, Z]", model=GROUND2)
    assert t.grounded == (idx["C"], idx["Z"])
    assert parsed(tmp_path, "initial: grounded").grounded == (2,)


def test_bounds_that_are_allowed(tmp_path):
    """max_steps 1, modes 1, a two-row motor table, ramp 0, fy in a 3D model; a motor
    drive has no breakpoints, a force's ramp end has."""
    t = parsed(tmp_path, "max_steps: 1, method: modal, modes: 1")
    assert (t.max_steps, t.modes) == (1, 1)
    t = parsed(tmp_path, "drums: {hoist: {motor: {characteristic: [[0, 2], [1, 0]]}}}, "
               "forces: {B: {force: [0, 0, 1], ramp: 0.1}}")
    assert t.drums[0].motor.table.tolist() == [[0, 2], [1, 0]]
    assert t.breakpoints.tolist() == [0.1]
    t = parsed(tmp_path, "drums: {hoist: {speed: 1, ramp: 0}}")
    assert t.drums[0].profile.times.tolist() == [0.0]
    t = parsed(tmp_path, "forces: {B: {force: [0, 1, 0]}}",
               model=HOIST.replace("plane: xz\n", ""))
    assert t.forces[0].profile.values.tolist() == [[0, 1, 0]]


ERRORS = [
    ("tyrp: 1", "analysis.tyrp", None),
    ("duration: 0", "analysis.duration", None),
    ("duration: 1, time_step: 1.5", "analysis.time_step",
     "1.5 s is longer than the duration (1 s); give a shorter step or leave it out "
     "(automatic)"),
    ("max_steps: 0", "analysis.max_steps", None),
    ("time_step: 0", "analysis.time_step", None),
    ("max_steps: 1.5", "analysis.max_steps", None),
    ("method: rk4", "analysis.method", "'rk4' is not one of direct, modal"),
    ("method: modal, modes: 0", "analysis.modes", None),
    ("modes: 4", "analysis.modes", "modes is the number of modes of method: modal; add "
     "method: modal or remove it"),
    ("static_correction: 1", "analysis.static_correction", None),
    ("initial: hanging", "analysis.initial", "'hanging' is not one of static, grounded"),
    ("initial: grounded, method: modal", "analysis.method",
     "lift-off changes the equations (the ground lets go), which modal superposition "
     "cannot follow; use method: direct with initial: grounded"),
    ("grounded: [B]", "analysis.grounded", "the loads on the ground are for initial: "
     "grounded"),
    ("initial: grounded, grounded: [Q]", "analysis.grounded[0]", "unknown node 'Q'"),
    ("initial: grounded, grounded: [B, S]", "analysis.grounded[1]",
     "node 'S' carries no point mass (masses:); only a load resting on the ground can "
     "lift off"),
    ("initial: grounded, grounded: []", "analysis.grounded", None),
    ("output_step: -1", "analysis.output_step", None),
    ("drums: [hoist]", "analysis.drums", "must be a mapping: drum name -> {speed: ...}, "
     "{torque: ...} or {motor: {...}}"),
    ("drums: {winch: {speed: 1}}", "analysis.drums.winch",
     "unknown drum 'winch'; drums of the model: hoist"),
    ("drums: {hoist: {sped: 1}}", "analysis.drums.hoist.sped", None),
    ("drums: {hoist: {speed: 1, torque: 2}}", "analysis.drums.hoist",
     "give exactly one of speed (rad/s), torque (N m at the drum, or a table [[t, M], "
     "...]) or motor {...} (docs/transient.md)"),
    ("drums: {hoist: {ramp: 1}}", "analysis.drums.hoist", None),
    ("drums: {hoist: {speed: 1, ramp: -1}}", "analysis.drums.hoist.ramp", None),
    ("drums: {hoist: {speed: x}}", "analysis.drums.hoist.speed", None),
    ("drums: {hoist: {torque: [[0, 1], [1, 2]], ramp: 1}}", "analysis.drums.hoist.torque",
     "a table gives the whole history; remove 'ramp'"),
    ("drums: {hoist: {torque: [[0, 1], [0, 2]]}}", "analysis.drums.hoist.torque",
     "the times (first column) must increase from row to row"),
    ("drums: {hoist: {torque: [[-1, 1], [1, 2]]}}", "analysis.drums.hoist.torque[0]",
     "times start at t >= 0"),
    ("drums: {hoist: {torque: [[0, 1], [1]]}}", "analysis.drums.hoist.torque[1]", None),
    ("drums: {hoist: {motor: {stall_torque: 1, synchronous_speed: 2}, ramp: 1}}",
     "analysis.drums.hoist.ramp", "a motor follows its characteristic; remove 'ramp'"),
    ("drums: {hoist: {motor: {stall_torque: 1}}}", "analysis.drums.hoist.motor",
     "give one characteristic: {stall_torque, synchronous_speed} (linear), "
     "{breakdown_torque, breakdown_slip, synchronous_speed} (Kloss) or "
     "{characteristic: [[n, M], ...]} (N m against rad/s at the motor shaft)"),
    ("drums: {hoist: {motor: {stall: 1}}}", "analysis.drums.hoist.motor.stall", None),
    ("drums: {hoist: {motor: {stall_torque: 1, synchronous_speed: 0}}}",
     "analysis.drums.hoist.motor.synchronous_speed", None),
    ("drums: {hoist: {motor: {stall_torque: x, synchronous_speed: 1}}}",
     "analysis.drums.hoist.motor.stall_torque", None),
    ("drums: {hoist: {motor: {breakdown_torque: 1, breakdown_slip: 1, "
     "synchronous_speed: 1}}}", "analysis.drums.hoist.motor.breakdown_slip",
     "1 is not a slip below 1 (typically 0.1-0.4)"),
    ("drums: {hoist: {motor: {breakdown_torque: 1, breakdown_slip: 0, "
     "synchronous_speed: 1}}}", "analysis.drums.hoist.motor.breakdown_slip", None),
    ("drums: {hoist: {motor: {breakdown_torque: 0, breakdown_slip: 0.3, "
     "synchronous_speed: 1}}}", "analysis.drums.hoist.motor.breakdown_torque", None),
    ("drums: {hoist: {motor: {characteristic: [[0, 1]]}}}",
     "analysis.drums.hoist.motor.characteristic", None),
    ("drums: {hoist: {motor: {characteristic: [[0, 1], [2]]}}}",
     "analysis.drums.hoist.motor.characteristic[1]", None),
    ("drums: {hoist: {motor: {characteristic: [[0, 1], [0, 2]]}}}",
     "analysis.drums.hoist.motor.characteristic",
     "the speeds (first column) must increase"),
    ("drums: {hoist: {motor: {characteristic: [[1, 1], [0, 2]]}}}",
     "analysis.drums.hoist.motor.characteristic",
     "the speeds (first column) must increase"),
    ("forces: [B]", "analysis.forces", "must be a mapping: node name -> {force: [fx, fy, "
     "fz]}"),
    ("forces: {Q: {force: [0, 0, 1]}}", "analysis.forces.Q", "unknown node 'Q'"),
    ("forces: {S: {force: [0, 0, 1]}}", "analysis.forces.S",
     "node 'S' is fixed (ground): a force on it does nothing"),
    ("forces: {B: {ramp: 1}}", "analysis.forces.B", None),
    ("forces: {B: {force: [0, 0, 1], ramp: -1}}", "analysis.forces.B.ramp", None),
    ("forces: {B: {force: [0, 0]}}", "analysis.forces.B.force", None),
    ("forces: {B: {force: [0, 1, 0]}}", "analysis.forces.B.force",
     "a plane: xz model moves in x and z only; give fy = 0"),
    ("forces: {B: {force: [[0, 0, 0, 0], [1, 0, 1, 0]]}}", "analysis.forces.B.force",
     "a plane: xz model moves in x and z only; give fy = 0"),
]


@pytest.mark.parametrize("analysis, entry, message", ERRORS)
def test_errors_name_the_scene_file_the_entry_and_the_fix(tmp_path, analysis, entry,
                                                          message):
    got = error(tmp_path, analysis)
    assert got[0] == entry
    if message is not None:
        assert got[1] == message


def test_errors_that_depend_on_the_model_or_effects(tmp_path):
    assert error(tmp_path, "initial: grounded", effects="{sway: true}") == (
        "analysis.initial", "a load resting on the ground has no pendulum stiffness: use "
        "initial: grounded with effects: {sway: false}")
    assert error(tmp_path, "drums: {hoist: {speed: 1}}",
                 effects="{sway: false, drive: held}") == (
        "analysis.drums.hoist", "with effects: {drive: held} the drum has no rotation "
        "coordinate; a driven drum needs drive: coupled")
    braked = HOIST.replace("inertia: 500.0}", "inertia: 500.0, brake: true}")
    assert braked != HOIST
    assert error(tmp_path, "drums: {hoist: {speed: 1}}", model=braked) == (
        "analysis.drums.hoist", "drum 'hoist' is braked in the model (brake: true), so it "
        "has no rotation to drive; set brake: false in the model")
    assert error(tmp_path, "drums: {hoist: {speed: 1}}", model=HOIST.replace(
        "drums:\n  hoist:", "drums:\n  other:").replace("path: [hoist,", "path: [other,")
    ) == ("analysis.drums.hoist", "unknown drum 'hoist'; drums of the model: other")
    # a load on a member only: nothing that can lift off
    bar = ("cranefe: 1\nplane: xz\nnodes: {S: [0, 0, 0], X: [1, 0, 0]}\nground: [S]\n"
           "masses: {X: 10}\nmembers:\n  bar: {type: truss, nodes: [S, X], E: 2.1e11, A: 1.0e-3}\n")
    assert error(tmp_path, "initial: grounded", model=bar) == (
        "analysis.initial", "initial: grounded needs a load hanging on ropes (a point mass "
        "at a node of its own); the model has none")
    assert error(tmp_path, "drums: {hoist: {speed: 1}}", model=bar) == (
        "analysis.drums.hoist", "unknown drum 'hoist'; drums of the model: none")


def test_not_a_transient_scene(tmp_path):
    (tmp_path / "model.yaml").write_text(HOIST)
    path = tmp_path / "s.yaml"
    path.write_text("cranefe: 1\nmodel: model.yaml\nanalysis: {type: modes}\n")
    with pytest.raises(ModelError) as e:
        parse(load(path))
    assert (str(e.value.file), e.value.entry) == (str(path), "analysis.type")
    assert e.value.message == ("this is not a transient scene: give analysis: {type: "
                               "transient, ...} (docs/transient.md)")
