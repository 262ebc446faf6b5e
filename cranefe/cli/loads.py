"""Dynamic factors of EN 13001-2 (phi1-phi7) computed from simulations of the crane
itself: lift-off at each hoist drive class's speed, release of a part of the load, the
start of every drive, each beside the standard's simplified value (docs/loads.md).

FILE is a model, a transient scene (its drum speed is the full hoisting speed) or a
loads scene with 'analysis: {type: loads, ...}'."""

HELP = "dynamic factors phi1-phi7 of EN 13001-2 from simulations (docs/loads.md)"


def add_arguments(p):
    p.add_argument("file", help="model, transient scene or loads scene (YAML)")
    p.add_argument("--json", action="store_true", help="print one JSON document")


def run(args):
    from ..api import loads
    from ..outputs.report import dumps
    result = loads(args.file)
    print(dumps(result.to_dict()) if args.json else result.table())
    return 0
