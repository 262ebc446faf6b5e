"""Running the variants: serially, on local processes (default: all cores), or on a Dask
distributed cluster. Results stream to the journal as they finish; an interrupted sweep
resumes with only the variants it is missing."""

import multiprocessing
import os
import time
from concurrent.futures import ProcessPoolExecutor, as_completed

from ..errors import ModelError
from ..outpaths import Plan
from .evaluate import evaluate
from .table import Journal, journal_path, read_journal, write_table

CHUNK = 8            # variants per task: amortises the transfer of the base model
BLAS_THREADS = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")
SCHEDULER_TIMEOUT = 30.0   # s to connect to a Dask scheduler before giving up


def check_outputs(sweep, plots=None):
    """The table, its journal (and a plots folder) may not be a file the sweep reads
    nor coincide (`cranefe.outpaths.Plan`)."""
    plan = Plan(sweep.inputs)
    plan.file("output", sweep.output)
    plan.file("output", journal_path(sweep.output))
    plan.folder("--plots", plots)


def _chunk(jobs):
    return [evaluate(j) for j in jobs]


def run_sweep(sweep, workers=None, scheduler=None, reuse=True, progress=None,
              limit=None, restart=False, plots=None, scheduler_timeout=SCHEDULER_TIMEOUT):
    """Run the variants not yet in the journal; returns {index: result} of all done.

    workers: None = all cores, 0 = serial in this process; scheduler: a Dask scheduler
    address (or a distributed.Client). limit: stop after that many new variants (tests).
    The journal is locked while the sweep runs and keyed to `sweep.digest` (the spec
    and every file it read): a journal of another sweep is refused unless `restart`,
    which deletes it and the table first. `plots`: a folder checked with the outputs.
    """
    check_outputs(sweep, plots)
    journal = Journal(sweep.output, sweep.digest, restart)   # locked while it runs
    try:
        done = read_journal(sweep.output, sweep.digest)
    except BaseException:
        journal.close()
        raise
    todo = [i for i in range(len(sweep.variants)) if i not in done][:limit]
    jobs = [(sweep.raw, sweep.parameters, sweep.outputs, sweep.modes, reuse, i,
             sweep.variants[i]) for i in todo]
    chunks = [jobs[k:k + CHUNK] for k in range(0, len(jobs), CHUNK)]
    last_write = time.perf_counter()
    try:
        for rows in _execute(chunks, workers, scheduler, scheduler_timeout):
            for row in rows:
                journal.add(row)
                done[row["index"]] = row
            if progress:
                progress(len(rows))
            if time.perf_counter() - last_write > 2.0:     # keep the table current
                write_table(sweep.output, sweep, done)
                last_write = time.perf_counter()
    finally:
        journal.close()
        write_table(sweep.output, sweep, done)
    return done


def _execute(chunks, workers, scheduler, timeout):
    if scheduler is not None:
        yield from _dask(chunks, scheduler, timeout)
    elif workers == 0:
        for c in chunks:
            yield _chunk(c)
    else:
        # fresh interpreters with single-threaded BLAS: a worker per core, each with a
        # multi-threaded BLAS, would oversubscribe the cores (as Dask's workers avoid too)
        saved = {k: os.environ.get(k) for k in BLAS_THREADS}
        os.environ.update({k: "1" for k in BLAS_THREADS})
        try:
            pool = ProcessPoolExecutor(max_workers=workers or os.cpu_count(),
                                       mp_context=multiprocessing.get_context("spawn"))
            futures = [pool.submit(_chunk, c) for c in chunks]
        finally:
            for k, v in saved.items():
                if v is None:
                    os.environ.pop(k, None)
                else:
                    os.environ[k] = v
        with pool:
            for f in as_completed(futures):
                yield f.result()


def check_scheduler(address):
    """A Dask scheduler address: [PROTOCOL://]HOST:PORT."""
    import re
    m = re.match(r"^(?:(tcp|tls|ucx|ws|wss|inproc)://)?([A-Za-z0-9_.-]+|\[[0-9a-fA-F:]+\])"
                 r":([0-9]{1,5})$", address or "")
    if not m or not 0 < int(m[3]) < 65536:
        raise ModelError("is not a scheduler address; give PROTOCOL://HOST:PORT, e.g. "
                         "tcp://10.0.0.5:8786", None, f"--scheduler {address!r}")
    return address


def _connect(scheduler, timeout):
    from distributed import Client
    if isinstance(scheduler, Client):
        return scheduler
    check_scheduler(scheduler)
    try:
        return Client(scheduler, timeout=f"{timeout}s")
    except (OSError, TimeoutError) as exc:
        raise ModelError(f"cannot reach the scheduler within {timeout:g} s ({type(exc).__name__})"
                         "; check the address and that the scheduler runs", None,
                         f"--scheduler {scheduler!r}") from None


def _dask(chunks, scheduler, timeout=SCHEDULER_TIMEOUT):
    try:
        from distributed import as_completed as dask_completed
    except ImportError:
        from ..errors import AnalysisError
        raise AnalysisError("--scheduler needs Dask: pip install 'cranefe[dask]'") from None
    client = _connect(scheduler, timeout)
    try:
        futures = client.map(_chunk, chunks, pure=False)
        for f in dask_completed(futures):
            yield f.result()
    finally:
        if client is not scheduler:
            client.close()
