"""Kill tests for cranefe/analysis/luffing/sway.py (tools/mutation.py luffing_sway;
docs/mutation.md): the load's sway under a jib tip on a circle, against references that
do not use the module: the paper's model in closed form (psi = -(x - x0) / H), the linear
and nonlinear pendulums integrated from the tip's motion written out by hand, the linear
residual swing as a 30-digit quadrature, and the swing-free law checked against its own
definition (no residual swing, its end angles, its Euler-Lagrange equation).

Geometry: a boom of length L hinged at the origin, tip x = L cos(alpha), z = L sin(alpha);
reduced inertia J(alpha) = 2 + cos(alpha), own-axis part Jp = 3 + cos(alpha) (any positive
functions serve: the module reads them only through the proxy).
"""

from functools import lru_cache

import mpmath as mp
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from cranefe.analysis.luffing.laws import standard_law
from cranefe.analysis.luffing.optimum import LawSolution
from cranefe.analysis.luffing.sway import (KINDS, TipMotion, residual_linear_exact,
                                           simulate, swing_free_law)

L, H, G, TK = 20.0, 12.0, 9.81, 8.0
A0, AK = np.radians(70.0), np.radians(30.0)


class _Proxy:
    def __call__(self, key, a):
        a = np.asarray(a, dtype=float)
        return {"dx": -L * np.sin(a), "ddx": -L * np.cos(a), "dz": L * np.cos(a),
                "ddz": -L * np.sin(a), "J": 2 + np.cos(a), "dJ": -np.sin(a),
                "Jp": 3 + np.cos(a), "dJp": -np.sin(a)}[key]


def _tip(name, t):
    """x, z and their first and second time derivatives at t by hand."""
    law = standard_law(name, A0, AK)
    a, d1, d2 = (v[0] for v in law.evaluate(t / TK))
    da, dda = d1 / TK, d2 / TK**2
    return (L * np.cos(a), L * np.sin(a), -L * np.sin(a) * da, L * np.cos(a) * da,
            -L * np.cos(a) * da**2 - L * np.sin(a) * dda,
            -L * np.sin(a) * da**2 + L * np.cos(a) * dda)


@lru_cache(maxsize=None)
def _pendulum(name, kind):
    """(psi, psi') at the stop and max |psi|, integrated from the hand tip (DOP853,
    rtol 1e-12; the largest |psi| at 201 samples), the start's jump psi'(0+) = -x'(0+)/H included."""
    def rhs(t, y):
        _, _, _, _, ax, az = _tip(name, t)
        if kind == "linear":
            return [y[1], -(G * y[0] + ax) / H]
        return [y[1], -(ax * np.cos(y[0]) + (G + az) * np.sin(y[0])) / H]
    y0 = [0.0, -_tip(name, 0.0)[2] / H]
    sol = solve_ivp(rhs, (0, TK), y0, method="DOP853", rtol=1e-12, atol=1e-14,
                    dense_output=True)
    ts = np.linspace(0, TK, 201)
    return sol.y[:, -1], float(np.abs(sol.sol(ts)[0]).max())


@lru_cache(maxsize=None)
def _residual_quad(name):
    """|int_0^t_k x'(t) e^(-i w t) dt| / H in mpmath (the law's breaks as pieces)."""
    w = mp.sqrt(mp.mpf(G) / H)
    edges = [0.0, 0.2 * TK, 0.8 * TK, TK] if name == "trapezoidal" else [0.0, TK]
    f = lambda t: _tip(name, float(t))[2] * mp.expj(-w * t)  # noqa: E731
    return float(abs(mp.quad(f, edges)) / H)


@pytest.mark.parametrize("name", ["linear", "cubic", "trapezoidal"])
def test_tip_motion_by_hand(name):
    """The Chebyshev interpolants give the tip's velocity and acceleration to 1e-11 m/s
    (exact to ~1e-13 per the module); a linear law starts and stops with a speed."""
    law = standard_law(name, A0, AK)
    tip = TipMotion(law, _Proxy(), TK)
    for t in (0.0, 0.7, 1.5, 3.3, 6.5, 7.9, TK):     # off the breaks 1.6, 6.4
        ref = _tip(name, t)
        np.testing.assert_allclose(tip(t), ref[2:], rtol=0, atol=1e-11)
    np.testing.assert_allclose(tip.v_start, _tip(name, 0.0)[2:4], atol=1e-11)
    np.testing.assert_allclose(tip.v_end, _tip(name, TK)[2:4], atol=1e-11)
    assert tip.edges == ([0.0, 1.6, 6.4, TK] if name == "trapezoidal" else [0.0, TK])
    np.testing.assert_allclose(tip.sample([0.7, 3.3]),
                               [_tip(name, 0.7)[2:], _tip(name, 3.3)[2:]], atol=1e-11)
    assert abs(tip.v_start[0]) > 1 if name == "linear" else abs(tip.v_start[0]) < 1e-9


def test_the_papers_model_in_closed_form():
    """H psi'' = -x'' from psi = 0, psi' = -x'(0+)/H: psi = -(x - x0)/H exactly, no
    restoring force (residual nan) and the load at rest relative to the ground after
    the stop: psi' + x'(t_k)/H = 0."""
    law = standard_law("linear", A0, AK)
    out = simulate(TipMotion(law, _Proxy(), TK), H, G, "paper", samples=81)
    x0 = L * np.cos(A0)
    ref = np.array([-(_tip("linear", t)[0] - x0) / H for t in out["t"]])
    np.testing.assert_allclose(out["psi"], ref, rtol=0, atol=1e-9)
    dref = np.array([-_tip("linear", t)[2] / H for t in out["t"]])
    np.testing.assert_allclose(out["dpsi"], dref, rtol=0, atol=1e-9)
    assert np.isnan(out["residual"])
    assert out["max"] == pytest.approx(np.abs(ref).max(), abs=1e-9)
    assert out["end"][0] == pytest.approx(ref[-1], abs=1e-9)
    assert abs(out["end"][1]) < 1e-9


@pytest.mark.parametrize("name", ["linear", "cubic", "trapezoidal"])
@pytest.mark.parametrize("kind", ["linear", "nonlinear"])
def test_pendulums_against_a_hand_integration(name, kind):
    """End state, largest sway and residual swing to 1e-8 rad (both integrations at
    rtol 1e-11..1e-12). The residual: linear sqrt(psi^2 + (psi'/w)^2), nonlinear from
    the energy 1/2 (psi'/w)^2 + 1 - cos(psi) = 1 - cos(residual), with the stop's jump
    psi' += (x' cos psi + z' sin psi)/H (linear: x'/H); linear also against the
    30-digit quadrature |int x' e^(-i w t) dt| / H."""
    law = standard_law(name, A0, AK)
    out = simulate(TipMotion(law, _Proxy(), TK), H, G, kind, samples=201)
    (p, dp), mx = _pendulum(name, kind)
    _, _, vx, vz, _, _ = _tip(name, TK)
    w = np.sqrt(G / H)
    if kind == "linear":
        dp = dp + vx / H
        res = np.hypot(p, dp / w)
        assert res == pytest.approx(_residual_quad(name), abs=1e-8)
    else:
        dp = dp + (vx * np.cos(p) + vz * np.sin(p)) / H
        res = np.arccos(1 - (0.5 * (dp / w) ** 2 + 1 - np.cos(p)))
    assert out["end"] == pytest.approx((p, dp), abs=1e-8)
    assert out["residual"] == pytest.approx(res, abs=1e-8)
    assert out["max"] == pytest.approx(mx, abs=1e-8)
    assert out["t"][-1] == TK and len(out["psi"]) == 201
    assert res > 1e-3                                    # the cases do swing
    assert KINDS == ("linear", "nonlinear", "paper")


@pytest.mark.parametrize("name", ["linear", "cubic", "trapezoidal"])
def test_residual_linear_exact_against_quadrature(name):
    law = standard_law(name, A0, AK)
    assert residual_linear_exact(law, _Proxy(), TK, H, G) == pytest.approx(
        _residual_quad(name), rel=1e-10)


@pytest.mark.parametrize("tk, over", [(0.14, True), (0.15, False)])
def test_a_swing_over_the_top_counts_as_pi(tk, over):
    """A 40 deg luff in 0.14 s throws the load over: end energy 2.06 m g H > 2 m g H,
    residual pi; in 0.15 s 1.87 m g H: residual arccos(1 - E) = 2.62 rad (E from the end
    state, which the test above checks against a hand integration)."""
    law = standard_law("linear", A0, AK)
    out = simulate(TipMotion(law, _Proxy(), tk), H, G, "nonlinear", samples=11)
    p, dp = out["end"]
    E = 0.5 * (dp / np.sqrt(G / H)) ** 2 + 1 - np.cos(p)
    assert (E > 2) == over and abs(E - 2) > 0.05
    assert out["residual"] == (np.pi if over else pytest.approx(np.arccos(1 - E), abs=1e-12))


@pytest.mark.parametrize("which, j", [("complete", "J"), ("own", "Jp")])
def test_swing_free_law_meets_its_definition(which, j):
    """No residual swing of the linear model (the 30-digit-checked quadrature, < 1e-7
    rad against 0.05 rad of the cubic guess), the end angles, and the Euler-Lagrange
    equation J a.. + 1/2 J' a.^2 = mu. x_a with mu = l1 cos(W tau) + l2 sin(W tau) from the
    reported multipliers (to 1e-5 of its terms: the collocation tolerance 1e-9)."""
    guess = standard_law("cubic", A0, AK)
    p = _Proxy()
    law = swing_free_law(p, A0, AK, TK, H, G, guess, which=which)
    assert law.status == 0 and law.name == "swing-free"
    # what the luffing report shows of the solve (analysis.py: status, message,
    # iterations, nodes, time)
    assert isinstance(law.message, str) and law.message
    assert law.iterations >= 1 and law.evaluations == 0 and 0 < law.time_s < 600
    assert law.info["nodes"] >= 81
    assert residual_linear_exact(guess, p, TK, H, G) > 0.05
    assert residual_linear_exact(law, p, TK, H, G) < 1e-7
    W = np.sqrt(G / H) * TK
    assert law.info["W"] == pytest.approx(W, rel=1e-15)
    tau = np.linspace(0, 1, 41)
    a, da, dda = law.evaluate(tau)
    assert a[0] == pytest.approx(A0, abs=1e-9) and a[-1] == pytest.approx(AK, abs=1e-9)
    l1, l2 = law.info["multipliers"]
    dmu = W * (-l1 * np.sin(W * tau) + l2 * np.cos(W * tau))
    lhs = p(j, a) * dda + 0.5 * p("d" + j, a) * da**2
    scale = np.abs(p(j, a) * dda).max()
    np.testing.assert_allclose(lhs, dmu * p("dx", a), rtol=0, atol=1e-5 * scale)
    # alpha. is the derivative of alpha (central differences, h = 1e-5)
    h = 1e-5
    mid = tau[1:-1]
    fd = (law.evaluate(mid + h)[0] - law.evaluate(mid - h)[0]) / (2 * h)
    np.testing.assert_allclose(law.evaluate(mid)[1], fd, rtol=0, atol=1e-6)


def test_swing_free_law_uses_the_complete_inertia_by_default():
    guess = standard_law("cubic", A0, AK)
    law = swing_free_law(_Proxy(), A0, AK, TK, H, G, guess)
    ref = swing_free_law(_Proxy(), A0, AK, TK, H, G, guess, which="complete")
    np.testing.assert_allclose(law.info["multipliers"], ref.info["multipliers"], rtol=1e-12)


def test_tip_motion_at_its_edges():
    """At a break the left piece answers (the integration of [a, b] ends there with the
    acceleration from the left: the trapezoid accelerates up to t = 1.6 s); a time a
    round-off past the end answers the end (the Chebyshev variable clipped to 1, as
    before the start to -1); a law without breaks is one piece; the law is sampled
    only on [0, 1] (a law undefined outside, nan there, still gives a finite tip)."""
    tip = TipMotion(standard_law("trapezoidal", A0, AK), _Proxy(), TK)
    left, right = _tip("trapezoidal", 1.6 - 1e-9), _tip("trapezoidal", 1.6 + 1e-9)
    np.testing.assert_allclose(tip(1.6), left[2:], atol=1e-7)
    assert abs(tip(1.6)[2] - right[4]) > 0.1
    np.testing.assert_allclose(tip(TK + 1e-12), tip(TK), atol=1e-12)
    np.testing.assert_allclose(tip(-1e-12), tip(0.0), atol=1e-12)
    base = standard_law("cubic", A0, AK)

    def inside(tau):
        tau = np.atleast_1d(tau)
        a, d1, d2 = base.evaluate(tau)
        bad = (tau < 0) | (tau > 1)
        return np.where(bad, np.nan, a), np.where(bad, np.nan, d1), np.where(bad, np.nan, d2)

    tip = TipMotion(LawSolution("own", inside), _Proxy(), TK)     # info without breaks
    assert tip.edges == [0.0, TK]
    for t in (0.0, 3.3, TK):
        np.testing.assert_allclose(tip(t), _tip("cubic", t)[2:], atol=1e-11)


def test_simulate_samples_801_times_by_default():
    out = simulate(TipMotion(standard_law("cubic", A0, AK), _Proxy(), TK), H, G, "linear")
    assert len(out["t"]) == len(out["psi"]) == 801
