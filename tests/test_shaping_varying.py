"""The time-varying ZV shaper (cranefe/analysis/shaping/varying.py) against exact answers:
constant frequency gives the ZV shaper; a pendulum whose length changes during the move
is left at rest by it, integrated in its own angle (l th'' + 2 l' th' + g th = -a), not
in the transformed coordinate the shaper was derived in.

Tolerances: the shaper's half periods come from DOP853 at rtol 1e-10 refined by Newton,
its table samples a smooth speed every 0.1 s (linear interpolation error h^2/8 |v''|
~ 1e-6 of the speed); the reference integrates each piece of the table (constant
acceleration) with DOP853 at rtol 1e-11, so a cancelled residual is ~1e-5 of the
unshaped one (measured 1.2e-6); asserted below 1e-4.
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from cranefe.analysis.shaping import shape, trapezoid, zv
from cranefe.analysis.shaping.varying import omega2_from_samples, time_varying_zv

G = 9.81


def test_constant_frequency_gives_the_zv_shaper():
    move = trapezoid(15.0, 1.0, 0.5)
    w = np.sqrt(G / 25.0)
    t, v = time_varying_zv(move.times, lambda x: float(move.acceleration(x)),
                           lambda x: w * w, 15.0)
    ref = shape(move, zv(w))
    assert t[-1] == pytest.approx(ref.end, rel=1e-9)
    assert np.allclose(v, ref.speed(t), rtol=0, atol=1e-8)


def _pendulum_residual(t_tab, v_tab, ell, dell, T):
    """Residual swing amplitude (rad) at T of l th'' + 2 l' th' + g th = -a, a the
    table's piecewise-constant acceleration, from rest; after the table the trolley
    rests. Amplitude from the energy of the local oscillator at T: sqrt(th^2 + (th'/w)^2)
    with w^2 = g / l (the length is constant by then)."""
    y = np.zeros(2)
    edges = list(t_tab) + [T]
    for k in range(len(edges) - 1):
        a = (v_tab[k + 1] - v_tab[k]) / (t_tab[k + 1] - t_tab[k]) if k < len(t_tab) - 1 \
            else 0.0

        def rhs(s, y, a=a):
            return [y[1], -(2 * dell(s) * y[1] + G * y[0] + a) / ell(s)]
        y = solve_ivp(rhs, (edges[k], edges[k + 1]), y, method="DOP853", rtol=1e-11,
                      atol=1e-14).y[:, -1]
    return float(np.hypot(y[0], y[1] / np.sqrt(G / ell(T))))


def test_a_pendulum_hoisted_during_the_move_is_left_at_rest():
    """l(t) = 30 - 10 (1 - cos(pi t / 25)) m for t < 25 s, then 10 m: hoisted 20 m with
    a smooth speed while the trolley runs 15 m (1 m/s, 0.5 m/s^2). The shaper takes
    w(t)^2 from sampled pendulum frequencies sqrt(g / l), as the study takes them from
    the crane's modes; its residual is < 1e-4 of the unshaped move's; ZV at the start or
    the mean length leaves 0.33 and 0.15 of it (measured)."""
    def ell(s):
        return 30.0 - 10.0 * (1 - np.cos(np.pi * min(s, 25.0) / 25.0))

    def dell(s):
        return -10.0 * np.pi / 25.0 * np.sin(np.pi * s / 25.0) if s < 25.0 else 0.0
    move = trapezoid(15.0, 1.0, 0.5)
    ts = np.linspace(0.0, 40.0, 161)
    omega2 = omega2_from_samples(ts, [np.sqrt(G / ell(s)) for s in ts])
    t, v = time_varying_zv(move.times, lambda x: float(move.acceleration(x)), omega2, 15.0)
    T = 45.0
    base = move.table()
    unshaped = _pendulum_residual(np.array(base["times"]), np.array(base["values"]),
                                  ell, dell, T)
    got = _pendulum_residual(t, v, ell, dell, T)
    assert got < 1e-4 * unshaped, (got, unshaped)
    assert float(np.sum(0.5 * (v[1:] + v[:-1]) * np.diff(t))) == pytest.approx(15.0,
                                                                               rel=1e-12)
    for length in (30.0, 20.0):
        p = shape(move, zv(np.sqrt(G / length))).table()
        fixed = _pendulum_residual(np.array(p["times"]), np.array(p["values"]), ell, dell, T)
        assert fixed > 0.1 * unshaped


def test_a_varying_gain_is_followed():
    """A suspension that moves k(t) = 1 + t / 20 m per metre of drive (a luffing tip's
    lever growing along the move) under a 20 m pendulum: with the gain the increments
    cancel in th'' + w^2 th = -k(t) a(t) / l (measured 1.6e-6 of the unshaped swing),
    without it they do not (0.078)."""
    l = 20.0
    w = np.sqrt(G / l)
    move = trapezoid(15.0, 1.0, 0.5)

    def k(t):
        return 1.0 + t / 20.0

    def residual(t_tab, v_tab):
        y = np.zeros(2)
        for j in range(len(t_tab) - 1):
            a = (v_tab[j + 1] - v_tab[j]) / (t_tab[j + 1] - t_tab[j])
            y = solve_ivp(lambda s, y: [y[1], -w * w * y[0] - k(s) * a / l],
                          (t_tab[j], t_tab[j + 1]), y, method="DOP853", rtol=1e-11,
                          atol=1e-14).y[:, -1]
        return float(np.hypot(y[0], y[1] / w))
    base = move.table()
    ref = residual(np.array(base["times"]), np.array(base["values"]))
    with_gain = residual(*time_varying_zv(move.times, lambda x: float(move.acceleration(x)),
                                          lambda x: w * w, 15.0, gain=k))
    without = residual(*time_varying_zv(move.times, lambda x: float(move.acceleration(x)),
                                        lambda x: w * w, 15.0))
    assert with_gain < 1e-4 * ref and without > 1e-2 * ref, (with_gain, without, ref)
