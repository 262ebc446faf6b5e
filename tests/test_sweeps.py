"""Parameter sweeps: local processes and Dask give identical results; an interrupted
sweep resumes with only the missing variants; a failing variant does not stop the rest."""

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
from cranefe.modal import modes
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
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        b = run_sweep(load_sweep(sweep_file(tmp_path, name="b")), scheduler=client)
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
    with open(sweep.output + ".journal") as fh:
        lines = fh.read().splitlines()
    assert len(rest) == 20 and len(lines) == 20           # nothing computed twice
    assert sorted(json.loads(x)["index"] for x in lines) == list(range(20))


def test_killed_sweep_process_resumes(tmp_path):
    path = sweep_file(tmp_path, ea="{range: [1.0e7, 4.0e7], count: 300}", name="k")
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
    assert 20 <= before < 600
    assert main(["sweep", str(path), "--workers", "0"]) == 0
    table = read_table(tmp_path / "k.h5")
    assert table.index.tolist() == list(range(600))
    lines = journal.read_text().splitlines()
    assert len({json.loads(x)["index"] for x in lines if x.strip().endswith("}")}) == 600


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
    assert sorted(os.listdir(tmp_path / "p")) == ["damping_ratio_2.png", "dofs.png",
                                                   "frequency_hz_2.png", "omega_1.png"]
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
