"""Automatic parameter reduction (§6.4.4, Fig. 6.1).

The dissertation reduced its 12-state models by hand and lists automating it
as open work (§8.2 item 7). :func:`reduce` automates the loop: drop the most
insensitive parameter (insensitivity above the limit) first, else the one with
the highest Cramér-Rao bound above its limit; re-fit; keep the removal only if
J_ave rose by at most ``max_rise_average`` and no single cost by more than
``max_rise_single`` and the model stays stable; otherwise restore it and try
the next candidate.  Stops when no untried candidate remains.
"""
from __future__ import annotations

from dataclasses import dataclass

import pandas as pd
from tqdm.auto import tqdm

from .errors import IdentificationError, UnstableModelError
from .fitting import FitResult, fit

__all__ = ["reduce", "ReductionResult"]


@dataclass
class ReductionResult:
    """Outcome of :func:`reduce`: the final fit, the initial fit and a log (DataFrame)."""

    result: FitResult
    initial: FitResult
    log: pd.DataFrame

    @property
    def removed(self) -> list:
        """Parameters removed (fixed to zero) by the reduction."""
        return list(self.log.loc[self.log.accepted, "parameter"])

    def to_pandas(self) -> pd.DataFrame:
        return self.log.copy()

    def plot(self, fig=None):
        return self.result.plot(fig=fig)


def reduce(structure, data, *, insensitivity_max=10.0, cramer_rao_max=20.0, max_rise_average=2.0,
           max_rise_single=10.0, protected=(), max_steps=100, progress=False, **fit_kwargs) -> ReductionResult:
    """Remove insensitive / poorly determined parameters while the fit stays good.

    Parameters
    ----------
    structure, data :
        As for :func:`fit` (``fit_kwargs`` are passed on, with the same pairs
        and frequency ranges at every step so costs are comparable).
    insensitivity_max, cramer_rao_max : float
        Candidate thresholds [%] (guideline: 10 % and 20 %).
    max_rise_average, max_rise_single : float
        Acceptable rise of J_ave and of any single J after a removal.
    protected : iterable of str
        Parameters never removed.

    Returns
    -------
    ReductionResult
    """
    current = fit(structure, data, **fit_kwargs)
    initial = current
    pairs = [(p.output, p.input) for p in current.pairs]
    ranges = {(p.output, p.input): (p.omega[0], p.omega[-1]) for p in current.pairs}
    fit_kwargs = {**fit_kwargs, "pairs": pairs, "frequency_ranges": ranges}
    tried = set(protected)
    log = []
    bar = tqdm(total=None, desc="reduce", disable=not progress)
    for _ in range(max_steps):
        table = current.parameters[current.parameters.status == "free"]
        table = table[~table.parameter.isin(tried)]
        ins = table[table.insensitivity_pct > insensitivity_max].sort_values("insensitivity_pct", ascending=False)
        crb = table[table.cramer_rao_pct > cramer_rao_max].sort_values("cramer_rao_pct", ascending=False)
        if len(ins):
            name, reason, metric = ins.parameter.iloc[0], "insensitivity", ins.insensitivity_pct.iloc[0]
        elif len(crb):
            name, reason, metric = crb.parameter.iloc[0], "cramer_rao", crb.cramer_rao_pct.iloc[0]
        else:
            break
        tried.add(name)
        trial_structure = current.structure.fix(name, 0.0)
        entry = {"parameter": name, "reason": reason, "metric_pct": metric,
                 "J_ave_before": current.J_ave}
        try:
            if not trial_structure.free_names:
                raise IdentificationError("no free parameter would remain")
            trial = fit(trial_structure, data, **fit_kwargs)
        except (UnstableModelError, IdentificationError) as err:
            entry.update(J_ave_after=float("nan"), max_single_rise=float("nan"), accepted=False,
                         note=str(err)[:120])
            log.append(entry)
            bar.update()
            continue
        before = current.costs
        rise = max(trial.costs[k] - before[k] for k in before)
        ok = (trial.J_ave - current.J_ave <= max_rise_average) and rise <= max_rise_single
        entry.update(J_ave_after=trial.J_ave, max_single_rise=rise, accepted=ok,
                     note="" if ok else "cost rise too large; kept")
        log.append(entry)
        if ok:
            current = trial
        bar.update()
    bar.close()
    columns = ["parameter", "reason", "metric_pct", "J_ave_before", "J_ave_after",
               "max_single_rise", "accepted", "note"]
    return ReductionResult(current, initial, pd.DataFrame(log, columns=columns))
