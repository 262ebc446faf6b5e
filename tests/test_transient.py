"""Transient scenes against closed forms: hoist start, lift-off, energy, modal = direct."""

import json
import os

import numpy as np
import pytest
import scipy.linalg as sla

from cranefe.cli import main
from cranefe.model import load
from cranefe.transient.integrate import simulate

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HOIST = os.path.join(ROOT, "models", "two_mass_hoist.yaml")
G = 9.81


def scene(tmp_path, analysis, name="scene.yaml", effects="{sway: false}"):
    path = tmp_path / name
    path.write_text(f"cranefe: 1\nscene: test\nmodel: {HOIST}\neffects: {effects}\n"
                    f"analysis:\n  type: transient\n{analysis}")
    return load(path)


def hoist_data():
    """Drum radius R, inertia J (with the motor), rope stiffness k, load m, falls n."""
    m = load(HOIST)
    rope = m.ropes[0]
    L = float(np.sum(rope.falls * np.linalg.norm(m.coords[rope.span_b] -
                                                 m.coords[rope.span_a], axis=1))
              + rope.extra_length)
    return m.drums[0].radius, m.drums[0].reduced_inertia, rope.EA / L, \
        float(m.masses.mass[0]), 2


def test_step_torque_against_the_closed_form(tmp_path):
    # q = (theta, z): stretch = R theta - n z; a step torque dT beyond the holding torque
    # from rest: rigid part phi0 phi0^T F t^2/2 plus elastic phi phi^T F (1 - cos wt)/w^2
    R, J, k, m, n = hoist_data()
    S0 = m * G / n
    torque = 9000.0
    model = scene(tmp_path, "  duration: 2.0\n  time_step: 0.0005\n  drums:\n"
                            f"    hoist: {{torque: {torque}}}\n")
    r = simulate(model)
    K = k * np.array([[R * R, -n * R], [-n * R, n * n]])
    M = np.diag([J, m])
    F = np.array([torque - R * S0, 0.0])
    w2, V = sla.eigh(K, M)
    t = r.times
    q = np.outer(V[:, 0] @ F * t**2 / 2, V[:, 0]) + \
        np.outer(V[:, 1] @ F * (1 - np.cos(np.sqrt(w2[1]) * t)) / w2[1], V[:, 1])
    force = S0 + k * (R * q[:, 0] - n * q[:, 1])
    # Newmark's period error (w h)^2 / 12 = 5e-6 shifts the phase by 5e-6 w t
    np.testing.assert_allclose(r.rope_force[:, 0], force, rtol=2e-4)
    assert r.rope_force_max[0] == pytest.approx(force.max(), rel=1e-5)
    assert r.energy_error < 1e-8


def test_lift_off_at_constant_hauling_speed(tmp_path):
    # rope hauled in at v_r = R w_d: force k v_r t until n S = m g (lift-off);
    # then the load starts from rest while the rope end moves: peak m g (1 + v w / g)
    R, J, k, m, n = hoist_data()
    wd = 2.0
    model = scene(tmp_path, "  duration: 1.2\n  time_step: 0.0002\n  initial: grounded\n"
                            f"  drums:\n    hoist: {{speed: {wd}}}\n")
    r = simulate(model)
    v = R * wd / n
    w = np.sqrt(n * n * k / m)
    assert r.lift_off_time == pytest.approx(m * G / (n * k * R * wd), rel=1e-6)
    assert r.dynamic_factor[0] == pytest.approx(1 + v * w / G, rel=1e-5)
    assert r.rope_force_static[0] == pytest.approx(m * G / n, rel=1e-12)


def test_modal_superposition_with_all_modes_equals_direct(tmp_path):
    table = "[[0, 0], [0.2, 15000], [1.0, 15000]]"
    direct = simulate(scene(tmp_path, "  duration: 1.5\n  time_step: 0.001\n  drums:\n"
                                      f"    hoist: {{torque: {table}}}\n", "d.yaml"))
    modal = simulate(scene(tmp_path, "  duration: 1.5\n  time_step: 0.001\n  method: modal\n"
                                     f"  modes: 2\n  drums:\n    hoist: {{torque: {table}}}\n",
                           "m.yaml"))
    np.testing.assert_allclose(modal.rope_force, direct.rope_force, rtol=1e-9)
    np.testing.assert_allclose(modal.drum_speed, direct.drum_speed, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("dt", [1e-3, 1e-5])
def test_slack_rope_events_keep_the_energy(tmp_path, dt):
    # the drive pays out faster than the load can fall: slack, free fall, re-tension
    duration = 1.5 if dt > 1e-4 else 0.12
    table = "[[0, -80000], [0.3, -80000], [0.31, 0], [1.5, 0]]"
    r = simulate(scene(tmp_path, f"  duration: {duration}\n  time_step: {dt}\n  drums:\n"
                                 f"    hoist: {{torque: {table}}}\n"))
    assert any("slack" in e for e in r.events)
    if dt > 1e-4:
        assert any("taut" in e for e in r.events)
    assert r.energy_error < 1e-7


def test_cli_json_csv_archive_and_plots(tmp_path, capsys):
    model = scene(tmp_path, "  duration: 0.5\n  time_step: 0.001\n  initial: grounded\n"
                            "  drums:\n    hoist: {speed: 2.0}\n")
    path = model.scene_file
    out = tmp_path / "o"
    out.mkdir()
    assert main(["simulate", path, "--json", "--csv", str(out / "t.csv"), "--archive",
                 str(out / "t.h5"), "--plots", str(out), "--xdmf", str(out / "t.xdmf")]) == 0
    doc = json.loads(capsys.readouterr().out)
    for key in ("duration_s", "dynamic_factor", "rope_force_max_N", "rope_force_static_N",
                "lift_off_time_s", "effects", "dofs"):
        assert key in doc
    assert doc["effects"]["sway"] is False and doc["dofs"] == 2
    from cranefe.archive import read
    assert read(out / "t.h5").results["transient"].lift_off_time == doc["lift_off_time_s"]
    assert (out / "transient.png").exists() and (out / "t.xdmf").exists()
    assert len((out / "t.csv").read_text().splitlines()) == 502


@pytest.mark.parametrize("analysis, entry", [
    ("  duration: -1\n", "analysis.duration"),
    ("  method: rk4\n", "analysis.method"),
    ("  drums:\n    nope: {speed: 1}\n", "analysis.drums.nope"),
    ("  initial: grounded\n", "analysis.initial"),       # with sway on
])
def test_bad_transient_scenes(tmp_path, capsys, analysis, entry):
    path = tmp_path / "bad.yaml"
    path.write_text(f"cranefe: 1\nmodel: {HOIST}\nanalysis:\n  type: transient\n{analysis}")
    assert main(["simulate", str(path)]) == 2
    err = capsys.readouterr().err
    assert entry in err and str(path) in err
