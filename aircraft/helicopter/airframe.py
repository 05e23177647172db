"""Fuselage, empennage and pusher propeller (simple models; assumptions in configs).

* Fuselage: drag along body x from the area f_x, F_x = -1/2 rho f_x |V| u;
  cross-flow drag on the area f_z from the cross-flow velocity alone,
  (F_y, F_z) = -1/2 rho f_z |v_c| (v, w) with |v_c| = sqrt(v^2 + w^2) (a flat
  plate in cross flow is a drag, not a lifting surface); lift from its own area
  ``fuselage_lift_area`` (per rad), L = 1/2 rho (u^2 + w^2) S_L alpha,
  alpha = atan2(w, u), normal to the x-z velocity, in forward flight (u > 1 m/s).
* Tail rotor (single-rotor aircraft): blade-element momentum theory with
  uniform quasi-steady inflow (Glauert), thrust along body +-y.
* Horizontal / vertical tail: linear lift from the local angle of attack of the
  free stream (rotor downwash on the tail is not modelled), at the tail position.
* Propeller (Bailey-type momentum rotor, Appendix B.2): thrust along +x from
  blade-element momentum theory with uniform inflow, torque about x; or, with
  ``model="blade_element"``, annulus blade-element momentum theory with the
  twist and exact inflow angles (:mod:`aircraft.helicopter.propeller`).
"""
from __future__ import annotations

import numpy as np

from .propeller import propeller_blade_element

__all__ = ["fuselage_loads", "propeller_loads", "tail_rotor_loads", "PROPELLER_MODELS"]


def fuselage_loads(config, velocity, rates):
    """Force and moment (body axes, about the c.g.) from fuselage and tails.

    Parameters
    ----------
    config : AircraftConfig
        Areas, positions and lift slopes of fuselage and tails, air density.
    velocity : array (3,)
        Body velocity relative to the air (u, v, w) [m/s].
    rates : array (3,)
        Body angular velocity (p, q, r) [rad/s].

    Returns
    -------
    force, moment : numpy.ndarray (3,)
        [N] and [N m] in body axes about the c.g.

    Examples
    --------
    >>> from aircraft import coaxial_compound
    >>> f, m = fuselage_loads(coaxial_compound(), [0.0, 0.0, 2.0], [0.0, 0.0, 0.0])
    >>> round(float(f[2]), 3)          # -1/2 rho f_z w^2 = -0.5 * 1.225 * 20 * 4
    -49.0
    """
    rho = config.rho
    v = np.asarray(velocity, float)
    speed = np.linalg.norm(v)
    cross = np.hypot(v[1], v[2])
    f = -0.5 * rho * np.array([config.fuselage_fx * speed * v[0], config.fuselage_fz * cross * v[1],
                               config.fuselage_fz * cross * v[2]])
    if config.fuselage_lift_area and v[0] > 1.0:
        q_xz = 0.5 * rho * (v[0] ** 2 + v[2] ** 2)
        lift = q_xz * config.fuselage_lift_area * np.arctan2(v[2], v[0])
        f = f + lift * np.array([v[2], 0.0, -v[0]]) / np.hypot(v[0], v[2])
    m = np.zeros(3)
    for area, pos, slope, axis in ((config.htail_area, config.htail_position, config.htail_lift_slope, 2),
                                   (config.vtail_area, config.vtail_position, config.vtail_lift_slope, 1)):
        pos = np.asarray(pos, float)
        v_local = v + np.cross(rates, pos)
        if v_local[0] <= 1.0:
            continue   # no meaningful tail aerodynamics in hover / rearward flight
        alpha = np.arctan2(v_local[axis], v_local[0])
        q = 0.5 * rho * (v_local[0] ** 2 + v_local[axis] ** 2)
        lift = -q * area * slope * alpha   # opposes the cross-flow component
        force = np.zeros(3)
        force[axis] = lift
        f = f + force
        m = m + np.cross(pos, force)
    return f, m


#: propeller models of :func:`propeller_loads`
PROPELLER_MODELS = ("momentum", "blade_element")


def propeller_loads(prop, theta, forward_speed, rho, model="momentum"):
    """(thrust [N] along +x, torque [N m]) of the pusher at collective ``theta`` [rad].

    ``model="momentum"`` (default): uniform inflow and the small-angle formula
    with the pitch at three-quarter radius; ``"blade_element"``: annulus
    blade-element momentum theory with the twist and exact inflow angles
    (:func:`~aircraft.helicopter.propeller.propeller_blade_element`).
    """
    if model not in PROPELLER_MODELS:
        raise ValueError(f"model must be one of {PROPELLER_MODELS}, got {model!r}")
    if model == "blade_element":
        return propeller_blade_element(prop, theta, forward_speed, rho)
    if prop is None:
        return 0.0, 0.0
    vt = prop.omega * prop.radius
    mu = max(forward_speed, 0.0) / vt
    area = np.pi * prop.radius ** 2
    sa = prop.solidity * prop.lift_slope
    lam_i = 0.0
    for _ in range(60):
        # blade element C_T = sigma a / 2 (theta/3 - (mu + lam_i)/2); momentum C_T = 2 lam_i (mu + lam_i)
        ct_be = sa / 2 * (theta / 3 - (mu + lam_i) / 2)
        f = 2 * lam_i * (mu + lam_i) - ct_be
        df = 2 * mu + 4 * lam_i + sa / 4
        step = f / df
        lam_i -= step
        if abs(step) < 1e-13:
            break
    ct = sa / 2 * (theta / 3 - (mu + lam_i) / 2)
    cq = ct * (mu + lam_i) + prop.solidity * prop.cd0 / 8
    scale = rho * area * vt ** 2
    return ct * scale, cq * scale * prop.radius


def tail_rotor_loads(tail, theta, velocity, rho):
    """Side force [N] (body axes) and power [W] of a tail rotor at collective ``theta`` [rad].

    Uniform inflow from blade-element and Glauert momentum theory, solved by Newton
    iteration to round-off (smooth in every argument, so finite-difference
    linearisation sees it)::

        C_T = sigma a / 2 [theta_0 (1/3 + mu^2 / 2) + theta_tw (1 + mu^2) / 4 - lambda / 2]
        C_T = 2 lambda_i sqrt(mu^2 + lambda^2),   lambda = mu_c + lambda_i

    with ``theta_0 = theta - 0.75 theta_tw`` (``theta`` is the collective at 3/4
    radius), ``mu_c`` the hub velocity along the thrust axis and ``mu`` the in-plane
    speed, both on the tip speed; C_Q = C_T lambda + sigma c_d0 / 8 (1 + 4.65 mu^2).
    The thrust axis is body ``thrust_sign * y``; the rotor's shaft torque is not
    applied to the body.

    Parameters
    ----------
    tail : TailRotorConfig
    theta : float
        Collective pitch at 3/4 radius [rad].
    velocity : array (3,)
        Velocity of the tail-rotor hub relative to the air, body axes [m/s].
    rho : float
        Air density [kg/m^3].

    Returns
    -------
    force : numpy.ndarray (3,)
        Force on the body [N], along body y.
    power : float
        Shaft power [W].

    Examples
    --------
    >>> from aircraft.configs import TailRotorConfig
    >>> tr = TailRotorConfig()
    >>> f, p = tail_rotor_loads(tr, 0.2, [0.0, 0.0, 0.0], 1.225)   # hover, 11.5 deg
    >>> round(float(f[1]) / 1e3, 2), round(p / 1e3, 1)                # side force [kN], power [kW]
    (6.44, 134.1)
    """
    v = np.asarray(velocity, float)
    vt = tail.tip_speed
    axis = float(tail.thrust_sign)
    mu_c = axis * v[1] / vt
    mu = np.hypot(v[0], v[2]) / vt
    sa = tail.solidity * tail.lift_slope
    theta0 = theta - 0.75 * tail.twist
    ct_geo = sa / 2 * (theta0 * (1 / 3 + mu ** 2 / 2) + tail.twist * (1 + mu ** 2) / 4)
    # start from the hover momentum value (sign of the blade-element thrust)
    ct_start = ct_geo - sa / 4 * mu_c
    lam_i = np.sign(ct_start) * np.sqrt(abs(ct_start) / 2) + 1e-9
    for _ in range(60):
        lam = mu_c + lam_i
        root = np.sqrt(mu ** 2 + lam ** 2)
        f = 2 * lam_i * root - (ct_geo - sa / 4 * lam)
        df = 2 * root + 2 * lam_i * lam / root + sa / 4
        step = f / df
        lam_i -= step
        if abs(step) < 1e-14:
            break
    lam = mu_c + lam_i
    ct = ct_geo - sa / 4 * lam
    cq = ct * lam + tail.solidity * tail.cd0 / 8 * (1 + 4.65 * mu ** 2)
    scale = rho * tail.disk_area * vt ** 2
    force = np.array([0.0, axis * ct * scale, 0.0])
    return force, float(cq * scale * tail.radius * tail.omega)
