"""Configurations of cranefe/analysis/operation/loop.py (the compiled integration loop)
that tests/test_mutation_kills_lean_loop.py's scenes do not build (issue 20, mutation
testing: survivors of the loop's run that change a result there). Each scene runs
through loop.run (numba or not: `fast.available` answers True as in the lean loop's
tests) and is checked against values derived by hand and against the numpy loop
(`simulate(fast=False)`, the reference, mutation-tested against hand values: docs/
mutation.md) with test_operation_speed's comparison, every reported number to 1e-8 of
its scale:

- two ropes pulled taut in one step: both loads fall freely (exact for the trapezoidal
  rule) onto their ropes and both crossings fall in the same step; the earlier one
  (the shortest located step) is taken first: events at sqrt(2 d / g);
- a trapezoid with kinks at 0.25, 0.5 and 0.75 s (before 1 s, where t (1 + 1e-14) and
  t + 1e-14 part): the free-fall steps end at the kinks exactly (the step sequence of
  tests/test_mutation_kills_integrate_loop.py, derived there by hand);
- a tag line that stays stretched without sway: the trolley moves away from the tag's
  anchor, so the rope's force rate (the cubic Hermite samples between steps) carries
  the guided load's velocity (the span's kinematic velocity d_kin', which differs from
  the kinematic ends' velocity v_kin there);
- a trial step of the event search failing (Newton): the step is rejected and retried
  at a quarter, as the numpy loop does (the failure injected into the plain-Python
  loop: with numba the loop's functions are swapped for their Python originals);
- the energy balance's scale: a run whose largest term is the kinetic energy (a
  two loads thrown up on slack ropes: their kinetic energy at the start exceeds the
  potential change and the elastic energy, no drive works) and one whose largest is the potential
  change (a load hoisted and lowered): the energy error against the numpy loop's to 1 %
  (the error is a small difference of large terms; rounding moves it by < 1e-4 of
  itself, a wrong scale by the ratio of the terms).
"""

import dataclasses
import math

import numpy as np
import pytest
from test_mutation_kills_integrate import DROP2, ROPE, TROLLEY, _scene
from test_mutation_kills_integrate_loop import FREE, FREE_INITIAL, _failing
from test_mutation_kills_lean import CASES, TAG, TRAVEL, TWO_DRUMS, _drives, _scene_mech
from test_mutation_kills_lean_loop import _same_run

from cranefe.analysis.operation import loop
from cranefe.analysis.operation import integrate as integ
from cranefe.analysis.operation.integrate import simulate
from cranefe.analysis.operation.mechanism import Mechanism
from cranefe.analysis.operation.scene import parse
from cranefe.errors import AnalysisError

G = 9.81
REL = 1e-8
# the loop's functions that numba compiles (their Python originals as `py_func`)
JITTED = ("_motion", "_kin", "_trial", "_powers", "_energy", "_hermite_max1",
          "_hermite_bound", "_force_rate", "_accept", "_stretch_k", "_sign", "_locate",
          "_run")


def _drop2(duration, swap=False):
    """Two 100-kg loads at rest 0.2 m and 0.2005 m above their ropes' taut points (sway
    off: they fall vertically), max_step 0.5 s: the free fall is exact, the steps double
    from 1e-3 x duration and the step that crosses both taut points is the last one."""
    model = _scene(f"drop2-{duration}", DROP2, f"  duration: {duration}\n"
                   "  tolerance: 1.0e-8\n  max_step: 0.5\n", "{sway: false}")
    L0 = Mechanism(model, parse(model)).L0_ref
    d = [0.2005, 0.2] if swap else [0.2, 0.2005]
    init = {"q": np.array([10.0 - L0[0] + d[0], 10.0 - L0[1] + d[1]]), "v": np.zeros(2)}
    return model, init


def _taut_at_free_fall_times(res, swap=False):
    """The events: r1 then r2 taut (r2 then r1: swap) where d = g t^2 / 2 (d = 0.2,
    0.2005 m), to 1e-9 s (the Illinois search's stop, 1e-13 of the stretch)."""
    ev = [(t, w) for t, w in res.events if w.endswith("taut")]
    want = ["rope r2 taut", "rope r1 taut"] if swap else ["rope r1 taut", "rope r2 taut"]
    assert [w for _, w in ev] == want, res.events
    np.testing.assert_allclose([t for t, _ in ev],
                               [math.sqrt(2 * 0.2 / G), math.sqrt(2 * 0.2005 / G)],
                               rtol=0, atol=1e-9)


@pytest.mark.parametrize("first", ["r1", "r2"])
def test_two_ropes_pulled_taut_in_one_step(first, looped):
    """Both crossings in the last step (0.103 to 0.22 s): the event search locates each
    rope's and takes the earlier (the rope 0.2 m above its taut point, 0.2019 s), then
    the other's from there (0.2022 s); the earlier rope listed first or second."""
    model, init = _drop2(0.22, swap=first == "r2")
    res = simulate(model, initial=init)
    assert len(looped) == 1
    _taut_at_free_fall_times(res, swap=first == "r2")
    _same_run(simulate(model, initial=init, fast=False), res)


def test_kinks_before_one_second_end_the_steps(looped):
    """The free fall below a trolley moved by a trapezoid with kinks at 0.25, 0.5 and
    0.75 s: 14 steps (1, 2, ... 64 ms, cut to each kink, max_step 0.2), 2 Newton
    iterations each (the predictor is the solution), no rejection; the load's height
    exact; the trolley's position from the profile."""
    model = _scene("free", TROLLEY, FREE)
    res = simulate(model, initial=FREE_INITIAL)
    assert len(looped) == 1
    assert (res.steps, res.rejected, res.newton_iterations) == (14, 0, 28)
    assert [e for _, e in res.events] == ["drive trolley starts", "drive trolley stops"]
    z = res.mass_position[:, 0, 2]
    np.testing.assert_allclose(z, 5.0 + G / 2 * res.times - G / 2 * res.times ** 2,
                               rtol=0, atol=1e-12)
    assert res.status == 0 and res.times[-1] == 1.0
    _same_run(simulate(model, initial=FREE_INITIAL, fast=False), res)


# the tag line's anchor on the other side (x = -6): the trolley's 2 m travel (+x)
# stretches it from 6 to 8 m; EA 1e4 N; no damping (with a dashpot, a rope nearly
# perpendicular to its guided load's free direction has a near-zero frequency w, and
# b = psi c / (2 pi w) explodes: left to the damping model, see the mutation notes)
TAG_AWAY = TAG.replace("B: [6, 0, 0]", "B: [-6, 0, 0]").replace(
    "tag: {EA: 1.0e5,", "tag: {EA: 1.0e4,")


def _tag_away(damping, looped):
    """TAG_AWAY's 2 m trolley move without sway, compiled: (model, result, the load's
    positions, the tag's length from its anchor at x = -6 m)."""
    mech = _scene_mech(TAG_AWAY, _drives(TRAVEL), f"{{sway: false, damping: {damping}}}")
    model = _cut(mech.model, 3.5, 1e-7, 0.1)
    res = simulate(model)
    assert len(looped) == 1
    H = res.mass_position[:, 0]
    return model, res, H, np.hypot(H[:, 0] + 6.0, H[:, 2])


def test_tag_line_stretched_without_sway(looped):
    """The tag line taut through the move while the guided load follows the trolley:
    its force at the output times (cubic Hermite between steps, from the forces and
    their rates EA/L L' at the steps' ends, L' = the trolley's speed along the tag)
    against EA ln(L / 6 m) of the reported positions, to 0.05 N (the interpolation's
    error, h^4 |S''''| / 384 with h <= 70 ms; a rate without the guided load's velocity
    is off by ~EA/L x 1 m/s x h / 8 = 15 N); the numpy loop step for step."""
    assert TAG_AWAY != TAG
    model, res, H, L = _tag_away("none", looped)
    np.testing.assert_allclose(H[:, 0], res.drive_position[:, 0], rtol=0, atol=1e-12)
    tag = res.rope_force[:, 1]
    np.testing.assert_allclose(tag, 1e4 * np.log(L / 6.0), rtol=0, atol=0.05)
    assert tag[-1] == pytest.approx(1e4 * math.log(8 / 6), rel=1e-6)
    # the tag starts at its unstretched length (no force): taut at once, never slack
    ev = [(t, w) for t, w in res.events if w.startswith("rope")]
    assert [w for _, w in ev] == ["rope tag taut"] and ev[0][0] < 1e-6, ev
    # the numpy loop step for step, but the hoist's peak time (its force stays m g to
    # 1e-9 of itself without sway: the time of its maximum is rounding)
    _same_but_peak_times(simulate(model, fast=False), res, [1])


def test_a_damped_tag_line_that_no_coordinate_stretches(looped):
    """The same move with the ropes damped (hoist psi 0.3, tag psi 0.2): the tag stays
    level, so the guided load's height hardly stretches it (its row dL/dz = z / L ~ 1e-15)
    while the trolley does, at L' = (x + 6) / L x'. Its dashpot b = psi c / (2 pi w0
    sqrt(c / c0)) takes w0 from the one mode at rest (no mode strains the level tag: the
    lowest), the hoisting mode w0^2 = EA_h / (10 m) / 1000 kg, and c0 = EA / 6 m. The
    dashpot's force b L' (1.5 N at most) is the reported force less EA ln(L / 6 m), to
    0.03 N (the output's interpolation between steps: 0.010 N measured). The tag's own
    frequency, c z^2 / (L^2 m) -> 0, made it 4.4e9 N (found 2026-11-24)."""
    model, res, H, L = _tag_away("exact", looped)
    Ld = (H[:, 0] + 6.0) / L * res.drive_speed[:, 0]
    b = 0.2 * 1e4 / np.sqrt(6.0 * L) / (2 * np.pi * math.sqrt(1e7 / 10 / 1000))
    dash = res.rope_force[:, 1] - 1e4 * np.log(L / 6.0)
    assert (b * Ld).max() > 1.4
    np.testing.assert_allclose(dash, b * Ld, rtol=0, atol=0.03)
    assert res.rope_force_max[1] < 1e4 * math.log(8 / 6) + 2.0
    # both peaks are plateaus (the tag's after the stop): their times are rounding
    _same_but_peak_times(simulate(model, fast=False), res, [])


def test_a_damped_tag_line_going_taut_while_the_guided_load_moves(looped):
    """The tag's anchor on the other side (TAG): the trolley runs 1 m towards it (the tag
    slack), then 2 m back, so the tag goes taut as the load passes x = 0 at 1 m/s (t =
    3.5 s: 1 s of acceleration to 0.5 m, then 0.5 m at 1 m/s) with its dashpot at once
    b L' (L' = 1 m/s: the kinematic speed of the guided load, which the forces after the
    event must take). After the event the force is EA ln(L / 6 m) + b L' as in the move
    away, to 0.3 N (the outputs interpolate the dashpot's share as constant over a step,
    results.py: b L'' h / 4 ~ 0.4 N with steps of 0.1 s while L'' = 1 m/s^2; 0.17 N
    measured); the first output, 0.1 s after the event, also checks that the step after
    it starts from the tag's full rate EA/L L' although S = 0 there (without: 14 N low);
    the numpy loop step for step."""
    back = ("t: {slider: travel, profile: [{type: trapezoid, distance: 1, v_max: 1, "
            "a_max: 1}, {type: trapezoid, distance: -2, v_max: 1, a_max: 1, start: 2}]}")
    mech = _scene_mech(TAG, _drives(back), "{sway: false, damping: exact}")
    model = _cut(mech.model, 5.5, 1e-7, 0.1)
    res = simulate(model)
    assert len(looped) == 1
    taut = [t for t, w in res.events if w == "rope tag taut"]
    assert len(taut) == 1 and taut[0] == pytest.approx(3.5, abs=1e-6), res.events
    H = res.mass_position[:, 0]
    L = np.hypot(6.0 - H[:, 0], H[:, 2])
    on = res.times > 3.5 + 1e-6
    assert on.sum() >= 20 and (L[on] > 6.0).all()
    Ld = -(6.0 - H[on, 0]) / L[on] * res.drive_speed[on, 0]
    b = 0.2 * 1e5 / np.sqrt(6.0 * L[on]) / (2 * np.pi * math.sqrt(1e7 / 10 / 1000))
    dash = res.rope_force[on, 1] - 1e5 * np.log(L[on] / 6.0)
    assert (b * Ld).max() > 15.0
    np.testing.assert_allclose(dash, b * Ld, rtol=0, atol=0.3)
    _same_but_peak_times(simulate(model, fast=False), res, [])


def _same_but_peak_times(a, b, ropes):
    """test_operation_speed's comparison but the peak times only of `ropes` (the others'
    forces are constant to rounding, so the time of their maximum is rounding)."""
    assert (a.steps, a.rejected, a.newton_iterations) == \
        (b.steps, b.rejected, b.newton_iterations)
    assert [w for _, w in a.events] == [w for _, w in b.events]
    np.testing.assert_allclose([t for t, _ in b.events], [t for t, _ in a.events],
                               rtol=0, atol=1e-12)
    np.testing.assert_allclose(b.times, a.times, rtol=0, atol=1e-14)
    for k in ("rope_force", "rope_force_max", "mass_position", "drive_position",
              "drive_speed"):
        x = getattr(a, k)
        np.testing.assert_allclose(getattr(b, k), x, rtol=0,
                                   atol=REL * np.abs(x).max(), err_msg=k)
    np.testing.assert_allclose(b.rope_force_max_time[ropes], a.rope_force_max_time[ropes],
                               rtol=0, atol=1e-8)
    E = max(abs(x) for x in a.energy.values())
    for k in a.energy:
        assert b.energy[k] == pytest.approx(a.energy[k], rel=0, abs=REL * E), k
    # the error to 1 % of itself or 1e-9 (rounding over the run: 1e-12 measured)
    assert b.energy_error == pytest.approx(a.energy_error, rel=1e-2, abs=1e-9)


def _cut(model, duration, tol, out):
    a = dict(model.analysis, duration=duration, tolerance=tol, output_step=out)
    return dataclasses.replace(model, analysis=a)


def _plain_loop(monkeypatch):
    """The loop's functions as plain Python (numba or not), so that their globals can
    be replaced."""
    for name in JITTED:
        f = getattr(loop, name)
        monkeypatch.setattr(loop, name, getattr(f, "py_func", f))


@pytest.mark.parametrize("kind, progress", [("newton", False), ("collapse", False),
                                            ("newton", True)])
def test_a_failure_after_five_steps(kind, progress, looped, monkeypatch):
    """The free fall of test_kinks_before_one_second_end_the_steps: every step from the
    6th trial on fails (Newton: status 1) or reports the error 1e3 (rejected, the step
    times max(0.2, 0.9 x 1e3^(-1/3)) = 0.2) until the step is below the smallest: the
    run stops at t = 0.031 s (steps of 1, 2, 4, 8, 16 ms) with the numpy loop's message
    and results (its Stepper.step failing from the 6th call on); with a progress
    callback too (the loop then runs in 200 chunks and stops at the failing one)."""
    _plain_loop(monkeypatch)
    trial = loop._trial
    calls = {"n": 0}

    def failing_trial(*args):
        out = trial(*args)
        calls["n"] += 1
        if calls["n"] >= 6:
            return (1,) + tuple(out[1:]) if kind == "newton" else \
                tuple(out[:4]) + (1e3,) + tuple(out[5:])
        return out
    monkeypatch.setattr(loop, "_trial", failing_trial)
    model = _scene("free", TROLLEY, FREE)
    out = []
    for f in (None, False):
        if f is False:
            monkeypatch.setattr(integ, "Stepper", _failing(
                range(6, 10 ** 6), None if kind == "newton" else 1e3))
        with pytest.raises(AnalysisError) as exc:
            simulate(model, initial=FREE_INITIAL, fast=f,
                     progress=(lambda t, T: None) if progress else None)
        out.append((str(exc.value), exc.value.result))
    (mb, b), (ma, a) = out
    assert len(looped) == 1 and ma == mb, (ma, mb)
    want = "Newton's method does not converge" if kind == "newton" else \
        "the step size collapsed"
    assert f"{want} at t = 0.031 s" in ma, ma
    assert b.status == 1 and b.steps == 5
    _same_run(a, b)


@pytest.mark.parametrize("j, early", [(1, False), (2, False), (1, True)])
def test_a_failed_trial_of_the_event_search(j, early, looped, monkeypatch):
    """The two loads of test_two_ropes_pulled_taut_in_one_step in 0.2022 s: the last
    step crosses both taut points; the event search's j-th trial (1: its full step, 2:
    its first Illinois point) fails (Newton): the step is rejected and retried at a
    quarter; the events stay at the free-fall times; one rejection more than the run
    without the failure (two with the 3rd step failing too: `early`). The numpy loop
    with the same trials failing (its Stepper.step: the same calls in the same order)
    step for step."""
    _plain_loop(monkeypatch)
    model, init = _drop2(0.2022)
    ref = simulate(model, initial=init)
    state = {"on": False, "in": 0, "n": 0}

    def fails():
        """Count a trial step; True for the ones to fail."""
        state["n"] += 1
        state["in"] += state["on"]
        return (early and state["n"] == 3) or (state["on"] and state["in"] == j)

    def searching(search):
        def locate(*args):
            state["on"] = True
            try:
                return search(*args)
            finally:
                state["on"] = False
        return locate
    trial = loop._trial

    def failing_trial(*args):
        out = trial(*args)
        return (1,) + tuple(out[1:]) if fails() else out

    class Failing(integ.Stepper):
        def step(self, *args, **kw):
            out = super().step(*args, **kw)
            return None if fails() else out

    monkeypatch.setattr(loop, "_trial", failing_trial)
    monkeypatch.setattr(loop, "_locate", searching(loop._locate))
    res = simulate(model, initial=init)
    assert len(looped) == 2 and state["in"] > j
    _taut_at_free_fall_times(ref)
    _taut_at_free_fall_times(res)
    assert res.rejected == ref.rejected + 1 + early
    state.update(on=False, n=0)
    state["in"] = 0
    monkeypatch.setattr(integ, "Stepper", Failing)
    monkeypatch.setattr(integ, "_locate", searching(integ._locate))
    a = simulate(model, initial=init, fast=False)
    assert state["in"] > j
    _same_run(a, res)


@pytest.mark.parametrize("name", ["kinetic", "potential"])
def test_energy_error_scale(name, looped):
    """The energy error |dE - W + D + W_wound| / max(|W|, |D|, max T, max |V - V0|,
    max U) against the numpy loop's to 1 %. kinetic: two 100-kg loads thrown up on
    their slack ropes at 2 and 1 m/s (no drive: W = 0; max T = 250 J at the start, max
    |V - V0| = 200 J at 0.2 s, the second rope catching its load at 1 m/s); potential:
    the winch hoists its 1000-kg load for 2 s and lowers it (max |V - V0| = 609 J at
    2 s, |W| = 480 J at the end, max U = 202 J, max T = 17 J)."""
    if name == "kinetic":
        model = _scene("bounce", DROP2, "  duration: 0.3\n  tolerance: 1.0e-6\n"
                       "  output_step: 0.05\n", "{sway: false}")
        mech = Mechanism(model, parse(model))
        init = {"q": mech.q0.copy(), "v": np.array([2.0, 1.0])}
    else:
        mech = _scene_mech(*CASES["winch"]("{damping: none}"))
        model = _cut(mech.model, 3.0, 1e-6, 0.5)
        init = None
    res = simulate(model, initial=init)
    a = simulate(model, initial=init, fast=False)
    assert len(looped) == 1
    assert res.energy_error == pytest.approx(a.energy_error, rel=1e-2, abs=0)
    _same_run(a, res, 1e-6)


# a trolley carrying a 1000-kg load and a 500-kg one slung 5 m below it
TROLLEY_SLING = CASES["trolley"]("{}")[0].replace(
    "  H: [0, 0, 0]\n", "  H: [0, 0, 0]\n  B: [0, 0, -5]\n").replace(
    "masses: {H: 1000}", "masses: {H: 1000, B: 500}") + \
    "  sling: {EA: 1.0e7, path: [H, B]}\n"


def test_two_guided_loads_kinetic_energy(looped):
    """Sway off, both loads guided by the trolley (the trapezoid's 1 s at 1 m/s^2, then
    1 m/s): at 1.5 s their kinetic energy is (1000 + 500) x 1^2 / 2 = 750 J (no vertical
    motion: the rope forces stay the static ones, m g along the vertical), the drive's
    work the same 750 J (W = the guided loads' kinetic energy, nothing else moves); the
    numpy loop step for step."""
    assert "sling" in TROLLEY_SLING and "B: 500" in TROLLEY_SLING
    mech = _scene_mech(TROLLEY_SLING, _drives(TRAVEL), "{sway: false, damping: none}")
    model = _cut(mech.model, 1.5, 1e-7, 0.5)
    res = simulate(model)
    assert len(looped) == 1
    e = res.energy
    assert e["kinetic_final"] == pytest.approx(750.0, rel=1e-9)
    assert e["work_drives"] == pytest.approx(750.0, rel=1e-9)
    _same_but_peak_times(simulate(model, fast=False), res, [])


# TWO_DRUMS with a third winch: three ropes wound by three profile drums
THREE_DRUMS = TWO_DRUMS.replace("  H: [0, 0, 30]\n", "  H: [0, 0, 30]\n  X: [9, 0, 40]\n"
                                "  Y: [7, 0, 40]\n  Z: [7, 0, 30]\n").replace(
    "ground: [W, V, S, U]", "ground: [W, V, S, U, X, Y]").replace(
    "masses: {H: 1000, K: 500}", "masses: {H: 1000, K: 500, Z: 200}").replace(
    "  d2: {node: V,", "  d3: {node: X, radius: 0.4, inertia: 5, rope_reserve: 100}\n  d2: {node: V,") + \
    "  r3: {EA: 1.0e6, psi: 0.2, path: [d3, Y, Z]}\n"


def test_three_profile_drums(looped):
    """Three winches, each winding its own rope by a profile (d1 at 0.4 rad/s, d2 at
    -0.5 rad/s, d3 at 0.25 rad/s, all from rest at once): each rope's unstretched
    length L0 = L0_ref - R theta / lambda_ref takes its own drum's angle (the sum over
    the drums of W theta, zero for the others); each drive's reported angle is its own
    profile's s(t); the loads follow their ropes (the numpy loop step for step)."""
    assert "r3:" in THREE_DRUMS and "Z: 200" in THREE_DRUMS and "d3:" in THREE_DRUMS
    mech = _scene_mech(THREE_DRUMS, _drives(
        "a: {drum: d1, profile: {type: table, speed: [[0, 0.4]]}}",
        "b: {drum: d2, profile: {type: table, speed: [[0, -0.5]]}}",
        "c: {drum: d3, profile: {type: table, speed: [[0, 0.25]]}}"), "{damping: exact}")
    model = _cut(mech.model, 1.5, 1e-7, 0.25)
    res = simulate(model)
    assert len(looped) == 1
    t = res.times
    np.testing.assert_allclose(res.drive_position, np.c_[0.4 * t, -0.5 * t, 0.25 * t],
                               rtol=0, atol=1e-12)
    # the loads rise (d1 winds R omega = 0.2 m/s of r1, d3 0.1 m/s of r3) and sink (d2
    # unwinds 0.15 m/s), to 0.03 m: the axial oscillation started by the speed's jump,
    # v / w with w = sqrt(EA / (L m)) = 13.5, 14 and 22 rad/s, is at most 0.015 m
    z = res.mass_position[:, :, 2]              # H, Z, K: the nodes' order
    np.testing.assert_allclose(z[-1] - z[0], [0.2 * 1.5, 0.1 * 1.5, -0.15 * 1.5],
                               rtol=0, atol=0.03)
    _same_run(simulate(model, fast=False), res)


def test_a_rope_below_one_newton(looped):
    """A 50-g load on a soft rope (EA 1 kN) below the trolley's trapezoid: its rope's
    force stays within 0.45-0.55 N (under 1 N), swinging; the force samples between
    steps are cubic Hermite in the force and its rate EA/L L' (where S > 0), as the
    numpy loop's (step for step)."""
    mech = _scene_mech(CASES["trolley"]("{}")[0].replace("H: 1000", "H: 0.05").replace(
        "EA: 1.0e7", "EA: 1.0e3"), _drives(TRAVEL),
        "{damping: none}")
    model = _cut(mech.model, 3.5, 1e-7, 0.1)
    res = simulate(model)
    assert len(looped) == 1
    F = res.rope_force[:, 0]
    assert 0.4 < F.min() and F.max() < 0.6, (F.min(), F.max())
    _same_run(simulate(model, fast=False), res)


def test_a_winch_paying_out_faster_than_free_fall(looped):
    """The winch pays out R omega = 0.5 x 4 = 2 m/s of rope at once (1 m/s of the hook's
    two falls), faster than the load falling from rest: its rope goes slack at once and
    taut again when the fall has caught up (g t^2 / 2 = 1 m/s x t, t ~ 0.2 s); the wound
    rope's power after each event with the new slack/taut state; the numpy loop step
    for step."""
    mech = _scene_mech(CASES["winch"]("{}")[0], _drives(
        "h: {drum: hoist, profile: {type: table, speed: [[0, -4]]}}"), "{damping: none}")
    model = _cut(mech.model, 0.6, 1e-7, 0.05)
    res = simulate(model)
    assert len(looped) == 1
    ev = [(t, w) for t, w in res.events if w.startswith("rope")]
    assert [w for _, w in ev][:2] == ["rope r slack", "rope r taut"], ev
    _same_run(simulate(model, fast=False), res)


def test_a_run_starting_in_motion_interpolates_its_first_step(looped):
    """A 200-kg load on its 5-m rope (EA 4e5 N, sway off) leaves its static place moving
    down at 0.5 m/s: the rope's force rises at once at the rate EA/L L' = 8e4 N/m x
    0.5 m/s. The first step (1e-3 of the 0.1-s run) holds one output time, 8e-5 s: its
    force is the cubic Hermite interpolant from the start's force m g and its full rate
    (loop.run's first rate; a zero rate puts it 0.13 N low). By hand S = EA ln(L / L0),
    L = 5 + 0.5 t (the load's acceleration is zero at the static place; its jerk moves L
    by c L' t^3 / (6 m) = 2e-9 m), L0 = 5 exp(-m g / EA): to 1e-4 N (the neglected
    terms, 1e-5 N); the numpy loop step for step."""
    m, EA = 200.0, 4.0e5
    model = _scene("moving", ROPE, "  duration: 0.1\n  output_step: 8.0e-5\n", "{sway: false}")
    init = {"q": np.array([5.0]), "v": np.array([-0.5])}
    res = simulate(model, initial=init)
    assert len(looped) == 1
    t = res.times[1]
    assert t == pytest.approx(8e-5, rel=1e-12)
    assert res.rope_force[0, 0] == pytest.approx(m * G, rel=1e-12)
    L0 = 5.0 * math.exp(-m * G / EA)
    assert res.rope_force[1, 0] == pytest.approx(EA * math.log((5.0 + 0.5 * t) / L0),
                                                 rel=0, abs=1e-4)
    _same_run(simulate(model, initial=init, fast=False), res)
