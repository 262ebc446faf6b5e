"""Kill test for `Proxy` in cranefe/analysis/luffing/energy.py (tools/mutation.py
luffing_energy; docs/testing.md): the Chebyshev interpolants of the reduced quantities
against `Reduced.evaluate` itself (value-tested against the hand linkage by
tests/test_mutation_kills_luffing.py) at angles between the interpolation points.

Exact relations checked: an interpolant of an analytic function on its Chebyshev points
converges geometrically; with the last coefficients below tol = 1e-13 of the largest
value (`tail`), the interpolation error is of the order of the tail (a few 1e-13
relative; asserted 1e-11). Its derivative loses about degree^2 (asserted 1e-8 on dJ);
the antiderivative of dJ from a to b is J(b) - J(a) (1e-9 relative to J), sqrtJ and
sqrtJp are the square roots, f = dJ / (2 J) (eq. 22). The point counts double as
n -> 2 n - 1 from 33, so `evaluations` is the sum of 33, 65, ... up to degree + 1, and
the degree is the first whose tail is below tol (capped one doubling earlier, it is not).
"""

import os

import numpy as np
from test_values import ROOT

from cranefe.analysis.luffing.analysis import Luffing, read_scene
from cranefe.analysis.luffing.energy import Proxy
from cranefe.model import load


def test_proxy_interpolates_the_reduced_quantities():
    scene = os.path.join(ROOT, "models", "portal_crane_luffing_scene.yaml")
    model = load(scene)
    reduced = Luffing(model, read_scene(model, scene), scene).reduced
    lo, hi = np.radians(40.0), np.radians(75.0)
    p = Proxy(reduced, lo, hi)
    a = np.radians([40.0, 41.3, 47.77, 55.0, 61.9, 70.05, 75.0])
    v = reduced.evaluate(a)
    assert p.tail < 1e-13
    counts = [33]
    while counts[-1] < p.degree + 1:
        counts.append(2 * counts[-1] - 1)
    assert counts[-1] == p.degree + 1 and p.evaluations == sum(counts)
    # the first sufficient degree: capped one doubling earlier, the tail is not below tol
    assert len(counts) > 1
    assert Proxy(reduced, lo, hi, max_points=counts[-2]).tail >= 1e-13
    for k in ("J", "Jp", "V", "s", "ds", "x", "z"):
        scale = np.abs(v[k]).max()
        assert np.abs(p(k, a) - v[k]).max() < 1e-11 * scale, k
    assert np.allclose(p("sqrtJ", a), np.sqrt(v["J"]), rtol=1e-11, atol=0)
    assert np.allclose(p("sqrtJp", a), np.sqrt(v["Jp"]), rtol=1e-11, atol=0)
    assert np.abs(p.derivative("J", a) - v["dJ"]).max() < 1e-8 * np.abs(v["dJ"]).max()
    anti = p.antiderivative("dJ", a, lo)
    assert np.abs(anti - (v["J"] - v["J"][0])).max() < 1e-9 * v["J"].max()
    assert np.allclose(p.f(a), v["dJ"] / (2 * v["J"]), rtol=1e-9, atol=0)
    assert np.allclose(p.f(a, "paper"), v["dJp"] / (2 * v["Jp"]), rtol=1e-9, atol=0)
