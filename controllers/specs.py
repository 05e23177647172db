"""Specs of Table 7.3 (roll axis, hover) as objects wrapping plain metrics.

A spec maps an :class:`~controllers.emf.EMFDesign` to a value, a level (1/2/3)
and a normalised margin (>= 0: Level 1 met; -1: on the Level 2/3 boundary).
A spec set is a plain list: users add their own :class:`Spec`.  A spec that
can steer the design-margin optimiser carries its smooth NLP form in ``smooth``
(:mod:`controllers.smooth`), built from the spec's own boundary: the DMO's NLP
is assembled from the list, so adding such a spec is all it takes.

Boundary sources (numbers the dissertation does not print are taken from the
literature and marked as approximations where the source is a chart):
* GM >= 6 dB, PM >= 45 deg (Level 1): MIL-DTL-9490E / SAE AS94900, as in
  Table 7.3 StbMgG1; Level 2 4.5 dB / 35 deg (CONDUIT StbMgG1 default).
* Nichols margin: elliptical approximation of CONDUIT NicMgG1 (see
  :func:`controllers.metrics.nichols_margin`).
* Disturbance rejection bandwidth >= 0.9 rad/s (roll, Level 1) and peak <= 5 dB:
  dissertation §7.5 and Table 7.3 (ADS-33E-PRF §3.2.9 / Tischler et al. 2017);
  Level 2 boundaries 0.5 rad/s and 7 dB approximate CONDUIT's DrbRoH1/DrpAvH1.
* Damping: zeta >= 0.35 (0.5-4 rad/s) and >= 0.1 (4-20 rad/s), Table 7.3;
  Level 2 0.15 / 0.02 approximate CONDUIT's EigDpG1.
* Attitude bandwidth/phase delay, hover roll (ADS-33E-PRF Fig. 3.3-1): Level 1
  w_BW >= 2.5 rad/s (target acquisition and tracking) or 2.0 rad/s (all other
  MTEs) with tau_p <= 0.12 s (tracking) or 0.20 s (all other MTEs); Level 2
  w_BW >= 1.5 / 1.0 rad/s, tau_p <= 0.20 / 0.30 s.  These rectangles
  approximate the published charts' Level boundaries: check them against
  ADS-33E-PRF before relying on a marginal result.
* Minimum crossover: Level 1 boundary set by the DMO (CrsMnG2), Level 2 at 80 %.
* Open-loop onset point: Duda (1997); the Nichols-chart boundary is approximated
  by a line (see ``_olop_margin``), check it against the published chart.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Optional

import numpy as np
import pandas as pd

from . import metrics as m
from .actuator_limits import ActuatorLimits, olop_margin
from .smooth import (CrossoverMinimum, DisturbanceBandwidthFloor, DisturbancePeakLimit, GainMarginPastCritical,
                     NicholsEllipse, PhaseMarginBand, SmoothConstraint)

__all__ = ["Spec", "BandwidthSpec", "SpecEvaluationError", "default_specs", "evaluate_specs",
           "spec_by_name", "UNSTABLE_NOTE"]

#: status of a frequency-domain spec on a closed loop that is not stable
UNSTABLE_NOTE = "n/a: closed loop unstable"


class SpecEvaluationError(ValueError):
    """A spec could not be evaluated (non-finite response, bad value): names the spec."""


@dataclass
class Spec:
    """A scalar spec: ``direction='min'`` means value >= boundary is good.

    ``kind`` is ``"hard"`` (must be met: stability), ``"soft"`` (Level 1
    wanted) or ``"objective"`` (minimised, no boundary).  ``smooth`` is the
    spec's smooth form for the DMO's NLP (:mod:`controllers.smooth`), built
    from this spec's own boundary; None when the spec is honoured only by
    scoring candidates on the true metric.
    """

    name: str
    description: str
    metric: Callable
    direction: str
    level1: float = np.nan
    level2: float = np.nan
    kind: str = "soft"
    units: str = ""
    source: str = ""
    #: frequency-domain specs read "not applicable" (never met) on an unstable loop
    needs_stable: bool = True
    #: smooth NLP constraint of this spec's Level 1 boundary (None: true metric only)
    smooth: Optional[SmoothConstraint] = None

    def __post_init__(self):
        if self.smooth is not None and not isinstance(self.smooth, SmoothConstraint):
            raise TypeError(f"spec {self.name!r}: smooth must be a SmoothConstraint, got {type(self.smooth).__name__}")
        if self.direction not in ("min", "max"):
            raise ValueError(f"spec {self.name!r}: direction must be 'min' or 'max', got {self.direction!r}")
        if self.kind not in ("hard", "soft", "objective"):
            raise ValueError(f"spec {self.name!r}: kind must be 'hard', 'soft' or 'objective', got {self.kind!r}")
        if self.kind != "objective" and not (np.isfinite(self.level1) and np.isfinite(self.level2)):
            raise ValueError(f"spec {self.name!r}: Level 1/2 boundaries must be finite, got "
                             f"{self.level1}, {self.level2}")

    def value(self, design):
        return float(self.metric(design))

    def evaluate(self, design):
        v = self.value(design)
        if self.kind == "objective":
            return {"value": v, "level": np.nan, "margin": np.nan}
        span = abs(self.level1 - self.level2) or max(abs(self.level1), 1.0)
        sign = 1.0 if self.direction == "min" else -1.0
        if np.isnan(v):
            return {"value": v, "level": 3, "margin": -np.inf}
        margin = sign * (v - self.level1) / span
        level = 1 if margin >= 0 else (2 if sign * (v - self.level2) >= 0 else 3)
        return {"value": v, "level": level, "margin": float(margin)}


@dataclass
class BandwidthSpec(Spec):
    """ADS-33E attitude bandwidth (rad/s) and phase delay (s), a 2-D spec."""

    tau1: float = 0.12
    tau2: float = 0.20

    def value(self, design):
        bw, tau, *_ = m.attitude_bandwidth(design.attitude_response())
        return bw, tau

    def evaluate(self, design):
        try:
            bw, tau = self.value(design)
        except m.BandwidthUndefinedError:
            return {"value": np.nan, "level": 3, "margin": -np.inf}
        m_bw = (bw - self.level1) / (self.level1 - self.level2)
        m_tau = (self.tau1 - tau) / (self.tau2 - self.tau1)
        margin = min(m_bw, m_tau)
        if margin >= 0:
            level = 1
        elif bw >= self.level2 and tau <= self.tau2:
            level = 2
        else:
            level = 3
        return {"value": bw, "level": level, "margin": float(margin), "phase_delay": tau}


def _olop_margin(design, stick_amplitude=1.0, rate_limit=1.0):
    """Signed distance [dB] of the OLOP below an approximate Level 1 boundary.

    Boundary: an approximation of Duda's (1997) OLOP Level 1/2 line on the
    Nichols chart, taken as gain <= -2 dB at -180 deg rising linearly to
    +10 dB at -120 deg (and unbounded above -120 deg, where rate limiting is
    benign).  Stick amplitude and rate limit are in mixer units; defaults are
    placeholders a user sets for the aircraft (see default_specs).
    """
    phase, gain, w_on = m.open_loop_onset_point(design.broken_loop(), design.mixer_response_pilot(),
                                                stick_amplitude, rate_limit)
    if not np.isfinite(w_on):
        return 20.0   # the rate limit is never reached: far inside Level 1
    return float(m.duda_olop_limit(phase) - gain)


def _max_real_pole(design):
    return float(np.max(design.closed_loop_poles().real))


def default_specs(crossover_min=2.0, drb_min=0.9, mte="all other", olop_stick=0.05, olop_rate=1.0, limits=None):
    """The roll-axis spec set of Table 7.3 (see module docstring for sources).

    ``mte`` names the ADS-33E-PRF MTE class of the bandwidth chart, exactly
    and case-insensitively: ``"target acquisition and tracking"`` or
    ``"all other"`` (alias ``"all other MTEs"``); any other name raises
    :class:`ValueError` listing the valid ones.  The bandwidth boundaries come
    from :data:`controllers.hq.limits.BANDWIDTH_LIMITS`.

    ``olop_stick`` [stick units] and ``olop_rate`` [mixer units/s] set the
    open-loop-onset-point check (full-stick sinusoid against the actuator rate
    limit); the defaults are placeholders for the hand-written and coaxial plants.
    ``limits`` (:class:`~controllers.actuator_limits.ActuatorLimits`) replaces them
    with the aircraft's actuator rate and travel limits and its full-stick
    amplitude: the OLOP is then graded by
    :func:`~controllers.actuator_limits.olop_margin` (``+inf`` when the rate
    limit cannot be reached, no fixed margin) and ``olop_stick``/``olop_rate``
    are not used.

    Examples
    --------
    >>> from controllers.actuator_limits import ActuatorLimits
    >>> lim = ActuatorLimits(rate_limit=0.7, position_limit=0.14, stick_amplitude=10.0)
    >>> [s.source for s in default_specs(limits=lim) if s.name == "OlpOpG1"][0][:9]
    'Duda 1997'
    """
    from .hq.limits import BANDWIDTH_LIMITS, canonical_mte   # one definition; unknown MTE names raise

    nichols = NicholsEllipse(phase_axis=45.0, gain_axis=6.0)     # one definition: metric and NLP
    # the smallest gain change, up or down, that makes the loop critical: a loop around an
    # unstable plant is conditionally stable, and its reduction margin is the one that counts
    gm = lambda d: abs(m.gain_phase_margins(d.broken_loop())[0])
    pm = lambda d: m.gain_phase_margins(d.broken_loop())[1]
    mte = canonical_mte(mte)
    if limits is None:
        olop = lambda d: _olop_margin(d, olop_stick, olop_rate)      # the placeholder check, unchanged
    elif isinstance(limits, ActuatorLimits):
        olop = lambda d: olop_margin(d.broken_loop(), d.mixer_response_pilot(), limits.stick_amplitude, limits)
    else:
        raise TypeError(f"default_specs: limits must be ActuatorLimits or None, got {type(limits).__name__}")
    bw1, bw2, tau1, tau2 = BANDWIDTH_LIMITS[("roll", mte)]
    return [
        Spec("EigLcG1", "all eigenvalues in the left half plane", _max_real_pole, "max", 0.0, 0.0,
             kind="hard", units="1/s", source="generic", needs_stable=False),
        Spec("NicMgG1", "Nichols margin, loop broken at mixer input",
             lambda d: m.nichols_margin(d.broken_loop(), phase_axis=nichols.phase_axis,
                                        gain_axis=nichols.gain_axis), "min", 0.0, -0.25, kind="hard",
             source="CONDUIT NicMgG1 (elliptical approximation)", smooth=nichols),
        Spec("StbMgG1.GM", "gain margin (rise or fall), loop broken at mixer input", gm, "min", 6.0, 4.5,
             kind="hard", units="dB", source="MIL-DTL-9490E", smooth=GainMarginPastCritical()),
        Spec("StbMgG1.PM", "phase margin, loop broken at mixer input", pm, "min", 45.0, 35.0,
             kind="hard", units="deg", source="MIL-DTL-9490E", smooth=PhaseMarginBand()),
        BandwidthSpec("BnwAtH1", f"roll attitude bandwidth ({mte} MTEs)", None, "min", bw1, bw2,
                      kind="soft", units="rad/s", source="ADS-33E-PRF Fig. 3.3-1 (approx.)",
                      tau1=tau1, tau2=tau2),
        Spec("DrbRoH1", "roll attitude disturbance rejection bandwidth",
             lambda d: m.disturbance_rejection_bandwidth(d.disturbance_response()), "min", drb_min,
             min(0.5, 0.55 * drb_min), kind="soft", units="rad/s", source="ADS-33E-PRF §3.2.9; Table 7.3",
             smooth=DisturbanceBandwidthFloor()),
        Spec("DrpAvH1", "disturbance rejection peak",
             lambda d: m.disturbance_rejection_peak(d.disturbance_response()), "max", 5.0, 7.0,
             kind="soft", units="dB", source="Table 7.3; Tischler et al. 2017", smooth=DisturbancePeakLimit()),
        Spec("EigDpG1.hi", "damping ratio, 4-20 rad/s",
             lambda d: m.damping_in_band(d.closed_loop_poles(), 4.0, 20.0), "min", 0.1, 0.02,
             kind="soft", source="Table 7.3", needs_stable=False),
        Spec("EigDpG1.lo", "damping ratio, 0.5-4 rad/s",
             lambda d: m.damping_in_band(d.closed_loop_poles(), 0.5, 4.0), "min", 0.35, 0.15,
             kind="soft", source="Table 7.3; ADS-33E-PRF", needs_stable=False),
        Spec("OlpOpG1", "open-loop onset point, pilot input (dB below the approximate boundary)",
             olop, "min", 0.0, -6.0, kind="soft", units="dB",
             source="Duda 1997 OLOP criterion (approximate boundary)" + (
                 "" if limits is None else f"; actuator limits {limits.rate_limit:.4g}/s, travel "
                                           f"{limits.position_limit:.4g}, stick {limits.stick_amplitude:.4g}")),
        Spec("CrsMnG2", "minimum crossover frequency", lambda d: m.crossover_frequency(d.broken_loop()),
             "min", crossover_min, 0.8 * crossover_min, kind="soft", units="rad/s", source="generic",
             smooth=CrossoverMinimum()),
        Spec("CrsLnG1", "crossover frequency (minimised)", lambda d: m.crossover_frequency(d.broken_loop()),
             "max", kind="objective", units="rad/s", source="generic"),
        Spec("RmsAcG1.pilot", "mixer-input RMS, pilot input",
             lambda d: m.rms_response(d.mixer_response_pilot()), "max", kind="objective", source="generic"),
        Spec("RmsAcG1.dist", "mixer-input RMS, disturbance input",
             lambda d: m.rms_response(d.mixer_response_disturbance()), "max", kind="objective", source="generic"),
    ]


def spec_by_name(specs, name):
    """The spec called ``name`` in the list ``specs`` (KeyError naming the choices)."""
    for s in specs:
        if s.name == name:
            return s
    raise KeyError(f"no spec named {name!r}; available: {[s.name for s in specs]}")


def _is_stable(design):
    return float(np.max(design.closed_loop_poles().real)) <= 0.0


def evaluate_specs(design, specs=None, stop_at_first_unmet=False) -> pd.DataFrame:
    """Evaluate every spec on ``design``: one row per spec.

    Parameters
    ----------
    design : EMFDesign
    specs : list of Spec, optional
        Default :func:`default_specs`.
    stop_at_first_unmet : bool
        Return after the first unmet hard/soft spec (a search screening many
        candidates needs only to know that one fails); the table then has
        fewer rows.

    Returns
    -------
    pandas.DataFrame
        Columns: spec, description, kind, value, units, level, margin (CONDUIT's
        normalised design margin: 0 on the Level 1 boundary, -1 on the Level 2/3
        boundary, > 0 inside Level 1), met (hard/soft: Level 1 reached),
        status, source, phase_delay.  On a closed loop that is not stable the
        frequency-domain specs (``needs_stable``) are not evaluated: value NaN,
        level 3, margin -inf, met False, status :data:`UNSTABLE_NOTE`.

    Raises
    ------
    SpecEvaluationError
        A response is NaN/inf at some frequency, or a spec returns NaN where a
        number is required (the spec and the frequency are named).
    """
    specs = default_specs() if specs is None else list(specs)
    for s in specs:
        if not isinstance(s, Spec):
            raise TypeError(f"specs must be Spec objects, got {type(s).__name__}")
    try:
        stable = _is_stable(design)
    except np.linalg.LinAlgError as exc:
        raise SpecEvaluationError(f"closed-loop poles could not be computed: {exc}") from exc
    rows = []
    for s in specs:
        if s.needs_stable and not stable:
            r = {"value": np.nan, "level": 3, "margin": -np.inf}
            status = UNSTABLE_NOTE if s.kind != "objective" else UNSTABLE_NOTE
            met = False if s.kind != "objective" else True
        else:
            try:
                r = s.evaluate(design)
            except m.NonFiniteResponseError as exc:
                raise SpecEvaluationError(f"spec {s.name!r} ({s.description}): {exc}") from exc
            met = bool(r["margin"] >= 0) if s.kind != "objective" else True
            status = "objective" if s.kind == "objective" else ("met" if met else "not met")
        rows.append({"spec": s.name, "description": s.description, "kind": s.kind,
                     "value": r["value"], "units": s.units, "level": r["level"],
                     "margin": r["margin"], "met": met, "status": status,
                     "source": s.source, "phase_delay": r.get("phase_delay", np.nan)})
        if stop_at_first_unmet and not met:
            break
    return pd.DataFrame(rows)
