"""Fourier-transform identification of short records, and one entry point for every path.

Short multistep, doublet and multisine records are too short for the spectral
windows of the CIFER path. Klein & Morelli's frequency-domain methods work on
the finite Fourier transform of the whole record instead,

    X(w) = dt sum_k x(t_k) exp(-j w (t_k - t_0)),

evaluated at any frequencies (the chirp-z transform for an evenly spaced set,
a direct sum otherwise):

* **output error** (``method="output_error"``): minimise
  ``sum_w sum_i |Y_i(w) - sum_j H_ij(jw, theta) U_j(w)|^2 / S_i``, with S_i the
  residual power of output i re-estimated until it settles (Klein & Morelli §7.2);
* **equation error** (``method="equation_error"``, state-space structures whose
  outputs are the states): minimise ``sum_w |jw X - F X - G U e^{-jw tau}|^2 / S_i``
  per state equation (regressors taken as exact: biased if the measured states are noisy).

Standard-error convention (both methods): r is the vector of real and
imaginary parts of the scaled residuals, N_r its length, p the free parameters,

    s^2 = sum r^2 / (N_r - p),     SE = sqrt(diag(s^2 inv(Jr^T Jr))),

which is Klein & Morelli's Cramér-Rao bound M^-1 for complex Gaussian
residuals with the estimated S_i. With the default frequencies (spaced by the
record's resolution 2 pi / T) the residuals of white measurement noise are
uncorrelated, which the Monte Carlo tests check.

:func:`identify` takes a :class:`~flightid.flight_data.FlightRecord` and a structure and
runs the path that ``method`` names -- ``"cifer"`` (frequency responses with
coherence, then :func:`flightid.fit`), ``"output_error"`` or
``"equation_error"`` -- and returns a :class:`~flightid.FitResult` either way.
"""
from __future__ import annotations

import numpy as np
import pandas as pd
from scipy.optimize import least_squares
from scipy.signal import czt

from ._validation import names_in, real_array, real_scalar
from .degeneracy import hessian_report
from .errors import DataError, IdentificationError, InputValueError
from .fitting import FitResult, _jacobian, _PairData, fit
from .flight_data import FlightRecord
from .response import MeasuredResponse
from .statistics import residual_scaled_errors
from .structures import ModelStructure

__all__ = ["finite_fourier_transform", "fourier_fit", "identify", "METHODS"]

#: the paths :func:`identify` offers
METHODS = ("cifer", "output_error", "equation_error")


def finite_fourier_transform(t, x, omega):
    """Finite Fourier transform ``dt sum_k x_k exp(-j w (t_k - t_0))`` of uniformly sampled channels.

    Parameters
    ----------
    t : array_like
        Uniform time [s].
    x : array_like, shape (n,) or (n, n_channels)
        Channels.
    omega : array_like
        Frequencies [rad/s], any values (evenly spaced ones use the chirp-z transform).

    Returns
    -------
    ndarray, complex, shape (n_channels, n_freq) (or (n_freq,) for a 1-D ``x``)

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0, 10, 0.01)
    >>> X = finite_fourier_transform(t, np.ones_like(t), [2 * np.pi / 10])
    >>> bool(abs(X[0]) < 1e-12)           # a whole period of the frequency: zero
    True
    """
    t = real_array("t", t)
    xa = real_array("x", x)
    one = xa.ndim == 1
    xa = xa[:, None] if one else xa
    if t.ndim != 1 or xa.shape[0] != t.size or t.size < 2:
        raise DataError(f"x must have len(t) = {t.size} rows, got shape {np.shape(x)}")
    omega = np.atleast_1d(real_array("omega", omega, error=InputValueError))
    dt = (t[-1] - t[0]) / (t.size - 1)
    steps = np.diff(omega)
    if omega.size > 2 and np.ptp(steps) <= 1e-9 * max(abs(steps.mean()), 1e-12):
        out = czt(xa.T, m=omega.size, w=np.exp(-1j * steps.mean() * dt), a=np.exp(1j * omega[0] * dt), axis=-1)
    else:
        tau = t - t[0]
        out = np.exp(-1j * np.outer(omega, tau)) @ xa
        out = out.T
    out = dt * out
    return out[0] if one else out


def _default_omega(record, w_min, w_max):
    dw = 2 * np.pi / record.duration
    first = np.ceil(w_min / dw - 1e-9) * dw
    return np.arange(first, w_max + 1e-9 * w_max, dw)


def _scaled(res, scale):
    return np.concatenate([(res / scale[:, None]).real.ravel(), (res / scale[:, None]).imag.ravel()])


def fourier_fit(structure, record, *, method="output_error", omega=None, w_min=None, w_max=None,
                max_iterations=5) -> FitResult:
    """Frequency-domain output-error or equation-error fit on the records' finite Fourier transforms.

    Parameters
    ----------
    structure : ModelStructure
        Its ``inputs`` and ``outputs`` are channels of ``record``. For
        ``"equation_error"`` an F/G state-space structure whose outputs are its states.
    record : FlightRecord
        The whole record (perturbations from trim; it should start and end near
        trim, or the transform carries the end transients).
    method : {"output_error", "equation_error"}
        The cost minimised (module docstring).
    omega : array_like, optional
        Analysis frequencies [rad/s]; default: from ``w_min`` to ``w_max`` in
        steps of the record's resolution 2 pi / T.
    w_min, w_max : float, optional
        Band [rad/s] of the default frequencies.
    max_iterations : int
        Re-estimations of the residual powers S_i (stops once they change < 1 %).

    Returns
    -------
    FitResult
        ``standard_errors`` (and the ``cramer_rao_pct`` column, which for these
        methods *is* the residual-scaled relative standard error), the
        ``insensitivity_pct`` analogue 100 s / sqrt((Jr^T Jr)_ii) / |theta|, and a
        cost table whose ``J`` is the unexplained fraction of each output's
        transform power [%]. For one input, ``data`` is the empirical transfer
        function Y/U (coherence set to 1: not estimated) so ``plot()`` works.
    """
    if method not in ("output_error", "equation_error"):
        raise InputValueError(f"method must be 'output_error' or 'equation_error', got {method!r}")
    if not isinstance(structure, ModelStructure):
        raise InputValueError(f"structure must be a ModelStructure, got {type(structure).__name__}")
    if not isinstance(record, FlightRecord):
        raise InputValueError(f"record must be a FlightRecord (read_flight_data), got {type(record).__name__}")
    names_in("channel", structure.inputs + structure.outputs, record.names)
    bad = [n for n in structure.names if not np.isfinite(structure.values[n])]
    if bad:
        raise InputValueError(f"initial value(s) of parameter(s) {bad} are NaN or infinite")
    if omega is None:
        if w_min is None or w_max is None:
            raise InputValueError("give omega [rad/s] or both w_min and w_max [rad/s]")
        w_min = real_scalar("w_min", w_min, positive=True, unit="rad/s")
        w_max = real_scalar("w_max", w_max, positive=True, unit="rad/s")
        omega = _default_omega(record, w_min, w_max)
    omega = np.atleast_1d(real_array("omega", omega, error=InputValueError))
    if np.any(omega <= 0) or np.any(omega >= np.pi / record.dt):
        raise InputValueError(f"omega must lie in (0, pi/dt = {np.pi / record.dt:.4g}) rad/s")
    free = structure.free_names
    if not free:
        raise IdentificationError("the structure has no free parameters")
    if omega.size * len(structure.outputs) * 2 <= len(free):
        raise DataError(f"{omega.size} frequencies are too few for {len(free)} parameters: widen the band "
                        "or give more omega")
    U = finite_fourier_transform(record.t, np.column_stack([record[c] for c in structure.inputs]), omega)
    Y = finite_fourier_transform(record.t, np.column_stack([record[c] for c in structure.outputs]), omega)
    s = 1j * omega
    if method == "equation_error":
        mats = structure.matrices()
        if "F" not in mats or "G" not in mats:
            raise InputValueError("method='equation_error' needs an F/G state-space structure")
        a, _, c, d = structure._abcd(mats)
        if c.shape != a.shape or not np.allclose(c, np.eye(a.shape[0])) or np.any(d != 0):
            raise InputValueError("method='equation_error' needs the states measured: outputs = states "
                                  "(C the identity, no D)")
        scale_t = 1.0 if structure.omega is None else structure.omega

        def residual(vals):
            m = structure.matrices(vals)
            tau = structure._delays(m)
            ud = U[None, :, :] * np.exp(-tau[:, :, None] * s[None, None, :])       # (states, in, w)
            g = m["G"] * scale_t
            return s[None, :] * Y - (m["F"] * scale_t) @ Y - np.einsum("ij,ijw->iw", g, ud)
    else:
        def residual(vals):
            h = structure.frequency_response(omega, vals)
            return Y - np.einsum("ijw,jw->iw", h, U)
    lower = np.array([0.0 if n in structure.delay_names else -np.inf for n in free])
    x = np.maximum(np.array([structure.values[n] for n in free]), lower)
    scale = np.sqrt(np.mean(np.abs(residual(dict(zip(free, x)))) ** 2, axis=1))
    scale = np.where(scale > 0, scale, 1.0)
    for _ in range(int(max_iterations)):
        fn = lambda v: _scaled(residual(dict(zip(free, v))), scale)      # noqa: E731
        sol = least_squares(fn, x, bounds=(lower, np.full_like(x, np.inf)), x_scale="jac",
                            xtol=1e-12, ftol=1e-12, max_nfev=200 * (len(x) + 1))
        x = sol.x
        new = np.sqrt(np.mean(np.abs(residual(dict(zip(free, x)))) ** 2, axis=1))
        new = np.where(new > 0, new, 1.0)
        settled = np.max(np.abs(new / scale - 1)) < 0.01
        scale = new
        if settled:
            break
    fn = lambda v: _scaled(residual(dict(zip(free, v))), scale)          # noqa: E731
    jac = _jacobian(fn, x)
    r = fn(x)
    se = residual_scaled_errors(jac, r)
    s2 = float(r @ r) / max(r.size - len(free), 1)
    fitted = structure.with_values(dict(zip(free, x)))
    table = fitted.parameter_table()
    table["cramer_rao_pct"] = np.nan
    table["insensitivity_pct"] = np.nan
    diag = np.sum(jac ** 2, axis=0)
    with np.errstate(divide="ignore", over="ignore"):
        for k, n in enumerate(free):
            row = table.parameter == n
            mag = abs(x[k]) if x[k] != 0 else np.nan
            table.loc[row, "cramer_rao_pct"] = 100.0 * se[k] / mag
            table.loc[row, "insensitivity_pct"] = 100.0 * np.sqrt(s2 / diag[k]) / mag if diag[k] > 0 else np.inf
    v = residual(fitted.values)
    cost = pd.DataFrame({"output": structure.outputs, "input": ", ".join(structure.inputs),
                         "w_min": omega[0], "w_max": omega[-1],
                         "J": 100.0 * np.sum(np.abs(v) ** 2, axis=1) / np.sum(np.abs(Y) ** 2, axis=1)})
    j_ave = float(cost.J.mean())
    cost["J_ave"] = j_ave
    cost.attrs["J_ave"] = j_ave
    data, pairs = None, []
    if len(structure.inputs) == 1:
        etfe = Y / U[0][None, :]
        data = MeasuredResponse(etfe[:, None, :], omega, np.ones((len(structure.outputs), 1, omega.size)),
                                structure.inputs, structure.outputs, name=record.name)
        pairs = [_PairData(o, structure.inputs[0], i, 0, omega, etfe[i], np.ones(omega.size))
                 for i, o in enumerate(structure.outputs)]
    report = hessian_report(jac, free, x)
    success, message = bool(sol.success), str(sol.message)
    if report.no_influence:
        success = False
        message = f"parameters {report.no_influence} have no influence on the residuals; {sol.message}"
    return FitResult(fitted, table, cost, j_ave, data, success, message, omega.size, pairs,
                     degeneracy=report, standard_errors=dict(zip(free, se)), method=method)


def identify(structure, record, *, method="cifer", w_min, w_max, omega=None, response_kwargs=None,
             **fit_kwargs) -> FitResult:
    """Identify ``structure`` from a flight record by the path ``method`` names.

    Parameters
    ----------
    structure : ModelStructure
        Inputs and outputs are channels of ``record``.
    record : FlightRecord or sequence of FlightRecord
        The record; several records of one axis (``"cifer"`` only) are
        concatenated (:func:`flightid.concatenated_response`).
    method : {"cifer", "output_error", "equation_error"}
        ``"cifer"``: composite-window frequency responses with coherence, then
        :func:`flightid.fit` (long sweeps); the others: :func:`fourier_fit` on the
        whole record's Fourier transform (short multisteps, doublets, multisines).
    w_min, w_max : float
        Analysis band [rad/s].
    omega : array_like, optional
        Fourier-transform frequencies [rad/s] (Fourier methods only).
    response_kwargs : dict, optional
        Passed to the frequency-response estimate (``"cifer"`` only).
    **fit_kwargs
        Passed to :func:`flightid.fit` (``"cifer"``) or :func:`fourier_fit`.

    Returns
    -------
    FitResult
        The same kind of result for every method; ``result.method`` says which,
        ``result.statistics`` gives residual-scaled standard errors for all.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> from scipy.signal import lsim
    >>> from flightid import read_flight_data, doublet
    >>> from flightid.transfer_function import TransferFunctionStructure
    >>> t, u = doublet(1.0, 1.0, 0.02, 20.0)
    >>> y = lsim(([2.0], [1.0, 1.5]), u, t)[1]
    >>> rec = read_flight_data(pd.DataFrame({"t": t, "u": u, "y": y}))
    >>> s = TransferFunctionStructure(0, 1, delay=False, initial={"b0": 1.0, "a0": 1.0})
    >>> res = identify(s, rec, method="output_error", w_min=0.3, w_max=10.0)
    >>> [round(res.structure.values[k], 2) for k in ("b0", "a0")]
    [2.0, 1.5]
    """
    if method not in METHODS:
        raise InputValueError(f"method must be one of {METHODS}, got {method!r}")
    if method != "cifer":
        if response_kwargs:
            raise InputValueError("response_kwargs applies to method='cifer' only")
        return fourier_fit(structure, record, method=method, omega=omega, w_min=w_min, w_max=w_max,
                           **fit_kwargs)
    if omega is not None:
        raise InputValueError("omega applies to the Fourier methods; method='cifer' uses w_min/w_max")
    from .flight_data import concatenated_response
    from .mimo import mimo_response
    records = [record] if isinstance(record, FlightRecord) else list(record)
    kw = dict(response_kwargs or {})
    if len(structure.inputs) == 1:
        data = concatenated_response(records, structure.inputs[0], structure.outputs, w_min=w_min,
                                     w_max=w_max, **kw)
    else:
        if len(records) != 1:
            raise InputValueError("several inputs at once: give one record (simultaneous inputs)")
        rec = records[0]
        data = mimo_response(rec.t, np.column_stack([rec[c] for c in structure.inputs]),
                             np.column_stack([rec[c] for c in structure.outputs]), w_min=w_min, w_max=w_max,
                             input_names=structure.inputs, output_names=structure.outputs, **kw)
    return fit(structure, data, **fit_kwargs)
