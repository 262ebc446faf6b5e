"""Value tests of the drive profiles (cranefe/analysis/operation/profiles.py; issue 20,
mutation testing): every profile against its closed form written out by hand.

- trapezoid(D, v, a): accelerate for t_a = v/a (s = a tau^2/2), cruise for
  t_c = D/v - t_a, decelerate for t_a; triangular when D < v^2/a, peak sqrt(D a);
- S-curve (jerk j, acceleration a, speed v): when v >= a^2/j, t_j = a/j, t_a = v/a - t_j
  and the distance to reach v and stop again is v (t_a + 2 t_j) = v^2/a + v a/j; a
  distance D shorter than that lowers the peak speed to the root of v^2/a + v a/j = D,
  v = (a/2)(-a/j + sqrt(a^2/j^2 + 4 D/a)) (while v >= a^2/j), or, below a^2/j (no
  constant-acceleration phase), to 2 v sqrt(v/j) = D, v = (D sqrt(j) / 2)^(2/3);
  in the first jerk phase s = j tau^3/6, v = j tau^2/2, a = j tau;
- a speed table is linear in speed between its points: s = v0 tau + (dv/dt) tau^2/2;
- the sum of moves is the sum of their positions.

Tolerances: 1e-12 (a few floating operations on O(1-10) numbers) except the brentq root
(xtol 1e-14 v_max: 1e-12 relative) and the finite-difference checks of s' = v, v' = a
(central differences with h = 1e-5: truncation h^2/6 |s'''| ~ 1e-10, round-off
1e-16 / h ~ 1e-11; bound 1e-8).
"""

import math

import numpy as np
import pytest

from cranefe.analysis.operation.profiles import (Motion, combine, s_curve, speed_table,
                                                 trapezoid)

TOL = 1e-12


def _state(m, t):
    return np.array(m(t), float)


def _durations(m):
    """Segment durations, a cruise of round-off length (D/v - t_acc ~ 1e-14) left out."""
    d = np.diff(m.breakpoints)
    return d[d > 1e-12]


def _check_derivatives(m, times, h=1e-5):
    for t in times:
        s0, v0, a0 = m(t)
        sp, vp, _ = m(t + h)
        sm, vm, _ = m(t - h)
        assert abs((sp - sm) / (2 * h) - v0) < 1e-8, t
        assert abs((vp - vm) / (2 * h) - a0) < 1e-8, t


def test_trapezoid_by_hand():
    D, v, a, t0 = 3.0, 0.7, 0.4, 1.5
    m = trapezoid(D, v, a, start=t0)
    ta, tc = v / a, D / v - v / a
    assert m.kind == "trapezoid"
    assert np.allclose(m.breakpoints, [t0, t0 + ta, t0 + ta + tc, t0 + 2 * ta + tc],
                       rtol=0, atol=TOL)
    assert np.allclose(_state(m, 0.7), [0, 0, 0], atol=0)           # resting before
    tau = 0.9
    assert np.allclose(_state(m, t0 + tau), [a * tau**2 / 2, a * tau, a], atol=TOL)
    s1 = a * ta**2 / 2
    assert np.allclose(_state(m, t0 + ta + 1.2), [s1 + v * 1.2, v, 0.0], atol=TOL)
    tau = 0.5                                                        # decelerating
    assert np.allclose(_state(m, t0 + ta + tc + tau),
                       [s1 + v * tc + v * tau - a * tau**2 / 2, v - a * tau, -a],
                       atol=TOL)
    T = t0 + 2 * ta + tc
    assert np.allclose(_state(m, T + 5.0), [D, 0, 0], atol=TOL)    # rests at D after
    assert m.end == pytest.approx(T, rel=TOL)
    assert m.moves() == [(t0, pytest.approx(T, rel=TOL))]
    assert m.extremes(T + 1) == (pytest.approx(0.0, abs=TOL), pytest.approx(D, rel=TOL))
    assert m.extremes(t0 + ta) == (0.0, pytest.approx(s1, rel=TOL))   # stopped early
    _check_derivatives(m, [t0 + 0.3, t0 + ta + 0.5, t0 + ta + tc + 0.2])


def test_triangular_and_negative_trapezoid():
    D, v, a = 0.5, 2.0, 2.0                       # D < v^2 / a: peak sqrt(D a)
    m = trapezoid(-D, v, a)
    vp = math.sqrt(D * a)
    assert np.allclose(m.breakpoints, [0, vp / a, 2 * vp / a], atol=TOL)
    assert np.allclose(_state(m, vp / a), [-D / 2, -vp, a], atol=TOL)   # decelerating
    assert np.allclose(_state(m, 0.2), [-a * 0.04 / 2, -a * 0.2, -a], atol=TOL)
    assert vp == 1.0 and m(10.0)[1] == 0.0
    assert np.allclose(_state(m, 10.0), [-D, 0, 0], atol=TOL)
    lo, hi = m.extremes(10.0)
    assert lo == pytest.approx(-D, rel=TOL) and hi == 0.0


def test_zero_distance_is_a_rest():
    for m in (trapezoid(0.0, 1.0, 1.0, start=2.0), s_curve(0.0, 1.0, 1.0, 1.0, start=2.0)):
        assert list(m.breakpoints) == [2.0]
        assert _state(m, 3.0).tolist() == [0.0, 0.0, 0.0]
        assert m.end == 2.0 and m.moves() == []
    assert trapezoid(0.0, 1.0, 1.0).kind == "trapezoid"
    assert s_curve(0.0, 1.0, 1.0, 1.0).kind == "s_curve"


def test_s_curve_reaching_its_speed_by_hand():
    D, v, a, j, t0 = 10.0, 1.25, 0.5, 2.0, 0.25         # v >= a^2/j = 0.125
    m = s_curve(-D, v, a, j, start=t0)
    tj, ta = a / j, v / a - a / j
    dacc = v * (ta + 2 * tj)                            # to reach v and stop again
    tc = D / v - (ta + 2 * tj)
    assert m.kind == "s_curve"
    T = t0 + 2 * (2 * tj + ta) + tc
    assert np.allclose(np.diff(m.breakpoints),
                       [tj, ta, tj, tc, tj, ta, tj], rtol=0, atol=TOL)
    tau = 0.2                                            # first jerk phase (t_j 0.25)
    assert np.allclose(_state(m, t0 + tau), [-j * tau**3 / 6, -j * tau**2 / 2, -j * tau],
                       atol=TOL)
    # end of the first jerk phase: then constant acceleration a for ta
    s1, v1 = j * tj**3 / 6, j * tj**2 / 2
    tau = 0.7
    assert np.allclose(_state(m, t0 + tj + tau),
                       [-(s1 + v1 * tau + a * tau**2 / 2), -(v1 + a * tau), -a], atol=TOL)
    # cruising at v, half-way: by symmetry at D/2
    mid = t0 + 2 * tj + ta + tc / 2
    assert np.allclose(_state(m, mid), [-D / 2, -v, 0.0], atol=1e-11)
    assert np.allclose(_state(m, T), [-D, 0, 0], atol=1e-11)
    assert np.allclose(_state(m, T + 3), [-D, 0, 0], atol=1e-11)
    # second half mirrors the first: s(T - tau) = -D + j tau^3/6 in the last jerk phase
    tau = 0.2
    assert np.allclose(_state(m, T - tau), [-D + j * tau**3 / 6, -j * tau**2 / 2, j * tau],
                       atol=1e-11)
    assert dacc < D
    _check_derivatives(m, [t0 + 0.1, t0 + tj + 0.5, mid, T - 0.3, T - tj - 0.2])


def test_s_curve_with_a_lowered_peak_speed():
    a, j, v = 0.5, 1.5, 2.0
    # with a constant-acceleration phase: v^2/a + v a/j = D
    D = 1.5
    vp = (a / 2) * (-a / j + math.sqrt(a * a / (j * j) + 4 * D / a))
    assert vp >= a * a / j
    m = s_curve(D, v, a, j)
    tj, ta = a / j, vp / a - a / j
    assert np.allclose(_durations(m), [tj, ta, tj, tj, ta, tj], rtol=0, atol=1e-11)
    assert m(2 * tj + ta)[1] == pytest.approx(vp, rel=1e-12)
    assert m(10.0)[0] == pytest.approx(D, rel=1e-12)
    # without one: 2 v sqrt(v/j) = D, acceleration peak sqrt(v j) below a
    D = 0.05
    vp = (D * math.sqrt(j) / 2) ** (2 / 3)
    assert vp < a * a / j
    m = s_curve(D, v, a, j)
    tj = math.sqrt(vp / j)
    assert np.allclose(_durations(m), [tj, tj, tj, tj], rtol=0, atol=1e-11)
    assert m(tj)[2] == pytest.approx(tj * j, rel=1e-11)
    assert m(2 * tj)[1] == pytest.approx(vp, rel=1e-11)
    assert m(2 * tj)[0] == pytest.approx(D / 2, rel=1e-11)
    assert m(5.0)[0] == pytest.approx(D, rel=1e-11)


def test_speed_table_by_hand():
    m = speed_table([0.5, 2.0, 3.0], [1.0, 3.0, 3.0])
    assert m.kind == "table"
    assert np.allclose(_state(m, 0.2), [0.2, 1.0, 0.0], atol=TOL)     # first speed holds
    acc = (3.0 - 1.0) / 1.5
    tau = 0.6
    assert np.allclose(_state(m, 0.5 + tau), [0.5 + tau + acc * tau**2 / 2,
                                              1.0 + acc * tau, acc], atol=TOL)
    s2 = 0.5 + 1.5 + acc * 1.5**2 / 2
    assert np.allclose(_state(m, 2.5), [s2 + 1.5, 3.0, 0.0], atol=TOL)
    assert np.allclose(_state(m, 7.0), [s2 + 3.0 + 3.0 * 4.0, 3.0, 0.0], atol=TOL)
    assert m.end == math.inf                           # still moving after the table
    assert m.moves() == [(0.0, math.inf)]
    _check_derivatives(m, [0.3, 1.1, 2.4, 4.0])


def test_speed_table_through_zero_and_its_extremes():
    """v = 1 - t on [0, 2], then -1: s = t - t^2/2 peaks at t = 1 (s = 1/2)."""
    m = speed_table([0.0, 2.0], [1.0, -1.0])
    lo, hi = m.extremes(3.0)
    assert hi == pytest.approx(0.5, rel=TOL)
    assert lo == pytest.approx(-1.0, rel=TOL)           # s(3) = 0 - 1
    assert m.extremes(0.5) == (0.0, pytest.approx(0.5 - 0.125, rel=TOL))
    m = speed_table([1.0, 2.0, 4.0], [0.0, 2.0, 0.0])   # rests, moves, rests
    assert m.moves() == [(1.0, 4.0)]
    assert m.end == 4.0


def test_extremes_inside_a_jerk_phase():
    """An S-curve (D = 2, v = a = j = 1: one jerk phase up, one down, no cruise) on top of
    a constant speed -0.3: the speed j tau^2/2 - 0.3 vanishes at tau = sqrt(0.6), where
    s = 0.6^(3/2)/6 - 0.3 sqrt(0.6) = -0.2 sqrt(0.6) is the lowest point."""
    sc = s_curve(2.0, 1.0, 1.0, 1.0)
    assert np.allclose(np.diff(sc.breakpoints), [1.0, 1.0, 1.0, 1.0], atol=TOL)
    m = combine([sc, speed_table([0.0, 10.0], [-0.3, -0.3])])
    assert m.kind == "combined"
    lo, hi = m.extremes(4.0)
    assert lo == pytest.approx(-0.2 * math.sqrt(0.6), rel=1e-12)
    # and, mirrored, the highest where the speed falls back through 0.3 in the last jerk
    # phase, sqrt(0.6) before the end: s = 2 - 0.6^(3/2)/6 - 0.3 (4 - sqrt(0.6))
    assert hi == pytest.approx(0.8 + 0.2 * math.sqrt(0.6), rel=1e-12)
    lo, hi = m.extremes(10.0)
    assert lo == pytest.approx(2.0 - 3.0, rel=1e-12)    # s(10): the constant speed goes on
    assert hi == pytest.approx(0.8 + 0.2 * math.sqrt(0.6), rel=1e-12)


def test_combined_moves_add_their_positions():
    up = trapezoid(1.0, 0.5, 0.5)
    down = trapezoid(-1.0, 0.5, 0.5, start=6.0)
    m = combine([up, down])
    for t in (0.3, 1.0, 2.2, 3.5, 6.4, 7.5, 8.8, 12.0):
        assert np.allclose(_state(m, t), _state(up, t) + _state(down, t), atol=TOL)
    assert m.moves() == [(0.0, 3.0), (6.0, 9.0)]
    assert m.extremes(20.0) == (pytest.approx(0.0, abs=TOL), pytest.approx(1.0, rel=TOL))
    sc = s_curve(2.0, 0.8, 0.6, 1.1, start=0.4)
    m = combine([sc, up])
    for t in (0.2, 0.5, 1.3, 2.9, 4.4, 6.0):
        assert np.allclose(_state(m, t), _state(sc, t) + _state(up, t), atol=1e-12)
    assert combine([up]) is up


def test_moves_with_a_speed_before_their_first_time_cannot_be_combined():
    with pytest.raises(ValueError, match=r"^moves with a speed before their first time "
                                         r"cannot be combined$"):
        combine([speed_table([1.0, 2.0], [0.5, 0.0]), trapezoid(1.0, 1.0, 1.0, start=3.0)])
    # a table starting at t = 0 has no time before it: it combines
    m = combine([speed_table([0.0, 2.0], [0.5, 0.0]), trapezoid(1.0, 1.0, 1.0, start=3.0)])
    assert m(10.0)[0] == pytest.approx(0.5 + 1.0, rel=TOL)


def test_build_with_an_initial_speed():
    m = Motion.build(2.0, [(1.0, 0.5, 0.0)], "table", v0=0.4)
    assert np.allclose(_state(m, 1.0), [0.4, 0.4, 0.0], atol=TOL)
    assert np.allclose(_state(m, 2.5), [0.8 + 0.2 + 0.5 * 0.125, 0.65, 0.5], atol=TOL)
    assert np.allclose(_state(m, 4.0), [0.8 + 0.4 + 0.25 + 0.9 * 1.0, 0.9, 0.0], atol=TOL)


def test_s_curve_with_a_short_cruise_and_its_moves():
    """D = 1.7 with v = 1, a = 1, j = 2: t_j = 0.5, t_a = 0.5, distance to reach v and
    stop v (t_a + 2 t_j) = 1.5, so a cruise of 0.2 s at v (shorter than a second)."""
    m = s_curve(1.7, 1.0, 1.0, 2.0, start=0.5)
    assert np.allclose(np.diff(m.breakpoints), [0.5, 0.5, 0.5, 0.2, 0.5, 0.5, 0.5],
                       atol=1e-12)
    assert np.allclose(_state(m, 0.5 + 1.6), [0.85, 1.0, 0.0], atol=1e-12)  # mid-cruise
    assert m(20.0)[0] == pytest.approx(1.7, rel=1e-12)
    assert m.moves() == [(0.5, pytest.approx(0.5 + 3.2, rel=1e-12))]
    # a jerk below the speed scale still counts as moving (first segment: v = a = 0)
    m = s_curve(3.0, 1.0, 0.3, 0.5, start=0.25)
    assert m.moves() == [(0.25, pytest.approx(m.end, rel=1e-15))]
    # the distance 3 is short of v (v/a + a/j) = 3.93 for v = 1: the peak speed is the
    # root of v^2/a + v a/j = 3, above a^2/j = 0.18, so the acceleration still reaches
    # a_max = 0.3 (t_j = a/j = 0.6, t_a = v/a - t_j), never more
    vp = 0.15 * (-0.6 + np.sqrt(0.36 + 4 * 3.0 / 0.3))
    assert np.abs(m.a).max() == pytest.approx(0.3, rel=1e-15)
    assert np.allclose(np.diff(m.breakpoints)[:2], [0.6, vp / 0.3 - 0.6], rtol=1e-11)
    assert m(50.0)[0] == pytest.approx(3.0, rel=1e-12)
    assert m.moves()[0][1] > 0.25


def test_moves_of_a_table_ending_in_a_ramp_from_rest():
    """Resting until t = 1, then v = 2 (t - 1) until 2, then v = 2 for ever: the move
    starts at 1 (the ramp), not at 2."""
    m = speed_table([1.0, 2.0], [0.0, 2.0])
    assert m.moves() == [(1.0, math.inf)]
    assert m(3.0)[0] == pytest.approx(1.0 + 2.0, rel=TOL)


def test_extremes_at_breakpoints_and_roots_of_ramps():
    # there and back within the first second: the top is the plateau between breakpoints
    m = combine([trapezoid(0.1, 1.0, 10.0), trapezoid(-0.1, 1.0, 10.0, start=0.5)])
    assert m.breakpoints[2] == pytest.approx(0.2, rel=1e-12)
    lo, hi = m.extremes(1.0)
    assert hi == pytest.approx(0.1, rel=1e-12) and lo == pytest.approx(0.0, abs=1e-15)
    # v = 1 - t/2 on [0, 4]: top at t = 2 (s = 2 - 1 = 1); then v = -1: s(5) = -1
    m = speed_table([0.0, 4.0], [1.0, -1.0])
    lo, hi = m.extremes(5.0)
    assert hi == pytest.approx(1.0, rel=TOL) and lo == pytest.approx(-1.0, rel=TOL)
    # v = t - 1 on [0, 2] (acceleration exactly 1): bottom at t = 1, s = -1/2
    m = speed_table([0.0, 2.0], [-1.0, 1.0])
    lo, hi = m.extremes(2.5)
    assert lo == pytest.approx(-0.5, rel=TOL) and hi == pytest.approx(0.5, rel=TOL)


def test_later_moves_combine():
    """Both moves start after t = 0 from rest: nothing moves before the first time."""
    up, down = trapezoid(1.0, 0.5, 0.5, start=2.0), trapezoid(-1.0, 0.3, 0.5, start=6.0)
    m = combine([up, down])
    assert m.breakpoints[0] == 2.0
    assert np.allclose(_state(m, 1.0), [0.0, 0.0, 0.0], atol=0)
    for t in (2.5, 4.4, 6.6, 9.5):
        assert np.allclose(_state(m, t), _state(up, t) + _state(down, t), atol=TOL)
    # a table moving before its first time combines with a move from t = 0 (the sum then
    # starts at 0, where each part's state is defined)
    early = speed_table([0.0, 2.0], [0.0, 1.0])
    late = speed_table([1.0, 2.0], [0.5, 0.0])
    m = combine([early, late])
    for t in (0.5, 1.5, 3.0):
        assert np.allclose(_state(m, t), _state(early, t) + _state(late, t), atol=TOL)
