"""aircraft: configurations, free-vortex wake, inflow models, rigid-body aircraft.

::

    configs ──► wake (free-vortex, time marching) ──► time histories
       │                                              (identified with flightid)
       └──► inflow (PittPeters, DynamicClimb, …, IdentifiedInflow)
                 └──► Helicopter(config, inflow) ─ trim ─ linearize ─► control.StateSpace

``aircraft.identify_inflow`` (:mod:`aircraft.identification`) runs the whole
identification of an inflow model from the wake. The wake is a subpackage
(``aircraft.wake``) imported on demand: it compiles numba kernels on first use.

An aircraft is also data: ``write_aircraft`` / ``read_aircraft``
(:mod:`aircraft.config_files`) store an ``AircraftConfig`` as a TOML file, and
``load_shipped_aircraft`` reads the two shipped ones (``aircraft/data/aircraft``).
"""
from .configs import (AircraftConfig, ConfigError, PropellerConfig, RotorConfig, TailRotorConfig, ASSUMPTIONS,
                      coaxial_compound, uh60_single_rotor)
from .config_files import ConfigFileError, load_aircraft, load_shipped_aircraft, read_aircraft, write_aircraft

__all__ = ["AircraftConfig", "ConfigError", "PropellerConfig", "RotorConfig", "TailRotorConfig", "ASSUMPTIONS",
           "coaxial_compound", "uh60_single_rotor", "read_aircraft", "write_aircraft",
           "load_shipped_aircraft", "load_aircraft", "ConfigFileError", "identify_inflow", "IdentificationSettings",
           "IdentifiedModel"]

_IDENTIFICATION = ("identify_inflow", "IdentificationSettings", "IdentifiedModel")


def __getattr__(name):
    # the identification pipeline (aircraft.identification) is imported on first use
    if name in _IDENTIFICATION:
        from . import identification
        return getattr(identification, name)
    raise AttributeError(f"module 'aircraft' has no attribute {name!r}")
