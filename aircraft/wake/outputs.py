"""Rotor outputs of the free-vortex wake: blade-sum loads and inflow harmonics.

All quantities are in each rotor's *own* frame (see :mod:`aircraft.inflow.base`):
azimuth from aft in the direction of rotation, inflow positive down, loads
``C_T``, ``C_L = -sum dT r sin psi``, ``C_M = -sum dT r cos psi`` on
``rho pi R^2 (Omega R)^2 (R)``.
"""
from __future__ import annotations

import numpy as np

__all__ = ["blade_sum_loads", "blade_sum_inflow", "flap_rate_mbc", "flap_mbc"]


def blade_sum_loads(dT, dQ, r, psi, thrust_scale):
    """Rotor loads from element forces.

    Parameters
    ----------
    dT : ndarray, shape (Nb, Ne)
        Element thrust (along the shaft, up) [N].
    dQ : ndarray, shape (Nb, Ne)
        Element in-plane drag force opposing rotation [N].
    r : ndarray, shape (Ne,)
        Element radius r/R [-].
    psi : ndarray, shape (Nb,)
        Blade azimuths in the rotor's own frame [rad].
    thrust_scale : float
        rho pi R^2 (Omega R)^2 [N].

    Returns
    -------
    (CT, CL, CM, CQ) : floats [-]
    """
    ct = dT.sum() / thrust_scale
    cl = -(dT * r[None, :] * np.sin(psi)[:, None]).sum() / thrust_scale
    cm = -(dT * r[None, :] * np.cos(psi)[:, None]).sum() / thrust_scale
    cq = (dQ * r[None, :]).sum() / thrust_scale
    return ct, cl, cm, cq


def blade_sum_inflow(lam, r, dr, psi):
    """Inflow harmonics by the blade sums of Eqs. 2.22, 2.25, 2.26.

    ``lam0 = 1/N_b sum_n int lam dr``, ``lam1s = 6/N_b sum_n int lam r sin(psi_n) dr``,
    ``lam1c`` likewise with cos.  The blade exists only outboard of the root cut-out,
    so the radial integrals are normalised by their value for the exact distribution
    ``lam0 + lam1s r sin psi + lam1c r cos psi`` (``int dr`` and ``int r^2 dr`` over the
    elements instead of 1 and 1/3); with N_b >= 3 that distribution is then recovered
    exactly.

    Parameters
    ----------
    lam : ndarray, shape (Nb, Ne)
        Induced inflow at the elements, positive down, on Omega R [-].
    r, dr : ndarray, shape (Ne,)
        Element radius and width, on R [-].
    psi : ndarray, shape (Nb,)
        Blade azimuths [rad].
    """
    nb = lam.shape[0]
    w0 = dr.sum()
    w1 = (r ** 2 * dr).sum()
    lam0 = (lam * dr).sum() / (nb * w0)
    lam1s = 2.0 * (lam * (r * dr)[None, :] * np.sin(psi)[:, None]).sum() / (nb * w1)
    lam1c = 2.0 * (lam * (r * dr)[None, :] * np.cos(psi)[:, None]).sum() / (nb * w1)
    return lam0, lam1s, lam1c


def flap_rate_mbc(beta, beta_dot, psi, omega):
    """Time derivatives of the multiblade flap coordinates [rad/s].

    ``beta1c = 2/N_b sum beta_n cos psi_n``, ``beta1s = 2/N_b sum beta_n sin psi_n``;
    their exact time derivatives use d psi_n / dt = Omega.

    Returns
    -------
    (beta1s_dot, beta1c_dot)
    """
    nb = beta.shape[0]
    s, c = np.sin(psi), np.cos(psi)
    b1c_dot = 2.0 / nb * np.sum(beta_dot * c - omega * beta * s)
    b1s_dot = 2.0 / nb * np.sum(beta_dot * s + omega * beta * c)
    return b1s_dot, b1c_dot


def flap_mbc(beta, psi):
    """Multiblade flap coordinates of the blades [rad].

    ``beta0 = 1/N_b sum beta_n``, ``beta1c = 2/N_b sum beta_n cos psi_n``,
    ``beta1s = 2/N_b sum beta_n sin psi_n`` (exact for N_b >= 3 blades flapping
    as ``beta0 + beta1c cos psi + beta1s sin psi``).

    Parameters
    ----------
    beta : ndarray, shape (Nb,)
        Blade flap angles [rad].
    psi : ndarray, shape (Nb,)
        Blade azimuths in the rotor's own frame [rad].

    Returns
    -------
    (beta0, beta1s, beta1c) : floats [rad]
    """
    nb = beta.shape[0]
    return (float(beta.mean()), float(2.0 / nb * np.sum(beta * np.sin(psi))),
            float(2.0 / nb * np.sum(beta * np.cos(psi))))
