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

from dataclasses import dataclass, replace

import numpy as np
import pandas as pd
from tqdm.auto import tqdm

from ._validation import real_scalar
from .errors import IdentificationError, InputValueError, UnstableModelError
from .fitting import FitResult, fit
from .statistics import COVARIANCES, NOISE_ESTIMATES, parameter_statistics

__all__ = ["reduce", "ReductionResult", "ReductionRule", "STATISTICS"]

#: Statistics a reduction (and the trust rule) can judge a parameter's determination by.
STATISTICS = ("cifer", "residual")


@dataclass(frozen=True)
class ReductionRule:
    """Which statistic and which cost-rise limits judge a parameter: one settings place for
    :func:`reduce` and the trust rule (``aircraft.identification.trust_check(..., rule=...)``).

    Parameters
    ----------
    statistic : {"cifer", "residual"}
        ``"cifer"`` (default): a parameter is poorly determined when its Cramér-Rao
        bound exceeds the limit (the dissertation's guideline, blind to the noise
        level). ``"residual"``: when its residual-scaled standard error
        (:func:`flightid.statistics.parameter_statistics`, one standard deviation,
        in % of the value) exceeds the same limit, and it is insensitive when its
        standard error with the others held (``standard_error_alone_pct``) exceeds
        the insensitivity limit.
    covariance : {"white", "sandwich"}
        Convention of the residual-scaled standard error (``statistic="residual"`` only).
    noise : {"residual", "differences"}
        What measures the noise in that standard error (``statistic="residual"`` only;
        :func:`flightid.statistics.residual_scaled_errors`).
    relative_rise : float, optional
        Rise limits relative to the first fit's J_ave, counted from the first fit
        (see :func:`reduce`). None (default): the absolute, step-by-step limits.

    Raises
    ------
    ValueError
        An unknown statistic or covariance, or a non-positive ``relative_rise``.

    Examples
    --------
    >>> ReductionRule(statistic="residual", relative_rise=0.5).column
    'standard_error_pct'
    """

    statistic: str = "cifer"
    covariance: str = "white"
    noise: str = "residual"
    relative_rise: float | None = None

    def __post_init__(self):
        if not (isinstance(self.noise, str) and self.noise in NOISE_ESTIMATES):
            raise InputValueError(f"noise must be one of {NOISE_ESTIMATES}, got {self.noise!r}")
        if not (isinstance(self.statistic, str) and self.statistic in STATISTICS):
            raise InputValueError(f"statistic must be one of {STATISTICS}, got {self.statistic!r}")
        if not (isinstance(self.covariance, str) and self.covariance in COVARIANCES):
            raise InputValueError(f"covariance must be one of {COVARIANCES}, got {self.covariance!r}")
        if self.relative_rise is not None:
            object.__setattr__(self, "relative_rise",
                               real_scalar("relative_rise", self.relative_rise, positive=True))

    @property
    def column(self) -> str:
        """Column of the parameter table the determination limit applies to."""
        return "cramer_rao_pct" if self.statistic == "cifer" else "standard_error_pct"

    @property
    def insensitivity_column(self) -> str:
        """Column of the parameter table the insensitivity limit applies to."""
        return "insensitivity_pct" if self.statistic == "cifer" else "standard_error_alone_pct"

    def table(self, result) -> pd.DataFrame:
        """``result``'s parameter table with the rule's statistic (``self.column``) in it."""
        if self.statistic == "cifer":
            return result.parameters
        return parameter_statistics(result, covariance=self.covariance, noise=self.noise)


@dataclass
class ReductionResult:
    """Outcome of :func:`reduce`: the final fit, the initial fit and a log (DataFrame)."""

    result: FitResult
    initial: FitResult
    log: pd.DataFrame
    #: the statistic and rise limits the reduction used
    rule: ReductionRule = ReductionRule()

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
           max_condition=1e10, refuse_flat=True, batch=1, relative_rise=None, rule=None,
           **fit_kwargs) -> ReductionResult:
    """Remove insensitive / poorly determined parameters while the fit stays good.

    Parameters
    ----------
    structure, data :
        As for :func:`fit` (``fit_kwargs`` are passed on, with the same pairs
        and frequency ranges at every step so costs are comparable).
    insensitivity_max, cramer_rao_max : float
        Candidate thresholds [%] (guideline: 10 % and 20 %); ``cramer_rao_max``
        applies to the rule's statistic (the standard error with ``"residual"``).
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
        (default) keeps the absolute limits. Shorthand for
        ``rule=ReductionRule(relative_rise=...)``.
    rule : ReductionRule, optional
        The statistic that selects poorly determined parameters (``cramer_rao_max``
        then applies to it) and the rise limits, in one place the trust rule also
        takes. Default: ``ReductionRule()`` (CIFER bounds, absolute limits).

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
    if rule is None:
        rule = ReductionRule(relative_rise=relative_rise)
    elif not isinstance(rule, ReductionRule):
        raise InputValueError(f"rule must be a ReductionRule, got {type(rule).__name__}")
    elif relative_rise is not None:
        if rule.relative_rise not in (None, relative_rise):
            raise InputValueError(f"relative_rise={relative_rise!r} contradicts rule.relative_rise="
                                  f"{rule.relative_rise!r}: give it in one place")
        rule = replace(rule, relative_rise=relative_rise)
    relative_rise = rule.relative_rise
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
        table = rule.table(current)
        table = table[table.status == "free"]
        table = table[~table.parameter.isin(tried)]
        icol, col = rule.insensitivity_column, rule.column
        ins = table[table[icol] > insensitivity_max].sort_values(icol, ascending=False)
        crb = table[table[col] > cramer_rao_max].sort_values(col, ascending=False)
        reason = "cramer_rao" if rule.statistic == "cifer" else "standard_error"
        # the worst first: insensitive parameters, then poorly determined ones
        candidates = [(n, "insensitivity", m) for n, m in zip(ins.parameter, ins[icol])]
        candidates += [(n, reason, m) for n, m in zip(crb.parameter, crb[col])
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
    return ReductionResult(current, initial, pd.DataFrame(log, columns=columns), rule)
