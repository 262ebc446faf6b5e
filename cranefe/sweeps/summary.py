"""What a finished sweep reports: counts, the range of every output, the failures."""

from dataclasses import dataclass, field

import numpy as np


@dataclass
class SweepRun:
    """A sweep run to its end (or as far as it went): the table and what failed."""

    name: str
    variants: int                 # in the spec
    done: int                     # in the table (this run and resumed ones)
    table_path: str
    table: object                 # sweeps.table.SweepTable
    outputs: tuple
    failed: list = field(default_factory=list)     # (index, error) in index order

    def output_range(self, k):
        """{'min', 'max'} of output k over the variants that gave it, else None."""
        col = self.table.results[:, k]
        if not np.isfinite(col).any():
            return None
        return {"min": float(np.nanmin(col)), "max": float(np.nanmax(col))}

    def to_dict(self):
        """The JSON document of ``cranefe sweep --json`` (docs/sweeps.md)."""
        return {"sweep": self.name, "variants": self.variants, "done": self.done,
                "failed": len(self.failed), "table": self.table_path,
                "outputs": {o: self.output_range(k) for k, o in enumerate(self.outputs)},
                "errors": [{"index": i, "error": e} for i, e in self.failed[:20]]}


def summarise(sweep, done):
    """The `SweepRun` of `sweep` whose finished variants are `done` ({index: row})."""
    from .table import read_table
    failed = [(i, r["error"]) for i, r in sorted(done.items()) if r["status"] != "ok"]
    return SweepRun(sweep.name, len(sweep.variants), len(done), sweep.output,
                    read_table(sweep.output), tuple(sweep.outputs), failed)
