"""Fuselage, empennage and pusher propeller (simple models; assumptions in configs).

* Fuselage: flat-plate drag areas f_x (along x) and f_z (along y and z):
  F = -1/2 rho f |V| V per axis.
* Horizontal / vertical tail: linear lift from the local angle of attack of the
  free stream (rotor downwash on the tail is not modelled), at the tail position.
* Propeller (Bailey-type momentum rotor, Appendix B.2): thrust along +x from
  blade-element momentum theory with uniform inflow, torque about x.
"""
from __future__ import annotations

import numpy as np

__all__ = ["fuselage_loads", "propeller_loads"]


def fuselage_loads(config, velocity, rates):
    """Force and moment (body axes, about the c.g.) from fuselage and tails."""
    rho = config.rho
    v = np.asarray(velocity, float)
    speed = np.linalg.norm(v)
    f = -0.5 * rho * speed * np.array([config.fuselage_fx * v[0], config.fuselage_fz * v[1],
                                       config.fuselage_fz * v[2]])
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


def propeller_loads(prop, theta, forward_speed, rho):
    """(thrust [N] along +x, torque [N m]) of the pusher at collective ``theta`` [rad]."""
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
