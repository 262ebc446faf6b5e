"""Summarise a cranefe HDF5 archive: what is in it and every result it holds (modes,
damping, transient, luffing, operation), each as the command that made it prints it."""

HELP = "summarise an archive (.h5)"


def add_arguments(p):
    p.add_argument("file", help="archive written with --archive")
    p.add_argument("--json", action="store_true", help="print one JSON document")


def _read_any(path):
    """An archive or a sweep table (run through `archive.guarded`)."""
    from ..outputs.archive import _read
    from ..sweeps.table import _read_table, is_sweep
    return _read_table(path) if is_sweep(path) else _read(path)


def _presenters():
    """class name -> (table, JSON document) of a result, as its command prints them."""
    from ..analysis.luffing.report import luffing_document, luffing_table
    from ..analysis.operation.output import table as operation_table
    from ..analysis.transient.output import document as transient_document
    from ..analysis.transient.output import table as transient_table
    from ..outputs.report import (damping_modes_document, damping_modes_table,
                                  modes_document, modes_table)
    return {"ModalResult": (modes_table, modes_document),
            "DampingResult": (damping_modes_table, damping_modes_document),
            "TransientResult": (transient_table, transient_document),
            "LuffingResult": (luffing_table, luffing_document),
            "OperationResult": (operation_table, lambda r: r.to_dict()),
            "MemberForces": (lambda r: r.table(), lambda r: r.summary())}


def _present(name, result, presenters):
    """(text, document) of one result; a result of a class this cranefe does not know
    (a dict of its fields) is listed by its fields."""
    kind = type(result).__name__
    if kind in presenters:
        table, document = presenters[kind]
        return f"results/{name} ({kind}):\n{table(result)}", document(result)
    fields = sorted(result) if isinstance(result, dict) else []
    return (f"results/{name}: a result this cranefe does not know, fields: "
            f"{', '.join(fields)}", {"fields": fields})


def run(args):
    from ..outputs.archive import guarded
    from ..outputs.report import dumps, modes_document
    from ..sweeps.table import SweepTable
    arc = guarded(_read_any, args.file)
    if isinstance(arc, SweepTable):
        return _show_sweep(args, arc)
    meta = {k: v for k, v in arc.meta.items() if k != "timings"}
    modal = arc.results.get("modes")
    presenters = _presenters()
    shown = {name: _present(name, r, presenters) for name, r in arc.results.items()}
    if args.json:
        doc = {"file": arc.path, "meta": meta, "model": arc.model["name"],
               "effects": arc.effects, "dofs": len(arc.labels),
               "results": sorted(arc.results), "timings_s": arc.meta["timings"],
               "documents": {name: d for name, (_, d) in shown.items()}}
        if type(modal).__name__ == "ModalResult":
            doc["modes"] = modes_document(modal)["modes"]
        print(dumps(doc))
        return 0
    print(f"{arc.path}: {meta['format']} v{meta['format_version']}, cranefe "
          f"{meta['cranefe_version']}, {meta['created']}")
    print(f"  command: {meta['command']}")
    print(f"  model: {arc.model['name']} ({arc.model['file']}), "
          f"{len(arc.model['node_names'])} nodes, {len(arc.mesh.lines)} line cells")
    if arc.K is not None:
        print(f"  coordinates: {len(arc.labels)}; K and M: {arc.K.shape[0]}x{arc.K.shape[1]},"
              f" {arc.K.nnz} and {arc.M.nnz} non-zeros")
    print(f"  results: {', '.join(sorted(arc.results)) or 'none'}")
    for name, (text, _) in shown.items():
        print()
        print(text)
    return 0


def _show_sweep(args, t):
    import numpy as np

    from ..outputs.report import dumps
    ok = np.array([s == "ok" for s in t.status], dtype=bool)
    doc = {"file": args.file, "sweep": t.name, "variants": t.total, "done": len(t.index),
           "failed": int((~ok).sum()), "parameters": list(t.parameters),
           "outputs": {o: {"min": float(np.nanmin(t.results[ok, k])),
                           "max": float(np.nanmax(t.results[ok, k]))} if ok.any() else None
                       for k, o in enumerate(t.outputs)}}
    if args.json:
        print(dumps(doc))
        return 0
    print(f"{args.file}: sweep '{t.name}', {len(t.index)}/{t.total} variants done, "
          f"{doc['failed']} failed")
    print(f"  parameters: {', '.join(t.parameters)}")
    for o, mm in doc["outputs"].items():
        if mm:
            print(f"  {o}: {mm['min']:.6g} .. {mm['max']:.6g}")
    for i, s, e in zip(t.index, t.status, t.errors):
        if s != "ok":
            print(f"  variant {i} failed: {e}")
    return 0
