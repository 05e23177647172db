"""Prescribed starting geometry of the free tip vortices (before any marching).

Hover (advance ratio below 0.05): Landgrebe's prescribed wake -- contraction to
0.78 R and a two-rate descent (Leishman, Principles of Helicopter Aerodynamics,
Sec. 10.7). Forward flight: an undistorted helix skewed by the free stream and
the momentum (Glauert) inflow. Either is only the march's initial condition.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["initial_tip_vortices"]


def initial_tip_vortices(wake, ir, ct, ages, mu):
    """Starting tip-vortex markers of rotor ``ir``.

    Parameters
    ----------
    wake : FreeVortexWake
        The wake (rotors, rotor speed, free stream, starting inflow ``_lam0``).
    ir : int
        Rotor index.
    ct : float
        Starting thrust coefficient of the rotor [-].
    ages : ndarray, shape (n_markers,)
        Wake age of each marker [rad].
    mu : float
        Advance ratio [-] (chooses the hover or the skewed-helix wake).

    Returns
    -------
    ndarray, shape (Nb, n_markers, 3)
        Marker positions in the computational frame [m].
    """
    rot = wake.rotors[ir]
    nk = ages.size
    sigma = rot.nb * rot.chord / (math.pi * rot.R)
    psib = wake._psi_blades(rot, wake.psi)
    X = np.empty((rot.nb, nk, 3))
    if mu < 0.05:
        # Landgrebe prescribed hover wake (Leishman, Principles, Sec. 10.7)
        tw = math.degrees(rot.twist)
        k1 = -0.25 * (ct / sigma + 0.001 * tw)
        k2 = -(1.41 + 0.0141 * tw) * math.sqrt(ct / 2.0)
        lam = 0.145 + 27.0 * ct
        rad = 0.78 + 0.22 * np.exp(-lam * ages)
        zb = 2 * np.pi / rot.nb
        zz = np.where(ages <= zb, k1 * ages, k1 * zb + k2 * (ages - zb))
        for b in range(rot.nb):
            ang = psib[b] - ages
            X[b, :, 0] = -rad * np.cos(ang)
            X[b, :, 1] = -rot.d * rad * np.sin(ang)
            X[b, :, 2] = zz
        X = rot.hub + rot.R * X + wake.v_inf * (ages / wake.omega)[None, :, None]
    else:
        # skewed undistorted helix with the momentum (Glauert) inflow
        vi = wake._lam0[ir] * wake.omega * rot.R
        drift = wake.v_inf - np.array([0.0, 0.0, vi])
        for b in range(rot.nb):
            ang = psib[b] - ages
            X[b, :, 0] = -rot.R * np.cos(ang)
            X[b, :, 1] = -rot.d * rot.R * np.sin(ang)
            X[b, :, 2] = 0.0
        X = rot.hub + X + drift * (ages / wake.omega)[None, :, None]
    return X
