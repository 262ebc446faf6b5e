"""Members (structure: flexible) against closed forms and hand-assembled references."""

from dataclasses import replace

import numpy as np
import pytest

from cranefe.cases import matched
from cranefe.analysis.modal import modes

G = 9.81
E, A, I, RHO = 2.1e11, 1.0e-2, 2.0e-4, 7850.0
BETA_L = np.array([1.875104068711961, 4.694091132974175, 7.854757438237613])


def cantilever(model_from, N, planar=True, mass="consistent"):
    text = f"""
    cranefe: 1
    {"plane: xz" if planar else ""}
    gravity: [0, 0, 0]
    nodes: {{O: [0, 0, 0], T: [10, 0, 0]}}
    ground: [O]
    members:
      b: {{type: beam, nodes: [O, T], E: {E}, G: 8.1e10, A: {A}, Iy: {I}, Iz: {4 * I},
          J: 1.0e-4, rho: {RHO}, elements: {N}, mass: {mass},
          orientation: [0, 0, 1]}}
    effects: {{structure: flexible}}
    """
    return modes(model_from(text, f"c{N}{planar}{mass}.yaml"))


@pytest.mark.parametrize("planar", [True, False])
def test_cantilever_converges_with_order_four(model_from, planar):
    # consistent cubic (Hermite) elements: frequency error O(h^4)
    exact = BETA_L**2 * np.sqrt(E * I / (RHO * A)) / 10**2
    Ns = [2, 4, 8, 16]
    err = []
    for N in Ns:
        w = cantilever(model_from, N, planar).omega
        # 3D: bending with Iy (in x-z) as in the plane, and with Iz = 4 Iy at twice the
        # frequencies, besides torsion and axial modes
        err.append(matched(w, exact) / exact - 1)
        if not planar:
            # same discretisation error by similarity (to 1e-9 of w: the 3D beam is a
            # graded problem, solved by Jacobi SVD to about 1e-10 relative)
            assert matched(w, 2 * exact[:1]) / (2 * exact[0]) - 1 == pytest.approx(
                err[-1][0], abs=1e-9)
    err = np.array(err)
    assert np.all(err > 0)                          # consistent mass: upper bounds
    slope = -np.polyfit(np.log(Ns[1:]), np.log(err[1:, 0]), 1)[0]
    assert slope == pytest.approx(4.0, abs=0.1)
    assert err[-1, 0] < 2e-7


def test_truss_matches_a_hand_assembled_reference(model_from):
    # two bars from supports A and B to a free node C carrying m; lumped bar mass
    m, rho = 500.0, 7850.0
    pts = {"A": np.array([0.0, 0, 0]), "B": np.array([6.0, 0, 0]), "C": np.array([2.0, 0, -3.0])}
    text = f"""
    cranefe: 1
    plane: xz
    gravity: [0, 0, 0]
    nodes: {{A: [0, 0, 0], B: [6, 0, 0], C: [2, 0, -3]}}
    ground: [A, B]
    masses: {{C: {m}}}
    members:
      ac: {{type: truss, nodes: [A, C], E: {E}, A: {A}, rho: {rho}, mass: lumped}}
      bc: {{type: truss, nodes: [B, C], E: {E}, A: 2.0e-2, rho: {rho}, mass: lumped}}
    effects: {{structure: flexible, sway: false}}
    """
    K = np.zeros((2, 2))
    Mc = m
    for a, area in (("A", A), ("B", 2.0e-2)):
        d = (pts["C"] - pts[a])[[0, 2]]
        L = np.linalg.norm(d)
        e = d / L
        K += E * area / L * np.outer(e, e)
        Mc += rho * area * L / 2
    w2 = np.linalg.eigvalsh(K / Mc)
    r = modes(model_from(text))
    assert r.omega == pytest.approx(np.sqrt(w2), rel=1e-12)


def k_compressed(EI, L, P):
    """Tip stiffness of a massless cantilever under axial compression P (exact):
    k = P / (L (tan(kL)/(kL) - 1)), k = sqrt(P/EI)."""
    kl = np.sqrt(P / EI) * L
    return P / (L * (np.tan(kl) / kl - 1))


def test_p_delta_lowers_a_loaded_column_as_the_closed_form(model_from):
    # massless vertical column, clamped, top mass M: w^2 = k(P)/M with P = M g
    from cranefe.cases import loaded_column
    text, exact = loaded_column()      # P = M g is 0.27 of the Euler load pi^2 EI / 4 L^2
    model = model_from(text)
    on, off = modes(model), modes(model, replace(model.effects, sway=False))
    w_on = on.omega[0]
    assert off.omega[0] == pytest.approx(exact["omega_no_sway"][0], rel=1e-9)
    # the cubic geometric stiffness converges at O(h^2) to the exact k(P): 16 elements
    assert w_on == pytest.approx(exact["omega"][0], rel=2e-6)
    assert w_on < off.omega[0]


def test_beam_tower_with_a_hanging_load_is_the_two_dof_model(model_from):
    # massless tower (tip stiffness with P-delta), top mass mt, pendulum load ml on l
    L, mt, ml, l = 30.0, 8.0e3, 5.0e3, 20.0
    EI = E * I * 50
    text = f"""
    cranefe: 1
    plane: xz
    nodes: {{O: [0, 0, 0], T: [0, 0, {L}], H: [0, 0, {L - l}]}}
    ground: [O]
    masses: {{T: {mt}, H: {ml}}}
    members:
      tower: {{type: beam, nodes: [O, T], E: {E}, A: {A}, Iy: {I * 50}, rho: 0,
              elements: 24}}
    ropes:
      hoist: {{EA: 1.0e12, path: [T, H]}}
    effects: {{structure: flexible}}
    """
    r = modes(model_from(text))
    kt = k_compressed(EI, L, (mt + ml) * G)
    kp = ml * G / l
    K = np.array([[kt + kp, -kp], [-kp, kp]])
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(np.diag([mt, ml]), K)).real)
    assert r.omega[:2] == pytest.approx(np.sqrt(w2), rel=1e-5)


def test_lumped_beam_mass_converges_too(model_from):
    # lumped (diagonal) mass with cubic stiffness: the first three frequencies converge
    # as N^-2 from below (mass lumped at the nodes: measured -1.79e-3, -6.2e-3, -1.0e-2 at
    # N = 16). Slopes over N = 8, 16, 32 within 0.05 of 2, and Richardson's extrapolation
    # (4 e_32 - e_16) / 3 leaves < 3e-5 of the mode's error: the limit is the exact
    # frequency (a wrong mass or stiffness would converge elsewhere)
    exact = BETA_L**2 * np.sqrt(E * I / (RHO * A)) / 10**2
    Ns = np.array([8, 16, 32])
    errs = np.array([cantilever(model_from, N, mass="lumped").omega[:3] / exact - 1
                     for N in Ns])                                  # (N, mode)
    assert np.all(errs < 0)
    for k in range(3):
        slope = -np.polyfit(np.log(Ns), np.log(-errs[:, k]), 1)[0]
        assert slope == pytest.approx(2.0, abs=0.05)
    richardson = (4 * errs[2] - errs[1]) / 3
    assert np.all(np.abs(richardson) < 3e-5)
    assert errs[1, 0] == pytest.approx(-1.789e-3, rel=1e-3)     # measured, N = 16


def test_column_loaded_past_euler_is_reported_unstable(model_from, tmp_path, capsys):
    from cranefe.cli import main
    text = f"""
cranefe: 1
plane: xz
nodes: {{O: [0, 0, 0], T: [0, 0, 12]}}
ground: [O]
masses: {{T: 2.0e5}}
members:
  col: {{type: beam, nodes: [O, T], E: {E}, A: {A}, Iy: {I}, rho: 0, elements: 8}}
effects: {{structure: flexible}}
"""
    path = tmp_path / "buckled.yaml"
    path.write_text(text)
    assert main(["modes", str(path)]) == 1
    assert "not a stable equilibrium" in capsys.readouterr().err


@pytest.mark.parametrize("solver", ["dense", "sparse"])
@pytest.mark.parametrize("factor", [1.001, 1.1])
def test_column_just_past_its_self_weight_buckling_is_an_error(model_from, solver, factor):
    # w^2 of the first mode falls linearly to zero at the critical weight (Greenhill,
    # test_structures), so 0.1 % past it w^2 = -1.6e-3 s^-2: far below the round-off of
    # the element energies (1e-13 of them), but below 1e-9 of the largest w^2 of the mesh
    # too, which once let it pass as a 0 Hz mode
    from cranefe.analysis.modal import modes as solve
    from cranefe.cases import self_weight_column
    from cranefe.errors import AnalysisError
    from cranefe.system import assemble
    crit = self_weight_column()[1]["critical"]
    model = model_from(self_weight_column(parameter=crit * factor)[0])
    with pytest.raises(AnalysisError, match="not a stable equilibrium"):
        solve(model, count=3, solver=solver, system=assemble(model))
