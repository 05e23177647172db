"""Height response to collective (ADS-33E-PRF §3.3.9, hover and low speed).

The vertical-rate response to a step of collective is fitted over its first
5 s by the first-order model ``hdot/delta_col = K e^{-tau s} / (T s + 1)``
(time constant T, equivalent delay tau).  Boundaries (Raol & Singh, *Flight
Mechanics Modeling and Analysis*, "HLSR - heave axis response criteria",
quoting ADS-33): Level 1 T <= 5 s and tau <= 0.2 s; Level 2 T <= infinity and
tau <= 0.3 s.  The chart is drawn in the (T [s], tau [s]) plane.
"""
from __future__ import annotations

from dataclasses import dataclass

import control
import numpy as np
from scipy.optimize import least_squares

from .base import RegionSpec
from .boundaries import LevelRegions

__all__ = ["HeightFit", "fit_height_response", "height_response_fit", "HEAVE_REGIONS", "heave_specs"]

_TEST = "tests/test_hq_specs.py::test_heave_fit_and_regions"
#: fit horizon of ADS-33E-PRF's first-order height-response fit [s]
FIT_DURATION = 5.0
_T_FAR, _T_LOW, _TAU_LOW = 1.0e3, -10.0, -1.0

#: Level 1: T <= 5 s, tau <= 0.20 s; Level 2: T unbounded, tau <= 0.30 s
HEAVE_REGIONS = LevelRegions(
    [(_T_LOW, _TAU_LOW), (5.0, _TAU_LOW), (5.0, 0.20), (_T_LOW, 0.20)],
    [(_T_LOW, _TAU_LOW), (_T_FAR, _TAU_LOW), (_T_FAR, 0.30), (_T_LOW, 0.30)],
    scale=(1.0, 0.1), x_label="time constant T [s]", y_label="equivalent delay tau [s]",
    limits=((0.0, 10.0), (0.0, 0.5)))


@dataclass(frozen=True)
class HeightFit:
    """First-order fit of a vertical-rate step response.

    Attributes
    ----------
    gain : float
        K [vertical rate per collective unit].
    time_constant : float
        T [s].
    delay : float
        tau [s].
    rms_error : float
        RMS fit residual over the fitted record [vertical-rate units].
    """

    gain: float
    time_constant: float
    delay: float
    rms_error: float


def _model(x, t, amplitude):
    k, T, tau = x
    s = np.clip(t - tau, 0.0, None)
    return amplitude * k * (1.0 - np.exp(-s / T))


def fit_height_response(t, hdot, amplitude=1.0, duration=FIT_DURATION):
    """Fit ``K e^{-tau s}/(T s + 1)`` to a vertical-rate step response.

    Parameters
    ----------
    t : array
        Time from the collective step [s], starting at 0.
    hdot : array
        Vertical rate (up positive) [e.g. ft/s], change from trim.
    amplitude : float
        Collective step size [collective units].
    duration : float
        Fit horizon [s] (ADS-33E-PRF fits the first 5 s).

    Returns
    -------
    HeightFit

    Raises
    ------
    ValueError
        Bad inputs, or a record shorter than ``duration``.

    Examples
    --------
    >>> t = np.linspace(0, 6, 601)
    >>> h = 2.0 * (1 - np.exp(-np.clip(t - 0.1, 0, None) / 1.5))
    >>> f = fit_height_response(t, h)
    >>> round(f.time_constant, 3), round(f.delay, 3)
    (1.5, 0.1)
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(hdot, dtype=float)
    if t.ndim != 1 or y.shape != t.shape or t.size < 10:
        raise ValueError(f"fit_height_response: t and hdot must be 1-D of equal length >= 10, got {t.shape}, {y.shape}")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(y))) or np.any(np.diff(t) <= 0):
        raise ValueError("fit_height_response: t must be finite and increasing and hdot finite")
    if not np.isfinite(amplitude) or amplitude == 0:
        raise ValueError(f"fit_height_response: amplitude must be finite and non-zero, got {amplitude}")
    if t[-1] < duration * (1 - 1e-9):
        raise ValueError(f"fit_height_response: the record ends at {t[-1]:g} s, before the {duration:g} s fit horizon")
    sel = t <= duration + 1e-12
    t, y = t[sel], y[sel]
    k0 = y[-1] / amplitude if y[-1] != 0 else 1.0
    # delay start: first time the response reaches 2 % of its final value; T start: 63 % rise time
    reach = np.flatnonzero(np.abs(y) >= 0.02 * abs(y[-1]))
    tau0 = float(t[reach[0]]) if reach.size else 0.0
    rise = np.flatnonzero(np.abs(y) >= 0.632 * abs(y[-1]))
    T0 = max(float(t[rise[0]]) - tau0, 0.05) if rise.size else 1.0
    res = least_squares(lambda x: _model(x, t, amplitude) - y, [k0, T0, tau0],
                        bounds=([-np.inf, 1e-3, 0.0], [np.inf, 1e3, duration]), x_scale=[abs(k0) or 1.0, 1.0, 0.1],
                        xtol=1e-12, ftol=1e-12)
    k, T, tau = res.x
    return HeightFit(float(k), float(T), float(tau), float(np.sqrt(np.mean(res.fun ** 2))))


def height_response_fit(vertical_rate_response, amplitude=1.0, dt=0.005):
    """First-order fit of an LTI vertical-rate response to a collective step.

    Parameters
    ----------
    vertical_rate_response : control.LTI
        hdot per collective input (SISO, continuous time; Padé for delays).
    amplitude : float
        Collective step [collective units].
    dt : float
        Time step of the simulated record [s].

    Returns
    -------
    HeightFit

    Examples
    --------
    >>> f = height_response_fit(control.tf([3.0], [2.0, 1.0]))
    >>> round(f.time_constant, 3), round(f.delay, 3)
    (2.0, 0.0)
    """
    if not isinstance(vertical_rate_response, control.LTI):
        raise TypeError("height_response_fit: vertical_rate_response must be a control.LTI")
    t = np.arange(0.0, FIT_DURATION + dt / 2, dt)
    y = np.squeeze(control.forced_response(vertical_rate_response, t, np.full_like(t, amplitude)).outputs)
    return fit_height_response(t, y, amplitude)


def _heave_metric(data):
    if isinstance(data, HeightFit):
        fit = data
    elif isinstance(data, control.LTI):
        fit = height_response_fit(data)
    else:
        fit = fit_height_response(*data)
    return fit.time_constant, fit.delay


def heave_specs():
    """The height-response spec (time constant and delay of the first-order fit).

    Returns
    -------
    list of RegionSpec
        Metric input: a :class:`HeightFit`, an LTI hdot/collective response,
        or a ``(t, hdot[, amplitude])`` tuple.

    Examples
    --------
    >>> heave_specs()[0].regions.level((3.0, 0.1))
    1
    """
    return [RegionSpec("HgtRsH1.heave", "height response: first-order fit time constant and delay",
                       _heave_metric, "max", kind="soft", units="s",
                       source="ADS-33E-PRF §3.3.9 height response: Level 1 T <= 5 s, tau <= 0.20 s; Level 2 "
                              "T <= infinity, tau <= 0.30 s (quoted by Raol & Singh, Flight Mechanics Modeling and "
                              "Analysis, 'HLSR - heave axis response criteria')",
                       family="heave", axis="heave", speeds=("hover",), status="printed", test=_TEST,
                       regions=HEAVE_REGIONS)]
