"""Kill tests for cranefe/analysis/shaping/swingfree.py (tools/mutation.py swingfree;
docs/testing.md, "Mutation testing"; docs/loads.md, "The minimum-time swing-free
trapezoid" and "The energy-optimal swing-free move").

Minimum time: on a pendulum of period T = 1 s (l = g / (4 pi^2)) the candidates are
worked out by hand: family "s = nT" (t_a = D / (a_max n T), feasible if D / (nT) <= v_max
and t_a <= nT), family "t_a = mT" (a = min(a_max, v_max / (mT)), s = D / (a mT), or the
triangle a = D / (mT)^2, s = mT when that s is shorter). Each chosen profile is checked
to travel D and to leave no sway (the closed form of the residual on the linear pendulum,
(4 a / (l w^2)) |sin(w t_a / 2) sin(w s / 2)|).

Energy optimal: without the sway constraints the classic a = (6 D / T^2)(1 - 2 t / T),
speed, position, cost 12 D^2 / T^3, peaks 1.5 D / T and 6 D / T^2 by hand; with them,
the coefficients from the Gram system assembled by mpmath quadrature at 25 digits
(computed once), the speed and position as mpmath integrals of that acceleration, and
the four constraints checked directly on the returned functions.

Tolerances: hand values of O(1) terms 1e-12; the module's Gauss-Legendre Gram system
(condition number ~1e4 here) agrees with the 25-digit one to ~1e-12: 1e-9 relative; the
peaks are maxima on the module's 2001-point grid, against the maximum of the reference
on a 200001-point grid: the grid error (h/2)^2 |a'| / 2 relative to the peak, h = T/2000,
is below 1e-6: asserted to 1e-5.
"""

from functools import lru_cache

import mpmath as mp
import numpy as np
import pytest

from cranefe.analysis.shaping import swingfree as sf
from cranefe.errors import ModelError

G = 9.81
L1 = G / (4 * np.pi**2)          # period 1 s
TOL = 1e-12


def residual(profile, length, g=G):
    """Closed form of the undamped trapezoid's residual (docs/loads.md)."""
    t = profile.times
    a, ta, s = profile.jumps[0], t[1] - t[0], t[2] - t[0]
    w = np.sqrt(g / length)
    return 4 * abs(a) / (length * w * w) * abs(np.sin(w * ta / 2) * np.sin(w * s / 2))


def check(r, total, family, a, ta, tc, D, length=L1, g=G):
    assert r["time_s"] == pytest.approx(total, abs=TOL)
    assert r["family"] == family
    assert r["acceleration"] == pytest.approx(a, abs=TOL)
    assert r["t_acc"] == pytest.approx(ta, abs=TOL)
    assert r["t_coast"] == pytest.approx(tc, abs=TOL)
    assert r["period_s"] == pytest.approx(2 * np.pi * np.sqrt(length / g), rel=1e-15)
    p = r["profile"]
    assert np.allclose(p.times, [0, ta, ta + tc, 2 * ta + tc], rtol=0, atol=TOL)
    assert np.allclose(p.jumps, [a, -a, -a, a], rtol=0, atol=TOL)
    assert float(p.position(total + 1.0)) == pytest.approx(D, abs=1e-11)
    assert residual(p, length, g) < 1e-12
    for k in ("time_s", "acceleration", "t_acc", "t_coast", "period_s"):
        assert type(r[k]) is float


def test_coast_family_wins():
    """D = 3, v_max 10, a_max 1: s = 2T, t_a = 1.5 (s = T would need t_a = 3 > s);
    the t_a = mT family needs 4 s."""
    check(sf.min_time_swing_free(3.0, 10.0, 1.0, L1), 3.5, "coast: t_a + t_c = 2 T",
          1.0, 1.5, 0.5, 3.0)


def test_acceleration_family_wins_when_the_speed_limits():
    """D = 3.5, v_max = a_max = 1: s = nT needs nT >= 3.5 (n = 4, 4.875 s); t_a = T at
    a = 1 and s = 3.5: 4.5 s."""
    check(sf.min_time_swing_free(3.5, 1.0, 1.0, L1), 4.5, "acceleration: t_a = 1 T",
          1.0, 1.0, 2.5, 3.5)


def test_speed_limit_reached_exactly_counts_as_feasible():
    """D = 3, v_max = 1, a_max = 10: s = 3T gives D / s = v_max exactly (and within the
    1e-12 slack when D is 1e-13 larger): t_a = 0.1, 3.1 s (else 4 s by t_a = T)."""
    check(sf.min_time_swing_free(3.0, 1.0, 10.0, L1), 3.1, "coast: t_a + t_c = 3 T",
          10.0, 0.1, 2.9, 3.0)
    D = 3.0 * (1 + 1e-13)
    r = sf.min_time_swing_free(D, 1.0, 10.0, L1)
    assert r["family"] == "coast: t_a + t_c = 3 T"
    # beyond the slack: not feasible
    r = sf.min_time_swing_free(3.0 * (1 + 1e-9), 1.0, 10.0, L1)
    assert r["family"] == "acceleration: t_a = 1 T"


def test_no_coast_is_feasible_and_comes_first():
    """D = 1, a_max = 1: s = T with t_a = T (no coast) is feasible (t_a <= s) and ties
    with t_a = T; the coast family is listed first."""
    check(sf.min_time_swing_free(1.0, 10.0, 1.0, L1), 2.0, "coast: t_a + t_c = 1 T",
          1.0, 1.0, 0.0, 1.0)


def test_candidates_by_hand():
    """D = 0.5, v_max 10, a_max 1, T = 1, two of each family; the t_a = mT ones are
    triangles (a lowered to D / (mT)^2)."""
    got = list(sf._candidates(0.5, 10.0, 1.0, 1.0, 2))
    want = [(1.5, "coast: t_a + t_c = 1 T", 1.0, 0.5, 1.0),
            (2.25, "coast: t_a + t_c = 2 T", 1.0, 0.25, 2.0),
            (2.0, "acceleration: t_a = 1 T", 0.5, 1.0, 1.0),
            (4.0, "acceleration: t_a = 2 T", 0.125, 2.0, 2.0)]
    assert len(got) == len(want)
    for g_, w_ in zip(got, want):
        assert g_[1] == w_[1]
        assert np.allclose(g_[:1] + g_[2:], w_[:1] + w_[2:], rtol=0, atol=TOL)
    # the speed limit lowers the acceleration of the t_a = mT family: a = v / (mT)
    got = list(sf._candidates(3.0, 0.4, 1.0, 1.0, 2))
    assert [c[1] for c in got] == ["acceleration: t_a = 1 T", "acceleration: t_a = 2 T"]
    assert np.allclose(got[0][2:], [0.4, 1.0, 7.5], rtol=0, atol=TOL)
    assert np.allclose(got[1][2:], [0.2, 2.0, 7.5], rtol=0, atol=TOL)


def test_own_gravity_and_the_number_of_candidates():
    """g = 4 pi^2 on l = 1: T = 1 s again (the coast-family case). With n_max = 1 the
    D = 3 move has only t_a = T (4 s)."""
    r = sf.min_time_swing_free(3.0, 10.0, 1.0, 1.0, g=4 * np.pi**2)
    check(r, 3.5, "coast: t_a + t_c = 2 T", 1.0, 1.5, 0.5, 3.0, length=1.0,
          g=4 * np.pi**2)
    r = sf.min_time_swing_free(3.0, 10.0, 1.0, L1, n_max=1)
    assert r["family"] == "acceleration: t_a = 1 T" and r["time_s"] == pytest.approx(4.0)
    # the search stops at n = 200 by default: D = 201 at v_max 1 cannot coast 201 T
    r = sf.min_time_swing_free(201.0, 1.0, 100.0, L1)
    assert r["family"] == "acceleration: t_a = 1 T"
    assert sf.min_time_swing_free(201.0, 1.0, 100.0, L1, n_max=201)["family"] == \
        "coast: t_a + t_c = 201 T"
    # a long move needs a large n: D = 150, v_max = 1, a_max = 100: s = 150T, n = 150
    r = sf.min_time_swing_free(150.0, 1.0, 100.0, L1)
    assert r["family"] == "coast: t_a + t_c = 150 T"
    assert r["time_s"] == pytest.approx(150.01, abs=1e-9)


@pytest.mark.parametrize("args", [(0, 1, 1, 1), (1, 0, 1, 1), (1, 1, 0, 1), (1, 1, 1, 0),
                                  (-1, 1, 1, 1), (1, -1, 1, 1), (1, 1, -1, 1),
                                  (1, 1, 1, -1)])
def test_min_time_refuses_bad_input(args):
    with pytest.raises(ModelError, match=r"^a swing-free move needs positive distance, "
                       r"v_max, a_max and length \(got "):
        sf.min_time_swing_free(*args)


@pytest.mark.parametrize("args", [(0, 1, 1), (1, 0, 1), (1, 1, 0), (-1, 1, 1),
                                  (1, -1, 1), (1, 1, -1)])
def test_energy_optimal_refuses_bad_input(args):
    with pytest.raises(ModelError, match=r"^an energy-optimal move needs positive "
                       r"distance, duration and length \(got "):
        sf.energy_optimal_swing_free(*args)


def test_energy_optimal_accepts_small_positive_input():
    """Distance, duration and length below 1 (0.5 m in 0.8 s on 0.5 m): at rest at D."""
    r = sf.energy_optimal_swing_free(0.5, 0.8, 0.5)
    assert float(r["position"](0.8)) == pytest.approx(0.5, rel=1e-9)
    assert abs(float(r["speed"](0.8))) < 1e-9


def test_energy_optimal_long_move_keeps_its_constraints():
    """T = 40 s on a 1 m pendulum (w T = 125 rad): at rest at D and no sway, checked by a
    300-node Gauss-Legendre rule of the returned acceleration (converged to round-off up
    to w T ~ 200: 1e-13 against the closed-form integrals)."""
    D, T, length = 5.0, 40.0, 1.0
    r = sf.energy_optimal_swing_free(D, T, length)
    w = np.sqrt(G / length)
    x, wq = np.polynomial.legendre.leggauss(300)
    t, wq = 0.5 * T * (x + 1), 0.5 * T * wq
    a = r["acceleration"](t)
    scale = np.sum(wq * np.abs(a))
    assert abs(np.sum(wq * a)) < 1e-9 * scale                       # speed back to 0
    assert np.sum(wq * (T - t) * a) == pytest.approx(D, rel=1e-9)    # the distance
    for f in (np.cos, np.sin):
        assert abs(np.sum(wq * a * f(w * t))) < 1e-9 * scale          # no sway


# ------------------------------------------------------------------ energy optimal

def test_classic_energy_optimal_move_by_hand():
    D, T = 5.0, 8.0
    r = sf.energy_optimal_swing_free(D, T, 4.0, swing_free=False)
    c = 6 * D / T**2
    t = np.array([0.0, 1.0, 2.5, 4.0, 6.0, 8.0])
    assert np.allclose(r["acceleration"](t), c * (1 - 2 * t / T), rtol=0, atol=TOL)
    assert np.allclose(r["speed"](t), c * (t - t**2 / T), rtol=0, atol=TOL)
    assert np.allclose(r["position"](t), c * (t**2 / 2 - t**3 / (3 * T)), rtol=0, atol=TOL)
    assert np.allclose(r["coefficients"], [-c, 2 * c / T, 0, 0], rtol=0, atol=TOL)
    assert r["cost"] == pytest.approx(12 * D**2 / T**3, rel=1e-12)
    assert r["peak_speed"] == pytest.approx(1.5 * D / T, rel=1e-12)       # t = T/2 on the grid
    assert r["peak_acceleration"] == pytest.approx(c, rel=1e-12)
    assert r["duration_s"] == T
    tab = r["table"](4)
    s = np.linspace(0, T, 5)
    assert np.allclose(tab["times"], s, rtol=0, atol=TOL)
    assert np.allclose(tab["values"], c * (s - s**2 / T), rtol=0, atol=TOL)
    assert np.allclose(tab["positions"], c * (s**2 / 2 - s**3 / (3 * T)), rtol=0, atol=TOL)
    assert len(r["table"]()["times"]) == 201


@lru_cache(maxsize=None)
def _optimal_ref(D, T, length, g):
    """The coefficients of a = l1 + l2 (T - t) + l3 cos wt + l4 sin wt from the Gram
    system <g_k, g_l> lambda = (0, D, 0, 0) by mpmath quadrature, 25 digits."""
    mp.mp.dps = 25
    w = mp.sqrt(mp.mpf(g) / length)
    T = mp.mpf(T)
    basis = [lambda t: 1, lambda t: T - t, lambda t: mp.cos(w * t), lambda t: mp.sin(w * t)]
    Gm = mp.matrix(4, 4)
    for i in range(4):
        for j in range(4):
            Gm[i, j] = mp.quad(lambda t: basis[i](t) * basis[j](t), [0, T / 2, T])
    lam = mp.lu_solve(Gm, mp.matrix([0, D, 0, 0]))

    def a(t):
        return sum(lam[k] * basis[k](t) for k in range(4))
    ts = [0.0, 0.7, 2.5, 4.1, 7.9]
    v = [float(mp.quad(a, [0, t])) if t else 0.0 for t in ts]
    s = [float(mp.quad(lambda u: (t - u) * a(u), [0, t])) if t else 0.0 for t in ts]
    cost = float(mp.quad(lambda t: a(t)**2, [0, T / 2, T]))
    return np.array([float(x) for x in lam]), ts, v, s, cost


def _acc(lam, w, T, t):
    return lam[0] + lam[1] * (T - t) + lam[2] * np.cos(w * t) + lam[3] * np.sin(w * t)


@pytest.mark.parametrize("length, g", [(4.0, G), (2.0, 1.62)])
def test_swing_free_energy_optimal_move(length, g):
    D, T = 5.0, 8.0
    r = (sf.energy_optimal_swing_free(D, T, length) if g == G
         else sf.energy_optimal_swing_free(D, T, length, g=g))
    lam, ts, v, s, cost = _optimal_ref(D, T, length, g)
    w = np.sqrt(g / length)
    scale = np.abs(lam).max()
    assert np.allclose(r["coefficients"], lam, rtol=0, atol=1e-9 * scale)
    ts = np.array(ts)
    assert np.allclose(r["acceleration"](ts), _acc(lam, w, T, ts), rtol=0, atol=1e-9 * scale)
    assert np.allclose(r["speed"](ts), v, rtol=0, atol=1e-9 * D)
    assert np.allclose(r["position"](ts), s, rtol=0, atol=1e-9 * D)
    assert r["cost"] == pytest.approx(cost, rel=1e-9)
    # the constraints on the returned functions: at rest at D, no sway (Duhamel)
    assert abs(float(r["speed"](T))) < 1e-9 * D and float(r["position"](T)) == \
        pytest.approx(D, rel=1e-9)
    x, wq = np.polynomial.legendre.leggauss(200)
    t, wq = 0.5 * T * (x + 1), 0.5 * T * wq
    for f in (np.cos, np.sin):
        assert abs(np.sum(wq * r["acceleration"](t) * f(w * t))) < 1e-9 * scale * T
    fine = np.linspace(0, T, 200001)
    a = _acc(lam, w, T, fine)
    vel = np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * np.diff(fine))])
    assert r["peak_acceleration"] == pytest.approx(np.abs(a).max(), rel=1e-5)
    assert r["peak_speed"] == pytest.approx(np.abs(vel).max(), rel=1e-5)
    tab = r["table"](3)
    sg = np.linspace(0, T, 4)
    assert np.allclose(tab["times"], sg, rtol=0, atol=TOL)
    assert np.allclose(tab["values"], r["speed"](sg), rtol=0, atol=TOL)
    assert np.allclose(tab["positions"], r["position"](sg), rtol=0, atol=TOL)
    assert np.allclose(r["position"](ts[1:3]), s[1:3], rtol=0, atol=1e-9 * D)


@pytest.mark.parametrize("w, T", [(9.9, 20.0), (1.5, 8.0), (0.01, 5.0), (0.3, 0.2), (0.5, 1.6)])
def test_gram_matrix_against_quadrature(w, T):
    """The closed-form Gram matrix of (1, T - t, cos w t, sin w t) against mpmath's
    quadrature at 20 digits (a piece per ~6 rad of w t): a 0.1 m sling over 20 s (w T =
    198, where a Gauss rule of too few nodes went wrong), a usual move, and two short
    ones (w T = 0.05 and 0.06, where 1 - cos and x - sin x lose every digit unless
    written without cancellation), and w T = 0.8, 2 w T = 1.6 (past the series' range 0.1:
    its truncation there would be 1e-7): each entry to 1e-12 of itself (sin(198) in double
    precision carries 1e-16 absolute, 2e-13 of the smallest entry there)."""
    G = sf._gram(w, T)
    ref = np.zeros((4, 4))
    with mp.workdps(20):
        wm, Tm = mp.mpf(w), mp.mpf(T)
        basis = [lambda t: 1, lambda t: Tm - t, lambda t: mp.cos(wm * t),
                 lambda t: mp.sin(wm * t)]
        pieces = mp.linspace(0, Tm, int(w * T / 6) + 2)
        for i in range(4):
            for j in range(i, 4):
                ref[i, j] = ref[j, i] = float(
                    mp.quad(lambda t: basis[i](t) * basis[j](t), pieces))
    np.testing.assert_allclose(G, ref, rtol=1e-12, atol=0)
