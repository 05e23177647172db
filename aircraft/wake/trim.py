"""Trim of the free-vortex wake and marching with prescribed controls."""
from __future__ import annotations

import math
import numbers
import time
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from .._validation import integer as _integer, real as _real
from ..inflow.base import rotor_suffix
from .threads import single_threaded_blas
from .errors import WakeDivergedError

__all__ = ["WakeTrim", "WakeTrimError", "WakeInputError", "trim_wake", "run_wake"]


class WakeTrimError(RuntimeError):
    """The wake trim did not converge, diverged, or ran out of its iteration/time budget.

    ``result`` is the :class:`WakeTrim` reached (None when the trim could not
    start); ``residuals`` maps each trim equation to its last residual [-].
    """

    def __init__(self, message, result=None, residuals=None):
        super().__init__(message)
        self.result = result
        self.residuals = dict(residuals or {})


class WakeInputError(ValueError):
    """A trim_wake/run_wake argument is NaN, infinite, complex, of the wrong type or out of range."""


@dataclass
class WakeTrim:
    """Result of :func:`trim_wake`.

    Attributes
    ----------
    controls : dict
        Trimmed swashplate angles [rad] by canonical name.
    outputs : dict
        Loads, torque, inflow harmonics and flap rates averaged over the last
        revolution (canonical names; ``CQ`` torque coefficients included).
    converged : bool
    iterations : int
    residual : float
        Largest absolute load error [-] at the last iteration.
    history : list of dict
    fd_jacobians : int
        Finite-difference Jacobians measured (each ``revs_per_iter`` revolutions per
        unknown on top of the iterations); 0 with the blade-element estimate.
    lift_offset : tuple of float
        The lateral lift offset trimmed to, per rotor [-] (``C_L = -LOS C_T``).
    """

    controls: dict
    outputs: dict
    converged: bool
    iterations: int
    residual: float
    history: list = field(default_factory=list)
    fd_jacobians: int = 0
    lift_offset: tuple = ()

    def to_pandas(self):
        """History of the iterations as a DataFrame."""
        return pd.DataFrame(self.history)


def _targets(wake, ct, mode):
    names = [r.name for r in wake.rotors]
    cfg = wake.config
    if ct is None:
        ct = cfg.trim_ct if len(cfg.trim_ct) == len(names) else None
        if ct is None:
            raise WakeTrimError("no thrust target: pass ct= or set AircraftConfig.trim_ct")
    ct = np.atleast_1d(np.asarray(ct))
    if ct.ndim != 1 or np.iscomplexobj(ct) or not np.issubdtype(ct.dtype, np.number):
        raise WakeInputError(f"ct must be real thrust coefficient(s), got {ct!r}")
    ct = ct.astype(float)
    if not np.all(np.isfinite(ct)):
        raise WakeInputError(f"ct must be finite, got {ct}")
    if mode not in ("thrust", "torque_balance"):
        raise WakeInputError(f"mode must be 'thrust' or 'torque_balance', got {mode!r}")
    if mode == "torque_balance" and len(names) != 2:
        raise WakeInputError("mode='torque_balance' needs a coaxial (two-rotor) configuration")
    if mode == "thrust" and ct.size != len(names):
        raise WakeInputError(f"ct needs one value per rotor ({len(names)}), got {ct.size}")
    if mode == "torque_balance" and ct.size not in (1, 2):
        raise WakeInputError(f"ct for mode='torque_balance' needs one or two values, got {ct.size}")
    if np.any(ct <= 0):
        raise WakeInputError(f"thrust coefficient targets ct must be positive, got {ct}")
    _check_blade_loading(wake, ct, mode)
    return ct


#: largest blade loading C_T/sigma a trim is attempted at: the section lift is
#: clipped at the stall angle (12 deg, c_l = a alpha_s ~ 1.2), and a uniformly
#: loaded blade cannot exceed C_T/sigma = c_l,max / 6 ~ 0.2; 0.25 leaves margin
_MAX_BLADE_LOADING = 0.25


def _check_blade_loading(wake, ct, mode):
    """Refuse at once a thrust target no blade-element rotor can reach (C_T/sigma)."""
    per_rotor = ct if mode == "thrust" else np.full(len(wake.rotors), ct.sum() / len(wake.rotors))
    for c, rot in zip(per_rotor, wake.rotors):
        sigma = rot.nb * rot.chord / (math.pi * rot.R)
        cl_max = rot.a * rot.stall
        limit = min(_MAX_BLADE_LOADING, cl_max / 6.0 * 1.25)
        if c / sigma > limit:
            raise WakeTrimError(
                f"thrust target C_T = {c:.4g} on rotor {rot.name!r} is a blade loading "
                f"C_T/sigma = {c / sigma:.3g}, above the {limit:.3g} a blade stalling at "
                f"{math.degrees(rot.stall):.3g} deg can carry: the trim cannot converge",
                residuals={f"CT{rotor_suffix(rot.name)}": float(c)})


def _lift_offsets(wake, lift_offset):
    """One lift offset [-] per rotor from a number or a per-rotor sequence, each in [-0.5, 0.5]."""
    n = len(wake.rotors)
    if isinstance(lift_offset, (list, tuple, np.ndarray)):
        if len(lift_offset) != n:
            raise WakeInputError(f"lift_offset needs one value or one per rotor ({n}), got {len(lift_offset)}")
        items = list(lift_offset)
    else:
        items = [lift_offset] * n
    return tuple(_real(WakeInputError, "lift_offset", v, lo=-0.5, hi=0.5) for v in items)


def _residual_names(wake, mode, cyclic):
    names = [r.name for r in wake.rotors]
    if mode == "thrust":
        out = [f"CT{rotor_suffix(n)}" for n in names]
    else:
        out = ["CT_total", "CQ_difference"]
    if cyclic:
        for n in names:
            out += [f"CL{rotor_suffix(n)}", f"CM{rotor_suffix(n)}"]
    return out


def _residual(wake, out, ct, mode, cyclic, lift_offset=(0.0, 0.0)):
    res = []
    names = [r.name for r in wake.rotors]
    if mode == "thrust":
        for i, n in enumerate(names):
            res.append(out[f"CT{rotor_suffix(n)}"] - ct[i])
    else:
        su, sl = rotor_suffix(names[0]), rotor_suffix(names[1])
        res.append(out[f"CT{su}"] + out[f"CT{sl}"] - ct.sum())
        res.append(out[f"CQ{su}"] - out[f"CQ{sl}"])
    if cyclic:
        for n, los in zip(names, lift_offset):
            x = rotor_suffix(n)
            # lift offset: C_L = -LOS C_T puts the centre of lift LOS R towards the
            # advancing side (psi = 90 deg, where blade_sum_loads counts lift negative)
            res += [out[f"CL{x}"] + los * out[f"CT{x}"], out[f"CM{x}"]]
    return np.array(res)


def _unknowns(wake, cyclic):
    names = []
    for r in wake.rotors:
        names.append(f"theta0{rotor_suffix(r.name)}")
    if cyclic:
        for r in wake.rotors:
            names += [f"theta1s{rotor_suffix(r.name)}", f"theta1c{rotor_suffix(r.name)}"]
    return names


def _jacobian_estimate(wake, ct, mode, cyclic):
    """Blade-element/momentum estimate of d(residual)/d(controls) [1/rad]."""
    blocks = []
    for i, rot in enumerate(wake.rotors):
        sigma = rot.nb * rot.chord / (math.pi * rot.R)
        c = ct[i] if mode == "thrust" else ct.sum() / len(wake.rotors)
        lam = math.sqrt(c / 2.0)
        dct = (sigma * rot.a / 6.0) / (1.0 + sigma * rot.a / (16.0 * lam))
        blocks.append((dct, 1.5 * lam * dct, sigma * rot.a / 16.0))
    n = len(wake.rotors)
    J_col = np.zeros((n, n))
    for i, (dct, dcq, _) in enumerate(blocks):
        if mode == "thrust":
            J_col[i, i] = dct
        else:
            J_col[0, i] = dct
            J_col[1, i] = dcq if i == 0 else -dcq
    if not cyclic:
        return J_col
    J = np.zeros((3 * n, 3 * n))
    J[:n, :n] = J_col
    for i, (_, _, dcyc) in enumerate(blocks):
        # rigid hub: C_L = -sigma a theta1s / 16, C_M = -sigma a theta1c / 16
        J[n + 2 * i, n + 2 * i] = -dcyc
        J[n + 2 * i + 1, n + 2 * i + 1] = -dcyc
    return J


def _fd_jacobian(wake, names, ct, mode, cyclic, res0, start, n_steps, h, lift_offset):
    """One-sided finite-difference Jacobian d(residual)/d(controls) [1/rad] of the wake.

    ``res0`` is the residual of the ``n_steps`` march just made from the state
    ``start`` (a :meth:`~FreeVortexWake.snapshot`).  Each column repeats that march
    from ``start`` with one control moved by ``h``, so a column is the response of
    one trim iteration to a control change at its beginning (blades, near wake and
    free wake), and any transient already under way cancels in the difference.
    The wake is returned to its state on entry.
    """
    end = wake.snapshot()
    J = np.empty((res0.size, len(names)))
    for j, n in enumerate(names):
        wake.restore(start)
        wake.controls[n] += h
        J[:, j] = (_residual(wake, wake.march(n_steps), ct, mode, cyclic, lift_offset) - res0) / h
    wake.restore(end)
    return J


def trim_wake(wake, ct=None, *, mode="thrust", cyclic=None, settle_revs=3, revs_per_iter=2,
              tol=2e-5, max_iter=20, damping=0.8, update_jacobian=False, jacobian="auto",
              fd_step=math.radians(0.5), fd_refresh=math.radians(3.0), max_time=None,
              raise_on_failure=True, lift_offset=0.0):
    """Time-march the wake to a periodic state and adjust the controls to the targets.

    Parameters
    ----------
    wake : FreeVortexWake
    ct : float or sequence, optional
        Thrust-coefficient targets: one per rotor (``mode="thrust"``), or per rotor
        with only their sum used (``mode="torque_balance"``).  Default
        ``config.trim_ct``.
    mode : {"thrust", "torque_balance"}
        ``"torque_balance"`` (coaxial): total thrust and equal torques; the thrust
        split is the result.
    cyclic : bool, optional
        Also trim each rotor's cyclic to zero hub moments C_L = C_M = 0.  Default:
        True in forward flight, False in hover (axisymmetric).
    settle_revs : int
        Revolutions marched before the first update.
    revs_per_iter : int
        Revolutions averaged per iteration.
    tol : float
        Convergence tolerance on every residual [-].
    max_iter : int
    damping : float
        Fraction of the (quasi-)Newton step taken.
    update_jacobian : bool
        Broyden-update the blade-element Jacobian estimate from the iterates.  Off
        by default: the residuals carry the wake's chaotic blade-passage scatter
        (~0.5 % of C_T per revolution), and secant updates from differences of
        noisy residuals corrupt the Jacobian (residuals jumping 10x between
        iterations were measured); the fixed estimate converges steadily.
    jacobian : {"auto", "estimate", "fd"}
        ``"estimate"``: the hover blade-element/momentum estimate
        (:func:`_jacobian_estimate`; diagonal hub-moment blocks).  ``"fd"``: a
        finite-difference Jacobian measured on the wake itself (one extra
        ``revs_per_iter`` march per unknown, repeated from the state at the start
        of the iteration so the wake's own transient cancels).  ``"auto"``
        (default): the estimate in hover, ``"fd"`` in forward flight.  There the
        estimate misses the advancing/retreating-side coupling of collective and
        cyclic (dC_T/dtheta1s = 0.04 and dC_L/dtheta0 = -0.03 against a diagonal
        of 0.07 and -0.03 at mu = 0.47, measured) and, with the free stream flowing
        up through a disk tilted back, gets the coaxial torque-balance row wrong in
        sign and ~15x in size; the coaxial trim then drifted away at mu = 0.3 and
        oscillated with growing amplitude at mu = 0.54.  With ``"fd"`` a step
        larger than 2 deg is scaled down as a whole (its direction kept) instead
        of clipped per component.
    fd_step : float
        Control perturbation of the finite-difference Jacobian [rad].  The
        revolution-averaged residuals scatter by ~2e-5 at mu = 0.1 and < 2e-6
        from mu = 0.2 on (coarse wake), i.e. < 10 % of a column at 0.5 deg.
    fd_refresh : float
        With ``"fd"`` the Jacobian is measured again once any control has moved
        more than this from where it was last measured [rad], or when the largest
        residual more than doubled in one iteration (smaller growth can be the
        wake's scatter at low mu): the rigid-hub moments and torques are far from
        linear in the cyclic between zero and the ~9 deg of a mu = 0.54 trim
        (dC_Q/dtheta1s changed 25x, measured), and a Jacobian kept from the start
        drove the coaxial torque balance away.
    max_time : float, optional
        Wall-clock budget [s]; the trim stops (and fails) after the iteration
        that exceeds it.  None: only ``max_iter`` bounds it.
    raise_on_failure : bool
        Raise :class:`WakeTrimError` when the trim does not converge (default).
        False returns the unconverged :class:`WakeTrim` (``converged=False``)
        for inspection; :func:`~aircraft.wake.run_sweeps` refuses it either way.
    lift_offset : float or sequence of float
        Lateral lift offset LOS [-] (forward flight, ``cyclic`` trim), one for
        every rotor or one per rotor: rotor r is trimmed to a roll moment of
        LOS_r x thrust x R towards its advancing side (psi = 90 deg of its own
        frame), ``C_L = -LOS C_T`` in our sign convention, instead of zero;
        ``C_M`` stays zero. On a coaxial equal offsets cancel in the body axes
        (the advancing sides are opposite), as in §7.2's lift-offset trim.
        0 (default): moment-balanced rotors.

    Returns
    -------
    WakeTrim

    Raises
    ------
    WakeTrimError
        Not converged within ``max_iter`` iterations or ``max_time``, the residual
        became non-finite or the wake diverged, or the thrust target exceeds what
        the blades can carry (refused before marching).  ``.result`` holds the
        last :class:`WakeTrim`, ``.residuals`` the residual of each equation.
    WakeInputError
        An argument is NaN, infinite, complex or out of range.
    """
    e = WakeInputError
    settle_revs = _integer(e, "settle_revs", settle_revs, minimum=0)
    revs_per_iter = _integer(e, "revs_per_iter", revs_per_iter, minimum=1)
    max_iter = _integer(e, "max_iter", max_iter, minimum=1)
    tol = _real(e, "tol", tol, positive=True)
    damping = _real(e, "damping", damping, positive=True, hi=1.0)
    fd_step = _real(e, "fd_step", fd_step, positive=True, hi=math.radians(10.0), unit="rad")
    fd_refresh = _real(e, "fd_refresh", fd_refresh, positive=True, unit="rad")
    if max_time is not None:
        max_time = _real(e, "max_time", max_time, positive=True, unit="s")
    if cyclic is not None and not isinstance(cyclic, bool):
        raise e(f"cyclic must be True, False or None, got {cyclic!r}")
    lift_offset = _lift_offsets(wake, lift_offset)
    t_start = time.perf_counter()
    ct = _targets(wake, ct, mode)
    if cyclic is None:
        cyclic = wake.flight.speed > 1.0
    if any(lift_offset) and (not cyclic or wake.flight.speed <= 1.0):
        raise WakeInputError(
            f"lift_offset = {lift_offset} needs forward flight (an advancing side) and the cyclic "
            f"trim (cyclic=True); got speed {wake.flight.speed:g} m/s, cyclic={cyclic}")
    names = _unknowns(wake, cyclic)
    if jacobian == "auto":
        jacobian = "fd" if wake.flight.speed > 1.0 else "estimate"
    if jacobian not in ("estimate", "fd"):
        raise WakeInputError(f"jacobian must be 'auto', 'estimate' or 'fd', got {jacobian!r}")
    J = _jacobian_estimate(wake, ct, mode, cyclic) if jacobian == "estimate" else None
    nrev = wake.settings.steps_per_rev
    if all(abs(wake.controls[n]) < 1e-12 for n in names):
        for i, rot in enumerate(wake.rotors):
            sigma = rot.nb * rot.chord / (math.pi * rot.R)
            c = ct[i] if mode == "thrust" else ct.sum() / len(wake.rotors)
            if wake.flight.speed <= 1.0:
                # blade-element/momentum start: CT = sigma a / 2 (theta75 / 3 - lam / 2)
                lam = 1.15 * math.sqrt(c / 2.0)
                theta = 3.0 * (2.0 * c / (sigma * rot.a) + lam / 2.0)
            else:
                # forward flight: Glauert inflow lam = lam_i - mu_z, where the free
                # stream flows *up* through the disk tilted back (mu_z = V sin alpha /
                # Omega R), and CT = sigma a / 2 (theta75 (1/3 + mu^2/2) - lam / 2)
                mu = wake.flight.speed * math.cos(wake.flight.alpha) / (wake.omega * rot.R)
                mu_z = wake.flight.speed * math.sin(wake.flight.alpha) / (wake.omega * rot.R)
                lam = 1.15 * math.sqrt(c / 2.0)
                for _ in range(100):
                    lam = 0.5 * lam + 0.5 * (1.15 * c / (2.0 * math.hypot(mu, lam)) - mu_z)
                theta = 3.0 * (2.0 * c / (sigma * rot.a) + lam / 2.0) / (1.0 + 1.5 * mu ** 2)
            wake.controls[f"theta0{rotor_suffix(rot.name)}"] = theta
    res_names = _residual_names(wake, mode, cyclic)
    history = []
    x = np.array([wake.controls[n] for n in names])
    res_prev = x_prev = x_jac = None
    n_jacobians = 0
    converged = False
    out = None
    failure = None
    res = np.full(len(res_names), np.nan)
    try:
        if settle_revs:
            wake.march(settle_revs * nrev)
    except WakeDivergedError as err:
        failure = f"the wake diverged while settling ({err})"
    for it in range(1, max_iter + 1):
        if failure:
            break
        start = wake.snapshot() if jacobian == "fd" else None
        try:
            out = wake.march(revs_per_iter * nrev)
        except WakeDivergedError as err:
            failure = f"the wake diverged at iteration {it} ({err})"
            break
        res = _residual(wake, out, ct, mode, cyclic, lift_offset)
        history.append({**{n: wake.controls[n] for n in names}, **out,
                        "iteration": it, "residual": float(np.abs(res).max())})
        if not np.all(np.isfinite(res)):
            failure = f"the residual became non-finite at iteration {it}"
            break
        if np.abs(res).max() < tol:
            converged = True
            break
        if max_time is not None and time.perf_counter() - t_start > max_time:
            failure = f"the time budget max_time = {max_time:g} s ran out after {it} iterations"
            break
        # a trim running away (residual 30x its best for two iterations in a row)
        # will not come back within max_iter: stop instead of marching on
        worst_recent = min(h["residual"] for h in history[-2:])
        if it >= 4 and worst_recent > 30.0 * min(h["residual"] for h in history):
            failure = (f"the trim is diverging (residual {history[-1]['residual']:.3g} at "
                       f"iteration {it}, best {min(h['residual'] for h in history):.3g})")
            break
        if it == max_iter:
            break
        if jacobian == "fd" and (J is None or np.abs(x - x_jac).max() > fd_refresh
                                 or np.abs(res).max() > 2.0 * np.abs(res_prev).max()):
            J = _fd_jacobian(wake, names, ct, mode, cyclic, res, start, revs_per_iter * nrev,
                             fd_step, lift_offset)
            x_jac = x.copy()
            n_jacobians += 1
        if update_jacobian and res_prev is not None:
            # Broyden update of the Jacobian from the last step
            dx, dr = x - x_prev, res - res_prev
            if np.dot(dx, dx) > 0:
                J = J + np.outer(dr - J @ dx, dx) / np.dot(dx, dx)
        try:
            step = -np.linalg.solve(J, res)
        except np.linalg.LinAlgError:
            failure = f"the trim Jacobian became singular at iteration {it}"
            break
        if jacobian == "fd":
            big = np.abs(step).max()
            if big > math.radians(2.0):
                step = step * (math.radians(2.0) / big)
        else:
            step = np.clip(step, -math.radians(2.0), math.radians(2.0))
        x_prev, res_prev = x.copy(), res.copy()
        x = x + damping * step
        for n, v in zip(names, x):
            wake.controls[n] = float(v)
    result = WakeTrim(controls=dict(wake.controls), outputs=out or {}, converged=converged,
                      iterations=len(history),
                      residual=history[-1]["residual"] if history else float("nan"),
                      history=history, fd_jacobians=n_jacobians, lift_offset=lift_offset)
    residuals = {n: float(r) for n, r in zip(res_names, res)}
    if failure is None and not converged:
        failure = f"not converged in max_iter = {max_iter} iterations"
    if failure is not None:
        wake.trim_result = result
        if raise_on_failure or not history or not np.all(np.isfinite(res)):
            worst = ", ".join(f"{k} = {v:.3g}" for k, v in residuals.items())
            raise WakeTrimError(f"wake trim failed: {failure} (tol {tol:g}); residuals: {worst}. "
                                f"Controls reached: { {k: round(float(v), 5) for k, v in result.controls.items()} } rad",
                                result, residuals)
        # unconverged but finite: returned on request (converged=False) for
        # inspection; run_sweeps refuses to start from it
        wake._trim_state = wake.snapshot()
        return result
    wake._trim_state = wake.snapshot()
    wake.trim_result = result
    return result


def _control_function(spec, name):
    """A callable of time [s] from a float, a callable, or a (t, u) pair of arrays."""
    if callable(spec):
        def checked(t, _f=spec):
            v = _f(t)
            if isinstance(v, (bool, np.bool_)) or not isinstance(v, numbers.Real) \
                    and not (isinstance(v, np.ndarray) and v.ndim == 0 and np.isrealobj(v)):
                raise WakeInputError(f"control {name!r}: the callable returned {v!r} at t = {t:.4g} s; "
                                     "it must return a real number [rad]")
            if not math.isfinite(float(v)):
                raise WakeInputError(f"control {name!r}: the callable returned {v!r} at t = {t:.4g} s; "
                                     "it must return a finite angle [rad]")
            return float(v)
        return checked
    if isinstance(spec, tuple) and len(spec) == 2:
        tt, uu = np.asarray(spec[0]), np.asarray(spec[1])
        for label, arr in (("t", tt), ("u", uu)):
            if np.iscomplexobj(arr) or not np.issubdtype(arr.dtype, np.number):
                raise WakeInputError(f"control {name!r}: {label} must be a real array, got dtype {arr.dtype}")
        tt, uu = tt.astype(float), uu.astype(float)
        if tt.shape != uu.shape or tt.ndim != 1 or tt.size < 2 or np.any(np.diff(tt) <= 0):
            raise WakeInputError(f"control {name!r}: (t, u) must be 1-D arrays of equal length "
                                 "(>= 2) with increasing t [s]")
        if not (np.all(np.isfinite(tt)) and np.all(np.isfinite(uu))):
            raise WakeInputError(f"control {name!r}: (t, u) contain NaN or infinite values")
        return lambda t: float(np.interp(t, tt, uu, left=uu[0], right=uu[-1]))
    v = _real(WakeInputError, f"control {name!r}", spec, unit="rad")
    return lambda t: v


def run_wake(wake, controls=None, duration=1.0, *, points=None, about_trim=True, from_trim=True,
             progress=False):
    """March with prescribed swashplate histories and record the outputs.

    Parameters
    ----------
    wake : FreeVortexWake
    controls : dict, optional
        ``{name: float | callable(t) | (t_array, u_array)}`` [rad] for any of the
        canonical controls; others are held.  Names in
        ``wake.flap_input_names`` (``beta1s_U``, ``beta1c_U``, ...) prescribe the
        tip-path plane instead (rigid-flap wakes only, always perturbations about
        the trim flapping); their rate is the central difference of the history
        over one step, see :meth:`~FreeVortexWake.set_flap_inputs`.
    duration : float
        Simulated time [s].
    points : dict, optional
        ``{label: (x, y, z)}`` off-rotor points in body axes [m]; each adds columns
        ``vx_label, vy_label, vz_label`` (body axes, on the first rotor's Omega R).
    about_trim : bool
        If True the controls are perturbations added to the trimmed values.
    from_trim : bool
        If True (and a trim exists) start from the trimmed wake state.

    Returns
    -------
    pandas.DataFrame
        Columns ``t`` [s], controls [rad], ``CT/CL/CM/CQ``, ``lam0/lam1s/lam1c``,
        ``beta1s_dot/beta1c_dot`` [rad/s] per rotor, requested velocities.
    """
    controls = {} if controls is None else dict(controls)
    flap_names = list(getattr(wake, "flap_input_names", []))
    unknown = set(controls) - set(wake.control_names) - set(flap_names)
    if unknown:
        raise WakeInputError(f"unknown control names {sorted(unknown)}; have "
                             f"{wake.control_names + flap_names}")
    duration = _real(WakeInputError, "duration", duration, positive=True, unit="s")
    if duration / wake.dt > 10_000_000:
        raise WakeInputError(f"duration = {duration:g} s is {duration / wake.dt:.3g} wake steps; "
                             "check its unit [s]")
    if from_trim and wake._trim_state is not None:
        wake.restore(wake._trim_state)
    base = dict(wake.controls)
    funcs = {n: _control_function(v, n) for n, v in controls.items()}
    labels = list((points or {}).keys())
    pts = np.array([points[k] for k in labels])
    if np.iscomplexobj(pts) or (pts.size and not np.issubdtype(pts.dtype, np.number)):
        raise WakeInputError(f"points must be real (x, y, z) coordinates [m], got {points!r}")
    if pts.size and (pts.shape != (len(labels), 3) or not np.all(np.isfinite(pts))):
        raise WakeInputError(f"points must map labels to three finite coordinates (x, y, z) [m], "
                             f"got {points!r}")
    pts = pts.astype(float).reshape(-1, 3)
    tip_speed = wake.omega * wake.rotors[0].R
    n_steps = int(math.ceil(duration / wake.dt - 1e-9))
    t0 = wake.t
    rows = []
    it = range(n_steps)
    if progress:
        from tqdm.auto import tqdm
        it = tqdm(it, desc="wake run", leave=False)

    def record():
        row = {"t": wake.t - t0}
        row.update({n: wake.controls[n] for n in wake.control_names})
        row.update(wake.current_outputs())
        if labels:
            v = wake.induced_velocity(pts) / tip_speed
            for k, lab in enumerate(labels):
                row[f"vx_{lab}"], row[f"vy_{lab}"], row[f"vz_{lab}"] = v[k]
        rows.append(row)

    record()
    with single_threaded_blas():
        for _ in it:
            tn = wake.t + wake.dt - t0
            for n in wake.control_names:
                if n in funcs:
                    u = funcs[n](tn)
                    wake.controls[n] = base[n] + u if about_trim else u
            flap = [n for n in flap_names if n in funcs]
            if flap:
                h = 0.5 * wake.dt
                wake.set_flap_inputs({n: funcs[n](tn) for n in flap},
                                     {n: (funcs[n](tn + h) - funcs[n](tn - h)) / wake.dt
                                      for n in flap})
            wake.step()
            record()
    return pd.DataFrame(rows)
