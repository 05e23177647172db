"""Is each axis's DMO answer of a multi-axis design the global one? An independent search tries to beat it.

The DMO's design objective on an axis is the highest crossover boundary (CrsMnG2)
at which one gain set meets every other spec of the axis. :func:`global_check`
hands each axis's final design plant (its loop with every other loop closed) and
the same specs, at the DMO's final DRB boundary, to
:func:`controllers.search.global_search` (differential evolution over the three
gains, no use of the DMO's answer, rays or NLP) and compares the crossovers. The
answer is trusted when the search cannot beat it by more than ``beat_tolerance``.

A design tuned with guards (``design_multi_axis(..., guard_other_axes=True)``)
was held to the other closed loops' stability margins too; the search then grades
the same guards (:func:`controllers.multi_axis_guard.axis_guards`, the other loops
at their final gains), or else it "beats" the DMO with gains that take another
loop's margin away.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from . import metrics as m
from .multi_axis_design import DEFAULT_CROSSOVER_START, axis_specs
from .multi_axis_guard import axis_guards
from .search import global_search
from .specs import evaluate_specs

__all__ = ["global_check"]


def global_check(result, maxiter=15, popsize=6, seed=0, beat_tolerance=0.01, mte=None, progress=False, guards=None):
    """Per axis: the DMO's crossover against an independent global search's on the same specs.

    Parameters
    ----------
    result : MultiAxisResult
        From :func:`controllers.multi_axis_design.design_multi_axis`.
    maxiter, popsize, seed : int
        Budget and seed of :func:`controllers.search.global_search`.
    beat_tolerance : float
        The search beats the DMO when its crossover exceeds the DMO's by more than this
        fraction (the DMO stops its boundary bisection at 0.5 %).
    mte : str or None
        None (default): the specs the design graded its final loops on
        (``result.spec_lists``: its MTE class, flight regime and final boundaries);
        a string: the specs of that MTE class, in the design's flight regime and with
        the boundaries it was given (``result.speed``, ``result.boundaries``), rebuilt
        at the DMO's final boundaries.
    progress : bool
        tqdm counters of the searches.
    guards : bool or None
        None (default): as the design was tuned (``result.guard_other_axes``). True:
        each axis's search also grades its guards, built as
        :func:`~controllers.multi_axis_design.design_multi_axis` builds them (the other
        loops closed during the axis's last tuning, at their final gains; the floor at
        the gains that tuning started from; ``result.guard_level``). False: the axis's
        own specs only.

    Returns
    -------
    pandas.DataFrame
        Index axis: ``dmo_crossover`` and ``search_crossover`` [rad/s] on the axis's design
        plant, their ratio, ``beaten`` (the search found feasible gains crossing more than
        ``beat_tolerance`` higher), both gain sets, ``dmo_feasible`` (the DMO's gains meet
        the specs the search used), ``search_mimo_met`` and ``search_mimo_crossover``
        (the search's gains in the simultaneous closed loop, the other axes at the DMO's
        gains: every spec but CrsMnG2 met, and the crossover there), the points scored, how many were feasible, and the
        search's wall time [s]; ``guarded`` (the search graded guards), ``guard_specs``
        (how many) and ``dmo_guards_met`` (the DMO's final gains meet them; True when
        there are none).

    Raises
    ------
    ValueError
        ``beat_tolerance`` negative or not finite, or ``guards`` not None, True or False.

    Examples
    --------
    >>> import control
    >>> from controllers import DMOSettings, design_multi_axis
    >>> plant = control.ss([[-1.5, 0], [1.0, 0]], [[5.0], [0]], [[1.0, 0], [0, 1.0]], 0,
    ...                    inputs=["delta_lat"], outputs=["p", "phi"])
    >>> res = design_multi_axis(plant, axes=["roll"], settings=DMOSettings(global_samples=4, max_steps=2),
    ...                         max_sweeps=1, progress=False, limits=None)       # doctest: +SKIP
    >>> global_check(res, maxiter=2, popsize=2).columns[:3].tolist()              # doctest: +SKIP
    ['dmo_crossover', 'search_crossover', 'ratio']
    """
    if not (np.isfinite(beat_tolerance) and beat_tolerance >= 0):
        raise ValueError(f"global_check: beat_tolerance must be >= 0, got {beat_tolerance!r}")
    if guards is not None and not isinstance(guards, (bool, np.bool_)):
        raise ValueError(f"global_check: guards must be None, True or False, got {guards!r}")
    guarded = bool(result.guard_other_axes if guards is None else guards)
    rows = []
    for a in result.emf.axes:
        design, res = result.designs[a], result.dmo_results.get(a)
        wc = res.crossover_boundary if res is not None else DEFAULT_CROSSOVER_START[a]
        wd = res.drb_boundary if res is not None and np.isfinite(res.drb_boundary) else 0.9
        # the design's own specs, so that a forward-flight design is checked on the
        # forward-flight charts it was designed against
        specs = (result.spec_lists[a] if mte is None
                 else axis_specs(a, wc, wd, mte=mte, limits=result.limits.get(a), speed=result.speed,
                                 boundaries=result.boundaries))
        table = evaluate_specs(design, specs)
        graded = table[(table.kind != "objective") & (table.spec != "CrsMnG2")]
        ok = bool(graded.met.all())
        dmo_wc = m.crossover_frequency(design.broken_loop()) if ok else np.nan
        # an old result without the tuning record: the floor at the final gains, every other loop closed
        start = design.with_gains(result.tuned_from.get(a, design.gains))
        guard_list = (axis_guards(result.emf.plant, result.emf.loops, start, result.spec_lists,
                                  closed=result.tuned_with.get(a), level=result.guard_level) if guarded else [])
        guards_met = bool(evaluate_specs(design, guard_list).met.all()) if guard_list else True
        search = global_search(design, specs + guard_list, reference_frequency=DEFAULT_CROSSOVER_START[a],
                               maxiter=maxiter, popsize=popsize, seed=seed, progress=progress)
        s_wc = search.crossover
        ratio = s_wc / dmo_wc if np.isfinite(dmo_wc) and np.isfinite(s_wc) else np.nan
        beaten = bool(np.isfinite(s_wc) and (not np.isfinite(dmo_wc) or s_wc > dmo_wc * (1 + beat_tolerance)))
        g, sg = design.gains, search.gains
        # the search's gains put back into the simultaneous closed loop (the other axes keep the DMO's)
        mimo_met, mimo_wc = False, np.nan
        if sg is not None:
            view = result.emf.with_gains({a: sg}).axis_view(a)
            t = evaluate_specs(view, specs)
            t = t[(t.kind != "objective") & (t.spec != "CrsMnG2")]
            mimo_met, mimo_wc = bool(t.met.all()), m.crossover_frequency(view.broken_loop())
        rows.append({"axis": a, "dmo_crossover": dmo_wc, "search_crossover": s_wc, "ratio": ratio,
                     "beaten": beaten, "dmo_feasible": ok,
                     "dmo_K_phi": g.K_phi, "dmo_K_Iphi": g.K_Iphi, "dmo_K_p": g.K_p,
                     "search_K_phi": sg.K_phi if sg else np.nan, "search_K_Iphi": sg.K_Iphi if sg else np.nan,
                     "search_K_p": sg.K_p if sg else np.nan, "search_mimo_met": mimo_met,
                     "search_mimo_crossover": mimo_wc, "points": len(search.points),
                     "feasible_points": int(search.points.feasible.sum()), "search_wall_s": search.wall_time,
                     "guarded": guarded, "guard_specs": len(guard_list), "dmo_guards_met": guards_met})
    return pd.DataFrame(rows).set_index("axis")
