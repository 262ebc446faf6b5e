"""Design loads (docs/loads.md): the hammerhead tower crane's load table (EN 13001-2
factors from `cranefe loads`) and its dynamic load chart over radius x hook load x hook
height as a sweep, with the chart's throughput serial and with 2 worker processes.

Writes results/loads_table.csv (factor, case, computed, standard, from), loads_chart.csv
(every variant), loads_chart_*_map.png/.csv (heat maps), loads_throughput.csv."""

import os
import shutil
import tempfile
import time

from ._common import write_csv

DESCRIPTION = "EN 13001-2 load table of the hammerhead; load chart sweep and its throughput"
MODELS = os.path.join(os.path.dirname(__file__), "..", "..", "models")
CHART = ("analysis.radius", "masses.HOOK", "analysis.hook_height")


def _sweep(folder, values, name):
    """A copy of models/sweeps/hammerhead_load_chart.yaml with these grid values."""
    base = os.path.abspath(os.path.join(MODELS, "loads", "hammerhead_load_chart.yaml"))
    params = "\n".join(f"  {p}: {{values: {list(v)}}}" for p, v in zip(CHART, values))
    path = os.path.join(folder, f"{name}.yaml")
    with open(path, "w") as fh:
        fh.write(f"cranefe: 1\nsweep: Hammerhead load chart\nbase: {base}\n"
                 f"parameters:\n{params}\n"
                 "outputs: [factors.phi2, factors.phi5.hoist, frequency_hz.1, "
                 "frequency_hz.3]\nmodes: 6\n"
                 f"output: {name}.h5\n")
    return path


def run(outdir, quick=False):
    from ..api import loads
    from ..sweeps.engine import run_sweep
    from ..sweeps.plots import heat_maps
    from ..sweeps.spec import load_sweep
    from ..sweeps.summary import summarise
    paths = []
    table = loads(os.path.join(MODELS, "loads", "two_mass_hoist_loads.yaml" if quick
                               else "hammerhead_loads.yaml"))
    rows = [{"factor": f, "case": c, "computed": "" if v is None else v,
             "standard": "" if s is None else s, "from": src}
            for f, c, v, s, src in table.rows()]
    paths.append(write_csv(outdir, "loads_table.csv", rows))
    values = ([10.0, 40.0], [8250], [10.0]) if quick else \
        ([10.0, 25.0, 40.0], [2250, 4250, 8250], [5.0, 25.0])
    timing = []
    with tempfile.TemporaryDirectory() as tmp:
        run_sweep(load_sweep(_sweep(tmp, ([25.0], [8250], [10.0]), "warm-up")),
                  workers=0)                                   # imports, caches
        for label, workers in (("serial", 0), ("2 worker processes", 2)):
            sweep = load_sweep(_sweep(tmp, values, f"chart{workers}"))
            t0 = time.perf_counter()
            done = run_sweep(sweep, workers=workers)
            sec = time.perf_counter() - t0
            timing.append({"engine": label, "variants": len(done), "seconds": sec,
                           "variants_per_s": len(done) / sec})
        chart = summarise(sweep, done).table
        rows = [dict(zip(chart.parameters, v), **dict(zip(chart.outputs, r)), status=s)
                for v, r, s in zip(chart.values, chart.results, chart.status)]
        paths.append(write_csv(outdir, "loads_chart.csv", rows))
        maps = heat_maps(chart, tmp, prefix="loads_chart_")
        for p in maps:
            target = os.path.join(outdir, os.path.basename(p))
            shutil.copyfile(p, target)
            paths.append(target)
    for t in timing:
        t["speedup"] = t["variants_per_s"] / timing[0]["variants_per_s"]
    paths.append(write_csv(outdir, "loads_throughput.csv", timing))
    return paths
