"""Kill tests for cranefe/analysis/shaping/motion.py (tools/mutation.py shaping_motion;
docs/testing.md, "Mutation testing"): the piecewise-constant acceleration (and jerk)
profiles, their shaping by an impulse train and the residual sway they leave, against
references written here independently of the module.

- Profiles by hand: the trapezoid 6 m at 2 m/s, 1 m/s^2 is t_a = 2 s, t_c = 1 s; its
  speed, position and acceleration at chosen times are read off the three phases. The
  S-curve with j = 2 m/s^3 is the trapezoid's acceleration averaged over t_j = 0.5 s.
- Shaping by hand: a two-impulse train (t_i, A_i) built here (not shapers.py), the jumps
  da_j A_i at t_j + t_i, coincident times added.
- Residual: the mode q'' + 2 zeta w q' + w^2 q = gain a(t) from rest, propagated exactly
  over each piece by the matrix exponential of the augmented state (q, q', a, j) (the
  input is polynomial of degree <= 1 on a piece: d/dt (a, j) = (j, 0)); the amplitude of
  the free vibration after the end, q = A e^(-zeta w tau) cos(w_d tau - phi), is
  A = sqrt(q^2 + ((q' + zeta w q) / w_d)^2). Undamped trapezoid: the closed form
  (4 a / (l w^2)) |sin(w t_a / 2) sin(w s / 2)| (s = t_a + t_c); ZV-shaped: that times
  |cos(pi w / (2 w0))| (Singer & Seering), 0 at the design frequency w0.
- Double pendulum: eigenvalues of K phi = w^2 M phi by scipy.linalg.eigh.
- Nonlinear pendulum: one solve_ivp over the whole move with the acceleration as a
  Python function (not piecewise), then the largest |theta| over one more period of
  free swing (not the energy formula), computed once (lru_cache).

Tolerances: hand values are sums of a few O(1) terms: 1e-12. The matrix exponential
(scipy expm, Pade 13) and the closed forms agree with the module's closed form to
~1e-15 relative: 1e-10. The nonlinear reference: rtol 1e-11 over the move, the maximum
sampled on a dense-output grid of 20001 points per period (error ~ (pi/20000)^2/2
relative = 1.2e-8): 1e-6 relative.
"""

from functools import lru_cache
from types import SimpleNamespace

import numpy as np
import pytest
import scipy.linalg as sl
from scipy.integrate import solve_ivp

from cranefe.analysis.shaping import motion as mo
from cranefe.errors import ModelError

TOL = 1e-12
G = 9.81


def trap():
    return mo.trapezoid(6.0, 2.0, 1.0)          # t_a = 2, t_c = 1, end 5


def zv(w0):
    """The undamped ZV train, built here: impulses 1/2, 1/2 half a period apart."""
    return SimpleNamespace(times=np.array([0.0, np.pi / w0]), amplitudes=np.array([0.5, 0.5]))


def ref_state(profile, w, zeta, gain, T):
    """(q, q') at T of q'' + 2 zeta w q' + w^2 q = gain a(t), from rest, propagated by
    the matrix exponential of the state (q, q', a, j) piece by piece."""
    A = np.zeros((4, 4))
    A[0, 1] = 1.0
    A[1, 0], A[1, 1], A[1, 2] = -w * w, -2 * zeta * w, gain
    A[2, 3] = 1.0
    x = np.zeros(4)
    t = 0.0
    for tj, dj in zip(profile.times, profile.jumps):
        x = sl.expm(A * (tj - t)) @ x
        t = tj
        x[2 + profile.order] += dj          # order 0: a jumps; order 1: j jumps
    x = sl.expm(A * (T - t)) @ x
    return x[0], x[1]


def ref_amplitude(profile, w, zeta, gain):
    q, dq = ref_state(profile, w, zeta, gain, profile.times[-1])
    wd = w * np.sqrt(1 - zeta**2)
    return np.hypot(q, (dq + zeta * w * q) / wd)


# ------------------------------------------------------------------ profiles by hand

def test_trapezoid_by_hand():
    p = trap()
    assert type(p) is mo.AccelSteps and p.order == 0
    assert np.allclose(p.times, [0, 2, 3, 5], rtol=0, atol=TOL)
    assert np.allclose(p.jumps, [1, -1, -1, 1], rtol=0, atol=TOL)
    assert p.end == 5.0
    t = np.array([0.0, 1.0, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0])
    assert np.allclose(p.acceleration(t), [1, 1, 0, 0, -1, -1, 0, 0], rtol=0, atol=TOL)
    assert np.allclose(p.speed(t), [0, 1, 2, 2, 2, 1, 0, 0], rtol=0, atol=TOL)
    assert np.allclose(p.position(t), [0, 0.5, 2, 3, 4, 5.5, 6, 6], rtol=0, atol=TOL)
    assert float(p.acceleration(1.0)) == 1.0          # a scalar time
    assert p.acceleration(t).shape == t.shape


def test_triangle_merges_the_coincident_jumps():
    """distance 1, v_max 2, a_max 1: v = sqrt(D a) = 1, t_a = 1, no coast: the two jumps
    at t = 1 are one of -2."""
    p = mo.trapezoid(1.0, 2.0, 1.0)
    assert np.allclose(p.times, [0, 1, 2], rtol=0, atol=TOL)
    assert np.allclose(p.jumps, [1, -2, 1], rtol=0, atol=TOL)
    assert float(p.position(2.0)) == pytest.approx(1.0, abs=TOL)
    # a coast of 1e-9 s (t_a = 1, v = 1): two jumps kept apart
    p = mo.trapezoid(1.0 + 1e-9, 1.0, 1.0)
    assert len(p.times) == 4


def test_merge_keeps_times_closer_than_its_tolerance_of_a_long_move_only():
    """_merge joins times within 1e-12 x max(|t_end|, 1): on a 1000 s move times 1e-10
    apart are one, on a 1 s move 1e-10 apart are two."""
    t = np.array([0.0, 500.0, 500.0 + 1e-10, 1000.0])
    p = mo._merge(t, np.array([1.0, -1.0, -1.0, 1.0]))
    assert len(p.times) == 3 and np.allclose(p.jumps, [1, -2, 1], rtol=0, atol=TOL)
    t = np.array([0.0, 0.5, 0.5 + 1e-10, 1.0])
    p = mo._merge(t, np.array([1.0, -1.0, -1.0, 1.0]))
    assert len(p.times) == 4
    # the scale is the LAST time (not the second, nor the one before the last) and at
    # least 1 s (not 2 s): the count of steps tells
    t = np.array([0.0, 0.001, 500.0, 500.0 + 1e-10, 1000.0])
    assert len(mo._merge(t, np.ones(5)).times) == 4
    t = np.array([0.0, 1e-10, 1.0, 1000.0])
    assert len(mo._merge(t, np.ones(4)).times) == 3
    t = np.array([0.0, 0.5, 0.5 + 1.5e-12, 1.0])
    assert len(mo._merge(t, np.ones(4)).times) == 4
    # unsorted input, the class kept
    p = mo._merge(np.array([2.0, 0.0, 1.0]), np.array([3.0, 1.0, 2.0]), mo.JerkSteps)
    assert type(p) is mo.JerkSteps
    assert np.allclose(p.times, [0, 1, 2]) and np.allclose(p.jumps, [1, 2, 3])


def test_table_by_hand():
    p = trap()
    tab = p.table()
    assert np.allclose(tab["times"], [0, 2, 3, 5], rtol=0, atol=TOL)
    assert np.allclose(tab["values"], [0, 2, 2, 0], rtol=0, atol=TOL)
    assert np.allclose(tab["positions"], [0, 2, 4, 6], rtol=0, atol=TOL)
    tab = p.table(per_piece=2)
    assert np.allclose(tab["times"], [0, 1, 2, 2.5, 3, 4, 5], rtol=0, atol=TOL)
    assert np.allclose(tab["values"], [0, 1, 2, 2, 2, 1, 0], rtol=0, atol=TOL)
    assert np.allclose(tab["positions"], [0, 0.5, 2, 3, 4, 5.5, 6], rtol=0, atol=TOL)
    assert all(isinstance(x, float) for x in tab["times"])
    # a profile that starts later: 0 is a corner too
    later = mo.AccelSteps(p.times + 1.0, p.jumps)
    assert np.allclose(later.table()["times"], [0, 1, 3, 4, 6], rtol=0, atol=TOL)


def test_s_curve_by_hand():
    """s_curve(6, 2, 1, 2): t_j = 0.5; the jerk +-2 at 0, 0.5, 2, 2.5, 3, 3.5, 5, 5.5.
    The acceleration is the trapezoid's averaged over [t - 0.5, t]."""
    p = mo.s_curve(6.0, 2.0, 1.0, 2.0)
    assert type(p) is mo.JerkSteps and p.order == 1
    assert np.allclose(p.times, [0, 0.5, 2, 2.5, 3, 3.5, 5, 5.5], rtol=0, atol=TOL)
    assert np.allclose(p.jumps, [2, -2, -2, 2, -2, 2, 2, -2], rtol=0, atol=TOL)
    t = np.array([0.25, 0.5, 1.0, 2.25, 2.5, 2.75, 5.75, 6.0])
    assert np.allclose(p.acceleration(t), [0.5, 1, 1, 0.5, 0, 0, 0, 0], rtol=0, atol=TOL)
    # speed: t^2 at first (j = 2), then 0.25 + (t - 0.5), ...; 2 at the cruise
    assert np.allclose(p.speed(t), [0.0625, 0.25, 0.75, 1.9375, 2, 2, 0, 0],
                       rtol=0, atol=TOL)
    # position: t^3/3 at first; the end at 6
    assert np.allclose(p.position([0.3, 0.5, 5.5, 7.0]),
                       [0.009, 1 / 24, 6, 6], rtol=0, atol=TOL)
    assert p.position(1.0) == pytest.approx(1 / 24 + 0.25 * 0.5 + 0.5 * 0.25, abs=TOL)
    # the table of an order-1 profile: the corners and the speed there
    tab = p.table()
    assert np.allclose(tab["times"], p.times, rtol=0, atol=TOL)
    assert np.allclose(tab["values"], [0, 0.25, 1.75, 2, 2, 1.75, 0.25, 0],
                       rtol=0, atol=TOL)


def test_shape_by_hand():
    """trapezoid [0, 2, 3, 5] x [1, -1, -1, 1] shaped by (t, A) = (0, 1/2), (1, 1/2):
    times 0 1 2 3 4 5 6, the two at 3 (3 + 0 and 2 + 1) added."""
    p = mo.shape(trap(), SimpleNamespace(times=np.array([0.0, 1.0]),
                                         amplitudes=np.array([0.5, 0.5])))
    assert type(p) is mo.AccelSteps
    assert np.allclose(p.times, [0, 1, 2, 3, 4, 5, 6], rtol=0, atol=TOL)
    assert np.allclose(p.jumps, [0.5, 0.5, -0.5, -1, -0.5, 0.5, 0.5], rtol=0, atol=TOL)
    assert float(p.position(6.0)) == pytest.approx(6.0, abs=TOL)
    assert float(np.max(p.speed(np.linspace(0, 6, 61)))) == pytest.approx(2.0, abs=TOL)
    # unequal amplitudes, an S-curve: the type is kept and the times add
    s = mo.shape(mo.s_curve(6.0, 2.0, 1.0, 2.0),
                 SimpleNamespace(times=np.array([0.0, 0.3]), amplitudes=np.array([0.25, 0.75])))
    assert type(s) is mo.JerkSteps
    assert np.allclose(s.times[:3], [0, 0.3, 0.5], rtol=0, atol=TOL)
    assert np.allclose(s.jumps[:3], [0.5, 1.5, -0.5], rtol=0, atol=TOL)


def test_bad_moves_are_refused():
    for args in [(0.0, 1.0, 1.0), (1.0, 0.0, 1.0), (1.0, 1.0, 0.0), (-1.0, 1.0, 1.0),
                 (1.0, -1.0, 1.0), (1.0, 1.0, -1.0)]:
        with pytest.raises(ModelError, match=r"^a trapezoidal move needs positive "
                           r"distance, v_max and a_max \(got "):
            mo.trapezoid(*args)
    for j in (0.0, -1.0):
        with pytest.raises(ModelError, match="jerk"):
            mo.s_curve(1.0, 1.0, 1.0, j)
    # a motion that does not end at constant speed
    with pytest.raises(ModelError, match=r"^the motion does not end at constant speed "
                       r"\(its acceleration is not zero after the last step\)$"):
        mo.residual_amplitude(mo.AccelSteps(np.array([0.0, 1.0]), np.array([1.0, -0.5])),
                              1.0)
    with pytest.raises(ModelError, match="constant speed"):
        mo.residual_amplitude(mo.JerkSteps(np.array([0.0, 1.0]), np.array([1.0, -0.5])),
                              1.0)
    # a small leftover acceleration on a long, strong move: 1e-6 of the jumps is refused
    with pytest.raises(ModelError, match="constant speed"):
        mo.residual_amplitude(mo.AccelSteps(np.array([0.0, 0.5]),
                                            np.array([1.0, -1.0 + 1e-6])), 1.0)




def test_end_check_threshold_scales_with_the_jumps_and_the_duration():
    """Refused when |a| after the end exceeds 1e-9 max|jump| max(T, 1)^(order + 1):
    a leftover of 1e-8 of the jumps passes on a 100 s move and 1e-6 does not; on a 1 s
    move 1.5e-9 is refused; a jerk profile of 100 s allows 1e-6."""
    def acc(end, left, cls=mo.AccelSteps):
        return cls(np.array([0.0, end]), np.array([1.0, -1.0 + left]))
    assert mo.residual_amplitude(acc(100.0, 1e-8), 1.0) > 0
    for p in (acc(100.0, 1e-6), acc(1.0, 1.5e-9), acc(0.5, 1.5e-9)):
        with pytest.raises(ModelError, match="constant speed"):
            mo.residual_amplitude(p, 1.0)
    # jerk steps [1, -2 + e, 1 - e] at (0, T/2, T): no jerk after the end, a leftover
    # acceleration e T / 2: 1e-6 on T = 100 s (threshold 1e-9 x 2 x 100^2), 5e-9 on 1 s
    # (threshold 2e-9)
    e = 2e-8
    p = mo.JerkSteps(np.array([0.0, 50.0, 100.0]), np.array([1.0, -2.0 + e, 1.0 - e]))
    assert mo.residual_amplitude(p, 1.0) > 0
    e = 1e-8
    p = mo.JerkSteps(np.array([0.0, 0.5, 1.0]), np.array([1.0, -2.0 + e, 1.0 - e]))
    with pytest.raises(ModelError, match="constant speed"):
        mo.residual_amplitude(p, 1.0)
    # the acceleration after a jerk profile is linear, a(t) = 3 - t here: zero 2 s
    # after the end, 1 one second after: refused
    with pytest.raises(ModelError, match="constant speed"):
        mo.residual_amplitude(mo.JerkSteps(np.array([0.0, 1.0]), np.array([2.0, -3.0])),
                              1.0)
    # no motion at all leaves no sway
    assert mo.residual_amplitude(mo.AccelSteps(np.array([0.0]), np.array([0.0])), 1.0) == 0


# ------------------------------------------------------------------ residual sway

@pytest.mark.parametrize("length", [4.0, 9.81 / 1.3**2])
def test_undamped_trapezoid_residual_closed_form(length):
    """(4 a / (l w^2)) |sin(w t_a / 2) sin(w s / 2)|, t_a = 2, s = 3 (gain 1/l)."""
    w = np.sqrt(G / length)
    want = 4 * 1.0 / (length * w * w) * abs(np.sin(w) * np.sin(1.5 * w))
    assert mo.residual_sway(trap(), length) == pytest.approx(want, rel=1e-10)
    assert mo.pendulum_omega(length) == pytest.approx(w, rel=1e-15)
    assert mo.pendulum_omega(length, g=1.62) == pytest.approx(np.sqrt(1.62 / length),
                                                              rel=1e-15)
    # on the moon: another w
    wm = np.sqrt(1.62 / length)
    want = 4 / (length * wm * wm) * abs(np.sin(wm) * np.sin(1.5 * wm))
    assert mo.residual_sway(trap(), length, g=1.62) == pytest.approx(want, rel=1e-10)


def test_zv_shaped_trapezoid_sensitivity_curve():
    """ZV for w0 = 1.1 rad/s: zero residual at w0, |cos(pi w / (2 w0))| of the unshaped
    one off it (undamped)."""
    w0 = 1.1
    p, s = trap(), mo.shape(trap(), zv(w0))
    assert mo.residual_amplitude(s, w0) < 1e-13          # round-off of O(1) terms
    for w in (0.6, 0.9, 1.4, 2.0):
        want = mo.residual_amplitude(p, w) * abs(np.cos(np.pi * w / (2 * w0)))
        unshaped = 4 / w**2 * abs(np.sin(w) * np.sin(1.5 * w))
        assert mo.residual_amplitude(p, w) == pytest.approx(unshaped, rel=1e-10)
        assert mo.residual_amplitude(s, w) == pytest.approx(want, rel=1e-10)
    L = G / w0**2
    assert mo.residual_sway(s, L) < 1e-13


@pytest.mark.parametrize("zeta, gain", [(0.0, 1.0), (0.05, -0.4), (0.3, 2.5)])
def test_damped_residual_against_the_matrix_exponential(zeta, gain):
    """AccelSteps (the trapezoid, ZV-shaped off-design) and JerkSteps (the S-curve, and
    shaped) against the exact piecewise propagation, damped."""
    w = 1.7
    for p in (trap(), mo.shape(trap(), zv(1.3)), mo.s_curve(6.0, 2.0, 1.0, 2.0),
              mo.shape(mo.s_curve(6.0, 2.0, 1.0, 2.0), zv(1.3))):
        got = mo.residual_amplitude(p, w, zeta, gain)
        assert got == pytest.approx(ref_amplitude(p, w, zeta, gain), rel=1e-10)


def test_defaults_and_residual_sway_damped():
    w = 0.8
    p = mo.s_curve(6.0, 2.0, 1.0, 2.0)
    assert mo.residual_amplitude(p, w) == pytest.approx(ref_amplitude(p, w, 0.0, 1.0),
                                                        rel=1e-10)
    L = G / w**2
    assert mo.residual_sway(p, L) == pytest.approx(ref_amplitude(p, w, 0.0, 1 / L),
                                                   rel=1e-10)
    assert mo.residual_sway(p, L, zeta=0.1) == pytest.approx(
        ref_amplitude(p, w, 0.1, 1 / L), rel=1e-10)
    assert mo.residual_sway(p, 2.0, g=3.0, zeta=0.2) == pytest.approx(
        ref_amplitude(p, np.sqrt(1.5), 0.2, 0.5), rel=1e-10)


def test_responses_at_a_delay():
    """s, h, rho at tau = 0.9 for w = 1.3, zeta = 0.2 against the matrix exponential of
    q'' + 2 zeta w q' + w^2 q = f for f = H(t) and f = t H(t)."""
    w, z, tau = 1.3, 0.2, 0.9
    s, h, rho = mo._responses(np.array([tau]), w, z)
    step = mo.AccelSteps(np.array([0.0]), np.array([1.0]))
    ramp = mo.JerkSteps(np.array([0.0]), np.array([1.0]))
    q, dq = ref_state(step, w, z, 1.0, tau)
    assert s[0] == pytest.approx(q, rel=1e-12) and h[0] == pytest.approx(dq, rel=1e-12)
    q, dq = ref_state(ramp, w, z, 1.0, tau)
    assert rho[0] == pytest.approx(q, rel=1e-12) and s[0] == pytest.approx(dq, rel=1e-12)


def test_double_pendulum_against_the_eigenproblem():
    l1, l2, m1, m2, g = 20.0, 3.0, 250.0, 4000.0, 9.7
    M = np.diag([m1, m2])
    K = g * np.array([[(m1 + m2) / l1 + m2 / l2, -m2 / l2], [-m2 / l2, m2 / l2]])
    ref = np.sqrt(sl.eigh(K, M, eigvals_only=True))
    assert np.allclose(mo.double_pendulum_omegas(l1, l2, m1, m2, g), ref, rtol=1e-12)
    K *= G / g
    ref = np.sqrt(sl.eigh(K, M, eigvals_only=True))
    assert np.allclose(mo.double_pendulum_omegas(l1, l2, m1, m2), ref, rtol=1e-12)


# ------------------------------------------------------------------ nonlinear pendulum

@lru_cache(maxsize=None)
def _nonlinear_ref(kind, length, g):
    """Largest |theta| of the exact pendulum after the move: one integration with a(t)
    from the hand formulas of the profiles, then one period of free swing sampled."""
    if kind == "trap":                     # big: 3 m/s^2 for 1 s, coast 1 s, brake
        def acc(t):
            return 3.0 if t < 1 else (0.0 if t < 2 else (-3.0 if t < 3 else 0.0))
        end, breaks = 3.0, [1.0, 2.0]
    else:                                  # S-curve 6, 2, 1, 2: averaged trapezoid
        def tr(t):
            return 1.0 if 0 <= t < 2 else (-1.0 if 3 <= t < 5 else 0.0)

        def acc(t):
            lo = max(t - 0.5, 0.0)
            pts = sorted({lo, t} | {b for b in (0.0, 2.0, 3.0, 5.0) if lo < b < t})
            return sum(tr(0.5 * (a + b)) * (b - a) for a, b in zip(pts[:-1], pts[1:])) / 0.5
        end, breaks = 5.5, [0.5, 2.0, 2.5, 3.0, 3.5, 5.0]

    def rhs(t, y):
        return [y[1], -(g * np.sin(y[0]) + acc(t) * np.cos(y[0])) / length]
    y = np.zeros(2)
    edges = [0.0] + breaks + [end]
    for a, b in zip(edges[:-1], edges[1:]):           # integrate across the kinks
        y = solve_ivp(rhs, (a, b), y, method="DOP853", rtol=1e-12, atol=1e-14).y[:, -1]
    per = 2 * np.pi * np.sqrt(length / g) * 1.2
    sol = solve_ivp(lambda t, y: [y[1], -g * np.sin(y[0]) / length], (0, per), y,
                    method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True)
    return float(np.max(np.abs(sol.sol(np.linspace(0, per, 20001))[0])))


def test_nonlinear_residual_of_a_big_trapezoid():
    """3 m/s^2 on a 2 m pendulum: 17 deg of sway, far from linear."""
    p = mo.AccelSteps(np.array([0.0, 1.0, 2.0, 3.0]), np.array([3.0, -3.0, -3.0, 3.0]))
    got = mo.nonlinear_residual_sway(p, 2.0)
    assert got == pytest.approx(_nonlinear_ref("trap", 2.0, G), rel=1e-6)
    assert got > 0.2
    got = mo.nonlinear_residual_sway(p, 2.0, g=5.0)
    assert got == pytest.approx(_nonlinear_ref("trap", 2.0, 5.0), rel=1e-6)


def test_nonlinear_residual_of_an_s_curve():
    p = mo.s_curve(6.0, 2.0, 1.0, 2.0)
    got = mo.nonlinear_residual_sway(p, 1.5)
    assert got == pytest.approx(_nonlinear_ref("s", 1.5, G), rel=1e-6)


def test_nonlinear_residual_over_the_top_is_pi():
    """80 m/s^2 for 0.3 s then braking as hard on a 1 m pendulum: the swing passes over
    the top (cos theta - l theta'^2 / (2 g) < -1), reported as pi."""
    p = mo.AccelSteps(np.array([0.0, 0.3, 0.6]), np.array([80.0, -160.0, 80.0]))
    assert mo.nonlinear_residual_sway(p, 1.0) == np.pi
