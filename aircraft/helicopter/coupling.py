"""Coupling numerators (Eq. 7.21): single-axis plants with other loops closed tightly.

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

__all__ = ["coupling_numerator", "CouplingError"]


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
        Constrained output name -> control used to hold it.
    """
    out_idx = [sys.output_labels.index(o) for o in constrained] if constrained else []
    in_idx = [sys.input_labels.index(i) for i in constrained.values()] if constrained else []
    if output not in sys.output_labels or input not in sys.input_labels:
        raise CouplingError(f"unknown output {output!r} or input {input!r}")
    a, b, c = np.asarray(sys.A), np.asarray(sys.B), np.asarray(sys.C)
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
