"""Fault injection for the wake cache and run_sweeps' resume.

The marching is replaced by a cheap deterministic runner (monkeypatched
``_trim``/``_run_spec``) so that every test takes well under a second of
computation: what is tested is the cache and the driver, not the wake.
"""
import os
import pickle
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from aircraft.configs import uh60_single_rotor
from aircraft.wake import (CACHE_ENV, CacheWarning, FlightCondition, SweepSpec, WakeCache,
                           WakeCacheError, WakeSettings, WakeTrim, WakeTrimError, resolve_cache_dir,
                           run_sweeps)
import aircraft.wake.sweeps as sweeps_module

CFG = uh60_single_rotor()
SETTINGS = WakeSettings()
FLIGHT = FlightCondition()
SPECS = [SweepSpec("theta0", kind="sine", amplitude=0.01 * (k + 1), duration=1.0, w_min=2.0,
                   label=f"run{k}") for k in range(4)]
#: the longer set the kill test interrupts
KILL_SPECS = SPECS + [SweepSpec("theta0", kind="sine", amplitude=0.05 + 0.01 * k, duration=1.0,
                                w_min=2.0, label=f"extra{k}") for k in range(6)]
ROOT = Path(__file__).resolve().parents[3]


def _fake_trim_result(converged=True):
    return WakeTrim(controls={"theta0": 0.15, "theta1s": 0.0, "theta1c": 0.0},
                    outputs={"CT": 0.0061, "lam0": 0.06}, converged=converged, iterations=3,
                    residual=1e-6 if converged else 6e-2)


def _expected(spec):
    """What the cheap runner returns for ``spec`` (a closed form to compare with)."""
    t = np.arange(0.0, spec.duration + 1e-9, 0.01)
    u = spec.amplitude * np.sin(spec.w_min * t)
    return pd.DataFrame({"t": t, spec.control: 0.15 + u, "CT": 0.0061 + 0.1 * u})


class Runner:
    """Counts trims and runs; ``nan_for`` makes one run return NaN."""

    def __init__(self, converged=True, nan_for=None):
        self.trims, self.runs, self.converged, self.nan_for = 0, [], converged, nan_for

    def trim(self, config, settings, flight, trim):
        self.trims += 1
        return {"X": np.zeros((2, 3)), "t": 0.0}, _fake_trim_result(self.converged)

    def run(self, config, settings, flight, snap, trim_result, spec, points):
        self.runs.append(spec.name)
        df = _expected(spec)
        if spec.name == self.nan_for:
            df.loc[5, "CT"] = np.nan
        return df


@pytest.fixture
def runner(monkeypatch):
    r = Runner()
    monkeypatch.setattr(sweeps_module, "_trim", r.trim)
    monkeypatch.setattr(sweeps_module, "_run_spec", r.run)
    return r


def _sweep(cache_dir, specs=SPECS, **kw):
    return run_sweeps(CFG, SETTINGS, FLIGHT, specs, trim={"ct": 0.0061}, n_jobs=1,
                      cache_dir=cache_dir, progress=False, **kw)


def _entries(folder):
    return sorted(p for p in Path(folder).glob("*.pkl") if not p.name.startswith("trim-"))


def _check_results(out, specs=SPECS):
    for s in specs:
        pd.testing.assert_frame_equal(out[s.name], _expected(s))


def test_second_call_is_served_from_the_cache(tmp_path, runner):
    out = _sweep(tmp_path)
    _check_results(out)
    assert runner.runs == [s.name for s in SPECS] and runner.trims == 1
    assert len(_entries(tmp_path)) == 4 and len(list(tmp_path.glob("trim-*.pkl"))) == 1
    runner.runs.clear()
    out2 = _sweep(tmp_path)
    _check_results(out2)
    assert runner.runs == [] and runner.trims == 1


@pytest.mark.parametrize("damage, reason", [
    ("garbage", "not a rotorwake cache entry|corrupt"),
    ("truncate", "truncated"),
    ("flip", "checksum"),
    ("header", "corrupt header|truncated header"),
])
def test_corrupt_or_truncated_entries_are_detected_and_recomputed(tmp_path, runner, damage, reason):
    _sweep(tmp_path)
    victim = _entries(tmp_path)[1]
    blob = victim.read_bytes()
    if damage == "garbage":
        victim.write_bytes(os.urandom(len(blob)))
    elif damage == "truncate":
        victim.write_bytes(blob[:len(blob) // 2])
    elif damage == "flip":
        i = len(blob) - 40
        victim.write_bytes(blob[:i] + bytes([blob[i] ^ 0xFF]) + blob[i + 1:])
    else:
        victim.write_bytes(blob[:20])
    runner.runs.clear()
    with pytest.warns(CacheWarning, match=reason):
        out = _sweep(tmp_path)
    _check_results(out)                       # the recomputed value, not the damaged one
    assert len(runner.runs) == 1              # only the damaged entry was recomputed
    runner.runs.clear()
    _sweep(tmp_path)                          # ... and it was stored again, cleanly
    assert runner.runs == []


def test_an_entry_copied_onto_another_key_is_wrong_contents(tmp_path, runner):
    _sweep(tmp_path)
    a, b = _entries(tmp_path)[:2]
    b.write_bytes(a.read_bytes())
    runner.runs.clear()
    with pytest.warns(CacheWarning, match="wrong contents"):
        out = _sweep(tmp_path)
    _check_results(out)
    assert len(runner.runs) == 1


def test_a_checksummed_nan_frame_is_never_served(tmp_path, runner):
    # the case: a *valid* file whose contents are NaN
    _sweep(tmp_path)
    victim = _entries(tmp_path)[0]
    key = victim.stem
    cache = WakeCache(tmp_path, sweeps_module._CACHE_VERSION)
    df = pickle.loads(pickle.dumps(cache.load(key)))
    df["CT"] = np.nan
    cache.store(key, df)                      # no check: written as a well-formed entry
    runner.runs.clear()
    with pytest.warns(CacheWarning, match="NaN or infinite values in columns \\['CT'\\]"):
        out = _sweep(tmp_path)
    _check_results(out)
    assert len(runner.runs) == 1


def test_stale_entries_from_other_code_versions_are_recomputed(tmp_path, runner):
    _sweep(tmp_path)
    victim = _entries(tmp_path)[2]
    old = WakeCache(tmp_path, "wake-0")
    old.store(victim.stem, _expected(SPECS[0]))
    runner.runs.clear()
    with pytest.warns(CacheWarning, match="stale: written by code version 'wake-0'"):
        _check_results(_sweep(tmp_path))
    assert len(runner.runs) == 1


def test_legacy_plain_pickles_are_migrated_only_when_they_pass_the_checks(tmp_path, runner):
    _sweep(tmp_path)
    files = _entries(tmp_path)
    cache = WakeCache(tmp_path, sweeps_module._CACHE_VERSION)
    good = cache.load(files[0].stem)
    bad = good.copy()
    bad.attrs = dict(good.attrs)
    bad["CT"] = np.nan
    pd.to_pickle(good, files[0])              # the old format: a bare pickle
    pd.to_pickle(bad, files[1])               # the NaN pickle, old format
    runner.runs.clear()
    with pytest.warns(CacheWarning) as record:
        _check_results(_sweep(tmp_path))
    text = " ".join(str(w.message) for w in record)
    assert "older unchecked format; it passed the content checks" in text
    assert "older-format entry with wrong contents" in text
    assert len(runner.runs) == 1              # only the NaN one was recomputed
    assert files[0].read_bytes().startswith(b"ROTORWAKE-CACHE\n")   # rewritten, checksummed


def test_a_corrupt_trim_entry_is_recomputed(tmp_path, runner):
    _sweep(tmp_path)
    (trim_file,) = tmp_path.glob("trim-*.pkl")
    trim_file.write_bytes(trim_file.read_bytes()[:-10])
    with pytest.warns(CacheWarning, match="truncated"):
        out = _sweep(tmp_path)
    assert runner.trims == 2 and out["trim"].converged


def test_sweeps_refuse_an_unconverged_trim_and_cache_nothing(tmp_path, monkeypatch):
    r = Runner(converged=False)
    monkeypatch.setattr(sweeps_module, "_trim", r.trim)
    monkeypatch.setattr(sweeps_module, "_run_spec", r.run)
    with pytest.raises(WakeTrimError, match="did not converge .* residual 0.06.*refusing to run sweeps"):
        _sweep(tmp_path)
    assert r.runs == [] and list(tmp_path.glob("*.pkl")) == []


def test_a_non_finite_run_is_an_error_and_is_not_stored(tmp_path, monkeypatch):
    r = Runner(nan_for="run2")
    monkeypatch.setattr(sweeps_module, "_trim", r.trim)
    monkeypatch.setattr(sweeps_module, "_run_spec", r.run)
    with pytest.raises(WakeCacheError, match="unusable record, not stored.*'run2'.*NaN"):
        _sweep(tmp_path)
    assert len(_entries(tmp_path)) == 2       # run0, run1 kept; run2 never written


def test_a_failed_write_leaves_neither_entry_nor_temporary_file(tmp_path, runner, monkeypatch):
    def broken_fsync(fd):
        raise OSError("disk full (injected)")
    monkeypatch.setattr(os, "fsync", broken_fsync)
    with pytest.raises(OSError, match="injected"):
        _sweep(tmp_path)
    assert list(tmp_path.iterdir()) == []      # no entry, no partial, no temporary file


def test_leftover_temporary_files_are_never_read(tmp_path, runner):
    _sweep(tmp_path)
    victim = _entries(tmp_path)[0]
    partial = tmp_path / f".{victim.name}.99999.deadbeef.tmp"
    partial.write_bytes(victim.read_bytes()[:50])   # what a kill mid-write leaves
    victim.unlink()
    runner.runs.clear()
    _check_results(_sweep(tmp_path))
    assert len(runner.runs) == 1


def test_cache_location_from_argument_environment_and_default(tmp_path, runner, monkeypatch):
    monkeypatch.delenv(CACHE_ENV, raising=False)
    assert resolve_cache_dir() == Path(".cache/wake")
    assert resolve_cache_dir(None) is None
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "env"))
    assert resolve_cache_dir() == tmp_path / "env"
    _sweep("default")
    assert len(_entries(tmp_path / "env")) == 4
    _sweep(tmp_path / "arg")                          # an argument wins over the variable
    assert len(_entries(tmp_path / "arg")) == 4
    monkeypatch.setenv(CACHE_ENV, "off")
    assert resolve_cache_dir() is None
    with pytest.raises(WakeCacheError, match="cache_dir must be a folder path"):
        resolve_cache_dir(3)


_KILL_SCRIPT = textwrap.dedent("""
    import sys, time
    import numpy as np, pandas as pd
    sys.path[:0] = [sys.argv[2]]
    from tests.aircraft.wake.test_wake_cache import KILL_SPECS, Runner, CFG, SETTINGS, FLIGHT
    import aircraft.wake.sweeps as sw
    r = Runner()
    def slow_run(*args):
        time.sleep(0.4)                  # long enough to be killed in the middle of the set
        return r.run(*args)
    sw._trim, sw._run_spec = r.trim, slow_run
    sw.run_sweeps(CFG, SETTINGS, FLIGHT, KILL_SPECS, trim={"ct": 0.0061}, n_jobs=1,
                  cache_dir=sys.argv[1], progress=False)
""")


@pytest.mark.slow
def test_a_sweep_set_killed_midway_resumes_with_every_finished_run(tmp_path, monkeypatch):
    specs = KILL_SPECS
    script = tmp_path / "kill_me.py"
    script.write_text(_KILL_SCRIPT)
    folder = tmp_path / "cache"
    proc = subprocess.Popen([sys.executable, str(script), str(folder), str(ROOT)], cwd=ROOT)
    try:
        deadline = time.time() + 120
        while time.time() < deadline and proc.poll() is None:
            if folder.exists() and len(_entries(folder)) >= 3:
                break
            time.sleep(0.05)
        assert proc.poll() is None, "the sweep set finished before it could be killed"
        os.kill(proc.pid, signal.SIGKILL)      # no clean-up handlers run
        proc.wait(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
    done = len(_entries(folder))
    assert 3 <= done < len(specs)
    r = Runner()
    monkeypatch.setattr(sweeps_module, "_trim", r.trim)
    monkeypatch.setattr(sweeps_module, "_run_spec", r.run)
    out = _sweep(folder, specs=specs)
    _check_results(out, specs)
    assert len(r.runs) == len(specs) - done    # only the unfinished runs are recomputed
    assert r.trims == 0                        # the converged trim was cached before the runs
    assert set(r.runs) == {s.name for s in specs[done:]}
