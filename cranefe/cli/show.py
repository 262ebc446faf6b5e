"""Summarise a cranefe HDF5 archive: what is in it and its frequency table."""

HELP = "summarise an archive (.h5)"


def add_arguments(p):
    p.add_argument("file", help="archive written with --archive")
    p.add_argument("--json", action="store_true", help="print one JSON document")


def run(args):
    from ..archive import read
    from ..report import dumps, modes_document, modes_table
    arc = read(args.file)
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
