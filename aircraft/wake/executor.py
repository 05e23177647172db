"""Where independent wake runs execute: one interface for every executor.

:func:`make_executor` returns a context manager with ``map_unordered(fn, jobs)``,
which yields ``fn(job)`` for every job as each finishes (in completion order, so
progress is reported as runs end, whatever ran them):

=================================  ==========================================
``scheduler=None, n_jobs <= 1``    in this process, one after another
                                   (:class:`SerialExecutor`)
``scheduler=None, n_jobs >= 2``    a local pool of ``n_jobs`` processes
                                   (:class:`LocalPoolExecutor`; the embedded
                                   default: no server, nothing to start)
``scheduler="tcp://host:port"``    the workers of the Dask ``distributed``
                                   cluster at that address
                                   (:class:`DaskExecutor`; a client is opened
                                   on entry and closed on exit)
``scheduler=Client``               the cluster of that
                                   ``dask.distributed.Client`` (left open)
=================================  ==========================================

With a scheduler ``n_jobs`` is ignored: the cluster's workers set the
concurrency.

Dask is optional (``pip install distributed``, or the package's ``cluster``
extra) and imported only when a scheduler is given.

Where the workers run, they may not share this machine's filesystem, so the
callers (:func:`aircraft.wake.run_sweeps`) write the cache in the calling
process as each result arrives; a worker writes nothing. ``initializer`` runs
once in each local pool worker, and before every task on a Dask worker (numba's
thread count is a per-thread setting, and a Dask worker's threads are not ours).

Lost workers
------------
A worker process that dies while running a job (killed, out of memory) never
hands back a partial result: the job either runs again elsewhere or fails with
a :class:`WorkerLostError` (a RuntimeError) naming the job.  A Dask cluster
reruns the job on another worker up to ``distributed.scheduler.allowed-failures``
times (Dask's setting, default 3) and then fails it; a local pool cannot rerun
anything (:class:`concurrent.futures.process.BrokenProcessPool` ends the whole
pool) and fails every unfinished job at once.  Whatever the failure (a lost
worker or an exception raised by the job), the jobs that had already finished
are still yielded before the error is raised, so a caller storing results as
they arrive keeps every finished one.

The executor cannot change a result: the wake cache's code digest does not
cover this module (see :mod:`aircraft.wake.records`).
"""
from __future__ import annotations

import multiprocessing
from concurrent.futures import ProcessPoolExecutor, as_completed
from concurrent.futures.process import BrokenProcessPool
from urllib.parse import urlsplit

__all__ = ["make_executor", "SerialExecutor", "LocalPoolExecutor", "DaskExecutor",
           "SchedulerError", "DaskNotInstalledError", "WorkerLostError"]

#: Dask communication protocols a scheduler address may name
_PROTOCOLS = ("tcp", "tls", "ws", "wss", "ucx")


class SchedulerError(ValueError):
    """A scheduler address that is not ``"<protocol>://host:port"``, or an unusable client."""


class DaskNotInstalledError(ImportError):
    """A Dask scheduler was given but ``distributed`` is not installed."""


class WorkerLostError(RuntimeError):
    """A worker process died (killed, out of memory) while running a job, which was not rerun.

    Attributes
    ----------
    names : tuple of str
        The jobs lost with it (the one a Dask cluster gave up on; every
        unfinished job of a broken local pool, which cannot tell which one
        its dead worker was running).
    """

    def __init__(self, message, names=()):
        super().__init__(message)
        self.names = tuple(names)


def _job_names(jobs, names):
    """``jobs`` as a list and one label per job (``names``, or ``"job <i>"``)."""
    jobs = list(jobs)
    if names is None:
        return jobs, [f"job {k}" for k in range(len(jobs))]
    names = [str(n) for n in names]
    if len(names) != len(jobs):
        raise ValueError(f"names: {len(names)} names for {len(jobs)} jobs")
    return jobs, names


class SerialExecutor:
    """Runs every job in this process, in order."""

    name = "serial"

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    def map_unordered(self, fn, jobs, names=None):
        """Yield ``fn(job)`` for each job.

        Parameters
        ----------
        fn : callable
            Called as ``fn(job)``.
        jobs : iterable
            The jobs.
        names : sequence of str, optional
            Unused (no worker can be lost); accepted for a common interface.

        Yields
        ------
        object
            ``fn(job)``, in job order.
        """
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

    def map_unordered(self, fn, jobs, names=None):
        """Yield ``fn(job)`` for each job as it finishes.

        Parameters
        ----------
        fn : callable
            A picklable (module-level) function, called as ``fn(job)`` in a worker.
        jobs : iterable
            Picklable jobs.
        names : sequence of str, optional
            One label per job, for the error naming the jobs a dead worker lost.

        Yields
        ------
        object
            ``fn(job)``, in completion order.

        Raises
        ------
        WorkerLostError
            A worker process died: the pool is broken and every unfinished job
            is lost (named in the message); the finished ones were yielded first.
        Exception
            The exception a job raised, after the finished jobs were yielded.
        """
        jobs, names = _job_names(jobs, names)
        futures = {self._pool.submit(fn, job): name for job, name in zip(jobs, names)}
        handed = set()
        for fut in as_completed(futures):
            if fut.exception() is None:
                handed.add(fut)
                yield fut.result()
                continue
            # hand over every job that did finish before reporting the failure
            for other, _ in list(futures.items()):
                if other not in handed and other.done() and not other.cancelled() \
                        and other.exception() is None:
                    handed.add(other)
                    yield other.result()
            if isinstance(fut.exception(), BrokenProcessPool):
                lost = [name for f, name in futures.items() if f not in handed]
                raise WorkerLostError(
                    f"a worker process of the local pool died (killed by a signal, or out of "
                    f"memory?) while running one of {lost}; the pool cannot rerun them: none of "
                    f"these has a result ({len(handed)} finished job(s) were handed over first).",
                    lost) from fut.exception()
            fut.result()     # re-raises the job's own exception


def _import_distributed():
    try:
        import distributed
    except ImportError as e:
        raise DaskNotInstalledError(
            "a Dask scheduler was given but dask.distributed is not installed: "
            "`pip install distributed` (or `pip install rotorwake-id[cluster]`)") from e
    return distributed


def _check_address(address):
    """``address`` if it is ``"<protocol>://host:port"``, else :class:`SchedulerError`."""
    text = address.strip()
    try:
        parts = urlsplit(text)
        port = parts.port
    except ValueError as e:   # a port that is not a number, or out of range
        raise SchedulerError(f"scheduler address {address!r}: {e}; expected 'tcp://host:port'") from None
    if parts.scheme not in _PROTOCOLS or "://" not in text:
        raise SchedulerError(f"scheduler address {address!r} must start with one of "
                             f"{[p + '://' for p in _PROTOCOLS]}, e.g. 'tcp://127.0.0.1:8786'")
    if not parts.hostname or port is None:
        raise SchedulerError(f"scheduler address {address!r} must name a host and a port, "
                             "e.g. 'tcp://127.0.0.1:8786'")
    if parts.path not in ("", "/") or parts.query or parts.fragment:
        raise SchedulerError(f"scheduler address {address!r} must be only '<protocol>://host:port'")
    return text


def _run_task(initializer, fn, job):
    """Body of one Dask task: the per-thread set-up, then the job."""
    if initializer is not None:
        initializer()
    return fn(job)


class DaskExecutor:
    """The workers of a Dask ``distributed`` cluster.

    Parameters
    ----------
    scheduler : str or distributed.Client
        A scheduler address ``"tcp://host:port"`` (a client is opened on entry
        and closed on exit), or a connected synchronous ``Client`` (used as is
        and left open).
    initializer : callable, optional
        Picklable; run on the worker before every task (e.g. one numba thread).
    timeout : float
        Seconds to wait for the scheduler when connecting to an address [s].

    Raises
    ------
    DaskNotInstalledError
        ``distributed`` is not installed (an ImportError).
    SchedulerError
        A malformed address, a closed or asynchronous client (a ValueError).
    TypeError
        ``scheduler`` is neither a string nor a Client.

    Notes
    -----
    A wake run is one process's worth of numba and NumPy work that holds the
    GIL between kernel calls, so start the workers with one thread each and one
    process per core, e.g. ``dask scheduler`` then, on every machine,
    ``dask worker tcp://host:8786 --nworkers <cores> --nthreads 1``. The workers
    need this package (the same version: :func:`aircraft.wake.run_sweeps`
    refuses results from other wake code) but not the caller's filesystem.

    A worker that dies takes every task it holds with it, and the scheduler
    counts the death against each of them (``allowed-failures``): set
    ``distributed.scheduler.worker-saturation: 1.0`` on the scheduler so a
    one-thread worker holds only the task it runs, and a job that keeps
    killing its workers is the one named by :class:`WorkerLostError`.
    """

    name = "dask"

    def __init__(self, scheduler, initializer=None, timeout=30.0):
        if not isinstance(scheduler, str) and type(scheduler).__name__ != "Client":
            raise TypeError("scheduler must be a Dask scheduler address 'tcp://host:port' or a "
                            f"dask.distributed.Client, got {type(scheduler).__name__}")
        distributed = _import_distributed()
        if isinstance(scheduler, str):
            scheduler = _check_address(scheduler)
        elif not isinstance(scheduler, distributed.Client):
            raise TypeError("scheduler must be a Dask scheduler address 'tcp://host:port' or a "
                            f"dask.distributed.Client, got {type(scheduler).__module__}.Client")
        else:
            if scheduler.asynchronous:
                raise SchedulerError("scheduler: an asynchronous dask.distributed.Client cannot be "
                                     "used; pass a synchronous one or its address")
            if scheduler.status != "running":
                raise SchedulerError(f"scheduler: the dask.distributed.Client is {scheduler.status!r}, "
                                     "not running (closed?)")
        if isinstance(timeout, bool) or not isinstance(timeout, (int, float)) or not timeout > 0:
            raise ValueError(f"timeout must be a positive number of seconds, got {timeout!r}")
        self.scheduler, self.initializer, self.timeout = scheduler, initializer, float(timeout)
        self._client, self._owned = None, False

    def __enter__(self):
        distributed = _import_distributed()
        if isinstance(self.scheduler, str):
            try:
                self._client = distributed.Client(self.scheduler, timeout=self.timeout,
                                                  set_as_default=False)
            except OSError as e:
                raise OSError(f"cannot reach the Dask scheduler at {self.scheduler!r} within "
                              f"{self.timeout:g} s: {e}") from e
            self._owned = True
        else:
            self._client, self._owned = self.scheduler, False
        return self

    def __exit__(self, *exc):
        if self._owned and self._client is not None:
            self._client.close()
        self._client = None
        return False

    def map_unordered(self, fn, jobs, names=None):
        """Yield ``fn(job)`` for each job as it finishes on the cluster.

        Parameters
        ----------
        fn : callable
            A module-level function importable on the workers, called as ``fn(job)``.
        jobs : iterable
            Picklable jobs.
        names : sequence of str, optional
            One label per job, for the error naming a job the cluster gave up on.

        Yields
        ------
        object
            ``fn(job)``, in completion order. A task whose worker died is rerun
            on another worker by Dask (up to its ``allowed-failures``).

        Raises
        ------
        WorkerLostError
            The workers running a job died more often than Dask allows
            (``distributed.KilledWorker``); the message names the job.
        Exception
            The exception a task raised.

        Notes
        -----
        On a failure, the jobs already finished are yielded first, then the error
        is raised and the tasks not yet finished are cancelled.
        """
        distributed = _import_distributed()
        client = self._client
        if client is None:
            raise RuntimeError("DaskExecutor.map_unordered must be called inside `with executor:`")
        jobs, names = _job_names(jobs, names)
        futures = [client.submit(_run_task, self.initializer, fn, job, pure=False) for job in jobs]
        name_of = dict(zip(futures, names))
        pending = set(futures)
        try:
            for fut in distributed.as_completed(futures, loop=client.loop):
                if fut.status == "finished":
                    result = fut.result()
                    pending.discard(fut)
                    fut.release()   # the result is here now: free it on the cluster
                    yield result
                    continue
                # a failure: first hand over every task that did finish
                pending.discard(fut)
                for other in [f for f in futures if f in pending and f.status == "finished"]:
                    result = other.result()
                    pending.discard(other)
                    other.release()
                    yield result
                try:
                    fut.result()
                except distributed.KilledWorker as e:
                    allowed = getattr(e, "allowed_failures", None)
                    tries = ("on every try the scheduler allows" if allowed is None else
                             f"on each of its {allowed + 1} tries")
                    raise WorkerLostError(
                        f"job {name_of[fut]!r}: the Dask worker running it died (killed, or out of "
                        f"memory?) {tries} (distributed.scheduler.allowed-failures); it has no "
                        f"result.",
                        [name_of[fut]]) from e
        finally:
            if pending:
                client.cancel(list(pending))


def make_executor(n_jobs=2, initializer=None, scheduler=None):
    """The executor for ``n_jobs`` workers, or for a Dask cluster.

    Parameters
    ----------
    n_jobs : int
        Without a scheduler: 1 runs in this process, >= 2 in a local process
        pool of that size. Ignored (but validated) with a scheduler.
    initializer : callable, optional
        Picklable; run once in each pool worker, or before each Dask task.
    scheduler : str or distributed.Client, optional
        None (default): this machine. A Dask scheduler address
        ``"tcp://host:port"`` or a ``dask.distributed.Client``: that cluster.

    Returns
    -------
    SerialExecutor or LocalPoolExecutor or DaskExecutor
        A context manager; nothing starts or connects until it is entered.

    Raises
    ------
    ValueError
        ``n_jobs`` is not an integer >= 1.
    SchedulerError, TypeError, DaskNotInstalledError
        See :class:`DaskExecutor`.
    """
    if isinstance(n_jobs, bool) or not hasattr(n_jobs, "__index__") or int(n_jobs) < 1:
        raise ValueError(f"n_jobs must be an integer >= 1, got {n_jobs!r}")
    if initializer is not None and not callable(initializer):
        raise TypeError(f"initializer must be callable or None, got {type(initializer).__name__}")
    if scheduler is not None:
        return DaskExecutor(scheduler, initializer)
    return SerialExecutor() if int(n_jobs) <= 1 else LocalPoolExecutor(int(n_jobs), initializer)
