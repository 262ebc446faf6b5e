"""Where cranefe reads and writes: one guard for every output path, atomic writes, and
the confinement of the paths that files name (docs/security.md).

- `Plan`: the outputs of one run, checked before anything is computed: a path is not
  empty, not a folder where a file is meant (or a file where a folder is meant), not a
  device, pipe or socket, in an existing folder cranefe may write in, not a file the
  run read (model, scene, mesh files, sweep file) and not another output of the run.
- `atomic(path)`: writing goes to ``.NAME.PID.tmp`` beside the target, renamed over it
  at the end, so a crash or SIGKILL never leaves half a file nor destroys the old one.
  Only a regular file (or nothing) is ever replaced; temporary files of dead processes
  left beside the target are removed first.
- `files_read()`: every file the loaders read in this run (`note_read`).
- `named_path(...)`: a path one file names (a scene's model, a model's mesh file, a
  sweep's base), resolved relative to the naming file; with confinement on
  (``--confine`` or CRANEFE_CONFINE=1) it must lie inside that file's folder.
"""

import contextlib
import errno
import os
import re
import shutil
import stat

from .errors import AnalysisError, ModelError

_READ = {}               # absolute paths of the files read in this run, in order
_CONFINE = [False]       # set by --confine; the environment variable works as well

CONFINE_ENV = "CRANEFE_CONFINE"


# ---------------------------------------------------------------- files read


def note_read(path):
    """Record that this run read `path` (outputs may never replace it)."""
    _READ[os.path.abspath(os.fspath(path))] = None


def files_read():
    return list(_READ)


def reset_reads():
    _READ.clear()


# ---------------------------------------------------------------- confinement


def set_confine(on):
    _CONFINE[0] = bool(on)


def confined():
    env = os.environ.get(CONFINE_ENV, "")
    return _CONFINE[0] or env not in ("", "0", "no", "false")


def inside(path, folder):
    """Whether `path` (symbolic links resolved) lies inside `folder`."""
    path, folder = os.path.realpath(path), os.path.realpath(folder)
    return os.path.commonpath([path, folder]) == folder


def named_path(name, naming_file, entry, what="file"):
    """The absolute path of `name`, relative to the folder of `naming_file`.

    With confinement on, an absolute name or one that leaves that folder (``..``, a
    symbolic link out of it) is refused, naming the entry."""
    folder = os.path.dirname(os.path.abspath(naming_file))
    full = os.path.join(folder, name)
    if confined() and (os.path.isabs(name) or not inside(full, folder)):
        raise ModelError(f"{what} {name!r} is outside the folder of {os.path.basename(naming_file)}"
                         f" ({folder}); with --confine (or {CONFINE_ENV}=1) every path a "
                         "file names must lie in or below its folder", naming_file, entry)
    return full


# ---------------------------------------------------------------- output checks


def _keys(path):
    """What identifies a file: its resolved path and, when it exists, device and inode
    (so a hard link or another spelling of the same file is the same file)."""
    keys = {("path", os.path.realpath(path))}
    try:
        st = os.stat(path)
        keys.add(("inode", st.st_dev, st.st_ino))
    except OSError:
        pass
    return keys


def _nearest_existing(folder):
    while folder and not os.path.exists(folder):
        parent = os.path.dirname(folder)
        if parent == folder:
            break
        folder = parent
    return folder


def _writable(folder):
    """Whether a file can be created in `folder` (tried, so root on a read-only file
    system and permission bits are both seen)."""
    if not os.access(folder, os.W_OK | os.X_OK):
        return False
    try:
        fd, probe = _mkstemp(folder)
    except OSError:
        return False
    os.close(fd)
    os.remove(probe)
    return True


def _mkstemp(folder):
    import tempfile
    return tempfile.mkstemp(prefix=f".cranefe-probe.{os.getpid()}.", dir=folder)


class Plan:
    """The files one run reads and the outputs it will write, checked together.

    ``Plan(inputs).file("--archive", path)`` and ``.folder("--images", path)`` raise
    `ModelError` (exit status 2) naming the option and the path."""

    def __init__(self, inputs=()):
        self.inputs = {}                  # key -> description
        for what, path in inputs:
            for k in _keys(path):
                self.inputs.setdefault(k, (what, path))
        self.outputs = {}                 # key -> option

    def _fail(self, option, path, message):
        raise ModelError(message, None, f"{option} {path!r}")

    def _claim(self, option, path, shown=None):
        it = "it" if shown is None else f"{path}, which it writes beside it,"
        shown = path if shown is None else shown
        for k in _keys(path):
            if k in self.inputs:
                what, p = self.inputs[k]
                self._fail(option, shown, f"{'is' if shown == path else it + ' is'} {what} "
                           f"this run reads ({p}); writing it would replace it: choose "
                           "another name")
            if k in self.outputs:
                self._fail(option, shown, f"{'is' if shown == path else it + ' is'} also "
                           f"the output of {self.outputs[k]}; give each output its own "
                           "name")
        for k in _keys(path):
            self.outputs[k] = option

    def file(self, option, path, companions=()):
        """Check an output file (and the files written beside it, e.g. an XDMF
        series' heavy-data file); returns the path."""
        if path is None:
            return None
        p = os.fspath(path)
        if not p.strip():
            self._fail(option, p, "is empty; name the file to write")
        if p.endswith(os.sep) or os.path.isdir(p):
            self._fail(option, p, "is a folder; name a file in it, e.g. "
                       f"{os.path.join(p, 'out' + _ext(option))}")
        if os.path.exists(p) and not stat.S_ISREG(os.stat(p).st_mode):
            self._fail(option, p, "is a device, pipe or socket, not a regular file; cranefe "
                       "writes outputs to a temporary file and renames it, so name a file")
        folder = os.path.dirname(os.path.realpath(p))
        if not os.path.isdir(folder):
            self._fail(option, p, f"the folder {folder} does not exist; create it first")
        if not _writable(folder):
            self._fail(option, p, f"cannot write in the folder {folder} (permission "
                       "denied or a read-only file system)")
        self._claim(option, p)
        for c in companions:
            self._claim(option, c, shown=p)
        return p

    def folder(self, option, path):
        """Check an output folder (created if missing); returns the path."""
        if path is None:
            return None
        p = os.fspath(path)
        if not p.strip():
            self._fail(option, p, "is empty; name the folder to write into")
        if os.path.exists(p) and not os.path.isdir(p):
            self._fail(option, p, "is a file, not a folder; name a folder (it is created "
                       "if missing)")
        base = _nearest_existing(os.path.abspath(p))
        if not os.path.isdir(base):
            self._fail(option, p, f"{base} is not a folder")
        if not _writable(base):
            self._fail(option, p, f"cannot write in {base} (permission denied or a "
                       "read-only file system)")
        self._claim(option, p)
        return p


def _ext(option):
    return {"--archive": ".h5", "--vtu": ".vtu", "--xdmf": ".xdmf", "--csv": ".csv",
            "--out": ".yaml"}.get(option, "")


def make_folder(path, option=None):
    """os.makedirs with a one-line error."""
    try:
        os.makedirs(path, exist_ok=True)
    except OSError as exc:
        raise ModelError(f"cannot create the folder ({exc.strerror})", None,
                         f"{option} {path!r}" if option else path) from None
    return path


# ---------------------------------------------------------------- atomic writes


TMP = re.compile(r"^\.?(?P<name>.+)\.(?P<pid>[0-9]+)\.tmp(?:\..*)?$")


def _alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):
        return True
    return True


def clean_stale(folder, name):
    """Remove ``.NAME.PID.tmp*`` (and the older ``NAME.PID.tmp``) left in `folder` by
    processes that no longer run; returns the paths removed."""
    removed = []
    try:
        entries = os.listdir(folder)
    except OSError:
        return removed
    for e in entries:
        m = TMP.match(e)
        if not m or m["name"] != name or int(m["pid"]) == os.getpid() or _alive(int(m["pid"])):
            continue
        p = os.path.join(folder, e)
        try:
            if os.path.isdir(p) and not os.path.islink(p):
                shutil.rmtree(p)
            else:
                os.remove(p)
            removed.append(p)
        except OSError:
            pass
    return removed


def temp_name(target, suffix=""):
    """The temporary name beside `target` that this process writes to."""
    folder, name = os.path.split(target)
    return os.path.join(folder, f".{name}.{os.getpid()}.tmp{suffix}")


def _replaceable(target, shown):
    """A target may be replaced only if it is a regular file or absent."""
    try:
        st = os.stat(target)
    except FileNotFoundError:
        return
    if not stat.S_ISREG(st.st_mode):
        raise ModelError("is not a regular file (a folder, device, pipe or socket); "
                         "cranefe replaces only regular files: name a file", shown)


_FULL = {errno.ENOSPC, errno.EDQUOT, errno.EFBIG, errno.EIO}   # exit 1, not a user's mistake


@contextlib.contextmanager
def atomic(path, suffix=""):
    """Yield a temporary path beside `path`; when the block ends without an exception,
    rename it over `path` (a symbolic link is written through, to the file it names).

    `suffix` is appended to the temporary name for writers that choose the format by
    the extension. OS errors become one-line messages: a full disk (or quota, or an I/O
    error) an `AnalysisError` (exit 1), any other a `ModelError` (exit 2)."""
    shown = os.fspath(path)
    target = os.path.realpath(shown)
    folder = os.path.dirname(target)
    if not os.path.isdir(folder):
        raise ModelError(f"the folder {folder} does not exist; create it first", shown)
    _replaceable(target, shown)
    clean_stale(folder, os.path.basename(target))
    tmp = temp_name(target, suffix)
    try:
        yield tmp
        _replaceable(target, shown)
        os.replace(tmp, target)
    except OSError as exc:
        if exc.errno in _FULL:        # the run was right, the machine could not keep it
            raise AnalysisError(f"{shown}: cannot write ({exc.strerror or exc}); the file "
                                "was left as it was: free some space and run again") from None
        raise ModelError(f"cannot write ({exc.strerror or exc})", shown) from None
    finally:
        if os.path.isdir(tmp) and not os.path.islink(tmp):
            shutil.rmtree(tmp, ignore_errors=True)
        elif os.path.lexists(tmp):
            os.remove(tmp)


def write_text(path, text):
    """Write a text file atomically."""
    with atomic(path) as tmp:
        with open(tmp, "w", encoding="utf-8") as fh:
            fh.write(text)
    return os.fspath(path)


def save_figure(fig, path, **kw):
    """fig.savefig(path) atomically (PNG)."""
    with atomic(path, ".png") as tmp:
        fig.savefig(tmp, format="png", **kw)
    return path
