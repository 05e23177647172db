"""The aircraft: rigid body + flapping blade-element rotors + pluggable inflow.

::

    Helicopter(config, inflow) ── trim(condition) ──► TrimResult
                               ├─ linearize(trim) ──► control.StateSpace ─► modes(sys)
                               │                      ├─ coupling_numerator(sys, "p", "delta_lat", {...})
                               │                      ├─ classify_modes(sys) / flap_mode_damping(sys)
                               │                      └─ effective_derivative(sys, "p", "p", omega)
                               └─ sweep.trim_sweep(heli, speeds) ──► TrimSweep (table, eigenvalues, .plot())
    compare_bare_airframe({"Dynamic Climb": DynamicClimb(), ...}) ──► BareAirframeComparison
    ShaftFixedRotors(config, inflow) ── trim / run / run_linear  (rotor-level truth checks)
    tilt_coupling.py (not re-exported): TiltCoupledHelicopter / helicopter_for, which
        feed a TiltInflow the flapping states as tip-path-plane tilts
    control_phase.py (not re-exported): cyclic_moment_shares(sys, config) and
        derive_control_phase(sys, config), which cyclic acts on which axis
    sweep.py (not re-exported): trim_sweep(heli, speeds), trims, linear models and
        eigenvalues against speed, with figures
    mode_tracking.py (not re-exported): flight_modes(sys) names the modes (phugoid,
        short period, dutch roll, spiral, ...); modes_over_speed(sweep) tracks them
        against speed (table + root-locus figure)
    hold.py (not re-exported): hold_states(sys, ["u", "v"]), states held at trim
        (a perfectly tight outer loop)
"""
from .mixing import PILOT_INPUTS, ROTOR_CONTROLS, mixing_matrix
from .model import BODY_STATES, Helicopter, HelicopterSettings
from .trim import TrimCondition, TrimError, TrimInputError, TrimResult, trim
from .linearize import (LinearizeInputError, NotAtTrimError, NotAtTrimWarning, default_steps,
                        linearize, modes, trim_derivatives)
from .coupling import CouplingError, coupling_numerator, residualize
from .derivatives import DerivativeError, effective_derivative
from .mode_physics import classify_modes, flap_mode_damping, flap_mode_sensitivity, pair_modes
from .responses import DEFAULT_RESPONSE_PAIRS, BareAirframeComparison, compare_bare_airframe
from .rotor_stand import RotorStandError, ShaftFixedRotors

__all__ = ["PILOT_INPUTS", "ROTOR_CONTROLS", "mixing_matrix", "BODY_STATES", "Helicopter",
           "HelicopterSettings", "TrimCondition", "TrimError", "TrimInputError", "TrimResult", "trim",
           "default_steps", "linearize", "modes", "trim_derivatives", "LinearizeInputError",
           "NotAtTrimError", "NotAtTrimWarning", "CouplingError", "coupling_numerator", "residualize",
           "DerivativeError", "effective_derivative",
           "classify_modes", "flap_mode_damping", "flap_mode_sensitivity", "pair_modes",
           "DEFAULT_RESPONSE_PAIRS", "BareAirframeComparison", "compare_bare_airframe",
           "RotorStandError", "ShaftFixedRotors"]
