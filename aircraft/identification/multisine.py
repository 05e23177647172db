"""Inflow identification from ONE multisine record of all swashplate controls.

:func:`identify_inflow_multisine` is :func:`aircraft.identification.identify_inflow`
with the one-control-at-a-time sweeps replaced by a single record in which every
control of :attr:`InflowStructure.controls` moves at once with orthogonal
multisines (:class:`aircraft.wake.MultisineSpec`); the MIMO response comes from
the cross-spectral matrix (:func:`flightid.mimo_response`) and the rest of the
pipeline (joint input-output, data-driven start, fit, reduction, doublet
verification beside the noise floor) is the same. This is the dissertation's
recommendation 6: fewer wake revolutions per identification.

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
        Seed of the start phases.
    """

    duration: float = 90.0
    amplitude: float = 0.02
    spectrum: str = "log"
    fade: float = 0.5
    trim_start: float = 0.5
    seed: int = 0


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
        Model structure (its ``controls`` are all excited in the one record; a
        model with flap-rate inputs is refused: they need prescribed tip-path-plane
        excitation).
    ct : float, optional
        Trim thrust coefficient of the system (coaxial: split equally, torques balanced).
    trim : dict, optional
        Full trim request (overrides ``ct``).
    settings : IdentificationSettings, optional
        Wake resolution, band ``w_min``/``w_max`` [rad/s] (the multisine's band
        too), fit, reduction and verification settings; ``sweep_s`` and
        ``amplitude`` are not used.
    multisine : MultisineSettings, optional
        The multisine record (default: 90 s, 0.02 rad peak, log spectrum).
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
        Trim failure, missing signals, flap-rate inputs, or inputs the record
        cannot separate.
    """
    from tqdm.auto import tqdm
    from aircraft.wake import FlightCondition, MultisineSpec, SweepSpec, run_sweeps
    from flightid.errors import SingularInputError
    from flightid import joint_input_output, mimo_response

    t_start = time.perf_counter()
    settings = settings or IdentificationSettings()
    multisine = multisine or MultisineSettings()
    if not isinstance(multisine, MultisineSettings):
        raise TypeError(f"multisine must be a MultisineSettings, got {type(multisine).__name__}")
    condition = condition or FlightCondition()
    structure = get_structure(structure)
    rotor_names = tuple(r.name for r in config.rotors)
    if len(rotor_names) != len(structure.rotors) or (len(rotor_names) > 1 and rotor_names != structure.rotors):
        raise PipelineError(f"structure {structure.key} is for rotors {structure.rotors}; "
                            f"the configuration has {rotor_names}")
    controls = list(structure.controls)
    if len(controls) < len(structure.inputs):
        raise PipelineError(f"{structure.key} has {len(structure.inputs)} inputs but {len(controls)} "
                            "swashplate controls: flap-rate inputs need prescribed tip-path-plane excitation")
    trim_req = _trim_request(config, ct, trim)
    digest, payload = identification_hash(config, condition, structure, settings, trim=trim_req)
    payload = {**payload, "excitation": {"kind": "orthogonal_multisine", **multisine.__dict__}}
    from aircraft.provenance import settings_hash
    digest = settings_hash(payload, digits=16)
    s = settings
    ms_spec = MultisineSpec(tuple(controls), amplitude=multisine.amplitude, duration=multisine.duration,
                            w_min=s.w_min, w_max=s.w_max, spectrum=multisine.spectrum, fade=multisine.fade,
                            trim_start=multisine.trim_start, seed=multisine.seed)
    # the same verification and noise-floor records as identify_inflow (shared cache entries)
    dbl_control = s.doublet_control or controls[0]
    doublet_spec = SweepSpec(dbl_control, kind="doublet", amplitude=s.doublet_amplitude, duration=s.doublet_s,
                             pulse_width=s.pulse_width)
    zero_spec = SweepSpec(dbl_control, kind="sine", amplitude=0.0, duration=s.noise_floor_s, w_min=1.0,
                          label="zero_input")
    stages = tqdm(total=4, desc=f"identify {structure.key} (multisine)", disable=not progress)
    runs = run_sweeps(config, s.wake_settings, condition, [ms_spec, doublet_spec, zero_spec], trim=trim_req,
                      n_jobs=n_jobs, cache_dir=cache_dir, progress=progress)
    wake_trim = runs["trim"]
    stages.update()
    df = runs[ms_spec.name]
    signals = structure.inputs + structure.outputs
    missing = [c for c in signals + controls if c not in df]
    if missing:
        stages.close()
        raise PipelineError(f"the wake record lacks signals {missing}")
    y = (df[signals] - df[signals].iloc[0]).to_numpy()
    u = (df[controls] - df[controls].iloc[0]).to_numpy()
    try:
        measured = mimo_response(df["t"].to_numpy(), u, y, w_min=s.w_min, w_max=s.w_max,
                                 input_names=controls, output_names=signals)
        responses = joint_input_output(measured.select(structure.outputs), measured.select(structure.inputs))
    except SingularInputError as err:
        stages.close()
        raise PipelineError(f"the multisine record cannot separate the inputs: {err}") from err
    stages.update()
    omega = float(config.rotors[0].omega)
    staged, reduction, result, check, floor, start_log, fit_start = _fit_and_verify(
        structure, responses, runs, doublet_spec, zero_spec, wake_trim, omega, s, progress, stages)
    dt = s.wake_settings.azimuth_step / omega
    excitation = ms_spec.multisine(dt)
    provenance = {"source": "aircraft.identification.identify_inflow_multisine", "schema": SCHEMA,
                  "starts": start_log,
                  "pipeline": PIPELINE_VERSION, "code_version": _code_version(),
                  "created": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
                  "wall_s": round(time.perf_counter() - t_start, 1),
                  "config": getattr(config, "name", repr(config)[:60]),
                  "revolutions": record_revolutions({k: v for k, v in runs.items() if k != "trim"}, omega),
                  "excitation": {"harmonics_per_control": [int(k.size) for k in excitation.harmonics],
                                 "relative_peak_factor": [float(r) for r in excitation.relative_peak_factor],
                                 "period_s": float(excitation.period)}}
    return IdentifiedModel(name=name or f"{structure.key} from one multisine record", structure=structure,
                           fit=result, reduction=reduction, responses=responses, verification=check,
                           noise_floor=floor, trim=wake_trim, omega=omega, settings=s, settings_hash=digest,
                           provenance=provenance, hash_payload=payload, staged=staged, fit_start=fit_start)
