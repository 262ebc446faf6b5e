"""The JSON documents of every example are unchanged by refactoring (issue 14).

tests/data/golden/*.json were written by the commands in `CASES` before the package was
reorganised into pipeline stages; numbers must agree to 1e-12 relative. Timings and
anything that measures the machine are left out. Regenerate only for a deliberate change
of results, with `python tests/test_golden_json.py --write`, and say why in the commit.
"""

import io
import json
import math
import sys
from contextlib import redirect_stdout
from pathlib import Path

import pytest

from cranefe.cli import main

ROOT = Path(__file__).resolve().parents[1]
GOLDEN = ROOT / "tests" / "data" / "golden"
MODELS = ("two_mass_hoist", "hammerhead_tower_crane", "lattice_tower_crane",
          "logging_skyline", "luffing_tower_crane", "portal_crane_luffing",
          "two_mass_hoist_scene")
SCENES = ("two_mass_hoist_lift", "two_mass_hoist_start", "scenes/hammerhead_lift_off",
          "scenes/luffing_lift_off", "scenes/two_mass_hoist_motor_start",
          "scenes/two_mass_hoist_slack", "scenes/two_mass_hoist_start_modal")


def _count(m):
    return ["--count", "12"] if m == "lattice_tower_crane" else []


CASES = {
    **{f"modes.{m}": ["modes", f"models/{m}.yaml", *_count(m)] for m in MODELS},
    **{f"damping.{m}": ["damping", f"models/{m}.yaml", "--method", "both", *_count(m)]
       for m in MODELS},
    **{f"simulate.{Path(s).name}": ["simulate", f"models/{s}.yaml"] for s in SCENES},
    "luff.portal_crane_luffing_scene": ["luff", "models/portal_crane_luffing_scene.yaml"],
    "check.hammerhead": ["check", "models/hammerhead_tower_crane.yaml"],
}
IGNORED = {"timings_s", "timings", "time_s", "wall_s"}
RTOL = 1e-12     # issue 14: the same numbers, up to the last bits of reordered sums


def run(args, monkeypatch=None):
    buf = io.StringIO()
    with redirect_stdout(buf):
        code = main([*args, "--json"])
    assert code == 0, (args, code)
    return json.loads(buf.getvalue())


def compare(a, b, path="$"):
    """Yield the paths where a and b differ (numbers beyond RTOL)."""
    if isinstance(a, dict) and isinstance(b, dict):
        keys = (set(a) | set(b)) - IGNORED
        for k in sorted(keys):
            if k not in a or k not in b:
                yield f"{path}.{k}: present in only one"
            else:
                yield from compare(a[k], b[k], f"{path}.{k}")
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            yield f"{path}: lengths {len(a)} != {len(b)}"
        for i, (x, y) in enumerate(zip(a, b)):
            yield from compare(x, y, f"{path}[{i}]")
    elif isinstance(a, (int, float)) and isinstance(b, (int, float)) \
            and not isinstance(a, bool):
        if not (math.isclose(a, b, rel_tol=RTOL, abs_tol=1e-300)
                or (math.isnan(a) and math.isnan(b))):
            yield f"{path}: {a!r} != {b!r}"
    elif a != b:
        yield f"{path}: {a!r} != {b!r}"


@pytest.mark.parametrize("name", sorted(CASES))
def test_json_unchanged(name, monkeypatch):
    monkeypatch.chdir(ROOT)
    expected = json.loads((GOLDEN / f"{name}.json").read_text())
    got = run(CASES[name])
    diffs = list(compare(expected, got))
    assert not diffs, "\n".join(diffs[:20])


if __name__ == "__main__" and "--write" in sys.argv:
    import os
    os.chdir(ROOT)
    for name, args in CASES.items():
        (GOLDEN / f"{name}.json").write_text(json.dumps(run(args), indent=1) + "\n")
