"""Orthogonal multisine excitation: several inputs swept at once in one record.

:func:`orthogonal_multisine` builds Morelli-type inputs (Morelli, "Multiple input
design for real-time parameter estimation in the frequency domain", 13th IFAC
SYSID, 2003): every input is a sum of harmonics of the record's base frequency
``2 pi / T``; the harmonics in ``[w_min, w_max]`` are dealt out to the inputs in
turn, so the harmonic sets are disjoint and the inputs are mutually orthogonal
over the record (their cross-spectra vanish at every harmonic). The phases start
from Schroeder's formula (low peak factor for a given power spectrum) and are
then improved by the clipping iteration of Van der Ouderaa et al. (1988).

With ``m`` inputs excited at once, one record replaces ``m`` one-at-a-time
sweeps: the dissertation's recommendation 6 (fewer revolutions per
identification).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from ._validation import integer, real_scalar
from .errors import InputValueError

__all__ = ["Multisine", "orthogonal_multisine", "relative_peak_factor"]

_MAX_SAMPLES = 5e7


def relative_peak_factor(u):
    """Relative peak factor of a signal, ``(max u - min u) / (2 sqrt(2) rms(u))``.

    A single sinusoid has RPF 1; a sum of harmonics with equal phases has
    roughly ``sqrt(2 N)``; Schroeder phases bring it to about 1.1-1.5.

    Parameters
    ----------
    u : array_like, shape (n,) or (n, m)
        Signal(s), one column per input (the mean is removed first).

    Returns
    -------
    float or ndarray
        RPF of each column (dimensionless).
    """
    u = np.asarray(u, dtype=float)
    if u.ndim not in (1, 2) or u.shape[0] < 2 or not np.all(np.isfinite(u)):
        raise InputValueError("u must be a finite 1-D or 2-D array of at least 2 samples")
    d = u - u.mean(axis=0)
    rms = np.sqrt(np.mean(d ** 2, axis=0))
    if np.any(rms == 0):
        raise InputValueError("u is constant: its peak factor is undefined")
    return (u.max(axis=0) - u.min(axis=0)) / (2 * np.sqrt(2) * rms)


@dataclass(frozen=True)
class Multisine:
    """Orthogonal multisine inputs (result of :func:`orthogonal_multisine`).

    Unpacks as ``t, U, harmonics = orthogonal_multisine(...)``.

    Attributes
    ----------
    t : ndarray, shape (n_t,)
        Time [s], ``n_periods`` whole periods sampled at ``dt`` (the sample one
        period after the last is not included, so the record is exactly periodic).
    U : ndarray, shape (n_t, n_inputs)
        Inputs [rad] (or the units of ``amplitude``); each column peaks at its amplitude.
    harmonics : tuple of ndarray of int
        Harmonic numbers ``k`` of each input (frequency ``2 pi k / period``); disjoint.
    harmonic_amplitudes : tuple of ndarray
        Amplitude of each input's harmonics (same units as ``U``).
    phases : tuple of ndarray
        Sine phase of each harmonic [rad]: ``u_j = sum a_k sin(w_k t + phi_k)``.
    period : float
        Period ``T`` [s]; base frequency ``2 pi / T`` [rad/s].
    relative_peak_factor : ndarray, shape (n_inputs,)
        RPF of each input (1 for a single sinusoid).
    """

    t: np.ndarray
    U: np.ndarray
    harmonics: tuple
    harmonic_amplitudes: tuple
    phases: tuple
    period: float
    relative_peak_factor: np.ndarray

    def __iter__(self):
        return iter((self.t, self.U, self.harmonics))

    @property
    def n_inputs(self):
        """Number of inputs."""
        return self.U.shape[1]

    @property
    def omega(self):
        """Frequencies of each input's harmonics [rad/s] (tuple of arrays)."""
        return tuple(2 * np.pi * k / self.period for k in self.harmonics)

    def to_pandas(self) -> pd.DataFrame:
        """Time history table: ``t`` [s] and one column ``u0, u1, ...`` per input."""
        return pd.DataFrame({"t": self.t, **{f"u{j}": self.U[:, j] for j in range(self.n_inputs)}})

    def harmonic_table(self) -> pd.DataFrame:
        """One row per harmonic: input, k, omega [rad/s], amplitude, phase [rad]."""
        rows = [pd.DataFrame({"input": j, "k": k, "omega": 2 * np.pi * k / self.period,
                              "amplitude": a, "phase": p})
                for j, (k, a, p) in enumerate(zip(self.harmonics, self.harmonic_amplitudes, self.phases))]
        return pd.concat(rows, ignore_index=True).sort_values("k", ignore_index=True)

    def plot(self, fig=None):
        """Time histories and harmonic amplitude spectra; a :class:`matplotlib.figure.Figure`.

        Parameters
        ----------
        fig : matplotlib.figure.Figure, optional
            Figure to draw in (a new one by default).
        """
        import matplotlib.pyplot as plt
        fig = fig or plt.figure(figsize=(10, 6))
        ax_t, ax_f = fig.subplots(2, 1)
        for j in range(self.n_inputs):
            ax_t.plot(self.t, self.U[:, j], lw=0.6,
                      label=f"u{j} (RPF {self.relative_peak_factor[j]:.2f})")
            ax_f.semilogx(self.omega[j], self.harmonic_amplitudes[j], ".", ms=3, label=f"u{j}")
        ax_t.set_xlabel("t [s]")
        ax_t.set_ylabel("input")
        ax_t.legend(fontsize=7, ncol=3)
        ax_f.set_xlabel("omega [rad/s]")
        ax_f.set_ylabel("harmonic amplitude")
        fig.tight_layout()
        return fig


def _synthesise(ks, amps, phases, n):
    """One period of ``sum a_k sin(2 pi k i / n + phi_k)`` on ``n`` samples (inverse real FFT)."""
    spec = np.zeros(n // 2 + 1, dtype=complex)
    # a sin(x + phi) = a cos(x + phi - pi/2); irfft of n/2 a e^{i theta} at bin k is a cos(.. + theta)
    spec[ks] = 0.5 * n * amps * np.exp(1j * (phases - np.pi / 2))
    return np.fft.irfft(spec, n)


def _schroeder(amps, offset):
    """Schroeder's phases for harmonic powers ``amps**2``: phi_k = -2 pi sum_{l<k} (k - l) p_l."""
    p = amps ** 2 / np.sum(amps ** 2)
    idx = np.arange(p.size)
    phi = np.array([-2 * np.pi * np.sum((k - idx[:k]) * p[:k]) for k in range(p.size)])
    return np.mod(phi + offset, 2 * np.pi)


def _reduce_peak(ks, amps, phases, n, iterations):
    """Clipping iteration: clip the signal, keep the phases of its spectrum at ``ks``, restore the
    amplitudes; the lowest-RPF phases seen are returned."""
    best, best_rpf = phases, relative_peak_factor(_synthesise(ks, amps, phases, n))
    for _ in range(iterations):
        u = _synthesise(ks, amps, phases, n)
        level = 0.9 * np.max(np.abs(u))
        spec = np.fft.rfft(np.clip(u, -level, level))
        phases = np.angle(spec[ks]) + np.pi / 2
        rpf = relative_peak_factor(_synthesise(ks, amps, phases, n))
        if rpf < best_rpf:
            best, best_rpf = phases, rpf
    return np.mod(best, 2 * np.pi)


def orthogonal_multisine(n_inputs, duration, dt, w_min, w_max, amplitude=1.0, *, spectrum="flat",
                         n_periods=1, fade=0.0, seed=None, iterations=40) -> Multisine:
    """Mutually orthogonal multisine inputs with low peak factors (Morelli-type).

    Parameters
    ----------
    n_inputs : int
        Number of inputs excited at once.
    duration : float
        Period ``T`` [s] (rounded to a whole number of samples); the harmonics are
        ``w_k = 2 pi k / T``.
    dt : float
        Sample time [s]; ``w_max`` must be below half the Nyquist frequency.
    w_min, w_max : float
        Excited band [rad/s]: every harmonic in it is given to exactly one input
        (input ``j`` gets the ``j``-th, ``j + n_inputs``-th, ... harmonic).
    amplitude : float or sequence of float
        Peak value of each input (one value for all, or one per input), in the
        units of the input ([rad] for a control).
    spectrum : {"flat", "log"}
        Harmonic amplitudes: equal ("flat", power uniform in frequency) or
        proportional to ``w_k^-1/2`` ("log", equal power per decade like an
        exponential sweep: more excitation at the low frequencies that a
        log-spaced fit weights as much as the high ones).
    n_periods : int
        Whole periods in the record (two or more allow coherence estimates of
        :func:`flightid.mimo.harmonic_response`).
    fade : float
        Half-cosine fade-in and fade-out [s] at the ends of the record (0: none),
        so a system at trim is not hit with a step; it breaks exact periodicity.
    seed : int or None
        Seed of the random start phase of each input's Schroeder phases (None:
        all start at zero). Explicit for reproducibility.
    iterations : int
        Clipping iterations of the peak-factor reduction per input (0: plain
        Schroeder phases).

    Returns
    -------
    Multisine
        ``t`` [s], ``U`` (n_t, n_inputs), the harmonic sets, their amplitudes and
        phases, the period [s] and each input's relative peak factor.

    Raises
    ------
    InputValueError
        A non-positive or non-finite argument, ``w_min >= w_max``, a band above
        half the Nyquist frequency, or a band holding fewer harmonics than inputs.
    """
    n_inputs = integer("n_inputs", n_inputs, minimum=1)
    duration = real_scalar("duration", duration, positive=True, unit="s")
    dt = real_scalar("dt", dt, positive=True, unit="s")
    w_min = real_scalar("w_min", w_min, positive=True, unit="rad/s")
    w_max = real_scalar("w_max", w_max, positive=True, unit="rad/s")
    n_periods = integer("n_periods", n_periods, minimum=1)
    iterations = integer("iterations", iterations, minimum=0)
    fade = real_scalar("fade", fade, nonnegative=True, unit="s")
    if spectrum not in ("flat", "log"):
        raise InputValueError(f"spectrum must be 'flat' or 'log', got {spectrum!r}")
    if not w_min < w_max:
        raise InputValueError(f"need 0 < w_min < w_max [rad/s], got w_min={w_min}, w_max={w_max}")
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, (int, np.integer))):
        raise InputValueError(f"seed must be an integer or None, got {seed!r}")
    amps_in = np.atleast_1d(np.asarray(amplitude, dtype=object))
    if amps_in.ndim != 1 or amps_in.size not in (1, n_inputs):
        raise InputValueError(f"amplitude must be one value or {n_inputs} values (one per input), "
                              f"got {amplitude!r}")
    peaks = np.array([real_scalar(f"amplitude[{j}]", a, positive=True)
                      for j, a in enumerate(amps_in)]) * np.ones(n_inputs)
    n = int(round(duration / dt))
    if n < 16:
        raise InputValueError(f"duration {duration:.4g} s holds fewer than 16 samples of dt = {dt:.4g} s")
    if n * n_periods > _MAX_SAMPLES:
        raise InputValueError(f"the record would hold {n * n_periods:.3g} samples (> {_MAX_SAMPLES:.0e}): "
                              "check dt [s] and duration [s]")
    period = n * dt
    if w_max > 0.5 * np.pi / dt:
        raise InputValueError(f"w_max = {w_max:.4g} rad/s is above half the Nyquist frequency "
                              f"({0.5 * np.pi / dt:.4g} rad/s) for dt = {dt:.4g} s")
    if 2 * fade > n * n_periods * dt:
        raise InputValueError(f"fade of {fade:.4g} s at each end is longer than half the record")
    dw = 2 * np.pi / period
    k_all = np.arange(int(np.ceil(w_min / dw - 1e-9)), int(np.floor(w_max / dw + 1e-9)) + 1)
    k_all = k_all[k_all >= 1]
    if k_all.size < n_inputs:
        raise InputValueError(
            f"the band [{w_min:.4g}, {w_max:.4g}] rad/s holds {k_all.size} harmonics of 2 pi / {period:.4g} s "
            f"but there are {n_inputs} inputs: lengthen the record (duration >= "
            f"{2 * np.pi * n_inputs / (w_max - w_min):.4g} s) or widen the band")
    rng = np.random.default_rng(seed)
    harmonics, amplitudes, phases, columns = [], [], [], []
    for j in range(n_inputs):
        ks = k_all[j::n_inputs]
        a = np.ones(ks.size) if spectrum == "flat" else (ks / ks[0]) ** -0.5
        offset = 0.0 if seed is None else rng.uniform(0, 2 * np.pi)
        ph = _reduce_peak(ks, a, _schroeder(a, offset), n, iterations)
        u = _synthesise(ks, a, ph, n)
        scale = peaks[j] / np.max(np.abs(u))
        harmonics.append(ks)
        amplitudes.append(a * scale)
        phases.append(ph)
        columns.append(np.tile(u * scale, n_periods))
    U = np.column_stack(columns)
    t = dt * np.arange(U.shape[0])
    if fade > 0:
        env = np.ones(t.size)
        t_end = t[-1] + dt
        rise = t < fade
        env[rise] = 0.5 * (1 - np.cos(np.pi * t[rise] / fade))
        fall = t > t_end - fade
        env[fall] = 0.5 * (1 - np.cos(np.pi * (t_end - t[fall]) / fade))
        U = U * env[:, None]
    return Multisine(t=t, U=U, harmonics=tuple(harmonics), harmonic_amplitudes=tuple(amplitudes),
                     phases=tuple(phases), period=period,
                     relative_peak_factor=np.atleast_1d(relative_peak_factor(U)))
