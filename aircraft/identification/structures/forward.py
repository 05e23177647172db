"""Single-rotor forward flight structure (§4.4, Eq. 4.3).

``M`` in the structure multiplies d/dpsi (azimuth time); ``Lbar`` is dimensionless;
delays are in seconds. A single rotor has one frame, so ``frame`` has no effect.
"""
from __future__ import annotations


from .base import PITT_PETERS_M11, PITT_PETERS_M22, InflowStructure, _low_frequency_inverse

__all__ = ["SingleRotorForward", "FORWARD_PATTERNS", "KEY_RESPONSES"]

#: Patterns of :class:`SingleRotorForward`.
FORWARD_PATTERNS = ("eq4_3", "full")

#: The responses §4.4 shows (Figs. 4.12-4.21): (output, input).
KEY_RESPONSES = (("lam0", "CT"), ("lam1s", "CL"), ("lam1c", "CM"), ("lam1c", "CT"), ("lam0", "CM"))

#: Entries (1-based) of Eq. 4.3's Lbar and tau (M is diagonal with M22 = M33).
_EQ43_ENTRIES = ((1, 1), (1, 3), (2, 2), (3, 1), (3, 3))


class SingleRotorForward(InflowStructure):
    """3-state single rotor in forward flight (Eq. 4.3, §4.2; printed values Eqs. 4.7-4.8).

    ``M lam' + Lbar lam = dC(t - tau)`` with, for ``pattern="eq4_3"`` (default),
    diagonal ``M`` with ``M22 = M33`` (Pitt-Peters keeps them equal in forward
    flight), ``Lbar`` and ``tau`` with the longitudinal couplings 13 and 31: the
    12 parameters of §4.2. ``pattern="full"`` frees all 27 entries of ``M``,
    ``Lbar`` and ``tau`` (the automatic reduction then removes what the data do
    not support).

    Parameters
    ----------
    frame : {"rotor", "printed"}
        Frame of the parameters (no effect for a single rotor).
    pattern : {"eq4_3", "full"}
        Free entries (see above).

    Raises
    ------
    ValueError
        Unknown ``pattern`` or ``frame``.
    """

    key = "single_rotor_forward"
    rotors = ("",)

    def __init__(self, frame="rotor", pattern="eq4_3"):
        super().__init__(frame)
        if pattern not in FORWARD_PATTERNS:
            raise ValueError(f"pattern must be one of {FORWARD_PATTERNS}, got {pattern!r}")
        self.pattern = pattern

    @property
    def protected(self):
        """The diagonal apparent masses (never removed by the reduction)."""
        return ("m11", "m22") if self.pattern == "eq4_3" else ("m11", "m22", "m33")

    def spec(self):
        return {**super().spec(), "pattern": self.pattern}

    def __repr__(self):
        return f"SingleRotorForward(frame={self.frame!r}, pattern={self.pattern!r})"

    def _patterns(self):
        if self.pattern == "full":
            full = lambda p: [[f"{p}{i}{j}" for j in (1, 2, 3)] for i in (1, 2, 3)]   # noqa: E731
            return full("m"), full("l"), full("t")
        m = [["m11", 0, 0], [0, "m22", 0], [0, 0, "m22"]]
        sparse = lambda p: [[f"{p}11", 0, f"{p}13"], [0, f"{p}22", 0], [f"{p}31", 0, f"{p}33"]]   # noqa: E731
        return m, sparse("l"), sparse("t")

    def parameter_names(self):
        """Names of the free parameters (sorted).

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
            Value of every parameter (``M`` per d/dpsi, delays [s]).
        omega : float
            Rotor speed [rad/s].
        fixed : iterable of str
            Parameters held at their value.

        Returns
        -------
        flightid.MLTauStructure
        """
        from flightid import MLTauStructure
        m, lb, tau = self._patterns()
        names = set(self.parameter_names())
        missing = names - set(dict(initial))
        if missing:
            raise KeyError(f"no initial value for {sorted(missing)}")
        init = {n: float(v) for n, v in dict(initial).items() if n in names}
        return MLTauStructure(m, lb, tau, inputs=self.inputs, outputs=self.outputs, initial=init,
                              fixed=[f for f in fixed if f in names], omega=omega)

    def initial_values(self, lam_over_c, n_points=3, coherence_min=None):
        """Data-driven start: ``Lbar`` from the inverted low-frequency lambda/C (its
        Eq. 4.3 entries, or all of it), Pitt-Peters ``M`` (off-diagonal 0), delays
        20 ms on the diagonal and 50 ms off it.

        Parameters
        ----------
        lam_over_c : flightid.MeasuredResponse
            Joint input-output lambda/C (outputs lam0, lam1s, lam1c; inputs CT, CL, CM).
        n_points : int
            Lowest frequencies averaged.

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
                vals[name] = (PITT_PETERS_M11 if i == 0 else PITT_PETERS_M22) if i == j else 0.0
            else:
                vals[name] = 0.02 if i == j else 0.05
        if not self.build(vals, 1.0).is_stable():
            # a noisy low-frequency inverse can give an unstable start (seen on a 20 deg,
            # 4-element wake at mu = 0.1: Lbar33 > 0, |Lbar31| > |Lbar11|), from which the fit
            # ends singular: keep the data's diagonal magnitudes with the Pitt-Peters signs
            # (Lbar11 > 0, Lbar22, Lbar33 < 0) and start the couplings at zero
            for name in vals:
                p, i, j = name[0], int(name[1]) - 1, int(name[2]) - 1
                if p == "l":
                    vals[name] = (1.0 if i == 0 else -1.0) * abs(vals[name]) if i == j else 0.0
        return vals

    def published_values(self, model):
        """Values of a printed :class:`aircraft.inflow.published.PublishedInflowModel`
        (e.g. Eq. 4.7) on this structure's parameters (``M`` per d/dpsi).

        Parameters
        ----------
        model : PublishedInflowModel
            A single-rotor model.

        Returns
        -------
        dict
        """
        if tuple(model.rotors) != ("",):
            raise ValueError(f"{model.name} is not a single-rotor model (rotors {model.rotors})")
        m = model.M * model.omega if model.time == "seconds" else model.M
        mats = {"m": m, "l": model.Lbar, "t": model.tau}
        return {n: float(mats[n[0]][int(n[1]) - 1, int(n[2]) - 1]) for n in self.parameter_names()}
