"""Inter-axis coupling specs (ADS-33E-PRF §3.3.8, hover and low speed).

* Pitch-roll coupling: the peak off-axis attitude change within ``at`` seconds
  of an on-axis step, divided by the on-axis attitude change at ``at`` seconds
  (ADS-33E-PRF's ratio for aggressive agility; the 4 s horizon is the default
  read from the requirement's definition).  Boundary values not found printed.
* Yaw due to collective: the largest yaw-rate excursion following an abrupt
  collective input.  Padfield, *Helicopter Flight Dynamics* §6.7.1
  ("Collective to yaw coupling"): "ADS-33 sets a limit of maximum yaw rate
  excursions of 5 deg/s following abrupt collective inputs" (Level 1); the
  Level 2 value and the ratio-to-vertical-velocity limits were not found printed.
"""
from __future__ import annotations

import numpy as np

from .base import HQSpec

__all__ = ["coupling_ratio", "peak_excursion", "coupling_specs"]

_TEST = "tests/test_hq_specs.py::test_coupling_metrics"


def _series(t, *ys):
    t = np.asarray(t, dtype=float)
    out = [np.asarray(y, dtype=float) for y in ys]
    if t.ndim != 1 or t.size < 2 or any(y.shape != t.shape for y in out):
        raise ValueError("coupling metrics: t and the responses must be 1-D arrays of equal length >= 2")
    if np.any(np.diff(t) <= 0):
        raise ValueError("coupling metrics: t must be strictly increasing")
    if not all(np.all(np.isfinite(y)) for y in out):
        raise ValueError("coupling metrics: responses have non-finite samples")
    return t, out


def coupling_ratio(t, on_axis, off_axis, at=4.0):
    """Peak |off-axis change| up to ``at`` s over |on-axis change| at ``at`` s.

    Parameters
    ----------
    t : array
        Time from the step [s].
    on_axis, off_axis : array
        Attitudes [same units], changes measured from the first sample.
    at : float
        Horizon [s].

    Returns
    -------
    float

    Examples
    --------
    >>> t = np.linspace(0, 5, 501)
    >>> round(coupling_ratio(t, 10 * t, 2 * np.sin(t)), 3)   # 2 / 40
    0.05
    """
    t, (on, off) = _series(t, on_axis, off_axis)
    if not (t[0] < at <= t[-1]):
        raise ValueError(f"coupling_ratio: at = {at} s must lie within the record ({t[0]}, {t[-1]}] s")
    on_at = abs(float(np.interp(at, t, on - on[0])))
    if on_at == 0:
        raise ValueError("coupling_ratio: the on-axis attitude has not changed at the horizon")
    sel = t <= at
    return float(np.max(np.abs(off[sel] - off[0]))) / on_at


def peak_excursion(t, response, window=None):
    """Largest |change| of ``response`` from its first sample, optionally within ``window`` s.

    Parameters
    ----------
    t : array
        Time [s], increasing.
    response : array
        The off-axis response, e.g. yaw rate [deg/s].
    window : float, optional
        Horizon from the first sample [s]; default the whole record.

    Returns
    -------
    float

    Examples
    --------
    >>> peak_excursion([0, 1, 2, 3], [1.0, 3.0, -4.0, 0.0], window=1.5)
    2.0
    """
    t, (y,) = _series(t, response)
    sel = np.ones_like(t, dtype=bool) if window is None else (t - t[0]) <= window
    return float(np.max(np.abs(y[sel] - y[0])))


def _ratio_metric(data):
    return coupling_ratio(*data) if isinstance(data, tuple) else float(data)


def _peak_metric(data):
    return peak_excursion(*data) if isinstance(data, tuple) else float(data)


def coupling_specs():
    """Inter-axis coupling specs of the library.

    Returns
    -------
    list of HQSpec

    Examples
    --------
    >>> [s.name for s in coupling_specs()]
    ['CouPRH1.pitch', 'CouPRH1.roll', 'CouYCH1.yaw']
    """
    specs = []
    for on, off in (("pitch", "roll"), ("roll", "pitch")):
        specs.append(HQSpec(f"CouPRH1.{on}", f"{off} due to {on}: peak {off} / {on} change at 4 s",
                            _ratio_metric, "max", units="-",
                            source="ADS-33E-PRF §3.3.8 pitch-roll and roll-pitch coupling (aggressive agility): "
                                   "boundary values not found printed",
                            family="coupling", axis=on, agilities=("aggressive",), speeds=("hover",),
                            status="not found", test=_TEST))
    specs.append(HQSpec("CouYCH1.yaw", "yaw-rate excursion following an abrupt collective input",
                        _peak_metric, "max", 5.0, np.nan, units="deg/s",
                        source="ADS-33E-PRF §3.3.8 yaw due to collective: Level 1 max yaw-rate excursion 5 deg/s "
                               "(Padfield, Helicopter Flight Dynamics, §6.7.1); Level 2 not found printed",
                        family="coupling", axis="yaw", speeds=("hover",), status="partial", test=_TEST))
    return specs
