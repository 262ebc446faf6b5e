"""Simulate a transient scene: hoist start, lifting a load off the ground, motor torque."""

HELP = "simulate a transient scene (docs/transient.md)"


def add_arguments(p):
    p.add_argument("file", help="scene file with analysis: {type: transient, ...}")
    p.add_argument("--json", action="store_true", help="print one JSON document")
    p.add_argument("--csv", metavar="OUT.csv", help="time histories (rope forces, drums)")
    p.add_argument("--archive", metavar="OUT.h5", help="write an HDF5 result archive")
    p.add_argument("--xdmf", metavar="OUT.xdmf", help="displacements as an XDMF time series")
    p.add_argument("--plots", metavar="DIR", help="PNG plots of rope forces and drum speeds")


def run(args):
    import sys

    from rich.progress import Progress

    from ..model import load
    from ..report import dumps, transient_document, transient_table
    from ..transient.integrate import simulate
    model = load(args.file)
    with Progress(transient=True, disable=not sys.stderr.isatty()) as bar:
        task = bar.add_task("simulating", total=None)
        result = simulate(model, progress=lambda k, n: bar.update(task, completed=k,
                                                                   total=n))
    print(dumps(transient_document(result)) if args.json else transient_table(result))
    written = []
    if args.csv:
        from ..transient.output import write_csv
        written.append(write_csv(args.csv, result))
    if args.archive or args.xdmf:
        from ..assemble import assemble
        system = assemble(model)
        if args.archive:
            from .. import archive
            written.append(archive.write(args.archive, model, system, {"transient": result},
                                         command=["cranefe"] + args.argv,
                                         timings=result.timings))
        if args.xdmf:
            from ..mesh import point_displacements
            from ..paraview import write_xdmf_series
            disp = point_displacements(system.dofs, result.q.T)
            written.append(write_xdmf_series(args.xdmf, model, system.dofs, result.times,
                                             {"displacement": disp}))
    if args.plots:
        from ..transient.output import plot
        written += plot(args.plots, result)
    for path in written:
        print(f"wrote {path}", file=sys.stderr)
    return 0
