"""HDF5 result archives (layout: docs/archive.md, format version 1).

One file keeps the model (its YAML text and parsed arrays), the effects, the coordinate
labels, the assembled matrices (CSR) and any result dataclasses (modes, damping, ...).
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
FORMAT_VERSION = 1
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
    return classes


def _dataset(g, name, value):
    value = np.asarray(value)
    if value.dtype.kind in "US":
        import h5py
        return g.create_dataset(name, data=value.astype(object),
                                dtype=h5py.string_dtype())
    return g.create_dataset(name, data=value, **(_COMPRESS if value.size > 64 else {}))


def _write_value(g, name, v):
    """Store v under name in group g; returns its type tag."""
    import scipy.sparse as sp
    if v is None:
        return "none"
    if isinstance(v, (bool, int, float, str, np.bool_, np.integer, np.floating)):
        g.attrs[name] = v
        return "scalar"
    if sp.issparse(v):
        _write_csr(g.create_group(name), v)
        return "csr"
    if isinstance(v, dict):
        sub = g.create_group(name)
        sub.attrs["__json__"] = json.dumps(v, default=float)
        return "dict"
    if isinstance(v, (list, tuple)) and all(isinstance(x, str) for x in v):
        _dataset(g, name, np.array(list(v), dtype=str))
        return "strings_tuple" if isinstance(v, tuple) else "strings_list"
    _dataset(g, name, np.asarray(v))
    return "array"


def _read_value(g, name, tag):
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


def _attrs(a):
    """h5py attributes as plain Python values."""
    return {k: (v.item() if isinstance(v, np.generic) else v) for k, v in a.items()}


def _write_dataclass(g, obj):
    tags = {f.name: _write_value(g, f.name, getattr(obj, f.name))
            for f in dataclasses.fields(obj)}
    g.attrs["__class__"] = type(obj).__name__
    g.attrs["__fields__"] = json.dumps(tags)


def _read_dataclass(g):
    cls = _result_classes().get(g.attrs["__class__"])
    tags = json.loads(g.attrs["__fields__"])
    values = {k: _read_value(g, k, t) for k, t in tags.items()}
    return cls(**values) if cls else values


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
    """Write an archive atomically (`cranefe.outpaths.atomic`), sealed; returns the path."""
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
            _dataset(g, "node_names", np.array(model.node_names, dtype=str))
            for k in ("coords", "ground", "gravity"):
                _dataset(g, k, getattr(model, k))
            mesh = line_mesh(model, system.dofs if system is not None else None)
            mg = g.create_group("mesh")
            mg.attrs["kinds"] = json.dumps(KINDS)
            _dataset(mg, "points", mesh.points)
            _dataset(mg, "point_names", np.array(mesh.point_names, dtype=str))
            _dataset(mg, "lines", mesh.lines)
            _dataset(mg, "kind", mesh.kind)
            _dataset(mg, "element", np.array(mesh.element, dtype=str))
            e = h.create_group("effects")
            e.attrs.update(model.effects.as_dict() if system is None
                           else system.effects.as_dict())
            if system is not None:
                d = h.create_group("dofs")
                _dataset(d, "labels", np.array(system.dofs.labels, dtype=str))
                _dataset(d, "kinds", np.array(system.dofs.kinds, dtype=str))
                m = h.create_group("matrices")
                _write_csr(m.create_group("K"), system.K)
                _write_csr(m.create_group("M"), system.M)
                _dataset(m, "f", system.f)
            r = h.create_group("results")
            for name, obj in (results or {}).items():
                _write_dataclass(r.create_group(name), obj)
            t = h.create_group("timings")
            t.attrs.update({k: float(v) for k, v in (timings or {}).items()})
        seal(tmp)
    return path


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
        mesh = LineMesh(mg["points"][()], tuple(mg["point_names"].asstr()[()]),
                        mg["lines"][()], mg["kind"][()], tuple(mg["element"].asstr()[()]))
        arc = Archive(path, meta, model, mesh, _attrs(h["effects"].attrs), ())
        if "dofs" in h:
            arc.labels = tuple(h["dofs/labels"].asstr()[()])
            arc.K = _read_csr(h["matrices/K"])
            arc.M = _read_csr(h["matrices/M"])
            arc.f = h["matrices/f"][()]
        arc.results = {k: _read_dataclass(v) for k, v in h["results"].items()}
        arc.meta["timings"] = _attrs(h["timings"].attrs)
    return arc
