"""Transient CSVs and plots include the rigid bodies (issue 18): each body's centre of
mass displacement and rotation, checked against the rigid-body motion of a node the
body carries (u_node = u_c + theta x (x_node - c), linearised)."""

import csv
import os

import numpy as np
import pytest

from cranefe.cli import main
from cranefe.model import load

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "models", "scenes", "hammerhead_lift_off.yaml")


@pytest.fixture(scope="module")
def histories(tmp_path_factory):
    d = tmp_path_factory.mktemp("h")
    assert main(["simulate", SCENE, "--csv", str(d / "h.csv"), "--plots", str(d / "p")]) == 0
    with open(d / "h.csv", newline="") as fh:
        rows = list(csv.reader(fh))
    cols = {name: np.array([float(r[k]) for r in rows[1:]]) for k, name in
            enumerate(rows[0])}
    return d, rows[0], cols


def test_body_columns_follow_the_point_masses(histories):
    """The trolley mass K rides on the jib, the counterweight CW on the counter-jib: their
    displacements (from the transient's own columns) are the rigid motion of the body's
    centre of mass and rotation (the new columns), to round-off."""
    _, header, cols = histories
    model = load(SCENE)
    for body, node in (("jib", "K"), ("counter_jib", "CW")):
        for a in "xyz":
            assert f"body_{body}_u{a}_m" in header and f"body_{body}_r{a}_rad" in header
        b = next(x for x in model.bodies if x.name == body)
        arm = model.coords[model.node_index[node]] - np.asarray(b.com)
        uc = np.stack([cols[f"body_{body}_u{a}_m"] for a in "xyz"], axis=1)
        th = np.stack([cols[f"body_{body}_r{a}_rad"] for a in "xyz"], axis=1)
        un = np.stack([cols[f"{node}_u{a}_m"] for a in "xyz"], axis=1)
        expected = uc + np.cross(th, arm)
        scale = np.abs(un).max()
        assert scale > 1e-6                              # the crane does move
        # 9 significant digits in the CSV
        np.testing.assert_allclose(un, expected, atol=1e-8 * scale + 1e-12)
    assert np.abs(cols["body_tower_ry_rad"]).max() > 0


def test_bodies_are_plotted(histories):
    d, _, _ = histories
    assert sorted(os.listdir(d / "p")) == ["transient.png", "transient_bodies.png"]


def test_operation_csv_has_the_bodies(tmp_path):
    """The overhead crane's trolley runs on a slider along x: its centre of mass moves
    by the drive's position along x and does not turn; the drive column of the same CSV
    is the reference."""
    import re
    ops = os.path.join(ROOT, "models", "operations")
    text = open(os.path.join(ops, "overhead_crane_estop.yaml")).read()
    text = text.replace("model: overhead_crane.yaml",
                        "model: " + os.path.join(ops, "overhead_crane.yaml"))
    text = re.sub(r"duration: \d+", "duration: 3", text).replace("output_step: 0.02",
                                                                 "output_step: 0.1")
    scene = tmp_path / "estop.yaml"
    scene.write_text(text)
    out = tmp_path / "op.csv"
    assert main(["simulate", str(scene), "--csv", str(out)]) == 0
    with open(out, newline="") as fh:
        rows = list(csv.reader(fh))
    cols = {n: np.array([float(r[k]) for r in rows[1:]]) for k, n in enumerate(rows[0])}
    model = load(str(scene))
    com = np.asarray(model.bodies[0].com)
    s = cols["trolley.position"] - cols["trolley.position"][0]
    assert s[-1] > 1.0
    np.testing.assert_allclose(cols["body_trolley.x_m"], com[0] + s, atol=1e-8)
    np.testing.assert_allclose(cols["body_trolley.z_m"], com[2], atol=1e-12)
    for a in "xyz":
        np.testing.assert_allclose(cols[f"body_trolley.r{a}_rad"], 0.0, atol=1e-12)
