"""Off-rotor induced-velocity models (§2.2.3, §4.6, Eqs. 2.39-2.40): :func:`identify_off_rotor`.

The induced velocity the rotor wake produces at a surface off the rotor (the
horizontal tail, a wing or the fuselage under the hub) is written as a static
output equation of the rotor inflow states, each with its own time delay::

    vbar_i(t) = sum_j K_ij lam_j(t - tau_ij),   lam = (lam0, lam1c, lam1s)

with one delay per inflow state (Eq. 2.39, the dissertation's tail form) or one
per element (Eq. 2.40, its wing form). ``vbar = (vx, vy, vz)`` are the body-axis
components (x forward, y right, z down) of the velocity averaged over the
surface's points, divided by the tip speed Omega R.

::

    wake trim ─► one swashplate sweep per control, a doublet per control and a
      zero-input run, recording the wake's velocity at the surfaces' points
      (aircraft.wake.run_sweeps: parallel, cached)
      ─► chirp-z responses (vbar, lam over theta) ─► joint input-output vbar/lam (Eq. 4.9)
      ─► data-driven start (gains and phase delays of the fit band)
      ─► CIFER-cost fit in the flight-dynamics band (1-5 rad/s, §4.6)
      ─► time-domain verification on the doublets (not used in the fit), beside
         the TIC of the zero-input run (the wake's own unsteadiness)

This module holds the model (surfaces, settings, the Eq. 2.39/2.40 structure and
its fit, the wake-exposure geometry); :mod:`aircraft.identification.off_rotor.identify`
runs it on the free wake (:func:`identify_off_rotor`) and holds the results.

Whether the tail sits in the wake is judged from the wake's skew
(:func:`wake_exposure`): a skewed cylinder through the disk edge, at the skew
angle of the trimmed inflow.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pandas as pd

from ..excitation import ExcitationSettings

__all__ = ["OffRotorError", "OffRotorSurface", "OffRotorSettings", "horizontal_tail", "wing_under_hub",
           "gain_delay_structure", "fit_off_rotor", "reduce_off_rotor", "wake_exposure", "INFLOW_STATES",
           "VELOCITY_COMPONENTS",
           "UH60_STABILATOR_ASPECT_RATIO", "PUBLISHED_HOVER"]

#: Model inputs, the rotor inflow harmonics, in the order of Eqs. 2.39-2.40.
INFLOW_STATES = ("lam0", "lam1c", "lam1s")
#: Body-axis velocity components of Eqs. 2.39-2.40 (x forward, y right, z down).
VELOCITY_COMPONENTS = ("x", "y", "z")
_KEY = {"lam0": "0", "lam1c": "1c", "lam1s": "1s"}
#: Aspect ratio of the UH-60A stabilator (14.4 ft span, 45 ft^2): the span of a
#: configuration's horizontal tail follows from its area with it.
UH60_STABILATOR_ASPECT_RATIO = 14.4 ** 2 / 45.0

#: The dissertation's hover models of its MFW (reference values, never outputs):
#: tail, §4.6.1 (Eq. 2.39, one delay per inflow state, average of 7 quarter-chord
#: points); wing under the hub, Eq. 4.10 (Eq. 2.40). Rows vx, vy, vz; columns lam0,
#: lam1c, lam1s; delays [s]. Its sign convention for the velocity components is
#: not stated (its wing K0z = -1.37 suggests z up); ours are body axes, z down.
PUBLISHED_HOVER = {
    "tail": {"K": ((-0.2892, -0.3108, 0.0532), (-0.142, -0.1353, 0.3407), (0.3148, 0.5361, -0.1104)),
             "tau": ((0.06225, 0.2115, 0.6929),) * 3},
    "wing": {"K": ((0.0221, -0.7496, -0.2117), (0.0, 0.207, -0.766), (-1.366, 0.02861, 0.0)),
             "tau": ((0.2149, 0.541, 0.3795), (0.0, 0.4452, 0.5327), (0.07075, 0.154, 0.0))},
}


class OffRotorError(ValueError):
    """Bad input to the off-rotor identification (surface, settings, data)."""


def _finite_vector(name, value, n=3):
    arr = np.asarray(value)
    if arr.shape != (n,) or np.iscomplexobj(arr) or not np.issubdtype(arr.dtype, np.number) \
            or not np.all(np.isfinite(arr.astype(float))):
        raise OffRotorError(f"{name} must be {n} finite real numbers [m], got {value!r}")
    return tuple(float(v) for v in arr)


def _positive(name, value, unit=""):
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not math.isfinite(float(value)) or not float(value) > 0:
        raise OffRotorError(f"{name} must be a positive finite number{' [' + unit + ']' if unit else ''}, "
                            f"got {value!r}")
    return float(value)


@dataclass(frozen=True)
class OffRotorSurface:
    """A lifting surface off the rotor, sampled along its quarter-chord line.

    Parameters
    ----------
    name : str
        Label (letters, digits, underscores); the wake columns are
        ``vx_<name>_<k>``.
    center : (float, float, float)
        Quarter-chord midpoint in body axes from the c.g. (x fwd, y right, z down) [m].
    span : float
        Span [m]; the points are spread evenly from ``-span/2`` to ``+span/2`` in y.
    n_points : int
        Points along the span (the dissertation averages seven, §4.6.1).
    form : {"2.39", "2.40"}
        Delay structure fitted: one delay per inflow state (Eq. 2.39) or one per
        gain (Eq. 2.40).
    """

    name: str
    center: tuple
    span: float
    n_points: int = 7
    form: str = "2.39"

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name.isidentifier():
            raise OffRotorError(f"surface name must be an identifier such as 'tail', got {self.name!r}")
        object.__setattr__(self, "center", _finite_vector("OffRotorSurface.center", self.center))
        object.__setattr__(self, "span", _positive("OffRotorSurface.span", self.span, "m"))
        if isinstance(self.n_points, bool) or not isinstance(self.n_points, (int, np.integer)) \
                or self.n_points < 1:
            raise OffRotorError(f"OffRotorSurface.n_points must be an integer >= 1, got {self.n_points!r}")
        if self.form not in ("2.39", "2.40"):
            raise OffRotorError(f"OffRotorSurface.form must be '2.39' (delay per inflow state) or '2.40' "
                                f"(delay per gain), got {self.form!r}")

    @property
    def labels(self):
        """Point labels ``<name>_<k>``."""
        return [f"{self.name}_{k}" for k in range(self.n_points)]

    def points(self):
        """``{label: (x, y, z)}`` body-axis points [m] for :func:`aircraft.wake.run_sweeps`."""
        x, y0, z = self.center
        ys = [y0] if self.n_points == 1 else list(y0 + np.linspace(-0.5, 0.5, self.n_points) * self.span)
        return {lab: (x, float(y), z) for lab, y in zip(self.labels, ys)}

    def average(self, df):
        """DataFrame ``vx, vy, vz`` [-]: the wake record's velocity averaged over the points."""
        out = {}
        for c in VELOCITY_COMPONENTS:
            cols = [f"v{c}_{lab}" for lab in self.labels]
            missing = [k for k in cols if k not in df.columns]
            if missing:
                raise OffRotorError(f"the wake record lacks the velocity columns {missing[:3]} of surface "
                                    f"{self.name!r} (was it run with these points?)")
            out[f"v{c}"] = df[cols].mean(axis=1).to_numpy()
        return pd.DataFrame(out, index=df.index)


def horizontal_tail(config, *, span=None, n_points=7, form="2.39"):
    """The configuration's horizontal tail as an :class:`OffRotorSurface`.

    Parameters
    ----------
    config : aircraft.AircraftConfig
        Its ``htail_position`` [m] (body axes from the c.g.) is taken as the
        quarter-chord midpoint.
    span : float, optional
        Tail span [m]. Default: from ``htail_area`` [m^2] with the UH-60A
        stabilator's aspect ratio (4.6), ``sqrt(4.6 * area)``.
    n_points : int
        Points along the quarter chord (7, as in §4.6.1).
    form : {"2.39", "2.40"}
        Delay structure (the dissertation fits the tail with Eq. 2.39).

    Returns
    -------
    OffRotorSurface
    """
    if span is None:
        span = math.sqrt(UH60_STABILATOR_ASPECT_RATIO * _positive("config.htail_area", config.htail_area, "m^2"))
    return OffRotorSurface("tail", tuple(config.htail_position), span, n_points, form)


def wing_under_hub(config, *, depth=0.25, span=None, n_points=7, form="2.40"):
    """A wing (or fuselage station) under the first rotor's hub as an :class:`OffRotorSurface`.

    Parameters
    ----------
    config : aircraft.AircraftConfig
    depth : float
        Distance below the hub [rotor radii] (0.25 R: about the UH-60's stub-wing
        and cabin-roof level, 2 m under the hub).
    span : float, optional
        Span [m] (default: that of :func:`horizontal_tail`, a "similar spread of
        points", §2.2.3).
    n_points : int
    form : {"2.39", "2.40"}
        Delay structure (the dissertation fits the wing with Eq. 2.40).

    Returns
    -------
    OffRotorSurface
    """
    rotor = config.rotors[0]
    depth = _positive("depth", depth, "R")
    if span is None:
        span = horizontal_tail(config).span
    hx, hy, hz = rotor.hub_position
    return OffRotorSurface("wing", (hx, hy, hz + depth * rotor.radius), span, n_points, form)


def gain_delay_structure(form, initial=None, *, fixed=(), outputs=None):
    """The flightid structure of Eq. 2.39 or 2.40 with named gains and delays.

    Gains are ``K<j><i>`` (``K0z``, ``K1cx``, ...), delays ``tau<j>`` (Eq. 2.39)
    or ``tau<j><i>`` (Eq. 2.40), ``j`` the inflow state (0, 1c, 1s) and ``i``
    the velocity component (x, y, z).

    Parameters
    ----------
    form : {"2.39", "2.40"}
    initial : dict, optional
        Start values (default: gains 0, delays 0 s).
    fixed : iterable of str
        Parameters held at their initial value.
    outputs : list of str, optional
        Output names (default ``["vx", "vy", "vz"]``).

    Returns
    -------
    flightid.GainDelayStructure
        Inputs :data:`INFLOW_STATES` [-], outputs the velocities [-], delays [s].
    """
    from flightid import GainDelayStructure
    if form not in ("2.39", "2.40"):
        raise OffRotorError(f"form must be '2.39' or '2.40', got {form!r}")
    outputs = list(outputs or [f"v{c}" for c in VELOCITY_COMPONENTS])
    K = [[f"K{_KEY[j]}{c}" for j in INFLOW_STATES] for c in VELOCITY_COMPONENTS]
    if form == "2.39":
        tau = [[f"tau{_KEY[j]}" for j in INFLOW_STATES] for _ in VELOCITY_COMPONENTS]
    else:
        tau = [[f"tau{_KEY[j]}{c}" for j in INFLOW_STATES] for c in VELOCITY_COMPONENTS]
    names = {n for row in K + tau for n in row}
    init = {n: 0.0 for n in names}
    init.update(dict(initial or {}))
    return GainDelayStructure(K, tau, inputs=list(INFLOW_STATES), outputs=outputs, initial=init,
                              fixed=fixed)


@dataclass(frozen=True)
class OffRotorSettings(ExcitationSettings):
    """Settings of :func:`identify_off_rotor` (SI units, radians).

    The wake records and the fit band are those of
    :class:`~aircraft.identification.excitation.ExcitationSettings`, with a fit band of
    1-5 rad/s by default (the flight-dynamics band of §4.6); added here:

    Parameters
    ----------
    controls : tuple of str
        Swashplate controls swept, one sweep each (three independent excitations
        for the three inflow states of the joint input-output).
    doublet_controls : tuple of str
        Controls with a verification doublet each.
    starts : int
        Starts of the fit (the data-driven start and seeded scatterings of it).
    reduce : bool
        Reduce the fit (:func:`reduce_off_rotor`): delays and gains the data do not
        support are removed, as for every other identified model.
    insensitivity_max, cramer_rao_max : float
        Reduction and trust thresholds [%] (guideline 10 % and 20 %).

    Notes
    -----
    The zero-input run's mean is the trim reference of every signal and its TIC the
    wake's noise floor; a gain is fitted only if its response reaches
    ``coherence_min`` on 5+ points of the fit band (the others are fixed at zero).

    Examples
    --------
    >>> OffRotorSettings().fit_range
    (1.0, 5.0)
    """

    error: ClassVar[type] = OffRotorError

    fit_range: tuple = (1.0, 5.0)
    controls: tuple = ("theta0", "theta1s", "theta1c")
    doublet_controls: tuple = ("theta0", "theta1s", "theta1c")
    starts: int = 4
    reduce: bool = True
    insensitivity_max: float = 10.0
    cramer_rao_max: float = 20.0

    def __post_init__(self):
        super().__post_init__()
        for name in ("insensitivity_max", "cramer_rao_max"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or not v > 0:
                raise OffRotorError(f"{name} must be a positive finite number [%], got {v!r}")
        if len(self.controls) < len(INFLOW_STATES):
            raise OffRotorError(f"the joint input-output needs at least {len(INFLOW_STATES)} swept controls "
                                f"(one per inflow state), got {self.controls!r}")
        if 2.0 * self.pulse_width + 1.0 > self.doublet_s:
            raise OffRotorError(f"doublet_s = {self.doublet_s} s is shorter than the doublet (1 s lead-in + "
                                f"2 x pulse_width = {1.0 + 2 * self.pulse_width} s)")
        if isinstance(self.starts, bool) or not isinstance(self.starts, int) or self.starts < 1:
            raise OffRotorError(f"starts must be an integer >= 1, got {self.starts!r}")

    def specs(self):
        """The wake records: sweeps, doublets and the zero-input run (:class:`aircraft.wake.SweepSpec`)."""
        from aircraft.wake import SweepSpec
        out = [SweepSpec(c, kind="sweep", amplitude=self.amplitude, duration=self.sweep_s, w_min=self.w_min,
                         w_max=self.w_max, seed=k) for k, c in enumerate(self.controls)]
        out += [SweepSpec(c, kind="doublet", amplitude=self.doublet_amplitude, duration=self.doublet_s,
                          pulse_width=self.pulse_width) for c in self.doublet_controls]
        out.append(SweepSpec(self.controls[0], kind="sine", amplitude=0.0, duration=self.noise_floor_s,
                             w_min=1.0, label="zero_input"))
        return out


# --------------------------------------------------------------------------- fitting
def _band(response, lo, hi):
    w = response.omega
    sel = (w >= lo) & (w <= hi)
    return sel


def _start_values(response, form, lo, hi, coherence_min, outputs):
    """Data-driven start and the fitted pairs.

    Each coherent element gives ``|K|`` (median magnitude over the band), the sign
    whose phase is nearer, and the delay of the least-squares slope of the
    remaining phase, ``tau = -sum(phi w) / sum(w^2)`` (>= 0). Eq. 2.39 shares a
    delay between the outputs of one inflow state: the magnitude-weighted mean.
    """
    sel = _band(response, lo, hi)
    w = response.omega[sel]
    initial, pairs, fixed = {}, [], []
    tau_acc = {j: [] for j in INFLOW_STATES}
    for o, c in zip(outputs, VELOCITY_COMPONENTS):
        for j in INFLOW_STATES:
            kname = f"K{_KEY[j]}{c}"
            tname = f"tau{_KEY[j]}" if form == "2.39" else f"tau{_KEY[j]}{c}"
            h, coh = response.element(o, j)
            h, coh = h[sel], coh[sel]
            if np.count_nonzero(coh >= coherence_min) < 5 or not np.all(np.isfinite(h)):
                initial[kname] = 0.0
                fixed.append(kname)
                if form == "2.40":
                    initial[tname] = 0.0
                    fixed.append(tname)
                continue
            pairs.append((o, j))
            mag = float(np.median(np.abs(h)))
            phase = np.unwrap(np.angle(h))
            sign = 1.0 if abs(np.angle(np.exp(1j * phase[0]))) <= math.pi / 2 else -1.0
            rest = np.unwrap(np.angle(h * sign))
            rest -= 2 * math.pi * np.round(rest[0] / (2 * math.pi))
            tau = max(0.0, float(-np.sum(rest * w) / np.sum(w * w)))
            initial[kname] = sign * mag
            if form == "2.40":
                initial[tname] = tau
            else:
                tau_acc[j].append((mag, tau))
    if form == "2.39":
        for j, acc in tau_acc.items():
            tname = f"tau{_KEY[j]}"
            if acc:
                m = np.array(acc)
                initial[tname] = float(np.sum(m[:, 0] * m[:, 1]) / np.sum(m[:, 0]))
            else:   # no coherent output of this inflow state: its delay has no influence
                initial[tname] = 0.0
                fixed.append(tname)
    return initial, pairs, fixed


def fit_off_rotor(responses, form="2.39", *, fit_range=(1.0, 5.0), outputs=None, n_omega=20,
                  coherence_min=0.6, starts=4, seed=0):
    """Fit Eq. 2.39 or 2.40 to measured off-rotor responses ``vbar / lam``.

    Parameters
    ----------
    responses : flightid.MeasuredResponse
        Velocities over the inflow states :data:`INFLOW_STATES` (e.g. from
        :func:`flightid.joint_input_output`), dimensionless; inputs must be named
        ``lam0, lam1c, lam1s``.
    form : {"2.39", "2.40"}
        One delay per inflow state or one per gain.
    fit_range : (float, float)
        Fit band [rad/s].
    outputs : list of str, optional
        The three velocity outputs (x, y, z) of ``responses`` (default
        ``["vx", "vy", "vz"]``).
    n_omega : int
        Frequencies per response in the cost.
    coherence_min : float
        Gains whose response has fewer than 5 points of this coherence in the band
        are fixed at zero (and, with Eq. 2.40, their delays at 0 s).
    starts : int
        Fit starts (the data-driven start plus seeded scatterings).
    seed : int
        Seed of the start scattering.

    Returns
    -------
    flightid.FitResult
        With the fitted :class:`flightid.GainDelayStructure` (gains [-], delays [s]).

    Raises
    ------
    OffRotorError
        Wrong input names, a bad band, or no coherent response at all.
    """
    from flightid import MeasuredResponse, fit
    outputs = list(outputs or [f"v{c}" for c in VELOCITY_COMPONENTS])
    if not isinstance(responses, MeasuredResponse):
        raise OffRotorError(f"responses must be a flightid.MeasuredResponse, got {type(responses).__name__}")
    if form not in ("2.39", "2.40"):
        raise OffRotorError(f"form must be '2.39' or '2.40', got {form!r}")
    missing = [n for n in INFLOW_STATES if n not in responses.input_labels] + \
        [n for n in outputs if n not in responses.output_labels]
    if missing or len(outputs) != 3:
        raise OffRotorError(f"responses need inputs {list(INFLOW_STATES)} and three outputs {outputs}; "
                            f"missing {missing} (have {responses.input_labels} -> {responses.output_labels})")
    try:
        lo, hi = (float(v) for v in fit_range)
    except (TypeError, ValueError):
        raise OffRotorError(f"fit_range must be (w_lo, w_hi) [rad/s], got {fit_range!r}") from None
    if not (0 < lo < hi) or hi < responses.omega.min() or lo > responses.omega.max():
        raise OffRotorError(f"fit_range ({lo}, {hi}) rad/s must be increasing, positive and overlap the "
                            f"responses' {responses.omega.min():.3g}-{responses.omega.max():.3g} rad/s")
    initial, pairs, fixed = _start_values(responses, form, lo, hi, coherence_min, outputs)
    if not pairs:
        raise OffRotorError(f"no off-rotor response reaches coherence {coherence_min} on 5 points of "
                            f"{lo:g}-{hi:g} rad/s: the data carry no information for Eq. {form}")
    structure = gain_delay_structure(form, initial, fixed=fixed, outputs=outputs)
    return fit(structure, responses, pairs=pairs, frequency_ranges=(lo, hi), n_omega=n_omega,
               coherence_min=coherence_min, starts=starts, seed=seed)


def reduce_off_rotor(fitted, responses, *, insensitivity_max=10.0, cramer_rao_max=20.0, starts=4, seed=0):
    """Reduce a fitted Eq. 2.39/2.40 model with :func:`flightid.reduce` (Fig. 6.1).

    The worst parameter over the guideline goes first -- a delay sitting at its
    0 s bound has an unbounded relative Cramér-Rao bound and insensitivity and is
    removed (fixed at 0 s) when that does not raise the cost -- then the next, each
    removal kept only if J_ave rises by at most 2 and no single J by more than 10.
    Same pairs and bands as ``fitted``; the analytic Jacobian makes the refits cheap.

    Parameters
    ----------
    fitted : flightid.FitResult
        A fit of :func:`fit_off_rotor`.
    responses : flightid.MeasuredResponse
        The responses it was fitted to.
    insensitivity_max, cramer_rao_max : float
        Candidate thresholds [%] (guideline 10 % and 20 %).
    starts, seed : int
        Starts of every refit and their seed (as :func:`fit_off_rotor`).

    Returns
    -------
    flightid.ReductionResult
        ``.result`` the reduced fit, ``.removed`` the parameters removed, ``.log``.

    Examples
    --------
    >>> import numpy as np
    >>> from flightid import MeasuredResponse
    >>> w = np.geomspace(0.5, 8.0, 60)
    >>> h = np.zeros((3, 3, w.size), complex)
    >>> h[2, 0] = 0.9 * np.exp(-0.2j * w)          # vz/lam0 = 0.9 e^(-0.2 s): a real delay
    >>> h[0, 1] = -0.5 + 0j                         # vx/lam1c = -0.5: no delay at all
    >>> coherence = np.where(np.abs(h) > 0, 0.99, 0.0)
    >>> data = MeasuredResponse(h, w, coherence, ["lam0", "lam1c", "lam1s"], ["vx", "vy", "vz"])
    >>> first = fit_off_rotor(data, "2.40", starts=1)
    >>> reduction = reduce_off_rotor(first, data, starts=1)
    >>> reduction.removed, round(reduction.result.structure.values["tau0z"], 3)
    (['tau1cx'], 0.2)
    """
    from flightid import reduce
    pairs = [(p.output, p.input) for p in fitted.pairs]
    ranges = {(p.output, p.input): (p.omega[0], p.omega[-1]) for p in fitted.pairs}
    reduction = reduce(fitted.structure, responses, insensitivity_max=insensitivity_max,
                       cramer_rao_max=cramer_rao_max, pairs=pairs, frequency_ranges=ranges, n_omega=fitted.n_omega,
                       starts=starts, seed=seed, jacobian="analytic")
    return _delays_at_bound_removed(reduction, fitted)


#: A delay below this is none [s] (a Padé pole beyond 2e6 rad/s; the structures' own threshold).
_NO_DELAY_S = 1e-6


def _delays_at_bound_removed(reduction, fitted):
    """A delay the reduction held (no influence left after another removal) while it sat at
    its 0 s bound is a delay the data do not support: set to 0 s (below 1 us the response
    is the same to double precision) and logged as removed, with the reason."""
    result = reduction.result
    first_fixed = set(fitted.structure.fixed)
    removed = set(reduction.removed)
    held = [n for n in result.structure.delay_names if n in result.structure.fixed and n not in first_fixed
            and n not in removed and abs(result.structure.values[n]) < _NO_DELAY_S]
    if not held:
        return reduction
    was = {n: result.structure.values[n] for n in held}
    result.structure = result.structure.with_values({n: 0.0 for n in held})
    result.parameters.loc[result.parameters.parameter.isin(held), "value"] = 0.0
    rows = [{"parameter": n, "reason": "at its bound", "metric_pct": float("inf"), "J_ave_before": result.J_ave,
             "J_ave_after": result.J_ave, "max_single_rise": 0.0, "accepted": True, "runaway": False,
             "note": f"held by the reduction at {was[n]:.3g} s (no influence left): a delay below "
                     f"{_NO_DELAY_S:g} s is none; removed"} for n in held]
    reduction.log = pd.concat([reduction.log, pd.DataFrame(rows)], ignore_index=True)
    return reduction


# --------------------------------------------------------------------------- wake exposure
def wake_exposure(surface, config, mu, lam, *, mu_z=0.0, hover_contraction=0.86):
    """Whether the surface's points lie in the rotor wake, from the wake's skew.

    The wake is a skewed cylinder below the first rotor: its axis leaves the hub
    at the skew angle ``chi = atan(mu / (lam - mu_z))`` from the shaft (momentum
    theory, Glauert), so at a depth ``h`` below the hub its centre is ``h tan chi``
    aft of the hub; its radius is ``r_w = R (c + (1 - c) sin chi)``, with the hover
    contraction ``c`` (0.86: the far-wake radius of our free wake without the
    near-wake contraction, :class:`aircraft.wake.WakeSettings`) relaxing to no
    contraction in edgewise flight. A point is in the wake when it lies within
    ``r_w`` of the axis at its depth.

    Parameters
    ----------
    surface : OffRotorSurface
    config : aircraft.AircraftConfig
        First rotor's hub [m] and radius [m]; shafts normal to body x.
    mu : float
        Advance ratio (in-plane free stream / Omega R) [-], >= 0.
    lam : float
        Induced inflow lam0 [-] (positive down).
    mu_z : float
        Free-stream component up through the disk / Omega R [-] (disk tilted back).
    hover_contraction : float
        Hover wake radius / R [-] in (0, 1].

    Returns
    -------
    pandas.DataFrame
        Per point: label, depth below the hub h [m], skew chi [deg], wake-centre x
        [m], wake radius r_w [m], distance from the axis / r_w [-], in_wake (bool).

    Raises
    ------
    OffRotorError
        Negative mu, non-finite values or a contraction outside (0, 1].
    """
    for name, v in (("mu", mu), ("lam", lam), ("mu_z", mu_z)):
        if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) \
                or not math.isfinite(float(v)):
            raise OffRotorError(f"{name} must be a finite real number [-], got {v!r}")
    if mu < 0:
        raise OffRotorError(f"advance ratio mu must be >= 0, got {mu!r}")
    if not 0 < hover_contraction <= 1:
        raise OffRotorError(f"hover_contraction must be in (0, 1] [R], got {hover_contraction!r}")
    rotor = config.rotors[0]
    hx, hy, hz = rotor.hub_position
    through = lam - mu_z
    chi = math.atan2(mu, through) if through > 0 else math.pi / 2
    rw = rotor.radius * (hover_contraction + (1.0 - hover_contraction) * math.sin(chi))
    rows = []
    for lab, (x, y, z) in surface.points().items():
        h = z - hz
        xc = hx - h * math.tan(chi) if (h > 0 and through > 0 and chi < math.pi / 2) else float("nan")
        dist = math.hypot(x - xc, y - hy) / rw if math.isfinite(xc) else float("inf")
        rows.append({"point": lab, "depth_m": h, "chi_deg": math.degrees(chi), "wake_center_x_m": xc,
                     "wake_radius_m": rw, "distance_over_rw": dist, "in_wake": bool(dist < 1.0)})
    return pd.DataFrame(rows)
