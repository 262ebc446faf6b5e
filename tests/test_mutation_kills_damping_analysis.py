"""Kill tests for cranefe/analysis/damping/analysis.py (tools/mutation.py
damping_analysis; docs/testing.md, "Mutation testing"): which modes the damping analysis
solves exactly (method modal / exact / both / auto, the auto switch by Hasselman's
coupling and by the predicted error), what it reports per mode (frequencies, decoupled
ratios b = psi c / (2 pi w), coupling and partner, dominant element, log decrement), its
warnings, its errors and the coupling partners it computes (`partner_modes`).

Every reference is built here from hand-written K, M and K_psi = sum psi_e k_e e e^T
(scipy's eigh for the undamped modes, numpy's eig of the state-space matrix for the
exact roots), or in closed form (uniform chain, two-mass hoist). Small models only
(2-20 coordinates): the whole file runs in about a second.
"""

import math

import numpy as np
import pytest
import scipy.linalg as sla
from test_damping import HOIST, chain_text
from test_mutation_kills_modal import BEAM

from cranefe import cases
from cranefe.analysis.damping import (
    ERROR_TOL,
    KAPPA,
    damping,
    first_modes,
    partner_modes,
    scene_method,
)
from cranefe.errors import ModelError
from cranefe.model import load
from cranefe.system import assemble

PAIR = """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {{G1: [0, 0, 0], A: [1, 0, 0], B: [2, 0, 0], G2: [3, 0, 0]}}
ground: [G1, G2]
masses: {{A: 100, B: 100}}
springs:
  - {{name: a, type: axial, nodes: [G1, A], stiffness: {ka}, psi: {pa}}}
  - {{name: b, type: axial, nodes: [B, G2], stiffness: {kb}, psi: {pb}}}
  - {{name: c, type: axial, nodes: [A, B], stiffness: {kc}, psi: 0.0}}
effects: {{sway: false}}
"""
# two oscillators 0.7 % apart, one heavily absorbing: coupling 0.5 (the criterion fails)
CLOSE = dict(ka=1.0e4, pa=0.1, kb=1.01e4, pb=3.0, kc=50.0)
# 9 % apart: coupling 0.024 (weak), but the light mode's estimate is off by ~19 %
LOOSE = dict(ka=1.0e4, pa=0.01, kb=1.2e4, pb=3.0, kc=50.0)
# a two-mass chain G -k0- N0 -k1- N1, well separated, weakly coupled, error < 0.1 %
WEAK = ([1.0e4, 5.0e3], [100.0, 50.0], [0.2, 0.05])


def pair_matrices(ka, pa, kb, pb, kc):
    K = np.array([[ka + kc, -kc], [-kc, kb + kc]])
    return K, np.diag([100.0, 100.0]), np.diag([pa * ka, pb * kb])


def chain_matrices(ks, ms, psis):
    (k0, k1), (p0, p1) = ks, psis
    K = np.array([[k0 + k1, -k1], [-k1, k1]])
    P = np.array([[p0 * k0 + p1 * k1, -p1 * k1], [-p1 * k1, p1 * k1]])
    return K, np.diag(ms), P


def decoupled(K, M, P):
    """Undamped w, H = V^T K_psi V / (2 pi) (mass-normalised V; Heletiy eq. 12, 14),
    zeta = H_ii / (2 w_i^2) (eq. 16), Hasselman's eps_ij = |H_ij| / |w_i^2 - w_j^2
    + i (H_ii - H_jj)| (docs/damping.md) and D_ij = H_ij / sqrt(w_i w_j) (eq. 15)."""
    w2, V = sla.eigh(K, M)
    w = np.sqrt(w2)
    H = V.T @ P @ V / (2 * np.pi)
    h = np.diag(H)
    S = w2 + 1j * h
    eps = np.abs(H - np.diag(h)) / (np.abs(S[:, None] - S[None, :]) + np.eye(len(w)))
    return w, V, H, h / (2 * w2), eps, H / np.sqrt(np.outer(w, w))


def exact_roots(K, M, P, w, V):
    """Per mode i: the state-space root with B_i = K_psi / (2 pi w_i) whose eigenvector
    is most like the undamped mode V_i (largest |V_i^T M z|^2 / z^H M z among roots with
    Im > 0: a heavily damped mode's root may lie nearer another mode's i w_j), zeta =
    -Re lam / |lam|, damped w = Im lam; and the eigenvalue mu of M^-1 (K + i K_psi /
    (2 pi)) chosen the same way, zeta = Im mu / (2 Re mu), damped w = Re sqrt(mu)."""
    n = len(w)
    Mi = np.linalg.inv(M)

    def like(Z, i, ok):
        part = np.abs(V[:, i] @ M @ Z) ** 2 / np.real(np.einsum("ij,ij->j", Z.conj(), M @ Z))
        return np.argmax(np.where(ok, part, -1.0))
    out_v, out_h = [], []
    mus, Y = np.linalg.eig(Mi @ (K + 1j * P / (2 * np.pi)))
    for i, wi in enumerate(w):
        A = np.block([[np.zeros((n, n)), np.eye(n)],
                      [-Mi @ K, -Mi @ P / (2 * np.pi * wi)]])
        ev, Z = np.linalg.eig(A)
        lam = ev[like(Z[:n], i, ev.imag > 0)]
        out_v.append((-lam.real / abs(lam), lam.imag))
        mu = mus[like(Y, i, np.ones(n, bool))]
        out_h.append((mu.imag / (2 * mu.real), np.sqrt(mu).real))
    return np.array(out_v), np.array(out_h)


def pair(**kw):
    return load("pair.yaml", PAIR.format(**kw))


# ------------------------------------------------------------------ what is reported

@pytest.mark.parametrize("method", ["modal", "auto", "exact", "both"])
def test_weak_chain_reports_the_decoupled_estimate_by_hand(method):
    """The weak chain: w, zeta, damped w = w sqrt(1 - zeta^2) (eq. 17), log decrement
    2 pi zeta / sqrt(1 - zeta^2), coupling (each mode's largest eps, its partner), D,
    the element absorbing most (spring k0: c psi (r V)^2 largest) with its share, to
    1e-10 (round-off of a 2x2 eigenproblem). Weakly coupled and predicted error below
    ERROR_TOL: auto solves nothing, exact/both solve both modes, to 1e-9 of the state
    space (the roots are refined to round-off)."""
    ks, ms, psis = WEAK
    r = damping(load("chain.yaml", chain_text(ks, ms, psis)), method=method)
    K, M, P = chain_matrices(*WEAK)
    w, V, H, zeta, eps, D = decoupled(K, M, P)
    assert r.method == method and r.dofs == 2 and r.model_name == "chain"
    assert list(r.rigid) == [False, False] and r.quasi_cyclic == ()
    np.testing.assert_allclose(r.omega, w, rtol=1e-12)
    np.testing.assert_allclose(r.zeta, zeta, rtol=1e-10)
    np.testing.assert_allclose(r.damped_omega, w * np.sqrt(1 - zeta**2), rtol=1e-10)
    np.testing.assert_allclose(r.log_decrement, 2 * np.pi * zeta / np.sqrt(1 - zeta**2),
                               rtol=1e-10)
    np.testing.assert_allclose(r.coupling, [eps[0, 1], eps[1, 0]], rtol=1e-9)
    np.testing.assert_allclose(r.coupling_matrix, eps, rtol=1e-9, atol=1e-15)
    assert list(r.coupled_with) == [1, 0]
    np.testing.assert_allclose(np.abs(r.D), np.abs(D), rtol=1e-9)
    # shares of spring k0 / k1 in H_ii: psi c (elongation)^2, elongation (V0, V1 - V0)
    parts = np.array([psis[0] * ks[0] * V[0]**2, psis[1] * ks[1] * (V[1] - V[0])**2])
    top = parts.argmax(axis=0)
    assert r.dominant_element == tuple(f"spring k{t}" for t in top)
    np.testing.assert_allclose(r.dominant_share, parts.max(axis=0) / parts.sum(axis=0),
                               rtol=1e-9)
    assert np.all(np.abs(r.predicted_error) < 1e-3) and r.criterion_holds.all()
    assert r.warnings == []
    assert set(r.timings) >= {"assemble", "modes", "decoupled"}
    if method in ("modal", "auto"):
        assert r.exact_zeta is None and r.hysteretic_zeta is None
        assert "exact_viscous" not in r.timings
    else:
        v, h = exact_roots(K, M, P, w, V)
        np.testing.assert_allclose(r.exact_zeta, v[:, 0], rtol=1e-9)
        np.testing.assert_allclose(r.exact_damped_omega, v[:, 1], rtol=1e-9)
        np.testing.assert_allclose(r.hysteretic_zeta, h[:, 0], rtol=1e-9)
        np.testing.assert_allclose(r.hysteretic_damped_omega, h[:, 1], rtol=1e-9)
        assert {"exact_viscous", "hysteretic"} <= set(r.timings)


def test_close_pair_fails_the_criterion_and_auto_solves_both_modes():
    """CLOSE: eps_12 = 0.4995 >= KAPPA (by hand); auto solves both modes (against the
    state space, 1e-8: the roots of a strongly coupled pair, refined), modal none; the
    warning names the pair and its coupling, and says what is done per method."""
    K, M, P = pair_matrices(**CLOSE)
    w, V, H, zeta, eps, _ = decoupled(K, M, P)
    assert eps[0, 1] == pytest.approx(0.4995, abs=1e-4)
    model = pair(**CLOSE)
    text = ("Hasselman's weak-coupling criterion fails (coupling >= 0.1) for modes "
            "1-2 (0.5): their decoupled damping ratios are not reliable")
    auto = damping(model, method="auto")
    np.testing.assert_allclose(auto.coupling, [eps[0, 1]] * 2, rtol=1e-9)
    assert auto.warnings == [text + "; they are solved exactly"]
    assert not auto.criterion_holds.any() and not np.isnan(auto.exact_zeta).any()
    assert not np.isnan(auto.hysteretic_zeta).any()
    exact = damping(model, method="exact")
    assert exact.warnings == [text]
    np.testing.assert_allclose(auto.exact_zeta, exact.exact_zeta, rtol=1e-12)
    np.testing.assert_allclose(auto.hysteretic_zeta, exact.hysteretic_zeta, rtol=1e-12)
    modal = damping(model, method="modal")
    assert modal.warnings == [text + "; use --method exact"]
    assert modal.exact_zeta is None
    doc = auto.to_dict()
    assert doc["criterion"] == {"coupling_limit": KAPPA, "error_limit": ERROR_TOL,
                                "holds": False}
    assert [m["weak_coupling"] for m in doc["modes"]] == [False, False]
    assert [m["coupled_with"] for m in doc["modes"]] == [2, 1]


def test_loose_pair_auto_solves_only_the_mode_whose_error_is_large():
    """LOOSE: weak coupling (eps 0.024 < KAPPA) but mode 1's decoupled ratio is 19 %
    above the exact one, so auto solves mode 1 only (mode 2 stays NaN); its exact values
    against the state space (1e-9), its predicted error against the true error (the
    perturbation's third-order remainder: 2e-3 absolute), and the warning's text."""
    K, M, P = pair_matrices(**LOOSE)
    w, V, H, zeta, eps, _ = decoupled(K, M, P)
    v, h = exact_roots(K, M, P, w, V)
    r = damping(pair(**LOOSE), method="auto")
    np.testing.assert_allclose(r.zeta, zeta, rtol=1e-10)
    assert eps[0, 1] < KAPPA and r.criterion_holds.all()
    err_v, err_h = zeta / v[:, 0] - 1, zeta / h[:, 0] - 1
    true = np.where(np.abs(err_v) > np.abs(err_h), err_v, err_h)
    assert true[0] > 0.15 and abs(true[1]) < ERROR_TOL
    np.testing.assert_allclose(r.predicted_error, true, atol=2e-3)
    assert r.exact_zeta[0] == pytest.approx(v[0, 0], rel=1e-9)
    assert r.exact_damped_omega[0] == pytest.approx(v[0, 1], rel=1e-9)
    assert r.hysteretic_zeta[0] == pytest.approx(h[0, 0], rel=1e-9)
    assert r.hysteretic_damped_omega[0] == pytest.approx(h[0, 1], rel=1e-9)
    assert np.isnan([r.exact_zeta[1], r.exact_damped_omega[1], r.hysteretic_zeta[1],
                     r.hysteretic_damped_omega[1]]).all()
    assert list(r.trusted) == [False, True]
    assert r.warnings == [
        "weakly coupled, but the predicted error of the decoupled damping ratio exceeds "
        f"2 % for mode(s) 1 ({100 * r.predicted_error[0]:+.1f} %); they are solved exactly"]
    assert r.warnings[0].endswith(f"1 (+{100 * true[0]:.1f} %); they are solved exactly")
    modal = damping(pair(**LOOSE), method="modal")
    assert modal.warnings[0].endswith("; use --method exact") and modal.exact_zeta is None
    doc = r.to_dict()
    m1, m2 = doc["modes"]
    assert m1["exact"]["damping_ratio"] == pytest.approx(v[0, 0], rel=1e-9)
    assert m1["exact"]["relative_error"] == pytest.approx(err_v[0], rel=1e-8)
    assert m1["hysteretic"]["relative_error"] == pytest.approx(err_h[0], rel=1e-8)
    assert "exact" not in m2 and "hysteretic" not in m2
    assert doc["criterion"]["holds"] is False


def test_hoist_with_a_rigid_drum_mode_by_closed_form():
    """models/two_mass_hoist.yaml (free drum): modes 0 (rigid drum), sqrt(g / 16)
    (pendulum: no rope stretches), and the hoist mode w^2 = c (4 / m + r^2 / J) with
    c = EA / L, L = |W S| + 2 x 16 + 2, J = 95 + 0.6 x 38^2 (the model's header). Only the
    rope absorbs: zeta = psi / (4 pi) in the hoist mode, zero in the others; exact
    viscous zeta the same (one absorbing element proportional to the mode's stiffness),
    damped w = w sqrt(1 - zeta^2); complex stiffness mu = w^2 (1 + i psi / (2 pi)).
    method exact: only the hoist mode is solved (its position among the elastic modes
    found by `searchsorted`), the rigid and undamped ones copied. 1e-9: the hand L."""
    r = damping(load(HOIST), method="exact")
    c = 1.7e7 / (math.hypot(12.0, 23.0) + 32.0 + 2.0)
    w = math.sqrt(c * (4 / 5200 + 0.25**2 / (95 + 0.6 * 38**2)))
    z = 0.2 / (4 * math.pi)
    np.testing.assert_allclose(r.omega, [0.0, math.sqrt(9.81 / 16), w], rtol=1e-9,
                               atol=1e-6)
    assert list(r.rigid) == [True, False, False] and r.quasi_cyclic == ("drum hoist",)
    np.testing.assert_allclose(r.zeta, [0, 0, z], rtol=1e-10, atol=1e-14)
    assert np.isnan(r.log_decrement[0])
    np.testing.assert_allclose(r.log_decrement[1:], [0, 2 * math.pi * z / math.sqrt(1 - z * z)],
                               rtol=1e-10, atol=1e-14)
    np.testing.assert_allclose(r.damped_omega[1:], r.omega[1:] * np.sqrt(1 - r.zeta[1:]**2),
                               rtol=1e-12)
    assert r.damped_omega[0] == 0.0
    np.testing.assert_allclose(r.exact_zeta, [0, 0, z], rtol=1e-9, atol=1e-14)
    np.testing.assert_allclose(r.exact_damped_omega, [0, r.omega[1], w * math.sqrt(1 - z * z)],
                               rtol=1e-9)
    np.testing.assert_allclose(r.hysteretic_zeta, [0, 0, z], rtol=1e-9, atol=1e-14)
    np.testing.assert_allclose(r.hysteretic_damped_omega[2],
                               (w * np.sqrt(1 + 1j * 0.2 / (2 * math.pi))).real, rtol=1e-9)
    assert r.dominant_element == ("", "", "rope hoist_rope")
    assert list(r.dominant_share) == [0.0, 0.0, 1.0]
    assert list(r.coupled_with) == [-1, -1, -1] and r.coupling.max() == 0.0
    assert r.D.shape == (3, 3) and r.D[0].max() == 0.0
    assert r.D[2, 2] == pytest.approx(2 * z * w, rel=1e-9)          # D_ii = 2 zeta w
    assert r.predicted_error[0] == 0.0 and np.isfinite(r.predicted_error).all()
    assert r.warnings == []
    assert r.effects == load(HOIST).effects.as_dict()
    doc = r.to_dict()
    assert list(doc) == ["model", "effects", "dofs", "quasi_cyclic", "method", "criterion",
                         "modes", "timings_s", "warnings"]
    assert doc["modes"][0]["rigid"] is True and doc["modes"][0]["log_decrement"] is None
    assert doc["modes"][2]["absorbed_most_by"] == {"element": "rope hoist_rope",
                                                   "share": 1.0}
    assert doc["modes"][1]["absorbed_most_by"] is None
    # auto: nothing to solve (weak, error 0): no exact arrays at all
    auto = damping(load(HOIST), method="auto")
    assert auto.exact_zeta is None and auto.hysteretic_zeta is None
    # count 2: the rigid and the pendulum mode only, the hoist mode as a partner
    two = damping(load(HOIST), method="both", count=2)
    assert len(two.omega) == 2 and two.D.shape == (2, 2)
    np.testing.assert_allclose(two.exact_zeta, [0, 0], atol=1e-14)


def test_warnings_of_undamped_and_overdamped_models():
    """No psi anywhere; psi on a rope made inextensible (rope_elasticity: false, so the
    rope has c = 0); one spring of psi 20: zeta = 20 / (4 pi) = 1.59 >= 1 (overdamped,
    log decrement infinite)."""
    r = damping(load("c.yaml", chain_text([1.0e4], [100.0], [0.0])), method="auto")
    assert r.warnings == ["no element has an absorption coefficient psi > 0: every damping "
                          "ratio is zero (give psi on ropes, springs or members)"]
    assert r.zeta[0] == 0.0 and r.exact_zeta is None
    with open(HOIST) as f:
        text = f.read() + "effects: {rope_elasticity: false}\n"
    r = damping(load("x.yaml", text), method="both")
    assert r.warnings == ["rope hoist_rope: psi > 0 but inextensible here "
                          "(rope_elasticity: false), so no element that deforms absorbs "
                          "energy: every damping ratio is zero"]
    np.testing.assert_array_equal(r.exact_zeta, [0.0, 0.0])
    r = damping(load("c.yaml", chain_text([1.0e4], [100.0], [20.0])), method="modal")
    assert r.zeta[0] == pytest.approx(20 / (4 * math.pi), rel=1e-12)
    assert r.log_decrement[0] == np.inf
    assert r.warnings[0] == "decoupled estimate overdamped (zeta >= 1) for mode(s) 1"
    # uniform psi: zeta = psi / (4 pi) in every mode, both overdamped
    r = damping(load("c.yaml", chain_text([1.0e4] * 2, [100.0] * 2, [40.0] * 2)), "modal")
    np.testing.assert_allclose(r.zeta, 40 / (4 * math.pi), rtol=1e-10)
    assert r.warnings[0] == "decoupled estimate overdamped (zeta >= 1) for mode(s) 1, 2"
    # psi c = 0.5 < 1 is still an absorption: no warning
    r = damping(load("c.yaml", chain_text([1.0], [1.0], [0.5])), method="auto")
    assert r.warnings == [] and r.zeta[0] == pytest.approx(0.5 / (4 * math.pi), rel=1e-12)
    # method exact with nothing absorbing: the exact arrays are the (exact) zeros
    r = damping(load("c.yaml", chain_text([1.0e4], [100.0], [0.0])), method="exact")
    np.testing.assert_array_equal(r.exact_zeta, [0.0])
    np.testing.assert_array_equal(r.hysteretic_zeta, [0.0])
    np.testing.assert_allclose(r.exact_damped_omega, [10.0], rtol=1e-12)
    # an inextensible rope with psi = 0: nothing absorbs, and nothing claims to
    with open(HOIST) as f:
        text = f.read().replace("psi: 0.20", "psi: 0.0") + "effects: {rope_elasticity: false}\n"
    assert "psi: 0.0" in text
    r = damping(load("x.yaml", text), method="auto")
    assert r.warnings == [NO_PSI]


NO_PSI = ("no element has an absorption coefficient psi > 0: every damping ratio is zero "
          "(give psi on ropes, springs or members)")


def test_two_inextensible_ropes_with_psi_are_named():
    """cases.double_pendulum with psi on both ropes, rope_elasticity: false."""
    text = cases.double_pendulum()[0].replace("EA: 5.0e7,", "EA: 5.0e7, psi: 0.1,")
    assert text.count("psi: 0.1") == 2
    r = damping(load("d.yaml", text + "effects: {rope_elasticity: false}\n"), "auto")
    assert r.warnings == ["rope lower, rope upper: psi > 0 but inextensible here "
                          "(rope_elasticity: false), so no element that deforms absorbs "
                          "energy: every damping ratio is zero"]


def test_beam_absorption_counts():
    """A cantilever beam (tests/test_mutation_kills_modal.py BEAM) whose member carries
    psi = 0.3: no warning, zeta = psi / (4 pi) in every mode (K_psi = psi K); with
    psi = 0 on the member the no-absorption warning."""
    r = damping(load("beam.yaml", BEAM), method="modal")
    assert r.warnings == []
    np.testing.assert_allclose(r.zeta, 0.3 / (4 * math.pi), rtol=1e-9)
    r = damping(load("beam.yaml", BEAM.replace("psi: 0.3", "psi: 0.0")), method="modal")
    assert r.warnings == [NO_PSI]


def test_model_with_only_a_rigid_mode():
    """Free drum, inextensible rope, no sway: one rigid mode, no elastic one."""
    with open(HOIST) as f:
        text = f.read() + "effects: {rope_elasticity: false, sway: false}\n"
    r = damping(load("x.yaml", text), method="both")
    assert list(r.rigid) == [True] and r.omega[0] == 0.0
    assert r.dominant_element == ("",) and list(r.dominant_share) == [0.0]
    assert list(r.coupled_with) == [-1] and r.exact_zeta.tolist() == [0.0]


def test_timings_are_durations_and_modal_warnings_are_kept():
    """Each timing lies between 0 and the wall time of the call; the warnings of the
    modes passed in come first."""
    import time
    from dataclasses import replace
    model = load("pair.yaml", PAIR.format(**LOOSE))
    s = assemble(model)
    modal, _ = partner_modes(model, s)
    t0 = time.perf_counter()
    r = damping(model, "auto", system=s, modal=replace(modal, warnings=["from modes"]))
    wall = time.perf_counter() - t0
    assert set(r.timings) == {"assemble", "modes", "decoupled", "exact_viscous",
                              "hysteretic"}
    assert all(0 <= v <= wall for v in r.timings.values()), r.timings
    assert r.warnings[0] == "from modes" and len(r.warnings) == 2


def test_dominant_element_of_each_mode_of_the_loose_pair():
    """Shares psi k (elongation)^2 of springs a (A to ground) and b (B to ground); the
    coupling spring c has psi 0. Mode 1 moves mostly A (a dominates), mode 2 B (b)."""
    K, M, P = pair_matrices(**LOOSE)
    w, V, H, zeta, eps, _ = decoupled(K, M, P)
    r = damping(pair(**LOOSE), method="modal")
    parts = np.array([LOOSE["pa"] * LOOSE["ka"] * V[0]**2, LOOSE["pb"] * LOOSE["kb"] * V[1]**2])
    assert r.dominant_element == ("spring a", "spring b")
    np.testing.assert_allclose(r.dominant_share, parts.max(axis=0) / parts.sum(axis=0),
                               rtol=1e-9)


def test_undamped_mode_has_no_partner():
    """The weak chain and, apart from it, a mass of 10 kg on a spring of 3000 N/m with no
    psi (w = sqrt(300) = 17.3 rad/s, mode 3): its H row is zero, so coupling 0 and no
    partner, while modes 1 and 2 are each other's partners."""
    text = chain_text(*WEAK).replace("N1: [2, 0, 0]}", "N1: [2, 0, 0], X: [10, 0, 0]}")
    text = text.replace("masses: {", "masses: {X: 10, ").replace(
        "effects:", "  - {name: x, type: axial, nodes: [G, X], stiffness: 3000, psi: 0}\n"
        "effects:")
    r = damping(load("c.yaml", text), method="modal")
    assert r.omega[2] == pytest.approx(math.sqrt(300.0), rel=1e-12)
    assert list(r.coupled_with) == [1, 0, -1] and r.coupling[2] == 0.0
    assert r.to_dict()["modes"][2]["coupled_with"] is None


# three oscillators A, B, C on ground springs a, b, c (B's from the same ground node as
# A's, all along x), coupled by springs ab and bc without psi
TRI = """cranefe: 1
plane: xz
gravity: [0, 0, 0]
nodes: {{G1: [0, 0, 0], A: [1, 0, 0], B: [2, 0, 0], C: [3, 0, 0], G2: [4, 0, 0]}}
ground: [G1, G2]
masses: {{A: 100, B: 100, C: 100}}
springs:
  - {{name: a, type: axial, nodes: [G1, A], stiffness: {ka}, psi: {pa}}}
  - {{name: b, type: axial, nodes: [G1, B], stiffness: {kb}, psi: {pb}}}
  - {{name: c, type: axial, nodes: [C, G2], stiffness: {kc}, psi: {pc}}}
  - {{name: ab, type: axial, nodes: [A, B], stiffness: 50.0, psi: 0.0}}
  - {{name: bc, type: axial, nodes: [B, C], stiffness: 50.0, psi: 0.0}}
effects: {{sway: false}}
"""


def tri_matrices(ka, pa, kb, pb, kc, pc):
    K = np.array([[ka + 50.0, -50.0, 0], [-50.0, kb + 100.0, -50.0], [0, -50.0, kc + 50.0]])
    return K, np.diag([100.0] * 3), np.diag([pa * ka, pb * kb, pc * kc])


def test_three_close_oscillators_fail_in_three_pairs():
    """1e4, 1.005e4, 1.01e4 N/m, the middle one heavily absorbing: every pair's eps by
    hand >= KAPPA, listed in order with its coupling."""
    kw = dict(ka=1.0e4, pa=0.1, kb=1.005e4, pb=3.0, kc=1.01e4, pc=0.1)
    eps = decoupled(*tri_matrices(**kw))[4]
    assert (eps[np.triu_indices(3, 1)] >= KAPPA).all()
    r = damping(load("t.yaml", TRI.format(**kw)), method="modal")
    np.testing.assert_allclose(r.coupling_matrix, eps, rtol=1e-8)
    assert r.warnings == [
        "Hasselman's weak-coupling criterion fails (coupling >= 0.1) for modes "
        f"1-2 ({eps[0, 1]:.2g}), 1-3 ({eps[0, 2]:.2g}), 2-3 ({eps[1, 2]:.2g}): their "
        "decoupled damping ratios are not reliable; use --method exact"]


def test_two_light_modes_beside_a_heavy_one_are_solved_exactly():
    """1e4 (psi 0.01), 1.2e4 (psi 3), 1.44e4 (psi 0.01): weakly coupled, but modes 1 and
    3 are estimated 18 % and 9 % too high (the state space, by hand); auto solves those
    two only (1e-9 of the state space), and the warning lists both."""
    kw = dict(ka=1.0e4, pa=0.01, kb=1.2e4, pb=3.0, kc=1.44e4, pc=0.01)
    K, M, P = tri_matrices(**kw)
    w, V, H, zeta, eps, _ = decoupled(K, M, P)
    v, h = exact_roots(K, M, P, w, V)
    r = damping(load("t.yaml", TRI.format(**kw)), method="auto")
    err = zeta / v[:, 0] - 1
    assert err[0] > 0.15 and err[2] > 0.05 and abs(err[1]) < 0.01
    assert r.criterion_holds.all() and list(r.trusted) == [False, True, False]
    np.testing.assert_allclose(r.exact_zeta[[0, 2]], v[[0, 2], 0], rtol=1e-9)
    np.testing.assert_allclose(r.hysteretic_zeta[[0, 2]], h[[0, 2], 0], rtol=1e-9)
    assert np.isnan(r.exact_zeta[1]) and np.isnan(r.hysteretic_zeta[1])
    e = r.predicted_error
    assert r.warnings == [
        "weakly coupled, but the predicted error of the decoupled damping ratio exceeds "
        f"2 % for mode(s) 1 ({100 * e[0]:+.1f} %), 3 ({100 * e[2]:+.1f} %); they are "
        "solved exactly"]


def test_partner_beyond_the_reported_modes_is_named():
    """The weak chain with count 1: mode 2 is computed as a partner only; the coupling
    of mode 1 is eps_12 and its partner is mode 2 (outside the report). With a strongly
    coupled partner outside (CLOSE, count 1) the warning names 1-2."""
    K, M, P = chain_matrices(*WEAK)
    eps = decoupled(K, M, P)[4]
    r = damping(load("chain.yaml", chain_text(*WEAK)), method="auto", count=1)
    assert len(r.omega) == 1 and r.coupling_matrix.shape == (1, 1)
    assert r.coupling[0] == pytest.approx(eps[0, 1], rel=1e-9)
    assert list(r.coupled_with) == [1]
    assert r.to_dict()["modes"][0]["coupled_with"] == 2
    c = damping(pair(**CLOSE), method="auto", count=1)
    assert c.warnings == [
        "Hasselman's weak-coupling criterion fails (coupling >= 0.1) for modes 1-2 "
        f"({c.coupling[0]:.2g}): their decoupled damping ratios are not reliable; "
        "they are solved exactly"]
    assert not np.isnan(c.exact_zeta).any()


def test_given_system_and_modes_are_used():
    """`system` and `modal` passed in: reported count = all of modal's modes, or count."""
    model = load("chain.yaml", chain_text(*WEAK))
    s = assemble(model)
    modal, _ = partner_modes(model, s)
    r = damping(model, "modal", system=s, modal=modal)
    assert len(r.omega) == 2
    r = damping(model, "modal", count=1, system=s, modal=modal)
    assert len(r.omega) == 1


# ------------------------------------------------------------------ partners

def _uniform(n):
    """A fixed-free chain of n unit masses on springs of 1e4 N/m: w_j = 2 sqrt(k/m)
    sin((2j - 1) pi / (2 (2n + 1))), j = 1..n."""
    model = load("u.yaml", chain_text([1.0e4] * n, [1.0] * n, [0.1] * n))
    j = np.arange(1, n + 1)
    return model, 200.0 * np.sin((2 * j - 1) * np.pi / (2 * (2 * n + 1)))


def test_partner_modes_dense_keeps_twice_the_highest_frequency():
    """20 masses. count 2: 2 w_2 covers modes 1-3, so count + EXTRA_MODES = 6 are kept;
    count 6: 2 w_6 = 2 sin(11 pi / 82) = 0.826 covers j with (2j - 1) pi / 82 <=
    asin(0.826): 13 modes (more than 6 + 4); count None or >= 20: all, all shown."""
    model, w = _uniform(20)
    s = assemble(model)
    for count, kept, shown in ((2, 6, 2), (6, 13, 6), (None, 20, 20), (20, 20, 20),
                               (25, 20, 20)):
        modal, m = partner_modes(model, s, count)
        assert (len(modal.omega), m) == (kept, shown), count
        np.testing.assert_allclose(modal.omega, w[:kept], rtol=1e-10)
        assert modal.shapes.shape[1] == kept and len(modal.node_shapes) == kept
        assert len(modal.rigid) == kept
    assert np.sum(w <= 2 * w[5]) == 13


def test_partner_modes_sparse_doubles_until_twice_the_frequency(monkeypatch):
    """The sparse path (SMALL and the dense limit set to 0): count 6 asks 10 modes
    (w_10 = 0.667 < 2 w_6 = 0.826, relative to 2 sqrt(k/m)), then 20 -> capped at n - 2 = 18;
    count 2: 6 modes (w_6 = 0.413 >= 2 w_2 = 0.227); no count: 10 shown, 14 then 18."""
    import cranefe.analysis.modal as modal_mod
    import cranefe.condense as condense
    model, w = _uniform(20)
    s = assemble(model)
    monkeypatch.setattr(modal_mod, "SMALL", 0)
    monkeypatch.setattr(condense, "DENSE_MAX", 0)
    # count 4: w_8 = sin(15 pi / 82) = 0.552 >= 2 w_4 = 0.530 > w_7 = 0.483: 8 modes;
    # count 5: w_9 = 0.606 < 2 w_5 = 0.680 (> 2 w_4): doubled to 18;
    # count 13: k = 17 (= n - 3), 2 w_13 > w_20: doubled, capped at 18
    for count, kept, shown in ((6, 18, 6), (2, 6, 2), (None, 18, 10), (4, 8, 4),
                               (5, 18, 5), (13, 18, 13)):
        modal, m = partner_modes(model, s, count)
        assert (len(modal.omega), m) == (kept, shown), count
        np.testing.assert_allclose(modal.omega, w[:kept], rtol=1e-8)
    # 40 masses, count 5: w_9 = sin(17 pi / 162) = 0.325 < 2 w_5 = 0.347, then 18 modes
    # (w_18 = 0.625): doubling, not tripling
    model, w = _uniform(40)
    modal, m = partner_modes(model, assemble(model), 5)
    assert (len(modal.omega), m) == (18, 5)
    np.testing.assert_allclose(modal.omega, w[:18], rtol=1e-8)


def test_partner_modes_without_a_count_are_all_modes_up_to_the_dense_limit(monkeypatch):
    """No count: every mode (dense) while n <= the dense limit of cranefe.condense, even
    above SMALL; at the limit itself (20 = n) too."""
    import cranefe.analysis.modal as modal_mod
    import cranefe.condense as condense
    model, w = _uniform(20)
    s = assemble(model)
    monkeypatch.setattr(modal_mod, "SMALL", 0)
    assert partner_modes(model, s)[1] == 20
    monkeypatch.setattr(condense, "DENSE_MAX", 20)
    modal, m = partner_modes(model, s)
    assert (len(modal.omega), m) == (20, 20)


def test_first_modes_cuts_every_per_mode_field():
    model, w = _uniform(5)
    modal, _ = partner_modes(model, assemble(model))
    cut = first_modes(modal, 2)
    np.testing.assert_array_equal(cut.omega, modal.omega[:2])
    np.testing.assert_array_equal(cut.shapes, modal.shapes[:, :2])
    assert len(cut.node_shapes) == 2 and list(cut.rigid) == [False, False]
    assert cut.dofs == modal.dofs


# ------------------------------------------------------------------ method and errors

def test_bad_method_and_count_name_the_entry():
    model = load("chain.yaml", chain_text(*WEAK))
    with pytest.raises(ModelError) as e:
        damping(model, method="rayleigh")
    assert (e.value.file, e.value.entry) == (None, "method")
    assert e.value.message == ("damping method 'rayleigh': use one of modal, exact, "
                               "both, auto")
    with pytest.raises(ModelError) as e:
        damping(model, count=0)
    assert (e.value.file, e.value.entry) == (None, "count")
    assert e.value.message == "count 0: ask for at least one mode"
    assert len(damping(model, "modal", count=1).omega) == 1


def test_scene_method(tmp_path):
    """analysis.method wins, then effects.damping (modal / exact), else auto; an unknown
    analysis.method names the scene file and the entry."""
    def scene(extra):
        p = tmp_path / "s.yaml"
        p.write_text(f"cranefe: 1\nmodel: {HOIST}\n{extra}")
        return load(p)
    assert scene_method(load(HOIST)) == "auto"
    assert scene_method(scene("analysis: {type: damping}\n")) == "auto"
    assert scene_method(scene("effects: {damping: exact}\nanalysis: {type: damping}\n")) \
        == "exact"
    assert scene_method(scene("effects: {damping: modal}\nanalysis: {type: damping}\n")) \
        == "modal"
    assert scene_method(scene("effects: {damping: exact}\n"
                              "analysis: {type: damping, method: both}\n")) == "both"
    with pytest.raises(ModelError) as e:
        scene_method(scene("analysis: {type: damping, method: rayleigh}\n"))
    assert e.value.file == str(tmp_path / "s.yaml") and e.value.entry == "analysis.method"
    assert e.value.message == "'rayleigh' is not one of modal, exact, both, auto"
