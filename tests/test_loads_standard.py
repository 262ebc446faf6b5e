"""EN 13001-2 dynamic factors (cranefe.analysis.loads.standard) and the exact
single-mass references (cranefe.analysis.loads.sdof) against tightly integrated ODEs.

Tolerances: the ODEs are integrated by DOP853 at rtol 1e-10/atol 1e-13 on O(1) scaled
variables, with the peaks located by events, so agreement to 1e-8 is the integrator's
error with margin; the standard's values are data and compare exactly (or to 1e-15
round-off).
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from cranefe.analysis.loads import sdof, standard
from cranefe.errors import ModelError

TOL = dict(method="DOP853", rtol=1e-10, atol=1e-13)


def _peak(rhs, y0, t_span):
    """The largest y[0] over t_span: at the events y[1] = 0 (and at the ends)."""
    sol = solve_ivp(rhs, t_span, y0, events=lambda t, y: y[1], **TOL)
    return max([y[0] for y in sol.y_events[0]] + [sol.y[0, -1], y0[0]])


def test_standard_tables():
    assert standard.phi2("HC1", 0.0) == 1.05
    assert standard.phi2("HC4", 1.0) == pytest.approx(1.88, abs=1e-15)
    np.testing.assert_allclose(standard.phi2("HC2", [0.0, 0.5]), [1.10, 1.27], atol=1e-15)
    assert standard.phi1(0.1) == (1.1, 0.9)
    assert standard.phi3(0.5, "fast") == 0.0 and standard.phi3(0.5, "slow") == 0.25
    assert standard.phi6(1.3) == pytest.approx(1.15) and standard.phi6(test="static") == 1
    assert standard.phi7(0.5) == 1.25 and standard.phi7(1.0) == pytest.approx(1.6)
    assert standard.phi5_guidance(backlash=True)[:2] == (3.0, 3.0)
    assert standard.phi5_guidance(sudden=True)[:2] == (1.5, 2.0)
    assert standard.phi5_guidance()[:2] == (1.0, 1.5)
    assert set(standard.CLAUSES) == {f"phi{i}" for i in range(1, 8)}


def test_characteristic_speed_per_drive_class():
    cs = standard.characteristic_speed
    assert cs("HD1", 1.0) == 1.0
    assert cs("HD2", 1.0, 0.1) == 0.1 and cs("HD3", 1.0, 0.1) == 0.1
    assert cs("HD4", 1.0) == 0.5 and cs("HD5", 1.0) == 0.0
    assert cs("HD2", 1.0, 0.1, "C1") == 1.0 and cs("HD5", 1.0, None, "C1") == 0.5
    assert cs("HD1", 1.0, None, "C1") is None
    with pytest.raises(ModelError, match="creep"):
        cs("HD2", 1.0)
    with pytest.raises(ModelError, match="HD1"):
        cs("HD9", 1.0)


def test_bad_values_are_model_errors():
    for call in (lambda: standard.phi1(0.2), lambda: standard.phi2("HC5", 1.0),
                 lambda: standard.phi3(1.5), lambda: standard.phi7(1.2)):
        with pytest.raises(ModelError):
            call()


def test_behaves_like():
    v = np.array([0.125, 0.25, 0.5, 1.0])
    r = standard.behaves_like(v, 1.12 + 0.4 * v)      # above HC2's line, below HC3's
    assert r["within"] == "HC3" and r["excess"]["HC3"] == pytest.approx(-0.03 - 0.11 * 0.125)
    stiff = [1.188, 1.376, 1.753, 2.506]              # docs/transient.md, two-mass hoist
    r = standard.behaves_like(v, stiff)
    assert r["within"] is None and r["closest"] == "HC4"


def test_buffer_characteristic():
    u = np.linspace(0, 0.2, 11)
    assert standard.buffer_characteristic(u, 5e4 * u) == pytest.approx(0.5, abs=1e-15)
    assert standard.buffer_characteristic(u, np.full_like(u, 3e3)) == pytest.approx(1.0)
    m, v, k = 2e4, 1.0, 5e5           # linear buffer: energy m v^2/2 = F^2/(2k)
    F = sdof.buffer_peak_force(m, v, k)
    assert F**2 / (2 * k) == pytest.approx(0.5 * m * v**2, rel=1e-15)


@pytest.mark.parametrize("t_r", [0.0, 0.3, 1.0, 2.2, 4 * np.pi / 3.0])
def test_phi5_ramp_against_ode(t_r):
    w, a = 3.0, 1.0                   # x'' + w^2 x = a(t), static x = a / w^2
    f = (lambda t: a) if t_r == 0 else (lambda t: a * min(t / t_r, 1.0))
    rhs = lambda t, y: [y[1], f(t) - w * w * y[0]]
    y = solve_ivp(rhs, (0, t_r), [0.0, 0.0], **TOL).y[:, -1] if t_r else np.zeros(2)
    peak = _peak(rhs, y, (t_r, t_r + 2 * np.pi / w * 1.5))
    assert peak * w * w / a == pytest.approx(sdof.phi5_ramp(w, t_r), abs=1e-8)
    t = np.linspace(0, t_r + 3, 7)
    ref = solve_ivp(rhs, (0, t[-1]), [0.0, 0.0], t_eval=t, **TOL).y[0] * w * w / a
    np.testing.assert_allclose(sdof.ramp_response(w, t_r, t), ref, atol=1e-8)


def test_phi5_limits():
    assert sdof.phi5_ramp(2.0, 0.0) == 2.0
    assert sdof.phi5_ramp(2.0, 2 * np.pi / 2.0) == pytest.approx(1.0, abs=1e-15)  # t_r = T


@pytest.mark.parametrize("v", [0.1, 0.5, 1.0])
def test_phi2_rigid_drive_against_ode(v):
    m, k, g = 5000.0, 4e6, 9.81           # rope end at v t; lift-off at k v t = m g
    w = np.sqrt(k / m)
    t_l = m * g / (k * v)
    rhs = lambda t, y: [y[1], (k * (v * (t + t_l) - y[0]) - m * g) / m]
    sol = solve_ivp(rhs, (0, 2 * np.pi / w), [0.0, 0.0],
                    events=lambda t, y: v - y[1], **TOL)
    S = max(k * (v * (t + t_l) - y[0]) for t, y in zip(sol.t_events[0], sol.y_events[0]))
    assert S / (m * g) == pytest.approx(sdof.phi2_rigid_drive(v, w, g), abs=1e-8)


def _release(m, dm, k, t_r, g=9.81):
    mr = m - dm                           # remaining mass; the released part's force ramps
    F = (lambda t: 0.0) if t_r == 0 else (lambda t: dm * g * max(1 - t / t_r, 0.0))
    rhs = lambda t, y: [y[1], (mr * g + F(t) - k * y[0]) / mr]
    T = 2 * np.pi * np.sqrt(mr / k)
    sol = solve_ivp(rhs, (0, t_r + 2 * T), [m * g / k, 0.0], events=lambda t, y: y[1],
                    dense_output=True, **TOL)
    x = [y[0] for t, y in zip(sol.t_events[0], sol.y_events[0]) if t > t_r]
    assert len(x) >= 3                    # both extremes of the free swing after release
    return k * min(x) / (m * g), k * max(x) / (m * g)


@pytest.mark.parametrize("frac", [0.2, 0.5, 0.8])
def test_phi3_sudden_against_ode(frac):
    m, k = 1000.0, 2e5
    lo, hi = _release(m, frac * m, k, 0.0)
    ref_lo, ref_hi = sdof.phi3_sudden(frac)
    assert lo == pytest.approx(ref_lo, abs=1e-8) and hi == pytest.approx(ref_hi, abs=1e-8)
    assert ref_lo == pytest.approx(standard.phi3(frac, "fast"), abs=1e-15)


@pytest.mark.parametrize("t_r", [0.05, 0.2, 0.6])
def test_phi3_linear_release_against_ode(t_r):
    m, dm, k = 1000.0, 400.0, 2e5
    w = np.sqrt(k / (m - dm))
    lo, hi = _release(m, dm, k, t_r)
    ref_lo, ref_hi = sdof.phi3_linear_release(dm / m, w, t_r)
    assert lo == pytest.approx(ref_lo, abs=1e-8)
    assert hi == pytest.approx(ref_hi, abs=1e-8)


def test_beta3_slow_release_time():
    # beta3 = 0.5 of the standard is a linear release over 0.603 periods of the remaining mass
    th = brentq(lambda x: np.sin(x) / x - 0.5, 1.0, 3.0)
    w = 2.0
    t_r = 2 * th / w
    assert t_r / (2 * np.pi / w) == pytest.approx(0.6034, abs=1e-4)
    assert sdof.phi3_linear_release(0.3, w, t_r)[0] == pytest.approx(
        standard.phi3(0.3, "slow"), abs=1e-14)
