"""The helicopter flying an inflow model that takes the rotors' tip-path-plane tilts.

:class:`~aircraft.helicopter.model.Helicopter` feeds an inflow model loads and (for
wake-distortion models) the full tip-path-plane rates. An
:class:`aircraft.inflow.tilt.TiltInflow` also takes each rotor's shaft-relative
tilt, ``beta1s`` and ``beta1c`` in that rotor's frame, which are the aircraft's
flapping states (MBC, :data:`~aircraft.helicopter.rotor.FLAP_STATES`).
:class:`TiltCoupledHelicopter` adds that term to the inflow derivatives; the rest
of the aircraft is the base class's, so trim and linearisation work unchanged.

::

    helicopter_for(config, inflow, settings)  ->  Helicopter or TiltCoupledHelicopter
"""
from __future__ import annotations

import numpy as np

from ..inflow.tilt import TILT_HARMONICS
from .model import Helicopter, HelicopterSettings
from .rotor import FLAP_STATES

__all__ = ["TiltCoupledHelicopter", "helicopter_for"]


class TiltCoupledHelicopter(Helicopter):
    """:class:`Helicopter` whose inflow model also reads the flapping states as tilts.

    Parameters
    ----------
    config, inflow, settings :
        As :class:`Helicopter`; ``inflow`` must have ``uses_flap_tilts``
        (an :class:`aircraft.inflow.tilt.TiltInflow`).

    Raises
    ------
    TypeError
        An inflow model without tilt inputs (fly it with :class:`Helicopter`).
    """

    def __init__(self, config, inflow, settings=None):
        if not getattr(inflow, "uses_flap_tilts", False):
            raise TypeError(f"{type(inflow).__name__} takes no tip-path-plane tilts: use Helicopter")
        super().__init__(config, inflow, HelicopterSettings() if settings is None else settings)
        self._tilt_index = np.array([9 + 8 * k + FLAP_STATES.index(b)
                                     for k in range(len(self.rotors)) for b in TILT_HARMONICS])

    def tilts(self, x):
        """Each rotor's shaft-relative tilt ``beta1s, beta1c`` [rad] from state ``x``."""
        return np.asarray(x, float)[self._tilt_index]

    def evaluate(self, x, u):
        # the base class calls inflow.derivatives without tilts: hand them over for
        # this evaluation only
        x = np.asarray(x, float)
        self.inflow._pending_tilts = self.tilts(x) if x.shape == (self.n_states,) else None
        try:
            return super().evaluate(x, u)
        finally:
            self.inflow._pending_tilts = None


def helicopter_for(config, inflow, settings=None):
    """The aircraft that flies ``inflow``: :class:`TiltCoupledHelicopter` for a model
    with tilt inputs, else :class:`Helicopter`.

    Parameters
    ----------
    config : aircraft.AircraftConfig
    inflow : aircraft.inflow.InflowModel
    settings : HelicopterSettings, optional
        Default: the helicopter's own default.

    Returns
    -------
    Helicopter
    """
    cls = TiltCoupledHelicopter if getattr(inflow, "uses_flap_tilts", False) else Helicopter
    return cls(config, inflow, HelicopterSettings() if settings is None else settings)
