"""Finite-element ropes against exact solutions, and their massless limit."""

import os
from dataclasses import replace

import numpy as np
import pytest

from cranefe.system import assemble
from cranefe.cases import G, hanging_chain, heavy_rope_end_mass, matched, tensioned_span
from cranefe.model import load
from cranefe.analysis.modal import modes

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def solve(text, N, matrix="consistent", **kw):
    model = load("case.yaml", text)
    return modes(model, replace(model.effects, rope_mass=N, rope_mass_matrix=matrix), **kw)


def order(errors, Ns):
    return -np.polyfit(np.log(Ns), np.log(np.abs(errors)), 1)[0]


@pytest.mark.parametrize("matrix", ["consistent", "lumped"])
def test_heavy_rope_with_end_mass(matrix):
    text, exact = heavy_rope_end_mass()
    Ns = [8, 16, 32, 64]
    err = np.array([solve(text, N, matrix).omega[:3] / exact["omega"][:3] - 1 for N in Ns])
    # consistent mass overestimates, lumped underestimates (Rayleigh quotient bounds)
    assert np.all(err > 0) if matrix == "consistent" else np.all(err < 0)
    for k in range(3):
        assert order(err[:, k], Ns) == pytest.approx(2.0, abs=0.05)
    assert np.abs(err[-1]).max() < 5e-4


@pytest.mark.parametrize("matrix", ["consistent", "lumped"])
def test_hanging_chain(matrix):
    text, exact = hanging_chain()
    Ns = [16, 32, 64, 128]          # lumped mass is pre-asymptotic for mode 3 at N = 8
    err = np.array([solve(text, N, matrix).omega[:3] / exact["omega"][:3] - 1 for N in Ns])
    for k in range(3):
        assert order(err[:, k], Ns) == pytest.approx(2.0, abs=0.15)
    assert np.abs(err[-1]).max() < 1e-2


def test_tension_varies_along_a_hanging_rope():
    text, _ = heavy_rope_end_mass(L=100.0, mu=5.0, M=2000.0)
    model = load("case.yaml", text)
    N = 10
    system = assemble(model, replace(model.effects, rope_mass=N, sway=True))
    S = system.static.element_force[system.springs.rope == 0]
    # element k (from the top) carries the end mass and the rope below its mid-point
    below = 100.0 * (1 - (np.arange(N) + 0.5) / N)
    np.testing.assert_allclose(S, (2000.0 + 5.0 * below) * G, rtol=1e-10)


@pytest.mark.parametrize("matrix", ["consistent", "lumped"])
def test_span_tensioned_over_a_sheave(matrix):
    text, exact = tensioned_span()
    Ns = [8, 16, 32]
    err = []
    for N in Ns:
        r = solve(text, N, matrix)
        # the counterweight swings on its (slightly heavy) fall: sqrt(g/h) to ~mu h / W
        assert r.omega[0] == pytest.approx(exact["pendulum"], rel=1e-3)
        err.append(matched(r.omega, exact["omega"]) / exact["omega"] - 1)
    err = np.array(err)
    # leading error of linear string elements: +-(k h)^2 / 24, k h = n pi / N
    # (consistent mass over-, lumped mass underestimates)
    sign = 1 if matrix == "consistent" else -1
    assert err[-1] == pytest.approx(sign * (np.arange(1, 5) * np.pi / Ns[-1]) ** 2 / 24,
                                    rel=0.02)
    assert order(err[:, 0], Ns) == pytest.approx(2.0, abs=0.1)


def test_rope_without_mass_is_the_massless_rope():
    path = os.path.join(ROOT, "models", "two_mass_hoist.yaml")
    model = load(path)
    massless = replace(model, ropes=tuple(replace(r, mass_per_length=0.0)
                                          for r in model.ropes))
    a = modes(massless)
    b = modes(massless, replace(model.effects, rope_mass=8))
    np.testing.assert_array_equal(a.omega, b.omega)


@pytest.mark.parametrize("name", ["two_mass_hoist", "hammerhead_tower_crane",
                                  "luffing_tower_crane"])
def test_massless_limit_of_rope_elements(name):
    # rope mass x s: the frequencies of the massless model are approached linearly in s;
    model = load(os.path.join(ROOT, "models", f"{name}.yaml"))
    ref = modes(model)
    errs = []
    for s in (1e-3, 1e-6):
        light = replace(model, ropes=tuple(replace(r, mass_per_length=r.mass_per_length * s)
                                           for r in model.ropes))
        r = modes(light, replace(model.effects, rope_mass=4))
        k = len(ref.omega)
        errs.append(np.abs(r.omega[:k] - ref.omega).max() / ref.omega.max())
        assert r.quasi_cyclic == ref.quasi_cyclic
    assert errs[1] < 1e-6 and errs[1] / errs[0] == pytest.approx(1e-3, rel=0.05)


def test_tower_crane_with_rope_mass_runs_sparse_and_dense_alike():
    model = load(os.path.join(ROOT, "models", "hammerhead_tower_crane.yaml"))
    eff = replace(model.effects, rope_mass=20)
    dense = modes(model, eff, solver="dense", count=10)
    sparse = modes(model, eff, solver="sparse", count=10)
    np.testing.assert_allclose(sparse.omega, dense.omega, rtol=1e-9, atol=1e-9)
    assert sum(lab.startswith("slip") for lab in dense.labels) == 7   # sheave passes
