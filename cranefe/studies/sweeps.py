"""Sweep throughput: variants per second of a realistic crane, serial and parallel, and
what reusing the structure's work (cranefe.assembly.reuse) saves per variant."""

import contextlib
import os
import tempfile
import time

from ._common import pyplot, save, write_csv

DESCRIPTION = "sweep throughput: serial loop, 1 and 2 worker processes, Dask; reuse gain"
MODELS = os.path.join(os.path.dirname(__file__), "..", "..", "models")
# the hammerhead tower crane with massless ropes (7 coordinates), and with 20 elements
# per fall of its ropes (413 coordinates: hoist-rope dynamics)
CRANES = (("hammerhead, massless ropes", {}), ("hammerhead, rope_mass: 20",
                                               {"rope_mass": 20}))


def _base(folder, effects):
    model = os.path.abspath(os.path.join(MODELS, "hammerhead_tower_crane.yaml"))
    if not effects:
        return model
    path = os.path.join(folder, "scene.yaml")
    with open(path, "w") as fh:
        fh.write(f"cranefe: 1\nmodel: {model}\neffects: {effects}\n".replace("'", ""))
    return path


def _spec(folder, base, n_ea, name, grid=(4, 3)):
    """A sweep of n_ea x grid[0] hook masses x grid[1] spring stiffnesses."""
    path = os.path.join(folder, f"{name}.yaml")
    with open(path, "w") as fh:
        fh.write(f"""cranefe: 1
sweep: hammerhead tower crane, {name}
base: {base}
parameters:
  ropes.hoist_rope.EA: {{range: [1.0e7, 3.0e7], count: {n_ea}}}
  masses.HOOK: {{range: [2000, 12000], count: {grid[0]}}}
  springs.1.stiffness: {{range: [2.0e8, 6.0e8], count: {grid[1]}}}
outputs: [frequency_hz.1, frequency_hz.3, frequency_hz.6]
output: {name}.h5
""")
    return path


def _throughput(folder, crane, base, n_ea, grid, client):
    """(crane, engine, variants, seconds) of each engine on the same sweep; Dask on
    `client` (None: not installed)."""
    from ..sweeps.engine import run_sweep
    from ..sweeps.evaluate import REUSE
    from ..sweeps.spec import load_sweep
    rows = []
    run_sweep(load_sweep(_spec(folder, base, 1, "warm-up")), workers=0)   # imports, caches
    engines = [("serial loop, nothing reused", dict(workers=0, reuse=False)),
               ("serial loop, structure reused", dict(workers=0, reuse=True)),
               ("1 worker process", dict(workers=1)),
               ("2 worker processes", dict(workers=2))]
    for k, (label, kw) in enumerate(engines):
        sweep = load_sweep(_spec(folder, base, n_ea, f"s{k}", grid))
        REUSE.clear()                        # as a fresh process starts, for the serial loop
        t0 = time.perf_counter()
        done = run_sweep(sweep, **kw)
        rows.append((crane, label, len(done), time.perf_counter() - t0))
    if client is None:
        return rows
    sweep = load_sweep(_spec(folder, base, n_ea, "dask", grid))
    t0 = time.perf_counter()
    done = run_sweep(sweep, scheduler=client)
    rows.append((crane, "Dask LocalCluster, 2 workers", len(done), time.perf_counter() - t0))
    return rows


@contextlib.contextmanager
def _dask_client():
    """One Dask LocalCluster (2 workers) for both cranes (its start, ~2.5 s, outside the
    timings), or None when distributed is not installed."""
    try:
        import distributed
    except ImportError:
        yield None
        return
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        yield client


def _stages(crane, base, n):
    """ms per variant of assembly (with and without reuse), of the modes, and of the
    COO -> CSR conversions inside the assembly, over n variants of the rope EA."""
    from dataclasses import replace

    import importlib
    import pkgutil

    from .. import assembly
    from ..analysis.modal import modes
    from ..assembly.reuse import Reuse
    from ..model import load
    from ..system import assemble
    model = load(base)
    variants = [replace(model, ropes=tuple(replace(r, EA=r.EA * (1 + 0.01 * k))
                                           for r in model.ropes)) for k in range(n)]
    coo, spent = assembly.coo, [0.0]
    # every module of the assembly stage that holds the one COO step under its name
    holders = [m for m in (importlib.import_module(f"{assembly.__name__}.{i.name}")
                           for i in pkgutil.iter_modules(assembly.__path__))
               if getattr(m, "coo", None) is coo]

    def timed(*args):
        t = time.perf_counter()
        try:
            return coo(*args)
        finally:
            spent[0] += time.perf_counter() - t

    out = {}
    for mod in holders:
        mod.coo = timed
    try:
        for label, reuse in (("nothing reused", None), ("structure reused", Reuse())):
            spent[0] = 0.0
            assemble_s = modes_s = 0.0
            for m in variants:
                t0 = time.perf_counter()
                system = assemble(m, reuse=reuse)
                t1 = time.perf_counter()
                modes(m, count=9, system=system)
                assemble_s += t1 - t0
                modes_s += time.perf_counter() - t1
            out[label] = (assemble_s, modes_s, spent[0], reuse)
    finally:
        for mod in holders:
            mod.coo = coo
    rows = []
    for label, (a, m, c, reuse) in out.items():
        rows.append({"crane": crane, "coordinates": system.K.shape[0], "assembly": label,
                     "assemble_ms": 1e3 * a / n, "modes_ms": 1e3 * m / n,
                     "variant_ms": 1e3 * (a + m) / n, "coo_to_csr_ms": 1e3 * c / n,
                     "reuse_hits": "" if reuse is None else
                     " ".join(f"{k}:{v}" for k, v in sorted(reuse.hits.items()))})
    return rows


def run(outdir, quick=False):
    rows, stages = [], []
    with tempfile.TemporaryDirectory() as tmp, _dask_client() as client:
        for k, (crane, effects) in enumerate(CRANES):
            folder = os.path.join(tmp, str(k))       # its own tables, nothing to resume
            os.makedirs(folder)
            base = _base(folder, effects)
            n_ea = (2 if quick else 80) if not effects else (1 if quick else 20)
            grid = (2, 2) if quick else (4, 3)      # quick: 8 and 4 variants per engine
            rows += _throughput(folder, crane, base, n_ea, grid, client)  # n_ea x grid
            stages += _stages(crane, base, 3 if quick else 40)
    table = []
    for crane, label, n, t in rows:
        ref = next(r for r in rows if r[0] == crane and r[1].endswith("structure reused"))
        table.append({"crane": crane, "engine": label, "variants": n, "seconds": round(t, 3),
                      "variants_per_s": round(n / t, 1),
                      "speedup_vs_serial": round(n / t / (ref[2] / ref[3]), 2)})
    paths = [write_csv(outdir, "sweep_throughput.csv", table),
             write_csv(outdir, "sweep_reuse.csv", stages)]
    plt = pyplot()
    fig, axes = plt.subplots(1, len(CRANES), figsize=(11, 3.8))
    for ax, (crane, _) in zip(axes, CRANES):
        mine = [r for r in table if r["crane"] == crane]
        ax.barh([r["engine"] for r in mine], [r["variants_per_s"] for r in mine],
                color="tab:blue")
        ax.invert_yaxis()
        ax.set_xlabel("variants per second")
        ax.set_title(crane, fontsize=10)
        ax.grid(axis="x", alpha=0.3)
    for ax in axes[1:]:
        ax.set_yticklabels([])
    paths.append(save(fig, outdir, "sweep_throughput.png"))
    return paths
