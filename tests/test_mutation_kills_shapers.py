"""Value tests of the input shapers (cranefe/analysis/shaping/shapers.py; issue 20,
mutation testing).

Reference: the residual vibration of an impulse train in Singhose, Seering & Singer's
real form (1994, eq. 1-3), written here independently of the code's complex sum:

    V(w, zeta) = exp(-zeta w t_N) sqrt(C^2 + S^2),
    C = sum A_i exp(zeta w t_i) cos(w_d t_i),  S = sum A_i exp(zeta w t_i) sin(w_d t_i),

w_d = w sqrt(1 - zeta^2); its w-derivative by central differences. The convolution of
two ZV shapers is the ZVD shaper (binomial amplitudes [1, 2K, K^2] / (1 + K)^2), and the
residual of a convolution of undamped shapers is the product of their residuals. The
damped EI shaper is checked by its defining conditions (V at the design frequency, a
zero slope there, zero residual on either side).

Tolerances: V by two formulas agrees to 1e-13 (sums of a few O(1) exponentials);
central differences with h = 1e-6: truncation h^2/6 |V'''| ~ 1e-12, round-off
1e-16 / h ~ 1e-10: bound 1e-8; the EI's conditions are solved to 1e-12 (its fsolve check).
"""

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from cranefe.analysis.shaping import shapers as sh
from cranefe.errors import AnalysisError, ModelError


def v_ref(times, amps, w, zeta):
    wd = w * np.sqrt(1 - zeta**2)
    e = amps * np.exp(zeta * w * times)
    C, S = np.sum(e * np.cos(wd * times)), np.sum(e * np.sin(wd * times))
    return np.exp(-zeta * w * times[-1]) * np.hypot(C, S)


def dv_ref(times, amps, w, zeta, h=1e-6):
    return (v_ref(times, amps, w + h, zeta) - v_ref(times, amps, w - h, zeta)) / (2 * h)


def test_residual_and_its_derivative_with_a_zeta_other_than_the_design():
    s = sh.zv(2.0, 0.1)
    for w in (1.3, 2.5):
        assert s.residual(w, zeta=0.3) == pytest.approx(v_ref(s.times, s.amplitudes, w, 0.3),
                                                        rel=1e-13)
        assert s.residual(w) == pytest.approx(v_ref(s.times, s.amplitudes, w, 0.1), rel=1e-13)
        assert s.residual_derivative(w, zeta=0.3) == pytest.approx(
            dv_ref(s.times, s.amplitudes, w, 0.3), abs=1e-8)
    # the slope |dZ/dw| at the design zero is the one-sided derivative of V there
    h = 1e-7
    for z in (0.1, 0.25):
        t = sh.zv(2.0, z)
        one_sided = v_ref(t.times, t.amplitudes, 2.0 + h, z) / h
        assert t.slope(2.0) == pytest.approx(one_sided, rel=1e-5)
    # at a frequency where V > 0, |dV/dw| <= |dZ/dw| (the docstring's bound), with zeta
    d = s.residual_derivative(2.5, zeta=0.3)
    assert abs(d) <= s.slope(2.5, zeta=0.3) * (1 + 1e-12)
    assert s.slope(2.5, zeta=0.3) != pytest.approx(s.slope(2.5), rel=1e-3)


def test_arrays_of_frequencies_give_each_frequency_its_own_value():
    s = sh.zvd(1.0, 0.05)
    w = np.array([0.7, 1.6, 2.2])
    for f in (s.residual, s.residual_derivative, s.slope):
        vals = f(w)
        assert vals.shape == (3,)
        assert np.allclose(vals, [f(x) for x in w], rtol=1e-14, atol=0)
    assert np.allclose(s.residual(w), [v_ref(s.times, s.amplitudes, x, 0.05) for x in w],
                       rtol=1e-13)
    assert np.allclose(s.residual_derivative(w),
                       [dv_ref(s.times, s.amplitudes, x, 0.05) for x in w], atol=1e-8)


def test_bad_design_values_are_model_errors():
    with pytest.raises(ModelError, match=r"frequency must be positive \(got 0.0 rad/s\)"):
        sh.zv(0.0)
    for z in (1.0, 1.5, -0.1):
        with pytest.raises(ModelError, match=r"damping ratio must lie in \[0, 1\) \(got "):
            sh.zvd(1.0, z)
    for V in (0.0, 1.0):
        with pytest.raises(ModelError, match=r"EI's tolerable vibration V must lie in"):
            sh.ei(1.0, 0.0, V)
    with pytest.raises(ModelError, match=r"^unknown shaper 'XY': use one of unshaped, ZV, "
                                         r"ZVD, ZVDD, EI$"):
        sh.make("XY", 1.0)


def test_names_and_design_values_are_kept():
    for name, f in (("ZV", sh.zv), ("ZVD", sh.zvd), ("ZVDD", sh.zvdd), ("EI", sh.ei)):
        for z in (0.0, 0.2):
            s = f(2.0, z)
            assert s.name == name and s.omega == 2.0 and s.zeta == z
            assert sh.make(name, 2.0, z).name == name
    assert sh.make("ZVD", 2.0).zeta == 0.0                 # undamped by default
    u = sh.make("unshaped", 3.0)
    assert u.name == "unshaped" and u.times.tolist() == [0.0]
    assert u.amplitudes.tolist() == [1.0] and u.duration == 0.0
    assert u.residual(1.7, zeta=0.2) == pytest.approx(1.0, rel=1e-15)


def test_make_passes_the_options():
    s = sh.make("EI", 2.0, 0.0, V=0.1)
    assert np.allclose(s.amplitudes, [1.1 / 4, 0.9 / 2, 1.1 / 4], rtol=1e-15)
    assert s.residual(2.0) == pytest.approx(0.1, rel=1e-12)


@pytest.mark.parametrize("zeta, upper", [(0.3, 1.6), (0.6, 4.0)])
def test_damped_ei_meets_its_conditions(zeta, upper):
    """(The zero above w moves out to about 3.4 w at zeta = 0.6: a scan of V shows no
    other local minimum below 4 w.)"""
    w, V = 2.0, 0.05
    s = sh.ei(w, zeta, V)
    assert s.name == "EI" and s.omega == w and s.zeta == zeta
    t, A = s.times, s.amplitudes
    assert A.sum() == pytest.approx(1.0, rel=1e-14) and (A > 0).all()
    assert t[0] == 0.0 and 0 < t[1] < t[2] <= 2 * np.pi / (w * np.sqrt(1 - zeta**2))
    assert v_ref(t, A, w, zeta) == pytest.approx(V, rel=1e-9)
    assert abs(dv_ref(t, A, w, zeta)) < 1e-7
    # a local maximum at w with a zero of V on either side
    for lo, hi in ((0.4 * w, w), (w, upper * w)):
        r = minimize_scalar(lambda x: v_ref(t, A, x, zeta), bounds=(lo, hi),
                            method="bounded", options={"xatol": 1e-12})
        assert r.fun < 1e-6 and lo + 1e-3 < r.x < hi - 1e-3


def test_two_zv_convolved_are_the_zvd():
    for z in (0.0, 0.1):
        c = sh.convolve(sh.zv(1.5, z), sh.zv(1.5, z))
        d = sh.zvd(1.5, z)
        assert c.name == "ZV*ZV" and c.zeta == z and np.isnan(c.omega)
        assert np.allclose(c.times, d.times, rtol=0, atol=1e-14)
        assert np.allclose(c.amplitudes, d.amplitudes, rtol=1e-14, atol=0)
    assert sh.convolve(sh.zv(1.5), sh.zv(1.5), name="two").name == "two"


def test_convolution_of_two_modes_multiplies_their_residuals():
    a, b = sh.zv(1.0), sh.zvd(2.7)
    c = sh.convolve(a, b)
    assert len(c.times) == 6
    assert np.allclose(c.times, np.sort((a.times[:, None] + b.times[None, :]).ravel()),
                       rtol=0, atol=1e-14)
    for w in (0.6, 1.0, 1.9, 2.7, 4.0):
        assert c.residual(w) == pytest.approx(a.residual(w) * b.residual(w), abs=1e-14)
        assert c.residual(w) == pytest.approx(v_ref(c.times, c.amplitudes, w, 0.0),
                                              abs=1e-14)
    # the damping ratio of the first factor is the convolution's
    assert sh.convolve(sh.zv(1.0, 0.1), sh.zv(2.0, 0.0)).zeta == 0.1
    assert sh.convolve(sh.zv(1.0, 0.0), sh.zv(2.0, 0.1)).zeta == 0.0
    e = sh.convolve()
    assert e.times.tolist() == [0.0] and e.amplitudes.tolist() == [1.0] and e.zeta == 0.0


def test_heavily_damped_ei_that_newton_cannot_find_is_an_error():
    """At zeta = 0.9 the continuation's fsolve stalls (no EI train with V = 0.05 found):
    an AnalysisError, not a train that misses its conditions."""
    with np.errstate(over="ignore", invalid="ignore"):
        with pytest.raises(AnalysisError, match=r"^no EI shaper found for zeta = 0.9, "
                                                r"V = 0.05: "):
            sh.ei(1.0, 0.9, 0.05)
