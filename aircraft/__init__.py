"""aircraft: configurations, free-vortex wake, inflow models, rigid-body aircraft.

::

    configs ──► wake (free-vortex, time marching) ──► time histories
       │                                              (identified with flightid)
       └──► inflow (PittPeters, DynamicClimb, …, IdentifiedInflow)
                 └──► Helicopter(config, inflow) ─ trim ─ linearize ─► control.StateSpace

The wake is a subpackage (``aircraft.wake``) imported on demand: it compiles
numba kernels on first use.
"""
from .configs import (AircraftConfig, ConfigError, PropellerConfig, RotorConfig, ASSUMPTIONS,
                      coaxial_compound, uh60_single_rotor)

__all__ = ["AircraftConfig", "ConfigError", "PropellerConfig", "RotorConfig", "ASSUMPTIONS",
           "coaxial_compound", "uh60_single_rotor"]
