"""What accuracy costs in time: every approximation's study, in one run, into results/.

Runs the studies listed in ACCURACY (each writes its CSV and PNG; see docs/accuracy.md),
with a progress bar, then regenerates docs/validation.md from the validation cases.
"""

import time
from importlib import import_module

DESCRIPTION = "every accuracy study (errors vs exact answers and their cost), one run"
ACCURACY = ("ropes", "drive", "eigensolvers", "damping", "transient", "luffing",
            "operations", "operation_effects", "operation_flexible")


def run(outdir, quick=False):
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    from . import NAMES
    names = [n for n in ACCURACY if n in NAMES]
    written = []
    with Progress(TextColumn("[bold]{task.description}"), BarColumn(),
                  TextColumn("{task.completed}/{task.total}"), TimeElapsedColumn(),
                  transient=False) as bar:
        task = bar.add_task("accuracy studies", total=len(names) + 1)
        for name in names:
            bar.update(task, description=f"study {name}")
            t0 = time.perf_counter()
            written += import_module(f".{name}", __package__).run(outdir, quick=quick)
            bar.console.log(f"{name}: {time.perf_counter() - t0:.1f} s")
            bar.advance(task)
        bar.update(task, description="validation table")
        from .validation import run as validation
        written += validation(outdir, quick=quick)
        bar.advance(task)
    return written
