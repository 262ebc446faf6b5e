"""Kill tests for cranefe/analysis/luffing/analysis.py (tools/mutation.py luffing_analysis;
docs/testing.md, "Mutation testing"): the luffing scene's keys, defaults and errors
(`read_scene`), the start and end given as angles or reaches, the figures of each law
(`Luffing.figures`), the optimum's report, the kinematics' summary and the arrays of
`analyse`, `law_figures`, the sensitivity and collocation reports' wiring and
`convergence_rate`, against a linkage whose every quantity is written out by hand.

The linkage: a parallelogram. Boom O-B (length L = 10, hinged to the ground at O =
(0, 0)), link F-E (the same length, hinged at F = (0, -2)) and a jib B-E-D joining their
ends, which therefore translates: B = L u(alpha), u = (cos, sin), the jib tip D = B +
(4, 0). Boom (1000 kg, I 8000, centre 5 u), link (200 kg, I 1500, centre F + 5 u), jib
(500 kg, I 700). A rack between A = (2, -3) (ground) and C = 4 u on the boom: s = |C -
A|, motor angle per alpha 500 s' (gear 100 / pinion 0.2), rotor 0.01 kg m^2. So
- J = 8000 + 1000 * 25 + 1500 + 200 * 25 + 500 L^2 + 0.01 * 500^2 s'^2 (the jib
  translates on a circle of radius L; docs/luffing.md's complete inertia),
- Jp = J - 500 L^2 (the paper's eq. 3: the jib turns about its own centre, by 0),
- dV/dalpha = g cos(alpha) (5 * 1000 + 5 * 200 + L * 500), tip x = L cos + 4, z = L sin.
The optimum of eq. 16 has J alpha'^2 constant: S = int sqrt(J) dalpha, T_mean = S^2 /
(2 t_k^2) (scipy's quad on the hand J); the standard laws' energies by quad too.
Time-critical pieces are replaced by stand-ins where their own kill tests cover them:
the swing-free law (a solve_bvp, 2 s; tests/test_mutation_kills_luffing_sway.py) by the
cycloidal law, whose arguments are recorded; the collocation and sensitivity reports in
`analyse` by markers (they are called on their own below). The sway figures are checked
against cranefe's sway module (value-tested in its own kill tests) fed by this law.
"""

import math
import os
import tempfile
import time
from dataclasses import replace
from functools import lru_cache

import numpy as np
import pytest
from scipy.integrate import cumulative_trapezoid, quad, trapezoid

import cranefe.analysis.luffing.analysis as an
import cranefe.analysis.luffing.sway as sway
from cranefe.analysis.luffing.laws import rest_to_rest_law, standard_law
from cranefe.errors import ModelError
from cranefe.model import load

L, E_OFF, A_REF = 10.0, 4.0, math.radians(30.0)
MB, IB, ML, IL, MJ, IJ = 1000.0, 8000.0, 200.0, 1500.0, 500.0, 700.0
IR, GEAR, PIN = 0.01, 100.0, 0.2
AX, AZ = 2.0, -3.0
G = 9.81
A0, AK, TK, MLOAD, H = math.radians(10.0), math.radians(50.0), 10.0, 1000.0, 5.0
RATIO = GEAR / PIN


def _p(x, z):
    return f"[{x!r}, 0, {z!r}]"


def model_text(extra=""):
    c, s = math.cos(A_REF), math.sin(A_REF)
    B = (L * c, L * s)
    return f"""cranefe: 1
name: parallelogram
plane: xz
nodes:
  O: [0.0, 0, 0.0]
  F: [0.0, 0, -2.0]
  B: {_p(*B)}
  E: {_p(B[0], B[1] - 2.0)}
  D: {_p(B[0] + E_OFF, B[1])}
  C: {_p(4 * c, 4 * s)}
  A: [{AX!r}, 0, {AZ!r}]
  Z: [30.0, 0, 30.0]
ground: [O, F, A]
bodies:
  boom: {{mass: {MB}, com: {_p(5 * c, 5 * s)}, inertia: {IB}, nodes: [O, B, C]}}
  link: {{mass: {ML}, com: {_p(5 * c, 5 * s - 2.0)}, inertia: {IL}, nodes: [F, E]}}
  jib: {{mass: {MJ}, com: {_p(B[0] + 2.0, B[1] - 1.0)}, inertia: {IJ}, nodes: [B, E, D]}}
joints:
  - {{type: hinge, bodies: [ground, boom], at: O}}
  - {{type: hinge, bodies: [ground, link], at: F}}
  - {{type: hinge, bodies: [boom, jib], at: B}}
  - {{type: hinge, bodies: [link, jib], at: E}}
linear_drives:
  luffing: {{nodes: [A, C], pinion_radius: {PIN}, gear_ratio: {GEAR}, rotor_inertia: {IR}}}
{extra}"""


BASE = ("type: luffing, boom: boom, pivot: O, tip: B, alpha0_deg: 10, alphak_deg: 50, "
        "t_k: 10, jib_tip: D, load: {mass: 1000, rope_length: 5.0}")


def scene(tmp_path, analysis=BASE, extra=""):
    (tmp_path / "m.yaml").write_text(model_text(extra))
    path = tmp_path / "s.yaml"
    path.write_text(f"cranefe: 1\nscene: p\nmodel: m.yaml\nanalysis: {{{analysis}}}\n")
    return load(path), str(path)


def hand(a):
    """Every reduced quantity of the parallelogram at the angles a (module docstring)."""
    a = np.asarray(a, float)
    c, s = np.cos(a), np.sin(a)
    Cx, Cz = 4 * c - AX, 4 * s - AZ
    S = np.hypot(Cx, Cz)
    ds = (Cx * -4 * s + Cz * 4 * c) / S
    dds = (16 - 4 * (Cx * c + Cz * s)) / S - ds**2 / S
    k = IR * RATIO**2
    J0 = IB + MB * 25 + IL + ML * 25 + MJ * L**2
    return {"J": J0 + k * ds**2, "dJ": 2 * k * ds * dds, "Jp": J0 - MJ * L**2 + k * ds**2,
            "dV": G * c * (5 * MB + 5 * ML + L * MJ), "s": S, "ds": ds,
            "x": L * c + E_OFF, "z": L * s, "dx": -L * s, "dz": L * c}


def _int(f, a, b):
    return quad(f, a, b, epsabs=0, epsrel=1e-13, limit=200)[0]


@lru_cache(maxsize=None)
def S_of(key):
    """int_A0^AK sqrt(J or Jp) dalpha."""
    return _int(lambda a: math.sqrt(hand(a)[key]), A0, AK)


@lru_cache(maxsize=None)
def optimum_inverse(key):
    """alpha(tau) of the optimum for J or Jp, by inverting tau(alpha) = S(alpha) /
    S(AK) on 200001 angles (linear interpolation: error ~1e-10 rad)."""
    al = np.linspace(A0, AK, 200001)
    cum = cumulative_trapezoid(np.sqrt(hand(al)[key]), al, initial=0.0)
    # trapezoid's error is O(h^2) ~ 1e-12 relative: enough for an inverse at 1e-10
    return lambda tau: np.interp(tau * cum[-1], cum, al)


@lru_cache(maxsize=None)
def standard_mean(name, key="J"):
    """Mean kinetic energy (1 / t_k^2) int 1/2 J alpha'^2 dtau of a standard law."""
    s1 = {"linear": lambda u: 1.0, "cubic": lambda u: 6 * u - 6 * u * u,
          "cycloidal": lambda u: 1 - math.cos(2 * math.pi * u)}[name]
    s0 = {"linear": lambda u: u, "cubic": lambda u: 3 * u * u - 2 * u**3,
          "cycloidal": lambda u: u - math.sin(2 * math.pi * u) / (2 * math.pi)}[name]
    D = AK - A0
    return _int(lambda u: 0.5 * hand(A0 + D * s0(u))[key] * (D * s1(u))**2, 0, 1) / TK**2


def T_opt(key="J"):
    return S_of(key) ** 2 / (2 * TK**2)


class FakeSwingFree:
    """Stand-in for sway.swing_free_law: the cycloidal law, with a chosen status; records
    its arguments."""

    def __init__(self, status=0):
        self.status, self.calls = status, []

    def __call__(self, proxy, alpha0, alphak, t_k, H, g, guess, which="complete"):
        self.calls.append(dict(proxy=proxy, alpha0=alpha0, alphak=alphak, t_k=t_k, H=H, g=g,
                               guess=guess.name, which=which))
        law = standard_law("cycloidal", alpha0, alphak)
        law.status, law.message = self.status, "stand-in message"
        return law


@pytest.fixture
def fake(monkeypatch):
    f = FakeSwingFree()
    monkeypatch.setattr(sway, "swing_free_law", f)
    return f


# The scene BASE as `read_scene` checks it (test_scene_defaults_and_ends): the tests of
# the linkage, the laws and the analysis build it directly, so that a mutant of
# read_scene runs only the scene tests (each analysis takes seconds).
SCENE = an.Scene("boom", "O", "B", TK, "luffing", "D", MLOAD, H, ("alpha", A0, "alpha0_deg"),
                 ("alpha", AK, "alphak_deg"), "complete", TK / 25)


@lru_cache(maxsize=None)
def _model():
    """The parallelogram, loaded once (the loader is not under test here)."""
    folder = tempfile.mkdtemp(prefix="luff-kill-")
    path = os.path.join(folder, "m.yaml")
    with open(path, "w") as f:
        f.write(model_text())
    return load(path)


@lru_cache(maxsize=None)
def _luffing(inertia="complete", tau=TK / 25):
    """A Luffing of the parallelogram, built once per inertia: its construction
    (`__init__`, `_angle`) is tested by the tests that build their own (reaches, linkage
    errors, analyse); the methods called on this object run per test, mutated."""
    return an.Luffing(_model(), replace(SCENE, inertia=inertia, rest_to_rest_tau=tau))


def luffing(tmp_path=None, analysis=None, **changes):
    if not changes:
        return _luffing()
    return _luffing(**changes)


# ------------------------------------------------------------------ the figures of a law

def test_figures_of_the_cubic_law_by_hand(tmp_path):
    """alpha = A0 + D (3 u^2 - 2 u^3): energies by quad (1e-9: the proxy's 1e-13
    interpolation and Gauss-Legendre with 64 nodes on a polynomial times a smooth J);
    motor torque Q / (500 s') with Q = (J alpha'' + 1/2 J' alpha'^2) / t_k^2 + dV,
    power Q alpha' / t_k, the load's weight torque m g dz / (500 s'), all at the 101
    samples (1e-10); no speed jump (cubic starts and stops at rest)."""
    lf = luffing(tmp_path)
    law = standard_law("cubic", A0, AK)
    T0 = T_opt()
    fig, series = lf.figures(law, T0, samples=101)
    u = np.linspace(0, 1, 101)
    D = AK - A0
    al, d1, d2 = A0 + D * (3 * u**2 - 2 * u**3), D * (6 * u - 6 * u**2), D * (6 - 12 * u)
    h = hand(al)
    Q = (h["J"] * d2 + 0.5 * h["dJ"] * d1**2) / TK**2 + h["dV"]
    assert fig["T_mean_J"] == pytest.approx(standard_mean("cubic"), rel=1e-9)
    assert fig["T_ratio"] == pytest.approx(standard_mean("cubic") / T0, rel=1e-9)
    assert fig["T_mean_paper_J"] == pytest.approx(standard_mean("cubic", "Jp"), rel=1e-9)
    assert fig["peak_motor_torque_Nm"] == pytest.approx(
        np.abs(Q / (RATIO * h["ds"])).max(), rel=1e-10)
    assert fig["peak_power_W"] == pytest.approx(np.abs(Q * d1 / TK).max(), rel=1e-10)
    assert fig["speed_jump_rad_s"] == 0.0 and fig["motor_impulse_Nms"] == 0.0
    assert fig["peak_load_weight_torque_Nm"] == pytest.approx(
        np.abs(MLOAD * G * h["dz"] / (RATIO * h["ds"])).max(), rel=1e-10)
    assert fig["max_alpha_deg"] == pytest.approx(50.0, rel=1e-12)
    assert fig["min_alpha_deg"] == pytest.approx(10.0, rel=1e-12)
    np.testing.assert_allclose(series["alpha"], al, rtol=1e-13)
    np.testing.assert_allclose(series["speed"], d1 / TK, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(series["motor_torque"], Q / (RATIO * h["ds"]), rtol=1e-10)
    np.testing.assert_allclose(series["kinetic_energy"], 0.5 * h["J"] * d1**2 / TK**2,
                               rtol=1e-10, atol=1e-12)
    # the sway figures: the sway module's pendulums for this law (each kind its own key)
    tip = sway.TipMotion(law, lf.proxy, TK)
    ref = {k: sway.simulate(tip, H, G, k, samples=101) for k in ("linear", "nonlinear",
                                                                  "paper")}
    for key, kind, what in (("max_sway_deg", "nonlinear", "max"),
                            ("residual_sway_deg", "nonlinear", "residual"),
                            ("max_sway_linear_deg", "linear", "max"),
                            ("residual_sway_linear_deg", "linear", "residual"),
                            ("max_sway_paper_eq9_deg", "paper", "max")):
        assert fig[key] == pytest.approx(math.degrees(ref[kind][what]), rel=1e-9), key
    assert len({fig["max_sway_deg"], fig["max_sway_linear_deg"],
                fig["max_sway_paper_eq9_deg"], fig["residual_sway_deg"]}) == 4
    np.testing.assert_allclose(series["sway"], ref["nonlinear"]["psi"], rtol=1e-9, atol=1e-14)
    np.testing.assert_allclose(series["sway_linear"], ref["linear"]["psi"], rtol=1e-9,
                               atol=1e-14)
    # the load's speed: tip velocity + H psi' (cos psi, sin psi), mean of 1/2 m v^2
    nl = ref["nonlinear"]
    vx, vz = h["dx"] * d1 / TK, h["dz"] * d1 / TK
    vl2 = (vx + H * nl["dpsi"] * np.cos(nl["psi"]))**2 + \
        (vz + H * nl["dpsi"] * np.sin(nl["psi"]))**2
    assert fig["T_load_mean_J"] == pytest.approx(trapezoid(0.5 * MLOAD * vl2, u), rel=1e-9)
    # the linear residual in closed form: |int x'(tau) e^(-i w t_k tau) dtau| / H
    W = math.sqrt(G / H) * TK
    xd = lambda v: -L * math.sin(A0 + D * (3 * v * v - 2 * v**3)) * D * (6 * v - 6 * v * v)  # noqa: E731
    # (an absolute floor: the integrals cancel to ~1e-2 of the integrand's size)
    re = quad(lambda v: xd(v) * math.cos(W * v), 0, 1, epsabs=1e-12, epsrel=1e-10)[0]
    im = quad(lambda v: xd(v) * math.sin(W * v), 0, 1, epsabs=1e-12, epsrel=1e-10)[0]
    assert fig["residual_sway_linear_exact_deg"] == pytest.approx(
        math.degrees(math.hypot(re, im) / H), rel=1e-8)


def test_figures_of_the_linear_law_have_speed_jumps(tmp_path):
    """The linear law jumps to D / t_k at both ends: the motor's angular impulse
    J D / t_k / |500 s'| at the larger end (1e-10)."""
    lf = luffing(tmp_path)
    fig, _ = lf.figures(standard_law("linear", A0, AK), T_opt(), samples=51)
    D = AK - A0
    h0, hk = hand(A0), hand(AK)
    assert fig["speed_jump_rad_s"] == pytest.approx(D / TK, rel=1e-12)
    assert fig["motor_impulse_Nms"] == pytest.approx(
        max(h0["J"] * D / TK / abs(RATIO * h0["ds"]), hk["J"] * D / TK / abs(RATIO * hk["ds"])),
        rel=1e-10)
    assert fig["T_mean_J"] == pytest.approx(standard_mean("linear"), rel=1e-9)
    assert lf.mean_energy(standard_law("linear", A0, AK), "Jp") == pytest.approx(
        standard_mean("linear", "Jp"), rel=1e-9)



def test_mean_energy_of_a_law_with_breaks_by_pieces():
    """The trapezoidal law (acceleration over tau < 0.2 and tau > 0.8, a = 6.25, top speed
    1.25): its mean kinetic energy is the sum over the three smooth pieces, each by quad
    (Gauss-Legendre per piece is exact to 1e-9 there; across the kinks it would not be)."""
    lf = luffing()
    D, acc, v = AK - A0, 6.25, 1.25
    pieces = [(0.0, 0.2, lambda u: 0.5 * acc * u * u, lambda u: acc * u),
              (0.2, 0.8, lambda u: 0.125 + v * (u - 0.2), lambda u: v),
              (0.8, 1.0, lambda u: 1 - 0.5 * acc * (1 - u) ** 2, lambda u: acc * (1 - u))]
    hand_mean = sum(_int(lambda u: 0.5 * hand(A0 + D * s0(u))["J"] * (D * s1(u)) ** 2, a, b)
                    for a, b, s0, s1 in pieces) / TK**2
    assert lf.mean_energy(standard_law("trapezoidal", A0, AK)) == pytest.approx(
        hand_mean, rel=1e-9)

def test_torque_of_the_sensitivity_rows_by_hand():
    """_torque: Q / (500 s') at 401 instants (the default) of the cubic law at t_k = 5 s:
    the J' alpha'^2 / 2 term is not zero inside the range."""
    lf = luffing()
    law = standard_law("cubic", A0, AK)
    u = np.linspace(0, 1, 401)
    D = AK - A0
    al, d1, d2 = A0 + D * (3 * u**2 - 2 * u**3), D * (6 * u - 6 * u**2), D * (6 - 12 * u)
    h = hand(al)
    Q = (h["J"] * d2 + 0.5 * h["dJ"] * d1**2) / 5.0**2 + h["dV"]
    np.testing.assert_allclose(an._torque(lf, law, 5.0), Q / (RATIO * h["ds"]), rtol=1e-11)
    assert np.abs(0.5 * h["dJ"] * d1**2).max() > 1e-3 * np.abs(Q).max()


def test_figures_default_samples_and_the_start_of_a_reversed_law():
    """figures' default: 801 samples. Luffing down (AK to A0) with the linear law: the
    impulse J D / t_k / |500 s'| at each end, the larger one (at A0, which is now the
    law's end) reported; together with the linear law up (A0 at its start) each end is
    the larger once."""
    lf = luffing()
    fig, series = lf.figures(standard_law("cubic", A0, AK), T_opt())
    assert series["alpha"].shape == (801,)
    D = AK - A0
    down = standard_law("linear", AK, A0)
    fig, _ = lf.figures(down, T_opt(), samples=11)
    ends = [hand(a)["J"] * D / TK / abs(RATIO * hand(a)["ds"]) for a in (A0, AK)]
    assert ends[0] != pytest.approx(ends[1], rel=1e-3)
    assert fig["motor_impulse_Nms"] == pytest.approx(max(ends), rel=1e-10)


def test_drive_terms_at_three_instants(tmp_path):
    lf = luffing(tmp_path)
    u = np.array([0.0, 0.3, 0.8])
    D = AK - A0
    al, d1, d2 = A0 + D * (3 * u**2 - 2 * u**3), D * (6 * u - 6 * u**2), D * (6 - 12 * u)
    h = hand(al)
    Q = (h["J"] * d2 + 0.5 * h["dJ"] * d1**2) / TK**2 + h["dV"]
    torque, power, q, load = lf.drive_terms(standard_law("cubic", A0, AK), u)
    np.testing.assert_allclose(q, Q, rtol=1e-11)
    np.testing.assert_allclose(torque, Q / (RATIO * h["ds"]), rtol=1e-11)
    np.testing.assert_allclose(power, Q * d1 / TK, rtol=1e-11, atol=1e-9)
    np.testing.assert_allclose(load, MLOAD * G * h["dz"] / (RATIO * h["ds"]), rtol=1e-11)


# ------------------------------------------------------------------ the laws

def test_laws_and_the_optimum(tmp_path, fake):
    """The optimum's T = S^2 / (2 t_k^2) (eq. 16, S by quad, 1e-10); optimal_paper is
    the optimum for Jp; rest_to_rest has the scene's tau (default t_k / 25 = 0.4); the
    swing-free law gets the rope length, g, the optimum as its guess and the inertia."""
    lf = luffing(tmp_path)
    laws = lf.laws()
    assert list(laws) == ["optimal", *an.ALL_LAWS[1:]]
    assert lf.optimal_energy(laws["optimal"]) == pytest.approx(T_opt(), rel=1e-10)
    assert laws["optimal"].info["S"] == pytest.approx(S_of("J"), rel=1e-10)
    assert laws["optimal_paper"].info["S"] == pytest.approx(S_of("Jp"), rel=1e-10)
    assert laws["optimal_paper"].name == "optimal_paper"
    assert laws["rest_to_rest"].info["tau_c_s"] == pytest.approx(0.4, rel=1e-12)
    assert fake.calls == [dict(proxy=lf.proxy, alpha0=A0, alphak=AK, t_k=TK, H=H, g=G,
                               guess="optimal", which="complete")]
    inv = optimum_inverse("J")
    u = np.linspace(0, 1, 11)
    np.testing.assert_allclose(laws["optimal"].evaluate(u)[0], inv(u), atol=1e-9)
    for name in ("linear", "cubic", "quintic", "cycloidal", "trapezoidal"):
        assert laws[name].evaluate(0.5)[0] == pytest.approx(
            standard_law(name, A0, AK).evaluate(0.5)[0], rel=1e-15)
    only = lf.laws(("cubic",))
    assert list(only) == ["optimal", "cubic"]


def test_optimum_with_the_papers_inertia(tmp_path, fake):
    """inertia: paper: the optimum minimises the Jp energy; optimal_paper is then the
    complete one; rest_to_rest and swing_free in Jp too."""
    lf = luffing(inertia="paper", tau=2.5)
    assert lf.scene.inertia == "paper" and lf.scene.rest_to_rest_tau == 2.5
    laws = lf.laws(("optimal_paper", "rest_to_rest", "swing_free"))
    assert laws["optimal"].info["S"] == pytest.approx(S_of("Jp"), rel=1e-10)
    assert laws["optimal_paper"].info["S"] == pytest.approx(S_of("J"), rel=1e-10)
    assert lf.optimal(which="complete").info["S"] == pytest.approx(S_of("J"), rel=1e-10)
    assert laws["rest_to_rest"].info["tau_c_s"] == 2.5
    want = rest_to_rest_law(lf.proxy, A0, AK, 2.5, TK, "paper").evaluate(0.3)[0]
    other = rest_to_rest_law(lf.proxy, A0, AK, 2.5, TK, "complete").evaluate(0.3)[0]
    assert laws["rest_to_rest"].evaluate(0.3)[0] == pytest.approx(want, rel=1e-14)
    assert abs(want - other) > 1e-6
    assert fake.calls[0]["which"] == "paper"
    fig, _ = lf.figures(standard_law("cubic", A0, AK), T_opt("Jp"), samples=21)
    assert fig["T_mean_J"] == pytest.approx(standard_mean("cubic", "Jp"), rel=1e-9)
    assert fig["T_ratio"] == pytest.approx(standard_mean("cubic", "Jp") / T_opt("Jp"),
                                           rel=1e-9)
    assert fig["T_mean_paper_J"] == pytest.approx(standard_mean("cubic", "Jp"), rel=1e-9)


def test_optimum_with_a_rigidly_carried_extra_inertia(tmp_path):
    """extra_inertia m |dD/dalpha|^2 = m L^2 (constant here): S = int sqrt(J + m L^2)."""
    lf = luffing(tmp_path)
    m = 300.0
    law = lf.optimal(extra_inertia=lambda al: (m * L**2 + 0 * al, 0 * al), name="x")
    want = _int(lambda a: math.sqrt(hand(a)["J"] + m * L**2), A0, AK)
    assert law.info["S"] == pytest.approx(want, rel=1e-10) and law.name == "x"
    law = lf.optimal(which="paper", extra_inertia=lambda al: (m * L**2 + 0 * al, 0 * al))
    want = _int(lambda a: math.sqrt(hand(a)["Jp"] + m * L**2), A0, AK)
    assert law.info["S"] == pytest.approx(want, rel=1e-10)
    u = np.linspace(0, 1, 5)
    al, d1, _ = law.evaluate(u)
    # J alpha'^2 constant along the optimum (eq. 16)
    np.testing.assert_allclose((hand(al)["Jp"] + m * L**2) * d1**2, want**2, rtol=1e-8)


# ------------------------------------------------------------------ analyse

def _rest_to_rest_excess(eps):
    """int_0^1 sigma'^2 du - 1 of the practical law: in the energy coordinate its energy
    is S^2 sigma'^2 / (2 t_k^2), so its ratio to the optimum is int sigma'^2; sigma =
    1/2 + B (u - 1/2) + C sinh((u - 1/2) / eps) with B + 2 C sinh(Y) = 1, B + C cosh(Y) /
    eps = 0, Y = 1 / (2 eps) (laws.py)."""
    Y = 1 / (2 * eps)
    C = 1 / (2 * math.sinh(Y) - math.cosh(Y) / eps)
    B = -C * math.cosh(Y) / eps
    return _int(lambda u: (B + C / eps * math.cosh((u - 0.5) / eps))**2, 0, 1) - 1


SWAY = {"linear": 0.01, "nonlinear": 0.02, "paper": 0.03}


def fast_sway(monkeypatch):
    """Stand-ins for the sway module's pendulums (seconds for nine laws; the wiring of
    the real ones is checked in test_figures_of_the_cubic_law_by_hand): psi = a constant
    per kind, psi' = 0, residual 10 x that, the linear closed form 0.04."""
    class Tip:
        def __init__(self, law, proxy, t_k):
            pass

    def simulate(tip, H, g, kind, samples=801):
        return {"psi": np.full(samples, SWAY[kind]), "dpsi": np.zeros(samples),
                "max": SWAY[kind], "residual": 10 * SWAY[kind]}
    monkeypatch.setattr(sway, "TipMotion", Tip)
    monkeypatch.setattr(sway, "simulate", simulate)
    monkeypatch.setattr(sway, "residual_linear_exact", lambda law, p, tk, H, g: 0.04)


def analysed_scene(tmp_path, monkeypatch):
    """The scene BASE on disk, with read_scene replaced by its result (SCENE)."""
    model, path = scene(tmp_path)
    monkeypatch.setattr(an, "read_scene", lambda model, file=None: SCENE)
    return model, path


def test_analyse_reports_by_hand(tmp_path, monkeypatch, fake):
    """Every number of the result: reaches, tip deviation, imbalance, the optimum's
    paper comparison (the paper law alpha_p(tau) by inverting its S_p; its complete
    energy S_p / (2 t_k^2) int J / sqrt(Jp)), speeds J alpha'^2 = S^2 at both ends, the
    coasting torque dV / (500 s') along the optimum, the rest-to-rest excess in closed
    form, the kinematics summary on the 241-angle grid, the arrays per law. 1e-9 unless
    said (quadratures and the proxy)."""
    marks = []
    monkeypatch.setattr(an, "collocation_report", lambda lf, law: marks.append(
        ("c", law.name, type(lf).__name__)) or {"collocation": law.name})
    monkeypatch.setattr(an, "sensitivity_report", lambda lf, law: marks.append(
        ("s", law.name, type(lf).__name__)) or {"sensitivity": law.name})
    fast_sway(monkeypatch)
    model, path = analysed_scene(tmp_path, monkeypatch)
    t0 = time.perf_counter()
    r = an.analyse(model, path, samples=51)
    wall = time.perf_counter() - t0
    assert marks == [("c", "optimal", "Luffing"), ("s", "optimal", "Luffing")]
    assert r.collocation == {"collocation": "optimal"}
    assert r.sensitivity == {"sensitivity": "optimal"}
    assert (r.status, r.message, r.model_name, r.scene) == (0, "ok", "parallelogram", "p")
    assert (r.alpha0, r.alphak, r.t_k) == (pytest.approx(A0, rel=1e-15),
                                           pytest.approx(AK, rel=1e-15), TK)
    h0, hk = hand(A0), hand(AK)
    assert r.reach0 == pytest.approx(h0["x"], rel=1e-12)
    assert r.reachk == pytest.approx(hk["x"], rel=1e-12)
    assert (r.load_mass, r.rope_length, r.inertia) == (MLOAD, H, "complete")
    assert r.jib_tip_deviation == pytest.approx(hk["z"] - h0["z"], rel=1e-12)
    grid = np.linspace(A0, AK, 241)
    hg = hand(grid)
    assert r.imbalance_moment == pytest.approx(np.abs(hg["dV"]).max(), rel=1e-12)
    assert r.imbalance_motor_torque == pytest.approx(
        np.abs(hg["dV"] / (RATIO * hg["ds"])).max(), rel=1e-12)
    np.testing.assert_allclose(r.alpha_grid, grid, rtol=1e-15)
    for name, key in (("tip_x", "x"), ("tip_z", "z"), ("J", "J"), ("J_paper", "Jp"),
                      ("imbalance", "dV")):
        np.testing.assert_allclose(getattr(r, name), hg[key], rtol=1e-12, err_msg=name)
    np.testing.assert_allclose(r.motor_ratio, RATIO * hg["ds"], rtol=1e-12)
    # the optimum
    o, S, Sp = r.optimum, S_of("J"), S_of("Jp")
    assert o["inertia"] == "complete"
    assert o["T_mean_J"] == pytest.approx(T_opt(), rel=1e-10)
    assert o["T_mean_paper_J"] == pytest.approx(T_opt("Jp"), rel=1e-10)
    Tpl = Sp / (2 * TK**2) * _int(lambda a: hand(a)["J"] / math.sqrt(hand(a)["Jp"]), A0, AK)
    assert o["T_mean_of_paper_law_J"] == pytest.approx(Tpl, rel=1e-9)
    assert o["paper_law_energy_excess"] == pytest.approx(Tpl / T_opt() - 1, rel=1e-6)
    assert o["paper_law_energy_excess"] > 1e-4
    tau = np.linspace(0, 1, 401)
    diff = np.abs(optimum_inverse("J")(tau) - optimum_inverse("Jp")(tau)).max()
    assert o["max_law_difference_deg"] == pytest.approx(math.degrees(diff), rel=1e-8)
    ratio = hg["Jp"] / hg["J"]
    assert o["J_paper_over_complete"] == pytest.approx([ratio.min(), ratio.max()], rel=1e-12)
    assert o["speed_start_rad_s"] == pytest.approx(S / math.sqrt(h0["J"]) / TK, rel=1e-9)
    assert o["speed_end_rad_s"] == pytest.approx(S / math.sqrt(hk["J"]) / TK, rel=1e-9)
    assert o["motor_impulse_Nms"] == pytest.approx(max(
        math.sqrt(h["J"]) * S / TK / abs(RATIO * h["ds"]) for h in (h0, hk)), rel=1e-9)
    opt_al = hand(optimum_inverse("J")(np.linspace(0, 1, 51)))
    assert o["coasting_motor_torque_Nm"] == pytest.approx(
        np.abs(opt_al["dV"] / (RATIO * opt_al["ds"])).max(), rel=1e-7)
    assert o["rest_to_rest_tau_s"] == pytest.approx(0.4, rel=1e-12)
    assert o["rest_to_rest_energy_excess"] == pytest.approx(_rest_to_rest_excess(0.04),
                                                            rel=1e-6)
    assert o["swing_free_energy_excess"] == pytest.approx(
        standard_mean("cycloidal") / T_opt() - 1, rel=1e-9)
    assert o["swing_free_status"] == 0 and r.warnings == []
    # the table and the series, one row per law in ALL_LAWS's order
    assert r.law_names == an.ALL_LAWS and list(r.table) == list(an.ALL_LAWS)
    assert r.table["cubic"]["T_mean_J"] == pytest.approx(standard_mean("cubic"), rel=1e-9)
    assert r.table["optimal"]["T_ratio"] == pytest.approx(1.0, rel=1e-9)
    np.testing.assert_allclose(r.t, np.linspace(0, TK, 51), rtol=1e-15)
    u = np.linspace(0, 1, 51)
    D = AK - A0
    k = an.ALL_LAWS.index("cubic")
    for name, shape in (("alpha", (9, 51)), ("speed", (9, 51)), ("motor_torque", (9, 51)),
                        ("kinetic_energy", (9, 51)), ("sway", (9, 51)),
                        ("sway_linear", (9, 51))):
        assert getattr(r, name).shape == shape, name
    np.testing.assert_allclose(r.alpha[k], A0 + D * (3 * u**2 - 2 * u**3), rtol=1e-13)
    np.testing.assert_allclose(r.speed[k], D * (6 * u - 6 * u**2) / TK, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(r.alpha[0], optimum_inverse("J")(u), atol=1e-9)
    ku = an.ALL_LAWS.index("linear")
    hl = hand(A0 + D * u)
    np.testing.assert_allclose(r.motor_torque[ku], hl["dV"] / (RATIO * hl["ds"]) +
                               0.5 * hl["dJ"] * (D / TK)**2 / (RATIO * hl["ds"]), rtol=1e-10)
    np.testing.assert_allclose(r.kinetic_energy[ku], 0.5 * hl["J"] * (D / TK)**2, rtol=1e-10)
    # the sway figures and series: the stand-ins' values, each kind in its place
    ks = an.ALL_LAWS.index("swing_free")
    np.testing.assert_array_equal(r.sway[ks], np.full(51, SWAY["nonlinear"]))
    np.testing.assert_array_equal(r.sway_linear[ks], np.full(51, SWAY["linear"]))
    cubic = r.table["cubic"]
    assert (cubic["max_sway_deg"], cubic["residual_sway_deg"], cubic["max_sway_linear_deg"],
            cubic["residual_sway_linear_deg"], cubic["max_sway_paper_eq9_deg"],
            cubic["residual_sway_linear_exact_deg"]) == pytest.approx(
        [math.degrees(x) for x in (0.02, 0.2, 0.01, 0.1, 0.03, 0.04)], rel=1e-15)
    # with psi' = 0 the load moves with the tip: |dD/dalpha| = L, so 1/2 m L^2 alpha'^2
    speed2 = (L * D * (6 * u - 6 * u**2) / TK)**2
    assert cubic["T_load_mean_J"] == pytest.approx(trapezoid(0.5 * MLOAD * speed2, u),
                                                   rel=1e-10)
    # the kinematics summary on the grid
    kin = r.kinematics
    assert kin["tip_height_mean_m"] == pytest.approx(hg["z"].mean(), rel=1e-12)
    assert kin["tip_height_range_m"] == pytest.approx([h0["z"], hk["z"]], rel=1e-12)
    assert kin["tip_slope_max"] == pytest.approx(1 / math.tan(A0), rel=1e-10)
    assert 0 <= kin["loop_closure_residual"] < 1e-9
    assert kin["drive_stroke_m"] == pytest.approx(np.ptp(hg["s"]), rel=1e-12)
    assert kin["load_weight_motor_torque_max_Nm"] == pytest.approx(
        np.abs(MLOAD * G * hg["dz"] / (RATIO * hg["ds"])).max(), rel=1e-12)
    assert isinstance(kin["proxy_degree"], int) and kin["proxy_degree"] >= 8
    assert 0 < kin["proxy_tail"] < 1e-10
    assert list(r.timings) == ["kinematics", "laws", "collocation", "sensitivity", "total"]
    assert all(0 <= v <= wall for v in r.timings.values())
    assert r.timings["total"] >= r.timings["laws"] + r.timings["kinematics"]


def test_analyse_without_reports_and_a_failed_swing_free_law(tmp_path, monkeypatch):
    """collocation / sensitivity False: empty, not timed; a swing-free law that did not
    converge is reported as a warning with solve_bvp's message and its status."""
    monkeypatch.setattr(sway, "swing_free_law", FakeSwingFree(status=2))
    fast_sway(monkeypatch)
    model, path = analysed_scene(tmp_path, monkeypatch)
    r = an.analyse(model, path, collocation=False, sensitivity=False)
    assert r.collocation == {} and r.sensitivity == {}
    assert list(r.timings) == ["kinematics", "laws", "total"]
    assert r.warnings == ["swing-free law: solve_bvp stand-in message"]
    assert r.optimum["swing_free_status"] == 2
    assert r.t.shape == (801,) and r.alpha.shape == (9, 801)        # the default
    doc = r.to_dict()
    assert (doc["alpha0_rad"], doc["alphak_rad"], doc["t_k_s"]) == (r.alpha0, r.alphak, TK)


def test_analyse_with_the_papers_inertia(tmp_path, monkeypatch, fake):
    """inertia: paper: the optimum is Jp's (T = S_p^2 / (2 t_k^2)), the 'paper law' is
    then the complete optimum (T = S^2 / (2 t_k^2), its Jp energy S / (2 t_k^2) int Jp /
    sqrt(J)), and the ratio reported is J / Jp."""
    fast_sway(monkeypatch)
    model, path = scene(tmp_path)
    monkeypatch.setattr(an, "read_scene", lambda model, file=None: replace(
        SCENE, inertia="paper"))
    r = an.analyse(model, path, collocation=False, sensitivity=False, samples=21)
    o, S = r.optimum, S_of("J")
    assert o["inertia"] == "paper" and r.inertia == "paper"
    assert o["T_mean_J"] == pytest.approx(T_opt("Jp"), rel=1e-10)
    assert o["T_mean_paper_J"] == pytest.approx(T_opt("J"), rel=1e-10)
    Tpl = S / (2 * TK**2) * _int(lambda a: hand(a)["Jp"] / math.sqrt(hand(a)["J"]), A0, AK)
    assert o["T_mean_of_paper_law_J"] == pytest.approx(Tpl, rel=1e-9)
    hg = hand(np.linspace(A0, AK, 241))
    ratio = hg["J"] / hg["Jp"]
    assert o["J_paper_over_complete"] == pytest.approx([ratio.min(), ratio.max()], rel=1e-12)
    assert fake.calls[0]["which"] == "paper"


def test_analyse_reads_the_scene(tmp_path):
    """analyse's own read_scene and Luffing (no stand-ins): a bad key and a jib tip on no
    body fail at once with the scene file and the entry, with and without a file."""
    for change, entry in ((("t_k: 10", "t_k: -1"), "analysis.t_k"),
                          (("jib_tip: D", "jib_tip: Z"), "analysis.jib_tip")):
        model, path = scene(tmp_path, BASE.replace(*change))
        for file in (path, None):
            with pytest.raises(ModelError) as e:
                an.analyse(model, file)
            assert (str(e.value.file), e.value.entry) == (path, entry)
        with pytest.raises(ModelError) as e:
            an.analyse(model, "given.yaml")
        assert (e.value.file, e.value.entry) == ("given.yaml", entry)


def test_law_figures_of_a_sweep(tmp_path, monkeypatch, fake):
    """law_figures: the table's figures of the laws asked for only."""
    model, _ = analysed_scene(tmp_path, monkeypatch)
    figs = an.law_figures(model, ["cubic", "linear"], samples=31)
    assert list(figs) == ["cubic", "linear"]
    assert figs["cubic"]["T_ratio"] == pytest.approx(standard_mean("cubic") / T_opt(),
                                                     rel=1e-9)
    assert figs["linear"]["speed_jump_rad_s"] == pytest.approx((AK - A0) / TK, rel=1e-12)
    assert fake.calls == []
    # the default: 801 samples (the peak power, inside the range, is a maximum over them)
    figs = an.law_figures(model, ["cubic"])
    peaks = []
    for n in (801, 802):
        u = np.linspace(0, 1, n)
        D = AK - A0
        al, d1, d2 = A0 + D * (3 * u**2 - 2 * u**3), D * (6 * u - 6 * u**2), D * (6 - 12 * u)
        h = hand(al)
        Q = (h["J"] * d2 + 0.5 * h["dJ"] * d1**2) / TK**2 + h["dV"]
        peaks.append(np.abs(Q * d1 / TK).max())
    assert abs(peaks[1] / peaks[0] - 1) > 1e-9
    assert figs["cubic"]["peak_power_W"] == pytest.approx(peaks[0], rel=1e-11)


# ------------------------------------------------------------------ the reports

def _same(a, b):
    """Equal dicts, NaN equal to NaN and arrays compared element-wise."""
    if set(a) != set(b):
        return False
    return all(np.array_equal(np.asarray(a[k], dtype=object if a[k] is None else None),
                              np.asarray(b[k], dtype=object if b[k] is None else None),
                              equal_nan=a[k] is not None and np.asarray(a[k]).dtype.kind
                              in "fc")
               for k in a)


def test_convergence_rate_by_hand():
    """error = 3 * 0.1^n: geometric ratio 0.1 (1 digit a point); error = 5 n^-3: order
    3; points at or below 1e-12 left out; fewer than two: None."""
    rows = [{"n": n, "error_rad": 3 * 0.1**n} for n in range(2, 9)]
    rows.append({"n": 15, "error_rad": 1e-13})
    r = an.convergence_rate(rows)
    assert r["geometric_ratio"] == pytest.approx(0.1, rel=1e-9)
    assert r["digits_per_point"] == pytest.approx(1.0, rel=1e-9)
    r = an.convergence_rate([{"n": n, "error_rad": 5.0 * n**-3.0} for n in (2, 4, 8, 16)])
    assert r["algebraic_order"] == pytest.approx(3.0, rel=1e-9)
    assert an.convergence_rate([{"n": 2, "error_rad": 1e-3}, {"n": 3, "error_rad": 1e-12}]) \
        == {"geometric_ratio": None, "algebraic_order": None}
    r = an.convergence_rate([{"n": 2, "error_rad": 1e-3}, {"n": 3, "error_rad": 1e-4}])
    assert r["geometric_ratio"] == pytest.approx(0.1, rel=1e-12)
    assert r["algebraic_order"] == pytest.approx(math.log(10) / math.log(1.5), rel=1e-12)


def test_collocation_report_of_the_parallelogram(tmp_path):
    """The paper's three variants and relaxed one, n-point collocation n = 2..10 on
    both point sets and solve_bvp, each with its error against the exact law; f =
    J' / (2 J) is smooth here, so Chebyshev collocation converges to < 1e-8 rad by
    n = 10 and the rates exist."""
    lf = luffing(tmp_path)
    exact = lf.optimal()
    rep = an.collocation_report(lf, exact)
    assert set(rep["paper"]) >= {"printed", "eq21", "corrected"}
    for kind in ("equally_spaced", "chebyshev"):
        assert [row["n"] for row in rep[kind]] == list(range(2, 11))
        assert rep[kind][-1]["error_rad"] < 1e-6
        assert rep[kind][0]["error_rad"] > rep[kind][-1]["error_rad"]
        assert rep[kind + "_rate"]["geometric_ratio"] < 1
    assert rep["solve_bvp"]["tol"] == 1e-8 and rep["solve_bvp"]["error_rad"] < 1e-6
    # the report's entries are those of the solvers (value-tested in their own kill
    # tests) called with f = J'/(2J) of the scene's inertia, each variant its own
    from cranefe.analysis.luffing import optimum as opt
    f = lambda x: lf.proxy.f(x, "complete")                    # noqa: E731
    for variant in ("printed", "eq21", "corrected"):
        sol = opt.paper_collocation(f, A0, AK, variant)
        info = sol.info
        want = {"status": sol.status, "message": sol.message, "iterations": sol.iterations,
                "spectral_radius": info.get("spectral_radius"),
                "eigenvalues": info.get("eigenvalues"), "relax_best": info.get("relax_best"),
                "spectral_radius_best": info.get("spectral_radius_best"),
                "fixed_point": info["fixed_point"],
                "error_rad": opt.law_error(sol, exact) if info["fixed_point_found"] else None}
        assert _same(rep["paper"][variant], want), variant
    best = rep["paper"]["corrected"]["relax_best"]
    if best is None:
        assert set(rep["paper"]) == {"printed", "eq21", "corrected"}
    else:
        sol = opt.paper_collocation(f, A0, AK, "corrected", relax=best)
        assert _same(rep["paper"]["corrected_relaxed"], {
            "status": sol.status, "message": sol.message, "iterations": sol.iterations,
            "relax": best, "error_rad": opt.law_error(sol, exact)})
    assert not _same(rep["paper"]["printed"], rep["paper"]["corrected"])
    for kind, points in (("equally_spaced", opt.equally_spaced),
                         ("chebyshev", opt.chebyshev_points)):
        for row in rep[kind]:
            sol = opt.collocation(f, A0, AK, points(row["n"]),
                                  df=lambda x: an._df(lf, x, "complete"))
            assert row == {"n": row["n"], "error_rad": opt.law_error(sol, exact),
                           "status": sol.status, "iterations": sol.iterations}
        assert rep[kind + "_rate"] == an.convergence_rate(rep[kind])
    sol = opt.bvp(f, A0, AK, tol=1e-8)
    assert rep["solve_bvp"] == {"tol": 1e-8, "error_rad": opt.law_error(sol, exact),
                                "nodes": sol.info["nodes"], "status": sol.status}
    # the derivative of f = J'/(2J) given to the collocation's Newton, by hand:
    # f' = (J''/J - J'^2/J^2) / 2, J'' by a central difference of the hand J' (1e-6)
    a = np.array([0.3, 0.6])
    dJ = lambda x: hand(x)["dJ"]                               # noqa: E731
    ddJ = (dJ(a + 1e-6) - dJ(a - 1e-6)) / 2e-6
    h = hand(a)
    np.testing.assert_allclose(an._df(lf, a, "complete"),
                               0.5 * (ddJ / h["J"] - h["dJ"]**2 / h["J"]**2), rtol=1e-5)
    # paper: Jp = J - 500 L^2, the same derivatives
    np.testing.assert_allclose(an._df(lf, a, "paper"),
                               0.5 * (ddJ / h["Jp"] - h["dJ"]**2 / h["Jp"]**2), rtol=1e-5)


def test_sensitivity_report_rows(tmp_path, monkeypatch):
    """t_k x (0.5, 0.75, 1, 1.5, 2): T = S^2 / (2 t_k^2); load mass x (0, 0.5, 1, 1.5)
    carried rigidly at the tip: S_m = int sqrt(J + m L^2) (|dD/dalpha| = L); rope length
    x (0.5, 1, 2); the swing-free law (stand-in) asked with each t_k and H; its excess
    from the cycloidal law's energy at that t_k (the stand-in's status 0), and the
    rest-to-rest law's peak torque Q / (500 s') at 401 instants."""
    fake = FakeSwingFree()
    monkeypatch.setattr(sway, "swing_free_law", fake)
    lf = luffing(tmp_path)
    exact = lf.optimal()
    rep = an.sensitivity_report(lf, exact)
    S = S_of("J")
    assert [row["t_k_s"] for row in rep["t_k"]] == [5.0, 7.5, 10.0, 15.0, 20.0]
    for row in rep["t_k"]:
        tk = row["t_k_s"]
        assert row["T_mean_J"] == pytest.approx(S**2 / (2 * tk**2), rel=1e-10)
        assert row["T_over_base"] == pytest.approx((TK / tk)**2, rel=1e-12)
        excess = standard_mean("cycloidal") * TK**2 / tk**2 / (S**2 / (2 * tk**2)) - 1
        assert row["swing_free_energy_excess"] == pytest.approx(excess, rel=1e-9)
        tip = sway.TipMotion(exact, lf.proxy, tk)
        ref = sway.simulate(tip, H, G, "nonlinear", samples=201)
        assert row["residual_sway_optimal_deg"] == pytest.approx(
            math.degrees(ref["residual"]), rel=1e-8)
        assert row["max_sway_optimal_deg"] == pytest.approx(math.degrees(ref["max"]),
                                                            rel=1e-8)
        rr = rest_to_rest_law(lf.proxy, A0, AK, 0.4, tk)
        u = np.linspace(0, 1, 401)
        al, d1, d2 = rr.evaluate(u)
        h = hand(al)
        Q = (h["J"] * d2 + 0.5 * h["dJ"] * d1**2) / tk**2 + h["dV"]
        assert row["rest_to_rest_peak_motor_torque_Nm"] == pytest.approx(
            np.abs(Q / (RATIO * h["ds"])).max(), rel=1e-9)
    assert [(c["t_k"], c["H"]) for c in fake.calls] == [
        (5.0, H), (7.5, H), (10.0, H), (15.0, H), (20.0, H), (TK, 2.5), (TK, 5.0), (TK, 10.0)]
    assert all(c["g"] == G and c["which"] == "complete" and c["guess"] == "optimal" and
               c["proxy"] is lf.proxy and (c["alpha0"], c["alphak"]) == (A0, AK)
               for c in fake.calls)
    assert [row["load_mass_kg"] for row in rep["load_mass"]] == [0.0, 500.0, 1000.0, 1500.0]
    u = np.linspace(0, 1, 201)
    for row in rep["load_mass"]:
        m = row["load_mass_kg"]
        Sm = _int(lambda a: math.sqrt(hand(a)["J"] + m * L**2), A0, AK)
        assert row["T_mean_with_load_J"] == pytest.approx(Sm**2 / (2 * TK**2), rel=1e-9)
        law = lf.optimal(extra_inertia=lambda al: (m * L**2 + 0 * al, 0 * al))
        assert row["T_links_of_that_law_J"] == pytest.approx(lf.mean_energy(law), rel=1e-9)
        assert row["T_links_of_that_law_J"] >= T_opt() * (1 - 1e-12)
        diff = np.abs(law.evaluate(u)[0] - exact.evaluate(u)[0]).max()
        assert row["max_law_difference_deg"] == pytest.approx(math.degrees(diff), rel=1e-9,
                                                              abs=1e-12)
    assert rep["load_mass"][0]["max_law_difference_deg"] < 1e-9
    assert rep["load_mass"][3]["max_law_difference_deg"] > 1e-3
    assert [row["rope_length_m"] for row in rep["rope_length"]] == [2.5, 5.0, 10.0]
    for row in rep["rope_length"]:
        tip = sway.TipMotion(exact, lf.proxy, TK)
        ref = sway.simulate(tip, row["rope_length_m"], G, "nonlinear", samples=201)
        assert row["residual_sway_optimal_deg"] == pytest.approx(
            math.degrees(ref["residual"]), rel=1e-8)
        assert row["swing_free_energy_excess"] == pytest.approx(
            standard_mean("cycloidal") / T_opt() - 1, rel=1e-9)
    assert rep["note"] == ("the optimum of eq. 16 does not depend on the load (its terms "
                           "cancel with eq. 9); load_mass rows carry the load rigidly at the "
                           "tip")
    fake.status = 1
    rep = an.sensitivity_report(lf, exact)
    assert all(row["swing_free_energy_excess"] is None
               for row in rep["t_k"] + rep["rope_length"])


# ------------------------------------------------------------------ the scene

def test_scene_defaults_and_ends(tmp_path):
    model, path = scene(tmp_path)
    sc = an.read_scene(model, path)
    assert sc == an.Scene("boom", "O", "B", 10.0, "luffing", "D", 1000.0, 5.0,
                          ("alpha", A0, "alpha0_deg"), ("alpha", AK, "alphak_deg"),
                          "complete", 0.4)
    model, path = scene(tmp_path, BASE.replace("alpha0_deg: 10", "alpha0: 0.5").replace(
        "alphak_deg: 50", "reachk: 12.0") + ", rest_to_rest_tau: 2.5, drive: luffing")
    sc = an.read_scene(model, path)
    assert sc.start == ("alpha", 0.5, "alpha0") and sc.end == ("reach", 12.0, "reachk")
    assert sc.rest_to_rest_tau == 2.5 and sc.drive == "luffing"
    model, path = scene(tmp_path, BASE + ", inertia: paper")
    assert an.read_scene(model, path).inertia == "paper"


def test_reach_is_turned_into_the_boom_angle():
    """reach x = L cos(alpha) + 4 -> alpha = acos((x - 4) / L), on both sides of the
    model's 30 deg (1e-12 rad: Newton to 1e-15 in the bracket)."""
    lf = an.Luffing(_model(), replace(SCENE, start=("reach", 12.0, "reach0"),
                                      end=("reach", 6.0, "reachk")))
    assert lf.alpha0 == pytest.approx(math.acos(0.8), abs=1e-12)
    assert lf.alphak == pytest.approx(math.acos(0.2), abs=1e-12)
    assert (lf.lo, lf.hi) == (lf.alpha0, lf.alphak)
    lf = an.Luffing(_model(), replace(SCENE, start=("reach", 6.0, "reach0"),
                                      end=("reach", 13.5, "reachk")))
    assert lf.alpha0 == pytest.approx(math.acos(0.2), abs=1e-12)
    assert lf.alphak == pytest.approx(math.acos(0.95), abs=1e-12)
    assert (lf.lo, lf.hi) == (lf.alphak, lf.alpha0)
    assert lf.g == G and lf.scene.drive == "luffing"


SCENE_ERRORS = [
    (("t_k: 10", "t_k: -1"), "analysis.t_k", None),
    (("t_k: 10", "t_k: 10, colour: red"), "analysis.colour", None),
    (("jib_tip: D", "jib_tip: Q"), "analysis.jib_tip", "unknown node 'Q'"),
    (("boom: boom", "boom: 3"), "analysis.boom", None),
    (("pivot: O", "pivot: 3"), "analysis.pivot", None),
    (("tip: B", "tip: 3"), "analysis.tip", None),
    (("jib_tip: D", "jib_tip: 3"), "analysis.jib_tip", None),
    (("t_k: 10", "t_k: 10, drive: hoist"), "analysis.drive",
     "unknown linear drive 'hoist'; the model has: luffing"),
    (("t_k: 10", "t_k: 10, drive: 3"), "analysis.drive", None),
    (("rope_length: 5.0", "rope_length: 0"), "analysis.load.rope_length", None),
    (("mass: 1000", "mass: -1"), "analysis.load.mass", None),
    (("load: {mass: 1000, rope_length: 5.0}", "load: {mass: 1000}"), "analysis.load", None),
    (("load: {mass: 1000, rope_length: 5.0}", "load: {mass: 1, rope_length: 5, x: 1}"),
     "analysis.load.x", None),
    (("alpha0_deg: 10", "alpha0_deg: 10, reach0: 12"), "analysis",
     "give exactly one of alpha0_deg, alpha0 (rad) or reach0 (m); found alpha0_deg, reach0"),
    (("alphak_deg: 50", "alphak: 0.5, reachk: 12"), "analysis",
     "give exactly one of alphak_deg, alphak (rad) or reachk (m); found alphak, reachk"),
    (("alphak_deg: 50, ", ""), "analysis",
     "give exactly one of alphak_deg, alphak (rad) or reachk (m)"),
    (("alpha0_deg: 10", "alpha0_deg: 180"), "analysis.alpha0_deg",
     "180 deg is not a boom angle in (-180, 180)"),
    (("alpha0_deg: 10", "alpha0_deg: -180"), "analysis.alpha0_deg",
     "-180 deg is not a boom angle in (-180, 180)"),
    (("alpha0_deg: 10", "alpha0: 3.5"), "analysis.alpha0",
     "3.5 rad is not a boom angle in (-pi, pi)"),
    (("alpha0_deg: 10", "alpha0: -3.5"), "analysis.alpha0",
     "-3.5 rad is not a boom angle in (-pi, pi)"),
    (("alpha0_deg: 10", "alpha0_deg: x"), "analysis.alpha0_deg", None),
    (("t_k: 10", "t_k: 10, inertia: own"), "analysis.inertia",
     "'own': use complete (links' translation included) or paper (eq. 3)"),
    (("t_k: 10", "t_k: 10, rest_to_rest_tau: 2.6"), "analysis.rest_to_rest_tau",
     "2.6 s is more than t_k/4; the practical law's acceleration time constant should be "
     "well below t_k"),
    (("t_k: 10", "t_k: 10, rest_to_rest_tau: 0"), "analysis.rest_to_rest_tau", None),
    (("type: luffing", "type: luffing, tip: B"), None, None),
    (("boom: boom, ", ""), "analysis", None),
    (("alpha0_deg: 10", "alpha0: 3.141592653589793"), "analysis.alpha0",
     "3.14159 rad is not a boom angle in (-pi, pi)"),
    (("alpha0_deg: 10", "alpha0: -3.141592653589793"), "analysis.alpha0",
     "-3.14159 rad is not a boom angle in (-pi, pi)"),
]


@pytest.mark.parametrize("change, entry, message", SCENE_ERRORS)
def test_scene_errors_name_the_scene_file_and_the_entry(tmp_path, change, entry, message):
    text = BASE.replace(*change)
    assert text != BASE
    if entry is None:          # a duplicate key: YAML refuses it before read_scene
        with pytest.raises(ModelError):
            scene(tmp_path, text)
        return
    model, path = scene(tmp_path, text)
    with pytest.raises(ModelError) as e:
        an.read_scene(model, path)
    assert (str(e.value.file), e.value.entry) == (path, entry)
    if message is not None:
        assert e.value.message == message


def test_scene_errors_that_depend_on_the_model(tmp_path):
    """Two drives and none named; no drive at all; not a luffing scene; a tau of exactly
    t_k / 4 is allowed; the scene file is the default file of the message."""
    two = "  other: {nodes: [A, Z], pinion_radius: 0.2, gear_ratio: 10, rotor_inertia: 1}\n"
    model, path = scene(tmp_path, extra=two)
    with pytest.raises(ModelError) as e:
        an.read_scene(model, path)
    assert (e.value.entry, e.value.message) == (
        "analysis.drive", "name the linear drive whose motor the energy is reduced to "
        "(one of: luffing, other)")
    (tmp_path / "m.yaml").write_text(model_text().split("linear_drives:")[0])
    model = load(path)
    with pytest.raises(ModelError) as e:
        an.read_scene(model, path)
    assert e.value.message == ("name the linear drive whose motor the energy is reduced "
                               "to (one of: none: add linear_drives)")
    model, path = scene(tmp_path, BASE + ", drive: luffing")
    (tmp_path / "m.yaml").write_text(model_text().split("linear_drives:")[0])
    with pytest.raises(ModelError) as e:
        an.read_scene(load(path), path)
    assert e.value.message == ("unknown linear drive 'luffing'; the model has: none (add "
                               "linear_drives)")
    model, path = scene(tmp_path, BASE.replace("type: luffing", "type: transient"))
    with pytest.raises(ModelError) as e:
        an.read_scene(model)
    assert (str(e.value.file), e.value.entry) == (path, "analysis")
    assert e.value.message == (
        "needs a scene with 'analysis: {type: luffing, boom: ..., pivot: ..., tip: ..., "
        "alpha0_deg: ..., alphak_deg: ..., t_k: ..., drive: ..., jib_tip: ..., load: "
        "{mass: ..., rope_length: ...}}' (docs/luffing.md)")
    model, path = scene(tmp_path, BASE + ", rest_to_rest_tau: 2.5")
    assert an.read_scene(model).rest_to_rest_tau == 2.5
    # without a file given, the scene file is named (the entries are the scene's; the
    # sweeps call law_figures(model, ...) so; before 2026-11-24 the model file was named)
    model, path = scene(tmp_path, BASE.replace("t_k: 10", "t_k: -1"))
    with pytest.raises(ModelError) as e:
        an.read_scene(model)
    assert str(e.value.file) == path != model.file
    model, path = scene(tmp_path, BASE.replace("alphak_deg: 50", "reachk: 15"))
    with pytest.raises(ModelError) as e:
        an.law_figures(model, ["linear"])
    assert (str(e.value.file), e.value.entry) == (path, "analysis.reachk")
    model, path = scene(tmp_path, BASE + ", drive: hoist", extra=two)
    with pytest.raises(ModelError) as e:
        an.read_scene(model, path)
    assert e.value.message == "unknown linear drive 'hoist'; the model has: luffing, other"


def test_linkage_errors(tmp_path):
    """A drive with a node on no body of the linkage (the model file and the drive's
    entry); a jib tip not carried; the two ends equal; a reach out of range; an end
    beyond the linkage's range (the parallelogram folds flat at alpha = -90 deg). Errors
    of the scene's keys name the file given ("s.yaml")."""
    two = "  other: {nodes: [A, Z], pinion_radius: 0.2, gear_ratio: 10, rotor_inertia: 1}\n"
    model, path = scene(tmp_path, extra=two)
    with pytest.raises(ModelError) as e:
        an.Luffing(model, replace(SCENE, drive="other"), path)
    assert (str(e.value.file), e.value.entry) == (model.file, "linear_drives.other")
    assert e.value.message == ("node 'Z' of linear drive 'other' is neither ground nor on a "
                               "body of the linkage")
    for change, entry, message in (
            (dict(jib_tip="Z"), "analysis.jib_tip",
             "node 'Z' is not carried by a body of the linkage"),
            (dict(end=("alpha", A0, "alphak_deg")), "analysis",
             "the start and end of the luffing coincide"),
            (dict(end=("reach", 15.0, "reachk")), "analysis.reachk",
             "reach 15 m is outside what the linkage can reach")):
        with pytest.raises(ModelError) as e:
            an.Luffing(_model(), replace(SCENE, **change), "s.yaml")
        assert (e.value.file, e.value.entry, e.value.message) == ("s.yaml", entry, message)
    with pytest.raises(ModelError) as e:
        an.Luffing(_model(), replace(SCENE, jib_tip="Z"))
    assert e.value.file == _model().file          # a model without a scene: its file
    model, path = scene(tmp_path)
    with pytest.raises(ModelError) as e:
        an.Luffing(model, replace(SCENE, jib_tip="Z"))
    assert (str(e.value.file), e.value.entry) == (path, "analysis.jib_tip")
    with pytest.raises(ModelError) as e:
        an.Luffing(_model(), replace(SCENE, start=("alpha", math.radians(-100), "alpha0_deg")),
                   "s.yaml")
    assert (e.value.file, e.value.entry) == ("s.yaml", "analysis.alpha0_deg")
    assert e.value.message.startswith("alpha = -100.00 deg is beyond the linkage's range (")
    with pytest.raises(ModelError) as e:
        an.Luffing(_model(), replace(SCENE, end=("alpha", math.radians(-100), "alphak")),
                   "s.yaml")
    assert e.value.entry == "analysis.alphak"


def test_sensitivity_report_with_the_papers_inertia(monkeypatch):
    """inertia: paper: the swing-free law (stand-in) and the rest-to-rest law of every row
    are asked in Jp: its peak torque by hand from the Jp law (laws.py's, value-tested)."""
    fake = FakeSwingFree()
    monkeypatch.setattr(sway, "swing_free_law", fake)
    lf = luffing(inertia="paper")
    rep = an.sensitivity_report(lf, lf.optimal())
    assert [c["which"] for c in fake.calls] == ["paper"] * 8
    row = rep["t_k"][0]
    rr = rest_to_rest_law(lf.proxy, A0, AK, 0.4, 5.0, "paper")
    al, d1, d2 = rr.evaluate(np.linspace(0, 1, 401))
    h = hand(al)
    Q = (h["J"] * d2 + 0.5 * h["dJ"] * d1**2) / 5.0**2 + h["dV"]
    assert row["rest_to_rest_peak_motor_torque_Nm"] == pytest.approx(
        np.abs(Q / (RATIO * h["ds"])).max(), rel=1e-9)
