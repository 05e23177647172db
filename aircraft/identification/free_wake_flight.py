"""The free-vortex wake flown with the aircraft ("MFW only"): hover collective responses.

::

    df = fly_free_wake(config, collective, duration, body="heave")        # wake inflow
    ref = fly_inflow_model(config, PittPeters(), collective, duration, body="heave")

Coupling (fixed step, the wake's own step ``dt = azimuth_step / Omega``):

1. the aircraft (blade-element rotor, flap equations and body of
   :class:`~aircraft.helicopter.Helicopter`) is integrated over one step with
   classical Runge-Kutta, its rotor inflow ``lam0, lam1s, lam1c`` held at the
   wake's latest outputs (a :class:`PrescribedInflow` without states stands in
   for an inflow model);
2. the wake is then driven to the aircraft's new state and marched one step:

   * controls: the wake's trim controls plus the aircraft's control
     perturbations from its own trim (the two blade models trim at slightly
     different collectives; perturbations keep both at their own trim when
     nothing is excited);
   * flapping: the wake's rigid, prescribed tip-path plane
     (``WakeSettings.free_flapping=False``) is set to the aircraft's coning
     (``beta_trim``) and cyclic flap with its exact cyclic rates
     (``set_flap_inputs``). The prescribed blade motion carries no coning
     *rate*; in hover its aerodynamic effect, an angle of attack change of
     ``-(r - e) beta0_dot / (Omega r)`` along the blade, is passed as the
     collective ``-beta0_dot / Omega`` instead (exact for a hinge at the
     centre; the hinge offset changes it by ``e / r``, a few percent at the
     inboard elements that carry little load);
   * body: the hub's vertical velocity ``w`` (body z, down) is the wake's axial
     free stream ``v_inf = (0, 0, w)`` (computational z up: a descending rotor
     sees air coming up).

The wake's flap model is therefore not used: the aircraft's flap equations,
driven by the aircraft's blade loads computed with the wake's inflow, give the
flapping for both. The comparison runs (:func:`fly_inflow_model`) fly the same
aircraft, trim and integrator with an inflow model's states instead.

Body options: ``"held"`` (shaft fixed: the body cannot move, as on a test
stand, Fig. 7.1) and ``"heave"`` (the body free in vertical translation only,
attitude and horizontal velocity held: the collective-to-coning loop of
Fig. 7.2 without the yaw and roll drift of a tail-rotor aircraft). Hover only:
the cyclics and the tail rotor stay at their hover trim (zero).
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pandas as pd
from scipy.optimize import least_squares

from ..inflow.base import InflowModel

__all__ = ["PrescribedInflow", "FreeWakeFlightError", "BODY_MODES", "fly_free_wake", "fly_inflow_model"]

#: body options: shaft fixed, or free in heave only
BODY_MODES = ("held", "heave")
_HUGE = 1e18


class FreeWakeFlightError(RuntimeError):
    """The aircraft trim or the coupled time march failed."""


class PrescribedInflow(InflowModel):
    """An inflow model without states whose inflow is set from outside.

    Parameters
    ----------
    lam : array_like, optional
        ``[lam0, lam1s, lam1c]`` of the single rotor (positive down, on Omega R).
    rotors : tuple of str
        Rotor names (default the single rotor ``("",)``).

    Examples
    --------
    >>> from aircraft.inflow import RotorOperatingPoint
    >>> m = PrescribedInflow([0.06, 0.0, 0.0])
    >>> m.n_states, float(m.inflow(None, None, (RotorOperatingPoint(27.0),))[0])
    (0, 0.06)
    """

    def __init__(self, lam=(0.0, 0.0, 0.0), rotors=("",)):
        self.rotors = tuple(rotors)
        self.lam = np.zeros(3 * len(self.rotors))
        self.set(lam)

    def set(self, lam):
        """Set the inflow harmonics (len 3 per rotor, finite)."""
        lam = np.asarray(lam, dtype=float).ravel()
        if lam.shape != self.lam.shape or not np.all(np.isfinite(lam)):
            raise ValueError(f"lam must be {self.lam.size} finite numbers [lam0, lam1s, lam1c per rotor], "
                             f"got {lam!r}")
        self.lam = lam.copy()

    @property
    def state_names(self):
        return []

    def steady_state(self, loads, ops):
        return np.zeros(0)

    def derivatives(self, x, loads, ops, rates=None):
        return np.zeros(0)

    def inflow(self, x, loads, ops):
        return self.lam.copy()


# --------------------------------------------------------------- the aircraft
class _Aircraft:
    """The helicopter with its body held or free in heave; trim and RK4 steps."""

    def __init__(self, config, inflow, body, settings):
        # lazy: the identification package keeps its helicopter edge lazy (docs/architecture.rst)
        from ..helicopter import Helicopter, HelicopterSettings
        if body not in BODY_MODES:
            raise ValueError(f"body must be one of {BODY_MODES}, got {body!r}")
        if config.is_coaxial or len(config.rotors) != 1:
            raise ValueError("config must be a single-rotor aircraft (coaxial coupling is not implemented)")
        # held attitude: (numerically) infinite inertias, so the flap equations lose
        # their body-acceleration terms exactly as on a test stand; "held" also
        # takes an infinite mass
        mass = _HUGE if body == "held" else config.mass
        self.body = body
        self.heli = Helicopter(replace(config, mass=mass, Ixx=_HUGE, Iyy=_HUGE, Izz=_HUGE, Ixz=0.0), inflow,
                               settings or HelicopterSettings(n_span=8, n_average=1))
        self.free = [2] if body == "heave" else []
        self.omega = self.heli.rotors[0].config.omega

    def rhs(self, x, u):
        xdot = self.heli.derivatives(x, u)
        keep = xdot[self.free].copy()
        xdot[:9] = 0.0
        xdot[self.free] = keep
        return xdot

    def step(self, x, u_of, t, dt):
        k1 = self.rhs(x, u_of(t))
        k2 = self.rhs(x + 0.5 * dt * k1, u_of(t + 0.5 * dt))
        k3 = self.rhs(x + 0.5 * dt * k2, u_of(t + 0.5 * dt))
        k4 = self.rhs(x + dt * k3, u_of(t + dt))
        return x + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)

    def trim(self, ct, tol=1e-9):
        """Collective, flapping and inflow states steady; held: C_T = ct, heave: w' = 0."""
        heli = self.heli
        n_in = heli.n_states - heli.n_rigid
        heli.inflow.release_trim()
        nu = len(heli.input_names)

        def unpack(v):
            x = np.zeros(heli.n_states)
            u = np.zeros(nu)
            u[0] = v[0]
            x[9:13] = v[1:5]
            x[heli.n_rigid:] = v[5:]
            return x, u

        def residual(v):
            x, u = unpack(v)
            xdot, extra = heli.evaluate(x, u)
            last = (extra["loads"][0] - ct) / ct if self.body == "held" else xdot[2] / 9.81
            return np.concatenate([xdot[13:17] / self.omega ** 2, xdot[heli.n_rigid:] / self.omega, [last]])

        rc = heli.rotors[0].config
        ct_guess = ct if ct is not None else 0.006
        th0 = 6 * ct_guess / (rc.solidity * rc.lift_slope) + 1.5 * math.sqrt(ct_guess / 2) - 0.75 * rc.twist
        v0 = np.concatenate([[th0, 0.02, 0.0, 0.0, 0.0], np.zeros(n_in)])
        if n_in:
            v0[5:] = heli.inflow.steady_state(np.array([ct_guess, 0.0, 0.0]), heli._ops(np.zeros(heli.n_states)))
        sol = least_squares(residual, v0, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=4000)
        r = residual(sol.x)
        if not np.all(np.isfinite(r)) or np.max(np.abs(r)) > tol:
            raise FreeWakeFlightError(f"aircraft hover trim did not converge (max scaled residual "
                                      f"{np.max(np.abs(r)):.2e})")
        x, u = unpack(sol.x)
        _, extra = heli.evaluate(x, u)
        heli.inflow.set_trim(x[heli.n_rigid:], extra["loads"], extra["ops"])
        return x, u

    def row(self, t, x, u):
        _, extra = self.heli.evaluate(x, u)
        xdot = self.rhs(x, u)
        lam = extra["inflow"]
        return {"t": t, "theta0": u[0], "beta0": x[9], "beta1c": x[10], "beta1s": x[11],
                "beta0_dot": x[13], "lam0": lam[0], "lam1s": lam[1], "lam1c": lam[2],
                "CT": extra["loads"][0], "w": x[2], "w_dot": xdot[2]}


def _collective(collective, duration):
    """``(callable t -> rad, duration)`` from a callable or ``(t, du)`` samples."""
    if isinstance(duration, bool) or not np.isfinite(duration) or duration <= 0:
        raise ValueError(f"duration must be a positive number of seconds, got {duration!r}")
    if callable(collective):
        return collective
    try:
        t_s, u_s = (np.asarray(a, dtype=float) for a in collective)
    except (TypeError, ValueError):
        raise TypeError("collective must be a callable t -> rad or a pair (t, du) of arrays [s, rad]") from None
    if t_s.ndim != 1 or t_s.shape != u_s.shape or t_s.size < 2 or np.any(np.diff(t_s) <= 0) \
            or not np.all(np.isfinite(u_s)):
        raise ValueError("collective (t, du) must be equal-length finite arrays with t increasing")
    return lambda t: float(np.interp(t, t_s, u_s))


def _times(duration, dt):
    n = int(round(duration / dt))
    return np.arange(n + 1) * dt


def _controls(u_trim, collective):
    def u_of(t):
        u = u_trim.copy()
        u[0] += collective(t)
        return u
    return u_of


def _progress(n, progress, desc):
    from tqdm.auto import tqdm
    return tqdm(total=n, desc=desc, disable=not progress, mininterval=2.0)


def fly_inflow_model(config, inflow, collective, duration, *, body="held", ct=None, dt=None, settings=None,
                     progress=False):
    """Hover collective response of the aircraft with an inflow model.

    Parameters
    ----------
    config : AircraftConfig
        Single-rotor aircraft.
    inflow : InflowModel
        Its rotor names must match the configuration's.
    collective : callable or (array_like, array_like)
        Collective perturbation from trim [rad]: ``f(t)`` or samples ``(t, du)``
        [s, rad] (linear interpolation, held outside).
    duration : float
        [s].
    body : {"held", "heave"}
        Shaft fixed, or the body free in vertical translation only.
    ct : float, optional
        Thrust coefficient of the trim (``"held"`` only; ``"heave"`` trims to
        the weight). Default ``config.trim_ct``.
    dt : float, optional
        Fixed Runge-Kutta step and output interval [s]; default 10 deg of
        azimuth, the free wake's default step.
    settings : HelicopterSettings, optional
        Default 8 span points and 1 azimuth (exact in hover).
    progress : bool
        tqdm progress bar.

    Returns
    -------
    pandas.DataFrame
        ``t`` [s], ``theta0, beta0, beta1c, beta1s`` [rad], ``beta0_dot`` [rad/s],
        ``lam0, lam1s, lam1c`` [-], ``CT`` [-], ``w`` [m/s] (body z, down) and
        ``w_dot`` [m/s^2]; ``attrs["trim"]``: the trim controls and states.

    Examples
    --------
    >>> from aircraft.configs import uh60_single_rotor
    >>> from aircraft.inflow import PittPeters
    >>> df = fly_inflow_model(uh60_single_rotor(), PittPeters(), lambda t: 0.0, 0.02)
    >>> round(float(df["CT"].iloc[-1]), 4)
    0.0061
    """
    plane = _Aircraft(config, inflow, body, settings)
    collective = _collective(collective, duration)
    ct = _ct(config, ct)
    dt = dt or math.radians(10.0) / plane.omega
    x, u_trim = plane.trim(ct)
    u_of = _controls(u_trim, collective)
    t = _times(duration, dt)
    rows = [plane.row(0.0, x, u_of(0.0))]
    with _progress(t.size - 1, progress, f"aircraft, {type(inflow).__name__} inflow") as bar:
        for k in range(t.size - 1):
            x = plane.step(x, u_of, t[k], dt)
            if not np.all(np.isfinite(x)):
                raise FreeWakeFlightError(f"the aircraft state became non-finite at t = {t[k + 1]:.3f} s")
            rows.append(plane.row(t[k + 1], x, u_of(t[k + 1])))
            bar.update()
    df = pd.DataFrame(rows)
    df.attrs["trim"] = {"theta0": float(u_trim[0]), "beta0": rows[0]["beta0"], "CT": rows[0]["CT"]}
    return df


def _ct(config, ct):
    ct = float(sum(config.trim_ct)) if ct is None else ct
    if isinstance(ct, bool) or not np.isfinite(ct) or ct <= 0:
        raise ValueError(f"ct must be a positive thrust coefficient, got {ct!r}")
    return float(ct)


def fly_free_wake(config, collective, duration, *, body="held", ct=None, wake=None, wake_settings=None,
                  settings=None, settle_revs=8, progress=True):
    """Hover collective response of the aircraft flown with the free-vortex wake's inflow.

    Parameters
    ----------
    config : AircraftConfig
        Single-rotor aircraft.
    collective : callable or (array_like, array_like)
        Collective perturbation from trim [rad]: ``f(t)`` or samples ``(t, du)``.
    duration : float
        [s].
    body : {"held", "heave"}
        Shaft fixed, or the body free in vertical translation only.
    ct : float, optional
        Thrust coefficient of the trim (``"held"``; ``"heave"`` trims to the
        weight). Default ``config.trim_ct``.
    wake : FreeVortexWake, optional
        A fresh wake of ``config`` in hover (rigid flapping); it is trimmed here.
        Default ``FreeVortexWake(config, wake_settings)``.
    wake_settings : WakeSettings, optional
        Used when ``wake`` is not given (default resolution otherwise).
    settings : HelicopterSettings, optional
        The aircraft's rotor resolution (default 8 span points, 1 azimuth).
    settle_revs : int
        Revolutions the wake is marched before its trim's first update
        (:func:`aircraft.wake.trim.trim_wake`). The trim's own default leaves
        the single rotor's wake still settling in the first revolution after
        it (a start transient in C_T and lam0 larger than the blade-passage
        ripple, measured); the default here does not.
    progress : bool
        tqdm progress bar over the wake steps.

    Returns
    -------
    pandas.DataFrame
        The columns of :func:`fly_inflow_model` on the wake's time grid (``lam*``
        are the wake's, held over each step) and ``CT_wake`` [-], the wake's own
        blade-load thrust; ``attrs["trim"]`` holds both trims.

    Examples
    --------
    A stand-in wake with a constant inflow (any object with the attributes
    used by the coupling will do):

    >>> from types import SimpleNamespace
    >>> from aircraft.configs import uh60_single_rotor
    >>> class Still:
    ...     dt, omega, v_inf = 0.0065, 27.0, [0.0, 0.0, 0.0]
    ...     controls, beta_trim, flap_input_names = {"theta0": 0.0}, {"": [0.0, 0.0, 0.0]}, []
    ...     settings = SimpleNamespace(free_flapping=False)
    ...     def trim(self, ct, **kw): return SimpleNamespace(controls={"theta0": 0.17}, outputs={"lam0": 0.064})
    ...     def set_flap_inputs(self, values, rates): pass
    ...     def step(self): pass
    ...     def current_outputs(self): return {"lam0": 0.064, "lam1s": 0.0, "lam1c": 0.0, "CT": 0.0061}
    >>> df = fly_free_wake(uh60_single_rotor(), lambda t: 0.0, 0.013, wake=Still(), progress=False)
    >>> len(df), round(float(df["lam0"].iloc[-1]), 3)
    (3, 0.064)
    """
    collective = _collective(collective, duration)
    if wake is None:
        from ..wake import FreeVortexWake, WakeSettings
        wake = FreeVortexWake(config, wake_settings or WakeSettings())
    if wake.settings.free_flapping:
        raise ValueError("wake must use the prescribed (rigid) tip-path plane: WakeSettings(free_flapping=False)")
    inflow = PrescribedInflow()
    plane = _Aircraft(config, inflow, body, settings)
    if not math.isclose(wake.omega, plane.omega, rel_tol=1e-9):
        raise ValueError(f"wake rotor speed {wake.omega} rad/s differs from the aircraft's {plane.omega} rad/s")
    ct = _ct(config, ct)
    # the aircraft's trim thrust (held: ct; heave: the weight's, whatever the inflow) from a
    # momentum-inflow guess, then the wake trimmed at it with the aircraft's flapping
    inflow.set([math.sqrt(ct / 2.0), 0.0, 0.0])
    x, u_trim = plane.trim(ct)
    ct_trim = float(plane.heli.evaluate(x, u_trim)[1]["loads"][0])
    name = next(iter(wake.beta_trim))
    wake.beta_trim[name] = np.array([x[9], x[10], x[11]])
    if isinstance(settle_revs, bool) or not float(settle_revs).is_integer() or settle_revs < 1:
        raise ValueError(f"settle_revs must be an integer >= 1, got {settle_revs!r}")
    wake_trim = wake.trim(ct=ct_trim, settle_revs=int(settle_revs))
    lam_mean = [wake_trim.outputs.get(k, 0.0) for k in ("lam0", "lam1s", "lam1c")]
    inflow.set(lam_mean)
    x, u_trim = plane.trim(ct_trim)          # the aircraft at the wake's mean trim inflow
    flap_trim = np.array([x[9], x[10], x[11]])
    wake.beta_trim[name] = flap_trim.copy()
    ctrl_trim = {k: float(v) for k, v in wake_trim.controls.items()}
    sfx = ("_" + name) if name else ""
    keys = [c + sfx for c in ("theta0", "theta1s", "theta1c")]
    dt = wake.dt
    u_of = _controls(u_trim, collective)
    t = _times(duration, dt)
    out = wake.current_outputs()
    inflow.set([out["lam0"], out["lam1s"], out["lam1c"]])
    rows = [dict(plane.row(0.0, x, u_of(0.0)), CT_wake=out["CT"])]
    with _progress(t.size - 1, progress, f"aircraft with free wake, body {body}") as bar:
        for k in range(t.size - 1):
            x = plane.step(x, u_of, t[k], dt)
            if not np.all(np.isfinite(x)):
                raise FreeWakeFlightError(f"the aircraft state became non-finite at t = {t[k + 1]:.3f} s")
            u = u_of(t[k + 1])
            for i, key in enumerate(keys):     # perturbations about each model's own trim
                wake.controls[key] = ctrl_trim.get(key, 0.0) + float(u[i] - u_trim[i])
            # the coning rate, absent from the prescribed blade motion, as its hover angle of attack
            wake.controls[keys[0]] -= x[13] / plane.omega
            wake.beta_trim[name] = np.array([x[9], flap_trim[1], flap_trim[2]])
            if wake.flap_input_names:
                wake.set_flap_inputs({f"beta1c{sfx}": x[10] - flap_trim[1], f"beta1s{sfx}": x[11] - flap_trim[2]},
                                     {f"beta1c{sfx}": x[14], f"beta1s{sfx}": x[15]})
            wake.v_inf = np.array([0.0, 0.0, x[2]])
            wake.step()
            out = wake.current_outputs()
            inflow.set([out["lam0"], out["lam1s"], out["lam1c"]])
            rows.append(dict(plane.row(t[k + 1], x, u), CT_wake=out["CT"]))
            bar.update()
    df = pd.DataFrame(rows)
    df.attrs["trim"] = {"theta0": float(u_trim[0]), "theta0_wake": ctrl_trim.get(keys[0]),
                        "CT": ct_trim, "lam0_wake": float(lam_mean[0])}
    return df
