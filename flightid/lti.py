"""Pure LTI operations on named state-space models: coupling numerators (Eq. 7.21), residualisation.

Shared by the aircraft (bare-airframe responses), the control design (design plants)
and anyone reducing an identified model; nothing here knows about rotors.

Coupling numerators are single-axis plants with the other loops closed tightly.

``p/delta_lat | q->delta_lon, r->delta_ped, w->delta_col`` is the response when
the constrained outputs are held at zero by infinitely tight feedback to their
controls.  Exactly: with y_c = C_c x = 0 and C_c B_c invertible (relative degree
one), u_c = -(C_c B_c)^-1 (C_c A x + C_c B_1 u_1); the motion stays on
null(C_c), onto which we project, giving a realisation whose transfer function
is the ratio of coupling numerators N(...)/N(...) of Eq. 7.21.
"""
from __future__ import annotations

import control
import numpy as np
from scipy.linalg import null_space

__all__ = ["coupling_numerator", "residualize", "CouplingError"]


class CouplingError(ValueError):
    """The constrained outputs cannot be held by the named controls."""


def coupling_numerator(sys, output, input, constrained):
    """SISO StateSpace output/input with ``constrained = {output: input, ...}`` held.

    Parameters
    ----------
    sys : control.StateSpace
        Named signals; strictly proper (D = 0) in the constrained outputs.
    output, input : str
    constrained : dict
        Constrained output name -> control used to hold it.  Each control holds
        one output; neither the swept ``input`` nor the plant ``output`` may
        appear in it (a swept control that also holds a loop is no input any
        more: the result would be an all-zero plant).

    Raises
    ------
    CouplingError
        Unknown names, a control used twice or also swept, the output itself
        constrained, a feedthrough (D != 0) in a constrained loop, non-finite
        matrices, or C_c B_c singular.
    """
    if not isinstance(sys, control.StateSpace):
        raise CouplingError(f"sys must be a control.StateSpace with named signals, got {type(sys).__name__}")
    if constrained is None:
        constrained = {}
    if not isinstance(constrained, dict):
        raise CouplingError(f"constrained must be a dict {{output: holding control}}, got {constrained!r}")
    outputs, inputs = list(sys.output_labels), list(sys.input_labels)
    if output not in outputs:
        raise CouplingError(f"unknown output {output!r}; the system has outputs {outputs}")
    if input not in inputs:
        raise CouplingError(f"unknown input {input!r}; the system has inputs {inputs}")
    unknown_o = [o for o in constrained if o not in outputs]
    unknown_i = [i for i in constrained.values() if i not in inputs]
    if unknown_o or unknown_i:
        raise CouplingError(f"constrained names unknown: outputs {unknown_o}, controls {unknown_i}; "
                            f"the system has outputs {outputs} and inputs {inputs}")
    if output in constrained:
        raise CouplingError(f"the plant output {output!r} cannot also be a constrained output")
    if input in constrained.values():
        held = [o for o, i in constrained.items() if i == input]
        raise CouplingError(f"the swept input {input!r} is also the control holding {held}: "
                            "a control cannot be both the plant input and a loop's control")
    if len(set(constrained.values())) != len(constrained):
        raise CouplingError(f"each constrained output needs its own control, got {constrained}")
    mats = [np.asarray(m) for m in (sys.A, sys.B, sys.C, sys.D)]
    if any(np.iscomplexobj(m) or not np.all(np.isfinite(m)) for m in mats):
        raise CouplingError("sys matrices contain complex, NaN or infinite values")
    out_idx = [outputs.index(o) for o in constrained]
    in_idx = [inputs.index(i) for i in constrained.values()]
    if out_idx and np.any(mats[3][np.ix_(out_idx, in_idx + [inputs.index(input)])] != 0):
        raise CouplingError("the constrained outputs have a feedthrough (D != 0) from the controls: "
                            "the tight-loop construction needs them strictly proper")
    a, b, c = (np.asarray(m, float) for m in mats[:3])
    j = sys.input_labels.index(input)
    i = sys.output_labels.index(output)
    if not constrained:
        return control.ss(a, b[:, [j]], c[[i], :], 0, inputs=[input], outputs=[output])
    cc, bc = c[out_idx, :], b[:, in_idx]
    cb = cc @ bc
    if np.linalg.cond(cb) > 1e12:
        raise CouplingError("C_c B_c is singular: the named controls cannot hold the constrained "
                            "outputs with relative degree one")
    k = np.linalg.solve(cb, cc)
    a_t = a - bc @ k @ a
    b_t = b[:, [j]] - bc @ np.linalg.solve(cb, cc @ b[:, [j]])
    basis = null_space(cc)
    a_r = basis.T @ a_t @ basis
    b_r = basis.T @ b_t
    c_r = c[[i], :] @ basis
    return control.ss(a_r, b_r, c_r, 0, inputs=[input], outputs=[output],
                      name=f"{output}/{input} coupling numerator")


def residualize(sys, cutoff):
    """Residualise the modes faster than ``cutoff`` [rad/s] (singular perturbation).

    The state space is block-diagonalised into slow (|lambda| < cutoff) and fast
    modes (ordered real Schur form + a Sylvester equation), and the fast block
    is replaced by its static (DC) contribution, so the DC gain is exact and the
    response below ~cutoff/10 changes by O(omega/cutoff).  Used to give control
    design a plant without the far-off dynamics (e.g. the unstable high-frequency
    poles a coupling numerator inherits from non-minimum-phase zeros of the
    constraining loops, ~100 rad/s for this hingeless coaxial).

    Parameters
    ----------
    sys : control.StateSpace
        System to reduce (any number of inputs and outputs).
    cutoff : float
        Modes with ``|lambda| >= cutoff`` [rad/s] are residualised.

    Returns
    -------
    control.StateSpace
        The slow modes with the fast modes' DC contribution in ``D`` (``sys``
        itself when no mode is fast).

    Raises
    ------
    CouplingError
        ``sys`` is not a StateSpace, has non-finite matrices, or ``cutoff`` is not
        a positive finite frequency [rad/s].
    """
    import math
    import numbers
    from scipy.linalg import schur, solve_sylvester
    if not isinstance(sys, control.StateSpace):
        raise CouplingError(f"sys must be a control.StateSpace, got {type(sys).__name__}")
    if isinstance(cutoff, bool) or not isinstance(cutoff, numbers.Real) or not math.isfinite(cutoff) \
            or cutoff <= 0:
        raise CouplingError(f"cutoff must be a positive finite frequency [rad/s], got {cutoff!r}")
    if not all(np.all(np.isfinite(np.asarray(m))) for m in (sys.A, sys.B, sys.C, sys.D)):
        raise CouplingError("sys matrices contain NaN or infinite values")
    a, b, c, d = (np.asarray(m, float) for m in (sys.A, sys.B, sys.C, sys.D))
    t, z, n_slow = schur(a, output="real", sort=lambda re, im: np.hypot(re, im) < cutoff)
    if n_slow == a.shape[0]:
        return sys
    a11, a12, a22 = t[:n_slow, :n_slow], t[:n_slow, n_slow:], t[n_slow:, n_slow:]
    x = solve_sylvester(a11, -a22, -a12)          # decouple: T = [[I, X], [0, I]]
    bt = z.T @ b
    ct = c @ z
    b1 = bt[:n_slow] - x @ bt[n_slow:]
    b2 = bt[n_slow:]
    c1 = ct[:, :n_slow]
    c2 = ct[:, :n_slow] @ x + ct[:, n_slow:]
    d_new = d - c2 @ np.linalg.solve(a22, b2)
    return control.ss(a11, b1, c1, d_new, inputs=sys.input_labels, outputs=sys.output_labels,
                      name=f"{sys.name} (residualised above {cutoff:g} rad/s)")
