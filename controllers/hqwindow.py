"""CONDUIT-style "HQ window": every spec on its own chart with Level 1/2/3 regions.

Each panel names its spec (CONDUIT short name, what it measures, hard/soft) and
its source; 2-D specs of :mod:`controllers.hq` are drawn from their Level
polygons, and a spec whose Level 2/3 boundary is not published shows Level 1
and a hatched "not Level 1" band; the Level 1/2/3 regions share one legend; each design's point is
labelled on every panel.  A Nichols chart of the broken loops shows the
exclusion boundary (the NicMgG1 ellipse and the GM/PM points).
"""
from __future__ import annotations

import textwrap

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Ellipse, Patch, Polygon, Rectangle

from .metrics import frequency_response_of
from .smooth import NicholsEllipse

__all__ = ["hq_window"]

_COLORS = {1: "#cdeccd", 2: "#fff0a8", 3: "#f5c2c2"}
_MARKERS = "osD^v<>"


def _short(label):
    """'(A) DC on DC' -> 'A'; other labels are kept up to 10 characters."""
    label = str(label)
    if label.startswith("(") and ")" in label:
        return label[1:label.index(")")]
    return label[:10]


def _title(ax, spec):
    text = textwrap.fill(f"{spec.name} ({spec.kind}): {spec.description}", 48)
    if spec.source:
        text += "\n" + textwrap.fill("source: " + spec.source, 56)
    ax.set_title(text, fontsize=6.5, loc="left")


def _scalar_panel(ax, spec, results, labels, colors):
    vals = np.array([r["value"] for r in results], float)
    b1, b2 = spec.level1, spec.level2
    partial = not np.isfinite(b2)   # Level 2/3 boundary not published: Level 1 or "not Level 1"
    b2 = b1 if partial else b2
    span = abs(b1 - b2) or max(abs(b1), 1.0)
    finite = vals[np.isfinite(vals)]
    lo = min([b1, b2] + [max(v, min(b1, b2) - 3 * span) for v in finite]) - 0.6 * span
    hi = max([b1, b2] + [min(v, max(b1, b2) + 3 * span) for v in finite]) + 0.6 * span
    if spec.direction == "min":
        bands = [(lo, b2, 3), (b2, b1, 2), (b1, hi, 1)]
    else:
        bands = [(lo, b1, 1), (b1, b2, 2), (b2, hi, 3)]
    for a, b, lev in bands:
        if b > a and partial and lev != 1:
            ax.axvspan(a, b, fc="none", ec="0.5", hatch="///", lw=0)
        elif b > a:
            ax.axvspan(a, b, color=_COLORS[lev], lw=0)
    n = max(len(vals), 1)
    for k, (v, r) in enumerate(zip(vals, results)):
        y = (k + 1) / (n + 1)
        if np.isnan(v):
            status = r.get("status", "")
            status = status if str(status).startswith("n/a") else "n/a: undefined"
            ax.text(0.5, y, f"{_short(labels[k])}: {status}", transform=ax.transAxes,
                    fontsize=6, ha="center", va="center", color=colors[k])
            continue
        shown = float(np.clip(v, lo, hi))
        ax.plot(shown, y, _MARKERS[k % 7], color=colors[k], ms=6, mec="k", mew=0.5)
        text = _short(labels[k]) + (f" ({v:.3g})" if shown != v else "")
        ax.annotate(text, (shown, y), xytext=(4, 3), textcoords="offset points", fontsize=6)
    ax.set_xlim(lo, hi)
    ax.set_ylim(0, 1)
    ax.set_yticks([])
    ax.tick_params(labelsize=6)
    ax.set_xlabel(spec.units or "normalised", fontsize=6, labelpad=1)


def _bandwidth_panel(ax, spec, results, labels, colors):
    xmax = max(8.0, 1.2 * max([np.nan_to_num(r["value"]) for r in results] + [0.0]))
    ymax = max(0.4, 1.2 * max([np.nan_to_num(r.get("phase_delay", 0.0)) for r in results] + [0.0]))
    ax.add_patch(Rectangle((0, 0), xmax, ymax, color=_COLORS[3], lw=0))
    ax.add_patch(Rectangle((spec.level2, 0), xmax, spec.tau2, color=_COLORS[2], lw=0))
    ax.add_patch(Rectangle((spec.level1, 0), xmax, spec.tau1, color=_COLORS[1], lw=0))
    for k, r in enumerate(results):
        x, y = r["value"], r.get("phase_delay", np.nan)
        if not (np.isfinite(x) and np.isfinite(y)):
            ax.text(0.05, 0.9 - 0.1 * k, f"{_short(labels[k])}: n/a", transform=ax.transAxes, fontsize=6)
            continue
        ax.plot(x, y, _MARKERS[k % 7], color=colors[k], ms=6, mec="k", mew=0.5)
        ax.annotate(_short(labels[k]), (x, y), xytext=(4, 3), textcoords="offset points", fontsize=6)
    ax.set_xlim(0, xmax)
    ax.set_ylim(0, ymax)
    ax.tick_params(labelsize=6)
    ax.set_xlabel("bandwidth [rad/s]", fontsize=6, labelpad=1)
    ax.set_ylabel("phase delay [s]", fontsize=6)


def _region_panel(ax, spec, results, labels, colors):
    """A 2-D chart (e.g. ADS-33E-PRF bandwidth vs phase delay) drawn from the spec's polygons."""
    r = spec.regions
    (x0, x1), (y0, y1) = r.limits or ((0.0, 10.0), (0.0, 1.0))
    ax.add_patch(Polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], closed=True, color=_COLORS[3], lw=0))
    ax.add_patch(Polygon(r.level2, closed=True, color=_COLORS[2], lw=0))
    ax.add_patch(Polygon(r.level1, closed=True, color=_COLORS[1], lw=0))
    for k, res in enumerate(results):
        x, y = res["value"], res.get("phase_delay", np.nan)
        if not (np.isfinite(x) and np.isfinite(y)):
            ax.text(0.05, 0.9 - 0.1 * k, f"{_short(labels[k])}: n/a", transform=ax.transAxes, fontsize=6)
            continue
        shown = (float(np.clip(x, x0, x1)), float(np.clip(y, y0, y1)))
        ax.plot(*shown, _MARKERS[k % 7], color=colors[k], ms=6, mec="k", mew=0.5)
        ax.annotate(_short(labels[k]), shown, xytext=(4, 3), textcoords="offset points", fontsize=6)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.tick_params(labelsize=6)
    ax.set_xlabel(r.x_label, fontsize=6, labelpad=1)
    ax.set_ylabel(r.y_label, fontsize=6)


def _nichols_panel(ax, designs, labels, colors, gm_db=6.0, pm_deg=45.0):
    w = np.geomspace(0.05, 100.0, 1500)
    ax.add_patch(Ellipse((-180.0, 0.0), 2 * pm_deg, 2 * gm_db, fc=_COLORS[3], ec="r", lw=1.0,
                         label="exclusion (NicMgG1 ellipse)"))
    ax.plot([-180, -180], [-gm_db, gm_db], "r:", lw=0.8)
    ax.plot([-180 - pm_deg, -180 + pm_deg], [0, 0], "r:", lw=0.8)
    for k, (d, lab) in enumerate(zip(designs, labels)):
        _, h = frequency_response_of(d.broken_loop(), w)
        mag = 20 * np.log10(np.abs(h))
        ph = np.degrees(np.unwrap(np.angle(h)))
        # branch: put the crossover phase in (-360, 0]
        kc = int(np.argmin(np.abs(mag)))
        ph -= 360.0 * np.ceil(ph[kc] / 360.0)
        sel = (mag > -25) & (mag < 25)
        ax.plot(np.where(sel, ph, np.nan), np.where(sel, mag, np.nan), color=colors[k], lw=1.0)
        ax.plot(ph[kc], mag[kc], _MARKERS[k % 7], color=colors[k], ms=5, mec="k", mew=0.5)
        ax.annotate(f"{_short(lab)} (w_c {w[kc]:.2g})", (ph[kc], mag[kc]), xytext=(4, 3),
                    textcoords="offset points", fontsize=6)
    ax.set_xlim(-300, -60)
    ax.set_ylim(-20, 20)
    ax.grid(alpha=0.3)
    ax.tick_params(labelsize=6)
    ax.set_xlabel("phase [deg]", fontsize=6, labelpad=1)
    ax.set_ylabel("gain [dB]", fontsize=6)
    ax.set_title(textwrap.fill("Nichols chart, loop broken at mixer input: exclusion ellipse "
                               f"(±{pm_deg:g} deg, ±{gm_db:g} dB about -180 deg, 0 dB)", 48) + "\n"
                 + textwrap.fill("source: CONDUIT NicMgG1 (elliptical approximation); MIL-DTL-9490E GM/PM", 56),
                 fontsize=6.5, loc="left")


def hq_window(designs, specs, labels=None, fig=None, ncols=4, nichols=True):
    """One panel per spec (objectives excluded) plus a Nichols chart; returns a Figure.

    Parameters
    ----------
    designs : EMFDesign or list of EMFDesign
        e.g. cases A, B, C.
    specs : list of Spec
        Boundaries to draw (one set for all designs).
    labels : list of str, optional
        Design names; '(A) ...' is shortened to 'A' on the charts.
    fig : matplotlib Figure, optional
    ncols : int
        Panels per row.
    nichols : bool
        Add the Nichols chart of the broken loops.

    Returns
    -------
    matplotlib.figure.Figure
        Every panel carries its spec's name, description, kind and source; a
        figure legend explains the Level 1/2/3 colours and the design markers.
    """
    from .specs import evaluate_specs
    designs = list(designs) if isinstance(designs, (list, tuple)) else [designs]
    labels = list(labels) if labels is not None else [f"design {k + 1}" for k in range(len(designs))]
    if len(labels) != len(designs):
        raise ValueError(f"{len(labels)} labels for {len(designs)} designs")
    specs = [s for s in specs if s.kind != "objective"]
    tables = [evaluate_specs(d, specs).set_index("spec") for d in designs]
    npanels = len(specs) + int(nichols)
    nrows = int(np.ceil(npanels / ncols))
    fig = fig or Figure(figsize=(3.4 * ncols, 2.55 * nrows + 0.6), constrained_layout=True)
    axes = list(np.atleast_1d(fig.subplots(nrows, ncols)).ravel())
    for ax in axes[npanels:]:
        fig.delaxes(ax)
    colors = [f"C{k}" for k in range(len(designs))]
    for ax, spec in zip(axes, specs):
        results = []
        for t in tables:
            row = t.loc[spec.name]
            results.append({"value": row.value, "phase_delay": row.phase_delay, "status": row.status})
        if getattr(spec, "regions", None) is not None:
            _region_panel(ax, spec, results, labels, colors)
        elif hasattr(spec, "tau1"):
            _bandwidth_panel(ax, spec, results, labels, colors)
        else:
            _scalar_panel(ax, spec, results, labels, colors)
        _title(ax, spec)
    if nichols:
        # the exclusion ellipse drawn is the one the spec list grades (default: 45 deg, 6 dB)
        ellipse = next((s.smooth for s in specs if isinstance(getattr(s, "smooth", None), NicholsEllipse)),
                       NicholsEllipse())
        _nichols_panel(axes[len(specs)], designs, labels, colors, ellipse.gain_axis, ellipse.phase_axis)
    handles = [Patch(color=_COLORS[k], label=f"Level {k}") for k in (1, 2, 3)]
    handles += [axes[0].plot([], [], _MARKERS[k % 7], color=colors[k], mec="k", mew=0.5,
                             label=labels[k])[0] for k in range(len(designs))]
    fig.legend(handles=handles, loc="outside upper center", ncols=min(len(handles), 8), fontsize=8,
               title="Level 1 = satisfactory, 2 = adequate, 3 = inadequate (CONDUIT convention); "
                     "values beyond the axis are written beside their marker", title_fontsize=7)
    return fig
