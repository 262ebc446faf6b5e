"""`cranefe loads` (docs/loads.md): the dynamic factors computed from simulations,
against the single-mass closed forms (through the API and the CLI), and the internal
consistency of a tower crane's load table."""

import json
import os

import numpy as np
import pytest

import cranefe
from cranefe.analysis.loads import sdof, standard
from cranefe.cli import main

MODELS = os.path.join(os.path.dirname(__file__), "..", "models")
SCENE = os.path.join(MODELS, "loads", "two_mass_hoist_loads.yaml")
G = 9.81


@pytest.fixture(scope="module")
def hoist():
    return cranefe.loads(SCENE)


@pytest.fixture(scope="module")
def omega():
    """Load-on-rope frequency with the drum held (its drive holds it), by the modal
    analysis (an independent path): sqrt(n^2 EA / (L m)) = 14.77 rad/s."""
    m = cranefe.modes(os.path.join(MODELS, "two_mass_hoist.yaml"), effects={"sway": False,
                                                           "drive": "held"})
    w = m.omega[~m.rigid]
    assert len(w) == 1
    return float(w[0])


def _scene(tmp_path, text):
    path = tmp_path / "s.yaml"
    path.write_text("cranefe: 1\nscene: t\nmodel: " + os.path.abspath(
        os.path.join(MODELS, "two_mass_hoist.yaml")) + "\n" + text)
    return str(path)


def test_phi2_is_one_plus_v_omega_over_g(hoist, omega):
    # rigid drive from the grounded state: 1 + v w / g exactly (docs/transient.md); the
    # trapezoidal rule keeps the amplitude, so the error is the peak's phase-sampling,
    # O((w h)^4) = 1e-5 at w h = 0.06
    curve = hoist.factors["phi2"]["curve"]
    assert len(curve) == 5
    for p in curve:
        exact = float(sdof.phi2_rigid_drive(p["v_h_m_s"], omega))
        assert p["value"] == pytest.approx(exact, rel=2e-5), p
    d = hoist.factors["phi2"]["drive_classes"]
    assert d["HD1"]["v_h_m_s"] == 0.5 and d["HD4"]["v_h_m_s"] == 0.25
    assert d["HD2"]["value"] == d["HD3"]["value"]
    assert d["HD2"]["v_h_m_s"] == pytest.approx(0.05)


def test_phi5_of_a_jerk_limited_start(hoist, omega):
    # acceleration rising over t_j: 1 + |sin(w t_j/2)|/(w t_j/2); the speed table is
    # exact at its samples and the trapezoidal rule's phase error at w h = 0.06 gives
    # ~1e-4 on the peak
    p = hoist.factors["phi5"]["hoist"]
    exact = float(sdof.phi5_ramp(omega, 0.25))
    assert p["value"] == pytest.approx(exact, rel=3e-4)
    assert p["acceleration_m_s2"] == pytest.approx(0.5 / (2.0 - 0.25))
    # HD5 (pre-tensioned, then this start): phi2 = 1 + phi5 a / g
    hd5 = hoist.factors["phi2"]["drive_classes"]["HD5"]
    assert hd5["value"] == pytest.approx(1 + p["value"] * p["acceleration_m_s2"] / G,
                                         rel=1e-9)


def test_phi3_sudden_release(hoist):
    # a quarter dropped at once: 1 - 2 dm/m = 0.5 (beta3 = 1), exact for one mass; the
    # modal run (all modes) with Hermite-tracked peaks: 1e-6
    p = hoist.factors["phi3"]
    assert p["dm_over_m"] == 0.25
    assert p["value"] == pytest.approx(1 - 2 * 0.25, abs=1e-6)
    assert p["standard"] == pytest.approx(0.5)
    assert p["beta3_equivalent"] == pytest.approx(1.0, abs=4e-6)


def test_phi3_release_over_time(tmp_path, omega):
    # spread over t_r: 1 - (dm/m)(1 + A(w' t_r)), w' of the remaining mass
    path = _scene(tmp_path, "analysis:\n  type: loads\n  hoist: {speed: 0.25}\n"
                  "  release: {fraction: 0.4, time: 0.3}\n  after_lift_off: 1.0\n"
                  "  time_step: 0.004\n")
    r = cranefe.loads(path)
    w1 = omega / np.sqrt(0.6)
    low, _ = sdof.phi3_linear_release(0.4, w1, 0.3)
    assert r.factors["phi3"]["value"] == pytest.approx(float(low), abs=2e-4)


def test_phi1_of_a_rigid_structure_is_one(hoist):
    p = hoist.factors["phi1"]
    assert p["value"] == 1.0 and p["by_mass"] == {}
    assert "rigid" in p["assumes"]


def test_phi4_phi6_phi7(hoist):
    f = hoist.factors
    assert f["phi6"]["value"] == pytest.approx(0.5 * (1 + f["phi2"]["value"]))
    assert f["phi4"]["value"] is None and "step" in f["phi4"]["missing"]
    assert f["phi7"]["value"] is None and "buffer" in f["phi7"]["missing"]


def test_cli_json_is_the_api_document(hoist, capsys):
    assert main(["loads", SCENE, "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    api = json.loads(json.dumps(hoist.to_dict()))
    for d in (doc, api):
        d.pop("timings_s")
        for s in d["simulations"]:
            s.pop("seconds")
    assert doc == api
    assert set(doc["factors"]) == {f"phi{k}" for k in range(1, 8)}
    assert doc["factors"]["phi2"]["simulation"] in [s["name"] for s in doc["simulations"]]


def test_bad_keys_exit_2(tmp_path, capsys):
    path = _scene(tmp_path, "analysis:\n  type: loads\n  hoist: {sped: 1}\n")
    assert main(["loads", path]) == 2
    assert "analysis.hoist" in capsys.readouterr().err
    path = _scene(tmp_path, "analysis:\n  type: loads\n  release: {fraction: 1.5}\n")
    assert main(["loads", path]) == 2


def test_tower_crane_table_is_consistent():
    """The hammerhead's load table (models/loads/hammerhead_loads.yaml): phi6 from phi2, the
    hoisting class from the computed curve, the crane's masses moving (phi1 > 1)."""
    r = cranefe.loads(os.path.join(MODELS, "loads", "hammerhead_loads.yaml"))
    f = r.factors
    p2 = f["phi2"]
    v = np.array([p["v_h_m_s"] for p in p2["curve"]])
    phi = np.array([p["value"] for p in p2["curve"]])
    assert np.all(np.diff(phi) > 0)                 # faster lifts, larger factors
    within = p2["behaves_like"]["within"]
    if within is not None:
        assert np.all(phi <= standard.phi2(within, v) + 1e-12)
        lower = list(standard.HOISTING_CLASSES)[list(standard.HOISTING_CLASSES)
                                                  .index(within) - 1] \
            if within != "HC1" else None
        assert lower is None or np.any(phi > standard.phi2(lower, v))
    else:
        assert np.any(phi > standard.phi2("HC4", v))
    assert f["phi6"]["value"] == pytest.approx(0.5 * (1 + p2["value"]), rel=1e-12)
    assert f["phi6"]["standard"] == pytest.approx(0.5 * (1 + p2["standard"]), rel=1e-12)
    assert f["phi1"]["value"] > 1.0 and f["phi1"]["lower"] < 1.0
    assert f["phi3"]["value"] < 1.0
    assert 1.0 < f["phi5"]["hoist"]["value"] <= 2.0 + 1e-9


def test_sweep_of_factors_is_exact(tmp_path, omega):
    """`factors.phi2` as a sweep output (only the HD1 lift-off runs): over the hook
    load, 1 + v w(m) / g with w^2 = n^2 k / m scaling as 1/m."""
    from cranefe.sweeps.engine import run_sweep
    from cranefe.sweeps.spec import load_sweep
    from cranefe.sweeps.summary import summarise
    path = tmp_path / "chart.yaml"
    path.write_text(f"cranefe: 1\nbase: {os.path.abspath(SCENE)}\nparameters:\n"
                    "  masses.H: {values: [2600, 5200]}\n"
                    "outputs: [factors.phi2, factors.phi5.hoist, frequency_hz.1]\n")
    s = load_sweep(str(path))
    t = summarise(s, run_sweep(s, workers=0)).table
    assert list(t.status) == ["ok", "ok"]
    for m, (phi2, phi5, f1) in zip(t.values[:, 0], t.results):
        w = omega * np.sqrt(5200 / m)
        assert phi2 == pytest.approx(float(sdof.phi2_rigid_drive(0.5, w)), rel=2e-5)
        assert phi5 == pytest.approx(float(sdof.phi5_ramp(w, 0.25)), rel=3e-4)
    bad = tmp_path / "bad.yaml"
    bad.write_text("cranefe: 1\nbase: " + os.path.abspath(os.path.join(
        MODELS, "two_mass_hoist.yaml")) + "\nparameters:\n  masses.H: {values: [1]}\n"
        "outputs: [factors.phi2]\n")
    with pytest.raises(cranefe.errors.ModelError, match="loads scene"):
        load_sweep(str(bad))


def test_phi5_of_a_trolley_move_on_the_operation_engine(tmp_path):
    """Overhead crane (models/operations/overhead_crane.yaml): the load on a 6 m
    pendulum below a trolley driven along its slider by an s-curve. The horizontal
    force on the load over m a is the single-mass 1 + |sin(w t_j/2)|/(w t_j/2), w =
    sqrt(g/l), in the linear limit; the acceleration phase lasts t_j + one period, so it
    leaves no swing and the braking repeats the same peak. Tolerance 5e-4: the exact
    pendulum at 0.02 rad of sway (~theta^2/4 = 1e-4), the engine's tolerance 1e-9 and
    second differences of the positions at 0.01 s (measured 1.8e-4)."""
    w = float(np.sqrt(G / 6.0))
    ramp = float(1.0 + 2 * np.pi / w)
    path = tmp_path / "oh.yaml"
    path.write_text(
        "cranefe: 1\nscene: t\nmodel: " + os.path.abspath(os.path.join(
            MODELS, "operations", "overhead_crane.yaml")) +
        f"\nanalysis:\n  type: loads\n  hoist: {{speed: 0.2}}\n  tolerance: 1.0e-9\n"
        f"  drives:\n    trolley_travel: {{v_max: 0.5, ramp: {ramp!r}, jerk_time: 1.0, "
        "distance: 6.0}\n")
    r = cranefe.loads(str(path), only=["trolley_travel"])
    p = r.factors["phi5"]["trolley_travel"]
    assert set(r.factors) == {"phi5"} and set(r.factors["phi5"]) == {"trolley_travel"}
    assert p["value"] == pytest.approx(float(sdof.phi5_ramp(w, 1.0)), rel=5e-4)
    assert p["acceleration"] == pytest.approx(0.5 / (ramp - 1.0))


LUFFING_MODEL = """cranefe: 1
name: A jib luffing on a hinge, the load on a 10 m rope below its tip
nodes:
  O:   [0.0, 0.0, 0.0]
  TIP: [0.0, 0.0, 20.0]
  D:   [-1.0, 0.0, 0.5]
  L:   [0.0, 0.0, 10.0]
ground: [O]
masses:
  L: 2000
bodies:
  jib: {mass: 3000, com: [0.0, 0.0, 10.0], inertia: [1.0e3, 1.0e5, 1.0e5],
        nodes: [TIP, D]}
joints:
  - {name: luffing, type: hinge, bodies: [ground, jib], at: O, axis: [0, 1, 0]}
springs:
  - {name: luffing_gear, type: rotational, bodies: [ground, jib], at: O, axis: [0, 1, 0],
     stiffness: 1.0e9}
drums:
  hoist: {node: D, radius: 0.2, inertia: 5.0, brake: false, rope_reserve: 20.0,
          motor: {rotor_inertia: 0.05, gear_ratio: 30}}
ropes:
  hoist_rope: {EA: 5.0e7, path: [hoist, TIP, L]}
"""


def test_phi5_of_a_luffing_hinge(tmp_path):
    """A hinge with a horizontal axis (luffing): the tip, 20 m above the hinge, moves
    horizontally by 20 x the angle (its height changes only to second order); the load
    on its 10 m rope then sees the drive's s-curve, and the horizontal force over m a is
    the single-mass 1 + |sin(w t_j/2)|/(w t_j/2), w = sqrt(g/l) (the acceleration
    phase t_j + one period long leaves no swing). Tolerance 1e-3: the tip's vertical
    acceleration 20 alpha phi and the lever's change over 1.5 deg (second order), the
    exact pendulum, second differences (measured 2.8e-4)."""
    (tmp_path / "luff.yaml").write_text(LUFFING_MODEL)
    w = float(np.sqrt(G / 10.0))
    ramp = float(1.0 + 2 * np.pi / w)
    path = tmp_path / "s.yaml"
    path.write_text("cranefe: 1\nscene: t\nmodel: luff.yaml\nanalysis:\n  type: loads\n"
                    "  hoist: {speed: 0.2}\n  tolerance: 1.0e-9\n  drives:\n"
                    f"    luffing: {{v_max_deg: 0.5, ramp: {ramp!r}, jerk_time: 1.0, "
                    "distance_deg: 5.0}\n")
    r = cranefe.loads(str(path), only=["luffing"])
    p = r.factors["phi5"]["luffing"]
    assert p["kind"] == "hinge"
    assert p["acceleration"] == pytest.approx(20 * np.radians(0.5) / (ramp - 1.0))
    assert p["value"] == pytest.approx(float(sdof.phi5_ramp(w, 1.0)), rel=1e-3)


def test_shapers_of_a_trolley_move_through_cranefe_loads(tmp_path, capsys):
    """`cranefe loads --shapers ZV,ZVD`: the overhead crane's trolley move (6 m
    pendulum, w = sqrt(g/l)) unshaped and shaped, frequency from the crane's own modes.
    ZV adds half a swing period pi/w to the move and ZVD a whole one (to 1e-3: the
    modes' pendulum is the elastic rope's, 1e-4 off the rigid one); both leave far less
    residual sway than the unshaped move (linear limit: none; the nonlinear and elastic
    residue is below 1 % of the unshaped swing, ZVD below ZV)."""
    w = float(np.sqrt(G / 6.0))
    path = tmp_path / "oh.yaml"
    path.write_text(
        "cranefe: 1\nscene: t\nmodel: " + os.path.abspath(os.path.join(
            MODELS, "operations", "overhead_crane.yaml")) +
        "\nanalysis:\n  type: loads\n  hoist: {speed: 0.2}\n  tolerance: 1.0e-8\n"
        "  drives:\n    trolley_travel: {v_max: 0.5, ramp: 1.5, jerk_time: 0.5, "
        "distance: 6.0}\n")
    r = cranefe.loads(str(path), only=["trolley_travel"], shapers=("ZV", "ZVD"))
    s = r.to_dict()["shapers"]["trolley_travel"]
    assert set(s) == {"unshaped", "ZV", "ZVD"}
    base = s["unshaped"]
    assert base["residual_sway_deg"] > 1.0
    assert s["ZV"]["move_time_s"] - base["move_time_s"] == pytest.approx(np.pi / w, rel=1e-3)
    assert s["ZVD"]["move_time_s"] - base["move_time_s"] == pytest.approx(2 * np.pi / w,
                                                                         rel=1e-3)
    assert s["ZV"]["residual_sway_deg"] < 0.01 * base["residual_sway_deg"]
    assert s["ZVD"]["residual_sway_deg"] < s["ZV"]["residual_sway_deg"]
    assert main(["loads", str(path), "--shapers", "ZV,XX"]) == 2
    assert "--shapers" in capsys.readouterr().err
