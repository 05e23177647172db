"""Automatic parameter reduction (§6.4.4, Fig. 6.1).

The dissertation reduced its 12-state models by hand and lists automating it
as open work (§8.2 item 7). :func:`reduce` automates the loop: drop the most
insensitive parameter (insensitivity above the limit) first, else the one with
the highest Cramér-Rao bound above its limit; re-fit; keep the removal only if
J_ave rose by at most ``max_rise_average`` and no single cost by more than
``max_rise_single`` and the model stays stable; otherwise restore it and try
the next candidate.  Stops when no untried candidate remains.

A removal is also refused when the re-fit has no finite optimum -- what the
cost cannot show (issue 9: removing one delay let the collective M and Lbar
run to infinity along a flat direction at almost no cost): a parameter that
grows by orders of magnitude (``runaway_factor``), a Hessian condition number
that blows up (``max_condition``), or a new flat direction. The log says why.
Parameters a removal leaves without any influence (the pole of a mode whose
gain was removed) are held fixed at their value, and the log says so.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
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


def _runaway(before, after, runaway_factor, max_condition, refuse_flat):
    """Why the re-fit ``after`` has no finite optimum (empty string if it has one)."""
    reasons = []
    if runaway_factor is not None:
        old = before.structure.values
        mags = np.abs([old[n] for n in before.structure.free_names if old[n] != 0])
        floor = 0.01 * float(np.median(mags)) if mags.size else 0.0
        for n in after.structure.free_names:
            a, b = after.structure.values[n], old[n]
            ref = max(abs(b), floor)
            if ref > 0 and abs(a) > runaway_factor * ref:
                reasons.append(f"{n} ran away {b:.4g} -> {a:.4g} (x{abs(a) / ref:.3g})")
    if max_condition is not None:
        c0, c1 = before.condition_number, after.condition_number
        if c1 > max_condition and not c1 <= 1e3 * c0:
            reasons.append(f"Hessian condition number rose {c0:.3g} -> {c1:.3g}")
    if refuse_flat and len(after.flat_directions) > len(before.flat_directions):
        new = after.flat_directions.parameters.iloc[0]
        reasons.append(f"a flat direction appeared ({new})")
    return "; ".join(reasons)


def reduce(structure, data, *, insensitivity_max=10.0, cramer_rao_max=20.0, max_rise_average=2.0,
           max_rise_single=10.0, protected=(), max_steps=100, progress=False, runaway_factor=100.0,
           max_condition=1e10, refuse_flat=True, **fit_kwargs) -> ReductionResult:
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
    runaway_factor : float or None
        Refuse a removal after which a free parameter's magnitude grows by more
        than this factor (relative to its value before, floored at 1 % of the
        median free-parameter magnitude). None disables.
    max_condition : float or None
        Refuse a removal after which the Hessian condition number (relative
        units) exceeds this and rose more than 1000-fold. None disables.
    refuse_flat : bool
        Refuse a removal after which the fit has more flat directions than before.

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
        idle = []
        trial_structure = current.structure.fix(name, 0.0)
        entry = {"parameter": name, "reason": reason, "metric_pct": metric,
                 "J_ave_before": current.J_ave}
        try:
            if not trial_structure.free_names:
                raise IdentificationError("no free parameter would remain")
            trial = fit(trial_structure, data, **fit_kwargs)
            # a removal can leave parameters without any influence (the pole of a
            # mode whose gain was removed): hold them where they are, not at zero
            idle = [n for n in trial.degeneracy.no_influence if n != name]
            if idle and len(idle) < len(trial.structure.free_names):
                trial = fit(trial.structure.fix(idle), data, **fit_kwargs)
        except (UnstableModelError, IdentificationError) as err:
            entry.update(J_ave_after=float("nan"), max_single_rise=float("nan"), accepted=False,
                         runaway=False, note=str(err)[:120])
            log.append(entry)
            bar.update()
            continue
        before = current.costs
        rise = max(trial.costs[k] - before[k] for k in before)
        cost_ok = (trial.J_ave - current.J_ave <= max_rise_average) and rise <= max_rise_single
        why = _runaway(current, trial, runaway_factor, max_condition, refuse_flat)
        ok = cost_ok and not why
        note = "" if ok else (f"runaway, no finite optimum: {why}; kept" if why else "cost rise too large; kept")
        if ok and idle:
            note = f"also held fixed (no influence left): {idle}"
        entry.update(J_ave_after=trial.J_ave, max_single_rise=rise, accepted=ok, runaway=bool(why),
                     note=note)
        log.append(entry)
        if ok:
            current = trial
        bar.update()
    bar.close()
    columns = ["parameter", "reason", "metric_pct", "J_ave_before", "J_ave_after",
               "max_single_rise", "accepted", "runaway", "note"]
    return ReductionResult(current, initial, pd.DataFrame(log, columns=columns))
