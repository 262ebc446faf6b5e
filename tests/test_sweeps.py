"""Parameter sweeps: local processes and Dask give identical results; an interrupted
sweep resumes with only the missing variants; a failing variant does not stop the rest."""

import glob
import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from cranefe.cli import main
from cranefe.model import load
from cranefe.analysis.modal import modes
from cranefe.sweeps.engine import run_sweep
from cranefe.sweeps.spec import load_sweep
from cranefe.sweeps.table import read_journal, read_table

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BASE = os.path.join(ROOT, "models", "two_mass_hoist.yaml")


def sweep_file(tmp_path, extra="", ea="{range: [1.0e7, 4.0e7], count: 3}", name="s"):
    path = tmp_path / f"{name}.yaml"
    path.write_text(f"""cranefe: 1
sweep: test sweep
base: {BASE}
parameters:
  ropes.hoist_rope.EA: {ea}
  masses.H: {{values: [3000, 6000]}}
outputs: [frequency_hz.2, omega.1, dofs, damping_ratio.2]
output: {name}.h5
{extra}""")
    return path


def test_results_are_the_direct_analyses(tmp_path):
    sweep = load_sweep(sweep_file(tmp_path))
    done = run_sweep(sweep, workers=0)
    assert len(done) == 6 == len(sweep.variants)
    base = load(BASE)
    for row in done.values():
        from dataclasses import replace
        EA, m = row["values"]
        model = replace(base, ropes=(replace(base.ropes[0], EA=EA),),
                        masses=replace(base.masses, mass=np.array([m])))
        r = modes(model)
        w = r.omega[~r.rigid]
        assert row["outputs"] == pytest.approx([w[1] / (2 * np.pi), w[0], r.dofs,
                                                0.2 / (4 * np.pi)], rel=1e-12)


def test_processes_and_dask_give_identical_results(tmp_path):
    distributed = pytest.importorskip("distributed")
    a = run_sweep(load_sweep(sweep_file(tmp_path, name="a")), workers=2)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        # as a user runs it: the scheduler's address on the command line
        assert main(["sweep", str(sweep_file(tmp_path, name="b")), "--scheduler",
                     cluster.scheduler_address]) == 0
    b = read_journal(str(tmp_path / "b.h5"))
    assert sorted(a) == sorted(b)
    for i in a:
        assert a[i]["outputs"] == b[i]["outputs"]
    ta, tb = read_table(tmp_path / "a.h5"), read_table(tmp_path / "b.h5")
    np.testing.assert_array_equal(ta.results, tb.results)


def test_interrupted_sweep_resumes_with_the_missing_variants(tmp_path):
    sweep = load_sweep(sweep_file(tmp_path, ea="{range: [1.0e7, 4.0e7], count: 10}"))
    first = run_sweep(sweep, workers=0, limit=7)
    assert len(first) == 7 and read_table(sweep.output).index.size == 7
    rest = run_sweep(sweep, workers=0)
    with open(sweep.output + ".journal") as fh:      # rows; also a header, owner lines
        lines = [x for x in fh.read().splitlines() if x.startswith('{"index"')]
    assert len(rest) == 20 and len(lines) == 20           # nothing computed twice
    assert sorted(json.loads(x)["index"] for x in lines) == list(range(20))


def test_killed_sweep_process_resumes(tmp_path):
    # 120 variants (~10 ms each): the process is killed once 20 are journaled, ~100
    # before its end (600 variants cost the resumed run 7 s more, to the same checks)
    path = sweep_file(tmp_path, ea="{range: [1.0e7, 4.0e7], count: 60}", name="k")
    journal = tmp_path / "k.h5.journal"
    p = subprocess.Popen([sys.executable, "-m", "cranefe", "sweep", str(path),
                          "--workers", "0"], stdout=subprocess.DEVNULL,
                         stderr=subprocess.DEVNULL)
    t0 = time.time()
    while time.time() - t0 < 60 and (not journal.exists() or
                                     len(journal.read_text().splitlines()) < 20):
        time.sleep(0.05)
    p.send_signal(signal.SIGKILL)
    p.wait()
    before = len(read_journal(str(tmp_path / "k.h5")))
    assert 20 <= before < 120
    assert main(["sweep", str(path), "--workers", "0"]) == 0
    table = read_table(tmp_path / "k.h5")
    assert table.index.tolist() == list(range(120))
    lines = [x for x in journal.read_text().splitlines() if x.startswith('{"index"')]
    assert len({json.loads(x)["index"] for x in lines if x.strip().endswith("}")}) == 120


def test_invalid_variant_is_reported_and_the_rest_finish(tmp_path, capsys):
    path = sweep_file(tmp_path, ea="{values: [2.0e7, -1.0, 3.0e7]}")
    assert main(["sweep", str(path), "--workers", "0", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["done"] == 6 and doc["failed"] == 2
    assert all("EA" in e["error"] and "positive" in e["error"] for e in doc["errors"])
    table = read_table(tmp_path / "s.h5")
    assert np.isnan(table.results[np.array(table.status) == "error"]).all()
    assert np.isfinite(table.results[np.array(table.status) == "ok"]).all()


def test_show_and_plots(tmp_path, capsys):
    path = sweep_file(tmp_path)
    assert main(["sweep", str(path), "--workers", "0", "--plots", str(tmp_path / "p")]) == 0
    outs = ["damping_ratio_2", "dofs", "frequency_hz_2", "omega_1"]
    assert sorted(os.listdir(tmp_path / "p")) == sorted(   # plots, heat maps, their tables
        [f"{o}.png" for o in outs] + [f"{o}_map.{e}" for o in outs for e in ("png", "csv")])
    capsys.readouterr()
    assert main(["show", str(tmp_path / "s.h5")]) == 0
    assert "6/6 variants" in capsys.readouterr().out


def test_sampling_methods(tmp_path):
    for method in ("random", "lhs"):
        s = load_sweep(sweep_file(tmp_path, extra=f"sampling: {{method: {method}, "
                                  "samples: 16, seed: 3}\n"))
        assert s.variants.shape == (16, 2)
        assert (s.variants[:, 0] >= 1.0e7).all() and (s.variants[:, 0] <= 4.0e7).all()
        assert set(s.variants[:, 1]) <= {3000.0, 6000.0}


@pytest.mark.parametrize("bad, entry", [
    ("ropes.nope.EA: {values: [1]}", "parameters.ropes.nope.EA"),
    ("masses: {values: [1]}", "parameters.masses"),
    ("ropes.hoist_rope.EA: {range: [2, 1], count: 3}", "parameters.ropes.hoist_rope.EA.range"),
])
def test_bad_sweep_files(tmp_path, capsys, bad, entry):
    path = tmp_path / "bad.yaml"
    path.write_text(f"cranefe: 1\nbase: {BASE}\nparameters:\n  {bad}\n"
                    "outputs: [frequency_hz.1]\n")
    assert main(["sweep", str(path)]) == 2
    err = capsys.readouterr().err
    assert entry in err and "Traceback" not in err


def test_dynamic_factor_of_a_transient_scene(tmp_path):
    # phi2 of lifting off the ground against the closed form 1 + v w / g
    scene = os.path.join(ROOT, "models", "two_mass_hoist_lift.yaml")
    path = tmp_path / "phi.yaml"
    path.write_text(f"""cranefe: 1
base: {scene}
parameters:
  masses.H: {{values: [3000, 6000]}}
outputs: [phi2.hoist_rope]
output: phi.h5
""")
    done = run_sweep(load_sweep(path), workers=0)
    base = load(BASE)
    rope = base.ropes[0]
    L = float(np.sum(rope.falls * np.linalg.norm(base.coords[rope.span_b] -
                                                 base.coords[rope.span_a], axis=1))
              + rope.extra_length)
    for row in done.values():
        m = row["values"][0]
        w = np.sqrt(4 * rope.EA / L / m)
        v = base.drums[0].radius * 2.0 / 2
        assert row["status"] == "ok"
        assert row["outputs"][0] == pytest.approx(1 + v * w / 9.81, rel=2e-3)


# ------------------------------------------------------------- reuse across variants

def _numbers(data, path=()):
    """Paths of every number in raw YAML data."""
    if isinstance(data, dict):
        for k, v in data.items():
            yield from _numbers(v, path + (k,))
    elif isinstance(data, list):
        for i, v in enumerate(data):
            yield from _numbers(v, path + (i,))
    elif isinstance(data, (int, float)) and not isinstance(data, bool):
        yield path


def _same(a, b):
    """Field-by-field equality of DofMaps (and the meshes and layout inside)."""
    import dataclasses
    import scipy.sparse as sp
    if dataclasses.is_dataclass(a):
        return type(a) is type(b) and all(_same(getattr(a, f.name), getattr(b, f.name))
                                          for f in dataclasses.fields(a))
    if sp.issparse(a):
        return a.shape == b.shape and abs(a - b).max() == 0 if a.nnz or b.nnz else True
    if isinstance(a, np.ndarray):
        return np.array_equal(a, b)
    if isinstance(a, (tuple, list)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    return a == b


EXAMPLES = sorted(glob.glob(os.path.join(ROOT, "models", "*.yaml")))


@pytest.mark.parametrize("path", EXAMPLES, ids=os.path.basename)
def test_an_unchanged_structure_key_means_an_unchanged_dof_map(path):
    # Perturb every number of the example (up to 60 of a big one), under the effects
    # that build rope and member meshes too: wherever the key stays, build_dofs must
    # give the same DofMap, else a sweep would reuse a stale one.
    import copy
    from dataclasses import replace
    from cranefe.coordinates.dofmap import build_dofs, structure_key
    from cranefe.model.load import build, read_raw
    from cranefe.errors import ModelError
    raw = read_raw(path)
    paths = list(_numbers(raw[0]))
    paths = paths[::max(1, len(paths) // 60)]
    base = build(*raw)
    kept = changed = 0
    for effects in {base.effects, replace(base.effects, rope_mass=3),
                    replace(base.effects, structure="flexible", sway=False)}:
        dofs0, key0 = build_dofs(base, effects), structure_key(base, effects)
        for p in paths:
            data = copy.deepcopy(raw[0])
            target = data
            for k in p[:-1]:
                target = target[k]
            target[p[-1]] = target[p[-1]] * 1.37 + 0.01
            try:
                model = build(data, *raw[1:])
                dofs = build_dofs(model, effects)
            except ModelError:
                continue
            if structure_key(model, effects) == key0:
                kept += 1
                assert _same(dofs, dofs0), (p, effects)
            else:
                changed += 1
    assert changed > 0
    if any(k in raw[0] for k in ("ropes", "springs", "members")):
        assert kept > 0           # stiffness values at least leave the structure alone


def test_rope_mass_sweep_over_EA_uses_each_EA(tmp_path):
    # the DofMap reused across variants once carried the first variant's rope EA
    scene = tmp_path / "m.yaml"
    scene.write_text(f"cranefe: 1\nmodel: {BASE}\neffects: {{rope_mass: 4}}\n")
    rows = {}
    for name, reuse in (("reused", True), ("rebuilt", False)):
        (tmp_path / f"{name}.yaml").write_text(
            "cranefe: 1\nbase: m.yaml\nparameters:\n"
            "  ropes.hoist_rope.EA: {values: [1.0e7, 4.0e7]}\n"
            f"outputs: [frequency_hz.2]\noutput: {name}.h5\n")
        done = run_sweep(load_sweep(tmp_path / f"{name}.yaml"), workers=0, reuse=reuse)
        rows[name] = [done[i]["outputs"][0] for i in range(2)]
    assert rows["reused"] == rows["rebuilt"]
    # the hoisting mode stiffens with EA: f ~ sqrt(EA) once the rope dominates
    assert rows["reused"][1] / rows["reused"][0] > 1.3


def test_reuse_is_exact_and_finds_the_structure_once():
    # variants that differ in stiffness and masses: the same matrices with and without
    # reuse, one DofMap per effects and one static null space
    from dataclasses import replace
    from cranefe.system import assemble
    from cranefe.assembly.reuse import Reuse
    base = load(os.path.join(ROOT, "models", "hammerhead_tower_crane.yaml"))
    base = base.with_effects(rope_mass=3)
    reuse = Reuse()
    for k, EA in enumerate((1.0e7, 2.0e7, 3.0e7)):
        model = replace(base, ropes=tuple(replace(r, EA=EA * (1 + i))
                                          for i, r in enumerate(base.ropes)),
                        masses=replace(base.masses, mass=base.masses.mass * (1 + k)))
        a, b = assemble(model), assemble(model, reuse=reuse)
        assert abs(a.K - b.K).max() == 0 and abs(a.M - b.M).max() == 0
        assert np.array_equal(a.f, b.f)
    # modal DofMap and static DofMap built once, found twice each
    assert reuse.misses["dofs"] == 2 and reuse.hits["dofs"] == 4
    assert reuse.misses["null_space"] == 1 and reuse.hits["null_space"] == 2


# ------------------------------------------------------------- scenes and luffing

LUFF = os.path.join(ROOT, "models", "portal_crane_luffing_scene.yaml")


@pytest.fixture(scope="module")
def luff_table():
    """The luffing analysis' table of the scene as it stands (t_k 25 s, 16 t on 15 m),
    made once for the two tests below (2 s each)."""
    from cranefe.analysis.luffing.analysis import analyse
    return analyse(load(LUFF), collocation=False, sensitivity=False).table


def test_luffing_sweep_over_scene_keys(tmp_path, luff_table):
    # parameters in the scene file; outputs equal the luffing analysis of each variant,
    # and the optimum's mean energy follows eq. 16, T = S^2 / (2 t_k^2)
    from cranefe.analysis.luffing.analysis import analyse
    from cranefe.model.load import build, read_raw
    path = tmp_path / "l.yaml"
    path.write_text(f"""cranefe: 1
base: {LUFF}
parameters:
  analysis.t_k: {{values: [12.5, 25.0]}}
  analysis.load.mass: {{values: [16000]}}
outputs: [luffing.optimal.T_mean_J, luffing.linear.T_ratio, luffing.linear.max_sway_deg]
output: l.h5
""")
    sweep = load_sweep(path)
    assert [p.scene for p in sweep.parameters] == [True, True]
    done = run_sweep(sweep, workers=0)
    raw = read_raw(LUFF)
    for row in done.values():
        t_k, mass = row["values"]
        assert raw[3]["analysis"]["t_k"] == 25.0 and raw[3]["analysis"]["load"] == {
            "mass": 16000, "rope_length": 15.0}
        scene = dict(raw[3], analysis=dict(raw[3]["analysis"], t_k=t_k,
                                           load={"mass": mass, "rope_length": 15.0}))
        table = luff_table if t_k == 25.0 else analyse(   # the scene's own: made once
            build(raw[0], raw[1], raw[2], scene, raw[4]), collocation=False,
            sensitivity=False).table
        assert row["outputs"] == [table["optimal"]["T_mean_J"], table["linear"]["T_ratio"],
                                  table["linear"]["max_sway_deg"]]
    fast, slow = done[0]["outputs"], done[1]["outputs"]
    assert fast[0] / slow[0] == pytest.approx(4.0, rel=1e-12)
    assert fast[1] == pytest.approx(slow[1], rel=1e-12)      # the shape of a law: t_k-free


def test_figures_are_the_documented_ones(luff_table):
    from cranefe.analysis.luffing.analysis import FIGURES
    assert all(tuple(figs) == FIGURES for figs in luff_table.values())


@pytest.mark.parametrize("base, param, output, entry, message", [
    (BASE, "masses.H", "luffing.optimal.T_mean_J", "outputs[0]", "needs a luffing scene"),
    (LUFF, "analysis.t_k", "luffing.fastest.T_mean_J", "outputs[0]", "unknown law"),
    (LUFF, "analysis.t_k", "luffing.optimal.energy", "outputs[0]", "unknown figure"),
    (LUFF, "analysis.t_k", "phi2.hoist", "outputs[0]", "needs a transient scene"),
    (os.path.join(ROOT, "models", "two_mass_hoist_lift.yaml"), "masses.H",
     "phi2.nope", "outputs[0]", "has no rope 'nope'"),
    (BASE, "analysis.t_k", "frequency_hz.1", "parameters.analysis.t_k", "has no"),
    (LUFF, "analysis.nope", "frequency_hz.1", "parameters.analysis.nope", "has no"),
])
def test_outputs_and_parameters_checked_against_the_base(tmp_path, capsys, base, param,
                                                         output, entry, message):
    path = tmp_path / "bad.yaml"
    path.write_text(f"cranefe: 1\nbase: {base}\nparameters:\n  {param}: {{values: [1]}}\n"
                    f"outputs: [{output}]\n")
    assert main(["sweep", str(path)]) == 2
    err = capsys.readouterr().err
    assert entry in err and message in err and "Traceback" not in err


def test_scene_effects_parameter(tmp_path):
    # effects.rope_mass set by the scene is swept in the scene (it overrides the model)
    scene = tmp_path / "scene.yaml"
    scene.write_text(f"cranefe: 1\nmodel: {BASE}\neffects: {{rope_mass: 2}}\n")
    path = tmp_path / "e.yaml"
    path.write_text(f"cranefe: 1\nbase: {scene}\nparameters:\n"
                    "  effects.rope_mass: {values: [2, 8]}\noutputs: [dofs]\noutput: e.h5\n")
    sweep = load_sweep(path)
    assert sweep.parameters[0].scene
    done = run_sweep(sweep, workers=0)
    model = load(BASE)
    assert [done[i]["outputs"][0] for i in range(2)] == [
        float(modes(model.with_effects(rope_mass=n)).dofs) for n in (2, 8)]


# ------------------------------------------------------------- the examples

PINNED_SWEEPS = {   # (output, its largest value over the sweep), pinned from this version
    "hoist_rope_and_load.yaml": ("frequency_hz.2", 8.29248828),
    "portal_crane_luffing_time.yaml": ("luffing.optimal.T_mean_J", 24585.5822),
    "hammerhead_load_chart.yaml": ("factors.phi2", 2.47806858),
}


# The variants run by default of the slower examples (0.5-1 s each): the first, the one
# of the pinned largest value and the last (the grid's opposite corners); the whole grid
# with `pytest -m slow` (18 variants each, 10 and 13 s under load without numba).
SWEEP_CORNERS = {
    "portal_crane_luffing_time.yaml": [0, 17],          # t_k 15 s, rope 8 m: the largest
    "hammerhead_load_chart.yaml": [0, 13, 17],          # 40 m, 2250 kg, 25 m: the largest
}
SWEEP_EXAMPLES = sorted(glob.glob(os.path.join(ROOT, "models", "sweeps", "*.yaml")))


def _example_sweep(path, tmp_path, corners):
    from dataclasses import replace
    sweep = replace(load_sweep(path), output=str(tmp_path / "t.h5"))
    if corners is not None:
        sweep = replace(sweep, variants=sweep.variants[corners])
    done = run_sweep(sweep, workers=0)
    assert len(done) == len(sweep.variants)
    assert all(r["status"] == "ok" for r in done.values())
    output, top = PINNED_SWEEPS[os.path.basename(path)]
    k = sweep.outputs.index(output)
    assert max(r["outputs"][k] for r in done.values()) == pytest.approx(top, rel=1e-6)
    return sweep, done


@pytest.mark.parametrize("path", SWEEP_EXAMPLES, ids=os.path.basename)
def test_example_sweeps(path, tmp_path):
    """Each example sweep runs (the corners of the two slow ones' grids, every variant of
    the others) and its largest pinned output is the pinned one; the luffing sweep's
    optimum energy falls as 1/t_k^2 (eq. 16, T = S^2 / (2 t_k^2)) between its corners,
    whatever the rope."""
    sweep, done = _example_sweep(path, tmp_path, SWEEP_CORNERS.get(os.path.basename(path)))
    if os.path.basename(path) == "portal_crane_luffing_time.yaml":
        (t0, _), (t1, _) = sweep.variants
        assert done[0]["outputs"][0] / done[1]["outputs"][0] == pytest.approx(
            (t1 / t0) ** 2, rel=1e-9)


@pytest.mark.slow
@pytest.mark.parametrize("path", sorted(SWEEP_CORNERS), ids=str)
def test_example_sweeps_every_variant(path, tmp_path):
    """The whole grid of the slow example sweeps (test_example_sweeps runs its corners)."""
    _example_sweep(os.path.join(ROOT, "models", "sweeps", path), tmp_path, None)


def test_a_sweep_stopped_before_any_result_writes_an_empty_table(tmp_path):
    # the table of no rows once failed to reshape, hiding why the sweep stopped
    sweep = load_sweep(sweep_file(tmp_path))
    assert run_sweep(sweep, workers=0, limit=0) == {}
    table = read_table(sweep.output)
    assert table.values.shape == (0, 2) and table.results.shape == (0, 4)
