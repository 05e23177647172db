"""Linearisation by central differences (Appendix A) and the modes table."""
from __future__ import annotations

import warnings

import control
import numpy as np
import pandas as pd

from .._validation import real as _real
from .mixing import mixing_matrix, pilot_inputs

__all__ = ["linearize", "modes", "default_steps", "NotAtTrimError", "NotAtTrimWarning",
           "LinearizeInputError", "trim_derivatives"]


class LinearizeInputError(ValueError):
    """A linearize argument is of the wrong type, NaN, infinite or out of range."""


class NotAtTrimError(ValueError):
    """The point to linearise about is not a trim: its state derivatives are not near zero.

    ``derivatives`` maps the worst states to their scaled derivatives.
    """

    def __init__(self, message, derivatives=None):
        super().__init__(message)
        self.derivatives = dict(derivatives or {})


class NotAtTrimWarning(UserWarning):
    """Linearising (on request) about a point whose state derivatives are not near zero."""


def trim_derivatives(trim_result):
    """Scaled state derivatives at a trim point (all should be ~0).

    Body accelerations and Euler-angle rates in SI, flap rates/accelerations
    divided by Omega / Omega^2, inflow derivatives by Omega -- the scaling
    :func:`~aircraft.helicopter.trim` converges.

    Parameters
    ----------
    trim_result : TrimResult
        Result of :func:`~aircraft.helicopter.trim`: its ``helicopter``, state
        ``x`` and controls ``u`` are evaluated.

    Returns
    -------
    pandas.Series
        Indexed by state name (``wdot`` for ``w`` etc.).
    """
    heli = trim_result.helicopter
    xdot = np.asarray(heli.derivatives(trim_result.x, trim_result.u), float)
    scale = np.ones(heli.n_states)
    for k, rm in enumerate(heli.rotors):
        scale[9 + 8 * k:9 + 8 * k + 4] = rm.config.omega
        scale[9 + 8 * k + 4:9 + 8 * k + 8] = rm.config.omega ** 2
    scale[heli.n_rigid:] = heli.rotors[0].config.omega
    # psi (heading) is free: a steady turn rate is not a trim violation of level flight here,
    # but it is zero in the trims we solve, so it is checked like the rest
    return pd.Series(xdot / scale, index=[f"{n}dot" for n in heli.state_names])


def default_steps(heli, scale=1.0):
    """Absolute perturbation per state [SI]: velocities 1e-3 m/s, rates 1e-4 rad/s,
    angles 1e-4 rad, flap 1e-5 rad, flap rates 1e-4 rad/s, inflow 1e-6; times ``scale``."""
    scale = _real(LinearizeInputError, "scale", scale, positive=True)
    h = np.empty(heli.n_states)
    h[0:3], h[3:6], h[6:9] = 1e-3, 1e-4, 1e-4
    for k in range(len(heli.rotors)):
        h[9 + 8 * k:9 + 8 * k + 4] = 1e-5
        h[9 + 8 * k + 4:9 + 8 * k + 8] = 1e-4
    h[heli.n_rigid:] = 1e-6
    return h * scale


def linearize(trim_result, inputs="pilot", step_scale=1.0, control_step=1e-5, *,
              trim_tol=1e-4, off_trim="raise"):
    """Linear model about a trim: named :class:`control.StateSpace`, outputs = states.

    Parameters
    ----------
    trim_result : TrimResult
    inputs : ``"pilot"`` (delta_col, delta_lon, delta_lat, delta_ped, and delta_prop on
        the coaxial, through the mixing of :mod:`aircraft.helicopter.mixing` with the
        aircraft's control phase) or ``"rotor"`` (the rotor controls).
    step_scale : float
        Multiplies the default perturbation sizes (convergence checks).
    control_step : float
        Perturbation of the rotor controls [rad].
    trim_tol : float
        Largest scaled state derivative (see :func:`trim_derivatives`) accepted
        at the linearisation point; default 1e-4 (e.g. w-dot 1e-4 m/s^2).
    off_trim : {"raise", "warn"}
        What to do when the point is not a trim: raise :class:`NotAtTrimError`
        (default) or linearise anyway with a :class:`NotAtTrimWarning`.

    The averaged (time-invariant) rotor model makes one linearisation exact for
    the whole revolution. The trim is attached as ``sys.trim``.

    Raises
    ------
    NotAtTrimError
        The state derivatives at the point are not near zero (e.g. the inflow
        model was re-trimmed at another condition since, or the state was edited).
    LinearizeInputError
        Bad arguments.

    Examples
    --------
    >>> from aircraft import coaxial_compound
    >>> from aircraft.helicopter import Helicopter, TrimCondition, linearize, trim
    >>> from aircraft.inflow import DynamicClimb
    >>> hover = trim(Helicopter(coaxial_compound(), DynamicClimb()), TrimCondition(speed=0.0))
    >>> sys = linearize(hover)                    # a control.StateSpace with named signals
    >>> sys.input_labels
    ['delta_col', 'delta_lon', 'delta_lat', 'delta_ped', 'delta_prop']
    >>> sys.output_labels[:9]
    ['u', 'v', 'w', 'p', 'q', 'r', 'phi', 'theta', 'psi']
    """
    from .trim import TrimResult
    if not isinstance(trim_result, TrimResult):
        raise LinearizeInputError(f"trim_result must be the TrimResult of aircraft.helicopter.trim, "
                                  f"got {type(trim_result).__name__}")
    step_scale = _real(LinearizeInputError, "step_scale", step_scale, positive=True)
    control_step = _real(LinearizeInputError, "control_step", control_step, positive=True,
                         hi=0.1, unit="rad")
    trim_tol = _real(LinearizeInputError, "trim_tol", trim_tol, positive=True)
    if off_trim not in ("raise", "warn"):
        raise LinearizeInputError(f"off_trim must be 'raise' or 'warn', got {off_trim!r}")
    if inputs not in ("pilot", "rotor"):
        raise LinearizeInputError(f"inputs must be 'pilot' or 'rotor', got {inputs!r}")
    for label, v in (("trim_result.x", trim_result.x), ("trim_result.u", trim_result.u)):
        if not np.all(np.isfinite(np.asarray(v, float))):
            raise LinearizeInputError(f"{label} contains NaN or infinite values")
    xdot = trim_derivatives(trim_result)
    worst = xdot.abs().sort_values(ascending=False)
    if not np.all(np.isfinite(xdot)) or worst.iloc[0] > trim_tol:
        top = {k: float(xdot[k]) for k in worst.index[:4]}
        msg = (f"linearize: the point is not a trim: scaled state derivatives up to "
               f"{worst.iloc[0]:.3g} > trim_tol = {trim_tol:g} (largest: "
               + ", ".join(f"{k} = {v:.3g}" for k, v in top.items())
               + "). Re-trim (the inflow model may have been re-trimmed at another condition "
               "since), or pass off_trim='warn' to linearise about a non-equilibrium point.")
        if off_trim == "raise":
            raise NotAtTrimError(msg, top)
        warnings.warn(msg, NotAtTrimWarning, stacklevel=2)
    heli = trim_result.helicopter
    x0, u0 = trim_result.x, trim_result.u
    hx = default_steps(heli, step_scale)
    n = heli.n_states
    a = np.empty((n, n))
    for j in range(n):
        e = np.zeros(n)
        e[j] = hx[j]
        a[:, j] = (heli.derivatives(x0 + e, u0) - heli.derivatives(x0 - e, u0)) / (2 * hx[j])
    m = len(u0)
    b = np.empty((n, m))
    for j in range(m):
        e = np.zeros(m)
        e[j] = control_step * step_scale
        b[:, j] = (heli.derivatives(x0, u0 + e) - heli.derivatives(x0, u0 - e)) / (2 * e[j])
    names = heli.input_names
    if inputs == "pilot":
        b = b @ mixing_matrix(heli.config)
        names = pilot_inputs(heli.config)
    sys = control.ss(a, b, np.eye(n), np.zeros((n, len(names))), states=heli.state_names,
                     inputs=list(names), outputs=list(heli.state_names), name="helicopter")
    sys.trim = trim_result
    return sys


def modes(sys, n_dominant=3) -> pd.DataFrame:
    """Pole table: pole, frequency [rad/s], damping, dominant states (participation factors).

    One row per real pole or complex pair (positive imaginary part shown).
    """
    if not isinstance(sys, control.StateSpace):
        raise LinearizeInputError(f"sys must be a control.StateSpace, got {type(sys).__name__}")
    if isinstance(n_dominant, bool) or not isinstance(n_dominant, (int, np.integer)) or n_dominant < 1:
        raise LinearizeInputError(f"n_dominant must be an integer >= 1, got {n_dominant!r}")
    a = np.asarray(sys.A)
    if a.size == 0 or not np.all(np.isfinite(a)):
        raise LinearizeInputError("sys.A must be a non-empty matrix of finite values")
    lam, right = np.linalg.eig(a)
    left = np.linalg.inv(right).T
    rows = []
    for k, l in enumerate(lam):
        if l.imag < -1e-9:
            continue
        part = np.abs(right[:, k] * left[:, k])
        part = part / part.sum() if part.sum() > 0 else part
        top = np.argsort(-part)[:n_dominant]
        wn = abs(l)
        rows.append({"pole": l, "real": l.real, "imag": l.imag, "frequency": wn,
                     "damping": -l.real / wn if wn > 0 else np.nan,
                     "dominant_states": ", ".join(f"{sys.state_labels[i]} ({part[i]:.2f})" for i in top)})
    return pd.DataFrame(rows).sort_values("frequency").reset_index(drop=True)
