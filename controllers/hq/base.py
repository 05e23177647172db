"""The spec object of the handling-qualities library.

:class:`HQSpec` is a :class:`controllers.specs.Spec` (usable in any spec list
given to :func:`controllers.evaluate_specs` and the DMO's scoring) that also
carries what the library needs to select, tabulate and chart it: its family,
axis, the MTE class / UCE / attention / speed it applies to, where its
boundary numbers come from and how sure we are of them, and the test that
checks them.  :class:`RegionSpec` grades a 2-D metric (e.g. bandwidth and
phase delay) against :class:`~controllers.hq.boundaries.LevelRegions`.

A spec's ``metric`` is a plain function of an LTI object, a frequency
response or a time response; ``response`` maps what is evaluated (an
:class:`~controllers.emf.EMFDesign`, a closed loop, ...) to the metric's
input (identity when omitted, so a spec also grades an LTI object directly).
"""
from __future__ import annotations

import numbers
from dataclasses import dataclass, field, replace
from typing import Callable, Optional

import numpy as np

from ..specs import Spec
from .boundaries import BoundaryNotPublishedError, LevelRegions
from .limits import MTE_CLASSES

__all__ = ["HQSpec", "RegionSpec", "STATUSES", "AXES", "SPEEDS", "MTE_CLASSES", "AGILITIES", "ATTENTIONS"]

#: how a spec's boundary numbers are known
STATUSES = ("printed", "approximate", "partial", "not found", "supplied", "design", "objective")
#: axis names of the library (signal-name checks are the design's business)
AXES = ("pitch", "roll", "yaw", "heave")
#: flight regimes
SPEEDS = ("hover", "forward")
#: ADS-33E-PRF MTE classes of the small/moderate-amplitude charts
#: ADS-33E-PRF agility classes of the large-amplitude and coupling requirements
AGILITIES = ("limited", "moderate", "aggressive")
#: pilot attention
ATTENTIONS = ("fully attended", "divided")


def _identity(x):
    return x


@dataclass
class HQSpec(Spec):
    """A scalar handling-qualities spec with its applicability and provenance.

    Besides :class:`~controllers.specs.Spec`'s fields (``level1`` is the
    Level 1/2 boundary, ``level2`` the Level 2/3 boundary):

    Attributes
    ----------
    family : str
        Library module (``"bandwidth"``, ``"heave"``, ...).
    axis : str
        One of :data:`AXES`, or ``"any"`` for generic specs.
    mtes, agilities, uces, attentions, speeds : tuple
        Where the spec applies (selector keys).
    excluded : tuple of (uce, attention)
        Combinations the spec does not apply to.
    response : callable, optional
        Maps the evaluated object to the metric's input.
    status : str
        One of :data:`STATUSES`: ``"printed"`` (numbers quoted in ``source``),
        ``"approximate"`` (values carried over and labelled approximate),
        ``"partial"`` (only the Level 1 boundary was found: ``level2`` is NaN,
        the spec tells Level 1 from "not Level 1"), ``"not found"`` (no
        printed value found: evaluating raises
        :class:`~controllers.hq.boundaries.BoundaryNotPublishedError`),
        ``"supplied"`` (boundaries given by the caller with
        :meth:`with_boundaries`, their source quoted in ``source``),
        ``"design"`` (a design parameter, e.g. the DMO's crossover boundary)
        or ``"objective"`` (no boundary).
    test : str
        The test that checks the boundary numbers and the metric.
    level3 : float
        An extra published limit beyond Level 2 (informational), NaN if none.
    missing_input : str
        What the spec still needs before it can grade (e.g. actuator limits);
        empty when complete.  Such a spec is not :attr:`available`.
    """

    family: str = ""
    axis: str = "any"
    mtes: tuple = MTE_CLASSES
    agilities: tuple = AGILITIES
    uces: tuple = (1, 2, 3)
    attentions: tuple = ATTENTIONS
    speeds: tuple = SPEEDS
    excluded: tuple = ()
    response: Optional[Callable] = None
    status: str = "printed"
    test: str = ""
    level3: float = np.nan
    missing_input: str = ""

    def __post_init__(self):
        if self.status not in STATUSES:
            raise ValueError(f"spec {self.name!r}: status must be one of {STATUSES}, got {self.status!r}")
        if self.status == "not found" or (self.status in ("partial", "supplied") and np.isnan(self.level2)):
            if self.direction not in ("min", "max"):
                raise ValueError(f"spec {self.name!r}: direction must be 'min' or 'max', got {self.direction!r}")
            if self.status != "not found" and not np.isfinite(self.level1):
                raise ValueError(f"spec {self.name!r}: a {self.status!r} spec needs a finite Level 1 boundary")
            return
        super().__post_init__()

    def applies_to(self, axis, mte, agility, uce, attention, speed):
        """Whether the spec applies to this axis, MTE class, agility, UCE, attention and speed."""
        return (self.axis in (axis, "any") and mte in self.mtes and agility in self.agilities
                and uce in self.uces and attention in self.attentions and speed in self.speeds
                and (uce, attention) not in self.excluded)

    @property
    def available(self):
        """Whether the spec can grade a design (boundaries known, inputs complete)."""
        return self.status != "not found" and not self.missing_input

    def with_boundaries(self, level1, level2=np.nan, *, source, level3=np.nan):
        """A copy of the spec graded against Level boundaries the caller supplies.

        For a spec whose boundary values were not found printed (evaluating it
        raises :class:`~controllers.hq.boundaries.BoundaryNotPublishedError`),
        or to grade against other values than the library's (a programme's own
        requirement).  The copy's ``status`` is ``"supplied"`` and its
        ``source`` quotes ``source`` first; its smooth NLP constraint, if it
        has one, reads the new Level 1 boundary, so the DMO honours it.

        Parameters
        ----------
        level1 : float
            Level 1/2 boundary [the spec's ``units``].
        level2 : float, optional
            Level 2/3 boundary; NaN (default) when only the Level 1 boundary is
            known: the copy then tells Level 1 from "not Level 1".
        source : str
            Where the values come from (document, paragraph, figure): quoted in
            tables and charts.
        level3 : float, optional
            A further limit beyond Level 2 (informational).

        Returns
        -------
        HQSpec

        Raises
        ------
        ValueError
            An objective or design-parameter spec; an empty ``source``; a
            boundary not a finite number; Level 1 less demanding than Level 2
            (or Level 2 than Level 3).

        See Also
        --------
        controllers.specs_for : its ``boundaries`` argument supplies them by spec name.

        Examples
        --------
        >>> from controllers.hq.generic import generic_specs
        >>> drb = [s for s in generic_specs() if s.name == "DrbPiH1"][0]
        >>> drb.available
        False
        >>> mine = drb.with_boundaries(0.5, 0.25, source="programme requirement, pitch DRB")
        >>> mine.available, mine.status, mine.boundary_text()
        (True, 'supplied', 'L1 >= 0.5 rad/s; L2 >= 0.25 rad/s')
        """
        if self.kind == "objective" or self.status in ("design", "objective"):
            raise ValueError(f"spec {self.name!r} is {'an objective' if self.kind == 'objective' else 'a design parameter'}"
                             " (no Level boundary to supply)")
        text = _source_text(self.name, source)
        l1, l2, l3 = (_boundary_number(self.name, n, v) for n, v in
                      (("level1", level1), ("level2", level2), ("level3", level3)))
        if not np.isfinite(l1):
            raise ValueError(f"spec {self.name!r}: level1 must be a finite number, got {level1!r}")
        sign = 1.0 if self.direction == "min" else -1.0
        word = "at least" if self.direction == "min" else "at most"
        for (a, na), (b, nb) in (((l1, "level1"), (l2, "level2")), ((l2, "level2"), (l3, "level3"))):
            if np.isfinite(a) and np.isfinite(b) and sign * (a - b) < 0:
                raise ValueError(f"spec {self.name!r} (direction {self.direction!r}): {na} must be {word} {nb} "
                                 f"(the better Level is the more demanding), got {na}={a:g}, {nb}={b:g}")
        if not np.isfinite(l2) and np.isfinite(l3):
            raise ValueError(f"spec {self.name!r}: level3 given without level2")
        return replace(self, level1=l1, level2=l2, level3=l3, status="supplied",
                       source=f"{text} (supplied; library entry: {self.source})")

    def boundary_text(self):
        """The boundary values as one line of text (for tables)."""
        if self.kind == "objective":
            return "objective (no boundary)"
        if self.status == "not found":
            return "not found printed"
        op = ">=" if self.direction == "min" else "<="
        u = f" {self.units}" if self.units and self.units != "-" else ""
        text = f"L1 {op} {self.level1:g}{u}"
        text += f"; L2 {op} {self.level2:g}{u}" if np.isfinite(self.level2) else "; L2 not found printed"
        if np.isfinite(self.level3):
            text += f"; L3 {op} {self.level3:g}{u}"
        return text

    def _input(self, obj):
        return (self.response or _identity)(obj)

    def value(self, design):
        return float(self.metric(self._input(design)))

    def _unpublished(self):
        return BoundaryNotPublishedError(
            f"spec {self.name!r} ({self.description}): its boundary values were not found printed "
            f"(source: {self.source}); give the spec Level boundaries read from the source before grading")

    def _check_inputs(self):
        if self.missing_input:
            raise ValueError(f"spec {self.name!r} ({self.description}) cannot be evaluated: it needs "
                             f"{self.missing_input}")

    def evaluate(self, design):
        if self.status == "not found":
            raise self._unpublished()
        self._check_inputs()
        if np.isfinite(self.level2) or self.kind == "objective":
            return super().evaluate(design)
        v = self.value(design)
        if np.isnan(v):
            return {"value": v, "level": 3, "margin": -np.inf}
        sign = 1.0 if self.direction == "min" else -1.0
        margin = sign * (v - self.level1) / max(abs(self.level1), 1.0)
        # Level 2/3 boundary unknown: only "Level 1" or "not Level 1" can be told apart
        return {"value": v, "level": 1 if margin >= 0 else np.nan, "margin": float(margin)}


def _source_text(name, source):
    if not isinstance(source, str) or not source.strip():
        raise ValueError(f"spec {name!r}: supplied boundaries need a source (document, paragraph, figure), "
                         f"got {source!r}")
    return source.strip()


def _boundary_number(name, what, value):
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(f"spec {name!r}: {what} must be a number, got {value!r}")
    v = float(value)
    if np.isinf(v):
        raise ValueError(f"spec {name!r}: {what} must be finite (or NaN: not given), got {value!r}")
    return v


@dataclass
class RegionSpec(HQSpec):
    """A 2-D spec: ``metric`` returns ``(x, y)``, graded against ``regions``.

    ``value`` (the table's number) is ``x``; ``y`` is returned as ``"y"`` and,
    for bandwidth charts, as ``"phase_delay"`` (the column the spec tables and
    :func:`controllers.hq_window` read).  ``level1``/``level2`` hold nothing
    for a region spec and are NaN.  ``chart_axes`` is ``(x_label, y_label,
    scale, limits)`` of the chart (see :class:`~controllers.hq.boundaries.LevelRegions`):
    what :meth:`with_boundaries` gives supplied polygons when the spec has no
    regions of its own.
    """

    regions: Optional[LevelRegions] = None
    undefined: tuple = field(default=())
    chart_axes: tuple = ()

    def __post_init__(self):
        if self.status not in STATUSES:
            raise ValueError(f"spec {self.name!r}: status must be one of {STATUSES}, got {self.status!r}")
        if self.kind not in ("hard", "soft"):
            raise ValueError(f"spec {self.name!r}: a region spec is 'hard' or 'soft', got {self.kind!r}")
        if self.status != "not found" and not isinstance(self.regions, LevelRegions):
            raise ValueError(f"spec {self.name!r}: a region spec with status {self.status!r} needs LevelRegions")

    def value(self, design):
        x, y = self.metric(self._input(design))
        return float(x), float(y)

    def with_boundaries(self, level1, level2, *, source, scale=None, limits=None):
        """A copy of the spec graded against Level regions the caller supplies.

        Parameters
        ----------
        level1, level2 : array_like, shape (n, 2)
            Vertices of the Level 1 region and of the Level 1 + Level 2 region
            (which must contain it), in the metric's ``(x, y)`` order and units
            (for bandwidth: w_BW [rad/s], tau_p [s]); close an open chart region
            with far vertices outside any plausible design.
        source : str
            Where the vertices come from (document, paragraph, figure).
        scale : (float, float), optional
            Distance units of the margin; default the spec's own chart's.
        limits : ((float, float), (float, float)), optional
            The chart's plotted extents ``((x0, x1), (y0, y1))``; default the
            spec's own chart's.

        Returns
        -------
        RegionSpec
            ``status`` ``"supplied"``.

        Raises
        ------
        ValueError
            An empty ``source``, a polygon of fewer than three finite vertices,
            a Level 1 vertex outside the Level 2 region, or a spec that knows
            no chart axes and is given no ``scale``.

        Examples
        --------
        >>> from controllers.hq.bandwidth import bandwidth_specs
        >>> pitch = [s for s in bandwidth_specs() if s.name == "BnwAtH1.pitch"][0]
        >>> pitch.available
        False
        >>> far = 100.0
        >>> mine = pitch.with_boundaries([(2, -1), (far, -1), (far, 0.15), (3, 0.15), (2, 0.1)],
        ...                              [(1, -1), (far, -1), (far, 0.25), (1, 0.25)],
        ...                              source="my reading of the chart")
        >>> mine.status, mine.regions.level((2.5, 0.1)), mine.regions.level((2.5, 0.14))
        ('supplied', 1, 2)
        """
        text = _source_text(self.name, source)
        r = self.regions
        x_label, y_label, own_scale, own_limits = ((r.x_label, r.y_label, r.scale, r.limits) if r is not None
                                                   else self.chart_axes or ("x", "y", None, None))
        scale = own_scale if scale is None else tuple(scale)
        if scale is None:
            raise ValueError(f"spec {self.name!r} knows no chart axes: give the scale of its (x, y) chart")
        regions = LevelRegions(level1, level2, scale, x_label, y_label,
                               limits=own_limits if limits is None else limits)
        return replace(self, regions=regions, status="supplied",
                       source=f"{text} (supplied; library entry: {self.source})")

    def boundary_text(self):
        if self.status == "not found":
            return "not found printed"
        r = self.regions
        fmt = lambda poly: " ".join(f"({x:g},{y:g})" for x, y in poly)
        return f"L1 polygon [{r.x_label}, {r.y_label}]: {fmt(r.level1)}; L1+L2 polygon: {fmt(r.level2)}"

    def evaluate(self, design):
        if self.status == "not found":
            raise self._unpublished()
        try:
            x, y = self.value(design)
        except self.undefined:
            return {"value": np.nan, "level": 3, "margin": -np.inf, "y": np.nan, "phase_delay": np.nan}
        point = (x, y)
        return {"value": x, "y": y, "phase_delay": y, "level": self.regions.level(point),
                "margin": float(self.regions.margin(point))}
