"""Inflow model identification from the free-vortex wake (library, not a study).

::

    structures.py  the dissertation's structures in our frames: SingleRotor3State
                   (Tables 4.1-4.2), Coaxial6State (Eq. 5.3), Coaxial12State (Eqs. 6.2-6.3)
    frames.py      conversion between the dissertation's common frame and our rotor frames
    pipeline.py    identify_inflow: trim -> sweeps -> responses -> joint input-output
                   -> fit -> reduce -> verify; IdentifiedModel
    store.py       versioned model files (aircraft/data/models/*.json), ModelRecord
    regenerate.py  recipes of the shipped models; ``python -m aircraft.identification.regenerate``
    synthetic.py   synthetic-truth data generated with scipy (independent of flightid)
    forward.py     single rotor in forward flight (§4.4): SingleRotorForward (Eq. 4.3),
                   identify_forward_flight, comparison with Pitt-Peters and Eqs. 4.7-4.8
    wake_distortion.py  K_R(omega) in hover from tip-path-plane sweeps (§4.7, Fig. 4.39)

The wake (numba) is imported only when a pipeline runs.
"""
from .frames import COAXIAL_DIRECTIONS, FrameError, convert_frames, frame_signs
from .structures import (STRUCTURES, Coaxial6State, Coaxial12State, InflowStructure, SingleRotor3State,
                         get_structure)
from .store import SCHEMA, ModelFileError, ModelRecord, load_record, shipped_models
from .pipeline import (PIPELINE_VERSION, IdentificationSettings, IdentifiedModel, PipelineError,
                       identification_hash, identify_inflow)
from .forward import (SingleRotorForward, forward_bode_overlay, forward_comparison_table, forward_condition,
                      identify_forward_flight, pitt_peters_forward)
from .wake_distortion import (KR_CONTROLS, WakeDistortionResult, identify_wake_distortion, kr_frequency_response,
                              wake_distortion_from_runs)

STRUCTURES[SingleRotorForward.key] = SingleRotorForward

__all__ = ["COAXIAL_DIRECTIONS", "FrameError", "convert_frames", "frame_signs",
           "STRUCTURES", "Coaxial6State", "Coaxial12State", "InflowStructure", "SingleRotor3State",
           "get_structure", "SCHEMA", "ModelFileError", "ModelRecord", "load_record", "shipped_models",
           "PIPELINE_VERSION", "IdentificationSettings", "IdentifiedModel", "PipelineError",
           "identification_hash", "identify_inflow",
           "SingleRotorForward", "forward_bode_overlay", "forward_comparison_table", "forward_condition",
           "identify_forward_flight", "pitt_peters_forward",
           "KR_CONTROLS", "WakeDistortionResult", "identify_wake_distortion", "kr_frequency_response",
           "wake_distortion_from_runs"]
