"""Summarise a cranefe HDF5 archive: what is in it and its frequency table."""

HELP = "summarise an archive (.h5)"


def add_arguments(p):
    p.add_argument("file", help="archive written with --archive")
    p.add_argument("--json", action="store_true", help="print one JSON document")


def _read_any(path):
    """An archive or a sweep table (run through `archive.guarded`)."""
    from ..outputs.archive import _read
    from ..sweeps.table import _read_table, is_sweep
    return _read_table(path) if is_sweep(path) else _read(path)


def run(args):
    from ..outputs.archive import guarded
    from ..outputs.report import dumps, modes_document, modes_table
    from ..sweeps.table import SweepTable
    arc = guarded(_read_any, args.file)
    if isinstance(arc, SweepTable):
        return _show_sweep(args, arc)
    meta = {k: v for k, v in arc.meta.items() if k != "timings"}
    modal = arc.results.get("modes")
    if args.json:
        doc = {"file": arc.path, "meta": meta, "model": arc.model["name"],
               "effects": arc.effects, "dofs": len(arc.labels),
               "results": sorted(arc.results), "timings_s": arc.meta["timings"]}
        if modal is not None:
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
    if modal is not None:
        print(modes_table(modal))
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
