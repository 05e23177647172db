"""The joint input-output method (§3.3.5, Eqs. 3.22-3.25, block form Eq. 4.11).

When the wanted model inputs ("input-outputs", e.g. rotor loads) are outputs of
the system and cannot be swept independently, sweep the true controls theta one
at a time, measure ``y/theta`` and ``u/theta``, and form
``y/u = (y/theta) (u/theta)^-1`` frequency by frequency.
"""
from __future__ import annotations

import numpy as np

from ._validation import real_scalar
from .errors import DataError, IdentificationError, SingularInputError
from .response import MeasuredResponse

__all__ = ["joint_input_output"]


def joint_input_output(y_over_theta: MeasuredResponse, u_over_theta: MeasuredResponse, *,
                       structural_zeros=None, max_condition=1e6, name=None,
                       coherence="weighted") -> MeasuredResponse:
    """Outputs over input-outputs, ``y/u = (y/theta) (u/theta)^+`` (Eq. 3.22).

    Parameters
    ----------
    y_over_theta : MeasuredResponse
        Outputs to controls, shape (n_y, n_theta).
    u_over_theta : MeasuredResponse
        Input-outputs to controls, shape (n_u, n_theta), same controls (same
        names, same order) and frequency grid.  ``n_theta >= n_u``: square
        matrices are inverted, over-determined ones use the pseudo-inverse.
    structural_zeros : array_like of bool (n_u, n_theta), optional
        Elements of u/theta known to be zero (e.g. the lower-left block of
        Eq. 4.11: loads do not drive prescribed flap-rate inputs); they are set
        to exactly zero before inversion.
    max_condition : float
        Largest acceptable condition number of u/theta; above it the matrix is
        treated as singular.
    coherence : {"weighted", "propagated"}
        ``"weighted"`` (default): the magnitude-weighted coherence of Eqs.
        3.23-3.25 (Notes). ``"propagated"``: the coherence equivalent to the
        random error that the inversion carries into each element (Notes), which
        grows with the conditioning of u/theta.

    Returns
    -------
    MeasuredResponse
        Shape (n_y, n_u), with the magnitude-weighted coherence of Eqs. 3.23-3.25.

    Raises
    ------
    SingularInputError
        Naming the frequencies [rad/s] where u/theta is singular.

    Notes
    -----
    Coherence (Eqs. 3.23-3.25): ``y/u_ij = sum_n Y_in Ui_nj`` with
    ``Ui = (u/theta)^+``; each term's coherence is taken as
    ``min(coh(Y_in), coh(U_jn))`` (the inverse element Ui_nj relates theta_n
    and u_j, whose measured coherence is that of U_jn), weighted by
    ``|Y_in Ui_nj| / sum_n |Y_in Ui_nj|``.  The dissertation divides by
    ``|y/u_ij|`` instead of the sum of magnitudes; that can exceed one when the
    terms cancel, so we normalise by the sum, which keeps the result in [0, 1].
    """
    for label, r in (("y_over_theta", y_over_theta), ("u_over_theta", u_over_theta)):
        if not isinstance(r, MeasuredResponse):
            raise DataError(f"{label} must be a MeasuredResponse (response with coherence), "
                            f"got {type(r).__name__}")
        # frdata/coherence are plain arrays a caller can overwrite after construction
        if not np.all(np.isfinite(r.frdata)):
            raise DataError(f"{label} holds {int(np.sum(~np.isfinite(r.frdata)))} NaN or infinite "
                            "response value(s); the joint input-output method needs finite responses")
        if not np.all(np.isfinite(r.coherence)):
            raise DataError(f"{label} holds NaN or infinite coherence values")
    max_condition = real_scalar("max_condition", max_condition, lo=1.0)
    if list(y_over_theta.input_labels) != list(u_over_theta.input_labels):
        raise IdentificationError(
            f"y/theta and u/theta must have the same controls in the same order: "
            f"{y_over_theta.input_labels} vs {u_over_theta.input_labels}")
    w = y_over_theta.omega
    if w.shape != u_over_theta.omega.shape or not np.allclose(w, u_over_theta.omega):
        raise IdentificationError("y/theta and u/theta must share one frequency grid")
    Y = np.moveaxis(y_over_theta.frdata, -1, 0)          # (n_w, n_y, n_theta)
    U = np.moveaxis(u_over_theta.frdata, -1, 0).copy()   # (n_w, n_u, n_theta)
    cy = np.moveaxis(y_over_theta.coherence, -1, 0)
    cu = np.moveaxis(u_over_theta.coherence, -1, 0)
    n_u, n_theta = U.shape[1:]
    if n_theta < n_u:
        raise IdentificationError(
            f"{n_u} input-outputs but only {n_theta} controls: the joint input-output "
            "method needs one independent sweep per input-output")
    if structural_zeros is not None:
        mask = np.asarray(structural_zeros)
        if mask.shape != (n_u, n_theta):
            raise IdentificationError(f"structural_zeros must be {n_u} x {n_theta} "
                                      f"(input-outputs x controls), got shape {mask.shape}")
        if mask.dtype != bool and not np.all(np.isin(mask, (0, 1))):
            raise IdentificationError("structural_zeros must hold booleans (True: known zero)")
        mask = mask.astype(bool)
        U[:, mask] = 0.0
    sv = np.linalg.svd(U, compute_uv=False)
    cond = sv[:, 0] / np.maximum(sv[:, -1], 1e-300)
    bad = cond > max_condition
    if np.any(bad):
        freqs = w[bad]
        raise SingularInputError(
            f"u/theta is singular (condition > {max_condition:.0e}) at {bad.sum()} of {w.size} "
            f"frequencies: {np.array2string(freqs, precision=3, max_line_width=200)} rad/s; "
            "a control sweep does not excite the input-outputs independently", freqs)
    Ui = np.linalg.pinv(U)                                # (n_w, n_theta, n_u)
    H = Y @ Ui                                             # (n_w, n_y, n_u)
    terms = np.abs(Y[:, :, :, None] * Ui[:, None, :, :])  # (n_w, n_y, n_theta, n_u)
    # coherence of term (i, n, j): min(coh Y_in, coh U_jn)
    cmin = np.minimum(cy[:, :, :, None], np.swapaxes(cu, 1, 2)[:, None, :, :])
    if coherence == "propagated":
        coh = _propagated_coherence(Y, U, H, Ui, cy, cu)
    else:
        weights = terms / np.maximum(terms.sum(axis=2, keepdims=True), 1e-300)
        coh = np.sum(weights * cmin, axis=2)
    return MeasuredResponse(np.moveaxis(H, 0, -1), w, np.moveaxis(coh, 0, -1),
                            list(u_over_theta.output_labels), list(y_over_theta.output_labels),
                            name=name)


def _propagated_coherence(Y, U, H, Ui, cy, cu):
    """Coherence equivalent to the propagated random error of H = Y Ui (see joint_input_output)."""
    qy = (1 - cy) / np.maximum(cy, 1e-12)                          # (w, y, theta)
    qu = (1 - cu) / np.maximum(cu, 1e-12)                          # (w, u, theta)
    # sum_k |H_ik|^2 |U_kn|^2 q_U,kn -> (w, y, theta)
    from_u = np.einsum("wik,wkn->win", np.abs(H) ** 2, np.abs(U) ** 2 * qu)
    per_theta = np.abs(Y) ** 2 * qy + from_u                       # (w, y, theta)
    var = np.einsum("win,wnj->wij", per_theta, np.abs(Ui) ** 2)    # (w, y, u)
    ratio = var / np.maximum(np.abs(H) ** 2, 1e-300)
    return 1.0 / (1.0 + ratio)
