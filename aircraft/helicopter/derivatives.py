"""Effective (frequency-dependent) stability and control derivatives of a linear aircraft.

A rigid-body derivative such as the roll damping ``L_p`` is, in a model with
flapping and inflow states, not one number: a body rate moves the flapping and
the inflow, whose dynamics return a moment with a lag. Holding the body motion
at ``exp(j omega t)`` and letting every other ("fast") state respond gives

    D(j omega) = A_rb + A_rf (j omega I - A_ff)^-1 A_fb        (body state b)
    D(j omega) = B_rb + A_rf (j omega I - A_ff)^-1 B_fb        (control b)

for the body acceleration ``r`` (e.g. ``p`` for ``p_dot``). At ``omega = 0`` it is
the quasi-static derivative (the fast states at their steady response); its change
with ``omega`` shows where an inflow model's slow states act. The main job uses it
to show where our identified inflow models change the roll damping and the control
power (``results/hover_control_comparison/roll_derivatives.csv``).
"""
from __future__ import annotations

import control
import numpy as np

from .model import BODY_STATES

__all__ = ["DerivativeError", "effective_derivative"]


class DerivativeError(ValueError):
    """Unknown signal names or an unusable frequency grid."""


def effective_derivative(sys, rate, cause, omega, body_states=None):
    """The effective derivative ``d(rate_dot)/d(cause)`` at each frequency [rad/s].

    Parameters
    ----------
    sys : control.StateSpace
        Linear aircraft with named states and inputs
        (:func:`aircraft.helicopter.linearize`).
    rate : str
        Body state whose derivative is the response (e.g. ``"p"``: roll acceleration).
    cause : str
        Body state (e.g. ``"p"`` for the roll damping ``L_p`` [1/s], ``"v"`` for
        ``L_v`` [rad/(m s)]) or input name (e.g. ``"delta_lat"``: the control
        power ``L_delta`` [rad/s^2 per stick unit]) held at ``exp(j omega t)``.
    omega : array_like
        Frequencies [rad/s], finite and >= 0.
    body_states : sequence of str, optional
        States held with the body motion (default
        :data:`aircraft.helicopter.BODY_STATES`); every other state responds.

    Returns
    -------
    numpy.ndarray of complex
        ``D(j omega)``, one value per frequency, in the units of ``rate`` per
        second per unit of ``cause``.

    Raises
    ------
    DerivativeError
        Unknown names, ``rate`` not a body state, frequencies not finite and >= 0,
        or fast dynamics singular at a requested frequency (a fast state with a
        pole at ``j omega``).
    """
    if not isinstance(sys, control.StateSpace):
        raise DerivativeError(f"sys must be a control.StateSpace, got {type(sys).__name__}")
    states, inputs = list(sys.state_labels), list(sys.input_labels)
    body = list(BODY_STATES if body_states is None else body_states)
    missing = [n for n in body if n not in states]
    if missing:
        raise DerivativeError(f"unknown body state(s) {missing}; states: {states}")
    if rate not in body:
        raise DerivativeError(f"rate {rate!r} must be one of the body states {body}")
    if cause not in states and cause not in inputs:
        raise DerivativeError(f"cause {cause!r} is neither a state nor an input; states: {states}; "
                              f"inputs: {inputs}")
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    if w.ndim != 1 or w.size == 0 or not np.all(np.isfinite(w)) or np.any(w < 0):
        raise DerivativeError(f"omega must be a non-empty 1-D array of finite frequencies >= 0 rad/s, "
                              f"got {omega!r}")
    a, b = np.asarray(sys.A, dtype=float), np.asarray(sys.B, dtype=float)
    r = states.index(rate)
    fast = [k for k, n in enumerate(states) if n not in body]
    if cause in states:
        column, direct = a[:, states.index(cause)], a[r, states.index(cause)]
    else:
        column, direct = b[:, inputs.index(cause)], b[r, inputs.index(cause)]
    if not fast:
        return np.full(w.shape, complex(direct))
    a_ff, a_rf, col_f = a[np.ix_(fast, fast)], a[r, fast], column[fast]
    poles = np.linalg.eigvals(a_ff)
    eye = np.eye(len(fast))
    out = np.empty(w.shape, dtype=complex)
    for k, wk in enumerate(w):
        # a fast pole on (or within round-off of) j omega: solve would return noise
        if np.any(np.abs(poles - 1j * wk) <= 1e-9 * (1.0 + np.abs(poles))):
            raise DerivativeError(f"the non-body states have a pole at j{wk:g} rad/s: the derivative "
                                  "is unbounded there")
        out[k] = direct + a_rf @ np.linalg.solve(1j * wk * eye - a_ff, col_f)
    return out
