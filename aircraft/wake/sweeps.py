"""Sweep driver: frequency sweeps and doublets on the trimmed wake, in parallel.

The cache (:mod:`aircraft.wake.cache`) lives in the ``cache_dir`` argument, else
the folder named by the environment variable ``ROTORWAKE_CACHE_DIR``, else
``.cache/wake``; its keys also hold a digest of the wake's source code.
Entries are written atomically by the calling process as soon as each run's
result arrives (the workers, which may be on a Dask cluster without this
machine's filesystem, write nothing), and checked (schema, code version, key,
length, SHA-256, finite values) on every read, so a sweep set killed midway and
started again reuses every finished run, recomputes only the rest and never
reads a partial file; a bad entry is reported with a
:class:`~aircraft.wake.cache.CacheWarning` and recomputed. Faults end in a
correct result or a clear error, never in a bad entry: two processes filling
the same entry both get whole, checked files (the last one written wins); a
worker killed mid-run is rerun elsewhere by a Dask cluster or ends the sweep
with a :class:`~aircraft.wake.executor.WorkerLostError` naming the lost runs
(the finished ones are stored first); a full disk turns each store into a
:class:`~aircraft.wake.cache.CacheStoreWarning` and the computed runs are
still returned. Where the runs
execute (this process, a local pool, a Dask cluster) is the executor's
business (:mod:`aircraft.wake.executor`) and cannot change a result or a key.

Each run is cached on disk (``.cache/wake/<hash>.pkl``) keyed on a SHA-256 of
every input (configuration, settings, flight condition, trim request, input
signal and requested points) and of the wake's own source code, so repeating a
study costs nothing and a code change never serves an old result.
"""
from __future__ import annotations

import functools
import hashlib
import json
import warnings
from dataclasses import dataclass, asdict
from pathlib import Path

import numpy as np

from .._validation import real as _real
from .cache import (CacheStoreWarning, CacheWriteError, WakeCache, WakeCacheError, _finite_tree,
                    check_finite_frame, resolve_cache_dir)
from .executor import make_executor
from .records import _run_spec, _trim   # noqa: F401 - looked up here at call time (tests patch them)

__all__ = ["MultisineSpec", "SweepSpec", "SweepSpecError", "run_sweeps", "sweep_inputs"]

_CACHE_VERSION = "wake-4"   # bump when the marching code changes results (4: common low-passed buffer
#                            velocity, convected far wake, flap MBC columns, TPP inputs)


#: Modules of this package that cannot change a number (orchestration: cache I/O,
#: keys and progress, where runs execute, re-exports). The cache's code digest leaves
#: them out so that a new executor keeps a cache of hours of wake runs; the input
#: signals they generate are keyed by content instead (:func:`_signal_digest`).
_ORCHESTRATION = ("__init__.py", "cache.py", "executor.py", "sweeps.py", "gpu.py")


def _wake_code_digest():
    """SHA-256 of the wake's numbers-producing source files and the configurations.

    Part of every cache key: an entry computed by other marching code (even a
    changed rounding, e.g. the Biot-Savart kernel) is never served, without
    relying on anyone remembering to bump _CACHE_VERSION. The orchestration
    modules (:data:`_ORCHESTRATION`) are left out; the GPU kernel's source joins
    the key when that kernel is the one in use (:func:`_kernel_key`).
    """
    digest = hashlib.sha256()
    here = Path(__file__).resolve().parent
    for path in sorted(here.glob("*.py")) + [here.parent / "configs.py"]:
        if path.name in _ORCHESTRATION and path.parent == here:
            continue
        digest.update(path.name.encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()


def _kernel_key():
    """Cache-key entries of the Biot-Savart backend: none for the CPU kernel (its
    source is in the code digest), the backend name and its source otherwise."""
    from .biot_savart import kernel_backend
    backend = kernel_backend()
    if backend == "cpu":
        return {}
    src = Path(__file__).resolve().parent / "gpu.py"
    return {"kernel": backend, "kernel_code": hashlib.sha256(src.read_bytes()).hexdigest()}


def _blade_key(config):
    """Cache-key entry of the real-blade model: its source (``aircraft/blade.py``,
    which computes the sections' lift and drag outside this package) when a rotor
    uses one, nothing for the classical blade, whose numbers are all in the wake's
    own modules (so the dissertation's aircraft keep their entries)."""
    if all(getattr(r, "blade", None) is None for r in config.rotors):
        return {}
    src = Path(__file__).resolve().parent.parent / "blade.py"
    return {"blade_code": hashlib.sha256(src.read_bytes()).hexdigest()}


def _signal_digest(spec, dt):
    """SHA-256 of the input time histories ``spec`` produces at step ``dt`` [s]: the
    key holds what the wake is driven with, whatever code generated it."""
    digest = hashlib.sha256()
    for control, (t, u) in sorted(spec.inputs(dt).items()):
        digest.update(control.encode() + b"\0")
        digest.update(np.ascontiguousarray(t, dtype=np.float64).tobytes())
        digest.update(np.ascontiguousarray(u, dtype=np.float64).tobytes())
    return digest.hexdigest()


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
    kind : {"sweep", "doublet", "sine", "step"}
        ``"step"``: zero until ``trim_start``, a linear ramp over ``pulse_width``
        to ``amplitude``, then held to ``duration`` (the quasi-steady check,
        :func:`aircraft.identification.quasi_steady_check`).
    amplitude : float
        [rad].
    duration : float
        [s].
    w_min, w_max : float
        Sweep frequency range [rad/s] (``"sine"`` uses ``w_min``).
    pulse_width : float
        Doublet pulse width, or the step's ramp time [s].
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
        if self.kind not in ("sweep", "doublet", "sine", "step"):
            raise SweepSpecError(f"SweepSpec.kind must be 'sweep', 'doublet', 'sine' or 'step', got {self.kind!r}")
        self._validate()

    def _validate(self):
        e = SweepSpecError
        if not isinstance(self.control, str) or not self.control:
            raise e(f"SweepSpec.control must be a control name such as 'theta0_U', got {self.control!r}")
        _real(e, "SweepSpec.duration", self.duration, positive=True, unit="s")
        _real(e, "SweepSpec.amplitude", self.amplitude, unit="rad")
        # a swashplate input of more than 0.5 rad (29 deg) is no small perturbation
        if abs(self.amplitude) > 0.5:
            raise e(f"SweepSpec.amplitude must be within +-0.5 rad, got {self.amplitude!r}")
        for name, unit in (("w_min", "rad/s"), ("w_max", "rad/s"), ("pulse_width", "s")):
            _real(e, f"SweepSpec.{name}", getattr(self, name), positive=True, unit=unit)
        for name in ("trim_start", "trim_end"):
            _real(e, f"SweepSpec.{name}", getattr(self, name), nonnegative=True, unit="s")
        _real(e, "SweepSpec.noise_fraction", self.noise_fraction, nonnegative=True)
        if self.kind == "step" and not self.trim_start + self.pulse_width < self.duration:
            raise e(f"SweepSpec step: trim_start + pulse_width ({self.trim_start} + {self.pulse_width} s) must "
                    f"end before duration ({self.duration} s), or nothing is held")
        if self.kind == "sweep" and not self.w_max > self.w_min:
            raise e(f"SweepSpec.w_max ({self.w_max}) must exceed w_min ({self.w_min}) [rad/s]")
        if self.seed is not None and (isinstance(self.seed, bool) or not isinstance(self.seed, (int, np.integer))):
            raise e(f"SweepSpec.seed must be an integer or None, got {self.seed!r}")
        if not isinstance(self.label, str):
            raise e(f"SweepSpec.label must be a string, got {self.label!r}")

    @property
    def name(self):
        return self.label or f"{self.kind}_{self.control}"

    @property
    def controls(self):
        """Controls this record moves."""
        return (self.control,)

    def inputs(self, dt):
        """``{control: (t, u)}``: the record's input time history [s, rad] at step ``dt`` [s]."""
        return {self.control: sweep_inputs(self, dt)}


@dataclass(frozen=True)
class MultisineSpec:
    """One record exciting several controls at once with orthogonal multisines.

    The controls get disjoint harmonic sets of ``2 pi / duration`` in
    ``[w_min, w_max]`` with Schroeder-like phases
    (:func:`flightid.orthogonal_multisine`), so one record replaces one sweep per
    control (the dissertation's recommendation 6); estimate the MIMO response
    with :func:`flightid.mimo_response`.

    Parameters
    ----------
    controls : tuple of str
        Controls moved together (canonical names, e.g. the six swashplate
        controls ``("theta0_U", "theta1s_U", ..., "theta1c_L")``); unique.
    amplitude : float
        Peak value of every control's input [rad] (<= 0.5).
    duration : float
        Multisine period and record length [s] (after ``trim_start``).
    w_min, w_max : float
        Excited band [rad/s].
    spectrum : {"flat", "log"}
        Harmonic amplitudes (see :func:`flightid.orthogonal_multisine`); "log"
        gives equal power per decade like the exponential sweeps.
    fade : float
        Half-cosine fade-in/out [s] at the ends of the multisine.
    trim_start : float
        Seconds at trim before the multisine starts [s].
    seed : int or None
        Seed of the start phases (reproducibility).
    label : str
        Name of the run (default ``"multisine_<n>controls"``).
    """

    controls: tuple
    amplitude: float = 0.02
    duration: float = 60.0
    w_min: float = 0.7
    w_max: float = 30.0
    spectrum: str = "log"
    fade: float = 0.5
    trim_start: float = 0.5
    seed: int | None = 0
    label: str = ""

    def __post_init__(self):
        e = SweepSpecError
        controls = self.controls
        if isinstance(controls, str) or not isinstance(controls, (tuple, list)) or not controls:
            raise e(f"MultisineSpec.controls must be a non-empty tuple of control names, got {controls!r}")
        if any(not isinstance(c, str) or not c for c in controls):
            raise e(f"MultisineSpec.controls must hold control names (strings), got {controls!r}")
        if len(set(controls)) != len(controls):
            raise e(f"MultisineSpec.controls must be unique, got {controls!r}")
        object.__setattr__(self, "controls", tuple(controls))
        _real(e, "MultisineSpec.duration", self.duration, positive=True, unit="s")
        _real(e, "MultisineSpec.amplitude", self.amplitude, positive=True, unit="rad")
        if self.amplitude > 0.5:
            raise e(f"MultisineSpec.amplitude must be within 0.5 rad, got {self.amplitude!r}")
        for name in ("w_min", "w_max"):
            _real(e, f"MultisineSpec.{name}", getattr(self, name), positive=True, unit="rad/s")
        if not self.w_max > self.w_min:
            raise e(f"MultisineSpec.w_max ({self.w_max}) must exceed w_min ({self.w_min}) [rad/s]")
        for name in ("fade", "trim_start"):
            _real(e, f"MultisineSpec.{name}", getattr(self, name), nonnegative=True, unit="s")
        if self.spectrum not in ("flat", "log"):
            raise e(f"MultisineSpec.spectrum must be 'flat' or 'log', got {self.spectrum!r}")
        if self.seed is not None and (isinstance(self.seed, bool) or not isinstance(self.seed, (int, np.integer))):
            raise e(f"MultisineSpec.seed must be an integer or None, got {self.seed!r}")
        if not isinstance(self.label, str):
            raise e(f"MultisineSpec.label must be a string, got {self.label!r}")

    @property
    def name(self):
        """Name of the run."""
        return self.label or f"multisine_{len(self.controls)}controls"

    def multisine(self, dt):
        """The :class:`flightid.Multisine` of this record at step ``dt`` [s] (time from its start).

        Parameters
        ----------
        dt : float
            Sample time [s].
        """
        from flightid import orthogonal_multisine   # imported here: optional dependency
        try:
            return orthogonal_multisine(len(self.controls), self.duration, dt, self.w_min, self.w_max,
                                        self.amplitude, spectrum=self.spectrum, fade=self.fade, seed=self.seed)
        except ValueError as err:
            raise SweepSpecError(f"MultisineSpec {self.name!r}: {err}") from None

    def inputs(self, dt):
        """``{control: (t, u)}`` [s, rad] at step ``dt`` [s]: trim, then the multisines.

        Parameters
        ----------
        dt : float
            Sample time [s].
        """
        ms = self.multisine(dt)
        n0 = int(round(self.trim_start / dt))
        t = dt * np.arange(n0 + ms.t.size + 1)
        out = {}
        for j, c in enumerate(self.controls):
            u = np.concatenate([np.zeros(n0), ms.U[:, j], [0.0]])
            out[c] = (t, u)
        return out


class SweepSpecError(ValueError):
    """A :class:`SweepSpec` field is NaN, infinite, complex, of the wrong type or out of range."""


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
    if spec.kind == "step":
        return t, spec.amplitude * np.clip((t - spec.trim_start) / spec.pulse_width, 0.0, 1.0)
    return t, spec.amplitude * np.sin(spec.w_min * t)


def _key(payload: dict) -> str:
    text = json.dumps(payload, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()[:24]


def _init_pool_worker(backend=None):
    # one kernel thread per worker: the pool already fills the cores; and the
    # caller's Biot-Savart backend (the cache key holds it, see _kernel_key)
    import numba
    numba.set_num_threads(1)
    if backend is not None:
        from .biot_savart import kernel_backend, set_kernel_backend
        if kernel_backend() != backend:
            set_kernel_backend(backend)


def _check_run(spec):
    """Content check of a stored/served run: finite numbers, and the record of ``spec``."""
    want = asdict(spec)

    def check(df):
        check_finite_frame(df, f"run {spec.name!r}")
        if df.attrs.get("spec") != want:
            raise WakeCacheError(f"run {spec.name!r}: the entry records spec {df.attrs.get('spec')!r}")
        if "t" not in df.columns:
            raise WakeCacheError(f"run {spec.name!r}: no time column 't'")
    return check


def _check_trim(value):
    """A stored/served trim must be a converged WakeTrim with a finite state."""
    from .trim import WakeTrim
    if not (isinstance(value, tuple) and len(value) == 2 and isinstance(value[1], WakeTrim)):
        raise WakeCacheError("trim entry: expected (snapshot, WakeTrim)")
    snap, tr = value
    if not tr.converged:
        raise WakeCacheError(f"trim entry: the trim did not converge (residual {tr.residual:.3g})")
    bad = _finite_tree(snap, "snapshot") + _finite_tree(tr.controls, "controls") \
        + _finite_tree(tr.outputs, "outputs") + _finite_tree(float(tr.residual), "residual")
    if bad:
        raise WakeCacheError(f"trim entry: NaN or infinite values in {bad[:5]}")


def _code_identity():
    """What must match between the caller and a worker for a result to be cached
    under the caller's key: the wake code digest and the Biot-Savart backend."""
    from .biot_savart import kernel_backend
    return _wake_code_digest(), kernel_backend()


def _worker(args):
    """One run, in whichever process the executor chose; stores nothing (the
    caller does, as each result arrives: a cluster worker may not see its disk)."""
    config, settings, flight, snap, trim_result, spec, points = args
    df = _run_spec(config, settings, flight, snap, trim_result, spec, points)
    df.attrs["spec"] = asdict(spec)
    check = _check_run(spec)
    try:
        check(df)
    except WakeCacheError as e:
        raise WakeCacheError(f"the wake run produced an unusable record, not stored: {e}") from None
    return spec.name, df, _code_identity()


def _store(cache, key, value, kind, check, what):
    """Store ``value``, or on a full disk warn (:class:`CacheStoreWarning`) and carry on.

    A sweep must not lose hours of computed runs because the cache has no room
    left: the value is still returned to the caller, only not cached.  Any other
    write failure (a read-only or vanished folder) is a set-up error and raised.
    """
    if cache is None:
        return
    try:
        cache.store(key, value, kind=kind, check=check)
    except CacheWriteError as e:
        if not e.no_space:
            raise
        warnings.warn(f"{what} is computed but not cached: {e}. Free space in "
                      f"{cache.directory} (or set cache_dir) to keep results", CacheStoreWarning,
                      stacklevel=3)


def _control_names(config):
    """Swashplate controls, then the prescribed tip-path-plane inputs (rigid-flap wakes)."""
    from ..inflow.base import rotor_suffix
    return [f"{k}{rotor_suffix(r.name)}" for r in config.rotors for k in ("theta0", "theta1s", "theta1c")] \
        + [f"{k}{rotor_suffix(r.name)}" for r in config.rotors for k in ("beta1s", "beta1c")]


def run_sweeps(config, settings, flight, specs, *, trim=None, points=None, n_jobs=2,
               cache_dir="default", progress=True, scheduler=None):
    """Trim once, then run every input record from the trimmed wake in parallel.

    Parameters
    ----------
    config : AircraftConfig
    settings : WakeSettings
    flight : FlightCondition
    specs : sequence of SweepSpec or MultisineSpec
        Input records (a MultisineSpec moves several controls in one record).
    trim : dict, optional
        Keyword arguments of :func:`aircraft.wake.trim_wake` (e.g. ``ct``, ``mode``).
        The trim must converge: the sweeps never start from an unconverged trim.
    points : dict, optional
        Off-rotor points ``{label: (x, y, z)}`` in body axes [m].
    n_jobs : int
        Worker processes (1: run in this process); ignored with ``scheduler``.
    cache_dir : str or Path or None
        Disk cache folder; None disables the cache.  The default, ``"default"``,
        is the environment variable ``ROTORWAKE_CACHE_DIR`` if set (an empty
        value, ``0`` or ``off`` disables the cache), else ``.cache/wake``.
    progress : bool
        Show a tqdm progress bar over the runs (advanced as each run finishes,
        whichever executor ran it).
    scheduler : str or dask.distributed.Client, optional
        None (default): the runs execute on this machine (``n_jobs``). A Dask
        scheduler address ``"tcp://host:port"`` or a ``Client``: on that
        cluster's workers (see :mod:`aircraft.wake.executor`), which need this
        package installed but not this machine's filesystem. The results and
        the cache entries are the same whichever executor ran them: this process
        trims, keys and stores every run, and refuses a result computed by other
        wake code or another Biot-Savart backend than its own.

    Returns
    -------
    dict
        ``{spec.name: pandas.DataFrame}`` (see :func:`aircraft.wake.run_wake`) plus
        ``"trim"``: the :class:`~aircraft.wake.WakeTrim`.

    Raises
    ------
    WakeTrimError
        The trim did not converge (its residual is in the message); nothing is run.
    SweepSpecError, ValueError
        Bad specs (unknown control, duplicate names), points or arguments.
    SchedulerError, TypeError, DaskNotInstalledError
        A bad ``scheduler`` (see :class:`aircraft.wake.executor.DaskExecutor`),
        raised before anything is computed.
    WakeCacheError
        A worker ran other wake code (its code digest or kernel backend differs
        from this process's); its result is not stored.
    WorkerLostError
        A worker process died while running a record and it was not rerun (a
        local pool cannot; a Dask cluster gave up after its allowed failures);
        the message names the records without a result. Every run finished
        before is in the cache, so calling again computes only the rest.
    CacheWriteError
        The cache folder cannot be written for a reason other than a full disk
        (read-only, vanished); an OSError.

    Warns
    -----
    CacheWarning
        A cache entry was corrupt, truncated, stale or held the wrong contents; it
        is recomputed.
    CacheStoreWarning
        The disk is full: a computed run (or the trim) could not be cached; it is
        returned all the same.

    Examples
    --------
    Two sweeps and a doublet of the UH-60-like rotor in hover, trimmed to C_T = 0.0061
    (a few minutes on 2 cores; cached under ``.cache/wake``):

    >>> from aircraft import uh60_single_rotor
    >>> from aircraft.wake import FlightCondition, SweepSpec, WakeSettings, run_sweeps
    >>> specs = [SweepSpec("theta0", kind="sweep", amplitude=0.02, duration=45.0, w_min=0.7, w_max=30.0),
    ...          SweepSpec("theta1s", kind="sweep", amplitude=0.02, duration=45.0, w_min=0.7, w_max=30.0, seed=1),
    ...          SweepSpec("theta0", kind="doublet", amplitude=0.05, duration=4.0, pulse_width=0.5)]
    >>> runs = run_sweeps(uh60_single_rotor(), WakeSettings(), FlightCondition(), specs,
    ...                   trim={"ct": 0.0061})                        # doctest: +SKIP
    >>> runs[specs[0].name][["CT", "lam0"]].describe()              # doctest: +SKIP
    """
    from tqdm.auto import tqdm
    from ..configs import AircraftConfig
    from .settings import FlightCondition, WakeSettings
    from .trim import WakeTrimError

    for name, value, cls in (("config", config, AircraftConfig), ("settings", settings, WakeSettings),
                             ("flight", flight, FlightCondition)):
        if not isinstance(value, cls):
            raise TypeError(f"{name} must be an aircraft {cls.__name__}, got {type(value).__name__}")
    if isinstance(specs, (SweepSpec, MultisineSpec)):
        specs = [specs]
    specs = list(specs)
    if not specs:
        raise SweepSpecError("run_sweeps needs at least one SweepSpec")
    controls = _control_names(config)
    for k, s in enumerate(specs):
        if not isinstance(s, (SweepSpec, MultisineSpec)):
            raise SweepSpecError(f"specs[{k}] must be a SweepSpec or MultisineSpec, got {type(s).__name__}")
        unknown = [c for c in s.controls if c not in controls]
        if unknown:
            what = f"control {unknown[0]!r}" if len(unknown) == 1 else f"controls {unknown}"
            raise SweepSpecError(f"{type(s).__name__} {s.name!r}: unknown {what}; "
                                 f"this configuration has {controls}")
    names = [s.name for s in specs]
    if len(set(names)) != len(names):
        raise SweepSpecError(f"SweepSpec names must be unique, got {names}")
    if isinstance(n_jobs, bool) or not isinstance(n_jobs, (int, np.integer)) or n_jobs < 1:
        raise ValueError(f"n_jobs must be an integer >= 1, got {n_jobs!r}")
    if trim is not None and not isinstance(trim, dict):
        raise TypeError(f"trim must be a dict of trim_wake keyword arguments, got {type(trim).__name__}")
    for label, p in dict(points or {}).items():
        if not isinstance(label, str) or not label:
            raise ValueError(f"point labels must be non-empty strings, got {label!r}")
        arr = np.asarray(p)
        if arr.shape != (3,) or not np.isrealobj(arr) or not np.all(np.isfinite(arr.astype(float))):
            raise ValueError(f"point {label!r} must be three finite real coordinates (x, y, z) [m], "
                             f"got {p!r}")
    from .biot_savart import kernel_backend
    # built (and the scheduler validated) before the trim; nothing starts until entered
    executor = make_executor(n_jobs, initializer=functools.partial(_init_pool_worker, kernel_backend()),
                             scheduler=scheduler)
    trim = dict(trim or {})
    points = dict(points or {})
    base = {"v": _CACHE_VERSION, "code": _wake_code_digest(), "config": repr(config), "settings": asdict(settings),
            "flight": asdict(flight), "trim": trim,
            "points": {k: list(map(float, v)) for k, v in points.items()}, **_kernel_key(), **_blade_key(config)}
    dt = settings.azimuth_step / float(config.rotors[0].omega)   # the wake's time step [s]
    keys = {s.name: _key({**base, "spec": asdict(s), "signal": _signal_digest(s, dt)}) for s in specs}
    folder = resolve_cache_dir(cache_dir)
    cache = WakeCache(folder, _CACHE_VERSION) if folder is not None else None
    results, todo = {}, []
    for s in specs:
        df = cache.load(keys[s.name], kind="run", check=_check_run(s)) if cache is not None else None
        if df is None:
            todo.append(s)
        else:
            results[s.name] = df
    trim_key = f"trim-{_key(base)}"
    cached_trim = cache.load(trim_key, kind="trim", check=_check_trim) if cache is not None else None
    if cached_trim is None:
        snap, trim_result = _trim(config, settings, flight, trim)
        if not trim_result.converged:
            raise WakeTrimError(
                f"run_sweeps: the wake trim did not converge in {trim_result.iterations} iterations "
                f"(largest load residual {trim_result.residual:.3g}); refusing to run sweeps from "
                "it. Loosen tol, raise max_iter, or check the thrust target.", trim_result)
        _store(cache, trim_key, (snap, trim_result), "trim", _check_trim, "the wake trim")
    else:
        snap, trim_result = cached_trim
    jobs = [(config, settings, flight, snap, trim_result, s, points) for s in todo]
    if len(jobs) == 1 and scheduler is None:
        executor = make_executor(1)   # no pool for one run
    by_name = {s.name: s for s in specs}
    identity = _code_identity()
    bar = tqdm(total=len(specs), initial=len(specs) - len(todo), desc="wake sweeps",
               disable=not progress)
    try:
        if jobs:
            with executor:
                names = [job[5].name for job in jobs]
                for name, df, worker_identity in executor.map_unordered(_worker, jobs, names=names):
                    if worker_identity != identity:
                        raise WakeCacheError(
                            f"run {name!r} was computed by other wake code or another Biot-Savart "
                            f"backend (worker: digest {worker_identity[0][:12]}, kernel "
                            f"{worker_identity[1]!r}; this process: {identity[0][:12]}, "
                            f"{identity[1]!r}); install the same version on the workers. Not stored.")
                    # stored here, as each run arrives: a kill later loses nothing finished
                    _store(cache, keys[name], df, "run", _check_run(by_name[name]), f"run {name!r}")
                    results[name] = df
                    bar.update()
    finally:
        bar.close()
    out = {s.name: results[s.name] for s in specs}
    out["trim"] = trim_result
    return out
