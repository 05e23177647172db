"""The analytic Jacobian of the CIFER residual (opt-in: ``fit(..., jacobian="analytic")``).

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
