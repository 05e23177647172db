"""Quasi-steady candidate structures of the coaxial at 200 kt, and the inflow time constants.

At 200 kt (mu = 0.54) the first-order candidates' apparent masses go to zero: the
inflow lag ``T = M / (Omega Lbar)`` is a few hundredths of a second, its corner ``1/T``
at or above the top of the fit band, and below the corner a first-order lag
``1 / (1 + s T)`` differs from the delay ``exp(-s T)`` only at second order in
``omega T``, so the cost can hardly tell an apparent mass from a delay. These
structures ask the data the question they can answer::

    CoaxialForwardQuasiSteady()                    lambda_i = sum_j K_ij C_j(t - tau_ij), per rotor
                                                   (Eq. 4.3's pattern, no states), 20 parameters
    CoaxialForwardQuasiSteady(interference=True)   + the same-harmonic upper <-> lower gains, 32
        (without_lam0_cm=True, shared_delays=True)  less lam0 / C_M; one delay for both rotors
    CoaxialForwardPittPetersMasses()               the isolated first-order rotors with the
                                                   apparent masses held at Pitt-Peters' values
    quasi_steady_candidates()                      the seven variants the study identifies
    inflow_time_constants(lam0, mu, omega, band)   Pitt-Peters' lags against the fitted band
    trim_time_constants(trim_outputs, config, band) the same for each rotor of the 200 kt wake trim

The gain pattern is the inverse pattern of Eq. 4.3's ``Lbar`` (the ``lam0``/``lam1c``
pair coupled, ``lam1s`` alone): with ``M = 0``, ``lambda = Lbar^-1 C`` has these
entries. Gains are dimensionless, delays in seconds; the structures are studies'
objects built from the library's :class:`~aircraft.identification.structures.base.InflowStructure`
and :class:`flightid.GainDelayStructure`.
"""
from __future__ import annotations

import math

import numpy as np
import pandas as pd

from aircraft.identification.structures.base import (PITT_PETERS_M11, PITT_PETERS_M22, InflowStructure,
                                                     low_frequency_gain)
from aircraft.identification.structures.coaxial_forward_small import (INTERFERENCE_ENTRIES, ROTOR_BLOCK_ENTRIES,
                                                                      CoaxialForwardIsolated)

__all__ = ["CoaxialForwardQuasiSteady", "CoaxialForwardPittPetersMasses", "QUASI_STEADY_CANDIDATES",
           "quasi_steady_candidates", "inflow_time_constants", "trim_time_constants", "START_BAND"]

#: Band of the phase-slope start of the delays [rad/s]: the lower part of the fit band,
#: where the wake's lam/C responses are coherent at 200 kt.
START_BAND = (1.0, 10.0)

#: Keys of :func:`quasi_steady_candidates`, in the order the study identifies them.
QUASI_STEADY_CANDIDATES = ("coaxial_forward_quasi_steady", "coaxial_forward_quasi_steady_without_lam0_cm",
                           "coaxial_forward_quasi_steady_without_lam0_cm_shared_delays",
                           "coaxial_forward_quasi_steady_interference",
                           "coaxial_forward_quasi_steady_interference_without_lam0_cm",
                           "coaxial_forward_isolated_pitt_peters_m",
                           "coaxial_forward_isolated_pitt_peters_m_without_lam0_cm")


class CoaxialForwardQuasiSteady(InflowStructure):
    """Quasi-steady coaxial inflow at high speed: a gain and a delay per response, no states.

    ``lambda_i(t) = sum_j K_ij C_j(t - tau_ij)`` (the off-rotor gain/delay form, Eqs.
    2.39-2.40, applied to the rotor's own inflow): per rotor the ``K`` entries 11, 13,
    22, 31, 33 (1-based in ``lam0, lam1s, lam1c`` over ``C_T, C_L, C_M``), each with its
    own delay: 10 gains and 10 delays, 20 parameters. With ``interference`` each
    harmonic of one rotor also responds to the same load of the other (entries 14, 41,
    25, 52, 36, 63, as :data:`INTERFERENCE_ENTRIES`): 32 parameters. Gains ``k<i><j>``
    [-], delays ``t<i><j>`` [s]. The model has no apparent mass to lose: the parameters
    the first-order form could not bound at 200 kt are not there.

    Parameters
    ----------
    interference : bool
        Add the upper <-> lower same-harmonic gains and delays (default False).
    frame : {"rotor", "printed"}
        Frame of the parameters (the pattern is the same in both).
    without_lam0_cm : bool
        Drop the ``lam0 / C_M`` gains (entries 13 and 46) and so that response from the
        fit (§4.4.1.2 allows it; at 200 kt the wake's ``lam0 / C_M`` has a notch inside
        the fit band that no gain follows): 16 parameters. Default False.
    shared_delays : bool
        One delay per harmonic and load for both rotors (the lower rotor's entries use
        the upper's ``t<i><j>``; the interference 41, 52, 63 use 14, 25, 36): the same
        transport at the same advance ratio. Default False (a delay per response).

    Raises
    ------
    TypeError
        An option is not a bool.

    Examples
    --------
    >>> s = CoaxialForwardQuasiSteady()
    >>> len(s.parameter_names()), s.parameter_names()[:3], s.states
    (20, ['k11', 'k13', 'k22'], [])
    >>> len(CoaxialForwardQuasiSteady(interference=True).parameter_names())
    32
    >>> len(CoaxialForwardQuasiSteady(without_lam0_cm=True, shared_delays=True).parameter_names())
    12
    """

    rotors = ("U", "L")
    form = "gain_delay"
    #: no apparent mass, no state: nothing is protected from the reduction
    protected = ()
    #: a quasi-steady model has no inflow states
    states = []

    def __init__(self, interference=False, frame="rotor", *, without_lam0_cm=False, shared_delays=False):
        super().__init__(frame)
        for name, v in (("interference", interference), ("without_lam0_cm", without_lam0_cm),
                        ("shared_delays", shared_delays)):
            if not isinstance(v, (bool, np.bool_)):
                raise TypeError(f"{name} must be True or False, got {v!r}")
        self.interference = bool(interference)
        self.without_lam0_cm = bool(without_lam0_cm)
        self.shared_delays = bool(shared_delays)

    @property
    def key(self):
        return ("coaxial_forward_quasi_steady" + ("_interference" if self.interference else "")
                + ("_without_lam0_cm" if self.without_lam0_cm else "")
                + ("_shared_delays" if self.shared_delays else ""))

    #: the structure's exact derivatives (a gain/delay response is linear in K)
    fit_options = {"jacobian": "analytic"}

    def spec(self):
        return {**super().spec(), "interference": self.interference, "without_lam0_cm": self.without_lam0_cm,
                "shared_delays": self.shared_delays, "fit_options": dict(self.fit_options)}

    def __repr__(self):
        return (f"{type(self).__name__}(interference={self.interference}, frame={self.frame!r}, "
                f"without_lam0_cm={self.without_lam0_cm}, shared_delays={self.shared_delays})")

    def _entries(self):
        """1-based (row, column) of every gain, rotor blocks first."""
        block = [e for e in ROTOR_BLOCK_ENTRIES if not (self.without_lam0_cm and e == (1, 3))]
        out = [(i + off, j + off) for off in (0, 3) for i, j in block]
        return out + (list(INTERFERENCE_ENTRIES) if self.interference else [])

    def _delay_name(self, i, j):
        """Delay of gain (i, j): its own, or with ``shared_delays`` the upper rotor's entry of
        the same harmonic and load (the rotor blocks' 44 -> 11, ...; interference 41 -> 14)."""
        if self.shared_delays and i > 3:
            i, j = (i - 3, j - 3) if j > 3 else (j, i)
        return f"t{i}{j}"

    def _patterns(self):
        """(K, tau) as 6 x 6 lists of parameter names and zeros."""
        k = [[0] * 6 for _ in range(6)]
        t = [[0] * 6 for _ in range(6)]
        for i, j in self._entries():
            k[i - 1][j - 1] = f"k{i}{j}"
            t[i - 1][j - 1] = self._delay_name(i, j)
        return k, t

    def parameter_names(self):
        """Names of the structure's parameters (sorted).

        Returns
        -------
        list of str
        """
        return sorted({f"k{i}{j}" for i, j in self._entries()} | {self._delay_name(i, j) for i, j in self._entries()})

    def build(self, initial, omega=None, fixed=()):
        """The :class:`flightid.GainDelayStructure` at ``initial`` values.

        Parameters
        ----------
        initial : dict
            Value of every parameter (gains [-], delays [s]); extra keys ignored.
        omega : float, optional
            Rotor speed [rad/s]; unused (a gain has no time derivative), accepted as
            every structure's ``build`` takes it.
        fixed : iterable of str
            Parameters held at their value.

        Returns
        -------
        flightid.GainDelayStructure

        Raises
        ------
        KeyError
            A parameter has no initial value.
        """
        from flightid import GainDelayStructure
        names = set(self.parameter_names())
        init = {n: float(v) for n, v in dict(initial).items() if n in names}
        missing = names - set(init)
        if missing:
            raise KeyError(f"no initial value for {sorted(missing)}")
        k, t = self._patterns()
        return GainDelayStructure(k, t, inputs=self.inputs, outputs=self.outputs, initial=init,
                                  fixed=[f for f in fixed if f in names])

    def initial_values(self, lam_over_c, n_points=3, coherence_min=None):
        """Data-driven start: each gain from the measured low-frequency lambda/C (real part
        averaged over the lowest points), delays 20 ms on a rotor's own loads and 50 ms
        across rotors (the first-order candidates' start).

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
        g0 = low_frequency_gain(lam_over_c, n_points, coherence_min, outputs=self.outputs, inputs=self.inputs)
        vals = {}
        for i, j in self._entries():
            vals[f"k{i}{j}"] = float(g0[i - 1, j - 1])
            vals[self._delay_name(i, j)] = 0.02 if (i - 1) // 3 == (j - 1) // 3 else 0.05
        return vals

    def extra_starts(self, lam_over_c, omega):
        """The band start: per gain the median magnitude over :data:`START_BAND` with the sign
        of the nearer phase, per delay the least-squares slope of the remaining phase
        (the off-rotor start, ``tau = -sum(phi w) / sum(w^2)``, at least 0).

        Parameters
        ----------
        lam_over_c : flightid.MeasuredResponse
        omega : float
            Rotor speed [rad/s] (unused).

        Returns
        -------
        list of (str, dict)
            One start, or none where the band holds no frequency.
        """
        w = lam_over_c.omega
        sel = (w >= START_BAND[0]) & (w <= START_BAND[1])
        if np.count_nonzero(sel) < 3:
            return []
        vals, delays = {}, {}
        for i, j in self._entries():
            h, _ = lam_over_c.element(self.outputs[i - 1], self.inputs[j - 1])
            k, tau = _gain_and_delay(h[sel], w[sel])
            vals[f"k{i}{j}"] = k
            delays.setdefault(self._delay_name(i, j), []).append(tau)
        # a shared delay starts at the mean of its rotors' phase slopes
        vals.update({n: float(np.mean(v)) for n, v in delays.items()})
        return [(f"band gain and phase-slope delay ({START_BAND[0]:g}-{START_BAND[1]:g} rad/s)", vals)]

    def to_inflow(self, values, omega, **kwargs):
        """Not available: the aircraft's inflow models carry inflow states.

        Raises
        ------
        NotImplementedError
            Always (a quasi-steady model would be a feedthrough of the loads, which the
            aircraft's inflow interface does not take).
        """
        raise NotImplementedError(f"{self.key} is quasi-steady (no inflow states): it cannot go into the "
                                  "aircraft as an IdentifiedInflow")


def _gain_and_delay(h, w):
    """(signed median magnitude, phase-slope delay >= 0 [s]) of a response ``h`` at ``w``."""
    mag = float(np.median(np.abs(h)))
    phase = np.unwrap(np.angle(h))
    sign = 1.0 if abs(np.angle(np.exp(1j * phase[0]))) <= math.pi / 2 else -1.0
    rest = np.unwrap(np.angle(h * sign))
    rest -= 2 * math.pi * np.round(rest[0] / (2 * math.pi))
    return sign * mag, max(0.0, float(-np.sum(rest * w) / np.sum(w * w)))


class CoaxialForwardPittPetersMasses(CoaxialForwardIsolated):
    """Two isolated first-order rotors with the apparent masses held at Pitt-Peters' values.

    :class:`~aircraft.identification.structures.coaxial_forward_small.CoaxialForwardIsolated`
    (Eq. 4.3 per rotor) with ``m11 = m44 = 8/(3 pi)`` and ``m22 = m55 = -16/(45 pi)``
    (azimuth time; ``M33 = M22`` per rotor) fixed, not fitted: 20 free parameters
    (``Lbar`` and ``tau``) of 24. Pitt-Peters' ``M`` does not depend on the advance
    ratio, so the lag it leaves, ``M / (Omega Lbar)``, is what the fitted ``Lbar`` says.

    Parameters
    ----------
    without_lam0_cm : bool
        Leave every ``lam0 / C_M`` response out of the fit (as the isolated candidate
        can). Default False.
    frame : {"rotor", "printed"}

    Examples
    --------
    >>> s = CoaxialForwardPittPetersMasses()
    >>> s.key, sorted(s.fixed_masses)
    ('coaxial_forward_isolated_pitt_peters_m', ['m11', 'm22', 'm44', 'm55'])
    >>> s.build(s.start_masses({}), 20.3).free_names[:2]
    ['l11', 'l13']
    """

    #: the masses are fixed, so none is left to protect
    protected = ()
    #: the held apparent masses (azimuth time)
    fixed_masses = {"m11": PITT_PETERS_M11, "m22": PITT_PETERS_M22, "m44": PITT_PETERS_M11,
                    "m55": PITT_PETERS_M22}

    def __init__(self, frame="rotor", without_lam0_cm=False):
        super().__init__(frame, without_lam0_cm)

    @property
    def key(self):
        return "coaxial_forward_isolated_pitt_peters_m" + ("_without_lam0_cm" if self.without_lam0_cm else "")

    def spec(self):
        return {**super().spec(), "fixed_masses": dict(self.fixed_masses)}

    def start_masses(self, values):
        """``values`` with the apparent masses at Pitt-Peters' (a start of ``Lbar`` and
        ``tau`` is completed with zeros, for the examples).

        Parameters
        ----------
        values : dict

        Returns
        -------
        dict
        """
        out = {n: 0.0 for n in self.parameter_names()}
        out.update(values)
        out.update(self.fixed_masses)
        return out

    def build(self, initial, omega, fixed=()):
        """As the isolated candidate's, with the apparent masses at Pitt-Peters' values and fixed.

        Parameters
        ----------
        initial : dict
            Values of ``Lbar`` and ``tau`` (masses given here are replaced).
        omega : float
            Rotor speed [rad/s].
        fixed : iterable of str
            Further parameters held at their value.

        Returns
        -------
        flightid.MLTauStructure
        """
        init = {**dict(initial), **self.fixed_masses}
        return super().build(init, omega, fixed=set(fixed) | set(self.fixed_masses))

    def extra_starts(self, lam_over_c, omega):
        """None: the equation-error start estimates the masses, which are held here.

        Returns
        -------
        list
        """
        return []


def quasi_steady_candidates():
    """The candidates of this module, keyed as the study's ``structures.csv`` names them.

    Returns
    -------
    dict
        :data:`QUASI_STEADY_CANDIDATES` -> structure: the quasi-steady isolated rotors (20
        parameters), without ``lam0 / C_M`` (16), the same with the delays shared by the
        rotors (12), the quasi-steady rotors with interference (32) and without ``lam0 /
        C_M`` (28), the first-order isolated rotors with Pitt-Peters' masses held (20
        free of 24), and the latter without the ``lam0 / C_M`` responses.

    Examples
    --------
    >>> list(quasi_steady_candidates()) == list(QUASI_STEADY_CANDIDATES)
    True
    """
    qs = CoaxialForwardQuasiSteady
    structures = (qs(), qs(without_lam0_cm=True), qs(without_lam0_cm=True, shared_delays=True),
                  qs(interference=True), qs(interference=True, without_lam0_cm=True),
                  CoaxialForwardPittPetersMasses(), CoaxialForwardPittPetersMasses(without_lam0_cm=True))
    return {s.key: s for s in structures}


def inflow_time_constants(lam0, mu, omega, band=(1.0, 25.0), mu_z=0.0):
    """Pitt-Peters' inflow lags at a trim against a fit band.

    The first-order inflow ``M lam' + Lbar lam = C`` (azimuth time) has the lags
    ``T = 1 / (Omega * eig(M^-1 Lbar))`` [s] (the frozen-mass-flow ``Lbar = [V][Lhat]^-1``
    of :func:`aircraft.inflow.pitt_peters.pitt_peters_matrices`). Below its corner
    ``1/T`` a lag ``1 / (1 + s T)`` is the delay ``exp(-s T)`` to first order in
    ``omega T``; the magnitude differs by ``10 log10(1 + (omega T)^2)`` dB and the phase
    by ``omega T - atan(omega T)``: where both are small over the band, the data cannot
    separate an apparent mass from a delay.

    Parameters
    ----------
    lam0 : float
        Induced inflow of the rotor at trim [-] (> 0).
    mu : float
        Advance ratio [-] (>= 0).
    omega : float
        Rotor speed [rad/s] (> 0).
    band : (float, float)
        Fit band [rad/s].
    mu_z : float
        Free-stream flow through the disk, positive in climb [-].

    Returns
    -------
    pandas.DataFrame
        One row per mode (eigenvalue of ``Omega M^-1 Lbar``, slowest first; a complex
        pair gives two rows): ``lag_s`` (one over the real part) [s], ``rate_imag_1_s``
        (the imaginary part) [1/s], ``corner_rad_s`` [rad/s], ``omega_T_at_band_top`` [-],
        ``magnitude_lag_vs_delay_db`` and ``phase_lag_vs_delay_deg`` (the lag's
        departure from the delay of the same ``T`` at the band's top).

    Raises
    ------
    ValueError
        A non-positive ``lam0`` or ``omega``, a negative ``mu``, or a bad band.

    Examples
    --------
    Hover: ``Lbar = diag(2 lam0, -lam0, -lam0)`` (frozen mass flow), so the collective
    lag is ``M11 / (2 lam0 Omega)``:

    >>> t = inflow_time_constants(0.05, 0.0, 20.0)
    >>> round(float(t.lag_s.max()), 4), round(8 / (3 * np.pi) / (2 * 0.05 * 20.0), 4)
    (0.4244, 0.4244)
    """
    from aircraft.inflow.pitt_peters import pitt_peters_matrices
    for name, v in (("lam0", lam0), ("omega", omega)):
        if not (isinstance(v, (int, float, np.floating)) and math.isfinite(v) and v > 0):
            raise ValueError(f"{name} must be a positive finite number, got {v!r}")
    if not (isinstance(mu, (int, float, np.floating)) and math.isfinite(mu) and mu >= 0):
        raise ValueError(f"mu must be a finite number >= 0, got {mu!r}")
    try:
        lo, hi = (float(b) for b in band)
    except (TypeError, ValueError):
        raise ValueError(f"band must be (lo, hi) [rad/s], got {band!r}") from None
    if not 0 < lo < hi:
        raise ValueError(f"band must be (lo, hi) with 0 < lo < hi [rad/s], got {band!r}")
    m, lbar = pitt_peters_matrices(float(lam0), float(mu), float(mu_z))
    rate = np.linalg.eigvals(np.linalg.solve(m, lbar)) * float(omega)   # 1/s
    rate = rate[np.argsort(np.real(rate), kind="stable")]                 # slowest first
    lags = 1.0 / np.real(rate)
    wt = hi * lags
    return pd.DataFrame({"lag_s": lags, "rate_imag_1_s": np.imag(rate), "corner_rad_s": 1.0 / lags,
                         "omega_T_at_band_top": wt,
                         "magnitude_lag_vs_delay_db": -10.0 * np.log10(1.0 + wt ** 2),
                         "phase_lag_vs_delay_deg": np.degrees(wt - np.arctan(wt))})


def trim_time_constants(trim_outputs, config, band):
    """:func:`inflow_time_constants` of each rotor of a wake trim, one table.

    Parameters
    ----------
    trim_outputs : mapping
        The wake trim's outputs (``lam0_<rotor>`` of every rotor of ``config``) [-].
    config : AircraftConfig
        The coaxial; its first rotor gives ``Omega`` and ``R``.
    band : (float, float)
        Fit band [rad/s].

    Returns
    -------
    pandas.DataFrame
        :func:`inflow_time_constants`' columns with ``rotor``, ``lam0``, ``mu`` and
        ``mu_z`` first; ``mu = V cos(alpha) / (Omega R)`` and ``mu_z = -V sin(alpha) /
        (Omega R)`` at the 200 kt condition (the free stream flows up through a disk
        tilted back).

    Examples
    --------
    >>> from aircraft.configs import coaxial_compound
    >>> t = trim_time_constants({"lam0_U": 0.0129, "lam0_L": 0.0125}, coaxial_compound(cruise=True), (1.0, 25.0))
    >>> t.rotor.tolist()[:3], bool((t.lag_s < 0.05).all())
    (['U', 'U', 'U'], True)
    """
    from aircraft.identification.coaxial_forward_flight import ROTOR_AOA, SPEED_200KT
    rotor = config.rotors[0]
    tip = float(rotor.omega) * float(rotor.radius)
    mu = SPEED_200KT * math.cos(ROTOR_AOA) / tip
    mu_z = -SPEED_200KT * math.sin(ROTOR_AOA) / tip
    parts = []
    for r in config.rotors:
        lam0 = float(trim_outputs[f"lam0_{r.name}"])
        t = inflow_time_constants(lam0, mu, float(r.omega), band, mu_z=mu_z)
        parts.append(t.assign(rotor=r.name, lam0=lam0, mu=mu, mu_z=mu_z))
    out = pd.concat(parts, ignore_index=True)
    first = ["rotor", "lam0", "mu", "mu_z"]
    return out[first + [c for c in out.columns if c not in first]]
