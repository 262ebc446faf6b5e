"""Property-based tests (hypothesis): invariants of the physics, and input fuzzing of the
model loader (any YAML gives a result or a clear error, never a traceback)."""

import os
import re
from dataclasses import replace

import numpy as np
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from cranefe.errors import AnalysisError, ModelError
from cranefe.model import load
from cranefe.analysis.modal import modes

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = os.path.join(ROOT, "models")
FAST = settings(max_examples=25, deadline=None,
                suppress_health_check=[HealthCheck.function_scoped_fixture])


def text_of(name):
    with open(os.path.join(MODELS, name)) as fh:
        return fh.read()


@FAST
@given(q=st.lists(st.floats(-1, 1), min_size=4, max_size=4).filter(
    lambda v: np.linalg.norm(v) > 0.1),
    shift=st.lists(st.floats(-1e3, 1e3), min_size=3, max_size=3))
def test_rigid_motion_of_a_whole_model(q, shift):
    model = load(os.path.join(MODELS, "hammerhead_tower_crane.yaml"))
    R = Rotation.from_quat(q).as_matrix()
    s = np.array(shift)
    rot = (lambda v: None if v is None else R @ v)
    moved = replace(
        model, coords=model.coords @ R.T + s, gravity=R @ model.gravity,
        bodies=tuple(replace(b, com=R @ b.com + s, inertia=R @ b.inertia @ R.T)
                     for b in model.bodies),
        joints=tuple(replace(j, axis=rot(j.axis)) for j in model.joints),
        springs=tuple(replace(sp, axis=rot(sp.axis)) for sp in model.springs),
        masses=replace(model.masses, inertia=R @ model.masses.inertia @ R.T))
    np.testing.assert_allclose(modes(moved).omega, modes(model).omega, rtol=1e-8,
                               atol=1e-9)


@FAST
@given(st.data())
def test_renaming_nodes(data):
    text = text_of("luffing_tower_crane.yaml")
    names = list(yaml.safe_load(text)["nodes"])
    fresh = data.draw(st.lists(st.from_regex(r"[A-Za-z][A-Za-z0-9_]{0,8}", fullmatch=True),
                               min_size=len(names), max_size=len(names), unique=True))
    used = set(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", text))
    if set(fresh) & (used - set(names)):
        return                          # would collide with another name or key
    if any(not isinstance(yaml.safe_load(f), str) for f in fresh):
        return                          # YAML reads it as a boolean or null (`No`, `off`,
                                        # `null`): not a name unless quoted, and refused
    tmp = {n: f"@@{k}@@" for k, n in enumerate(names)}
    renamed = text
    for n, t in tmp.items():           # whole-word replacement, two steps (no chains)
        renamed = re.sub(rf"(?<![A-Za-z0-9_]){re.escape(n)}(?![A-Za-z0-9_])", t, renamed)
    for (n, t), new in zip(tmp.items(), fresh):
        renamed = renamed.replace(t, new)
    a = modes(load("a.yaml", text))
    b = modes(load("b.yaml", renamed))
    np.testing.assert_allclose(b.omega, a.omega, rtol=1e-12, atol=1e-12)


@FAST
@given(t=st.floats(0.05, 0.95))
def test_splitting_a_span_at_a_sheave_with_no_angle(t):
    # a fixed sheave on the straight drum-to-head-sheave span changes nothing
    text = text_of("two_mass_hoist.yaml")
    d = yaml.safe_load(text)
    rope = next(iter(d["ropes"].values()))
    drum = d["drums"][rope["path"][0]]
    a, b = np.array(d["nodes"][drum["node"]]), np.array(d["nodes"][rope["path"][1]])
    d["nodes"]["MID"] = (a + t * (b - a)).tolist()
    d["ground"] = list(d.get("ground", [])) + ["MID"]
    rope["path"] = [rope["path"][0], "MID"] + rope["path"][1:]
    np.testing.assert_allclose(modes(load("s.yaml", yaml.safe_dump(d))).omega,
                               modes(load("m.yaml", text)).omega, rtol=1e-10, atol=1e-12)


@FAST
@given(s=st.floats(0.01, 100.0))
def test_scaling_all_masses(s):
    # sway off: every inertia x s -> every frequency / sqrt(s)
    model = load(os.path.join(MODELS, "luffing_tower_crane.yaml"))
    model = replace(model, effects=replace(model.effects, sway=False))
    heavy = replace(
        model, bodies=tuple(replace(b, mass=b.mass * s, inertia=b.inertia * s)
                            for b in model.bodies),
        masses=replace(model.masses, mass=model.masses.mass * s,
                       inertia=model.masses.inertia * s),
        drums=tuple(replace(d, inertia=d.inertia * s, rotor_inertia=d.rotor_inertia * s)
                    for d in model.drums))
    np.testing.assert_allclose(modes(heavy).omega, modes(model).omega / np.sqrt(s),
                               rtol=1e-9, atol=1e-12)


# ----------------------------------------------------------------- loader fuzzing
JUNK = st.one_of(st.none(), st.booleans(), st.integers(-10**6, 10**6),
                 st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=12),
                 st.lists(st.integers(-5, 5), max_size=4),
                 st.dictionaries(st.text(max_size=5), st.integers(), max_size=3))


def _paths(obj, prefix=()):
    yield prefix
    if isinstance(obj, dict):
        for k, v in obj.items():
            yield from _paths(v, prefix + (k,))
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            yield from _paths(v, prefix + (i,))


def _outcome(path):
    """Load and solve: a result, or a clear error naming the file; never anything else."""
    try:
        model = load(path)
        modes(model)
    except (ModelError, AnalysisError) as exc:
        assert str(exc).strip() and "Traceback" not in str(exc)
        if isinstance(exc, ModelError):
            assert str(path) in str(exc) or exc.file is None


@settings(max_examples=150, deadline=2000,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data(), name=st.sampled_from(["two_mass_hoist.yaml",
                                             "luffing_tower_crane.yaml",
                                             "hammerhead_tower_crane.yaml"]))
def test_mutated_models_never_crash(tmp_path, data, name):
    d = yaml.safe_load(text_of(name))
    paths = [p for p in _paths(d) if p]
    for _ in range(data.draw(st.integers(1, 3))):
        p = data.draw(st.sampled_from(paths))
        parent = d
        try:
            for k in p[:-1]:
                parent = parent[k]
            action = data.draw(st.sampled_from(["delete", "junk", "rename"]))
            if action == "delete" and isinstance(parent, dict):
                del parent[p[-1]]
            elif action == "rename" and isinstance(parent, dict):
                parent[data.draw(st.text(max_size=6))] = parent.pop(p[-1])
            else:
                parent[p[-1]] = data.draw(JUNK)
        except (KeyError, IndexError, TypeError):
            continue
    path = tmp_path / "fuzz.yaml"
    path.write_text(yaml.safe_dump(d, allow_unicode=True))
    _outcome(path)


@settings(max_examples=200, deadline=2000,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(text=st.text(alphabet=st.sampled_from(list("abcAB01 :-[]{},&*!|>'\"#\n\t.e+")),
                    max_size=120))
def test_arbitrary_text_never_crashes(tmp_path, text):
    path = tmp_path / "t.yaml"
    path.write_text("cranefe: 1\n" + text)
    _outcome(path)
