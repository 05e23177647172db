"""Trim: the nonlinear algebraic force/moment, flap and inflow equilibrium.

Hover: unknowns are the four pilot controls (collective, longitudinal, lateral,
pedal), roll and pitch attitude, the flap MBC displacements and the inflow
states; every acceleration, flap acceleration and inflow derivative is zero.
Forward flight (speed > 0) of the compound: the pitch attitude is set by the
target rotor angle of attack (shaft normal to body x), and the propeller control
replaces it as an unknown. A single-rotor aircraft keeps its pitch attitude as an
unknown at every speed (``rotor_aoa`` is not used): the same 4 controls, 2
attitudes, flap and inflow states balance the same equations from hover up.  The coaxial's differential cyclics are fixed: zero longitudinal
difference and a chosen lateral difference (lift offset), as in §7.2.
Solved with scipy's Levenberg-Marquardt then Newton polishing to |residual| <
``tol`` (scaled: body accelerations in SI, flap accelerations / Omega^2, inflow
derivatives / Omega).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy.optimize import least_squares

from .._validation import integer as _integer, real as _real
from ..inflow.pitt_peters import InflowError
from .mixing import lateral_cyclic_difference_controls, mixing_matrix, pilot_inputs
from .model import Helicopter

__all__ = ["TrimCondition", "TrimResult", "TrimError", "TrimInputError", "trim"]

#: largest blade loading C_T/sigma a trim is attempted at: sections stall at
#: ``stall_angle`` (c_l,max = a alpha_s ~ 1.2 at 12 deg), and a uniformly loaded
#: blade then carries at most C_T/sigma = c_l,max / 6 ~ 0.2; 25 % margin above it
_STALL_MARGIN = 1.25


class TrimError(RuntimeError):
    """Trim failed; ``residuals`` names the equations that are not satisfied."""

    def __init__(self, message, residuals=None):
        super().__init__(message)
        self.residuals = residuals


class TrimInputError(ValueError):
    """A trim argument (condition, tolerance, budget) is NaN, infinite, complex or out of range."""


class _BudgetExceeded(Exception):
    """Internal: the trim's wall-clock budget ran out inside the solver."""


@dataclass(frozen=True)
class TrimCondition:
    """speed [m/s] (level flight), rotor_aoa [rad] (compound in forward flight, shaft angle to the
    flight path, positive nose up), lateral_cyclic_difference [rad]: the
    differential lateral cyclic held fixed at trim to set the lift offset (§7.2), paired
    with the aircraft's control phase like the lateral stick: positive moves each
    rotor's lift towards its own advancing side
    (:func:`aircraft.helicopter.mixing.lateral_cyclic_difference_controls`)."""

    speed: float = 0.0
    rotor_aoa: float = np.radians(2.0)
    lateral_cyclic_difference: float = 0.0

    def __post_init__(self):
        _real(TrimInputError, "TrimCondition.speed", self.speed, nonnegative=True, hi=200.0, unit="m/s")
        _real(TrimInputError, "TrimCondition.rotor_aoa", self.rotor_aoa, lo=-math.pi / 6,
              hi=math.pi / 6, unit="rad")
        _real(TrimInputError, "TrimCondition.lateral_cyclic_difference",
              self.lateral_cyclic_difference, lo=-math.pi / 6, hi=math.pi / 6, unit="rad")


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
        rows += [("pilot", n, v) for n, v in zip(pilot_inputs(h.config), self.pilot)]
        rows += [("load", k, float(v)) for k, v in self.loads.items() if np.isscalar(v)]
        return pd.DataFrame(rows, columns=["kind", "name", "value"])


def _controls(heli, pilot, condition):
    """Rotor controls of the pilot inputs (mixing with the aircraft's control phase), plus the
    coaxial's differential lateral cyclic (lift-offset control), paired the same way."""
    u = mixing_matrix(heli.config) @ pilot
    if heli.config.is_coaxial and condition.lateral_cyclic_difference:
        u = u + lateral_cyclic_difference_controls(heli.config, condition.lateral_cyclic_difference)
    return u


def _pedal_guess(cfg, ct, rc):
    """Pedal of a hover trim estimate: tail-rotor thrust from the main rotor's momentum
    torque (induced power with 15 % losses plus profile power), collective from
    blade-element momentum theory at 3/4 radius, through the pedal sign of the mixing."""
    from .mixing import mixing_matrix
    tr = cfg.tail_rotor
    cq = 1.15 * ct ** 1.5 / np.sqrt(2.0) + rc.solidity * rc.cd0 / 8
    torque = cq * rc.thrust_scale(cfg.rho) * rc.radius
    ct_tr = torque / abs(tr.position[0]) / (cfg.rho * tr.disk_area * tr.tip_speed ** 2)
    theta_tr = 6 * ct_tr / (tr.solidity * tr.lift_slope) + 1.5 * np.sqrt(ct_tr / 2)
    return theta_tr / mixing_matrix(cfg)[3, 3]


def _start_from(heli, start, coax, forward, nrot, nin, size):
    """Unknowns of the trim problem taken from an earlier trim of the same helicopter."""
    if not isinstance(start, TrimResult) or start.helicopter is not heli:
        raise TrimInputError("start must be a TrimResult of this same Helicopter, got "
                             f"{type(start).__name__}")
    z = list(start.pilot[:4])
    if coax and forward:
        z.append(start.pilot[4])
    z.append(start.x[6])
    if not (coax and forward):
        z.append(start.x[7])
    for k in range(nrot):
        z += list(start.x[9 + 8 * k:9 + 8 * k + 4])
    z += list(start.x[heli.n_rigid:heli.n_rigid + nin])
    z = np.array(z, float)
    if z.size != size:
        raise TrimInputError(f"start has {z.size} trim unknowns, this trim {size}")
    return z


def _check_blade_loading(heli):
    """Refuse at once a weight no rotor of this aircraft can carry (C_T/sigma vs stall)."""
    share = heli.config.weight / len(heli.rotors)
    for rm in heli.rotors:
        rc = rm.config
        ct = share / rm.scale_t
        limit = rc.lift_slope * rc.stall_angle / 6.0 * _STALL_MARGIN
        if ct / rc.solidity > limit:
            raise TrimError(
                f"no trim: carrying the weight ({heli.config.weight:.4g} N) needs a blade loading "
                f"C_T/sigma = {ct / rc.solidity:.3g} on rotor {rc.name!r}, above the {limit:.3g} its "
                f"blades can reach before stalling at {math.degrees(rc.stall_angle):.3g} deg "
                f"(C_T = {ct:.4g}, sigma = {rc.solidity:.4g}); reduce the mass or enlarge the rotor",
                {"CT_required": float(ct), "CT_over_sigma": float(ct / rc.solidity)})


def trim(heli: Helicopter, condition=TrimCondition(), tol=1e-9, max_iter=30, *, max_nfev=None,
         max_time=60.0, start=None) -> TrimResult:
    """Trim ``heli`` at ``condition``; raise :class:`TrimError` naming the residuals if it fails.

    Parameters
    ----------
    heli : Helicopter
    condition : TrimCondition
    tol : float
        Convergence tolerance on every scaled residual (body accelerations [SI],
        flap accelerations / Omega^2, inflow derivatives / Omega).
    max_iter : int
        Newton polishing iterations after Levenberg-Marquardt (>= 1).
    max_nfev : int, optional
        Model evaluations (:meth:`Helicopter.derivatives` calls, finite-difference
        Jacobians included) allowed to the whole trim; default ``50 (n + 1)`` for
        ``n`` unknowns, ~1,000 (trims that converge use 70-250, measured).
    max_time : float or None
        Wall-clock budget [s] of the whole trim; None: only the evaluation
        budgets bound it.
    start : TrimResult, optional
        A trim of the same helicopter to start from (its controls, attitudes,
        flap and inflow states), e.g. the neighbouring speed of a sweep; default:
        a momentum-theory estimate.

    Raises
    ------
    TrimError
        No trim within the budgets (message and ``.residuals``: the largest
        residuals by equation), or a weight the blades cannot carry (refused
        before solving).
    TrimInputError
        A bad argument.

    Examples
    --------
    >>> from aircraft import coaxial_compound
    >>> from aircraft.helicopter import Helicopter, TrimCondition, linearize, trim
    >>> from aircraft.inflow import DynamicClimb
    >>> hover = trim(Helicopter(coaxial_compound(), DynamicClimb()), TrimCondition(speed=0.0))
    >>> bool(hover.max_residual < 1e-8), round(hover.loads["CT_U"] / hover.loads["CT_L"], 2)
    (True, 1.14)
    """
    if not isinstance(heli, Helicopter):
        raise TrimInputError(f"heli must be a Helicopter, got {type(heli).__name__}")
    if not isinstance(condition, TrimCondition):
        raise TrimInputError(f"condition must be a TrimCondition, got {type(condition).__name__}")
    tol = _real(TrimInputError, "tol", tol, positive=True)
    max_iter = _integer(TrimInputError, "max_iter", max_iter, minimum=1)
    if max_nfev is not None:
        max_nfev = _integer(TrimInputError, "max_nfev", max_nfev, minimum=1)
    if max_time is not None:
        max_time = _real(TrimInputError, "max_time", max_time, positive=True, unit="s")
    _check_blade_loading(heli)
    t_start = time.perf_counter()
    cfg = heli.config
    # an inflow model frozen at an earlier trim (ClimbingLowerRotor holds its
    # climb there) must be released first, or this trim inherits that condition
    heli.inflow.release_trim()
    nin = len(heli.inflow.state_names)
    nrot = len(heli.rotors)
    forward = condition.speed > 0
    coax = cfg.is_coaxial
    # initial guess: momentum inflow, collective from thrust, flap coning from thrust
    w_share = cfg.weight / nrot
    loads0 = []
    for rm in heli.rotors:
        ct = w_share / rm.scale_t
        loads0 += [ct, 0.0, 0.0]
    from ..inflow.base import RotorOperatingPoint
    ops0 = tuple(RotorOperatingPoint(omega=rm.config.omega) for rm in heli.rotors)
    try:
        xin0 = heli.inflow.steady_state(np.array(loads0), ops0)
    except InflowError as err:
        raise TrimError(f"no trim start: the inflow model has no steady state at the weight's "
                        f"thrust ({err})") from err
    rc = heli.rotors[0].config
    ct0 = loads0[0]
    theta75 = 6 * ct0 / (rc.solidity * rc.lift_slope) + 1.5 * np.sqrt(ct0 / 2)
    th0 = theta75 - 0.75 * rc.twist
    pilot0 = np.array([th0, 0.0, 0.0, 0.0, 0.0]) if coax else np.array([th0, 0.0, 0.0, 0.0])
    if coax:
        pilot0[0] = th0    # delta_col = K (th0 + th0) = th0 for K = 0.5
    elif cfg.tail_rotor is not None:
        pilot0[3] = _pedal_guess(cfg, ct0, rc)
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
        if forward and coax:
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

    keep = list(range(6)) + [9 + 8 * k + 4 + j for k in range(nrot) for j in range(4)] \
        + list(range(heli.n_rigid, heli.n_states))
    refused = {"count": 0, "last": None}
    evaluations = {"n": 0, "budget": None}

    def residual(z):
        x, pilot = unpack(z)
        xdot = heli.derivatives(x, _controls(heli, pilot, condition))
        return (xdot / scale)[keep]

    def guarded(z):
        # the solver may probe states outside the inflow model's domain (flow up
        # through the disk): a large residual there makes it step back instead of
        # dying with the inflow model's error; a spent budget stops it
        if max_time is not None and time.perf_counter() - t_start > max_time:
            raise _BudgetExceeded(f"the time budget max_time = {max_time:g} s ran out")
        evaluations["n"] += 1
        if evaluations["budget"] is not None and evaluations["n"] > evaluations["budget"]:
            raise _BudgetExceeded(f"the evaluation budget max_nfev = {evaluations['budget']} ran out")
        try:
            r = residual(z)
        except InflowError as err:
            refused["count"] += 1
            refused["last"] = str(err)
            return np.full(len(keep), 1e3)
        if not np.all(np.isfinite(r)):
            refused["count"] += 1
            refused["last"] = "non-finite state derivatives"
            return np.full(len(keep), 1e3)
        return r

    z0 = list(pilot0[:4])
    if coax and forward:
        z0.append(0.1)
    z0.append(att0[0])
    if not (forward and coax):
        z0.append(att0[1])
    for k in range(nrot):
        z0 += [0.02, 0.0, 0.0, 0.0]
    z0 += list(xin0)
    z0 = np.array(z0, float)
    if start is not None:
        z0 = _start_from(heli, start, coax, forward, nrot, nin, z0.size)
    if len(residual(z0)) != len(z0):
        raise TrimError(f"trim problem is not square: {len(residual(z0))} equations, {len(z0)} unknowns")
    names = ["udot", "vdot", "wdot", "pdot", "qdot", "rdot"] + \
        [f"flap_accel_{i}" for i in range(4 * nrot)] + list(heli.inflow.state_names)

    def fail(why, z):
        try:
            r = residual(z)
        except InflowError:
            r = np.full(len(keep), np.nan)
        worst = {names[i]: float(r[i]) for i in np.argsort(-np.abs(r))[:5]} \
            if np.all(np.isfinite(r)) else {}
        extra = ""
        if refused["count"]:
            extra = (f"; the inflow model refused {refused['count']} trial state(s), last: "
                     f"{refused['last']}")
        size = f"max residual {np.max(np.abs(r)):.3g} > {tol:g}" if worst else "residual undefined there"
        raise TrimError(f"trim did not converge: {why} ({size}, {time.perf_counter() - t_start:.1f} s); "
                        f"largest residuals: {worst}{extra}", worst)

    n_unknowns = z0.size
    budget = max_nfev if max_nfev is not None else 50 * (n_unknowns + 1)
    evaluations["budget"] = budget
    best_z = {"z": z0, "r": np.inf}

    def tracked(z):
        r = guarded(z)
        if np.max(np.abs(r)) < best_z["r"]:
            best_z["z"], best_z["r"] = np.array(z, float), float(np.max(np.abs(r)))
        return r

    try:
        sol = least_squares(tracked, z0, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15,
                            max_nfev=budget)
    except _BudgetExceeded as why:
        fail(f"{why} in Levenberg-Marquardt", best_z["z"])
    z = sol.x
    # Newton polishing with a central-difference Jacobian; it stops when it
    # stalls (three steps without halving the residual) instead of running on
    stalled = 0
    try:
        best = np.max(np.abs(guarded(z)))
        for _ in range(max_iter):
            r = guarded(z)
            if np.max(np.abs(r)) < tol or stalled >= 3:
                break
            jac = np.empty((r.size, z.size))
            for j in range(z.size):
                h = 1e-7 * max(1.0, abs(z[j]))
                e = np.zeros_like(z)
                e[j] = h
                jac[:, j] = (guarded(z + e) - guarded(z - e)) / (2 * h)
            z = z - np.linalg.lstsq(jac, r, rcond=None)[0]
            now = np.max(np.abs(guarded(z)))
            stalled = stalled + 1 if now > 0.5 * best else 0
            best = min(best, now)
    except _BudgetExceeded as why:
        fail(f"{why} in Newton polishing", best_z["z"])
    try:
        r = residual(z)
    except InflowError as err:
        fail(f"the last iterate is outside the inflow model's domain ({err}); residuals at the "
             "best iterate", best_z["z"])
    x, pilot = unpack(z)
    u = _controls(heli, pilot, condition)
    if not np.all(np.isfinite(r)) or np.max(np.abs(r)) > tol:
        fail(f"no solution within {evaluations['n']} model evaluations (budget {budget}) and "
             f"{max_iter} Newton steps", z)
    _, extra = heli.evaluate(x, u)
    loads = {n: float(v) for n, v in zip(heli.inflow.load_names, extra["loads"])}
    loads.update({k: float(v) for k, v in extra.items() if k.startswith(("torque", "CQ"))})
    heli.inflow.set_trim(x[heli.n_rigid:], extra["loads"], extra["ops"])
    return TrimResult(heli, condition, x, u, pilot, r, loads)
