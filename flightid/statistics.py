"""Parameter statistics that follow the noise: residual-scaled standard errors.

CIFER's Cramér-Rao bound (Eqs. 3.15-3.16, :func:`flightid.fit`) is
``CR_i = 2 sqrt(inv(H)_ii)`` with ``H = 2 Jr^T Jr`` the Gauss-Newton Hessian of
the cost ``J_sum = sum r^2``: it does not contain the residual variance, so it
does not change with the noise level. The residual-scaled standard error
reported beside it is the least-squares convention

    s^2 = J_sum / (N_r - p),      SE_i = sqrt(s^2 inv(Jr^T Jr)_ii) = CR_i sqrt(J_sum / (2 (N_r - p)))

with N_r the number of residuals (a magnitude and a phase residual per fitted
frequency and response) and p the number of free parameters. It assumes
uncorrelated residuals; residuals of neighbouring CIFER frequency points are
correlated (they come from overlapping spectral windows and are interpolated
to ``n_omega`` points), so it can err by the usual coloured-residual factor,
which this module does not correct. For the Fourier-transform fits
(:func:`flightid.fourier_fit`) the residuals are at frequencies spaced by the
record's resolution 2 pi / T, where the convention is exact for white noise.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

__all__ = ["parameter_statistics", "residual_scaled_errors"]


def residual_scaled_errors(jac, residuals):
    """Standard errors ``sqrt(diag(s^2 inv(J^T J)))``, ``s^2 = sum r^2 / (N_r - p)``.

    Parameters
    ----------
    jac : ndarray, shape (N_r, p)
        Jacobian of the residual vector with respect to the free parameters.
    residuals : ndarray, shape (N_r,)
        Residuals at the optimum.

    Returns
    -------
    ndarray, shape (p,)
        Standard errors (inf along directions the data cannot see).
    """
    jac = np.asarray(jac, float)
    r = np.asarray(residuals, float)
    n_r, p = jac.shape
    s2 = float(r @ r) / max(n_r - p, 1)
    info = jac.T @ jac
    eigval, eigvec = np.linalg.eigh(info)
    if not eigval.max() > 0:
        return np.full(p, np.inf)
    floor = eigval.max() * 1e-14
    with np.errstate(over="ignore"):
        cov_diag = np.sum(eigvec ** 2 / np.maximum(eigval, floor)[None, :], axis=1)
    return np.sqrt(s2 * cov_diag)


def parameter_statistics(result) -> pd.DataFrame:
    """A fit's parameter table with residual-scaled standard errors beside CIFER's bounds.

    Parameters
    ----------
    result : FitResult
        From :func:`flightid.fit`, :func:`flightid.fourier_fit` or a function built on them.

    Returns
    -------
    DataFrame
        The columns of ``result.parameters`` (unchanged) and ``standard_error``
        (absolute, parameter units) and ``standard_error_pct`` (relative to the
        value); NaN for fixed parameters.

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
    >>> list(stats.columns)[-2:]
    ['standard_error', 'standard_error_pct']
    """
    table = result.parameters.copy()
    free = result.structure.free_names
    if result.standard_errors is not None:
        se = np.array([result.standard_errors[n] for n in free])
    else:
        # the fit knows its residuals and their Jacobian: it scales them with residual_scaled_errors
        se = result.residual_scaled_errors()
    table["standard_error"] = np.nan
    table["standard_error_pct"] = np.nan
    for n, e in zip(free, se):
        row = table.parameter == n
        v = result.structure.values[n]
        table.loc[row, "standard_error"] = e
        with np.errstate(divide="ignore", over="ignore"):
            table.loc[row, "standard_error_pct"] = 100.0 * e / abs(v) if v != 0 else np.inf
    return table
