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
    design_space.py  identify_design_space: the coaxial 6-state model over rotor spacing x
                   thrust, DesignSpaceResult (table, plot, .schedule() -> ScheduledInflow)

The wake (numba) is imported only when a pipeline runs.
"""
from .frames import COAXIAL_DIRECTIONS, FrameError, convert_frames, frame_signs
from .structures import (STRUCTURES, Coaxial6State, Coaxial12State, InflowStructure, SingleRotor3State,
                         get_structure)
from .store import SCHEMA, ModelFileError, ModelRecord, load_record, shipped_models
from .pipeline import (PIPELINE_VERSION, IdentificationSettings, IdentifiedModel, PipelineError,
                       identification_hash, identify_inflow)
from .design_space import (KEY_PARAMETERS, DesignPoint, DesignSpaceError, DesignSpaceResult,
                           identify_design_space, spaced_config)

__all__ = ["COAXIAL_DIRECTIONS", "FrameError", "convert_frames", "frame_signs",
           "STRUCTURES", "Coaxial6State", "Coaxial12State", "InflowStructure", "SingleRotor3State",
           "get_structure", "SCHEMA", "ModelFileError", "ModelRecord", "load_record", "shipped_models",
           "PIPELINE_VERSION", "IdentificationSettings", "IdentifiedModel", "PipelineError",
           "identification_hash", "identify_inflow", "KEY_PARAMETERS", "DesignPoint", "DesignSpaceError",
           "DesignSpaceResult", "identify_design_space", "spaced_config"]
