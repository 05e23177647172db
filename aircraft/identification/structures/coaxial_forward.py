"""The forward-flight coaxial inflow structure (Eqs. 6.4-6.7, §6.2.2) in our rotor frames.

At 200 kt (mu ~ 0.54, rotor AoA 2 deg) the dissertation gives up the hover
symmetries: every inflow harmonic of both rotors responds to every load of both
rotors, and the flap-rate (wake distortion) inputs are dropped. Eq. 6.5 keeps
the near/far-wake form of the hover model,

::

    x' = F x + G C,     lambda = lambda_N + lambda_F   (x: lam0N, lam0F, lam1sN,
                                                           lam1sF, lam1cN, lam1cF per rotor)

with the pattern of Eqs. 6.6-6.7 as the *start* of the identification: a
near-wake state (odd row, 1-based) depends on the near-wake states only (odd
columns), a far-wake state (even row) on every state, and ``G`` is full (12 x 6,
columns ``C_T, C_L, C_M`` of the upper then the lower rotor, Eq. 6.4). That is
108 + 72 = 180 parameters (§6.4.4: "Eq. (6.7) shows 180 parameters"); the
automatic reduction of :func:`aircraft.identification.identify_inflow` (Fig. 6.1)
then removes the insensitive and poorly determined ones. The printed result is
Eqs. 6.12-6.13 (:data:`aircraft.inflow.published.COAXIAL_200KT_12STATE`).

Frames
------
No entry of the pattern is tied to another, so the pattern is the same in the
dissertation's common frame and in our per-rotor frames; only the *values*
differ. Between the two every signal is multiplied by ``s = +-1``
(:mod:`aircraft.inflow.frames`: ``-1`` for the lower rotor's lateral
signals ``lam1sN_L, lam1sF_L, CL_L``), ``F_o = T_x F_d T_x``,
``G_o = T_x G_d T_u``, ``C_o = C_d`` (the summing matrix is invariant):
:meth:`CoaxialForward12State.published_values` converts the printed
Eqs. 6.12-6.13 that way, and ``tests/aircraft/identification/test_coaxial_forward.py`` checks that the
converted model's lambda/C responses are the printed ones with the lower rotor's
lateral rows and columns negated. Parameters are ``f<row>_<col>`` and
``g<row>_<col>``, 1-based, in Eq. 6.4's state order and the canonical load order
(which is Eq. 6.4's input order). ``F`` and ``G`` multiply d/dpsi in the
structure (azimuth time; :class:`flightid.FGCStructure` with ``omega``); the
printed matrices are per second (divide by Omega).
"""
from __future__ import annotations

import numpy as np

from aircraft.inflow.published import fgc_state_names

from .base import (InflowStructure, _low_frequency_inverse, low_frequency_gain)

__all__ = ["CoaxialForward12State", "F_PATTERN", "G_PATTERN"]


def _f_pattern():
    """(row, col) 1-based free entries of Eq. 6.6: near rows <- near columns, far rows <- all."""
    out = []
    for i in range(1, 13):
        cols = range(1, 13) if i % 2 == 0 else range(1, 13, 2)
        out += [(i, j) for j in cols]
    return out


#: Free entries of ``F`` (Eq. 6.6), 1-based (row, column): 108.
F_PATTERN = tuple(_f_pattern())
#: Free entries of ``G`` (Eq. 6.7, six load columns): every entry, 72.
G_PATTERN = tuple((i, j) for i in range(1, 13) for j in range(1, 7))

#: Far-wake pole of the start [1/rev]: slower than the near wake, as in the hover start.
_FAR_POLE = -0.25
#: Fraction of each load's low-frequency inflow the start routes through the far
#: wake (small: the start's DC gain stays within 2 % of the data's, but every far-wake
#: parameter has an influence, so the fit has no flat direction at its start).
_FAR_SHARE = 0.005


class CoaxialForward12State(InflowStructure):
    """12-state coaxial model in forward flight, fully coupled (Eqs. 6.4-6.7, 6.12-6.13).

    States ``lam0N, lam0F, lam1sN, lam1sF, lam1cN, lam1cF`` per rotor (Eq. 6.4),
    ``lambda = lambda_N + lambda_F``; inputs the six loads ``C_T, C_L, C_M`` per
    rotor; no flap-rate inputs and no delays (§6.2.2). Free at the start: the
    pattern of Eqs. 6.6-6.7 (180 parameters, no ties: forward flight has no
    axis symmetry), see the module docstring for the frames.

    Parameters
    ----------
    frame : {"rotor", "printed"}
        ``"rotor"``: our per-rotor frames (default); ``"printed"``: the
        dissertation's common frame (for comparisons only).
    near_wake_only : bool
        Keep the near-wake half only (no far-wake parameter: far-wake rows of ``F``
        and ``G`` zero, their diagonal fixed at -0.25/rev, so the far wake never
        responds): a first-order model with full 6 x 6 couplings, 36 + 36 parameters. Step 3 of §6.4.3 ("a
        state-space inflow model that is similar to that found in Chap. 5");
        for small data sets and tests. Default False (Eq. 6.5 in full).
    rotors : (str, str), optional
        Upper and lower rotor names of the signals (default ``("U", "L")``).
    """

    key = "coaxial_forward_12state"
    rotors = ("U", "L")
    form = "fgc"
    uses_flap_rates = False
    #: every diagonal of ``F``: without one a state has no dynamics of its own
    protected = tuple(f"f{k}_{k}" for k in range(1, 13))
    #: A bound on each fit's cost evaluations (the pipeline's fit and every refit of
    #: the reduction): from the 180-parameter optimum (J_ave 1.6, 80 flat directions)
    #: the reduction's first refit crawled for over 34 min with scipy's default
    #: budget of 200 x (n + 1). The analytic Jacobian (one model evaluation per
    #: Jacobian instead of one per parameter) makes a refit of the 180 parameters
    #: about 10x faster (CPU time) than finite differences (``benchmarks/coaxial_forward_refit.py``),
    #: so that the reduction runs to completion.
    fit_options = {"max_nfev": 150, "jacobian": "analytic"}

    def __init__(self, frame="rotor", near_wake_only=False, *, rotors=None):
        super().__init__(frame, rotors=rotors)
        if not isinstance(near_wake_only, (bool, np.bool_)):
            raise TypeError(f"near_wake_only must be True or False, got {near_wake_only!r}")
        self.near_wake_only = bool(near_wake_only)
        if self.near_wake_only:
            self.protected = tuple(f"f{k}_{k}" for k in range(1, 13, 2))

    def spec(self):
        return {**super().spec(), "near_wake_only": self.near_wake_only, "fit_options": dict(self.fit_options)}

    def __repr__(self):
        return (f"CoaxialForward12State(frame={self.frame!r}, near_wake_only={self.near_wake_only}"
                f"{self._rotors_repr()})")

    @property
    def states(self):
        """State names of Eq. 6.4 (``lam0N_U, lam0F_U, ...``)."""
        return fgc_state_names(self.rotors)

    @property
    def controls(self):
        """The six swashplate controls swept (collective, lateral, longitudinal per rotor)."""
        return super().controls

    def _entries(self):
        """(F entries, G entries) that are parameters."""
        if not self.near_wake_only:
            return F_PATTERN, G_PATTERN
        f = tuple((i, j) for i, j in F_PATTERN if i % 2 == 1)
        g = tuple((i, j) for i, j in G_PATTERN if i % 2 == 1)
        return f, g

    def parameter_names(self):
        """Names of the structure's parameters (``f<i>_<j>``, ``g<i>_<j>``, 1-based)."""
        f, g = self._entries()
        return [f"f{i}_{j}" for i, j in f] + [f"g{i}_{j}" for i, j in g]

    def build(self, initial, omega, fixed=()):
        """The :class:`flightid.FGCStructure` (F, G per d/dpsi; ``omega`` [rad/s]).

        Parameters
        ----------
        initial : dict
            Value of every parameter of :meth:`parameter_names` (extra keys are
            ignored).
        omega : float
            Rotor speed [rad/s] (the structure's time unit is the azimuth).
        fixed : iterable of str
            Parameters held at their initial value.

        Returns
        -------
        flightid.FGCStructure
        """
        from flightid import FGCStructure
        f_free, g_free = self._entries()
        F = [[0] * 12 for _ in range(12)]
        if self.near_wake_only:          # far wake present but never excited
            for k in range(2, 13, 2):
                F[k - 1][k - 1] = _FAR_POLE
        for i, j in f_free:
            F[i - 1][j - 1] = f"f{i}_{j}"
        G = [[0] * 6 for _ in range(12)]
        for i, j in g_free:
            G[i - 1][j - 1] = f"g{i}_{j}"
        names = set(self.parameter_names())
        init = {n: float(v) for n, v in dict(initial).items() if n in names}
        missing = names - set(init)
        if missing:
            raise KeyError(f"no initial value for {sorted(missing)[:6]} ({len(missing)} parameters)")
        return FGCStructure(F, G, self._summing_matrix(), inputs=self.inputs, outputs=self.outputs,
                            initial=init, fixed=[f for f in fixed if f in names], omega=omega,
                            states=self.states)

    @staticmethod
    def _summing_matrix():
        c = np.zeros((6, 12))
        for k in range(6):
            c[k, 2 * k] = c[k, 2 * k + 1] = 1.0
        return c

    def initial_values(self, lam_over_c, n_points=3, coherence_min=None):
        """A quasi-steady start from the measured lambda/C (azimuth time).

        The real part of the measured lambda/C averaged over its ``n_points``
        lowest frequencies, ``G0`` (6 x 6, every coupling), is put in the near wake:
        near-wake state k gets the pole ``-a_k`` with ``a_k = |Lbar_kk / M_kk|``
        (``Lbar = G0^-1``, Pitt-Peters hover ``M``) and the gains ``a_k G0[k, :]``,
        so the start's steady response is ``G0``. Far-wake states get a pole at
        -0.25/rev and 0.5 % of the near wake's gains (every parameter then has an
        influence); all cross-state couplings of ``F`` start at 0.

        Parameters
        ----------
        lam_over_c : flightid.MeasuredResponse
            Joint input-output lambda/C, inputs the six loads, outputs the six inflows.
        n_points : int
            Lowest frequencies averaged.

        Returns
        -------
        dict
            Parameter name -> value.
        """
        from .base import PITT_PETERS_M11, PITT_PETERS_M22
        g0 = low_frequency_gain(lam_over_c, n_points, coherence_min, outputs=list(self.outputs),
                                inputs=list(self.loads))
        l0 = _low_frequency_inverse(lam_over_c, n_points, outputs=list(self.outputs), inputs=list(self.loads),
                                    coherence_min=coherence_min)
        m = np.array([PITT_PETERS_M11, PITT_PETERS_M22, PITT_PETERS_M22] * 2)
        a = np.abs(np.diag(l0) / m)
        vals = {n: 0.0 for n in self.parameter_names()}
        for k in range(6):
            near, far = 2 * k + 1, 2 * k + 2
            vals[f"f{near}_{near}"] = -float(a[k])
            if not self.near_wake_only:
                vals[f"f{far}_{far}"] = _FAR_POLE
            for j in range(6):
                vals[f"g{near}_{j + 1}"] = float(a[k] * g0[k, j])
                if not self.near_wake_only:
                    vals[f"g{far}_{j + 1}"] = float(_FAR_SHARE * -_FAR_POLE * g0[k, j])
        return vals

    def published_values(self, model):
        """Eqs. 6.12-6.13 (per d/dpsi, converted to ``self.frame``) on the parameters.

        Parameters
        ----------
        model : aircraft.inflow.published.PublishedFGCModel
            A forward-flight model with six load inputs (F, G per second).

        Returns
        -------
        dict
            Every parameter's value; printed entries outside the pattern raise.

        Raises
        ------
        ValueError
            If the model has flap-rate inputs or an entry outside the pattern.
        """
        from aircraft.inflow.published import in_rotor_frames
        if tuple(model.input_order) != tuple(self.loads):
            raise ValueError(f"{model.name}: inputs {model.input_order} are not the six loads {self.loads}")
        if self.frame == "rotor" and model.frame == "printed":
            model = in_rotor_frames(model)
        elif self.frame == "printed" and model.frame == "rotor":
            raise ValueError(f"{model.name} is in our rotor frames; the structure asks for the printed frame")
        F, G = model.F / model.omega, model.G / model.omega
        f_free, g_free = self._entries()
        outside = [(i + 1, j + 1) for i, j in zip(*np.nonzero(F)) if (i + 1, j + 1) not in set(f_free)]
        if outside:
            raise ValueError(f"{model.name}: F entries {outside[:5]} lie outside the structure's pattern")
        vals = {f"f{i}_{j}": float(F[i - 1, j - 1]) for i, j in f_free}
        vals.update({f"g{i}_{j}": float(G[i - 1, j - 1]) for i, j in g_free})
        return vals
