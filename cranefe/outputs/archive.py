"""HDF5 result archives (layout: docs/archive.md, format version 2; version 1 is read).

One file keeps the model (its YAML text and parsed arrays), the effects, the coordinate
labels, the assembled matrices (CSR) and any result dataclasses (modes, damping, ...),
one group per analysis, every number a dataset with its units and a description
(`archive_schema`), so that h5py or HDFView explain the file without cranefe.
Writing goes to a temporary file in the target folder that is renamed over the target
at the end, so a crash never leaves half a file nor destroys an earlier archive; the
file carries a seal (size and SHA-256) checked before it is read.
"""

import dataclasses
import datetime
import json
import os
import sys
from dataclasses import dataclass, field

import numpy as np

from .. import __version__
from ..errors import ModelError

FORMAT = "cranefe-archive"
FORMAT_VERSION = 2
_COMPRESS = dict(compression="gzip", compression_opts=4, shuffle=True)


@dataclass
class Archive:
    """An archive read back: metadata, model arrays, matrices and results."""

    path: str
    meta: dict
    model: dict               # name, file, planar, yaml, node_names, coords, ground, ...
    mesh: object              # cranefe.outputs.mesh.LineMesh
    effects: dict
    labels: tuple
    K: object = None          # scipy.sparse.csr_matrix
    M: object = None
    f: np.ndarray = None
    results: dict = field(default_factory=dict)


def _result_classes():
    from ..analysis.modal import ModalResult
    classes = {"ModalResult": ModalResult}
    from ..analysis.damping import DampingResult
    from ..analysis.transient.results import TransientResult
    classes["DampingResult"] = DampingResult
    classes["TransientResult"] = TransientResult
    from ..analysis.luffing.analysis import LuffingResult
    classes["LuffingResult"] = LuffingResult
    from ..analysis.operation.results import OperationResult
    classes["OperationResult"] = OperationResult
    from .member_forces import MemberForces
    classes["MemberForces"] = MemberForces
    return classes


def _dataset(g, name, value):
    value = np.asarray(value)
    if value.dtype.kind in "USO":
        import h5py
        return g.create_dataset(name, data=value.astype(object),
                                dtype=h5py.string_dtype())
    return g.create_dataset(name, data=value, **(_COMPRESS if value.size > 64 else {}))


# ---------------------------------------------------------------- format 2: results
#
# Every field of a result dataclass is one member of its group: numbers and arrays are
# datasets (a scalar is a 0-d dataset) with attributes `field` (the dataclass field),
# `python_type` (how to read it back), `units` (numbers only, archive_schema) and
# `description`; a dict is a subgroup of such members; None an empty dataset. No JSON.

def _describe(obj, units, description, field=None, python_type=None):
    if field is not None:
        obj.attrs["field"] = field
    if python_type is not None:
        obj.attrs["python_type"] = python_type
    if units is not None:
        obj.attrs["units"] = units
    if description:
        obj.attrs["description"] = description


def _member_name(key):
    key = str(key)
    return key.replace("/", "\u2215") if key not in ("", ".") else f"[{key}]"


def _is_scalar(v):
    return isinstance(v, (bool, int, float, str, np.bool_, np.integer, np.floating))


def _is_records(v):
    """A list of equal-length tuples of scalars with one kind per column (events)."""
    if not v or not all(isinstance(x, tuple) for x in v):
        return False
    n = len(v[0])
    if n == 0 or any(len(x) != n for x in v) or not all(_is_scalar(c) for x in v for c in x):
        return False
    return all(len({isinstance(x[k], str) for x in v}) == 1 for k in range(n))


def _write_member(g, name, v, units=None, description=None, field=None):
    """Store v as member `name` of group g (format 2)."""
    import h5py
    import scipy.sparse as sp
    if isinstance(v, dict):
        sub = g.create_group(name, track_order=True)     # keys in their order
        _describe(sub, None, description, field, "dict")
        for k, x in v.items():
            from .archive_schema import key_units
            m = _write_member(sub, _member_name(k), x,
                              key_units(str(k), units) if not isinstance(x, dict) else units)
            m.attrs["key"] = str(k)
        return sub
    if v is None:
        d = g.create_dataset(name, data=h5py.Empty("f8"))
        _describe(d, None, description, field, "none")
        return d
    if sp.issparse(v):
        sub = g.create_group(name)
        _write_csr(sub, v)
        _describe(sub, units, description, field, "csr")
        return sub
    if _is_scalar(v):
        kind = type(v).__name__ if type(v) in (bool, int, float, str) else \
            "numpy." + np.asarray(v).dtype.name
        d = _dataset(g, name, v if not isinstance(v, str) else np.array(v, dtype=object))
        _describe(d, None if isinstance(v, str) or isinstance(v, (bool, np.bool_))
                  else units, description, field, kind)
        return d
    if isinstance(v, (list, tuple)):
        kind = "tuple" if isinstance(v, tuple) else "list"
        if _is_records(v):
            sub = g.create_group(name)
            _describe(sub, None, description, field, "records_" + kind)
            for k in range(len(v[0])):
                _write_member(sub, f"column_{k}", [x[k] for x in v],
                              units if not isinstance(v[0][k], str) else None)
            return sub
        if all(isinstance(x, str) for x in v) or \
                all(_is_scalar(x) and not isinstance(x, str) for x in v):
            d = _dataset(g, name, np.array(list(v), dtype=str) if v and
                         isinstance(v[0], str) else np.array(list(v), dtype=float
                                                             if not v else None))
            text = bool(v) and isinstance(v[0], str)
            _describe(d, None if text else units, description, field,
                      ("strings_" if text else "numbers_") + kind)
            return d
        sub = g.create_group(name)
        _describe(sub, None, description, field, "items_" + kind)
        for k, x in enumerate(v):
            _write_member(sub, f"{k:06d}", x, units)
        return sub
    arr = np.asarray(v)
    d = _dataset(g, name, arr)
    _describe(d, units if arr.dtype.kind in "fciu" else None, description, field, "array")
    return d


def _read_member(m):
    """The Python value of a member written by `_write_member`."""
    kind = m.attrs.get("python_type", "array")
    if kind == "dict":
        return {m[k].attrs.get("key", k): _read_member(m[k]) for k in m}
    if kind == "none":
        return None
    if kind == "csr":
        return _read_csr(m)
    if kind.startswith("records_"):
        cols = [_read_member(m[f"column_{k}"]) for k in range(len(m))]
        rows = [tuple(r) for r in zip(*cols)]
        return tuple(rows) if kind.endswith("tuple") else rows
    if kind.startswith("items_"):
        items = [_read_member(m[k]) for k in sorted(m)]
        return tuple(items) if kind.endswith("tuple") else items
    if kind.startswith("strings_"):
        items = list(m.asstr()[()])
        return tuple(items) if kind.endswith("tuple") else items
    if kind.startswith("numbers_"):
        items = m[()].tolist()
        return tuple(items) if kind.endswith("tuple") else items
    if kind == "str":
        return m.asstr()[()]
    if kind in ("bool", "int", "float"):
        return {"bool": bool, "int": int, "float": float}[kind](m[()])
    if kind.startswith("numpy."):           # a numpy scalar: its dtype's name
        return np.dtype(kind[6:]).type(m[()])
    return m[()]


def _write_dataclass(g, obj):
    """One result group (format 2): its fields by their archive names (archive_schema),
    then the derived datasets (frequency in Hz, ...)."""
    from .archive_schema import DERIVED, field_info
    cls = type(obj).__name__
    g.attrs["class"] = cls
    g.attrs["description"] = (type(obj).__doc__ or cls).strip().split("\n")[0]
    for f in dataclasses.fields(obj):
        name, units, description = field_info(cls, f.name)
        _write_member(g, name, getattr(obj, f.name), units, description, field=f.name)
    for name, (units, description, value) in DERIVED.get(cls, {}).items():
        d = _dataset(g, name, np.asarray(value(obj), dtype=float))
        _describe(d, units, description + " (derived)", python_type="array")
        d.attrs["derived"] = True


def _read_dataclass(g):
    if "__fields__" in g.attrs:             # format 1
        return _read_dataclass_v1(g)
    cls = _result_classes().get(g.attrs.get("class"))
    values = {m.attrs["field"]: _read_member(m) for m in g.values() if "field" in m.attrs}
    if cls is None:
        return values
    known = {f.name for f in dataclasses.fields(cls)}
    return cls(**{k: v for k, v in values.items() if k in known})


# ---------------------------------------------------------------- format 1 (read only)

def _read_value_v1(g, name, tag):
    if tag == "none":
        return None
    if tag == "scalar":
        v = g.attrs[name]
        return v.item() if isinstance(v, np.generic) else v
    if tag == "csr":
        return _read_csr(g[name])
    if tag == "dict":
        return json.loads(g[name].attrs["__json__"])
    if tag in ("strings_tuple", "strings_list"):
        items = list(g[name].asstr()[()])
        return tuple(items) if tag == "strings_tuple" else items
    return g[name][()]


def _read_dataclass_v1(g):
    cls = _result_classes().get(g.attrs["__class__"])
    tags = json.loads(g.attrs["__fields__"])
    values = {k: _read_value_v1(g, k, t) for k, t in tags.items()}
    return cls(**values) if cls else values


def _attrs(a):
    """h5py attributes as plain Python values."""
    return {k: (v.item() if isinstance(v, np.generic) else v) for k, v in a.items()}


def _write_csr(g, A):
    A = A.tocsr()
    g.attrs["shape"] = A.shape
    for k in ("data", "indices", "indptr"):
        _dataset(g, k, getattr(A, k))


def _read_csr(g):
    import scipy.sparse as sp
    return sp.csr_matrix((g["data"][()], g["indices"][()], g["indptr"][()]),
                         shape=tuple(g.attrs["shape"]))


def write(path, model, system=None, results=None, command=None, timings=None):
    """Write an archive atomically (`cranefe.outpaths.atomic`), sealed; returns the path.

    `results`: {group name: result dataclass}, e.g. {"modes": ModalResult}; the layout
    is docs/archive.md."""
    import h5py

    from .mesh import KINDS, line_mesh
    from ..outpaths import atomic
    path = os.fspath(path)
    with atomic(path) as tmp:
        with h5py.File(tmp, "w", userblock_size=SEAL_SIZE) as h:
            h.attrs.update(format=FORMAT, format_version=FORMAT_VERSION,
                           cranefe_version=__version__,
                           command=" ".join(command if command is not None else sys.argv),
                           created=datetime.datetime.now(datetime.timezone.utc).isoformat(
                               timespec="seconds"))
            g = h.create_group("model")
            g.attrs.update(name=model.name, file=model.file, planar=model.planar,
                           scene=model.scene or "")
            g.create_dataset("yaml", data=model.text, dtype=h5py.string_dtype())
            _describe(g["yaml"], None, "the model file's text, verbatim")
            _describe(_dataset(g, "node_names", np.array(model.node_names, dtype=str)),
                      None, "node names (node,)")
            _describe(_dataset(g, "coords", model.coords), "m",
                      "node positions x, y, z (node, 3)")
            _describe(_dataset(g, "ground", model.ground), None,
                      "indices of the ground nodes into node_names")
            _describe(_dataset(g, "gravity", model.gravity), "m/s^2",
                      "gravitational acceleration (3,)")
            mesh = line_mesh(model, system.dofs if system is not None else None)
            mg = g.create_group("mesh")
            mg.attrs["kinds"] = np.array(KINDS, dtype=object)
            _describe(_dataset(mg, "points", mesh.points), "m",
                      "nodes, then one point per body at its centre of mass (point, 3)")
            _describe(_dataset(mg, "point_names", np.array(mesh.point_names, dtype=str)),
                      None, "name of each point (point,)")
            _describe(_dataset(mg, "lines", mesh.lines), None,
                      "point indices of each line cell (line, 2)")
            _describe(_dataset(mg, "kind", mesh.kind), None,
                      "index into the attribute kinds (line,)")
            _describe(_dataset(mg, "element", np.array(mesh.element, dtype=str)), None,
                      "element of each line (line,)")
            e = h.create_group("effects")
            e.attrs.update(model.effects.as_dict() if system is None
                           else system.effects.as_dict())
            if system is not None:
                d = h.create_group("dofs")
                _describe(_dataset(d, "labels", np.array(system.dofs.labels, dtype=str)),
                          None, "generalised coordinates (n,)")
                _describe(_dataset(d, "kinds", np.array(system.dofs.kinds, dtype=str)),
                          None, "body | node | drum (n,)")
                m = h.create_group("matrices")
                _write_csr(m.create_group("K"), system.K)
                _describe(m["K"], "mixed", "stiffness matrix, CSR (n, n)")
                _write_csr(m.create_group("M"), system.M)
                _describe(m["M"], "mixed", "mass matrix, CSR (n, n)")
                _describe(_dataset(m, "f", system.f), "mixed", "gravity forces (n,)")
            r = h.create_group("results")
            for name, obj in (results or {}).items():
                _write_dataclass(r.create_group(name), obj)
                _name_nodes(r[name], obj, model.node_names)
            t = h.create_group("timings")
            for k, v in (timings or {}).items():
                _describe(_dataset(t, k, float(v)), "s", "wall time of the stage")
        seal(tmp)
    return path


def _name_nodes(g, obj, node_names):
    """A modal group: the node names of the rows of `mode_shape`; a member-force group:
    the names of the axes of its arrays."""
    if type(obj).__name__ == "MemberForces":
        from .member_forces import FORCE_NAMES, STRESS_NAMES
        text = lambda v: np.array(v, dtype=object)        # noqa: E731
        g["section_forces"].attrs["dims"] = text(["state", "element", "end", "component"])
        g["section_forces"].attrs["components"] = text(FORCE_NAMES)
        g["section_forces"].attrs["component_units"] = text(["N"] * 3 + ["N m"] * 3)
        g["extreme_fibre_stress"].attrs["dims"] = text(["state", "element", "end", "fibre"])
        g["extreme_fibre_stress"].attrs["components"] = text(STRESS_NAMES)
        return
    if type(obj).__name__ == "ModalResult" and "mode_shape" in g \
            and len(node_names) == g["mode_shape"].shape[1]:
        _describe(_dataset(g, "node_names", np.array(node_names, dtype=str)), None,
                  "node of each row of mode_shape (node,)")
        g["mode_shape"].attrs["dims"] = np.array(["mode", "node", "xyz"], dtype=object)


# ---------------------------------------------------------------- integrity seal
#
# HDF5 leaves a "user block" at the start of a file for the application. cranefe writes
# there, after the file is complete, a line with the file's size and the SHA-256 of all
# bytes after the block. A reader checks both before HDF5 parses anything, so a damaged
# or truncated file is refused in the time it takes to hash it; HDF5's own parser can
# hang or crash on damaged metadata. Files without a seal (written before it existed,
# or whose seal itself is damaged) are read in a child process with a time limit.

SEAL_SIZE = 512
SEAL_MAGIC = b"cranefe-seal 1 "
UNSEALED_TIMEOUT = 20.0        # s, plus the time to read the file at 20 MB/s
DAMAGED = "damaged or incomplete archive"


def _digest(fh, start):
    import hashlib
    fh.seek(start)
    h = hashlib.sha256()
    for block in iter(lambda: fh.read(1 << 20), b""):
        h.update(block)
    return h.hexdigest()


def seal(path):
    """Write the seal into the user block of a closed HDF5 file made with
    ``userblock_size=SEAL_SIZE``."""
    with open(path, "r+b") as fh:
        size = os.fstat(fh.fileno()).st_size
        line = SEAL_MAGIC + json.dumps({"size": size, "sha256": _digest(fh, SEAL_SIZE)},
                                       separators=(",", ":")).encode() + b"\n"
        fh.seek(0)
        fh.write(line.ljust(SEAL_SIZE, b"\0"))


def check_seal(path, what="archive"):
    """True if `path` carries a seal that matches its bytes; False if it has none;
    raises `ModelError` ("damaged or incomplete archive") if the seal does not match."""
    damaged = DAMAGED if what == "archive" else f"damaged or incomplete {what}"
    try:
        with open(path, "rb") as fh:
            head = fh.read(SEAL_SIZE)
            if not head.startswith(SEAL_MAGIC):
                return False
            try:
                info = json.loads(head[len(SEAL_MAGIC):].split(b"\n", 1)[0])
                size, digest = int(info["size"]), str(info["sha256"])
            except (ValueError, KeyError, TypeError):
                raise ModelError(f"{damaged} (its integrity record is unreadable)",
                                 path) from None
            actual = os.fstat(fh.fileno()).st_size
            if actual != size:
                raise ModelError(f"{damaged} ({actual} bytes where {size} were written)",
                                 path)
            if _digest(fh, SEAL_SIZE) != digest:
                raise ModelError(f"{damaged} (its checksum does not match: bytes were "
                                 "changed after it was written)", path)
    except FileNotFoundError:
        raise ModelError("file not found", path) from None
    except IsADirectoryError:
        raise ModelError("is a folder, not an archive", path) from None
    except OSError as exc:
        raise ModelError(f"cannot be read ({exc.strerror})", path) from None
    return True


def guarded(function, path, *args, what="archive"):
    """function(path, *args), any failure of it a `ModelError` "damaged or incomplete".

    A sealed file that matches is read here; an unsealed one in a forked child with a
    time limit (UNSEALED_TIMEOUT plus the file's size at 20 MB/s), since HDF5 can hang
    on damaged metadata."""
    path = os.fspath(path)
    if check_seal(path, what):
        return _catching(function, path, args, what)
    timeout = UNSEALED_TIMEOUT + os.path.getsize(path) / 20e6
    return _in_child(function, path, args, what, timeout)


def _catching(function, path, args, what):
    try:
        return function(path, *args)
    except ModelError:
        raise
    except Exception as exc:        # h5py raises many kinds on damaged files
        raise ModelError(f"damaged or incomplete {what} ({type(exc).__name__}: "
                         f"{str(exc)[:200]})", path) from None


def _in_child(function, path, args, what, timeout):
    import multiprocessing
    import pickle
    try:
        ctx = multiprocessing.get_context("fork")
    except ValueError:              # no fork (Windows): read here
        return _catching(function, path, args, what)
    recv, send = ctx.Pipe(duplex=False)

    def child():
        try:
            out = ("ok", _catching(function, path, args, what))
        except ModelError as exc:
            out = ("error", str(exc.message))
        try:
            send.send_bytes(pickle.dumps(out))
        except Exception as exc:
            send.send_bytes(pickle.dumps(("error", f"damaged or incomplete {what} "
                                          f"({type(exc).__name__})")))
        os._exit(0)

    proc = ctx.Process(target=child, daemon=True)
    proc.start()
    send.close()
    try:
        if not recv.poll(timeout):
            raise ModelError(f"damaged or incomplete {what} (reading it did not finish in "
                             f"{timeout:.0f} s)", path)
        status, value = pickle.loads(recv.recv_bytes())
    except EOFError:
        raise ModelError(f"damaged or incomplete {what} (the reader crashed)", path) from None
    finally:
        recv.close()
        if proc.is_alive():
            proc.kill()
        proc.join()
    if status == "error":
        raise ModelError(value, path)
    return value


def read(path):
    """Read an archive back into an `Archive` (results as their dataclasses); a damaged
    or truncated file is a `ModelError` "damaged or incomplete archive", in bounded time
    (`guarded`)."""
    return guarded(_read, path)


def _read(path):
    import h5py

    from .mesh import LineMesh
    path = os.fspath(path)
    try:
        h = h5py.File(path, "r")
    except FileNotFoundError:
        raise ModelError("file not found", path) from None
    except OSError as exc:
        raise ModelError(f"not an HDF5 file ({exc})", path) from None
    with h:
        if h.attrs.get("format") != FORMAT:
            raise ModelError("not a cranefe archive (no format attribute)", path)
        if h.attrs["format_version"] > FORMAT_VERSION:
            raise ModelError(f"archive format {h.attrs['format_version']} is newer than "
                             f"this cranefe reads ({FORMAT_VERSION}); update cranefe", path)
        meta = _attrs(h.attrs)
        g = h["model"]
        model = _attrs(g.attrs)
        model["yaml"] = g["yaml"].asstr()[()]
        model["node_names"] = tuple(g["node_names"].asstr()[()])
        for k in ("coords", "ground", "gravity"):
            model[k] = g[k][()]
        mg = g["mesh"]
        if isinstance(mg.attrs["kinds"], str):      # format 1: a JSON list
            model["kinds"] = tuple(json.loads(mg.attrs["kinds"]))
        else:
            model["kinds"] = tuple(str(k) for k in mg.attrs["kinds"])
        mesh = LineMesh(mg["points"][()], tuple(mg["point_names"].asstr()[()]),
                        mg["lines"][()], mg["kind"][()], tuple(mg["element"].asstr()[()]))
        arc = Archive(path, meta, model, mesh, _attrs(h["effects"].attrs), ())
        if "dofs" in h:
            arc.labels = tuple(h["dofs/labels"].asstr()[()])
            arc.K = _read_csr(h["matrices/K"])
            arc.M = _read_csr(h["matrices/M"])
            arc.f = h["matrices/f"][()]
        arc.results = {k: _read_dataclass(v) for k, v in h["results"].items()}
        tg = h["timings"]
        arc.meta["timings"] = _attrs(tg.attrs) if meta["format_version"] < 2 else \
            {k: float(tg[k][()]) for k in tg}
    return arc
