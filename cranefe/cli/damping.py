"""Modal damping from the elements' absorption coefficients: the decoupled (Hasselman)
estimate, the coupling figure, and the exact complex solutions."""

from ._outputs import add_output_arguments, write_outputs

HELP = "damping ratios from absorption coefficients (decoupled and exact)"


def add_arguments(p):
    p.add_argument("file", help="model or scene file (YAML)")
    p.add_argument("--method", choices=("modal", "exact", "both", "auto"), default=None,
                   help="modal: decoupled estimate; exact: complex eigenproblems; both; "
                   "auto (default): exact where Hasselman's criterion fails (a scene's "
                   "effects.damping sets the default)")
    p.add_argument("--count", type=int, default=None, help="number of elastic modes")
    p.add_argument("--json", action="store_true", help="print one JSON document")
    add_output_arguments(p)


def run(args):
    from ..assemble import assemble
    from ..damping import damping
    from ..model import load
    from ..modal import modes
    from ..report import damping_document, damping_table, dumps
    model = load(args.file)
    method = args.method or {"modal": "modal", "exact": "exact"}.get(model.effects.damping,
                                                                     "auto")
    count = args.count or model.analysis.get("count")
    system = assemble(model)
    modal = modes(model, count=None if count is None else count + 6, system=system)
    result = damping(model, method, count, system=system, modal=modal)
    print(dumps(damping_document(result, modal)) if args.json else damping_table(result))
    write_outputs(args, model, system, {"modes": modal, "damping": result}, modal)
    return 0
