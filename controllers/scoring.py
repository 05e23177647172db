"""Scoring of gain sets by the true specs: the spec tables every DMO candidate is judged by.

Independent of the optimiser's smooth formulas: :func:`design_margins` evaluates
the specs (:func:`~controllers.specs.evaluate_specs`) on every plant of a
(multi-model) design and names what is unmet and what limits the design.
"""
from __future__ import annotations

from dataclasses import dataclass

import pandas as pd

from .emf import EMFDesign
from .smooth import CrossoverMinimum
from .specs import evaluate_specs

__all__ = ["OptimizationResult", "design_margins"]


@dataclass
class OptimizationResult:
    """One boundary set: the design found, its spec tables and what is unmet.

    Attributes
    ----------
    design : EMFDesign
        The design (first plant).
    designs : list of EMFDesign
        The same gains on every plant.
    feasible : bool
        Every hard and soft spec met on every plant.
    specs : pandas.DataFrame
        Stacked spec tables (column ``plant``).
    unmet : list of str
        Unmet specs.
    crossover_min, drb_min : float
        Crossover and DRB boundaries of this step [rad/s].
    min_margin : float
        Smallest normalised design margin (crossover boundary excluded).
    limiting_spec : str
        The spec that has it.
    ipopt_status : list of str
        IPOPT return status of every solve.
    starts : int
        Candidates scored.
    """

    design: EMFDesign
    designs: list
    feasible: bool
    specs: pd.DataFrame
    unmet: list
    crossover_min: float
    drb_min: float
    min_margin: float
    limiting_spec: str
    ipopt_status: list
    starts: int


def design_margins(designs, specs, labels=None, exclude=None, stop_at_first_unmet=False):
    """Spec table of one gain set over several designs, and its summary.

    Returns ``(table, unmet, min_margin, limiting_spec)``: the stacked
    :func:`evaluate_specs` tables (column ``plant``), the unmet hard/soft spec
    names (``"spec @ plant"`` when several; specs not applicable on an unstable
    loop are left out, EigLcG1 names the instability), the smallest CONDUIT normalised
    design margin over every non-objective spec and plant except ``exclude``
    (default: the specs carrying a :class:`~controllers.smooth.CrossoverMinimum`, the
    crossover boundary the DMO drives its design onto), and the spec that has it.

    Parameters
    ----------
    designs : EMFDesign or list of EMFDesign
        One gain set on one or several plants.
    specs : list of Spec
        Specs evaluated on each design (:func:`evaluate_specs`).
    labels : list of str, optional
        Plant labels (default ``"plant 0"``, ``"plant 1"``, ...).
    exclude : sequence of str, optional
        Names of the specs left out of the minimum margin (default: the
        crossover-boundary specs, found by their smooth constraint).
    stop_at_first_unmet : bool
        Stop at the first unmet spec (and the first plant with one), for speed.

    Returns
    -------
    table : pandas.DataFrame
    unmet : list of str
    min_margin : float
    limiting_spec : str
    """
    designs = designs if isinstance(designs, (list, tuple)) else [designs]
    if exclude is None:
        exclude = [s.name for s in specs if isinstance(getattr(s, "smooth", None), CrossoverMinimum)]
    labels = labels or [f"plant {k}" for k in range(len(designs))]
    tables = []
    for d, lab in zip(designs, labels):
        tables.append(evaluate_specs(d, specs, stop_at_first_unmet).assign(plant=lab))
        if stop_at_first_unmet and not tables[-1].met.all():
            break
    table = pd.concat(tables, ignore_index=True)
    hard_soft = table[table.kind != "objective"]
    # specs read "n/a" on an unstable loop are not named: EigLcG1 is, and it alone
    # already makes the design infeasible
    bad = hard_soft[~hard_soft.met & (hard_soft.status == "not met")]
    unmet = list(dict.fromkeys(bad.spec if len(designs) == 1 else bad.spec + " @ " + bad.plant))
    pool = hard_soft[~hard_soft.spec.isin(exclude) & ~hard_soft.status.str.startswith("n/a")]
    pool = pool if len(pool) else hard_soft
    k = pool.margin.astype(float).idxmin()
    limiting = table.loc[k, "spec"] + ("" if len(designs) == 1 else f" @ {table.loc[k, 'plant']}")
    return table, unmet, float(table.loc[k, "margin"]), limiting


def _as_designs(design):
    """One design or a list of them as a non-empty list of EMFDesign."""
    designs = list(design) if isinstance(design, (list, tuple)) else [design]
    if not designs:
        raise ValueError("at least one EMFDesign is needed")
    for d in designs:
        if not isinstance(d, EMFDesign):
            raise TypeError(f"expected EMFDesign objects, got {type(d).__name__}")
    return designs


def _scored(designs, specs, gains, crossover_min, drb_min, labels):
    """An OptimizationResult for a gain set scored by the true specs (no NLP)."""
    cands = [d.with_gains(gains) for d in designs]
    table, unmet, margin, limiting = design_margins(cands, specs, labels)
    return OptimizationResult(cands[0], cands, not unmet, table, unmet, crossover_min, drb_min, margin,
                              limiting, [], 0)

