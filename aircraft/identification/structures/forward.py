"""Single-rotor forward flight structure (§4.4, Eq. 4.3).

``M`` in the structure multiplies d/dpsi (azimuth time); ``Lbar`` is dimensionless;
delays are in seconds. A single rotor has one frame, so ``frame`` has no effect.
"""
from __future__ import annotations


import numpy as np

from .base import PITT_PETERS_M11, PITT_PETERS_M22, InflowStructure, _low_frequency_inverse

__all__ = ["SingleRotorForward", "FORWARD_PATTERNS", "KEY_RESPONSES", "FORWARD_FIT_PAIRS", "pitt_peters_start"]

#: Patterns of :class:`SingleRotorForward`.
FORWARD_PATTERNS = ("eq4_3", "full")

#: The responses §4.4 shows (Figs. 4.12-4.21): (output, input).
KEY_RESPONSES = (("lam0", "CT"), ("lam1s", "CL"), ("lam1c", "CM"), ("lam1c", "CT"), ("lam0", "CM"))

#: The key responses without ``lam0/CM``: the wake's quasi-steady ``lam0/CM`` can have the
#: sign that, with the other three longitudinal gains, no stable Eq. 4.3 model reaches
#: (``det`` of the 2 x 2 gain block must be < 0 when ``M11 > 0 > M33``); §4.4.1.2 notes the
#: response "can likely be removed from the optimization".
FORWARD_FIT_PAIRS = KEY_RESPONSES[:4]

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
    start : dict, optional
        A further start beside the data-driven ones (e.g. the linearised
        Pitt-Peters at the flight condition, :func:`pitt_peters_start`): the
        pipeline fits every start and keeps the lowest cost. Its nonzero couplings
        put the coupling responses in the cost from the first iteration (a start
        with ``Lbar13 = Lbar31 = 0`` makes them structurally zero, and a default
        fit then leaves them out).
    pairs : sequence of (output, input), optional
        The responses fitted (default: every coherent response the structure can
        produce). :data:`FORWARD_FIT_PAIRS` leaves out ``lam0/CM``.

    Raises
    ------
    ValueError
        Unknown ``pattern`` or ``frame``, a ``start`` without every parameter, a
        pair outside the structure's outputs and inputs.
    """

    key = "single_rotor_forward"
    rotors = ("",)

    def __init__(self, frame="rotor", pattern="eq4_3", start=None, pairs=None):
        super().__init__(frame)
        if pattern not in FORWARD_PATTERNS:
            raise ValueError(f"pattern must be one of {FORWARD_PATTERNS}, got {pattern!r}")
        self.pattern = pattern
        self.start = None
        if start is not None:
            missing = set(self.parameter_names()) - set(dict(start))
            if missing:
                raise ValueError(f"start lacks parameters {sorted(missing)}")
            self.start = {n: float(dict(start)[n]) for n in self.parameter_names()}
        self.pairs = None
        if pairs is not None:
            pairs = [tuple(p) for p in pairs]
            bad = [p for p in pairs if len(p) != 2 or p[0] not in self.outputs or p[1] not in self.inputs]
            if bad or not pairs:
                raise ValueError(f"pairs must be (output, input) of {self.outputs} x {self.inputs}, got {pairs!r}")
            self.pairs = pairs

    @property
    def fit_options(self):
        """``pairs`` for the fit and the reduction when given (else none)."""
        return {} if self.pairs is None else {"pairs": list(self.pairs)}

    def extra_starts(self, lam_over_c, omega):
        """The given ``start`` (e.g. linearised Pitt-Peters), when there is one.

        Parameters
        ----------
        lam_over_c : flightid.MeasuredResponse
        omega : float
            Rotor speed [rad/s].

        Returns
        -------
        list of (str, dict)
        """
        return [] if self.start is None else [("given start", dict(self.start))]

    @property
    def protected(self):
        """The diagonal apparent masses (never removed by the reduction)."""
        return ("m11", "m22") if self.pattern == "eq4_3" else ("m11", "m22", "m33")

    def spec(self):
        out = {**super().spec(), "pattern": self.pattern}
        # added only when set: the hash of a default structure is what it was before they existed
        if self.start is not None:
            out["start"] = {k: round(v, 12) for k, v in sorted(self.start.items())}
        if self.pairs is not None:
            out["pairs"] = [list(p) for p in self.pairs]
        return out

    def __repr__(self):
        extra = "" if self.pairs is None else f", pairs={self.pairs!r}"
        extra += "" if self.start is None else ", start={...}"
        return f"SingleRotorForward(frame={self.frame!r}, pattern={self.pattern!r}{extra})"

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


def pitt_peters_start(M, Lbar, pattern="eq4_3"):
    """Start values of :class:`SingleRotorForward` from an ``M`` (per d/dpsi) and ``Lbar``.

    Delays start at 20 ms on the diagonal and 50 ms off it (as the data-driven start).

    Parameters
    ----------
    M, Lbar : (3, 3) array_like
        Apparent mass (azimuth time) and Lbar, e.g. :func:`pitt_peters_forward`.
    pattern : {"eq4_3", "full"}

    Returns
    -------
    dict

    Examples
    --------
    >>> import numpy as np
    >>> v = pitt_peters_start(np.diag([0.85, -0.11, -0.11]), np.array([[0.12, 0, 0.23], [0, -0.05, 0], [0.21, 0, -0.17]]))
    >>> v["l13"], v["m22"], v["t13"]
    (0.23, -0.11, 0.05)
    """
    M = np.asarray(M, float)
    Lbar = np.asarray(Lbar, float)
    if M.shape != (3, 3) or Lbar.shape != (3, 3):
        raise ValueError(f"M and Lbar must be 3 x 3, got {M.shape} and {Lbar.shape}")
    mats = {"m": M, "l": Lbar}
    out = {}
    for name in SingleRotorForward(pattern=pattern).parameter_names():
        p, i, j = name[0], int(name[1]) - 1, int(name[2]) - 1
        out[name] = float(mats[p][i, j]) if p in mats else (0.02 if i == j else 0.05)
    return out
