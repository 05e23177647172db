"""Level regions as data: polygons, point-in-region tests and normalised margins.

A handling-qualities chart (ADS-33E-PRF draws most of them as polygons in a
plane such as bandwidth vs phase delay) is stored as two closed polygons: the
Level 1 region and the Level 1 + Level 2 region (everything outside the latter
is Level 3).  Distances are measured in a plane whose axes are divided by
``scale`` (one unit per axis, e.g. 1 rad/s and 0.1 s) so that a margin does not
depend on the units the chart happens to use.

The normalised margin follows CONDUIT's convention (Tischler et al. 2017):
0 on the Level 1 boundary, -1 on the Level 2/3 boundary, > 0 inside Level 1,
continuous and monotone across both boundaries.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["LevelRegions", "point_in_polygon", "signed_distance", "BoundaryNotPublishedError"]


class BoundaryNotPublishedError(LookupError):
    """A spec's boundary values were not found printed in the sources searched.

    The spec, its metric and its intended source are defined; its Level
    boundaries must be supplied by the user (e.g. read from their copy of
    ADS-33E-PRF) before it can grade a design.
    """


def _as_polygon(vertices, name):
    v = np.asarray(vertices, dtype=float)
    if v.ndim != 2 or v.shape[1] != 2 or v.shape[0] < 3:
        raise ValueError(f"{name} must be a sequence of at least 3 (x, y) vertices, got shape {v.shape}")
    if not np.all(np.isfinite(v)):
        raise ValueError(f"{name} has non-finite vertices")
    return v


def point_in_polygon(point, polygon):
    """True if ``point`` lies inside or on the closed ``polygon`` (even-odd rule).

    Parameters
    ----------
    point : (float, float)
    polygon : array_like, shape (n, 2)
        Vertices in order; the last is joined to the first.

    Returns
    -------
    bool

    Examples
    --------
    >>> point_in_polygon((0.5, 0.5), [(0, 0), (1, 0), (1, 1), (0, 1)])
    True
    """
    x, y = map(float, point)
    v = np.asarray(polygon, dtype=float)
    if _edge_distance((x, y), v) <= 1e-12:
        return True
    inside = False
    n = len(v)
    for k in range(n):
        (x1, y1), (x2, y2) = v[k], v[(k + 1) % n]
        if (y1 > y) != (y2 > y):
            xc = x1 + (y - y1) * (x2 - x1) / (y2 - y1)
            if xc > x:
                inside = not inside
    return inside


def _edge_distance(point, v):
    """Euclidean distance from ``point`` to the polygon's boundary."""
    p = np.asarray(point, dtype=float)
    a = v
    b = np.roll(v, -1, axis=0)
    ab = b - a
    t = np.clip(np.einsum("ij,ij->i", p - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0, 1)
    closest = a + t[:, None] * ab
    return float(np.min(np.hypot(*(closest - p).T)))


def signed_distance(point, polygon, scale=(1.0, 1.0)):
    """Distance from ``point`` to the polygon's boundary, > 0 inside, < 0 outside.

    Both the point and the polygon are divided by ``scale`` first.

    Parameters
    ----------
    point : (float, float)
    polygon : array_like, shape (n, 2)
    scale : (float, float)
        Axis units: distances are measured in multiples of them.

    Returns
    -------
    float

    Examples
    --------
    >>> round(signed_distance((0.5, 0.5), [(0, 0), (1, 0), (1, 1), (0, 1)]), 6)
    0.5
    """
    s = np.asarray(scale, dtype=float)
    v = np.asarray(polygon, dtype=float) / s
    p = np.asarray(point, dtype=float) / s
    d = _edge_distance(p, v)
    return d if point_in_polygon(p, v) else -d


@dataclass
class LevelRegions:
    """Level 1 and Level 2 regions of a 2-D handling-qualities chart.

    Attributes
    ----------
    level1 : array, shape (n, 2)
        Closed polygon of the Level 1 region (x, y) in the chart's units.
    level2 : array, shape (m, 2)
        Closed polygon of the Level 1 + Level 2 region (it contains ``level1``).
    scale : (float, float)
        Axis units used for distances (see module docstring).
    x_label, y_label : str
        Axis names with units, for charts and tables.
    """

    level1: np.ndarray
    level2: np.ndarray
    scale: tuple = (1.0, 1.0)
    x_label: str = "x"
    y_label: str = "y"
    limits: tuple = field(default=None)

    def __post_init__(self):
        self.level1 = _as_polygon(self.level1, "LevelRegions.level1")
        self.level2 = _as_polygon(self.level2, "LevelRegions.level2")
        s = np.asarray(self.scale, dtype=float)
        if s.shape != (2,) or not np.all(np.isfinite(s)) or np.any(s <= 0):
            raise ValueError(f"LevelRegions.scale must be two finite values > 0, got {self.scale}")
        for p in self.level1:
            if not point_in_polygon(p, self.level2):
                raise ValueError(f"LevelRegions: Level 1 vertex {tuple(p)} lies outside the Level 2 region")

    def level(self, point):
        """Level (1, 2 or 3) of ``point``; NaN coordinates are Level 3."""
        if not np.all(np.isfinite(point)):
            return 3
        if point_in_polygon(point, self.level1):
            return 1
        return 2 if point_in_polygon(point, self.level2) else 3

    def margin(self, point):
        """CONDUIT normalised margin of ``point``: 0 on the Level 1 boundary, -1 on Level 2/3.

        Inside Level 1 the distance to the Level 1 boundary is divided by the
        local width of the Level 2 band (distance from the nearest Level 1
        boundary point to the Level 2 boundary); outside, the margin is
        ``-d1 / (d1 + d2)`` in Level 2 and ``-1 - d2 / w`` in Level 3, with
        d1, d2 the distances to the two boundaries and w the band width.
        """
        if not np.all(np.isfinite(point)):
            return -np.inf
        d1 = signed_distance(point, self.level1, self.scale)
        d2 = signed_distance(point, self.level2, self.scale)
        if d1 >= 0:
            return d1 / self._band_width(point)
        if d2 >= 0:
            return -(-d1) / ((-d1) + d2) if (-d1 + d2) > 0 else -1.0
        return -1.0 - (-d2) / self._band_width(point)

    def _band_width(self, point):
        s = np.asarray(self.scale, dtype=float)
        v1 = self.level1 / s
        p = np.asarray(point, dtype=float) / s
        a, b = v1, np.roll(v1, -1, axis=0)
        ab = b - a
        t = np.clip(np.einsum("ij,ij->i", p - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0, 1)
        closest = a + t[:, None] * ab
        k = int(np.argmin(np.hypot(*(closest - p).T)))
        w = _edge_distance(closest[k], self.level2 / s)
        return w if w > 1e-9 else 1.0
