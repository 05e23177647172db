"""Identified inflow with the rotors' tip-path-plane *tilts* as further inputs.

A coaxial rotor's inflow answers a held tilt of a tip-path plane relative to the
other rotor: the tilted blades move through the vertical gradient of the other
rotor's induced velocity (:mod:`aircraft.identification.structures.tilt`). The tilt
that matters is the one relative to the shaft (both rotors move with the
airframe), i.e. the aircraft's flapping states ``beta1s, beta1c`` of each rotor in
its own frame (:mod:`aircraft.inflow.base`), not the space-fixed tip-path-plane
attitude that the integral of the flap-rate inputs would give.

::

    TiltInflow(system, tilt_matrix, tilt_names)     x' = A x + B [dC; beta_dot] + B_T (beta - beta_ref)
        .derivatives(x, loads, ops, rates, tilts)
        .linear(loads, ops)  StateSpace with the tilts as inputs too
        .tilt_gain()       steady inflow per rad of tilt, a DataFrame
    flown by aircraft.helicopter.tilt_coupling.TiltCoupledHelicopter
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from .base import rotor_suffix
from .identified import IdentifiedInflow
from .pitt_peters import InflowError

__all__ = ["TiltInflow", "TILT_HARMONICS", "tilt_names"]


#: The tilt harmonics per rotor, in the order of every tilt vector and matrix column.
TILT_HARMONICS = ("beta1s", "beta1c")


def tilt_names(rotors):
    """The tilt inputs' names: ``beta1s_U, beta1c_U, beta1s_L, beta1c_L`` (single rotor:
    ``beta1s, beta1c``).

    Parameters
    ----------
    rotors : sequence of str
        Rotor names (``("U", "L")``, or ``("",)`` for a single rotor).

    Returns
    -------
    list of str
    """
    return [f"{b}{rotor_suffix(r)}" for r in rotors for b in TILT_HARMONICS]


class TiltInflow(IdentifiedInflow):
    """:class:`IdentifiedInflow` plus a tip-path-plane tilt input matrix.

    Parameters
    ----------
    system : control.StateSpace
        The model without the tilts (as :class:`IdentifiedInflow`; time in seconds).
    tilt_matrix : array_like, shape (n_states, 2 * n_rotors) or (k, 2 * n_rotors), k < n_states
        ``d x / d t`` per rad of shaft-relative tilt [1/s], columns in
        :func:`tilt_names` order; fewer rows than states are the leading states'
        (the rest zero).
    rotors, loads_ref, inflow_ref, name :
        As :class:`IdentifiedInflow`.
    tilt_ref : array_like, optional
        Tilts at the identification trim [rad] (default zeros: the wake's rigid,
        unflapped trim).

    Raises
    ------
    InflowError
        A tilt matrix of the wrong shape or with non-finite entries.
    """

    uses_flap_tilts = True
    #: the tilts of the aircraft state being evaluated (set by TiltCoupledHelicopter)
    _pending_tilts = None

    def __init__(self, system, tilt_matrix, rotors=None, loads_ref=None, inflow_ref=None, name="identified",
                 tilt_ref=None):
        super().__init__(system, rotors, loads_ref, inflow_ref, name)
        bt = np.asarray(tilt_matrix, float)
        n, m = self.system.nstates, 2 * len(self.rotors)
        if bt.ndim != 2 or bt.shape[1] != m or bt.shape[0] > n:
            raise InflowError(f"tilt_matrix must have {m} columns {self.tilt_names} and at most {n} rows, "
                              f"got shape {bt.shape}")
        if not np.all(np.isfinite(bt)):
            raise InflowError("tilt_matrix has non-finite entries")
        self.tilt_matrix = np.vstack([bt, np.zeros((n - bt.shape[0], m))])
        self.tilt_ref = np.zeros(m) if tilt_ref is None else np.asarray(tilt_ref, float)
        if self.tilt_ref.shape != (m,):
            raise InflowError(f"tilt_ref needs {m} entries {self.tilt_names}")

    @classmethod
    def from_inflow(cls, inflow, tilt_matrix, names=None, *, inflow_block=None, tilt_ref=None):
        """Add tilt inputs to an :class:`IdentifiedInflow`.

        Parameters
        ----------
        inflow : IdentifiedInflow
        tilt_matrix : array_like, shape (k, 2 * n_rotors) [1/s per rad]
            Rows: the first ``k`` states of ``inflow.system``.
        names : list of str, optional
            The columns' names; must be :func:`tilt_names` (checked).
        inflow_block : array_like, shape (k, k), optional
            The state matrix those ``k`` rows belong to [1/s]: checked against
            ``inflow.system.A[:k, :k]``, so that a realisation that reordered the
            states (e.g. by its delays) cannot silently take the gains on the wrong states.
        """
        bt = np.asarray(tilt_matrix, float)
        if names is not None and list(names) != tilt_names(inflow.rotors):
            raise InflowError(f"tilt columns {list(names)} must be {tilt_names(inflow.rotors)}")
        if inflow_block is not None:
            k = bt.shape[0]
            a = np.asarray(inflow.system.A)[:k, :k]
            blk = np.asarray(inflow_block, float)
            if blk.shape != (k, k) or not np.allclose(a, blk, rtol=1e-10, atol=1e-12 * max(1.0, np.abs(blk).max())):
                raise InflowError("the model's leading states are not the tilt gains' states "
                                  "(its realisation reordered them)")
        return cls(inflow.system, bt, inflow.rotors, inflow.loads_ref, inflow.inflow_ref, inflow.name, tilt_ref)

    @property
    def tilt_names(self):
        return tilt_names(self.rotors)

    def _tilt_term(self, tilts):
        if tilts is None:
            raise InflowError(f"{self.name!r} takes the rotors' tip-path-plane tilts {self.tilt_names} [rad]: "
                              "fly it with aircraft.helicopter.tilt_coupling.TiltCoupledHelicopter")
        b = np.asarray(tilts, float)
        if b.shape != self.tilt_ref.shape or not np.all(np.isfinite(b)):
            raise InflowError(f"tilts must be {self.tilt_ref.size} finite values {self.tilt_names} [rad], "
                              f"got {tilts!r}")
        return self.tilt_matrix @ (b - self.tilt_ref)

    def derivatives(self, x, loads, ops, rates=None, tilts=None):
        """``dx/dt`` [1/s]: the identified model's, plus the tilt term.

        ``tilts`` [rad] are required: given here, or set for the current evaluation
        by :class:`~aircraft.helicopter.tilt_coupling.TiltCoupledHelicopter` (the
        base helicopter calls this without them)."""
        if tilts is None:
            tilts = self._pending_tilts
        return super().derivatives(x, loads, ops, rates) + self._tilt_term(tilts)

    def steady_state(self, loads, ops, tilts=None):
        """States at equilibrium with ``loads`` and ``tilts`` (zeros: the reference tilts)."""
        b = self.tilt_ref if tilts is None else tilts
        return -np.linalg.solve(self.system.A, self.system.B @ self._u(loads, None) + self._tilt_term(b))

    def linear(self, loads, ops):
        """The linear model with the tilts as further inputs (after the loads and flap
        rates), about ``loads`` and the reference tilts; as :meth:`IdentifiedInflow.linear`."""
        import control
        base = super().linear(loads, ops)
        sys = control.ss(base.A, np.hstack([np.asarray(base.B), self.tilt_matrix]), base.C,
                         np.zeros((base.noutputs, base.ninputs + self.tilt_matrix.shape[1])),
                         inputs=list(base.input_labels) + self.tilt_names, outputs=list(base.output_labels),
                         states=list(base.state_labels), name=base.name)
        sys.trim_states = base.trim_states
        sys.trim_inputs = np.concatenate([base.trim_inputs, self.tilt_ref])
        sys.trim_outputs = base.trim_outputs
        return sys

    def without_tilts(self):
        """The same model with the tilt path disconnected (an :class:`IdentifiedInflow`)."""
        return IdentifiedInflow(self.system, self.rotors, self.loads_ref, self.inflow_ref,
                                f"{self.name} without tilts")

    def tilt_gain(self):
        """Steady inflow change per rad of tilt [-/rad], outputs x tilts (DC gain of the tilt path)."""
        sys = self.system
        g = -np.asarray(sys.C) @ np.linalg.solve(np.asarray(sys.A), self.tilt_matrix)
        return pd.DataFrame(g, index=list(sys.output_labels), columns=self.tilt_names)
