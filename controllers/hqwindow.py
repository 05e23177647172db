"""CONDUIT-style "HQ window": every spec on its own chart with Level 1/2/3 regions."""
from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

__all__ = ["hq_window"]

_COLORS = {1: "#d9f2d9", 2: "#fff2b3", 3: "#f7c6c6"}


def hq_window(designs, specs, labels=None, fig=None, ncols=4):
    """One panel per spec (objectives excluded): Level 1/2/3 bands and each design's value.

    ``designs`` is one design or a list (e.g. cases A, B, C); returns a Figure.
    The bandwidth spec is drawn on its 2-D chart (bandwidth vs phase delay).
    """
    designs = designs if isinstance(designs, (list, tuple)) else [designs]
    labels = labels or [f"design {k + 1}" for k in range(len(designs))]
    specs = [s for s in specs if s.kind != "objective"]
    nrows = int(np.ceil(len(specs) / ncols))
    fig = fig or Figure(figsize=(3.2 * ncols, 2.4 * nrows), constrained_layout=True)
    axes = np.atleast_1d(fig.subplots(nrows, ncols)).ravel()
    markers = "osD^v<>"
    for ax, spec in zip(axes, specs):
        results = [spec.evaluate(d) for d in designs]
        if hasattr(spec, "tau1"):
            xmax = max(8.0, 1.3 * max(np.nan_to_num(r["value"]) for r in results))
            ax.add_patch(Rectangle((0, 0), xmax, 0.4, color=_COLORS[3]))
            ax.add_patch(Rectangle((spec.level2, 0), xmax, spec.tau2, color=_COLORS[2]))
            ax.add_patch(Rectangle((spec.level1, 0), xmax, spec.tau1, color=_COLORS[1]))
            for k, r in enumerate(results):
                ax.plot(r["value"], r.get("phase_delay", np.nan), markers[k % 7], label=labels[k])
            ax.set_xlim(0, xmax)
            ax.set_ylim(0, 0.4)
            ax.set_xlabel("bandwidth [rad/s]")
            ax.set_ylabel("phase delay [s]")
        else:
            vals = np.array([r["value"] for r in results], float)
            finite = vals[np.isfinite(vals)]
            lo = min([spec.level1, spec.level2, *finite]) if finite.size else spec.level1
            hi = max([spec.level1, spec.level2, *finite]) if finite.size else spec.level2
            pad = 0.3 * (hi - lo or 1.0)
            lo, hi = lo - pad, hi + pad
            b1, b2 = spec.level1, spec.level2
            if spec.direction == "min":
                bands = [(lo, b2, 3), (b2, b1, 2), (b1, hi, 1)]
            else:
                bands = [(lo, b1, 1), (b1, b2, 2), (b2, hi, 3)]
            for a, b, lev in bands:
                if b > a:
                    ax.axvspan(a, b, color=_COLORS[lev])
            for k, v in enumerate(vals):
                ax.plot(v, 0.5 + 0.1 * k, markers[k % 7], label=labels[k])
            ax.set_xlim(lo, hi)
            ax.set_ylim(0, 1)
            ax.set_yticks([])
            ax.set_xlabel(spec.units or "-")
        ax.set_title(f"{spec.name} ({spec.kind})", fontsize=8)
    for ax in axes[len(specs):]:
        ax.set_visible(False)
    axes[0].legend(fontsize=7, loc="upper left")
    return fig
