"""Sweep values with units (issue 18): a parameter's values and range read by the model
files' units machinery in the SI unit of the entry they set; a rope speed for a drum's
speed by the drum's radius; a wrong dimension names the sweep entry."""

import os
import shutil

import numpy as np
import pytest

from cranefe.errors import ModelError
from cranefe.sweeps.spec import load_sweep

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def sweep(tmp_path, parameters, base="two_mass_hoist_lift.yaml"):
    for f in ("two_mass_hoist.yaml", base):
        shutil.copy(os.path.join(ROOT, "models", f), tmp_path / f)
    path = tmp_path / "s.yaml"
    path.write_text(f"cranefe: 1\nbase: {base}\nparameters:\n{parameters}"
                    "outputs: [phi2.hoist_rope]\n")
    return load_sweep(path)


def test_values_and_ranges_with_units_are_si(tmp_path):
    s = sweep(tmp_path, "  ropes.hoist_rope.EA: {values: ['100 MN', 2.0e8]}\n"
                        "  masses.H: {range: ['1 t', '5 t'], count: 3}\n"
                        "  analysis.drums.hoist.speed: {values: ['30 m/min', '1 rad/s']}\n")
    ea, mass, speed = (s.parameters[k] for k in range(3))
    assert ea.values == (1.0e8, 2.0e8)
    assert (mass.low, mass.high) == (1000.0, 5000.0)
    # 30 m/min = 0.5 m/s of rope on a drum of radius 0.25 m: 2 rad/s
    assert speed.values == pytest.approx((2.0, 1.0), rel=1e-15)
    assert s.variants.shape == (2 * 3 * 2, 3)
    np.testing.assert_allclose(np.unique(s.variants[:, 1]), [1000, 3000, 5000])


def test_a_value_of_the_wrong_dimension_names_the_sweep_entry(tmp_path):
    with pytest.raises(ModelError) as err:
        sweep(tmp_path, "  ropes.hoist_rope.EA: {values: ['5 m']}\n")
    assert err.value.entry == "parameters.ropes.hoist_rope.EA.values[0]"
    assert "a length" in err.value.message and "EA" in err.value.message
    with pytest.raises(ModelError, match="plain number"):
        sweep(tmp_path, "  ropes.hoist_rope.psi: {values: ['5 m']}\n")


def test_a_base_value_written_with_units_can_be_swept(tmp_path):
    base = tmp_path / "m.yaml"
    text = open(os.path.join(ROOT, "models", "two_mass_hoist.yaml")).read()
    base.write_text(text.replace("EA: ", "EA: '1.0e8 N' #", 1))
    (tmp_path / "s.yaml").write_text("cranefe: 1\nbase: m.yaml\nparameters:\n"
                                     "  ropes.hoist_rope.EA: {values: ['50 MN']}\n"
                                     "outputs: [frequency_hz.1]\n")
    assert load_sweep(tmp_path / "s.yaml").parameters[0].values == (5.0e7,)
