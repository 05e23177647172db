"""CONDUIT generic specs (Table 7.3): stability, margins, crossover, DRB/DRP, damping, OLOP, RMS, ModFoG2.

The Table 7.3 roll-axis set of :func:`controllers.specs.default_specs` is the
single definition of these boundaries; :func:`generic_specs` re-labels its
specs as :class:`~controllers.hq.base.HQSpec` (family, axis, provenance)
without changing a number, and adds:

* ``OlpOpG1.pilot`` / ``OlpOpG1.dist``: the open-loop onset point with the
  aircraft's actuator rate **and position** limits (:class:`ActuatorLimits`,
  no placeholder defaults); when the rate limit is never reached the value is
  ``+inf`` (not a fixed margin).  The Level 1 boundary is the approximate
  Duda (1997) line described in :mod:`controllers.specs` (-2 dB at -180 deg rising to
  +10 dB at -120 deg); the printed chart's values were not found.
* Disturbance-rejection bandwidth per axis: roll 0.9 rad/s (dissertation
  §7.5.1: "the current criteria for the roll axis, which is w_DRB = 0.9
  rad/sec", citing CONDUIT); pitch, yaw and heave values not found printed.
* ``ModFoG2``: model-following cost, the CIFER cost J of dissertation
  Eq. 3.13 between the closed-loop and the commanded (delayed command model)
  attitude responses, 20 log-spaced points over 1-10 rad/s (W_g = 1,
  W_p = 0.01745, coherence 1 so W_gamma = 0.998).  CONDUIT's ModFoG2 Level
  boundaries were not found printed: the spec is an objective.
"""
from __future__ import annotations

from dataclasses import fields

import numpy as np

from .. import metrics as m
from ..actuator_limits import ActuatorLimits, olop_margin
from ..metrics import duda_olop_limit
from ..specs import Spec, default_specs
from .base import HQSpec

__all__ = ["ActuatorLimits", "olop_margin", "model_following_cost", "generic_specs", "duda_olop_limit"]

_TEST = "tests/test_hq_specs.py::test_generic_specs_match_table_7_3"
_TEST_OLOP = "tests/test_hq_specs.py::test_olop_with_actuator_limits"
_TEST_MF = "tests/test_hq_specs.py::test_model_following_cost"

_PROVENANCE = {
    "EigLcG1": ("printed", "stability: every closed-loop eigenvalue in the left half plane (Table 7.3)"),
    "NicMgG1": ("approximate", "the elliptical exclusion zone approximates CONDUIT NicMgG1; chart not found printed"),
    "StbMgG1.GM": ("approximate", "Level 1 6 dB (MIL-DTL-9490E, Table 7.3); Level 2 4.5 dB carried over from the "
                                  "toolkit's earlier specs (CONDUIT default, not found printed)"),
    "StbMgG1.PM": ("approximate", "Level 1 45 deg (MIL-DTL-9490E, Table 7.3); Level 2 35 deg carried over from "
                                  "the toolkit's earlier specs (CONDUIT default, not found printed)"),
    "DrbRoH1": ("approximate", "Level 1 0.9 rad/s (dissertation §7.5.1, citing CONDUIT); Level 2 carried over "
                               "from the toolkit's earlier specs (not found printed)"),
    "DrpAvH1": ("approximate", "5 dB / 7 dB carried over from the toolkit's earlier specs (not found printed in "
                               "the sources searched)"),
    "EigDpG1.hi": ("approximate", "Level 1 zeta >= 0.1 for 4-20 rad/s (Table 7.3); Level 2 carried over (not "
                                  "found printed)"),
    "EigDpG1.lo": ("approximate", "Level 1 zeta >= 0.35 for 0.5-4 rad/s (Table 7.3); Level 2 carried over (not "
                                  "found printed)"),
    "CrsMnG2": ("design", "boundary set by the DMO (design parameter), Level 2 at 80 %"),
    "CrsLnG1": ("objective", "objective"),
    "RmsAcG1.pilot": ("objective", "objective"),
    "RmsAcG1.dist": ("objective", "objective"),
}


def model_following_cost(response, command, fit_range=(1.0, 10.0), n_points=20):
    """Model-following cost J (dissertation Eq. 3.13) between a response and its command model.

    Parameters
    ----------
    response, command : LTI, FrequencyFunction or callable H(s)
        Closed-loop response and the commanded response (e.g. the delayed command model).
    fit_range : (float, float)
        Frequency range [rad/s].
    n_points : int
        Log-spaced frequency points.

    Returns
    -------
    float
        J (0 for perfect following; gains in dB, phases in deg, W_p = 0.01745).

    Examples
    --------
    >>> import control
    >>> round(model_following_cost(control.tf([4.0], [1, 4.0]), control.tf([4.0], [1, 4.0])), 12)
    0.0
    """
    from flightid.fitting import cifer_cost
    lo, hi = fit_range
    if not (0 < lo < hi and np.isfinite(hi)) or int(n_points) < 2:
        raise ValueError(f"model_following_cost: need 0 < fit_range[0] < fit_range[1] and n_points >= 2, "
                         f"got {fit_range}, {n_points}")
    w = np.geomspace(lo, hi, int(n_points))
    _, h = m.frequency_response_of(response, w)
    _, hc = m.frequency_response_of(command, w)
    return cifer_cost(h, hc, np.ones_like(w))


def _disturbance_bandwidth(design):
    return m.disturbance_rejection_bandwidth(design.disturbance_response())


def _relabel(spec, **meta):
    base = {f.name: getattr(spec, f.name) for f in fields(Spec)}
    return HQSpec(**{**base, **meta})


def generic_specs(limits=None, crossover_min=2.0, drb_min=0.9):
    """The CONDUIT generic specs of the library (roll-axis numbers of Table 7.3 unless noted).

    Parameters
    ----------
    limits : ActuatorLimits, optional
        Actuator limits for the OLOP specs; without them the OLOP specs are
        returned not :attr:`~controllers.hq.base.HQSpec.available` (their
        ``missing_input`` names what they need).
    crossover_min : float
        CrsMnG2 Level 1 boundary [rad/s] (a DMO design parameter).
    drb_min : float
        Roll DRB Level 1 boundary [rad/s].

    Returns
    -------
    list of HQSpec

    Examples
    --------
    >>> [s.name for s in generic_specs()][:3]
    ['EigLcG1', 'NicMgG1', 'StbMgG1.GM']
    """
    out = []
    for s in default_specs(crossover_min, drb_min):
        if s.name not in _PROVENANCE:
            continue   # bandwidth: family "bandwidth"; OlpOpG1: replaced below
        status, note = _PROVENANCE[s.name]
        out.append(_relabel(s, family="generic", axis="roll" if s.name == "DrbRoH1" else "any",
                            status=status, test=_TEST, source=f"{s.source}; {note}"))
    for axis, name in (("pitch", "DrbPiH1"), ("yaw", "DrbYaH1"), ("heave", "DrbHeH1")):
        out.append(HQSpec(name, f"{axis} disturbance rejection bandwidth", _disturbance_bandwidth, "min",
                          units="rad/s", source=f"CONDUIT {name} / ADS-33E-PRF: {axis} DRB boundary not found printed",
                          family="generic", axis=axis, status="not found", test=_TEST))
    amplitude = {"pilot": None if limits is None else limits.stick_amplitude,
                 "dist": None if limits is None else limits.disturbance_amplitude}
    for kind, method in (("pilot", "mixer_response_pilot"), ("dist", "mixer_response_disturbance")):
        a = amplitude[kind]
        have = a is not None and np.isfinite(a)
        metric = (lambda d, method=method, a=a: olop_margin(d.broken_loop(), getattr(d, method)(), a, limits))
        out.append(HQSpec(f"OlpOpG1.{kind}", f"open-loop onset point, {kind} input, actuator rate/position limits "
                          "(dB below the approximate Level 1 line)", metric, "min", 0.0, -6.0, units="dB",
                          source="Duda 1997 OLOP criterion (CONDUIT OlpOpG1); approximate Level 1 line, chart not "
                                 "found printed; Level 2 at -6 dB carried over from the toolkit's earlier specs",
                          family="generic", axis="any", status="approximate", test=_TEST_OLOP,
                          missing_input="" if have else f"ActuatorLimits (rate/position limits and the {kind} "
                                                        "input amplitude)"))
    out.append(HQSpec("ModFoG2", "model-following cost J, closed-loop vs commanded attitude, 1-10 rad/s",
                      lambda d: model_following_cost(d.attitude_response(), d.commanded_attitude()), "max",
                      kind="objective", units="-",
                      source="CONDUIT ModFoG2 (Table 7.3): cost of dissertation Eq. 3.13; Level boundaries not found "
                             "printed, used as an objective", family="generic", axis="any", status="objective",
                      test=_TEST_MF))
    return out
