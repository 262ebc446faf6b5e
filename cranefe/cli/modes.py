"""Natural frequencies and mode shapes of a model or scene."""

from ._outputs import add_output_arguments, check_outputs, write_outputs
from ._outputs import add_member_force_arguments

HELP = "natural frequencies and modes"


def add_arguments(p):
    p.add_argument("file", help="model or scene file (YAML)")
    p.add_argument("--count", type=int, default=None, help="number of modes (default: all "
                   "for small models, 10 for large ones, or the scene's count)")
    p.add_argument("--json", action="store_true", help="print one JSON document")
    p.add_argument("--solver", choices=("auto", "dense", "sparse"), default="auto")
    add_member_force_arguments(p, modes=True)
    add_output_arguments(p)
    p.add_argument("--color", choices=("displacement", "stress"), default="displacement",
                   help="with --images: colour the deformed crane by the relative "
                   "displacement (default) or the members by their extreme-fibre stress "
                   "in the mode, scaled as --member-forces-scale says")


def run(args):
    from ..system import assemble
    from ..model import load
    from ..analysis.modal import drive_reduction, modes
    from ..outputs.report import dumps, modes_document, modes_table
    import time
    t0 = time.perf_counter()
    if args.count is not None and args.count < 1:        # as `cranefe damping`
        from ..errors import ModelError
        raise ModelError(f"--count {args.count}: ask for at least one mode")
    model = load(args.file)
    t_load = time.perf_counter() - t0
    check_outputs(args, model)
    colour = getattr(args, "color", "displacement")
    if colour == "stress" and not args.images:
        from ..errors import ModelError
        raise ModelError("--color stress colours the pictures: give --images DIR")
    count = args.count or model.analysis.get("count")
    system = assemble(model)
    result = modes(model, count=count, solver=args.solver, system=system)
    result.timings = {"load": t_load, **result.timings,
                      "total": time.perf_counter() - t0}
    comparison = drive_reduction(model, result) if model.effects.drive == "reduced" else None
    results = {"modes": result}
    if model.effects.damping != "none":        # a scene asking for damping gets it too
        from ..analysis.damping import damping, partner_modes
        # with the coupling partners beyond the modes shown, as `cranefe damping`
        modal, shown = partner_modes(model, system, len(result.omega))
        results["damping"] = damping(model, model.effects.damping, shown, system=system,
                                     modal=modal)
    member_forces = None
    if getattr(args, "member_forces", False) or colour == "stress":
        from ..outputs.member_forces import modal_member_forces
        mm = system.dofs.members
        if mm is not None and len(mm.member):
            member_forces = modal_member_forces(model, system.dofs, result.shapes,
                                                result.node_shapes, args.member_forces_scale)
        elif colour == "stress":
            from ..errors import ModelError
            raise ModelError("--color stress colours members, and this model has none "
                             "as finite elements (members with effects: {structure: "
                             "flexible})", args.file)
    if getattr(args, "member_forces", False) and member_forces is not None:
        results["member_forces"] = member_forces            # the archive's group
    if args.json:
        doc = modes_document(result, comparison)
        if "member_forces" in results:
            doc["member_forces"] = member_forces.to_dict()
        if "damping" in results:
            from ..outputs.report import damping_document
            doc["damping"] = damping_document(results["damping"])["modes"]
            doc["warnings"] += [w for w in results["damping"].warnings
                                if w not in doc["warnings"]]
        print(dumps(doc))
    else:
        print(modes_table(result, comparison))
        if "damping" in results:
            from ..outputs.report import damping_table
            print(damping_table(results["damping"]))
    write_outputs(args, model, system, results, result,
                  member_forces=results.get("member_forces"),
                  colour_forces=member_forces if colour == "stress" else None)
    return 0
