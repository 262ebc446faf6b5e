"""Value tests of cranefe/analysis/operation/integrate.py (issue 20, mutation testing,
third round): the configurations the first two kill files do not build, each against
values derived by hand. Every run passes fast=False (the numpy loop of integrate.py)
unless it tests the compiled path's hand-over itself.

- the energy bookkeeping of an event step: a drum under a constant torque hoists a load
  that falls freely on a slack rope; both accelerations are constant, so the rope goes
  taut in closed form, and the drive's work is exactly tau x (the drum's turn), since
  the trapezoidal rule's own update theta1 - theta0 = h (omega0 + omega1) / 2 is the
  quadrature the recorder applies to the power tau omega (so the event step's share, a
  tenth of the turn, is in the sum with its sign);
- the right limits at a kink in a model with a joint coordinate and a damped rope: the
  step after the kink starts from accelerations computed with the ropes' taut flags
  (the dashpot force b e' of a taut rope, b = psi (EA/L) / (2 pi w)), checked against
  Newton's law by hand from the state at the kink;
- two drums of different radii: each drum angle's error weight is its own radius;
- the hand-over to the compiled loop and step (numba): the free fall's exact steps;
- a long step over a slack rope, a load lighter than 1 N, a failed event search after a
  rejection, a run stopped by a paid-out drum or two-blocking;
- a massless block (the algebraic rows): the load below it against DOP853 on the
  equations by hand, the block in equilibrium at every instant.
"""

import functools
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from test_mutation_kills_integrate import _scene, _stepper
from test_mutation_kills_mechanism import WINCH

from cranefe.analysis.operation import integrate as integ
from cranefe.analysis.operation.integrate import simulate
from cranefe.analysis.operation.mechanism import Mechanism
from cranefe.analysis.operation.scene import parse

G = 9.81


# ----------------------------------------------------------------- event step's work

TAU, J_DRUM, R_DRUM, EA_W, M_W = 3000.0, 10.0, 0.5, 2.0e6, 1000.0


def test_the_event_step_enters_the_drive_work_with_its_sign():
    """The winch (drum radius 0.5 m, inertia 10 kg m^2, 2 falls to a 1000-kg load, sway
    off, damping psi 0.2) under a torque of 3000 N m, the load lifted 0.5 m above its
    static place at rest: the rope is slack, the drum turns by theta = tau t^2 / (2 J)
    = 150 t^2, the load falls freely. The rope's length L = 23.5 - 2 d + g t^2 (its
    static length 23.5 m, d = 0.5) meets its unstretched length L0_ref - R theta /
    lambda_ref (lambda_ref = exp(m g / 2 / EA)) at
    t^2 = (2 d - 23.5 (1 - 1/lambda_ref)) / (g + R tau / (2 J lambda_ref)):
    t = 0.10553 s, found to 1e-9 s (the regula falsi's stop |stretch| < 1e-13).
    Up to it the drum angle is 150 t^2 and the load's height z0 + d - g t^2/2 to
    round-off (constant accelerations: the rule is exact; 1e-10 m: the round-off of
    ~100 steps at 30 m, measured 5e-12). The rope then jerks the load
    up, goes slack again, and the drive's work stays tau (theta(T) - theta(0)) to
    round-off (the trapezoidal identity above; the event step alone carries
    tau x 0.10 rad = 309 J, counted with the wrong sign it is off by 618 J). The balance
    (the recorder's kinetic, gravity and elastic energies against the work, the dashpot's
    dissipation and the energy wound onto the drum) closes to 2e-5 of its scale (measured
    6.6e-6: the trapezoidal quadrature of the dissipation; the slack event step alone
    dissipates 1.9 J of 666 J, 1.1e-3 of the scale counted with the wrong sign)."""
    model = _scene("winch_ev", WINCH, "  duration: 0.2\n  tolerance: 1.0e-8\n"
                   "  output_step: 0.01\n  drives:\n    h: {drum: hoist, torque: 3000}\n",
                   "{sway: false, damping: exact}")
    mech = Mechanism(model, parse(model))
    assert mech.n == 2 and list(mech.qdrums) == [0]
    q = mech.q0.copy()
    q[0] += 0.5
    res = simulate(model, initial={"q": q, "v": np.zeros(2)}, fast=False)
    lam = math.exp(M_W * G / 2 / EA_W)
    tev = math.sqrt((1.0 - 23.5 * (1 - 1 / lam)) /
                    (G + R_DRUM * TAU / (2 * J_DRUM * lam)))
    assert [w for _, w in res.events] == ["rope r taut", "rope r slack"], res.events
    assert res.events[0][0] == pytest.approx(tev, abs=1e-9)
    before = res.times < tev
    theta = res.drive_position[:, 0]
    np.testing.assert_allclose(theta[before], TAU / (2 * J_DRUM) * res.times[before] ** 2,
                               rtol=0, atol=1e-12)
    np.testing.assert_allclose(res.mass_position[before, 0, 2],
                               30.5 - G / 2 * res.times[before] ** 2, rtol=0, atol=1e-10)
    assert theta[-1] < theta[res.times.searchsorted(0.14)]   # the load pulled the drum back
    W = res.energy["work_drives"]
    assert W == pytest.approx(TAU * (theta[-1] - theta[0]), rel=1e-10, abs=1e-8)
    assert res.energy["dissipated"] > 100
    assert res.energy_error < 2e-5, res.energy_error


# ----------------------------------------------------------------- right limits at a kink

# the pendulum on the trolley (tests/test_mutation_kills_integrate_loop.py) with a
# 1000-kg load on a damped rope (psi 1) hanging 10 m below the trolley
PENDL = """cranefe: 1
name: pendulum and load on a trolley
plane: xz
nodes:
  K: [0, 0, 10]
  B: [0, 0, 8]
  H: [0, 0, 0]
masses: {H: 1000}
bodies:
  trolley: {mass: 500, com: [0, 0, 10], inertia: [10, 10, 10], nodes: [K]}
  bob: {mass: 100, com: [0, 0, 8], inertia: [5, 5, 5], nodes: [B]}
joints:
  - {name: travel, type: slider, bodies: [ground, trolley], at: K, axis: [1, 0, 0],
     range: [-1, 20]}
  - {name: swing, type: hinge, bodies: [trolley, bob], at: K, axis: [0, 1, 0],
     range: [-1, 1]}
ropes:
  hoist: {EA: 1.0e6, psi: 1.0, path: [K, H]}
"""
EA_P, PSI, M_P = 1.0e6, 1.0, 1000.0
MB, DB, IOB = 100.0, 2.0, 5.0 + 100.0 * 4.0     # the bob: mass, com below K, I about K


def test_the_step_after_a_kink_starts_from_the_right_limits_with_the_taut_flags():
    """The trolley's trapezoid (0.5 m, 1 m/s, 4 m/s^2) has s'' = 4 before t = 0.25 s and
    0 after; the load is thrown down at 0.3 m/s, so its damped rope (b = psi (EA/L) /
    (2 pi w), w = sqrt(EA / (L m)): 1590 N s/m) shortens at 0.2 m/s (its dashpot's force
    320 N) when the step ends at the kink. The step after it starts from the state there (q, v continuous) with
    the right limits of the accelerations, by Newton's law by hand:
    m a_H = -(S + b e') d / L + m g (d = X_H - X_K, e' = d . (V_H - V_K) / L, K at
    (s, 10) moving at s' = 1), and the hinge I_O phi'' = m d cos(phi) s''(0.25+) -
    m g d sin(phi) with s''(0.25+) = 0 (s'' = 4 from the left: 1.98 rad/s^2 apart)."""
    model = _scene("pendl", PENDL, "  duration: 0.3\n  tolerance: 1.0e-8\n"
                   "  output_step: 0.05\n  drives:\n    trolley: {slider: travel, profile: "
                   "{type: trapezoid, distance: 0.5, v_max: 1, a_max: 4}}\n"
                   "    sw: {hinge: swing, torque: 0}\n", "{damping: exact}")
    mech = Mechanism(model, parse(model))
    assert mech.n == 3 and mech.nJ == 1
    v = np.zeros(3)
    v[1] = -0.3
    starts = []

    class Rec(integ.Recorder):
        def accept(self, t0, q0, v0, a0, ev0, *rest):
            starts.append((t0, q0.copy(), v0.copy(), a0.copy()))
            return super().accept(t0, q0, v0, a0, ev0, *rest)

    saved = integ.Recorder
    integ.Recorder = Rec
    try:
        res = simulate(model, initial={"q": mech.q0.copy(), "v": v}, fast=False)
    finally:
        integ.Recorder = saved
    assert res.status == 0
    at = [s for s in starts if s[0] == 0.25]
    assert len(at) == 1
    _, q, v, a = at[0]
    L0 = 10.0 * math.exp(-M_P * G / EA_P)
    d = np.array([q[0] - 0.125, q[1] - 10.0])        # K at s(0.25) = 4 x 0.25^2 / 2
    L = math.hypot(*d)
    edot = d @ (v[:2] - [1.0, 0.0]) / L
    assert abs(edot) > 0.1
    w = math.sqrt(EA_P / (L * M_P))
    b = PSI * EA_P / L / (2 * math.pi * w)
    S = EA_P * math.log(L / L0)
    aH = -(S + b * edot) * d / (L * M_P) + [0.0, -G]
    np.testing.assert_allclose(a[:2], aH, rtol=1e-9, atol=1e-9)
    # the hinge's coordinate is the arc u = rho phi, rho = 2 m (the bob's point B, the
    # farthest from the axis)
    assert mech.jc[0]["rho"] == 2.0
    phi = q[2] / 2.0
    assert a[2] == pytest.approx(-2.0 * MB * G * DB * math.sin(phi) / IOB, rel=1e-9,
                                 abs=1e-12)


# ----------------------------------------------------------------- two drums

WINCH2 = """cranefe: 1
name: two winches
plane: xz
nodes:
  W1: [-2, 0, 40]
  S1: [0, 0, 40]
  H1: [0, 0, 30]
  W2: [8, 0, 40]
  S2: [10, 0, 40]
  H2: [10, 0, 30]
ground: [W1, S1, W2, S2]
masses: {H1: 1000, H2: 500}
drums:
  d1: {node: W1, radius: 0.5, inertia: 10, rope_reserve: 100}
  d2: {node: W2, radius: 0.25, inertia: 4, rope_reserve: 100}
ropes:
  r1: {EA: 2.0e6, path: [d1, S1, H1]}
  r2: {EA: 1.0e6, path: [d2, S2, H2]}
"""


def test_each_drum_angle_is_weighted_by_its_own_radius():
    """Two torque-driven drums (radii 0.5 and 0.25 m): the coordinates are the two
    loads' heights (m) and the two drum angles (rad); the position error weighs each
    angle's acceleration difference by its drum's radius (metres of rope):
    err = max(|da_z1|, |da_z2|, 0.5 |da_1|, 0.25 |da_2|) / tol h^2/12 (the ropes slack:
    no force term)."""
    model = _scene("winch2", WINCH2, "  duration: 5\n  tolerance: 1.0e-6\n  drives:\n"
                   "    a: {drum: d1, torque: 2000}\n    b: {drum: d2, torque: 1000}\n",
                   "{sway: false}")
    mech, st = _stepper(model)
    assert mech.n == 4 and list(mech.qdrums) == [0, 1] and mech.nx == 2
    np.testing.assert_array_equal(st.wq, [1.0, 1.0, 0.5, 0.25])
    q = mech.q0.copy()
    a0, ev = st.accel(0.0, q, np.zeros(4), mech.taut0.copy())
    h, tol = 0.01, 1e-6 * model.length_scale
    slack = np.array([False, False])
    for da, e in [([1e-3, 0, 0, 0], 1e-3), ([0, 2e-3, 0, 0], 2e-3),
                  ([1e-3, 0, 4e-3, 0], 2e-3), ([1e-3, 0, 0, 6e-3], 1.5e-3),
                  ([0, 0, 3e-3, 8e-3], 2e-3), ([0, 0, 1e-3, 8e-3], 2e-3)]:
        err = st.error(h, a0, a0 + np.array(da), ev, slack)
        assert err == pytest.approx(e / tol * h * h / 12, rel=1e-12), da


# ----------------------------------------------------------------- the compiled paths

def _free_fall_model():
    from test_mutation_kills_integrate import TROLLEY
    from test_mutation_kills_integrate_loop import FREE
    return _scene("free", TROLLEY, FREE)


def _free_fall_checks(res):
    """The free fall of test_mutation_kills_integrate_loop.py: 14 error-free steps
    (doubling from 1 ms, cut at the kinks 0.25, 0.5, 0.75 s), 2 Newton iterations each,
    the height 5 + g/2 t - g/2 t^2 exact to round-off."""
    assert res.status == 0 and res.times[-1] == 1.0
    assert res.steps == 14 and res.rejected == 0 and res.newton_iterations == 28
    assert [e for _, e in res.events] == ["drive trolley starts", "drive trolley stops"]
    z = res.mass_position[:, 0, 2]
    np.testing.assert_allclose(z, 5.0 + G / 2 * res.times - G / 2 * res.times ** 2,
                               atol=1e-12)


needs_numba = pytest.mark.skipif(not integ._fast.available(), reason="numba not installed")


@needs_numba
def test_the_compiled_loop_takes_the_same_exact_steps():
    """fast=None with numba: the whole loop compiled (loop.py), handed the state, the
    step bounds (hmin, NEWTON_MAX, MAX_STEPS) and the progress callback by simulate():
    the same 14 steps and the exact free fall; progress is called as the loop advances,
    the last call at the end (1, 1)."""
    from test_mutation_kills_integrate_loop import FREE_INITIAL
    calls = []
    res = simulate(_free_fall_model(), initial=FREE_INITIAL,
                   progress=lambda t, T: calls.append((t, T)))
    _free_fall_checks(res)
    assert calls and calls[-1] == (1.0, 1.0)
    assert all(a[0] <= b[0] for a, b in zip(calls, calls[1:]))


@needs_numba
def test_the_compiled_loop_stops_at_the_step_limit(monkeypatch):
    """MAX_STEPS = 5 handed to the compiled loop: its 6th step (to 0.063 s) is one too
    many; the failure comes back through simulate's callback as the Python loop words
    it, with the results up to there (status 1)."""
    from test_mutation_kills_integrate_loop import FREE_INITIAL
    monkeypatch.setattr(integ, "MAX_STEPS", 5)
    with pytest.raises(integ.AnalysisError) as exc:
        simulate(_free_fall_model(), initial=FREE_INITIAL)
    assert str(exc.value) == "more than 5 steps at t = 0.063 s; raise analysis.tolerance"
    assert exc.value.result.status == 1 and exc.value.result.steps == 6


@pytest.mark.parametrize("duration, max_step, t6", [
    # T = 20 s: the first step is 1e-2 (not 1e-3 T = 0.02): 0.01, 0.02, 0.04, 0.08, then
    # 0.16 cut at the profile's kink 0.25, then max_step 0.2: the 6th step ends at 0.45
    # (a first step of 0.02 reaches 0.65)
    ("20", "0.2", "0.45"),
    # max_step 1e-4 < 1e-3 T: every step 1e-4, the 6th ends at 6e-4 (a first step of
    # 1e-3 T reaches 1.5e-3)
    ("1", "1.0e-4", "0.0006")])
def test_the_first_step_is_capped_by_max_step_and_by_10_ms(monkeypatch, duration, max_step,
                                                              t6):
    """The first step, min(max_step, 1e-3 T, 1e-2) s, in both loops (the free fall's
    error estimate is zero, so the steps double from it): MAX_STEPS = 5 stops each run
    at the end of its 6th step, where the two loops must agree with the hand sum."""
    from test_mutation_kills_integrate import TROLLEY
    from test_mutation_kills_integrate_loop import FREE, FREE_INITIAL
    monkeypatch.setattr(integ, "MAX_STEPS", 5)
    model = _scene("free", TROLLEY, FREE.replace("duration: 1\n", f"duration: {duration}\n")
                   .replace("max_step: 0.2", f"max_step: {max_step}"))
    for fast in (False, True):
        with pytest.raises(integ.AnalysisError) as exc:
            simulate(model, initial=FREE_INITIAL, fast=fast)
        assert str(exc.value) == f"more than 5 steps at t = {t6} s; raise analysis.tolerance"


@needs_numba
def test_the_compiled_step_in_the_python_loop():
    """fast="step": the Python loop calling fast.py's compiled step with the stepper's
    mass, tolerances and force scales: the free fall's exact steps, and the trolley
    pendulum (a taut rope: the force term of the estimate decides the steps) against
    DOP853 as in test_mutation_kills_integrate.py (6e-5 m; measured 2.9e-5 m with the
    numpy step), at most 510 steps and 3 rejections (measured 503 and 3 with the numpy
    step), 2 Newton iterations per trial (the jerk predictor)."""
    from test_mutation_kills_integrate import DURATION, TROLLEY, _ref_at
    from test_mutation_kills_integrate_loop import FREE_INITIAL
    res = simulate(_free_fall_model(), initial=FREE_INITIAL, fast="step")
    _free_fall_checks(res)
    model = _scene("trolley", TROLLEY, f"  duration: {DURATION}\n  tolerance: 1.0e-8\n"
                   "  output_step: 0.05\n  drives:\n    trolley: {slider: travel, "
                   "profile: {type: trapezoid, distance: 2, v_max: 1, a_max: 1}}\n")
    res = simulate(model, fast="step")
    assert res.status == 0
    ref = np.array([_ref_at(t) for t in res.times])
    P = res.mass_position[:, 0]
    err = max(np.abs(P[:, 0] - ref[:, 0]).max(), np.abs(P[:, 2] - ref[:, 1]).max())
    assert err < 6e-5, err
    assert res.steps <= 510 and res.rejected <= 3, (res.steps, res.rejected)
    assert res.newton_iterations == 2 * (res.steps + res.rejected)
    # the same steps as the numpy step (the reference; its force term of the estimate
    # decides them here: without it 381 steps instead of 503) and the same peak force
    ref = simulate(model, fast=False)
    assert (res.steps, res.rejected) == (ref.steps, ref.rejected)
    np.testing.assert_allclose(res.rope_force_max, ref.rope_force_max, rtol=1e-9)


# ----------------------------------------------------------------- long slack steps

LONG = """cranefe: 1
name: load on a long rope
nodes:
  A: [0, 0, 100]
  H: [0, 0, 0]
ground: [A]
masses: {H: 200}
ropes:
  r: {EA: 4.0e5, path: [A, H]}
"""


def test_a_slack_rope_adds_nothing_to_the_error_of_a_long_step():
    """The load on a 100-m rope thrown up at 40 m/s from 1 m above its static place (the
    rope slack: L = 99 m < L0 = 100 exp(-m g / EA) = 99.51 m) flies freely for 8.17 s
    (back at L = L0): every step's estimate is round-off, so from 1e-3 x 8 s the steps
    double to 4.088 s and the last, cut to the end, is 3.912 s long: accepted, the
    slack rope's force term being zero (its h^2/12 = 1.28 alone would exceed 1). 10
    steps, none rejected; the height 1 + 40 t - g t^2/2 to round-off (1e-9 m at 80 m)."""
    model = _scene("long", LONG, "  duration: 8\n  tolerance: 1.0e-8\n  max_step: 8\n"
                   "  output_step: 1\n", "{sway: false}")
    res = simulate(model, initial={"q": np.array([1.0]), "v": np.array([40.0])}, fast=False)
    assert res.events == [] and res.status == 0
    assert res.steps == 10 and res.rejected == 0
    np.testing.assert_allclose(res.mass_position[:, 0, 2],
                               1.0 + 40.0 * res.times - G / 2 * res.times ** 2, atol=1e-9)


def test_a_load_lighter_than_1_n_still_has_its_force_term():
    """A 50-g load (static force 0.49 N) on a 5-m rope of EA 4e5 N: the force term of the
    estimate, EA / (FORCE_TOL tol) |G da| / (L S0) with G = dL/dz = -1, L = 5 m, is
    8155 times the position term |da| / (tol x 10 m): err = that x h^2/12."""
    from test_mutation_kills_integrate import ROPE
    model = _scene("light1", ROPE.replace("masses: {H: 200}", "masses: {H: 0.05}"),
                   "  duration: 1\n  tolerance: 1.0e-6\n", "{sway: false}")
    mech, st = _stepper(model)
    S0 = 0.05 * G
    np.testing.assert_allclose(mech.S0, [S0], rtol=1e-12)
    assert st.fscale is not None
    taut = mech.taut0.copy()
    a0, ev = st.accel(0.0, mech.q0.copy(), np.zeros(1), taut)
    h, da = 0.01, 1e-3
    ef = 4.0e5 / (integ.FORCE_TOL * 1e-6) * da / (5.0 * S0)
    assert ef > 1000 * da / (1e-6 * model.length_scale)
    err = st.error(h, a0, a0 + da, ev, taut)
    assert err == pytest.approx(ef * h * h / 12, rel=1e-9)


# ----------------------------------------------------------------- rejections counted

def test_a_failed_event_search_adds_one_rejection_to_those_before():
    """The two loads falling onto their ropes (test_mutation_kills_integrate_loop.py):
    the 2nd step fails (Newton, injected) and the event search's first trial fails too:
    two rejections, counted on top of each other and of the error rejections the loop
    meets after the events (the taut ropes' force term: counted here from the estimates
    the loop receives); both events stay at sqrt(2 d / g)."""
    import sys

    from test_mutation_kills_integrate import DROP2

    class Failing(integ.Stepper):
        calls, searched, too_large = 0, False, 0

        def step(self, *args, **kw):
            Failing.calls += 1
            if Failing.calls == 2:
                return None
            search = "_locate" in sys._getframe(1).f_code.co_name
            if search and not Failing.searched:
                Failing.searched = True
                return None
            out = super().step(*args, **kw)
            if not search and out is not None and out[4] > 1.0:
                Failing.too_large += 1          # the loop's own error rejections
            return out

    model = _scene("drop2c", DROP2, "  duration: 0.2022\n  tolerance: 1.0e-8\n"
                   "  max_step: 0.5\n", "{sway: false}")
    mech = Mechanism(model, parse(model))
    L0 = mech.L0_ref
    init = {"q": np.array([10.0 - L0[0] + 0.2, 10.0 - L0[1] + 0.2005]), "v": np.zeros(2)}
    saved = integ.Stepper
    integ.Stepper = Failing
    try:
        res = simulate(model, initial=init, fast=False)
    finally:
        integ.Stepper = saved
    assert Failing.searched and Failing.calls > 10
    assert Failing.too_large <= 2
    assert res.rejected == 2 + Failing.too_large, (res.rejected, Failing.too_large)
    assert [w for _, w in res.events] == ["rope r1 taut", "rope r2 taut"]
    np.testing.assert_allclose([t for t, _ in res.events],
                               [math.sqrt(0.4 / G), math.sqrt(0.401 / G)], atol=1e-9)


# ----------------------------------------------------------------- failures in a run

@pytest.mark.parametrize("case, torque, what", [
    # the drum free (torque 0) lets the load pay out its 1 m of rope
    ("payout", 0, "drum 'hoist' (drive 'h', torque) has paid out 1."),
    # 30 kN m hauls the load 10 m up into its sheave S within 0.5 s
    ("block", 30000, "the span S-H is down to "),
])
def test_a_run_stops_with_the_time_it_reached(case, torque, what):
    """A drum's rope paid out (rope_reserve 1 m) and a load hauled into its sheave stop
    the run (exit 1) with a message naming the time of the last accepted step, which is
    the failed result's duration."""
    text = WINCH.replace("rope_reserve: 100", "rope_reserve: 1") if case == "payout" else WINCH
    model = _scene(f"fail_{case}", text, "  duration: 5\n  tolerance: 1.0e-6\n  drives:\n"
                   f"    h: {{drum: hoist, torque: {torque}}}\n", "{sway: false}")
    with pytest.raises(integ.AnalysisError) as exc, np.errstate(invalid="ignore"):
        simulate(model, fast=False)
    r = exc.value.result
    assert r.status == 1 and 0 < r.duration < 1
    msg = str(exc.value)
    assert msg.startswith(f"at t = {r.duration:.6g} s {what}"), msg
    assert msg.endswith(f"the results up to t = {r.duration:.6g} s are kept")


# ----------------------------------------------------------------- a massless block

EA_H, EA_S, M_B = 1.0e7, 5.0e6, 1000.0


def _block_height(z):
    """The massless block's height y where its two falls hold the sling (sway off):
    2 EA_h ln((5 + 2 (20 - y)) / L0_h) = EA_s ln((y - z) / L0_s)."""
    L0h = 25.0 * math.exp(-M_B * G / 2 / EA_H)
    L0s = 3.0 * math.exp(-M_B * G / EA_S)
    return brentq(lambda y: 2 * EA_H * math.log((45.0 - 2 * y) / L0h)
                  - EA_S * math.log((y - z) / L0s), z + 2.0, 22.0, xtol=1e-15, rtol=1e-15)


@functools.cache
def _block_reference():
    L0s = 3.0 * math.exp(-M_B * G / EA_S)

    def f(t, s):
        return [s[1], EA_S * math.log((_block_height(s[0]) - s[0]) / L0s) / M_B - G]

    return solve_ivp(f, (0, 0.25), [7.0 - 1e-3, 0.0], method="DOP853", rtol=1e-12,
                     atol=1e-14, dense_output=True).sol


def test_a_load_below_a_massless_block_against_the_equations_by_hand():
    """The load on a sling below a massless block on 2 falls (tests/test_operation_massless.py,
    sway off: the load's and the block's heights, the block's row algebraic): released
    1 mm below its static place (the block put into equilibrium by the stepper), the
    load's height against DOP853 on m z'' = S_s(y(z) - z) - m g with the block's y(z)
    from its equilibrium 2 S_h = S_s by hand, to 8e-7 m over 0.25 s (1.1 axial periods;
    measured 3.8e-7 at tolerance 1e-8, 8.8e-8 at 1e-9, 2.0e-8 at 1e-10: tolerance^(2/3),
    it converges). Newton: 2 iterations per trial (the block's velocity from the
    implicit function keeps the predictor's error O(h^4))."""
    from test_operation_massless import BLOCK
    model = _scene("block", BLOCK, "  duration: 0.25\n  tolerance: 1.0e-8\n"
                   "  output_step: 0.01\n", "{sway: false}")
    mech = Mechanism(model, parse(model))
    assert mech.n == 2 and list(mech.qy) == [1] and list(mech.M) == [M_B, 0.0]
    assert mech.q0[1] == pytest.approx(_block_height(7.0), abs=1e-9)
    q = mech.q0.copy()
    q[0] -= 1e-3
    res = simulate(model, initial={"q": q}, fast=False)
    assert res.status == 0
    z = res.mass_position[:, 0, 2]
    err = np.abs(z - _block_reference()(res.times)[0]).max()
    assert err < 8e-7, err
    assert np.ptp(z) > 1.5e-3
    assert res.newton_iterations == 2 * (res.steps + res.rejected)


@pytest.mark.parametrize("fast", [False, None])
def test_a_prescribed_drum_hauls_its_load_into_the_sheave(fast):
    """The winch's drum by a speed table (0 -> 20 rad/s in 1 s, held to 1.99 s, back to
    0 at 2.99 s: 39.8 rad, 19.9 m of rope, the falls hold 20 m) hauls the load up until
    the span S-H is below 1 % of its 10 m: with rigid ropes span = 10 - R theta / 2,
    0.1 m at theta = 39.6 rad, t = 1.99 + 1 - sqrt(0.02) = 2.8486 s (0.05 s: the falls'
    static stretch, 0.058 m of rope, moves the span by up to 0.03 m at the haul's
    0.7 m/s; measured 2 ms). The numpy loop and the compiled one (numba; its failure
    status handed back to simulate's callback with the mechanism) stop there with the
    same message."""
    if fast is None and not integ._fast.available():
        pytest.skip("numba not installed")
    model = _scene("haul", WINCH, "  duration: 5\n  tolerance: 1.0e-6\n  drives:\n"
                   "    h: {drum: hoist, profile: {type: table, speed: [[0, 0], [1, 20], "
                   "[1.99, 20], [2.99, 0]]}}\n", "{sway: false}")
    with pytest.raises(integ.AnalysisError) as exc, np.errstate(invalid="ignore"):
        simulate(model, fast=fast)
    r = exc.value.result
    assert r.status == 1
    assert r.duration == pytest.approx(1.99 + 1 - math.sqrt(0.02), abs=0.05)
    msg = str(exc.value)
    assert msg.startswith(f"at t = {r.duration:.6g} s the span S-H is down to 0.0"), msg
    assert "(1.0% of its length): the load was hauled into its sheave (two-blocking)" in msg
    assert msg.endswith(f"the results up to t = {r.duration:.6g} s are kept")


def test_a_sliver_before_a_kink_is_taken_into_the_step():
    """The free fall below the trolley, its trapezoid's first kink put at
    v_max / a_max = 0.25500000001 s: the doubling steps reach 0.127 s and the next
    (0.128 s) would stop 1e-11 s short of the kink, less than 1e-9 of the step: the
    step is stretched to end at the kink (no sliver step of 1e-11 s after it); then
    twice that step capped by max_step 0.2 s, and the end cut: 12 steps."""
    from test_mutation_kills_integrate import TROLLEY
    from test_mutation_kills_integrate_loop import FREE, FREE_INITIAL, _run, _times
    model = _scene("sliver", TROLLEY, FREE.replace(
        "distance: 0.5, v_max: 1, a_max: 4", "distance: 0.5, v_max: 0.25500000001, a_max: 1"))
    res, steps = _run(model, initial=FREE_INITIAL)
    k = 0.25500000001
    want = [0, .001, .003, .007, .015, .031, .063, .127, k, k + 0.2, k + 0.4, k + 0.6, 1.0]
    np.testing.assert_allclose(_times(steps), want, rtol=0, atol=1e-15)
    assert steps[7][1] == k
    assert res.steps == 12 and res.rejected == 0
