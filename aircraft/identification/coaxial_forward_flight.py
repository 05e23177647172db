"""The coaxial in fast forward flight: identification from the wake (§6.6).

::

    identify_coaxial_forward(...)       wake trim at 200 kt -> sweeps -> Eq. 6.5 fit -> reduce
        -> IdentifiedModel                (aircraft.identification.identify_inflow)

The flight condition is the dissertation's: 200 kt, rotor (shaft) angle of attack
2 deg nose up (the free stream flows up through the disk), the cruise rotor speed
(:func:`aircraft.configs.coaxial_compound` ``cruise=True``, mu = 0.54). The wake
is trimmed to the system thrust the aircraft needs there (from the aircraft's own
trim with Isolated Rotors, :func:`aircraft_thrust_at`), split equally with the
torques balanced and each rotor's hub moments trimmed (mode ``"torque_balance"``;
the forward-flight wake trim measures its Jacobian on the wake): the pitch
moment to zero, the roll moment to the rotor's lift offset below (zero
without one).

Lift offset: the aircraft holds a differential lateral cyclic at trim (§7.2,
``lateral_cyclic_difference``), which leaves each rotor with a roll moment;
:func:`aircraft_lift_offset` reads the per-rotor lift offsets LOS = -C_L/C_T of
that trim, and ``identify_coaxial_forward(lift_offset=...)`` trims the wake to
them (:func:`aircraft.wake.trim_wake` ``lift_offset``), so that the identified
model is linearised about the rotor loads the aircraft flies at. 0: the
moment-balanced rotors of the wake trim before (C_L = C_M = 0 on each rotor).
"""
from __future__ import annotations

import math

import numpy as np
import pandas as pd

from .conditions import flight_condition

__all__ = ["SPEED_200KT", "ROTOR_AOA", "aircraft_thrust_at", "aircraft_lift_offset", "forward_trim_request",
           "identify_coaxial_forward"]

#: 200 kt [m/s] and the rotor angle of attack of §6.6 [rad].
SPEED_200KT = 200.0 * 0.514444
ROTOR_AOA = math.radians(2.0)


def _config(config):
    from aircraft.configs import coaxial_compound
    config = config if config is not None else coaxial_compound(cruise=True)
    if len(config.rotors) != 2:
        raise ValueError(f"the 200 kt identification is for a coaxial (two rotors), got "
                         f"{len(config.rotors)} rotor(s)")
    return config


def _speed(speed):
    from aircraft._validation import real
    return real(ValueError, "speed", speed, positive=True, hi=200.0, unit="m/s")


def _aircraft_trim(config, speed, rotor_aoa, lateral_cyclic_difference):
    """The aircraft's trim with Isolated Rotors at ``speed`` [m/s], ``rotor_aoa`` [rad]."""
    from aircraft.helicopter import Helicopter, HelicopterSettings, TrimCondition, trim
    from aircraft.inflow import IsolatedRotors
    from aircraft.inflow.base import config_rotor_names
    config = _config(config)
    return trim(Helicopter(config, IsolatedRotors(rotors=config_rotor_names(config)),
                           HelicopterSettings(n_span=8, n_average=4)),
                TrimCondition(speed=_speed(speed), rotor_aoa=rotor_aoa,
                              lateral_cyclic_difference=lateral_cyclic_difference))


def aircraft_thrust_at(config=None, speed=SPEED_200KT, rotor_aoa=ROTOR_AOA, lateral_cyclic_difference=0.0):
    """System thrust coefficient the aircraft trims to (Isolated Rotors), C_T_U + C_T_L [-].

    Parameters
    ----------
    config : AircraftConfig, optional
        Default ``coaxial_compound(cruise=True)``.
    speed : float
        Flight speed [m/s].
    rotor_aoa : float
        Rotor angle of attack [rad].
    lateral_cyclic_difference : float
        Differential lateral cyclic of the aircraft trim [rad]
        (:class:`aircraft.helicopter.TrimCondition`).

    Returns
    -------
    float
        Twice the mean rotor thrust rounded to 3 significant digits (the wake
        cache keys on the value; the rounding, < 5e-6 per rotor, is below the wake
        trim's tolerance of 1e-4).
    """
    tr = _aircraft_trim(config, speed, rotor_aoa, lateral_cyclic_difference)
    upper, lower = (f"CT_{r.name}" for r in tr.helicopter.config.rotors)
    return 2.0 * float(f"{0.5 * (tr.loads[upper] + tr.loads[lower]):.3g}")


def aircraft_lift_offset(config=None, speed=SPEED_200KT, rotor_aoa=ROTOR_AOA, lateral_cyclic_difference=0.03):
    """Per-rotor lift offsets of the aircraft's trim, ``(LOS_U, LOS_L)`` = -C_L/C_T [-].

    Parameters
    ----------
    config : AircraftConfig, optional
        Default ``coaxial_compound(cruise=True)``.
    speed : float
        Flight speed [m/s].
    rotor_aoa : float
        Rotor angle of attack [rad].
    lateral_cyclic_difference : float
        Differential lateral cyclic held at the aircraft trim [rad] (§7.2).

    Returns
    -------
    tuple of float
        Each rotor's roll moment over thrust x R towards its advancing side, from
        the aircraft's trim with Isolated Rotors, rounded to 3 decimals (the wake
        cache keys on the values; 1e-3 of LOS is 5e-6 of C_L at C_T ~ 0.005,
        below the 1e-4 tolerance of the 200 kt wake trim).
    """
    tr = _aircraft_trim(config, speed, rotor_aoa, lateral_cyclic_difference)
    names = (r.name for r in tr.helicopter.config.rotors)      # upper, lower
    return tuple(round(-float(tr.loads[f"CL_{r}"]) / float(tr.loads[f"CT_{r}"]), 3) + 0.0 for r in names)


def forward_trim_request(ct, *, lift_offset=0.0, tol=1e-4, max_iter=30):
    """The wake trim request at 200 kt (keyword arguments of :func:`aircraft.wake.trim_wake`).

    Parameters
    ----------
    ct : float
        System thrust coefficient [-], split equally (the torque balance sets the split).
    tol : float
        Residual tolerance [-] (1e-4: the coaxial's revolution-averaged scatter).
    max_iter : int
        Trim iterations (the 200 kt trim converged in 9 on the coarse wake).

    lift_offset : float or (float, float)
        Lift offset LOS [-] of both rotors or per rotor (upper, lower), see
        :func:`aircraft.wake.trim_wake`; 0 (default): moment-balanced rotors.

    Returns
    -------
    dict
        ``{"ct": (c/2, c/2), "mode": "torque_balance", "tol": tol, "max_iter": max_iter}``,
        plus ``"lift_offset": (LOS_U, LOS_L)`` when it is not zero (absent otherwise,
        so the requests and cached runs of the moment-balanced trim stay the same).

    Raises
    ------
    ValueError
        If ``ct`` is not a positive finite number, or a lift offset is not
        a finite number in [-0.5, 0.5].
    """
    from aircraft._validation import real
    c = real(ValueError, "ct", ct, positive=True, hi=0.1)
    los = lift_offset if isinstance(lift_offset, (tuple, list, np.ndarray)) else (lift_offset, lift_offset)
    if len(los) != 2:
        raise ValueError(f"lift_offset needs one value or two (upper, lower), got {len(los)}")
    los = tuple(real(ValueError, "lift_offset", v, lo=-0.5, hi=0.5) for v in los)
    request = {"ct": (c / 2.0, c / 2.0), "mode": "torque_balance", "tol": float(tol), "max_iter": int(max_iter)}
    if any(los):
        request["lift_offset"] = los
    return request


def identify_coaxial_forward(config=None, *, speed=SPEED_200KT, rotor_aoa=ROTOR_AOA, ct=None,
                             structure=None, settings=None, n_jobs=2, cache_dir="default", progress=True,
                             name=None, max_reduction_steps=1000, lift_offset=0.0, reduction_batch=1,
                             verification_failure="raise"):
    """Identify the 200 kt coaxial inflow model (Eq. 6.5 structure) from our free wake.

    Parameters
    ----------
    config : AircraftConfig, optional
        Default ``coaxial_compound(cruise=True)`` (Omega = 20.3 rad/s, mu = 0.54 at 200 kt).
    speed : float
        Flight speed [m/s] (default 200 kt).
    rotor_aoa : float
        Rotor angle of attack [rad] (default 2 deg).
    ct : float, optional
        System thrust coefficient of the wake trim [-]; default
        :func:`aircraft_thrust_at` (what the aircraft needs there).
    structure : InflowStructure, optional
        Default :class:`CoaxialForward12State`, the full Eq. 6.5 pattern (180
        parameters at the start), with the configuration's rotor names; any coaxial
        structure without flap-rate inputs with those rotor names (e.g.
        :class:`CoaxialForward6State`) is identified from the same records.
    settings : IdentificationSettings, optional
        Default: the pipeline's defaults with a lower-rotor lateral doublet
        (``theta1s_L`` with the default rotor names, as Figs. 6.29-6.33) of
        0.035 rad (2 deg).
    n_jobs : int
        Wake worker processes.
    cache_dir : str or None
        Wake cache (see :func:`aircraft.wake.run_sweeps`).
    progress : bool
        Progress bars.
    name : str, optional
        Model name.
    max_reduction_steps : int
        Removals tried by the automatic reduction (Fig. 6.1; one refit each); 0
        skips it, as ``settings.reduce=False`` does. The pipeline fits, then the
        reduction runs here with this bound (``provenance["max_reduction_steps"]``);
        the doublet verification is then redone on the reduced model. The default
        lets it run to completion (every candidate tried; the structure's analytic
        Jacobian makes a refit a few seconds); ``provenance["reduction_untried"]``
        lists the candidates a smaller bound left untried.
    reduction_batch : int
        Candidates the reduction removes together per refit (:func:`flightid.reduce`
        ``batch``): the 180-parameter start removes ~100 parameters, one refit
        each at 1 (the default, Fig. 6.1).
    verification_failure : {"raise", "record"}
        When the reduced model's doublet simulation is not finite (an ill-conditioned
        model): raise (default), or keep the reduced fit with the first fit's
        verification and say so in ``provenance["verification_error"]`` (the trust
        verdict needs no simulation; used to compare candidate structures).
    lift_offset : float or (float, float)
        Lift offset of the wake trim [-], both rotors or (upper, lower): e.g.
        :func:`aircraft_lift_offset`, the aircraft's own (see
        :func:`forward_trim_request`).

    Returns
    -------
    IdentifiedModel
        The reduced fit, its cost table and parameters (CR %, insensitivity %),
        the doublet verification beside the wake's noise floor.
    """
    import dataclasses
    import time
    from .structures.coaxial_forward import CoaxialForward12State
    from .pipeline import (IdentificationSettings, _verify, identification_hash, identify_inflow)
    from aircraft.inflow.base import config_rotor_names
    config = _config(config)
    from .structures.base import InflowStructure
    names = config_rotor_names(config)          # (upper, lower): the signals' rotor names
    structure = structure if structure is not None else CoaxialForward12State(rotors=names)
    # any coaxial load-driven structure: the sweeps (its excitations) are then the
    # 12-state's six swashplate controls, so that the wake records are the same
    if not isinstance(structure, InflowStructure) or tuple(structure.rotors) != tuple(names) \
            or structure.uses_flap_rates:
        raise TypeError(f"structure must be a coaxial InflowStructure without flap-rate inputs with the "
                        f"rotors {tuple(names)} (e.g. CoaxialForward12State), got {structure!r}")
    settings = settings or IdentificationSettings(doublet_control=f"theta1s_{names[1]}", doublet_amplitude=0.035)
    if verification_failure not in ("raise", "record"):
        raise ValueError(f"verification_failure must be 'raise' or 'record', got {verification_failure!r}")
    if isinstance(max_reduction_steps, bool) or not isinstance(max_reduction_steps, int) \
            or max_reduction_steps < 0:
        raise ValueError(f"max_reduction_steps must be an integer >= 0, got {max_reduction_steps!r}")
    if ct is None:
        ct = aircraft_thrust_at(config, speed, rotor_aoa)
    condition = flight_condition(speed=_speed(speed), alpha=float(rotor_aoa))
    request = forward_trim_request(ct, lift_offset=lift_offset)
    name = name or f"coaxial {speed / 0.514444:.0f} kt {structure.key} from our wake"
    # the pipeline fits once; the reduction (one refit per removal, 180 parameters at
    # the start) runs here so that its number of steps can be bounded
    model = identify_inflow(config, condition, structure, trim=request,
                            settings=dataclasses.replace(settings, reduce=False), n_jobs=n_jobs,
                            cache_dir=cache_dir, progress=progress, name=name)
    if not settings.reduce or max_reduction_steps == 0:
        return model
    from flightid import reduce
    from flightid.errors import DataError
    t0 = time.perf_counter()
    s = settings
    reduction = reduce(model.fit.structure, model.responses, insensitivity_max=s.insensitivity_max,
                       cramer_rao_max=s.cramer_rao_max, protected=structure.protected, progress=progress,
                       max_steps=max_reduction_steps, batch=reduction_batch, **structure.fit_options,
                       frequency_ranges=tuple(s.fit_range), n_omega=s.n_omega,
                       coherence_min=s.coherence_min)
    ss = reduction.result.structure.to_statespace(pade_order=s.pade_order)
    ref = pd.Series(model.trim.outputs)
    doublet, zero = _verification_runs(config, condition, request, s, structure, cache_dir)
    verification_error = ""
    try:
        check = _verify(ss, doublet, ref, structure.inputs, structure.outputs)
        floor = _verify(ss, zero, ref, structure.inputs, structure.outputs)
    except DataError as err:
        if verification_failure == "raise":
            raise
        # "record": the reduced fit (and its trust verdict, which needs no simulation) is kept
        check, floor, verification_error = model.verification, model.noise_floor, str(err)[:300]
    digest, payload = identification_hash(config, condition, structure, settings, trim=request)
    provenance = {**model.provenance, "reduction": "aircraft.identification.coaxial_forward_flight",
                  "max_reduction_steps": max_reduction_steps, "reduction_batch": reduction_batch,
                  "reduction_untried": _untried(reduction, s, structure.protected),
                  "reduction_wall_s": round(time.perf_counter() - t0, 1)}
    if verification_error:
        provenance["verification_error"] = ("the reduced model's doublet simulation failed (" + verification_error
                                            + "); the verification shown is the first fit's")
    return dataclasses.replace(model, fit=reduction.result, reduction=reduction, verification=check,
                               noise_floor=floor, settings=settings, settings_hash=digest,
                               hash_payload=payload, provenance=provenance)


def _untried(reduction, s, protected):
    """Free parameters still over a threshold that the reduction never tried to remove
    (empty when it ran to completion)."""
    table = reduction.result.parameters
    free = table[table.status == "free"]
    over = free[(free.insensitivity_pct > s.insensitivity_max) | (free.cramer_rao_pct > s.cramer_rao_max)]
    tried = {n.strip() for names in reduction.log.parameter for n in str(names).split(",")}
    return [n for n in over.parameter if n not in tried and n not in set(protected)]


def _verification_runs(config, condition, request, s, structure, cache_dir):
    """The doublet and zero-input records, specified as :func:`identify_inflow` specifies
    them (served from the wake cache, which keys records by content)."""
    from aircraft.wake import SweepSpec, run_sweeps
    control = s.doublet_control or structure.controls[0]
    specs = [SweepSpec(control, kind="doublet", amplitude=s.doublet_amplitude, duration=s.doublet_s,
                       pulse_width=s.pulse_width),
             SweepSpec(control, kind="sine", amplitude=0.0, duration=s.noise_floor_s, w_min=1.0,
                       label="zero_input")]
    runs = run_sweeps(config, s.wake_settings, condition, specs, trim=request, n_jobs=1, cache_dir=cache_dir,
                      progress=False)
    return runs[specs[0].name], runs[specs[1].name]
