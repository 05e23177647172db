"""Runs that survive faults: concurrent writers, killed workers, a full disk.

Each fault must end in either a correct result or a clear error, and leave no
corrupt, partial or temporary file that could ever be read.  The marching is
replaced by a cheap closed form (what is tested is the cache, the executors and
the driver, not the wake); the processes and the Dask workers are real, and a
worker is killed with SIGKILL (no clean-up handler runs), as the kernel's
out-of-memory killer or an operator would.
"""
import errno
import functools
import logging
import multiprocessing
import os
import pickle
import re
import signal
import sys
import traceback
import warnings
from dataclasses import asdict
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import aircraft.wake.cache as cache_module
import aircraft.wake.sweeps as sweeps_module
from aircraft.configs import uh60_single_rotor
from aircraft.wake import (CacheWarning, FlightCondition, SweepSpec, WakeCache, WakeSettings,
                           WakeTrim, run_sweeps)
from aircraft.wake.cache import CacheStoreWarning, CacheWriteError, check_finite_frame
from aircraft.wake.executor import LocalPoolExecutor, WorkerLostError, make_executor

# every test here shares a fixture that takes seconds to build: not in the quick set (make test-quick)
pytestmark = [pytest.mark.skipif(sys.platform == "win32", reason="SIGKILL and POSIX rename semantics"),
              pytest.mark.slow]

CFG = uh60_single_rotor()
SETTINGS = WakeSettings()
FLIGHT = FlightCondition()
SPECS = [SweepSpec("theta0", kind="sine", amplitude=0.01 * (k + 1), duration=1.0, w_min=2.0,
                   label=f"run{k}") for k in range(4)]
VERSION = sweeps_module._CACHE_VERSION
SPAWN = multiprocessing.get_context("spawn")   # as the library's pool: no fork of numba threads


# ---------------------------------------------------------------- fake marching
def _expected(spec):
    """What the cheap runner returns for ``spec`` (a closed form to compare with)."""
    t = np.arange(0.0, spec.duration + 1e-9, 0.01)
    u = spec.amplitude * np.sin(spec.w_min * t)
    return pd.DataFrame({"t": t, spec.control: 0.15 + u, "CT": 0.0061 + 0.1 * u})


def _fake_trim(config, settings, flight, trim):
    return {"X": np.zeros((2, 3)), "t": 0.0}, WakeTrim(
        controls={"theta0": 0.15, "theta1s": 0.0, "theta1c": 0.0}, outputs={"CT": 0.0061},
        converged=True, iterations=3, residual=1e-6)


def _fake_run(config, settings, flight, snap, trim_result, spec, points):
    return _expected(spec)


def _killing_worker(kill, job):
    """Stands in for ``sweeps._worker`` in a worker process.

    ``kill = (case, marker)``: running ``case``, the worker process SIGKILLs itself
    (every time if ``marker`` is None, else only when the file ``marker`` does not
    exist yet, which it creates first: a one-off kill).
    """
    case, marker = kill
    spec = job[5]
    if spec.name == case and (marker is None or not os.path.exists(marker)):
        if marker is not None:
            Path(marker).write_text(str(os.getpid()))
        os.kill(os.getpid(), signal.SIGKILL)
    df = _expected(spec)
    df.attrs["spec"] = asdict(spec)
    return spec.name, df, sweeps_module._code_identity()


@pytest.fixture
def fake(monkeypatch):
    monkeypatch.setattr(sweeps_module, "_trim", _fake_trim)
    monkeypatch.setattr(sweeps_module, "_run_spec", _fake_run)


def _sweep(folder, **kw):
    kw.setdefault("n_jobs", 1)
    return run_sweeps(CFG, SETTINGS, FLIGHT, SPECS, trim={"ct": 0.0061}, cache_dir=folder,
                      progress=False, **kw)


def _check_results(out, names=None):
    for s in SPECS:
        if names is None or s.name in names:
            pd.testing.assert_frame_equal(out[s.name], _expected(s), check_exact=True)


def _check_folder(folder):
    """Every entry in ``folder`` reads back valid (no CacheWarning) and holds the
    expected run; no temporary or stray file. Returns the names of the runs stored."""
    folder = Path(folder)
    files = sorted(p.name for p in folder.iterdir())
    assert all(n.endswith(".pkl") and not n.startswith(".") for n in files), files
    cache = WakeCache(folder, VERSION)
    by_name = {s.name: s for s in SPECS}
    stored = []
    with warnings.catch_warnings():
        warnings.simplefilter("error", CacheWarning)
        for n in files:
            if n.startswith("trim-"):
                assert cache.load(n[:-4], kind="trim", check=sweeps_module._check_trim) is not None
                continue
            df = cache.load(n[:-4], kind="run")
            spec = by_name[df.attrs["spec"]["label"]]
            sweeps_module._check_run(spec)(df)
            pd.testing.assert_frame_equal(df, _expected(spec), check_exact=True)
            stored.append(spec.name)
    assert len(stored) == len(set(stored)) and sum(n.startswith("trim-") for n in files) <= 1, files
    return sorted(stored)


# ------------------------------------------------- 1. two processes, one entry
_RACE_ROUNDS = 8


def _race_value():
    # a few MB, so that each write takes long enough for the two to overlap
    rng = np.random.default_rng(7)
    return pd.DataFrame(rng.standard_normal((40_000, 3)), columns=["t", "a", "b"])


def _race_process(folder, barrier, report):
    """One of two processes: store the same entry together with the other one,
    round after round, and read it back; then run the same sweep set at the same
    time. Anything but the right value (an exception, a CacheWarning, a wrong
    frame) is reported."""
    try:
        warnings.simplefilter("error", CacheWarning)    # a bad read would only warn
        cache = WakeCache(Path(folder) / "store", VERSION)
        value = _race_value()
        for _ in range(_RACE_ROUNDS):
            barrier.wait(timeout=60)
            cache.store("same-key", value, kind="run", check=check_finite_frame)
            got = cache.load("same-key", kind="run", check=check_finite_frame)
            if got is None or not got.equals(value):
                raise AssertionError(f"read back {type(got).__name__}, not the value stored")
        sweeps_module._trim, sweeps_module._run_spec = _fake_trim, _fake_run
        barrier.wait(timeout=60)
        out = _sweep(Path(folder) / "sweep")
        _check_results(out)
        report.put("ok")
    except BaseException:
        barrier.abort()          # the other process stops waiting for this one
        report.put(traceback.format_exc())


@pytest.fixture(scope="module")
def race(tmp_path_factory):
    folder = tmp_path_factory.mktemp("race")
    barrier, report = SPAWN.Barrier(2), SPAWN.Queue()
    procs = [SPAWN.Process(target=_race_process, args=(str(folder), barrier, report))
             for _ in range(2)]
    for p in procs:
        p.start()
    try:
        reports = [report.get(timeout=120) for _ in procs]
    finally:
        for p in procs:
            p.join(timeout=30)
            if p.is_alive():
                p.kill()
    return folder, reports


def test_two_processes_storing_the_same_entry_both_read_back_their_value(race):
    folder, reports = race
    assert reports == ["ok", "ok"], "\n".join(reports)
    assert sorted(p.name for p in (folder / "store").iterdir()) == ["same-key.pkl"]   # no *.tmp
    with warnings.catch_warnings():
        warnings.simplefilter("error", CacheWarning)
        got = WakeCache(folder / "store", VERSION).load("same-key", check=check_finite_frame)
    pd.testing.assert_frame_equal(got, _race_value(), check_exact=True)


def test_two_processes_running_the_same_sweep_set_fill_the_cache_correctly(race, fake):
    folder, reports = race
    assert reports == ["ok", "ok"], "\n".join(reports)          # both got every run right
    assert sorted(_check_folder(folder / "sweep")) == [s.name for s in SPECS]
    # and a third caller is served entirely from what the two left
    calls = []
    sweeps_module._run_spec = lambda *a: calls.append(a) or _fake_run(*a)
    _check_results(_sweep(folder / "sweep"))
    assert calls == []


def test_a_bad_entry_replaced_by_another_process_is_not_deleted(tmp_path):
    cache = WakeCache(tmp_path, VERSION)
    good = _expected(SPECS[0])
    cache.store("k", good)
    cache.path("k").write_bytes(cache.path("k").read_bytes()[:-10])      # truncated
    real_discard = WakeCache._discard

    def discard_after_a_rewrite(self, p, why, identity=None):
        # the other process finishes its (good) entry between our read and our delete
        self.store("k", good)
        return real_discard(self, p, why, identity)

    cache._discard = discard_after_a_rewrite.__get__(cache)
    with pytest.warns(CacheWarning, match="truncated"):
        assert cache.load("k") is None                        # this caller recomputes...
    assert cache.path("k").exists()                           # ...the other's entry stays
    pd.testing.assert_frame_equal(WakeCache(tmp_path, VERSION).load("k"), good)


# ----------------------------------------------------- 2. a worker killed mid-sweep
@pytest.fixture(scope="module")
def cluster():
    distributed = pytest.importorskip("distributed", reason="the `cluster` extra is not installed")
    import dask
    # one task at a time per one-thread worker (Dask's default queues a second one
    # there): a killed worker then takes only the task it was running with it, so
    # the job the scheduler gives up on is the one that kills, not a bystander
    with dask.config.set({"distributed.scheduler.worker-saturation": 1.0}), \
            distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                     dashboard_address=None, silence_logs=logging.CRITICAL) as cl, \
            distributed.Client(cl, set_as_default=False) as client:
        yield cl, client


def _finished_last(real):
    """``distributed.as_completed`` that waits for every task and yields the failed
    ones first: the order in which a finished job can be stranded behind a failure."""
    def as_completed(futures, **kw):
        futures = list(futures)
        for _ in real(futures, **kw):
            pass
        return sorted(futures, key=lambda f: f.status == "finished")
    return as_completed


def test_finished_dask_jobs_are_handed_over_before_a_failure(cluster, monkeypatch):
    import distributed
    import math
    _, client = cluster
    monkeypatch.setattr(distributed, "as_completed", _finished_last(distributed.as_completed))
    got = []
    with make_executor(scheduler=client) as ex, pytest.raises(ValueError, match="math domain error"):
        for value in ex.map_unordered(math.sqrt, [4.0, -1.0, 9.0], names=["a", "b", "c"]):
            got.append(value)
    assert sorted(got) == [2.0, 3.0]


def test_a_dask_worker_killed_mid_sweep_is_replaced_and_the_sweep_completes(cluster, fake, tmp_path,
                                                                            monkeypatch):
    _, client = cluster
    client.wait_for_workers(2, timeout=60)
    before = set(client.run(os.getpid).values())
    marker = tmp_path / "killed-once"
    monkeypatch.setattr(sweeps_module, "_worker", functools.partial(_killing_worker, ("run1", str(marker))))
    out = _sweep(tmp_path / "cache", scheduler=client)
    assert int(marker.read_text()) in before                 # a worker really was killed, in run1
    _check_results(out)                                      # and run1 was rerun on another one
    assert sorted(_check_folder(tmp_path / "cache")) == [s.name for s in SPECS]


def test_a_case_that_keeps_killing_dask_workers_is_named_and_nothing_partial_is_stored(
        cluster, fake, tmp_path, monkeypatch):
    cl, client = cluster
    # the scheduler gives up at the first death (Dask's default reruns 3 times): a short test
    monkeypatch.setattr(cl.scheduler, "allowed_failures", 0)
    monkeypatch.setattr(sweeps_module, "_worker", functools.partial(_killing_worker, ("run2", None)))
    with pytest.raises(WorkerLostError, match=r"job 'run2': the Dask worker running it died "
                                              r"\(killed, or out of memory\?\) on each of its 1 tries") as err:
        _sweep(tmp_path / "cache", scheduler=client)
    assert err.value.names == ("run2",) and isinstance(err.value, RuntimeError)
    stored = _check_folder(tmp_path / "cache")               # all valid, no temporary file
    assert "run2" not in stored
    # run again once the case is fixed: only what has no entry is computed
    monkeypatch.undo()
    calls = []
    monkeypatch.setattr(sweeps_module, "_trim", _fake_trim)
    monkeypatch.setattr(sweeps_module, "_run_spec", lambda *a: calls.append(a[5].name) or _fake_run(*a))
    _check_results(_sweep(tmp_path / "cache"))
    assert sorted(calls) == sorted(set(s.name for s in SPECS) - set(stored))


def test_a_killed_local_pool_worker_is_a_clear_error_naming_the_case(monkeypatch):
    # a local pool cannot rerun anything (BrokenProcessPool ends it): the error
    # names every job left without a result, and the finished ones come first,
    # even when the failure is seen before them (the order forced here)
    from concurrent.futures.process import BrokenProcessPool
    import aircraft.wake.executor as executor_module
    from tests.aircraft.wake._fault_jobs import kill_on
    real = executor_module.as_completed

    def failed_first(futures):
        futures = list(real(futures))
        return sorted(futures, key=lambda f: f.exception() is None)
    monkeypatch.setattr(executor_module, "as_completed", failed_first)
    got = []
    with LocalPoolExecutor(2) as ex, pytest.raises(WorkerLostError) as err:
        for value in ex.map_unordered(kill_on, ["a", "kill", "b", "c"], names=["a", "kill", "b", "c"]):
            got.append(value)
    assert isinstance(err.value, RuntimeError) and isinstance(err.value.__cause__, BrokenProcessPool)
    assert "kill" in err.value.names and not set(got) & set(err.value.names)
    assert "a" in got                      # done long before "kill" (0.5 s) killed its worker
    assert sorted(got + list(err.value.names)) == ["a", "b", "c", "kill"]
    assert re.search(r"worker process of the local pool died \(killed by a signal, or out of memory\?\) "
                     r"while running one of \[.*'kill'.*\]", str(err.value))


# --------------------------------------------------------------- 3. a full disk
def _no_space(*args, **kwargs):
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


class _FillingFile:
    """A file whose disk fills up after ``room`` bytes: writes what fits, then ENOSPC."""

    def __init__(self, f, room):
        self._f, self._room = f, room

    def write(self, data):
        if len(data) > self._room:
            self._f.write(data[:self._room])
            self._f.flush()                    # the partial file really is on disk
            self._room = 0
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        self._room -= len(data)
        return self._f.write(data)

    def __getattr__(self, name):
        return getattr(self._f, name)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self._f.close()
        return False


def _disk_full(monkeypatch, where, room=100):
    """Make the cache's next writes fail with ENOSPC at ``where``."""
    if where == "write":
        real_open = open

        def filling_open(path, mode="r", *a, **kw):
            f = real_open(path, mode, *a, **kw)
            return _FillingFile(f, room) if "w" in mode else f
        monkeypatch.setattr(cache_module, "open", filling_open, raising=False)
    elif where == "fsync":
        monkeypatch.setattr(os, "fsync", _no_space)
    else:
        monkeypatch.setattr(os, "replace", _no_space)


@pytest.mark.parametrize("where", ["write", "fsync", "replace"])
def test_a_full_disk_fails_the_store_cleanly_and_keeps_the_old_entry(tmp_path, monkeypatch, where):
    cache = WakeCache(tmp_path, VERSION)
    old, new = _expected(SPECS[0]), _expected(SPECS[1])
    cache.store("k", old)
    _disk_full(monkeypatch, where)
    with pytest.raises(CacheWriteError, match=r"\[Errno 28\] cannot write wake cache entry .*k\.pkl") as err:
        cache.store("k", new)
    assert err.value.errno == errno.ENOSPC and err.value.no_space and isinstance(err.value, OSError)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["k.pkl"]      # no partial temporary file
    monkeypatch.undo()
    pd.testing.assert_frame_equal(cache.load("k"), old)                 # untouched


@pytest.mark.parametrize("where", ["write", "fsync"])
def test_a_sweep_on_a_full_disk_warns_and_still_returns_every_run(tmp_path, fake, monkeypatch, where):
    _disk_full(monkeypatch, where)
    with pytest.warns(CacheStoreWarning, match="not cached.*No space left on device") as record:
        out = _sweep(tmp_path)
    _check_results(out)                                       # nothing computed is lost
    warned = " ".join(str(w.message) for w in record if w.category is CacheStoreWarning)
    assert "the wake trim" in warned and all(f"run {s.name!r}" in warned for s in SPECS)
    assert list(tmp_path.iterdir()) == []                     # no entry, no partial, no *.tmp
    monkeypatch.undo()
    monkeypatch.setattr(sweeps_module, "_trim", _fake_trim)
    monkeypatch.setattr(sweeps_module, "_run_spec", _fake_run)
    _check_results(_sweep(tmp_path))
    assert sorted(_check_folder(tmp_path)) == [s.name for s in SPECS]


def test_a_disk_filling_up_midway_keeps_the_entries_written_before(tmp_path, fake, monkeypatch):
    real_fsync, calls = os.fsync, []

    def fsync_until_full(fd):
        calls.append(fd)
        if len(calls) > 3:                    # the trim and two runs fit
            _no_space()
        real_fsync(fd)
    monkeypatch.setattr(os, "fsync", fsync_until_full)
    with pytest.warns(CacheStoreWarning) as record:
        out = _sweep(tmp_path)
    _check_results(out)
    assert [str(w.message).split(" is computed")[0] for w in record] == ["run 'run2'", "run 'run3'"]
    assert _check_folder(tmp_path) == ["run0", "run1"]


def test_an_unwritable_cache_folder_is_an_error_not_a_warning(tmp_path, fake, monkeypatch):
    def read_only(*args, **kwargs):
        raise OSError(errno.EROFS, os.strerror(errno.EROFS))
    monkeypatch.setattr(os, "fsync", read_only)
    with pytest.raises(CacheWriteError, match="Read-only file system") as err:
        _sweep(tmp_path)
    assert not err.value.no_space
    assert list(tmp_path.iterdir()) == []


def test_an_older_format_entry_is_served_when_the_disk_is_too_full_to_rewrite_it(tmp_path, monkeypatch):
    cache = WakeCache(tmp_path, VERSION)
    value = _expected(SPECS[0])
    cache.path("k").write_bytes(pickle.dumps(value))             # a plain pickle of earlier versions
    monkeypatch.setattr(os, "fsync", _no_space)
    with pytest.warns(CacheStoreWarning, match="could not be rewritten"):
        got = cache.load("k", check=check_finite_frame)
    pd.testing.assert_frame_equal(got, value)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["k.pkl"]
