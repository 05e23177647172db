"""Smaller coaxial structures for fast forward flight: candidates below Eq. 6.5.

At 200 kt the fully coupled 12-state (:class:`CoaxialForward12State`, 180
parameters at the start) reduces to a model most of whose parameters the trust
rule rejects. These first-order (M / Lbar / tau, Eq. 2.30) structures ask the
same data a smaller question:

=================================  ========================================================
key                                structure
=================================  ========================================================
``coaxial_forward_isolated``       :class:`CoaxialForwardIsolated`: one Eq. 4.3 3-state per
                                   rotor, no interference (block diagonal), 24 parameters
``coaxial_forward_6state``         :class:`CoaxialForward6State`: the same plus the
                                   cross-rotor couplings of Eq. 5.3's form (each harmonic
                                   of one rotor on the same harmonic of the other), 42
=================================  ========================================================

Per rotor the block is Eq. 4.3 (§4.2): diagonal ``M`` with ``M22 = M33``,
``Lbar`` and ``tau`` with the longitudinal couplings 13 and 31. Indices are
1-based in the canonical signal order (``lam0_U, lam1s_U, lam1c_U, lam0_L,
lam1s_L, lam1c_L``; loads ``CT_U, CL_U, CM_U, CT_L, CL_L, CM_L``); ``M``
multiplies d/dpsi (azimuth time), ``Lbar`` is dimensionless, delays are seconds.
No entry is tied across rotors, so the pattern is the same in the printed and in
our rotor frames (only values differ).
"""
from __future__ import annotations

import numpy as np

from .base import PITT_PETERS_M11, PITT_PETERS_M22, InflowStructure, _low_frequency_inverse

__all__ = ["CoaxialForwardIsolated", "CoaxialForward6State", "ROTOR_BLOCK_ENTRIES", "INTERFERENCE_ENTRIES"]

#: Free (row, column) entries of each rotor's Eq. 4.3 block of ``Lbar`` and ``tau``, 1-based.
ROTOR_BLOCK_ENTRIES = ((1, 1), (1, 3), (2, 2), (3, 1), (3, 3))
#: Cross-rotor entries of ``M``, ``Lbar``, ``tau`` of the interference model (same harmonic), 1-based.
INTERFERENCE_ENTRIES = ((1, 4), (4, 1), (2, 5), (5, 2), (3, 6), (6, 3))


class _CoaxialForwardFirstOrder(InflowStructure):
    """Shared machinery of the first-order forward-flight coaxial candidates."""

    rotors = ("U", "L")
    form = "mltau"
    #: the diagonal apparent masses (the 1c masses are tied to the 1s ones)
    protected = ("m11", "m22", "m44", "m55")
    interference = False

    def __init__(self, frame="rotor", without_lam0_cm=False):
        super().__init__(frame)
        if not isinstance(without_lam0_cm, (bool, np.bool_)):
            raise TypeError(f"without_lam0_cm must be True or False, got {without_lam0_cm!r}")
        self.without_lam0_cm = bool(without_lam0_cm)

    @property
    def pairs(self):
        """The responses fitted, (output, input): None (every coherent response the structure
        produces) unless ``without_lam0_cm``, then those less every ``lam0 / C_M``."""
        if not self.without_lam0_cm:
            return None
        # the responses the pattern produces: lam0 and lam1c on C_T and C_M, lam1s on C_L
        # (Eq. 4.3 couples the longitudinal harmonics only), own rotor unless interference
        lateral = lambda name: name.startswith(("lam1s", "CL"))   # noqa: E731
        return [(o, i) for o in self.outputs for i in self.inputs
                if (self.interference or o[-1] == i[-1]) and lateral(o) == lateral(i)
                and not (o.startswith("lam0") and i.startswith("CM"))]

    @property
    def fit_options(self):
        """The analytic Jacobian (exact for M / Lbar / tau, a refit several times faster than
        differences) and, with ``without_lam0_cm``, the ``pairs`` fitted."""
        out = {"jacobian": "analytic"}
        if self.pairs is not None:
            out["pairs"] = list(self.pairs)
        return out

    def spec(self):
        out = {**super().spec(), "fit_options": {k: v for k, v in self.fit_options.items() if k != "pairs"}}
        if self.without_lam0_cm:
            out["without_lam0_cm"] = True
        return out

    def __repr__(self):
        return f"{type(self).__name__}(frame={self.frame!r}, without_lam0_cm={self.without_lam0_cm})"

    def _patterns(self):
        """(M, Lbar, tau) as 6 x 6 lists of parameter names and zeros."""
        mats = {p: [[0] * 6 for _ in range(6)] for p in "mlt"}
        for off in (0, 3):
            for i, j in ROTOR_BLOCK_ENTRIES:
                for p in "lt":
                    mats[p][i - 1 + off][j - 1 + off] = f"{p}{i + off}{j + off}"
            # M22 = M33 per rotor (Eq. 4.3, as Pitt-Peters in forward flight)
            mats["m"][off][off] = f"m{1 + off}{1 + off}"
            mats["m"][1 + off][1 + off] = mats["m"][2 + off][2 + off] = f"m{2 + off}{2 + off}"
        if self.interference:
            for i, j in INTERFERENCE_ENTRIES:
                for p in "mlt":
                    mats[p][i - 1][j - 1] = f"{p}{i}{j}"
        return mats["m"], mats["l"], mats["t"]

    def parameter_names(self):
        """Names of the structure's parameters (sorted).

        Returns
        -------
        list of str
        """
        return sorted({n for mat in self._patterns() for row in mat for n in row if isinstance(n, str)})

    def build(self, initial, omega, fixed=()):
        """The :class:`flightid.MLTauStructure` at ``initial`` values, ``omega`` [rad/s].

        Parameters
        ----------
        initial : dict
            Value of every parameter (``M`` per d/dpsi, delays [s]); extra keys ignored.
        omega : float
            Rotor speed [rad/s].
        fixed : iterable of str
            Parameters held at their value.

        Returns
        -------
        flightid.MLTauStructure

        Raises
        ------
        KeyError
            A parameter has no initial value.
        """
        from flightid import MLTauStructure
        names = set(self.parameter_names())
        init = {n: float(v) for n, v in dict(initial).items() if n in names}
        missing = names - set(init)
        if missing:
            raise KeyError(f"no initial value for {sorted(missing)}")
        m, lb, tau = self._patterns()
        return MLTauStructure(m, lb, tau, inputs=self.inputs, outputs=self.outputs, initial=init,
                              fixed=[f for f in fixed if f in names], omega=omega)

    def initial_values(self, lam_over_c, n_points=3, coherence_min=None):
        """Data-driven start: each pattern entry of ``Lbar`` from the inverse of the measured
        low-frequency lambda/C (the whole 6 x 6, so interference is in the start), the
        Pitt-Peters hover ``M`` on the diagonal and 0 across rotors, delays 20 ms on the
        diagonal and 50 ms off it.

        Parameters
        ----------
        lam_over_c : flightid.MeasuredResponse
            Joint input-output lambda/C (six inflow outputs, six load inputs).
        n_points : int
            Lowest frequencies averaged.
        coherence_min : float, optional
            Use the lowest points where every element is this coherent.

        Returns
        -------
        dict
        """
        l0 = _low_frequency_inverse(lam_over_c, n_points, coherence_min=coherence_min)
        vals = {}
        for name in self.parameter_names():
            p, i, j = name[0], int(name[1]) - 1, int(name[2]) - 1
            if p == "l":
                vals[name] = float(l0[i, j])
            elif p == "m":
                vals[name] = (PITT_PETERS_M11 if i % 3 == 0 else PITT_PETERS_M22) if i == j else 0.0
            else:
                vals[name] = 0.02 if i == j else 0.05
        if not self.build(vals, 1.0).is_stable():
            # as the single-rotor forward start: a noisy inverse can be unstable; keep the
            # diagonal magnitudes with the Pitt-Peters signs and start the couplings at zero
            for name in vals:
                p, i, j = name[0], int(name[1]) - 1, int(name[2]) - 1
                if p == "l":
                    vals[name] = (1.0 if i % 3 == 0 else -1.0) * abs(vals[name]) if i == j else 0.0
        return vals

    def extra_starts(self, lam_over_c, omega):
        """The equation-error start (``M`` from ``Im(H^-1)`` over 1-10 rad/s), when it is stable.

        The hover 6-state needs it on exact data (its low-frequency start ends in a
        local optimum with the cross masses of the wrong sign); the interference
        masses here are of the same kind.

        Parameters
        ----------
        lam_over_c : flightid.MeasuredResponse
        omega : float
            Rotor speed [rad/s].

        Returns
        -------
        list of (str, dict)
        """
        from ..starts import equation_error_start
        try:
            values = equation_error_start(self, lam_over_c, omega)
        except (ValueError, np.linalg.LinAlgError):
            return []          # no data in the band, or a singular block: no such start
        if not self.build(values, omega).is_stable():
            return []
        return [("equation-error M (1-10 rad/s)", values)]

    def published_values(self, model):
        """Values of a printed first-order coaxial model (``M``, ``Lbar``, ``tau``) on these
        parameters, converted to ``self.frame``.

        Parameters
        ----------
        model : PublishedInflowModel
            A coaxial M / Lbar / tau model.

        Returns
        -------
        dict
        """
        from aircraft.inflow.published import in_rotor_frames
        if getattr(model, "M", None) is None:
            raise ValueError(f"{model.name} has no M / Lbar / tau matrices")
        if self.frame == "rotor" and model.frame == "printed":
            model = in_rotor_frames(model)
        m = model.M * model.omega if model.time == "seconds" else model.M
        mats = {"m": m, "l": model.Lbar, "t": model.tau}
        return {n: float(mats[n[0]][int(n[1]) - 1, int(n[2]) - 1]) for n in self.parameter_names()}


class CoaxialForwardIsolated(_CoaxialForwardFirstOrder):
    """Two isolated forward-flight rotors: one Eq. 4.3 3-state per rotor, no interference.

    ``M lam' + Lbar lam = C(t - tau)`` with block-diagonal ``M``, ``Lbar``, ``tau``;
    each rotor's block is :class:`SingleRotorForward`'s Eq. 4.3 pattern (12
    parameters), 24 in all. The fit sees only the responses the structure can
    produce (each rotor's inflow over its own loads).

    Parameters
    ----------
    frame : {"rotor", "printed"}
        Frame of the parameters (the pattern is the same in both).
    without_lam0_cm : bool
        Leave every ``lam0 / C_M`` response out of the fit (as
        :data:`~aircraft.identification.structures.forward.FORWARD_FIT_PAIRS` does for
        one rotor: the wake's quasi-steady ``lam0 / C_M`` can have a sign no stable
        Eq. 4.3 block reaches, §4.4.1.2). Default False (every coherent response).

    Examples
    --------
    >>> s = CoaxialForwardIsolated()
    >>> len(s.parameter_names()), s.parameter_names()[:3]
    (24, ['l11', 'l13', 'l22'])
    """

    key = "coaxial_forward_isolated"
    interference = False


class CoaxialForward6State(_CoaxialForwardFirstOrder):
    """Coaxial 6-state in forward flight: Eq. 4.3 per rotor plus Eq. 5.3's interference.

    :class:`CoaxialForwardIsolated`'s blocks plus, in ``M``, ``Lbar`` and ``tau``,
    each harmonic of one rotor on the same harmonic of the other (entries 14, 41,
    25, 52, 36, 63; untied, forward flight has no roll/pitch symmetry): 42
    parameters.

    Parameters
    ----------
    frame : {"rotor", "printed"}
        Frame of the parameters (the pattern is the same in both).
    without_lam0_cm : bool
        Leave every ``lam0 / C_M`` response out of the fit (as
        :data:`~aircraft.identification.structures.forward.FORWARD_FIT_PAIRS` does for
        one rotor: the wake's quasi-steady ``lam0 / C_M`` can have a sign no stable
        Eq. 4.3 block reaches, §4.4.1.2). Default False (every coherent response).

    Examples
    --------
    >>> s = CoaxialForward6State()
    >>> len(s.parameter_names()), "l25" in s.parameter_names()
    (42, True)
    """

    key = "coaxial_forward_6state"
    interference = True
