"""The sweep's results: an append-only journal (survives a killed run) and the HDF5 table
rewritten atomically from it."""

import json
import os
from dataclasses import dataclass

import numpy as np

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


def read_journal(table_path):
    """Results recorded so far, by variant index (a truncated last line is ignored)."""
    done = {}
    try:
        with open(journal_path(table_path)) as fh:
            for line in fh:
                try:
                    row = json.loads(line)
                except json.JSONDecodeError:
                    continue
                done[row["index"]] = row
    except FileNotFoundError:
        pass
    return done


class Journal:
    def __init__(self, table_path):
        self.fh = open(journal_path(table_path), "a")

    def add(self, row):
        self.fh.write(json.dumps(row, allow_nan=True) + "\n")
        self.fh.flush()

    def close(self):
        self.fh.close()


def write_table(path, sweep, done):
    """Write the HDF5 table of all results in `done` (temporary file, then rename)."""
    import h5py
    rows = [done[i] for i in sorted(done)]
    tmp = f"{path}.{os.getpid()}.tmp"
    try:
        with h5py.File(tmp, "w") as h:
            h.attrs.update(format=FORMAT, format_version=1, name=sweep.name,
                           total=len(sweep.variants), spec=sweep.text)
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
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def read_table(path):
    import h5py
    with h5py.File(path, "r") as h:
        strings = lambda k: tuple(h[k].asstr()[()])          # noqa: E731
        return SweepTable(str(h.attrs["name"]), strings("parameters"), strings("outputs"),
                          h["index"][()], h["values"][()], h["results"][()],
                          strings("status"), strings("errors"), h["seconds"][()],
                          int(h.attrs["total"]), str(h.attrs["spec"]))


def is_sweep(path):
    import h5py
    try:
        with h5py.File(path, "r") as h:
            return h.attrs.get("format") == FORMAT
    except OSError:
        return False
