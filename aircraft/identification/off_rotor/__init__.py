"""Off-rotor induced-velocity models (Eqs. 2.39-2.40): surfaces, fit, and identification from the wake.

::

    surfaces.py   OffRotorSurface (points on a tail or wing), horizontal_tail, wing_under_hub,
                  gain_delay_structure, fit_off_rotor, reduce_off_rotor, wake_exposure,
                  OffRotorSettings
    identify.py   identify_off_rotor: wake runs -> averaged velocities -> Eq. 2.39/2.40 fit ->
                  doublet verification; OffRotorModel, OffRotorResult
"""
from .surfaces import (INFLOW_STATES, VELOCITY_COMPONENTS, OffRotorError, OffRotorSettings, OffRotorSurface,
                       fit_off_rotor, gain_delay_structure, horizontal_tail, reduce_off_rotor, wake_exposure,
                       wing_under_hub)
from .identify import OffRotorModel, OffRotorResult, identify_off_rotor

__all__ = ["INFLOW_STATES", "VELOCITY_COMPONENTS", "OffRotorError", "OffRotorSettings", "OffRotorSurface",
           "fit_off_rotor", "reduce_off_rotor", "gain_delay_structure", "horizontal_tail", "wake_exposure",
           "wing_under_hub",
           "OffRotorModel", "OffRotorResult", "identify_off_rotor"]
