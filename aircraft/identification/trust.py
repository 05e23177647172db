"""When an identified model is trusted: the guideline with its keep rule, in one place.

The guideline (Tischler & Remple; the dissertation's §3.3.7, §4.4) asks every free
parameter for a Cramér-Rao bound below ``settings.cramer_rao_max`` (20 %) and an
insensitivity below ``settings.insensitivity_max`` (10 %), and the reduction removes the
ones that fail one at a time (Fig. 6.1) -- unless a removal spoils the fit: a parameter
over the Cramér-Rao bound whose removal raised the average cost by more than 2, or one
response's cost by more than 10, stays, with that measured rise as its reason (read from
the reduction's own log). An insensitive parameter is never kept (it hardly moves the
cost, so no cost rise can keep it). Besides the parameters, a trusted model has no flat
direction of the cost (a low J on a flat valley is a failure, not a result) and an
average cost J_ave of at most :data:`TRUST_J_AVE_MAX` (a low bound on a poor fit is no
trust: the forward-flight mu = 0.2 model had every bound under 20 % at J_ave 490), or at
most the limit the caller gives (e.g. the dissertation's J_ave for the same structure
and band).

::

    trust_check(model) -> TrustCheck        (IdentifiedModel.trusted / .trust use it)
        .passes        True when every check holds
        .table         one row per free parameter: bounds, verdict (ok / kept / fails), reason
        .failures      the reasons the model is not trusted, as sentences
        .plot()        the parameters' bounds against the guideline

A model without a reduction log (a fit that was not reduced, a model file written
before files kept the log) is held to the bounds strictly: nothing says a parameter
over them cannot be removed.

The last part of the rule is reproduction: the same identification on a second wake
data set that differs at round-off (:func:`reproduction_check`; the pipeline makes one
with ``identify_inflow(..., reproduce=True)`` from a wake started a single-precision
rounding away) must keep the same parameters, each within its Cramér-Rao bound of the
first value. A model whose reproduction was not checked is judged on the rest, and
its check says so (``limits["reproduction"]``).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from flightid.reduction import ReductionRule

__all__ = ["TRUST_J_AVE_MAX", "TrustCheck", "trust_check", "ReproductionCheck", "reproduction_check"]

#: The CIFER guideline on the average cost of a trusted model (Tischler & Remple:
#: J_ave <= 100 "generally reflects an acceptable level of accuracy").
TRUST_J_AVE_MAX = 100.0


@dataclass
class TrustCheck:
    """Result of :func:`trust_check`.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per free parameter: ``parameter``, ``cramer_rao_pct`` (``standard_error_pct``
        with a residual rule), ``insensitivity_pct`` [%], ``verdict`` (``"ok"``, ``"kept"`` or ``"fails"``) and
        ``reason`` (empty for ``"ok"``).
    failures : list of str
        Why the model is not trusted (empty when it is).
    limits : dict
        The limits applied: ``cramer_rao_max``, ``insensitivity_max`` [%], ``j_ave_max``,
        ``max_rise_average``, ``max_rise_single`` [-], ``keep_rule`` (a reduction log was read).
    """

    table: pd.DataFrame
    failures: list = field(default_factory=list)
    limits: dict = field(default_factory=dict)

    @property
    def passes(self) -> bool:
        """True when the model is trusted."""
        return not self.failures

    def to_pandas(self) -> pd.DataFrame:
        """The per-parameter table (a copy)."""
        return self.table.copy()

    def plot(self, fig=None):
        """Cramér-Rao bound and insensitivity of every free parameter against the guideline.

        Returns
        -------
        matplotlib.figure.Figure
        """
        from matplotlib.figure import Figure
        fig = fig or Figure(figsize=(max(5.0, 0.35 * len(self.table) + 2.0), 3.6))
        ax = fig.add_subplot(111)
        x = np.arange(len(self.table))
        colours = {"ok": "tab:green", "kept": "tab:orange", "fails": "tab:red"}
        # the statistic the check judged by: the Cramér-Rao bound or the standard error
        col = "cramer_rao_pct" if "cramer_rao_pct" in self.table else "standard_error_pct"
        ax.bar(x - 0.2, self.table[col].clip(upper=1e4), 0.4, color=[colours[v] for v in self.table.verdict],
               label="Cramér-Rao [%]" if col == "cramer_rao_pct" else "standard error [%]")
        icol = "insensitivity_pct" if "insensitivity_pct" in self.table else "standard_error_alone_pct"
        ax.bar(x + 0.2, self.table[icol].clip(upper=1e4), 0.4, color="0.6", label="insensitivity [%]")
        ax.axhline(self.limits.get("cramer_rao_max", 20.0), color="k", ls="--", lw=0.8)
        ax.axhline(self.limits.get("insensitivity_max", 10.0), color="0.4", ls=":", lw=0.8)
        ax.set_yscale("log")
        ax.set_xticks(x, self.table.parameter, rotation=90, fontsize=7)
        ax.set_title(("trusted" if self.passes else "not trusted") + " (bar colour: ok / kept / fails)", fontsize=9)
        ax.legend(fontsize=7)
        fig.tight_layout()
        return fig


def _limit(settings, name, default):
    if settings is None:
        return default
    if isinstance(settings, dict):
        return float(settings.get(name, default))
    return float(getattr(settings, name, default))


@dataclass
class ReproductionCheck:
    """Result of :func:`reproduction_check`.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per parameter free in either fit: ``parameter``, ``value``, ``value_again``,
        ``cramer_rao_pct`` [%] (of the first fit), ``shift_pct`` (``|again - value| /
        |value|`` [%]), ``shift_in_bounds`` (shift over the bound [-]) and ``reproduced``.
    J_ave, J_ave_again : float
        Average costs of the two fits [-].
    """

    table: pd.DataFrame
    J_ave: float
    J_ave_again: float

    @property
    def passes(self) -> bool:
        """True when every parameter reproduces."""
        return bool(len(self.table)) and bool(self.table.reproduced.all())

    @property
    def failures(self) -> list:
        """The parameters that do not reproduce, as sentences."""
        out = []
        for r in self.table[~self.table.reproduced].itertuples():
            if not np.isfinite(r.value_again):
                out.append(f"{r.parameter} is not free in the second fit")
            elif not np.isfinite(r.value):
                out.append(f"{r.parameter} is free only in the second fit")
            else:
                out.append(f"{r.parameter} moved {r.shift_pct:.3g} % (its bound {r.cramer_rao_pct:.3g} %)")
        return out

    def to_pandas(self) -> pd.DataFrame:
        """The per-parameter table (a copy)."""
        return self.table.copy()


def _free_table(model):
    fit = getattr(model, "fit", None)
    params = getattr(fit, "parameters", None) if fit is not None else getattr(model, "parameters", None)
    if not isinstance(params, pd.DataFrame) or "status" not in params:
        raise ValueError(f"model {getattr(model, 'name', model)!r} has no parameter table to compare")
    return params[params.status == "free"].set_index("parameter")


def reproduction_check(model, again):
    """Whether an identification reproduces on a second data set, parameter by parameter.

    A parameter reproduces when it is free in both fits and the second value lies
    within the first fit's Cramér-Rao bound of the first (``|again - value| <=
    CR% |value|``): the bound is the scatter the data are said to allow, so a fit
    that moves further on data differing at round-off has found another optimum, not
    the parameter's value.

    Parameters
    ----------
    model, again : IdentifiedModel or ModelRecord
        The identification and the same identification on the second data set (each
        with a parameter table: ``parameter``, ``value``, ``status``, ``cramer_rao_pct``).

    Returns
    -------
    ReproductionCheck

    Raises
    ------
    ValueError
        A model without a parameter table.

    Examples
    --------
    >>> import pandas as pd
    >>> from types import SimpleNamespace
    >>> def model(values, cr, J):
    ...     table = pd.DataFrame({"parameter": ["m", "l"], "value": values, "status": "free",
    ...                           "cramer_rao_pct": cr, "insensitivity_pct": 1.0})
    ...     return SimpleNamespace(fit=SimpleNamespace(parameters=table), J_ave=J)
    >>> check = reproduction_check(model([1.0, 2.0], [5.0, 5.0], 10.0), model([1.01, 2.3], [5.0, 5.0], 10.2))
    >>> check.passes, check.table.reproduced.tolist()
    (False, [True, False])
    """
    a, b = _free_table(model), _free_table(again)
    rows = []
    for name in list(a.index) + [n for n in b.index if n not in a.index]:
        va = float(a.value[name]) if name in a.index else np.nan
        vb = float(b.value[name]) if name in b.index else np.nan
        cr = float(a.cramer_rao_pct[name]) if name in a.index else np.nan
        shift = abs(vb - va) / abs(va) * 100.0 if va != 0 else (0.0 if vb == 0 else np.inf)
        in_bounds = shift / cr if cr > 0 else (0.0 if shift == 0 else np.inf)
        ok = bool(np.isfinite(va) and np.isfinite(vb) and in_bounds <= 1.0)
        rows.append((name, va, vb, cr, shift, in_bounds, ok))
    table = pd.DataFrame(rows, columns=["parameter", "value", "value_again", "cramer_rao_pct", "shift_pct",
                                        "shift_in_bounds", "reproduced"])
    return ReproductionCheck(table, float(getattr(model, "J_ave", np.nan)), float(getattr(again, "J_ave", np.nan)))


def trust_check(model, *, j_ave_max=None, max_rise_average=2.0, max_rise_single=10.0, reproduction=None,
                rule=None):
    """Whether an identified model is trusted, parameter by parameter, with the reasons.

    Parameters
    ----------
    model : IdentifiedModel or ModelRecord
        An identified model (its fit, settings, degeneracy report and, when reduced, the
        reduction's log), or a model file's record (its parameter table and settings,
        and the reduction log and reproduction table when the file stores them).
    j_ave_max : float, optional
        Largest trusted average cost (default :data:`TRUST_J_AVE_MAX`; pass the
        dissertation's J_ave for the same structure and band where it prints one).
    max_rise_average, max_rise_single : float
        Cost rises [-] of a refused removal that keep a parameter over the Cramér-Rao
        bound: the average J, any single response's J (:func:`flightid.reduce`'s defaults).
    reproduction : ReproductionCheck, optional
        The same identification on a second data set (:func:`reproduction_check`; by
        default the model's own ``reproduction`` if it has one). Without one the
        reproduction is reported as not checked, not as a failure.
    rule : flightid.reduction.ReductionRule, optional
        The statistic and rise limits, as given to :func:`flightid.reduce`. With
        ``statistic="residual"`` a parameter is judged by its residual-scaled standard
        errors (columns ``standard_error_pct`` and ``standard_error_alone_pct``; the
        model's fit must be a :class:`flightid.FitResult`) against
        ``settings.cramer_rao_max`` and ``settings.insensitivity_max``; with
        ``relative_rise`` a refused removal keeps a parameter when it raised J_ave by
        more than ``relative_rise`` times the first fit's J_ave or one response's J
        by more than five times that (the reduction's own relative limits), instead
        of ``max_rise_average`` / ``max_rise_single``. Default: ``ReductionRule()``
        (the Cramér-Rao bound and the absolute limits).

    Returns
    -------
    TrustCheck

    Raises
    ------
    ValueError
        Non-positive limits, or a model without a parameter table.

    Examples
    --------
    >>> import pandas as pd
    >>> from types import SimpleNamespace
    >>> fit = SimpleNamespace(parameters=pd.DataFrame({"parameter": ["m", "l"], "status": ["free", "free"],
    ...                                                 "cramer_rao_pct": [4.0, 35.0],
    ...                                                 "insensitivity_pct": [1.0, 2.0]}), degeneracy=None)
    >>> check = trust_check(SimpleNamespace(fit=fit, J_ave=12.0, settings=None, reduction=None))
    >>> check.passes, check.table.verdict.tolist()
    (False, ['ok', 'fails'])
    """
    for name, v in (("max_rise_average", max_rise_average), ("max_rise_single", max_rise_single)):
        if not (isinstance(v, (int, float)) and v > 0):
            raise ValueError(f"{name} must be positive, got {v!r}")
    if rule is None:
        rule = ReductionRule()
    elif not isinstance(rule, ReductionRule):
        raise ValueError(f"rule must be a flightid.reduction.ReductionRule, got {type(rule).__name__}")
    j_max = TRUST_J_AVE_MAX if j_ave_max is None else j_ave_max
    if not (isinstance(j_max, (int, float)) and j_max > 0):
        raise ValueError(f"j_ave_max must be positive, got {j_ave_max!r}")
    fit = getattr(model, "fit", None)
    params = getattr(fit, "parameters", None) if fit is not None else getattr(model, "parameters", None)
    if not isinstance(params, pd.DataFrame) or "status" not in params:
        raise ValueError(f"model {getattr(model, 'name', model)!r} has no parameter table to judge")
    settings = getattr(model, "settings", None)
    cr_max = _limit(settings, "cramer_rao_max", 20.0)
    ins_max = _limit(settings, "insensitivity_max", 10.0)
    reduction = getattr(model, "reduction", None)
    log = getattr(reduction, "log", None) if reduction is not None else None
    stored = getattr(model, "reduction_log", None)          # a model file's copy of the log
    if log is None and isinstance(stored, pd.DataFrame) and len(stored):
        log = stored
    keep_rule = isinstance(log, pd.DataFrame)
    if rule.statistic == "residual":
        if not hasattr(fit, "residual_scaled_errors"):
            raise ValueError(f"model {getattr(model, 'name', model)!r} holds no fit to compute residual-scaled "
                             "standard errors from (rule.statistic='residual')")
        params = rule.table(fit)
    column, label = rule.column, ("Cramér-Rao" if rule.statistic == "cifer" else "standard error")
    rises = (max_rise_average, max_rise_single)
    if rule.relative_rise is not None and keep_rule:
        initial = getattr(reduction, "initial", None)
        j_first = float(initial.J_ave) if initial is not None else float(log.J_ave_before.iloc[0])
        rises = (rule.relative_rise * j_first, 5 * rule.relative_rise * j_first)
    free = params[params.status == "free"]
    failures, rows = [], []
    if not len(free):
        failures.append("no free parameter")
    for p in free.itertuples():
        cr, ins = float(getattr(p, column)), float(getattr(p, rule.insensitivity_column))
        bad_cr, bad_ins = not cr < cr_max, not ins < ins_max
        if not (bad_cr or bad_ins):
            rows.append((p.parameter, cr, ins, "ok", ""))
        elif bad_ins:
            rows.append((p.parameter, cr, ins, "fails", f"insensitivity {ins:.3g} % >= {ins_max:g} %: it hardly "
                         "moves the cost, so no cost rise can keep it"))
        elif not keep_rule:
            rows.append((p.parameter, cr, ins, "fails", f"{label} {cr:.3g} % >= {cr_max:g} % (no reduction log "
                         "says its removal is too costly)"))
        else:
            rows.append((p.parameter, cr, ins) + _keep_verdict(p.parameter, cr, cr_max, log, *rises, label=label,
                                                               from_first=rule.relative_rise is not None))
    table = pd.DataFrame(rows, columns=["parameter", column, rule.insensitivity_column, "verdict", "reason"])
    bad = table[table.verdict == "fails"]
    if len(bad):
        failures.append(f"parameters outside the bounds and not kept by the guideline: {bad.parameter.tolist()}")
    j_ave = float(getattr(model, "J_ave", np.nan))
    if not j_ave <= j_max:
        failures.append(f"J_ave {j_ave:.4g} > {j_max:g}")
    deg = getattr(fit, "degeneracy", None) if fit is not None else None
    if deg is not None and len(deg.flat_directions):
        failures.append(f"{len(deg.flat_directions)} flat direction(s) of the cost: "
                        + "; ".join(deg.flat_directions.parameters.astype(str)))
    if reproduction is None:
        reproduction = getattr(model, "reproduction", None)
        if isinstance(reproduction, pd.DataFrame):           # a model file's copy of the table
            reproduction = (ReproductionCheck(reproduction, float(getattr(model, "J_ave", np.nan)), np.nan)
                            if len(reproduction) else None)
    if reproduction is not None and not reproduction.passes:
        failures.append("the fit does not reproduce on a second data set: " + "; ".join(reproduction.failures))
    limits = {"cramer_rao_max": cr_max, "insensitivity_max": ins_max, "j_ave_max": float(j_max),
              "max_rise_average": float(rises[0]), "max_rise_single": float(rises[1]),
              "keep_rule": keep_rule,
              "reproduction": "not checked" if reproduction is None else
              ("reproduced" if reproduction.passes else "not reproduced")}
    if rule != ReductionRule():
        limits["rule"] = rule
    return TrustCheck(table, failures, limits)


def _keep_verdict(name, cr, cr_max, log, max_rise_average, max_rise_single, label="Cramér-Rao",
                  from_first=False):
    """(verdict, reason) of a parameter over the bound, from the reduction's log (rises of J_ave
    step by step, or counted from the first fit with ``from_first``)."""
    tries = log[(log.parameter == name) & ~log.accepted.astype(bool)]
    j_first = float(log.J_ave_before.iloc[0]) if len(log) else np.nan
    for t in tries.itertuples():
        rise_avg = float(t.J_ave_after) - (j_first if from_first else float(t.J_ave_before))
        rise_one = float(t.max_single_rise)
        if bool(t.runaway) or not (np.isfinite(rise_avg) and np.isfinite(rise_one)):
            continue
        if rise_avg > max_rise_average or rise_one > max_rise_single:
            return "kept", (f"{label} {cr:.3g} % >= {cr_max:g} %, kept: removing it raised J_ave by "
                            f"{rise_avg:.3g} (limit {max_rise_average:g}) and one response's J by {rise_one:.3g} "
                            f"(limit {max_rise_single:g})")
    why = ("its removal was refused only because the fit ran away (a flat valley, not a kept parameter)"
           if len(tries) and tries.runaway.astype(bool).any() else
           "the reduction never found its removal too costly" if len(tries) else
           "the reduction did not try to remove it")
    return "fails", f"{label} {cr:.3g} % >= {cr_max:g} %: {why}"
