"""Executors of run_sweeps: serial, local pool, Dask cluster.

A real (tiny) wake set is run by each executor; the kernel is deterministic
(each target's induced velocity is summed in the same order by whichever thread
or process computes it, and BLAS is single-threaded while the wake marches), so
the DataFrames must be *exactly* equal, not close, and the cache entries the
calling process writes must carry the same keys and contents. The serial run is
the independent reference: no pickling, no other process.
"""
import functools
import logging
import math
import operator
import shutil
import socket
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

import aircraft.wake.sweeps as sweeps_module
from aircraft.configs import uh60_single_rotor
from aircraft.wake import (DaskNotInstalledError, FlightCondition, SchedulerError, SweepSpec,
                           WakeCache, WakeCacheError, WakeSettings, WakeTrim, make_executor,
                           run_sweeps)
from aircraft.wake.executor import DaskExecutor, LocalPoolExecutor, SerialExecutor

CFG = uh60_single_rotor()
# the smallest wake that still trims (30 deg steps, one revolution of free wake, 3
# blade elements): each 0.5 s record is ~1-2 s of marching on a busy 2-core machine
SETTINGS = WakeSettings(azimuth_step=math.radians(30), wake_revolutions=1.0, n_elements=3)
FLIGHT = FlightCondition()
TRIM = {"ct": 0.0061}
SPECS = [SweepSpec("theta0", kind="sine", amplitude=0.01, duration=0.5, w_min=5.0, label="collective"),
         SweepSpec("theta1s", kind="sine", amplitude=0.02, duration=0.5, w_min=8.0, label="lateral")]


def _entries(folder):
    return {p.name for p in Path(folder).glob("*.pkl")}


def _run(folder, **kw):
    t0 = time.perf_counter()
    out = run_sweeps(CFG, SETTINGS, FLIGHT, SPECS, trim=TRIM, cache_dir=folder,
                     progress=kw.pop("progress", False), **kw)
    return out, time.perf_counter() - t0


def _seed_with_trim(reference, folder):
    """A fresh cache holding only the reference's trim: the executor under test
    computes every run (the trim is done by the calling process anyway)."""
    folder.mkdir()
    for p in Path(reference).glob("trim-*.pkl"):
        shutil.copy(p, folder / p.name)


def _assert_same(out, reference):
    for s in SPECS:
        # exact: the same deterministic kernel ran the same inputs
        pd.testing.assert_frame_equal(out[s.name], reference[s.name], check_exact=True)
        assert out[s.name].attrs == reference[s.name].attrs


def _assert_same_cache(folder, reference_folder):
    assert _entries(folder) == _entries(reference_folder)
    cache = WakeCache(folder, sweeps_module._CACHE_VERSION)
    ref = WakeCache(reference_folder, sweeps_module._CACHE_VERSION)
    for name in _entries(folder):
        if not name.startswith("trim-"):
            key = name[:-len(".pkl")]
            pd.testing.assert_frame_equal(cache.load(key), ref.load(key), check_exact=True)


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    folder = tmp_path_factory.mktemp("serial")
    out, wall = _run(folder, n_jobs=1)
    assert len(_entries(folder)) == len(SPECS) + 1          # every run and the trim
    return out, folder, wall


@pytest.fixture(scope="module")
def cluster():
    distributed = pytest.importorskip("distributed", reason="the `cluster` extra is not installed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None, silence_logs=logging.ERROR) as cl, \
            distributed.Client(cl, set_as_default=False) as client:
        yield cl, client


@pytest.mark.slow
def test_local_pool_gives_the_serial_results_and_cache(serial, tmp_path):
    ref, ref_folder, _ = serial
    folder = tmp_path / "pool"
    _seed_with_trim(ref_folder, folder)
    out, _ = _run(folder, n_jobs=2)
    _assert_same(out, ref)
    _assert_same_cache(folder, ref_folder)


@pytest.mark.slow
def test_dask_cluster_gives_the_serial_results_and_cache(serial, cluster, tmp_path, capsys):
    ref, ref_folder, _ = serial
    cl, client = cluster
    folder = tmp_path / "client"
    _seed_with_trim(ref_folder, folder)
    out, _ = _run(folder, scheduler=client, progress=True)
    _assert_same(out, ref)
    _assert_same_cache(folder, ref_folder)
    err = capsys.readouterr().err
    assert "wake sweeps" in err and "2/2" in err           # the bar advanced as runs arrived
    assert client.status == "running"                      # a passed-in client is left open

    # by address; one run already cached: only the other one goes to the cluster
    folder = tmp_path / "address"
    _seed_with_trim(ref_folder, folder)
    key = next(n for n in _entries(ref_folder) if not n.startswith("trim-"))
    shutil.copy(ref_folder / key, folder / key)
    out, _ = _run(folder, scheduler=cl.scheduler_address)
    _assert_same(out, ref)
    _assert_same_cache(folder, ref_folder)


def test_dask_tasks_get_one_numba_thread_and_the_callers_kernel(cluster):
    _, client = cluster

    def probe(_):   # local function: cloudpickle sends it by value
        import numba
        from aircraft.wake.biot_savart import kernel_backend
        return numba.get_num_threads(), kernel_backend()

    # a worker's numba default is one thread per core (2 here, so this can fail);
    # the setting is per thread and sticks, so it is set before every task
    init = functools.partial(sweeps_module._init_pool_worker, "cpu")
    with make_executor(initializer=init, scheduler=client) as ex:
        assert list(ex.map_unordered(probe, range(4))) == [(1, "cpu")] * 4


def test_dask_executor_yields_every_result_and_raises_a_task_error(cluster):
    _, client = cluster
    with make_executor(scheduler=client) as ex:
        assert sorted(ex.map_unordered(operator.neg, range(6))) == [-5, -4, -3, -2, -1, 0]
        with pytest.raises(ValueError, match="math domain error"):
            list(ex.map_unordered(math.sqrt, [4.0, -1.0, 9.0]))


def test_make_executor_picks_the_executor():
    assert isinstance(make_executor(1), SerialExecutor)
    assert isinstance(make_executor(3), LocalPoolExecutor) and make_executor(3).n_jobs == 3
    with make_executor(1) as ex:
        assert list(ex.map_unordered(operator.neg, [1, 2])) == [-1, -2]


@pytest.mark.parametrize("scheduler, error, match", [
    (8786, TypeError, "scheduler must be a Dask scheduler address 'tcp://host:port' or a "
                      "dask.distributed.Client, got int"),
    ("localhost:8786", SchedulerError, "must start with one of"),
    ("http://localhost:8786", SchedulerError, "must start with one of"),
    ("tcp://localhost", SchedulerError, "must name a host and a port"),
    ("tcp://:8786", SchedulerError, "must name a host and a port"),
    ("tcp://localhost:port", SchedulerError, "expected 'tcp://host:port'"),
    ("tcp://localhost:99999", SchedulerError, "expected 'tcp://host:port'"),
    ("tcp://localhost:8786/x", SchedulerError, "must be only"),
])
def test_bad_schedulers_are_refused(scheduler, error, match):
    pytest.importorskip("distributed")
    with pytest.raises(error, match=match):
        make_executor(2, scheduler=scheduler)


def test_bad_n_jobs_and_initializer_are_refused():
    for bad in (0, 2.0, True, "2"):
        with pytest.raises(ValueError, match="n_jobs must be an integer >= 1"):
            make_executor(bad)
    with pytest.raises(TypeError, match="initializer must be callable or None, got int"):
        make_executor(2, initializer=1)


def test_a_missing_dask_names_the_package_to_install(monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)   # `import distributed` now fails
    with pytest.raises(DaskNotInstalledError, match="pip install distributed") as info:
        make_executor(2, scheduler="tcp://127.0.0.1:8786")
    assert isinstance(info.value, ImportError)


def test_a_closed_client_and_an_unreachable_scheduler(cluster):
    distributed = pytest.importorskip("distributed")
    cl, _ = cluster
    client = distributed.Client(cl, set_as_default=False)
    client.close()
    with pytest.raises(SchedulerError, match="is 'closed', not running"):
        make_executor(scheduler=client)
    with socket.socket() as s:          # a free port: nothing listens there
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    ex = DaskExecutor(f"tcp://127.0.0.1:{port}", timeout=1.0)
    with pytest.raises(OSError, match=f"cannot reach the Dask scheduler at 'tcp://127.0.0.1:{port}'"):
        with ex:
            pass
    with pytest.raises(RuntimeError, match="inside `with executor:`"):
        next(DaskExecutor(cl.scheduler_address).map_unordered(abs, [1]))
    with pytest.raises(ValueError, match="timeout must be a positive number"):
        DaskExecutor(cl.scheduler_address, timeout=0)


class _Fake:
    """Cheap stand-in for the march: what is tested is the driver, not the wake."""

    def __init__(self):
        self.trims = 0

    def trim(self, config, settings, flight, trim):
        self.trims += 1
        return {"X": 0.0}, WakeTrim(controls={"theta0": 0.15, "theta1s": 0.0, "theta1c": 0.0},
                                    outputs={"CT": 0.0061}, converged=True, iterations=1, residual=1e-9)

    def run(self, config, settings, flight, snap, trim_result, spec, points):
        return pd.DataFrame({"t": [0.0, 0.1], spec.control: [0.15, 0.15 + spec.amplitude]})


def test_run_sweeps_validates_the_scheduler_before_trimming(tmp_path, monkeypatch):
    pytest.importorskip("distributed")
    fake = _Fake()
    monkeypatch.setattr(sweeps_module, "_trim", fake.trim)
    with pytest.raises(SchedulerError, match="must name a host and a port"):
        _run(tmp_path, scheduler="tcp://nowhere")
    assert fake.trims == 0 and _entries(tmp_path) == set()


@pytest.mark.slow
def test_a_result_from_other_wake_code_is_not_stored(tmp_path, monkeypatch):
    fake = _Fake()
    monkeypatch.setattr(sweeps_module, "_trim", fake.trim)
    monkeypatch.setattr(sweeps_module, "_run_spec", fake.run)
    real = sweeps_module._worker

    def stale_worker(job):   # what a cluster worker with another version returns
        name, df, (digest, kernel) = real(job)
        return name, df, ("0" * 64, kernel)

    monkeypatch.setattr(sweeps_module, "_worker", stale_worker)
    with pytest.raises(WakeCacheError, match="computed by other wake code .* digest 000000000000.*Not stored"):
        _run(tmp_path, n_jobs=1)
    assert not any(not n.startswith("trim-") for n in _entries(tmp_path))   # no run entry
