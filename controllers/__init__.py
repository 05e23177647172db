"""controllers: explicit model following, ADS-33-style specs, CasADi design-margin optimisation.

::

    plant (p/delta_lat, any order, exact delay) ─► EMFDesign(command model, inverse plant,
        tau_eq, PID gains, actuator, sensor)
            ├─ exact frequency responses ──► metrics (crossover, GM/PM, Nichols, DRB, DRP,
            │                                bandwidth/phase delay, damping, RMS)
            ├─ control.interconnect state space (Padé) ─► poles, time responses
            └─ specs (Table 7.3) ─► evaluate_specs ─► hq_window
    hq: spec library (every axis, ADS-33E-PRF boundaries as data, provenance per spec):
        specs_for(axis, mte=..., uce=..., attention=..., speed=...), spec_table()
    smooth: each spec's own NLP constraint (the DMO's NLP is assembled from the spec list)
    dmo(design or [designs]): CasADi/IPOPT, boundaries raised by bisection to a
                 tolerance, several starts per step, every result re-checked with
                 python-control; search_designs: independent dense search
    roll_design_plant(linearize(trim(heli))): the Eq. 7.21 roll plant
"""
from .plants import (HOVER_ROLL_CONSTRAINTS, DelayedLTI, first_order_actuator, hover_roll_plant,
                     roll_design_plant, second_order_actuator)
from .metrics import (attitude_bandwidth, crossover_frequency, damping_in_band,
                      disturbance_rejection_bandwidth, disturbance_rejection_peak,
                      gain_phase_margins, nichols_margin, rms_response, NonFiniteResponseError)
from .emf import (CommandModel, EMFDesign, FrequencyFunction, PIDGains, fit_equivalent_delay,
                  fit_inverse_plant)
from .specs import (BandwidthSpec, Spec, SpecEvaluationError, default_specs, evaluate_specs,
                    spec_by_name)
from .dmo import (DMOResult, DMOSettings, InfeasibleDesignError, OptimizationResult, SolverError,
                  VerificationError, design_margins, dmo, optimize)
from .search import SearchResult, search_designs
from .hqwindow import hq_window
from .hq import BoundaryNotPublishedError, HQSpec, spec_table, specs_for

__all__ = [
    "HOVER_ROLL_CONSTRAINTS", "DelayedLTI", "first_order_actuator", "hover_roll_plant",
    "roll_design_plant", "second_order_actuator",
    "attitude_bandwidth", "crossover_frequency", "damping_in_band",
    "disturbance_rejection_bandwidth", "disturbance_rejection_peak", "gain_phase_margins",
    "nichols_margin", "rms_response", "NonFiniteResponseError",
    "CommandModel", "EMFDesign", "FrequencyFunction", "PIDGains", "fit_equivalent_delay",
    "fit_inverse_plant",
    "BandwidthSpec", "Spec", "SpecEvaluationError", "default_specs", "evaluate_specs", "spec_by_name",
    "DMOResult", "DMOSettings", "InfeasibleDesignError", "OptimizationResult", "SolverError",
    "VerificationError", "design_margins", "dmo", "optimize",
    "SearchResult", "search_designs",
    "hq_window",
    "specs_for", "spec_table", "HQSpec", "BoundaryNotPublishedError",
]
