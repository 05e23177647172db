"""controllers: explicit model following, ADS-33-style specs, CasADi design-margin optimisation.

::

    plant (p/delta_lat, any order, exact delay) ─► EMFDesign(command model, inverse plant,
        tau_eq, PID gains, actuator, sensor)
            ├─ exact frequency responses ──► metrics (crossover, GM/PM, Nichols, DRB, DRP,
            │                                bandwidth/phase delay, damping, RMS)
            ├─ control.interconnect state space (Padé) ─► poles, time responses
            └─ specs (Table 7.3) ─► evaluate_specs ─► hq_window
    hq: spec library (every axis, ADS-33E-PRF boundaries as data, provenance per spec):
        specs_for(axis, mte=..., uce=..., attention=..., speed=..., boundaries=...), spec_table();
        boundaries the library lacks are supplied by name (status "supplied")
    smooth: each spec's own NLP constraint (the DMO's NLP is assembled from the spec list)
    dmo(design or [designs]): CasADi/IPOPT, boundaries raised by bisection to a
                 tolerance, several starts per step, every result re-checked with
                 python-control; search_designs: independent dense search
    roll_design_plant(linearize(trim(heli))): the Eq. 7.21 roll plant
    design_multi_axis(aircraft StateSpace): all four EMF loops (roll, pitch, yaw, heave) of one
                 MIMO aircraft, each axis's specs graded on the simultaneous closed loop
                 (MultiAxisEMF), OLOP with the actuators' rate/travel limits (ActuatorLimits)
    multi_axis_joint.joint_check(result): every axis's gains searched at once, every loop graded:
                 is the design dominated (every crossover higher, every spec met)?
    multi_axis_report.write_multi_axis_report(result, folder, check=global_check(result)):
                 the design's tables (axes, specs, limits, coupling, sweeps, global check)
                 as CSV files and one HQ window per axis
"""

from .plants import roll_design_plant, hover_roll_plant, DelayedLTI, first_order_actuator, second_order_actuator
from .metrics import crossover_frequency, gain_phase_margins, attitude_bandwidth
from .emf import EMFDesign, CommandModel, PIDGains
from .specs import Spec, BandwidthSpec, default_specs, evaluate_specs, SpecEvaluationError
from .dmo import dmo, DMOSettings, DMOResult, InfeasibleDesignError, design_margins, optimize
from .search import search_designs
from .hqwindow import hq_window
from .hq import specs_for, spec_table, HQSpec, BoundaryNotPublishedError
from .actuator_limits import ActuatorLimits
from .multi_axis import MultiAxisEMF, RateCommandModel
from .multi_axis_design import design_multi_axis

__all__ = ["roll_design_plant", "hover_roll_plant", "DelayedLTI", "first_order_actuator", "second_order_actuator",
           "crossover_frequency", "gain_phase_margins", "attitude_bandwidth", "EMFDesign", "CommandModel",
           "PIDGains", "Spec", "BandwidthSpec", "default_specs", "evaluate_specs", "SpecEvaluationError",
           "dmo", "DMOSettings", "DMOResult", "InfeasibleDesignError", "design_margins", "optimize",
           "search_designs", "hq_window", "specs_for", "spec_table", "HQSpec", "BoundaryNotPublishedError",
           "ActuatorLimits", "MultiAxisEMF", "RateCommandModel", "design_multi_axis"]
