"""Damping of the modes from the elements' absorption coefficients psi (Heletiy 2016,
eq. 11-17; docs/damping.md): the decoupled estimate with Hasselman's coupling
coefficients, and the exact complex solutions (viscous, each mode's own B; and complex
stiffness). --method: modal (the estimate), exact or both (also the exact solutions),
auto (the estimate, solved exactly where the coupling criterion fails; the default).
A scene sets the method by analysis.method or effects.damping."""

from ._outputs import add_output_arguments, check_outputs, write_outputs

HELP = "damping ratios from absorption coefficients (decoupled and exact)"


def add_arguments(p):
    p.add_argument("file", help="model or scene file (YAML)")
    p.add_argument("--method", choices=("modal", "exact", "both", "auto"), default=None,
                   help="modal: decoupled estimate; exact / both: also the complex "
                   "eigensolutions; auto: exact where Hasselman's criterion fails "
                   "(default, or the scene's analysis.method / effects.damping)")
    p.add_argument("--count", type=int, default=None,
                   help="number of modes, rigid ones included (default: as cranefe modes, "
                   "or the scene's count)")
    p.add_argument("--json", action="store_true", help="print one JSON document")
    add_output_arguments(p)


def run(args):
    import time

    from ..system import assemble
    from ..analysis.damping import damping, first_modes, partner_modes, scene_method
    from ..errors import ModelError
    from ..model import load
    from ..outputs.report import damping_modes_document, damping_modes_table, dumps
    t0 = time.perf_counter()
    if args.count is not None and args.count < 1:
        raise ModelError(f"--count {args.count}: ask for at least one mode")
    model = load(args.file)
    t_load = time.perf_counter() - t0
    check_outputs(args, model)
    method = args.method or scene_method(model)
    count = args.count or model.analysis.get("count")
    system = assemble(model)
    t1 = time.perf_counter()
    modal, shown = partner_modes(model, system, count)
    t_modes = time.perf_counter() - t1
    result = damping(model, method, shown, system=system, modal=modal)
    result.timings = {"load": t_load, **result.timings, "assemble": system.timings[
        "assemble"], "modes": t_modes, "total": time.perf_counter() - t0}
    if args.json:
        print(dumps(damping_modes_document(result)))
    else:
        print(damping_modes_table(result))
    shown_modes = first_modes(modal, len(result.omega))   # outputs: the reported ones
    write_outputs(args, model, system, {"modes": shown_modes, "damping": result},
                  shown_modes)
    return 0
