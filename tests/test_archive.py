"""Archive format 2 (issue 18): every result kind written and read back field by field,
opened with h5py alone against the tables of docs/archive.md, and format 1 still read."""

import dataclasses
import json
import os
import re
import subprocess
import sys

import numpy as np
import pytest

from cranefe import api
from cranefe.outputs import archive
from cranefe.outputs.archive_schema import FIELDS

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = os.path.join(ROOT, "models")
HOIST = os.path.join(MODELS, "two_mass_hoist.yaml")
V1 = os.path.join(ROOT, "tests", "data", "archive_v1_damping.h5")
DOC = os.path.join(ROOT, "docs", "archive.md")


def operation_scene(folder, duration=8):
    """The overhead crane's emergency stop (models/operations), shortened."""
    text = open(os.path.join(MODELS, "operations", "overhead_crane_estop.yaml")).read()
    text = text.replace("model: overhead_crane.yaml", "model: " +
                        os.path.join(MODELS, "operations", "overhead_crane.yaml"))
    text = re.sub(r"duration: \d+", f"duration: {duration}", text)
    path = os.path.join(folder, "estop.yaml")
    with open(path, "w") as fh:
        fh.write(text)
    return path


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    """One archive per analysis kind: {group: (path, result)}."""
    d = tmp_path_factory.mktemp("arc")
    model = api.load(HOIST)
    from cranefe.system import assemble
    system = assemble(model)
    out = {"modes": (model, system, api.modes(model)),
           "damping": (model, system, api.damping(model, method="both"))}
    scene = api.load(os.path.join(MODELS, "two_mass_hoist_start.yaml"))
    out["transient"] = (scene, assemble(scene), api.simulate(scene))
    luff = api.load(os.path.join(MODELS, "portal_crane_luffing_scene.yaml"))
    out["luffing"] = (luff, None, api.luff(luff, sensitivity=False))
    op = api.load(operation_scene(str(d)))
    out["operation"] = (op, None, api.simulate(op))
    out["member_forces"] = member_force_modes(str(d))
    paths = {}
    for group, (m, s, r) in out.items():
        paths[group] = (archive.write(d / f"{group}.h5", m, s, {group: r},
                                      command=["test"], timings=getattr(r, "timings", {})),
                        r)
    return paths


def member_force_modes(folder):
    """(model, system, MemberForces) of the first three modes of a 3D cantilever of two
    members, one of them without section moduli (nan stresses), scaled to 0.01 m."""
    from cranefe.outputs.member_forces import modal_member_forces
    from cranefe.system import assemble
    path = os.path.join(folder, "cantilever.yaml")
    with open(path, "w") as fh:
        fh.write("""cranefe: 1
nodes: {O: [0, 0, 0], A: [2, 0, 0], T: [4, 0, 0]}
ground: [O]
members:
  root: {type: beam, nodes: [O, A], E: 2.1e11, G: 8.1e10, rho: 7850, elements: 2,
         orientation: [0, 0, 1], section: {shape: rectangle, b: 0.1, h: 0.2}}
  tip: {type: beam, nodes: [A, T], E: 2.1e11, G: 8.1e10, rho: 7850, A: 0.02, Iy: 6.7e-5,
        Iz: 1.7e-5, J: 4.6e-5, orientation: [0, 0, 1]}
masses: {T: 100}
effects: {structure: flexible}
""")
    model = api.load(path)
    system = assemble(model)
    r = api.modes(model, count=3)
    return model, system, modal_member_forces(model, system.dofs, r.shapes, r.node_shapes,
                                              0.01)


def same(a, b, where):
    """Deep equality of values read back (NaN equal to NaN, types kept)."""
    if isinstance(a, np.ndarray):
        assert isinstance(b, np.ndarray) and a.dtype == b.dtype and a.shape == b.shape, where
        assert np.array_equal(a, b, equal_nan=a.dtype.kind in "fc"), where
    elif isinstance(a, dict):
        assert isinstance(b, dict) and list(a) == list(b), where
        for k in a:
            same(a[k], b[k], f"{where}[{k!r}]")
    elif isinstance(a, (list, tuple)):
        assert type(a) is type(b) and len(a) == len(b), where
        for k, (x, y) in enumerate(zip(a, b)):
            same(x, y, f"{where}[{k}]")
    elif isinstance(a, float) and np.isnan(a):
        assert isinstance(b, float) and np.isnan(b), where
    else:
        assert type(a) is type(b) and a == b, (where, a, b)


@pytest.mark.parametrize("group", ["modes", "damping", "transient", "luffing", "operation",
                                   "member_forces"])
def test_every_field_comes_back(written, group):
    path, result = written[group]
    back = archive.read(path).results[group]
    assert type(back) is type(result)
    for f in dataclasses.fields(result):
        same(getattr(result, f.name), getattr(back, f.name), f"{group}.{f.name}")


def test_every_result_field_has_a_name_units_and_description():
    """A field added to a result class must be described in archive_schema.FIELDS (its
    archive name, units and meaning) and in docs/archive.md."""
    for name, cls in archive._result_classes().items():
        missing = [f.name for f in dataclasses.fields(cls) if f.name not in FIELDS[name]]
        assert not missing, f"{name}: describe {missing} in archive_schema.FIELDS"
        names = [FIELDS[name][f.name][0] for f in dataclasses.fields(cls)]
        assert len(set(names)) == len(names)


def documented():
    """{group: [(dataset, units or None)]} from the tables of docs/archive.md."""
    text = open(DOC).read()
    out = {}
    for m in re.finditer(r"### `/results/(\w+)` \(\w+\)\n\n\| dataset \| units \| "
                         r"description \|\n\|---\|---\|---\|\n((?:\|.*\|\n)+)", text):
        rows = []
        for line in m.group(2).splitlines():
            cells = [c.strip() for c in line.strip("|").split("|")]
            rows.append((cells[0].strip("`"), None if cells[1] == "—" else cells[1]))
        out[m.group(1)] = rows
    return out


H5PY_ONLY = r"""
import json, sys
import h5py
paths, tables = json.loads(sys.argv[1]), json.loads(sys.argv[2])
problems, found = [], {}
for group, rows in tables.items():
    with h5py.File(paths[group], "r") as h:
        g = h["results"][group]
        for name, units in rows:
            if name not in g:
                problems.append(f"{group}/{name}: missing")
                continue
            m = g[name]
            if "description" not in m.attrs:
                problems.append(f"{group}/{name}: no description")
            if isinstance(m, h5py.Group) and units is not None:   # a dict: its entries
                for k, x in m.items():
                    if isinstance(x, h5py.Dataset) and x.dtype.kind == "f" \
                            and x.attrs.get("units") is None:
                        problems.append(f"{group}/{name}/{k}: no units")
                continue
            if m.attrs.get("units") != units:
                problems.append(f"{group}/{name}: units {m.attrs.get('units')!r}, "
                                f"documented {units!r}")
        found[group] = sorted(k for k, m in g.items() if "units" in m.attrs)
assert not any(k.startswith("cranefe") for k in sys.modules), "cranefe was imported"
print(json.dumps({"problems": problems, "with_units": found}))
"""


def test_h5py_alone_finds_every_documented_dataset(written):
    """A process that never imports cranefe opens each archive with h5py and finds every
    dataset of the docs/archive.md tables with its documented units; every dataset with
    units in the file is in the tables (doc and file cannot drift)."""
    tables = documented()
    assert set(tables) == {"modes", "damping", "transient", "luffing", "operation",
                           "member_forces"}
    paths = {g: str(p) for g, (p, _) in written.items()}
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    out = subprocess.run([sys.executable, "-c", H5PY_ONLY, json.dumps(paths),
                          json.dumps(tables)], capture_output=True, text=True, env=env,
                         cwd=os.path.dirname(paths["modes"]), timeout=120)
    assert out.returncode == 0, out.stderr[-2000:]
    report = json.loads(out.stdout)
    assert report["problems"] == []
    for group, names in report["with_units"].items():
        listed = {n for n, u in tables[group] if u is not None}
        assert set(names) <= listed, f"{group}: not documented: {set(names) - listed}"


def test_self_describing_names_and_values(written):
    import h5py
    path, result = written["modes"]
    with h5py.File(path, "r") as h:
        g = h["results/modes"]
        np.testing.assert_array_equal(g["frequency_hz"][()], result.omega / (2 * np.pi))
        np.testing.assert_array_equal(g["period_s"][()][1:], 2 * np.pi / result.omega[1:])
        assert g["mode_shape"].shape == (len(result.omega), 3, 3)
        assert tuple(g["node_names"].asstr()[()]) == api.load(HOIST).node_names
        assert list(g["mode_shape"].attrs["dims"]) == ["mode", "node", "xyz"]
        # no JSON text for numbers anywhere in the file
        texts = []
        h.visititems(lambda n, o: texts.extend(
            f"{n}@{k}" for k, v in o.attrs.items() if isinstance(v, str) and
            v.lstrip().startswith(("{", "["))))
        assert texts == []
    path, result = written["damping"]
    with h5py.File(path, "r") as h:
        g = h["results/damping"]
        assert g["damping_ratio"][2] == pytest.approx(0.2 / (4 * np.pi), rel=1e-12)
        assert g["damping_ratio"].attrs["units"] == "1"
    path, result = written["operation"]
    with h5py.File(path, "r") as h:
        g = h["results/operation"]
        t = g["t_s"][()]
        assert t[0] == 0 and t[-1] == pytest.approx(8.0) and g["t_s"].attrs["units"] == "s"
        assert g["mass_position"].shape == (len(t), 1, 3)
        assert g["events/column_0"].attrs["units"] == "s"


def test_format_1_archives_still_read():
    """tests/data/archive_v1_damping.h5 was written by format 1 (cranefe damping
    two_mass_hoist.yaml --method both): its results come back as the same classes, with
    the figures today's code computes (same model, same arithmetic: 1e-12)."""
    arc = archive.read(V1)
    assert arc.meta["format_version"] == 1
    assert set(arc.results) == {"modes", "damping"}
    now = api.damping(api.load(HOIST), method="both")
    back = arc.results["damping"]
    np.testing.assert_allclose(back.omega, now.omega, rtol=1e-12)
    np.testing.assert_allclose(back.zeta, now.zeta, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(arc.results["modes"].omega, now.omega, rtol=1e-12)
    assert arc.model["kinds"] == ("rope", "body", "spring", "member", "drive")
    assert arc.meta["timings"]["solve"] > 0


def test_newer_format_is_refused(tmp_path, written):
    import h5py
    import shutil
    from cranefe.errors import ModelError
    p = tmp_path / "new.h5"
    shutil.copy(written["modes"][0], p)
    with h5py.File(p, "r+") as h:
        h.attrs["format_version"] = archive.FORMAT_VERSION + 1
    archive.seal(p)                        # as a newer cranefe would have sealed it
    with pytest.raises(ModelError, match="newer than this cranefe reads"):
        archive.read(p)


# ------------------------------------------------------------------ cranefe show

@pytest.mark.parametrize("group", ["modes", "damping", "transient", "luffing", "operation",
                                   "member_forces"])
def test_show_prints_every_result_as_its_command_does(written, group, capsys):
    """`cranefe show` prints each result's table (the one its own command prints, from
    the values read back) and, with --json, its JSON document."""
    from cranefe.cli import main
    from cranefe.cli.show import _presenters
    from cranefe.outputs.report import dumps
    path, result = written[group]
    table, document = _presenters()[type(result).__name__]
    assert main(["show", str(path)]) == 0
    out = capsys.readouterr().out
    assert f"results/{group} ({type(result).__name__}):\n{table(result)}" in out
    assert main(["show", str(path), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["results"] == [group]
    assert doc["documents"][group] == json.loads(dumps(document(result)))


def test_show_prints_modes_and_damping_of_one_archive_and_of_format_1(tmp_path, capsys):
    from cranefe.cli import main
    out = tmp_path / "d.h5"
    assert main(["damping", HOIST, "--method", "both", "--archive", str(out)]) == 0
    capsys.readouterr()
    for path in (out, V1):
        assert main(["show", str(path)]) == 0
        text = capsys.readouterr().out
        assert "results/damping (DampingResult):" in text and "zeta exact" in text
        assert "results/modes (ModalResult):" in text and "w [rad/s]" in text
        assert "0.01592" in text              # zeta = psi / (4 pi), psi = 0.2


def test_simulate_writes_the_archive_of_an_operation_scene(tmp_path, capsys):
    from cranefe.cli import main
    scene = operation_scene(str(tmp_path), duration=3)
    out = tmp_path / "op.h5"
    assert main(["simulate", scene, "--json", "--archive", str(out)]) == 0
    doc = json.loads(capsys.readouterr().out)
    back = archive.read(out).results["operation"]
    assert json.loads(json.dumps(back.to_dict(), default=str))["rope_force_max_N"] == \
        doc["rope_force_max_N"]
    assert back.mass_position.shape == (len(back.times), 1, 3)
    assert main(["show", str(out)]) == 0
    assert "results/operation (OperationResult):" in capsys.readouterr().out
