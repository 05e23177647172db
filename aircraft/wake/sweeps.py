"""Sweep driver: frequency sweeps and doublets on the trimmed wake, in parallel.

Each run is cached on disk (``.cache/wake/<hash>.pkl``) keyed on a SHA-256 of
every input (configuration, settings, flight condition, trim request, input
signal and requested points), so repeating a study costs nothing.
"""
from __future__ import annotations

import hashlib
import json
import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, asdict, field
from pathlib import Path

import numpy as np
import pandas as pd

__all__ = ["SweepSpec", "run_sweeps", "sweep_inputs"]

_CACHE_VERSION = "wake-4"   # bump when the marching code changes results (4: common low-passed buffer
#                            velocity, convected far wake, flap MBC columns, TPP inputs)


@dataclass(frozen=True)
class SweepSpec:
    """One input record for :func:`run_sweeps`.

    Parameters
    ----------
    control : str
        Canonical control name (``"theta0_U"``, ``"theta1s"``, ...), or a
        prescribed tip-path-plane input (``"beta1s_U"``, ``"beta1c_L"``, ...; rigid
        flap wakes only): a sweep of the rotor's multiblade flap coordinate about
        its trim value, which excites the flap rates ``beta1s_dot``/``beta1c_dot``
        independently of the loads (the flap-rate input of Eq. 4.11, Sec. 6.3).
    kind : {"sweep", "doublet", "sine"}
    amplitude : float
        [rad].
    duration : float
        [s].
    w_min, w_max : float
        Sweep frequency range [rad/s] (``"sine"`` uses ``w_min``).
    pulse_width : float
        Doublet pulse width [s].
    trim_start, trim_end : float
        Sweep trim lead-in/out [s].
    seed : int or None
        Seed of the sweep's noise (reproducibility).
    noise_fraction : float
    label : str
        Name of the run (default ``"<kind>_<control>"``).
    """

    control: str
    kind: str = "sweep"
    amplitude: float = 0.01
    duration: float = 30.0
    w_min: float = 0.5
    w_max: float = 30.0
    pulse_width: float = 0.5
    trim_start: float = 1.0
    trim_end: float = 1.0
    seed: int | None = 0
    noise_fraction: float = 0.0
    label: str = ""

    def __post_init__(self):
        if self.kind not in ("sweep", "doublet", "sine"):
            raise ValueError(f"SweepSpec.kind must be 'sweep', 'doublet' or 'sine', got {self.kind!r}")
        if not self.duration > 0:
            raise ValueError("SweepSpec.duration must be positive [s]")

    @property
    def name(self):
        return self.label or f"{self.kind}_{self.control}"


def sweep_inputs(spec: SweepSpec, dt: float):
    """Input time history ``(t, u)`` of a spec [s, rad] at step ``dt`` [s]."""
    if spec.kind == "sweep":
        from flightid import frequency_sweep   # imported here: optional dependency
        return frequency_sweep(spec.w_min, spec.w_max, spec.duration, dt, spec.amplitude,
                               trim_start=spec.trim_start, trim_end=spec.trim_end,
                               noise_fraction=spec.noise_fraction, seed=spec.seed)
    if spec.kind == "doublet":
        from flightid import doublet
        return doublet(spec.amplitude, spec.pulse_width, dt, spec.duration)
    t = np.arange(0.0, spec.duration + 0.5 * dt, dt)
    return t, spec.amplitude * np.sin(spec.w_min * t)


def _key(payload: dict) -> str:
    text = json.dumps(payload, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()[:24]


def _init_pool_worker():
    # one kernel thread per worker process: the pool already fills the cores
    import numba
    numba.set_num_threads(1)


def _worker(args):
    config, settings, flight, snap, trim_result, spec, points, path = args
    from .wake import FreeVortexWake
    wake = FreeVortexWake(config, settings, flight)
    wake.restore(snap)
    wake._trim_state = snap
    wake.trim_result = trim_result
    t, u = sweep_inputs(spec, wake.dt)
    df = wake.run({spec.control: (np.asarray(t), np.asarray(u))}, duration=float(t[-1]),
                  points=points)
    df.attrs["spec"] = asdict(spec)
    if path is not None:
        tmp = f"{path}.{os.getpid()}.tmp"
        df.to_pickle(tmp)
        os.replace(tmp, path)
    return spec.name, df


def run_sweeps(config, settings, flight, specs, *, trim=None, points=None, n_jobs=2,
               cache_dir=".cache/wake", progress=True):
    """Trim once, then run every input record from the trimmed wake in parallel.

    Parameters
    ----------
    config : AircraftConfig
    settings : WakeSettings
    flight : FlightCondition
    specs : sequence of SweepSpec
    trim : dict, optional
        Keyword arguments of :func:`aircraft.wake.trim_wake` (e.g. ``ct``, ``mode``).
    points : dict, optional
        Off-rotor points ``{label: (x, y, z)}`` in body axes [m].
    n_jobs : int
        Worker processes (1: run in this process).
    cache_dir : str or Path or None
        Disk cache folder; None disables the cache.
    progress : bool
        Show a tqdm progress bar over the runs.

    Returns
    -------
    dict
        ``{spec.name: pandas.DataFrame}`` (see :func:`aircraft.wake.run_wake`) plus
        ``"trim"``: the :class:`~aircraft.wake.WakeTrim`.
    """
    from tqdm.auto import tqdm
    from .wake import FreeVortexWake

    specs = list(specs)
    if not specs:
        raise ValueError("run_sweeps needs at least one SweepSpec")
    names = [s.name for s in specs]
    if len(set(names)) != len(names):
        raise ValueError(f"SweepSpec names must be unique, got {names}")
    trim = dict(trim or {})
    points = dict(points or {})
    base = {"v": _CACHE_VERSION, "config": repr(config), "settings": asdict(settings),
            "flight": asdict(flight), "trim": trim,
            "points": {k: list(map(float, v)) for k, v in points.items()}}
    keys = {s.name: _key({**base, "spec": asdict(s)}) for s in specs}
    cache = Path(cache_dir) if cache_dir is not None else None
    results, todo = {}, []
    if cache is not None:
        cache.mkdir(parents=True, exist_ok=True)
        for s in specs:
            p = cache / f"{keys[s.name]}.pkl"
            if p.exists():
                results[s.name] = pd.read_pickle(p)
            else:
                todo.append(s)
    else:
        todo = specs
    trim_path = cache / f"trim-{_key(base)}.pkl" if cache is not None else None
    if todo or trim_path is None or not trim_path.exists():
        wake = FreeVortexWake(config, settings, flight)
        trim_result = wake.trim(**trim)
        snap = wake._trim_state
        if trim_path is not None:
            pd.to_pickle((snap, trim_result), trim_path)
    else:
        snap, trim_result = pd.read_pickle(trim_path)
    jobs = [(config, settings, flight, snap, trim_result, s, points,
             str(cache / f"{keys[s.name]}.pkl") if cache is not None else None) for s in todo]
    bar = tqdm(total=len(jobs), desc="wake sweeps", disable=not progress)
    if n_jobs <= 1 or len(jobs) <= 1:
        for job in jobs:
            name, df = _worker(job)
            results[name] = df
            bar.update()
    else:
        # "spawn", not fork: numba's OpenMP threading layer aborts a forked child
        # ("fork() called from a process already using GNU OpenMP")
        with ProcessPoolExecutor(max_workers=n_jobs, mp_context=multiprocessing.get_context("spawn"),
                                 initializer=_init_pool_worker) as pool:
            for name, df in pool.map(_worker, jobs):
                results[name] = df
                bar.update()
    bar.close()
    out = {s.name: results[s.name] for s in specs}
    out["trim"] = trim_result
    return out
