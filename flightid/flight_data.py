"""Flight-test records in: named channels with units, resampling, detrending, multi-run responses.

A flight-test record arrives as a table (a :class:`pandas.DataFrame`, or a CSV
file read through pandas) with a time column and named channels. This module
turns it into a :class:`FlightRecord` -- uniform time [s], channels, units --
and from one or several records of the same axis into a
:class:`~flightid.MeasuredResponse` with coherence:

* :func:`read_flight_data` checks the time base. A non-uniform record is
  refused (the error names the ``resample`` argument) unless ``resample`` gives
  the new step: ``method="linear"`` interpolates, ``method="antialias"``
  low-pass filters (zero-phase Butterworth at 80 % of the new Nyquist frequency)
  before sampling, which is what a record logged faster than it is analysed needs.
* :meth:`FlightRecord.detrended` removes each channel's mean (``"mean"``) or
  least-squares line (``"linear"``), as CIFER and SIDPAC do before transforming
  a whole record. (:func:`~flightid.frequency_response` already removes mean and
  trend in every window segment.)
* :func:`concatenated_response` is CIFER's multi-run concatenation: for each
  composite window the auto and cross spectra of all runs are pooled (summed
  over every run's segments) before H = G_xy / G_xx and gamma^2 are formed --
  never an average of the runs' H's. It uses the same chirp-z, composite-window
  machinery as :func:`~flightid.frequency_response`.
"""
from __future__ import annotations

import os
import re
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from scipy.signal import butter, sosfiltfilt

from ._validation import names_in, real_array, real_scalar
from .errors import DataError, InputValueError, SignalNameError
from .response import MeasuredResponse, _composite, _frequency_plan, _validate, frequency_response

__all__ = ["FlightRecord", "read_flight_data", "concatenated_response"]

_UNIT = re.compile(r"^\s*(?P<name>.*?)\s*[\[(](?P<unit>[^\])]*)[\])]\s*$")
_RESAMPLE_METHODS = ("linear", "antialias")
_DETREND_KINDS = ("mean", "linear")


def _uniform(t):
    """True when the steps of ``t`` [s] are positive and equal (to 1e-6 relative)."""
    steps = np.diff(t)
    dt = steps.mean()
    return dt > 0 and np.max(np.abs(steps - dt)) <= 1e-6 * max(dt, 1e-12) + 1e-9


@dataclass
class FlightRecord:
    """One flight-test record: uniform time, named channels and their units.

    Attributes
    ----------
    t : ndarray
        Time [s], uniformly sampled and increasing.
    channels : DataFrame
        One column per channel, one row per sample of ``t``.
    units : dict
        Unit string of each channel (``""`` when unknown).
    name : str or None
        Label of the record (e.g. the run number).
    """

    t: np.ndarray
    channels: pd.DataFrame
    units: dict = field(default_factory=dict)
    name: str | None = None

    @property
    def dt(self) -> float:
        """Sample time [s]."""
        return float((self.t[-1] - self.t[0]) / (self.t.size - 1))

    @property
    def duration(self) -> float:
        """Record length [s]."""
        return float(self.t[-1] - self.t[0])

    @property
    def names(self) -> list:
        """Channel names."""
        return list(self.channels.columns)

    def __getitem__(self, channel):
        names_in("channel", [channel], self.names)
        return self.channels[channel].to_numpy(dtype=float)

    def detrended(self, kind="linear", channels=None) -> "FlightRecord":
        """Copy with each channel's mean (``"mean"``) or least-squares line (``"linear"``) removed.

        Parameters
        ----------
        kind : {"linear", "mean"}
            What is removed from each channel.
        channels : list of str, optional
            Channels to detrend (default: all).

        Returns
        -------
        FlightRecord
        """
        if kind not in _DETREND_KINDS:
            raise InputValueError(f"kind must be one of {_DETREND_KINDS}, got {kind!r}")
        chosen = self.names if channels is None else list(channels)
        names_in("channel", chosen, self.names)
        out = self.channels.copy()
        x = self.t - self.t.mean()
        for c in chosen:
            v = out[c].to_numpy(dtype=float)
            v = v - v.mean()
            if kind == "linear":
                v = v - (v @ x) / (x @ x) * x
            out[c] = v
        return FlightRecord(self.t.copy(), out, dict(self.units), self.name)

    def response(self, input, outputs, *, w_min, w_max, **kwargs) -> MeasuredResponse:
        """Frequency response of ``outputs`` to ``input`` (:func:`~flightid.frequency_response`).

        Parameters
        ----------
        input : str
            Input channel.
        outputs : str or list of str
            Output channels.
        w_min, w_max : float
            Frequency range [rad/s].
        **kwargs
            Passed to :func:`~flightid.frequency_response` (windows, points, ...).

        Returns
        -------
        MeasuredResponse
        """
        outputs = [outputs] if isinstance(outputs, str) else list(outputs)
        names_in("channel", [input] + outputs, self.names)
        y = np.column_stack([self[o] for o in outputs])
        return frequency_response(self.t, self[input], y, w_min=w_min, w_max=w_max, input_name=input,
                                  output_names=outputs, name=kwargs.pop("name", self.name), **kwargs)

    def to_pandas(self) -> pd.DataFrame:
        """The record as one table: a ``t`` column [s] and the channels."""
        return pd.concat([pd.Series(self.t, name="t", index=self.channels.index), self.channels], axis=1)

    def plot(self, channels=None, fig=None):
        """Time histories of the channels (one axis each); returns a Figure.

        Parameters
        ----------
        channels : list of str, optional
            Channels to plot (default: all).
        fig : matplotlib.figure.Figure, optional
            Figure to draw in.
        """
        chosen = self.names if channels is None else list(channels)
        names_in("channel", chosen, self.names)
        if fig is None:
            fig = Figure(figsize=(8, 1.8 * len(chosen)), constrained_layout=True)
        axes = fig.subplots(len(chosen), 1, squeeze=False, sharex=True)[:, 0]
        for ax, c in zip(axes, chosen):
            ax.plot(self.t, self[c], "k-", lw=0.8)
            unit = self.units.get(c, "")
            ax.set_ylabel(f"{c} [{unit}]" if unit else c)
            ax.grid(alpha=0.3)
        axes[-1].set_xlabel("t [s]")
        return fig


def _split_unit(column):
    """``"q [deg/s]"`` -> (``"q"``, ``"deg/s"``); a name without brackets has unit ``""``."""
    m = _UNIT.match(str(column))
    return (m.group("name"), m.group("unit").strip()) if m else (str(column), "")


def _resample(t, values, dt, method):
    """Channels ``values`` (n, k) sampled at ``t`` [s] onto a uniform step ``dt`` [s]."""
    t_new = t[0] + dt * np.arange(int(np.floor((t[-1] - t[0]) / dt * (1 + 1e-12))) + 1)
    if method == "antialias":
        # interpolate onto a uniform grid at the record's finest typical step,
        # low-pass below the new Nyquist frequency, then sample at dt
        fine = min(float(np.median(np.diff(t))), dt)
        t_fine = t[0] + fine * np.arange(int(np.floor((t[-1] - t[0]) / fine)) + 1)
        vf = np.column_stack([np.interp(t_fine, t, v) for v in values.T])
        if dt > fine * (1 + 1e-9):
            sos = butter(8, 0.8 * fine / dt, output="sos")      # 0.8 x new Nyquist, normalised
            vf = sosfiltfilt(sos, vf, axis=0)
        t, values = t_fine, vf
    return t_new, np.column_stack([np.interp(t_new, t, v) for v in values.T])


def read_flight_data(source, *, time="t", channels=None, units=None, resample=None, method="linear",
                     detrend=None, name=None, **read_csv_kwargs) -> FlightRecord:
    """Read a flight-test record from a DataFrame or a CSV file.

    Parameters
    ----------
    source : DataFrame, str or path
        The table, or a CSV file read with :func:`pandas.read_csv`.
    time : str
        Name of the time column [s].
    channels : list of str, optional
        Channels to keep (default: every other numeric column).
    units : dict, optional
        Unit of each channel. Column names of the form ``"q [deg/s]"`` (or
        ``"q (deg/s)"``) give the channel ``q`` with unit ``deg/s``; ``units``
        overrides them.
    resample : float, optional
        New sample time [s]. Required when the time column is not uniformly
        sampled (else :class:`~flightid.DataError` naming ``resample``).
    method : {"linear", "antialias"}
        Resampling: linear interpolation, or a zero-phase low-pass (8th-order
        Butterworth at 80 % of the new Nyquist frequency) before sampling.
    detrend : {None, "mean", "linear"}
        Remove each channel's mean or least-squares line after resampling.
    name : str, optional
        Label of the record.
    **read_csv_kwargs
        Passed to :func:`pandas.read_csv` when ``source`` is a path.

    Returns
    -------
    FlightRecord

    Raises
    ------
    DataError
        Non-uniform time without ``resample``, NaN samples, fewer than 16 samples.
    SignalNameError
        ``time`` or a channel is not a column.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> t = np.arange(0, 20, 0.02)
    >>> df = pd.DataFrame({"t": t, "de [deg]": np.sin(t), "q [deg/s]": np.cos(t)})
    >>> rec = read_flight_data(df)
    >>> rec.names, rec.units["q"], round(rec.dt, 3)
    (['de', 'q'], 'deg/s', 0.02)
    """
    if isinstance(source, (str, os.PathLike)):
        table = pd.read_csv(source, **read_csv_kwargs)
    elif isinstance(source, pd.DataFrame):
        table = source
    else:
        raise InputValueError(f"source must be a DataFrame or a CSV path, got {type(source).__name__}")
    split = {c: _split_unit(c) for c in table.columns}
    by_name = {n: c for c, (n, _) in split.items()}
    if len(by_name) != len(split):
        raise DataError(f"channel names repeat once units are split off: {list(table.columns)}")
    if time not in by_name:
        raise SignalNameError(f"time column {time!r} not found (argument time); columns: {list(by_name)}")
    if channels is None:
        channels = [n for n, c in by_name.items() if n != time and pd.api.types.is_numeric_dtype(table[c])]
    else:
        channels = [channels] if isinstance(channels, str) else list(channels)
        names_in("channel", channels, [n for n in by_name if n != time])
    if not channels:
        raise DataError("the table has no numeric channel besides the time column")
    t = real_array(time, table[by_name[time]].to_numpy())
    if t.ndim != 1 or t.size < 16:
        raise DataError(f"the record must hold at least 16 samples, got {t.size}")
    values = np.column_stack([real_array(c, table[by_name[c]].to_numpy()) for c in channels])
    unit_map = {n: split[by_name[n]][1] for n in channels}
    if units is not None:
        names_in("channel", list(units), channels)
        unit_map.update({k: str(v) for k, v in units.items()})
    if method not in _RESAMPLE_METHODS:
        raise InputValueError(f"method must be one of {_RESAMPLE_METHODS}, got {method!r}")
    if resample is None:
        if np.any(np.diff(t) <= 0):
            raise DataError("time must increase strictly; sort the record or pass resample=dt [s]")
        if not _uniform(t):
            steps = np.diff(t)
            raise DataError(f"time is not uniformly sampled (steps {steps.min():.6g}..{steps.max():.6g} s): "
                            "pass resample=dt [s] (method='linear' or 'antialias')")
    else:
        dt = real_scalar("resample", resample, positive=True, unit="s")
        order = np.argsort(t, kind="stable")
        t, values = t[order], values[order]
        if np.any(np.diff(t) <= 0):
            raise DataError("time holds repeated samples; remove the duplicates before resampling")
        if dt > (t[-1] - t[0]) / 15:
            raise InputValueError(f"resample = {dt:.4g} s leaves fewer than 16 samples in the "
                                  f"{t[-1] - t[0]:.4g} s record")
        t, values = _resample(t, values, dt, method)
    record = FlightRecord(t, pd.DataFrame(values, columns=channels), unit_map, name)
    if detrend is not None:
        if detrend not in _DETREND_KINDS:
            raise InputValueError(f"detrend must be None or one of {_DETREND_KINDS}, got {detrend!r}")
        record = record.detrended(detrend)
    return record


def concatenated_response(records, input, outputs, *, w_min, w_max, n_points=None, points_per_decade=25,
                          windows=None, n_windows=5, max_window=None, min_window=None, overlap=0.8,
                          cycles_per_window=2.0, name=None) -> MeasuredResponse:
    """One frequency response from several records of one axis (CIFER multi-run concatenation).

    For each composite window, the auto and cross spectra of every record are
    pooled over all records' segments (the sums of the spectra, not an average
    of H's); H = G_xy / G_xx and gamma^2 = |G_xy|^2 / (G_xx G_yy) follow from
    the pooled spectra, and the windows are combined as in
    :func:`~flightid.frequency_response` (with one record the result is that
    function's, bit for bit).

    Parameters
    ----------
    records : sequence of FlightRecord
        Runs of one axis, all with the same sample time.
    input : str
        Input channel.
    outputs : str or list of str
        Output channels.
    w_min, w_max : float
        Frequency range [rad/s]; the *shortest* record sets the longest window
        (default half its length) and so the lowest usable ``w_min``.
    n_points, points_per_decade, windows, n_windows, max_window, min_window, overlap, cycles_per_window :
        As for :func:`~flightid.frequency_response` (window lengths in [s]).
    name : str, optional
        Name of the result.

    Returns
    -------
    MeasuredResponse

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from scipy.signal import lsim
    >>> rng = np.random.default_rng(0)
    >>> runs = []
    >>> for k in range(2):
    ...     t = np.arange(0, 60, 0.02)
    ...     u = rng.standard_normal(t.size)
    ...     y = lsim(([2.0], [1.0, 2.0]), u, t)[1]
    ...     runs.append(read_flight_data(pd.DataFrame({"t": t, "u": u, "y": y})))
    >>> r = concatenated_response(runs, "u", "y", w_min=0.5, w_max=10.0)
    >>> bool(abs(abs(r.frdata[0, 0, 0]) - 2 / abs(0.5j + 2)) < 0.05)
    True
    """
    if isinstance(records, FlightRecord):
        records = [records]
    records = list(records)
    if not records or not all(isinstance(r, FlightRecord) for r in records):
        raise InputValueError("records must be a non-empty sequence of FlightRecord (read_flight_data)")
    outputs = [outputs] if isinstance(outputs, str) else list(outputs)
    dts = [r.dt for r in records]
    if max(dts) - min(dts) > 1e-6 * min(dts):
        raise DataError(f"records must share one sample time, got {sorted(set(np.round(dts, 9)))} s: "
                        "read them with the same resample=dt")
    pairs = []
    for k, r in enumerate(records):
        missing = [c for c in [input] + outputs if c not in r.names]
        if missing:
            raise SignalNameError(f"records[{k}] lacks channel(s) {missing}; available: {r.names}")
        t, u, y, _ = _validate(r.t, r[input], np.column_stack([r[o] for o in outputs]))
        pairs.append((t, u, y))
    if len(set(outputs)) != len(outputs) or input in outputs:
        raise DataError(f"outputs must be unique and differ from the input {input!r}, got {outputs}")
    overlap = real_scalar("overlap", overlap, lo=0.0, hi=1.0, hi_open=True)
    cycles_per_window = real_scalar("cycles_per_window", cycles_per_window, positive=True)
    shortest = min(pairs, key=lambda p: p[0][-1] - p[0][0])[0]
    omega, windows = _frequency_plan(shortest, dts[0], w_min=w_min, w_max=w_max, n_points=n_points,
                                     points_per_decade=points_per_decade, windows=windows,
                                     n_windows=n_windows, max_window=max_window, min_window=min_window,
                                     cycles_per_window=cycles_per_window)
    h, coh = _composite([(u, y) for _, u, y in pairs], dts[0], omega, windows, overlap, cycles_per_window)
    return MeasuredResponse(h[:, None, :], omega, coh[:, None, :], [input], outputs, name=name)
