"""Pictures (issue 18): the ground and what stands on it, an axes triad, the frequency in
the title, one camera for every mode of a model, the direction of view, animations that
move the scene in place (GIF, MP4). Pixels are checked where the projection of the
scene's own points says a thing must be drawn."""

import os

import numpy as np
import pytest

from cranefe.analysis.modal import modes
from cranefe.cli import main
from cranefe.errors import ModelError
from cranefe.model import load
from cranefe.outputs import render
from cranefe.system import assemble

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HOIST = os.path.join(ROOT, "models", "two_mass_hoist.yaml")
TOWER = os.path.join(ROOT, "models", "hammerhead_tower_crane.yaml")
SIZE = (400, 300)


def solved(path, count=None):
    model = load(path)
    system = assemble(model)
    return model, system, modes(model, count=count, system=system)


@pytest.fixture(scope="module")
def hoist():
    model, system, result = solved(HOIST)
    scene = render.ModeScene(model, system.dofs, result, size=SIZE)
    yield model, result, scene
    scene.close()


def background(img, rc, radius=1):
    r, c = rc
    patch = img[max(r - radius, 0):r + radius + 1, max(c - radius, 0):c + radius + 1, :3]
    return bool((patch.reshape(-1, 3) == render.BACKGROUND).all(axis=1).all())


def test_ground_drum_and_support_are_drawn_where_they_stand(hoist):
    """The two-mass hoist (view xz): the head sheave S stands on the ground at 24 m, the
    winch drum W at 1 m. Below the lowest the hook reaches (8 m - 12 % of 23 m), only
    the post from S to the floor is at x = 0; the drum is drawn at W; a point far from
    every element is background."""
    model, result, scene = hoist
    scene.show(len(result.omega) - 1)
    img = scene.image()
    S, W = (model.coords[model.node_names.index(n)] for n in ("S", "W"))
    post = scene.pixels([[S[0], 0.0, 3.0], [S[0], 0.0, 4.5]])
    drum = scene.pixels([W])[0]
    empty = scene.pixels([[-9.0, 0.0, 20.0]])[0]
    for rc in post:
        assert not background(img, rc)
        assert np.abs(img[rc[0], rc[1], :3].astype(int) - _rgb(render.GROUND_COLOUR)).max() < 40
    assert not background(img, drum, radius=0)
    assert background(img, empty, radius=3)


def _rgb(hex_colour):
    return np.array([int(hex_colour[k:k + 2], 16) for k in (1, 3, 5)])


def test_axes_triad_is_drawn_in_its_corner(hoist):
    """The triad's x axis (red) and z axis (blue) are drawn in the lower left corner
    and nowhere else has their colours (viridis, greys and browns have no such red)."""
    model, result, scene = hoist
    scene.show(1)
    img = scene.image()[:, :, :3].astype(int)
    h, w = img.shape[:2]
    red = (img[:, :, 0] > 200) & (img[:, :, 1] < 150) & (img[:, :, 2] < 130)
    blue = (img[:, :, 2] > 150) & (img[:, :, 0] < 80) & (img[:, :, 1] < 80)
    corner = np.zeros_like(red)
    corner[int(h * (1 - 0.22)):, :int(w * 0.18)] = True
    assert (red & corner).sum() > 10 and (blue & corner).sum() > 10
    assert (red & ~corner).sum() == 0


def test_title_has_the_frequency_and_the_bar_is_relative(hoist):
    model, result, scene = hoist
    f = result.omega[2] / (2 * np.pi)
    assert f"mode 3: {f:.4g} Hz" in scene.title_text(2)
    assert "rigid" in scene.title_text(0)
    assert render.BAR_TITLE == "relative displacement"
    np.testing.assert_allclose(scene.relative.max(axis=1)[result.omega > 0], 1.0)


def test_all_modes_share_one_camera(tmp_path):
    """Every PNG of the tower crane is seen by one camera: its parameters are the same
    for every mode, and the pixels around a corner of the floor (which no mode moves;
    floor and background meet there, so a shifted view changes them) are the same in
    every image."""
    from PIL import Image
    model, system, result = solved(TOWER, count=4)
    scene = render.ModeScene(model, system.dofs, result, size=SIZE)
    cams = []
    for k in range(4):
        scene.show(k)
        cam = scene.p.camera
        cams.append(np.r_[cam.position, cam.focal_point, cam.up, cam.parallel_scale])
    corners = scene.pixels(scene.floor_corners)
    base = corners[np.argmin(corners[:, 1])]                  # the leftmost corner
    scene.close()
    assert all(np.array_equal(c, cams[0]) for c in cams)
    paths = render.render_modes(tmp_path, model, system.dofs, result, size=SIZE)
    imgs = [np.asarray(Image.open(p).convert("RGB")) for p in paths]
    r, c = base
    window = [img[r - 6:r + 7, c - 6:c + 7] for img in imgs]
    assert not background(imgs[0], base, radius=6) and background(imgs[0], base + (0, -8))
    assert all(np.array_equal(window[0], x) for x in window[1:])


@pytest.mark.parametrize("view, right, up", [("xz", 0, 2), ("xy", 0, 1), ("yz", 1, 2)])
def test_view_directions(view, right, up):
    """In view xz the x axis runs to the right and z up; xy: x right, y up; yz: y right
    (seen from +x), z up."""
    model, system, result = solved(TOWER, count=1)
    scene = render.ModeScene(model, system.dofs, result, size=SIZE, view=view)
    try:
        o = np.zeros(3)
        e_r, e_u = np.eye(3)[right] * 10, np.eye(3)[up] * 10
        (r0, c0), (r1, c1), (r2, c2) = scene.pixels([o, e_r, e_u])
        assert c1 > c0 + 5 and abs(r1 - r0) <= 1       # right
        assert r2 < r0 - 5 and abs(c2 - c0) <= 1       # up
    finally:
        scene.close()
    with pytest.raises(ModelError, match="--view"):
        render.ModeScene(model, system.dofs, result, size=SIZE, view="top")


def test_view_option_of_the_cli(tmp_path, capsys):
    assert main(["modes", HOIST, "--images", str(tmp_path), "--view", "xy",
                 "--image-size", "120x90", "--count", "1"]) == 0
    with pytest.raises(SystemExit) as exit_:          # argparse: usage, status 2
        main(["modes", HOIST, "--images", str(tmp_path), "--view", "up"])
    assert exit_.value.code == 2
    assert "--view" in capsys.readouterr().err


def test_animation_moves_the_crane_under_one_camera(tmp_path, hoist):
    """A GIF of mode 3: frames differ (the crane moves), the drum at W (ground) stays."""
    from PIL import Image, ImageSequence
    model, result, scene = hoist
    frames = []
    for phase in np.sin(np.linspace(0, 2 * np.pi, 8, endpoint=False)):
        scene.show(2, phase)
        frames.append(scene.image())
    path = render.write_animation(str(tmp_path / "m.gif"), frames, fps=8)
    with Image.open(path) as gif:
        back = [np.asarray(f.convert("RGB")) for f in ImageSequence.Iterator(gif)]
    assert len(back) == 8 and back[0].shape == (SIZE[1], SIZE[0], 3)
    assert not np.array_equal(back[0], back[2])
    W = model.coords[model.node_names.index("W")]
    r, c = scene.pixels([W])[0]
    assert all(np.array_equal(back[0][r - 3:r + 4, c - 3:c + 4], b[r - 3:r + 4, c - 3:c + 4])
               for b in back)


def test_mp4(tmp_path, hoist):
    pytest.importorskip("imageio_ffmpeg")
    import imageio.v2 as imageio
    model, result, scene = hoist
    frames = []
    for phase in np.linspace(-1, 1, 6):
        scene.show(2, phase)
        frames.append(scene.image())
    path = render.write_animation(str(tmp_path / "m.mp4"), frames, fps=6)
    reader = imageio.get_reader(path, format="FFMPEG")
    n = sum(1 for _ in reader)
    reader.close()
    assert n == 6


def test_mp4_without_imageio_ffmpeg_says_what_to_install(tmp_path, monkeypatch):
    import sys
    monkeypatch.setitem(sys.modules, "imageio_ffmpeg", None)
    with pytest.raises(ModelError, match="imageio-ffmpeg"):
        render.write_animation(str(tmp_path / "m.mp4"), [np.zeros((16, 16, 3), np.uint8)])
    with pytest.raises(ModelError, match=r"\.gif or \.mp4"):
        render.write_animation(str(tmp_path / "m.avi"), [np.zeros((16, 16, 3), np.uint8)])
