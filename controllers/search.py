"""Independent check of the DMO: a dense search over the same gains, scored by the specs.

:func:`search_designs` scans rays of fixed gain ratios (K_Iphi/K_phi and
K_p/K_phi on log grids, zero included) densely in the overall gain K_phi, and
scores every point with :func:`~controllers.specs.evaluate_specs` only (no
optimiser formula); it then zooms in around the best feasible point.  The rays
follow the feasible set's long direction (the crossover grows with the overall
gain), so a fine step is affordable there.  It returns the feasible design with
the highest crossover (the smallest over the plants for a multi-model search).
Hundreds of full spec evaluations: meant for tests and benchmarks.

:func:`global_search` is the second, structure-free check: differential evolution
(scipy, seeded) over the three gains on log scales, every candidate scored by the
same spec evaluation, maximising the crossover subject to every other hard/soft
spec. It assumes nothing about rays or starting points, so an optimiser's answer
it cannot beat is trusted as the global one (within the search's budget).
"""
from __future__ import annotations

import itertools
import time
from dataclasses import dataclass

import numpy as np
import pandas as pd
from tqdm.auto import tqdm

from scipy.optimize import differential_evolution

from .emf import PIDGains
from .nlp import _gain_scale
from .scoring import _as_designs, design_margins
from .smooth import CrossoverMinimum, spec_with_constraint
from .specs import default_specs

__all__ = ["SearchResult", "search_designs", "global_search"]


@dataclass
class SearchResult:
    """Best feasible design of the search and every point scored."""

    design: object
    designs: list
    gains: PIDGains
    crossover: float
    points: pd.DataFrame
    wall_time: float

    @property
    def feasible(self):
        return self.design is not None

    def to_pandas(self):
        return self.points.copy()

    def plot(self, fig=None):
        """Scored points: crossover vs K_phi, feasible ones highlighted; returns a Figure."""
        from matplotlib.figure import Figure
        fig = fig or Figure(figsize=(6, 3.5), constrained_layout=True)
        ax = fig.subplots()
        p = self.points
        ok = p.feasible.astype(bool)
        ax.semilogx(p.K_phi[ok], p.crossover[ok], "o", ms=4, label="feasible")
        if self.feasible:
            ax.semilogx(self.gains.K_phi, self.crossover, "r*", ms=12, label="best feasible")
        ax.set_xlabel("K_phi [stick/rad]")
        ax.set_ylabel("crossover [rad/s]")
        ax.set_title(f"{int(ok.sum())} feasible of {len(p)} scored", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        return fig


def search_designs(design, specs=None, n_scale=15, scale_span=(0.2, 5.0), integral_ratios=(0.03, 1.0),
                   rate_ratios=(0.03, 2.0), n_ratio=5, zoom_rounds=2, reference_frequency=2.0,
                   progress=False):
    """Dense search for the feasible gain set with the highest crossover.

    Parameters
    ----------
    design : EMFDesign or list of EMFDesign
        Plant(s) with inverse plant and tau_eq; gains are ignored.
    specs : list of Spec, optional
        Every hard/soft spec must be met (default ``default_specs()``).
    n_scale : int
        Log-spaced K_phi values per ray, K_phi in ``scale_span`` x k0 with
        k0 = w_ref / |Q(j w_ref)| (|K_phi/w Q| = 1 at w_ref).
    scale_span : (float, float)
        Range of K_phi / k0.
    integral_ratios, rate_ratios : (float, float)
        Ranges of K_Iphi / (K_phi w_ref) and K_p w_ref / K_phi, each on
        ``n_ratio - 1`` log-spaced values plus 0.
    n_ratio : int
        Values per ratio range (0 included), at least 2.
    zoom_rounds : int
        Refinement rounds: a 3x3x3 grid around the best feasible point, one grid
        step wide, shrinking 3x per round.
    reference_frequency : float
        w_ref [rad/s].
    progress : bool
        Show a tqdm counter of the evaluated points.

    Returns
    -------
    SearchResult
        ``design`` is None when no point is feasible.
    """
    designs = _as_designs(design)
    specs = default_specs() if specs is None else specs
    if n_scale < 2 or n_ratio < 2:
        raise ValueError("n_scale and n_ratio must be >= 2")
    for name, span in (("scale_span", scale_span), ("integral_ratios", integral_ratios),
                       ("rate_ratios", rate_ratios)):
        try:
            lo, hi = (float(v) for v in span)
        except (TypeError, ValueError):
            raise ValueError(f"{name} must be (low, high), got {span!r}") from None
        if not (np.isfinite(lo) and np.isfinite(hi) and 0 < lo < hi):
            raise ValueError(f"{name} must be (low, high) with 0 < low < high, got {span!r}")
    if not np.isfinite(reference_frequency) or reference_frequency <= 0:
        raise ValueError(f"reference_frequency must be > 0 rad/s, got {reference_frequency!r}")
    crossover_name = spec_with_constraint(specs, CrossoverMinimum).name   # the spec that reads the crossover
    t0 = time.perf_counter()
    w_ref = reference_frequency
    k0 = _gain_scale(designs, w_ref)
    scales = k0 * np.geomspace(*scale_span, n_scale)
    r_i = np.r_[0.0, np.geomspace(*integral_ratios, n_ratio - 1)]
    r_p = np.r_[0.0, np.geomspace(*rate_ratios, n_ratio - 1)]
    rows, best = [], None
    bar = tqdm(desc="search", disable=not progress)

    def evaluate(k_phi, k_i, k_p):
        nonlocal best
        gains = PIDGains(float(k_phi), float(k_i), float(k_p))
        cands = [d.with_gains(gains) for d in designs]
        table, unmet, margin, limiting = design_margins(cands, specs, stop_at_first_unmet=True)
        ok = not unmet
        wc = float(table.loc[table.spec == crossover_name, "value"].min()) if ok else np.nan
        rows.append({"K_phi": gains.K_phi, "K_Iphi": gains.K_Iphi, "K_p": gains.K_p, "feasible": ok,
                     "crossover": wc, "first_unmet": unmet[0] if unmet else ""})
        bar.update(1)
        if ok and (best is None or wc > best[1]):
            best = (cands, wc, gains)

    for a, b in itertools.product(r_i, r_p):
        for k in scales:
            evaluate(k, a * k * w_ref, b * k / w_ref)
    step = np.log(scales[1] / scales[0])
    for _ in range(zoom_rounds):
        if best is None:
            break
        g = best[2].as_array()
        axes = [v * np.exp(np.linspace(-step, step, 3)) if v > 0 else np.r_[0.0] for v in g]
        for point in itertools.product(*axes):
            evaluate(*point)
        step /= 3.0
    bar.close()
    points = pd.DataFrame(rows)
    if best is None:
        return SearchResult(None, [], None, float("nan"), points, time.perf_counter() - t0)
    return SearchResult(best[0][0], best[0], best[2], best[1], points, time.perf_counter() - t0)


def global_search(design, specs, reference_frequency=2.0, decades=(-3.0, 2.0), maxiter=20, popsize=8, seed=0,
                  polish_rounds=6, progress=False):
    """Differential evolution over (K_phi, K_Iphi, K_p) for the feasible gains with the highest crossover.

    Parameters
    ----------
    design : EMFDesign or list of EMFDesign
        Plant(s) with inverse plant and tau_eq; gains are ignored.
    specs : list of Spec
        Every hard/soft spec must be met except the crossover-boundary spec (the one
        carrying a :class:`~controllers.smooth.CrossoverMinimum`), whose value is maximised.
        Each is graded on the candidate design, so specs that read more than its loop
        (the guards of :func:`controllers.multi_axis_guard.guard_specs`: the other closed
        loops' margins with the candidate's gains) are graded like the others.
    reference_frequency : float
        w_ref [rad/s] of the natural gain scales k0 = w_ref / |Q(j w_ref)|: K_phi / k0,
        K_Iphi / (k0 w_ref) and K_p w_ref / k0 are searched.
    decades : (float, float)
        log10 range of each scaled gain (the low end stands for "about zero").
    maxiter, popsize : int
        Differential-evolution generations and population per dimension (scipy's meaning).
    seed : int
        Seed of the Sobol initial population and of the evolution (reproducible).
    polish_rounds : int
        Compass-search rounds from the best feasible point (each gain up and down by a
        log step, the step halved every round, starting at 0.2 decade): the evolution
        approaches an optimum that sits on a spec boundary slowly.
    progress : bool
        Show a tqdm counter of the evaluated points.

    Returns
    -------
    SearchResult
        Best feasible design (``design`` None when no point is feasible) and every
        point scored (``penalty``: 0 when feasible, else 1 + the sum of the unmet
        specs' normalised margins, each capped at 10).

    Examples
    --------
    >>> from controllers import EMFDesign, PIDGains, default_specs, hover_roll_plant
    >>> d = EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.1, 0.05))
    >>> res = global_search(d, default_specs(1.5), maxiter=1, popsize=2)   # a tiny budget: ~16 points
    >>> res.points.columns.tolist()
    ['K_phi', 'K_Iphi', 'K_p', 'feasible', 'crossover', 'penalty']
    """
    designs = _as_designs(design)
    if not np.isfinite(reference_frequency) or reference_frequency <= 0:
        raise ValueError(f"global_search: reference_frequency must be > 0 rad/s, got {reference_frequency!r}")
    lo, hi = (float(v) for v in decades)
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise ValueError(f"global_search: decades must be (low, high) with low < high, got {decades!r}")
    for name, v in (("maxiter", maxiter), ("popsize", popsize)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 1:
            raise ValueError(f"global_search: {name} must be an integer >= 1, got {v!r}")
    crossover_name = spec_with_constraint(specs, CrossoverMinimum).name
    graded = [s for s in specs if s.kind != "objective" and s.name != crossover_name]
    k0 = _gain_scale(designs, reference_frequency)
    unit = np.array([k0, k0 * reference_frequency, k0 / reference_frequency])     # K_phi, K_Iphi, K_p
    t0 = time.perf_counter()
    rows, best = [], None
    bar = tqdm(desc="global search", disable=not progress)

    def cost(x):
        nonlocal best
        gains = PIDGains(*(unit * 10.0 ** np.asarray(x)))
        cands = [d.with_gains(gains) for d in designs]
        table, unmet, _, _ = design_margins(cands, graded + [spec_with_constraint(specs, CrossoverMinimum)])
        rest = table[table.spec != crossover_name]
        bad = rest[(rest.kind != "objective") & ~rest.met.astype(bool)]
        wc = float(table.loc[table.spec == crossover_name, "value"].min())
        ok = bad.empty and np.isfinite(wc)
        # infeasible points are ranked by how far they are from every boundary (graded, capped)
        penalty = 0.0 if ok else 1.0 + float(np.sum(np.minimum(-bad.margin.astype(float).to_numpy(), 10.0)))
        rows.append({"K_phi": gains.K_phi, "K_Iphi": gains.K_Iphi, "K_p": gains.K_p, "feasible": ok,
                     "crossover": wc if ok else np.nan, "penalty": penalty})
        bar.update(1)
        if ok and (best is None or wc > best[1]):
            best = (cands, wc, gains)
        return -wc if ok else penalty

    differential_evolution(cost, [(lo, hi)] * 3, maxiter=int(maxiter), popsize=int(popsize), seed=seed, tol=0.0,
                           polish=False, init="sobol")
    step = 0.2
    for _ in range(int(polish_rounds) if best is not None else 0):
        for k, sign in itertools.product(range(3), (1.0, -1.0)):
            trial = np.log10(best[2].as_array() / unit)     # cost() keeps the best feasible point
            trial[k] += sign * step
            cost(trial)
        step /= 2.0
    bar.close()
    points = pd.DataFrame(rows)
    if best is None:
        return SearchResult(None, [], None, float("nan"), points, time.perf_counter() - t0)
    return SearchResult(best[0][0], best[0], best[2], best[1], points, time.perf_counter() - t0)
