"""Energy-optimal luffing of an articulated jib (Loveikin et al. 2013): the optimum of the
mean kinetic energy, the standard laws, motor torque, load sway (docs/luffing.md).

FILE is a scene with 'analysis: {type: luffing, ...}'."""

HELP = "energy-optimal luffing law of a level-luffing jib and a comparison of laws"


def add_arguments(p):
    p.add_argument("file", help="scene file (YAML) with analysis: {type: luffing, ...}")
    p.add_argument("--json", action="store_true", help="print one JSON document")
    p.add_argument("--archive", metavar="OUT.h5", help="write an HDF5 result archive")
    p.add_argument("--plots", metavar="DIR", help="write PNG plots into DIR")
    p.add_argument("--no-sensitivity", action="store_true",
                   help="skip the sensitivity to t_k, load and rope length")


def run(args):
    import sys

    from ..analysis.luffing.analysis import analyse
    from ..analysis.luffing.report import luffing_document, luffing_table
    from ..model import load
    from ..outputs.report import dumps
    from ._outputs import check_outputs
    model = load(args.file)
    check_outputs(args, model)
    result = analyse(model, file=args.file, sensitivity=not args.no_sensitivity)
    if args.json:
        print(dumps(luffing_document(result)))
    else:
        print(luffing_table(result))
    written = []
    if args.archive is not None:
        from ..outputs import archive
        written.append(archive.write(args.archive, model, None, {"luffing": result},
                                     command=["cranefe"] + args.argv,
                                     timings=result.timings))
    if args.plots is not None:
        from ..analysis.luffing.plots import write_plots
        written += write_plots(result, args.plots)
    for path in written:
        print(f"wrote {path}", file=sys.stderr)
    return 0
