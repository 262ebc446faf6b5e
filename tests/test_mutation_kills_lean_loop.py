"""Value tests of cranefe/analysis/operation/loop.py (issue 20, mutation testing): the
whole integration loop of the lean path written for numba. Without numba (CI: the
`fast` extra is not in `test`) its functions are plain Python; `fast.available` is
then made to answer True here so that `simulate` takes the loop (with numba the loop
runs compiled, as it does by default). For the mutation run numba's JIT is disabled
(NUMBA_DISABLE_JIT=1), so that mutmut's trampolines are plain Python too.

Independent values:
- the drive profiles' table (`_motion`) against profiles.Motion written out by hand
  (s = s_k + v_k tau + a_k tau^2/2 + j_k tau^3/6, the speed before the first segment);
- the trolley pendulum against scipy's DOP853 at rtol 1e-12 (tests/
  test_mutation_kills_integrate.py's reference: the load's path to 6e-5 m, the rope's
  force to 6e-5 of the static force, the energy balance to 5e-5, 2 Newton iterations a
  trial step);
- two loads thrown up on their ropes: the slack and taut events against scipy
  (tests/test_mutation_kills_integrate_loop.py's reference, the same bounds).
The reference implementation (integrate.py's numpy loop, fast=False, and lean.py's
Lean, both mutation-tested against hand values: docs/mutation.md): the kinematics
`_kin` against Lean._kin, the powers and energies against Lean.powers/energy and
Recorder._force_rate at states off the static one, and whole runs of small scenes
(a slider, a slider on a hinge, a hinge on a hinge, an undriven joint on a driven one,
a joint listed child first, a drum wound by a profile, sway off, damping on and off,
ropes going slack and taut, output times inside and at the ends of steps, a progress
callback, failures) step for step: the same formulas in the same order up to the
summation order of a few products, so the same steps, and every reported number to
1e-8 of its scale (rounding amplified over a few hundred steps).
"""

import dataclasses
import math

import numpy as np
import pytest
from test_mutation_kills_integrate import DROP2, DURATION, TROLLEY, _ref_at, _scene
from test_mutation_kills_integrate_loop import _bounce_reference
from test_mutation_kills_lean import PAIRS, _mech
from test_operation_speed import same_run

from cranefe.analysis.operation import fast, loop
from cranefe.analysis.operation import integrate as integ
from cranefe.analysis.operation.integrate import Stepper, simulate
from cranefe.analysis.operation.lean import Lean
from cranefe.analysis.operation.mechanism import Mechanism
from cranefe.analysis.operation.profiles import Motion
from cranefe.analysis.operation.results import Recorder
from cranefe.analysis.operation.scene import parse
from cranefe.errors import AnalysisError

G = 9.81
REL = 1e-8


def _same_run(a, b, rel=REL):
    """test_operation_speed's comparison of two runs, here with the output times to
    1e-14 s and the energy balance's error to 1e-6 of itself."""
    same_run(a, b, rel, times_atol=1e-14, energy_rel=1e-6)


# ----------------------------------------------------------------- profiles

def test_motion_table_by_hand():
    """Two motions stacked: a table from 0.2 m/s at rest before t = 1 (its speed
    before the first segment), then 1 s at 0.3 m/s^2 and 0.5 s with jerk -0.4; a
    trapezoid of 2 m (v 1, a 1) from t = 0."""
    m1 = Motion.build(1.0, [(1.0, 0.3, 0.0), (0.5, 0.3, -0.4)], "table", v0=0.2)
    m2 = Motion.build(0.0, [(1.0, 1.0, 0.0), (1.0, 0.0, 0.0), (1.0, -1.0, 0.0)],
                      "trapezoid")
    mt, mseg, moff = loop._motions_table([m1, m2])
    assert moff.tolist() == [0, 3, 7]
    np.testing.assert_allclose(mt, [1, 2, 2.5, 0, 1, 2, 3], atol=0)

    def hand1(t):
        if t < 1:
            return 0.2 * t, 0.2
        if t < 2:
            u = t - 1
            return 0.2 + 0.2 * u + 0.15 * u * u, 0.2 + 0.3 * u
        u = t - 2
        s1, v1 = 0.2 + 0.2 + 0.15, 0.5
        if t < 2.5:
            return s1 + v1 * u + 0.15 * u * u - 0.4 * u ** 3 / 6, v1 + 0.3 * u - 0.2 * u * u
        return hand1(2.5 - 1e-15)[0] + (t - 2.5) * (v1 + 0.15 - 0.05), v1 + 0.15 - 0.05

    def hand2(t):
        if t < 1:
            return 0.5 * t * t, t
        if t < 2:
            return 0.5 + (t - 1), 1.0
        if t < 3:
            u = t - 2
            return 1.5 + u - 0.5 * u * u, 1 - u
        return 2.0, 0.0
    for t in (0.0, 0.4, 1.0, 1.3, 2.0, 2.2, 2.5, 2.9, 3.0, 4.0):
        np.testing.assert_allclose(loop._motion(mt, mseg, 0, 3, t), hand1(t), atol=1e-12)
        np.testing.assert_allclose(loop._motion(mt, mseg, 3, 7, t), hand2(t), atol=1e-12)
        np.testing.assert_allclose(loop._motion(mt, mseg, 0, 3, t), m1(t)[:2], atol=1e-14)


# ----------------------------------------------------------------- parts

def _prepared(mech, monkeypatch):
    monkeypatch.setattr(fast, "available", lambda: True)
    spec = mech.spec                           # its drives (prepare maps them)
    st = Stepper(mech, spec, mech.model.length_scale)
    assert isinstance(st.ops, fast.FastLean)
    prep = loop.prepare(st, spec)
    assert prep is not None
    return st, prep


@pytest.mark.parametrize("case, eff", PAIRS)
def test_kinematics_powers_and_energy_equal_lean(case, eff, monkeypatch):
    """_kin against Lean._kin at times before, in and after the moves; _powers,
    _energy and _force_rate against Lean.powers, Lean.energy and Recorder._force_rate
    at states off the static one (all ropes taut, the first slack)."""
    st, (kd, fd, dmap) = _prepared(_mech(case, eff), monkeypatch)
    mech = st.m
    lean = Lean(mech)
    rec = Recorder(mech, parse(mech.model), lean)
    rng = np.random.default_rng(2)
    nr = len(mech.ropes)
    for t in (0.0, 0.5, 1.5, 2.2, 3.7):
        kt = loop._kin(t, kd)
        ref = lean.kin(t)
        for k, sc in ((0, 60.0), (1, 10.0), (2, 60.0), (3, 10.0), (4, 10.0), (5, 1.0),
                      (6, 1.0), (7, 60.0), (8, 10.0)):
            want = np.zeros_like(kt[k]) if ref[k] is None else ref[k]
            np.testing.assert_allclose(kt[k], want, rtol=0, atol=1e-12 * sc, err_msg=k)
        assert kt[9] == pytest.approx(ref[9], rel=1e-12, abs=1e-12)
        for c, (kind, i, d) in enumerate(dmap):
            want = d.motion(t)[:2] if kind == "joint" else d.motion(t)[:2]
            np.testing.assert_allclose(kt[10][i], want, atol=1e-12)
        for taut in (np.ones(nr, bool), np.r_[False, np.ones(nr - 1, bool)],
                     np.r_[np.ones(nr - 1, bool), False]):
            q = mech.q0 + rng.uniform(-0.2, 0.2, mech.n)
            v = rng.uniform(-1, 1, mech.n)
            ev = lean.evaluate(t, q, v, taut, ref)
            lean.powers(ev)
            Dm, Af, extra, EA, beta, Fg, D, falls, span_rope, damped = fd[:10]
            K0 = np.zeros((0, 0))
            out = fast._forces(q, v, Dm, kt[2], kt[3], Af, extra, kt[7], EA, kt[8], taut,
                               beta, Fg, D, falls, span_rope, damped, False, K0, K0)
            P = max(abs(ev.P_drive), abs(ev.P_diss), abs(ev.P_wound), 1.0)
            np.testing.assert_allclose(loop._powers(out, kt, taut, fd),
                                       [ev.P_drive, ev.P_diss, ev.P_wound], rtol=0,
                                       atol=1e-10 * P)
            E = lean.energy(ev, taut)
            np.testing.assert_allclose(loop._energy(out, kt, q, v, taut, fd, st.M), E,
                                       rtol=0, atol=1e-10 * (max(map(abs, E)) + 1))
            F, r = loop._force_rate(out, EA, taut)
            F1, r1, _ = rec._force_rate(ev, taut)
            sc = np.abs(F1).max() + 1.0
            np.testing.assert_allclose(F, F1, rtol=0, atol=1e-10 * sc)
            np.testing.assert_allclose(r, r1, rtol=0, atol=1e-10 * (np.abs(r1).max() + 1))
            for k in range(nr):
                assert loop._stretch_k(out, k) == out[6][k]


def test_sign():
    assert [loop._sign(x) for x in (-2.0, -1e-300, 0.0, 1e-300, 3.0)] == [-1, -1, 0, 1, 1]


# ----------------------------------------------------------------- whole runs

def test_trolley_pendulum_against_scipy(looped):
    """The loop's run of the trolley pendulum against DOP853 (module docstring) and the
    numpy loop step for step."""
    model = _scene("trolley", TROLLEY, f"  duration: {DURATION}\n  tolerance: 1.0e-8\n"
                   "  output_step: 0.05\n  drives:\n    trolley: {slider: travel, "
                   "profile: {type: trapezoid, distance: 2, v_max: 1, a_max: 1}}\n")
    res = simulate(model)
    assert len(looped) == 1
    assert res.status == 0 and res.times[-1] == pytest.approx(DURATION, abs=1e-12)
    ref = np.array([_ref_at(t) for t in res.times])
    P = res.mass_position[:, 0]
    err = max(np.abs(P[:, 0] - ref[:, 0]).max(), np.abs(P[:, 2] - ref[:, 1]).max())
    assert err < 6e-5, err
    M, EA = 1000.0, 1.0e6
    L0 = 10.0 * math.exp(-M * G / EA)
    xs = np.array([_ref_at_trolley(t) for t in res.times])
    L = np.hypot(ref[:, 0] - xs, ref[:, 1] - 10.0)
    S = EA * np.log(L / L0)
    assert np.abs(res.rope_force[:, 0] - S).max() < 6e-5 * M * G
    assert res.energy_error < 5e-5, res.energy_error
    assert res.newton_iterations == 2 * (res.steps + res.rejected)
    # the drive's position and speed at the output times: the trapezoid
    np.testing.assert_allclose(res.drive_position[:, 0], xs, atol=1e-12)
    _same_run(simulate(model, fast=False), res)


def _ref_at_trolley(t):
    from test_mutation_kills_mechanism import trolley_xs
    return trolley_xs(t)[0]


RUNS = {
    # (case of test_mutation_kills_lean.CASES, effects, duration, tolerance, output step)
    "trolley": ("trolley", "{damping: exact}", 3.5, 1e-7, 0.1),
    "trolley child first, sway off": ("trolley child first",
                                      "{sway: false, damping: exact}", 3.5, 1e-7, 0.25),
    "slewing trolley": ("slewing trolley", "{damping: exact}", 2.5, 1e-6, 0.1),
    "slewing trolley, sway off": ("slewing trolley", "{sway: false, damping: exact}", 2.5,
                                  1e-6, 0.3),
    "slewing, trolley held": ("slewing, trolley held", "{damping: none}", 2.5, 1e-6, 0.1),
    "trolley on a held jib": ("trolley on a held jib", "{}", 2.5, 1e-6, 0.5),
    # the slewing starts at 0.2 rad/s at once: the load is jerked and snatches its rope
    # (14 slack/taut events); each snatch amplifies rounding: the numpy loop itself
    # started 2e-16 off the static state moves by 1e-8 of the peak force (measured
    # 1.9e-3 N of 2.2e5 N, the events by 2e-10 s), as far as the two loops part: 1e-7
    "luffing on slewing": ("luffing on slewing", "{}", 2.5, 1e-6, 0.1),
    "winch": ("winch", "{damping: exact}", 3.0, 1e-7, 0.1),
    "winch, no damping": ("winch", "{damping: none}", 3.0, 1e-7, 0.5),
    "winch on a trolley": ("winch on a trolley", "{damping: exact}", 3.0, 1e-7, 0.1),
    "winch and sling, sway off": ("winch and sling", "{sway: false, damping: exact}", 3.0,
                                  1e-7, 0.1),
    "v sling": ("v sling", "{damping: exact}", 3.5, 1e-7, 0.1),
    "tag line, sway off": ("tag line", "{sway: false, damping: exact}", 3.5, 1e-7, 0.1),
}


def _cut(model, duration, tol, out):
    a = dict(model.analysis, duration=duration, tolerance=tol, output_step=out)
    return dataclasses.replace(model, analysis=a)


@pytest.mark.parametrize("name", list(RUNS))
def test_runs_equal_the_numpy_loop(name, looped):
    case, eff, T, tol, out = RUNS[name]
    model = _cut(_mech(case, eff).model, T, tol, out)
    a = simulate(model, fast=False)
    b = simulate(model)
    assert len(looped) == 1 and a.steps > 20
    _same_run(a, b, 1e-7 if name == "luffing on slewing" else REL)


def test_two_loads_thrown_up_against_scipy(looped):
    """Slack and taut events located in the step (module docstring); the numpy loop's
    run step for step."""
    model = _scene("bounce", DROP2, "  duration: 0.3\n  tolerance: 1.0e-8\n"
                   "  output_step: 0.01\n", "{sway: false}")
    mech = Mechanism(model, parse(model))
    L0 = mech.L0_ref
    init = {"q": mech.q0.copy(), "v": np.array([2.0, 1.0])}
    res = simulate(model, initial=init)
    assert len(looped) == 1
    assert [w for _, w in res.events] == ["rope r1 slack", "rope r2 slack", "rope r2 taut",
                                          "rope r2 slack"], res.events
    ra, rb = _bounce_reference(float(L0[0]), float(L0[1]))
    want = [ra[0], rb[0], rb[1], rb[2]]
    got = [t for t, _ in res.events]
    np.testing.assert_allclose(got[:3], want[:3], rtol=0, atol=5e-8)
    assert abs(got[3] - want[3]) < 4e-6, got[3] - want[3]
    _same_run(simulate(model, initial=init, fast=False), res)


def test_snatch_with_sway_and_damping(looped):
    """Both loads thrown up and sideways (sway on, dashpots): ropes slack and taut
    while swinging, with a rejection or two; the numpy loop step for step."""
    text = DROP2.replace("r1: {EA: 1.0e6,", "r1: {EA: 1.0e6, psi: 0.2,")
    model = _scene("snatch", text, "  duration: 0.6\n  tolerance: 1.0e-7\n"
                   "  output_step: 0.02\n", "{damping: exact}")
    mech = Mechanism(model, parse(model))
    v = np.zeros(mech.n)
    v[0], v[2], v[3], v[5] = 0.5, 2.0, -0.3, 1.0
    init = {"q": mech.q0.copy(), "v": v}
    b = simulate(model, initial=init)
    a = simulate(model, initial=init, fast=False)
    assert len(looped) == 1 and len(a.events) >= 4
    _same_run(a, b)


def test_progress_runs_in_chunks_with_the_same_steps(looped):
    model = _cut(_mech("slewing trolley", "{}").model, 1.0, 1e-6, 0.1)
    seen = []
    a = simulate(model)
    b = simulate(model, progress=lambda t, T: seen.append((t, T)))
    _same_run(a, b, 0.0)
    assert len(looped) == 2
    assert 100 <= len(seen) <= 200 and seen[-1] == (pytest.approx(1.0), 1.0)
    ts = [x[0] for x in seen]
    assert all(np.diff(ts) >= 0) and ts[0] >= 1.0 / 200


def _fails(model, monkeypatch, **init):
    out = []
    for f in (False, None):
        with pytest.raises(AnalysisError) as exc:
            simulate(model, fast=f, **init)
        out.append((str(exc.value), exc.value.result))
    (ma, a), (mb, b) = out
    assert ma == mb and "t = " in ma and a.status == b.status == 1
    _same_run(a, b)
    return ma


@pytest.mark.parametrize("failure", ["newton", "collapse", "too many steps",
                                     "two-blocking"])
def test_failures_as_the_numpy_loop(failure, looped, monkeypatch):
    """The same AnalysisError and the results up to it: Newton never converging
    (NEWTON_MAX = 1), the error never below the tolerance (tolerance 1e-300: the step
    collapses), more than MAX_STEPS = 40 steps, a span below 1 % of its reference
    length (two-blocking: reference lengths 100x the spans')."""
    model = _cut(_mech("trolley", "{damping: exact}").model, 2.0, 1e-7, 0.1)
    if failure == "newton":
        monkeypatch.setattr(integ, "NEWTON_MAX", 1)
        want = "Newton's method does not converge at t = 0 s"
    elif failure == "collapse":
        class Tight(Stepper):
            def __init__(self, *a, **k):
                super().__init__(*a, **k)
                self.tol = 1e-300
        monkeypatch.setattr(integ, "Stepper", Tight)
        want = "the step size collapsed at t = 0 s"
    elif failure == "too many steps":
        monkeypatch.setattr(integ, "MAX_STEPS", 40)
        want = "more than 40 steps at t = "
    else:
        class Short(Mechanism):
            def __init__(self, *a, **k):
                super().__init__(*a, **k)
                self.span_ref = self.span_ref * 100.0
        monkeypatch.setattr(integ, "Mechanism", Short)
        want = "(two-blocking)"
    msg = _fails(model, monkeypatch)
    assert want in msg, msg
    assert len(looped) == 1


def test_what_the_loop_does_not_cover(monkeypatch):
    """prepare: None without numba, for the numpy step, for the Generic evaluator (a
    torque drum: a coordinate)."""
    mech = _mech("trolley", "{}")
    spec = mech.spec
    monkeypatch.setattr(fast, "available", lambda: False)
    st = Stepper(mech, spec, mech.model.length_scale, fast=True)
    assert not st.fast and loop.prepare(st, spec) is None
    monkeypatch.setattr(fast, "available", lambda: True)
    st = Stepper(mech, spec, mech.model.length_scale, fast=False)
    assert loop.prepare(st, spec) is None
    st = Stepper(mech, spec, mech.model.length_scale, fast=True)
    assert loop.prepare(st, spec) is not None
    st.wq = np.ones(mech.n)
    assert loop.prepare(st, spec) is None
