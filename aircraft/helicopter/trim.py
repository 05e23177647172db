"""Trim: the nonlinear algebraic force/moment, flap and inflow equilibrium.

Hover: unknowns are the four pilot controls (collective, longitudinal, lateral,
pedal), roll and pitch attitude, the flap MBC displacements and the inflow
states; every acceleration, flap acceleration and inflow derivative is zero.
Forward flight (speed > 0): the pitch attitude is set by the target rotor angle
of attack (shaft normal to body x), and the propeller control replaces it as
an unknown.  The coaxial's differential cyclics are fixed: zero longitudinal
difference and a chosen lateral difference (lift offset), as in §7.2.
Solved with scipy's Levenberg-Marquardt then Newton polishing to |residual| <
``tol`` (scaled: body accelerations in SI, flap accelerations / Omega^2, inflow
derivatives / Omega).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy.optimize import least_squares

from .mixing import PILOT_INPUTS, mixing_matrix
from .model import Helicopter

__all__ = ["TrimCondition", "TrimResult", "TrimError", "trim"]


class TrimError(RuntimeError):
    """Trim failed; ``residuals`` names the equations that are not satisfied."""

    def __init__(self, message, residuals=None):
        super().__init__(message)
        self.residuals = residuals


@dataclass(frozen=True)
class TrimCondition:
    """speed [m/s] (level flight), rotor_aoa [rad] (forward flight, shaft angle to the
    flight path, positive nose up), lateral_cyclic_difference [rad]: the
    differential cyclic held fixed at trim to set the lift offset (§7.2; the same
    own-frame theta1c on both rotors, see ``_controls``)."""

    speed: float = 0.0
    rotor_aoa: float = np.radians(2.0)
    lateral_cyclic_difference: float = 0.0

    def __post_init__(self):
        if self.speed < 0:
            raise ValueError(f"speed must be >= 0 m/s, got {self.speed}")


@dataclass
class TrimResult:
    """Trimmed state ``x``, rotor controls ``u``, pilot controls, residuals and loads."""

    helicopter: Helicopter
    condition: TrimCondition
    x: np.ndarray
    u: np.ndarray
    pilot: np.ndarray
    residual: np.ndarray
    loads: dict

    @property
    def max_residual(self):
        return float(np.max(np.abs(self.residual)))

    def to_pandas(self) -> pd.DataFrame:
        h = self.helicopter
        rows = [("state", n, v) for n, v in zip(h.state_names, self.x)]
        rows += [("control", n, v) for n, v in zip(h.input_names, self.u)]
        if h.config.is_coaxial:
            rows += [("pilot", n, v) for n, v in zip(PILOT_INPUTS, self.pilot)]
        rows += [("load", k, float(v)) for k, v in self.loads.items() if np.isscalar(v)]
        return pd.DataFrame(rows, columns=["kind", "name", "value"])


def _controls(heli, pilot, condition):
    if heli.config.is_coaxial:
        u = mixing_matrix() @ pilot
        # differential (lift-offset) cyclic: the same own-frame theta1c on both
        # rotors. Each rotor then loads the same side of its own azimuth, which in
        # body axes are opposite sides, so the roll moments cancel (lift offset).
        # Equal/opposite own-frame theta1c is the lateral stick, equal theta1s the
        # longitudinal stick (mixing.py), so this input is orthogonal to both.
        u[2] += condition.lateral_cyclic_difference / 2
        u[5] += condition.lateral_cyclic_difference / 2
        return u
    return np.asarray(pilot, float)


def trim(heli: Helicopter, condition=TrimCondition(), tol=1e-9, max_iter=30) -> TrimResult:
    """Trim ``heli`` at ``condition``; raise :class:`TrimError` naming the residuals if it fails."""
    cfg = heli.config
    # an inflow model frozen at an earlier trim (ClimbingLowerRotor holds its
    # climb there) must be released first, or this trim inherits that condition
    heli.inflow.release_trim()
    nin = len(heli.inflow.state_names)
    nrot = len(heli.rotors)
    forward = condition.speed > 0
    coax = cfg.is_coaxial
    # initial guess: momentum inflow, collective from thrust, flap coning from thrust
    x0 = np.zeros(heli.n_states)
    w_share = cfg.weight / nrot
    loads0 = []
    for rm in heli.rotors:
        ct = w_share / rm.scale_t
        loads0 += [ct, 0.0, 0.0]
    from ..inflow.base import RotorOperatingPoint
    ops0 = tuple(RotorOperatingPoint(omega=rm.config.omega) for rm in heli.rotors)
    xin0 = heli.inflow.steady_state(np.array(loads0), ops0)
    rc = heli.rotors[0].config
    ct0 = loads0[0]
    theta75 = 6 * ct0 / (rc.solidity * rc.lift_slope) + 1.5 * np.sqrt(ct0 / 2)
    th0 = theta75 - 0.75 * rc.twist
    pilot0 = np.array([th0, 0.0, 0.0, 0.0, 0.0]) if coax else np.array([th0, 0.0, 0.0, 0.0])
    if coax:
        pilot0[0] = th0    # delta_col = K (th0 + th0) = th0 for K = 0.5
    att0 = np.array([0.0, 0.0])

    def unpack(z):
        i = 0
        pilot = pilot0.copy()
        if coax:
            pilot[0:4] = z[0:4]
            i = 4
            if forward:
                pilot[4] = z[i]
                i += 1
        else:
            pilot[0:4] = z[0:4]
            i = 4
        phi = z[i]
        i += 1
        if forward:
            theta = condition.rotor_aoa
        else:
            theta = z[i]
            i += 1
        x = np.zeros(heli.n_states)
        for k in range(nrot):
            x[9 + 8 * k:9 + 8 * k + 4] = z[i:i + 4]
            i += 4
        x[heli.n_rigid:] = z[i:i + nin]
        x[6], x[7] = phi, theta
        if forward:
            x[0] = condition.speed * np.cos(theta)
            x[2] = condition.speed * np.sin(theta)
        return x, pilot

    scale = np.ones(heli.n_states)
    for k, rm in enumerate(heli.rotors):
        scale[9 + 8 * k:9 + 8 * k + 8] = rm.config.omega ** 2
    scale[heli.n_rigid:] = rc.omega

    def residual(z):
        x, pilot = unpack(z)
        xdot = heli.derivatives(x, _controls(heli, pilot, condition))
        res = xdot / scale
        keep = list(range(6)) + [9 + 8 * k + 4 + j for k in range(nrot) for j in range(4)] \
            + list(range(heli.n_rigid, heli.n_states))
        return res[keep]

    z0 = list(pilot0[:4])
    if coax and forward:
        z0.append(0.1)
    z0.append(att0[0])
    if not forward:
        z0.append(att0[1])
    for k in range(nrot):
        z0 += [0.02, 0.0, 0.0, 0.0]
    z0 += list(xin0)
    z0 = np.array(z0, float)
    if len(residual(z0)) != len(z0):
        raise TrimError(f"trim problem is not square: {len(residual(z0))} equations, {len(z0)} unknowns")
    sol = least_squares(residual, z0, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=4000)
    z = sol.x
    # Newton polishing with a central-difference Jacobian
    for _ in range(max_iter):
        r = residual(z)
        if np.max(np.abs(r)) < tol:
            break
        jac = np.empty((r.size, z.size))
        for j in range(z.size):
            h = 1e-7 * max(1.0, abs(z[j]))
            e = np.zeros_like(z)
            e[j] = h
            jac[:, j] = (residual(z + e) - residual(z - e)) / (2 * h)
        z = z - np.linalg.lstsq(jac, r, rcond=None)[0]
    r = residual(z)
    x, pilot = unpack(z)
    u = _controls(heli, pilot, condition)
    if not np.all(np.isfinite(r)) or np.max(np.abs(r)) > tol:
        names = ["udot", "vdot", "wdot", "pdot", "qdot", "rdot"] + \
            [f"flap_accel_{i}" for i in range(4 * nrot)] + list(heli.inflow.state_names)
        worst = {names[i]: float(r[i]) for i in np.argsort(-np.abs(r))[:5]}
        raise TrimError(f"trim did not converge (max residual {np.max(np.abs(r)):.3g} > {tol}); "
                        f"largest residuals: {worst}", worst)
    _, extra = heli.evaluate(x, u)
    loads = {n: float(v) for n, v in zip(heli.inflow.load_names, extra["loads"])}
    loads.update({k: float(v) for k, v in extra.items() if k.startswith(("torque", "CQ"))})
    heli.inflow.set_trim(x[heli.n_rigid:], extra["loads"], extra["ops"])
    return TrimResult(heli, condition, x, u, pilot, r, loads)
