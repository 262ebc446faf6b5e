"""Simulate a transient scene: hoist start, lifting a load off the ground, slack ropes.

Prints the peak rope forces and dynamic factors (phi2 of EN 13001-2), drum speeds and
torques, lift-off times and the energy balance; writes time histories on request.
The keys of `analysis: {type: transient, ...}` are in docs/transient.md.
"""

import sys
import time

HELP = ("simulate a transient scene (rope forces, dynamic factors, lift-off; "
        "docs/transient.md) or an operation scene (large motions; docs/operations.md)")
PROGRESS_AFTER = 2.0       # s: a progress bar appears for runs longer than this


def add_arguments(p):
    p.add_argument("file", help="scene file with analysis: {type: transient, ...} or "
                   "{type: operation, ...}")
    p.add_argument("--json", action="store_true", help="print one JSON document")
    p.add_argument("--csv", metavar="OUT.csv", help="time histories (rope forces, drums, "
                   "load displacements, ground forces)")
    p.add_argument("--archive", metavar="OUT.h5", help="write an HDF5 result archive")
    p.add_argument("--xdmf", metavar="OUT.xdmf", help="displacements as an XDMF time "
                   "series for ParaView")
    p.add_argument("--plots", metavar="DIR", help="PNG plot of the histories (DIR/transient.png)")
    from ._outputs import add_animation_arguments, add_member_force_arguments
    add_member_force_arguments(p)
    add_animation_arguments(p)


class _Progress:
    """A rich progress bar on stderr that appears only once a run passes
    PROGRESS_AFTER seconds (and only on a terminal)."""

    def __init__(self):
        self.t0 = time.perf_counter()
        self.bar = None
        self.task = None
        self.enabled = sys.stderr.isatty()

    def __call__(self, t, duration):
        if not self.enabled:
            return
        if self.bar is None:
            if time.perf_counter() - self.t0 < PROGRESS_AFTER:
                return
            from rich.progress import Progress
            self.bar = Progress(transient=True)
            self.bar.start()
            self.task = self.bar.add_task("simulating", total=duration)
        self.bar.update(self.task, completed=t)

    def close(self):
        if self.bar is not None:
            self.bar.stop()


def run_operation(args, model):
    """An operation scene (docs/operations.md): large motions of the drives."""
    from ..errors import AnalysisError
    from ..analysis.operation.integrate import simulate
    from ..analysis.operation.output import plot, table
    from ..outputs.report import dumps
    if args.xdmf:
        from ..errors import ModelError
        raise ModelError("--xdmf is not written for operation scenes yet; use --archive, "
                         "--json, --csv, --plots or --animate")
    progress = _Progress()
    failed = None
    try:
        result = simulate(model, progress=progress)
    except AnalysisError as exc:
        failed, result = exc, getattr(exc, "result", None)
        if result is None:
            raise
    finally:
        progress.close()
    print(dumps(result.to_dict()) if args.json else table(result))
    written = []
    if args.csv:
        from ..outputs.histories import write_operation_csv
        written.append(write_operation_csv(args.csv, result, model))
    if args.plots:
        written += plot(args.plots, result)
    written += _operation_outputs(args, model, result)
    for path in written:
        print(f"wrote {path}", file=sys.stderr)
    if failed is not None:
        raise failed
    return 0


def _member_force_envelope(model, result):
    """Envelope of the members' end forces over the run's output times (None without
    flexible members): the static state plus the run's displacements."""
    from ..statics import solve_static
    from ..system import assemble
    from ..outputs.member_forces import transient_envelope
    system = assemble(model)
    mm = system.dofs.members
    if mm is None or not len(mm.member):
        return None
    return transient_envelope(model, system.dofs, solve_static(model).u, result.q)


def _operation_outputs(args, model, result):
    """--archive of an operation run (also of a run that failed part-way: what it
    computed, with its status); no coordinates or matrices, as for luffing."""
    written = []
    if args.archive is not None:
        from ..outputs import archive
        written.append(archive.write(args.archive, model, None, {"operation": result},
                                     command=["cranefe"] + args.argv,
                                     timings=result.timings))
    if args.animate is not None and len(result.times):
        from ..outputs.movie import animate_operation
        from ._outputs import image_size
        written.append(animate_operation(args.animate, model, result,
                                         size=image_size(args), view=args.view))
    return written


def run(args):
    from ..model import load
    from ..outputs.report import dumps
    from ..analysis.transient.integrate import simulate
    from ..analysis.transient.output import document, table
    from ._outputs import check_outputs
    model = load(args.file)
    check_outputs(args, model)
    if model.analysis.get("type") == "operation":
        if getattr(args, "member_forces", False):
            from ..errors import ModelError
            raise ModelError("--member-forces is not computed for operation scenes yet; "
                             "use it with a transient scene", args.file)
        return run_operation(args, model)
    if args.animate is not None:
        from ..errors import ModelError
        raise ModelError("--animate draws operation scenes (analysis: {type: operation}); "
                         "for a transient scene use --plots or --xdmf")
    progress = _Progress()
    try:
        result = simulate(model, progress=progress)
    finally:
        progress.close()
    doc = document(result)
    envelope = None
    if getattr(args, "member_forces", False):
        envelope = _member_force_envelope(model, result)
        if envelope is not None:
            doc["member_forces"] = envelope.to_dict()
    print(dumps(doc) if args.json else table(result))
    written = []
    system = None
    if args.archive is not None or args.xdmf is not None or (
            model.bodies and (args.csv is not None or args.plots is not None)):
        from ..system import assemble
        system = assemble(model)
    if args.csv is not None:
        from ..outputs.histories import write_transient_csv
        written.append(write_transient_csv(args.csv, result, model,
                                           system.dofs if system is not None else None))
    if args.archive is not None or args.xdmf is not None:
        if args.archive is not None:
            from ..outputs import archive
            results = {"transient": result}
            if envelope is not None:
                results["member_forces"] = envelope
            written.append(archive.write(args.archive, model, system, results,
                                         command=["cranefe"] + args.argv,
                                         timings=result.timings))
        if args.xdmf is not None:
            from ..outputs.mesh import point_displacements
            from ..outputs.paraview import write_xdmf_series
            disp = point_displacements(system.dofs, result.q.T)
            per_time = None
            if getattr(args, "member_forces", False) and system.dofs.members is not None \
                    and len(system.dofs.members.member):
                from ..statics import solve_static
                from ..outputs.member_forces import run_member_forces
                per_time = run_member_forces(model, system.dofs, solve_static(model).u,
                                             result.q)
            written.append(write_xdmf_series(args.xdmf, model, system.dofs, result.times,
                                             {"displacement": disp},
                                             member_forces=per_time))
    if args.plots is not None:
        from ..analysis.transient.output import plot
        written += plot(args.plots, result)
        if system is not None:
            from ..outputs.histories import plot_bodies
            written += plot_bodies(args.plots, result, model, system.dofs)
    for path in written:
        print(f"wrote {path}", file=sys.stderr)
    return 0
