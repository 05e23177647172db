"""State-space structures with parametrised output equations (DERIVID-like).

:class:`StateSpaceStructure` is ``x' = F x + G u(t - tau)``,
``y = C x + D u(t - tau)`` where *every* matrix -- F, G, C and D -- is a pattern
matrix (numbers fixed, names free, shared names tied, ``-name`` tied with the
opposite sign). With C and D carrying parameters, models with measured
accelerations are written directly, e.g. the short-period pair with states
(w, q), outputs (q, a_z)::

    F = [["Zw", "U0"], ["Mw", "Mq"]]     G = [["Zde"], ["Mde"]]
    C = [[0, 1], ["Zw", 0]]              D = [[0], ["Zde"]]       # a_z = Zw w + Zde de

so one set of stability and control derivatives is fitted jointly to every
output's response with :func:`flightid.fit` (CIFER cost, Cramér-Rao bounds,
insensitivities, stability, reduction) or :func:`flightid.identify`.
"""
from __future__ import annotations

import numpy as np

from .errors import IdentificationError
from .structures import ModelStructure, _fgc_factors, _fgc_response, _unit_sensitivity

__all__ = ["StateSpaceStructure"]


class StateSpaceStructure(ModelStructure):
    """``x' = F x + G u(t - tau)``, ``y = C x + D u(t - tau)``, every matrix a pattern.

    Parameters
    ----------
    F, G : pattern matrices (n x n, n x n_inputs)
        Dynamics and control matrices.
    C : pattern matrix (n_outputs x n)
        Output matrix; may carry parameters (e.g. a_z = Zw w + Zde de).
    D : pattern matrix (n_outputs x n_inputs), optional
        Feedthrough; may carry parameters.
    tau : pattern matrix (n_outputs x n_inputs), optional
        Delay [s] of input j on output i.
    inputs, outputs : list of str
    initial : dict
        Initial value of every parameter.
    fixed : iterable of str
        Parameters held at their value.
    states : list of str, optional
        State names.

    Examples
    --------
    >>> s = StateSpaceStructure([["a"]], [["b"]], [[1.0], ["c"]], D=[[0.0], ["d"]],
    ...                         inputs=["u"], outputs=["x", "z"],
    ...                         initial={"a": -2.0, "b": 1.0, "c": 3.0, "d": 0.5})
    >>> h = s.frequency_response([0.0])[:, 0, 0].real     # static gains: b/2 and c b/2 + d
    >>> [round(float(v), 3) for v in h]
    [0.5, 2.0]
    """

    def __init__(self, F, G, C, D=None, tau=None, *, inputs, outputs, initial, fixed=(), states=None):
        for label, value in (("F", F), ("G", G), ("C", C)):
            if value is None:
                raise IdentificationError(f"{label} is required")
        bad = [k for k, v in dict(initial or {}).items()
               if not isinstance(v, (int, float, np.floating, np.integer)) or not np.isfinite(v)]
        if bad:
            raise IdentificationError(f"initial values must be finite numbers; check initial{bad}")
        self._init_parameters({"F": F, "G": G, "C": C, "D": D, "tau": tau}, inputs, outputs, initial,
                              fixed, None)
        n = self._patterns["F"].shape[0]
        n_out, n_in = len(self.outputs), len(self.inputs)
        if self._patterns["F"].shape != (n, n):
            raise IdentificationError(f"F must be square, got {self._patterns['F'].shape}")
        if self._patterns["G"].shape != (n, n_in):
            raise IdentificationError(f"G must be {n} x {n_in}, got {self._patterns['G'].shape}")
        if self._patterns["C"].shape != (n_out, n):
            raise IdentificationError(f"C must be {n_out} x {n}, got {self._patterns['C'].shape}")
        for label in ("D", "tau"):
            if label in self._patterns and self._patterns[label].shape != (n_out, n_in):
                raise IdentificationError(f"{label} must be {n_out} x {n_in}, "
                                          f"got {self._patterns[label].shape}")
        self.states = list(states) if states is not None else None
        if self.states is not None and len(self.states) != n:
            raise IdentificationError(f"states must name the {n} states, got {self.states}")

    def _state_names(self, n):
        return self.states if self.states and len(self.states) == n else super()._state_names(n)

    def _undelayed(self, mats, s):
        return _fgc_response(mats["F"], mats["G"], mats["C"], mats.get("D"), s)

    def _abcd(self, mats):
        d = mats.get("D", np.zeros((len(self.outputs), len(self.inputs))))
        return mats["F"], mats["G"], mats["C"], d

    def _entry_sensitivities(self, mats, s, i, j):
        f, g, c = mats["F"], mats["G"], mats["C"]
        row, col = _fgc_factors(f, g, c, s, i, j)
        out = {"F": row[:, :, None] * col[:, None, :], "G": np.zeros((s.size,) + g.shape, dtype=complex),
               "C": np.zeros((s.size,) + c.shape, dtype=complex)}
        out["G"][:, :, j] = row
        out["C"][:, i, :] = col          # dU_ij/dC_ib = (R G)_bj
        u = row @ g[:, j]
        if "D" in mats:
            out["D"] = _unit_sensitivity(mats["D"].shape, s.size, i, j)
            u = u + mats["D"][i, j]
        return u, out
