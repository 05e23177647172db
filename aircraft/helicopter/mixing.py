"""Pilot mixing (Eq. 7.19, K = 0.5) between pilot inputs and rotor controls.

The dissertation mixes sums and differences of the upper and lower swashplate
angles: collective = K (theta0^U + theta0^L), pedal = K (theta0^U - theta0^L),
cyclic sticks = K x (sum of the two rotors' cyclic), propeller = K theta_PR.
Its HeliUM azimuth origin pairs lateral stick with theta1s; in our per-rotor
frame (azimuth from aft in the direction of rotation, :mod:`aircraft.inflow.base`)
a lateral disk tilt is produced by the cos(psi) term, and the counter-rotating
lower rotor needs the opposite sign in its own frame for the same body roll.
So, with the same K and the same sum/difference structure::

    delta_col = K (theta0_U + theta0_L)          delta_ped = K (theta0_U - theta0_L)
    delta_lon = -K (theta1s_U + theta1s_L)       delta_lat = K (theta1c_L - theta1c_U)
    delta_prop = K theta_prop

(positive: more collective, stick forward = nose down, stick right = roll right,
right pedal = nose right).  The differential cyclics (lift offset, zero
longitudinal difference) are fixed at trim, as in §7.2.
"""
from __future__ import annotations

import numpy as np

__all__ = ["PILOT_INPUTS", "ROTOR_CONTROLS", "mixing_matrix"]

PILOT_INPUTS = ["delta_col", "delta_lon", "delta_lat", "delta_ped", "delta_prop"]
ROTOR_CONTROLS = ["theta0_U", "theta1s_U", "theta1c_U", "theta0_L", "theta1s_L", "theta1c_L", "theta_prop"]


def mixing_matrix(k=0.5):
    """T (7 x 5) with theta = T delta + offsets, the inverse of Eq. 7.19's mixing."""
    t = np.zeros((7, 5))
    inv = 1.0 / k
    # delta_col, delta_ped -> theta0_U = (col + ped)/(2K), theta0_L = (col - ped)/(2K)
    t[0, 0], t[0, 3] = inv / 2, inv / 2
    t[3, 0], t[3, 3] = inv / 2, -inv / 2
    # delta_lon -> theta1s_U = theta1s_L = -lon/(2K)
    t[1, 1] = t[4, 1] = -inv / 2
    # delta_lat -> theta1c_U = -lat/(2K), theta1c_L = +lat/(2K)
    t[2, 2], t[5, 2] = -inv / 2, inv / 2
    t[6, 4] = inv
    return t
