"""Momentum-based coaxial inflow models with rotor-rotor interference (§2.2.2.3-2.2.2.4).

* :class:`ClimbingLowerRotor`: the lower rotor operates in a climb equal to the
  upper rotor's *trimmed* mean inflow; the climb changes its mass flow (Eqs.
  2.4-2.5) and adds to its downwash (Eq. 2.6). Static: frozen at trim.
* :class:`DynamicClimb`: each rotor climbs in a fraction of the other rotor's
  *current* mean inflow, mu_c^U = 0.86 lam0^L, mu_c^L = 1.13 lam0^U (Eq. 2.7),
  coupling lam0 of both rotors dynamically through [L]; downwash Eqs. 2.8-2.9.
"""
from __future__ import annotations

import numpy as np

from .pitt_peters import PittPeters

__all__ = ["ClimbingLowerRotor", "DynamicClimb"]


class ClimbingLowerRotor(PittPeters):
    """Isolated Pitt-Peters rotors, the lower one in a climb of the upper trimmed inflow.

    Until :meth:`set_trim` is called (the aircraft does it after trimming) the
    climb follows the upper rotor's current lam0, so that solving for trim gives
    the consistent equilibrium; afterwards it is frozen (static interference).
    """

    def __init__(self, kr=0.0, climb_fraction=1.0):
        super().__init__(rotors=("U", "L"), kr=kr)
        self.climb_fraction = float(climb_fraction)
        self.frozen_climb = None

    def _climbs(self, x, ops):
        c = self.frozen_climb if self.frozen_climb is not None else self.climb_fraction * x[0]
        return np.array([0.0, c])

    def set_trim(self, x, loads, ops):
        self.frozen_climb = self.climb_fraction * float(np.asarray(x)[0])

    def steady_state(self, loads, ops):
        frozen, self.frozen_climb = self.frozen_climb, None
        try:
            return super().steady_state(loads, ops)
        finally:
            self.frozen_climb = frozen


class DynamicClimb(PittPeters):
    """Coaxial "Dynamic Climb" inflow (Eq. 2.7), K_R wake distortion optional.

    Parameters
    ----------
    upper_fraction, lower_fraction : float
        mu_c^U = upper_fraction * lam0^L, mu_c^L = lower_fraction * lam0^U
        (0.86 and 1.13 in hover, Ref. 38 via Eq. 2.7).
    kr : float
        Wake-distortion parameter (Eq. 2.29).
    """

    def __init__(self, upper_fraction=0.86, lower_fraction=1.13, kr=0.0):
        super().__init__(rotors=("U", "L"), kr=kr)
        self.upper_fraction = float(upper_fraction)
        self.lower_fraction = float(lower_fraction)

    def _climbs(self, x, ops):
        return np.array([self.upper_fraction * x[3], self.lower_fraction * x[0]])
