"""Non-parametric frequency responses from time histories.

:func:`frequency_response` estimates SISO/SIMO responses by the chirp-z
transform over several overlapping windows of different lengths, and combines
the window estimates into one composite estimate (§3.2, Eqs. 3.1-3.5).  The
result, :class:`MeasuredResponse`, is a :class:`control.FrequencyResponseData`
(so it plots, combines and evaluates like any python-control LTI object) that
also carries the coherence of every element.
"""
from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
import control
from scipy.signal import czt

from ._validation import integer, names_in, real_array, real_scalar
from .errors import DataError, InputValueError, SettlingWarning, SignalNameError

__all__ = ["MeasuredResponse", "frequency_response", "combine_responses", "excitation_span"]

#: The input is at trim while it stays within this fraction of its largest excursion from
#: the first sample: a designed sweep's half-cosine fade stays under it for a fraction of a
#: period, and a flight record's trim noise is usually well below it.
_QUIET_FRACTION = 0.05


class MeasuredResponse(control.FrequencyResponseData):
    """Measured (non-parametric) frequency response with coherence.

    Parameters
    ----------
    response : array_like, complex, shape (n_outputs, n_inputs, n_freq)
    omega : array_like
        Frequencies [rad/s], increasing.
    coherence : array_like, shape like ``response``
        Coherence gamma^2 in [0, 1] of each element.
    inputs, outputs : list of str
        Signal names.
    """

    def __init__(self, response, omega, coherence, inputs, outputs, name=None):
        response = np.asarray(response, dtype=complex)
        if response.ndim != 3:
            raise DataError("response must have shape (n_outputs, n_inputs, n_freq), got "
                            f"shape {response.shape}")
        if not np.all(np.isfinite(response)):
            raise DataError(f"response contains {int(np.sum(~np.isfinite(response)))} NaN or "
                            "infinite value(s): a measured response must be finite")
        coherence = real_array("coherence", coherence)
        if coherence.shape != response.shape:
            raise DataError(f"coherence shape {coherence.shape} differs from response shape {response.shape}")
        # round-off may put a coherence a hair outside [0, 1]; anything more is an error
        if np.any(coherence < -1e-6) or np.any(coherence > 1 + 1e-6):
            raise DataError(f"coherence must lie in [0, 1], got values in "
                            f"[{coherence.min():.4g}, {coherence.max():.4g}]")
        omega = real_array("omega", omega)
        if omega.ndim != 1 or omega.size != response.shape[2]:
            raise DataError(f"omega must be 1-D with {response.shape[2]} frequencies [rad/s], "
                            f"got shape {omega.shape}")
        if np.any(omega < 0) or np.any(np.diff(omega) <= 0):
            raise DataError("omega must be non-negative and strictly increasing [rad/s]")
        inputs, outputs = [str(n) for n in inputs], [str(n) for n in outputs]
        if len(inputs) != response.shape[1] or len(outputs) != response.shape[0]:
            raise DataError(f"{len(outputs)} output and {len(inputs)} input names for a "
                            f"{response.shape[0]} x {response.shape[1]} response")
        for kind, labels in (("input", inputs), ("output", outputs)):
            if len(set(labels)) != len(labels):
                raise DataError(f"{kind} names must be unique, got {labels}")
        super().__init__(response, omega, inputs=inputs, outputs=outputs, name=name, smooth=False)
        self.coherence = np.clip(coherence, 0.0, 1.0)

    @property
    def data(self) -> np.ndarray:
        """Complex response, shape (n_outputs, n_inputs, n_freq)."""
        return self.frdata

    def element(self, output, input):
        """Complex response and coherence of one (output, input) pair (names or indices)."""
        i = self._index("output", output, self.output_labels)
        j = self._index("input", input, self.input_labels)
        return self.frdata[i, j], self.coherence[i, j]

    @staticmethod
    def _index(kind, key, labels):
        labels = list(labels)
        if isinstance(key, (int, np.integer)) and not isinstance(key, bool):
            if not -len(labels) <= key < len(labels):
                raise SignalNameError(f"{kind} index {key} out of range for {len(labels)} {kind}s {labels}")
            return int(key)
        names_in(kind, [key], labels)
        return labels.index(key)

    def select(self, outputs=None, inputs=None) -> "MeasuredResponse":
        """Sub-response with the named outputs/inputs (in the order given)."""
        if isinstance(outputs, str):
            outputs = [outputs]
        if isinstance(inputs, str):
            inputs = [inputs]
        outputs = list(self.output_labels) if outputs is None else list(outputs)
        inputs = list(self.input_labels) if inputs is None else list(inputs)
        if not outputs or not inputs:
            raise SignalNameError("select needs at least one output and one input name")
        names_in("output", outputs, self.output_labels)
        names_in("input", inputs, self.input_labels)
        oi = [self.output_labels.index(o) for o in outputs]
        ii = [self.input_labels.index(i) for i in inputs]
        return MeasuredResponse(self.frdata[np.ix_(oi, ii)], self.omega,
                                self.coherence[np.ix_(oi, ii)], inputs, outputs, name=self.name)

    def to_pandas(self) -> pd.DataFrame:
        """Long table: omega [rad/s], output, input, magnitude_db, phase_deg, coherence."""
        rows = []
        for i, o in enumerate(self.output_labels):
            for j, u in enumerate(self.input_labels):
                h = self.frdata[i, j]
                rows.append(pd.DataFrame({
                    "omega": self.omega, "output": o, "input": u,
                    "magnitude_db": 20 * np.log10(np.maximum(np.abs(h), 1e-300)),
                    "phase_deg": np.degrees(np.unwrap(np.angle(h))),
                    "coherence": self.coherence[i, j]}))
        return pd.concat(rows, ignore_index=True)

    def plot(self, outputs=None, inputs=None, fig=None):
        """Bode plot (magnitude dB, phase deg) with coherence, one column per pair.

        Returns a :class:`matplotlib.figure.Figure`.
        """
        from .plotting import bode_with_coherence
        sub = self.select(outputs, inputs)
        pairs = [(o, u) for o in sub.output_labels for u in sub.input_labels]
        return bode_with_coherence([(sub, "data")], pairs, fig=fig)


def _validate(t, u, y):
    t = real_array("t", t)
    u = real_array("u", u)
    y = real_array("y", y)
    if t.ndim != 1 or t.size < 16:
        raise DataError("t must be a 1-D array of at least 16 samples")
    if u.shape != t.shape:
        raise DataError(f"u has {u.shape} samples but t has {t.shape}: lengths must match")
    if y.ndim == 1:
        y = y[:, None]
    if y.ndim != 2 or y.shape[0] != t.size:
        raise DataError(f"y must have shape (len(t), n_outputs) = ({t.size}, n); got {y.shape}")
    steps = np.diff(t)
    dt = steps.mean()
    if dt <= 0 or np.max(np.abs(steps - dt)) > 1e-6 * max(dt, 1e-12) + 1e-9:
        raise DataError("t must be uniformly sampled and increasing "
                        f"(steps range {steps.min():.6g}..{steps.max():.6g} s); resample first")
    if np.ptp(u) == 0:
        raise DataError("u is constant: the input does not excite the system")
    return t, u, y, dt


def _detrend(segments):
    """Remove each segment's mean and linear trend (least squares)."""
    n = segments.shape[1]
    x = np.linspace(-1.0, 1.0, n)
    mean = segments.mean(axis=1, keepdims=True)
    slope = (segments @ x)[:, None] / (x @ x)
    return segments - mean - slope * x[None, :]


def _window_spectra(x, ys, dt, t_win, overlap, w_lo, w_hi, n_lin):
    """Auto/cross spectra for one window length on a linear grid [w_lo, w_hi].

    Returns (omega_lin, Gxx, Gyy, Gxy, n_segments); spectra are one-sided
    densities normalised by the window energy, so estimates from windows of
    different lengths are directly comparable (Eq. 3.3).
    """
    n_win = int(round(t_win / dt))
    step = max(1, int(round(n_win * (1.0 - overlap))))
    starts = np.arange(0, x.size - n_win + 1, step)
    taper = np.hanning(n_win)
    scale = 2.0 * dt / np.sum(taper ** 2)
    dw = (w_hi - w_lo) / max(n_lin - 1, 1)
    a = np.exp(1j * w_lo * dt)
    w = np.exp(-1j * dw * dt)
    idx = starts[:, None] + np.arange(n_win)[None, :]
    xs = x[idx]
    xs = _detrend(xs) * taper
    X = czt(xs, m=n_lin, w=w, a=a, axis=-1)
    gxx = scale * np.mean(np.abs(X) ** 2, axis=0)
    gyy = np.empty((ys.shape[1], n_lin))
    gxy = np.empty((ys.shape[1], n_lin), dtype=complex)
    for k in range(ys.shape[1]):
        yk = ys[:, k][idx]
        yk = _detrend(yk) * taper
        Y = czt(yk, m=n_lin, w=w, a=a, axis=-1)
        gyy[k] = scale * np.mean(np.abs(Y) ** 2, axis=0)
        gxy[k] = scale * np.mean(np.conj(X) * Y, axis=0)
    omega_lin = w_lo + dw * np.arange(n_lin)
    return omega_lin, gxx, gyy, gxy, len(starts)


def _frequency_plan(t, dt, *, w_min, w_max, n_points, points_per_decade, windows, n_windows,
                    max_window, min_window, cycles_per_window):
    """Checked log frequency grid [rad/s] and composite window lengths [s] of a record.

    Shared by :func:`frequency_response` and :func:`flightid.mimo_response`;
    raises InputValueError / DataError for a band or windows the record ``t`` [s]
    (step ``dt`` [s]) cannot resolve. Returns ``(omega, windows)``.
    """
    w_min = real_scalar("w_min", w_min, positive=True, unit="rad/s")
    w_max = real_scalar("w_max", w_max, positive=True, unit="rad/s")
    if not w_min < w_max:
        raise InputValueError(f"need 0 < w_min < w_max [rad/s], got w_min={w_min}, w_max={w_max}")
    points_per_decade = real_scalar("points_per_decade", points_per_decade, positive=True)
    n_windows = integer("n_windows", n_windows, minimum=1)
    if n_points is not None:
        n_points = integer("n_points", n_points, minimum=2)
    if max_window is not None:
        max_window = real_scalar("max_window", max_window, positive=True, unit="s")
    if min_window is not None:
        min_window = real_scalar("min_window", min_window, positive=True, unit="s")
    nyquist = np.pi / dt
    if w_max > 0.5 * nyquist:
        raise DataError(f"w_max = {w_max:.4g} rad/s is above half the Nyquist frequency "
                        f"({0.5 * nyquist:.4g} rad/s) for dt = {dt:.4g} s")
    record = t[-1] - t[0]
    if windows is not None:
        windows = np.sort(np.atleast_1d(real_array("windows", windows, error=InputValueError)))[::-1]
        if windows.size == 0 or windows.ndim != 1 or np.any(windows <= 0):
            raise InputValueError("windows must be a non-empty 1-D sequence of positive lengths [s]")
        if windows[-1] < 32 * dt:
            raise DataError(f"window of {windows[-1]:.4g} s holds fewer than 32 samples (dt = {dt:.4g} s)")
        max_window = windows[0]
    t_max = record / 2.0 if max_window is None else float(max_window)
    if t_max > record:
        raise DataError(f"the longest window ({t_max:.4g} s) is longer than the record ({record:.4g} s)")
    lowest = cycles_per_window * 2 * np.pi / t_max
    if w_min < lowest * (1 - 1e-9) and windows is not None:
        raise DataError(f"the longest window ({t_max:.4g} s) resolves only down to {lowest:.4g} "
                        f"rad/s, above w_min = {w_min:.4g} rad/s: add a window of >= "
                        f"{cycles_per_window * 2 * np.pi / w_min:.4g} s")
    if w_min < lowest * (1 - 1e-9):
        need = cycles_per_window * 2 * np.pi / w_min * record / t_max
        raise DataError(f"record of {record:.4g} s is too short for w_min = {w_min:.4g} rad/s: "
                        f"the longest window ({t_max:.4g} s) resolves only down to "
                        f"{lowest:.4g} rad/s; a record of >= {need:.4g} s is needed")
    if windows is None:
        t_min = t_max / 8.0 if min_window is None else float(min_window)
        t_min = max(t_min, 32 * dt)
        windows = np.geomspace(t_max, t_min, n_windows) if n_windows > 1 else np.array([t_max])
    if n_points is None:
        n_points = int(np.ceil(points_per_decade * np.log10(w_max / w_min))) + 1
    omega = np.geomspace(w_min, w_max, n_points)
    return omega, windows


def _composite(records, dt, omega, windows, overlap, cycles_per_window):
    """Composite-window response and coherence of one or several records of one input.

    ``records`` is a list of ``(u, y)`` pairs (y of shape (n, n_outputs)) sampled
    every ``dt`` [s]. For each window length the auto and cross spectra of all
    records are pooled -- summed over every record's segments (CIFER's multi-run
    concatenation), not averaged H's -- and the windows are then combined frequency
    by frequency with weights 1/eps_r^2 (see :func:`frequency_response`).
    Returns ``(h, coherence)`` of shape (n_outputs, n_freq).
    """
    n_out = records[0][1].shape[1]
    n_points = omega.size
    w_max = omega[-1]
    sum_w = np.zeros((n_out, n_points))
    acc_xx = np.zeros((n_out, n_points))
    acc_yy = np.zeros((n_out, n_points))
    acc_xy = np.zeros((n_out, n_points), dtype=complex)
    for t_win in windows:
        w_lo_win = cycles_per_window * 2 * np.pi / t_win
        valid = omega >= w_lo_win * (1 - 1e-9)
        if not valid.any():
            continue
        lo = omega[valid][0]
        # oversample the window's natural resolution 2 pi / T four times so
        # linear interpolation to the log grid adds negligible error
        n_lin = int(np.ceil((w_max - lo) / (2 * np.pi / t_win / 4))) + 2
        parts = [_window_spectra(u, y, dt, t_win, overlap, lo, w_max, n_lin) for u, y in records]
        if len(parts) == 1:
            wl, gxx, gyy, gxy, n_seg = parts[0]
        else:
            # pooled over all runs' segments: sum of the spectra, each run's mean
            # spectrum weighted by its number of segments
            wl = parts[0][0]
            n_seg = sum(p[4] for p in parts)
            gxx = sum(p[1] * p[4] for p in parts) / n_seg
            gyy = sum(p[2] * p[4] for p in parts) / n_seg
            gxy = sum(p[3] * p[4] for p in parts) / n_seg
        gxx_i = np.interp(omega[valid], wl, gxx)
        for k in range(n_out):
            gyy_i = np.interp(omega[valid], wl, gyy[k])
            gxy_i = np.interp(omega[valid], wl, gxy[k].real) + 1j * np.interp(omega[valid], wl, gxy[k].imag)
            coh = np.abs(gxy_i) ** 2 / np.maximum(gxx_i * gyy_i, 1e-300)
            coh = np.clip(coh, 1e-6, 0.9999)
            # effective number of independent averages with overlapped Hann windows
            n_eff = max(1.0, n_seg * (1.0 - overlap) * 2.0)
            eps2 = (1 - coh) / (coh * 2 * n_eff)
            wgt = 1.0 / eps2
            sum_w[k, valid] += wgt
            acc_xx[k, valid] += wgt * gxx_i
            acc_yy[k, valid] += wgt * gyy_i
            acc_xy[k, valid] += wgt * gxy_i
    gxx = acc_xx / sum_w
    gyy = acc_yy / sum_w
    gxy = acc_xy / sum_w
    if np.any(gxx <= 0):
        raise DataError("the input has no power at some requested frequencies: widen the sweep band")
    h = gxy / gxx
    coh = np.abs(gxy) ** 2 / np.maximum(gxx * gyy, 1e-300)
    return h, coh


def frequency_response(t, u, y, *, w_min, w_max, n_points=None, points_per_decade=25,
                       windows=None, n_windows=5, max_window=None, min_window=None, overlap=0.8,
                       cycles_per_window=2.0, input_name="u", output_names=None, name=None,
                       settling_time=None):
    """SISO/SIMO frequency response by chirp-z transform with composite windowing.

    Parameters
    ----------
    t : array_like
        Uniformly sampled time [s].
    u : array_like
        The (single) input time history.
    y : array_like, shape (n,) or (n, n_outputs)
        Output time histories.
    w_min, w_max : float
        Frequency range of the result [rad/s].
    n_points : int, optional
        Number of log-spaced frequencies; default ``points_per_decade`` per decade.
    windows : sequence of float, optional
        Explicit window lengths [s] (each at least 32 samples and at most the
        record). Overrides ``n_windows``, ``max_window`` and ``min_window``.
    n_windows : int
        Number of window lengths, geometrically spaced between ``min_window``
        and ``max_window`` [s] (defaults: half the record, and an eighth of that).
    overlap : float
        Fractional overlap of successive windows (0.8 as in CIFER's FRESPID).
    cycles_per_window : float
        A window of length T contributes only at frequencies >= cycles * 2 pi / T;
        the record must therefore be at least ``2 * cycles * 2 pi / w_min`` long.
    input_name, output_names : str, list of str
        Signal names carried by the result.
    settling_time : float, optional
        Time [s] the response needs to settle after a change of input; the
        record's lead-in and lead-out at trim (:func:`excitation_span`) should be
        at least this long. Default ``1 / w_min``: the time constant of a lag at
        the lowest analysed frequency, the slowest mode the response claims to
        resolve.

    Returns
    -------
    MeasuredResponse
        Shape (n_outputs, 1, n_points), with coherence.

    Warns
    -----
    SettlingWarning
        The lead-in or lead-out is shorter than ``settling_time``, or the
        excitation lasts fewer than two periods of ``w_min``.

    Notes
    -----
    Each window's spectra (Eq. 3.3) are averaged over overlapping Hann-tapered
    segments, evaluated on a fine linear grid by the chirp-z transform and
    interpolated to the log grid. The windows are combined frequency by
    frequency with weights 1/eps_r^2, eps_r = sqrt(1-gamma^2)/(|gamma| sqrt(2 n_d))
    being each window's normalised random error (Bendat & Piersol) -- a
    closed-form stand-in for CIFER's optimised composite (Tischler & Remple §7.8).

    Examples
    --------
    >>> import numpy as np, control
    >>> from flightid import frequency_sweep, frequency_response
    >>> t, u = frequency_sweep(0.5, 20.0, 60.0, 0.01, seed=0)
    >>> y = control.forced_response(control.tf([4.0], [1.0, 2.0]), t, u).outputs     # 4 / (s + 2)
    >>> data = frequency_response(t, u, y, w_min=0.5, w_max=20.0, output_names=["y"])
    >>> k = np.argmin(abs(data.omega - 2.0))
    >>> exact = abs(4.0 / (1j * data.omega[k] + 2.0))
    >>> bool(abs(abs(data.frdata[0, 0, k]) / exact - 1) < 0.02), bool(data.coherence[0, 0, k] > 0.95)
    (True, True)
    """
    t, u, y, dt = _validate(t, u, y)
    overlap = real_scalar("overlap", overlap, lo=0.0, hi=1.0, hi_open=True)
    cycles_per_window = real_scalar("cycles_per_window", cycles_per_window, positive=True)
    omega, windows = _frequency_plan(t, dt, w_min=w_min, w_max=w_max, n_points=n_points,
                                     points_per_decade=points_per_decade, windows=windows,
                                     n_windows=n_windows, max_window=max_window, min_window=min_window,
                                     cycles_per_window=cycles_per_window)
    if not isinstance(input_name, str) or not input_name:
        raise InputValueError(f"input_name must be a non-empty string, got {input_name!r}")
    n_out = y.shape[1]
    if output_names is None:
        output_names = ["y"] if n_out == 1 else [f"y{k}" for k in range(n_out)]
    if isinstance(output_names, str):
        output_names = [output_names]
    output_names = list(output_names)
    if len(output_names) != n_out:
        raise DataError(f"{len(output_names)} output names for {n_out} outputs")
    if len(set(output_names)) != n_out or input_name in output_names:
        raise DataError(f"output names must be unique and differ from the input name "
                        f"{input_name!r}, got {output_names}")

    settling_time = (1.0 / omega[0] if settling_time is None else
                     real_scalar("settling_time", settling_time, nonnegative=True, unit="s"))
    _check_settling(t, u, omega[0], settling_time)
    h, coh = _composite([(u, y)], dt, omega, windows, overlap, cycles_per_window)
    return MeasuredResponse(h[:, None, :], omega, coh[:, None, :], [input_name],
                            list(output_names), name=name)


def excitation_span(t, u):
    """Lead-in, excitation and lead-out of a record: how long the input stays at trim.

    The input is at trim while it stays within 5 % of its largest excursion from its
    first sample.

    Parameters
    ----------
    t, u : array_like
        Time [s] and the input.

    Returns
    -------
    tuple of float
        ``(lead_in, excitation, lead_out)`` [s]; a record without excitation
        returns ``(T, 0, 0)`` with T its length.

    Examples
    --------
    >>> from flightid import frequency_sweep
    >>> t, u = frequency_sweep(0.5, 20.0, 60.0, 0.01, trim_start=4.0, trim_end=2.0)
    >>> lead_in, span, lead_out = excitation_span(t, u)     # the fade-in stays quiet for 1.2 s
    >>> round(lead_in, 1), round(lead_out, 1)
    (5.2, 2.0)
    """
    t = np.asarray(t, float)
    dev = np.abs(np.asarray(u, float) - float(np.asarray(u, float)[0]))
    peak = dev.max() if dev.size else 0.0
    active = np.flatnonzero(dev > _QUIET_FRACTION * peak) if peak > 0 else np.array([], int)
    if not active.size:
        return float(t[-1] - t[0]), 0.0, 0.0
    first, last = active[0], active[-1]
    return float(t[first] - t[0]), float(t[last] - t[first]), float(t[-1] - t[last])


def _check_settling(t, u, w_min, settling_time, stacklevel=3):
    """Warn (SettlingWarning) when the record's trims or excitation are too short."""
    lead_in, span, lead_out = excitation_span(t, u)
    short = [f"{name} {v:.3g} s" for name, v in (("lead-in", lead_in), ("lead-out", lead_out))
             if v < settling_time]
    if short:
        warnings.warn(f"the record's {' and '.join(short)} at trim is shorter than the response's settling "
                      f"time {settling_time:.3g} s (default 1 / w_min): the transient to the start or the "
                      "end of the excitation is cut off; lengthen the trims or pass settling_time [s]",
                      SettlingWarning, stacklevel=stacklevel)
    if span < 4 * np.pi / w_min:
        warnings.warn(f"the excitation lasts {span:.3g} s, fewer than two periods of w_min = {w_min:.3g} "
                      f"rad/s ({4 * np.pi / w_min:.3g} s): the record is long enough only through its trims; "
                      "lengthen the sweep or raise w_min", SettlingWarning, stacklevel=stacklevel)


def combine_responses(responses, name=None) -> MeasuredResponse:
    """Place SISO/SIMO responses to *different* inputs side by side (MIMO matrix).

    All responses must share the frequency grid; outputs are matched by name
    (the union of outputs must be present in every response).
    """
    if isinstance(responses, MeasuredResponse):
        responses = [responses]
    responses = list(responses)
    if not responses:
        raise DataError("combine_responses needs at least one response")
    for k, r in enumerate(responses):
        if not isinstance(r, MeasuredResponse):
            raise DataError(f"responses[{k}] must be a MeasuredResponse, got {type(r).__name__}")
    omega = responses[0].omega
    outputs = list(responses[0].output_labels)
    inputs, data, coh = [], [], []
    for r in responses:
        if r.omega.shape != omega.shape or not np.allclose(r.omega, omega):
            raise DataError("responses must share one frequency grid to be combined")
        missing = [o for o in outputs if o not in r.output_labels]
        if missing:
            raise SignalNameError(f"response to {r.input_labels} lacks outputs {missing}")
        for j, u in enumerate(r.input_labels):
            if u in inputs:
                raise DataError(f"input {u!r} appears in more than one response")
            inputs.append(u)
            idx = [r.output_labels.index(o) for o in outputs]
            data.append(r.frdata[idx, j, :])
            coh.append(r.coherence[idx, j, :])
    return MeasuredResponse(np.stack(data, axis=1), omega, np.stack(coh, axis=1),
                            inputs, outputs, name=name)
