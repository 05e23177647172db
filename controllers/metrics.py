"""Stability, handling-qualities and loads metrics as plain functions.

Each takes an LTI object (python-control TF/SS/FRD, or a :class:`DelayedLTI`
with an exact delay) or a callable ``H(s)``, evaluates it on a dense log grid,
and returns numbers in SI units (rad/s, s) with gains in dB and phases in deg.
Phases are unwrapped before any crossing is searched (python-control users hit
wrapping bugs there); crossings are refined by interpolation in log frequency.
"""
from __future__ import annotations

import numpy as np
import control

__all__ = ["duda_olop_limit", "frequency_response_of", "crossover_frequency", "gain_phase_margins",
           "nichols_margin", "disturbance_rejection_bandwidth", "disturbance_rejection_peak",
           "attitude_bandwidth", "damping_in_band", "rms_response", "open_loop_onset_point",
           "DEFAULT_OMEGA", "NonFiniteResponseError", "BandwidthUndefinedError"]

#: default evaluation grid [rad/s]
DEFAULT_OMEGA = np.geomspace(0.01, 200.0, 4000)


class NonFiniteResponseError(ValueError):
    """A frequency response is NaN or inf at some frequency of the grid."""

    def __init__(self, message, frequency=float("nan")):
        super().__init__(message)
        self.frequency = frequency


class BandwidthUndefinedError(ValueError):
    """The attitude bandwidth is undefined (the phase never reaches -180 deg on the grid)."""


def _checked(omega, h, name=""):
    bad = ~np.isfinite(h)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise NonFiniteResponseError(
            f"{name or 'frequency response'} is {h[k]} at omega = {omega[k]:.6g} rad/s "
            f"({int(bad.sum())} of {h.size} grid points non-finite)", float(omega[k]))
    return omega, h


def frequency_response_of(sys, omega=None):
    """Complex response of ``sys`` at ``omega`` [rad/s].

    Raises
    ------
    NonFiniteResponseError
        If the response is NaN or inf anywhere on the grid (the first such
        frequency is named): a metric read from it would be silently wrong.
    """
    omega = DEFAULT_OMEGA if omega is None else np.asarray(omega, dtype=float)
    if omega.ndim != 1 or not np.all(np.isfinite(omega)) or np.any(omega <= 0):
        raise ValueError("omega must be a 1-D array of finite frequencies > 0 rad/s")
    name = getattr(sys, "name", "") or ""
    h = _frequency_response(sys, omega)
    return _checked(*h, name)


def _frequency_response(sys, omega):
    if callable(getattr(sys, "response", None)):
        # DelayedLTI / FrequencyFunction: exact delays (e^{-jw tau}), no Padé
        return omega, np.asarray(sys.response(omega), dtype=complex)
    if isinstance(sys, control.LTI):
        if sys.ninputs != 1 or sys.noutputs != 1:
            raise ValueError("metrics need a SISO system")
        if isinstance(sys, control.FrequencyResponseData):
            return sys.frequency, np.squeeze(sys.frdata)
        return omega, np.squeeze(control.frequency_response(sys, omega).complex)
    if callable(sys):
        return omega, np.asarray(sys(1j * omega), dtype=complex)
    raise TypeError(f"cannot take a frequency response of {type(sys).__name__}")


def _crossings(x, y, level):
    """Values of x where y crosses ``level`` (linear interpolation), with direction."""
    d = y - level
    idx = np.flatnonzero(np.sign(d[:-1]) * np.sign(d[1:]) < 0)
    xs = x[idx] + (x[idx + 1] - x[idx]) * (-d[idx]) / (d[idx + 1] - d[idx])
    return xs, np.sign(d[idx + 1] - d[idx])


def _mag_phase(sys, omega):
    w, h = frequency_response_of(sys, omega)
    mag_db = 20 * np.log10(np.maximum(np.abs(h), 1e-300))
    phase = np.degrees(np.unwrap(np.angle(h)))
    return w, mag_db, phase


def crossover_frequency(loop, omega=None):
    """Gain-crossover frequency [rad/s] of a broken-loop response (|L| = 1).

    The highest crossing from above is returned (CONDUIT's convention for
    loops whose gain falls through 0 dB more than once); ``nan`` if none.
    """
    w, mag, _ = _mag_phase(loop, omega)
    xs, direction = _crossings(np.log(w), mag, 0.0)
    down = xs[direction < 0]
    return float(np.exp(down[-1])) if down.size else float("nan")


def gain_phase_margins(loop, omega=None):
    """Gain margin [dB], phase margin [deg] and their frequencies [rad/s].

    Returns ``(gm_db, pm_deg, w_180, w_c)``. The gain margin is read at every
    frequency where the *unwrapped* phase crosses -180 deg (mod 360), and the one
    closest to critical is returned, with its sign: positive where the loop gain
    may rise by ``gm_db`` before the loop goes critical, negative where it may
    only fall by ``-gm_db`` (a conditionally stable loop, as every loop closed
    around an unstable plant is; python-control's
    :func:`control.stability_margins` makes the same choice). Where the closest
    crossing is a rise and a fall is nearly as close, the rise is returned. PM is
    taken at the gain crossover (:func:`crossover_frequency`). ``inf`` when there
    is no crossing.

    Parameters
    ----------
    loop : control LTI or FrequencyFunction
        Broken-loop response L.
    omega : numpy.ndarray, optional
        Frequencies [rad/s] (default: the metrics' dense grid).

    Returns
    -------
    gm_db : float
        Signed gain margin [dB] (see above).
    pm_deg : float
        Phase margin [deg].
    w_180 : float
        Frequency of the gain margin's phase crossing [rad/s].
    w_c : float
        Gain-crossover frequency [rad/s].

    See Also
    --------
    nichols_margin : the distance from the critical point in both gain and phase.

    Examples
    --------
    >>> import control
    >>> gm, pm, w180, wc = gain_phase_margins(control.tf([8.0], [1, 3, 3, 1]))
    >>> round(gm, 2)                          # 20 log10(8 / 8): critical at w = sqrt(3)
    0.0
    >>> L = control.tf([3.0, 1.5], [1.0, -1.0, 0.0])       # 3 (s + 0.5) / (s (s - 1)): unstable plant
    >>> gm, _, w180, _ = gain_phase_margins(L)
    >>> round(gm, 2), round(w180, 3)          # -20 log10(3) at w = 1/sqrt(2): only a gain reduction
    (-9.54, 0.707)
    """
    w, mag, phase = _mag_phase(loop, omega)
    lw = np.log(w)
    margins = []
    for k in range(-3, 3):
        xs, _ = _crossings(lw, phase, -180.0 + 360.0 * k)
        margins += [(float(-np.interp(x, lw, mag)), x) for x in xs]
    gm, w180 = float("inf"), float("nan")
    if margins:
        # closest to critical in either direction; the rise first on a tie (round-off)
        g, x = min(margins, key=lambda t: (round(abs(t[0]), 9), -np.sign(t[0])))
        gm, w180 = g, float(np.exp(x))
    wc = crossover_frequency(loop, omega)
    if np.isnan(wc):
        return gm, float("inf"), w180, wc
    ph = float(np.interp(np.log(wc), lw, phase))
    pm = (ph + 180.0) % 360.0
    pm = pm - 360.0 if pm > 180.0 else pm
    return gm, pm, w180, wc


def nichols_margin(loop, omega=None, phase_axis=45.0, gain_axis=6.0):
    """Normalised distance of the Nichols curve from an elliptical exclusion zone.

    The zone is the ellipse centred on the critical point (-180 deg, 0 dB) with
    semi-axes ``phase_axis`` [deg] and ``gain_axis`` [dB]; it passes through the
    Level 1 gain/phase-margin points (6 dB, 45 deg) of MIL-DTL-9490E / ADS-33E
    and approximates the Nichols-margin exclusion zone of CONDUIT's NicMgG1
    (Tischler et al., *Practical Methods for Aircraft and Rotorcraft Flight
    Control Design*, AIAA 2017, Ch. 6), which is not printed in the dissertation.

    Returns ``min_k sqrt((dphi_k/phase_axis)^2 + (g_k/gain_axis)^2) - 1``, where
    dphi is the phase distance to the nearest odd multiple of 180 deg:
    >= 0 means the curve stays outside the zone.
    """
    _, mag, phase = _mag_phase(loop, omega)
    dphi = (phase + 180.0) % 360.0
    dphi = np.where(dphi > 180.0, dphi - 360.0, dphi)
    dist = np.sqrt((dphi / phase_axis) ** 2 + (mag / gain_axis) ** 2)
    return float(dist.min() - 1.0)


def disturbance_rejection_bandwidth(sys, omega=None):
    """Frequency [rad/s] where the disturbance response first reaches -3 dB.

    ``sys`` is the output-disturbance response (e.g. phi'/phi_d = 1/(1+L)).
    ADS-33E-PRF §3.2.9 / Tischler et al. (2017): for L = K/s this is exactly K.
    """
    w, mag, _ = _mag_phase(sys, omega)
    xs, direction = _crossings(np.log(w), mag, -3.0103)
    up = xs[direction > 0]
    return float(np.exp(up[0])) if up.size else float("nan")


def disturbance_rejection_peak(sys, omega=None):
    """Peak magnitude [dB] of the disturbance response."""
    _, mag, _ = _mag_phase(sys, omega)
    return float(mag.max())


def attitude_bandwidth(sys, omega=None, response_type="attitude"):
    """ADS-33E bandwidth [rad/s] and phase delay [s] of an attitude response.

    ``sys`` is attitude / control input (e.g. phi/delta_lat).  Following
    ADS-33E-PRF §3.2 (Fig. 3.2-1 definitions): w_180 where the phase is -180 deg;
    w_BW,phase where the phase is -135 deg; w_BW,gain where the gain is 6 dB
    above the gain at w_180; bandwidth = min of the two for rate response
    types (``response_type="rate"``), w_BW,phase alone for attitude-command
    (ACAH) response types (``"attitude"``, ADS-33E-PRF §3.2); phase delay
    tau_p = -(phase(2 w_180) + 180) / (57.3 * 2 w_180).

    Returns ``(bandwidth, phase_delay, w_bw_phase, w_bw_gain, w_180)``.
    """
    w, mag, phase = _mag_phase(sys, omega)
    lw = np.log(w)
    # the attitude response starts near -90 deg (integrator); search the unwrapped phase
    x180, d180 = _crossings(lw, phase, -180.0)
    x135, d135 = _crossings(lw, phase, -135.0)
    if not x180.size or not x135.size:
        raise BandwidthUndefinedError("the attitude response never reaches -180 deg on the frequency grid")
    w180 = float(np.exp(x180[0]))
    wbw_phase = float(np.exp(x135[0]))
    gain180 = float(np.interp(x180[0], lw, mag))
    xg, dg = _crossings(lw, mag, gain180 + 6.0)
    down = xg[dg < 0]
    wbw_gain = float(np.exp(down[-1])) if down.size else float("inf")
    phase_2w = float(np.interp(np.log(2 * w180), lw, phase))
    tau_p = -(phase_2w + 180.0) / (np.degrees(1.0) * 2 * w180)
    if response_type not in ("rate", "attitude"):
        raise ValueError(f"response_type must be 'rate' or 'attitude', got {response_type!r}")
    bw = min(wbw_phase, wbw_gain) if response_type == "rate" else wbw_phase
    return bw, tau_p, wbw_phase, wbw_gain, w180


def damping_in_band(poles, w_lo, w_hi):
    """Smallest damping ratio of the poles with natural frequency in [w_lo, w_hi] rad/s.

    Returns ``inf`` if no pole lies in the band. Unstable poles give negative damping.
    The band edges are widened by a relative 1e-6 so that a pole placed on an
    edge (the 4 rad/s command model against the 4-20 rad/s band) is counted
    regardless of round-off in the eigenvalue solver.
    """
    poles = np.asarray(poles, dtype=complex)
    wn = np.abs(poles)
    sel = (wn >= w_lo * (1 - 1e-6)) & (wn <= w_hi * (1 + 1e-6)) & (wn > 0)
    if not sel.any():
        return float("inf")
    return float(np.min(-poles[sel].real / wn[sel]))


def rms_response(sys, omega=None, input_band=(0.1, 10.0)):
    """RMS of the response to unit-intensity white noise band-limited to ``input_band`` [rad/s].

    ``sqrt(1/pi * int |H(jw)|^2 dw)`` over the band: CONDUIT's RmsAcG1-style
    actuator-activity measure (Tischler et al. 2017, Ch. 6), used as an objective.
    """
    lo, hi = input_band
    w = np.geomspace(lo, hi, 800) if omega is None else np.asarray(omega, float)
    _, h = frequency_response_of(sys, w)
    return float(np.sqrt(np.trapezoid(np.abs(h) ** 2, w) / np.pi))


def open_loop_onset_point(loop, pilot_to_actuator, stick_amplitude, rate_limit, omega=None):
    """Open-loop onset point (OLOP, Duda 1997) for actuator rate limiting.

    The onset frequency is the lowest frequency at which a sinusoidal stick input
    of amplitude ``stick_amplitude`` drives the actuator (mixer input) at its
    ``rate_limit``: ``w |delta_mx/delta(jw)| A = R``. The OLOP is the broken-loop
    response ``loop`` at that frequency on the Nichols chart.

    Returns ``(phase_deg, gain_db, w_onset)``; ``(nan, nan, inf)`` if the rate
    limit is never reached on the grid.
    """
    w = DEFAULT_OMEGA if omega is None else np.asarray(omega, float)
    _, h_act = frequency_response_of(pilot_to_actuator, w)
    rate = w * np.abs(h_act) * stick_amplitude
    above = np.flatnonzero(rate >= rate_limit)
    if not above.size:
        return float("nan"), float("nan"), float("inf")
    k = above[0]
    w_on = w[k] if k == 0 else float(np.exp(np.interp(np.log(rate_limit), np.log(rate[k - 1:k + 1]),
                                                       np.log(w[k - 1:k + 1]))))
    _, mag, phase = _mag_phase(loop, w)
    return (float(np.interp(np.log(w_on), np.log(w), phase)), float(np.interp(np.log(w_on), np.log(w), mag)), w_on)


def duda_olop_limit(phase_deg):
    """Approximate OLOP Level 1 gain limit [dB] at a loop phase [deg].

    The line used by the OLOP specs (``OlpOpG1``): -2 dB
    at -180 deg (and below, down to -360 deg) rising linearly to +10 dB at
    -120 deg, unbounded from -120 deg to 0 deg (an approximation of Duda's
    (1997) boundary; the printed chart was not found).  The phase is taken
    modulo 360 deg.

    Parameters
    ----------
    phase_deg : float
        Broken-loop phase at the onset frequency [deg].

    Returns
    -------
    float

    Examples
    --------
    >>> duda_olop_limit(-180.0), duda_olop_limit(-150.0)
    (-2.0, 4.0)
    """
    ph = (phase_deg + 360.0) % 360.0 - 180.0    # distance above -180 deg, in [-180, 180)
    return -2.0 + 12.0 * max(0.0, ph) / 60.0 if ph < 60.0 else float("inf")
