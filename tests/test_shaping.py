"""Input shapers and swing-free moves (cranefe.analysis.shaping) against exact answers.

Tolerances: the shapers' residuals are sums of a few exponentials of O(1) size, so the
exact zeros come out at round-off (1e-12 leaves 1e4 ulps); residuals of whole moves are
compared relative to the unshaped move's. ODE references use DOP853 at rtol 1e-10 and
atol 1e-13 on O(1) variables: agreement to 1e-8 relative is the integrator's error.
"""

import numpy as np
import pytest
import scipy.linalg as sl
from scipy.integrate import solve_ivp

from cranefe.analysis import shaping as sh
from cranefe.errors import ModelError

L, G = 20.0, 9.81
W = np.sqrt(G / L)
TOL = dict(method="DOP853", rtol=1e-10, atol=1e-13)


def _integrate_linear(profile, omega, zeta, gain):
    """q'' + 2 zeta w q' + w^2 q = gain a(t) from rest, piecewise between the steps."""
    y = np.zeros(2)
    edges = np.unique(np.concatenate([[0.0], profile.times]))
    for t0, t1 in zip(edges[:-1], edges[1:]):       # a(t) = a0 + slope (t - tm) here
        tm = 0.5 * (t0 + t1)
        a0 = float(profile.acceleration(tm))
        slope = float(np.sum(profile.jumps[profile.times <= t0])) if profile.order else 0.0
        rhs = lambda t, y: [y[1], gain * (a0 + slope * (t - tm))
                            - 2 * zeta * omega * y[1] - omega**2 * y[0]]
        y = solve_ivp(rhs, (t0, t1), y, **TOL).y[:, -1]
    wd = omega * np.sqrt(1 - zeta**2)
    return np.hypot(y[0], (y[1] + zeta * omega * y[0]) / wd)


@pytest.mark.parametrize("zeta", [0.0, 0.05, 0.2])
@pytest.mark.parametrize("name", ["ZV", "ZVD", "ZVDD"])
def test_zero_residual_at_design_frequency(name, zeta):
    s = sh.make(name, W, zeta)
    assert np.sum(s.amplitudes) == pytest.approx(1.0, abs=1e-15)
    assert s.residual(W) < 1e-12
    move = sh.trapezoid(15.0, 1.0, 0.5)
    ref = sh.residual_amplitude(move, W, zeta, 1 / L)
    assert sh.residual_amplitude(sh.shape(move, s), W, zeta, 1 / L) < 1e-12 * ref


@pytest.mark.parametrize("zeta", [0.0, 0.1])
def test_zvd_zero_slope_and_analytic_derivative(zeta):
    s = sh.zvd(W, zeta)
    T = 2 * np.pi / W
    assert s.slope(W) < 1e-12 * T           # the residual vector and its slope vanish
    zv = sh.zv(W, zeta)
    assert zv.slope(W) > 0.1 * T            # ZV: zero residual, but a kink
    h = 1e-6 * W                       # central difference: error O(h^2) ~ 1e-12
    fd = (zv.residual(1.3 * W + h) - zv.residual(1.3 * W - h)) / (2 * h)
    assert zv.residual_derivative(1.3 * W) == pytest.approx(fd, rel=1e-7)


def test_durations():
    T = 2 * np.pi / W
    assert sh.zv(W).duration == pytest.approx(T / 2, rel=1e-15)
    assert sh.zvd(W).duration == pytest.approx(T, rel=1e-15)
    assert sh.zvdd(W).duration == pytest.approx(1.5 * T, rel=1e-15)
    assert sh.ei(W).duration == pytest.approx(T, rel=1e-15)


@pytest.mark.parametrize("zeta", [0.0, 0.05, 0.15])
@pytest.mark.parametrize("V", [0.02, 0.05, 0.1])
def test_ei_residual_is_v_and_below_v_over_its_band(zeta, V):
    s = sh.ei(W, zeta, V)
    assert s.residual(W) == pytest.approx(V, abs=1e-12)
    assert abs(s.residual_derivative(W)) < 1e-10 / W
    r = np.linspace(0.5, 1.5, 20001) * W
    res = s.residual(r)
    inside = res <= V + 1e-12
    band = r[inside]                  # one interval around W, with zeros inside
    assert band[0] < W < band[-1] and np.all(inside[(r >= band[0]) & (r <= band[-1])])
    if zeta == 0.0:                   # the zeros at w T/2 = pi +/- arccos((1-V)/(1+V))
        c = np.arccos((1 - V) / (1 + V)) / np.pi
        assert s.residual((1 - c) * W) < 1e-12 and s.residual((1 + c) * W) < 1e-12
    assert np.min(res[:len(r) // 2]) < 1e-4 and np.min(res[len(r) // 2:]) < 1e-4


def test_double_pendulum_and_multimode_shaper():
    l1, l2, m1, m2 = 20.0, 3.0, 400.0, 2000.0
    w1, w2 = sh.double_pendulum_omegas(l1, l2, m1, m2)
    M = np.diag([m1, m2])
    K = G * np.array([[(m1 + m2) / l1 + m2 / l2, -m2 / l2], [-m2 / l2, m2 / l2]])
    lam, V = sl.eigh(K, M)
    np.testing.assert_allclose([w1, w2], np.sqrt(lam), rtol=1e-13)
    s = sh.convolve(sh.zv(w1), sh.zv(w2))
    assert len(s.times) == 4 and np.sum(s.amplitudes) == pytest.approx(1.0, abs=1e-15)
    assert s.residual(w1) < 1e-12 and s.residual(w2) < 1e-12
    # trolley acceleration a: M x'' + K x = -a M 1 (x relative to the trolley), so mode k
    # has gain -(phi_k^T M 1) for mass-normalised phi_k
    move = sh.trapezoid(15.0, 1.0, 0.5)
    gains = -V.T @ M @ np.ones(2)
    for k, w in enumerate((w1, w2)):
        ref = sh.residual_amplitude(move, w, 0.0, gains[k])
        for shaper, cancels in ((s, True), (sh.zv(w1), k == 0)):
            res = sh.residual_amplitude(sh.shape(move, shaper), w, 0.0, gains[k])
            assert (res < 1e-12 * ref) == cancels


@pytest.mark.parametrize("zeta", [0.0, 0.1])
def test_residual_closed_form_against_ode(zeta):
    move = sh.shape(sh.trapezoid(6.0, 1.0, 0.8), sh.ei(W * 1.1, 0.0, 0.05))
    for w in (W, 1.7 * W):
        ref = _integrate_linear(move, w, zeta, 1 / L)
        assert sh.residual_amplitude(move, w, zeta, 1 / L) == pytest.approx(ref, rel=1e-8)


def test_shaped_profile_and_table():
    move = sh.trapezoid(15.0, 1.0, 0.5)
    assert move.end == pytest.approx(17.0) and move.position(move.end) == pytest.approx(15)
    tri = sh.trapezoid(1.0, 1.0, 0.5)          # too short for 1 m/s: a triangle
    assert tri.speed(tri.times[1]) == pytest.approx(np.sqrt(0.5)) and len(tri.times) == 3
    s = sh.zvd(W, 0.05)
    shaped = sh.shape(move, s)
    assert shaped.end == pytest.approx(move.end + s.duration, rel=1e-14)
    tab = shaped.table()
    assert tab["positions"][-1] == pytest.approx(15.0, rel=1e-14)
    assert tab["values"][-1] == pytest.approx(0.0, abs=1e-14)
    assert max(tab["values"]) == pytest.approx(1.0, rel=1e-14)
    t = np.linspace(0, shaped.end, 1001)          # the table is exact between its rows
    np.testing.assert_allclose(np.interp(t, tab["times"], tab["values"]), shaped.speed(t),
                               atol=1e-13)
    assert np.all(np.diff(tab["times"]) > 0)


def test_swing_free_trapezoid():
    for D, v, a, l in ((15.0, 1.0, 0.5, 20.0), (3.0, 1.0, 0.5, 20.0), (40, 2.0, 0.3, 8.0)):
        r = sh.min_time_swing_free(D, v, a, l)
        p = r["profile"]
        assert p.position(p.end) == pytest.approx(D, rel=1e-13)
        assert np.max(np.abs(p.jumps)) <= a * (1 + 1e-15)
        assert p.speed(r["t_acc"]) <= v * (1 + 1e-12)
        plain = sh.trapezoid(D, v, a)
        scale = sh.residual_sway(plain, l)
        assert sh.residual_sway(p, l) < 1e-12 * max(scale, 1e-3)
        w = np.sqrt(G / l)
        assert _integrate_linear(p, w, 0.0, 1 / l) < 1e-8 * max(scale, 1e-3)
        assert r["time_s"] >= plain.end - 1e-12
        # no faster swing-free trapezoid on a fine grid of accelerations and coasts
        T = 2 * np.pi / w
        for ta in np.linspace(0.05, 3 * T, 301):
            s = D / (a * ta)
            if s >= ta and a * ta <= v and ta + s < r["time_s"] - 1e-9:
                res = 4 * a / (l * w * w) * abs(np.sin(w * ta / 2) * np.sin(w * s / 2))
                assert res > 1e-6


def test_residual_product_formula():
    # a trapezoid's residual = (4 a / (l w^2)) |sin(w t_a/2) sin(w (t_a + t_c)/2)|
    move = sh.trapezoid(15.0, 1.0, 0.5)
    ta, s = move.times[1], move.times[2]
    ref = 4 * 0.5 / G * abs(np.sin(W * ta / 2) * np.sin(W * s / 2))
    assert sh.residual_sway(move, L) == pytest.approx(ref, rel=1e-13)


def test_nonlinear_residual_reported_and_linear_limit():
    move = sh.trapezoid(15.0, 1.0, 0.5)
    zv = sh.shape(move, sh.zv(W))
    nl = sh.nonlinear_residual_sway(zv, L)
    assert 1e-7 < nl < 1e-4           # nonlinear deviation: small but not zero
    small = sh.trapezoid(0.15, 0.01, 0.005)      # 100 x smaller: the linear limit
    lin = sh.residual_sway(small, L)
    assert sh.nonlinear_residual_sway(small, L) == pytest.approx(lin, rel=1e-6)


def test_bad_input():
    with pytest.raises(ModelError):
        sh.zv(-1.0)
    with pytest.raises(ModelError):
        sh.ei(1.0, 0.0, 1.5)
    with pytest.raises(ModelError):
        sh.make("XYZ", 1.0)
    with pytest.raises(ModelError):
        sh.trapezoid(0.0, 1.0, 1.0)
    with pytest.raises(ModelError, match="constant speed"):     # stops mid-acceleration
        sh.residual_sway(sh.AccelSteps(np.array([0.0, 1.0]), np.array([1.0, -0.5])), L)
    with pytest.raises(ModelError, match="constant speed"):
        sh.residual_sway(sh.JerkSteps(np.array([0.0, 1.0]), np.array([1.0, -1.0])), L)


def test_s_curve():
    """The S-curve is the trapezoid filtered by a box of width t_j: same distance and top
    speed, t_j longer, jerk a/t_j, residual x |sin(w t_j/2)|/(w t_j/2)."""
    a, j = 0.5, 0.25
    tj = a / j
    p, tr = sh.s_curve(15.0, 1.0, a, j), sh.trapezoid(15.0, 1.0, a)
    assert p.end == pytest.approx(tr.end + tj, rel=1e-15)
    assert p.position(p.end) == pytest.approx(15.0, rel=1e-14)
    t = np.linspace(0, p.end, 2001)
    assert np.max(np.abs(p.acceleration(p.times))) == pytest.approx(a, rel=1e-14)
    assert np.max(np.abs(np.diff(p.acceleration(t)) / np.diff(t))) <= j * (1 + 1e-9)
    for w in (W, 2.3 * W):
        sinc = abs(np.sin(w * tj / 2) / (w * tj / 2))
        assert sh.residual_amplitude(p, w, 0.0, 1 / L) == pytest.approx(
            sh.residual_amplitude(tr, w, 0.0, 1 / L) * sinc, rel=1e-12)
    tab = p.table(per_piece=8)                # piecewise-quadratic speed: error j h^2/8
    h = np.max(np.diff(tab["times"]))
    err = np.max(np.abs(np.interp(t, tab["times"], tab["values"]) - p.speed(t)))
    assert 0 < err <= j * h * h / 8 * (1 + 1e-9)


@pytest.mark.parametrize("zeta", [0.0, 0.1])
def test_shaped_s_curve_zero_residual_and_ode(zeta):
    p = sh.s_curve(6.0, 1.0, 0.8, 1.5)
    ref = sh.residual_amplitude(p, W, zeta, 1 / L)
    assert sh.residual_amplitude(sh.shape(p, sh.zvd(W, zeta)), W, zeta, 1 / L) < 1e-12 * ref
    shaped = sh.shape(p, sh.ei(1.1 * W, zeta, 0.05))
    assert isinstance(shaped, sh.JerkSteps)
    for w in (W, 1.7 * W):
        assert sh.residual_amplitude(shaped, w, zeta, 1 / L) == pytest.approx(
            _integrate_linear(shaped, w, zeta, 1 / L), rel=1e-8)
    small = sh.s_curve(0.06, 0.01, 0.008, 0.015)      # 100 x smaller: linear limit
    assert sh.nonlinear_residual_sway(small, L) == pytest.approx(
        sh.residual_sway(small, L), rel=1e-6)


def test_energy_optimal_swing_free():
    D, l = 15.0, 20.0
    w = np.sqrt(G / l)
    classic = sh.energy_optimal_swing_free(D, 17.0, l, swing_free=False)
    np.testing.assert_allclose(classic["coefficients"][:2],
                               [-6 * D / 17.0**2, 12 * D / 17.0**3], rtol=1e-13)
    free = sh.min_time_swing_free(D, 1.0, 0.5, l)
    T = free["time_s"]
    r = sh.energy_optimal_swing_free(D, T, l)
    assert r["position"](T) == pytest.approx(D, rel=1e-13)
    assert abs(r["speed"](T)) < 1e-13 * D / T and abs(r["speed"](0.0)) == 0.0
    h = 1e-4                      # the closed-form speed is the integral of a
    assert (r["speed"](5.0 + h) - r["speed"](5.0 - h)) / (2 * h) == pytest.approx(
        float(r["acceleration"](5.0)), rel=1e-7)
    y = solve_ivp(lambda t, y: [y[1], -float(r["acceleration"](t)) / l - w * w * y[0]],
                  (0, T), [0.0, 0.0], **TOL).y[:, -1]
    scale = sh.residual_sway(sh.trapezoid(D, 1.0, 0.5), l)
    assert np.hypot(y[0], y[1] / w) < 1e-8 * scale           # swing-free
    # optimality: the swing-free trapezoid of the same duration meets the same
    # constraints, so it cannot cost less (int a^2 = 2 a^2 t_a)
    trap_cost = 2 * free["acceleration"]**2 * free["t_acc"]
    assert r["cost"] < trap_cost
    unconstrained = sh.energy_optimal_swing_free(D, T, l, swing_free=False)
    assert r["cost"] > unconstrained["cost"]                   # the sway constraints cost
    tab = r["table"](400)
    assert tab["positions"][-1] == pytest.approx(D, rel=1e-13)
