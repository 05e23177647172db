"""Derivatives of the CIFER residual: the central-difference Jacobian (the default), the
analytic one (opt-in: ``fit(..., jacobian="analytic")``), and the Cramér-Rao bounds and
insensitivities built on either.

The residual of one response is the weighted magnitude error in dB and phase error
in degrees (Eq. 3.13). With H the model's response and dH/dp its derivative,

    d(20 log10 |H|)/dp = (20 / ln 10) Re(dH/dp / H)
    d(angle H [deg])/dp = (180 / pi) Im(dH/dp / H)

(the phase wrap is piecewise constant, so it has no derivative). dH/dp comes from
the structure: for ``x' = F x + G u``, ``y = C x`` with ``R = (s I - F)^-1``,
``dH = C R dF R G + C R dG`` (and the M/Lbar form's ``dH = -C X^-1 dX X^-1``,
``X = M s + Lbar``), exact delays ``dH/dtau = -s H``. Every entry of a pattern
matrix maps to its parameter with its sign (ties add up). One evaluation costs two
linear solves per response and frequency instead of one model evaluation per
parameter, which is what makes a refit of a structure with a hundred or more free
parameters cheap.
"""
from __future__ import annotations

import numpy as np

__all__ = []

_DB = 20.0 / np.log(10.0)
_DEG = 180.0 / np.pi


def _residual_jacobian(structure, values, pairs, slices_weights, maps):
    """d(residual)/d(free parameters) of the CIFER residual without the stability penalty.

    ``pairs``: the fitted pairs (omega, i, j); ``slices_weights``: per pair the
    (magnitude, phase) weights multiplying the dB and degree errors; ``maps``:
    :meth:`ModelStructure._reference_maps` of the free parameters.
    Rows in the order of the residual: per pair, magnitudes then phases.
    """
    mats = structure.matrices(values)
    blocks = []
    for p, (w_mag, w_ph) in zip(pairs, slices_weights):
        h, dh = structure._pair_derivatives(mats, 1j * p.omega, p.i, p.j, maps)
        # a response that is identically zero sits at the -inf dB floor: no gradient there
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(h[:, None] != 0, dh / np.where(h == 0, 1.0, h)[:, None], 0.0)
        blocks.append(w_mag[:, None] * _DB * ratio.real)
        blocks.append(w_ph[:, None] * _DEG * ratio.imag)
    return np.vstack(blocks)


def _penalty_gradient(penalty, x):
    """Central differences of the stability penalty (eigenvalues only: cheap); zero where
    the penalty is inactive."""
    if penalty(x) == 0.0:
        return np.zeros(x.size)
    return _jacobian(lambda z: np.atleast_1d(penalty(z)), x)[0]


def _jacobian(residual_fn, x):
    """Central-difference Jacobian of the residual vector (relative step 1e-6: the
    residuals are smooth in the parameters and carry about 1e-15 relative round-off,
    so the truncation and round-off errors balance near this step)."""
    columns = []
    for k in range(x.size):
        h = 1e-6 * max(1.0, abs(x[k]))
        e = np.zeros_like(x)
        e[k] = h
        columns.append((np.asarray(residual_fn(x + e)) - np.asarray(residual_fn(x - e))) / (2 * h))
    return np.stack(columns, axis=1) if columns else np.empty((np.size(residual_fn(x)), 0))


def _cramer_rao_insensitivity(residual_fn, x, jac=None):
    """Eqs. 3.15-3.16 with H = d2 J_sum / dTheta2 ~ 2 Jr^T Jr (Gauss-Newton).

    Returns the *un-normalised* (2 sqrt(inv(H)_ii), 1/sqrt(H_ii)) per parameter.
    """
    if jac is None:
        jac = _jacobian(residual_fn, x)
    hess = 2.0 * jac.T @ jac
    diag = np.diag(hess)
    ins = np.where(diag > 0, 1.0 / np.sqrt(np.maximum(diag, 1e-300)), np.inf)
    # covariance by symmetric eigendecomposition: a direction the data cannot
    # see (near-zero eigenvalue) must give a huge bound, never a clipped 0
    # (inverting an ill-conditioned H directly can yield negative diagonals)
    eigval, eigvec = np.linalg.eigh(hess)
    if not eigval.max() > 0:
        # the cost does not depend on any free parameter (e.g. a gain fixed at 0
        # multiplies them all): every bound is unbounded
        return np.full(x.size, np.inf), ins
    floor = eigval.max() * 1e-14
    with np.errstate(over="ignore"):
        cov_diag = np.sum(eigvec ** 2 / np.maximum(eigval, floor)[None, :], axis=1)
    cr = 2.0 * np.sqrt(cov_diag)
    return cr, ins
