"""Input paths of an identified inflow model, switched off one group at a time.

An identified coaxial 12-state answers two kinds of input: the rotor loads
(``CT_U``, ``CL_U``, ...) and, with flap-rate inputs (Eq. 6.2), the tip-path-plane
rates (``beta1s_dot_U``, ...: the wake-curvature path). Flying the model with one
group disconnected says which path sets a derivative of the aircraft, e.g. which
one takes the roll damping away below the fit band
(:func:`studies.analysis.twelve_state_variants.compare_twelve_state_variants`).

::

    without_inputs(IdentifiedInflow, ["beta1s_dot_U", ...]) -> IdentifiedInflow
        (the same A, C, D and trim references; those columns of B zero)
"""
from __future__ import annotations

import control
import numpy as np

from .identified import IdentifiedInflow, _sysname
from .pitt_peters import InflowError

__all__ = ["without_inputs"]


def without_inputs(model, names):
    """The same inflow model with the named inputs disconnected: a diagnostic of its paths.

    Their columns of ``B`` are set to zero, so the inflow no longer answers them;
    everything else (states, poles, the other inputs' responses, the trim
    references) is unchanged. E.g. ``without_inputs(model, model.rate_names)``
    keeps only the load path, to see what the flap-rate (wake-curvature) path does
    to the aircraft.

    Parameters
    ----------
    model : aircraft.inflow.IdentifiedInflow
        The model (loads, and flap rates where it has them, as inputs).
    names : str or sequence of str
        Input names of the model (loads ``CT_U``, ... or flap rates
        ``beta1s_dot_U``, ...).

    Returns
    -------
    IdentifiedInflow
        A new model named ``"<name> without <inputs>"``.

    Raises
    ------
    TypeError
        If ``model`` is not an :class:`IdentifiedInflow`.
    InflowError
        An empty list, or a name that is not one of the model's inputs.
    """
    if not isinstance(model, IdentifiedInflow):
        raise TypeError(f"model must be an IdentifiedInflow, got {type(model).__name__}")
    names = [names] if isinstance(names, str) else list(names)
    inputs = list(model.system.input_labels)
    unknown = [n for n in names if n not in inputs]
    if not names or unknown:
        raise InflowError(f"without_inputs needs names among the model's inputs {inputs}, got {names}")
    B = np.array(model.system.B, dtype=float)
    B[:, [inputs.index(n) for n in names]] = 0.0
    label = f"{model.name} without {', '.join(names)}"
    sys = control.ss(model.system.A, B, model.system.C, model.system.D, inputs=inputs,
                     outputs=list(model.system.output_labels), states=list(model.system.state_labels),
                     name=_sysname(label))
    return IdentifiedInflow(sys, model.rotors, model.loads_ref.copy(), model.inflow_ref.copy(), name=label)
