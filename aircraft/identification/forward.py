"""Single-rotor forward flight (§4.4): the Eq. 4.3 structure, identification and comparisons.

::

    SingleRotorForward        Eq. 4.3 (12 parameters: M11, M22 = M33, Lbar11, Lbar13, Lbar22,
                              Lbar31, Lbar33, tau11, tau13, tau22, tau31, tau33), or every
                              entry of M, Lbar and tau free (``pattern="full"``, 27)
    forward_condition         the wind-tunnel FlightCondition of an advance ratio
    identify_forward_flight   identify_inflow at mu (wake trim C_T and zero hub moments)
    pitt_peters_forward       the linearised Pitt-Peters (Peters & HaQuang) M, Lbar at the trim
    forward_comparison_table  ours / linearised Pitt-Peters / the dissertation's Eqs. 4.7-4.8
    forward_bode_overlay      the key responses: data, ours, Pitt-Peters, Eq. 4.7 or 4.8

Units: ``M`` in the structure multiplies d/dpsi (azimuth time); the tables print
``M/Omega`` [s] as Eqs. 4.7-4.8 do (that reading of the printed M is argued in
:mod:`aircraft.inflow.published`); ``Lbar`` is dimensionless; delays are in seconds.
A single rotor has one frame, so ``frame`` has no effect.
"""
from __future__ import annotations

import math

import numpy as np
import pandas as pd

from .structures import _PP_M11, _PP_M22, InflowStructure, _low_frequency_inverse

__all__ = ["SingleRotorForward", "forward_condition", "identify_forward_flight", "pitt_peters_forward",
           "forward_comparison_table", "forward_bode_overlay", "FORWARD_PATTERNS", "KEY_RESPONSES"]

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
                vals[name] = (_PP_M11 if i == 0 else _PP_M22) if i == j else 0.0
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
        mats = {"m": m, "l": model.L, "t": model.tau}
        return {n: float(mats[n[0]][int(n[1]) - 1, int(n[2]) - 1]) for n in self.parameter_names()}


def forward_condition(config, mu, alpha=0.0):
    """Wind-tunnel flight condition of advance ratio ``mu`` at shaft angle ``alpha``.

    Parameters
    ----------
    config : aircraft.AircraftConfig
        Rotor (its first rotor's Omega R sets the speed).
    mu : float
        Advance ratio (in-plane free stream / Omega R), > 0.
    alpha : float
        Shaft angle of attack [rad], positive tilting the disk back.

    Returns
    -------
    aircraft.wake.FlightCondition
        Speed ``mu Omega R / cos(alpha)`` [m/s].

    Raises
    ------
    ValueError
        ``mu`` not a positive finite number, or ``alpha`` not finite.
    """
    from aircraft.wake import FlightCondition
    if isinstance(mu, bool) or not isinstance(mu, (int, float, np.floating, np.integer)) \
            or not math.isfinite(mu) or not mu > 0:
        raise ValueError(f"advance ratio mu must be a positive finite number, got {mu!r}")
    if not math.isfinite(alpha):
        raise ValueError(f"alpha must be finite [rad], got {alpha!r}")
    rc = config.rotors[0]
    return FlightCondition(speed=float(mu) * rc.omega * rc.radius / math.cos(alpha), alpha=float(alpha))


def identify_forward_flight(config, mu, *, alpha=0.0, ct=0.0061, pattern="eq4_3", settings=None,
                            name=None, n_jobs=2, cache_dir="default", progress=True):
    """Identify the forward-flight model of one rotor at advance ratio ``mu`` from the free wake.

    The wake is trimmed in the wind tunnel to ``ct`` and zero hub moments (shaft
    fixed at ``alpha``, flapping held), then :func:`identify_inflow` runs with
    :class:`SingleRotorForward`: one sweep per swashplate control, joint
    input-output lambda/C, fit, automatic reduction (M diagonal protected), doublet
    verification beside the noise floor.

    Parameters
    ----------
    config : aircraft.AircraftConfig
        A single-rotor configuration.
    mu : float
        Advance ratio, > 0.
    alpha : float
        Shaft angle of attack [rad] (positive tilts the disk back).
    ct : float
        Trim thrust coefficient.
    pattern : {"eq4_3", "full"}
        Structure pattern (:class:`SingleRotorForward`).
    settings : IdentificationSettings, optional
    name : str, optional
    n_jobs : int
        Wake worker processes.
    cache_dir : str or None
        Wake run cache (see :func:`aircraft.wake.run_sweeps`).
    progress : bool

    Returns
    -------
    IdentifiedModel

    Raises
    ------
    ValueError
        Bad ``mu``, ``alpha`` or ``pattern``, or a configuration with more than one rotor.
    PipelineError
        The wake trim fails.
    """
    from .pipeline import identify_inflow
    if len(config.rotors) != 1:
        raise ValueError(f"identify_forward_flight is for a single rotor, got {len(config.rotors)} rotors")
    condition = forward_condition(config, mu, alpha)
    structure = SingleRotorForward(pattern=pattern)
    return identify_inflow(config, condition, structure, trim={"ct": float(ct)}, settings=settings,
                           name=name or f"single rotor mu = {mu:g} ({structure.key}, {pattern})", n_jobs=n_jobs,
                           cache_dir=cache_dir, progress=progress)


def pitt_peters_forward(ct, mu, alpha=0.0, omega=27.0):
    """Linearised Pitt-Peters (Peters & HaQuang mass flow) at thrust ``ct`` and advance ratio ``mu``.

    The nonlinear :class:`aircraft.inflow.PittPeters` is linearised numerically about
    its steady state (so the mass-flow perturbation is included, as in the
    aircraft), and ``M``, ``Lbar`` are recovered with
    :func:`aircraft.inflow.mlbar_from_statespace`.

    Parameters
    ----------
    ct : float
        Thrust coefficient.
    mu : float
        Advance ratio, >= 0.
    alpha : float
        Shaft angle of attack [rad] (positive tilts the disk back: the free stream
        flows up through it, ``mu_z = -mu tan(alpha)``).
    omega : float
        Rotor speed [rad/s] (``M`` is returned per d/dpsi, so it only sets the time scale).

    Returns
    -------
    M, Lbar : ndarray (3, 3)
        Azimuth-time ``M`` [-] and ``Lbar`` [-] of ``M lam' + Lbar lam = dC``.
    """
    from aircraft.inflow import PittPeters, RotorOperatingPoint, mlbar_from_statespace
    op = RotorOperatingPoint(omega=float(omega), mu=float(mu), mu_z=-float(mu) * math.tan(alpha))
    sys = PittPeters().linear(np.array([float(ct), 0.0, 0.0]), (op,))
    return mlbar_from_statespace(sys, float(omega))


def _published_for(mu):
    from aircraft.inflow.published import UH60_MU01_MFW, UH60_MU02_MFW
    return {0.1: UH60_MU01_MFW, 0.2: UH60_MU02_MFW}.get(round(float(mu), 6))


_ROWS = (("M11/Omega [s]", "M", (0, 0)), ("M22/Omega [s]", "M", (1, 1)), ("M33/Omega [s]", "M", (2, 2)),
         ("Lbar11", "L", (0, 0)), ("Lbar13", "L", (0, 2)), ("Lbar22", "L", (1, 1)), ("Lbar31", "L", (2, 0)),
         ("Lbar33", "L", (2, 2)), ("tau11 [s]", "tau", (0, 0)), ("tau13 [s]", "tau", (0, 2)),
         ("tau22 [s]", "tau", (1, 1)), ("tau31 [s]", "tau", (2, 0)), ("tau33 [s]", "tau", (2, 2)))


def forward_comparison_table(models, *, alpha=0.0):
    """Identified coefficients beside linearised Pitt-Peters and the dissertation's Eqs. 4.7-4.8.

    Parameters
    ----------
    models : dict
        ``{mu: IdentifiedModel}`` (from :func:`identify_forward_flight`).
    alpha : float
        Shaft angle [rad] of the Pitt-Peters linearisation (that of the wake runs).

    Returns
    -------
    pandas.DataFrame
        One row per (mu, coefficient): ``ours``, ``cramer_rao_pct``,
        ``insensitivity_pct``, ``status`` (free / removed by the reduction / tied),
        ``pitt_peters`` (at the wake's trimmed C_T) and ``dissertation`` (printed
        Eq. 4.7 for mu = 0.1, Eq. 4.8 for mu = 0.2, else NaN; reference data, never an
        output). ``M`` rows are ``M/Omega`` [s], delays [s].

    Raises
    ------
    ValueError
        Empty ``models``.
    """
    if not models:
        raise ValueError("forward_comparison_table needs at least one {mu: IdentifiedModel}")
    rows = []
    for mu, model in sorted(models.items()):
        omega = model.omega
        mats = model.fit.structure.matrices()
        p = model.parameters.set_index("parameter")
        pp_m, pp_l = pitt_peters_forward(model.trim.outputs["CT"], mu, alpha, omega)
        pub = _published_for(mu)
        for label, mat, (i, j) in _ROWS:
            scale = 1.0 / omega if mat == "M" else 1.0
            pname = f"{ {'M': 'm', 'L': 'l', 'tau': 't'}[mat]}{i + 1}{j + 1}".replace(" ", "")
            if pname in p.index:
                cr, ins, status = (p.loc[pname, "cramer_rao_pct"], p.loc[pname, "insensitivity_pct"],
                                   p.loc[pname, "status"])
            else:
                cr, ins, status = np.nan, np.nan, "tied" if np.ravel(mats[mat])[3 * i + j] != 0 else "not in model"
            pp = {"M": pp_m[i, j] / omega, "L": pp_l[i, j], "tau": 0.0}[mat]
            ref = np.nan
            if pub is not None:
                ref = {"M": pub.M_seconds, "L": pub.L, "tau": pub.tau}[mat][i, j]
            rows.append({"mu": mu, "coefficient": label, "ours": float(mats[mat][i, j]) * scale,
                         "cramer_rao_pct": cr, "insensitivity_pct": ins, "status": status,
                         "pitt_peters": float(pp), "dissertation": float(ref)})
    return pd.DataFrame(rows)


def forward_bode_overlay(model, mu, *, alpha=0.0, pairs=KEY_RESPONSES, fig=None):
    """Bode overlay of the key forward-flight responses: wake data, ours, Pitt-Peters, Eq. 4.7/4.8.

    Parameters
    ----------
    model : IdentifiedModel
        From :func:`identify_forward_flight`.
    mu : float
        Advance ratio (selects the printed Eq. 4.7 or 4.8 and the Pitt-Peters point).
    alpha : float
        Shaft angle [rad] of the Pitt-Peters linearisation.
    pairs : sequence of (output, input)
        Responses shown (default :data:`KEY_RESPONSES`).
    fig : matplotlib.figure.Figure, optional

    Returns
    -------
    matplotlib.figure.Figure
        Magnitude [dB], phase [deg] and coherence per response.
    """
    from flightid import MLTauStructure
    from flightid.plotting import bode_with_coherence
    omega = model.omega
    w = model.responses.omega
    lo, hi = model.settings.fit_range
    w = w[(w >= lo) & (w <= hi)]
    sources = [(model.responses, "free wake (joint input-output)"),
               (model.fit.structure.to_frd(w, name="ours"), "ours")]
    names = model.structure.inputs, model.structure.outputs
    pp_m, pp_l = pitt_peters_forward(model.trim.outputs["CT"], mu, alpha, omega)
    pp = MLTauStructure(pp_m, pp_l, inputs=names[0], outputs=names[1], initial={}, omega=omega)
    sources.append((pp.to_frd(w), "linearised Pitt-Peters"))
    pub = _published_for(mu)
    if pub is not None:
        ref = MLTauStructure(pub.M * pub.omega if pub.time == "seconds" else pub.M, pub.L, pub.tau,
                             inputs=names[0], outputs=names[1], initial={}, omega=pub.omega)
        sources.append((ref.to_frd(w), f"dissertation Eq. {'4.7' if round(mu, 6) == 0.1 else '4.8'} (printed)"))
    return bode_with_coherence(sources, list(pairs), fig=fig)
