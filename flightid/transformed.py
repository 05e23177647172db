"""Fitting in transformed signal coordinates (for nearly rank-deficient MIMO blocks).

The CIFER cost (Eq. 3.13) compares responses element by element in dB and
degrees. When a square block of the measured response is nearly rank one (a
coaxial rotor's collective lambda/C_T block: sigma_min/sigma_max ~ 0.06, because
both rotors' inflow follows the *total* thrust), every element is dominated by
the large singular value and the cost cannot see the small one. A fit then
wanders along a flat valley (apparent masses of several hundred, Cramer-Rao
bounds of 40-600 %) although the data do hold the small direction.

The cure is a change of coordinates, not of model: fit ``T H Sinv`` instead of
``H``, with ``T`` (outputs) and ``Sinv`` (inputs) chosen so that the large and the
small singular directions land in different elements (for a coaxial pair, the
rotors' sum and difference). The parameters stay those of the original
structure, in its own frame, so their Cramer-Rao bounds and insensitivities are
the ones a user reads; only the cost's view of the data changes.

::

    H (outputs x inputs, measured)  --transform_response(T, Sinv)-->  T H Sinv
    structure (parameters theta)    --TransformedStructure(T, Sinv)-> T H(theta) Sinv
                                      fit / reduce on the transformed pairs
    result.structure.inner          <- the fitted structure, original signals

The coherence of a transformed element is propagated from the elements'
random errors: with ``eps_ij^2 = (1 - g_ij) / g_ij |H_ij|^2`` (the normalised
variance of Bendat & Piersol, up to the common 1/(2 n_d)),
``eps_t^2 = sum_ij |T_ai|^2 |Sinv_jb|^2 eps_ij^2`` and
``g_t = 1 / (1 + eps_t^2 / |H_t|^2)`` (errors of different elements taken as
uncorrelated). An element that cancels (a difference of two nearly equal
responses) therefore comes out with the low coherence its data deserve.
"""
from __future__ import annotations

import numpy as np
import pandas as pd
import control

from .errors import IdentificationError
from .response import MeasuredResponse
from .structures import ModelStructure

__all__ = ["TransformedStructure", "transform_response", "sum_difference_transform", "pair_costs"]


def _matrices(t, s_inv, n_out, n_in):
    t = np.asarray(t, dtype=float)
    s_inv = np.asarray(s_inv, dtype=float)
    if t.ndim != 2 or t.shape[1] != n_out:
        raise IdentificationError(f"T must have {n_out} columns (one per original output), got shape {t.shape}")
    if s_inv.ndim != 2 or s_inv.shape[0] != n_in:
        raise IdentificationError(f"Sinv must have {n_in} rows (one per original input), got shape {s_inv.shape}")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(s_inv))):
        raise IdentificationError("T and Sinv must be finite")
    # full rank: no original signal may be lost (a stack [I; T] that keeps the
    # original elements beside the transformed ones is allowed)
    if np.linalg.matrix_rank(t) < n_out:
        raise IdentificationError(f"T must have rank {n_out} (every original output seen), "
                                  f"got rank {np.linalg.matrix_rank(t)}")
    if np.linalg.matrix_rank(s_inv) < n_in:
        raise IdentificationError(f"Sinv must have rank {n_in} (every original input reached), "
                                  f"got rank {np.linalg.matrix_rank(s_inv)}")
    return t, s_inv


def _names(names, n, what):
    names = [str(x) for x in names]
    if len(names) != n or len(set(names)) != n:
        raise IdentificationError(f"need {n} distinct transformed {what} names, got {names}")
    return names


def transform_response(response, T, Sinv, outputs, inputs, name=None) -> MeasuredResponse:
    """The measured response in transformed coordinates, ``T H Sinv``, with propagated coherence.

    Parameters
    ----------
    response : MeasuredResponse
        Original response (all the outputs and inputs the transform mixes).
    T : array_like (n, n_outputs)
        Output transform: new output ``a`` is ``sum_i T[a, i] y_i``.
    Sinv : array_like (n_inputs, m)
        Input transform: original input ``u = Sinv u_t`` (so ``y = (H Sinv) u_t``).
    outputs, inputs : list of str
        Names of the transformed outputs and inputs.
    name : str, optional
        Name of the result (default: the response's name plus ``" (transformed)"``,
        or none if the response has none).

    Returns
    -------
    MeasuredResponse
        Shape (n, m, n_freq); coherence propagated from the elements' random
        errors (module docstring).
    """
    if not isinstance(response, MeasuredResponse):
        raise IdentificationError(f"response must be a MeasuredResponse, got {type(response).__name__}")
    h, g = response.data, response.coherence
    t, s_inv = _matrices(T, Sinv, h.shape[0], h.shape[1])
    outputs = _names(outputs, t.shape[0], "output")
    inputs = _names(inputs, s_inv.shape[1], "input")
    ht = np.einsum("ai,ijw,jb->abw", t, h, s_inv)
    # a coherence of 0 is an element with no information: infinite variance
    with np.errstate(divide="ignore", invalid="ignore"):
        eps2 = np.where(g > 0, (1.0 - g) / np.where(g > 0, g, 1.0) * np.abs(h) ** 2, np.inf)
        var = np.einsum("ai,ijw,jb->abw", t ** 2, eps2, s_inv ** 2)
        gt = np.where(np.isfinite(var), 1.0 / (1.0 + var / np.maximum(np.abs(ht) ** 2, 1e-300)), 0.0)
    if name is None and response.name:
        name = f"{response.name} (transformed)"
    return MeasuredResponse(ht, response.omega, np.clip(gt, 0.0, 1.0), inputs, outputs, name=name)


def sum_difference_transform(groups, outputs, inputs, signs=None):
    """Sum and difference coordinates for pairs of signals (a coaxial rotor's upper and lower).

    Parameters
    ----------
    groups : list of ((out_a, out_b), (in_a, in_b), label)
        Each pair of outputs and of inputs to recombine, and the label of the new
        signals (``label + "_sum"``, ``label + "_diff"``).
    outputs, inputs : list of str
        The original signal order.
    signs : list of float, optional
        Per group, the sign ``s`` of the second signal in the sum (``a + s b``),
        for frames in which the two members are mirrored; default +1.

    Returns
    -------
    T, Sinv, new_outputs, new_inputs
        Orthonormal ``T`` (``T^-1 = T^T``) and ``Sinv = T^T`` restricted to the
        inputs: ``u_sum = (u_a + s u_b)/sqrt(2)``, ``u_diff = (u_a - s u_b)/sqrt(2)``.
        Signals in no group are kept as they are.
    """
    outputs, inputs = list(outputs), list(inputs)
    signs = [1.0] * len(groups) if signs is None else [float(s) for s in signs]
    if len(signs) != len(groups) or any(s not in (1.0, -1.0) for s in signs):
        raise IdentificationError(f"signs must be one +1 or -1 per group, got {signs}")
    t = np.eye(len(outputs))
    s_fwd = np.eye(len(inputs))
    new_out, new_in = list(outputs), list(inputs)
    r = 1.0 / np.sqrt(2.0)
    for ((oa, ob), (ia, ib), label), sg in zip(groups, signs):
        for names, pair, mat, new in ((outputs, (oa, ob), t, new_out), (inputs, (ia, ib), s_fwd, new_in)):
            missing = [p for p in pair if p not in names]
            if missing:
                raise IdentificationError(f"group {label!r}: signals {missing} not among {names}")
            a, b = names.index(pair[0]), names.index(pair[1])
            mat[a, :], mat[b, :] = 0.0, 0.0
            mat[a, a], mat[a, b] = r, sg * r
            mat[b, a], mat[b, b] = r, -sg * r
            new[a], new[b] = f"{label}_sum", f"{label}_diff"
    if len(set(new_out)) != len(new_out) or len(set(new_in)) != len(new_in):
        raise IdentificationError("each signal may belong to one group only")
    # inputs: u_t = S u with S orthonormal, so u = S^T u_t
    return t, s_fwd.T, new_out, new_in


class TransformedStructure(ModelStructure):
    """A structure seen in transformed coordinates: response ``T H(theta) Sinv``.

    The parameters (names, values, fixed set, delays, stability) are the inner
    structure's own and are shared with it, so :func:`flightid.fit` and
    :func:`flightid.reduce` work unchanged and their Cramer-Rao bounds refer to
    the inner parameters. ``inner`` is the fitted model in its original signals.

    Parameters
    ----------
    inner : ModelStructure
    T, Sinv, outputs, inputs
        As in :func:`transform_response` (use the same for the data).
    """

    def __init__(self, inner, T, Sinv, outputs, inputs):
        if not isinstance(inner, ModelStructure):
            raise IdentificationError(f"inner must be a ModelStructure, got {type(inner).__name__}")
        self.inner = inner.copy()
        self.T, self.Sinv = _matrices(T, Sinv, len(inner.outputs), len(inner.inputs))
        self.outputs = _names(outputs, self.T.shape[0], "output")
        self.inputs = _names(inputs, self.Sinv.shape[1], "input")

    # the parameter bookkeeping is the inner structure's (shared, not copied)
    names = property(lambda self: self.inner.names)
    values = property(lambda self: self.inner.values)
    fixed = property(lambda self: self.inner.fixed)
    delay_names = property(lambda self: self.inner.delay_names)
    omega = property(lambda self: self.inner.omega)

    def matrices(self, values=None):
        return self.inner.matrices(values)

    def frequency_response(self, omega, values=None):
        h = self.inner.frequency_response(omega, values)
        return np.einsum("ai,ijw,jb->abw", self.T, h, self.Sinv)

    def poles(self, values=None):
        return self.inner.poles(values)

    def to_statespace(self, values=None, pade_order=None, minimal=True, name=None):
        sys = self.inner.to_statespace(values, pade_order=pade_order, minimal=minimal)
        out = control.ss([], [], [], self.T) * sys * control.ss([], [], [], self.Sinv)
        return control.ss(out.A, out.B, out.C, out.D, inputs=self.inputs, outputs=self.outputs,
                          name=name or f"{type(self.inner).__name__} (transformed)")

    def __repr__(self):
        return f"TransformedStructure({self.inner!r}, outputs={self.outputs})"


def pair_costs(structure, response, pairs, frequency_ranges, n_omega=20) -> pd.DataFrame:
    """CIFER cost (Eq. 3.13) of ``structure`` on given ``pairs`` of ``response``, without fitting.

    Parameters
    ----------
    structure : ModelStructure
    response : MeasuredResponse
    pairs : list of (output, input)
    frequency_ranges : (float, float) or dict
        ``(w_lo, w_hi)`` [rad/s] for every pair, or per pair.
    n_omega : int
        Log-spaced points per pair (as in :func:`flightid.fit`).

    Returns
    -------
    pandas.DataFrame
        ``output, input, w_min, w_max, J``; ``.attrs["J_ave"]`` is the mean.
    """
    from .fitting import _pair_residual, _sample_pair
    rows = []
    for o, u in pairs:
        if o not in structure.outputs or u not in structure.inputs:
            raise IdentificationError(f"pair {o}/{u} is not a response of the structure")
        lo, hi = frequency_ranges[(o, u)] if isinstance(frequency_ranges, dict) else frequency_ranges
        w, h, c = _sample_pair(response, o, u, lo, hi, n_omega)
        hm = structure.frequency_response(w)[structure.outputs.index(o), structure.inputs.index(u)]
        rows.append({"output": o, "input": u, "w_min": lo, "w_max": hi,
                     "J": float(np.sum(_pair_residual(hm, h, c) ** 2))})
    table = pd.DataFrame(rows)
    table.attrs["J_ave"] = float(table.J.mean()) if len(table) else float("nan")
    return table
