"""Attitude bandwidth / phase delay specs (ADS-33E-PRF hover and low speed, forward flight).

The metric is :func:`controllers.metrics.attitude_bandwidth` (ADS-33E-PRF
§3.2 definitions: w_BW,phase at -135 deg, w_BW,gain at +6 dB gain margin,
phase delay from the phase at 2 w_180).  Each chart is a
:class:`~controllers.hq.boundaries.LevelRegions` in the (w_BW [rad/s],
tau_p [s]) plane.

Provenance of the numbers (see also ``results/hq_spec_library``):

* ADS-33E-PRF §3.3.2.1, Fig. 3.3-1 draws three hover/low-speed pitch and roll
  charts (target acquisition and tracking; all other MTEs, UCE = 1 and fully
  attended; all other MTEs, UCE > 1 and/or divided attention) with sloped
  boundaries.  Their vertex values were not found printed in the sources
  searched for this library.  For roll, the toolkit's earlier rectangles are
  kept and labelled ``"approximate"``: target acquisition and tracking Level 1
  w_BW >= 2.5 rad/s with tau_p <= 0.12 s, Level 2 w_BW >= 1.5 rad/s with
  tau_p <= 0.20 s; all other MTEs (UCE = 1, fully attended) Level 1
  w_BW >= 2.0 rad/s with tau_p <= 0.20 s, Level 2 w_BW >= 1.0 rad/s with
  tau_p <= 0.30 s.  Pitch and the UCE > 1 / divided-attention chart: not found.
* Yaw (ADS-33E-PRF §3.3.5, heading bandwidth): Padfield, *Helicopter Flight
  Dynamics* (2nd ed.) §6, Fig. 6.64 (after ADS-33), quotes a Level 1 boundary
  at w_BW = 3.5 rad/s for target acquisition and tracking; the phase-delay
  limits and the Level 2 boundary were not found printed, so the chart is
  ``"not found"`` (the 3.5 rad/s is recorded in its source text).
* Forward flight (ADS-33E-PRF §3.4 pitch and roll bandwidth): not found.
"""
from __future__ import annotations


from .. import metrics as m
from .base import RegionSpec
from .boundaries import LevelRegions
from .limits import BANDWIDTH_LIMITS

__all__ = ["bandwidth_chart", "bandwidth_specs", "rectangle_regions", "BANDWIDTH_LIMITS"]

#: far corners that close the open chart regions (outside any plausible design)
_BW_FAR, _TAU_LOW = 100.0, -1.0
#: distance units of the bandwidth chart: 1 rad/s and 0.1 s
_SCALE = (1.0, 0.1)
_AXES = ("bandwidth w_BW [rad/s]", "phase delay tau_p [s]", _SCALE, ((0.0, 8.0), (0.0, 0.4)))
_TEST = "tests/test_hq_specs.py::test_bandwidth_chart_values"


_APPROX_SOURCE = ("ADS-33E-PRF §3.3.2.1 Fig. 3.3-1 ({chart}); the chart's sloped vertices were not found "
                  "printed: rectangle L1 w_BW >= {bw1:g} rad/s, tau_p <= {tau1:g} s; L2 w_BW >= {bw2:g} rad/s, "
                  "tau_p <= {tau2:g} s carried over from the toolkit's earlier (approximate) roll specs")
_NOT_FOUND = {
    "pitch": "ADS-33E-PRF §3.3.2.1 Fig. 3.3-1 ({chart}), pitch: boundary values not found printed",
    "roll": "ADS-33E-PRF §3.3.2.1 Fig. 3.3-1 ({chart}), roll: boundary values not found printed",
    "yaw": ("ADS-33E-PRF §3.3.5 heading bandwidth ({chart}): Padfield, Helicopter Flight Dynamics, Fig. 6.64 "
            "(after ADS-33) quotes Level 1 w_BW = 3.5 rad/s for target acquisition and tracking; phase-delay "
            "and Level 2 boundaries not found printed"),
}


def rectangle_regions(bw1, bw2, tau1, tau2):
    """Level regions ``w_BW >= bw1, tau_p <= tau1`` (Level 1) and ``w_BW >= bw2, tau_p <= tau2`` (Level 2).

    Parameters
    ----------
    bw1, bw2 : float
        Level 1/2 and Level 2/3 bandwidth boundaries [rad/s], ``bw1 >= bw2``.
    tau1, tau2 : float
        Level 1/2 and Level 2/3 phase-delay boundaries [s], ``tau1 <= tau2``.

    Returns
    -------
    LevelRegions

    Examples
    --------
    >>> r = rectangle_regions(2.0, 1.0, 0.20, 0.30)
    >>> r.level((3.0, 0.1)), r.level((1.5, 0.25)), r.level((0.5, 0.1))
    (1, 2, 3)
    """
    if not (bw1 >= bw2 > 0 and tau2 >= tau1):
        raise ValueError(f"rectangle_regions: need bw1 >= bw2 > 0 and tau2 >= tau1, got {bw1}, {bw2}, {tau1}, {tau2}")
    box = lambda bw, tau: [(bw, _TAU_LOW), (_BW_FAR, _TAU_LOW), (_BW_FAR, tau), (bw, tau)]
    return LevelRegions(box(bw1, tau1), box(bw2, tau2), _SCALE, _AXES[0], _AXES[1],
                        limits=((0.0, max(8.0, 3 * bw1)), (0.0, max(0.4, 1.5 * tau2))))


def _chart_name(mte, uce, attention):
    if mte == "target acquisition and tracking":
        return "target acquisition and tracking"
    if uce == 1 and attention == "fully attended":
        return "all other MTEs, UCE = 1, fully attended"
    return "all other MTEs, UCE > 1 and/or divided attention"


def bandwidth_chart(axis, mte="all other", uce=1, attention="fully attended"):
    """The hover/low-speed bandwidth chart for an axis and MTE class.

    Parameters
    ----------
    axis : {"pitch", "roll", "yaw"}
    mte : {"target acquisition and tracking", "all other"}
    uce : int
        Usable cue environment, 1 to 3.
    attention : {"fully attended", "divided"}

    Returns
    -------
    (LevelRegions or None, str, str)
        Regions (None when not found printed), the source text and the status
        (``"approximate"`` or ``"not found"``).

    Examples
    --------
    >>> regions, source, status = bandwidth_chart("roll", "target acquisition and tracking")
    >>> status, regions.level((3.0, 0.10))
    ('approximate', 1)
    """
    chart = _chart_name(mte, uce, attention)
    key = (axis, mte)
    if key in BANDWIDTH_LIMITS and (mte == "target acquisition and tracking" or chart.startswith("all other MTEs, UCE = 1")):
        bw1, bw2, tau1, tau2 = BANDWIDTH_LIMITS[key]
        return (rectangle_regions(bw1, bw2, tau1, tau2),
                _APPROX_SOURCE.format(chart=chart, bw1=bw1, bw2=bw2, tau1=tau1, tau2=tau2), "approximate")
    return None, _NOT_FOUND.get(axis, "not found").format(chart=chart), "not found"


def _attitude_of(obj):
    return obj.attitude_response() if callable(getattr(obj, "attitude_response", None)) else obj


def _bandwidth_metric(response_type):
    def metric(sys):
        bw, tau, *_ = m.attitude_bandwidth(sys, response_type=response_type)
        return bw, tau
    return metric


def bandwidth_specs(response_type="attitude"):
    """Every bandwidth/phase-delay spec of the library (hover charts and forward flight).

    Parameters
    ----------
    response_type : {"attitude", "rate"}
        ADS-33E-PRF §3.2: attitude-command response types use w_BW,phase alone,
        rate response types the smaller of w_BW,phase and w_BW,gain.

    Returns
    -------
    list of RegionSpec

    Examples
    --------
    >>> [s.name for s in bandwidth_specs()][:2]
    ['BnwAtH1.pitch', 'BnwAtH1.pitch']
    """
    specs = []
    both = ("fully attended", "divided")
    # (MTE class, UCEs, attentions, excluded (UCE, attention) pairs, a (UCE, attention) that selects the chart)
    charts = [("target acquisition and tracking", (1, 2, 3), both, (), (1, "fully attended")),
              ("all other", (1,), ("fully attended",), (), (1, "fully attended")),
              ("all other", (1, 2, 3), both, ((1, "fully attended"),), (2, "divided"))]
    for axis in ("pitch", "roll", "yaw"):
        for mte, uces, attentions, excluded, (uce, attention) in charts:
            regions, source, status = bandwidth_chart(axis, mte, uce, attention)
            word = "heading" if axis == "yaw" else f"{axis} attitude"
            specs.append(RegionSpec(
                f"BnwAtH1.{axis}", f"{word} bandwidth and phase delay, hover/low speed "
                f"({_chart_name(mte, uce, attention)})",
                _bandwidth_metric(response_type), "min", kind="soft", units="rad/s", source=source,
                family="bandwidth", axis=axis, mtes=(mte,), uces=uces, attentions=attentions, excluded=excluded,
                speeds=("hover",), response=_attitude_of, status=status, test=_TEST, regions=regions,
                undefined=(m.BandwidthUndefinedError,), chart_axes=_AXES))
    for axis in ("pitch", "roll"):
        specs.append(RegionSpec(
            f"BnwAtF1.{axis}", f"{axis} attitude bandwidth and phase delay, forward flight",
            _bandwidth_metric(response_type), "min", kind="soft", units="rad/s",
            source=f"ADS-33E-PRF §3.4 forward-flight {axis} bandwidth chart: boundary values not found printed",
            family="bandwidth", axis=axis, speeds=("forward",), response=_attitude_of, status="not found",
            test=_TEST, undefined=(m.BandwidthUndefinedError,), chart_axes=_AXES))
    return specs
