"""Running the variants: serially, on local processes (default: all cores), or on a Dask
distributed cluster. Results stream to the journal as they finish; an interrupted sweep
resumes with only the variants it is missing."""

import multiprocessing
import os
import time
from concurrent.futures import ProcessPoolExecutor, as_completed

from .evaluate import evaluate
from .table import Journal, read_journal, write_table

CHUNK = 8            # variants per task: amortises the transfer of the base model
BLAS_THREADS = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")


def _chunk(jobs):
    return [evaluate(j) for j in jobs]


def run_sweep(sweep, workers=None, scheduler=None, reuse=True, progress=None,
              limit=None):
    """Run the variants not yet in the journal; returns {index: result} of all done.

    workers: None = all cores, 0 = serial in this process; scheduler: a Dask scheduler
    address (or a distributed.Client). limit: stop after that many new variants (tests).
    """
    done = read_journal(sweep.output)
    todo = [i for i in range(len(sweep.variants)) if i not in done][:limit]
    jobs = [(sweep.raw, sweep.parameters, sweep.outputs, sweep.modes, reuse, i,
             sweep.variants[i]) for i in todo]
    chunks = [jobs[k:k + CHUNK] for k in range(0, len(jobs), CHUNK)]
    journal = Journal(sweep.output)
    last_write = time.perf_counter()
    try:
        for rows in _execute(chunks, workers, scheduler):
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


def _execute(chunks, workers, scheduler):
    if scheduler is not None:
        yield from _dask(chunks, scheduler)
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


def _dask(chunks, scheduler):
    try:
        from distributed import Client, as_completed as dask_completed
    except ImportError:
        from ..errors import AnalysisError
        raise AnalysisError("--scheduler needs Dask: pip install 'cranefe[dask]'") from None
    client = scheduler if isinstance(scheduler, Client) else Client(scheduler)
    try:
        futures = client.map(_chunk, chunks, pure=False)
        for f in dask_completed(futures):
            yield f.result()
    finally:
        if client is not scheduler:
            client.close()
