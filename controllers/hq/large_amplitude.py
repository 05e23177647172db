"""Large-amplitude attitude and rate specs (ADS-33E-PRF §3.3.4 pitch/roll, §3.3.7 heading).

The metric is the largest angular rate achieved in a (full-)controller step,
from a simulated LTI response or a recorded time history.  Printed values
found: the hover heading-rate requirement of a moderate-agility MTE, Level 1
+-22 deg/s (Raol, Singh et al., *Flight Mechanics Modeling and Analysis*,
"HLSR - yaw axis response criteria", quoting ADS-33).  Its Level 2 value and
every other large-amplitude boundary (pitch and roll attitude/rate, limited and
aggressive agility) were not found printed.
"""
from __future__ import annotations

import control
import numpy as np

from .base import HQSpec

__all__ = ["achieved_rate", "step_achieved_rate", "large_amplitude_specs"]

_TEST = "tests/test_hq_specs.py::test_large_amplitude_rate"


def achieved_rate(t, rate):
    """Largest absolute angular rate of a time history [rate units].

    Parameters
    ----------
    t : array
        Time [s], increasing.
    rate : array
        Angular rate [e.g. deg/s].

    Returns
    -------
    float

    Examples
    --------
    >>> achieved_rate([0, 1, 2], [0.0, -25.0, 10.0])
    25.0
    """
    t = np.asarray(t, dtype=float)
    r = np.asarray(rate, dtype=float)
    if t.shape != r.shape or t.ndim != 1 or t.size < 2:
        raise ValueError(f"achieved_rate: t and rate must be 1-D of equal length >= 2, got {t.shape}, {r.shape}")
    if not np.all(np.isfinite(r)):
        raise ValueError("achieved_rate: rate has non-finite samples")
    return float(np.max(np.abs(r)))


def step_achieved_rate(rate_response, control_input, duration=10.0, dt=0.01):
    """Largest angular rate of an LTI rate response to a controller step.

    Parameters
    ----------
    rate_response : control.LTI
        Angular rate per controller input [e.g. (deg/s)/in].
    control_input : float
        Step size [controller units], e.g. the full controller travel.
    duration, dt : float
        Simulated time and step [s].

    Returns
    -------
    float

    Examples
    --------
    >>> round(step_achieved_rate(control.tf([20.0], [0.5, 1.0]), 1.0, duration=10.0), 3)
    20.0
    """
    if not isinstance(rate_response, control.LTI) or rate_response.ninputs != 1 or rate_response.noutputs != 1:
        raise TypeError("step_achieved_rate: rate_response must be a SISO control.LTI")
    if not np.isfinite(control_input) or control_input == 0:
        raise ValueError(f"step_achieved_rate: control_input must be finite and non-zero, got {control_input}")
    t = np.arange(0.0, duration + dt / 2, dt)
    y = np.squeeze(control.forced_response(rate_response, t, np.full_like(t, control_input)).outputs)
    return achieved_rate(t, y)


def _rate_metric(data):
    if isinstance(data, tuple):
        return achieved_rate(*data)
    return float(data)


def large_amplitude_specs():
    """Large-amplitude specs of the library.

    Returns
    -------
    list of HQSpec
        Metric input: ``(t, rate)`` in deg/s or an already-computed rate [deg/s].

    Examples
    --------
    >>> [s.boundary_text() for s in large_amplitude_specs() if s.status == "partial"]
    ['L1 >= 22 deg/s; L2 not found printed']
    """
    specs = [HQSpec("LrgRtH1.yaw", "achievable heading rate, hover (moderate-agility MTEs)", _rate_metric, "min",
                    22.0, np.nan, units="deg/s",
                    source="ADS-33E-PRF §3.3.7 large-amplitude heading changes, moderate agility: Level 1 +-22 deg/s "
                           "(quoted by Raol & Singh, Flight Mechanics Modeling and Analysis, 'HLSR - yaw axis response "
                           "criteria'); Level 2 not found printed",
                    family="large_amplitude", axis="yaw", agilities=("moderate",), speeds=("hover",),
                    status="partial", test=_TEST)]
    for axis, para in (("yaw", "§3.3.7"), ("pitch", "§3.3.4"), ("roll", "§3.3.4")):
        for agility in ("limited", "moderate", "aggressive"):
            if axis == "yaw" and agility == "moderate":
                continue
            specs.append(HQSpec(f"LrgRtH1.{axis}", f"achievable {axis} rate, hover ({agility}-agility MTEs)",
                                _rate_metric, "min", units="deg/s",
                                source=f"ADS-33E-PRF {para} large-amplitude {axis} changes, {agility} agility: "
                                       "boundary values not found printed",
                                family="large_amplitude", axis=axis, agilities=(agility,), speeds=("hover",),
                                status="not found", test=_TEST))
    return specs
