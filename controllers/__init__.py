"""controllers: explicit model following, ADS-33-style specs, CasADi design-margin optimisation.

::

    plant (p/delta_lat, any order, exact delay) ─► EMFDesign(command model, inverse plant,
        tau_eq, PID gains, actuator, sensor)
            ├─ exact frequency responses ──► metrics (crossover, GM/PM, Nichols, DRB, DRP,
            │                                bandwidth/phase delay, damping, RMS)
            ├─ control.interconnect state space (Padé) ─► poles, time responses
            └─ specs (Table 7.3) ─► evaluate_specs ─► hq_window
    dmo(design): CasADi/IPOPT feasibility + objective phases, boundaries raised until
                 infeasible, every result re-checked with python-control
"""
from .plants import DelayedLTI, first_order_actuator, hover_roll_plant, second_order_actuator
from .metrics import (attitude_bandwidth, crossover_frequency, damping_in_band,
                      disturbance_rejection_bandwidth, disturbance_rejection_peak,
                      gain_phase_margins, nichols_margin, rms_response)
from .emf import (CommandModel, EMFDesign, FrequencyFunction, PIDGains, fit_equivalent_delay,
                  fit_inverse_plant)
from .specs import BandwidthSpec, Spec, default_specs, evaluate_specs, spec_by_name
from .dmo import DMOResult, DMOSettings, OptimizationResult, VerificationError, dmo, optimize
from .hqwindow import hq_window

__all__ = [
    "DelayedLTI", "first_order_actuator", "hover_roll_plant", "second_order_actuator",
    "attitude_bandwidth", "crossover_frequency", "damping_in_band",
    "disturbance_rejection_bandwidth", "disturbance_rejection_peak", "gain_phase_margins",
    "nichols_margin", "rms_response",
    "CommandModel", "EMFDesign", "FrequencyFunction", "PIDGains", "fit_equivalent_delay",
    "fit_inverse_plant",
    "BandwidthSpec", "Spec", "default_specs", "evaluate_specs", "spec_by_name",
    "DMOResult", "DMOSettings", "OptimizationResult", "VerificationError", "dmo", "optimize",
    "hq_window",
]
