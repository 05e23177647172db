"""Parameter statistics that follow the noise: residual-scaled standard errors.

CIFER's Cramér-Rao bound (Eqs. 3.15-3.16, :func:`flightid.fit`) is
``CR_i = 2 sqrt(inv(H)_ii)`` with ``H = 2 Jr^T Jr`` the Gauss-Newton Hessian of
the cost ``J_sum = sum r^2``: it does not contain the residual variance, so it
does not change with the noise level. The residual-scaled standard error
reported beside it has two conventions (``covariance``):

``"white"`` (default)
    the least-squares convention for uncorrelated residuals of equal variance,

        s^2 = J_sum / (N_r - p),      SE_i = sqrt(s^2 inv(Jr^T Jr)_ii) = CR_i sqrt(J_sum / (2 (N_r - p)))

    with N_r the number of residuals (a magnitude and a phase residual per fitted
    frequency and response) and p the number of free parameters. For the
    Fourier-transform fits (:func:`flightid.fourier_fit`) the residuals are at
    frequencies spaced by the record's resolution 2 pi / T, where it is exact
    for white noise.
``"sandwich"``
    the heteroscedasticity-consistent (HC2, leverage-corrected) covariance
    ``A^-1 (sum_k g_k g_k^T) A^-1`` with ``A = Jr^T Jr``, ``g_k = Jr_k r_k /
    sqrt(1 - h_k)`` and ``h_k`` the leverage of residual k. On the CIFER path the
    residuals' variance is not uniform: the coherence weight W_gamma saturates
    near gamma^2 = 1 while the spectral estimate's random error
    sqrt(1 - gamma^2) / gamma keeps growing as the coherence falls (at the high
    frequencies that fix a delay), so the white convention under-states the
    error of the parameters those points determine (measured: a delay's SE half
    its Monte Carlo scatter). Neighbouring CIFER points are nearly independent at
    the default 20 points per response: the grid spacing (17 % of the frequency
    for 20 points over a 24 : 1 band) exceeds the Hann resolution 2 x 2 pi / T of
    the longest window except at the lowest few points, and a Bartlett
    correlation kernel of that width changed the errors by < 5 %, so no
    correlation correction is applied.

Both conventions scale with the residual, which at low noise is dominated by the
spectral estimate's own deterministic error (leakage of the windows, the
interpolation to the fitted grid): a noise-free record fitted by its own model
leaves a residual that no repeat of the noise scatters (on a first-order-plus-delay
sweep it is 99 % of the residual at 1 % output noise, 40 % at 10 %, 8 % at 30 %).
Two ways take it out:

* ``noise="differences"`` (data only): the noise of each residual is measured by
  the second difference of the residuals along frequency, which removes a floor
  that varies smoothly with frequency. Neighbouring points' noise is positively
  correlated where the grid is finer than the windows' resolution (correlation
  0.8 at the lowest points, 0.15-0.3 above), which the differences partly cancel:
  they under-state the error at high noise by about 15-30 %, where the residual
  itself is the better measure. Comparing the two tells which regime a fit is in:
  residual-based errors several times the difference-based ones (measured 2-3.5 x
  at 1 % noise, 1.2-1.45 x at 10-30 %) say the floor dominates.
* ``bias`` / ``reference``: subtract the residual of the fitted model against the
  response of a noise-free simulation of itself through the same
  :func:`flightid.frequency_response` settings. It works only as well as that
  simulation reproduces the record's own discretisation: at low noise an error of
  0.01 dB or 0.1 deg (a delay rounded to a sample, a Padé approximant, first-order
  hold against band-limited input) is larger than the noise.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

__all__ = ["parameter_statistics", "residual_scaled_errors", "COVARIANCES", "NOISE_ESTIMATES"]

#: Conventions of :func:`residual_scaled_errors` (see the module docstring).
COVARIANCES = ("white", "sandwich")
#: What measures the noise: the residual itself, or its second differences along frequency.
NOISE_ESTIMATES = ("residual", "differences")


def _second_differences(r, segments):
    """Noise of each residual from its second difference along its run of frequencies:
    ``(r[k-1] - 2 r[k] + r[k+1]) / sqrt(6)`` has the variance of r[k] for uncorrelated
    noise of locally equal variance and removes a deterministic part that is locally
    linear in the index; the end points take their neighbour's value."""
    out = np.empty_like(r)
    edges = np.cumsum([0] + list(segments))
    if edges[-1] != r.size or min(segments) < 3:
        raise ValueError(f"segments must be run lengths >= 3 summing to the {r.size} residuals, got {segments}")
    for a, b in zip(edges[:-1], edges[1:]):
        d = (r[a:b - 2] - 2.0 * r[a + 1:b - 1] + r[a + 2:b]) / np.sqrt(6.0)
        out[a:b] = np.concatenate([d[:1], d, d[-1:]])
    return out


def residual_scaled_errors(jac, residuals, *, covariance="white", bias=None, noise="residual", segments=None,
                           alone=False):
    """Standard errors of least-squares parameters scaled by the residuals.

    Parameters
    ----------
    jac : ndarray, shape (N_r, p)
        Jacobian of the residual vector with respect to the free parameters.
    residuals : ndarray, shape (N_r,)
        Residuals at the optimum.
    covariance : {"white", "sandwich"}
        ``"white"``: ``sqrt(diag(s^2 inv(J^T J)))``, ``s^2 = sum r^2 / (N_r - p)``
        (uncorrelated residuals of one variance). ``"sandwich"``: the HC2
        heteroscedasticity-consistent covariance (residuals of unequal variance).
    bias : ndarray, shape (N_r,), optional
        Deterministic part of the residual (the residual a noise-free record
        leaves), subtracted before scaling. Default: none.
    noise : {"residual", "differences"}
        ``"residual"``: the residuals measure the noise. ``"differences"``: their
        second differences along each run of frequencies do (``segments``), which
        drops a deterministic part that varies smoothly with frequency; no
        degrees of freedom are lost to the fit (its correction is smooth too).
    segments : sequence of int, optional
        Lengths of the residual's runs along frequency, in order (required with
        ``noise="differences"``; a CIFER fit has a magnitude and a phase run per response).
    alone : bool
        False (default): the standard errors with every parameter free. True: each
        parameter's standard error with the others held at their values (the
        residual-scaled counterpart of CIFER's insensitivity, Eq. 3.15).

    Returns
    -------
    ndarray, shape (p,)
        Standard errors (inf along directions the data cannot see).

    Raises
    ------
    ValueError
        An unknown ``covariance`` or ``noise``, ``bias`` of another shape than
        ``residuals``, or ``segments`` missing or not matching them.

    Examples
    --------
    Fitting a constant to ``[1, 2, 3, 4]``: the white error is ``s / sqrt(4)``.

    >>> import numpy as np
    >>> r = np.array([1.0, 2.0, 3.0, 4.0]) - 2.5
    >>> float(residual_scaled_errors(np.ones((4, 1)), r)[0]) == float(np.sqrt(np.var(r, ddof=1) / 4))
    True
    """
    if not (isinstance(covariance, str) and covariance in COVARIANCES):
        raise ValueError(f"covariance must be one of {COVARIANCES}, got {covariance!r}")
    jac = np.asarray(jac, float)
    r = np.asarray(residuals, float)
    if bias is not None:
        bias = np.asarray(bias, float)
        if bias.shape != r.shape:
            raise ValueError(f"bias must have the residuals' shape {r.shape}, got {bias.shape}")
        r = r - bias
    if not (isinstance(noise, str) and noise in NOISE_ESTIMATES):
        raise ValueError(f"noise must be one of {NOISE_ESTIMATES}, got {noise!r}")
    n_r, p = jac.shape
    dof = n_r - p
    if noise == "differences":
        if segments is None:
            raise ValueError("segments (the residual's run lengths along frequency) are needed with "
                             "noise='differences'")
        r, dof = _second_differences(r, segments), n_r
    info = jac.T @ jac
    if alone:
        return _alone(jac, r, covariance, n_r, dof, noise, np.diag(info))
    eigval, eigvec = np.linalg.eigh(info)
    if not eigval.max() > 0:
        return np.full(p, np.inf)
    floor = eigval.max() * 1e-14
    if covariance == "white":
        s2 = float(r @ r) / max(dof, 1)
        with np.errstate(over="ignore"):
            cov_diag = np.sum(eigvec ** 2 / np.maximum(eigval, floor)[None, :], axis=1)
        return np.sqrt(s2 * cov_diag)
    inv_eig = 1.0 / np.maximum(eigval, floor)
    # HC2: each residual's square is its own variance, inflated by 1 / (1 - h_k) for
    # the part the fit absorbed at high-leverage points (few points fix a delay)
    a_inv = (eigvec * inv_eig[None, :]) @ eigvec.T
    leverage = np.clip(np.einsum("ij,jk,ik->i", jac, a_inv, jac), 0.0, 1.0 - 1e-12)
    if noise == "differences":
        leverage = np.zeros(n_r)          # the differences hold no part the fit absorbed
    g = jac * (r / np.sqrt(1.0 - leverage))[:, None]
    with np.errstate(over="ignore", invalid="ignore"):
        cov = a_inv @ (g.T @ g) @ a_inv
    return np.sqrt(np.maximum(np.diag(cov), 0.0))


def _alone(jac, r, covariance, n_r, dof, noise, info_diag):
    """One-parameter standard errors (the others fixed): the white or HC2 formula with
    a single column of the Jacobian."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        if covariance == "white":
            return np.sqrt(float(r @ r) / max(dof, 1) / info_diag)
        leverage = (np.zeros_like(jac) if noise == "differences" else
                    np.clip(jac ** 2 / info_diag[None, :], 0.0, 1.0 - 1e-12))
        return np.sqrt(np.sum(jac ** 2 * r[:, None] ** 2 / (1.0 - leverage), axis=0)) / info_diag


def parameter_statistics(result, *, covariance="white", noise="residual", reference=None) -> pd.DataFrame:
    """A fit's parameter table with residual-scaled standard errors beside CIFER's bounds.

    Parameters
    ----------
    result : FitResult
        From :func:`flightid.fit`, :func:`flightid.fourier_fit` or a function built on them.
    covariance : {"white", "sandwich"}
        Convention of the standard error (module docstring); ignored for fits that
        give their standard errors directly (Fourier-transform fits).
    noise : {"residual", "differences"}
        What measures the noise (:func:`residual_scaled_errors`); CIFER fits only.
    reference : MeasuredResponse, optional
        CIFER fits only: the response of a noise-free simulation of the *fitted*
        model with the record's input, estimated with the same
        :func:`flightid.frequency_response` settings. The fitted model's residual
        against it (the spectral estimate's own error) is subtracted before
        scaling. Default: none.

    Returns
    -------
    DataFrame
        The columns of ``result.parameters`` (unchanged) and ``standard_error``
        (absolute, parameter units) and ``standard_error_pct`` (relative to the
        value), and ``standard_error_alone_pct``: the standard error with the other
        parameters held, in % (the residual-scaled insensitivity; CIFER fits only,
        NaN for Fourier-transform fits); NaN for fixed parameters.

    Examples
    --------
    >>> import numpy as np
    >>> from flightid import MeasuredResponse
    >>> from flightid.transfer_function import fit_transfer_function
    >>> w = np.geomspace(0.3, 30, 60)
    >>> noise = 1 + 0.01 * np.random.default_rng(0).standard_normal(60)
    >>> h = 4.0 / (1j * w + 2.0) * noise
    >>> r = MeasuredResponse(h[None, None], w, np.ones((1, 1, 60)), ["u"], ["y"])
    >>> stats = parameter_statistics(fit_transfer_function(r, 0, 1, delay=False))
    >>> list(stats.columns)[-3:]
    ['standard_error', 'standard_error_pct', 'standard_error_alone_pct']
    """
    table = result.parameters.copy()
    free = result.structure.free_names
    alone = None
    if result.standard_errors is not None:
        se = np.array([result.standard_errors[n] for n in free])
    else:
        # the fit knows its residuals and their Jacobian: it scales them with residual_scaled_errors
        bias = None if reference is None else result.reference_residuals(reference)
        se = result.residual_scaled_errors(covariance=covariance, bias=bias, noise=noise)
        alone = result.residual_scaled_errors(covariance=covariance, bias=bias, noise=noise, alone=True)
    table["standard_error"] = np.nan
    table["standard_error_pct"] = np.nan
    table["standard_error_alone_pct"] = np.nan
    for k, (n, e) in enumerate(zip(free, se)):
        row = table.parameter == n
        v = result.structure.values[n]
        table.loc[row, "standard_error"] = e
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            table.loc[row, "standard_error_pct"] = 100.0 * e / abs(v) if v != 0 else np.inf
            if alone is not None:
                table.loc[row, "standard_error_alone_pct"] = 100.0 * alone[k] / abs(v) if v != 0 else np.inf
    return table
