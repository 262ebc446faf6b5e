"""`cranefe simulate SCENE --animate OUT.gif|OUT.mp4` (issue 18): the crane of an
operation run moving, bodies moved by their joints, loads from the samples, trails."""

import os
import re

import numpy as np
import pytest

from cranefe import api
from cranefe.cli import main
from cranefe.outputs import movie

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OPS = os.path.join(ROOT, "models", "operations")


def estop(folder, duration=3.0):
    """The overhead crane's emergency stop (models/operations), shortened, sampled
    every 0.1 s."""
    text = open(os.path.join(OPS, "overhead_crane_estop.yaml")).read()
    text = text.replace("model: overhead_crane.yaml",
                        "model: " + os.path.join(OPS, "overhead_crane.yaml"))
    text = re.sub(r"duration: \d+", f"duration: {duration}", text)
    text = text.replace("output_step: 0.02", "output_step: 0.1")
    path = os.path.join(folder, "estop.yaml")
    with open(path, "w") as fh:
        fh.write(text)
    return path


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    scene = estop(str(tmp_path_factory.mktemp("op")))
    model = api.load(scene)
    return scene, model, api.simulate(model)


def test_bodies_follow_their_joints_and_loads_their_samples(run):
    """The trolley (a body on the slider 'trolley_travel', axis x) and its nodes move by
    the drive's position along x, exactly; the hook is where the run sampled it."""
    scene, model, result = run
    idx, P = movie.operation_positions(model, result, frames=20)
    assert len(idx) == 20 and idx[0] == 0 and idx[-1] == len(result.times) - 1
    s = result.drive_position[idx, 0] - result.drive_position[0, 0]
    assert s[-1] > 0.1                                   # the trolley did move
    nn = len(model.node_names)
    for name in ("G", "D"):
        i = model.node_index[name]
        np.testing.assert_allclose(P[:, i] - model.coords[i], s[:, None] * [1, 0, 0],
                                   atol=1e-12)
    np.testing.assert_allclose(P[:, nn] - model.bodies[0].com, s[:, None] * [1, 0, 0],
                               atol=1e-12)                   # the trolley's com
    k = result.mass_names.index("HOOK")
    np.testing.assert_array_equal(P[:, model.node_index["HOOK"]],
                                  result.mass_position[idx, k])


def test_the_trail_grows_and_the_camera_stays(run):
    scene, model, result = run
    sc = movie.OperationScene(model, result, size=(240, 180), frames=12)
    try:
        orange = []
        cams = []
        for f in (0, len(sc.index) - 1):
            sc.show(f)
            img = sc.image()[:, :, :3].astype(int)
            orange.append(((img[:, :, 0] > 200) & (img[:, :, 1] > 90) & (img[:, :, 1] < 160)
                           & (img[:, :, 2] < 60)).sum())
            cam = sc.p.camera
            cams.append(np.r_[cam.position, cam.focal_point, cam.parallel_scale])
        assert sc.trail_nodes == [model.node_index["HOOK"]]
        assert orange[1] > orange[0] + 5
        assert np.array_equal(cams[0], cams[1])
    finally:
        sc.close()


def test_simulate_animate_writes_a_gif(run, tmp_path, capsys):
    from PIL import Image
    scene, model, result = run
    out = tmp_path / "estop.gif"
    assert main(["simulate", scene, "--animate", str(out), "--image-size", "160x120",
                 "--view", "xz"]) == 0
    with Image.open(out) as gif:
        assert gif.n_frames == min(len(result.times), movie.MAX_FRAMES)
        assert gif.size == (160, 120)


def test_animate_refuses_other_files_and_transient_scenes(tmp_path, capsys, run):
    scene = run[0]
    assert main(["simulate", scene, "--animate", str(tmp_path / "x.avi")]) == 2
    assert ".gif or .mp4" in capsys.readouterr().err
    transient = os.path.join(ROOT, "models", "two_mass_hoist_start.yaml")
    assert main(["simulate", transient, "--animate", str(tmp_path / "x.gif")]) == 2
    assert "operation scenes" in capsys.readouterr().err


def test_mp4_without_imageio_ffmpeg_is_refused_before_the_run(tmp_path, capsys,
                                                                 monkeypatch, run):
    import sys
    monkeypatch.setitem(sys.modules, "imageio_ffmpeg", None)
    assert main(["simulate", run[0], "--animate", str(tmp_path / "x.mp4")]) == 2
    assert "imageio-ffmpeg" in capsys.readouterr().err
    assert main(["modes", os.path.join(ROOT, "models", "two_mass_hoist.yaml"), "--images",
                 str(tmp_path / "i"), "--animate", "mp4"]) == 2
    assert "imageio-ffmpeg" in capsys.readouterr().err
    assert not os.path.exists(tmp_path / "i")
