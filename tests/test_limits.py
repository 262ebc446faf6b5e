"""What a file can ask for is bounded before anything is allocated (issue 15): a tackle
of a billion falls, a billion rope elements per fall, or millions of rope elements in
all are refused with the entry and the limit, exit status 2, no traceback."""

from pathlib import Path

import pytest

from cranefe.cli import main
from cranefe.model.load import MAX_FALLS, MAX_ROPE_ELEMENTS, MAX_ROPE_ELEMENTS_TOTAL

BASE = (Path(__file__).resolve().parents[1] / "models" / "two_mass_hoist.yaml").read_text()
CASES = {
    "falls": (BASE.replace("{node: H, falls: 2}", "{node: H, falls: 1000000000}"),
              "ropes.hoist_rope.path[2].falls", f"at most {MAX_FALLS:,}"),
    "rope_mass": (BASE.replace("cranefe: 1", "cranefe: 1\neffects: {rope_mass: 100000000}"),
                  "effects.rope_mass", f"at most {MAX_ROPE_ELEMENTS:,}"),
    "total": (BASE.replace("cranefe: 1", "cranefe: 1\neffects: {rope_mass: 5000}")
              .replace("{node: H, falls: 2}", "{node: H, falls: 500}"),
              "effects.rope_mass", f"limit of {MAX_ROPE_ELEMENTS_TOTAL:,}"),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_limits_refused(name, tmp_path, capsys):
    text, entry, says = CASES[name]
    f = tmp_path / "m.yaml"
    f.write_text(text)
    assert main(["modes", str(f)]) == 2
    err = capsys.readouterr().err
    assert entry in err and says in err and "Traceback" not in err


def test_scene_effects_are_bounded_too(tmp_path, capsys):
    """The total is checked with the effects a scene sets, naming the scene's entry."""
    (tmp_path / "m.yaml").write_text(BASE.replace("{node: H, falls: 2}",
                                                  "{node: H, falls: 500}"))
    scene = tmp_path / "s.yaml"
    scene.write_text("cranefe: 1\nscene: s\nmodel: m.yaml\neffects: {rope_mass: 5000}\n")
    assert main(["modes", str(scene)]) == 2
    err = capsys.readouterr().err
    assert "s.yaml" in err and "effects.rope_mass" in err


SWEEP = """cranefe: 1
sweep: too big
base: m.yaml
parameters:
{params}
outputs: [frequency_hz.1]
output: t.h5
"""


@pytest.mark.parametrize("params,says", [
    ("  masses.H: {range: [1000, 2000], count: 1000000000}", "parameters.masses.H.count"),
    ("  masses.H: {range: [1000, 2000], count: 100000}\n"
     "  ropes.hoist_rope.EA: {range: [1.0e7, 2.0e7], count: 100000}", "10,000,000,000"),
])
def test_sweep_size_is_bounded_before_the_grid_is_made(params, says, tmp_path, capsys):
    """A sweep of count 1e9 or a 1e5 x 1e5 grid is refused at once (issue 15)."""
    (tmp_path / "m.yaml").write_text(BASE)
    spec = tmp_path / "s.yaml"
    spec.write_text(SWEEP.format(params=params))
    assert main(["sweep", str(spec), "--workers", "0"]) == 2
    err = capsys.readouterr().err
    assert says in err and "Traceback" not in err
