"""Generated lattice cranes: mesh import, the compact `pairs` form, and agreement with
independently written assemblies (the floor script, OpenSeesPy when installed)."""

import json
import subprocess
import sys

import numpy as np
import pytest

from cranefe.cli import main
from cranefe.model.generate import panels_for, to_yaml, tower_crane, with_meshes
from cranefe.model import load
from cranefe.analysis.modal import modes


@pytest.fixture(scope="module")
def crane_files(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("lattice")
    model = tower_crane(panels=panels_for(3000))
    yml = to_yaml(model, str(tmp / "crane.yaml"))
    mesh = str(tmp / "crane_mesh.yaml")
    to_yaml(with_meshes(model, mesh), mesh)
    return yml, mesh


def test_mesh_files_give_the_same_model(crane_files):
    yml, mesh = crane_files
    a, b = modes(load(yml), count=12), modes(load(mesh), count=12)
    assert a.dofs == b.dofs > 2900
    np.testing.assert_allclose(b.omega, a.omega, rtol=1e-10)


def _script(module, path, count):
    out = subprocess.run([sys.executable, "-m", module, path, str(count)],
                         capture_output=True, text=True, check=True).stdout
    return np.array(json.loads(out[out.index("{"):])["frequency_hz"])


def test_agrees_with_an_independent_bare_assembly(crane_files):
    # the floor script assembles the same trusses with its own few lines of numpy
    yml, _ = crane_files
    r = modes(load(yml), count=10)
    np.testing.assert_allclose(r.frequency_hz, _script("cranefe.studies._floor", yml, 10),
                               rtol=1e-9)


def test_agrees_with_opensees(crane_files):
    # checked in a subprocess: importing OpenSees here would print at this process's exit
    from cranefe.studies.performance import _opensees_available
    if not _opensees_available():
        pytest.skip("OpenSeesPy is not installed (pip install -e '.[bench]')")
    yml, _ = crane_files
    r = modes(load(yml), count=10)
    # OpenSees' ARPACK over a profile Cholesky agrees to its eigen tolerance
    np.testing.assert_allclose(r.frequency_hz, _script("cranefe.studies._opensees", yml, 10),
                               rtol=1e-7)


def test_generate_command(tmp_path, capsys):
    out = tmp_path / "g.yaml"
    assert main(["generate", "tower-crane", "--dofs", "1500", "--mesh", "--out",
                 str(out)]) == 0
    assert sorted(p.name for p in tmp_path.glob("g_*.vtu"))
    assert main(["modes", str(out), "--count", "3", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert abs(doc["dofs"] - 1500) < 100 and doc["solver"] == "sparse"


def test_mesh_member_errors(tmp_path, capsys):
    text = """cranefe: 1
nodes: {A: [0, 0, 0]}
members:
  m: {type: truss, mesh: missing.vtu, E: 2.1e11, A: 1.0e-3}
"""
    (tmp_path / "m.yaml").write_text(text)
    assert main(["check", str(tmp_path / "m.yaml")]) == 2
    err = capsys.readouterr().err
    assert "members.m.mesh" in err and "not found" in err
