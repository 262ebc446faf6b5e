"""Kill tests for cranefe/analysis/operation/shaped.py (tools/mutation.py shaped;
docs/testing.md, "Mutation testing"; docs/shaping.md): the shaper spec of a scene, the
impulse trains built from it, the shaped move, the crane's own frequencies for
`frequency: auto` and the scene pass - without running the engine (parse only: each
scene here parses in a few 10 ms; tests/test_shaping_engine.py runs the engine).

References, written here:
- impulse trains by hand: ZV (1/(1+K), K/(1+K)) at (0, pi/w_d), K = exp(-zeta pi /
  sqrt(1 - zeta^2)); EI undamped ((1+V)/4, (1-V)/2, (1+V)/4) at (0, T/2, T); a two-mode
  ZV as the four sums of the two trains' times with amplitudes 1/4;
- the shaped move as sum_i A_i s(t - t_i) with s(t) the trapezoid of the phases by hand;
- the overhead crane (models/operations/overhead_crane.yaml: 10.2 t on 4 falls of one
  rope, 6 m below the drum, EA 6.5e6 N, 24 m of falls + 1 m extra_length): the pendulum
  w^2 = g / 6 (the 4 falls' geometric stiffness 4 S / l = m g / l) and the hoisting mode
  w^2 = 16 EA / (25 m) / m (equal tension in the falls: the hook moves a quarter of the
  rope's stretch under a quarter of the force);
- the tower crane's hook (250 kg, 33.4 m) and load (4 t on a 3 m sling): the double
  pendulum's frequencies from scipy.linalg.eigh of its 2 x 2 K, M;
- a hook lowered by a drum: the pendulum length 6 m + r phi / 2 (both rope ends wound on
  the drum, 4 falls), phi the drum angle at the start of the shaped trolley move.

Tolerances: impulse trains and hand motions 1e-12; frequencies of the engine's Newton
static state (converged to 1e-10 of the model size) 1e-9 relative.
"""

from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import scipy.linalg as sl

from cranefe.analysis.operation import profiles
from cranefe.analysis.operation import shaped as sp
from cranefe.analysis.operation.scene import parse
from cranefe.errors import ModelError
from cranefe.model import load
from cranefe.model.load import _Reader

G = 9.81
ROOT = Path(__file__).resolve().parents[1] / "models" / "operations"
OVERHEAD = ROOT / "overhead_crane.yaml"
TOWER = ROOT / "tower_crane.yaml"
W_OH = np.sqrt(G / 6.0)
W_HOIST = np.sqrt(16 * 6.5e6 / 25.0 / 10200.0)
TOL = 1e-12
E = "analysis.drives.t.profile.shaper"


def scene(tmp_path, model, drives, duration=40, extra="", name="s.yaml"):
    path = tmp_path / name
    path.write_text(f"cranefe: 1\nscene: shaped kill test\nmodel: {model}\n{extra}"
                    f"analysis:\n  type: operation\n  duration: {duration}\n  drives:\n{drives}")
    return load(path)


def trolley(dist="1.0", v="0.5", a="0.5", shaper="{type: ZV}", start=0):
    return (f"    trolley: {{slider: trolley_travel, profile: {{type: trapezoid, "
            f"distance: {dist}, v_max: {v}, a_max: {a}, start: {start}, shaper: {shaper}}}}}\n")


def drive(op, name):
    return next(d for d in op.drives if d.name == name)


# ------------------------------------------------------------------ has_shaper, the spec

def test_has_shaper():
    assert not sp.has_shaper(None) and not sp.has_shaper({})
    assert not sp.has_shaper({"t": {"profile": {"type": "trapezoid"}}})
    assert not sp.has_shaper({"t": {"torque": 3.0, "shaper": {}}})
    assert not sp.has_shaper({"t": "free", "u": None})
    assert sp.has_shaper({"t": {"profile": {"type": "trapezoid", "shaper": {}}}})
    assert sp.has_shaper({"u": {"profile": {}},
                          "t": {"profile": [{"type": "x"}, 3, {"shaper": {}}]}})
    assert not sp.has_shaper({"t": {"profile": [{"type": "x"}, "shaper"]}})


def test_parse_shaper_values():
    r = _Reader("f.yaml")
    s = sp.parse_shaper(r, {"type": "ZVD"}, E)
    assert (s.kind, s.omegas, s.zeta, s.modes, s.V, s.entry) == ("ZVD", None, 0.0, None,
                                                                 0.05, E)
    s = sp.parse_shaper(r, {"type": "EI", "frequency": [0.2, 0.5], "damping": 0.1,
                            "V": 0.1}, E)
    assert s.kind == "EI" and s.zeta == 0.1 and s.V == 0.1 and s.modes is None
    assert np.allclose(s.omegas, [0.4 * np.pi, np.pi], rtol=1e-15)
    s = sp.parse_shaper(r, {"type": "ZV", "frequency": 0.25}, E)
    assert len(s.omegas) == 1 and s.omegas[0] == pytest.approx(np.pi / 2, rel=1e-15)
    s = sp.parse_shaper(r, {"type": "ZVDD", "frequency": "auto", "modes": [2, 1],
                            "damping": 0.99}, E)
    assert s.omegas is None and s.modes == (2, 1) and s.zeta == 0.99
    assert type(s.modes[0]) is int
    s = sp.parse_shaper(r, {"type": "EI"}, E)
    assert s.V == 0.05
    assert sp.ShaperSpec("ZV").zeta == 0.0 and sp.ShaperSpec("ZV").V == 0.05
    assert sp.ShaperSpec("ZV").omegas is None and sp.ShaperSpec("ZV").modes is None


@pytest.mark.parametrize("spec, entry, words", [
    ({}, E, "missing required key 'type'"),
    ({"type": "ZV", "speed": 3}, f"{E}.speed", "unknown key"),
    ({"type": "ZX"}, f"{E}.type", "'ZX' is not one of ZV, ZVD, ZVDD, EI"),
    ({"type": "ZV", "frequency": []}, f"{E}.frequency", "=an empty list; give auto, a "
     "frequency in Hz or a list of them (one per mode)"),
    ({"type": "ZV", "frequency": -1}, f"{E}.frequency", "positive"),
    ({"type": "ZV", "frequency": [0.2, 0]}, f"{E}.frequency", "positive"),
    ({"type": "ZV", "frequency": 0.2, "modes": [1]}, f"{E}.modes", "=modes selects among "
     "the crane's own modes: it goes with frequency: auto"),
    ({"type": "ZV", "damping": 1.0}, f"{E}.damping", "1: a damping ratio below 1"),
    ({"type": "ZV", "damping": -0.1}, f"{E}.damping", "negative"),
    ({"type": "ZV", "V": 0.1}, f"{E}.V", "=V (the tolerated residual) belongs to the EI "
     "shaper"),
    ({"type": "EI", "V": 1.0}, f"{E}.V", "1: the tolerated residual is a fraction below 1"),
    ({"type": "EI", "V": 0}, f"{E}.V", "positive"),
    ({"type": "ZV", "modes": [1.5]}, f"{E}.modes", "=mode numbers are whole numbers from "
     "1 (the lowest)"),
    ({"type": "ZV", "modes": [1, 0]}, f"{E}.modes[1]", "positive"),
    ({"type": "ZV", "modes": []}, f"{E}.modes", "at least 1"),
    ({"type": "ZV", "modes": 2}, f"{E}.modes", "must be a list"),
])
def test_parse_shaper_errors(spec, entry, words):
    with pytest.raises(ModelError) as e:
        sp.parse_shaper(_Reader("f.yaml"), spec, E)
    assert e.value.entry == entry and e.value.file == "f.yaml"
    if words.startswith("="):                    # the whole message
        assert e.value.message == words[1:]
    else:
        assert words in e.value.message


# ------------------------------------------------------------------ trains, shaped moves

def test_build_shaper_by_hand():
    w, z = 1.3, 0.1
    s = sp.build_shaper(sp.ShaperSpec("ZV", zeta=z), (w,))
    K = np.exp(-z * np.pi / np.sqrt(1 - z * z))
    assert np.allclose(s.times, [0, np.pi / (w * np.sqrt(1 - z * z))], rtol=0, atol=TOL)
    assert np.allclose(s.amplitudes, [1 / (1 + K), K / (1 + K)], rtol=0, atol=TOL)
    s = sp.build_shaper(sp.ShaperSpec("EI", V=0.1), (w,))
    T = 2 * np.pi / w
    assert np.allclose(s.times, [0, T / 2, T], rtol=0, atol=1e-9)
    assert np.allclose(s.amplitudes, [0.275, 0.45, 0.275], rtol=0, atol=1e-9)
    w1, w2 = 0.5, 2.0
    s = sp.build_shaper(sp.ShaperSpec("ZV"), (w1, w2))
    assert s.name == "ZV*ZV"
    t1, t2 = np.pi / w1, np.pi / w2
    assert np.allclose(np.sort(s.times), [0, t2, t1, t1 + t2], rtol=0, atol=TOL)
    assert np.allclose(s.amplitudes, 0.25, rtol=0, atol=TOL)
    s = sp.build_shaper(sp.ShaperSpec("ZVD"), (w1, w2, 3.7))
    assert s.name == "ZVD*ZVD*ZVD" and len(s.times) == 27


def _trap(t, D, v, a, t0):
    """Trapezoid (t_a = v/a, cruise, brake) by its phases: position at t."""
    ta, tc = v / a, D / v - v / a
    tau = t - t0
    if tau <= 0:
        return 0.0
    if tau < ta:
        return a * tau**2 / 2
    if tau < ta + tc:
        return v * ta / 2 + v * (tau - ta)
    if tau < 2 * ta + tc:
        u = 2 * ta + tc - tau
        return D - a * u**2 / 2
    return D


def test_shape_motion_by_hand():
    move = profiles.trapezoid(3.0, 1.0, 0.5, start=1.0)        # t_a 2, t_c 1
    train = SimpleNamespace(times=np.array([0.0, 0.7, 1.5]),
                            amplitudes=np.array([0.2, 0.5, 0.3]))
    out = sp.shape_motion(move, train)
    assert out.kind == "trapezoid"
    for t in (0.5, 1.4, 2.2, 3.1, 4.0, 5.3, 6.1, 6.9, 8.0, 9.0):
        want = sum(A * _trap(t - ti, 3.0, 1.0, 0.5, 1.0) for ti, A in
                   zip(train.times, train.amplitudes))
        assert out(t)[0] == pytest.approx(want, abs=TOL), t
    assert out.t[0] == 1.0 and out.t[-1] == pytest.approx(7.5, abs=TOL)
    assert out(7.5)[1] == pytest.approx(0.0, abs=TOL)


# ------------------------------------------------------------------ the crane's modes

def test_crane_modes_of_the_overhead_crane(tmp_path):
    m = scene(tmp_path, OVERHEAD, trolley())
    w, hor, vert, phi, mech = sp.crane_modes(m, parse(m), 0.0)
    assert np.allclose(w, [W_OH, W_HOIST], rtol=1e-9)
    assert np.allclose(hor, [1.0, 0.0], rtol=0, atol=1e-9)
    assert np.allclose(vert, [0.0, 1.0], rtol=0, atol=1e-9)
    assert phi.shape == (len(w), len(w))


def _double_pendulum(l1, l2, m1, m2):
    M = np.diag([m1, m2])
    K = G * np.array([[(m1 + m2) / l1 + m2 / l2, -m2 / l2], [-m2 / l2, m2 / l2]])
    return np.sqrt(sl.eigh(K, M, eigvals_only=True))


def test_auto_on_the_tower_crane(tmp_path):
    """Both pendulum modes, each once (the x and y swings are degenerate); modes: [2]
    keeps the second; mode 3 is refused naming both frequencies; the hoist drum's auto
    takes the lowest vertical mode."""
    ref = _double_pendulum(33.4, 3.0, 250.0, 4000.0)
    m = scene(tmp_path, TOWER, trolley("5.0", "1.0", "0.5"))
    op = parse(m)
    w, hor, _, _, _ = sp.crane_modes(m, op, 0.0)
    pend = w[hor > 0.5]
    assert np.allclose(pend, np.repeat(ref, 2), rtol=1e-9)
    (i, s, ws), = drive(op, "trolley").motion.shapers
    assert i == 0 and np.allclose(ws, ref, rtol=1e-9) and s.name == "ZV*ZV"
    assert all(type(x) is float for x in ws)
    m = scene(tmp_path, TOWER, trolley("5.0", "1.0", "0.5", "{type: ZV, modes: [2]}"))
    (_, s, ws), = drive(parse(m), "trolley").motion.shapers
    assert np.allclose(ws, ref[1:], rtol=1e-9) and s.name == "ZV"
    m = scene(tmp_path, TOWER, trolley("5.0", "1.0", "0.5", "{type: ZV, modes: [2, 1]}"))
    (_, s, ws), = drive(parse(m), "trolley").motion.shapers
    assert np.allclose(ws, ref[::-1], rtol=1e-9)
    m = scene(tmp_path, TOWER, trolley("5.0", "1.0", "0.5", "{type: ZV, modes: [1, 3]}"))
    with pytest.raises(ModelError) as e:
        parse(m)
    hz = ref / (2 * np.pi)
    assert e.value.entry == "analysis.drives.trolley.profile.shaper.modes"
    assert e.value.message.startswith(f"mode 3: the crane has 2 pendulum mode(s) at the "
                                      f"start of this move ({hz[0]:.4g}, {hz[1]:.4g} Hz)")
    assert e.value.file == m.scene_file


def test_auto_of_a_drum_takes_the_hoisting_mode(tmp_path):
    drums = ("    hoist: {drum: hoist, profile: {type: trapezoid, distance: -2, v_max: 1, "
             "a_max: 1, shaper: {type: ZV}}}\n")
    (i, s, ws), = drive(parse(scene(tmp_path, OVERHEAD, drums)), "hoist").motion.shapers
    assert ws == pytest.approx((W_HOIST,), rel=1e-9)
    assert s.times[1] == pytest.approx(np.pi / W_HOIST, rel=1e-9)


def test_auto_of_the_tower_crane_hoist_takes_only_the_lowest_vertical_mode(tmp_path):
    """The tower crane has two mostly vertical modes (16.2 and 382 rad/s): a drum's auto
    takes the lowest only; modes: [2] is refused naming the one hoisting mode."""
    def hoist(shaper):
        return ("    hoist: {drum: hoist, profile: {type: trapezoid, distance: 1, v_max: 1, "
                f"a_max: 1, shaper: {shaper}}}}}\n")
    m = scene(tmp_path, TOWER, hoist("{type: ZV}"))
    op = parse(m)
    w, hor, _, _, _ = sp.crane_modes(m, op, 0.0)
    vert = w[hor < 0.5]
    assert len(vert) == 2
    (_, s, ws), = drive(op, "hoist").motion.shapers
    assert ws == (pytest.approx(vert[0], rel=1e-12),) and s.name == "ZV"
    with pytest.raises(ModelError) as e:
        parse(scene(tmp_path, TOWER, hoist("{type: ZV, modes: [2]}")))
    assert e.value.message == (f"mode 2: the crane has 1 hoisting (vertical) mode(s) at the "
                               f"start of this move ({vert[0] / (2 * np.pi):.4g} Hz); number "
                               "them from 1")


def test_static_state_of_a_moving_crane_is_at_rest(tmp_path):
    """crane_modes at times the trolley accelerates (0.5 s), cruises (5 s) and after it
    has travelled 10 m (15 s): the static state of that geometry at rest (no inertial
    load, the pendulum hanging straight below the trolley 10 m away from where the
    model has it): always sqrt(g / 6 m)."""
    drives = ("    trolley: {slider: trolley_travel, profile: [{type: trapezoid, distance: 10, "
              "v_max: 1, a_max: 0.5}, {type: trapezoid, distance: 1, v_max: 0.5, a_max: 0.5, "
              "start: 15, shaper: {type: ZV}}]}\n")
    m = scene(tmp_path, OVERHEAD, drives)
    op = parse(m)
    for t in (0.5, 5.0, 15.0):
        w, hor, _, _, _ = sp.crane_modes(m, op, t)
        assert np.allclose(w, [W_OH, W_HOIST], rtol=1e-9), t
    (i, _, ws), = drive(op, "trolley").motion.shapers
    assert i == 1 and ws == (pytest.approx(W_OH, rel=1e-9),)


def test_auto_refused_without_sway(tmp_path):
    m = scene(tmp_path, OVERHEAD, trolley(), extra="effects: {sway: false}\n")
    with pytest.raises(ModelError) as e:
        parse(m)
    assert e.value.message == ("frequency: auto shapes for the pendulum modes, and with "
                               "effects sway: false the loads do not swing; give the "
                               "frequency in Hz or turn sway on")
    assert e.value.entry == "analysis.drives.trolley.profile.shaper"
    assert e.value.file == m.scene_file
    # given in Hz it needs no modes
    m = scene(tmp_path, OVERHEAD, trolley(shaper="{type: ZV, frequency: 0.5}"),
              extra="effects: {sway: false}\n")
    (_, s, ws), = drive(parse(m), "trolley").motion.shapers
    assert ws == pytest.approx((np.pi,), rel=1e-15)


# ------------------------------------------------------------------ the scene pass

def test_auto_sees_the_geometry_left_by_the_shaped_moves_before(tmp_path):
    """The hoist pays out 8/0.15 rad in 11.67 s (v 5 rad/s, a 5), ZV-shaped at 0.1 Hz
    (5 s longer); the trolley (listed first) starts at 14 s with ZV auto. The shaped
    hoist then stands at phi = (D + phi_unshaped(9 s)) / 2 = (53.33 + 42.5) / 2 rad:
    the hook 0.075 phi lower, w^2 = g / (6 + 0.075 phi). Unshaped moves first, or in the
    order listed, would give l = 10 m."""
    D = 8.0 / 0.15
    drives = (trolley("2.0", "0.5", "0.5", "{type: ZV}", start=14)
              + f"    hoist: {{drum: hoist, profile: {{type: trapezoid, distance: {-D}, "
              f"v_max: 5, a_max: 5, shaper: {{type: ZV, frequency: 0.1}}}}}}\n")
    op = parse(scene(tmp_path, OVERHEAD, drives))
    phi = 0.5 * (D + (2.5 + 5.0 * 8.0))
    (_, s, ws), = drive(op, "trolley").motion.shapers
    assert ws[0] == pytest.approx(np.sqrt(G / (6.0 + 0.075 * phi)), rel=1e-9)
    hoist = drive(op, "hoist").motion
    assert isinstance(hoist, sp.ShapedMotion)
    assert hoist.t[-1] == pytest.approx(D / 5 + 1 + 5.0, rel=1e-12)
    assert hoist(14.0)[0] == pytest.approx(-phi, rel=1e-12)


def test_a_list_of_shaped_moves(tmp_path):
    """Two trolley moves, each shaped (ZV at 0.25 Hz: +2 s; at 0.5 Hz: +1 s): the
    ShapedMotion lists (move index, train, frequencies) in move order; the motion is the
    two shaped moves' sum (positions by hand)."""
    drives = ("    trolley:\n      slider: trolley_travel\n      profile:\n"
              "        - {type: trapezoid, distance: 3, v_max: 1, a_max: 0.5, start: 1, "
              "shaper: {type: ZV, frequency: 0.25}}\n"
              "        - {type: trapezoid, distance: -3, v_max: 1, a_max: 0.5, start: 10, "
              "shaper: {type: ZV, frequency: 0.5}}\n")
    op = parse(scene(tmp_path, OVERHEAD, drives))
    mo = drive(op, "trolley").motion
    assert [x[0] for x in mo.shapers] == [0, 1]
    assert mo.shapers[0][2] == pytest.approx((np.pi / 2,)) and \
        mo.shapers[1][2] == pytest.approx((np.pi,))
    for t in (2.0, 4.5, 7.2, 9.5, 11.3, 13.0, 15.9, 18.0):
        want = (0.5 * _trap(t, 3, 1, 0.5, 1) + 0.5 * _trap(t - 2, 3, 1, 0.5, 1)
                - 0.5 * _trap(t, 3, 1, 0.5, 10) - 0.5 * _trap(t - 1, 3, 1, 0.5, 10))
        assert mo(t)[0] == pytest.approx(want, abs=TOL), t
    assert mo.moves() == [(1.0, 8.0), (10.0, 16.0)]


def test_a_shaped_move_that_runs_into_the_next_is_refused(tmp_path):
    """The first move ends at 3 s, shaped (ZV 0.1 Hz) at 8 s; the second starts at 6 s.
    A second that starts exactly when the shaped first ends is accepted."""
    def two(start2):
        return ("    trolley:\n      slider: trolley_travel\n      profile:\n"
                "        - {type: trapezoid, distance: 1, v_max: 0.5, a_max: 0.5, "
                "shaper: {type: ZV, frequency: 0.1}}\n"
                f"        - {{type: trapezoid, distance: -1, v_max: 0.5, a_max: 0.5, "
                f"start: {start2}}}\n")
    with pytest.raises(ModelError) as e:
        parse(scene(tmp_path, OVERHEAD, two(6)))
    assert e.value.entry == "analysis.drives.trolley.profile[1].start"
    assert e.value.message == ("starts at 6 s, before the previous (shaped) move ends (8 s: "
                               "the shaper adds its duration)")
    # the second move's own start counts (not its second breakpoint, 8.5 s), against
    # the shaped first's end (not its breakpoint before, 7 s), to 1e-12 s
    with pytest.raises(ModelError, match=r"starts at 7.5 s, before"):
        parse(scene(tmp_path, OVERHEAD, two(7.5)))
    with pytest.raises(ModelError, match=r"starts at 7.99 s, before"):
        parse(scene(tmp_path, OVERHEAD, two(7.99)))
    mo = drive(parse(scene(tmp_path, OVERHEAD, two(8))), "trolley").motion
    # the ZV copies of the 3 s move (at 0 and 5 s) leave a rest from 3 to 5 s
    assert mo.moves() == [(0.0, 3.0), (5.0, 11.0)]


def test_a_bad_shaper_in_a_list_names_its_move(tmp_path):
    drives = ("    trolley:\n      slider: trolley_travel\n      profile:\n"
              "        - {type: trapezoid, distance: 1, v_max: 0.5, a_max: 0.5}\n"
              "        - {type: trapezoid, distance: -1, v_max: 0.5, a_max: 0.5, start: 6, "
              "shaper: {type: ZX}}\n")
    with pytest.raises(ModelError) as e:
        parse(scene(tmp_path, OVERHEAD, drives))
    assert e.value.entry == "analysis.drives.trolley.profile[1].shaper.type"


def test_drives_after_an_unshaped_kind_are_shaped(tmp_path):
    """A torque drive listed first does not stop the pass: the trolley after it is
    shaped, and keeps its motion's kind."""
    drives = ("    hoist: {drum: hoist, torque: 0}\n"
              + trolley(shaper="{type: ZV, frequency: 0.25}"))
    op = parse(scene(tmp_path, OVERHEAD, drives))
    mo = drive(op, "trolley").motion
    assert isinstance(mo, sp.ShapedMotion) and mo.t[-1] == pytest.approx(5.0, abs=TOL)
    plain = drive(parse(scene(tmp_path, OVERHEAD, drives.replace(
        ", shaper: {type: ZV, frequency: 0.25}", ""))), "trolley").motion
    assert mo.kind == plain.kind == "trapezoid"


def test_speed_tables(tmp_path):
    """A table that starts moving at t = 0 cannot be shaped; one from rest is."""
    def table(rows):
        return (f"    trolley: {{slider: trolley_travel, profile: {{type: table, speed: "
                f"{rows}, shaper: {{type: ZV, frequency: 0.25}}}}}}\n")
    with pytest.raises(ModelError) as e:
        parse(scene(tmp_path, OVERHEAD, table("[[0, 0.5], [2, 0.5], [3, 0]]")))
    assert e.value.entry == "analysis.drives.trolley.profile"
    assert "starts moving at t = 0 cannot be shaped" in e.value.message
    mo = drive(parse(scene(tmp_path, OVERHEAD, table("[[0, 0], [1, 0.5], [3, 0.5], [4, 0]]"))),
               "trolley").motion
    assert mo(10.0)[0] == pytest.approx(1.5, abs=TOL)
    assert mo.t[-1] == pytest.approx(6.0, abs=TOL)
    # a table starting at rest but from a negative speed is refused too
    with pytest.raises(ModelError, match="cannot be shaped"):
        parse(scene(tmp_path, OVERHEAD, table("[[0, -0.5], [2, 0]]")))


def test_unshaped_scene_and_unshaped_drives_pass_through(tmp_path):
    drives = ("    trolley: {slider: trolley_travel, profile: {type: trapezoid, "
              "distance: 1, v_max: 0.5, a_max: 0.5}}\n"
              "    hoist: {drum: hoist, profile: {type: trapezoid, distance: -2, v_max: 1, "
              "a_max: 1, shaper: {type: ZV, frequency: 0.5}}}\n")
    op = parse(scene(tmp_path, OVERHEAD, drives))
    assert not isinstance(drive(op, "trolley").motion, sp.ShapedMotion)
    assert isinstance(drive(op, "hoist").motion, sp.ShapedMotion)
    op = parse(scene(tmp_path, OVERHEAD, drives.replace(
        ", shaper: {type: ZV, frequency: 0.5}", "")))
    assert not any(isinstance(d.motion, sp.ShapedMotion) for d in op.drives)


def test_shaped_moves_take_the_units_of_their_drive(tmp_path):
    """Regression (found by this mutation work): the scene pass re-read each move with
    `target == "hinge"` in place of the target and no drum radius, so a shaped move with
    units (1 m, 0.5 m/s on a slider; a rope length on a drum) or with _deg keys on a
    hinge was refused ("v_max of a False drive ..."). The shaped move is the unshaped
    one's convolution whatever units it is given in."""
    plain = parse(scene(tmp_path, OVERHEAD, trolley(shaper="{type: ZV, frequency: 0.25}")))
    units = parse(scene(tmp_path, OVERHEAD, trolley("1 m", "0.5 m/s", "0.5 m/s^2",
                                                    "{type: ZV, frequency: 0.25}")))
    a, b = drive(plain, "trolley").motion, drive(units, "trolley").motion
    assert np.allclose(a.t, b.t, rtol=0, atol=TOL) and np.allclose(a.s, b.s, atol=TOL)
    rope = parse(scene(tmp_path, OVERHEAD, (
        "    hoist: {drum: hoist, profile: {type: trapezoid, distance: -0.3 m, "
        "v_max: 0.15 m/s, a_max: 1, shaper: {type: ZV, frequency: 0.5}}}\n")))
    mo = drive(rope, "hoist").motion
    assert mo(20.0)[0] == pytest.approx(-2.0, rel=1e-12)        # 0.3 m / r = 2 rad
    assert mo.t[-1] == pytest.approx(2.0 + 1 + 1.0, rel=1e-12)  # t_a 1 s, t_c 1 s, ZV + 1 s
    slew = parse(scene(tmp_path, TOWER, (
        "    slew: {hinge: slewing, profile: {type: trapezoid, distance_deg: 30, "
        "v_max_deg: 10, a_max_deg: 5, shaper: {type: ZV, frequency: 0.1}}}\n")))
    mo = drive(slew, "slew").motion
    assert mo(20.0)[0] == pytest.approx(np.pi / 6, rel=1e-12)
    assert np.allclose(mo.t, [0, 2, 3, 5, 7, 8, 10], rtol=0, atol=TOL)


def test_auto_with_a_free_joint(tmp_path):
    """Regression (found by this mutation work): crane_modes set q[:nx] (point masses,
    then the joint coordinates) from the point masses alone and took E phi over all nx
    coordinates, so frequency: auto on a scene with a free joint (here the luffing
    crane's boom, free on its hinge, held by its luffing rope) or an elastic structure
    raised a ValueError with a traceback. The hook's pendulum mode is horizontal, the
    hoist drum's auto takes the lowest mostly vertical mode."""
    path = tmp_path / "free.yaml"
    path.write_text(f"cranefe: 1\nscene: free boom\nmodel: {ROOT / 'luffing_crane.yaml'}\n"
                    "analysis:\n  type: operation\n  duration: 40\n  drives:\n"
                    "    boom: {hinge: luffing, free: true}\n"
                    "    hoist: {drum: hoist, profile: {type: trapezoid, distance: 5, "
                    "v_max: 1, a_max: 1, shaper: {type: ZV}}}\n")
    m = load(path)
    op = parse(m)
    w, hor, vert, phi, mech = sp.crane_modes(m, op, 0.0)
    assert mech.nJ == 1 and phi.shape == (mech.nx, mech.nx) and len(w) == mech.nx
    assert np.all(np.isfinite(w)) and np.all((hor > -1e-9) & (hor < 1 + 1e-9))
    assert np.any(hor > 0.999)                                  # the hook's swing
    (_, s, ws), = drive(op, "hoist").motion.shapers
    assert ws == (pytest.approx(w[vert > 0.5][0], rel=1e-12),)
