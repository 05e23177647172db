"""Shaft-fixed ("wind-tunnel") rotors of the aircraft model with a pluggable inflow model.

::

    stand = ShaftFixedRotors(config, inflow)    # body held still, flap + inflow free
    stand.trim(ct)                        # collectives: total thrust, equal torques
    df = stand.run({"theta0_U": (t, u)}, duration)   # same columns as aircraft.wake.run_wake

This is the blade-element rotor of :class:`~aircraft.helicopter.Helicopter`
(same blades, flap equations and inflow interface) with the airframe removed,
so that its flapping and load responses can be compared with the free-vortex
wake's free-flapping runs (:func:`aircraft.wake.run_wake`) input by input: the
rotor-level check of §7.2.2 ("MFW only" against "state-space inflow"). Hover
only: the wake's hover trim holds the cyclics at zero, and so does this one.
"""
from __future__ import annotations

import numpy as np
import pandas as pd
from scipy.interpolate import interp1d
from scipy.integrate import solve_ivp
from scipy.optimize import least_squares

from ..inflow.base import rotor_suffix
from .model import Helicopter, HelicopterSettings

__all__ = ["ShaftFixedRotors", "RotorStandError"]


class RotorStandError(RuntimeError):
    """Trim or time integration of the shaft-fixed rotors failed."""


class ShaftFixedRotors:
    """The aircraft's rotors on a fixed shaft, flapping freely with an inflow model.

    Parameters
    ----------
    config : AircraftConfig
        Coaxial (two rotors) or single rotor.
    inflow : InflowModel
    settings : HelicopterSettings, optional
        Default 8 span points, 1 azimuth (exact in hover).
    """

    def __init__(self, config, inflow, settings=None):
        from dataclasses import replace
        # the shaft is held: an airframe of (numerically) infinite inertia takes the hub loads
        # without moving, so the flap equations lose their body-acceleration terms exactly
        # as on a test stand (body states stay zero; their derivatives are ignored)
        held = replace(config, mass=1e18, Ixx=1e18, Iyy=1e18, Izz=1e18, Ixz=0.0)
        self.heli = Helicopter(held, inflow, settings or HelicopterSettings(n_span=8, n_average=1))
        self.config = config
        self.n_rigid = self.heli.n_rigid
        self.u_trim = None
        self.x_trim = None

    @property
    def control_names(self):
        """Rotor controls (no propeller or tail rotor)."""
        return [n for n in self.heli.input_names if n.startswith("theta") and n not in ("theta_prop", "theta_tr")]

    def _full(self, z):
        x = np.zeros(self.heli.n_states)
        x[9:] = z
        return x

    def _rhs(self, z, u):
        return self.heli.derivatives(self._full(z), u)[9:]

    def trim(self, ct=None, tol=1e-10):
        """Collective(s) for the total thrust (coaxial: and equal torques), flap and inflow steady.

        Parameters
        ----------
        ct : float, optional
            Total thrust coefficient (sum over rotors). Default ``sum(config.trim_ct)``.
        tol : float
            Largest scaled residual accepted.

        Returns
        -------
        dict
            Trimmed loads ``CT_U, CL_U, CM_U, CQ_U, ...`` and controls.
        """
        heli, cfg = self.heli, self.config
        nrot = len(heli.rotors)
        ct = float(sum(cfg.trim_ct)) if ct is None else float(ct)
        omega = heli.rotors[0].config.omega
        heli.inflow.release_trim()
        n_in = heli.n_states - self.n_rigid

        def unpack(v):
            u = np.zeros(len(heli.input_names))
            z = np.zeros(heli.n_states - 9)
            u[0] = v[0]
            if nrot == 2:
                u[3] = v[1]
            k = nrot
            for r in range(nrot):
                z[8 * r:8 * r + 4] = v[k:k + 4]
                k += 4
            z[8 * nrot:] = v[k:]
            return z, u

        def residual(v):
            z, u = unpack(v)
            xdot, extra = heli.evaluate(self._full(z), u)
            res = [xdot[9 + 8 * r + 4:9 + 8 * r + 8] / omega ** 2 for r in range(nrot)]
            res.append(xdot[self.n_rigid:] / omega)
            loads = extra["loads"]
            res.append([(sum(loads[3 * r] for r in range(nrot)) - ct) / ct])
            if nrot == 2:
                cq_upper, cq_lower = (extra[f"CQ{rotor_suffix(rm.config.name)}"] for rm in heli.rotors)
                res.append([(cq_upper - cq_lower) / max(abs(cq_upper), 1e-6)])
            return np.concatenate([np.ravel(r) for r in res])

        rc = heli.rotors[0].config
        ct_rotor = ct / nrot
        th0 = 6 * ct_rotor / (rc.solidity * rc.lift_slope) + 1.5 * np.sqrt(ct_rotor / 2) - 0.75 * rc.twist
        v0 = np.concatenate([[th0] * nrot, np.tile([0.02, 0, 0, 0], nrot),
                             np.zeros(n_in)])
        ops = heli._ops(np.zeros(heli.n_states))
        v0[nrot + 4 * nrot:] = heli.inflow.steady_state(np.tile([ct_rotor, 0.0, 0.0], nrot), ops)
        sol = least_squares(residual, v0, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=4000)
        r = residual(sol.x)
        if not np.all(np.isfinite(r)) or np.max(np.abs(r)) > tol:
            raise RotorStandError(f"shaft-fixed trim did not converge (max scaled residual {np.max(np.abs(r)):.2e})")
        z, u = unpack(sol.x)
        self.x_trim, self.u_trim = z, u
        _, extra = heli.evaluate(self._full(z), u)
        heli.inflow.set_trim(z[8 * nrot:], extra["loads"], extra["ops"])
        return self._outputs(z, u)

    def _outputs(self, z, u):
        heli = self.heli
        xdot, extra = heli.evaluate(self._full(z), u)
        out = {n: float(v) for n, v in zip(self.heli.input_names, u) if n in self.control_names}
        lam = extra["inflow"]
        for k, rm in enumerate(heli.rotors):
            sfx = rotor_suffix(rm.config.name)
            for j, c in enumerate(("CT", "CL", "CM")):
                out[c + sfx] = float(extra["loads"][3 * k + j])
            out["CQ" + sfx] = float(extra["CQ" + sfx])
            for j, c in enumerate(("lam0", "lam1s", "lam1c")):
                out[c + sfx] = float(lam[3 * k + j])
            flap, rate = z[8 * k:8 * k + 4], z[8 * k + 4:8 * k + 8]
            for j, c in enumerate(("beta0", "beta1c", "beta1s", "betad")):
                out[c + sfx] = float(flap[j])
            # shaft fixed: the shaft-relative rates are the full tip-path-plane rates
            out["beta1s_dot" + sfx], out["beta1c_dot" + sfx] = float(rate[2]), float(rate[1])
        return out

    def linearize(self, step=1e-6):
        """Perturbation model about the trim: ``control.StateSpace`` in seconds.

        Inputs: :attr:`control_names` [rad]; outputs: the numeric columns of
        :meth:`run` other than the controls (perturbations); central differences
        with absolute steps ``step`` (states) and ``step`` rad (controls).
        """
        import control
        if self.u_trim is None:
            raise RotorStandError("trim() first")
        z0, u0 = self.x_trim, self.u_trim
        idx = [self.heli.input_names.index(n) for n in self.control_names]
        out_names = [k for k in self._outputs(z0, u0) if k not in self.control_names]

        def y(z, u):
            o = self._outputs(z, u)
            return np.array([o[k] for k in out_names])
        n, m = z0.size, len(idx)
        a, c = np.empty((n, n)), np.empty((len(out_names), n))
        b, d = np.empty((n, m)), np.empty((len(out_names), m))
        for j in range(n):
            e = np.zeros(n)
            e[j] = step
            a[:, j] = (self._rhs(z0 + e, u0) - self._rhs(z0 - e, u0)) / (2 * step)
            c[:, j] = (y(z0 + e, u0) - y(z0 - e, u0)) / (2 * step)
        for j, i in enumerate(idx):
            e = np.zeros(u0.size)
            e[i] = step
            b[:, j] = (self._rhs(z0, u0 + e) - self._rhs(z0, u0 - e)) / (2 * step)
            d[:, j] = (y(z0, u0 + e) - y(z0, u0 - e)) / (2 * step)
        states = self.heli.state_names[9:]
        return control.ss(a, b, c, d, states=states, inputs=self.control_names, outputs=out_names,
                          name="shaft-fixed rotors")

    def run_linear(self, controls, t):
        """Like :meth:`run` but with the linear model (fast; small inputs).

        Parameters
        ----------
        controls : dict
            ``{name: du_array}`` [rad] on the time grid ``t``.
        t : array_like
            Uniform time grid [s].

        Returns
        -------
        pandas.DataFrame
            ``t``, the controls and the outputs of :meth:`linearize`, as totals (trim + perturbation).
        """
        import control
        sys = self.linearize()
        t = np.asarray(t, float)
        u = np.zeros((len(self.control_names), t.size))
        for name, du in controls.items():
            if name not in self.control_names:
                raise ValueError(f"unknown control {name!r}; have {self.control_names}")
            u[self.control_names.index(name)] = np.asarray(du, float)
        resp = control.forced_response(sys, t, u)
        trim = self._outputs(self.x_trim, self.u_trim)
        df = pd.DataFrame({"t": t})
        for k, name in enumerate(self.control_names):
            df[name] = trim[name] + u[k]
        for k, name in enumerate(sys.output_labels):
            df[name] = trim[name] + resp.outputs[k]
        return df

    def run(self, controls, duration, dt=None, rtol=1e-7):
        """Time response to control perturbations about the trim.

        Parameters
        ----------
        controls : dict
            ``{name: (t_array, du_array)}`` [s, rad] perturbations of the rotor
            controls (linear interpolation, held outside the samples), or
            ``{name: callable(t)}``.
        duration : float
            [s].
        dt : float, optional
            Output sample interval [s]; default one sample per 10 deg of azimuth.
        rtol : float
            Relative tolerance of the (RK45) integration.

        Returns
        -------
        pandas.DataFrame
            ``t`` [s], the controls [rad], ``CT/CL/CM/CQ``, ``lam0/lam1s/lam1c`` (total,
            interference included), ``beta0/beta1c/beta1s/betad`` [rad] and
            ``beta1s_dot/beta1c_dot`` [rad/s] per rotor: the columns of
            :func:`aircraft.wake.run_wake` and more.
        """
        if self.u_trim is None:
            raise RotorStandError("trim() first")
        names = self.heli.input_names
        funs = {}
        for name, spec in controls.items():
            if name not in self.control_names:
                raise ValueError(f"unknown control {name!r}; have {self.control_names}")
            if callable(spec):
                funs[names.index(name)] = spec
            else:
                t_s, u_s = (np.asarray(a, float) for a in spec)
                funs[names.index(name)] = interp1d(t_s, u_s, bounds_error=False, fill_value=(u_s[0], u_s[-1]))

        def u_of(t):
            u = self.u_trim.copy()
            for i, f in funs.items():
                u[i] += float(f(t))
            return u

        omega = self.heli.rotors[0].config.omega
        dt = dt or np.radians(10.0) / omega
        t_eval = np.arange(0.0, duration + 0.5 * dt, dt)
        sol = solve_ivp(lambda t, z: self._rhs(z, u_of(t)), (0.0, t_eval[-1]), self.x_trim, t_eval=t_eval,
                        rtol=rtol, atol=1e-10, max_step=dt)
        if not sol.success:
            raise RotorStandError(f"time integration failed: {sol.message}")
        rows = [dict(t=t, **self._outputs(z, u_of(t))) for t, z in zip(sol.t, sol.y.T)]
        return pd.DataFrame(rows)
