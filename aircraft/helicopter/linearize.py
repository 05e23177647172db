"""Linearisation by central differences (Appendix A) and the modes table."""
from __future__ import annotations

import control
import numpy as np
import pandas as pd

from .mixing import PILOT_INPUTS, mixing_matrix

__all__ = ["linearize", "modes", "default_steps"]


def default_steps(heli, scale=1.0):
    """Absolute perturbation per state [SI]: velocities 1e-3 m/s, rates 1e-4 rad/s,
    angles 1e-4 rad, flap 1e-5 rad, flap rates 1e-4 rad/s, inflow 1e-6; times ``scale``."""
    h = np.empty(heli.n_states)
    h[0:3], h[3:6], h[6:9] = 1e-3, 1e-4, 1e-4
    for k in range(len(heli.rotors)):
        h[9 + 8 * k:9 + 8 * k + 4] = 1e-5
        h[9 + 8 * k + 4:9 + 8 * k + 8] = 1e-4
    h[heli.n_rigid:] = 1e-6
    return h * scale


def linearize(trim_result, inputs="pilot", step_scale=1.0, control_step=1e-5):
    """Linear model about a trim: named :class:`control.StateSpace`, outputs = states.

    Parameters
    ----------
    trim_result : TrimResult
    inputs : ``"pilot"`` (delta_col, delta_lon, delta_lat, delta_ped, delta_prop via
        Eq. 7.19 mixing; coaxial only) or ``"rotor"`` (the rotor controls).
    step_scale : float
        Multiplies the default perturbation sizes (convergence checks).
    control_step : float
        Perturbation of the rotor controls [rad].

    The averaged (time-invariant) rotor model makes one linearisation exact for
    the whole revolution. The trim is attached as ``sys.trim``.
    """
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
        if not heli.config.is_coaxial:
            raise ValueError("pilot inputs (Eq. 7.19) are defined for the coaxial; use inputs='rotor'")
        b = b @ mixing_matrix()
        names = PILOT_INPUTS
    elif inputs != "rotor":
        raise ValueError(f"inputs must be 'pilot' or 'rotor', got {inputs!r}")
    sys = control.ss(a, b, np.eye(n), np.zeros((n, len(names))), states=heli.state_names,
                     inputs=list(names), outputs=list(heli.state_names), name="helicopter")
    sys.trim = trim_result
    return sys


def modes(sys, n_dominant=3) -> pd.DataFrame:
    """Pole table: pole, frequency [rad/s], damping, dominant states (participation factors).

    One row per real pole or complex pair (positive imaginary part shown).
    """
    a = np.asarray(sys.A)
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
