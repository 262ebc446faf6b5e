"""Damping from absorption coefficients against exact answers (Heletiy 2016, eq. 11-17)."""

import json
import os

import numpy as np
import pytest
import scipy.linalg as sla

from cranefe.cli import main
from cranefe.damping import KAPPA, damping
from cranefe.model import load

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def chain(ks, ms, psis):
    """Masses in a line on axial springs (the first to the ground), sway off."""
    n = len(ms)
    nodes = ", ".join(f"N{i}: [{i + 1}, 0, 0]" for i in range(n))
    ends = ["G"] + [f"N{i}" for i in range(n)]
    springs = "\n".join(f"  - {{name: k{i}, type: axial, nodes: [{a}, {b}], stiffness: {k}, "
                        f"psi: {p}}}" for i, (k, p, (a, b)) in
                        enumerate(zip(ks, psis, zip(ends[:-1], ends[1:]))))
    masses = ", ".join(f"N{i}: {m}" for i, m in enumerate(ms))
    return load("chain.yaml", f"cranefe: 1\nplane: xz\ngravity: [0, 0, 0]\n"
                f"nodes: {{G: [0, 0, 0], {nodes}}}\nground: [G]\nmasses: {{{masses}}}\n"
                f"springs:\n{springs}\neffects: {{sway: false}}\n")


def reference(ks, ms, psis):
    """Independent: hand-built K, M, K_psi; state-space eigenvalues for each mode's own B
    (b = psi c / (2 pi w_i)), the one nearest i w_i."""
    n = len(ms)
    K, P = np.zeros((n, n)), np.zeros((n, n))
    for i, (k, p) in enumerate(zip(ks, psis)):
        idx = [i] if i == 0 else [i - 1, i]
        e = np.array([1.0]) if i == 0 else np.array([-1.0, 1.0])
        K[np.ix_(idx, idx)] += k * np.outer(e, e)
        P[np.ix_(idx, idx)] += p * k * np.outer(e, e)
    M = np.diag(ms)
    w = np.sqrt(sla.eigh(K, M, eigvals_only=True))
    zeta = []
    for wi in w:
        B = P / (2 * np.pi * wi)
        A = np.block([[np.zeros((n, n)), np.eye(n)],
                      [-np.linalg.solve(M, K), -np.linalg.solve(M, B)]])
        lam = np.linalg.eigvals(A)
        lam = lam[lam.imag > 0]
        lam = lam[np.argmin(abs(lam - 1j * wi))]
        zeta.append(-lam.real / abs(lam))
    return w, np.array(zeta)


def test_single_dof_reproduces_psi_exactly():
    # zeta = b / (2 m w) = psi c / (4 pi m w^2) = psi / (4 pi); decoupled = exact for 1 DOF
    psi = 0.6
    r = damping(chain([1.0e4], [100.0], [psi]), method="both")
    assert r.zeta[0] == pytest.approx(psi / (4 * np.pi), rel=1e-14)
    assert r.exact_zeta[0] == pytest.approx(psi / (4 * np.pi), rel=1e-12)
    assert r.hysteretic_zeta[0] == pytest.approx(psi / (4 * np.pi), rel=1e-12)
    # free decay: log decrement 2 pi zeta / sqrt(1 - zeta^2), psi = 4 pi zeta
    assert r.log_decrement[0] == pytest.approx(2 * np.pi * r.zeta[0] /
                                               np.sqrt(1 - r.zeta[0] ** 2), rel=1e-14)
    assert r.damped_omega[0] == pytest.approx(10 * np.sqrt(1 - r.zeta[0] ** 2), rel=1e-14)


@pytest.mark.parametrize("ks, ms, psis", [
    ([2.0e4, 1.0e4], [100.0, 50.0], [0.0, 0.5]),
    ([3.0e4, 1.0e4, 2.0e4], [80.0, 40.0, 60.0], [0.0, 0.8, 0.0]),
])
def test_chains_with_damping_on_one_element_match_state_space(ks, ms, psis):
    w, zeta = reference(ks, ms, psis)
    r = damping(chain(ks, ms, psis), method="exact")
    np.testing.assert_allclose(r.omega, w, rtol=1e-12)
    np.testing.assert_allclose(r.exact_zeta, zeta, rtol=1e-8)
    # non-proportional: the decoupled estimate differs, but by little (well separated)
    assert np.max(np.abs(r.zeta / zeta - 1)) < 0.05
    assert r.coupling.max() > 0


def test_proportional_damping_gives_zero_coupling():
    # the same psi everywhere: K_psi = psi K, so V^T K_psi V = psi diag(w^2)
    r = damping(chain([3.0e4, 1.0e4, 2.0e4], [80.0, 40.0, 60.0], [0.3] * 3), method="both")
    assert r.coupling.max() < 1e-12
    np.testing.assert_allclose(r.zeta, 0.3 / (4 * np.pi), rtol=1e-12)
    np.testing.assert_allclose(r.exact_zeta, r.zeta, rtol=1e-10)


def test_close_frequencies_with_heavy_damping_fail_the_criterion(capsys, tmp_path):
    # two nearly equal oscillators joined by a heavily absorbing soft spring
    text = """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {G1: [0, 0, 0], A: [1, 0, 0], B: [2, 0, 0], G2: [3, 0, 0]}
ground: [G1, G2]
masses: {A: 100, B: 100}
springs:
  - {name: a, type: axial, nodes: [G1, A], stiffness: 1.0e4, psi: 0.1}
  - {name: b, type: axial, nodes: [B, G2], stiffness: 1.01e4, psi: 3.0}
  - {name: c, type: axial, nodes: [A, B], stiffness: 50.0, psi: 0.0}
effects: {sway: false}
"""
    path = tmp_path / "close.yaml"
    path.write_text(text)
    model = load(path)
    r = damping(model, method="auto")
    assert (r.coupling >= KAPPA).all() and r.exact_zeta is not None
    assert "criterion fails" in r.warnings[0] and "exact solution is used" in r.warnings[0]
    assert np.max(np.abs(r.zeta / r.exact_zeta - 1)) > 0.1     # the estimate is off
    assert main(["damping", str(path), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["modes"][0]["weak_coupling"] is False and "exact" in doc["modes"][0]


def test_model_with_quasi_cyclic_coordinates():
    # free drum: its rigid motion is not damped; the hoist mode carries the rope's psi
    r = damping(load(os.path.join(ROOT, "models", "two_mass_hoist.yaml")), method="both")
    assert len(r.omega) == 2                  # pendulum and hoist; the rigid one left out
    assert r.zeta[0] == 0.0                  # the swing does not stretch the rope
    assert r.zeta[1] == pytest.approx(0.2 / (4 * np.pi), rel=1e-12)   # only the rope
    np.testing.assert_allclose(r.exact_zeta, r.zeta, atol=1e-12)


def test_large_model_uses_sparse_exact_solutions():
    from dataclasses import replace

    from cranefe import damping as dmod
    model = load(os.path.join(ROOT, "models", "hammerhead_tower_crane.yaml"))
    model = replace(model, effects=replace(model.effects, rope_mass=20))
    dense = damping(model, method="exact", count=4)
    saved = dmod.DENSE_MAX
    dmod.DENSE_MAX = 10
    try:
        sparse = damping(model, method="exact", count=4)
    finally:
        dmod.DENSE_MAX = saved
    np.testing.assert_allclose(sparse.exact_zeta, dense.exact_zeta, rtol=1e-8)
    np.testing.assert_allclose(sparse.hysteretic_zeta, dense.hysteretic_zeta, rtol=1e-8)


def test_cli_and_scene_effect(tmp_path, capsys):
    scene = tmp_path / "s.yaml"
    scene.write_text(f"cranefe: 1\nmodel: {os.path.join(ROOT, 'models', 'two_mass_hoist.yaml')}"
                     "\neffects: {damping: exact}\nanalysis: {type: damping}\n")
    assert main(["damping", str(scene), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["method"] == "exact" and doc["dofs"] == 3
    assert doc["modes"][1]["exact"]["damping_ratio"] == pytest.approx(0.2 / (4 * np.pi))


def test_polyharmonic_k1_equates_dissipated_power():
    from cranefe.damping import polyharmonic_k1
    assert polyharmonic_k1([1.0], [7.0]) == 1.0
    a, w, psi, c = np.array([1.0, 0.4, 0.1]), np.array([2.0, 9.0, 31.0]), 0.3, 5.0e4
    b = psi * c / (2 * np.pi * w[0] * polyharmonic_k1(a, w))
    # power of the dashpot over a long time = power absorbed by psi (per harmonic psi U w/2pi)
    t = np.linspace(0, 2000, 2_000_001)
    v = (a[:, None] * w[:, None] * np.cos(w[:, None] * t)).sum(axis=0)
    dashpot = b * np.mean(v**2)
    hysteretic = np.sum(psi * 0.5 * c * a**2 * w / (2 * np.pi))
    assert dashpot == pytest.approx(hysteretic, rel=1e-3)


def test_modes_of_a_scene_with_damping(tmp_path, capsys):
    scene = tmp_path / "s.yaml"
    scene.write_text(f"cranefe: 1\nmodel: {os.path.join(ROOT, 'models', 'two_mass_hoist.yaml')}"
                     "\neffects: {damping: modal}\n")
    assert main(["modes", str(scene), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["damping"][1]["damping_ratio"] == pytest.approx(0.2 / (4 * np.pi))
