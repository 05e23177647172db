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

The last part of the rule is reproduction on a second wake data set that differs at
round-off (:func:`reproduction_check`; the pipeline makes one with
``identify_inflow(..., reproduce=True)`` from a wake started a single-precision rounding
away). It is reported in two parts: whether the whole identification again keeps the
same structure, and whether the first model's final structure, refitted on the second
data set from the first fit's start, keeps every parameter within its Cramér-Rao bound
of the first value. The verdict requires the second (the fit reproduces); the first is
reported beside it (see :func:`reproduction_check` for why, and its
``rule="identification"`` for the former verdict that required both). A model whose
reproduction was not checked is judged on the rest, and its check says so
(``limits["reproduction"]``).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from flightid.reduction import ReductionRule

__all__ = ["TRUST_J_AVE_MAX", "TrustCheck", "trust_check", "ReproductionCheck", "reproduction_check",
           "REPRODUCTION_RULES", "refit_structure"]

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
        ``max_rise_average``, ``max_rise_single`` [-], ``keep_rule`` (a reduction log was read),
        ``reproduction`` (``"reproduced"``, ``"not reproduced"`` or ``"not checked"``) and
        ``reproduction_structure`` (``"same"``, ``"different"`` or ``"not checked"``).
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


#: The checks :func:`reproduction_check` can judge a model on.
REPRODUCTION_RULES = ("refit", "identification")


@dataclass
class ReproductionCheck:
    """Result of :func:`reproduction_check`.

    Attributes
    ----------
    table : pandas.DataFrame
        The table the verdict is judged on (:attr:`refit` under the ``"refit"`` rule,
        :attr:`identification` under ``"identification"``). One row per parameter:
        ``parameter``, ``value``, ``value_again``, ``cramer_rao_pct`` [%] (of the first
        fit), ``shift_pct`` (``|again - value| / |value|`` [%]), ``shift_in_bounds``
        (shift over the bound [-]) and ``reproduced``.
    J_ave, J_ave_again : float
        Average costs of the first and of the second identification [-].
    identification : pandas.DataFrame or None
        The whole identification again (start, fit, reduction) on the second data
        set against the first, over the parameters free in either (None: not run).
    refit : pandas.DataFrame or None
        The first model's final structure refitted on the second data set from the
        first fit's start, over the first fit's free parameters (None: not run).
    J_ave_refit : float
        Average cost of the refit [-] (NaN without one).
    rule : str
        ``"refit"`` or ``"identification"``: which of the two the verdict requires.
    refit_error : str
        Why the refit failed (empty when it ran).
    """

    table: pd.DataFrame
    J_ave: float
    J_ave_again: float
    identification: pd.DataFrame | None = None
    refit: pd.DataFrame | None = None
    J_ave_refit: float = np.nan
    rule: str = "identification"
    refit_error: str = ""

    @property
    def passes(self) -> bool:
        """True when the check the rule requires holds (every parameter of its table reproduces)."""
        if self.rule == "refit" and self.refit_error:
            return False
        return bool(len(self.table)) and bool(self.table.reproduced.all())

    @property
    def same_structure(self):
        """Whether the second identification's reduction kept the same free parameters
        (None when the identification was not run again)."""
        t = self.identification
        if t is None:
            return None
        return bool(np.isfinite(t.value.to_numpy(float)).all() and np.isfinite(t.value_again.to_numpy(float)).all())

    @property
    def parameters_reproduce(self):
        """Whether every parameter of the refit lies within its bound of the first value
        (None when there is no refit; False when it failed)."""
        if self.refit_error:
            return False
        if self.refit is None:
            return None
        return bool(len(self.refit)) and bool(self.refit.reproduced.all())

    @property
    def failures(self) -> list:
        """Why the check the rule requires fails, as sentences."""
        if self.rule == "refit" and self.refit_error:
            return [f"the refit on the second data set failed: {self.refit_error}"]
        return _failures(self.table)

    @property
    def structure_failures(self) -> list:
        """The parameters the two reductions did not both keep, as sentences."""
        t = self.identification
        if t is None:
            return []
        return [s for s in _failures(t) if " free " in s]

    def summary(self) -> str:
        """Both parts in words: the structure the reduction keeps, the parameters of the refit."""
        def count(t):
            worst = t.shift_in_bounds.replace(np.inf, np.nan)
            return (f"{int(t.reproduced.sum())} of {len(t)} parameters reproduced, largest shift "
                    f"{worst.max():.3g} bounds" if worst.notna().any() else f"{int(t.reproduced.sum())} of {len(t)}")
        lines = [f"reproduction ({self.rule} rule): {'passes' if self.passes else 'fails'}"]
        if self.identification is not None:
            lines.append(f"  identification again: same structure {self.same_structure}; "
                         f"{count(self.identification)}; J_ave {self.J_ave:.4g} -> {self.J_ave_again:.4g}")
        if self.refit is not None:
            lines.append(f"  refit of the first structure: {count(self.refit)}; J_ave {self.J_ave_refit:.4g}")
        elif self.refit_error:
            lines.append(f"  refit of the first structure failed: {self.refit_error}")
        return "\n".join(lines)

    def to_pandas(self) -> pd.DataFrame:
        """Both parts, one row per parameter and part: the table the verdict is judged on
        first, with a ``part`` column (``"refit"`` or ``"identification"``) and ``judged``
        (True on the verdict's rows)."""
        parts = [("refit", self.refit), ("identification", self.identification)]
        if self.rule != "refit":
            parts.reverse()
        out = [t.assign(part=name, judged=name == self.rule) for name, t in parts if t is not None]
        return pd.concat(out, ignore_index=True) if out else self.table.assign(part=self.rule, judged=True)


def _failures(table):
    out = []
    for r in table[~table.reproduced].itertuples():
        if not np.isfinite(r.value_again):
            out.append(f"{r.parameter} is not free in the second fit")
        elif not np.isfinite(r.value):
            out.append(f"{r.parameter} is free only in the second fit")
        else:
            out.append(f"{r.parameter} moved {r.shift_pct:.3g} % (its bound {r.cramer_rao_pct:.3g} %)")
    return out


def _free_table(model):
    fit = getattr(model, "fit", None)
    params = getattr(fit, "parameters", None) if fit is not None else getattr(model, "parameters", None)
    if not isinstance(params, pd.DataFrame) or "status" not in params:
        raise ValueError(f"model {getattr(model, 'name', model)!r} has no parameter table to compare")
    return params[params.status == "free"].set_index("parameter")


def _compare(a, b):
    """Per-parameter comparison of two free-parameter tables (the first's bounds)."""
    rows = []
    for name in list(a.index) + [n for n in b.index if n not in a.index]:
        va = float(a.value[name]) if name in a.index else np.nan
        vb = float(b.value[name]) if name in b.index else np.nan
        cr = float(a.cramer_rao_pct[name]) if name in a.index else np.nan
        shift = abs(vb - va) / abs(va) * 100.0 if va != 0 else (0.0 if vb == 0 else np.inf)
        in_bounds = shift / cr if cr > 0 else (0.0 if shift == 0 else np.inf)
        ok = bool(np.isfinite(va) and np.isfinite(vb) and in_bounds <= 1.0)
        rows.append((name, va, vb, cr, shift, in_bounds, ok))
    return pd.DataFrame(rows, columns=["parameter", "value", "value_again", "cramer_rao_pct", "shift_pct",
                                       "shift_in_bounds", "reproduced"])


def reproduction_check(model, again=None, *, refit=None, rule=None, refit_error=""):
    """Whether an identification reproduces on a second data set, in two parts.

    The second data set differs at round-off. Two things can then differ, and they are
    reported apart:

    (i) the *structure*: the whole identification again (``again``: start, fit and
        reduction) keeps the same free parameters or not (:attr:`ReproductionCheck.same_structure`);
    (ii) the *parameters*: the first model's final structure (the same free and fixed
         parameters, the same ties, the same responses and bands) refitted on the second
         data set from the first fit's start (``refit``) lies within the first fit's
         Cramér-Rao bounds or not (:attr:`ReproductionCheck.parameters_reproduce`).

    A parameter reproduces when it is free in both fits and the second value lies
    within the first fit's Cramér-Rao bound of the first (``|again - value| <=
    CR% |value|``): the bound is the scatter the data are said to allow, so a fit
    that moves further on data differing at round-off has found another optimum, not
    the parameter's value.

    The trust rule's words are "the fit reproduces (parameters within their bounds)",
    and the ``"refit"`` rule (the default when a refit is given) holds a model to (ii)
    only. The refit changes nothing but the data, so its shifts measure what the
    Cramér-Rao bounds claim to bound: how far a round-off change of the data moves the
    optimum of this structure. The identification again measures much more than that.
    It re-runs the start and the staged fit, whose path through large intermediate
    structures can end far apart on data that differ little; it fits the unreduced
    structure, whose flat directions let the optimizer stop anywhere along a valley of
    nearly equal cost; and it re-runs the reduction, a chain of threshold decisions
    (insensitivity and Cramér-Rao limits, cost rises, runaway tests) in which a
    parameter near a limit flips on any data change. Its different kept set then
    compares the parameters of two different models: it says the identification's path
    is fragile, not that the final model's parameters are undetermined, and the trust
    rule judges the final model. (i) is therefore reported beside the verdict (and in
    :func:`trust_check`'s ``limits``), not required by it. The refit starts where the
    first identification started its fit, not from the first answer, so a fit that
    reaches the first optimum only from that optimum is not credited. The
    ``"identification"`` rule (the default without a refit) keeps the former verdict:
    the identification again must keep the same parameters, each within its bound.

    Parameters
    ----------
    model : IdentifiedModel or ModelRecord
        The first identification (a parameter table: ``parameter``, ``value``,
        ``status``, ``cramer_rao_pct``).
    again : IdentifiedModel or ModelRecord, optional
        The same identification on the second data set (part (i)).
    refit : flightid.FitResult or IdentifiedModel, optional
        The first model's final structure refitted on the second data set (part (ii)).
    rule : {"refit", "identification"}, optional
        Which part the verdict requires (default ``"refit"`` when ``refit`` or
        ``refit_error`` is given, else ``"identification"``).
    refit_error : str
        Why the refit could not run (it then fails the ``"refit"`` rule).

    Returns
    -------
    ReproductionCheck

    Raises
    ------
    ValueError
        A model without a parameter table, neither ``again`` nor ``refit`` given, an
        unknown ``rule``, or a rule whose part was not given.

    Examples
    --------
    >>> import pandas as pd
    >>> from types import SimpleNamespace
    >>> def model(values, cr, J, names=("m", "l")):
    ...     table = pd.DataFrame({"parameter": list(names), "value": values, "status": "free",
    ...                           "cramer_rao_pct": cr, "insensitivity_pct": 1.0})
    ...     return SimpleNamespace(fit=SimpleNamespace(parameters=table), J_ave=J)
    >>> first = model([1.0, 2.0], [5.0, 5.0], 10.0)
    >>> check = reproduction_check(first, model([1.01, 2.3], [5.0, 5.0], 10.2))
    >>> check.rule, check.passes, check.table.reproduced.tolist()
    ('identification', False, [True, False])
    >>> check = reproduction_check(first, model([1.3], [5.0], 10.5, names=["m"]),
    ...                            refit=model([1.02, 2.04], [5.0, 5.0], 10.1))
    >>> check.rule, check.passes, check.same_structure, check.parameters_reproduce
    ('refit', True, False, True)
    """
    if again is None and refit is None and not refit_error:
        raise ValueError("give the second identification (again) or the refit (refit), or both")
    if rule is None:
        rule = "refit" if (refit is not None or refit_error) else "identification"
    if rule not in REPRODUCTION_RULES:
        raise ValueError(f"rule must be one of {REPRODUCTION_RULES}, got {rule!r}")
    if rule == "refit" and refit is None and not refit_error:
        raise ValueError("the 'refit' rule needs the refit (or the refit_error saying why it failed)")
    if rule == "identification" and again is None:
        raise ValueError("the 'identification' rule needs the second identification (again)")
    first = _free_table(model)
    ident = _compare(first, _free_table(again)) if again is not None else None
    re = _compare(first, _free_table(refit)) if refit is not None else None
    table = re if rule == "refit" else ident
    if table is None:       # the refit failed: the first fit's parameters, none reproduced
        table = _compare(first, first.iloc[:0])
    return ReproductionCheck(table, float(getattr(model, "J_ave", np.nan)),
                             float(getattr(again, "J_ave", np.nan)) if again is not None else np.nan,
                             identification=ident, refit=re,
                             J_ave_refit=float(getattr(refit, "J_ave", np.nan)) if refit is not None else np.nan,
                             rule=rule, refit_error=str(refit_error))


def refit_structure(model, responses):
    """The model's final structure refitted on other ``responses`` from its fit's start.

    The same free and fixed parameters (fixed ones at their final values), the same
    ties, the same responses and frequency bands as the model's final fit; the free
    parameters start where the model's identification started its fit
    (``model.fit_start``; the final values where it has none). Only the data differ,
    so the refit's shifts against the model's Cramér-Rao bounds are the reproduction
    check's parameter part (:func:`~aircraft.identification.trust.reproduction_check`).

    Parameters
    ----------
    model : IdentifiedModel
        An identified model (its final fit, settings and structure).
    responses : flightid.MeasuredResponse
        The measured responses of the second data set (e.g. the ``responses`` of
        the same identification on it).

    Returns
    -------
    flightid.FitResult

    Raises
    ------
    ValueError
        ``responses`` lack a fitted pair or a frequency band (flightid's errors
        subclass ValueError and RuntimeError).

    Examples
    --------
    >>> from aircraft import identify_inflow, uh60_single_rotor
    >>> model = identify_inflow(uh60_single_rotor(), ct=0.0061)            # doctest: +SKIP
    >>> refit_structure(model, model.responses).J_ave == model.J_ave      # doctest: +SKIP
    True
    """
    from flightid import fit
    s, final = model.settings, model.fit.structure
    start = model.fit_start or {}
    begin = final.with_values({n: start[n] for n in final.free_names if n in start})
    kwargs = {"n_omega": s.n_omega, "coherence_min": s.coherence_min, **model.structure.fit_options,
              "pairs": [(p.output, p.input) for p in model.fit.pairs],
              "frequency_ranges": {(p.output, p.input): (p.omega[0], p.omega[-1]) for p in model.fit.pairs}}
    return fit(begin, responses, **kwargs)


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
        The fit on a second data set (:func:`reproduction_check`; by default the model's
        own ``reproduction`` if it has one): its ``passes`` enters the verdict, its
        ``same_structure`` is reported in ``limits["reproduction_structure"]``. Without one
        the reproduction is reported as not checked, not as a failure.
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
        how = (" (the first structure refitted)" if getattr(reproduction, "rule", "identification") == "refit"
               else "")
        failures.append(f"the fit does not reproduce on a second data set{how}: "
                        + "; ".join(reproduction.failures))
    same = getattr(reproduction, "same_structure", None) if reproduction is not None else None
    limits = {"cramer_rao_max": cr_max, "insensitivity_max": ins_max, "j_ave_max": float(j_max),
              "max_rise_average": float(rises[0]), "max_rise_single": float(rises[1]),
              "keep_rule": keep_rule,
              "reproduction": "not checked" if reproduction is None else
              ("reproduced" if reproduction.passes else "not reproduced"),
              # reported, not required (see reproduction_check)
              "reproduction_structure": "not checked" if same is None else ("same" if same else "different")}
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
