"""Attitude quickness (ADS-33E-PRF §3.3.3 pitch/roll, §3.3.6 heading; moderate amplitude).

Quickness is the peak angular rate divided by the peak attitude change of a
rapid attitude change (a pulse of the controller):
``Q = rate_pk / d_att_pk`` [1/s], plotted against the minimum attitude change
``d_att_min`` (the smallest attitude change after the peak, i.e. what is left
once any overshoot has come back).  ADS-33E-PRF draws the Level boundaries as
curves of Q against d_att_min for target acquisition and tracking and for all
other MTEs; their values were not found printed in the sources searched, so
these specs carry the metric and are marked ``"not found"``.
"""
from __future__ import annotations

from dataclasses import dataclass

import control
import numpy as np
from scipy.integrate import cumulative_trapezoid

from .base import RegionSpec

__all__ = ["QuicknessResult", "attitude_quickness", "pulse_quickness", "quickness_specs"]

_TEST = "tests/test_hq_specs.py::test_quickness_pulse_closed_form"
#: the metric's (x, y) and its distance units: 0.1 1/s of quickness weighs as 2 deg of attitude
#: (the charts span a few 1/s against some tens of degrees)
_AXES = ("quickness Q [1/s]", "minimum attitude change [deg]", (0.1, 2.0), ((0.0, 4.0), (0.0, 60.0)))


@dataclass(frozen=True)
class QuicknessResult:
    """Attitude quickness of one response.

    Attributes
    ----------
    quickness : float
        rate_pk / d_att_pk [1/s].
    peak_rate : float
        Peak angular rate (in the direction of the change) [attitude units/s].
    peak_change : float
        Peak attitude change [attitude units].
    min_change : float
        Smallest attitude change after the peak [attitude units].
    """

    quickness: float
    peak_rate: float
    peak_change: float
    min_change: float


def attitude_quickness(t, attitude, rate=None):
    """Quickness of a time response (ADS-33E-PRF moderate-amplitude definition).

    Parameters
    ----------
    t : array
        Time [s], increasing.
    attitude : array
        Attitude [deg or rad]; the change is measured from ``attitude[0]``.
    rate : array, optional
        Angular rate [attitude units/s]; default the gradient of ``attitude``.

    Returns
    -------
    QuicknessResult

    Raises
    ------
    ValueError
        Inputs of different lengths, non-increasing time, non-finite samples,
        or no attitude change.

    Examples
    --------
    >>> t = np.linspace(0, 2, 201)
    >>> r = attitude_quickness(t, np.minimum(t, 1.0) * 10.0)   # 10 deg/s for 1 s
    >>> round(r.quickness, 6), r.peak_change
    (1.0, 10.0)
    """
    t = np.asarray(t, dtype=float)
    att = np.asarray(attitude, dtype=float)
    if t.ndim != 1 or att.shape != t.shape or t.size < 3:
        raise ValueError(f"attitude_quickness: t and attitude must be 1-D of equal length >= 3, got {t.shape}, {att.shape}")
    if np.any(np.diff(t) <= 0):
        raise ValueError("attitude_quickness: t must be strictly increasing")
    rate = np.gradient(att, t) if rate is None else np.asarray(rate, dtype=float)
    if rate.shape != t.shape:
        raise ValueError(f"attitude_quickness: rate has shape {rate.shape}, t {t.shape}")
    if not (np.all(np.isfinite(att)) and np.all(np.isfinite(rate))):
        raise ValueError("attitude_quickness: attitude or rate has non-finite samples")
    change = att - att[0]
    k = int(np.argmax(np.abs(change)))
    sign = np.sign(change[k])
    if sign == 0:
        raise ValueError("attitude_quickness: the attitude does not change")
    peak_change = abs(change[k])
    peak_rate = float(np.max(sign * rate))
    min_change = float(np.min(sign * change[k:]))
    return QuicknessResult(float(peak_rate / peak_change), peak_rate, float(peak_change), min_change)


def pulse_quickness(rate_response, amplitude=1.0, width=0.5, duration=10.0, dt=0.002):
    """Quickness of an LTI rate response to a rectangular controller pulse.

    Parameters
    ----------
    rate_response : control.LTI
        Angular rate per controller input (SISO, continuous time).
    amplitude : float
        Pulse height [controller units].
    width : float
        Pulse width [s].
    duration : float
        Simulated time [s]; long enough for the attitude to settle.
    dt : float
        Time step [s].

    Returns
    -------
    QuicknessResult
        The attitude is the trapezoidal integral of the simulated rate.

    Examples
    --------
    >>> r = pulse_quickness(control.tf([2.0], [0.5, 1.0]), width=1.0, duration=12.0)
    >>> round(r.quickness, 3)   # (1 - exp(-1/0.5)) / 1 s
    0.865
    """
    if not isinstance(rate_response, control.LTI) or rate_response.ninputs != 1 or rate_response.noutputs != 1:
        raise TypeError("pulse_quickness: rate_response must be a SISO control.LTI")
    for name, v in (("width", width), ("duration", duration), ("dt", dt)):
        if not np.isfinite(v) or v <= 0:
            raise ValueError(f"pulse_quickness: {name} must be finite and > 0, got {v}")
    if duration <= width:
        raise ValueError(f"pulse_quickness: duration ({duration} s) must exceed the pulse width ({width} s)")
    t = np.arange(0.0, duration + dt / 2, dt)
    u = np.where(t < width, amplitude, 0.0)
    rate = np.squeeze(control.forced_response(rate_response, t, u).outputs)
    return attitude_quickness(t, cumulative_trapezoid(rate, t, initial=0.0), rate)


def _quickness_metric(result):
    r = result if isinstance(result, QuicknessResult) else attitude_quickness(*result)
    return r.quickness, r.min_change


def quickness_specs():
    """Attitude-quickness specs (pitch, roll, heading; both MTE classes), boundaries not found.

    Returns
    -------
    list of RegionSpec
        The metric takes a :class:`QuicknessResult` or a ``(t, attitude[, rate])``
        tuple and returns ``(Q [1/s], d_att_min [deg])``.

    Examples
    --------
    >>> sorted({s.axis for s in quickness_specs()})
    ['pitch', 'roll', 'yaw']
    """
    specs = []
    paragraphs = {"pitch": "§3.3.3", "roll": "§3.3.3", "yaw": "§3.3.6"}
    for axis, para in paragraphs.items():
        for mte in ("target acquisition and tracking", "all other"):
            word = "heading" if axis == "yaw" else f"{axis} attitude"
            specs.append(RegionSpec(
                f"QikAtH1.{axis}", f"{word} quickness vs minimum attitude change ({mte} MTEs)",
                _quickness_metric, "min", kind="soft", units="1/s",
                source=f"ADS-33E-PRF {para} moderate-amplitude {word} changes ({mte}): "
                       "quickness boundary values not found printed",
                family="quickness", axis=axis, mtes=(mte,), speeds=("hover",), status="not found", test=_TEST,
                chart_axes=_AXES))
    return specs
