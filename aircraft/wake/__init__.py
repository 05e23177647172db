"""Lightweight time-accurate free-vortex wake for single and coaxial rotors.

Architecture
------------
::

    settings.py     WakeSettings, FlightCondition (dataclasses, SI / rad)
    biot_savart.py  segment_velocity (numba, parallel over targets; chained
                    segments reuse 1/|P - A|), segment_influence, Vatistas n=2 core
                    + core growth; array-in / array-out so a GPU kernel can slot in
    segments_common.py  input checks and the numpy reference of the kernel, shared
                    by the CPU and GPU kernels (no import circle between them)
    wake.py         FreeVortexWake: rigid ~30 deg near wake, one free tip vortex per
                    blade marched with a PC2B-type predictor-corrector, frozen
                    far-wake buffer and a far-wake continuation
    blades.py       lifting-line blade solve (linear lift, stall limit,
                    Kutta-Joukowski) and the flap step (rigid or spring-hinge)
    kinematics.py   compiled near-wake geometry of the blades (numba)
    initial_wake.py prescribed starting tip vortices (Landgrebe hover / skewed helix)
    reference.py    the former numpy near-wake helpers: the reference march
                    (FreeVortexWake._reference_march, same numbers; benchmark baseline)
    errors.py       WakeDivergedError (leaf: wake raises, trim catches)
    far_wake.py     convected / prescribed helical far-wake continuation (sources only)
    threads.py      single-threaded BLAS while numba kernels run
    outputs.py      blade-sum loads and inflow harmonics (Eqs. 2.22, 2.25, 2.26)
    trim.py         trim_wake (thrust / coaxial torque balance, zero hub moments),
                    run_wake (prescribed controls -> pandas.DataFrame)
    cache.py        checked disk cache: atomic writes, schema + code version, SHA-256,
                    finite values; bad entries warned about and recomputed
    records.py      what one record computes (trim a fresh wake, march one input
                    record from it): the numbers-producing part of run_sweeps
    executor.py     where independent runs execute, one interface (map_unordered,
                    completion order): this process, a local process pool (the
                    default), or a Dask distributed cluster (scheduler= address or
                    Client; dask imported only then)
    sweeps.py       run_sweeps: sweeps, doublets and multisine records (SweepSpec,
                    MultisineSpec) through the executor with tqdm and a disk cache
                    keyed on a hash of every input, written by the calling process
                    as each run arrives
    gpu.py          segment_velocity on a CUDA device (numba.cuda), chosen by
                    biot_savart.kernel_backend() when a device passes its self-check

Conventions follow :mod:`aircraft.inflow.base` (each rotor in its own frame).
"""
from .settings import WakeSettings, FlightCondition, WakeSettingsError
from .biot_savart import segment_velocity, segment_velocity_numpy, core_radius
from .wake import FreeVortexWake, WakeDivergedError
from .trim import WakeTrim, WakeTrimError, WakeInputError, trim_wake, run_wake
from .sweeps import run_sweeps, MultisineSpec, SweepSpec, SweepSpecError
from .cache import CACHE_ENV, CacheStoreWarning, CacheWarning, CacheWriteError, WakeCache, WakeCacheError, resolve_cache_dir
from .executor import make_executor, SchedulerError, DaskNotInstalledError, WorkerLostError

__all__ = ["WakeSettings", "FlightCondition", "WakeSettingsError",
           "segment_velocity", "segment_velocity_numpy", "core_radius",
           "FreeVortexWake", "WakeDivergedError",
           "WakeTrim", "WakeTrimError", "WakeInputError", "trim_wake", "run_wake",
           "run_sweeps", "MultisineSpec", "SweepSpec", "SweepSpecError",
           "CACHE_ENV", "CacheWarning", "CacheStoreWarning", "CacheWriteError", "WakeCache", "WakeCacheError", "resolve_cache_dir",
           "make_executor", "SchedulerError", "DaskNotInstalledError", "WorkerLostError"]
