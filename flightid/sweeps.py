"""Test inputs: CIFER-style frequency sweeps, shaped noise, doublets and 3-2-1-1s.

All functions return ``(t, u)``: time [s] starting at 0 and the input signal,
sampled every ``dt`` seconds, starting and ending at trim (zero perturbation).
"""
from __future__ import annotations

import warnings

import numpy as np

from ._validation import integer, real_scalar
from .errors import DataError, InputValueError, SettlingWarning

__all__ = ["frequency_sweep", "shaped_noise", "doublet", "multistep_3211"]

# CIFER / Tischler & Remple recommended exponential growth constants: with these
# the instantaneous frequency reaches w_max exactly at the end of the sweep
# (C2 (e^C1 - 1) = 1.002) while spending most of the record at low frequency,
# where longer periods need more time to be identified.
_C1 = 4.0
_C2 = 0.0187
#: largest record any input generator builds (8e7 samples = 640 MB of float64)
_MAX_SAMPLES = 80_000_000


def _check_positive(**values):
    """Each value as a positive finite real float (InputValueError naming it otherwise)."""
    return [real_scalar(name, value, positive=True) for name, value in values.items()]


def frequency_sweep(w_min, w_max, duration, dt, amplitude=1.0, *, trim_start=3.0,
                    trim_end=3.0, noise_fraction=0.0, seed=None, fade_cycles=0.5, settling_time=None):
    """CIFER-style swept sine with trim lead-in and lead-out.

    The instantaneous frequency grows log-linearly (exponentially in time) from
    ``w_min`` to ``w_max``: ``w(t) = w_min + C2 (exp(C1 t / T) - 1) (w_max - w_min)``
    with C1 = 4, C2 = 0.0187 (Tischler & Remple, *Aircraft and Rotorcraft System
    Identification*, Ch. 6), and the signal is ``amplitude * sin(int w dt)``.

    Parameters
    ----------
    w_min, w_max : float
        Start and end frequency [rad/s], ``0 < w_min < w_max``.
    duration : float
        Length of the swept part [s]; it should hold at least two periods of
        ``w_min`` (``4 pi / w_min``).
    dt : float
        Sample time [s]; must resolve ``w_max`` with >= 8 samples per period.
    amplitude : float
        Sweep amplitude (units of the input).
    trim_start, trim_end : float
        Seconds at trim (zero) before and after the sweep.
    noise_fraction : float
        RMS of an added shaped-noise companion (band-limited to [w_min, w_max],
        §3.3.4) as a fraction of ``amplitude``; 0 disables it.
    seed : int or None
        Seed of the noise generator (explicit for reproducibility).
    fade_cycles : float
        The first and last ``fade_cycles`` periods are faded in/out with a
        half-cosine so the input starts and ends at trim without a step. Fades
        longer than the sweep together raise :class:`InputValueError`.

    settling_time : float, optional
        Time [s] the response needs to settle after a change of input; each trim
        should be at least this long. Default ``1 / w_min`` (the time constant of
        a lag at the lowest swept frequency), the default of
        :func:`frequency_response`'s check.

    Warns
    -----
    UserWarning
        When the whole record (trims included) is shorter than
        :func:`frequency_response` needs to resolve ``w_min`` with its default
        windows (``8 pi / w_min``: two windows of two periods).
    SettlingWarning
        When ``trim_start`` or ``trim_end`` is shorter than ``settling_time``.

    Returns
    -------
    t : ndarray
        Time [s], ``trim_start + duration + trim_end`` long.
    u : ndarray
        The input.

    Examples
    --------
    >>> t, u = frequency_sweep(0.5, 20.0, 60.0, 0.01, seed=0)
    >>> round(float(t[-1]), 2), round(float(np.abs(u).max()), 2)    # 3 s trims around 60 s
    (66.0, 1.0)
    """
    w_min, w_max, duration, dt = _check_positive(w_min=w_min, w_max=w_max, duration=duration, dt=dt)
    amplitude = real_scalar("amplitude", amplitude)
    trim_start = real_scalar("trim_start", trim_start, nonnegative=True, unit="s")
    trim_end = real_scalar("trim_end", trim_end, nonnegative=True, unit="s")
    noise_fraction = real_scalar("noise_fraction", noise_fraction, nonnegative=True)
    fade_cycles = real_scalar("fade_cycles", fade_cycles, positive=True)
    if not w_max > w_min:
        raise InputValueError(f"w_max ({w_max}) must exceed w_min ({w_min}) [rad/s]")
    if duration < 4 * np.pi / w_min:
        raise InputValueError(f"duration {duration:.3g} s holds fewer than two periods of "
                         f"w_min = {w_min:.3g} rad/s (needs >= {4 * np.pi / w_min:.3g} s)")
    if dt > 2 * np.pi / w_max / 8:
        raise InputValueError(f"dt = {dt:.3g} s gives fewer than 8 samples per period at w_max = "
                         f"{w_max:.3g} rad/s (needs dt <= {2 * np.pi / w_max / 8:.3g} s)")
    fade_in = fade_cycles * 2 * np.pi / w_min
    fade_out = fade_cycles * 2 * np.pi / w_max
    if fade_in + fade_out > duration:
        raise InputValueError(f"fade_cycles = {fade_cycles:g} fades over {fade_in + fade_out:.4g} s, longer "
                              f"than the sweep (duration = {duration:.4g} s): the fades would overlap and "
                              f"the envelope jump; use fade_cycles <= "
                              f"{duration / (2 * np.pi / w_min + 2 * np.pi / w_max):.4g}")
    settling_time = (1.0 / w_min if settling_time is None else
                     real_scalar("settling_time", settling_time, nonnegative=True, unit="s"))
    short = [f"{n} = {v:.3g} s" for n, v in (("trim_start", trim_start), ("trim_end", trim_end))
             if v < settling_time]
    if short:
        warnings.warn(f"{' and '.join(short)} shorter than the response's settling time {settling_time:.3g} s "
                      "(default 1 / w_min): the transient to the start or the end of the sweep would be cut "
                      "off; lengthen the trims [s]", SettlingWarning, stacklevel=2)
    record = trim_start + duration + trim_end
    needed = 2 * 2.0 * 2 * np.pi / w_min
    if record < needed:
        warnings.warn(f"the record ({record:.4g} s with trims) is shorter than frequency_response needs to "
                      f"resolve w_min = {w_min:.4g} rad/s with its default windows (>= {needed:.4g} s: "
                      "two windows of two periods); lengthen duration or trim_start [s]", UserWarning,
                      stacklevel=2)
    n_total = int(round((trim_start + duration + trim_end) / dt)) + 1
    if n_total > _MAX_SAMPLES:
        raise InputValueError(f"the record would hold {n_total:.3g} samples (> {_MAX_SAMPLES:.0e}): "
                              "check dt [s] and the durations [s]")
    t = np.arange(n_total) * dt
    tau = t - trim_start
    inside = (tau >= 0) & (tau <= duration)
    # phase = integral of w(t): closed form of the exponential growth law
    ts = np.clip(tau, 0, duration)
    phase = w_min * ts + (w_max - w_min) * _C2 * (
        duration / _C1 * (np.exp(_C1 * ts / duration) - 1.0) - ts)
    u = np.where(inside, amplitude * np.sin(phase), 0.0)
    # half-cosine fades so the sweep leaves and returns to trim smoothly
    env = np.ones_like(t)
    m = inside & (tau < fade_in)
    env[m] = 0.5 * (1 - np.cos(np.pi * tau[m] / fade_in))
    m = inside & (tau > duration - fade_out)
    env[m] = 0.5 * (1 - np.cos(np.pi * (duration - tau[m]) / fade_out))
    u = u * env
    if noise_fraction:
        noise = shaped_noise(n_total, dt, w_min, w_max, rms=noise_fraction * abs(amplitude), seed=seed)
        u = u + np.where(inside, noise * env, 0.0)
    return t, u


def shaped_noise(n, dt, w_min, w_max, rms=1.0, seed=None):
    """Gaussian noise band-limited to [w_min, w_max] rad/s, scaled to ``rms``.

    Used as a decorrelating companion input (§3.3.4). Shaping is done in the
    frequency domain (zeroing FFT bins outside the band), so the band edges are
    exact. ``seed`` makes it reproducible.
    """
    n = integer("n", n, minimum=2)
    dt, w_min, w_max = _check_positive(dt=dt, w_min=w_min, w_max=w_max)
    rms = real_scalar("rms", rms, nonnegative=True)
    if not w_max > w_min:
        raise InputValueError(f"w_max ({w_max}) must exceed w_min ({w_min}) [rad/s]")
    rng = np.random.default_rng(seed)
    white = rng.standard_normal(n)
    spec = np.fft.rfft(white)
    w = 2 * np.pi * np.fft.rfftfreq(n, dt)
    spec[(w < w_min) | (w > w_max)] = 0.0
    shaped = np.fft.irfft(spec, n)
    std = shaped.std()
    if std == 0:
        raise InputValueError("the band [w_min, w_max] holds no frequency bin of this record: "
                              "lengthen the record (n * dt) or widen the band")
    return shaped * (rms / std)


def _pulses(levels, amplitude, pulse_width, dt, duration, start):
    pulse_width, dt, duration = _check_positive(pulse_width=pulse_width, dt=dt, duration=duration)
    amplitude = real_scalar("amplitude", amplitude)
    start = real_scalar("start", start, nonnegative=True, unit="s")
    if pulse_width < dt:
        raise InputValueError(f"pulse_width ({pulse_width:.3g} s) must be at least one sample "
                              f"(dt = {dt:.3g} s)")
    end = start + pulse_width * sum(abs(n) for n, _ in levels)
    if end > duration:
        raise DataError(f"the input ends at {end:.3g} s, after the record ({duration:.3g} s)")
    if duration / dt > _MAX_SAMPLES:
        raise InputValueError(f"the record would hold {duration / dt:.3g} samples (> {_MAX_SAMPLES:.0e}): "
                              "check dt and duration [s]")
    t = np.arange(int(round(duration / dt)) + 1) * dt
    u = np.zeros_like(t)
    t0 = start
    for n_widths, sign in levels:
        t1 = t0 + n_widths * pulse_width
        u[(t >= t0 - 1e-12) & (t < t1 - 1e-12)] = sign * amplitude
        t0 = t1
    return t, u


def doublet(amplitude, pulse_width, dt, duration, start=1.0):
    """Doublet: +amplitude for ``pulse_width`` s, then -amplitude as long, then trim.

    Returns ``(t, u)`` with t in [0, duration] s.
    """
    return _pulses([(1, 1.0), (1, -1.0)], amplitude, pulse_width, dt, duration, start)


def multistep_3211(amplitude, pulse_width, dt, duration, start=1.0):
    """3-2-1-1 multistep: +3, -2, +1, -1 pulse widths of ``pulse_width`` s."""
    return _pulses([(3, 1.0), (2, -1.0), (1, 1.0), (1, -1.0)],
                   amplitude, pulse_width, dt, duration, start)
