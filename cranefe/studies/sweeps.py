"""Sweep throughput: variants per second of a realistic crane, serial and parallel."""

import os
import tempfile
import time

from ._common import write_csv

DESCRIPTION = "sweep throughput: serial loop, 1 and 2 worker processes, Dask, DOF-map reuse"
MODEL = os.path.join(os.path.dirname(__file__), "..", "..", "models",
                     "hammerhead_tower_crane.yaml")


def _spec(folder, n_ea, name):
    path = os.path.join(folder, f"{name}.yaml")
    with open(path, "w") as fh:
        fh.write(f"""cranefe: 1
sweep: hammerhead tower crane, {name}
base: {os.path.abspath(MODEL)}
parameters:
  ropes.hoist_rope.EA: {{range: [1.0e7, 3.0e7], count: {n_ea}}}
  masses.HOOK: {{range: [2000, 12000], count: 4}}
  springs.1.stiffness: {{range: [2.0e8, 6.0e8], count: 3}}
outputs: [frequency_hz.1, frequency_hz.3, frequency_hz.6]
output: {name}.h5
""")
    return path


def run(outdir, quick=False):
    from ..sweeps.engine import run_sweep
    from ..sweeps.spec import load_sweep
    n_ea = 2 if quick else 80                      # x 4 x 3 variants
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        cases = [("serial loop, DOF map rebuilt", dict(workers=0, reuse=False)),
                 ("serial loop, DOF map reused", dict(workers=0, reuse=True)),
                 ("1 worker process", dict(workers=1)),
                 ("2 worker processes", dict(workers=2))]
        for k, (label, kw) in enumerate(cases):
            sweep = load_sweep(_spec(tmp, n_ea, f"s{k}"))
            t0 = time.perf_counter()
            done = run_sweep(sweep, **kw)
            t = time.perf_counter() - t0
            rows.append((label, len(done), t))
        try:
            import distributed
            with distributed.LocalCluster(n_workers=2, threads_per_worker=1,
                                          dashboard_address=None) as cluster, \
                    distributed.Client(cluster) as client:
                sweep = load_sweep(_spec(tmp, n_ea, "dask"))
                t0 = time.perf_counter()
                done = run_sweep(sweep, scheduler=client)
                rows.append(("Dask LocalCluster, 2 workers", len(done),
                             time.perf_counter() - t0))
        except ImportError:
            pass
    base = rows[1][1] / rows[1][2]
    return [write_csv(outdir, "sweep_throughput.csv", [
        {"engine": label, "variants": n, "seconds": round(t, 3),
         "variants_per_s": round(n / t, 1), "speedup_vs_serial": round(n / t / base, 2)}
        for label, n, t in rows])]
