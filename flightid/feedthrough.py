"""M/Lbar/tau structure with a direct (quasi-static) feedthrough.

``M x' + Lbar x = u(t - tau)``, ``y = C x + D u(t - tau)``: the apparent-mass
form of :class:`flightid.MLTauStructure` plus a pattern matrix ``D`` of
instantaneous gains. For an inflow model, ``D`` is the part of the induced
velocity that follows the loads without lag (the bound and near-wake vorticity,
whose own dynamics are far above the fit band); the 12-state F/G/C model of §6.3
gives that part its own fast states instead. The delays act on the whole element
(dynamic and direct part alike), as row-wise delays do in :class:`MLTauStructure`.
"""
from __future__ import annotations

from .errors import IdentificationError
from .structures import MLTauStructure

__all__ = ["MLTauFeedthroughStructure"]


class MLTauFeedthroughStructure(MLTauStructure):
    """``M x' + Lbar x = u(t - tau)``, ``y = C x + D u(t - tau)``.

    Parameters
    ----------
    M, Lbar, tau
        As in :class:`flightid.MLTauStructure`.
    D : pattern matrix (n_outputs x n_inputs)
        Direct gains [output units per input unit]; names are parameters, shared
        names are ties, ``-name`` a tie of opposite sign.
    inputs, outputs, initial, fixed, C, states
        As in :class:`flightid.MLTauStructure` (``initial`` includes ``D``'s
        parameters).
    omega : float, optional
        Rotor speed [rad/s]: if given, ``x'`` is d/dpsi (azimuth time), as in
        :class:`flightid.MLTauStructure`.
    """

    def __init__(self, M, Lbar, tau=None, D=None, *, inputs, outputs, initial, fixed=(), C=None, omega=None,
                 states=None):
        if D is None:
            raise IdentificationError("MLTauFeedthroughStructure needs a D pattern "
                                      "(use MLTauStructure for none)")
        self._d_pattern = D
        super().__init__(M, Lbar, tau, inputs=inputs, outputs=outputs, initial=initial, fixed=fixed, C=C,
                         omega=omega, states=states)
        if self._patterns["D"].shape != (len(self.outputs), len(self.inputs)):
            raise IdentificationError(f"D must be {len(self.outputs)} x {len(self.inputs)}, "
                                      f"got {self._patterns['D'].shape}")

    def _init_parameters(self, patterns, inputs, outputs, initial, fixed, omega):
        # D's parameters join M's, Lbar's and tau's in one bookkeeping
        super()._init_parameters(dict(patterns, D=self._d_pattern), inputs, outputs, initial, fixed, omega)

    def _undelayed(self, mats, s):
        return super()._undelayed(mats, s) + mats["D"][:, :, None]

    def _abcd(self, mats):
        a, b, c, _ = super()._abcd(mats)
        return a, b, c, mats["D"]
