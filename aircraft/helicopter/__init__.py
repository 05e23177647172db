"""The aircraft: rigid body + flapping blade-element rotors + pluggable inflow.

::

    Helicopter(config, inflow) ── trim(condition) ──► TrimResult
                               └─ linearize(trim) ──► control.StateSpace ─► modes(sys)
                                                      └─ coupling_numerator(sys, "p", "delta_lat", {...})
"""
from .mixing import PILOT_INPUTS, ROTOR_CONTROLS, mixing_matrix
from .model import BODY_STATES, Helicopter, HelicopterSettings
from .trim import TrimCondition, TrimError, TrimInputError, TrimResult, trim
from .linearize import (LinearizeInputError, NotAtTrimError, NotAtTrimWarning, default_steps,
                        linearize, modes, trim_derivatives)
from .coupling import CouplingError, coupling_numerator, residualize

__all__ = ["PILOT_INPUTS", "ROTOR_CONTROLS", "mixing_matrix", "BODY_STATES", "Helicopter",
           "HelicopterSettings", "TrimCondition", "TrimError", "TrimInputError", "TrimResult", "trim",
           "default_steps", "linearize", "modes", "trim_derivatives", "LinearizeInputError",
           "NotAtTrimError", "NotAtTrimWarning", "CouplingError", "coupling_numerator", "residualize"]
