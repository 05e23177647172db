"""Forward-flight specs: mid-term pitch (phugoid), lateral-directional oscillation, spiral.

Metrics read the modes off the poles of an LTI object (or a pole array):
:func:`oscillatory_mode` returns the damping ratio and natural frequency of
the least-damped complex pair in a frequency band, :func:`time_to_double`
the time to double amplitude of the slowest real mode (the spiral).

Provenance.  ADS-33E-PRF §3.4 draws the forward-flight pitch and roll
bandwidth, the mid-term (phugoid) damping and the lateral-directional
oscillation charts; their values were not found printed in the sources
searched.  The lateral-directional oscillation and spiral specs therefore carry
the fixed-wing MIL-F-8785C limits as a clearly labelled proxy, as printed in
Nelson, *Flight Stability and Automatic Control*, Tables 10.2 and 10.3
(reproduced by heli-air.net, "Lateral directional flying qualities"):
dutch roll, Category A, Class I/IV: Level 1 zeta >= 0.19, zeta w_n >= 0.35
rad/s, w_n >= 1.0 rad/s; Level 2 zeta >= 0.02, zeta w_n >= 0.05 rad/s,
w_n >= 0.4 rad/s.  Spiral, Category B/C (Class I/IV): minimum time to double
amplitude Level 1 20 s, Level 2 12 s, Level 3 4 s.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import control
import numpy as np

from .base import HQSpec, _source_text

__all__ = ["oscillatory_mode", "time_to_double", "DampingFrequencySpec", "forward_flight_specs",
           "DUTCH_ROLL_MIL_F_8785C"]

_TEST_LDO = "tests/test_hq_specs.py::test_dutch_roll_and_spiral_from_poles"

#: MIL-F-8785C dutch roll, Category A, Class I/IV: {quantity: (Level 1, Level 2)}
DUTCH_ROLL_MIL_F_8785C = {"zeta": (0.19, 0.02), "sigma": (0.35, 0.05), "wn": (1.0, 0.4)}


def _poles(sys_or_poles):
    if isinstance(sys_or_poles, control.LTI):
        return np.asarray(control.poles(sys_or_poles), dtype=complex)
    p = np.atleast_1d(np.asarray(sys_or_poles, dtype=complex))
    if p.ndim != 1 or not np.all(np.isfinite(p)):
        raise ValueError("poles must be a 1-D array of finite complex numbers")
    return p


def oscillatory_mode(sys_or_poles, w_min=0.0, w_max=np.inf):
    """Damping ratio and natural frequency [rad/s] of the least-damped complex pair in a band.

    Parameters
    ----------
    sys_or_poles : control.LTI or array of complex
        System or its poles [rad/s].
    w_min, w_max : float
        Band of natural frequencies searched [rad/s].

    Returns
    -------
    (float, float)
        ``(zeta, w_n)``; ``(nan, nan)`` when no complex pair lies in the band.

    Examples
    --------
    >>> zeta, wn = oscillatory_mode([-0.3 + 1.2j, -0.3 - 1.2j, -4.0])
    >>> round(zeta, 4), round(wn, 4)
    (0.2425, 1.2369)
    """
    p = _poles(sys_or_poles)
    wn = np.abs(p)
    sel = (np.abs(p.imag) > 1e-9 * np.maximum(wn, 1.0)) & (wn >= w_min) & (wn <= w_max)
    if not sel.any():
        return float("nan"), float("nan")
    zeta = -p[sel].real / wn[sel]
    k = int(np.argmin(zeta))
    return float(zeta[k]), float(wn[sel][k])


def time_to_double(sys_or_poles):
    """Time to double amplitude [s] of the slowest real mode (spiral); ``inf`` if it is stable.

    Parameters
    ----------
    sys_or_poles : control.LTI or array of complex
        System or its poles [rad/s].

    Returns
    -------
    float
        ``ln 2 / lambda`` for the real pole of smallest magnitude, ``lambda > 0``;
        ``inf`` when that pole is stable (it never doubles).

    Examples
    --------
    >>> round(time_to_double([-2.0, 0.05, -0.5 + 1j, -0.5 - 1j]), 3)
    13.863
    """
    p = _poles(sys_or_poles)
    real = p[np.abs(p.imag) <= 1e-9 * np.maximum(np.abs(p), 1.0)].real
    if not real.size:
        raise ValueError("time_to_double: no real pole (no spiral mode) among the poles")
    lam = real[int(np.argmin(np.abs(real)))]
    return float(np.log(2.0) / lam) if lam > 0 else float("inf")


@dataclass
class DampingFrequencySpec(HQSpec):
    """A mode spec with several simultaneous boundaries on zeta, zeta*w_n and w_n.

    ``limits`` maps ``"zeta"``, ``"sigma"`` (= zeta w_n [rad/s]) and ``"wn"``
    [rad/s] to ``(Level 1, Level 2)`` lower bounds; ``metric`` returns
    ``(zeta, w_n)``.  The level is the worst over the bounds; the margin is
    the smallest of ``(v - L1) / (L1 - L2)`` (0 on a Level 1 boundary, -1 on a
    Level 2 boundary).  ``value`` reports zeta; ``"wn"`` is returned as well.
    """

    limits: dict = field(default_factory=dict)

    def __post_init__(self):
        if self.status not in ("not found",):
            for k, (b1, b2) in self.limits.items():
                if k not in ("zeta", "sigma", "wn") or not (np.isfinite(b1) and np.isfinite(b2) and b1 > b2):
                    raise ValueError(f"spec {self.name!r}: bad limit {k!r}: {(b1, b2)}")
        # the table's level1/level2: the damping-ratio bounds, else the first bound given
        key = "zeta" if "zeta" in self.limits else next(iter(self.limits), None)
        self.level1, self.level2 = self.limits[key] if key is not None else (np.nan, np.nan)
        super().__post_init__()

    def with_boundaries(self, limits, *, source):
        """A copy of the spec graded against bounds the caller supplies.

        Parameters
        ----------
        limits : mapping
            ``"zeta"`` [-], ``"sigma"`` (zeta w_n) [rad/s] and/or ``"wn"`` [rad/s] ->
            ``(Level 1, Level 2)`` lower bounds, Level 1 the higher.
        source : str
            Where the values come from (document, paragraph, figure).

        Returns
        -------
        DampingFrequencySpec
            ``status`` ``"supplied"``.

        Raises
        ------
        ValueError
            An empty ``source`` or ``limits``, an unknown key, or a pair that is
            not two finite numbers with Level 1 above Level 2.

        Examples
        --------
        >>> ldo = [s for s in forward_flight_specs() if s.name == "LatDirOscF.ADS-33"][0]
        >>> mine = ldo.with_boundaries({"zeta": (0.2, 0.05)}, source="my reading of the chart")
        >>> mine.evaluate([complex(-0.3, 1.0), complex(-0.3, -1.0)])["level"]
        1
        """
        text = _source_text(self.name, source)
        if not isinstance(limits, Mapping) or not limits:
            raise ValueError(f"spec {self.name!r}: limits must be a non-empty mapping of 'zeta', 'sigma' and/or "
                             f"'wn' -> (Level 1, Level 2), got {limits!r}")
        pairs = {}
        for k, v in limits.items():
            try:
                pairs[k] = tuple(float(b) for b in v)
            except (TypeError, ValueError):
                raise ValueError(f"spec {self.name!r}: limits[{k!r}] must be (Level 1, Level 2), got {v!r}") from None
            if len(pairs[k]) != 2:
                raise ValueError(f"spec {self.name!r}: limits[{k!r}] must be (Level 1, Level 2), got {v!r}")
        return replace(self, limits=pairs, status="supplied", source=f"{text} (supplied; library entry: {self.source})")

    def value(self, design):
        zeta, wn = self.metric(self._input(design))
        return float(zeta), float(wn)

    def boundary_text(self):
        if self.status == "not found":
            return "not found printed"
        names = {"zeta": "zeta", "sigma": "zeta*w_n [rad/s]", "wn": "w_n [rad/s]"}
        return "; ".join(f"{names[k]}: L1 >= {b1:g}, L2 >= {b2:g}" for k, (b1, b2) in self.limits.items())

    def evaluate(self, design):
        if self.status == "not found":
            raise self._unpublished()
        zeta, wn = self.value(design)
        if not (np.isfinite(zeta) and np.isfinite(wn)):
            return {"value": zeta, "wn": wn, "level": 3, "margin": -np.inf}
        v = {"zeta": zeta, "sigma": zeta * wn, "wn": wn}
        margins = [(v[k] - b1) / (b1 - b2) for k, (b1, b2) in self.limits.items()]
        margin = float(min(margins))
        level = 1 if margin >= 0 else (2 if margin >= -1 else 3)
        return {"value": zeta, "wn": wn, "level": level, "margin": margin}


def _ldo_metric(sys_or_poles):
    return oscillatory_mode(sys_or_poles, 0.1, 10.0)


def _phugoid_metric(sys_or_poles):
    return oscillatory_mode(sys_or_poles, 0.0, 1.0)


def forward_flight_specs():
    """Forward-flight specs: lateral-directional oscillation, spiral, mid-term pitch.

    Returns
    -------
    list of HQSpec
        Metric input: an LTI object or its poles.

    Examples
    --------
    >>> [s.name for s in forward_flight_specs()]
    ['LatDirOscF.MIL-F-8785C', 'LatDirOscF.ADS-33', 'SpiralF.MIL-F-8785C', 'PhugoidF.pitch']
    """
    proxy = ("fixed-wing proxy: ADS-33E-PRF §3.4 value not found printed; MIL-F-8785C limits as printed in "
             "Nelson, Flight Stability and Automatic Control, Table {table} (heli-air.net, 'Lateral directional "
             "flying qualities')")
    return [
        DampingFrequencySpec("LatDirOscF.MIL-F-8785C", "dutch roll damping and frequency (forward flight)",
                             _ldo_metric, "min", units="-", source="MIL-F-8785C Category A, Class I/IV; "
                             + proxy.format(table="10.2"), family="forward_flight", axis="yaw", speeds=("forward",),
                             status="printed", test=_TEST_LDO, limits=dict(DUTCH_ROLL_MIL_F_8785C)),
        DampingFrequencySpec("LatDirOscF.ADS-33", "lateral-directional oscillation (forward flight)",
                             _ldo_metric, "min", units="-",
                             source="ADS-33E-PRF §3.4 lateral-directional oscillatory requirements: boundary values "
                                    "not found printed", family="forward_flight", axis="yaw", speeds=("forward",),
                             status="not found", test=_TEST_LDO),
        HQSpec("SpiralF.MIL-F-8785C", "spiral: time to double amplitude (forward flight)", time_to_double, "min",
               20.0, 12.0, units="s", level3=4.0,
               source="MIL-F-8785C Category B/C, Class I/IV; " + proxy.format(table="10.3"),
               family="forward_flight", axis="roll", speeds=("forward",), status="printed", test=_TEST_LDO),
        DampingFrequencySpec("PhugoidF.pitch", "mid-term (phugoid) pitch damping and frequency (forward flight)",
                             _phugoid_metric, "min", units="-",
                             source="ADS-33E-PRF §3.4 mid-term pitch response (Padfield, Helicopter Flight Dynamics "
                                    "Fig. 5.8 shows the chart): boundary values not found printed",
                             family="forward_flight", axis="pitch", speeds=("forward",), status="not found",
                             test=_TEST_LDO),
    ]
