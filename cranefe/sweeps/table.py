"""The sweep's results: an append-only journal (survives a killed run) and the HDF5 table
rewritten atomically from it."""

import json
import os
from dataclasses import dataclass

import numpy as np

from ..errors import ModelError

FORMAT = "cranefe-sweep"


@dataclass
class SweepTable:
    name: str
    parameters: tuple
    outputs: tuple
    index: np.ndarray         # (n,) variant numbers, sorted
    values: np.ndarray        # (n, p)
    results: np.ndarray       # (n, q), NaN where a variant failed
    status: tuple             # "ok" | "error"
    errors: tuple
    seconds: np.ndarray
    total: int                # variants in the sweep
    spec: str = ""


def journal_path(table_path):
    return table_path + ".journal"


def read_journal(table_path, digest=None):
    """Results recorded so far, by variant index (a truncated last line is ignored).

    With `digest`, the journal must have been started for the same sweep (its first
    line records the digest of the spec and of every file the sweep read): a journal of
    another sweep, or one without a digest, is a `JournalMismatch`."""
    done = {}
    header = None
    try:
        with open(journal_path(table_path)) as fh:
            for line in fh:
                try:
                    row = json.loads(line)
                except json.JSONDecodeError:
                    continue
                if not isinstance(row, dict):
                    continue
                if "journal" in row and header is None:
                    header = row
                elif "index" in row:
                    done[row["index"]] = row
    except FileNotFoundError:
        return done
    if digest is not None and (done or header is not None):
        if header is None or header.get("digest") != digest["digest"]:
            raise JournalMismatch(table_path, header, digest)
    return done


class JournalMismatch(ModelError):
    """The journal beside a table belongs to another sweep (other spec or inputs)."""

    def __init__(self, table_path, header, digest):
        if header is None:
            why = "it records no digest of its sweep (an older cranefe wrote it)"
        else:
            old = header.get("files", {})
            changed = [f for f in digest["files"] if old.get(f) != digest["files"][f]]
            changed += [f for f in old if f not in digest["files"]]
            why = ("these files changed since: " + ", ".join(changed) if changed else
                   "the sweep it was started for differs")
        super().__init__(
            f"the journal {journal_path(table_path)} was started for another sweep: "
            f"{why}; resuming would mix the results of two sweeps. To start afresh run "
            "'cranefe sweep FILE --restart' (it deletes the journal and the table), or "
            "give the sweep another 'output:' (docs/sweeps.md, \"Resuming\")", table_path)


class JournalBusy(ModelError):
    pass


class Journal:
    """The append-only journal, locked (fcntl) for as long as it is open: a second
    sweep on the same output is refused, naming the process that holds it."""

    def __init__(self, table_path, digest=None, restart=False):
        import fcntl
        import socket
        import time
        self.path = journal_path(table_path)
        try:
            self.fh = open(self.path, "a+")
        except OSError as exc:
            raise ModelError(f"cannot write the journal ({exc.strerror})", self.path) \
                from None
        try:
            fcntl.flock(self.fh.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            owner = _owner(self.path)
            self.fh.close()
            raise JournalBusy(f"another sweep is writing this output ({owner}); wait for "
                              "it to finish or stop it, or give this sweep another "
                              "'output:'", self.path) from None
        if restart:                     # start afresh: no old results, no old table
            self.fh.truncate(0)
            if os.path.isfile(table_path):
                os.remove(table_path)
        self.fh.seek(0, os.SEEK_END)
        if digest is not None and self.fh.tell() == 0:
            self._line({"journal": 1, **digest})
        self._line({"owner": os.getpid(), "host": socket.gethostname(),
                    "started": time.strftime("%Y-%m-%dT%H:%M:%S%z")})

    def _line(self, row):
        self.fh.write(json.dumps(row, allow_nan=True) + "\n")
        self.fh.flush()

    def add(self, row):
        self._line(row)

    def close(self):
        self.fh.close()         # releases the lock


def _owner(path):
    """'process N on HOST since T' from the journal's last owner line."""
    last = None
    try:
        with open(path) as fh:
            for line in fh:
                if line.startswith('{"owner"'):
                    last = line
        row = json.loads(last)
        return f"process {row['owner']} on {row['host']}, since {row['started']}"
    except (OSError, TypeError, ValueError, KeyError):
        return "a process that has not yet written its id"


def write_table(path, sweep, done):
    """Write the HDF5 table of all results in `done` (temporary file, then rename)."""
    import h5py
    from ..outputs.archive import SEAL_SIZE, seal
    from ..outpaths import atomic
    rows = [done[i] for i in sorted(done)]
    with atomic(path) as tmp:
        with h5py.File(tmp, "w", userblock_size=SEAL_SIZE) as h:
            h.attrs.update(format=FORMAT, format_version=1, name=sweep.name,
                           total=len(sweep.variants), spec=sweep.text,
                           digest=getattr(sweep, "digest", {}).get("digest", ""))
            s = h5py.string_dtype()
            h.create_dataset("parameters", data=[p.name for p in sweep.parameters], dtype=s)
            h.create_dataset("outputs", data=list(sweep.outputs), dtype=s)
            h.create_dataset("index", data=np.array([r["index"] for r in rows], dtype=int))
            h.create_dataset("values", data=np.array([r["values"] for r in rows], dtype=float)
                             .reshape(len(rows), len(sweep.parameters)))
            h.create_dataset("results", data=np.array([r["outputs"] for r in rows],
                                                      dtype=float)
                             .reshape(len(rows), len(sweep.outputs)))
            h.create_dataset("status", data=[r["status"] for r in rows], dtype=s)
            h.create_dataset("errors", data=[r["error"] for r in rows], dtype=s)
            h.create_dataset("seconds", data=np.array([r["seconds"] for r in rows]))
        seal(tmp)


def read_table(path):
    """The table at `path`; a damaged file is a `ModelError` in bounded time."""
    from ..outputs.archive import guarded
    return guarded(_read_table, path, what="sweep table")


def _read_table(path):
    import h5py
    with h5py.File(path, "r") as h:
        strings = lambda k: tuple(h[k].asstr()[()])          # noqa: E731
        return SweepTable(str(h.attrs["name"]), strings("parameters"), strings("outputs"),
                          h["index"][()], h["values"][()], h["results"][()],
                          strings("status"), strings("errors"), h["seconds"][()],
                          int(h.attrs["total"]), str(h.attrs["spec"]))


def is_sweep(path):
    """Whether `path` is a sweep table (call it through `archive.guarded` on files
    from elsewhere: HDF5 can hang on damaged bytes)."""
    import h5py
    try:
        with h5py.File(path, "r") as h:
            return h.attrs.get("format") == FORMAT
    except OSError:
        return False
