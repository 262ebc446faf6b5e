"""Run a parameter sweep: many variants of one model, locally or on a Dask cluster."""

from ._outputs import count_type, seconds_type

HELP = "run a parameter sweep (docs/sweeps.md)"


def add_arguments(p):
    p.add_argument("file", help="sweep file (YAML)")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--workers", type=count_type(0), default=None,
                   help="local processes (default: all cores; 0 = serial, in this process)")
    g.add_argument("--scheduler", metavar="ADDRESS",
                   help="run on a Dask distributed cluster (e.g. tcp://host:8786)")
    p.add_argument("--scheduler-timeout", metavar="SECONDS", type=seconds_type,
                   default=30.0, help="give up connecting to the scheduler after this "
                   "long (default 30)")
    p.add_argument("--restart", action="store_true",
                   help="start afresh: delete the journal and table of an earlier run on "
                   "the same output (needed when the sweep file or its base changed)")
    p.add_argument("--no-reuse", action="store_true",
                   help="reuse nothing across variants (DOF maps, the static null "
                   "space): for measuring")
    p.add_argument("--plots", metavar="DIR", help="write output-vs-parameter PNGs")
    p.add_argument("--json", action="store_true", help="print a JSON summary")


def run(args):
    import json
    import sys

    from rich.progress import Progress

    from ..sweeps.engine import check_outputs, check_scheduler, run_sweep
    from ..sweeps.spec import load_sweep
    from ..sweeps.summary import summarise
    if args.scheduler is not None:
        check_scheduler(args.scheduler)
    sweep = load_sweep(args.file)
    check_outputs(sweep, args.plots)
    with Progress(transient=True, disable=not sys.stderr.isatty()) as bar:
        task = bar.add_task(sweep.name, total=len(sweep.variants))
        done = run_sweep(sweep, workers=args.workers, scheduler=args.scheduler,
                         reuse=not args.no_reuse, restart=args.restart, plots=args.plots,
                         scheduler_timeout=args.scheduler_timeout,
                         progress=lambda k: bar.advance(task, k))
    run_ = summarise(sweep, done)
    table, failed = run_.table, run_.failed
    if args.plots:
        from ..sweeps.plots import heat_maps, plot_table
        for path in plot_table(table, args.plots) + heat_maps(table, args.plots):
            print(f"wrote {path}", file=sys.stderr)
    summary = run_.to_dict()
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(f"{sweep.name}: {len(done)}/{len(sweep.variants)} variants, {len(failed)} "
              f"failed; table {sweep.output}")
        for o, mm in summary["outputs"].items():
            if mm:
                print(f"  {o}: {mm['min']:.6g} .. {mm['max']:.6g}")
        for i, e in failed[:10]:
            print(f"  variant {i} failed: {e}")
    return 0
