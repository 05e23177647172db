"""aircraft: configurations, free-vortex wake, inflow models, rigid-body aircraft.

::

    configs ──► wake (free-vortex, time marching) ──► time histories
       │                                              (identified with flightid)
       └──► inflow (PittPeters, DynamicClimb, …, IdentifiedInflow)
                 └──► Helicopter(config, inflow) ─ trim ─ linearize ─► control.StateSpace

``aircraft.identify_inflow`` (:mod:`aircraft.identification`) runs the whole
identification of an inflow model from the wake. The wake is a subpackage (``aircraft.wake``) imported on demand: it compiles
numba kernels on first use.
"""
from .configs import (AircraftConfig, ConfigError, PropellerConfig, RotorConfig, ASSUMPTIONS,
                      coaxial_compound, uh60_single_rotor)

__all__ = ["AircraftConfig", "ConfigError", "PropellerConfig", "RotorConfig", "ASSUMPTIONS",
           "coaxial_compound", "uh60_single_rotor", "identify_inflow", "IdentificationSettings",
           "IdentifiedModel"]

_IDENTIFICATION = ("identify_inflow", "IdentificationSettings", "IdentifiedModel")


def __getattr__(name):
    # the identification pipeline (aircraft.identification) is imported on first use
    if name in _IDENTIFICATION:
        from . import identification
        return getattr(identification, name)
    raise AttributeError(f"module 'aircraft' has no attribute {name!r}")
