"""The DMO's global stage: the gain space sampled and scored by the true specs.

A design-margin optimiser that raises its boundaries by continuation follows one
connected piece of the feasible set. On some plants the feasible set is not
connected along the crossover: a low-damped closed-loop mode inside the 0.5-4 rad/s
band at a moderate gain leaves that band at a higher one, so the designs at
2 rad/s and at 7 rad/s are separated by an infeasible gap that no continuation
crosses. This module gives the optimiser a view of the whole space:

* :func:`sample_gains` scores a scrambled Sobol sample of (K_phi, K_Iphi, K_p),
  with the two gain ratios exactly zero in a share of the samples (a zero integral
  or rate gain is often best), against every hard and soft spec (no optimiser
  formula: :func:`~controllers.specs.evaluate_specs` and the metrics);
* :func:`extend_along_ray` raises the overall gain of a feasible design along its
  fixed gain ratios (expansion, then bisection) to the largest feasible one: along a
  ray the crossover grows with the gain, so this pushes a sampled design to the edge
  of its feasible piece.

:func:`controllers.dmo.dmo` runs both and then its NLP continuation from the best
candidates.
"""
from __future__ import annotations

import numpy as np
import pandas as pd
from scipy.stats import qmc

from . import metrics as m
from .emf import PIDGains
from .specs import evaluate_specs

__all__ = ["sample_gains", "extend_along_ray", "score_gains"]


def score_gains(designs, specs, gains):
    """Feasibility and crossover of one gain set on every design.

    Parameters
    ----------
    designs : list of EMFDesign
    specs : list of Spec
        Every hard and soft spec must reach Level 1.
    gains : PIDGains

    Returns
    -------
    feasible : bool
    crossover : float
        Smallest loop crossover frequency over the designs [rad/s] (NaN when not feasible).
    first_unmet : str
        Name of the first unmet spec ("" when feasible).
    """
    cands = [d.with_gains(gains) for d in designs]
    for d in cands:
        table = evaluate_specs(d, specs, stop_at_first_unmet=True)
        bad = table[(table.kind != "objective") & ~table.met]
        if len(bad):
            return False, float("nan"), str(bad.spec.iloc[0])
    return True, float(min(m.crossover_frequency(d.broken_loop()) for d in cands)), ""


def sample_gains(designs, specs, scale, reference_frequency, n_samples=128, seed=0,
                 scale_span=(0.2, 10.0), integral_ratios=(0.01, 1.0), rate_ratios=(0.01, 3.0),
                 zero_fraction=0.25):
    """Score a quasi-random sample of the gain space against the true specs.

    Parameters
    ----------
    designs : list of EMFDesign
        One gain set is scored on every design (robust design: all must pass).
    specs : list of Spec
    scale : float
        Gain scale k0 [stick/rad]: K_phi = k0 puts |L| near 1 at ``reference_frequency``.
    reference_frequency : float
        w_ref [rad/s] of the gain ratios.
    n_samples : int
        Sobol points (a power of two is best balanced).
    seed : int
        Seed of the Sobol scrambling.
    scale_span : (float, float)
        Range of K_phi / k0 (log-uniform).
    integral_ratios, rate_ratios : (float, float)
        Ranges of K_Iphi / (K_phi w_ref) and K_p w_ref / K_phi (log-uniform).
    zero_fraction : float
        Share of the samples in which each ratio is exactly zero.

    Returns
    -------
    pandas.DataFrame
        One row per sample: ``K_phi, K_Iphi, K_p, feasible, crossover, first_unmet``.
    """
    if not np.isfinite(scale) or scale <= 0:
        raise ValueError(f"scale must be a finite gain > 0, got {scale!r}")
    if not np.isfinite(reference_frequency) or reference_frequency <= 0:
        raise ValueError(f"reference_frequency must be > 0 rad/s, got {reference_frequency!r}")
    for name, span in (("scale_span", scale_span), ("integral_ratios", integral_ratios),
                       ("rate_ratios", rate_ratios)):
        lo, hi = (float(v) for v in span)
        if not (np.isfinite(lo) and np.isfinite(hi) and 0 < lo < hi):
            raise ValueError(f"{name} must be (low, high) with 0 < low < high, got {span!r}")
    if not 0 <= zero_fraction < 1:
        raise ValueError(f"zero_fraction must be in [0, 1), got {zero_fraction!r}")
    if int(n_samples) < 1:
        raise ValueError(f"n_samples must be >= 1, got {n_samples!r}")
    u = qmc.Sobol(3, scramble=True, seed=seed).random(int(n_samples))

    def log_between(x, span):
        lo, hi = span
        return lo * (hi / lo) ** x

    def ratio(x, span):
        # the lowest zero_fraction of the unit interval maps to exactly zero
        y = (x - zero_fraction) / (1 - zero_fraction)
        return np.where(x < zero_fraction, 0.0, log_between(np.clip(y, 0, 1), span))

    k_phi = scale * log_between(u[:, 0], scale_span)
    k_i = ratio(u[:, 1], integral_ratios) * k_phi * reference_frequency
    k_p = ratio(u[:, 2], rate_ratios) * k_phi / reference_frequency
    rows = []
    for a, b, c in zip(k_phi, k_i, k_p):
        ok, wc, unmet = score_gains(designs, specs, PIDGains(float(a), float(b), float(c)))
        rows.append({"K_phi": float(a), "K_Iphi": float(b), "K_p": float(c), "feasible": ok,
                     "crossover": wc, "first_unmet": unmet})
    return pd.DataFrame(rows)


def extend_along_ray(designs, specs, gains, tolerance=0.005, growth=1.2, max_steps=40):
    """Largest feasible overall gain along a feasible design's fixed gain ratios.

    Parameters
    ----------
    designs : list of EMFDesign
    specs : list of Spec
    gains : PIDGains
        A feasible gain set (its ratios K_Iphi/K_phi and K_p/K_phi are kept).
    tolerance : float
        Relative bisection tolerance on the gain factor.
    growth : float
        Factor per expanding step (> 1).
    max_steps : int
        Expanding steps at most.

    Returns
    -------
    gains : PIDGains
        The largest feasible gain set found on the ray (``gains`` itself if no larger one is).
    crossover : float
        Its crossover [rad/s].
    evaluations : int
        Spec evaluations spent.
    """
    base = gains.as_array()
    ok, wc, _ = score_gains(designs, specs, gains)
    n = 1
    if not ok:
        raise ValueError("extend_along_ray needs a feasible starting gain set")
    lo, hi, best = 1.0, None, (gains, wc)
    for _ in range(max_steps):
        t = lo * growth
        g = PIDGains(*(base * t))
        ok, w, _ = score_gains(designs, specs, g)
        n += 1
        if not ok:
            hi = t
            break
        lo, best = t, (g, w)
    while hi is not None and hi / lo - 1 > tolerance:
        t = np.sqrt(lo * hi)
        g = PIDGains(*(base * t))
        ok, w, _ = score_gains(designs, specs, g)
        n += 1
        if ok:
            lo, best = t, (g, w)
        else:
            hi = t
    return best[0], best[1], n
