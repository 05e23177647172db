"""Inflow model identification from the free-vortex wake (library, not a study).

::

    structures.py  the dissertation's structures in our frames: SingleRotor3State
                   (Tables 4.1-4.2), Coaxial6State (Eq. 5.3), Coaxial12State (Eqs. 6.2-6.3)
    frames.py      conversion between the dissertation's common frame and our rotor frames
    pipeline.py    identify_inflow: trim -> sweeps -> responses -> joint input-output
                   -> fit -> reduce -> verify; IdentifiedModel
    multisine.py   identify_inflow_multisine: the same from ONE orthogonal-multisine record of
                   all swashplate controls (mimo_response), recommendation 6
    store.py       versioned model files (aircraft/data/models/*.json), ModelRecord
    regenerate.py  recipes of the shipped models; ``python -m aircraft.identification.regenerate``
    synthetic.py   synthetic-truth data generated with scipy (independent of flightid)
    off_rotor.py   off-rotor induced-velocity models (Eqs. 2.39-2.40): surfaces, fit, wake exposure
    off_rotor_identify.py  identify_off_rotor: wake runs -> vbar/lam -> Eq. 2.39/2.40 -> doublet TIC
    coaxial_forward.py  CoaxialForward12State: the fully coupled 200 kt structure
                   (Eqs. 6.4-6.7, 6.12-6.13), registered in STRUCTURES
    coaxial_200kt.py  the 200 kt condition and trim request, identify_coaxial_forward
                   (bounded reduction), isolated_rotor_check (Figs. 7.7-7.10)
    forward.py     single rotor in forward flight (§4.4): SingleRotorForward (Eq. 4.3),
                   identify_forward_flight, comparison with Pitt-Peters and Eqs. 4.7-4.8
    wake_distortion.py  K_R(omega) in hover from tip-path-plane sweeps (§4.7, Fig. 4.39)
    design_space.py  identify_design_space: the coaxial 6-state model over rotor spacing x
                   thrust, DesignSpaceResult (table, plot, .schedule() -> ScheduledInflow)
    quasi_steady.py  quasi_steady_check: a model's DC gain against held steps of the wake
                   (what a fit on 1-25 rad/s cannot see), QuasiSteadyCheck
    starts.py      equation-error starts of the M/Lbar/tau structures (M from Im(H^-1))
    axisymmetric.py  Coaxial6StateAxisymmetric: Eq. 5.3 plus the 1s/1c couplings hover's
                   axisymmetry allows, optional a priori values (PITT_PETERS_COLLECTIVE_MASS)
    six_state_diagnostics.py  the same 6-state data fitted several ways (coordinates,
                   feedthrough, a priori masses, axisymmetric terms): why Eq. 5.3 is not trusted
    wake_sensitivity.py  wake_setting_sensitivity: the same sweeps on wakes differing in
                   chosen WakeSettings, tabulated differences (WakeSensitivityResult)
    twelve_state_variants.py  Coaxial12StateConstrained: the 12-state with freedoms removed
                   by name (first-order collective, a priori values, removed couplings);
                   compare_twelve_state_variants on one data set. Import it from the
                   module (not re-exported yet: adding it here would mark every committed
                   result stale until the next full regeneration)
    steady_gains.py  wake_steady_gains: the wake's steady gains per load, flap rate and
                   tip-path-plane tilt from held steps, ramps and held tilts; SteadyGains
                   (.equivalent_kr, .compare(model), .plot()). Import it from the module
                   (same reason)
    guideline.py   guideline_check: the guideline's keep rule (a parameter over a bound
                   kept when its removal raised the cost), from the reduction's log.
                   Import it from the module (same reason)
    tilt_inputs.py  Coaxial12StateTilt: the 12-state plus tip-path-plane tilt inputs
                   (integrator states of the flap rates; shipped as
                   coaxial_hover_12state_tilt); tilt_inflow_from_record -> TiltInflow.
                   Import it from the module (same reason)
    six_state_scan.py  six_state_scan: the Eq. 5.3 family (band, a priori masses,
                   cross-rotor feedthrough; Coaxial6StateVariant) fitted from every start
                   and judged by the guidelines; SixStateScan (.table, .plot()),
                   plot_cyclic_pairs. Import it from the module (same reason)

The wake (numba) is imported only when a pipeline runs.
"""
from .frames import COAXIAL_DIRECTIONS, FrameError, convert_frames, frame_signs
from .structures import (STRUCTURES, Coaxial6State, Coaxial12State, InflowStructure, SingleRotor3State,
                         get_structure, low_frequency_gain, low_frequency_points)
from .coaxial_forward import CoaxialForward12State
from .coaxial_200kt import (IsolatedRotorCheck, forward_flight_condition, forward_trim_request,
                            identify_coaxial_forward, isolated_rotor_check)
from .store import SCHEMA, ModelFileError, ModelRecord, load_record, shipped_models
from .pipeline import (PIPELINE_VERSION, TRUST_J_AVE_MAX, IdentificationSettings, IdentifiedModel,
                       PipelineError, identification_hash, identify_inflow)
from .multisine import MultisineSettings, identify_inflow_multisine, record_revolutions
from .off_rotor import (INFLOW_STATES, VELOCITY_COMPONENTS, OffRotorError, OffRotorSettings, OffRotorSurface,
                        fit_off_rotor, gain_delay_structure, horizontal_tail, wake_exposure, wing_under_hub)
from .off_rotor_identify import OffRotorModel, OffRotorResult, flight_condition, identify_off_rotor
from .forward import (SingleRotorForward, forward_bode_overlay, forward_comparison_table, forward_condition,
                      identify_forward_flight, pitt_peters_forward)
from .wake_distortion import (KR_CONTROLS, WakeDistortionResult, identify_wake_distortion, kr_frequency_response,
                              wake_distortion_from_runs)
from .design_space import (KEY_PARAMETERS, DesignPoint, DesignSpaceError, DesignSpaceResult,
                           identify_design_space, spaced_config)
from .quasi_steady import QuasiSteadyCheck, quasi_steady_check
from .starts import equation_error_masses, equation_error_start
from .wake_sensitivity import WakeSensitivityResult, wake_setting_sensitivity
# registers its structures in STRUCTURES on import
from .axisymmetric import PITT_PETERS_COLLECTIVE_MASS, Coaxial6StateAxisymmetric
from .six_state_diagnostics import Coaxial6StateFeedthrough, coaxial_sum_difference, six_state_diagnostics

STRUCTURES[SingleRotorForward.key] = SingleRotorForward

STRUCTURES[CoaxialForward12State.key] = CoaxialForward12State

__all__ = ["CoaxialForward12State", "IsolatedRotorCheck", "forward_flight_condition", "forward_trim_request",
           "identify_coaxial_forward", "isolated_rotor_check", "COAXIAL_DIRECTIONS", "FrameError", "convert_frames", "frame_signs",
           "STRUCTURES", "Coaxial6State", "Coaxial12State", "InflowStructure", "SingleRotor3State",
           "get_structure", "SCHEMA", "ModelFileError", "ModelRecord", "load_record", "shipped_models",
           "PIPELINE_VERSION", "IdentificationSettings", "IdentifiedModel", "PipelineError",
           "identification_hash", "identify_inflow",
           "MultisineSettings", "identify_inflow_multisine", "record_revolutions",
           "INFLOW_STATES", "VELOCITY_COMPONENTS", "OffRotorError", "OffRotorSettings", "OffRotorSurface",
           "fit_off_rotor", "gain_delay_structure", "horizontal_tail", "wake_exposure", "wing_under_hub",
           "OffRotorModel", "OffRotorResult", "flight_condition", "identify_off_rotor",
           "SingleRotorForward", "forward_bode_overlay", "forward_comparison_table", "forward_condition",
           "identify_forward_flight", "pitt_peters_forward",
           "KR_CONTROLS", "WakeDistortionResult", "identify_wake_distortion", "kr_frequency_response",
           "wake_distortion_from_runs",
           "KEY_PARAMETERS", "DesignPoint", "DesignSpaceError",
           "DesignSpaceResult", "identify_design_space", "spaced_config",
           "QuasiSteadyCheck", "quasi_steady_check", "TRUST_J_AVE_MAX", "low_frequency_gain", "low_frequency_points",
           "equation_error_masses", "equation_error_start", "WakeSensitivityResult", "wake_setting_sensitivity",
           "PITT_PETERS_COLLECTIVE_MASS", "Coaxial6StateAxisymmetric", "Coaxial6StateFeedthrough",
           "coaxial_sum_difference", "six_state_diagnostics"]
