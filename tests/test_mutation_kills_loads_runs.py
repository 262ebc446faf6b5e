"""Kill tests for cranefe/analysis/loads/runs.py (tools/mutation.py loads_runs;
docs/testing.md, "Mutation testing"): every run behind the dynamic factors on models of
one or two masses, each checked against its closed form, in a few seconds.

The hoist (as in docs/loads.md, "Single-mass references"): a drum (R = 0.25 m, J = 500
kg m^2) hauls a 2-fall tackle carrying m = 5000 kg; the rope is 30 + 2 x 20 = 70 m long
with EA = 3.15e6 N, so k = EA / 70 = 45 000 N/m. With the drum's speed prescribed the
hook's relative coordinate z obeys m z'' + n^2 k z = -m a_hook(t): w^2 = n^2 k / m = 36
s^-2, and the rope force is S0 + (m / n) (a_hook - z''). A prescribed drum speed that is
piecewise linear in time (the transient core's tables) gives a piecewise constant hook
acceleration, so the force is the sum of step responses
    S(t) = S0 + (m / n) sum_i da_i (1 - cos w (t - t_i)),  t > t_i        (1)
(da_i the jumps of the hook acceleration at t_i). The lift-off at a steady hook speed v
(rope end moving at v from t = 0, the load resting): n S = m g at t = g / (w^2 v), then
phi2 = 1 + v w / g.

Tolerances: the trapezoidal rule keeps the amplitude of an undamped oscillator, its
period error is (w h)^2 / 12 = 3e-4 at w h = 0.06, and the engine interpolates its peaks
(cubic Hermite): a peak of (1) to 1e-4 (the analysis kill tests measure 1.3e-5); exact
numbers (names, durations, guesses, speeds) to 1e-12. The operation engine's moves are
compared with the linear pendulum (below) to 2e-3 (swing 1.8 deg: the pendulum's
nonlinearity theta^2 / 16 = 6e-5; the engine's local tolerance 1e-6; the elastic rope
lengthens the pendulum by m g / EA = 1e-2 m of 2 m, 5e-3 in length, 2.5e-3 in w over
the ~1 rad of phase; measured 7e-4).

The operation engine's compiled loop (numba) is switched off here: its first compilation
costs about a minute in a fresh copy (mutmut's); the numpy step is the reference it is
tested against (tests/test_operation_fast.py).
"""

import time

import numpy as np
import pytest

from cranefe.analysis.loads import runs
from cranefe.analysis.loads.scene import JointMove, LoadsSpec
from cranefe.errors import AnalysisError
from cranefe.model import load

G = 9.81
M, R, J, EA, FALLS = 5000.0, 0.25, 500.0, 3.15e6, 2
K = EA / 70.0
W = np.sqrt(FALLS**2 * K / M)                       # 6 rad/s
S0 = M * G / FALLS
TOL = 1e-4

# a 10 kg mass on the ground node S listed first: the load's mass is found by node
HOIST = f"""cranefe: 1
name: single mass on an elastic rope
plane: xz
nodes: {{D: [0, 0, 0], S: [0, 0, 30], H: [0, 0, 10]}}
ground: [D, S]
masses: {{S: 10.0, H: {M}}}
drums:
  hoist: {{node: D, radius: {R}, inertia: {J}, brake: false}}
ropes:
  hoist_rope: {{EA: {EA}, path: [hoist, S, {{node: H, falls: {FALLS}}}]}}
"""


@pytest.fixture(autouse=True)
def numpy_operation_engine(monkeypatch):
    from cranefe.analysis.operation import fast
    monkeypatch.setattr(fast, "available", lambda: False)


def spec(**kw):
    """A checked loads spec written out (scene.py's parse is tested elsewhere)."""
    base = dict(drum="hoist", loads=("H",), speed=0.5, creep=0.05, ramp=1.0, jerk=0.0,
                fraction=0.25, release_time=0.0, moves=(), after_lift_off=0.6,
                time_step=0.01)
    base.update(kw)
    return LoadsSpec(**base)


def hoist(text=HOIST):
    return runs.lift_model(load("hoist.yaml", text))


def timed(run, *args, **kw):
    """run(*args, **kw) and its trace's `seconds`, which must lie within the wall time
    of the call (a cost, measured by the run: between 0 and what the caller saw)."""
    t0 = time.perf_counter()
    out = run(*args, **kw)
    wall = time.perf_counter() - t0
    seconds = out[-2].seconds if run is runs.hoist_start or run is runs.joint_move \
        else out[-1].seconds
    assert 0 <= seconds <= wall
    return out


def test_trace_document():
    t = runs.Trace("x", "transient", {"a": 1}, 2.5, 10, 0.12345678)
    assert t.to_dict() == {"name": "x", "engine": "transient", "parameters": {"a": 1},
                           "duration_s": 2.5, "steps": 10, "seconds": 0.123457}


def test_lift_model_is_a_vertical_undamped_lift():
    m = load("h.yaml", HOIST + "effects: {sway: true, damping: modal}\n")
    e = runs.lift_model(m).effects
    assert (e.sway, e.damping) == (False, "none")
    assert e.drive == m.effects.drive and e.rope_mass == m.effects.rope_mass


def test_working_point_without_ground_and_with_gravity_along_y():
    """No ground node: the axis is through the origin. Gravity (0, -4, 0): up is +y, so
    the radius is measured in the x-z plane; a node on the axis goes to +x (the chosen
    azimuth), a node at (3, 7, 4) (5 m off at azimuth (3, 0, 4) / 5) to radius 10:
    (6, 7, 8), C 0.5 m off at +z to (0, 3, 10); hook_height puts H's y to 2.5, x and z
    kept."""
    text = """cranefe: 1
nodes: {A: [0, 9, 0], B: [3, 7, 4], H: [1, 5, 2], C: [0, 3, 0.5]}
ground: []
gravity: [0, -4, 0]
masses: {H: 100, B: 100}
springs:
  - {name: s1, type: axial, nodes: [A, H], stiffness: 1.0e5}
"""
    m = load("p.yaml", text)
    s = spec(radius=10.0, radius_nodes=("A", "B", "C"), hook_height=2.5)
    X = runs.placed(m, s).coords
    assert X[m.node_index["C"]] == pytest.approx([0.0, 3.0, 10.0], abs=1e-12)   # 0.5 m off
    assert X[m.node_index["A"]] == pytest.approx([10.0, 9.0, 0.0], abs=1e-12)
    assert X[m.node_index["B"]] == pytest.approx([6.0, 7.0, 8.0], abs=1e-12)
    assert X[m.node_index["H"]] == pytest.approx([1.0, 2.5, 2.0], abs=1e-12)
    assert runs.placed(m, spec()) is m                 # no working point: as modelled
    # radius only (H stays), height only (A, B stay)
    X = runs.placed(m, spec(radius=10.0, radius_nodes=("B",))).coords
    assert X[m.node_index["H"]] == pytest.approx([1.0, 5.0, 2.0], abs=1e-12)
    X = runs.placed(m, spec(hook_height=-1.0)).coords
    assert X[m.node_index["H"]] == pytest.approx([1.0, -1.0, 2.0], abs=1e-12)
    assert X[m.node_index["B"]] == pytest.approx([3.0, 7.0, 4.0], abs=1e-12)


def test_working_point_about_the_first_ground_node():
    """The axis through the first ground node D = (2, 1, 3) (not S); a node at
    (5, 5, 30) is 5 m off it at azimuth (3, 4) / 5: radius 10 -> (8, 9, 30); H below it
    likewise -> (8, 9, 10) (3D model: no plane)."""
    text = HOIST.replace("nodes: {D: [0, 0, 0], S: [0, 0, 30], H: [0, 0, 10]}",
                         "nodes: {D: [2, 1, 3], S: [5, 5, 30], H: [5, 5, 10]}").replace(
                             "plane: xz\n", "")
    m = load("g.yaml", text)
    X = runs.placed(m, spec(radius=10.0, radius_nodes=("S", "H"))).coords
    assert X[m.node_index["S"]] == pytest.approx([8.0, 9.0, 30.0], abs=1e-12)
    assert X[m.node_index["H"]] == pytest.approx([8.0, 9.0, 10.0], abs=1e-12)


@pytest.mark.parametrize("falls", [1, 2, 3])
def test_hook_travel_per_drum_radian(falls):
    """R / falls from the drum's rope row, whatever else hangs below: a second mass B
    on a 4-fall tackle under H (its row has larger coefficients but no drum)."""
    text = HOIST.replace(f"falls: {FALLS}", f"falls: {falls}").replace(
        "H: [0, 0, 10]}", "H: [0, 0, 10], B: [0, 0, 5]}").replace(
        "H: 5000.0}", "H: 5000.0, B: 1000.0}") + \
        "  lower: {EA: 1.0e7, path: [H, {node: B, falls: 4}]}\n"
    assert runs.hook_per_drum(load("b.yaml", text), "hoist") == \
        pytest.approx(R / falls, rel=1e-12)


@pytest.mark.parametrize("first", [True, False])
def test_a_drum_with_two_ropes(first):
    """Two ropes leave the drum: the 2-fall hoist of H and a single fall to B; the mass
    moved most (H, coefficient 2) decides: R / 2, in either order of the ropes."""
    other = "  aux: {EA: 1.0e7, path: [hoist, T, B]}\n"
    text = HOIST.replace("H: [0, 0, 10]}", "H: [0, 0, 10], T: [6, 0, 30], B: [6, 0, 10]}")\
        .replace("ground: [D, S]", "ground: [D, S, T]").replace(
            "H: 5000.0}", "H: 5000.0, B: 1000.0}")
    if first:
        text += other
    else:
        text = text.replace("ropes:\n", "ropes:\n" + other)
    assert runs.hook_per_drum(load("two.yaml", text), "hoist") == \
        pytest.approx(R / FALLS, rel=1e-12)


def test_a_drum_that_moves_no_mass():
    bare = HOIST.replace("[hoist, S, {node: H, falls: 2}]", "[hoist, S]") + \
        "  other: {EA: 1.0e7, path: [S, H]}\n"
    with pytest.raises(AnalysisError) as e:
        runs.hook_per_drum(load("b.yaml", bare), "hoist")
    assert str(e.value) == ("drum 'hoist' moves no point mass through its rope; cranefe "
                            "loads needs a hoist load hanging on the drum's rope")


@pytest.mark.parametrize("ramp, jerk, h", [(2.0, 0.5, 0.01), (1.0, 0.5, 0.2),
                                           (1.0, 0.25, 0.05), (1.0, 0.0, 0.01)])
def test_s_curve_speed_table(ramp, jerk, h):
    """a = v / (ramp - t_j); v = a t^2 / (2 t_j) up to t_j, a (t - t_j / 2) on, then
    v_max - a (ramp - t)^2 / (2 t_j); max(8, ceil(t_j / h)) + 1 points on each rounded
    part (a shared middle point once); jerk 0: the straight ramp."""
    v = 3.0
    table, a = runs.s_curve_speeds(v, ramp, jerk, h)
    assert a == pytest.approx(v / (ramp - jerk), rel=1e-14)
    if jerk == 0:
        assert table == [[0.0, 0.0], [ramp, v]]
        return
    t, s = np.array(table).T
    n = {0.01: 50, 0.2: 8, 0.05: 8}[h]
    exact = np.where(t <= jerk, a * t**2 / (2 * jerk),
                     np.where(t <= ramp - jerk, a * (t - jerk / 2),
                              v - a * (ramp - t) ** 2 / (2 * jerk)))
    np.testing.assert_allclose(s, exact, rtol=0, atol=1e-12)
    shared = ramp == 2 * jerk
    assert len(t) == 2 * (n + 1) - shared
    np.testing.assert_allclose(t[:n + 1], np.linspace(0, jerk, n + 1), atol=1e-12)
    np.testing.assert_allclose(t[-n - 1:], ramp - np.linspace(0, jerk, n + 1)[::-1],
                               atol=1e-12)


def test_table_step():
    """min(time_step, t_j / 16, 0.01)."""
    assert runs._table_step(spec(time_step=None, jerk=0.0)) == 0.01
    assert runs._table_step(spec(time_step=None, jerk=0.32)) == 0.01
    assert runs._table_step(spec(time_step=None, jerk=0.08)) == 0.005
    assert runs._table_step(spec(time_step=0.002, jerk=0.08)) == 0.002
    assert runs._table_step(spec(time_step=0.02, jerk=0.0)) == 0.01


def test_default_time_step():
    """60 steps a period of the highest mode of the lift model (drum free:
    w^2 = k (n^2 / m + R^2 / J)); a given step is kept; no model: no step."""
    lift = hoist()
    w_max = np.sqrt(K * (FALLS**2 / M + R**2 / J))
    assert runs._steps(spec(time_step=None), lift) == {
        "max_steps": 10**7, "time_step": pytest.approx(2 * np.pi / (60 * w_max),
                                                       rel=1e-9)}
    assert runs._steps(spec(time_step=0.003), lift) == {"max_steps": 10**7,
                                                        "time_step": 0.003}
    assert runs._steps(spec(time_step=None)) == {"max_steps": 10**7}
    # a soft rope (EA / 100): w_max = 0.645 rad/s, below 1, still 60 steps a period
    soft = hoist(HOIST.replace(f"EA: {EA}", f"EA: {EA / 100}"))
    w_soft = np.sqrt(K / 100 * (FALLS**2 / M + R**2 / J))
    assert w_soft < 1
    assert runs._steps(spec(time_step=None), soft)["time_step"] == \
        pytest.approx(2 * np.pi / (60 * w_soft), rel=1e-9)


def lifted(res, v):
    """The lift-off's closed forms at the hook speed v."""
    t_lift = G / (W**2 * v)
    assert res.lift_off_time == pytest.approx(t_lift, rel=1e-6)
    assert res.rope_force_max[0] == pytest.approx(S0 * (1 + v * W / G), rel=TOL)
    return t_lift


def test_lift_off_retries_a_short_guess():
    """0.125 m/s: lift-off at 2.18 s. Default guess 1 s: 1.6 s unlifted -> 4 x 1 s:
    4.6 s covers 2.18 + 0.6. A guess of 0.5 s: 1.1 s unlifted -> 2 s: lifted at 2.18,
    but 2.78 > 2.6 -> 1.05 x 2.18 + 0.6."""
    lift = hoist()
    v = 0.125
    res, tr = timed(runs.lift_off, lift, spec(time_step=0.04), "slow", v / (R / FALLS))
    assert res.lift_off_time == pytest.approx(G / (W**2 * v), rel=1e-6)
    assert tr.duration == pytest.approx(4.6, rel=1e-12) == res.duration
    assert (res.initial, res.ground_names, res.scene) == ("grounded", ("H",),
                                                          "loads: slow")
    assert tr.name == "slow" and tr.engine == "transient" and tr.steps == res.steps == 115
    assert tr.parameters == {"initial": "grounded", "loads": ["H"], "drum": "hoist",
                             "drum_speed_rad_s": 1.0,
                             "start": "step to full speed at t = 0",
                             "time_step_s": pytest.approx(0.04, rel=1e-12),
                             "effects": {"sway": False, "damping": "none"}}
    res, tr = runs.lift_off(lift, spec(time_step=0.04), "slow", v / (R / FALLS), guess=0.5)
    t_lift = res.lift_off_time
    assert t_lift == pytest.approx(G / (W**2 * v), rel=1e-6)
    assert tr.duration == pytest.approx(1.05 * t_lift + 0.6, rel=1e-6)


def test_lift_off_at_full_speed_within_the_first_guess():
    """0.5 m/s: lift-off at 0.545 s, peak 1 + v w / g a quarter period later; the guess
    1 s + 0.6 s is enough; a lift-off exactly at the end of after_lift_off is enough."""
    lift = hoist()
    res, tr = runs.lift_off(lift, spec(), "fast", 0.5 / (R / FALLS))
    t_lift = lifted(res, 0.5)
    assert tr.duration == pytest.approx(1.6, rel=1e-12)
    assert res.rope_force_max_time[0] == pytest.approx(t_lift + np.pi / (2 * W), abs=0.02)
    # guess = the lift-off time: the run ends exactly after_lift_off after it (to
    # round-off of the lift-off's location, 1e-9 of the duration); no time step given:
    # 60 per period of the highest mode, shortened to a whole number in the run
    res, tr = runs.lift_off(lift, spec(after_lift_off=0.3, time_step=None), "exact",
                            0.5 / (R / FALLS), guess=t_lift)
    assert tr.duration == pytest.approx(t_lift + 0.3, rel=1e-12)
    h = 2 * np.pi / (60 * np.sqrt(K * (FALLS**2 / M + R**2 / J)))
    assert res.time_step == pytest.approx(tr.duration / np.ceil(tr.duration / h),
                                          rel=1e-9)


def test_lift_off_grounds_the_spec_loads_only():
    """A hook block H (500 kg) hangs on the hoist, the load B (5000 kg) on a sling below
    it: B alone rests on the ground (the transient core alone would ground every free
    mass, H too)."""
    text = HOIST.replace("H: [0, 0, 10]}", "H: [0, 0, 10], B: [0, 0, 8]}").replace(
        f"masses: {{S: 10.0, H: {M}}}", "masses: {H: 500.0, B: 5000.0}") + \
        "  sling: {EA: 1.0e8, path: [H, B]}\n"
    res, tr = runs.lift_off(hoist(text), spec(loads=("B",), time_step=0.02), "chain",
                            0.5 / (R / FALLS))
    assert res.ground_names == ("B",) and tr.parameters["loads"] == ["B"]
    assert np.isfinite(res.lift_off_time)


def test_a_load_that_never_lifts():
    """Drum at rest: six runs of 1, 4, 16, 64, 256, 1024 s (+ 1000 s after the lift-off),
    then the error (time step 500 s: nothing moves)."""
    with pytest.raises(AnalysisError) as e:
        runs.lift_off(hoist(), spec(time_step=500.0, after_lift_off=1000.0), "still", 0.0)
    assert str(e.value) == ("still: the load does not lift off within 2024 s at drum "
                            "speed 0 rad/s")


def test_hoist_start_of_a_sudden_acceleration():
    """Jerk time 0: the drum speed rises linearly to 2 rad/s (0.25 m/s at the hook) in
    0.8 s > pi / w: a = 0.3125 m/s^2 held for longer than half a period, so by (1) the
    peak is S0 + 2 m a / n, at pi / w; the run lasts the ramp + 0.6 s."""
    lift = hoist()
    res, tr, acc = timed(runs.hoist_start, lift, spec(ramp=0.8, after_lift_off=0.6), 2.0)
    a = 0.25 / 0.8
    assert acc == pytest.approx(2.0 / 0.8, rel=1e-14)       # drum rad/s^2
    assert res.rope_force_static[0] == pytest.approx(S0, rel=1e-12)
    assert res.rope_force_max[0] == pytest.approx(S0 + 2 * M * a / FALLS, rel=TOL)
    assert res.rope_force_max_time[0] == pytest.approx(np.pi / W, abs=0.02)
    assert tr.duration == pytest.approx(1.4, rel=1e-12) == res.duration
    assert (res.initial, res.scene, tr.name, tr.engine, tr.steps) == \
        ("static", "loads: hoist start", "hoist start", "transient", res.steps)
    assert tr.parameters == {"initial": "static", "drum": "hoist", "drum_speed_rad_s": 2.0,
                             "start": "jerk-limited, 0.8 s to full speed, jerk time 0 s",
                             "time_step_s": pytest.approx(0.01, rel=1e-12),
                             "effects": {"sway": False, "damping": "none"}}


def test_hoist_start_with_a_jerk_time():
    """Jerk time t_j = 0.15 s, held acceleration a = v / (ramp - t_j) for one period
    (ramp = t_j + 2 pi / w, so the stop of the acceleration leaves no swing). The table
    (16 segments of d = t_j / 16, the speed exact at their ends) has on segment k the
    mean acceleration a (k + 1/2) / 16: jumps a / 32 at 0 and t_j, a / 16 between; by (1)
    the force swings about S0 + m a / n with amplitude (m / n) |sum da_i e^(-i w t_i)|
    (a |sin x| / x, x = w t_j / 2, for a smooth rise) once the rise is over, and the hold
    lasts longer than half a period: the peak is S0 + (m / n) (a + |C|). No time step
    given: 60 per period of the highest mode."""
    lift = hoist()
    tj = 0.15
    ramp = tj + 2 * np.pi / W
    s = spec(ramp=ramp, jerk=tj, time_step=None, after_lift_off=0.5)
    res, tr, acc = runs.hoist_start(lift, s, 2.0)
    a = 0.25 / (ramp - tj)
    assert acc == pytest.approx(2.0 / (ramp - tj), rel=1e-14)
    t = tj / 16 * np.arange(17)
    da = a / 16 * np.r_[0.5, np.ones(15), 0.5]
    C = abs(np.sum(da * np.exp(-1j * W * t)))
    assert C == pytest.approx(a * np.sin(W * tj / 2) / (W * tj / 2), rel=1e-3)
    assert res.rope_force_max[0] == pytest.approx(S0 + M * (a + C) / FALLS, rel=TOL)
    w_max = np.sqrt(K * (FALLS**2 / M + R**2 / J))
    duration = ramp + 0.5
    # the core shortens the step to a whole number of steps in the run
    h = 2 * np.pi / (60 * w_max)
    assert res.time_step == pytest.approx(duration / np.ceil(duration / h), rel=1e-9)
    assert tr.duration == pytest.approx(duration, rel=1e-12)
    assert tr.parameters["start"] == \
        f"jerk-limited, {ramp:g} s to full speed, jerk time 0.15 s"


def test_sudden_release():
    """dm = 0.25 m released at once: the run is m' = 0.75 m at rest under a downward
    force dm g, so its rope force is S' + (dm g / n) (1 - cos w' t), w'^2 = n^2 k / m',
    peak (m' + 2 dm) g / n at pi / w'; integrated by modal superposition with every mode;
    no time step given: 60 per period of the reduced model's highest mode."""
    lift = hoist()
    res, reduced, tr = timed(runs.release, lift, spec(time_step=None))
    m1, dm = 0.75 * M, 0.25 * M
    assert reduced.masses.mass.tolist() == [10.0, m1]
    assert lift.masses.mass.tolist() == [10.0, M]
    w1 = np.sqrt(FALLS**2 * K / m1)
    assert res.rope_force_static[0] == pytest.approx(m1 * G / FALLS, rel=1e-12)
    assert res.rope_force_max[0] == pytest.approx((m1 + 2 * dm) * G / FALLS, rel=TOL)
    assert res.rope_force_max_time[0] == pytest.approx(np.pi / w1, abs=0.02)
    w_max = np.sqrt(K * (FALLS**2 / m1 + R**2 / J))
    h = 2 * np.pi / (60 * w_max)               # a whole number of steps in 0.6 s
    assert res.time_step == pytest.approx(0.6 / np.ceil(0.6 / h), rel=1e-9)
    assert (res.method, res.modes, res.initial, res.scene) == \
        ("modal", 1, "static", "loads: release")
    assert tr.duration == pytest.approx(0.6, rel=1e-12) == res.duration
    assert (tr.name, tr.engine, tr.steps) == ("release", "transient", res.steps)
    assert tr.parameters == {"load": "H", "mass_kg": M, "released_kg": dm,
                             "release_time_s": 0.0, "method": "modal (all modes)",
                             "time_step_s": pytest.approx(res.time_step, rel=1e-12),
                             "effects": {"sway": False, "damping": "none"}}


def test_release_keeps_every_mode():
    """With rope mass (10 elements a fall: more coordinates than the transient core's
    default of 20 modes) every elastic mode is kept (the drum's free rotation is not
    one)."""
    text = HOIST.replace(f"EA: {EA}, ", f"EA: {EA}, mass_per_length: 2.0, ") + \
        "effects: {rope_mass: 10}\n"
    lift = hoist(text)
    res, reduced, tr = runs.release(lift, spec(time_step=0.01, after_lift_off=0.05))
    assert res.dofs > 21
    assert res.modes == res.dofs - 1            # all but the free drum's rotation


def test_slow_release():
    """dm = 0.5 m released over T = 0.2 s: a ramped step, amplitude |sin x| / x of the
    sudden one, x = w' T / 2; the run lasts T + 0.6 s (the peak at T + ... < 0.8 s).
    Time step 5 ms: w' h = 0.042."""
    lift = hoist()
    res, reduced, tr = runs.release(lift, spec(fraction=0.5, release_time=0.2,
                                               time_step=0.005))
    m1 = dm = 0.5 * M
    w1 = np.sqrt(FALLS**2 * K / m1)
    x = w1 * 0.2 / 2
    assert res.rope_force_max[0] == pytest.approx(
        (m1 + dm * (1 + np.sin(x) / x)) * G / FALLS, rel=TOL)
    assert tr.duration == pytest.approx(0.8, rel=1e-12) == res.duration
    assert tr.parameters["release_time_s"] == 0.2 and tr.parameters["released_kg"] == dm


CART = """cranefe: 1
name: a cart on a slider, the load on a 2 m rope below it
plane: xz
nodes:
  P:   [0.0, 0.0, 5.0]
  D:   [-1.0, 0.0, 5.5]
  L:   [0.0, 0.0, 3.0]
ground: []
masses:
  L: 2000
bodies:
  cart: {mass: 3000, com: [0.0, 0.0, 5.0], inertia: 1.0e3, nodes: [P, D]}
joints:
  - {name: travel, type: slider, bodies: [ground, cart], at: P, axis: [1, 0, 0],
     range: [-1.0, 5.0]}
drums:
  hoist: {node: D, radius: 0.2, inertia: 5.0, brake: false, rope_reserve: 20.0}
ropes:
  hoist_rope: {EA: 2.0e6, path: [hoist, P, L]}
effects: {sway: false, damping: modal}
"""


def residual_deg(a, ramp, jerk, dist_time, l=2.0):
    """Residual swing (deg) of a linear pendulum (w^2 = g / l) under its support's
    acceleration a over (ramp - t_j), rounded by t_j (a box of width t_j convolved),
    and -a from dist_time on: theta'' + w^2 theta = -x'' / l summed over the four jumps
    of x'' gives the amplitude (a / g) 4 |sin(w (ramp - t_j) / 2) sin(w d / 2)|, times
    |sin(w t_j / 2) / (w t_j / 2)| for the rounding."""
    w = np.sqrt(G / l)
    box = np.sinc(w * jerk / 2 / np.pi)
    return np.degrees(a / G * 4 * abs(np.sin(w * (ramp - jerk) / 2) *
                                      np.sin(w * dist_time / 2) * box))


@pytest.mark.parametrize("jerk", [0.0, 0.2])
def test_a_slider_move(jerk):
    """0.2 m at 0.1 m/s, reached over 0.8 s: the cart ends at 0.2 m, the load swings
    with the linear pendulum's residual (sway on although the model has it off); the run
    lasts the move (2 s + ramp) and three quarters of the period of a pendulum as long
    as the highest node (the drum, 5.5 m) is above the load (3 m)."""
    m = load("cart.yaml", CART)
    mv = JointMove("travel", "slider", 0.1, 0.8, 0.2, jerk)
    res, tr, a_max = timed(runs.joint_move, m, spec(loads=("L",), tolerance=1e-6), mv)
    a = 0.1 / (0.8 - jerk)
    assert a_max == pytest.approx(a, rel=1e-14)
    assert res.drive_position[-1, 0] == pytest.approx(0.2, abs=1e-9)
    assert res.sway_residual_deg[0] == pytest.approx(residual_deg(a, 0.8, jerk, 2.0),
                                                     rel=2e-3)
    assert res.effects["sway"] is True and res.effects["damping"] == "none"
    assert res.scene == "loads: travel move"
    assert res.times[1] - res.times[0] == pytest.approx(0.01, rel=1e-9)
    duration = 2.0 + 0.8 + 0.75 * 2 * np.pi * np.sqrt(2.5 / G)
    assert tr.duration == pytest.approx(duration, rel=1e-12)
    assert res.duration == pytest.approx(duration, rel=1e-12)
    prof = {"type": "trapezoid", "distance": 0.2, "v_max": 0.1, "a_max": a} if not jerk \
        else {"type": "s_curve", "distance": 0.2, "v_max": 0.1, "a_max": a,
              "j_max": a / jerk}
    params = dict(tr.parameters)
    profile = dict(params.pop("profile"))
    assert profile.pop("type") == prof.pop("type")     # approx takes numbers only
    assert profile == pytest.approx(prof, rel=1e-14)
    assert params == {"joint": "travel", "kind": "slider", "tolerance": 1e-6,
                      "output_step_s": 0.01, "effects": {"sway": True, "damping": "none"}}
    assert (tr.name, tr.engine, tr.steps) == ("travel move", "operation", res.steps)


def test_the_move_takes_the_scene_tolerance():
    """A 100 x looser tolerance than the engine's default (1e-6 relative; the default
    is tighter) takes fewer steps; the default is used when the scene gives none."""
    m = load("cart.yaml", CART)
    mv = JointMove("travel", "slider", 0.1, 0.8, 0.2, 0.0)
    loose, tr, _ = runs.joint_move(m, spec(loads=("L",), tolerance=1e-4), mv,
                                   output_step=0.05)
    plain, tr0, _ = runs.joint_move(m, spec(loads=("L",)), mv, output_step=0.05)
    assert loose.steps < plain.steps
    assert tr0.parameters["tolerance"] is None
    assert plain.times[1] - plain.times[0] == pytest.approx(0.05, rel=1e-9)


def test_shaped_moves():
    """With shapers: the move unshaped and ZV-shaped on the crane's own pendulum
    frequency; the unshaped one swings as the linear pendulum, the ZV one (nearly) not."""
    m = load("cart.yaml", CART)
    mv = JointMove("travel", "slider", 0.1, 0.8, 0.2, 0.0)
    out = runs.joint_move(m, spec(loads=("L",), tolerance=1e-6), mv, shapers=("ZV",))
    assert set(out) == {"unshaped", "ZV"}
    assert out["unshaped"]["residual_sway_deg"] == pytest.approx(
        residual_deg(0.125, 0.8, 0.0, 2.0), rel=2e-3)
    assert out["ZV"]["residual_sway_deg"] < 0.01 * out["unshaped"]["residual_sway_deg"]


JIB = """cranefe: 1
name: a luffing jib, the load 0.5 m below its tip
nodes:
  O:   [0.0, 0.0, 0.0]
  TIP: [0.0, 0.0, 20.0]
  D:   [-1.0, 0.0, 0.5]
  L:   [0.0, 0.0, 19.5]
ground: [O]
masses:
  L: 2000
bodies:
  jib: {mass: 3000, com: [0.0, 0.0, 10.0], inertia: [1.0e3, 1.0e5, 1.0e5],
        nodes: [TIP, D]}
joints:
  - {name: luffing, type: hinge, bodies: [ground, jib], at: O, axis: [0, 1, 0]}
drums:
  hoist: {node: D, radius: 0.2, inertia: 5.0, brake: false, rope_reserve: 20.0}
ropes:
  hoist_rope: {EA: 5.0e7, path: [hoist, TIP, L]}
"""


def test_a_hinge_move():
    """A hinge turns by its distance (rad); the pendulum of the duration is at least
    1 m long (the load 0.5 m below the top node)."""
    m = load("jib.yaml", JIB)
    mv = JointMove("luffing", "hinge", np.radians(2.0), 0.5, np.radians(1.0), 0.0)
    res, tr, a_max = runs.joint_move(m, spec(loads=("L",), tolerance=1e-4), mv)
    assert res.drive_position[-1, 0] == pytest.approx(np.radians(1.0), abs=1e-9)
    duration = 0.5 + 0.5 + 0.75 * 2 * np.pi * np.sqrt(1.0 / G)
    assert tr.duration == pytest.approx(duration, rel=1e-12)
    assert tr.parameters["kind"] == "hinge" and tr.name == "luffing move"
    assert a_max == pytest.approx(np.radians(2.0) / 0.5, rel=1e-14)
