"""Trim of the free-vortex wake and marching with prescribed controls."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..inflow.base import rotor_suffix
from .threads import single_threaded_blas

__all__ = ["WakeTrim", "WakeTrimError", "trim_wake", "run_wake"]


class WakeTrimError(RuntimeError):
    """Raised when the wake trim does not converge."""


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
    """

    controls: dict
    outputs: dict
    converged: bool
    iterations: int
    residual: float
    history: list = field(default_factory=list)
    fd_jacobians: int = 0

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
    ct = np.atleast_1d(np.asarray(ct, dtype=float))
    if mode not in ("thrust", "torque_balance"):
        raise ValueError(f"mode must be 'thrust' or 'torque_balance', got {mode!r}")
    if mode == "torque_balance" and len(names) != 2:
        raise ValueError("mode='torque_balance' needs a coaxial (two-rotor) configuration")
    if mode == "thrust" and ct.size != len(names):
        raise ValueError(f"ct needs one value per rotor ({len(names)}), got {ct.size}")
    if np.any(ct <= 0):
        raise ValueError("thrust coefficient targets must be positive")
    return ct


def _residual(wake, out, ct, mode, cyclic):
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
        for n in names:
            res += [out[f"CL{rotor_suffix(n)}"], out[f"CM{rotor_suffix(n)}"]]
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


def _fd_jacobian(wake, names, ct, mode, cyclic, res0, start, n_steps, h):
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
        J[:, j] = (_residual(wake, wake.march(n_steps), ct, mode, cyclic) - res0) / h
    wake.restore(end)
    return J


def trim_wake(wake, ct=None, *, mode="thrust", cyclic=None, settle_revs=3, revs_per_iter=2,
              tol=2e-5, max_iter=20, damping=0.8, update_jacobian=False, jacobian="auto",
              fd_step=math.radians(0.5), fd_refresh=math.radians(3.0)):
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

    Returns
    -------
    WakeTrim
    """
    ct = _targets(wake, ct, mode)
    if cyclic is None:
        cyclic = wake.flight.speed > 1.0
    names = _unknowns(wake, cyclic)
    if jacobian == "auto":
        jacobian = "fd" if wake.flight.speed > 1.0 else "estimate"
    if jacobian not in ("estimate", "fd"):
        raise ValueError(f"jacobian must be 'auto', 'estimate' or 'fd', got {jacobian!r}")
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
    wake.march(settle_revs * nrev)
    history = []
    x = np.array([wake.controls[n] for n in names])
    res_prev = x_prev = x_jac = None
    n_jacobians = 0
    converged = False
    out = None
    for it in range(1, max_iter + 1):
        start = wake.snapshot() if jacobian == "fd" else None
        out = wake.march(revs_per_iter * nrev)
        res = _residual(wake, out, ct, mode, cyclic)
        history.append({**{n: wake.controls[n] for n in names}, **out,
                        "iteration": it, "residual": float(np.abs(res).max())})
        if np.abs(res).max() < tol:
            converged = True
            break
        if jacobian == "fd" and (J is None or np.abs(x - x_jac).max() > fd_refresh
                                 or np.abs(res).max() > 2.0 * np.abs(res_prev).max()):
            J = _fd_jacobian(wake, names, ct, mode, cyclic, res, start, revs_per_iter * nrev,
                             fd_step)
            x_jac = x.copy()
            n_jacobians += 1
        if update_jacobian and res_prev is not None:
            # Broyden update of the Jacobian from the last step
            dx, dr = x - x_prev, res - res_prev
            if np.dot(dx, dx) > 0:
                J = J + np.outer(dr - J @ dx, dx) / np.dot(dx, dx)
        step = -np.linalg.solve(J, res)
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
    result = WakeTrim(controls=dict(wake.controls), outputs=out, converged=converged,
                      iterations=len(history), residual=history[-1]["residual"], history=history,
                      fd_jacobians=n_jacobians)
    wake._trim_state = wake.snapshot()
    wake.trim_result = result
    return result


def _control_function(spec, name):
    """A callable of time [s] from a float, a callable, or a (t, u) pair of arrays."""
    if callable(spec):
        return spec
    if isinstance(spec, tuple) and len(spec) == 2:
        tt, uu = (np.asarray(spec[0], dtype=float), np.asarray(spec[1], dtype=float))
        if tt.shape != uu.shape or tt.ndim != 1 or np.any(np.diff(tt) <= 0):
            raise ValueError(f"control {name!r}: (t, u) must be 1-D arrays of equal length "
                             "with increasing t [s]")
        return lambda t: float(np.interp(t, tt, uu, left=uu[0], right=uu[-1]))
    v = float(spec)
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
        raise ValueError(f"unknown control names {sorted(unknown)}; have "
                         f"{wake.control_names + flap_names}")
    if not duration > 0:
        raise ValueError(f"duration must be positive [s], got {duration!r}")
    if from_trim and wake._trim_state is not None:
        wake.restore(wake._trim_state)
    base = dict(wake.controls)
    funcs = {n: _control_function(v, n) for n, v in controls.items()}
    labels = list((points or {}).keys())
    pts = np.array([points[k] for k in labels], dtype=float).reshape(-1, 3)
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
