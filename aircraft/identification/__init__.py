"""Inflow model identification from the free-vortex wake: what a user calls on their own rotor.

::

    pipeline.py          identify_inflow: trim -> sweeps -> responses -> joint input-output
                         -> fit -> reduce -> verify; IdentificationSettings, IdentifiedModel
    multisine.py         identify_inflow_multisine: the same from orthogonal-multisine records
    multisine_records.py   the controls split over parallel records, their responses assembled
    structures/          the inflow structures and their one registry (STRUCTURES, get_structure)
    conditions.py        flight_condition: the wind-tunnel condition of an advance ratio or a speed
    forward_flight.py    identify_forward_flight (single rotor), pitt_peters_forward
    advance_ratio.py     identify_over_advance_ratio: the 3-state M, Lbar over mu beside Pitt-Peters
    coaxial_forward_flight.py  identify_coaxial_forward (the coaxial at 200 kt, bounded reduction)
    off_rotor/           off-rotor induced-velocity models (tail, wing): identify_off_rotor
    wake_distortion.py   K_R(omega) from tip-path-plane sweeps: identify_wake_distortion
    design_space.py      the 6-state model over rotor spacing x thrust: identify_design_space
    trust.py             when a model is trusted (the guideline and its keep rule): trust_check
    quasi_steady.py      a model's DC gain against held steps of the wake: quasi_steady_check
    steady_gains.py      the wake's steady gains from held steps, ramps and tilts: wake_steady_gains
    wake_sensitivity.py  the same sweeps on wakes of different settings: wake_setting_sensitivity
    starts.py            equation-error starts of the M/Lbar/tau structures
    shipped.py           recipes of the shipped model files (``rotorwake shipped-models``)
    model_code.py        the code digest a model file records, and why a file is stale
    testing.py           synthetic-truth data generated with scipy, for tests

The model files and frame conversions live in :mod:`aircraft.inflow` (``model_files``,
``frames``). The wake (numba) is imported only when a pipeline runs.

Examples
--------
>>> from aircraft.identification import IdentificationSettings, get_structure
>>> get_structure("coaxial_6state").key
'coaxial_6state'
>>> IdentificationSettings().cramer_rao_max
20.0
"""
from .structures import STRUCTURES, InflowStructure, get_structure, register_structure
from .conditions import flight_condition
from .pipeline import IdentificationSettings, IdentifiedModel, PipelineError, identification_hash, identify_inflow
from .multisine import MultisineSettings, identify_inflow_multisine
from .forward_flight import identify_forward_flight, pitt_peters_forward
from .advance_ratio import AdvanceRatioSweep, identify_over_advance_ratio
from .coaxial_forward_flight import identify_coaxial_forward
from .off_rotor import OffRotorSettings, OffRotorSurface, identify_off_rotor
from .wake_distortion import identify_wake_distortion
from .design_space import DesignSpaceResult, identify_design_space
from .trust import TrustCheck, trust_check
from .quasi_steady import quasi_steady_check
from .steady_gains import wake_steady_gains
from .wake_sensitivity import wake_setting_sensitivity

__all__ = ["identify_inflow", "IdentificationSettings", "IdentifiedModel", "PipelineError", "identification_hash",
           "identify_inflow_multisine", "MultisineSettings", "STRUCTURES", "InflowStructure", "get_structure",
           "register_structure", "flight_condition", "identify_forward_flight", "pitt_peters_forward",
           "identify_over_advance_ratio", "AdvanceRatioSweep",
           "identify_coaxial_forward", "identify_off_rotor", "OffRotorSettings", "OffRotorSurface",
           "identify_wake_distortion", "identify_design_space", "DesignSpaceResult", "trust_check",
           "TrustCheck", "quasi_steady_check", "wake_steady_gains", "wake_setting_sensitivity"]
