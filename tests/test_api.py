"""The Python API returns what the command line prints (issue 14): for each command,
`result.to_dict()` equals the `--json` document, timings aside."""

import pytest

import cranefe
from cranefe.errors import ModelError
from test_golden_json import ROOT, compare, run

CASES = [
    ("modes", lambda: cranefe.modes("models/two_mass_hoist.yaml"),
     ["modes", "models/two_mass_hoist.yaml"]),
    ("modes-count", lambda: cranefe.modes("models/hammerhead_tower_crane.yaml", count=5),
     ["modes", "models/hammerhead_tower_crane.yaml", "--count", "5"]),
    ("damping", lambda: cranefe.damping("models/luffing_tower_crane.yaml", method="both"),
     ["damping", "models/luffing_tower_crane.yaml", "--method", "both"]),
    ("simulate", lambda: cranefe.simulate("models/two_mass_hoist_lift.yaml"),
     ["simulate", "models/two_mass_hoist_lift.yaml"]),
    ("simulate-operation",
     lambda: cranefe.simulate("models/operations/overhead_crane_estop.yaml"),
     ["simulate", "models/operations/overhead_crane_estop.yaml"]),
    ("luff", lambda: cranefe.luff("models/portal_crane_luffing_scene.yaml",
                                  sensitivity=False),
     ["luff", "models/portal_crane_luffing_scene.yaml", "--no-sensitivity"]),
]


@pytest.mark.parametrize("name,call,args", CASES, ids=[c[0] for c in CASES])
def test_to_dict_is_the_json_document(name, call, args, monkeypatch):
    monkeypatch.chdir(ROOT)
    diffs = list(compare(run(args), call().to_dict()))
    assert not diffs, "\n".join(diffs[:20])


def test_effects_override_and_model_objects(monkeypatch):
    """A Model or a path; `effects` changes the physics: without sway the hoist has no
    pendulum, so one mode fewer."""
    monkeypatch.chdir(ROOT)
    model = cranefe.load("models/two_mass_hoist.yaml")
    assert len(cranefe.modes(model).omega) == len(
        cranefe.modes(model, effects={"sway": False}).omega) + 1


def test_bad_input_raises_model_error(monkeypatch):
    monkeypatch.chdir(ROOT)
    with pytest.raises(ModelError, match="not found"):
        cranefe.load("models/no_such_model.yaml")


def test_import_stays_light():
    """`import cranefe` loads no analysis until a function is used."""
    import subprocess
    import sys
    code = ("import sys, cranefe; print(any(m.startswith('cranefe.analysis') or "
            "m == 'scipy' for m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT).stdout.strip()
    assert out == "False"
