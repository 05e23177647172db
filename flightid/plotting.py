"""Bode-with-coherence plots shared by responses and fit results (no pyplot state)."""
from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

__all__ = ["bode_with_coherence"]


def bode_with_coherence(sources, pairs, fig=None, max_columns=6):
    """Plot (output, input) pairs of several responses: magnitude, phase, coherence.

    ``sources`` is a list of (response, label); a response is a
    MeasuredResponse (coherence shown) or anything with ``omega`` and a
    ``(n_out, n_in, n_w)`` complex array via ``.frdata``, and output/input labels.
    Returns a :class:`matplotlib.figure.Figure`.
    """
    n = len(pairs)
    ncol = min(n, max_columns)
    nrow_blocks = int(np.ceil(n / ncol))
    if fig is None:
        fig = Figure(figsize=(3.2 * ncol, 6.5 * nrow_blocks), constrained_layout=True)
    axes = fig.subplots(3 * nrow_blocks, ncol, squeeze=False, sharex="col")
    for k, (out, inp) in enumerate(pairs):
        blk, col = divmod(k, ncol)
        am, ap, ac = axes[3 * blk, col], axes[3 * blk + 1, col], axes[3 * blk + 2, col]
        first_phase = None      # later curves take the 360-deg branch of the first one
        for resp, label in sources:
            if out not in resp.output_labels or inp not in resp.input_labels:
                continue
            i, j = resp.output_labels.index(out), resp.input_labels.index(inp)
            h = resp.frdata[i, j]
            w = resp.frequency
            style = "-" if hasattr(resp, "coherence") else "--"
            am.semilogx(w, 20 * np.log10(np.maximum(np.abs(h), 1e-300)), style, label=label)
            phase = np.degrees(np.unwrap(np.angle(h)))
            if first_phase is None:
                first_phase = phase[0]
            else:
                phase -= 360.0 * np.round((phase[0] - first_phase) / 360.0)
            ap.semilogx(w, phase, style, label=label)
            if hasattr(resp, "coherence"):
                ac.semilogx(w, resp.coherence[i, j], style, label=label)
        am.set_title(f"{out} / {inp}", fontsize=9)
        am.set_ylabel("mag [dB]")
        ap.set_ylabel("phase [deg]")
        ac.set_ylabel("coherence")
        ac.set_ylim(0, 1.05)
        ac.set_xlabel("omega [rad/s]")
        for a in (am, ap, ac):
            a.grid(True, which="both", alpha=0.3)
    axes[0, 0].legend(fontsize=7)
    return fig
