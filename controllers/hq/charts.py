"""HQ-window charts of the library: Level regions drawn from the boundary data, with a design's point.

Every panel names its spec and source; regions come from the spec itself
(polygons of a :class:`~controllers.hq.base.RegionSpec`, the limits of a
:class:`~controllers.hq.forward_flight.DampingFrequencySpec`, the scalar
boundaries of an :class:`~controllers.hq.base.HQSpec`).  A spec whose
boundaries were not found printed is drawn as an empty, labelled panel.
Figures are built with :class:`matplotlib.figure.Figure` (no pyplot state).
"""
from __future__ import annotations

import textwrap

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Patch, Polygon

from .base import RegionSpec
from .forward_flight import DampingFrequencySpec

__all__ = ["spec_chart", "family_window"]

_COLORS = {1: "#cdeccd", 2: "#fff0a8", 3: "#f5c2c2"}


def _title(ax, spec):
    text = textwrap.fill(f"{spec.name}: {spec.description}", 52)
    text += "\n" + textwrap.fill(f"source [{spec.status}]: {spec.source}", 60)
    ax.set_title(text, fontsize=5.5, loc="left")


def _region_axes(ax, spec, point):
    r = spec.regions
    (x0, x1), (y0, y1) = r.limits or ((0, 10), (0, 1))
    ax.add_patch(Polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], closed=True, color=_COLORS[3], lw=0))
    ax.add_patch(Polygon(r.level2, closed=True, color=_COLORS[2], lw=0))
    ax.add_patch(Polygon(r.level1, closed=True, color=_COLORS[1], lw=0))
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_xlabel(r.x_label, fontsize=6)
    ax.set_ylabel(r.y_label, fontsize=6)
    if point is not None and np.all(np.isfinite(point)):
        shown = (float(np.clip(point[0], x0, x1)), float(np.clip(point[1], y0, y1)))
        ax.plot(*shown, "o", color="C0", mec="k", ms=6)


def _damping_axes(ax, spec, point):
    zeta = np.linspace(-0.1, 1.0, 221)
    wn = np.linspace(0.0, 3.0, 241)
    Z, W = np.meshgrid(zeta, wn)
    level = np.full(Z.shape, 1)
    v = {"zeta": Z, "sigma": Z * W, "wn": W}
    for k, (b1, b2) in spec.limits.items():
        level = np.maximum(level, np.where(v[k] >= b1, 1, np.where(v[k] >= b2, 2, 3)))
    from matplotlib.colors import ListedColormap
    ax.pcolormesh(Z, W, level, cmap=ListedColormap([_COLORS[1], _COLORS[2], _COLORS[3]]), vmin=0.5, vmax=3.5,
                  shading="auto")
    ax.set_xlabel("damping ratio zeta [-]", fontsize=6)
    ax.set_ylabel("natural frequency w_n [rad/s]", fontsize=6)
    if point is not None and np.all(np.isfinite(point)):
        ax.plot(*point, "o", color="C0", mec="k", ms=6)


def _scalar_axes(ax, spec, value):
    b1, b2 = spec.level1, spec.level2
    span = abs(b1 - b2) if np.isfinite(b2) and b1 != b2 else max(abs(b1), 1.0)
    lo, hi = min(b1, b2 if np.isfinite(b2) else b1) - 1.5 * span, max(b1, b2 if np.isfinite(b2) else b1) + 1.5 * span
    if np.isfinite(value):
        lo, hi = min(lo, value - 0.3 * span), max(hi, value + 0.3 * span)
    good_up = spec.direction == "min"
    if np.isfinite(b2):
        bands = [(lo, b2, 3), (b2, b1, 2), (b1, hi, 1)] if good_up else [(lo, b1, 1), (b1, b2, 2), (b2, hi, 3)]
    else:   # Level 2/3 boundary not published: Level 1 and "not Level 1" (hatched)
        bands = [(lo, b1, 0), (b1, hi, 1)] if good_up else [(lo, b1, 1), (b1, hi, 0)]
    for a, b, lev in bands:
        if lev:
            ax.axvspan(a, b, color=_COLORS[lev], lw=0)
        else:
            ax.axvspan(a, b, fc="none", ec="0.5", hatch="///", lw=0)
    if np.isfinite(value):
        ax.plot(value, 0.5, "o", color="C0", mec="k", ms=6)
    ax.set_xlim(lo, hi)
    ax.set_ylim(0, 1)
    ax.set_yticks([])
    ax.set_xlabel(spec.units or "-", fontsize=6)


def spec_chart(spec, design=None, ax=None):
    """Draw one spec's Level regions and, optionally, a design's point; returns the Axes.

    Parameters
    ----------
    spec : HQSpec
        A library spec.
    design : object, optional
        Whatever the spec evaluates (an EMFDesign, an LTI object, a time
        response tuple, ...); its point is drawn.
    ax : matplotlib Axes, optional
        Default: a new one on a new :class:`~matplotlib.figure.Figure`.

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> from controllers.hq.heave import heave_specs
    >>> ax = spec_chart(heave_specs()[0], design=(3.0, 0.1))
    """
    ax = ax if ax is not None else Figure(figsize=(3.6, 2.8), constrained_layout=True).subplots()
    _title(ax, spec)
    ax.tick_params(labelsize=6)
    if not spec.available or spec.kind == "objective":
        ax.text(0.5, 0.5, "boundary values not found printed" if not spec.available else "objective (no boundary)",
                transform=ax.transAxes, ha="center", va="center", fontsize=7, color="0.3")
        ax.set_xticks([])
        ax.set_yticks([])
        return ax
    result = None
    if design is not None:
        if isinstance(spec, RegionSpec) and isinstance(design, tuple) and len(design) == 2 \
                and all(np.isscalar(v) for v in design):
            result = {"value": design[0], "y": design[1]}   # a point given directly
        else:
            result = spec.evaluate(design)
    if isinstance(spec, RegionSpec):
        _region_axes(ax, spec, None if result is None else (result["value"], result["y"]))
    elif isinstance(spec, DampingFrequencySpec):
        _damping_axes(ax, spec, None if result is None else (result["value"], result["wn"]))
    else:
        _scalar_axes(ax, spec, np.nan if result is None else float(result["value"]))
    return ax


def family_window(specs, design=None, label="design", ncols=3, fig=None):
    """One panel per spec (e.g. one family, or one axis's specs); returns a Figure.

    Parameters
    ----------
    specs : list of HQSpec
        Specs to draw (objectives are drawn as labelled empty panels).
    design : object, optional
        What the specs evaluate; its point is drawn on every available panel.
    label : str
        Name of the design in the legend.
    ncols : int
        Panels per row.
    fig : matplotlib Figure, optional

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> from controllers.hq.bandwidth import bandwidth_specs
    >>> fig = family_window(bandwidth_specs())
    """
    specs = list(specs)
    if not specs:
        raise ValueError("family_window: no specs to draw")
    nrows = int(np.ceil(len(specs) / ncols))
    fig = fig or Figure(figsize=(3.6 * ncols, 2.9 * nrows + 0.5), constrained_layout=True)
    axes = list(np.atleast_1d(fig.subplots(nrows, ncols)).ravel())
    for ax in axes[len(specs):]:
        fig.delaxes(ax)
    for ax, spec in zip(axes, specs):
        spec_chart(spec, design, ax)
    handles = [Patch(color=_COLORS[k], label=f"Level {k}") for k in (1, 2, 3)]
    handles.append(Patch(fc="none", ec="0.5", hatch="///", label="not Level 1 (Level 2/3 boundary not published)"))
    if design is not None:
        handles.append(axes[0].plot([], [], "o", color="C0", mec="k", label=label)[0])
    fig.legend(handles=handles, loc="outside upper center", ncols=len(handles), fontsize=7)
    return fig
