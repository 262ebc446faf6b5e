"""`cranefe luff`: JSON keys, archive, plots, bad scenes (exit 2 naming the entry), and
the committed results of `cranefe study luffing`."""

import json
import os
import textwrap

import pytest

from cranefe.outputs import archive
from cranefe.cli import main

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODEL = os.path.join(ROOT, "models", "portal_crane_luffing.yaml")
SCENE = os.path.join(ROOT, "models", "portal_crane_luffing_scene.yaml")
LAWS = ("optimal", "linear", "cubic", "quintic", "cycloidal", "trapezoidal")


def test_luff_json_archive_and_plots(tmp_path, capsys):
    out = tmp_path / "luff.h5"
    plots = tmp_path / "plots"
    assert main(["luff", SCENE, "--json", "--no-sensitivity", "--archive", str(out),
                 "--plots", str(plots)]) == 0
    doc = json.loads(capsys.readouterr().out)
    for key in ("alpha0_rad", "alphak_rad", "t_k_s", "jib_tip_deviation_m"):
        assert isinstance(doc[key], float)
    assert set(doc["optimum"]) >= {"T_mean_J", "T_mean_paper_J"}
    for name in LAWS:
        assert set(doc["laws"][name]) >= {"T_mean_J", "T_ratio", "peak_motor_torque_Nm",
                                          "max_sway_deg", "residual_sway_deg"}
    assert doc["laws"]["optimal"]["T_ratio"] == pytest.approx(1.0, abs=1e-12)
    assert doc["t_k_s"] == 25.0
    arc = archive.read(out)
    back = arc.results["luffing"]
    assert type(back).__name__ == "LuffingResult"
    assert back.alpha.shape == (len(back.law_names), len(back.t))
    assert back.table["optimal"]["T_mean_J"] == doc["laws"]["optimal"]["T_mean_J"]
    names = sorted(os.listdir(plots))
    assert names == sorted(f"luffing_{k}.png" for k in
                           ("alpha", "speed", "torque", "energy", "sway", "tip_path"))


def test_luff_table(capsys):
    assert main(["luff", SCENE, "--no-sensitivity"]) == 0
    out = capsys.readouterr().out
    assert "optimal" in out and "paper 3-point collocation (corrected)" in out


def _scene(tmp_path, analysis, name="s.yaml"):
    text = textwrap.dedent(f"""\
        cranefe: 1
        scene: bad
        model: {MODEL}
        analysis:
        """) + textwrap.indent(textwrap.dedent(analysis), "  ")
    path = tmp_path / name
    path.write_text(text)
    return str(path)


BASE = """\
type: luffing
boom: boom
pivot: O
tip: B
reach0: 30.0
reachk: 8.0
t_k: 25.0
drive: luffing
jib_tip: D
load: {mass: 16000, rope_length: 15.0}
"""


@pytest.mark.parametrize("change, entry", [
    (("t_k: 25.0", "t_k: -1"), "analysis.t_k"),
    (("drive: luffing", "drive: hoist"), "analysis.drive"),
    (("boom: boom", "boom: mast"), "analysis.boom"),
    (("pivot: O", "pivot: B"), "analysis.pivot"),
    (("jib_tip: D", "jib_tip: X"), "analysis.jib_tip"),
    (("reach0: 30.0", "reach0: 60.0"), "analysis.reach0"),
    (("reach0: 30.0", "alpha0_deg: 95.0"), "analysis.alpha0_deg"),
    (("reach0: 30.0", "alpha0_deg: 50\nreach0: 30.0"), "analysis"),
    (("load: {mass: 16000, rope_length: 15.0}", "load: {mass: 16000}"), "analysis.load"),
    (("t_k: 25.0", "t_k: 25.0\nspeed: 3"), "analysis.speed"),
])
def test_bad_scene_names_the_entry(tmp_path, capsys, change, entry):
    path = _scene(tmp_path, BASE.replace(*change))
    assert main(["luff", path, "--json"]) == 2
    err = capsys.readouterr().err
    assert f": {entry}:" in err and "Traceback" not in err


def test_luff_needs_a_luffing_scene(capsys):
    assert main(["luff", MODEL]) == 2
    assert "analysis" in capsys.readouterr().err


# The cost study's table (results/luffing_cost.csv) is checked where it is computed:
# tests/test_studies.py::check_luffing runs `cranefe study luffing --quick`.
