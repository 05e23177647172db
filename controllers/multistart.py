"""The DMO's multistart stage: seeded starts over the whole gain box, each polished on the true specs.

The boundary-raising continuation of :func:`controllers.dmo` follows one piece of
the feasible set, and its ray-based global stage (:mod:`controllers.gain_sampling`)
samples gain *ratios* in fixed ranges. On rate-command loops (yaw, heave) the best
designs can lie outside those ranges (a proportional gain tens of times the
attitude gain), and the continuation then ends on a local optimum that an
independent global search beats.

:func:`multistart` removes the assumption: a scrambled Sobol set of starts over the
three gains, each on its own log scale over ``decades`` of the natural gain units
(the box of :func:`controllers.search.global_search`), is scored by the true specs;
the best few feasible starts from different basins, together with any given
starting gains, are each polished by a short compass (pattern) search in the log
gains that maximises the crossover subject to every other spec. Nothing here uses
an optimiser formula: every point is scored by :func:`~controllers.specs.evaluate_specs`
and :func:`~controllers.metrics.crossover_frequency`.
"""
from __future__ import annotations

import numpy as np
import pandas as pd
from scipy.stats import qmc

from . import metrics as m
from .emf import PIDGains
from .gain_sampling import extend_along_ray, score_gains
from .nlp import _gain_scale
from .scoring import design_margins
from .smooth import CrossoverMinimum, spec_with_constraint

__all__ = ["multistart", "compass_polish", "ratio_polish"]

#: pattern of the compass search in the three log gains: each gain alone, all three
#: together (along a ray of fixed gain ratios, where the crossover grows), and one gain
#: traded for another (the best design sits where a spec boundary runs across the gain
#: axes: e.g. attitude gain traded for rate gain on a rate-command loop, a move no
#: single-gain step makes without leaving the feasible set)
#: a gain ratio this small against the crossover (K_Iphi/K_phi below 1e-6 wc, K_p/K_phi below
#: 1e-6 / wc) changes no response in the handling-qualities band: the compass search sets it to
#: exactly zero instead of walking it down by decades to round-off (a 1e-13 integral gain leaves
#: a pole at +-1e-13 1/s whose sign decides the stability verdict from one machine to the next)
_NEGLIGIBLE_RATIO = 1e-6
_MOVES = np.vstack([np.eye(3), -np.eye(3), np.ones((1, 3)), -np.ones((1, 3)),
                    [np.eye(3)[i] - np.eye(3)[j] for i in range(3) for j in range(3) if i != j]])


def _graded(specs):
    """Every spec but the crossover boundary (whose value is maximised)."""
    name = spec_with_constraint(specs, CrossoverMinimum).name
    return [s for s in specs if s.name != name]


def _score(designs, graded, gains):
    """(feasible, crossover [rad/s] or NaN, penalty, first unmet spec) of one gain set.

    An infeasible point is ranked by how far it is from every boundary: 1 + the sum
    of its unmet specs' normalised margins, each capped at 100 (a cap keeps one wild
    value from swamping the others; at 10 an unstable loop's margins all sit on the cap
    and the compass search sees a flat penalty), so that a start outside the feasible
    set is walked into it rather than dropped.
    """
    cands = [d.with_gains(gains) for d in designs]
    table, unmet, _, _ = design_margins(cands, graded)
    bad = table[(table.kind != "objective") & ~table.met.astype(bool)]
    if bad.empty:
        return True, float(min(m.crossover_frequency(d.broken_loop()) for d in cands)), 0.0, ""
    margins = np.nan_to_num(-bad.margin.astype(float).to_numpy(), nan=100.0)
    return False, float("nan"), 1.0 + float(np.sum(np.minimum(margins, 100.0))), str(bad.spec.iloc[0])


def _log(gains, unit):
    """Finite log10 of the non-zero gains in their units (for the search box)."""
    g = gains.as_array()
    return [float(v) for v in np.log10(g[g > 0] / np.asarray(unit)[g > 0])] or [0.0]


def _value(ok, wc, penalty):
    """What the compass search maximises: the crossover when feasible, else minus the penalty."""
    return wc if ok else -penalty


def compass_polish(designs, specs, gains, unit, step=0.25, min_step=0.004, max_evaluations=60,
                   decades=(-3.0, 2.0)):
    """Raise a design's crossover by a compass search in the log gains.

    From an infeasible start the search first walks down the penalty (the unmet
    specs' normalised margins) until every spec is met, then raises the crossover.

    Parameters
    ----------
    designs : list of EMFDesign
        One gain set is scored on every design (the smallest crossover counts).
    specs : list of Spec
        Every hard/soft spec but the crossover boundary must be met.
    gains : PIDGains
        Start (a zero gain stays zero).
    unit : array of 3 floats
        Natural units of (K_phi, K_Iphi, K_p); the search moves ``log10(gains / unit)``.
    step : float
        First step [decades]; halved whenever no move improves.
    min_step : float
        Stop when the step falls below this [decades] (0.004 decade is about 1 %).
    max_evaluations : int
        Spec evaluations at most.
    decades : (float, float)
        Box of the search: log10 range of each gain in ``unit`` (a move out of it is not tried).

    Returns
    -------
    gains : PIDGains
    crossover : float
        Its crossover [rad/s] (NaN when no feasible point was reached).
    evaluations : int

    Examples
    --------
    >>> from controllers import EMFDesign, default_specs, hover_roll_plant
    >>> d = EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.1, 0.05))
    >>> specs = default_specs(1.5)
    >>> g, wc, n = compass_polish([d], specs, d.gains, np.ones(3), max_evaluations=12)
    >>> n <= 12
    True
    """
    graded = _graded(specs)
    unit = np.asarray(unit, float)
    ok, wc, penalty, _ = _score(designs, graded, gains)
    n = 1
    # a zero gain stays zero (its log is -inf): the move changes the others only
    x = np.log10(np.where(gains.as_array() > 0, gains.as_array(), np.nan) / unit)
    best = (gains, _value(ok, wc, penalty), ok)
    last = 0
    while step >= min_step and n < max_evaluations:
        improved = False
        # a successful move is tried first again: the search then runs along a ridge
        # (e.g. down a ray out of an unstable region) at one evaluation per step
        for j in [last] + [i for i in range(len(_MOVES)) if i != last]:
            move = _MOVES[j]
            if n >= max_evaluations:
                break
            trial = x + step * move
            if (np.allclose(np.nan_to_num(trial - x), 0.0)
                    or np.any((trial < decades[0] - 1e-9) | (trial > decades[1] + 1e-9))):
                continue
            g = PIDGains(*np.where(np.isfinite(trial), unit * 10.0 ** np.nan_to_num(trial), 0.0))
            ok, w, penalty, _ = _score(designs, graded, g)
            n += 1
            if _value(ok, w, penalty) > best[1]:
                x, best, improved, last = trial, (g, _value(ok, w, penalty), ok), True, j
                break
        if not improved:
            step /= 2.0
    return best[0], (best[1] if best[2] else float("nan")), n


def _edge(designs, graded, gains, tolerance):
    """Largest feasible gain along ``gains``' ratios (scaled down first if infeasible); (gains, wc, n)."""
    base, n = gains.as_array(), 0
    for k in range(8):
        g = PIDGains(*(base * 0.6 ** k))
        ok, _, _ = score_gains(designs, graded, g)
        n += 1
        if ok:
            g, wc, m_ = extend_along_ray(designs, graded, g, tolerance)
            return g, wc, n + m_
    return None, float("nan"), n


def ratio_polish(designs, specs, gains, step=0.5, min_step=0.01, max_evaluations=200, tolerance=0.005):
    """Raise a feasible design's crossover by a compass search over its two gain ratios.

    The crossover at the edge of the feasible set along a ray of fixed ratios
    (K_Iphi/K_phi, K_p/K_phi), the overall gain pushed to the largest feasible one
    (:func:`controllers.gain_sampling.extend_along_ray`), is a function of the two
    ratios only; a compass search over their logs follows a spec boundary that runs
    obliquely across the gains (e.g. attitude gain traded for rate gain on a
    rate-command loop), where a search over the gains themselves stalls.

    Parameters
    ----------
    designs : list of EMFDesign
    specs : list of Spec
        Every spec but the crossover boundary must be met; the crossover is maximised.
    gains : PIDGains
        Feasible start with K_phi > 0 (a zero ratio stays zero).
    step, min_step : float
        First and last ratio step [decades]; the step halves when no move improves.
    max_evaluations : int
        Spec evaluations at most (about ten per ratio pair tried).
    tolerance : float
        Relative bisection tolerance of the overall gain along each ray.

    Returns
    -------
    gains : PIDGains
    crossover : float
        [rad/s] (NaN when ``gains`` is not feasible or K_phi is 0).
    evaluations : int

    Examples
    --------
    >>> from controllers import EMFDesign, default_specs, hover_roll_plant
    >>> d = EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.0, 0.05))
    >>> specs = [s for s in default_specs(1.0) if s.name in ("EigLcG1", "StbMgG1.GM", "CrsMnG2")]
    >>> g, wc, n = ratio_polish([d], specs, PIDGains(0.1, 0.0, 0.02), max_evaluations=20)
    >>> bool(wc > 1.0), g.K_Iphi
    (True, 0.0)
    """
    graded = _graded(specs)
    if gains.K_phi <= 0:
        return gains, float("nan"), 0
    best, wc, n = _edge(designs, graded, gains, tolerance)
    if best is None:
        return gains, float("nan"), n
    g0 = best.as_array()
    r = np.log10(np.where(g0[1:] > 0, g0[1:], np.nan) / g0[0])      # log ratios; NaN: zero stays zero
    floor = np.log10(_NEGLIGIBLE_RATIO * np.array([wc, 1.0 / wc]))
    moves = [np.array(v, float) for v in ((1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (-1, -1), (1, -1), (-1, 1))]
    last = 0
    while step >= min_step and n < max_evaluations:
        improved = False
        for j in [last] + [i for i in range(len(moves)) if i != last]:
            if n >= max_evaluations:
                break
            trial = r + step * moves[j]
            trial = np.where(trial < floor, np.nan, trial)      # negligible: exactly zero
            if np.array_equal(np.isnan(trial), np.isnan(r)) and np.allclose(np.nan_to_num(trial - r), 0.0):
                continue
            k_phi = best.K_phi
            ratios = np.where(np.isfinite(trial), 10.0 ** np.nan_to_num(trial), 0.0)
            g, w, k = _edge(designs, graded, PIDGains(k_phi, k_phi * ratios[0], k_phi * ratios[1]), tolerance)
            n += k
            if g is not None and w > wc:
                r, best, wc, improved, last = trial, g, w, True, j
                break
        if not improved:
            step /= 2.0
    return best, wc, n


def multistart(designs, specs, reference_frequency, n_starts=64, n_polish=3, decades=(-3.0, 2.0), seed=0,
               polish_evaluations=60, extra_starts=()):
    """Seeded starts over the gain box, the best distinct feasible ones polished on the true specs.

    Parameters
    ----------
    designs : list of EMFDesign
    specs : list of Spec
        At the starting boundaries; every spec but the crossover boundary must be met
        and the crossover is maximised.
    reference_frequency : float
        w_ref [rad/s] of the natural units k0 = w_ref / |Q(j w_ref)|: K_phi / k0,
        K_Iphi / (k0 w_ref) and K_p w_ref / k0 are sampled.
    n_starts : int
        Sobol starts (a power of two is best balanced).
    n_polish : int
        Best starts polished, one per basin (starts within 0.5 decade of a kept one in
        every gain count as the same basin): feasible ones by crossover first, then
        infeasible ones by penalty.
    decades : (float, float)
        log10 range of each scaled gain (the low end stands for "about zero").
    seed : int
        Seed of the Sobol scrambling.
    polish_evaluations : int
        Spec evaluations per polished start.
    extra_starts : sequence of PIDGains
        Gains polished as well when feasible (e.g. the previous design).

    Returns
    -------
    samples : pandas.DataFrame
        Every start scored: ``K_phi, K_Iphi, K_p, feasible, crossover, penalty, first_unmet``.
    candidates : list of (PIDGains, float)
        Polished designs and their crossovers [rad/s], best first.
    polished : pandas.DataFrame
        One row per polished start: start and end gains, crossovers, evaluations.

    Examples
    --------
    >>> from controllers import EMFDesign, default_specs, hover_roll_plant
    >>> d = EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.1, 0.05))
    >>> samples, cands, _ = multistart([d], default_specs(1.5), 1.5, n_starts=8, n_polish=1,
    ...                                polish_evaluations=6)
    >>> len(samples)
    8
    """
    lo, hi = (float(v) for v in decades)
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise ValueError(f"multistart: decades must be (low, high) with low < high, got {decades!r}")
    for name, v in (("n_starts", n_starts), ("n_polish", n_polish), ("polish_evaluations", polish_evaluations)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 0:
            raise ValueError(f"multistart: {name} must be an integer >= 0, got {v!r}")
    if not np.isfinite(reference_frequency) or reference_frequency <= 0:
        raise ValueError(f"multistart: reference_frequency must be > 0 rad/s, got {reference_frequency!r}")
    graded = _graded(specs)
    k0 = _gain_scale(designs, reference_frequency)
    unit = np.array([k0, k0 * reference_frequency, k0 / reference_frequency])
    x = lo + (hi - lo) * qmc.Sobol(3, scramble=True, seed=seed).random(int(n_starts)) if n_starts else np.zeros((0, 3))
    rows = []
    for point in x:
        g = PIDGains(*(unit * 10.0 ** point))
        ok, wc, penalty, unmet = _score(designs, graded, g)
        rows.append({"K_phi": g.K_phi, "K_Iphi": g.K_Iphi, "K_p": g.K_p, "feasible": ok, "crossover": wc,
                     "penalty": penalty, "first_unmet": unmet, "value": _value(ok, wc, penalty)})
    columns = ["K_phi", "K_Iphi", "K_p", "feasible", "crossover", "penalty", "first_unmet"]
    samples = pd.DataFrame(rows, columns=columns + ["value"])
    starts, kept = [], []
    # feasible starts by crossover, then (if too few) infeasible ones by penalty
    for r in samples.sort_values("value", ascending=False).itertuples():
        if len(starts) >= n_polish:
            break
        xl = np.log10(np.array([r.K_phi, r.K_Iphi, r.K_p]) / unit)
        if any(np.max(np.abs(xl - k)) < 0.5 for k in kept):
            continue
        kept.append(xl)
        starts.append(PIDGains(r.K_phi, r.K_Iphi, r.K_p))
    starts += list(extra_starts)
    out, polished = [], []
    for g0 in starts:
        g, wc, n = compass_polish(designs, specs, g0, unit, max_evaluations=polish_evaluations,
                                  decades=(min(lo, *_log(g0, unit)), max(hi, *_log(g0, unit))))
        polished.append({"start_K_phi": g0.K_phi, "start_K_Iphi": g0.K_Iphi, "start_K_p": g0.K_p,
                         "K_phi": g.K_phi, "K_Iphi": g.K_Iphi, "K_p": g.K_p, "crossover": wc,
                         "evaluations": n})
        if np.isfinite(wc):
            out.append((g, wc))
    return samples[columns], sorted(out, key=lambda c: -c[1]), pd.DataFrame(polished)

