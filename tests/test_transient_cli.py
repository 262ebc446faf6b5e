"""`cranefe simulate`: outputs (JSON, CSV, archive, XDMF, PNG), bad scenes, and every
transient example scene with one pinned figure."""

import glob
import json
import os

import numpy as np
import pytest

from cranefe.cli import main

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HOIST = os.path.join(ROOT, "models", "two_mass_hoist.yaml")
SCENES = sorted(glob.glob(os.path.join(ROOT, "models", "scenes", "*.yaml")))

# dynamic factor of the first rope, pinned from this version (a change means the
# physics changed); the scenes' headers give the hand estimates
PINNED = {
    "hammerhead_lift_off.yaml": 1.621667,
    "luffing_lift_off.yaml": 1.185977,
    "two_mass_hoist_motor_start.yaml": 1.169796,
    "two_mass_hoist_slack.yaml": 2.355064,
    "two_mass_hoist_start_modal.yaml": 1.092298,
}


def test_every_scene_is_pinned():
    assert sorted(PINNED) == sorted(os.path.basename(s) for s in SCENES)


@pytest.mark.parametrize("path", SCENES, ids=os.path.basename)
def test_example_scenes(path, capsys):
    assert main(["simulate", path, "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    first = next(iter(doc["dynamic_factor"].values()))
    assert first == pytest.approx(PINNED[os.path.basename(path)], rel=1e-6)
    assert doc["energy_error"] < 1e-9
    assert doc["effects"]["sway"] is False


def test_cli_json_csv_archive_xdmf_and_plots(tmp_path, capsys):
    path = tmp_path / "lift.yaml"
    path.write_text(f"cranefe: 1\nscene: lift\nmodel: {HOIST}\neffects: {{sway: false}}\n"
                    "analysis:\n  type: transient\n  duration: 0.5\n  time_step: 0.001\n"
                    "  output_step: 0.005\n  initial: grounded\n"
                    "  drums:\n    hoist: {speed: 2.0}\n")
    out = tmp_path / "o"
    out.mkdir()
    assert main(["simulate", str(path), "--json", "--csv", str(out / "t.csv"), "--archive",
                 str(out / "t.h5"), "--plots", str(out), "--xdmf", str(out / "t.xdmf")]) == 0
    doc = json.loads(capsys.readouterr().out)
    for key in ("duration_s", "dynamic_factor", "rope_force_max_N", "rope_force_static_N",
                "lift_off_time_s", "effects", "dofs"):
        assert key in doc
    assert doc["effects"]["sway"] is False and doc["dofs"] == 2
    assert doc["duration_s"] == 0.5 and doc["steps"] == 500
    assert doc["lift_off_time_s"] == pytest.approx(0.179869, rel=1e-5)
    assert doc["drums"]["hoist"]["drive"] == "speed"
    from cranefe.outputs.archive import read
    arc = read(out / "t.h5")
    res = arc.results["transient"]
    assert res.lift_off_time == doc["lift_off_time_s"]
    assert res.rope_force_max[0] == doc["rope_force_max_N"]["hoist_rope"]
    assert res.events == ["0.179869 s: H lift-off"]
    assert (out / "transient.png").stat().st_size > 10000
    assert (out / "t.xdmf").exists() and (out / "t.xdmf.h5").exists()
    rows = (out / "t.csv").read_text().splitlines()
    assert len(rows) == 1 + 101             # header, t = 0 and every 5th of 500 steps
    assert rows[0].startswith("t_s,rope_hoist_rope_N,drum_hoist_rad,drum_hoist_rad_s")
    # the peak is tracked on every step, not only at the stored output times
    forces = np.array([float(r.split(",")[1]) for r in rows[1:]])
    assert forces.max() < doc["rope_force_max_N"]["hoist_rope"]


def test_table_output(capsys):
    path = os.path.join(ROOT, "models", "two_mass_hoist_lift.yaml")
    assert main(["simulate", path]) == 0
    out = capsys.readouterr().out
    assert "dynamic factor" in out and "lift-off at t = 0.179869 s" in out


@pytest.mark.parametrize("analysis, entry", [
    ("  duration: -1\n", "analysis.duration"),
    ("  method: rk4\n", "analysis.method"),
    ("  drums:\n    nope: {speed: 1}\n", "analysis.drums.nope"),
    ("  initial: grounded\n", "analysis.initial"),           # sway is on in the model
    ("  dureation: 2\n", "analysis.dureation"),
    ("  drums:\n    hoist: {torque: [[0, 1], [0, 2]]}\n", "analysis.drums.hoist.torque"),
    ("  drums:\n    hoist: {torque: 1, speed: 2}\n", "analysis.drums.hoist"),
    ("  drums:\n    hoist: {motor: {stall_torque: 400}}\n", "analysis.drums.hoist.motor"),
    ("  forces:\n    S: {force: [0, 0, 1]}\n", "analysis.forces.S"),
    ("  forces:\n    H: {force: [0, 5, 1]}\n", "analysis.forces.H.force"),
    ("  modes: 3\n", "analysis.modes"),
    ("  duration: 1\n  time_step: 2\n", "analysis.time_step"),
    ("  grounded: [H]\n", "analysis.grounded"),
])
def test_bad_transient_scenes(tmp_path, capsys, analysis, entry):
    path = tmp_path / "bad.yaml"
    path.write_text(f"cranefe: 1\nmodel: {HOIST}\nanalysis:\n  type: transient\n{analysis}")
    assert main(["simulate", str(path)]) == 2
    err = capsys.readouterr().err
    assert entry in err and str(path) in err and "Traceback" not in err


def test_grounded_needs_direct_and_simulate_needs_a_transient(tmp_path, capsys):
    path = tmp_path / "bad.yaml"
    path.write_text(f"cranefe: 1\nmodel: {HOIST}\neffects: {{sway: false}}\nanalysis:\n"
                    "  type: transient\n  initial: grounded\n  method: modal\n")
    assert main(["simulate", str(path)]) == 2
    assert "analysis.method" in capsys.readouterr().err
    assert main(["simulate", HOIST]) == 2
    assert "analysis.type" in capsys.readouterr().err
