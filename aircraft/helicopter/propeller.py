"""Pusher propeller by blade-element momentum theory with its twist and large inflow angles.

The uniform-inflow propeller of :func:`~aircraft.helicopter.airframe.propeller_loads`
uses the small-angle rotor formula ``C_T = sigma a / 2 (theta / 3 - lambda / 2)``
with the pitch at three-quarter radius alone. A pusher at cruise runs at an
axial inflow ratio ``mu = V / (Omega R)`` of about 0.4, so the inflow angle
``phi = atan(lambda / r)`` is 28 deg at three-quarter radius and 53 deg at
0.3 R, and its pitch is set to match: the small-angle formula does not hold.
Here each annulus of radius ``r`` (on R) balances the blade-element thrust,
with the exact angles, against the annulus momentum thrust::

    dC_T = sigma / 2 U^2 (c_l cos(phi) - c_d sin(phi)) dr = 4 lambda_i |mu + lambda_i| r dr
    dC_Q = sigma / 2 U^2 (c_l sin(phi) + c_d cos(phi)) r dr
    U^2 = r^2 + (mu + lambda_i)^2,  phi = atan2(mu + lambda_i, r)
    c_l = a (theta(r) - phi),  theta(r) = theta_75 + twist (r - 0.75),  c_d = c_d0

(no stall, no tip loss, blades from the axis to the tip, as the uniform-inflow
model). The induced velocity of each annulus is solved by Newton iteration to
round-off, so the loads are smooth in every argument and finite-difference
linearisation sees them. In the small-angle limit this is the classical
annulus solution::

    lambda(r) = sqrt((sigma a / 16 - mu / 2)^2 + sigma a theta r / 8) - (sigma a / 16 - mu / 2)
"""
from __future__ import annotations

import numpy as np

__all__ = ["propeller_blade_element"]

_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(24)
#: Gauss points on r in (0, 1)
_R = 0.5 * (_NODES + 1.0)
_W = 0.5 * _WEIGHTS


def _element_thrust(prop, theta_r, mu, lam_i):
    lam = mu + lam_i
    phi = np.arctan2(lam, _R)
    u2 = _R ** 2 + lam ** 2
    cl = prop.lift_slope * (theta_r - phi)
    ct = 0.5 * prop.solidity * u2 * (cl * np.cos(phi) - prop.cd0 * np.sin(phi))
    cq = 0.5 * prop.solidity * u2 * (cl * np.sin(phi) + prop.cd0 * np.cos(phi)) * _R
    return ct, cq


def _residual(prop, theta_r, mu, lam_i):
    return 4.0 * lam_i * np.abs(mu + lam_i) * _R - _element_thrust(prop, theta_r, mu, lam_i)[0]


def propeller_blade_element(prop, theta, forward_speed, rho):
    """Thrust [N] along +x and torque [N m] of a pusher by annulus blade-element momentum theory.

    Parameters
    ----------
    prop : PropellerConfig or None
        Radius, speed, solidity, lift slope, ``cd0`` and linear ``twist`` [rad]
        (tip minus root). ``None``: no propeller, zero loads.
    theta : float
        Pitch at three-quarter radius [rad].
    forward_speed : float
        Axial speed of the air through the disk [m/s]; negative speeds count as zero.
    rho : float
        Air density [kg/m^3].

    Returns
    -------
    thrust : float
        [N], positive forward.
    torque : float
        Shaft torque [N m] (power = torque * omega).

    Raises
    ------
    ValueError
        ``theta``, ``forward_speed`` or ``rho`` is not a finite number, or
        ``rho`` is not positive.

    Examples
    --------
    >>> import math
    >>> from aircraft.configs import PropellerConfig
    >>> thrust, torque = propeller_blade_element(PropellerConfig(), math.radians(40.0), 100.0, 1.225)
    >>> round(thrust / 1e3, 1), round(torque * PropellerConfig().omega / 1e6, 2)   # kN, MW
    (27.3, 3.08)
    """
    for name, value in (("theta", theta), ("forward_speed", forward_speed), ("rho", rho)):
        if isinstance(value, bool) or not isinstance(value, (int, float, np.floating)) or not np.isfinite(value):
            raise ValueError(f"{name} must be a finite number, got {value!r}")
    if rho <= 0:
        raise ValueError(f"rho must be positive [kg/m^3], got {rho!r}")
    if prop is None:
        return 0.0, 0.0
    vt = prop.omega * prop.radius
    mu = max(float(forward_speed), 0.0) / vt
    theta_r = theta + prop.twist * (_R - 0.75)
    # start from the small-angle annulus solution (exact in that limit)
    sa = prop.solidity * prop.lift_slope
    b = sa / 16.0 - mu / 2.0
    lam_i = np.sqrt(np.maximum(b ** 2 + sa * theta_r * _R / 8.0, 0.0)) - b - mu
    for _ in range(100):
        f = _residual(prop, theta_r, mu, lam_i)
        h = 1e-7 * (1.0 + np.abs(lam_i))
        df = (_residual(prop, theta_r, mu, lam_i + h) - _residual(prop, theta_r, mu, lam_i - h)) / (2 * h)
        step = f / df
        # the momentum side turns at lambda_i = -mu / 2: keep the iterate on its rising branch
        lam_new = np.maximum(lam_i - step, -0.5 * mu + 1e-12 if mu > 0 else -np.inf)
        done = np.max(np.abs(lam_new - lam_i)) < 1e-14
        lam_i = lam_new
        if done:
            break
    ct_el, cq_el = _element_thrust(prop, theta_r, mu, lam_i)
    ct, cq = float(_W @ ct_el), float(_W @ cq_el)
    scale = rho * np.pi * prop.radius ** 2 * vt ** 2
    return ct * scale, cq * scale * prop.radius
