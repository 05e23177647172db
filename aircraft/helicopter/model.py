"""The rigid-body helicopter: ``Helicopter(config, inflow)``.

State vector (named): body ``u v w p q r phi theta psi`` (Eq. 7.7, SI, body axes),
then per rotor the flap MBC ``beta0, beta1c, beta1s, betad`` and their rates
(``*_dot``), then the inflow model's states.  Inputs: the rotor controls
``theta0_U, theta1s_U, theta1c_U, theta0_L, theta1s_L, theta1c_L, theta_prop``
(the suffixes are the configuration's rotor names; single rotor: ``theta0, theta1s,
theta1c`` plus ``theta_tr``, the tail rotor's collective at 3/4 radius [rad] when the
configuration has a ``tail_rotor``, otherwise an idealised yaw moment control,
``HelicopterSettings``).

Each rotor's shaft is tilted forward by its ``shaft_tilt`` ``i_s``: body vectors
go to the shaft frame by a rotation about body y (shaft x axis
``(cos i_s, 0, sin i_s)``, shaft z axis ``(-sin i_s, 0, cos i_s)``) and then to
the rotor's own frame by the mirror of a clockwise rotor.

Inflow models with wake-distortion inputs (``uses_flap_rates``) receive the
full tip-path-plane rates of each rotor, ``beta1s_dot - p_r`` and
``beta1c_dot - q_r`` in that rotor's frame (:mod:`aircraft.inflow.base`), i.e.
Eq. 2.29 with its body-rate terms Delta p / Omega, Delta q / Omega.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..configs import GRAVITY, AircraftConfig
from ..inflow.base import InflowModel, RotorOperatingPoint, rotor_suffix
from ..provenance import HASHED_IF_SET
from .airframe import PROPELLER_MODELS, fuselage_loads, propeller_loads, tail_rotor_loads
from .rotor import FLAP_STATES, RotorModel

__all__ = ["Helicopter", "HelicopterSettings", "BODY_STATES"]

BODY_STATES = ["u", "v", "w", "p", "q", "r", "phi", "theta", "psi"]


@dataclass(frozen=True)
class HelicopterSettings:
    """Numerical settings: Gauss points over span, averaging azimuths per blade passage."""

    n_span: int = 8
    n_average: int = 4
    #: single rotor without a ``tail_rotor`` only: yaw moment [N m] per rad of ``theta_tr``
    tail_rotor_yaw_per_rad: float = 2.0e5
    #: pusher propeller model (:func:`~aircraft.helicopter.airframe.propeller_loads`):
    #: "momentum" (uniform inflow, small angles) or "blade_element" (twist, exact angles)
    propeller_model: str = field(default="momentum", metadata=HASHED_IF_SET)

    def __post_init__(self):
        if self.propeller_model not in PROPELLER_MODELS:
            raise ValueError(f"HelicopterSettings.propeller_model must be one of {PROPELLER_MODELS}, "
                             f"got {self.propeller_model!r}")


class Helicopter:
    """Rigid body + flapping blade-element rotors + a pluggable inflow model.

    Parameters
    ----------
    config : AircraftConfig
    inflow : InflowModel
        Its rotor names must match the configuration's (e.g. ``DynamicClimb(rotors=...)``
        with :func:`~aircraft.inflow.base.config_rotor_names` of ``config``); the
        flap, inflow and control signals carry these names.
    settings : HelicopterSettings
    """

    def __init__(self, config: AircraftConfig, inflow: InflowModel, settings=HelicopterSettings()):
        names = tuple(r.name for r in config.rotors)
        if tuple(inflow.rotors) != names:
            raise ValueError(f"inflow model rotors {inflow.rotors} do not match the aircraft's {names}")
        self.config = config
        self.inflow = inflow
        self.settings = settings
        self.rotors = [RotorModel(r, settings.n_span, settings.n_average, config.rho) for r in config.rotors]
        self.state_names = list(BODY_STATES)
        for r in config.rotors:
            sfx = rotor_suffix(r.name)
            self.state_names += [f"{b}{sfx}" for b in FLAP_STATES]
            self.state_names += [f"{b}_dot{sfx}" for b in FLAP_STATES]
        self.n_rigid = len(self.state_names)
        self.state_names += list(inflow.state_names)
        if config.is_coaxial:
            # the controls carry the configuration's rotor names ("U" upper, "L" lower, as every signal does)
            self.input_names = [f"{c}{rotor_suffix(r.name)}" for r in config.rotors
                                for c in ("theta0", "theta1s", "theta1c")] + ["theta_prop"]
        else:
            self.input_names = ["theta0", "theta1s", "theta1c", "theta_tr"]
        inertia = np.array([[config.Ixx, 0, -config.Ixz], [0, config.Iyy, 0], [-config.Ixz, 0, config.Izz]])
        self.inertia = inertia
        self.inertia_inv = np.linalg.inv(inertia)
        # body -> shaft rotation per rotor; None for an untilted shaft (kept exactly the identity)
        self._shaft = []
        for r in config.rotors:
            i_s = r.shaft_tilt
            self._shaft.append(None if i_s == 0.0 else np.array(
                [[np.cos(i_s), 0.0, np.sin(i_s)], [0.0, 1.0, 0.0], [-np.sin(i_s), 0.0, np.cos(i_s)]]))

    def _to_shaft(self, k, vec):
        """Body-axes vector in rotor ``k``'s shaft frame."""
        s = self._shaft[k]
        return vec if s is None else s @ vec

    def _from_shaft(self, k, vec):
        """Shaft-frame vector of rotor ``k`` in body axes."""
        s = self._shaft[k]
        return vec if s is None else s.T @ vec

    @property
    def n_states(self):
        return len(self.state_names)

    def _ops(self, x):
        ops = []
        vel = x[0:3]
        rates = x[3:6]
        for k, rm in enumerate(self.rotors):
            cfg = rm.config
            v_hub = self._to_shaft(k, vel + np.cross(rates, np.asarray(cfg.hub_position, float)))
            vt = cfg.tip_speed
            ops.append(RotorOperatingPoint(omega=cfg.omega, mu=float(np.hypot(v_hub[0], v_hub[1]) / vt),
                                           mu_z=float(-v_hub[2] / vt)))
        return tuple(ops)

    def evaluate(self, x, u):
        """Derivatives and a dict of loads (per-rotor C_T, C_L, C_M, torque)."""
        x = np.asarray(x, dtype=float)
        u = np.asarray(u, dtype=float)
        if x.shape != (self.n_states,):
            raise ValueError(f"state vector must have {self.n_states} entries, got {x.shape}")
        if u.shape != (len(self.input_names),):
            raise ValueError(f"input vector must have {len(self.input_names)} entries {self.input_names}")
        cfg = self.config
        vel, rates = x[0:3], x[3:6]
        phi, theta = x[6], x[7]
        ops = self._ops(x)
        xin = x[self.n_rigid:]
        lam = self.inflow.inflow(xin, None, ops)
        force = np.zeros(3)
        moment = np.zeros(3)
        xdot = np.zeros_like(x)
        loads, rates_tpp, extra = [], [], {}
        for k, rm in enumerate(self.rotors):
            rc = rm.config
            d = rc.direction
            mirror = np.array([1.0, float(d), 1.0])        # rotor frame <-> body (y -> -y for CW)
            base = 9 + 8 * k
            flap, flap_rate = x[base:base + 4], x[base + 4:base + 8]
            hub = np.asarray(rc.hub_position, float)
            v_hub = self._to_shaft(k, vel + np.cross(rates, hub))
            rates_s = self._to_shaft(k, rates)
            ctrl = u[3 * k:3 * k + 3] if cfg.is_coaxial else u[0:3]
            out = rm.evaluate(flap, flap_rate, ctrl, lam[3 * k:3 * k + 3], mirror * v_hub,
                              np.array([d * rates_s[0], rates_s[1], d * rates_s[2]]))
            f_body = self._from_shaft(k, mirror * out["force"])
            m_body = self._from_shaft(k, np.array([d * out["moment"][0], out["moment"][1],
                                                   d * out["moment"][2]]))
            force += f_body
            moment += m_body + np.cross(hub, f_body)
            xdot[base:base + 4] = flap_rate
            xdot[base + 4:base + 8] = out["flap_accel"]
            loads += [out["ct"], out["cl"], out["cm"]]
            rates_tpp += list(out["tpp_rates"])
            extra[f"torque{rotor_suffix(rc.name)}"] = out["torque"]
            extra[f"CQ{rotor_suffix(rc.name)}"] = out["cq"]
        loads = np.array(loads)
        if cfg.is_coaxial:
            thrust, torque = propeller_loads(cfg.propeller, u[6], vel[0], cfg.rho,
                                             model=self.settings.propeller_model)
            pos = np.asarray(cfg.propeller.position, float) if cfg.propeller else np.zeros(3)
            fp = np.array([thrust, 0.0, 0.0])
            force += fp
            moment += np.cross(pos, fp) + np.array([torque, 0.0, 0.0])
        elif cfg.tail_rotor is not None:
            tr = cfg.tail_rotor
            pos = np.asarray(tr.position, float)
            f_tr, power_tr = tail_rotor_loads(tr, u[3], vel + np.cross(rates, pos), cfg.rho)
            force += f_tr
            moment += np.cross(pos, f_tr)
            extra["power_tr"] = power_tr
        else:
            moment[2] += self.settings.tail_rotor_yaw_per_rad * u[3]
        ff, mf = fuselage_loads(cfg, vel, rates)
        force += ff
        moment += mf
        m = cfg.mass
        g = GRAVITY
        p, q, r = rates
        uu, vv, ww = vel
        xdot[0] = r * vv - q * ww - g * np.sin(theta) + force[0] / m
        xdot[1] = p * ww - r * uu + g * np.sin(phi) * np.cos(theta) + force[1] / m
        xdot[2] = q * uu - p * vv + g * np.cos(phi) * np.cos(theta) + force[2] / m
        xdot[3:6] = self.inertia_inv @ (moment - np.cross(rates, self.inertia @ rates))
        xdot[6] = p + (q * np.sin(phi) + r * np.cos(phi)) * np.tan(theta)
        xdot[7] = q * np.cos(phi) - r * np.sin(phi)
        xdot[8] = (q * np.sin(phi) + r * np.cos(phi)) / np.cos(theta)
        # blade inertial coupling with the body angular acceleration (see rotor.py)
        for k, rm in enumerate(self.rotors):
            d = rm.config.direction
            acc_s = self._to_shaft(k, xdot[3:6])
            acc_r = np.array([d * acc_s[0], acc_s[1], d * acc_s[2]])
            base = 9 + 8 * k
            xdot[base + 4:base + 8] += rm.flap_acceleration_correction(acc_r)
        # full tip-path-plane rates (body rates included, Eq. 2.29; RotorModel.tpp_rates)
        tpp = np.array(rates_tpp) if self.inflow.uses_flap_rates else None
        xdot[self.n_rigid:] = self.inflow.derivatives(xin, loads, ops, tpp)
        extra.update({"loads": loads, "force": force, "moment": moment, "ops": ops, "inflow": lam})
        return xdot, extra

    def derivatives(self, x, u):
        """dx/dt [SI] for state ``x`` and rotor controls ``u``."""
        return self.evaluate(x, u)[0]
