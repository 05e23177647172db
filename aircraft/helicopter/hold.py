"""Hold states of a linear aircraft model at their trim values (a perfectly tight outer loop).

The roll design plant of Eq. 7.21 constrains p, q, r and w through the controls and
leaves everything else free, the translational drift u, v included. In our coaxial
with an identified inflow model, that drift sets a pair of zeros within 0.05 rad/s
of the origin whose sign is a small difference of large cross-axis terms
(``results/hover_control_comparison/slow_zeros.csv``). A position-hold outer loop
would hold u and v; :func:`hold_states` models it as a perfectly tight one, by
removing the held states from the state equations (their perturbations stay zero)::

    hold_states(linearize(trim_result), ["u", "v"]) -> control.StateSpace
"""
from __future__ import annotations

import control
import numpy as np

__all__ = ["hold_states"]


def hold_states(sys, names):
    """The linear model with the named states held at their trim values.

    Parameters
    ----------
    sys : control.StateSpace
        Linear model with named states (e.g. :func:`aircraft.helicopter.linearize`).
    names : str or sequence of str
        States held (e.g. ``["u", "v"]``: body velocities [m/s]); their rows and
        columns are removed, so their perturbations stay zero and nothing else
        changes.

    Returns
    -------
    control.StateSpace
        Same inputs and outputs, the remaining states in their order.

    Raises
    ------
    ValueError
        An empty list, an unknown state, a repeated one, or every state held.
    """
    names = [names] if isinstance(names, str) else list(names)
    states = list(sys.state_labels)
    unknown = [n for n in names if n not in states]
    if not names or unknown or len(set(names)) != len(names):
        raise ValueError(f"hold_states needs distinct state names among {states[:12]}..., got {names}")
    keep = [i for i, n in enumerate(states) if n not in names]
    if not keep:
        raise ValueError("hold_states would hold every state")
    A = np.asarray(sys.A)[np.ix_(keep, keep)]
    return control.ss(A, np.asarray(sys.B)[keep], np.asarray(sys.C)[:, keep], np.asarray(sys.D),
                      inputs=list(sys.input_labels), outputs=list(sys.output_labels),
                      states=[states[i] for i in keep], name=f"{sys.name} holding {', '.join(names)}")
