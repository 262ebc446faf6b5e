"""Every example in models/ is loaded and solved, with one pinned figure each."""

import glob
import json
import os

import numpy as np
import pytest

from cranefe.cli import main
from cranefe.model import load
from cranefe.analysis.modal import modes

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = sorted(glob.glob(os.path.join(ROOT, "models", "*.yaml")))

# First elastic frequency (Hz), pinned from this version; the models' headers derive
# them by hand to 2-3 digits. Pinned to 1e-6: a change means the physics changed.
PINNED = {
    "two_mass_hoist.yaml": 0.12462198,
    "two_mass_hoist_scene.yaml": 2.44806889,
    "hammerhead_tower_crane.yaml": 0.09057813,
    "luffing_tower_crane.yaml": 0.07883838,
    "logging_skyline.yaml": 0.19440453,
    "lattice_tower_crane.yaml": 0.22051153,
    "two_mass_hoist_start.yaml": 2.44806889,
    "two_mass_hoist_lift.yaml": 2.44806889,
    "portal_crane_luffing.yaml": 0.12870903,
    "portal_crane_luffing_scene.yaml": 0.12870903,
}


def test_every_example_is_pinned():
    assert sorted(PINNED) == sorted(os.path.basename(m) for m in MODELS)


@pytest.mark.parametrize("path", MODELS, ids=os.path.basename)
def test_example_modes(path, capsys):
    assert main(["modes", path, "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    first = next(m["frequency_hz"] for m in doc["modes"] if not m["rigid"])
    assert first == pytest.approx(PINNED[os.path.basename(path)], rel=1e-6)
    assert doc["warnings"] == []
    assert main(["check", path]) == 0


@pytest.mark.parametrize("path", MODELS, ids=os.path.basename)
def test_dense_and_sparse_solvers_agree(path):
    model = load(path)
    dense = modes(model)
    k = min(6, len(dense.omega) - 1)
    sparse = modes(model, solver="sparse", count=k)
    # both solve the same pencil; shift-invert Lanczos converges to ~1e-10 relative
    assert sparse.omega == pytest.approx(dense.omega[:k], rel=1e-9, abs=1e-9)
    assert sparse.rigid.tolist() == dense.rigid[:k].tolist()


@pytest.mark.parametrize("path", [m for m in MODELS if "type: transient" in open(m).read()],
                         ids=os.path.basename)
def test_transient_examples(path, capsys):
    assert main(["simulate", path, "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert 1.0 < doc["dynamic_factor"][next(iter(doc["dynamic_factor"]))] < 2.0


def test_sparse_solver_asked_for_every_mode_solves_densely():
    # ARPACK finds k < n modes only; it once returned 2 of the hoist's 3 without a word
    model = load(os.path.join(ROOT, "models", "two_mass_hoist.yaml"))
    dense, sparse = modes(model), modes(model, solver="sparse", count=8)
    assert len(sparse.omega) == len(dense.omega) == 3
    np.testing.assert_array_equal(sparse.omega, dense.omega)
    assert any("solved densely" in w for w in sparse.warnings)
