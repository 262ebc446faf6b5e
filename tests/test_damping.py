"""Damping from absorption coefficients against exact answers (Heletiy 2016, eq. 11-17;
docs/damping.md). Independent references are built here from hand-made K, M, K_psi."""

import json
import os

import numpy as np
import pytest
import scipy.linalg as sla

from cranefe.analysis import damping as dmod
from cranefe.cli import main
from cranefe.analysis.damping import (KAPPA, damping, damping_matrix, equivalent_viscous,
                             polyharmonic_k1, psi_stiffness)
from cranefe.model import load

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HOIST = os.path.join(ROOT, "models", "two_mass_hoist.yaml")


def chain_text(ks, ms, psis):
    """Masses in a line on axial springs (the first to the ground), sway off."""
    n = len(ms)
    nodes = ", ".join(f"N{i}: [{i + 1}, 0, 0]" for i in range(n))
    ends = ["G"] + [f"N{i}" for i in range(n)]
    springs = "\n".join(f"  - {{name: k{i}, type: axial, nodes: [{a}, {b}], stiffness: {k}, "
                        f"psi: {p}}}" for i, (k, p, (a, b)) in
                        enumerate(zip(ks, psis, zip(ends[:-1], ends[1:]))))
    masses = ", ".join(f"N{i}: {m}" for i, m in enumerate(ms))
    return (f"cranefe: 1\nplane: xz\ngravity: [0, 0, 0]\n"
            f"nodes: {{G: [0, 0, 0], {nodes}}}\nground: [G]\nmasses: {{{masses}}}\n"
            f"springs:\n{springs}\neffects: {{sway: false}}\n")


def chain(ks, ms, psis):
    return load("chain.yaml", chain_text(ks, ms, psis))


def chain_matrices(ks, ms, psis):
    """Hand-built K, M and K_psi = sum psi_e K_e of the chain."""
    n = len(ms)
    K, P = np.zeros((n, n)), np.zeros((n, n))
    for i, (k, p) in enumerate(zip(ks, psis)):
        idx = [i] if i == 0 else [i - 1, i]
        e = np.array([1.0]) if i == 0 else np.array([-1.0, 1.0])
        K[np.ix_(idx, idx)] += k * np.outer(e, e)
        P[np.ix_(idx, idx)] += p * k * np.outer(e, e)
    return K, np.diag(np.asarray(ms, float)), P


def reference(ks, ms, psis):
    """Independent state space: for each undamped mode i, the eigenvalues of
    [[0, I], [-M^-1 K, -M^-1 B_i]] with B_i = K_psi / (2 pi w_i) (eq. 12), the one nearest
    i w_i; and the complex stiffness K + i K_psi / (2 pi), nearest w_i^2."""
    K, M, P = chain_matrices(ks, ms, psis)
    n = len(ms)
    w = np.sqrt(sla.eigh(K, M, eigvals_only=True))
    Minv = np.linalg.inv(M)
    lam = []
    for wi in w:
        A = np.block([[np.zeros((n, n)), np.eye(n)],
                      [-Minv @ K, -Minv @ P / (2 * np.pi * wi)]])
        ev = np.linalg.eigvals(A)
        lam.append(ev[np.argmin(abs(ev - 1j * wi))])
    lam = np.array(lam)
    mu = sla.eigvals(K + 1j * P / (2 * np.pi), M)
    mu = np.array([mu[np.argmin(abs(mu - wi**2))] for wi in w])
    return w, lam, mu


def test_single_dof_free_decay_reproduces_psi():
    psi, k, m = 0.6, 1.0e4, 100.0
    w = np.sqrt(k / m)
    r = damping(chain([k], [m], [psi]), method="both")
    zeta = psi / (4 * np.pi)                     # b / (2 m w), b = psi k / (2 pi w)
    assert r.zeta[0] == pytest.approx(zeta, rel=1e-14)
    # one degree of freedom: the decoupled estimate is the exact viscous solution, and
    # the complex stiffness k (1 + i psi / 2 pi) has the same zeta = eta / 2
    assert r.exact_zeta[0] == pytest.approx(zeta, rel=1e-12)
    assert r.hysteretic_zeta[0] == pytest.approx(zeta, rel=1e-12)
    assert r.exact_damped_omega[0] == pytest.approx(r.damped_omega[0], rel=1e-12)
    # free decay x(t) = e^{At} x0, measured over one damped period: the log decrement
    lam = -zeta * w + 1j * r.exact_damped_omega[0]
    b = psi * k / (2 * np.pi * w)                # eq. 12 by hand, not the code's
    A = np.array([[0.0, 1.0], [-k / m, -b / m]])
    Td = 2 * np.pi / lam.imag
    x = sla.expm(A * Td) @ np.array([1.0, 0.3])
    delta = np.log(1.0 / x[0])
    assert delta == pytest.approx(r.log_decrement[0], rel=1e-10)
    assert delta == pytest.approx(r.exact_log_decrement[0], rel=1e-10)
    # psi = 2 delta holds exactly per undamped period (decay rate psi w / 4 pi) and to
    # O(zeta^2) per damped period: psi = 2 delta sqrt(1 - zeta^2)
    assert -lam.real * 2 * np.pi / w == pytest.approx(psi / 2, rel=1e-14)
    assert 2 * delta * np.sqrt(1 - zeta**2) == pytest.approx(psi, rel=1e-10)
    assert 2 * delta == pytest.approx(psi, rel=2 * zeta**2)
    # and eq. 12 itself: a dashpot b at w dissipates psi times the peak strain energy
    a = 0.01
    assert np.pi * equivalent_viscous(psi, k, w) * w * a**2 == pytest.approx(
        psi * k * a**2 / 2, rel=1e-15)


@pytest.mark.parametrize("ks, ms, psis", [
    ([2.0e4, 1.0e4], [100.0, 50.0], [0.0, 0.5]),
    ([3.0e4, 1.0e4, 2.0e4], [80.0, 40.0, 60.0], [0.0, 0.8, 0.0]),
])
def test_chains_with_damping_on_one_element_match_state_space(ks, ms, psis):
    w, lam, mu = reference(ks, ms, psis)
    r = damping(chain(ks, ms, psis), method="exact")
    np.testing.assert_allclose(r.omega, w, rtol=1e-12)
    np.testing.assert_allclose(r.exact_zeta, -lam.real / abs(lam), rtol=1e-8)
    np.testing.assert_allclose(r.exact_damped_omega, lam.imag, rtol=1e-8)
    np.testing.assert_allclose(r.hysteretic_zeta, mu.imag / (2 * mu.real), rtol=1e-8)
    np.testing.assert_allclose(r.hysteretic_damped_omega, np.sqrt(mu).real, rtol=1e-8)
    # non-proportional: modes are coupled, the estimate is close (well separated) and
    # its error is what the second-order estimate predicts
    assert r.coupling.max() > 1e-3
    err = r.error_viscous
    assert 0 < np.max(np.abs(err)) < 0.05
    np.testing.assert_allclose(r.predicted_error, np.where(
        np.abs(err) > np.abs(r.error_hysteretic), err, r.error_hysteretic), rtol=0.1,
        atol=1e-6)


def test_modal_damping_matrix_and_equivalent_viscous_rows():
    ks, ms, psis = [3.0e4, 1.0e4, 2.0e4], [80.0, 40.0, 60.0], [0.1, 0.8, 0.3]
    model = chain(ks, ms, psis)
    from cranefe.system import assemble
    system = assemble(model)
    K, M, P = chain_matrices(ks, ms, psis)
    np.testing.assert_allclose(psi_stiffness(system).toarray(), P, rtol=1e-14)
    w, V = sla.eigh(K, M)
    w = np.sqrt(w)
    # B_i = (R T)^T diag(psi c / (2 pi w_i)) (R T); D_ii = V_i^T B(w_i) V_i (eq. 15)
    r = damping(model, method="modal", system=system)
    for i, wi in enumerate(w):
        B = damping_matrix(system, wi).toarray()
        np.testing.assert_allclose(B, P / (2 * np.pi * wi), rtol=1e-14)
        assert r.D[i, i] == pytest.approx(V[:, i] @ B @ V[:, i], rel=1e-10)
        assert r.zeta[i] == pytest.approx(r.D[i, i] / (2 * wi), rel=1e-12)   # eq. 16
    # off-diagonal: geometric mean of the two frequencies, symmetric
    Dref = V.T @ P @ V / (2 * np.pi * np.sqrt(np.outer(w, w)))
    np.testing.assert_allclose(np.abs(r.D), np.abs(Dref), rtol=1e-9, atol=1e-14)
    assert np.all(np.linalg.eigvalsh(r.D) > -1e-12)      # positive semi-definite


def test_proportional_damping_gives_zero_coupling():
    # one psi everywhere and no tension stiffness (sway off): K_psi = psi K, so
    # V^T K_psi V = psi diag(w^2) and every B(w_i) is stiffness-proportional
    psi = 0.3
    r = damping(chain([3.0e4, 1.0e4, 2.0e4], [80.0, 40.0, 60.0], [psi] * 3),
                method="both")
    assert r.coupling.max() < 1e-12
    assert np.abs(r.predicted_error).max() < 1e-12
    np.testing.assert_allclose(r.zeta, psi / (4 * np.pi), rtol=1e-12)
    np.testing.assert_allclose(r.exact_zeta, r.zeta, rtol=1e-10)
    np.testing.assert_allclose(r.hysteretic_zeta, r.zeta, rtol=1e-10)
    assert not r.warnings


CLOSE = """cranefe: 1
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


def test_close_frequencies_with_heavy_damping_fail_the_criterion(tmp_path, capsys):
    # two oscillators 0.5 % apart, one heavily absorbing, joined by a soft spring
    path = tmp_path / "close.yaml"
    path.write_text(CLOSE)
    model = load(path)
    modal = damping(model, method="modal")
    assert (modal.coupling >= KAPPA).all() and modal.exact_zeta is None
    assert "criterion fails" in modal.warnings[0] and "--method exact" in modal.warnings[0]
    auto = damping(model, method="auto")          # switches to the exact solution
    assert "solved exactly" in auto.warnings[0]
    np.testing.assert_allclose(auto.zeta, modal.zeta, rtol=0)
    exact = damping(model, method="exact")
    np.testing.assert_allclose(auto.exact_zeta, exact.exact_zeta, rtol=1e-12)
    assert np.max(np.abs(auto.error_viscous)) > 0.1          # the estimate is off
    assert main(["damping", str(path), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["method"] == "auto" and doc["criterion"]["holds"] is False
    first = doc["modes"][0]
    assert first["weak_coupling"] is False and first["coupling"] >= KAPPA
    assert first["coupled_with"] == 2 and "exact" in first and "hysteretic" in first
    assert abs(first["exact"]["relative_error"]) > 0.1
    assert any("criterion fails" in w for w in doc["warnings"])
    assert main(["damping", str(path)]) == 0                  # the table warns too
    assert "warning: Hasselman's weak-coupling criterion fails" in capsys.readouterr().out


def test_close_pair_state_space_independent():
    """The failing case against an independent two-mass state space (no modal basis)."""
    K = np.array([[1.0e4 + 50.0, -50.0], [-50.0, 1.01e4 + 50.0]])
    P = np.diag([0.1 * 1.0e4, 3.0 * 1.01e4])
    M = np.diag([100.0, 100.0])
    w, V = sla.eigh(K, M)
    w = np.sqrt(w)
    r = damping(load("close.yaml", CLOSE), method="exact")
    for i, wi in enumerate(w):
        A = np.block([[np.zeros((2, 2)), np.eye(2)],
                      [-np.linalg.solve(M, K), -np.linalg.solve(M, P / (2 * np.pi * wi))]])
        ev, Z = np.linalg.eig(A)
        part = np.abs(V[:, i] @ M @ Z[:2]) ** 2 / np.real(
            np.einsum("ij,ij->j", Z[:2].conj(), M @ Z[:2])) * (ev.imag > 0)
        lam = ev[np.argmax(part)]
        assert r.exact_zeta[i] == pytest.approx(-lam.real / abs(lam), rel=1e-8)


def test_repeated_frequency_is_flagged_or_exact():
    # a 3D mass on two perpendicular springs of equal stiffness, 30 deg off the axes:
    # one double frequency, psi 0.1 and 0.5 along the springs. The undamped basis is
    # arbitrary, so the estimate holds only if it happens to align with the springs;
    # otherwise the coupling says so. The exact answers are psi / (4 pi) each.
    c, s = np.cos(np.pi / 6), np.sin(np.pi / 6)
    text = f"""cranefe: 1
gravity: [0, 0, 0]
nodes: {{O: [0, 0, 0], P: [{-c}, {-s}, 0], Q: [{s}, {-c}, 0]}}
ground: [P, Q]
masses: {{O: 100}}
springs:
  - {{name: a, type: axial, nodes: [P, O], stiffness: 1.0e4, psi: 0.1}}
  - {{name: b, type: axial, nodes: [Q, O], stiffness: 1.0e4, psi: 0.5}}
effects: {{sway: false}}
"""
    r = damping(load("double.yaml", text), method="auto")
    assert r.dofs == 2
    expect = np.array([0.1, 0.5]) / (4 * np.pi)
    if r.exact_zeta is None:                       # the basis happened to align
        np.testing.assert_allclose(np.sort(r.zeta), expect, rtol=1e-9)
    else:
        assert not r.criterion_holds.all()
        np.testing.assert_allclose(np.sort(r.exact_zeta), expect, rtol=1e-9)
        np.testing.assert_allclose(np.sort(r.hysteretic_zeta), expect, rtol=1e-9)


def test_model_with_quasi_cyclic_coordinates(capsys):
    # free drum: its rigid motion deforms no element and gets no damping; the swing
    # does not stretch the rope; the hoist mode carries the rope's psi alone
    r = damping(load(HOIST), method="both")
    assert list(r.rigid) == [True, False, False] and r.quasi_cyclic == ("drum hoist",)
    assert r.zeta[0] == 0.0 and np.isnan(r.log_decrement[0])
    assert r.zeta[1] == 0.0 and r.coupling.max() == 0.0
    assert r.zeta[2] == pytest.approx(0.2 / (4 * np.pi), rel=1e-12)
    np.testing.assert_allclose(r.exact_zeta, r.zeta, rtol=1e-10, atol=1e-15)
    np.testing.assert_allclose(r.hysteretic_zeta, r.zeta, rtol=1e-10, atol=1e-15)
    assert r.dominant_element[2] == "rope hoist_rope" and r.dominant_share[2] == 1.0
    assert main(["damping", HOIST, "--method", "both", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)     # allow_nan=False: no NaN/inf leaked
    assert doc["quasi_cyclic"] == ["drum hoist"] and doc["modes"][0]["rigid"] is True
    assert doc["modes"][0]["log_decrement"] is None


def test_sparse_and_dense_exact_solutions_agree(monkeypatch):
    rng = np.random.default_rng(3)
    n = 50
    ks, ms, psis = rng.uniform(1e4, 5e4, n), rng.uniform(50, 150, n), rng.uniform(0, 0.8, n)
    model = chain(ks, ms, psis)
    monkeypatch.setattr(dmod, "DENSE_MAX", 10)       # block shift-invert per mode
    sparse = damping(model, method="exact", count=8)
    monkeypatch.setattr(dmod, "DENSE_MAX", 100)      # QZ
    dense = damping(model, method="exact", count=8)
    w, lam, mu = reference(ks, ms, psis)
    np.testing.assert_allclose(sparse.exact_zeta, -lam.real[:8] / abs(lam[:8]), rtol=1e-9)
    np.testing.assert_allclose(dense.exact_zeta, -lam.real[:8] / abs(lam[:8]), rtol=1e-9)
    np.testing.assert_allclose(sparse.hysteretic_zeta, dense.hysteretic_zeta, rtol=1e-9)
    np.testing.assert_allclose(sparse.exact_damped_omega, dense.exact_damped_omega,
                               rtol=1e-11)


def test_polyharmonic_k1_equates_dissipated_power():
    assert polyharmonic_k1([1.0], [7.0]) == 1.0
    a, w, psi, c = np.array([1.0, 0.4, 0.1]), np.array([2.0, 9.0, 31.0]), 0.3, 5.0e4
    k1 = polyharmonic_k1(a, w)
    b = psi * c / (2 * np.pi * w[0] * k1)                 # Heletiy (2016) eq. 13
    # the dashpot's power over a whole number of common periods (2 pi) equals the
    # absorbed power, psi times the peak strain energy once per cycle of each harmonic
    t = np.linspace(0, 2 * np.pi, 200_001)[:-1]
    v = (a[:, None] * w[:, None] * np.cos(w[:, None] * t)).sum(axis=0)
    dashpot = b * np.mean(v**2)
    absorbed = np.sum(psi * 0.5 * c * a**2 * w / (2 * np.pi))
    assert dashpot == pytest.approx(absorbed, rel=1e-12)
    # vectorised over elements; a zero first amplitude is allowed
    amps = np.array([[1.0, 0.4, 0.1], [0.0, 1.0, 0.0], [2.0, 0.0, 0.0]])
    np.testing.assert_allclose(polyharmonic_k1(amps, w), [k1, 4.5, 1.0], rtol=1e-14)


def test_cli_contract_and_scene(tmp_path, capsys):
    scene = tmp_path / "s.yaml"
    scene.write_text(f"cranefe: 1\nmodel: {HOIST}\neffects: {{damping: exact}}\n"
                     "analysis: {type: damping, count: 3}\n")
    assert main(["damping", str(scene), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["method"] == "exact" and doc["dofs"] == 3 and len(doc["modes"]) == 3
    hoist = doc["modes"][2]
    assert {"index", "frequency_hz", "damping_ratio", "damped_frequency_hz",
            "log_decrement", "coupling", "exact"} <= set(hoist)
    assert hoist["exact"]["damping_ratio"] == pytest.approx(0.2 / (4 * np.pi))
    assert hoist["exact"]["damped_frequency_hz"] == pytest.approx(
        hoist["damped_frequency_hz"], rel=1e-9)
    # the same modes, in the same order, as `cranefe modes`
    assert main(["modes", HOIST, "--json"]) == 0
    modes = json.loads(capsys.readouterr().out)["modes"]
    assert [m["frequency_hz"] for m in modes] == pytest.approx(
        [m["frequency_hz"] for m in doc["modes"]])
    # analysis.method wins over effects.damping; --method over both
    scene.write_text(f"cranefe: 1\nmodel: {HOIST}\neffects: {{damping: exact}}\n"
                     "analysis: {type: damping, method: modal}\n")
    assert main(["damping", str(scene), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["method"] == "modal" and "exact" not in doc["modes"][2]
    assert main(["damping", str(scene), "--json", "--method", "both", "--count", "2"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["method"] == "both" and len(doc["modes"]) == 2


def test_cli_exit_codes(tmp_path, capsys):
    assert main(["damping", str(tmp_path / "missing.yaml")]) == 2
    assert main(["damping", HOIST, "--count", "0"]) == 2
    scene = tmp_path / "s.yaml"
    scene.write_text(f"cranefe: 1\nmodel: {HOIST}\nanalysis: {{type: damping, "
                     "method: rayleigh}\n")
    assert main(["damping", str(scene)]) == 2
    assert "analysis.method" in capsys.readouterr().err
    with pytest.raises(SystemExit) as exc:                   # argparse: a bad choice
        main(["damping", HOIST, "--method", "rayleigh"])
    assert exc.value.code == 2
    buckled = tmp_path / "buckled.yaml"                      # valid, but unstable
    buckled.write_text("""cranefe: 1
plane: xz
nodes: {O: [0, 0, 0], T: [0, 0, 12]}
ground: [O]
masses: {T: 2.0e5}
members:
  col: {type: beam, nodes: [O, T], E: 2.1e11, A: 1.0e-3, Iy: 1.0e-6, rho: 0,
        elements: 8, psi: 0.05}
effects: {structure: flexible}
""")
    capsys.readouterr()
    assert main(["damping", str(buckled)]) == 1
    err = capsys.readouterr().err
    assert "not a stable equilibrium" in err and "Traceback" not in err


def test_archive_keeps_the_result(tmp_path, capsys):
    from cranefe.outputs.archive import read
    out = tmp_path / "d.h5"
    assert main(["damping", HOIST, "--method", "both", "--archive", str(out)]) == 0
    back = read(out).results["damping"]
    assert back.zeta[2] == pytest.approx(0.2 / (4 * np.pi))
    assert back.exact_zeta[2] == pytest.approx(0.2 / (4 * np.pi))


def test_modes_of_a_scene_with_damping(tmp_path, capsys):
    scene = tmp_path / "s.yaml"
    scene.write_text(f"cranefe: 1\nmodel: {HOIST}\neffects: {{damping: modal}}\n")
    assert main(["modes", str(scene), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    # the damping entries follow the modes, rigid one first
    assert len(doc["damping"]) == len(doc["modes"]) == 3
    assert doc["damping"][2]["damping_ratio"] == pytest.approx(0.2 / (4 * np.pi))


# The damping study (`cranefe study damping --quick`) and its values: 
# tests/test_studies.py::check_damping.


SERIES = """cranefe: 1
name: massless block in series
plane: xz
nodes: {S: [0, 0, 20], D: [0, 0, 12], B: [0, 0, 5]}
ground: [S]
masses: {B: 2000}
ropes:
  r1: {EA: 1.0e7, psi: 0.2, path: [S, {node: D, falls: 2}]}
  r2: {EA: 2.0e7, path: [D, {node: B, falls: 3}]}
"""


def test_massless_block_beside_a_dashpot_keeps_the_oscillating_root(tmp_path):
    # Block D is massless; only the upper rope absorbs. Viscously damped, D has a real
    # relaxation root whose shape on the mass is the hoist mode's own: the exact answer
    # once picked it (zeta = 1). With x = z_B, y = z_D: m x'' + k2 (x - y) = 0 and
    # k1 y + b y' = k2 (x - y), so m b s^3 + m (k1 + k2) s^2 + k2 b s + k1 k2 = 0 with
    # k1 = 2^2 EA1 / 16 m, k2 = 3^2 EA2 / 21 m, b = psi k1 / (2 pi w) at the undamped w.
    import mpmath
    mpmath.mp.dps = 30
    path = tmp_path / "series.yaml"
    path.write_text(SERIES)
    m = mpmath.mpf(2000)
    k1, k2 = 4 * mpmath.mpf("1e7") / 16, 9 * mpmath.mpf("2e7") / 21
    w = mpmath.sqrt(k1 * k2 / (k1 + k2) / m)
    b = mpmath.mpf("0.2") * k1 / (2 * mpmath.pi * w)
    coef = [m * b, m * (k1 + k2), k2 * b, k1 * k2]
    start = next(r for r in np.roots([float(c) for c in coef]) if r.imag > 0)
    lam = mpmath.findroot(lambda s: ((coef[0] * s + coef[1]) * s + coef[2]) * s + coef[3],
                          mpmath.mpc(start))
    zeta_exact = float(-mpmath.re(lam) / abs(lam))
    r = damping(load(path), "both")
    hoist = int(np.argmax(r.zeta))
    assert r.omega[hoist] == pytest.approx(float(w), rel=1e-12)
    # QZ then refined by inverse iteration: to round-off of the 1e4 spread of the roots
    assert r.exact_zeta[hoist] == pytest.approx(zeta_exact, rel=1e-9)
    assert r.exact_damped_omega[hoist] == pytest.approx(float(mpmath.im(lam)), rel=1e-9)


COUPLED = """cranefe: 1
name: two close oscillators
plane: xz
nodes: {G1: [0, 0, 0], A: [0, 0, 1], B: [0, 0, 2], G2: [0, 0, 3]}
ground: [G1, G2]
masses: {A: 1000, B: 1000}
springs:
  - {name: ka, type: axial, nodes: [G1, A], stiffness: 1.0e6, psi: 0.0}
  - {name: kb, type: axial, nodes: [B, G2], stiffness: 1.01e6, psi: 0.6}
  - {name: kab, type: axial, nodes: [A, B], stiffness: 1.0e4, psi: 0.0}
effects: {sway: false, damping: modal}
"""


def test_modes_of_a_damping_scene_see_partners_beyond_the_count(tmp_path, capsys):
    # `modes --count 1` once judged mode 1's coupling without mode 2 (coupling 0, "weak")
    # and its JSON dropped the damping warnings
    path = tmp_path / "coupled.yaml"
    path.write_text(COUPLED)
    assert main(["damping", str(path), "--count", "1", "--json"]) == 0
    ref = json.loads(capsys.readouterr().out)
    assert main(["modes", str(path), "--count", "1", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    mine, theirs = doc["damping"][0], ref["modes"][0]
    assert mine == {k: theirs[k] for k in mine}
    assert doc["damping"][0]["coupling"] > 0.5 and not doc["damping"][0]["weak_coupling"]
    assert any("weak-coupling criterion fails" in w for w in doc["warnings"])
