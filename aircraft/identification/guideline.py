"""The identification guideline's keep rule: which poorly determined parameters a model may keep, and why.

The guideline (Tischler & Remple; the dissertation's §4.4) asks every free parameter
for a Cramér-Rao bound below 20 % and an insensitivity below 10 %, and removes the
ones that fail one at a time (Fig. 6.1) -- unless a removal spoils the fit: a
parameter whose removal raises the average cost by more than about 2, or one
response's cost by more than about 10, stays, with that as its reason.
:meth:`IdentifiedModel.trust_failures` applies the bounds strictly;
:func:`guideline_check` applies them with the keep rule, reading the reduction's own
log, so every kept parameter comes with the measured cost rise that kept it::

    guideline_check(identified_model) -> GuidelineCheck
        .passes        every bound met, or the parameter kept by the rule
        .table         one row per parameter outside a bound: verdict and reason
        .failures      the reasons it does not pass (J_ave, flat directions, parameters)
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

__all__ = ["GuidelineCheck", "guideline_check"]


@dataclass
class GuidelineCheck:
    """Result of :func:`guideline_check`.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per free parameter outside a bound: ``parameter``,
        ``cramer_rao_pct``, ``insensitivity_pct`` [%], ``verdict`` (``"kept"`` or
        ``"fails"``) and ``reason``.
    failures : list of str
        Why the model does not meet the guideline (empty when it does).
    """

    table: pd.DataFrame
    failures: list = field(default_factory=list)

    @property
    def passes(self):
        return not self.failures

    def to_pandas(self):
        return self.table.copy()


def guideline_check(model, *, max_rise_average=2.0, max_rise_single=10.0):
    """The guideline with its keep rule, for an identified model.

    Parameters
    ----------
    model : IdentifiedModel
        From :func:`aircraft.identify_inflow` with ``settings.reduce`` on (the
        reduction's log says which removals were tried).
    max_rise_average, max_rise_single : float
        Cost rises [-] that keep a parameter: the average J, any single J
        (:func:`flightid.reduce`'s defaults).

    Returns
    -------
    GuidelineCheck

    Raises
    ------
    ValueError
        A model without a reduction log, or non-positive limits.
    """
    if not (max_rise_average > 0 and max_rise_single > 0):
        raise ValueError(f"max_rise_average and max_rise_single must be positive, got "
                         f"{max_rise_average!r}, {max_rise_single!r}")
    reduction = getattr(model, "reduction", None)
    if reduction is None or not hasattr(reduction, "log"):
        raise ValueError(f"model {getattr(model, 'name', model)!r} has no reduction log: identify it with "
                         "settings.reduce=True to apply the keep rule")
    s = model.settings
    # J_ave and flat directions are not the keep rule's business: the strict check's
    # sentences about them stand
    failures = [f for f in model.trust_failures()
                if not f.startswith(("Cramer-Rao", "insensitivity"))]
    log = reduction.log
    free = model.fit.parameters[model.fit.parameters.status == "free"]
    rows = []
    for p in free.itertuples():
        cr, ins = float(p.cramer_rao_pct), float(p.insensitivity_pct)
        bad_cr, bad_ins = not cr < s.cramer_rao_max, not ins < s.insensitivity_max
        if not (bad_cr or bad_ins):
            continue
        if bad_ins:
            rows.append((p.parameter, cr, ins, "fails", f"insensitivity {ins:.3g} % >= {s.insensitivity_max:g} %: "
                         "it hardly moves the cost, so no cost rise can keep it"))
            continue
        tries = log[(log.parameter == p.parameter) & ~log.accepted.astype(bool)]
        kept = None
        for t in tries.itertuples():
            rise_avg = float(t.J_ave_after) - float(t.J_ave_before)
            rise_one = float(t.max_single_rise)
            if bool(t.runaway) or not (np.isfinite(rise_avg) and np.isfinite(rise_one)):
                continue
            if rise_avg > max_rise_average or rise_one > max_rise_single:
                kept = (f"Cramér-Rao {cr:.3g} % >= {s.cramer_rao_max:g} %, kept: removing it raised J_ave by "
                        f"{rise_avg:.3g} (limit {max_rise_average:g}) and one response's J by {rise_one:.3g} "
                        f"(limit {max_rise_single:g})")
        if kept:
            rows.append((p.parameter, cr, ins, "kept", kept))
        else:
            why = ("its removal was refused only because the fit ran away (a flat valley, not a kept parameter)"
                   if len(tries) and tries.runaway.astype(bool).any() else
                   "the reduction never found its removal too costly" if len(tries) else
                   "the reduction did not try to remove it")
            rows.append((p.parameter, cr, ins, "fails", f"Cramér-Rao {cr:.3g} % >= {s.cramer_rao_max:g} %: {why}"))
    table = pd.DataFrame(rows, columns=["parameter", "cramer_rao_pct", "insensitivity_pct", "verdict", "reason"])
    bad = table[table.verdict == "fails"]
    if len(bad):
        failures.append(f"parameters outside the bounds and not kept by the guideline: {bad.parameter.tolist()}")
    return GuidelineCheck(table, failures)
