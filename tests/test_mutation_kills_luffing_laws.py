"""Kill tests for cranefe/analysis/luffing/laws.py (tools/mutation.py luffing_laws;
docs/mutation.md): the standard luffing laws by hand, the practical rest-to-rest law in the
energy coordinate against its closed form evaluated in mpmath, and the law in the boom
angle through a reduced inertia whose energy coordinate inverts by hand.

The law's definition (laws.py's docstring, docs/luffing.md): sigma(u) with sigma(0) = 0,
sigma(1) = 1, sigma'(0) = sigma'(1) = 0 and sigma'' = eps^2 sigma'''' (the Euler-Lagrange
equation of int 1/2 sigma'^2 + 1/2 eps^2 sigma''^2 du), so
sigma = 1/2 + B (u - 1/2) + C sinh((u - 1/2)/eps) with, Y = 1/(2 eps),
B + 2 C sinh Y = 1 and B + C cosh(Y)/eps = 0. Solved here in mpmath at 30 digits.
"""

from functools import lru_cache

import mpmath as mp
import numpy as np
import pytest

from cranefe.analysis.luffing.laws import (BREAKS, STANDARD, rest_to_rest_law,
                                           rest_to_rest_sigma, standard_law, standard_s)

TAU = np.array([0.0, 0.1, 0.2, 0.3, 0.5, 0.65, 0.8, 0.9, 1.0])


# s, s', s'' of each law at TAU, by hand from model-format.md's definitions
def _hand(name, t):
    t = mp.mpf(t)
    if name == "linear":
        return t, 1, 0
    if name == "cubic":
        return 3 * t**2 - 2 * t**3, 6 * t * (1 - t), 6 * (1 - 2 * t)
    if name == "quintic":
        return (t**3 * (10 - 15 * t + 6 * t**2), 30 * t**2 * (1 - t)**2,
                60 * t * (1 - t) * (1 - 2 * t))
    if name == "cycloidal":
        w = 2 * mp.pi
        return t - mp.sin(w * t) / w, 1 - mp.cos(w * t), w * mp.sin(w * t)
    # trapezoidal speed, 20 % accelerating: top speed 1/0.8 = 1.25, acceleration 6.25
    if t < mp.mpf("0.2"):
        return mp.mpf("3.125") * t**2, mp.mpf("6.25") * t, mp.mpf("6.25")
    if t <= mp.mpf("0.8"):
        return mp.mpf("0.125") + mp.mpf("1.25") * (t - mp.mpf("0.2")), mp.mpf("1.25"), 0
    return 1 - mp.mpf("3.125") * (1 - t)**2, mp.mpf("6.25") * (1 - t), -mp.mpf("6.25")


@pytest.mark.parametrize("name", STANDARD)
def test_standard_laws_by_hand(name):
    """Each law's s, s' and s'' at nine points, to 1e-14 (float round-off of terms <= 60);
    tau = 0.2 and 0.8 lie on the trapezoid's breaks, which take the cruise branch's
    value (continuous in s and s'; s'' the cruise's 0 at 0.8 and the acceleration's
    right limit 0 at 0.2 is the code's choice: `tau < ta`)."""
    s, ds, dds = standard_s(name, TAU)
    ref = np.array([[float(v) for v in _hand(name, t)] for t in TAU]).T
    np.testing.assert_allclose(s, ref[0], rtol=0, atol=1e-14)
    np.testing.assert_allclose(ds, ref[1], rtol=0, atol=1e-13)
    if name == "trapezoidal":        # at the breaks s'' is one-sided: compare elsewhere
        keep = ~np.isin(TAU, [0.2, 0.8])
        np.testing.assert_allclose(dds[keep], ref[2][keep], rtol=0, atol=1e-12)
        assert dds[TAU == 0.2] == 0.0 and dds[TAU == 0.8] == 0.0
    else:
        np.testing.assert_allclose(dds, ref[2], rtol=0, atol=1e-12)
    assert s.shape == ds.shape == dds.shape == TAU.shape


def test_an_unknown_law_is_refused():
    with pytest.raises(ValueError, match="unknown law 'sine'"):
        standard_s("sine", TAU)


@pytest.mark.parametrize("name", STANDARD)
def test_standard_law_in_the_boom_angle(name):
    """alpha = alpha0 + (alphak - alpha0) s: from 70 deg down to 20 deg (D < 0), a scalar
    tau gives arrays of one value; the trapezoid's breaks are reported."""
    a0, ak = np.radians(70.0), np.radians(20.0)
    law = standard_law(name, a0, ak)
    a, da, dda = law.evaluate(0.3)
    s, ds, dds = (float(v) for v in _hand(name, 0.3))
    D = ak - a0
    np.testing.assert_allclose([a[0], da[0], dda[0]], [a0 + D * s, D * ds, D * dds],
                               rtol=1e-14, atol=1e-15)
    assert law.name == name
    assert law.info == {"breaks": [0.2, 0.8] if name == "trapezoidal" else []}
    assert BREAKS == {"trapezoidal": (0.2, 0.8)}


@lru_cache(maxsize=None)
def _sigma_ref(eps):
    """(u, sigma, sigma', sigma'') at 11 points, 30 digits, from the boundary conditions."""
    with mp.workdps(30):
        e = mp.mpf(eps)
        Y = 1 / (2 * e)
        C = 1 / (2 * mp.sinh(Y) - mp.cosh(Y) / e)
        B = -C * mp.cosh(Y) / e
        u = [mp.mpf(k) / 10 for k in range(11)]
        out = [[float(x) for x in u],
               [float(mp.mpf(1) / 2 + B * (x - mp.mpf(1) / 2) + C * mp.sinh((x - mp.mpf(1) / 2) / e))
                for x in u],
               [float(B + C / e * mp.cosh((x - mp.mpf(1) / 2) / e)) for x in u],
               [float(C / e**2 * mp.sinh((x - mp.mpf(1) / 2) / e)) for x in u]]
    return tuple(np.array(v) for v in out)


@pytest.mark.parametrize("eps", [0.3, 0.05, 0.004])
def test_rest_to_rest_sigma_against_its_closed_form(eps):
    """sigma, sigma', sigma'' to 1e-12 of their scale (sigma'' ~ 1/eps), including
    eps = 0.004, where cosh(Y) = cosh(125) would overflow a direct evaluation: the
    boundary layers at both ends carry the acceleration, the middle coasts at speed
    sigma' -> 1 / (1 - 2 eps)."""
    u, s_ref, ds_ref, dds_ref = _sigma_ref(eps)
    s, ds, dds = rest_to_rest_sigma(u, eps)
    np.testing.assert_allclose(s, s_ref, rtol=0, atol=1e-12)
    np.testing.assert_allclose(ds, ds_ref, rtol=0, atol=1e-12)
    np.testing.assert_allclose(dds, dds_ref, rtol=0, atol=1e-12 / eps)
    assert s[0] == pytest.approx(0, abs=1e-15) and s[-1] == pytest.approx(1, abs=1e-14)
    assert abs(ds[0]) < 1e-12 and abs(ds[-1]) < 1e-12


class _Proxy:
    """A reduced inertia J(alpha) = (1 + alpha)^2 (kg m^2): sqrt(J) = 1 + alpha, whose energy
    coordinate sigma(alpha) = alpha + alpha^2 / 2 inverts by hand. The own-axis part Jp is
    taken as (2 + alpha)^2. Unknown keys raise."""

    shift = {"": 1.0, "p": 2.0}

    def __call__(self, key, a):
        a = np.asarray(a, dtype=float)
        part = {"sqrtJ": "", "dJ": "", "sqrtJp": "p", "dJp": "p"}[key]
        c = self.shift[part]
        return c + a if key.startswith("sqrt") else 2 * (c + a)

    def antiderivative(self, key, a, a0):
        c = self.shift[{"sqrtJ": "", "sqrtJp": "p"}[key]]
        f = lambda x: c * x + x**2 / 2  # noqa: E731
        return f(np.asarray(a, dtype=float)) - f(a0)


@pytest.mark.parametrize("which, c", [("complete", 1.0), ("own", 2.0)])
@pytest.mark.parametrize("a0, ak", [(0.3, 1.1), (1.1, 0.3)])
def test_rest_to_rest_law_in_the_boom_angle(which, c, a0, ak):
    """alpha(tau) = -c + sqrt((c + a0)^2 + 2 S sigma(tau)) with S = sigma(ak) - sigma(a0),
    and its tau-derivatives differentiated by hand: alpha' = S sigma' / r,
    alpha'' = (S sigma'' - r' alpha'^2) / r with r = sqrt(J) = c + alpha, r' = J' / (2 r) = 1;
    the Newton inversion converges to 1e-15, so 1e-12."""
    tau_c, t_k = 2.0, 10.0
    law = rest_to_rest_law(_Proxy(), a0, ak, tau_c, t_k, which)
    u, sg, dsg, ddsg = _sigma_ref(tau_c / t_k)
    S = (c * ak + ak**2 / 2) - (c * a0 + a0**2 / 2)
    a_ref = -c + np.sqrt((c + a0) ** 2 + 2 * S * sg)
    r = c + a_ref
    da_ref = S * dsg / r
    dda_ref = (S * ddsg - da_ref**2) / r
    a, da, dda = law.evaluate(u)
    np.testing.assert_allclose(a, a_ref, rtol=0, atol=1e-12)
    np.testing.assert_allclose(da, da_ref, rtol=0, atol=1e-11)
    np.testing.assert_allclose(dda, dda_ref, rtol=0, atol=1e-10)
    assert law.name == "rest-to-rest"
    assert law.info == {"tau_c_s": 2.0, "eps": 0.2}
    a1, _, _ = law.evaluate(0.5)                # a scalar tau: one value
    assert a1.shape == (1,) and a1[0] == pytest.approx(a_ref[5], abs=1e-12)


def test_rest_to_rest_law_uses_the_complete_inertia_by_default():
    """Without `which`, the complete J (sqrt(J) = 1 + alpha here), not the own-axis Jp."""
    law = rest_to_rest_law(_Proxy(), 0.3, 1.1, 2.0, 10.0)
    ref = rest_to_rest_law(_Proxy(), 0.3, 1.1, 2.0, 10.0, "complete")
    own = rest_to_rest_law(_Proxy(), 0.3, 1.1, 2.0, 10.0, "own")
    tau = np.linspace(0, 1, 11)
    np.testing.assert_array_equal(law.evaluate(tau)[0], ref.evaluate(tau)[0])
    assert np.abs(law.evaluate(tau)[0] - own.evaluate(tau)[0]).max() > 1e-3
