"""Energy-optimal luffing (issue 7; Loveikin et al. 2013): kinematics against the paper's
closed forms (eq. 12-15) and finite differences, the exact optimum of eq. 16, the paper's
collocation and its corrections, n-point collocation, laws, sway."""

import os

import numpy as np
import pytest

from cranefe.analysis.luffing.analysis import Luffing, analyse, read_scene
from cranefe.analysis.luffing.cases import paper_linkage
from cranefe.analysis.luffing.energy import Reduced
from cranefe.analysis.luffing.kinematics import Linkage
from cranefe.analysis.luffing.optimum import (GRID, bvp, chebyshev_points, collocation,
                                     equally_spaced, law_error, paper_collocation,
                                     paper_map, paper_trial)
from cranefe.model import load

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODEL = os.path.join(ROOT, "models", "portal_crane_luffing.yaml")
SCENE = os.path.join(ROOT, "models", "portal_crane_luffing_scene.yaml")


@pytest.fixture(scope="module")
def crane():
    model = load(SCENE)
    return Luffing(model, read_scene(model, SCENE), SCENE)


@pytest.fixture(scope="module")
def result():
    """The analysis without its sensitivity report (12 of its 21 s, eight swing-free
    boundary-value problems); test_sensitivity_report makes the report itself."""
    return analyse(load(SCENE), file=SCENE, sensitivity=False)


@pytest.fixture(scope="module")
def paper_case(tmp_path_factory):
    text, exact = paper_linkage()
    path = tmp_path_factory.mktemp("luff") / "paper.yaml"
    path.write_text(text)
    model = load(path)
    lk = Linkage(model, "boom", "O", "B")
    return model, lk, exact


def _fd(fun, a, h=5e-4):
    """Fourth-order central difference: truncation ~h^4 f^(5)/30 (~1e-9 relative at the
    small-reach end, where the jib turns fastest), round-off ~1e-16 |f| / h."""
    return (-fun(a + 2 * h) + 8 * fun(a + h) - 8 * fun(a - h) + fun(a - 2 * h)) / (12 * h)


# ------------------------------------------------------------------ kinematics
def test_loop_closure_to_1e12(crane):
    lk = crane.linkage
    al = np.linspace(crane.alpha0, crane.alphak, 61)
    st = lk.state(al)
    assert st.residual.max() < 1e-12                     # |Phi| in m (hinges)
    idx = crane.model.node_index
    ref = crane.model.coords[:, [0, 2]]
    for a, b, body in (("O", "B", "boom"), ("E", "F", "backstay"), ("P", "Q", "rod"),
                       ("G", "W", "rocker"), ("B", "D", "jib")):
        k = [x.name for x in crane.model.bodies].index(body)
        pa, pb = st.point(idx[a], k)[0], st.point(idx[b], k)[0]
        length = np.linalg.norm(ref[idx[b]] - ref[idx[a]])
        assert np.abs(np.linalg.norm(pb - pa, axis=1) - length).max() < 1e-12
    # every hinge node carried by its two bodies coincides
    for j in lk.joints:
        x = [st.point(j.at, b)[0] for b in j.bodies if b != -1]
        if len(x) == 2:
            assert np.abs(x[0] - x[1]).max() < 1e-12


def test_transfer_functions_match_paper_eq12_to_eq15(paper_case):
    model, lk, exact = paper_case
    al = np.radians(np.linspace(40, 75, 36))
    st = lk.state(al)
    jib = [b.name for b in model.bodies].index("jib")
    _, w, dw = st.angle(jib)
    d1, d2 = exact["jib"](al)
    # the paper measures the jib angle phi3 clockwise: dtheta = -dphi3
    np.testing.assert_allclose(-w, d1, rtol=1e-12)           # eq. 12
    np.testing.assert_allclose(-dw, d2, rtol=1e-11, atol=1e-13)   # eq. 13
    red = Reduced(lk, model.linear_drives[0], model.node_index["D"])
    v = red.evaluate(al)
    m1, m2 = exact["motor"](al)
    np.testing.assert_allclose(red.ratio * v["ds"], m1, rtol=1e-12)    # eq. 14
    np.testing.assert_allclose(red.ratio * v["dds"], m2, rtol=1e-12)   # eq. 15
    assert np.abs(v["z"] - exact["H"]).max() < 1e-12          # the tip on z = H
    assert np.abs(v["dz"]).max() < 1e-12


def test_transfer_functions_against_finite_differences(crane):
    red = crane.reduced
    al = np.linspace(crane.alpha0, crane.alphak, 9)
    v = red.evaluate(al)
    st = crane.linkage.state(al)
    for name, d in (("J", "dJ"), ("Jp", "dJp"), ("V", "dV"), ("s", "ds"), ("ds", "dds"),
                    ("x", "dx"), ("dx", "ddx"), ("z", "dz"), ("dz", "ddz")):
        fd = _fd(lambda a, n=name: red.evaluate(a)[n], al)
        assert np.abs(fd - v[d]).max() <= 1e-8 * np.abs(v[d]).max(), name
    fd = _fd(lambda a: crane.linkage.state(a).q, al)
    assert np.abs(fd - st.dq).max() <= 1e-8 * np.abs(st.dq).max()
    fd = _fd(lambda a: crane.linkage.state(a).dq, al)
    assert np.abs(fd - st.ddq).max() <= 1e-8 * np.abs(st.ddq).max()


def test_paper_inertia_differs_by_the_jibs_translation(crane):
    """Eq. 3 takes each link about its own axis; for links hinged to the ground that is
    exact, so J - J_paper is the translational energy of the coupler links only."""
    red = crane.reduced
    al = np.linspace(crane.alpha0, crane.alphak, 7)
    v = red.evaluate(al)
    st = crane.linkage.state(al)
    jib = [b.name for b in crane.model.bodies].index("jib")
    body = crane.model.bodies[jib]
    dX = st.body_point(jib, np.zeros(2))[1]
    np.testing.assert_allclose(v["J"] - v["Jp"], body.mass * np.sum(dX**2, axis=1),
                               rtol=1e-10)


def test_example_crane_is_level_luffing_and_balanced(result):
    assert result.reach0 == pytest.approx(30.0, abs=1e-9)
    assert result.reachk == pytest.approx(8.0, abs=1e-9)
    # 67.11 mm, from the independent hand solution of the linkage
    # (test_values.py::test_portal_crane_jib_tip_stays_level_within_its_measured_deviation);
    # cranefe takes max - min of 801 samples: < 1e-7 m short of the true extremes
    assert result.jib_tip_deviation == pytest.approx(0.0671128, abs=1e-6)
    unbalanced = 2.0e6                                       # boom + jib + backstay alone
    assert result.imbalance_moment < 0.06 * unbalanced


# ------------------------------------------------------------------ the optimum
def test_exact_law_satisfies_eq16_and_boundary_conditions(crane):
    law = crane.optimal()
    al, d1, d2 = law.evaluate(np.array([0.0, 1.0]))
    assert al[0] == pytest.approx(crane.alpha0, abs=1e-14)
    assert al[1] == pytest.approx(crane.alphak, abs=1e-14)
    tau = np.linspace(0.05, 0.95, 19)
    a = law.evaluate(tau)[0]
    da = _fd(lambda t: law.evaluate(t)[0], tau, h=1e-3)      # independent of eq. 16
    dda = _fd(lambda t: _fd(lambda s: law.evaluate(s)[0], t, h=1e-3), tau, h=1e-3)
    v = crane.reduced.evaluate(a)                            # the kinematics itself
    energy = v["J"] * da**2                                  # J alpha.^2: constant
    assert np.ptp(energy) < 1e-9 * energy.mean()
    residual = v["J"] * dda + 0.5 * v["dJ"] * da**2          # Loveikin et al. eq. 16
    assert np.abs(residual).max() < 1e-6 * np.abs(0.5 * v["dJ"] * da**2).max()
    # and solve_bvp agrees
    sol = bvp(lambda x: crane.proxy.f(x), crane.alpha0, crane.alphak, tol=1e-10)
    assert law_error(sol, law) < 1e-9


def test_exact_law_against_adaptive_quadrature(crane):
    from cranefe.studies.luffing import check_reference
    assert check_reference(crane, crane.optimal()) < 1e-12


def test_corrected_collocation_equations_are_the_residuals():
    """Each line of the corrected eq. 21/25 is a residual of eq. 16 at t = 1/4, 1/2, 3/4
    solved for one coefficient: a - G(a) = -(r1/2, r2, 4 r3/9); the printed lines 2-3
    are not."""
    rng = np.random.default_rng(7)
    f = lambda al: 0.3 * np.sin(al) + 0.1                   # noqa: E731 any f(alpha)
    for _ in range(5):
        a = rng.normal(scale=0.3, size=3)
        al, d1, d2 = paper_trial(a, np.array([0.25, 0.5, 0.75]), 0.9, 1.4)
        r = d2 + f(al) * d1**2
        lhs = a - paper_map(a, f, 0.9, 1.4, "corrected")
        np.testing.assert_allclose(lhs, -np.array([r[0] / 2, r[1], 4 * r[2] / 9]),
                                   atol=1e-14)
        assert np.abs(a - paper_map(a, f, 0.9, 1.4, "printed")
                      + np.array([r[0] / 2, r[1], 4 * r[2] / 9])).max() > 1e-3


def test_paper_trial_values_at_the_collocation_points():
    """Corrected eq. 18-20 (the printed alpha. and alpha.. at 1/2 and 3/4 are wrong)."""
    a0, a1, a2 = 0.3, -0.7, 1.1
    D = 0.5
    al, d1, d2 = paper_trial([a0, a1, a2], np.array([0.25, 0.5, 0.75]), 0.0, D)
    np.testing.assert_allclose(d1, [D + a0 / 2 + 5 * a1 / 16 + a2 / 8, D + a1 / 4 + a2 / 4,
                                    D - a0 / 2 - 3 * a1 / 16], atol=1e-15)
    np.testing.assert_allclose(d2, [-2 * a0 + a1 / 2 + 3 * a2 / 4, -2 * a0 - a1,
                                    -2 * a0 - 5 * a1 / 2 - 9 * a2 / 4], atol=1e-14)
    np.testing.assert_allclose(al, [(D + 0.75 * (a0 + a1 / 4 + a2 / 16)) / 4,
                                    (D + 0.5 * (a0 + a1 / 2 + a2 / 4)) / 2,
                                    (D + 0.25 * (a0 + 0.75 * a1 + 9 * a2 / 16)) * 0.75],
                               atol=1e-15)


def test_paper_fixed_point_iteration(crane):
    f = crane.proxy.f
    exact = crane.optimal()
    printed = paper_collocation(f, crane.alpha0, crane.alphak, "printed")
    corrected = paper_collocation(f, crane.alpha0, crane.alphak, "corrected")
    relaxed = paper_collocation(f, crane.alpha0, crane.alphak, "corrected",
                                relax=corrected.info["relax_best"])
    # as printed it converges, to the wrong law
    assert printed.status == 0 and printed.info["spectral_radius"] < 1
    # corrected, plain fixed-point iteration diverges: spectral radius above 1
    assert corrected.status == 2 and corrected.info["spectral_radius"] > 1
    assert relaxed.status == 0 and relaxed.info["spectral_radius_relaxed"] < 1
    np.testing.assert_allclose(relaxed.evaluate(GRID)[0], corrected.evaluate(GRID)[0],
                               atol=1e-12)
    # the corrected fixed point is 3-point equally spaced collocation
    three = collocation(f, crane.alpha0, crane.alphak, equally_spaced(3))
    np.testing.assert_allclose(three.evaluate(GRID)[0], corrected.evaluate(GRID)[0],
                               atol=1e-12)
    assert law_error(printed, exact) > 20 * law_error(corrected, exact)


def test_collocation_error_falls_with_n(crane):
    exact = crane.optimal()
    for points in (equally_spaced, chebyshev_points):
        errors = [law_error(collocation(crane.proxy.f, crane.alpha0, crane.alphak,
                                        points(n)), exact) for n in range(2, 11)]
        assert all(b < a for a, b in zip(errors, errors[1:]))
        ratio = np.exp(np.polyfit(np.arange(2, 11), np.log(errors), 1)[0])
        assert ratio < 0.6              # geometric: x0.45 (equally spaced), x0.28 (Cheb.)
    assert errors[-1] < 1e-6


# ------------------------------------------------------------------ laws and sway
def test_optimum_is_below_every_other_law(result):
    T = {name: f["T_mean_J"] for name, f in result.table.items()}
    assert T["optimal"] == pytest.approx(result.optimum["T_mean_J"], rel=1e-12)
    for name, value in T.items():
        if name != "optimal":
            assert value > T["optimal"], name
    assert result.optimum["T_mean_paper_J"] < result.optimum["T_mean_J"]


def test_swing_free_law_has_no_residual_sway(result, crane):
    f = result.table["swing_free"]
    assert np.radians(f["residual_sway_linear_deg"]) < 1e-6
    assert np.radians(f["residual_sway_linear_exact_deg"]) < 1e-6
    assert f["T_ratio"] > 1                                # it costs energy
    assert result.table["optimal"]["residual_sway_linear_deg"] > 1


def test_sway_models(result):
    H = result.rope_length
    dx = abs(result.reachk - result.reach0)
    for name, f in result.table.items():
        # eq. 9 has no gravity: the load stays behind, psi = -(x - x0)/H
        assert np.radians(f["max_sway_paper_eq9_deg"]) == pytest.approx(dx / H, rel=1e-6)
        # the linear residual by the ODE and by its closed form agree
        assert f["residual_sway_linear_deg"] == pytest.approx(
            f["residual_sway_linear_exact_deg"], abs=1e-6)


def test_rest_to_rest_law(crane, result):
    from cranefe.analysis.luffing.laws import rest_to_rest_law
    excess = []
    for tau_c in (2.0, 1.0, 0.5):
        law = rest_to_rest_law(crane.proxy, crane.alpha0, crane.alphak, tau_c, 25.0)
        al, d1, _ = law.evaluate(np.array([0.0, 1.0]))
        assert np.allclose(al, [crane.alpha0, crane.alphak], atol=1e-13)
        assert np.abs(d1).max() < 1e-12                    # starts and ends at rest
        excess.append(crane.mean_energy(law) / result.optimum["T_mean_J"] - 1)
    assert 0 < excess[2] < excess[1] < excess[0]


def test_motor_torque_of_the_optimum_is_the_imbalance(crane):
    """Coasting: J alpha'' + J' alpha'^2/2 = 0, so the motor only holds the links' weight."""
    law = crane.optimal()
    tau = np.linspace(0, 1, 11)
    torque, _, Q, _ = crane.drive_terms(law, tau)
    al = law.evaluate(tau)[0]
    np.testing.assert_allclose(Q, crane.proxy("dV", al), rtol=1e-9, atol=1e-6)


def test_sensitivity_report(crane, result, monkeypatch):
    """The report's t_k and load-mass rows (the lines asserted here) of the scene's
    optimum. Its swing-free rows solve eight boundary-value problems (10 s, checked
    value by value by tests/test_golden_json.py's luff.portal_crane_luffing_scene and
    the kill tests of the sway module): a stand-in here, as in
    test_mutation_kills_luffing_configs.py's load-row test."""
    import cranefe.analysis.luffing.analysis as an
    from cranefe.analysis.luffing import sway
    from cranefe.analysis.luffing.laws import standard_law

    def fake_sf(proxy, alpha0, alphak, t_k, H, g, guess, which="complete"):
        law = standard_law("cycloidal", alpha0, alphak)
        law.status, law.message = 0, "stand-in"
        return law
    monkeypatch.setattr(sway, "swing_free_law", fake_sf)
    assert result.sensitivity == {}
    s = an.sensitivity_report(crane, crane.optimal())
    assert result.t_k == crane.scene.t_k
    for row in s["t_k"]:                         # T_mean = S^2 / (2 t_k^2) exactly
        assert row["T_over_base"] == pytest.approx((result.t_k / row["t_k_s"]) ** 2,
                                                   rel=1e-12)
    rows = s["load_mass"]
    assert rows[0]["max_law_difference_deg"] < 1e-9     # no load: the same optimum
    assert all(b["T_mean_with_load_J"] > a["T_mean_with_load_J"]
               for a, b in zip(rows, rows[1:]))
