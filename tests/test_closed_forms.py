"""Natural frequencies against closed forms (issue: core, acceptance)."""

from dataclasses import replace

import numpy as np
import pytest

from cranefe.system import assemble
from cranefe.cli import main
from cranefe.condense import condense
from cranefe.analysis.modal import drive_reduction, modes

G = 9.81
# Closed forms are exact for the linear model; only round-off remains.
RTOL = 1e-10


def hoist_yaml(falls, brake, sway=False, J=100.0, rotor=1.0, gear=20.0, R=0.25, m=5000.0,
               EA=2.0e7):
    return f"""
    cranefe: 1
    name: hoist {falls}
    plane: xz
    nodes: {{D: [0, 0, 0], S: [0, 0, 30], B: [0, 0, 10]}}
    ground: [D, S]
    masses: {{B: {m}}}
    drums:
      hoist: {{node: D, radius: {R}, inertia: {J}, brake: {str(brake).lower()},
              motor: {{rotor_inertia: {rotor}, gear_ratio: {gear}}}}}
    ropes:
      hoist: {{EA: {EA}, path: [hoist, S, {{node: B, falls: {falls}}}]}}
    effects: {{sway: {str(sway).lower()}}}
    """


def elastic(result):
    return result.omega[~result.rigid]


@pytest.mark.parametrize("falls", [1, 2, 3, 4])
@pytest.mark.parametrize("brake", [True, False])
def test_two_mass_hoist(model_from, falls, brake):
    # L = 30 (drum to sheave) + 20 n; load moves 1/n of the rope hauled in:
    # braked w^2 = n^2 k / m; free drum w^2 = k (n^2/m + R^2/J), J = J_d + J_r i^2.
    r = modes(model_from(hoist_yaml(falls, brake)))
    k = 2.0e7 / (30 + 20 * falls)
    J = 100 + 1.0 * 20**2
    w2 = falls**2 * k / 5000 if brake else k * (falls**2 / 5000 + 0.25**2 / J)
    assert elastic(r) == pytest.approx([np.sqrt(w2)], rel=RTOL)
    assert r.rigid.sum() == (0 if brake else 1)
    assert r.quasi_cyclic == (() if brake else ("drum hoist",))


def test_drive_reduction_error_is_dimensionless_formula(model_from):
    # Relative error of w^2 of the shortcut (eq. 10): m r^2 / (m r^2 + J), r = R / n.
    falls, R, J, m = 2, 0.25, 500.0, 5000.0
    model = model_from(hoist_yaml(falls, False, J=J, rotor=0.0))
    reduced = modes(model, replace(model.effects, drive="reduced"))
    err = drive_reduction(model, reduced)["modes"][0]["relative_error"]
    r = R / falls
    expected_w2 = m * r**2 / (m * r**2 + J)
    assert (1 + err) ** 2 == pytest.approx(1 - expected_w2, rel=RTOL)


def test_tackles_in_series_through_massless_block(model_from):
    # A (ground) --p falls-- D (massless) --m falls-- B: k_eff = 1/(1/(p^2 k1) + 1/(m^2 k2))
    p, m_, l1, l2, mass = 3, 2, 12.0, 8.0, 4000.0
    text = f"""
    cranefe: 1
    plane: xz
    nodes: {{A: [0, 0, 40], D: [0, 0, {40 - l1}], B: [0, 0, {40 - l1 - l2}]}}
    ground: [A]
    masses: {{B: {mass}}}
    ropes:
      luff: {{EA: 3.0e7, path: [A, {{node: D, falls: {p}}}]}}
      hoist: {{EA: 2.0e7, path: [D, {{node: B, falls: {m_}}}]}}
    """
    model = model_from(text)
    k1, k2 = 3.0e7 / (p * l1), 2.0e7 / (m_ * l2)
    keff = 1 / (1 / (p**2 * k1) + 1 / (m_**2 * k2))
    r = modes(model)
    # sway on: the block is massless, so the hook swings on l1 + l2
    assert np.sort(r.omega) == pytest.approx(
        np.sort([np.sqrt(G / (l1 + l2)), np.sqrt(keff / mass)]), rel=RTOL)
    assert len(r.massless) == 2
    r_off = modes(model, replace(model.effects, sway=False))
    assert r_off.omega == pytest.approx([np.sqrt(keff / mass)], rel=RTOL)


@pytest.mark.parametrize("pose, sign", [("down", 1), ("up", -1), ("level", 0)])
def test_hinged_bar_with_spring_and_gravity(model_from, pose, sign):
    # I_O th'' + (k + sign m g l) th = 0; I_O = I_c + m l^2 (level: gravity adds nothing)
    m, l, Ic, k = 800.0, 3.0, 900.0, 2.0e5
    com = {"down": [0, 0, -l], "up": [0, 0, l], "level": [l, 0, 0]}[pose]
    text = f"""
    cranefe: 1
    plane: xz
    nodes: {{O: [0, 0, 0], E: {[2 * c for c in com]}}}
    bodies:
      bar: {{mass: {m}, com: {com}, inertia: {Ic}, nodes: [O, E]}}
    joints:
      - {{type: hinge, bodies: [ground, bar], at: O}}
    springs:
      - {{name: s, type: rotational, bodies: [ground, bar], at: O, stiffness: {k}}}
    """
    r = modes(model_from(text))
    assert r.omega == pytest.approx([np.sqrt((k + sign * m * G * l) / (Ic + m * l**2))],
                                    rel=RTOL)


def test_bar_without_spring_is_a_physical_pendulum(model_from):
    m, l, Ic = 300.0, 2.0, 150.0
    text = f"""
    cranefe: 1
    plane: xz
    nodes: {{O: [0, 0, 5]}}
    bodies:
      bar: {{mass: {m}, com: [0, 0, {5 - l}], inertia: {Ic}, nodes: [O]}}
    joints:
      - {{type: hinge, bodies: [ground, bar], at: O}}
    """
    r = modes(model_from(text))
    assert r.omega == pytest.approx([np.sqrt(m * G * l / (Ic + m * l**2))], rel=RTOL)


def pendulum_yaml(falls=1, l=12.0, m=2000.0, planar=True, extra=""):
    return f"""
    cranefe: 1
    {"plane: xz" if planar else ""}
    nodes: {{S: [0, 0, 30], B: [0, 0, {30 - l}]}}
    ground: [S]
    masses: {{B: {m}}}
    ropes:
      r: {{EA: 1.0e7, path: [S, {{node: B, falls: {falls}}}]}}
    {extra}
    """


@pytest.mark.parametrize("falls", [1, 2, 4])
def test_single_and_tackle_hung_pendulum(model_from, falls):
    l, m = 12.0, 2000.0
    r = modes(model_from(pendulum_yaml(falls, l, m)))
    k = 1.0e7 / (falls * l)
    assert r.omega == pytest.approx([np.sqrt(G / l), np.sqrt(falls**2 * k / m)], rel=RTOL)


def test_spatial_pendulum_has_a_repeated_pair(model_from):
    l, m = 12.0, 2000.0
    r = modes(model_from(pendulum_yaml(1, l, m, planar=False)))
    assert r.omega == pytest.approx([np.sqrt(G / l)] * 2 + [np.sqrt(1.0e7 / l / m)], rel=RTOL)
    # a repeated pair still has M-orthonormal shapes
    M = assemble(model_from(pendulum_yaml(1, l, m, planar=False))).M.toarray()
    assert r.shapes.T @ M @ r.shapes == pytest.approx(np.eye(3), abs=1e-12)


def test_double_pendulum_quartic(model_from):
    # m1 l1 l2 w^4 - (m1 + m2) g (l1 + l2) w^2 + (m1 + m2) g^2 = 0
    from cranefe.cases import double_pendulum
    text, exact = double_pendulum()
    r = modes(model_from(text))
    assert r.omega[:2] == pytest.approx(exact["omega"], rel=RTOL)


def test_inextensible_ropes_leave_only_the_pendulum_modes(model_from):
    text = pendulum_yaml(2, extra="effects: {rope_elasticity: false}")
    r = modes(model_from(text))
    assert r.omega == pytest.approx([np.sqrt(G / 12.0)], rel=RTOL)


def free_chain_yaml(m1=1000.0, m2=2000.0, k=1.0e6):
    return f"""
    cranefe: 1
    plane: xz
    gravity: [0, 0, 0]
    nodes: {{A: [0, 0, 0], B: [1, 0, 0]}}
    masses: {{A: {m1}, B: {m2}}}
    springs:
      - {{name: k, type: axial, nodes: [A, B], stiffness: {k}}}
    effects: {{sway: false}}
    """


def test_free_free_chain_exactly_one_zero_frequency(model_from, capsys, tmp_path):
    # w^2 = k (1/m1 + 1/m2) = 1500 s^-2 and one rigid mode; a general FE code's default
    # eigensolver returns 500 here (it cannot factor the singular K).
    r = modes(model_from(free_chain_yaml()))
    assert r.rigid.tolist() == [True, False]
    assert r.omega[0] == 0.0
    assert r.omega[1] ** 2 == pytest.approx(1500.0, rel=RTOL)
    # the rigid mode is a uniform translation, mass-normalised
    assert r.shapes[:, 0] == pytest.approx([1 / np.sqrt(3000)] * 2, rel=1e-12)
    # and the sparse path agrees
    rs = modes(model_from(free_chain_yaml()), solver="sparse", count=1)
    assert rs.rigid.tolist() == [True]


def test_scaling_all_masses(model_from):
    # all masses x s -> elastic frequencies / sqrt(s) (sway off: no mass-proportional
    # stiffness); with sway on, masses and stiffnesses x s leave every frequency unchanged
    base = modes(model_from(hoist_yaml(3, False)))
    s = 7.3
    scaled = modes(model_from(hoist_yaml(3, False, J=100 * s, rotor=1.0 * s, m=5000 * s)))
    assert elastic(scaled) == pytest.approx(elastic(base) / np.sqrt(s), rel=RTOL)
    on = modes(model_from(hoist_yaml(3, False, sway=True)))
    on_s = modes(model_from(hoist_yaml(3, False, sway=True, J=100 * s, rotor=1.0 * s,
                                       m=5000 * s, EA=2.0e7 * s)))
    assert elastic(on_s) == pytest.approx(elastic(on), rel=1e-9)


def test_schur_and_sequential_condensation_agree(model_from):
    # two independent hoists and a free chain: three quasi-cyclic coordinates
    text = """
    cranefe: 1
    plane: xz
    nodes: {D1: [0, 0, 0], S1: [0, 0, 30], B1: [0, 0, 10],
            D2: [5, 0, 0], S2: [5, 0, 25], B2: [5, 0, 12]}
    ground: [D1, S1, D2, S2]
    masses: {B1: 5000, B2: 3000}
    drums:
      h1: {node: D1, radius: 0.25, inertia: 300}
      h2: {node: D2, radius: 0.3, inertia: 200, motor: {rotor_inertia: 0.5, gear_ratio: 30}}
    ropes:
      r1: {EA: 2.0e7, path: [h1, S1, {node: B1, falls: 2}]}
      r2: {EA: 1.5e7, path: [h2, S2, {node: B2, falls: 3}]}
    """
    system = assemble(model_from(text))
    a, b = condense(system, "schur"), condense(system, "sequential")
    assert set(a.quasi_cyclic) == {"drum h1", "drum h2"}
    assert b.M == pytest.approx(a.M, rel=1e-13)
    assert np.all(np.linalg.eigvalsh(a.K) > 0) and np.all(np.linalg.eigvalsh(a.M) > 0)
    r = modes(system.model, system=system)
    K, M = system.K.toarray(), system.M.toarray()
    assert r.shapes.T @ M @ r.shapes == pytest.approx(np.eye(len(r.omega)), abs=1e-10)
    assert r.shapes.T @ K @ r.shapes == pytest.approx(np.diag(r.omega**2), abs=1e-6)


def test_cli_json_contract(tmp_path, capsys):
    import json
    path = tmp_path / "h.yaml"
    import textwrap
    path.write_text(textwrap.dedent(hoist_yaml(2, False)))
    assert main(["modes", str(path), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["dofs"] == 2 and doc["quasi_cyclic"] == ["drum hoist"]
    assert doc["modes"][0]["frequency_hz"] == 0.0 and doc["modes"][0]["period_s"] is None
    assert doc["modes"][1]["omega_rad_s"] == pytest.approx(
        np.sqrt(2.0e7 / 70 * (4 / 5000 + 0.0625 / 500)), rel=1e-10)
    assert {"assemble", "solve"} <= set(doc["timings_s"])
