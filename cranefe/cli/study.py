"""Run a study (error against exact answers versus time) and write its tables and plots."""

HELP = "run a study into results/ (CSV + PNG)"


def add_arguments(p):
    from ..studies import NAMES
    p.add_argument("name", choices=NAMES + ("all",), help="which study")
    p.add_argument("--out", default="results", help="output folder (default: results)")
    p.add_argument("--quick", action="store_true", help="small sizes (for tests)")


def run(args):
    from importlib import import_module

    from ..outpaths import Plan, make_folder
    from ..studies import NAMES
    make_folder(Plan().folder("--out", args.out), "--out")
    for name in NAMES if args.name == "all" else (args.name,):
        mod = import_module(f"..studies.{name}", __package__)
        for path in mod.run(args.out, quick=args.quick):
            print(path)
    return 0
