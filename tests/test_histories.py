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
