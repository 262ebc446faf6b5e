"""Dynamic factors of EN 13001-2 (phi1-phi7) computed from simulations of the crane
itself: lift-off at each hoist drive class's speed, release of a part of the load, the
start of every drive, each beside the standard's simplified value (docs/loads.md).

FILE is a model, a transient scene (its drum speed is the full hoisting speed) or a
loads scene with 'analysis: {type: loads, ...}'."""

HELP = "dynamic factors phi1-phi7 of EN 13001-2 from simulations (docs/loads.md)"


def add_arguments(p):
    p.add_argument("file", help="model, transient scene or loads scene (YAML)")
    p.add_argument("--json", action="store_true", help="print one JSON document")
    p.add_argument("--shapers", metavar="LIST", help="also run every trolley, slewing and "
                   "luffing move shaped by these input shapers, e.g. ZV,ZVD,EI "
                   "(frequencies from the crane's own modes; docs/shaping.md)")


def run(args):
    from ..api import loads
    from ..outputs.report import dumps
    shapers = ()
    if args.shapers:
        from ..analysis.shaping.shapers import SHAPERS
        kinds = [k for k in SHAPERS if k != "unshaped"]
        shapers = tuple(k.strip().upper() for k in args.shapers.split(",") if k.strip())
        bad = [k for k in shapers if k not in kinds]
        if bad or not shapers:
            from ..errors import ModelError
            raise ModelError(f"unknown shaper(s) {', '.join(bad) or '(none)'}; give a "
                             f"comma-separated list of {', '.join(kinds)}", None,
                             "--shapers")
    result = loads(args.file, shapers=shapers)
    print(dumps(result.to_dict()) if args.json else result.table())
    return 0
