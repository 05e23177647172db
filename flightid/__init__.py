"""flightid: frequency-domain system identification (CIFER-class), generic.

Nothing here knows about rotors: the same code identifies a free-vortex wake,
a flight-test record or a wind-tunnel record.

::

    frequency_sweep / doublet / multistep_3211          (test inputs)
    orthogonal_multisine                                (all inputs in one record)
    read_flight_data ─► FlightRecord (DataFrame/CSV, units, resample, detrend)
              │ time histories t, u, y
              ▼
    frequency_response ─► MeasuredResponse (FRD + coherence)   chirp-z, composite windows
    concatenated_response (several runs of one axis: pooled spectra)
    mimo_response / harmonic_response ─► MIMOResponse           simultaneous inputs (G_yu G_uu^-1)
              │ combine_responses, joint_input_output (y/u from y/θ and u/θ)
              ▼
    MLTauStructure / FGCStructure / GainDelayStructure  (free / fixed / tied parameters)
    TransferFunctionStructure (fit_transfer_function, loes_fit); StateSpaceStructure (C, D too)
    MLTauFeedthroughStructure (+ direct D);  TransformedStructure (fit in other
              coordinates, e.g. sum/difference, with transform_response)
              │ fit  (CIFER cost, Cramér-Rao, insensitivity, stability, multi-start;
              │       DegeneracyReport: flat directions, square-block singular values)
              │ identify(method="cifer" | "output_error" | "equation_error"): a FlightRecord
              │   by composite-window responses or by Fourier transforms of the whole record
              │ fit_staged (plan of Stage s, §6.4.3)
              │ reduce (automatic Fig. 6.1 loop; refuses removals without a finite optimum)
              ▼
    FitResult.model  ─►  control.StateSpace (Padé delays)  ─►  verify (TIC, RMS)
"""
from .errors import (DataError, IdentificationError, InputValueError, SignalNameError,
                     SingularInputError, UnstableModelError)
from .sweeps import doublet, frequency_sweep, multistep_3211, shaped_noise
from .response import MeasuredResponse, combine_responses, frequency_response
from .joint import joint_input_output
from .multisine import Multisine, orthogonal_multisine, relative_peak_factor
from .mimo import MIMOResponse, harmonic_response, mimo_response
from .structures import FGCStructure, GainDelayStructure, MLTauStructure, ModelStructure
from .fitting import COHERENCE_FLOOR, FitResult, cifer_cost, coherence_weight, fit
from .degeneracy import DegeneracyReport, MultiStartReport, NoInformationError
from .reduction import ReductionResult, reduce
from .staging import Stage, StagedFitResult, fit_staged
from .verification import VerificationResult, theil_inequality, verify
from .feedthrough import MLTauFeedthroughStructure
from .flight_data import concatenated_response, read_flight_data
from .transfer_function import TransferFunctionStructure, fit_transfer_function, loes_fit
from .state_space import StateSpaceStructure
from .fourier import identify
from .transformed import TransformedStructure, pair_costs, sum_difference_transform, transform_response

__all__ = [
    "DataError", "IdentificationError", "InputValueError", "SignalNameError",
    "SingularInputError", "UnstableModelError",
    "doublet", "frequency_sweep", "multistep_3211", "shaped_noise",
    "MeasuredResponse", "combine_responses", "frequency_response",
    "joint_input_output",
    "Multisine", "orthogonal_multisine", "relative_peak_factor",
    "MIMOResponse", "harmonic_response", "mimo_response",
    "FGCStructure", "GainDelayStructure", "MLTauStructure", "ModelStructure",
    "COHERENCE_FLOOR", "FitResult", "cifer_cost", "coherence_weight", "fit",
    "DegeneracyReport", "MultiStartReport", "NoInformationError",
    "ReductionResult", "reduce",
    "Stage", "StagedFitResult", "fit_staged",
    "VerificationResult", "theil_inequality", "verify",
    "MLTauFeedthroughStructure", "TransformedStructure", "pair_costs", "sum_difference_transform",
    "transform_response",
    "concatenated_response", "read_flight_data",
    "TransferFunctionStructure", "fit_transfer_function", "loes_fit", "StateSpaceStructure", "identify",
]
