"""The wind-tunnel flight condition of an identification: one definition of speed and advance ratio.

The advance ratio is the in-plane component of the free stream over the tip speed,
``mu = V cos(alpha) / (Omega R)``, so a condition of advance ratio ``mu`` at shaft angle
``alpha`` flies at ``V = mu Omega R / cos(alpha)`` and the free stream's component up
through the disk is ``mu_z = mu tan(alpha)`` (Pitt-Peters' ``mu_z = -mu tan(alpha)`` with
its sign of inflow). Used by every identification (single rotor, coaxial, off-rotor).
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["flight_condition"]


def _real(name, value):
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not math.isfinite(value):
        raise ValueError(f"{name} must be a finite real number, got {value!r}")
    return float(value)


def flight_condition(config=None, mu=None, alpha=0.0, *, speed=None):
    """The wind-tunnel :class:`aircraft.wake.FlightCondition` of an advance ratio or a speed.

    Parameters
    ----------
    config : aircraft.AircraftConfig, optional
        The aircraft; its first rotor's tip speed ``Omega R`` turns ``mu`` into a speed.
        Needed with ``mu``.
    mu : float, optional
        Advance ratio ``V cos(alpha) / (Omega R)`` [-], >= 0 (0: hover). Give ``mu`` or ``speed``.
    alpha : float
        Shaft angle of attack [rad], within +-30 deg; positive tilts the disk back (the
        free stream flows up through it).
    speed : float, optional
        Free-stream speed [m/s], >= 0, instead of ``mu``.

    Returns
    -------
    aircraft.wake.FlightCondition
        Speed ``mu Omega R / cos(alpha)`` (or ``speed``) [m/s] and ``alpha`` [rad].

    Raises
    ------
    ValueError
        Neither or both of ``mu`` and ``speed``; ``mu`` without ``config``; a negative or
        non-finite ``mu``, ``speed`` or ``alpha``.

    Examples
    --------
    >>> from aircraft import uh60_single_rotor
    >>> rotor = uh60_single_rotor().rotors[0]
    >>> fc = flight_condition(uh60_single_rotor(), 0.1)
    >>> round(fc.speed / (0.1 * rotor.omega * rotor.radius), 12)
    1.0
    >>> flight_condition(speed=102.9, alpha=0.035).speed
    102.9
    """
    from aircraft.wake import FlightCondition
    if (mu is None) == (speed is None):
        raise ValueError("give exactly one of mu (advance ratio) and speed [m/s]")
    alpha = _real("alpha [rad]", alpha)
    if mu is not None:
        if config is None:
            raise ValueError("an advance ratio needs the aircraft config (its tip speed)")
        mu = _real("advance ratio mu", mu)
        if mu < 0:
            raise ValueError(f"advance ratio mu must be >= 0, got {mu!r}")
        rotor = config.rotors[0]
        speed = mu * rotor.omega * rotor.radius / math.cos(alpha)
    else:
        speed = _real("speed [m/s]", speed)
        if speed < 0:
            raise ValueError(f"speed must be >= 0 [m/s], got {speed!r}")
    return FlightCondition(speed=speed, alpha=alpha)
