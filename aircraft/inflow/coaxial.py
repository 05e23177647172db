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

from .base import check_rotor_names
from .pitt_peters import KR_ANALYTICAL, InflowError, PittPeters

__all__ = ["ClimbingLowerRotor", "DynamicClimb"]


class ClimbingLowerRotor(PittPeters):
    """Isolated Pitt-Peters rotors, the lower one in a climb of the upper trimmed inflow.

    The lower rotor's climb ``mu_c^L = climb_fraction * lam0^U(trim)`` enters its
    mass flow, hence [L]^-1 (Eqs. 2.4-2.5), and its total downwash (Eq. 2.6:
    :meth:`inflow` returns ``lam0^L + mu_c^L``). Until :meth:`set_trim` is called
    (the aircraft does it after trimming) the climb follows the upper rotor's
    current lam0, so that solving for trim gives the consistent equilibrium;
    afterwards it is frozen (static interference: a perturbation of the upper
    rotor's inflow does not change the lower rotor's climb). :meth:`linear`
    always freezes it at the equilibrium it linearises about.
    :meth:`release_trim` unfreezes it (call it before trimming again at another
    condition).

    Parameters
    ----------
    kr : float
        Wake-distortion parameter K_R (Eq. 2.29).
    climb_fraction : float
        Fraction of the upper rotor's trimmed lam0 taken as the lower rotor's climb
        (1 in §2.2.2.3).
    rotors : (str, str)
        Names of the upper and the lower rotor, in this order (default ``("U", "L")``,
        the :func:`~aircraft.configs.coaxial_compound` names); give the aircraft's
        (:func:`~aircraft.inflow.base.config_rotor_names`) for another naming.

    Raises
    ------
    InflowError
        If ``rotors`` is not two distinct names.
    """

    def __init__(self, kr=0.0, climb_fraction=1.0, *, rotors=("U", "L")):
        super().__init__(rotors=check_rotor_names(rotors, 2, error=InflowError), kr=kr)
        self.climb_fraction = float(climb_fraction)
        self.frozen_climb = None

    def _climbs(self, x, ops):
        c = self.frozen_climb if self.frozen_climb is not None else self.climb_fraction * x[0]
        return np.array([0.0, c])

    def set_trim(self, x, loads, ops):
        self.frozen_climb = self.climb_fraction * float(np.asarray(x)[0])

    def release_trim(self):
        """Let the climb follow the upper rotor's lam0 again (before a new trim)."""
        self.frozen_climb = None

    def linear(self, loads, ops):
        """Perturbation model with the climb frozen at this equilibrium (static interference)."""
        saved = self.frozen_climb
        try:
            self.frozen_climb = None
            x0 = PittPeters.steady_state(self, loads, ops)
            self.frozen_climb = self.climb_fraction * float(x0[0])
            return super().linear(loads, ops)
        finally:
            self.frozen_climb = saved

    def steady_state(self, loads, ops):
        frozen, self.frozen_climb = self.frozen_climb, None
        try:
            return super().steady_state(loads, ops)
        finally:
            self.frozen_climb = frozen


class DynamicClimb(PittPeters):
    """Coaxial "Dynamic Climb" inflow (Eq. 2.7), K_R wake distortion optional.

    Each rotor is a nonlinear Pitt-Peters rotor in a climb equal to a fraction of
    the other rotor's *current* lam0 state; the climb changes its mass flow and
    so its [L]^-1 (Eqs. 2.4-2.5) at every instant, coupling the two lam0 states
    dynamically (the harmonics stay uncoupled). The downwash a blade sees is the
    state plus the climb (Eqs. 2.8-2.9), returned by :meth:`inflow`.

    Parameters
    ----------
    upper_fraction, lower_fraction : float
        mu_c^U = upper_fraction * lam0^L, mu_c^L = lower_fraction * lam0^U
        (0.86 and 1.13 in hover, Ref. 38 via Eq. 2.7; Ref. 38 uses other
        fractions at other speeds).
    kr : float
        Wake-distortion parameter K_R (Eq. 2.29), same on both rotors. Default:
        the single-rotor analytical value ``KR_ANALYTICAL`` (1.5, §2.2.2.5), as
        the dissertation's Dynamic Climb model uses "standard analytical values"
        for wake distortion (§2.2.2.4); the model then takes the full
        tip-path-plane rates as inputs. ``kr=0`` gives the model without them.
    rotors : (str, str)
        Names of the upper and the lower rotor, in this order (default ``("U", "L")``,
        the :func:`~aircraft.configs.coaxial_compound` names); give the aircraft's
        (:func:`~aircraft.inflow.base.config_rotor_names`) for another naming.

    Raises
    ------
    InflowError
        If ``rotors`` is not two distinct names.

    Examples
    --------
    >>> from aircraft.inflow import DynamicClimb
    >>> DynamicClimb(rotors=("upper", "lower")).state_names[:4]
    ['lam0_upper', 'lam1s_upper', 'lam1c_upper', 'lam0_lower']

    Notes
    -----
    The climb adds to the flow through the disk: in hover ``lam0^U (lam0^U +
    0.86 lam0^L) = C_T^U / 2`` and ``lam0^L (lam0^L + 1.13 lam0^U) = C_T^L / 2``
    (see :mod:`aircraft.inflow.pitt_peters` on the sign of mu_c in Eqs. 2.4-2.5).
    """

    def __init__(self, upper_fraction=0.86, lower_fraction=1.13, kr=KR_ANALYTICAL, *, rotors=("U", "L")):
        super().__init__(rotors=check_rotor_names(rotors, 2, error=InflowError), kr=kr)
        self.upper_fraction = float(upper_fraction)
        self.lower_fraction = float(lower_fraction)

    def _climbs(self, x, ops):
        return np.array([self.upper_fraction * x[3], self.lower_fraction * x[0]])
