"""Blade-element rotor with hingeless flapping in multi-blade coordinates.

Each rotor is computed in its own frame (x forward, y to the right of a
counter-clockwise rotor, z down; a clockwise rotor uses the mirror image y -> -y,
see :mod:`aircraft.inflow.base`), so one code serves both rotors of a coaxial.

Blade element: quasi-steady, linear lift with a stall clip, constant profile
drag, Gauss-Legendre points over the lifting span, N_b blades. Element velocities
and forces are formed as 3-D vectors (hub translation, body rotation, rotor
rotation, flapping, induced inflow lambda(r, psi) = lam0 + lam1s r sin psi +
lam1c r cos psi along the shaft, down), so U_T, U_P and force directions follow
from geometry rather than hand-expanded formulas.

Flapping (rigid blade about an equivalent hinge at e R, spring giving nu_beta)::

    beta_k'' = -nu^2 Omega^2 beta_k + M_aero,k / I_b + 2 Omega (p cos psi_k - q sin psi_k)

      + (p_dot sin psi + q_dot cos psi)

(p, q in the rotor frame; blade weight neglected). The body angular
accelerations depend only on flap *positions* (hub spring and shear moments), so
the aircraft computes them first and :meth:`RotorModel.flap_acceleration_correction`
adds their term; with blades as heavy as these (I_b comparable to the
aircraft's roll inertia) dropping it destabilises the flap-body coupling. The blade equations are projected exactly onto the multi-blade
coordinates (beta0, beta1c, beta1s, betad for 4 blades) and, for a time-invariant
model, averaged over ``n_average`` reference azimuths in one blade passage.
Hub moments: effective hub stiffness (nu^2 - 1) I_b Omega^2 per blade plus the
hinge-force moments; shaft torque reaction along the shaft.
"""
from __future__ import annotations

import numpy as np

from ..configs import RotorConfig

__all__ = ["RotorModel", "FLAP_STATES"]

FLAP_STATES = ("beta0", "beta1c", "beta1s", "betad")


class RotorModel:
    """Loads and flap dynamics of one rotor (vectorised over azimuths, blades, span).

    Parameters
    ----------
    config : RotorConfig
    n_span : int
        Gauss-Legendre points over the lifting span.
    n_average : int
        Reference azimuths averaged over one blade passage (1 is exact in hover).
    rho : float
        Air density [kg/m^3].
    """

    def __init__(self, config: RotorConfig, n_span=8, n_average=4, rho=1.225):
        if config.n_blades not in (2, 3, 4):
            raise ValueError("the multi-blade coordinates here support 2-4 blades")
        self.config = config
        self.rho = rho
        x, w = np.polynomial.legendre.leggauss(n_span)
        c0 = config.root_cutout
        self.r = c0 + (1 - c0) * (x + 1) / 2             # r/R
        self.wr = w * (1 - c0) / 2 * config.radius        # weights in metres
        self.psi_ref = np.arange(n_average) * (2 * np.pi / config.n_blades) / n_average
        self.blade_offsets = 2 * np.pi * np.arange(config.n_blades) / config.n_blades
        self.i_b = config.blade_flap_inertia
        self.k_eff = (config.flap_frequency ** 2 - 1.0) * self.i_b * config.omega ** 2
        self.scale_t = rho * config.disk_area * config.tip_speed ** 2
        self.d_sign = np.array([(-1.0) ** k for k in range(config.n_blades)])

    def flap_acceleration_correction(self, angular_acceleration):
        """MBC flap-acceleration increment from body angular acceleration (rotor frame).

        Blade term p_dot sin psi_k + q_dot cos psi_k projects exactly onto
        beta1s (p_dot) and beta1c (q_dot): returns (0, q_dot, p_dot, 0).
        """
        pd, qd = angular_acceleration[0], angular_acceleration[1]
        return np.array([0.0, qd, pd, 0.0])

    @staticmethod
    def tpp_rates(flap_rate, rates):
        """Full (space-fixed) tip-path-plane rates ``(beta1s_dot, beta1c_dot)`` [rad/s].

        In the rotor frame (x forward, y to the advancing side at psi = 90 deg, z
        down) a blade's elevation above the space-fixed plane is
        ``beta - phi sin(psi) - theta cos(psi)`` (roll right-side-down lowers the
        psi = 90 deg side, pitch nose-up the aft psi = 0 side), so::

            beta1s_dot_full = beta1s_dot - p_r,    beta1c_dot_full = beta1c_dot - q_r

        with the body rates in the rotor frame, ``p_r = direction * p``,
        ``q_r = q`` (the clockwise lower rotor mirrors y). Divided by Omega these
        are ``-(Delta p / Omega - beta1s*)`` and ``-(Delta q / Omega - beta1c*)``, the
        bracket of Eq. 2.29 with its sign: an inflow model forced by
        ``-K_R * rate / Omega`` is Eq. 2.29 with the body-rate terms included.

        Parameters
        ----------
        flap_rate : array (4,)
            Shaft-relative MBC flap rates (beta0, beta1c, beta1s, betad) [rad/s].
        rates : array (3,)
            Body angular velocity in the rotor frame [rad/s].
        """
        return np.array([flap_rate[2] - rates[0], flap_rate[1] - rates[1]])

    def evaluate(self, flap, flap_rate, controls, inflow, hub_velocity, rates):
        """Rotor-frame loads and flap accelerations.

        Parameters
        ----------
        flap, flap_rate : array (4,)
            (beta0, beta1c, beta1s, betad) [rad] and their time derivatives [rad/s].
        controls : array (3,)
            (theta0, theta1s, theta1c) [rad] in the rotor's own azimuth.
        inflow : array (3,)
            (lam0, lam1s, lam1c), total (interference included), on Omega R.
        hub_velocity : array (3,)
            Hub velocity relative to the air [m/s], rotor frame.
        rates : array (3,)
            Body angular velocity [rad/s], rotor frame.

        Returns
        -------
        dict with ``force`` (3,) [N] and ``moment`` (3,) [N m] on the body at the hub
        (rotor frame), ``ct, cl, cm`` (aerodynamic, convention of
        :mod:`aircraft.inflow.base`), ``cq`` and ``torque`` [N m], ``flap_accel``
        (4,) [rad/s^2] in MBC, ``tpp_rates`` (beta1s_dot, beta1c_dot) [rad/s]: the
        *full* tip-path-plane rates relative to space (:meth:`tpp_rates`), what
        the wake-distortion inputs of an inflow model take (Eq. 2.29).
        """
        cfg = self.config
        om, R = cfg.omega, cfg.radius
        psi = self.psi_ref[:, None] + self.blade_offsets[None, :]          # (na, nb)
        b0, b1c, b1s, bd = flap
        db0, db1c, db1s, dbd = flap_rate
        nb = cfg.n_blades
        dsg = self.d_sign[None, :] if nb == 4 else 0.0
        cp, sp = np.cos(psi), np.sin(psi)
        beta = b0 + b1c * cp + b1s * sp + bd * dsg
        beta_dot = db0 + (db1c + om * b1s) * cp + (db1s - om * b1c) * sp + dbd * dsg
        # unit vectors (na, nb, 3)
        z = np.zeros_like(psi)
        e_r = np.stack([-cp, sp, z], -1)
        t = np.stack([sp, cp, z], -1)
        up = np.array([0.0, 0.0, -1.0])
        cb, sb = np.cos(beta)[..., None], np.sin(beta)[..., None]
        e_s = cb * e_r + sb * up
        n = -sb * e_r + cb * up
        hinge = cfg.hinge_offset * R * e_r                                  # (na, nb, 3)
        s = (self.r - cfg.hinge_offset) * R                                 # (ns,)
        pos = hinge[:, :, None, :] + s[None, None, :, None] * e_s[:, :, None, :]
        omega_vec = np.asarray(rates, float) + om * up
        v_el = (np.asarray(hub_velocity, float) + np.cross(omega_vec, pos)
                + (s[None, None, :, None] * beta_dot[:, :, None, None]) * n[:, :, None, :])
        lam0, lam1s, lam1c = inflow
        lam = lam0 + self.r[None, None, :] * (lam1s * sp[..., None] + lam1c * cp[..., None])
        v_air = np.zeros_like(v_el)
        v_air[..., 2] = lam * om * R
        w_rel = v_air - v_el
        ut = -np.einsum("abkx,abx->abk", w_rel, t)
        up_ = -np.einsum("abkx,abx->abk", w_rel, n)
        th0, th1s, th1c = controls
        theta = th0 + cfg.twist * self.r[None, None, :] + (th1c * cp + th1s * sp)[..., None]
        # inflow angle; in reverse flow (ut < 0, air from the trailing edge) it is
        # wrapped into +-90 deg, so a flat section at small incidence sees a small
        # angle of attack, and lift_dir (normal to the relative wind, along -n
        # there) gives the flat-plate normal force of the right sign
        inflow_angle = np.arctan2(up_, ut)
        inflow_angle = np.where(ut < 0.0, np.arctan2(-up_, -ut), inflow_angle)
        alpha = theta - inflow_angle
        cl = cfg.lift_slope * np.clip(alpha, -cfg.stall_angle, cfg.stall_angle)
        u2 = ut ** 2 + up_ ** 2
        u = np.sqrt(u2)
        q = 0.5 * self.rho * cfg.chord * u2 * self.wr[None, None, :]       # N per element / coeff
        lift_dir = (n[:, :, None, :] * ut[..., None] - t[:, :, None, :] * up_[..., None]) / u[..., None]
        drag_dir = -(t[:, :, None, :] * ut[..., None] + n[:, :, None, :] * up_[..., None]) / u[..., None]
        f = (q * cl)[..., None] * lift_dir + (q * cfg.cd0)[..., None] * drag_dir   # (na, nb, ns, 3)
        m_flap = np.einsum("abk,abkx,abx->ab", np.broadcast_to(s, f.shape[:3]), f, n)
        f_blade = f.sum(axis=2)                                             # (na, nb, 3)
        aero_moment = np.cross(pos, f).sum(axis=2)                         # about hub
        # individual blade flap accelerations and their MBC projection (exact for nb = 4)
        p_r, q_r = rates[0], rates[1]
        acc = (-(cfg.flap_frequency * om) ** 2 * beta + m_flap / self.i_b
               + 2 * om * (p_r * cp - q_r * sp))
        a0 = acc.mean(axis=1)
        xc = 2 * (acc * cp).mean(axis=1)
        xs = 2 * (acc * sp).mean(axis=1)
        ad = (acc * dsg).mean(axis=1) if nb == 4 else np.zeros_like(a0)
        dd_b1c = xc - 2 * om * db1s + om ** 2 * b1c
        dd_b1s = xs + 2 * om * db1c + om ** 2 * b1s
        flap_accel = np.array([a0.mean(), dd_b1c.mean(), dd_b1s.mean(), ad.mean()])
        # loads transmitted to the hub
        total_force = f_blade.sum(axis=1).mean(axis=0)
        flap_axis = np.cross(e_r, up)                                       # (na, nb, 3)
        spring = (self.k_eff * beta)[..., None] * flap_axis
        hinge_moment = np.cross(hinge, f_blade)
        hub_moment = (spring + hinge_moment).sum(axis=1).mean(axis=0)
        aero_m = aero_moment.sum(axis=1).mean(axis=0)
        torque = -aero_m @ up                                               # shaft torque needed [N m]
        hub_moment[2] = torque                                              # reaction on the body (z down)
        scale_m = self.scale_t * R
        return {
            "force": total_force, "moment": hub_moment,
            "ct": -total_force[2] / self.scale_t,
            "cl": aero_m[0] / scale_m, "cm": aero_m[1] / scale_m,
            "torque": torque, "cq": torque / scale_m,
            "flap_accel": flap_accel,
            "tpp_rates": self.tpp_rates(flap_rate, rates),
        }
