"""Archives, ParaView files and off-screen images (issue: results people can keep)."""

import json
import os

import numpy as np
import pytest

from cranefe.outputs import archive
from cranefe.system import assemble
from cranefe.cli import main
from cranefe.model import load
from cranefe.analysis.modal import modes

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TOWER = os.path.join(ROOT, "models", "hammerhead_tower_crane.yaml")
LUFFING = os.path.join(ROOT, "models", "luffing_tower_crane.yaml")


@pytest.fixture(scope="module")
def tower():
    model = load(TOWER)
    system = assemble(model)
    return model, system, modes(model, system=system)


def test_archive_round_trip(tmp_path, tower):
    model, system, result = tower
    path = archive.write(tmp_path / "a.h5", model, system, {"modes": result},
                         command=["cranefe", "modes", TOWER], timings=result.timings)
    arc = archive.read(path)
    assert arc.meta["format_version"] == archive.FORMAT_VERSION
    assert arc.model["yaml"] == model.text
    assert arc.model["node_names"] == model.node_names
    np.testing.assert_array_equal(arc.model["coords"], model.coords)
    assert (arc.K != system.K).nnz == 0 and (arc.M != system.M).nnz == 0
    np.testing.assert_array_equal(arc.f, system.f)
    assert arc.labels == system.dofs.labels
    back = arc.results["modes"]
    assert type(back) is type(result)
    for name in ("omega", "shapes", "node_shapes", "rigid"):
        np.testing.assert_array_equal(getattr(back, name), getattr(result, name))
    assert back.quasi_cyclic == result.quasi_cyclic and back.labels == result.labels
    assert back.effects == result.effects
    assert len(arc.mesh.lines) == len(arc.mesh.kind) == len(arc.mesh.element) > 0


def test_interrupted_write_keeps_the_previous_archive(tmp_path, tower, monkeypatch):
    model, system, result = tower
    path = tmp_path / "a.h5"
    archive.write(path, model, system, {"modes": result})
    before = path.read_bytes()

    def boom(*a, **k):
        raise KeyboardInterrupt("simulated crash")
    monkeypatch.setattr(archive, "_write_dataclass", boom)
    with pytest.raises(KeyboardInterrupt):
        archive.write(path, model, system, {"modes": result})
    assert path.read_bytes() == before
    assert os.listdir(tmp_path) == ["a.h5"]         # no temporary file left


def test_show_reads_any_archive(tmp_path, capsys):
    out = tmp_path / "h.h5"
    assert main(["modes", os.path.join(ROOT, "models", "two_mass_hoist.yaml"),
                 "--archive", str(out)]) == 0
    capsys.readouterr()
    assert main(["show", str(out), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["results"] == ["modes"] and doc["dofs"] == 3
    assert doc["meta"]["command"].startswith("cranefe modes")
    assert main(["show", str(tmp_path / "missing.h5")]) == 2


def test_vtu_and_xdmf_have_the_modes(tmp_path, tower):
    import meshio
    model, system, result = tower
    assert main(["modes", TOWER, "--vtu", str(tmp_path / "t.vtu"),
                 "--xdmf", str(tmp_path / "t.xdmf"), "--archive", str(tmp_path / "t.h5")]) == 0
    m = meshio.read(tmp_path / "t.vtu")
    names = [k for k in m.point_data if k.startswith("mode_")]
    assert len(names) == len(result.omega)
    np.testing.assert_allclose(m.points[:len(model.node_names)], model.coords)
    # point data are the node translations of each mode
    k = 4
    np.testing.assert_allclose(m.point_data[names[k]][:len(model.node_names)],
                               result.node_shapes[k], atol=1e-12)
    assert set(np.unique(m.cell_data["kind"][0])) == {0, 1}      # ropes and bodies
    with meshio.xdmf.TimeSeriesReader(str(tmp_path / "t.xdmf")) as r:
        r.read_points_cells()
        assert r.num_steps == len(result.omega)
        _, pd, _ = r.read_data(k)
    np.testing.assert_allclose(pd["displacement"][:len(model.node_names)],
                               result.node_shapes[k], atol=1e-12)
    # the XDMF data file does not overwrite the archive of the same base name
    assert archive.read(tmp_path / "t.h5").results["modes"].omega.size == result.omega.size


@pytest.mark.parametrize("path, size", [(TOWER, (640, 480)), (LUFFING, (400, 500))])
def test_images_are_rendered_off_screen(tmp_path, path, size):
    from PIL import Image
    assert main(["modes", path, "--count", "3", "--images", str(tmp_path),
                 "--image-size", f"{size[0]}x{size[1]}"]) == 0
    files = sorted(os.listdir(tmp_path))
    assert files == ["mode_01.png", "mode_02.png", "mode_03.png"]
    for f in files:
        img = np.asarray(Image.open(tmp_path / f).convert("RGB")).astype(int)
        assert img.shape == (size[1], size[0], 3)
        white = (img == 255).all(axis=2)
        assert 0.002 < 1 - white.mean() < 0.6               # a drawing, not blank
        spread = img.max(axis=2) - img.min(axis=2)
        grey = ~white & (spread < 8) & (img.mean(axis=2) > 60)   # undeformed (grey)
        coloured = spread > 40                                  # deformed (viridis)
        assert grey.sum() > 50 and coloured.sum() > 50


def test_animation_gif(tmp_path):
    from PIL import Image
    path = os.path.join(ROOT, "models", "two_mass_hoist.yaml")
    assert main(["modes", path, "--count", "2", "--images", str(tmp_path), "--animate",
                 "--image-size", "200x160"]) == 0
    with Image.open(tmp_path / "mode_02.gif") as gif:
        assert gif.n_frames > 10 and gif.size == (200, 160)


def test_animate_without_images_is_an_input_error(capsys):
    path = os.path.join(ROOT, "models", "two_mass_hoist.yaml")
    assert main(["modes", path, "--animate"]) == 2
    assert main(["modes", path, "--images", "x", "--image-size", "big"]) == 2
