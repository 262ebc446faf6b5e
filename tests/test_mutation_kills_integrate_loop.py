"""Value tests of the main loop of cranefe/analysis/operation/integrate.py (issue 20,
mutation testing): its step sequence, rejections and breakpoints, which the error
control hides from the values of a run (a step across a kink or a different step
sequence stays within the tolerance), so they are checked where the steps are known
exactly. Every run passes fast=False (the numpy loop of integrate.py; loop.py mirrors it
and is tested equal to it by tests/test_operation_speed.py).

- free fall: a load thrown up on a slack rope has the constant acceleration -g, which
  the trapezoidal rule integrates exactly, so every step's error estimate is round-off
  (< 1e-9, the controller's factor capped at 2 for anything below 0.09) and its
  Newton iteration ends at the second iterate (the predictor q0 + h v0 + h^2/2 a0 is the
  solution): the step sequence follows from the documented rules alone (docs/operations.md
  "Integrator"): the first step min(max_step, 1e-3 duration, 1e-2); each accepted step
  doubles the next (the controller's bound 2), but not the one after a rejection (bound
  1); a Newton failure quarters the step, an error rejection multiplies it by
  max(0.2, 0.9 err^(-1/3)); steps are cut to end at the breakpoints of the prescribed
  motions (the trolley's kinks), after which the next step is the longer of the step
  before the cut and the controller's; never longer than max_step. The failures are
  injected by a Stepper whose step fails or reports an error on chosen calls;
- a physical pendulum on a hinge (a joint coordinate) below a trolley moved by a
  trapezoid: I_O phi'' = m d cos(phi) s''(t) - m g d sin(phi) against scipy's DOP853 at
  rtol 1e-12, segment by segment between the kinks where s'' jumps; the steps end at
  the kinks exactly, each evaluated with the acceleration from the left.
"""

import functools
import itertools
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from test_mutation_kills_integrate import DROP2, TROLLEY, _scene
from test_mutation_kills_mechanism import ARM, trolley_xs

from cranefe.analysis.operation import integrate as integ
from cranefe.analysis.operation.integrate import simulate
from cranefe.analysis.operation.mechanism import Mechanism
from cranefe.analysis.operation.scene import parse
from cranefe.errors import AnalysisError

G = 9.81

# the trolley's trapezoid: distance 0.5 m, v_max 1 m/s, a_max 4 m/s^2: accelerating for
# v/a = 0.25 s over 0.125 m, cruising 0.25 m for 0.25 s: kinks at 0.25, 0.5 and 0.75 s
FREE = ("  duration: 1\n  tolerance: 1.0e-8\n  max_step: 0.2\n  output_step: 0.1\n"
        "  drives:\n    trolley: {slider: travel, profile: {type: trapezoid, distance: 0.5, "
        "v_max: 1, a_max: 4}}\n")
# the load 5 m below the trolley (its rope's L0 is 9.9 m: slack), thrown up at g/2 m/s:
# it rises 1.23 m and is back at t = 1 s, the rope slack throughout
FREE_INITIAL = {"q": np.array([0.0, 5.0]), "v": np.array([0.0, G / 2])}


def _run(model, stepper=None, **kw):
    """simulate() recording every accepted step (t0, t1) (Recorder.accept's arguments)."""
    steps = []

    class Rec(integ.Recorder):
        def accept(self, t0, q0, v0, a0, ev0, t1, *rest):
            steps.append((t0, t1))
            return super().accept(t0, q0, v0, a0, ev0, t1, *rest)

    saved = integ.Recorder, integ.Stepper
    integ.Recorder = Rec
    if stepper is not None:
        integ.Stepper = stepper
    try:
        res = simulate(model, fast=False, **kw)
    finally:
        integ.Recorder, integ.Stepper = saved
    return res, steps


def _failing(calls, err=None):
    """A Stepper whose step fails (Newton) on the given call numbers (1-based), or,
    with err, returns its solution with that error estimate instead."""

    class Failing(integ.Stepper):
        n = 0

        def step(self, *args, **kw):
            Failing.n += 1
            out = super().step(*args, **kw)
            if calls == "all" or Failing.n in calls:
                return None if err is None else out[:4] + (err,)
            return out

    return Failing


def _times(steps):
    t = [steps[0][0]] + [b for _, b in steps]
    assert all(b == a2 for (_, b), (a2, _) in itertools.pairwise(steps))   # contiguous
    return t


def test_free_fall_steps_double_and_end_at_the_kinks():
    """Error-free steps (the estimate is round-off): 1, 2, 4, ... 64 ms from the first step 1e-3 x 1 s; at t = 0.127
    the 128-ms step is cut to the kink at 0.25 (0.123 s); then the longer of 0.128 and
    2 x 0.123 = 0.246, capped by max_step 0.2 -> 0.45; the cut 0.05 to the kink at 0.5;
    then max(0.246, 0.4) = 0.4 capped -> 0.2 and the cut 0.05 twice, to 0.75 and to the
    end. Newton: 2 iterations per step (the predictor is the solution)."""
    model = _scene("free", TROLLEY, FREE)
    res, steps = _run(model, initial=FREE_INITIAL)
    want = [0, .001, .003, .007, .015, .031, .063, .127, .25, .45, .5, .7, .75, .95, 1.0]
    np.testing.assert_allclose(_times(steps), want, rtol=0, atol=1e-15)
    assert steps[7][1] == 0.25 and steps[9][1] == 0.5 and steps[11][1] == 0.75
    assert res.steps == 14 and res.rejected == 0 and res.newton_iterations == 28
    assert [e for _, e in res.events] == ["drive trolley starts", "drive trolley stops"]
    # the free fall itself, exact (round-off over 14 steps)
    z = res.mass_position[:, 0, 2]
    np.testing.assert_allclose(z, 5.0 + G / 2 * res.times - G / 2 * res.times ** 2,
                               atol=1e-12)
    assert res.status == 0 and res.times[-1] == 1.0


def test_a_newton_failure_quarters_the_step_and_the_next_does_not_grow():
    """The 4th step (8 ms at t = 0.007) fails: retried at 2 ms; the step after a
    rejection does not grow (2 ms again), then doubling: 0.009, 0.011, 0.015, 0.023,
    0.039, 0.071, 0.135; cut to the kink (0.115 s), then max(0.128, 0.23) = 0.23 capped
    at 0.2 -> 0.45, 0.5, 0.7, 0.75, 0.95, 1."""
    model = _scene("free", TROLLEY, FREE)
    res, steps = _run(model, _failing({4}), initial=FREE_INITIAL)
    want = [0, .001, .003, .007, .009, .011, .015, .023, .039, .071, .135, .25, .45, .5,
            .7, .75, .95, 1.0]
    np.testing.assert_allclose(_times(steps), want, rtol=0, atol=1e-15)
    assert res.steps == 17 and res.rejected == 1
    assert res.newton_iterations == 2 * 18      # the failed call iterated as usual


def test_an_error_rejection_shrinks_by_the_controller():
    """The 4th step (8 ms at t = 0.007) reports the error 8: rejected, retried at
    8 x 0.9 / 8^(1/3) = 3.6 ms, the next not longer (3.6 ms), then doubling: 0.0106,
    0.0142, 0.0214, 0.0358, 0.0646, 0.1222, 0.2374; cut to 0.25 (0.0126 s), then
    max(0.2304, 0.0252) = 0.2304 capped at 0.2 -> 0.45, 0.5, 0.7, 0.75, 0.95, 1."""
    model = _scene("free", TROLLEY, FREE)
    res, steps = _run(model, _failing({4}, err=8.0), initial=FREE_INITIAL)
    want = [0, .001, .003, .007, .0106, .0142, .0214, .0358, .0646, .1222, .2374, .25,
            .45, .5, .7, .75, .95, 1.0]
    np.testing.assert_allclose(_times(steps), want, rtol=0, atol=1e-14)
    assert res.steps == 17 and res.rejected == 1


@pytest.mark.parametrize("err, what, n", [
    # Newton failing throughout: 1e-3 / 4^k < 1e-12 first at k = 15 (9.31e-13 s)
    (None, "Newton's method does not converge at t = 0 s (step 9.31e-13 s)", 15),
    # the error 1e3 throughout: factor max(0.2, 0.9e-1) = 0.2, 1e-3 x 0.2^13 = 8.19e-13
    (1e3, "the step size collapsed at t = 0 s (step 8.19e-13 s)", 13),
    # the error 2: factor 0.9 / 2^(1/3) = 0.714, 1e-3 x 0.714^k < 1e-12 at k = 62
    (2.0, "the step size collapsed at t = 0 s (step 8.", 62),
])
@pytest.mark.parametrize("T", [1, 2])
def test_the_step_collapses_below_1e_12_of_the_duration(err, what, n, T):
    """hmin = 1e-12 max(duration, 1 s): every step refused from the first (1e-3 T) on
    (with T = 2 s the bound and the first step double: the same count, twice the step)."""
    model = _scene(f"free{T}", TROLLEY, FREE.replace("duration: 1\n", f"duration: {T}\n"))
    if T == 2:
        what = what.replace("9.31e-13", "1.86e-12").replace("8.19e-13", "1.64e-12") \
            .replace("(step 8.", "(step 1.")
    with pytest.raises(AnalysisError) as exc:
        _run(model, _failing("all", err=err), initial=FREE_INITIAL)
    assert what in str(exc.value)
    assert "the results up to t = 0 s are kept" in str(exc.value)
    assert exc.value.result.status == 1 and exc.value.result.rejected == n


# ----------------------------------------------------------------- joint coordinate

PEND = """cranefe: 1
name: pendulum on a trolley
plane: xz
nodes:
  K: [0, 0, 10]
  B: [0, 0, 8]
bodies:
  trolley: {mass: 500, com: [0, 0, 10], inertia: [10, 10, 10], nodes: [K]}
  bob: {mass: 100, com: [0, 0, 8], inertia: [5, 5, 5], nodes: [B]}
joints:
  - {name: travel, type: slider, bodies: [ground, trolley], at: K, axis: [1, 0, 0],
     range: [-1, 20]}
  - {name: swing, type: hinge, bodies: [trolley, bob], at: K, axis: [0, 1, 0],
     range: [-1, 1]}
"""
MP, DP, ICP = 100.0, 2.0, 5.0           # the bob: mass, com 2 m below the hinge, I_c
IOP = ICP + MP * DP * DP                # about the hinge (Steiner)


def _pend_rhs(t, y):
    """x = s - d sin(phi), z = -d cos(phi) (a turn phi about +y takes +z to +x);
    Lagrange: I_O phi'' - m d cos(phi) s'' = -m g d sin(phi)."""
    s2 = trolley_xs(t)[2]
    return [y[1], (MP * DP * math.cos(y[0]) * s2 - MP * G * DP * math.sin(y[0])) / IOP]


@functools.cache
def _pend_reference():
    y, sols = [0.0, 0.0], []
    for a, b in [(0, 1), (1, 2), (2, 3), (3, 4)]:
        s = solve_ivp(_pend_rhs, (a, b), y, method="DOP853", rtol=1e-12, atol=1e-14,
                      dense_output=True)
        sols.append((a, b, s.sol))
        y = s.y[:, -1]
    return sols


def test_pendulum_on_a_moving_trolley_against_scipy():
    """The swing angle to 1.2e-4 rad over 4 s (tolerance 1e-7 x 10 m per step; measured
    5.7e-5 rad, 1.3e-5 at 1e-8, 2.9e-6 at 1e-9: tolerance^(2/3), it converges to the
    reference; the swing is ~0.1 rad). Steps end at the kinks 1, 2, 3 s exactly; the
    step that ends there sees s'' from the left: from the wrong side its a1 is off by
    m d s''-jump / I_O = 0.47 rad/s^2, an error estimate far above 1, rejected steps."""
    model = _scene("pend", PEND, "  duration: 4\n  tolerance: 1.0e-7\n  output_step: 0.05\n"
                   "  drives:\n    trolley: {slider: travel, profile: {type: trapezoid, "
                   "distance: 2, v_max: 1, a_max: 1}}\n    sw: {hinge: swing, torque: 0}\n")
    res, steps = _run(model)
    ends = [b for _, b in steps]
    assert 1.0 in ends and 2.0 in ends and 3.0 in ends and ends[-1] == 4.0
    phi = res.drive_position[:, 1]
    ref = []
    for t in res.times:
        ref.append(next(sol(t)[0] for a, b, sol in _pend_reference() if a <= t <= b))
    err = np.abs(phi - np.array(ref)).max()
    assert err < 1.2e-4, err
    assert np.abs(phi).max() > 0.05
    # no drive work on a free hinge; the trolley's prescribed motion works on the bob
    assert res.energy_error < 1e-4, res.energy_error
    # the cost: 449 steps, 2 rejected (measured; a step from the wrong side of a kink is
    # rejected, 3 kinks); 2 Newton iterations per trial (near-linear: the predictor's
    # error O(h^4) is gone after one correction)
    assert res.rejected <= 2 and res.steps < 460, (res.steps, res.rejected)
    assert res.newton_iterations == 2 * (res.steps + res.rejected)


# ----------------------------------------------------------------- two ropes, slack/taut

def _bounce_events(L0, v0, m=100.0, EA=1.0e6, T=0.3):
    """Times where a load thrown up from rest on its Hencky rope (S = EA ln(L/L0), 0 for
    L <= L0; the rope from z = 10 m, the load at z with L = 10 - z) crosses L = L0:
    DOP853 at rtol 1e-13, restarted at each crossing (the force's slope jumps there)."""
    def f(t, y):
        L = 10.0 - y[0]
        return [y[1], -G + (EA * math.log(L / L0) / m if L > L0 else 0.0)]

    t, y, out, d = 0.0, [10.0 - L0 * math.exp(m * G / EA), v0], [], -1
    while True:
        def ev(t, y):
            return 10.0 - y[0] - L0
        ev.terminal, ev.direction, d = True, d, -d
        s = solve_ivp(f, (t, T), y, method="DOP853", rtol=1e-13, atol=1e-15, events=ev)
        if s.status != 1:
            return out
        t, y = s.t_events[0][0], s.y_events[0][0].copy()
        out.append(t)


@functools.cache
def _bounce_reference(L0a, L0b):
    return _bounce_events(L0a, 2.0), _bounce_events(L0b, 1.0)


def test_two_loads_thrown_up_slacken_their_ropes_one_at_a_time():
    """Two loads at rest on their ropes (static stretch 4.9 mm, axial w = 44.7 rad/s)
    thrown up at 2 and 1 m/s: each rope goes slack where the stretch vanishes, the
    first while the other is still taut (the crossing test on all-taut ropes), the
    second while the first is slack (the mixed test, each rope by its own flag); the
    second load falls back (taut at 0.204 s) and bounces off (slack at 0.284 s) while
    the first still flies. Each event against scipy: the first three to 5e-8 s
    (tolerance 1e-8 x 5 m per step, measured 7e-9 to 1.7e-8 s); the bounce's slack
    event to 4e-6 s (measured 1.5e-6; 3.6e-7 at tolerance 1e-9: tolerance^(2/3), it
    converges): the axial oscillation's position error at 1 m/s."""
    model = _scene("bounce", DROP2, "  duration: 0.3\n  tolerance: 1.0e-8\n  output_step: 0.01\n",
                   "{sway: false}")
    mech = Mechanism(model, parse(model))
    L0 = mech.L0_ref
    res = simulate(model, initial={"q": mech.q0.copy(), "v": np.array([2.0, 1.0])}, fast=False)
    assert [w for _, w in res.events] == ["rope r1 slack", "rope r2 slack", "rope r2 taut",
                                          "rope r2 slack"], res.events
    ra, rb = _bounce_reference(float(L0[0]), float(L0[1]))
    assert len(ra) == 1 and len(rb) == 3
    want = [ra[0], rb[0], rb[1], rb[2]]
    got = [t for t, _ in res.events]
    np.testing.assert_allclose(got[:3], want[:3], rtol=0, atol=5e-8)
    assert abs(got[3] - want[3]) < 4e-6, got[3] - want[3]


# ----------------------------------------------------------------- long steps

def test_a_constant_acceleration_takes_doubling_steps_up_to_max_step():
    """The trolley pushed by 300 N carrying a guided load (sway off) accelerates at
    F / (m_t + m) = 0.2 m/s^2 exactly: every step's estimate is round-off, so from
    1e-3 x 10 s the steps double (0.01 ... 2.56 s, to t = 5.11) until max_step 4 s
    (to 9.11) and the end cuts the last (0.89 s). s = 0.1 t^2 to round-off."""
    model = _scene("guided10", TROLLEY, "  duration: 10\n  tolerance: 1.0e-8\n  max_step: 4\n"
                   "  output_step: 1\n  drives:\n    f: {slider: travel, force: 300}\n",
                   "{sway: false}")
    res, steps = _run(model)
    want = [0, .01, .03, .07, .15, .31, .63, 1.27, 2.55, 5.11, 9.11, 10.0]
    np.testing.assert_allclose(_times(steps), want, rtol=0, atol=1e-13)
    assert res.steps == 11 and res.rejected == 0 and res.newton_iterations == 22
    np.testing.assert_allclose(res.drive_position[:, 0], 0.1 * res.times ** 2, atol=1e-12)


# ----------------------------------------------------------------- units and masses

def test_the_position_error_weighs_a_drum_angle_by_its_radius():
    """A torque-driven drum (radius 0.5 m) is a coordinate in radians: the estimate
    weighs its acceleration difference by the radius (metres of rope), the load's not;
    a slack rope's force term left out: err = max(|da_z|, 0.5 |da_theta|) / tol h^2/12."""
    from test_mutation_kills_integrate import _stepper
    from test_mutation_kills_mechanism import WINCH

    model = _scene("winch", WINCH, "  duration: 5\n  tolerance: 1.0e-6\n  drives:\n"
                   "    h: {drum: hoist, torque: 3000}\n", "{sway: false}")
    mech, st = _stepper(model)
    assert mech.n == 2 and len(mech.qdrums) == 1
    np.testing.assert_array_equal(st.wq, [1.0, 0.5])
    taut = mech.taut0.copy()
    a0, ev = st.accel(0.0, mech.q0.copy(), np.zeros(2), taut)
    h, tol = 0.01, 1e-6 * model.length_scale
    for da, e in [([1e-3, 4e-3], 2e-3), ([3e-3, 4e-3], 3e-3)]:
        err = st.error(h, a0, a0 + np.array(da), ev, np.array([False]))
        assert err == pytest.approx(e / tol * h * h / 12, rel=1e-12)


# the luffing arm of the mechanism kill tests with a 0.5 kg load on a soft sling
LIGHT = (ARM.replace("name: luffing arm", "name: arm with a light load")
         .replace("H: [4, 0, 5]", "H: [4, 0, 8]")
         .replace("masses: {H: 300}", "masses: {H: 0.5}")
         .replace("  hoist: {EA: 1.0e8, psi: 0.2, path: [T, H]}\n"
                  "  stay: {EA: 5.0e8, path: [P, T]}\n",
                  "  stay: {EA: 5.0e8, path: [P, T]}\n"
                  "  sling: {EA: 1.0e4, path: [T, H]}\n"))


def test_a_light_load_beside_a_joint_coordinate_is_accelerated():
    """With a joint coordinate the accelerations are solved block by block (the loads'
    diagonal M, the joint's M_J): a 0.5 kg load on a 2 m sling (EA 1e4 N, static force
    m g) lifted by 1 mm: m z'' = EA ln(L/L0) - m g = EA ln(1 - 1e-3/2) (L0 = 2 exp(-m g/EA)),
    z'' = -10.0 m/s^2."""
    from test_mutation_kills_integrate import _stepper

    model = _scene("light", LIGHT, "  duration: 1\n  tolerance: 1.0e-6\n  drives:\n"
                   "    d: {hinge: luff, torque: -3924}\n")
    mech, st = _stepper(model)
    assert st.nJ == 1
    q = mech.q0.copy()
    iz = [i for i in range(mech.n) if q[i] == pytest.approx(8.0)]
    assert len(iz) == 1
    q[iz[0]] += 1e-3
    a, _ = st.accel(0.0, q, np.zeros(mech.n), mech.taut0.copy())
    assert a[iz[0]] == pytest.approx(1.0e4 * math.log(1 - 1e-3 / 2) / 0.5, rel=1e-6)


# ----------------------------------------------------------------- messages

def test_two_blocking_ignores_a_span_between_two_fixed_points():
    """The winch's rope runs drum W -> sheave S -> load H: the span W-S joins two fixed
    points (it cannot be hauled shut by the load), so only the span S-H at 1 % of its
    length is two-blocking, named by its nodes."""
    from test_mutation_kills_mechanism import WINCH

    model = _scene("winch2", WINCH, "  duration: 5\n  drives:\n    h: {drum: hoist, torque: 3000}\n",
                   "{sway: false}")
    mech = Mechanism(model, parse(model))
    names = model.node_names
    spans = [(names[a], names[b]) for a, b in zip(mech.span_a, mech.span_b)]
    iw = [i for i, s in enumerate(spans) if set(s) == {"W", "S"}]
    ih = [i for i, s in enumerate(spans) if set(s) == {"S", "H"}]
    assert len(iw) == 1 and len(ih) >= 1
    l = mech.span_ref.copy()
    l[iw[0]] = 1e-4 * mech.span_ref[iw[0]]          # fixed points: never two-blocking
    integ._two_blocking(mech, l, 1.0)
    l[ih[0]] = 0.5e-2 * mech.span_ref[ih[0]]
    with pytest.raises(AnalysisError) as exc:
        integ._two_blocking(mech, l, 1.0)
    assert str(exc.value).startswith(f"at t = 1 s the span {spans[ih[0]][0]}-{spans[ih[0]][1]} "
                                     "is down to 0.05 m (0.5% of its length): the load was "
                                     "hauled into its sheave (two-blocking); likely cause: a "
                                     "drive torque far above what holds the load")


def test_failure_messages_in_full():
    """The messages as docs/operations.md words them (the whole sentence, not a part)."""
    taut, slack = np.array([True]), np.array([False])
    e = integ._blowup(1.5, 2e-13, "the step size collapsed", None, None, taut)
    assert str(e) == ("the step size collapsed at t = 1.5 s (step 2e-13 s): likely cause: a "
                      "drive accelerating the load harder than the ropes can transmit, or a "
                      "tolerance too tight for the rope's axial frequency; the results up to "
                      "t = 1.5 s are kept")
    e = integ._blowup(1.5, 2e-13, "Newton's method does not converge", None, None, slack)
    assert str(e) == ("Newton's method does not converge at t = 1.5 s (step 2e-13 s): likely "
                      "cause: ropes switching between slack and taut (snatch loads) faster "
                      "than the step can follow; the results up to t = 1.5 s are kept")
    for status, what in [(integ._loop.NEWTON, "Newton's method does not converge"),
                         (integ._loop.COLLAPSE, "the step size collapsed")]:
        with pytest.raises(AnalysisError) as exc:
            integ._fail(None, status, 1.0, 1e-3, taut, None)
        assert str(exc.value).startswith(f"{what} at t = 1 s (step 0.001 s): likely cause: a drive")
    with pytest.raises(AnalysisError) as exc:
        integ._fail(None, -12345, 1.0, 1e-3, taut, None)
    assert str(exc.value) == (f"more than {integ.MAX_STEPS} steps at t = 1 s; raise "
                              "analysis.tolerance")


def test_the_step_limit_counts_accepted_steps(monkeypatch):
    """MAX_STEPS = 5: the free fall's 6th step (ending at 0.063 s, the steps above) is
    one too many; the results up to there are kept (status 1)."""
    monkeypatch.setattr(integ, "MAX_STEPS", 5)
    model = _scene("free", TROLLEY, FREE)
    with pytest.raises(AnalysisError) as exc:
        _run(model, initial=FREE_INITIAL)
    assert str(exc.value) == "more than 5 steps at t = 0.063 s; raise analysis.tolerance"
    assert exc.value.result.status == 1 and exc.value.result.steps == 6


def test_the_first_step_is_at_most_10_ms():
    """h0 = min(max_step, 1e-3 duration, 1e-2): over 20 s the 10-ms cap decides; the
    trolley pushed by 75 N (0.05 m/s^2, s = 0.025 t^2) then doubles its error-free steps
    to 5.11 s, takes max_step 4 s thrice and the cut 2.89 s to the end."""
    model = _scene("guided20", TROLLEY, "  duration: 20\n  tolerance: 1.0e-8\n  max_step: 4\n"
                   "  output_step: 1\n  drives:\n    f: {slider: travel, force: 75}\n",
                   "{sway: false}")
    res, steps = _run(model)
    want = [0, .01, .03, .07, .15, .31, .63, 1.27, 2.55, 5.11, 9.11, 13.11, 17.11, 20.0]
    np.testing.assert_allclose(_times(steps), want, rtol=0, atol=1e-12)
    np.testing.assert_allclose(res.drive_position[:, 0], 0.025 * res.times ** 2, atol=1e-11)


def test_a_given_state_defaults_to_the_static_one():
    """initial with only "v" keeps the static positions (a load at rest stays there);
    with only "q" the velocities are zero (the free fall from rest, exact until the
    rope is taut again near 1 s)."""
    from test_mutation_kills_integrate import ROPE

    model = _scene("rest", ROPE, "  duration: 0.05\n  tolerance: 1.0e-8\n  output_step: 0.01\n",
                   "{sway: false}")
    res = simulate(model, initial={"v": np.zeros(1)}, fast=False)
    np.testing.assert_allclose(res.mass_position[:, 0, 2], 5.0, atol=1e-12)
    model = _scene("free", TROLLEY, FREE)
    res = simulate(model, initial={"q": FREE_INITIAL["q"]}, fast=False)
    free = res.times <= 0.9             # 4.9 m down at 1 s, its rope (9.9 m) taut again
    np.testing.assert_allclose(res.mass_position[free, 0, 2],
                               5.0 - G / 2 * res.times[free] ** 2, atol=1e-12)


def test_drive_events_inside_the_run_only():
    """A move that stops at the end of the run (0.75 s) has no "stops" event; one that
    starts at the end (start: 0.5, the run 0.5 s long) no "starts" event."""
    model = _scene("stopT", TROLLEY, FREE.replace("duration: 1\n", "duration: 0.75\n"))
    res = simulate(model, initial=FREE_INITIAL, fast=False)
    assert res.events == [(0.0, "drive trolley starts")]
    model = _scene("startT", TROLLEY, FREE.replace("duration: 1\n", "duration: 0.5\n")
                   .replace("a_max: 4}", "a_max: 4, start: 0.5}"))
    res = simulate(model, initial=FREE_INITIAL, fast=False)
    assert res.events == []


def test_a_failed_trial_of_the_event_search_quarters_the_step():
    """Two loads falling freely onto their ropes (0.2 and 0.2005 m above taut): from
    1e-3 x 0.2022 s the steps double to t = 511 x 2.022e-4 = 0.1033242 s; the next, cut
    to the end (0.0988758 s), crosses both taut points and the event search starts. If
    its first trial fails (Newton), the step is retried at a quarter (to 0.12804315 s),
    one more rejection; the events stay at sqrt(2 d / g). The step count equals the
    accepted steps (the located event steps included)."""
    model = _scene("drop2b", DROP2, "  duration: 0.2022\n  tolerance: 1.0e-8\n  max_step: 0.5\n",
                   "{sway: false}")
    mech = Mechanism(model, parse(model))
    L0 = mech.L0_ref
    init = {"q": np.array([10.0 - L0[0] + 0.2, 10.0 - L0[1] + 0.2005]), "v": np.zeros(2)}
    ref, steps0 = _run(model, initial=init)
    ends0 = [b for _, b in steps0]
    np.testing.assert_allclose(ends0[:9], 2.022e-4 * (2.0 ** np.arange(1, 10) - 1), rtol=1e-12)
    assert ref.steps == len(steps0)
    # calls 1-9: the accepted steps, 10: the crossing step, 11: the search's first trial
    res, steps = _run(model, _failing({11}), initial=init)
    ends = [b for _, b in steps]
    assert ends[:9] == ends0[:9]
    assert ends[9] == pytest.approx(ends0[8] + 0.25 * (0.2022 - ends0[8]), abs=1e-12)
    assert res.rejected == ref.rejected + 1 and res.steps == len(steps)
    for r in (ref, res):
        assert [w for _, w in r.events] == ["rope r1 taut", "rope r2 taut"]
        np.testing.assert_allclose([t for t, _ in r.events],
                                   [math.sqrt(0.4 / G), math.sqrt(0.401 / G)], atol=1e-9)


def test_progress_timings_and_the_failed_result():
    """progress(t, T) after every accepted step (the free fall's 14 ends); the timings'
    parts (setup, integrate, results, total: wall seconds of this run, total their
    sum); a failed run's result carries the error's message and its own timings."""
    model = _scene("free", TROLLEY, FREE)
    calls = []
    res, steps = _run(model, initial=FREE_INITIAL, progress=lambda t, T: calls.append((t, T)))
    assert calls == [(b, 1.0) for _, b in steps]
    tm = res.timings
    assert set(tm) == {"setup", "integrate", "results", "total"}
    assert all(0 <= tm[k] < 600 for k in tm)
    assert tm["total"] == pytest.approx(tm["setup"] + tm["integrate"] + tm["results"],
                                        abs=1e-3)
    with pytest.raises(AnalysisError) as exc:
        _run(model, _failing("all"), initial=FREE_INITIAL)
    r = exc.value.result
    assert r.status == 1 and r.message == str(exc.value)
    assert set(r.timings) >= {"setup", "integrate", "total"}
    assert all(0 <= r.timings[k] < 600 for k in ("setup", "integrate", "total"))
    assert r.timings["total"] == pytest.approx(r.timings["setup"] + r.timings["integrate"],
                                               abs=1e-3)


def test_rope_events_in_a_driven_run_keep_the_energy_balance():
    """The load 1 mm above its rope's taut point below the moving trolley, at rest: it
    falls freely and pulls the rope taut at sqrt(2e-3 / g) = 0.0142784 s (the trolley's
    2 t^2 = 0.4 mm offset lengthens the rope by 8e-9 m: 6e-8 s earlier, inside 1e-7 s),
    then bounces (slack, taut) while the drive works on it; the energy balance over the
    events' steps closes (drive work 115 J; measured 2e-8 of the energy scale)."""
    model = _scene("free", TROLLEY, FREE)
    mech = Mechanism(model, parse(model))
    z0 = 10.0 - mech.L0_ref[0] + 1e-3
    res = simulate(model, initial={"q": np.array([0.0, z0]), "v": np.zeros(2)}, fast=False)
    assert [w for _, w in res.events] == ["drive trolley starts", "rope hoist taut",
                                          "rope hoist slack", "rope hoist taut",
                                          "drive trolley stops"], res.events
    assert res.events[1][0] == pytest.approx(math.sqrt(2e-3 / G), abs=1e-7)
    assert res.energy["work_drives"] > 100
    assert res.energy_error < 1e-6, res.energy_error
