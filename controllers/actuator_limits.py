"""Actuator rate/position limits and stick amplitudes as data, and the open-loop onset point they set.

The open-loop onset point (OLOP, Duda 1997; CONDUIT ``OlpOpG1``) needs three
numbers the linear model does not carry: the actuator's rate limit, its
position (travel) limit and the amplitude of the pilot's (or a disturbance's)
sinusoidal input. :class:`ActuatorLimits` holds them with their units;
:func:`olop_margin` grades a loop against the approximate Level 1 line;
:func:`olop_point` returns the point itself (onset frequency, loop phase and gain).

Units. "Mixer units" are the units of the plant input the loop drives (the
signal ``delta_mx`` enters the actuator): for the coaxial of dissertation
Eq. 7.19 they are radians of blade pitch, the mean of the two rotors'
swashplate angles (K = 0.5), so rates are rad/s of blade pitch. "Stick units"
are the units of the pilot input of the command model (its gain is command per
stick unit).

:data:`HOVER_ACTUATOR_LIMITS` are the limits :func:`controllers.multi_axis_design.design_multi_axis`
uses by default. No rate or travel limit of the coaxial's actuators is printed
in the dissertation; the values are assumptions, listed with their reasons in
:data:`LIMITS_ASSUMPTIONS` (the same way :data:`aircraft.ASSUMPTIONS` lists the
aircraft's), to be replaced by the aircraft's own data when known.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import metrics as m
from .metrics import duda_olop_limit

__all__ = ["ActuatorLimits", "olop_margin", "olop_point", "full_stick", "HOVER_ACTUATOR_LIMITS",
           "HOVER_FULL_STICK_COMMAND", "LIMITS_ASSUMPTIONS"]


@dataclass(frozen=True)
class ActuatorLimits:
    """Actuator limits and input amplitudes for the open-loop onset point.

    Attributes
    ----------
    rate_limit : float
        Actuator rate limit [mixer units/s] (coaxial: rad/s of blade pitch).
    position_limit : float
        Actuator position (travel) limit about trim [mixer units]; ``inf`` if none.
    stick_amplitude : float
        Pilot input amplitude [stick units], e.g. full stick.
    disturbance_amplitude : float
        Disturbance amplitude for ``OlpOpG1.dist`` [rad]; NaN leaves that spec out.

    Raises
    ------
    ValueError
        A limit or amplitude is not > 0 (the attribute is named).

    Examples
    --------
    >>> lim = ActuatorLimits(rate_limit=math.radians(40.0), position_limit=math.radians(10.0), stick_amplitude=10.0)
    >>> round(lim.rate_limit / lim.position_limit, 6)     # full travel covered in 0.25 s
    4.0
    """

    rate_limit: float
    position_limit: float
    stick_amplitude: float
    disturbance_amplitude: float = float("nan")

    def __post_init__(self):
        for name in ("rate_limit", "position_limit", "stick_amplitude"):
            v = getattr(self, name)
            if np.isnan(v) or v <= 0 or (name != "position_limit" and not np.isfinite(v)):
                raise ValueError(f"ActuatorLimits.{name} must be > 0 (finite except position_limit), got {v}")
        d = self.disturbance_amplitude
        if not np.isnan(d) and (not np.isfinite(d) or d <= 0):
            raise ValueError(f"ActuatorLimits.disturbance_amplitude must be > 0 or NaN, got {d}")


class _PositionLimited:
    """Input -> actuator response whose amplitude is capped by the position limit."""

    def __init__(self, sys, amplitude, position_limit):
        self.sys, self.amplitude, self.position_limit = sys, amplitude, position_limit

    def response(self, omega):
        _, h = m.frequency_response_of(self.sys, omega)
        cap = np.minimum(1.0, self.position_limit / np.maximum(self.amplitude * np.abs(h), 1e-300))
        return h * cap


def _check(amplitude, limits, who):
    if not isinstance(limits, ActuatorLimits):
        raise TypeError(f"{who}: limits must be ActuatorLimits, got {type(limits).__name__}")
    if not np.isfinite(amplitude) or amplitude <= 0:
        raise ValueError(f"{who}: amplitude must be finite and > 0, got {amplitude}")


def olop_point(loop, input_to_actuator, amplitude, limits):
    """The open-loop onset point: onset frequency and the broken loop there.

    The onset frequency is the lowest at which a sinusoid of ``amplitude``
    drives the actuator command (mixer input) at ``limits.rate_limit``, the
    command's amplitude capped at ``limits.position_limit`` (a saturated
    actuator cannot move farther).

    Parameters
    ----------
    loop : LTI or FrequencyFunction
        Broken loop at the actuator (mixer) input.
    input_to_actuator : LTI or FrequencyFunction
        Pilot (or disturbance) input -> actuator (mixer) input, closed loop.
    amplitude : float
        Input amplitude [stick units, or rad for a disturbance].
    limits : ActuatorLimits

    Returns
    -------
    dict
        ``onset_frequency`` [rad/s] (``inf`` when the rate limit is never reached on
        the grid, 0.01-200 rad/s), ``phase_deg`` and ``gain_db`` of the loop there
        (NaN when never reached) and ``margin_db`` below the approximate Level 1 line
        (``+inf`` when never reached: rate limiting cannot occur).

    Examples
    --------
    >>> import control
    >>> lim = ActuatorLimits(rate_limit=1.0, position_limit=np.inf, stick_amplitude=0.1)
    >>> p = olop_point(lambda s: 1 / s ** 2, control.tf([1.0], [1.0]), 0.1, lim)
    >>> round(p["onset_frequency"], 6), round(p["gain_db"], 6), round(p["margin_db"], 6)
    (10.0, -40.0, 38.0)
    """
    _check(amplitude, limits, "olop_point")
    capped = _PositionLimited(input_to_actuator, amplitude, limits.position_limit)
    phase, gain, w_on = m.open_loop_onset_point(loop, capped, amplitude, limits.rate_limit)
    margin = float("inf") if not np.isfinite(w_on) else float(duda_olop_limit(phase) - gain)
    return {"onset_frequency": w_on, "phase_deg": phase, "gain_db": gain, "margin_db": margin}


def olop_margin(loop, input_to_actuator, amplitude, limits):
    """dB of the open-loop onset point below the approximate Level 1 line.

    Parameters
    ----------
    loop : LTI or FrequencyFunction
        Broken loop at the actuator (mixer) input.
    input_to_actuator : LTI or FrequencyFunction
        Pilot (or disturbance) input -> actuator (mixer) input, closed loop.
    amplitude : float
        Input amplitude [stick units, or rad for a disturbance].
    limits : ActuatorLimits
        Rate and position limits of the actuator.

    Returns
    -------
    float
        Margin [dB] (> 0 inside Level 1); ``+inf`` when the rate limit is
        never reached on the frequency grid (rate limiting cannot occur).

    Examples
    --------
    >>> import control
    >>> lim = ActuatorLimits(rate_limit=1.0, position_limit=np.inf, stick_amplitude=0.1)
    >>> olop_margin(control.tf([1.0], [1.0, 0.0]), control.tf([1.0], [1.0]), 0.1, lim) > 0
    True
    """
    _check(amplitude, limits, "olop_margin")
    return olop_point(loop, input_to_actuator, amplitude, limits)["margin_db"]


#: full-stick command per axis in hover: attitude [rad] (roll, pitch) or steady rate [rad/s, m/s] (yaw, heave)
HOVER_FULL_STICK_COMMAND = {"roll": math.radians(30.0), "pitch": math.radians(20.0), "yaw": math.radians(22.0),
                            "heave": 1000.0 * 0.3048 / 60.0}
#: actuator (rate [rad/s], travel about trim [rad]) of blade pitch per axis, Eq. 7.19 units
_HOVER_ACTUATORS = {"roll": (math.radians(40.0), math.radians(8.0)),
                    "pitch": (math.radians(40.0), math.radians(8.0)),
                    "yaw": (math.radians(40.0), math.radians(5.0)),
                    "heave": (math.radians(30.0), math.radians(8.0))}

LIMITS_ASSUMPTIONS = {
    "full_stick.roll/pitch": "an attitude-command hover law commanding 30 deg of roll and 20 deg of pitch at full "
                             "stick (assumed; ADS-33E-PRF sets the attitude a full stick must reach only as "
                             "large-amplitude minima, whose values for pitch/roll were not found printed)",
    "full_stick.yaw": "22 deg/s of heading rate at full pedal: the ADS-33E-PRF §3.3.7 Level 1 hover heading "
                      "rate of a moderate-agility MTE (the LrgRtH1.yaw boundary of controllers.hq), so a full "
                      "pedal commands no more than the aircraft must achieve",
    "full_stick.heave": "1000 ft/min (5.08 m/s) of vertical rate at full collective (assumed, a typical "
                        "rate-command collective; not printed)",
    "rate_limit": "40 deg/s of blade pitch for the cyclics and the differential collective, 30 deg/s for the "
                  "collective (assumed: a hydraulic swashplate actuator stroking its cyclic travel in about "
                  "0.2 s; no actuator rate of the coaxial is printed in the dissertation)",
    "position_limit": "8 deg of blade pitch about the hover trim for the cyclics and the collective, 5 deg for "
                      "the differential collective (assumed control authority; not printed)",
}


def full_stick(axis, command_gain):
    """Hover limits of one axis with the full stick of :data:`HOVER_FULL_STICK_COMMAND`.

    Parameters
    ----------
    axis : {"roll", "pitch", "yaw", "heave"}
    command_gain : float
        Command-model gain: command per stick unit [rad, rad/s or m/s per stick unit].

    Returns
    -------
    ActuatorLimits
        Rate and travel of :data:`LIMITS_ASSUMPTIONS`; stick amplitude = full-stick
        command / ``command_gain`` [stick units]; no disturbance amplitude.

    Raises
    ------
    ValueError
        Unknown axis or a gain that is not > 0.

    Examples
    --------
    >>> round(full_stick("roll", 0.05).stick_amplitude, 3)     # 30 deg at 0.05 rad per stick unit
    10.472
    """
    if axis not in HOVER_FULL_STICK_COMMAND:
        raise ValueError(f"full_stick: axis must be one of {list(HOVER_FULL_STICK_COMMAND)}, got {axis!r}")
    if not np.isfinite(command_gain) or command_gain <= 0:
        raise ValueError(f"full_stick: command_gain must be finite and > 0, got {command_gain!r}")
    rate, travel = _HOVER_ACTUATORS[axis]
    return ActuatorLimits(rate, travel, HOVER_FULL_STICK_COMMAND[axis] / float(command_gain))


#: default hover limits with the default command models (roll/pitch 0.05 rad, yaw 0.3 rad/s, heave 3 m/s per stick)
HOVER_ACTUATOR_LIMITS = {a: full_stick(a, g) for a, g in (("roll", 0.05), ("pitch", 0.05), ("yaw", 0.3),
                                                          ("heave", 3.0))}
