"""Compiled geometry of the blades' rigid near wake (numba), for the wake march.

The near wake of every blade is rebuilt at least twice per time step (velocities at
the start of the step, and after the blades advance), and the former numpy version
looped in Python over the near-wake ages, building the blade frames once per age:
at the default resolution it cost as much as a third of the Biot-Savart kernel.
:func:`near_wake_points` does the same arithmetic in one compiled loop.

Round-off: each point is the same sequence of IEEE-754 operations, in the same
order, as :meth:`aircraft.wake.wake.FreeVortexWake._near_wake_points` of the
reference march (:mod:`aircraft.wake.reference`), including the additions of
exact zeros from the unit vector z, and it is compiled without ``fastmath`` (no
reassociation, no fused multiply-add). The sines and cosines are computed by numpy
and passed in, so no libm difference between numba and numpy enters either: the
result equals the reference bit for bit.
"""
from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["near_wake_points"]


@njit(cache=True, fastmath=False)
def _near_wake_kernel(hub, radius, hinge, direction, r_edge, cos_psi, sin_psi, cos_beta,
                      sin_beta, contraction, drift, ages, omega):
    nb, na = cos_psi.shape
    ne1 = r_edge.shape[0]
    out = np.empty((nb, ne1, na, 3))
    r_e = radius * hinge                 # (R e), grouped as in the reference
    md = -float(direction)
    for b in range(nb):
        cb = cos_beta[b]
        sb = sin_beta[b]
        for m in range(na):
            # blade frame at this age: radial e_r, flapped span direction
            erx = -cos_psi[b, m]
            ery = md * sin_psi[b, m]
            erz = 0.0
            # span = cos(beta) e_r + sin(beta) z, with z = (0, 0, 1) written out
            spx = cb * erx + sb * 0.0
            spy = cb * ery + sb * 0.0
            spz = cb * erz + sb * 1.0
            cm = contraction[m]
            sx = drift[0] * ages[m] / omega
            sy = drift[1] * ages[m] / omega
            sz = drift[2] * ages[m] / omega
            for j in range(ne1):
                rs = radius * (r_edge[j] - hinge)
                px = hub[0] + r_e * erx + rs * spx
                py = hub[1] + r_e * ery + rs * spy
                pz = hub[2] + r_e * erz + rs * spz
                px = hub[0] + cm * (px - hub[0])
                py = hub[1] + cm * (py - hub[1])
                out[b, j, m, 0] = px + sx
                out[b, j, m, 1] = py + sy
                out[b, j, m, 2] = pz + sz
    return out


def near_wake_points(hub, radius, hinge, direction, r_edge, psi_blades, beta, ages,
                     contraction, drift, omega):
    """Rigid near-wake trailer points of every blade of one rotor.

    Parameters
    ----------
    hub : ndarray, shape (3,)
        Hub position in the computational frame [m].
    radius : float
        Rotor radius R [m].
    hinge : float
        Flap hinge offset e over R [-].
    direction : int
        Sense of rotation, +1 or -1 [-].
    r_edge : ndarray, shape (Ne + 1,)
        Panel edges r/R [-].
    psi_blades : ndarray, shape (Nb,)
        Blade azimuths [rad].
    beta : ndarray, shape (Nb,)
        Blade flap angles [rad].
    ages : ndarray, shape (Na,)
        Near-wake ages, 0 first [rad].
    contraction : ndarray, shape (Na,)
        Radial scale of the near wake at each age [-].
    drift : ndarray, shape (3,)
        Drift velocity of the near wake [m/s].
    omega : float
        Rotor speed [rad/s] (converts age to time).

    Returns
    -------
    ndarray, shape (Nb, Ne + 1, Na, 3)
        Trailer points [m], age 0 first.
    """
    ang = psi_blades[:, None] - ages[None, :]
    return _near_wake_kernel(np.asarray(hub, dtype=float), float(radius), float(hinge),
                             int(direction), np.ascontiguousarray(r_edge, dtype=float),
                             np.cos(ang), np.sin(ang), np.cos(beta), np.sin(beta),
                             np.ascontiguousarray(contraction, dtype=float),
                             np.asarray(drift, dtype=float), np.ascontiguousarray(ages, dtype=float),
                             float(omega))
