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

from .errors import IdentificationError, DataError, SettlingWarning
from .sweeps import frequency_sweep, doublet, multistep_3211
from .multisine import orthogonal_multisine
from .flight_data import read_flight_data, concatenated_response
from .response import frequency_response, MeasuredResponse, combine_responses
from .joint import joint_input_output
from .mimo import mimo_response
from .structures import ModelStructure, MLTauStructure, FGCStructure, GainDelayStructure
from .transfer_function import TransferFunctionStructure, fit_transfer_function
from .state_space import StateSpaceStructure
from .fitting import fit, FitResult, cifer_cost
from .fourier import identify
from .reduction import reduce, ReductionRule
from .verification import verify
from .staging import fit_staged

__all__ = ["IdentificationError", "DataError", "frequency_sweep", "doublet", "multistep_3211",
           "orthogonal_multisine", "read_flight_data", "concatenated_response", "frequency_response",
           "MeasuredResponse", "combine_responses", "joint_input_output", "mimo_response", "ModelStructure",
           "MLTauStructure", "FGCStructure", "GainDelayStructure", "TransferFunctionStructure",
           "StateSpaceStructure", "fit", "FitResult", "fit_transfer_function", "identify", "reduce", "verify",
           "fit_staged", "cifer_cost", "SettlingWarning", "ReductionRule"]
