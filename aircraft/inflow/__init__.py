"""Inflow models: one interface (:class:`InflowModel`), perturbation models about a trim.

::

    InflowModel (base.py: conventions, names, numerical linearisation)
      ├─ PittPeters / IsolatedRotors          (pitt_peters.py, Eq. 1.10, K_R of Eq. 2.29)
      ├─ ClimbingLowerRotor / DynamicClimb    (coaxial.py, §2.2.2.3-2.2.2.4, Eq. 2.7)
      ├─ IdentifiedInflow                     (identified.py: any identified model, Padé delays)
      │    └─ TiltInflow                      (tilt.py, not re-exported: + tip-path-plane tilt inputs)
      └─ ScheduledInflow                      (scheduled.py: identified models interpolated in spacing, C_T)
    published.py: the dissertation's printed identified models, as reference data
"""
from .base import (InflowModel, RotorOperatingPoint, check_rotor_names, config_rotor_names, flap_rate_names,
                   inflow_names, load_names, rotor_suffix)
from .pitt_peters import (KR_ANALYTICAL, InflowError, IsolatedRotors, PittPeters, mlbar_from_statespace,
                          momentum_inflow, pitt_peters_matrices)
from .coaxial import ClimbingLowerRotor, DynamicClimb
from .identified import IdentifiedInflow, mltau_statespace
from .scheduled import ScheduledInflow
from . import published

__all__ = ["InflowModel", "RotorOperatingPoint", "check_rotor_names", "config_rotor_names", "flap_rate_names",
           "inflow_names",
           "load_names", "rotor_suffix", "KR_ANALYTICAL", "InflowError", "IsolatedRotors", "PittPeters",
           "mlbar_from_statespace", "momentum_inflow", "pitt_peters_matrices",
           "ClimbingLowerRotor", "DynamicClimb", "IdentifiedInflow", "mltau_statespace", "ScheduledInflow", "published"]
