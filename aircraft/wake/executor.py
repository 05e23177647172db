"""Where independent wake runs execute: one interface for every executor.

:func:`make_executor` returns a context manager with ``map_unordered(fn, jobs)``,
which yields ``fn(job)`` for every job as each finishes (in completion order, so
progress is reported as runs end, whatever ran them):

=====================  ====================================================
``n_jobs <= 1``        in this process, one after another
``n_jobs >= 2``        a local pool of ``n_jobs`` processes (the embedded
                       default: no server, nothing to start)
=====================  ====================================================

The executor cannot change a result: the wake cache's code digest does not
cover this module (see :mod:`aircraft.wake.records`).
"""
from __future__ import annotations

import multiprocessing
from concurrent.futures import ProcessPoolExecutor, as_completed

__all__ = ["make_executor", "SerialExecutor", "LocalPoolExecutor"]


class SerialExecutor:
    """Runs every job in this process, in order."""

    name = "serial"

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    def map_unordered(self, fn, jobs):
        """Yield ``fn(job)`` for each job."""
        for job in jobs:
            yield fn(job)


class LocalPoolExecutor:
    """A local pool of worker processes (``spawn`` context).

    Parameters
    ----------
    n_jobs : int
        Worker processes.
    initializer : callable, optional
        Run once in each worker (e.g. one numba thread per worker).
    """

    name = "local processes"

    def __init__(self, n_jobs, initializer=None):
        self.n_jobs, self.initializer, self._pool = int(n_jobs), initializer, None

    def __enter__(self):
        # "spawn", not fork: numba's OpenMP threading layer aborts a forked child
        # ("fork() called from a process already using GNU OpenMP")
        self._pool = ProcessPoolExecutor(max_workers=self.n_jobs, initializer=self.initializer,
                                         mp_context=multiprocessing.get_context("spawn"))
        return self

    def __exit__(self, *exc):
        self._pool.shutdown(wait=True, cancel_futures=True)
        return False

    def map_unordered(self, fn, jobs):
        """Yield ``fn(job)`` for each job as it finishes."""
        futures = [self._pool.submit(fn, job) for job in jobs]
        for fut in as_completed(futures):
            yield fut.result()


def make_executor(n_jobs=2, initializer=None):
    """The executor for ``n_jobs`` workers.

    Parameters
    ----------
    n_jobs : int
        1: in this process; >= 2: a local process pool.
    initializer : callable, optional
        Run once in each pool worker.

    Returns
    -------
    SerialExecutor or LocalPoolExecutor
    """
    if isinstance(n_jobs, bool) or not isinstance(n_jobs, int) or n_jobs < 1:
        raise ValueError(f"n_jobs must be an integer >= 1, got {n_jobs!r}")
    return SerialExecutor() if n_jobs <= 1 else LocalPoolExecutor(n_jobs, initializer)
