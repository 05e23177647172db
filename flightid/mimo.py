"""MIMO frequency responses from simultaneous inputs in one record.

:func:`mimo_response` is CIFER's conditioned (MISO) spectral analysis applied to
every output: from the composite-window cross-spectral matrix of inputs and
outputs (the chirp-z machinery of :func:`flightid.frequency_response`),
``H = G_yu G_uu^-1`` frequency by frequency. Element ``H_ij`` equals the
conditioned-spectra estimate ``G_{u_j y_i . r} / G_{u_j u_j . r}``, with every other
input ``r`` removed first (Bendat & Piersol Ch. 7; Tischler & Remple §9.4), so
the inputs may be partially correlated (a pilot's or a controller's inputs,
secondary inputs of a sweep) as long as no input is a linear combination of the
others at some frequency. The coherence of each element is the *partial*
coherence, and the *multiple* coherence of each output says how much of it all
inputs together explain.

:func:`harmonic_response` is the direct estimate for orthogonal multisines
(:func:`flightid.orthogonal_multisine`): at the harmonics of input ``j`` no other
input has power, so ``H[:, j](w_k) = Y(w_k) / U_j(w_k)`` from the Fourier
coefficients of whole periods, with the coherence over periods.

Both return a :class:`MeasuredResponse`, so :func:`flightid.joint_input_output`,
:func:`flightid.fit` and the plots carry over unchanged.
"""
from __future__ import annotations

import numpy as np
from scipy.signal import czt

from ._validation import real_array, real_scalar
from .errors import DataError, InputValueError, SingularInputError
from .response import MeasuredResponse, _detrend, _frequency_plan

__all__ = ["MIMOResponse", "mimo_response", "harmonic_response"]


class MIMOResponse(MeasuredResponse):
    """A :class:`MeasuredResponse` estimated from simultaneous inputs.

    ``coherence`` holds the partial coherence of each element (output i with
    input j, every other input removed); the extra attributes are diagnostics.

    Parameters
    ----------
    response, omega, coherence, inputs, outputs, name
        As :class:`MeasuredResponse` (``omega`` in [rad/s]).
    multiple_coherence : array_like, shape (n_outputs, n_freq)
        Multiple coherence of each output with all inputs together, in [0, 1].
    input_coherence : array_like, shape (n_inputs, n_inputs, n_freq)
        Ordinary coherence between the inputs (0: uncorrelated, 1: the same
        signal up to a linear filter); CIFER flags > 0.5 as correlated.
    """

    def __init__(self, response, omega, coherence, inputs, outputs, multiple_coherence,
                 input_coherence, name=None):
        super().__init__(response, omega, coherence, inputs, outputs, name=name)
        mc = real_array("multiple_coherence", multiple_coherence)
        ic = real_array("input_coherence", input_coherence)
        n_out, n_in, n_w = self.frdata.shape
        if mc.shape != (n_out, n_w) or ic.shape != (n_in, n_in, n_w):
            raise DataError(f"multiple_coherence must have shape {(n_out, n_w)} and input_coherence "
                            f"{(n_in, n_in, n_w)}, got {mc.shape} and {ic.shape}")
        self.multiple_coherence = np.clip(mc, 0.0, 1.0)
        self.input_coherence = np.clip(ic, 0.0, 1.0)

    def to_pandas(self):
        """Long table of :meth:`MeasuredResponse.to_pandas` plus ``multiple_coherence`` of each row's output."""
        df = super().to_pandas()
        n_w = self.omega.size
        mc = {o: self.multiple_coherence[i] for i, o in enumerate(self.output_labels)}
        df["multiple_coherence"] = np.concatenate(
            [mc[o][:n_w] for o in df.output.iloc[::n_w]])
        return df


def _as_columns(name, values, n):
    arr = real_array(name, values)
    if arr.ndim == 1:
        arr = arr[:, None]
    if arr.ndim != 2 or arr.shape[0] != n:
        raise DataError(f"{name} must have shape (len(t), n) = ({n}, n); got {arr.shape}")
    return arr


def _check_record(t, u, y):
    t = real_array("t", t)
    if t.ndim != 1 or t.size < 16:
        raise DataError("t must be a 1-D array of at least 16 samples")
    u = _as_columns("u", u, t.size)
    y = _as_columns("y", y, t.size)
    steps = np.diff(t)
    dt = steps.mean()
    if dt <= 0 or np.max(np.abs(steps - dt)) > 1e-6 * max(dt, 1e-12) + 1e-9:
        raise DataError("t must be uniformly sampled and increasing "
                        f"(steps range {steps.min():.6g}..{steps.max():.6g} s); resample first")
    flat = np.flatnonzero(np.ptp(u, axis=0) == 0)
    if flat.size:
        raise DataError(f"input column(s) {flat.tolist()} are constant: they excite nothing")
    return t, u, y, float(dt)


def _names(kind, names, n, default):
    if names is None:
        names = [default] if n == 1 else [f"{default}{k}" for k in range(n)]
    if isinstance(names, str):
        names = [names]
    names = [str(x) for x in names]
    if len(names) != n:
        raise DataError(f"{len(names)} {kind} names for {n} {kind}s")
    return names


def _window_matrix(x, dt, t_win, overlap, w_lo, w_hi, n_lin):
    """Cross-spectral matrix ``G[a, b] = 2 dt E[conj(X_a) X_b] / sum(taper^2)`` of the columns of
    ``x`` for one window length, on a linear grid [w_lo, w_hi] (chirp-z); (omega, G, n_segments)."""
    n_win = int(round(t_win / dt))
    step = max(1, int(round(n_win * (1.0 - overlap))))
    starts = np.arange(0, x.shape[0] - n_win + 1, step)
    taper = np.hanning(n_win)
    scale = 2.0 * dt / np.sum(taper ** 2)
    dw = (w_hi - w_lo) / max(n_lin - 1, 1)
    idx = starts[:, None] + np.arange(n_win)[None, :]
    spectra = []
    for c in range(x.shape[1]):
        seg = _detrend(x[:, c][idx]) * taper
        spectra.append(czt(seg, m=n_lin, w=np.exp(-1j * dw * dt), a=np.exp(1j * w_lo * dt), axis=-1))
    Z = np.stack(spectra, axis=1)                        # (n_seg, n_sig, n_lin)
    G = scale * np.einsum("sal,sbl->abl", np.conj(Z), Z) / len(starts)
    return w_lo + dw * np.arange(n_lin), G, len(starts)


def _interp_complex(x, xp, fp):
    """Linear interpolation of complex ``fp`` (last axis on ``xp``) at ``x``."""
    flat = fp.reshape(-1, fp.shape[-1])
    out = np.array([np.interp(x, xp, f.real) + 1j * np.interp(x, xp, f.imag) for f in flat])
    return out.reshape(fp.shape[:-1] + (x.size,))


def _conditioned(Guu, guy, gyy, j):
    """Spectra of input j and output y with every other input removed (conditioned spectra).

    ``Guu`` (n_w, m, m), ``guy`` (n_w, m), ``gyy`` (n_w,); returns ``(G_jj.r, G_jy.r, G_yy.r)``.
    """
    m = Guu.shape[1]
    r = [k for k in range(m) if k != j]
    if not r:
        return Guu[:, j, j].real, guy[:, j], gyy
    Grr = Guu[:, r][:, :, r]
    Grj = Guu[:, r, j]
    Gry = guy[:, r]
    a = np.linalg.solve(Grr, Grj[..., None])[..., 0]     # Grr^-1 Grj
    b = np.linalg.solve(Grr, Gry[..., None])[..., 0]     # Grr^-1 Gry
    # G_jj.r = G_jj - G_jr Grr^-1 G_rj with G_jr = conj(G_rj)
    gjj = (Guu[:, j, j] - np.sum(np.conj(Grj) * a, axis=1)).real
    gjy = guy[:, j] - np.sum(np.conj(Grj) * b, axis=1)
    gyy_r = (gyy - np.sum(np.conj(Gry) * b, axis=1)).real
    return gjj, gjy, gyy_r


def mimo_response(t, u, y, *, w_min, w_max, n_points=None, points_per_decade=25, windows=None,
                  n_windows=5, max_window=None, min_window=None, overlap=0.8, cycles_per_window=2.0,
                  input_names=None, output_names=None, max_condition=1e8, name=None) -> MIMOResponse:
    """MIMO frequency response from simultaneous (possibly correlated) inputs.

    Parameters
    ----------
    t : array_like
        Uniformly sampled time [s].
    u : array_like, shape (n,) or (n, n_inputs)
        Input time histories, all applied in this one record.
    y : array_like, shape (n,) or (n, n_outputs)
        Output time histories.
    w_min, w_max : float
        Frequency range of the result [rad/s].
    n_points, points_per_decade, windows, n_windows, max_window, min_window, overlap, cycles_per_window
        Frequency grid and composite windows exactly as :func:`flightid.frequency_response`
        (window lengths in [s]).
    input_names, output_names : list of str, optional
        Signal names (defaults ``u0, u1, ...`` and ``y0, y1, ...``).
    max_condition : float
        Largest acceptable condition number of the input spectral matrix ``G_uu``;
        above it the inputs are linearly dependent at that frequency.
    name : str, optional
        Name of the result.

    Returns
    -------
    MIMOResponse
        Shape (n_outputs, n_inputs, n_points); ``coherence`` is the partial
        coherence of each element, ``multiple_coherence`` that of each output,
        ``input_coherence`` the ordinary coherence between the inputs.

    Raises
    ------
    DataError
        Unusable time histories (as :func:`flightid.frequency_response`).
    SingularInputError
        The inputs are linearly dependent (fully correlated) at some frequencies
        [rad/s]: their contributions cannot be separated from this record.

    Notes
    -----
    Each window's cross-spectral matrix of ``[u, y]`` is averaged over overlapping
    Hann-tapered segments and interpolated to the log grid; windows are combined
    per output with weights ``1/eps_r^2`` from that output's multiple coherence
    (the SISO rule of :func:`flightid.frequency_response`; with one input the
    result is the same). Then ``H_i = G_uu^-1 G_u y_i`` (with ``G_ab = E[conj(a) b]``),
    the multiple coherence ``Re(G_yu H^T) / G_yy`` and the partial coherence
    ``|G_jy.r|^2 / (G_jj.r G_yy.r)`` from the conditioned spectra.
    """
    t, u, y, dt = _check_record(t, u, y)
    overlap = real_scalar("overlap", overlap, lo=0.0, hi=1.0, hi_open=True)
    cycles_per_window = real_scalar("cycles_per_window", cycles_per_window, positive=True)
    max_condition = real_scalar("max_condition", max_condition, lo=1.0)
    omega, windows = _frequency_plan(t, dt, w_min=w_min, w_max=w_max, n_points=n_points,
                                     points_per_decade=points_per_decade, windows=windows,
                                     n_windows=n_windows, max_window=max_window, min_window=min_window,
                                     cycles_per_window=cycles_per_window)
    w_max, n_w = omega[-1], omega.size
    m, p = u.shape[1], y.shape[1]
    input_names = _names("input", input_names, m, "u")
    output_names = _names("output", output_names, p, "y")
    if len(set(input_names + output_names)) != m + p:
        raise DataError(f"signal names must be unique, got inputs {input_names} and outputs {output_names}")
    x = np.hstack([u, y])
    acc_w = np.zeros((p, n_w))
    acc_uu = np.zeros((p, n_w, m, m), dtype=complex)
    acc_uy = np.zeros((p, n_w, m), dtype=complex)
    acc_yy = np.zeros((p, n_w))
    for t_win in windows:
        valid = omega >= cycles_per_window * 2 * np.pi / t_win * (1 - 1e-9)
        if not valid.any():
            continue
        lo = omega[valid][0]
        # oversample the window's resolution 2 pi / T four times (as frequency_response)
        n_lin = int(np.ceil((w_max - lo) / (2 * np.pi / t_win / 4))) + 2
        wl, G, n_seg = _window_matrix(x, dt, t_win, overlap, lo, w_max, n_lin)
        Gi = np.moveaxis(_interp_complex(omega[valid], wl, G), -1, 0)   # (n_v, n_sig, n_sig)
        Guu = Gi[:, :m, :m].copy()
        # frequencies where this window cannot separate the inputs get no weight (others may)
        good = np.linalg.cond(Guu) <= max_condition
        Guu[~good] = np.eye(m)
        Guy = Gi[:, :m, m:]
        gyy = np.real(np.einsum("wii->wi", Gi[:, m:, m:]))
        H = np.linalg.solve(Guu, Guy)                     # (n_v, m, p): column i is H_i^T
        explained = np.real(np.sum(np.conj(H) * Guy, axis=1))
        mc = np.clip(explained / np.maximum(gyy, 1e-300), 1e-6, 0.9999)
        n_eff = max(1.0, n_seg * (1.0 - overlap) * 2.0)
        wgt = 2 * n_eff * mc / (1 - mc) * good[:, None]   # 1 / eps_r^2
        for i in range(p):
            acc_w[i, valid] += wgt[:, i]
            acc_uu[i, valid] += wgt[:, i, None, None] * Guu
            acc_uy[i, valid] += wgt[:, i, None] * Guy[:, :, i]
            acc_yy[i, valid] += wgt[:, i] * gyy[:, i]
    if np.any(acc_w == 0):
        bad = omega[np.any(acc_w == 0, axis=0)]
        raise SingularInputError(
            f"the input spectral matrix is singular (condition > {max_condition:.0e}) in every window at "
            f"{bad.size} of {n_w} frequencies: {np.array2string(bad, precision=3, max_line_width=200)} "
            "rad/s; the inputs are fully correlated there and cannot be separated", bad)
    resp = np.empty((p, m, n_w), dtype=complex)
    partial = np.empty((p, m, n_w))
    multiple = np.empty((p, n_w))
    input_coh = np.empty((m, m, n_w))
    for i in range(p):
        Guu = acc_uu[i] / acc_w[i][:, None, None]
        guy = acc_uy[i] / acc_w[i][:, None]
        gyy = acc_yy[i] / acc_w[i]
        Hi = np.linalg.solve(Guu, guy[..., None])[..., 0]   # (n_w, m)
        resp[i] = Hi.T
        multiple[i] = np.real(np.sum(np.conj(Hi) * guy, axis=1)) / np.maximum(gyy, 1e-300)
        for j in range(m):
            gjj, gjy, gyy_r = _conditioned(Guu, guy, gyy, j)
            partial[i, j] = np.abs(gjy) ** 2 / np.maximum(gjj * np.maximum(gyy_r, 0.0), 1e-300)
        if i == 0:
            d = np.real(np.einsum("wjj->wj", Guu))
            input_coh = np.moveaxis(np.abs(Guu) ** 2 / np.maximum(d[:, :, None] * d[:, None, :], 1e-300), 0, -1)
    return MIMOResponse(resp, omega, np.clip(partial, 0, 1), input_names, output_names,
                        np.clip(multiple, 0, 1), np.clip(input_coh, 0, 1), name=name)


def harmonic_response(t, u, y, harmonics, period, *, omega=None, skip=0.0, input_names=None,
                      output_names=None, name=None) -> MeasuredResponse:
    """Direct MIMO estimate of an orthogonal multisine record at each input's own harmonics.

    Parameters
    ----------
    t : array_like
        Uniformly sampled time [s].
    u : array_like, shape (n, n_inputs)
        The multisine inputs (e.g. ``Multisine.U`` as applied).
    y : array_like, shape (n,) or (n, n_outputs)
        Output time histories.
    harmonics : sequence of array_like of int
        Harmonic numbers of each input (``Multisine.harmonics``); disjoint.
    period : float
        Multisine period ``T`` [s] (``Multisine.period``), a whole number of samples.
    omega : array_like, optional
        Frequencies of the result [rad/s] (default: 25 per decade over the range
        every input's harmonics cover); each input's column is interpolated
        (real and imaginary parts, linearly) from its own harmonics.
    skip : float
        Seconds dropped at the start (the transient) before the whole periods used.
    input_names, output_names : list of str, optional
        Signal names.
    name : str, optional
        Name of the result.

    Returns
    -------
    MeasuredResponse
        Shape (n_outputs, n_inputs, n_freq). The coherence at a harmonic is the
        ordinary coherence over the periods, ``|sum_p conj(U_p) Y_p|^2 /
        (sum_p |U_p|^2 sum_p |Y_p|^2)``: 1 without noise.

    Raises
    ------
    DataError
        Fewer than two whole periods after ``skip`` (no coherence), a period that
        is not a whole number of samples, a harmonic an input does not excite, or
        overlapping harmonic sets.
    """
    t, u, y, dt = _check_record(t, u, y)
    period = real_scalar("period", period, positive=True, unit="s")
    skip = real_scalar("skip", skip, nonnegative=True, unit="s")
    m, p = u.shape[1], y.shape[1]
    if isinstance(harmonics, np.ndarray) and harmonics.ndim == 1:
        harmonics = [harmonics]
    harmonics = [np.atleast_1d(np.asarray(k)) for k in harmonics]
    if len(harmonics) != m:
        raise DataError(f"{len(harmonics)} harmonic sets for {m} inputs")
    for j, k in enumerate(harmonics):
        if k.size == 0 or not np.issubdtype(k.dtype, np.integer) or np.any(k < 1):
            raise DataError(f"harmonics[{j}] must be a non-empty array of positive integers")
    allk = np.concatenate(harmonics)
    if np.unique(allk).size != allk.size:
        raise DataError("the harmonic sets overlap: the inputs are not orthogonal")
    n_per = int(round(period / dt))
    if abs(n_per * dt - period) > 1e-6 * period:
        raise DataError(f"period {period:.6g} s is not a whole number of samples of dt = {dt:.6g} s")
    if allk.max() >= n_per // 2:
        raise DataError(f"harmonic {allk.max()} is at or above the Nyquist bin {n_per // 2}")
    n_skip = int(round(skip / dt))
    n_periods = (t.size - n_skip) // n_per
    if n_periods < 2:
        raise DataError(f"after skipping {skip:.4g} s the record holds {max(n_periods, 0)} whole period(s) of "
                        f"{period:.4g} s; at least 2 are needed for a coherence estimate")
    input_names = _names("input", input_names, m, "u")
    output_names = _names("output", output_names, p, "y")
    seg = slice(n_skip, n_skip + n_periods * n_per)
    U = np.fft.rfft(u[seg].reshape(n_periods, n_per, m), axis=1)
    Y = np.fft.rfft(y[seg].reshape(n_periods, n_per, p), axis=1)
    lo = max(2 * np.pi * k.min() / period for k in harmonics)
    hi = min(2 * np.pi * k.max() / period for k in harmonics)
    if omega is None:
        if not hi > lo:
            raise DataError("the inputs' harmonic ranges do not overlap: give omega")
        omega = np.geomspace(lo, hi, int(np.ceil(25 * np.log10(hi / lo))) + 1)
    omega = real_array("omega", omega, error=InputValueError)
    if omega.ndim != 1 or omega.size < 2 or np.any(np.diff(omega) <= 0):
        raise InputValueError("omega must be a 1-D increasing array of at least 2 frequencies [rad/s]")
    if omega[0] < lo * (1 - 1e-9) or omega[-1] > hi * (1 + 1e-9):
        raise InputValueError(f"omega must lie within [{lo:.4g}, {hi:.4g}] rad/s, covered by every input's "
                              "harmonics (no extrapolation)")
    resp = np.empty((p, m, omega.size), dtype=complex)
    coh = np.empty((p, m, omega.size))
    for j, k in enumerate(harmonics):
        k = np.sort(k)
        uj = U[:, k, j]                                   # (P, n_k)
        puu = np.sum(np.abs(uj) ** 2, axis=0)
        if np.any(puu <= 1e-20 * puu.max()):
            raise DataError(f"input {input_names[j]!r} has no power at some of its harmonics")
        yk = Y[:, k, :]                                   # (P, n_k, p)
        cross = np.sum(np.conj(uj)[..., None] * yk, axis=0)
        pyy = np.sum(np.abs(yk) ** 2, axis=0)
        h = cross / puu[:, None]                          # (n_k, p)
        c = np.abs(cross) ** 2 / np.maximum(puu[:, None] * pyy, 1e-300)
        wk = 2 * np.pi * k / period
        resp[:, j, :] = _interp_complex(omega, wk, h.T)
        coh[:, j, :] = np.array([np.interp(omega, wk, ci) for ci in c.T])
    return MeasuredResponse(resp, omega, np.clip(coh, 0, 1), input_names, output_names, name=name)
