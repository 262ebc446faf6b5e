"""Kill tests for cranefe/analysis/shaping/varying.py (tools/mutation.py varying;
docs/testing.md, "Mutation testing"), against answers found without the module.

half_periods: D(tau) and rho(tau) of eq. (1), w(t)^2 = g / l for lengths growing
linearly (l'' = 0), short and long, and for constant lengths (D = pi / w, rho = -1 in
closed form), one of them on a long move, one at negative times. Reference: the free
swing started at tau with y = 0, y' = 1, integrated on its own (DOP853, rtol 1e-13, atol
1e-15) to tau + D: there y must vanish, y' equal rho, and y stay positive in between
(the FIRST zero). Tolerances: |y(tau + D)| w < 1e-9 of the swing's size 1 / w (the
module's Newton refinement converges to round-off of its rtol-1e-10 solutions: measured
<= 1.6e-10); rho to 1e-8 (rtol 1e-10 over up to 30 periods: measured <= 5e-10).

time_varying_zv: with a constant length the shaped speed is the ZV shaper's, in closed
form v(t) = (v_c(t) + v_c(t - pi/w)) / 2, v_c the trapezoid written out by hand, and the
table's points are, as documented, every `step` s from the start, the command's corners
and their arrivals (corners + pi / w) and the end. With a varying length (30 m -> 10 m,
the case of tests/test_shaping_varying.py) the residual swing of eq. (1) left by the
shaped table, by Duhamel's integral over a tightly integrated pair of free solutions
(computed once): below 4e-6 of the unshaped move's (measured 1.25e-6 with n = 1000,
1.21e-6 with the default 4000: the table's linear interpolation of the speed between
points 0.1 s apart, h^2/8 |v''|; a coarser quadrature of eq. 2 over 50 points instead
of n + 1 leaves 2.0e-5). n = 400 or 1000 here to keep the file fast (the constant-length
answers are exact for any n).

omega2_from_samples: samples of a cubic length (reproduced exactly by the not-a-knot
spline) give w^2 = (g - l'') / l by hand, held at the end values outside the samples.

The errors: no distance (ModelError), w(t)^2 <= 0 on the move (l'' >= g: the free
swing would have no period and the integration no end), a frequency that is undefined
after the move (the free swing does not integrate).
"""

import functools

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from cranefe.analysis.shaping import trapezoid
from cranefe.analysis.shaping.varying import half_periods, omega2_from_samples, time_varying_zv
from cranefe.errors import AnalysisError, ModelError

G = 9.81


def _grow(l0, rate):
    return lambda t: G / (l0 + rate * t)


def _const(ell):
    return lambda t: G / ell


# (w^2(t), t0, t1, taus): W = w(t0)^2 far from 1 on both sides (the Newton step's scale),
# |rho| far from 1 (l = 1 + 4 t: the swing's amplitude changes within a half period), a
# long pendulum (pi / w = 10 s) at negative times, a short one on a 60 s move (30
# periods)
CASES = {
    "l=10+2t": (_grow(10.0, 2.0), 0.0, 5.0, (0.0, 1.3, 4.0)),
    "l=1+4t": (_grow(1.0, 4.0), 0.0, 5.0, (0.0, 0.7, 4.0)),
    "l=80+20t": (_grow(80.0, 20.0), 0.0, 5.0, (0.0, 2.0, 5.0)),
    "l=100, t<0": (_const(100.0), -30.0, -14.0, (-30.0, -20.0, -14.0)),
    "l=1, 60 s": (_const(1.0), 0.0, 60.0, (0.0, 33.3, 60.0)),
}


@pytest.mark.parametrize("case", CASES)
def test_half_period_ends_at_the_next_zero_of_the_free_swing(case):
    omega2, t0, t1, taus = CASES[case]
    at = half_periods(omega2, t0, t1)
    for tau in taus:
        D, rho = at(tau)
        assert D > 0
        sol = solve_ivp(lambda t, y: [y[1], -omega2(t) * y[0]], (tau, tau + D), [0.0, 1.0],
                        method="DOP853", rtol=1e-13, atol=1e-15, dense_output=True)
        y, dy = sol.y[:, -1]
        w = np.sqrt(omega2(tau + D))
        assert abs(y) * w < 1e-9, (tau, y)
        assert rho == pytest.approx(dy, rel=1e-8)
        assert sol.sol(tau + D * np.linspace(0.01, 0.99, 50))[0].min() > 0   # first zero
        if "+" in case:
            # a longer pendulum swings slower; the amplitude grows as the rope pays out
            assert D > np.pi / np.sqrt(omega2(tau)) and -1.0 < rho < 0.0
        if "," in case:                                  # constant length: closed form
            assert D == pytest.approx(np.pi / np.sqrt(omega2(tau)), rel=1e-9)
            assert rho == pytest.approx(-1.0, rel=1e-8)


def _vc(t):
    """trapezoid(15, 1, 0.5)'s speed by hand: 0.5 m/s^2 for 2 s, 1 m/s to 15 s, down
    to rest at 17 s."""
    t = np.asarray(t, dtype=float)
    return np.clip(np.minimum(0.5 * t, 1.0 - 0.5 * (t - 15.0)), 0.0, 1.0) * (t > 0)


def test_constant_length_table_is_the_zv_shaper_point_by_point():
    """D = 3.002 s puts the end at 20.002 s, just after the grid point 20.0 (the table
    keeps both)."""
    move = trapezoid(15.0, 1.0, 0.5)
    D = 3.002
    w = np.pi / D
    t, v = time_varying_zv(move.times, lambda x: float(move.acceleration(x)),
                           lambda x: w * w, 15.0, n=400)
    corners = np.array([0.0, 2.0, 15.0, 17.0])
    want = np.unique(np.concatenate([np.arange(0.0, 17.0 + D, 0.1), corners,
                                     corners + D, [17.0 + D]]))
    assert len(t) == len(want) and np.allclose(t, want, rtol=0, atol=1e-9)
    # exact: v is linear between the kinks, all of them table points; D from Newton to
    # ~1e-12 s
    assert np.allclose(v, 0.5 * (_vc(t) + _vc(t - D)), rtol=0, atol=1e-9)
    assert v[-1] == 0.0 and v[0] == 0.0


def test_a_move_shorter_than_a_metre_is_shaped():
    """trapezoid(0.5, 0.5, 0.5): a triangle of 1 s up, 1 s down; ZV with D = 2 s by
    hand, travelling 0.5 m."""
    move = trapezoid(0.5, 0.5, 0.5)
    w = np.pi / 2.0
    t, v = time_varying_zv(move.times, lambda x: float(move.acceleration(x)),
                           lambda x: w * w, 0.5, n=400)

    def vc(s):
        return np.clip(np.minimum(0.5 * s, 1.0 - 0.5 * s), 0.0, None)
    assert t[-1] == pytest.approx(4.0, rel=0, abs=1e-9)          # D from Newton, ~1e-11
    assert np.allclose(v, 0.5 * (vc(t) + vc(t - 2.0)), rtol=0, atol=1e-9)
    assert float(np.sum(0.5 * (v[1:] + v[:-1]) * np.diff(t))) == pytest.approx(0.5,
                                                                              rel=1e-12)


def _ell(t):
    """30 m -> 10 m over 25 s: l = 20 + 10 cos(pi t / 25), then 10 m."""
    return 20.0 + 10.0 * np.cos(np.pi * min(t, 25.0) / 25.0)


def _omega2_hoist(t):
    """eq. (1): w^2 = (g - l'') / l, l'' = -10 (pi/25)^2 cos(pi t / 25) before 25 s."""
    d2 = -10.0 * (np.pi / 25.0) ** 2 * np.cos(np.pi * t / 25.0) if t < 25.0 else 0.0
    return (G - d2) / _ell(t)


T_END = 30.0


@functools.lru_cache(maxsize=None)
def _free_pair():
    """y1, y2 of u'' + w^2 u = 0 (y1 = 1, y2' = 1 at 0, Wronskian 1) and their running
    integrals Y1, Y2, on [0, 25] and [25, 30] (w^2 jumps at 25 s), DOP853 at rtol 1e-12:
    the dense outputs."""
    def rhs(t, s):
        w2 = _omega2_hoist(t)
        return [s[1], -w2 * s[0], s[3], -w2 * s[2], s[0], s[2]]
    a = solve_ivp(rhs, (0.0, 25.0), [1.0, 0.0, 0.0, 1.0, 0.0, 0.0], method="DOP853",
                  rtol=1e-12, atol=1e-14, dense_output=True)
    b = solve_ivp(rhs, (25.0, T_END), a.y[:, -1], method="DOP853", rtol=1e-12,
                  atol=1e-14, dense_output=True)
    return a.sol, b.sol


def _state(t):
    a, b = _free_pair()
    return np.array([a(x) if x <= 25.0 else b(x) for x in np.atleast_1d(t)]).T


def _residual(t_tab, v_tab):
    """The free swing of eq. (1) at T_END after the table (a = dv/dt constant between its
    points, the suspension at rest after it), from rest: u(T) = -int a(tau) y_tau(T) dtau
    with y_tau(T) = y1(tau) y2(T) - y2(tau) y1(T) (Wronskian 1), int y_i over a piece =
    the change of Y_i. Amplitude sqrt(u^2 + (u'/w)^2), w = sqrt(g / 10) after 25 s."""
    t_tab, v_tab = np.asarray(t_tab, float), np.asarray(v_tab, float)
    a = np.diff(v_tab) / np.diff(t_tab)
    s = _state(t_tab)
    c1 = float(np.sum(a * np.diff(s[4])))
    c2 = float(np.sum(a * np.diff(s[5])))
    y1, dy1, y2, dy2 = _state(T_END)[:4, 0]
    u = -(c1 * y2 - c2 * y1)
    du = -(c1 * dy2 - c2 * dy1)
    return float(np.hypot(u, du / np.sqrt(G / 10.0)))


def test_hoisting_pendulum_residual_by_duhamel():
    move = trapezoid(15.0, 1.0, 0.5)
    base = move.table()
    unshaped = _residual(base["times"], base["values"])
    t, v = time_varying_zv(move.times, lambda x: float(move.acceleration(x)),
                           _omega2_hoist, 15.0, n=1000)
    got = _residual(t, v)
    assert got < 4e-6 * unshaped, (got / unshaped)


def test_omega2_from_cubic_samples():
    def ell(t):
        return 20.0 + 3.0 * t - 0.5 * t ** 2 + 0.02 * t ** 3

    def want(t):
        return (G - (-1.0 + 0.12 * t)) / ell(t)
    ts = np.linspace(0.0, 10.0, 11)
    omega2 = omega2_from_samples(ts, np.sqrt(G / ell(ts)))
    # interior, between the first two and the last two samples (1e-10: the spline's
    # solve in round-off), and held outside
    for t in (0.0, 0.3, 4.45, 9.7, 10.0):
        assert omega2(t) == pytest.approx(want(t), rel=1e-10)
    assert omega2(-2.0) == pytest.approx(want(0.0), rel=1e-10)
    assert omega2(13.0) == pytest.approx(want(10.0), rel=1e-10)


def _shape(omega2, accel=None, distance=15.0):
    move = trapezoid(15.0, 1.0, 0.5)
    accel = accel or (lambda x: float(move.acceleration(x)))
    return time_varying_zv(move.times, accel, omega2, distance, n=200)


def test_a_command_of_no_distance_is_refused():
    with pytest.raises(ModelError) as e:
        _shape(lambda x: 1.0, accel=lambda x: 0.0)
    assert str(e.value) == "time-varying shaper: the command travels no distance"


@pytest.mark.parametrize("omega2", [lambda x: 0.5 - 0.1 * x, lambda x: 0.0,
                                    lambda x: -1.0 if x < 1.0 else 1.0])
def test_a_frequency_without_swing_is_refused(omega2):
    """w^2 < 0 from 5 s on, or 0, or < 0 in the move's first second only: before the fix
    the free swing's span was nan or inf and the integration never ended."""
    with pytest.raises(AnalysisError, match=r"^time-varying shaper: w\(t\)\^2 = "):
        _shape(omega2)


def test_an_undefined_frequency_is_reported():
    with pytest.raises(AnalysisError) as e:
        half_periods(lambda x: G / 10.0 if x < 3.0 else float("nan"), 0.0, 2.0)
    assert str(e.value).startswith("time-varying shaper: the free swing did not integrate (")
