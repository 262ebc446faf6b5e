"""Kill tests for cranefe/analysis/shaping/engine.py (tools/mutation.py shaping_engine;
docs/testing.md, "Mutation testing"; docs/shaping.md): the scene edits (a drive's
moves passed through an edit, shaped, stripped, the duration lengthened by what the
shaper adds), the summary of an engine result and the document of `compare` - without
the engine: `compare`'s call of the operation engine is replaced here by a stand-in
that returns what it was given (the scene's duration, the drive's motion end), so that
the document's every field is checked against hand values in a fraction of a second.
The engine's own residuals are tests/test_shaping_engine.py's (about 30 s).

Hand values on the overhead crane (models/operations/overhead_crane.yaml): the trolley
move 1 m at 0.5 m/s, 0.5 m/s^2 from t = 1 s takes 3 s (t_a = t_c = 1 s); a ZV shaper at
f Hz adds half a period 1 / (2 f) (damped: 1 / (2 f sqrt(1 - zeta^2))); the pendulum is
sqrt(g / 6 m) (tests/test_mutation_kills_shaped.py derives it).

Tolerances: sums of a few O(1) times: 1e-12; the crane's frequency (Newton's static
state to 1e-10): 1e-9 relative.
"""

from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from cranefe.analysis.operation import integrate, profiles
from cranefe.analysis.operation.scene import parse
from cranefe.analysis.shaping import engine as en
from cranefe.errors import ModelError
from cranefe.model import load

G = 9.81
ROOT = Path(__file__).resolve().parents[1] / "models" / "operations"
OVERHEAD = ROOT / "overhead_crane.yaml"
TOWER = ROOT / "tower_crane.yaml"
W_OH = np.sqrt(G / 6.0)
TOL = 1e-12


def scene(tmp_path, drives, duration=30, model=OVERHEAD, name="s.yaml"):
    path = tmp_path / name
    path.write_text(f"cranefe: 1\nscene: engine kill test\nmodel: {model}\n"
                    f"analysis:\n  type: operation\n  duration: {duration}\n  drives:\n{drives}")
    return load(path)


TROLLEY = ("    trolley: {slider: trolley_travel, profile: {type: trapezoid, distance: 1, "
           "v_max: 0.5, a_max: 0.5, start: 1%s}}\n")
HOIST = "    hoist: {drum: hoist, torque: 0}\n"
TWO = ("    trolley:\n      slider: trolley_travel\n      profile:\n"
       "        - {type: trapezoid, distance: 1, v_max: 0.5, a_max: 0.5, start: 1}\n"
       "        - {type: trapezoid, distance: -1, v_max: 0.5, a_max: 0.5, start: 10, "
       "shaper: {type: ZVD, frequency: 1}}\n")


def drive(m, name="trolley"):
    return next(d for d in parse(m).drives if d.name == name)


# ------------------------------------------------------------------ scene edits

def test_with_profiles_edits_each_move_of_a_copy(tmp_path):
    m = scene(tmp_path, TWO + HOIST)
    seen = []

    def edit(p, k):
        seen.append((k, dict(p)))
        p["start"] = float(p["start"]) + 0.5
        return p
    out = en.with_profiles(m, "trolley", edit, extend=2.5)
    assert [k for k, _ in seen] == [0, 1] and seen[1][1]["distance"] == -1
    prof = out.analysis["drives"]["trolley"]["profile"]
    assert isinstance(prof, list) and [p["start"] for p in prof] == [1.5, 10.5]
    assert out.analysis["duration"] == 32.5
    # the input model is untouched (a deep copy) and the rest of the scene is kept
    assert [p["start"] for p in m.analysis["drives"]["trolley"]["profile"]] == [1, 10]
    assert m.analysis["duration"] == 30
    assert out.analysis["drives"]["hoist"] == {"drum": "hoist", "torque": 0}
    assert out.analysis["type"] == "operation" and out.file == m.file
    # one move stays one move (a mapping), and no extension leaves the duration
    m1 = scene(tmp_path, TROLLEY % "")
    out = en.with_profiles(m1, "trolley", lambda p, k: {**p, "k": k})
    assert out.analysis["drives"]["trolley"]["profile"]["k"] == 0
    assert out.analysis["duration"] == 30


def test_with_profiles_refuses_a_drive_without_a_profile(tmp_path):
    m = scene(tmp_path, TROLLEY % "" + HOIST)
    for name in ("hoist", "crab"):
        with pytest.raises(ModelError) as e:
            en.with_profiles(m, name, lambda p, k: p)
        assert e.value.message == (f"no drive '{name}' with a profile in the scene "
                                   "(drives: trolley, hoist)")
        assert e.value.entry == "analysis.drives" and e.value.file == m.scene_file
    m.analysis["drives"] = {}
    with pytest.raises(ModelError) as e:
        en.with_profiles(m, "trolley", lambda p, k: p)
    assert e.value.message.endswith("(drives: none)")
    m.analysis["drives"] = {"trolley": None}
    with pytest.raises(ModelError, match="no drive 'trolley' with a profile"):
        en.with_profiles(m, "trolley", lambda p, k: p)


def test_shaped_model(tmp_path):
    """ZV at 0.25 Hz adds 2 s: the scene's duration grows by 2 s; unshaped (None) strips
    every shaper and keeps the duration; extend=False keeps it too."""
    m = scene(tmp_path, TWO)
    spec = {"type": "ZV", "frequency": 0.25}
    out = en.shaped_model(m, "trolley", spec)
    prof = out.analysis["drives"]["trolley"]["profile"]
    assert all(p["shaper"] == spec for p in prof) and prof[0]["shaper"] is not spec
    # the second move had ZVD at 1 Hz; both now ZV at 0.25 Hz: the end 13 s (stripped)
    # -> 15 s
    assert out.analysis["duration"] == pytest.approx(32.0, abs=TOL)
    assert drive(out).motion.t[-1] == pytest.approx(15.0, abs=TOL)
    # a shaper that adds less than a second: ZV at 1 Hz, 0.5 s
    out = en.shaped_model(m, "trolley", {"type": "ZV", "frequency": 1.0})
    assert out.analysis["duration"] == pytest.approx(30.5, abs=TOL)
    out = en.shaped_model(m, "trolley", None)
    assert all("shaper" not in p for p in out.analysis["drives"]["trolley"]["profile"])
    assert out.analysis["duration"] == 30
    out = en.shaped_model(m, "trolley", spec, extend=False)
    assert out.analysis["duration"] == 30 and "shaper" in \
        out.analysis["drives"]["trolley"]["profile"][0]
    # with the frequency auto (the pendulum, 6 m): half its period added
    out = en.shaped_model(scene(tmp_path, TROLLEY % ""), "trolley", {"type": "ZV"})
    assert out.analysis["duration"] == pytest.approx(30 + np.pi / W_OH, rel=1e-9)
    assert en._strip({"a": 1, "shaper": 2}, 0) == {"a": 1}
    assert en._strip({"a": 1}, 3) == {"a": 1}
    assert en._moves([1, 2]) == [1, 2] and en._moves({"a": 1}) == [{"a": 1}]


# ------------------------------------------------------------------ summary

def _res(resid, maxd, names=("HOOK", "LOAD"), end=7.5):
    return SimpleNamespace(sway_residual_deg=np.array(resid, float),
                           sway_max_deg=np.array(maxd, float), sway_names=names,
                           motion_end=end)


def test_summary_by_hand():
    mv = profiles.combine([profiles.trapezoid(1.0, 0.5, 0.5, start=1.0),
                           profiles.trapezoid(-2.0, 0.5, 0.5, start=6.0)])   # 1-4, 6-11
    s = en.summary(_res([0.3, np.nan], [np.nan, 2.5]), mv)
    assert s == {"residual_sway_deg": 0.3,
                 "residual_sway_deg_by_node": {"HOOK": 0.3, "LOAD": pytest.approx(np.nan,
                                                                                   nan_ok=True)},
                 "max_sway_deg": 2.5, "move_time_s": 10.0, "motion_end_s": 7.5}
    assert np.isnan(s["residual_sway_deg_by_node"]["LOAD"])
    assert all(type(s[k]) is float for k in ("residual_sway_deg", "max_sway_deg",
                                             "move_time_s", "motion_end_s"))
    s = en.summary(_res([0.3, 0.9], [1.0, 2.0]), mv)
    assert s["residual_sway_deg"] == 0.9 and s["max_sway_deg"] == 2.0
    s = en.summary(_res([np.nan, np.nan], [], names=(), end=3), profiles.Motion.build(
        0.0, [], "trapezoid"))
    assert s["residual_sway_deg"] is None and s["max_sway_deg"] is None
    assert s["move_time_s"] == 0.0 and s["residual_sway_deg_by_node"] == {}
    assert type(s["move_time_s"]) is float and type(s["motion_end_s"]) is float


# ------------------------------------------------------------------ compare

@pytest.fixture
def engine(monkeypatch):
    """The operation engine replaced: each call returns the scene's duration as the
    residual of HOOK (a second node never settles: nan), its drive's end as max sway."""
    runs = []

    def simulate(m):
        runs.append(m)
        end = drive(m).motion.t[-1]
        return SimpleNamespace(sway_residual_deg=np.array([m.analysis["duration"], np.nan]),
                               sway_max_deg=np.array([end, 0.0]),
                               sway_names=("HOOK", "X"), motion_end=end, status=3)
    monkeypatch.setattr(integrate, "simulate", simulate)
    return runs


def test_compare_with_a_given_frequency(tmp_path, engine):
    """The scene carries a ZVD shaper; unshaped strips it. ZV and ZVD at 0.25 Hz add 2
    and 4 s (to the scene's 30 s and the move's 3 s); damping 0.1 stretches them by
    1/sqrt(0.99)."""
    m = scene(tmp_path, TROLLEY % ", shaper: {type: ZVD, frequency: 1}")
    doc = en.compare(m, "trolley", kinds=("unshaped", "ZV", "ZVD"), frequency=0.25)
    assert doc["drive"] == "trolley" and list(doc["shapers"]) == ["unshaped", "ZV", "ZVD"]
    for kind, add in (("unshaped", 0.0), ("ZV", 2.0), ("ZVD", 4.0)):
        row = doc["shapers"][kind]
        assert row["extra_time_s"] == pytest.approx(add, abs=TOL)
        assert row["move_time_s"] == pytest.approx(3.0 + add, abs=TOL)
        assert row["residual_sway_deg"] == pytest.approx(30.0 + add, abs=TOL)
        assert row["residual_sway_deg_by_node"]["HOOK"] == pytest.approx(30.0 + add, abs=TOL)
        assert row["max_sway_deg"] == pytest.approx(4.0 + add, abs=TOL)
        assert row["motion_end_s"] == pytest.approx(4.0 + add, abs=TOL)
        assert row["status"] == 3
        assert row["frequencies_hz"] == ([] if kind == "unshaped" else [pytest.approx(0.25)])
    assert len(engine) == 3
    assert all(type(v) is float for v in doc["shapers"]["ZV"]["frequencies_hz"])
    doc = en.compare(m, "trolley", kinds=("ZV",), frequency=0.25, damping=0.1)
    assert doc["shapers"]["ZV"]["extra_time_s"] == pytest.approx(2.0 / np.sqrt(0.99),
                                                                 abs=TOL)
    sh = engine[-1].analysis["drives"]["trolley"]["profile"]["shaper"]
    assert sh == {"type": "ZV", "frequency": 0.25, "damping": 0.1}


def test_compare_defaults_and_modes(tmp_path, engine):
    """The default kinds and frequency auto: every kind is run, at the pendulum's
    frequency; modes go into the spec."""
    m = scene(tmp_path, TROLLEY % "")
    doc = en.compare(m, "trolley")
    assert list(doc["shapers"]) == ["unshaped", "ZV", "ZVD", "ZVDD", "EI"]
    f = W_OH / (2 * np.pi)
    assert doc["shapers"]["ZV"]["frequencies_hz"] == [pytest.approx(f, rel=1e-9)]
    assert doc["shapers"]["ZV"]["extra_time_s"] == pytest.approx(0.5 / f, rel=1e-9)
    assert doc["shapers"]["EI"]["extra_time_s"] == pytest.approx(1.0 / f, rel=1e-6)
    assert doc["shapers"]["ZVDD"]["extra_time_s"] == pytest.approx(1.5 / f, rel=1e-9)
    sh = engine[1].analysis["drives"]["trolley"]["profile"]["shaper"]
    assert sh == {"type": "ZV", "frequency": "auto", "damping": 0.0}
    # the tower crane's hook and load: both modes, or the first only
    tower = ("    trolley: {slider: trolley_travel, profile: {type: trapezoid, distance: 5, "
             "v_max: 1, a_max: 0.5}}\n")
    m = scene(tmp_path, tower, model=TOWER, name="t.yaml")
    both = en.compare(m, "trolley", kinds=("ZV",))["shapers"]["ZV"]["frequencies_hz"]
    one = en.compare(m, "trolley", kinds=("ZV",), modes=(1,))["shapers"]["ZV"]
    assert len(both) == 2 and both == sorted(both)
    assert one["frequencies_hz"] == [pytest.approx(both[0], rel=1e-12)]
    assert engine[-1].analysis["drives"]["trolley"]["profile"]["shaper"]["modes"] == [1]
