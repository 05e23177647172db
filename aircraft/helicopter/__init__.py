"""The aircraft: rigid body + flapping blade-element rotors + pluggable inflow.

::

    Helicopter(config, inflow) ── trim(condition) ──► TrimResult
                               └─ linearize(trim) ──► control.StateSpace ─► modes(sys)
                                                      └─ coupling_numerator(sys, "p", "delta_lat", {...})
"""
from .mixing import PILOT_INPUTS, ROTOR_CONTROLS, mixing_matrix
from .model import BODY_STATES, Helicopter, HelicopterSettings
from .trim import TrimCondition, TrimError, TrimResult, trim
from .linearize import default_steps, linearize, modes
from .coupling import CouplingError, coupling_numerator, residualize

__all__ = ["PILOT_INPUTS", "ROTOR_CONTROLS", "mixing_matrix", "BODY_STATES", "Helicopter",
           "HelicopterSettings", "TrimCondition", "TrimError", "TrimResult", "trim",
           "default_steps", "linearize", "modes", "CouplingError", "coupling_numerator", "residualize"]
