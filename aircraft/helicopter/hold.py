"""Hold states of a linear aircraft model at their trim values (a perfectly tight outer loop).

The roll design plant of Eq. 7.21 constrains p, q, r and w through the controls and
leaves everything else free, the translational drift u, v included. In our coaxial
with an identified inflow model, that drift sets a pair of zeros within 0.05 rad/s
of the origin whose sign is a small difference of large cross-axis terms
(``results/hover_control_comparison/slow_zeros.csv``). A position-hold outer loop
would hold u and v; :func:`hold_states` models it as a perfectly tight one, by
removing the held states from the state equations (their perturbations stay zero)::

    hold_states(linearize(trim_result), ["u", "v"]) -> control.StateSpace

In forward flight the pedals hold sideslip, not heading: :func:`sideslip_yaw_channel`
gives the yaw channel's signals the nose's angle from the flight path and its rate.
"""
from __future__ import annotations

import control
import numpy as np

__all__ = ["hold_states", "sideslip_yaw_channel"]


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


def sideslip_yaw_channel(sys, speed):
    """The linear model with the yaw channel's outputs r and psi replaced by sideslip ones.

    In forward flight the pedals command and hold sideslip (turns are made with bank);
    the yaw loop of a multi-axis design reads the outputs named ``r`` and ``psi``.
    This returns the model with those two outputs replaced, to first order in v/V, by
    the nose's angle from the flight path, ``-beta = -v / speed`` [rad] (as ``psi``),
    and its rate ``-v_dot / speed`` [rad/s] (as ``r``, from the state equation of v:
    the A and B rows of v over ``-speed``). Positive nose right of the flight path,
    the sense a right pedal gives; every other output and the states are unchanged.

    Parameters
    ----------
    sys : control.StateSpace
        Linear model with a state ``v`` (body lateral velocity [m/s]) and outputs
        ``r`` and ``psi`` (e.g. :func:`aircraft.helicopter.linearize`).
    speed : float
        Trim airspeed V [m/s], > 0.

    Returns
    -------
    control.StateSpace
        Same states, inputs and output names.

    Raises
    ------
    ValueError
        ``speed`` not a positive finite number, or no state ``v`` or output ``r``/``psi``.

    Examples
    --------
    >>> import control
    >>> sys = control.ss([[-0.5, 0.0], [0.0, 0.0]], [[2.0], [1.0]], [[0, 1.0], [0, 1.0]], 0,
    ...                  states=["v", "psi"], inputs=["delta_ped"], outputs=["r", "psi"])
    >>> out = sideslip_yaw_channel(sys, 10.0)
    >>> out.C.tolist(), out.D.tolist()
    ([[0.05, -0.0], [-0.1, 0.0]], [[-0.2], [0.0]])
    """
    if isinstance(speed, bool) or not np.isfinite(speed) or speed <= 0:
        raise ValueError(f"sideslip_yaw_channel: speed must be a positive airspeed [m/s], got {speed!r}")
    states, outputs = list(sys.state_labels), list(sys.output_labels)
    missing = [n for n in ("v",) if n not in states] + [n for n in ("r", "psi") if n not in outputs]
    if missing:
        raise ValueError(f"sideslip_yaw_channel: sys lacks {missing} (states {states[:9]}..., "
                         f"outputs {outputs[:9]}...)")
    A, B = np.asarray(sys.A), np.asarray(sys.B)
    C, D = np.array(sys.C, dtype=float), np.array(sys.D, dtype=float)
    iv, ir, ipsi = states.index("v"), outputs.index("r"), outputs.index("psi")
    C[ir], D[ir] = -A[iv] / speed, -B[iv] / speed
    C[ipsi], D[ipsi] = 0.0, 0.0
    C[ipsi, iv] = -1.0 / speed
    return control.ss(A, B, C, D, states=states, inputs=list(sys.input_labels), outputs=outputs,
                      name=f"{sys.name} with sideslip on the yaw channel")
