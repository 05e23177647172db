"""Inflow models: one interface (:class:`InflowModel`), perturbation models about a trim."""
from .base import (InflowModel, RotorOperatingPoint, flap_rate_names, inflow_names,
                   load_names, rotor_suffix)

__all__ = ["InflowModel", "RotorOperatingPoint", "flap_rate_names", "inflow_names",
           "load_names", "rotor_suffix"]
