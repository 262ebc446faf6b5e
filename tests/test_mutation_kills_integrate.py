"""Value tests of cranefe/analysis/operation/integrate.py (issue 20, mutation testing),
the numpy reference stepper (every run here passes fast=False, so the compiled loop of
loop.py/fast.py is never used and the module's own code is exercised):

- a pendulum on an elastic rope hanging from a trolley moved by a trapezoid, against
  scipy's DOP853 at rtol 1e-12 on the same equations written by hand (computed once per
  session, functools.lru_cache), segment by segment between the profile's kinks;
- one trapezoidal step of a linear oscillator (a load on an axial spring, sway off)
  against the rule solved by hand, q1 (1 + h^2 w^2/4) = q0 + h v0 + h^2/4 (a0 + w^2 q_e),
  and its error estimate h^2/12 |a1 - a0| / tolerance, which is O(h^3);
- the rope-force part of the estimate, EA/(FORCE_TOL tol) |G da| h^2/12 / (L S);
- the step controller's factors by hand (Gustafsson's rule, Hairer-Wanner IV.8.21);
- a rope going taut: a load thrown down on a slack rope falls freely until L = L0, so
  the event is where 0.2 m = v0 t + g t^2/2 (the Illinois search's location); this
  found a bug, fixed in simulate(): a rope given slack in `initial` started "taut" and
  the event step of ~1e-17 s at t = 0 reversed the given velocity;
- a torque-driven rigid arm (a joint coordinate): I_O phi'' = M + 2 m_b g cos(phi)
  against scipy;
- the two-blocking and blow-up errors and the step limit.
"""

import functools
import math
import tempfile
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from test_mutation_kills_mechanism import trolley_xs
from test_operation import scene

from cranefe.analysis.operation import integrate as integ
from cranefe.analysis.operation.integrate import StepControl, Stepper, simulate
from cranefe.analysis.operation.mechanism import Mechanism
from cranefe.analysis.operation.scene import parse
from cranefe.errors import AnalysisError
from cranefe.model import load

G = 9.81


@functools.lru_cache(maxsize=None)
def _dir():
    return Path(tempfile.mkdtemp(prefix="mutkill-integ-"))


def _scene(name, model_text, analysis, effects="{}"):
    return load(scene(_dir(), model_text, analysis, effects, name=f"s_{name}.yaml"))


# ----------------------------------------------------------------- trolley pendulum

M_LOAD, EA_ROPE, L_REF = 1000.0, 1.0e6, 10.0
TROLLEY = f"""cranefe: 1
name: trolley pendulum
plane: xz
nodes:
  K: [0, 0, 10]
  H: [0, 0, 0]
masses: {{H: {M_LOAD}}}
bodies:
  trolley: {{mass: 500, com: [0, 0, 10], inertia: [10, 10, 10], nodes: [K]}}
joints:
  - {{name: travel, type: slider, bodies: [ground, trolley], at: K, axis: [1, 0, 0],
     range: [-1, 20]}}
ropes:
  hoist: {{EA: {EA_ROPE}, path: [K, H]}}
"""
DURATION = 4.0


def _rhs(t, y):
    """The load on its Hencky rope from the moving trolley (docs/operations.md)."""
    x, z, vx, vz = y
    d = np.array([x - trolley_xs(t)[0], z - L_REF])
    L = math.hypot(*d)
    L0 = L_REF * math.exp(-M_LOAD * G / EA_ROPE)
    S = EA_ROPE * math.log(L / L0) if L > L0 else 0.0
    a = np.array([0.0, -G]) - S * d / (L * M_LOAD)
    return [vx, vz, a[0], a[1]]


@functools.lru_cache(maxsize=None)
def _reference():
    """DOP853 at rtol 1e-12 between the profile's kinks (t = 1, 2, 3)."""
    y = np.array([0.0, 0.0, 0.0, 0.0])
    sols = []
    for a, b in [(0, 1), (1, 2), (2, 3), (3, DURATION)]:
        s = solve_ivp(_rhs, (a, b), y, method="DOP853", rtol=1e-12, atol=1e-13,
                      dense_output=True)
        sols.append((a, b, s.sol))
        y = s.y[:, -1]
    return sols


def _ref_at(t):
    for a, b, sol in _reference():
        if a <= t <= b:
            return sol(t)
    raise ValueError(t)


def _trolley_run():
    # not cached: mutmut forks its runs from a process that already ran the tests, so a
    # cached result of the code under test would hide the mutants (only the scipy
    # reference, which does not depend on the code, is cached)
    model = _scene("trolley", TROLLEY, f"  duration: {DURATION}\n  tolerance: 1.0e-8\n"
                   "  output_step: 0.05\n  drives:\n    trolley: {slider: travel, "
                   "profile: {type: trapezoid, distance: 2, v_max: 1, a_max: 1}}\n")
    return simulate(model, fast=False)


def test_trolley_pendulum_against_scipy():
    """The load's path to 6e-5 m over 4 s (tolerance 1e-8 x 10 m per step, 500 steps:
    measured 2.9e-5 m; the global error of the second-order rule falls as
    tolerance^(2/3): 6.6e-6 m at 1e-9, 1.5e-6 m at 1e-10, so it converges to the
    reference), the rope force to 6e-5 of the static force (measured 3.0e-5: EA/L times
    the position error along the rope), the energy balance to 5e-5 (measured 2.1e-5)."""
    res = _trolley_run()
    assert res.status == 0 and res.times[-1] == pytest.approx(DURATION, abs=1e-12)
    ref = np.array([_ref_at(t) for t in res.times])
    P = res.mass_position[:, 0]
    err = max(np.abs(P[:, 0] - ref[:, 0]).max(), np.abs(P[:, 2] - ref[:, 1]).max())
    assert err < 6e-5, err
    L0 = L_REF * math.exp(-M_LOAD * G / EA_ROPE)
    xs = np.array([trolley_xs(t)[0] for t in res.times])
    L = np.hypot(ref[:, 0] - xs, ref[:, 1] - L_REF)
    S = EA_ROPE * np.log(L / L0)
    assert np.abs(res.rope_force[:, 0] - S).max() < 6e-5 * M_LOAD * G
    # the drive's events at its kinks
    assert (0.0, "drive trolley starts") in res.events
    assert (3.0, "drive trolley stops") in res.events
    # energy balance closes to the integrator's error
    assert res.energy_error < 5e-5, res.energy_error
    assert res.steps > 50 and res.rejected < res.steps
    # the cost: 2 Newton iterations per trial step (measured 1012 for 503 + 3): the
    # predictor from the last step's jerk leaves the O(h^4) error that one correction
    # removes (a worse predictor, tangent or jerk needs a third iteration)
    assert res.newton_iterations == 2 * (res.steps + res.rejected)
    # and the steps themselves (measured 503 and 3 rejected): a controller that keeps a
    # long step after an accepted one with a growing error is rejected more often
    assert res.steps <= 510 and res.rejected <= 3, (res.steps, res.rejected)


# ----------------------------------------------------------------- one step by hand

SPRING = """cranefe: 1
name: oscillator
nodes:
  A: [0, 0, 10]
  H: [0, 0, 5]
ground: [A]
masses: {H: 200}
springs:
  - {name: s, type: axial, nodes: [A, H], stiffness: 8.0e4}
"""


def _stepper(model):
    mech = Mechanism(model, parse(model))
    return mech, Stepper(mech, parse(model), model.length_scale, fast=False)


def test_one_trapezoidal_step_of_a_linear_oscillator_by_hand():
    """Sway off: the load's height z on a vertical spring is exactly linear,
    z'' = -w^2 (z - z_e), w^2 = k/m, z_e = 5. From z0 = 5.01, v0 = 0.2 the trapezoidal
    step solved by hand; the estimate h^2/12 |a1 - a0| / (tol x size) and its order 3
    (near the equilibrium a1 - a0 = -w^2 h v0 (1 + O(h^2 w^2, a0 h / v0)): 8 to 2 %)."""
    model = _scene("spring", SPRING, "  duration: 1\n  tolerance: 1.0e-6\n",
                   "{sway: false}")
    mech, st = _stepper(model)
    assert st.fscale is None            # no rope: the position error only
    m, k = 200.0, 8.0e4
    w2 = k / m
    q0, v0 = np.array([5.0001]), np.array([0.2])
    taut = mech.taut0.copy()
    a0, ev0 = st.accel(0.0, q0, v0, taut)
    np.testing.assert_allclose(a0, -w2 * (q0 - 5.0), rtol=1e-9)
    errs = []
    for h in (0.01, 0.005):
        q1, v1, a1, ev1, err = st.step(0.0, q0, v0, a0, h, taut)
        qh = (q0 + h * v0 + h * h / 4 * (a0 + w2 * 5.0)) / (1 + h * h * w2 / 4)
        ah = -w2 * (qh - 5.0)
        vh = v0 + h / 2 * (a0 + ah)
        np.testing.assert_allclose(q1, qh, rtol=0, atol=1e-12)
        np.testing.assert_allclose(v1, vh, rtol=0, atol=1e-9)
        np.testing.assert_allclose(a1, ah, rtol=0, atol=1e-7)
        tol = 1e-6 * model.length_scale
        assert err == pytest.approx(h * h / 12 * abs(ah - a0[0]) / tol, rel=1e-6)
        errs.append(err)
    # O(h^3): halving h divides it by 8 (to the O(h) of a1 - a0's next term)
    assert errs[0] / errs[1] == pytest.approx(8.0, rel=0.02)
    # linear: the fresh tangent's correction is exact, the second iterate confirms it;
    # one tangent per step
    assert st.newton_iterations == 4 and st.tangents == 2
    # with a predictor from a jerk: the same solution
    out = st.step(0.0, q0, v0, a0, 0.01, taut, jerk=np.array([3.0]))
    np.testing.assert_allclose(out[0], (q0 + 0.01 * v0 + 1e-4 / 4 * (a0 + w2 * 5.0))
                               / (1 + 1e-4 * w2 / 4), atol=1e-12)


ROPE = """cranefe: 1
name: hanging load
nodes:
  A: [0, 0, 10]
  H: [0, 0, 5]
ground: [A]
masses: {H: 200}
ropes:
  r: {EA: 4.0e5, path: [A, H]}
"""


def test_rope_force_error_estimate_by_hand():
    """A load on one rope (sway off): the estimate is the larger of the position error
    and EA/(FORCE_TOL tol) |G da| h^2/12 / (L max(S0, |S|)), G = dL/dz = -1."""
    model = _scene("rope", ROPE, "  duration: 1\n  tolerance: 1.0e-6\n", "{sway: false}")
    mech, st = _stepper(model)
    EA, m = 4.0e5, 200.0
    q0, v0 = np.array([5.0]), np.array([0.3])
    taut = mech.taut0.copy()
    a0, _ = st.accel(0.0, q0, v0, taut)
    h = 0.004
    q1, v1, a1, ev1, err = st.step(0.0, q0, v0, a0, h, taut)
    # the step satisfies m a1 = S(q1) - m g and the trapezoidal relations
    L0 = 5.0 * math.exp(-m * G / EA)
    L1 = 10.0 - q1[0]
    S1 = EA * math.log(L1 / L0)
    assert m * a1[0] == pytest.approx(S1 - m * G, rel=1e-9, abs=1e-6)
    np.testing.assert_allclose(q1, q0 + h * v0 + h * h / 4 * (a0 + a1), atol=1e-13)
    np.testing.assert_allclose(v1, v0 + h / 2 * (a0 + a1), atol=1e-10)
    da = a1[0] - a0[0]
    tol = 1e-6 * model.length_scale
    ftol = integ.FORCE_TOL * 1e-6
    e_pos = abs(da) / tol
    e_force = EA / ftol * abs(da) / (L1 * max(m * G, abs(S1)))
    assert err == pytest.approx(max(e_pos, e_force) * h * h / 12, rel=1e-6)
    assert e_force > e_pos               # the force term decides here
    # slack: the force term is left out for a slack rope
    errs = st.error(h, a0, a1, ev1, np.array([False]))
    assert errs == pytest.approx(e_pos * h * h / 12, rel=1e-9)
    # the crossing test: none while taut and stretched; the slack one when L < L0
    assert st.crossing(ev1, taut) is None
    ev1.L = np.array([0.9 * L0])
    assert st.crossing(ev1, taut).tolist() == [0]
    assert st.crossing(ev1, np.array([False])) is None
    ev1.L = np.array([1.1 * L0])
    assert st.crossing(ev1, np.array([False])).tolist() == [0]
    assert st.stretch(ev1)[0] == pytest.approx(math.log(1.1), rel=1e-12)


def test_step_control_by_hand():
    """Gustafsson's controller: accepted steps take the smaller of 0.9 err^(-1/3) and
    0.9 (h/h_prev) (err_prev/err)^(1/3) err^(-1/3), bounded to [0.2, 2] (1 after a
    rejection); rejected steps 0.9 err^(-1/3), at least 0.2."""
    c = StepControl()
    assert c.accepted(1.0, 0.001) == pytest.approx(2.0)          # 9.0: capped at 2
    # second: h = 2, err = 0.5: elementary 0.9 * 0.5^(-1/3) = 1.134; predictive
    # 0.9 * (2/1) * (max(0.001, 0.01)/0.5)^(1/3) * 0.5^(-1/3) = 0.9*2*0.2714*1.26 = 0.6156
    fac = min(0.9 * 0.5 ** (-1 / 3), 0.9 * 2.0 * (0.01 / 0.5) ** (1 / 3) * 0.5 ** (-1 / 3))
    assert c.accepted(2.0, 0.5) == pytest.approx(2.0 * fac, rel=1e-12)
    assert c.rejected(1.0, 8.0) == pytest.approx(0.45, rel=1e-12)
    assert c.rejected(1.0, 1e6) == pytest.approx(0.2, rel=1e-12)
    assert c.after_reject
    # after a rejection the next accepted step does not grow
    c.reset()
    assert c.h_acc is None and c.err_acc is None
    assert c.accepted(1.0, 0.001) == pytest.approx(1.0)
    assert not c.after_reject
    # err floored at 1e-10 before the power; the history keeps err >= 1e-2
    c2 = StepControl()
    assert c2.accepted(1.0, 0.0) == pytest.approx(2.0)
    assert c2.err_acc == 1e-2 and c2.h_acc == 1.0
    c3 = StepControl()
    assert c3.accepted(1.0, 0.9) == pytest.approx(0.9 * 0.9 ** (-1 / 3), rel=1e-12)
    assert c3.accepted(1.0, 1e-12) == pytest.approx(
        min(2.0, 0.9 * (1.0 / 1.0) * (0.9 / 1e-10) ** (1 / 3) * 1e-10 ** (-1 / 3)))
    c4 = StepControl()
    assert c4.accepted(1.0, 1e3) == pytest.approx(0.2)


# ----------------------------------------------------------------- events

DROP = """cranefe: 1
name: dropped load
nodes:
  A: [0, 0, 10]
  H: [0, 0, 5]
ground: [A]
masses: {H: 100}
ropes:
  r: {EA: 1.0e6, path: [A, H]}
"""


def test_a_dropped_load_pulls_its_rope_taut_at_the_free_fall_time():
    """Thrown down at 0.5 m/s from 0.2 m above where the rope becomes taut (L = L0): free
    fall, the taut event where 0.2 = 0.5 t + g t^2 / 2 (the stretch crosses zero: the
    Illinois search to ~1e-12 s; the step's error in the free fall is zero: a constant
    acceleration is integrated exactly by the trapezoidal rule)."""
    model = _scene("drop", DROP, "  duration: 0.22\n  tolerance: 1.0e-8\n  output_step: 0.01\n",
                   "{sway: false}")
    mech = Mechanism(model, parse(model))
    L0 = mech.L0_ref[0]
    z0 = 10.0 - L0 + 0.2
    v0 = -0.5                                   # thrown down at 0.5 m/s
    res = simulate(model, initial={"q": np.array([z0]), "v": np.array([v0])}, fast=False)
    # the rope given slack starts slack (no event at t = 0, which reversed the given
    # speed before the fix of 2026-11-24); taut where 0.2 = 0.5 t + g t^2 / 2
    assert [w for _, w in res.events] == ["rope r taut"], res.events
    t_star = (v0 + math.sqrt(v0 * v0 + 2 * G * 0.2)) / G
    assert res.events[0][0] == pytest.approx(t_star, abs=1e-9)
    z = res.mass_position[:, 0, 2]
    free = res.times < t_star
    np.testing.assert_allclose(z[free], z0 + v0 * res.times[free] - G * res.times[free] ** 2 / 2,
                               atol=1e-9)
    # the rope pulled taut: the load stopped and bounced below the taut point
    assert res.rope_force_max[0] > 100 * G
    # no drive, no dashpot: an elastic rope's events add no work and dissipate nothing
    assert res.energy["work_drives"] == 0.0 and res.energy["dissipated"] == 0.0


# ----------------------------------------------------------------- joint coordinate

ARM = """cranefe: 1
name: arm
plane: xz
nodes:
  O: [0, 0, 10]
  T: [4, 0, 10]
  P: [0, 0, 14]
ground: [P]
bodies:
  arm: {mass: 200, com: [2, 0, 10], inertia: [1, 50, 50], nodes: [O, T]}
joints:
  - {name: luff, type: hinge, bodies: [ground, arm], at: O, axis: [0, 1, 0],
     range: [-1, 1]}
ropes:
  stay: {EA: 5.0e8, path: [P, T]}
"""
MB, IO = 200.0, 50.0 + 200.0 * 4.0
TQ = -1.2 * 2 * MB * G          # 20 % above what holds the arm: it turns tip up


@functools.lru_cache(maxsize=None)
def _arm_reference():
    f = lambda t, y: [y[1], (TQ + 2 * MB * G * math.cos(y[0])) / IO]   # noqa: E731
    return solve_ivp(f, (0, 0.6), [0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14,
                     dense_output=True).sol


def test_torque_driven_arm_against_scipy():
    """Moments about O: I_O phi'' = M + 2 m_b g cos(phi) (the stay goes slacker as the tip
    rises); the drive angle to 3e-6 rad over 0.6 s (tolerance 1e-8 x 4 m per step, 67
    steps: measured 8.6e-7 rad; 2.5e-7 at 1e-9)."""
    model = _scene("arm", ARM, f"  duration: 0.6\n  tolerance: 1.0e-8\n  output_step: 0.05\n"
                   f"  drives:\n    d: {{hinge: luff, torque: {TQ!r}}}\n")
    res = simulate(model, fast=False)
    phi = res.drive_position[:, 0]
    ref = _arm_reference()(res.times)[0]
    assert phi[-1] < -0.15
    assert np.abs(phi - ref).max() < 3e-6, np.abs(phi - ref).max()
    # the cost: 2 Newton iterations per trial step (the joint block's tangent c1 M_J +
    # dM_J/du a exact: with a wrong one the modified Newton needs more)
    assert res.newton_iterations == 2 * (res.steps + res.rejected)


# ----------------------------------------------------------------- failures

def test_failures_name_their_cause():
    model = _scene("rope2", ROPE, "  duration: 1\n", "{sway: false}")
    mech = Mechanism(model, parse(model))
    # two-blocking: a span down to 1 % of its length
    integ._two_blocking(mech, np.array([0.06]), 1.0)
    with pytest.raises(AnalysisError) as exc:
        integ._two_blocking(mech, np.array([0.04]), 1.25)
    assert "span A-H is down to 0.04 m (0.8% of its length)" in str(exc.value)
    assert "t = 1.25 s" in str(exc.value)
    e = integ._blowup(2.0, 1e-13, "the step size collapsed", mech, None, np.array([True]))
    assert "the step size collapsed at t = 2 s (step 1e-13 s)" in str(e)
    assert "drive accelerating" in str(e)
    e = integ._blowup(2.0, 1e-13, "x", mech, None, np.array([False]))
    assert "snatch loads" in str(e)
    with pytest.raises(AnalysisError, match="Newton's method does not converge"):
        integ._fail(mech, integ._loop.NEWTON, 1.0, 1e-3, np.array([True]), None)
    with pytest.raises(AnalysisError, match="the step size collapsed"):
        integ._fail(mech, integ._loop.COLLAPSE, 1.0, 1e-3, np.array([True]), None)
    with pytest.raises(AnalysisError, match="two-blocking"):
        integ._fail(mech, integ._loop.TWO_BLOCK, 1.0, 1e-3, np.array([True]),
                    np.array([0.01]))
    with pytest.raises(AnalysisError, match="more than"):
        integ._fail(mech, -12345, 1.0, 1e-3, np.array([True]), None)


def test_step_limit_stops_the_run(monkeypatch):
    monkeypatch.setattr(integ, "MAX_STEPS", 5)
    model = _scene("rope3", ROPE, "  duration: 1\n", "{sway: false}")
    with pytest.raises(AnalysisError) as exc:
        simulate(model, initial={"q": np.array([5.01]), "v": np.zeros(1)}, fast=False)
    assert "more than 5 steps" in str(exc.value)
    assert exc.value.result.status == 1


def test_trolley_force_carries_a_guided_load_at_the_closed_form():
    """sway: false, the trolley a force coordinate (300 N) carrying the load's horizontal
    inertia: s'' = F / (m_t + m) = 0.2 m/s^2 exactly, s = 0.1 t^2; the load's height is
    in equilibrium and stays (the rule integrates a constant acceleration exactly: 1e-9
    is round-off over the steps)."""
    model = _scene("guided", TROLLEY, "  duration: 1\n  tolerance: 1.0e-8\n  output_step: 0.1\n"
                   "  drives:\n    f: {slider: travel, force: 300}\n", "{sway: false}")
    res = simulate(model, fast=False)
    np.testing.assert_allclose(res.drive_position[:, 0], 0.1 * res.times ** 2, atol=1e-9)
    np.testing.assert_allclose(res.mass_position[:, 0, 2], 0.0, atol=1e-9)
    np.testing.assert_allclose(res.mass_position[:, 0, 0], 0.1 * res.times ** 2, atol=1e-9)


DROP2 = """cranefe: 1
name: two dropped loads
nodes:
  A: [0, 0, 10]
  B: [3, 0, 10]
  H: [0, 0, 5]
  K: [3, 0, 5]
ground: [A, B]
masses: {H: 100, K: 100}
ropes:
  r1: {EA: 1.0e6, path: [A, H]}
  r2: {EA: 1.0e6, path: [B, K]}
"""


def test_two_ropes_pulled_taut_at_their_free_fall_times():
    """Two loads released at rest 0.2 m and 0.2005 m above their ropes' taut points: the
    free fall is integrated exactly, so the steps grow to the run's max_step and both
    crossings fall in one step; each event at sqrt(2 d / g), the earlier first."""
    model = _scene("drop2", DROP2, "  duration: 0.22\n  tolerance: 1.0e-8\n  max_step: 0.5\n",
                   "{sway: false}")
    mech = Mechanism(model, parse(model))
    L0 = mech.L0_ref
    q = np.array([10.0 - L0[0] + 0.2, 10.0 - L0[1] + 0.2005])
    res = simulate(model, initial={"q": q, "v": np.zeros(2)}, fast=False)
    ev = [(t, w) for t, w in res.events if w.endswith("taut")]
    assert [w for _, w in ev] == ["rope r1 taut", "rope r2 taut"], res.events
    assert ev[0][0] == pytest.approx(math.sqrt(2 * 0.2 / G), abs=1e-9)
    assert ev[1][0] == pytest.approx(math.sqrt(2 * 0.2005 / G), abs=1e-9)
