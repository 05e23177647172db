"""Inflow identification from multisine records of all the controls at once.

:func:`identify_inflow_multisine` is :func:`aircraft.identification.identify_inflow`
with the one-control-at-a-time sweeps replaced by a single record in which every
control of :attr:`InflowStructure.controls` moves at once with orthogonal
multisines (:class:`aircraft.wake.MultisineSpec`); the MIMO response comes from
the cross-spectral matrix (:func:`flightid.mimo_response`) and the rest of the
pipeline (joint input-output, data-driven start, fit, reduction, doublet
verification beside the noise floor) is the same. This is the dissertation's
recommendation 6: fewer wake revolutions per identification. A structure with
flap-rate inputs is excited on its prescribed tip-path-plane inputs as well, and
the controls may be divided between several records marched in parallel
(``MultisineSettings.records``, :mod:`aircraft.identification.multisine_records`).

::

    wake trim ─► ONE multisine record + doublet + zero-input run  (run_sweeps, cached)
      ─► mimo_response (C, lambda over all theta) ─► joint input-output (lambda/C)
      ─► start ─► fit ─► reduce ─► verify     (as identify_inflow)
"""
from __future__ import annotations

import datetime
import time
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .pipeline import (PIPELINE_VERSION, IdentificationSettings, IdentifiedModel, PipelineError, _code_version, _fit_and_verify, _trim_request, identification_hash)
from aircraft.inflow.model_files import SCHEMA
from .multisine_records import record_responses, split_controls
from .structures import get_structure

__all__ = ["MultisineSettings", "identify_inflow_multisine", "record_revolutions"]


@dataclass(frozen=True)
class MultisineSettings:
    """The multisine record of :func:`identify_inflow_multisine` (SI units, radians).

    Parameters
    ----------
    duration : float
        Multisine period = record length [s] (after ``trim_start``).
    amplitude : float
        Peak value of every control's multisine [rad].
    spectrum : {"flat", "log"}
        Harmonic amplitudes (:func:`flightid.orthogonal_multisine`).
    fade : float
        Half-cosine fade-in/out [s].
    trim_start : float
        Seconds at trim before the multisine [s].
    seed : int
        Seed of the start phases (record ``k`` of several uses ``seed + k``).
    records : int
        Records the excited controls are divided between (dealt out in turn,
        :func:`aircraft.identification.multisine_records.split_controls`), marched
        in parallel; each is an orthogonal multisine of its own controls. More
        records: fewer controls per record (more harmonics each, lower peak
        factors) for more revolutions in all.

    Raises
    ------
    ValueError
        A field of the wrong type or out of range.

    Examples
    --------
    >>> MultisineSettings(duration=30.0, records=2).records
    2
    """

    duration: float = 90.0
    amplitude: float = 0.02
    spectrum: str = "log"
    fade: float = 0.5
    trim_start: float = 0.5
    seed: int = 0
    records: int = 1

    def __post_init__(self):
        for name in ("duration", "amplitude"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not np.isfinite(value) \
                    or value <= 0:
                raise ValueError(f"MultisineSettings.{name} must be a positive finite number, got {value!r}")
        if self.spectrum not in ("flat", "log"):
            raise ValueError(f"MultisineSettings.spectrum must be 'flat' or 'log', got {self.spectrum!r}")
        for name in ("seed", "records"):
            value = getattr(self, name)
            if (value is not None or name == "records") and (
                    isinstance(value, bool) or not isinstance(value, (int, np.integer))):
                raise ValueError(f"MultisineSettings.{name} must be an integer, got {value!r}")
        if self.records < 1:
            raise ValueError(f"MultisineSettings.records must be at least 1, got {self.records!r}")

    def hash_fields(self):
        """The fields that key the identification (``records`` only when it is not 1).

        Returns
        -------
        dict
            Field name to value; with one record exactly the fields of the
            settings before ``records`` existed, so their hashes are unchanged.

        Examples
        --------
        >>> "records" in MultisineSettings().hash_fields()
        False
        """
        fields = dict(self.__dict__)
        if self.records == 1:
            del fields["records"]
        return fields


def record_revolutions(runs, omega):
    """Rotor revolutions marched in each wake record, ``{name: revolutions}``.

    Parameters
    ----------
    runs : dict
        ``{name: DataFrame with column "t" [s]}`` (as :func:`aircraft.wake.run_sweeps`
        returns; non-DataFrame entries such as ``"trim"`` are skipped).
    omega : float
        Rotor speed [rad/s].

    Returns
    -------
    dict
        Revolutions (record length [s] x omega / 2 pi) of each record.
    """
    if not omega > 0:
        raise ValueError(f"omega must be a positive rotor speed [rad/s], got {omega!r}")
    return {k: float(df["t"].iloc[-1] - df["t"].iloc[0]) * omega / (2 * np.pi)
            for k, df in runs.items() if isinstance(df, pd.DataFrame)}


def identify_inflow_multisine(config, condition=None, structure="coaxial_6state", *, ct=None, trim=None,
                              settings=None, multisine=None, name=None, n_jobs=2, cache_dir="default",
                              progress=True):
    """Identify an inflow model from ONE record exciting all swashplate controls at once.

    Parameters
    ----------
    config : aircraft.AircraftConfig
        Rotor(s) to identify.
    condition : aircraft.wake.FlightCondition, optional
        Flight condition (default hover).
    structure : InflowStructure or str
        Model structure (its ``controls`` are all excited; a model with flap-rate
        inputs is excited on all of its ``excitations``: the swashplate controls
        and the prescribed tip-path-plane inputs).
    ct : float, optional
        Trim thrust coefficient of the system (coaxial: split equally, torques balanced).
    trim : dict, optional
        Full trim request (overrides ``ct``).
    settings : IdentificationSettings, optional
        Wake resolution, band ``w_min``/``w_max`` [rad/s] (the multisine's band
        too), fit, reduction and verification settings; ``sweep_s`` and
        ``amplitude`` are not used.
    multisine : MultisineSettings, optional
        The multisine record(s) (default: one record, 90 s, 0.02 rad peak, log
        spectrum); with ``records > 1`` the excited controls are divided between
        that many records marched in parallel, and each control's response
        comes from the record that excites it.
    name : str, optional
        Name of the model.
    n_jobs : int
        Wake worker processes.
    cache_dir : str or None
        Wake run cache folder (see :func:`aircraft.wake.run_sweeps`).
    progress : bool
        tqdm progress.

    Returns
    -------
    IdentifiedModel
        As :func:`identify_inflow`; ``provenance["revolutions"]`` holds the
        revolutions of every wake record and ``provenance["excitation"]`` the
        multisine's harmonic sets' sizes and relative peak factors.

    Raises
    ------
    PipelineError
        Missing signals, fewer excitations than inputs, more records than
        excited controls, or inputs a record cannot separate.
    """
    from tqdm.auto import tqdm
    from aircraft.wake import FlightCondition, MultisineSpec, SweepSpec, run_sweeps
    from flightid.errors import DataError, SingularInputError
    from flightid import joint_input_output

    t_start = time.perf_counter()
    settings = settings or IdentificationSettings()
    multisine = multisine or MultisineSettings()
    if not isinstance(multisine, MultisineSettings):
        raise TypeError(f"multisine must be a MultisineSettings, got {type(multisine).__name__}")
    condition = condition or FlightCondition()
    structure = get_structure(structure)
    rotor_names = tuple(r.name for r in config.rotors)
    if len(rotor_names) > 1 and len(rotor_names) == len(structure.rotors):
        # a structure with its default names takes the aircraft's (same numbers, its signals)
        try:
            structure = structure.for_rotors(rotor_names)
        except ValueError as err:
            raise PipelineError(str(err)) from None
    if len(rotor_names) != len(structure.rotors) or (len(rotor_names) > 1 and rotor_names != structure.rotors):
        raise PipelineError(f"structure {structure.key} is for rotors {structure.rotors}; "
                            f"the configuration has {rotor_names}")
    # a structure with flap-rate inputs needs the prescribed tip-path-plane inputs too
    controls = list(structure.controls)
    if len(controls) < len(structure.inputs):
        controls = list(structure.excitations)
    if len(controls) < len(structure.inputs):
        raise PipelineError(f"{structure.key} has {len(structure.inputs)} inputs but {len(controls)} "
                            "excitations: the joint input-output needs one independent excitation per input")
    if multisine.records > len(controls):
        raise PipelineError(f"multisine.records ({multisine.records}) exceeds the {len(controls)} excited "
                            f"controls {controls}")
    trim_req = _trim_request(config, ct, trim)
    digest, payload = identification_hash(config, condition, structure, settings, trim=trim_req)
    payload = {**payload, "excitation": {"kind": "orthogonal_multisine", **multisine.hash_fields()}}
    from aircraft.provenance import settings_hash
    digest = settings_hash(payload, digits=16)
    s = settings
    groups = split_controls(controls, multisine.records)
    # one record keeps its default label (the cache key of the runs made before records existed)
    ms_specs = [MultisineSpec(group, amplitude=multisine.amplitude, duration=multisine.duration,
                              w_min=s.w_min, w_max=s.w_max, spectrum=multisine.spectrum, fade=multisine.fade,
                              trim_start=multisine.trim_start,
                              seed=None if multisine.seed is None else multisine.seed + k,
                              label="" if len(groups) == 1 else f"multisine_{k + 1}of{len(groups)}")
                for k, group in enumerate(groups)]
    # the same verification and noise-floor records as identify_inflow (shared cache entries)
    dbl_control = s.doublet_control or controls[0]
    doublet_spec = SweepSpec(dbl_control, kind="doublet", amplitude=s.doublet_amplitude, duration=s.doublet_s,
                             pulse_width=s.pulse_width)
    zero_spec = SweepSpec(dbl_control, kind="sine", amplitude=0.0, duration=s.noise_floor_s, w_min=1.0,
                          label="zero_input")
    stages = tqdm(total=4, desc=f"identify {structure.key} (multisine)", disable=not progress)
    runs = run_sweeps(config, s.wake_settings, condition, [*ms_specs, doublet_spec, zero_spec], trim=trim_req,
                      n_jobs=n_jobs, cache_dir=cache_dir, progress=progress)
    wake_trim = runs["trim"]
    stages.update()
    signals = structure.inputs + structure.outputs
    missing = sorted({c for spec in ms_specs for c in signals + list(spec.controls) if c not in runs[spec.name]})
    if missing:
        stages.close()
        raise PipelineError(f"the wake record lacks signals {missing}")
    try:
        measured = record_responses([(runs[spec.name], spec.controls) for spec in ms_specs], signals,
                                    w_min=s.w_min, w_max=s.w_max, order=controls)
        responses = joint_input_output(measured.select(structure.outputs), measured.select(structure.inputs))
    except SingularInputError as err:
        stages.close()
        raise PipelineError(f"the multisine record cannot separate the inputs: {err}") from err
    except DataError as err:
        stages.close()
        raise PipelineError(f"the multisine records ({multisine.duration:g} s) do not resolve the band "
                            f"from w_min = {s.w_min:g} rad/s: {err}") from err
    stages.update()
    omega = float(config.rotors[0].omega)
    staged, reduction, result, check, floor, start_log, fit_start = _fit_and_verify(
        structure, responses, runs, doublet_spec, zero_spec, wake_trim, omega, s, progress, stages)
    dt = s.wake_settings.azimuth_step / omega
    excitations = [spec.multisine(dt) for spec in ms_specs]
    by_control = {c: (ex, j) for spec, ex in zip(ms_specs, excitations) for j, c in enumerate(spec.controls)}
    provenance = {"source": "aircraft.identification.identify_inflow_multisine", "schema": SCHEMA,
                  "starts": start_log,
                  "pipeline": PIPELINE_VERSION, "code_version": _code_version(),
                  "created": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
                  "wall_s": round(time.perf_counter() - t_start, 1),
                  "config": getattr(config, "name", repr(config)[:60]),
                  "revolutions": record_revolutions({k: v for k, v in runs.items() if k != "trim"}, omega),
                  "excitation": {"harmonics_per_control": [int(by_control[c][0].harmonics[by_control[c][1]].size)
                                                           for c in controls],
                                 "relative_peak_factor": [float(by_control[c][0].relative_peak_factor[by_control[c][1]])
                                                          for c in controls],
                                 "period_s": float(excitations[0].period)}}
    return IdentifiedModel(name=name or f"{structure.key} from one multisine record", structure=structure,
                           fit=result, reduction=reduction, responses=responses, verification=check,
                           noise_floor=floor, trim=wake_trim, omega=omega, settings=s, settings_hash=digest,
                           provenance=provenance, hash_payload=payload, staged=staged, fit_start=fit_start)
