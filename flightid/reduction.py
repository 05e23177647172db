"""Automatic parameter reduction (§6.4.4, Fig. 6.1).

The dissertation reduced its 12-state models by hand and lists automating it
as open work (§8.2 item 7). :func:`reduce` automates the loop: drop the most
insensitive parameter (insensitivity above the limit) first, else the one with
the highest Cramér-Rao bound above its limit; re-fit; keep the removal only if
J_ave rose by at most ``max_rise_average`` and no single cost by more than
``max_rise_single`` and the model stays stable; otherwise restore it and try
the next candidate.  Stops when no untried candidate remains.

A removal is also refused when the re-fit has no finite optimum -- what the
cost cannot show (on a coaxial hover fit, removing one delay let the collective
M and Lbar run to infinity along a flat direction at almost no cost): a parameter that
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

from ._validation import real_scalar
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
           max_condition=1e10, refuse_flat=True, batch=1, relative_rise=None,
           **fit_kwargs) -> ReductionResult:
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
    max_steps : int
        Refits tried (one per removal attempt).
    batch : int
        Candidates removed together in one refit (the ``batch`` worst), for large
        structures (the 180-parameter Eq. 6.5 start): the group is kept only if
        the joint removal passes every check a single removal must (the cost
        rises count for the group as a whole), else its worst member is tried
        alone in the same step. 1 (default): one at a time, Fig. 6.1.
    relative_rise : float, optional
        Rise limits relative to the fit's own cost and counted from the *first*
        fit instead of the absolute, step-by-step ``max_rise_average`` /
        ``max_rise_single``: a removal is kept only if J_ave rises by at most
        ``relative_rise * J_ave_first`` and no single J by more than
        ``5 * relative_rise * J_ave_first`` above its first-fit value (the 2 : 10
        ratio of the absolute guideline). At low noise (J_ave << 1) the absolute
        limits accept removals the data reject; these follow the noise. None
        (default) keeps the absolute limits.

    Returns
    -------
    ReductionResult

    Examples
    --------
    >>> import numpy as np, control
    >>> from flightid import frequency_sweep, frequency_response
    >>> t, u = frequency_sweep(0.5, 20.0, 60.0, 0.01, seed=0)
    >>> y = control.forced_response(control.tf([4.0], [1.0, 2.0]), t, u).outputs     # 4 / (s + 2)
    >>> data = frequency_response(t, u, y, w_min=0.5, w_max=20.0, output_names=["y"])
    >>> from flightid import FGCStructure, reduce
    >>> structure = FGCStructure([["f"]], [["g"]], [[1.0]], tau=[["tau"]], inputs=["u"], outputs=["y"],
    ...                          initial={"f": -1.0, "g": 1.0, "tau": 0.05})
    >>> reduction = reduce(structure, data)        # the data hold no delay: tau goes
    >>> reduction.removed
    ['tau']
    """
    if isinstance(batch, bool) or not isinstance(batch, (int, np.integer)) or batch < 1:
        raise IdentificationError(f"batch must be an integer >= 1, got {batch!r}")
    if relative_rise is not None:
        relative_rise = real_scalar("relative_rise", relative_rise, positive=True)
    current = fit(structure, data, **fit_kwargs)
    initial = current
    pairs = [(p.output, p.input) for p in current.pairs]
    ranges = {(p.output, p.input): (p.omega[0], p.omega[-1]) for p in current.pairs}
    fit_kwargs = {**fit_kwargs, "pairs": pairs, "frequency_ranges": ranges}
    tried = set(protected)
    log = []
    bar = tqdm(total=None, desc="reduce", disable=not progress)

    def attempt(names):
        """Refit with ``names`` fixed at zero: (trial or None, accepted, log fields)."""
        idle = []
        trial_structure = current.structure.fix(list(names), 0.0)
        try:
            if not trial_structure.free_names:
                raise IdentificationError("no free parameter would remain")
            trial = fit(trial_structure, data, **fit_kwargs)
            # a removal can leave parameters without any influence (the pole of a
            # mode whose gain was removed): hold them where they are, not at zero
            idle = [n for n in trial.degeneracy.no_influence if n not in names]
            if idle and len(idle) < len(trial.structure.free_names):
                trial = fit(trial.structure.fix(idle), data, **fit_kwargs)
        except (UnstableModelError, IdentificationError) as err:
            return None, False, dict(J_ave_after=float("nan"), max_single_rise=float("nan"), accepted=False,
                                     runaway=False, note=str(err)[:120])
        before = current.costs if relative_rise is None else initial.costs
        rise = max(trial.costs[k] - before[k] for k in before)
        if relative_rise is None:
            cost_ok = (trial.J_ave - current.J_ave <= max_rise_average) and rise <= max_rise_single
        else:
            cost_ok = (trial.J_ave - initial.J_ave <= relative_rise * initial.J_ave
                       and rise <= 5 * relative_rise * initial.J_ave)
        why = _runaway(current, trial, runaway_factor, max_condition, refuse_flat)
        ok = cost_ok and not why
        note = "" if ok else (f"runaway, no finite optimum: {why}; kept" if why else "cost rise too large; kept")
        if ok and idle:
            note = f"also held fixed (no influence left): {idle}"
        return trial, ok, dict(J_ave_after=trial.J_ave, max_single_rise=rise, accepted=ok, runaway=bool(why),
                               note=note)

    steps = 0
    while steps < max_steps:
        table = current.parameters[current.parameters.status == "free"]
        table = table[~table.parameter.isin(tried)]
        ins = table[table.insensitivity_pct > insensitivity_max].sort_values("insensitivity_pct", ascending=False)
        crb = table[table.cramer_rao_pct > cramer_rao_max].sort_values("cramer_rao_pct", ascending=False)
        # the worst first: insensitive parameters, then poorly determined ones
        candidates = [(n, "insensitivity", m) for n, m in zip(ins.parameter, ins.insensitivity_pct)]
        candidates += [(n, "cramer_rao", m) for n, m in zip(crb.parameter, crb.cramer_rao_pct)
                       if n not in set(ins.parameter)]
        if not candidates:
            break
        group = candidates[:batch]
        if len(group) > 1:
            # several at once (a large structure): kept only if the joint removal passes
            # every check of a single one; otherwise the worst is tried alone below
            names = [g[0] for g in group]
            steps += 1
            trial, ok, fields = attempt(names)
            bar.update()
            if ok:
                for name, reason, metric in group:
                    log.append({"parameter": name, "reason": reason, "metric_pct": metric,
                                "J_ave_before": current.J_ave, **fields,
                                "note": f"removed with {len(group) - 1} others. {fields['note']}".strip()})
                tried.update(names)
                current = trial
                continue
            log.append({"parameter": ", ".join(names), "reason": "batch", "metric_pct": group[0][2],
                        "J_ave_before": current.J_ave, **fields,
                        "note": f"batch of {len(group)} refused ({fields['note']}); one at a time"})
            if steps >= max_steps:
                break
        name, reason, metric = candidates[0]
        tried.add(name)
        steps += 1
        trial, ok, fields = attempt([name])
        log.append({"parameter": name, "reason": reason, "metric_pct": metric, "J_ave_before": current.J_ave,
                    **fields})
        if ok:
            current = trial
        bar.update()
    bar.close()
    columns = ["parameter", "reason", "metric_pct", "J_ave_before", "J_ave_after",
               "max_single_rise", "accepted", "runaway", "note"]
    return ReductionResult(current, initial, pd.DataFrame(log, columns=columns))
