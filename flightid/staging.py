"""Staged fitting (§6.4.3): a plan of stages that free parameter groups and add responses.

Large structures (the 12-state coaxial F/G/C model has ~50 parameters) do not
converge when every parameter starts free: the dissertation builds the model
up -- first-order on-rotor terms on the on-rotor responses, then the
cross-rotor terms with the off-rotor responses, then all together, then the
flap-rate terms with the flap-rate responses, then the far-wake states. Each
stage starts from the values the previous one reached, so parameters not yet
used should start at zero (or at a value that keeps the model stable).

::

    plan = [Stage("on-rotor", free=[...], pairs=[...]),
            Stage("off-rotor", free=[...], add_pairs=[...]),
            Stage("all first-order", free="used"),
            Stage("flap rates", free=[...], add_pairs=[...]),
            Stage("far wake", free="all")]
    staged = fit_staged(structure, responses, plan, frequency_ranges=(0.5, 30.0))
    staged.log            # stage, J_ave, free parameters, conditioning, ...
    staged.result         # the final FitResult
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from tqdm.auto import tqdm

from .errors import IdentificationError, UnstableModelError
from .fitting import FitResult, fit

__all__ = ["Stage", "StagedFitResult", "fit_staged"]

_KEYWORDS = ("all", "used", "nonzero")


@dataclass
class Stage:
    """One step of a staged fit.

    Parameters
    ----------
    name : str
        Label in the log.
    free : list of str or "all" / "used" / "nonzero"
        The parameters adjusted in this stage; every other parameter is held at
        the value the previous stages left. ``"used"``: every parameter freed in
        an earlier stage (or this one's ``also_free``); ``"nonzero"``: every
        parameter whose current value is not zero; ``"all"``: all parameters.
    also_free : list of str
        Added to a keyword ``free`` (e.g. ``free="used", also_free=[...]``).
    pairs : list of (output, input), optional
        The responses fitted in this stage (replaces the previous list).
    add_pairs : list of (output, input)
        Responses added to the previous stage's list (§6.4.3: "add in the
        off-rotor frequency responses").
    set_values : dict, optional
        Values assigned before the stage (e.g. a stable start for states that
        are switched on here). A response whose model is identically zero at the
        stage start (all its gains still 0) has no gradient in dB: give its
        parameters a start here, or ``fit_kwargs={"revive_dead_pairs": True}``.
    prune_insensitive : float, optional
        After the fit, parameters freed here whose insensitivity [%] exceeds
        this are set back to zero, fixed, and the stage is re-fitted
        (step 4(d): a loose threshold such as 100 % removes only parameters
        with essentially no effect).
    fit_kwargs : dict
        Passed to :func:`flightid.fit` for this stage only (over the plan-wide ones).
    """

    name: str
    free: object = "all"
    also_free: list = field(default_factory=list)
    pairs: list | None = None
    add_pairs: list = field(default_factory=list)
    set_values: dict | None = None
    prune_insensitive: float | None = None
    fit_kwargs: dict = field(default_factory=dict)


@dataclass
class StagedFitResult:
    """Outcome of :func:`fit_staged`.

    Attributes
    ----------
    result : FitResult
        The last stage's fit (the identified model).
    stages : list of FitResult
        Every stage's fit, in order.
    log : DataFrame
        stage, name, n_free, free, n_pairs, J_ave, J_max, condition_number,
        n_flat, pruned, success, wall_s.
    """

    result: FitResult
    stages: list
    log: pd.DataFrame

    @property
    def structure(self):
        return self.result.structure

    @property
    def model(self):
        return self.result.model

    def to_pandas(self) -> pd.DataFrame:
        return self.log.copy()

    def plot(self, fig=None):
        """J_ave after each stage (bars) with the number of free parameters."""
        from matplotlib.figure import Figure
        if fig is None:
            fig = Figure(figsize=(6.0, 3.2), constrained_layout=True)
        ax = fig.subplots()
        x = np.arange(len(self.log))
        ax.bar(x, self.log.J_ave, color="C0")
        ax.set_xticks(x, [f"{n}\n({k} free)" for n, k in zip(self.log.name, self.log.n_free)], fontsize=7)
        ax.set_ylabel("J_ave")
        ax.set_yscale("log")
        ax.grid(True, axis="y", alpha=0.3)
        return fig


def _resolve_free(stage, structure, used):
    names = structure.names
    if isinstance(stage.free, str):
        if stage.free not in _KEYWORDS:
            raise IdentificationError(f"stage {stage.name!r}: free must be a list of parameter names or one "
                                      f"of {_KEYWORDS}, got {stage.free!r}")
        if stage.free == "all":
            chosen = list(names)
        elif stage.free == "used":
            chosen = [n for n in names if n in used]
        else:
            chosen = [n for n in names if structure.values[n] != 0]
        extra = list(stage.also_free)
    else:
        chosen, extra = list(stage.free), list(stage.also_free)
    chosen = list(dict.fromkeys(chosen + extra))
    unknown = [n for n in chosen if n not in names]
    if unknown:
        raise IdentificationError(f"stage {stage.name!r} frees unknown parameters {unknown}")
    if not chosen:
        raise IdentificationError(f"stage {stage.name!r} frees no parameter")
    return chosen


def fit_staged(structure, responses, stages, *, progress=False, **fit_kwargs) -> StagedFitResult:
    """Run a plan of :class:`Stage` s in order (§6.4.3), each from the previous values.

    Parameters
    ----------
    structure : ModelStructure
        Initial values of every parameter (zero for terms switched on later).
        Which parameters are free is decided by the stages, not by ``structure.fixed``.
    responses : MeasuredResponse or sequence of MeasuredResponse
    stages : sequence of Stage
    progress : bool
        Show a progress bar over the stages.
    **fit_kwargs
        Passed to every :func:`flightid.fit` (e.g. ``frequency_ranges``,
        ``n_omega``, ``stability_margin``); give ``frequency_ranges`` so that
        costs are comparable between stages.

    Returns
    -------
    StagedFitResult

    Raises
    ------
    UnstableModelError, IdentificationError
        From a stage's fit, with the stage named.
    """
    stages = list(stages)
    if not stages or not all(isinstance(s, Stage) for s in stages):
        raise IdentificationError("stages must be a non-empty sequence of flightid.staging.Stage")
    current = structure.copy()
    used, pairs, results, log = set(), None, [], []
    for k, stage in enumerate(tqdm(stages, desc="staged fit", disable=not progress)):
        t0 = time.perf_counter()
        if stage.set_values:
            current = current.with_values(stage.set_values)
        free = _resolve_free(stage, current, used)
        if stage.pairs is not None:
            pairs = [tuple(p) for p in stage.pairs]
        if stage.add_pairs:
            pairs = list(dict.fromkeys((pairs or []) + [tuple(p) for p in stage.add_pairs]))
        trial = current.fix([n for n in current.names if n not in free]).free(free)
        kwargs = {**fit_kwargs, **stage.fit_kwargs}
        if pairs is not None:
            kwargs["pairs"] = pairs
        try:
            res = fit(trial, responses, **kwargs)
            pruned = []
            if stage.prune_insensitive is not None:
                ins = res.insensitivity
                pruned = [n for n in free if ins.get(n, 0.0) > stage.prune_insensitive]
                if pruned and len(pruned) < len(free):
                    res = fit(res.structure.fix(pruned, 0.0), responses, **kwargs)
                elif pruned:
                    pruned = []    # pruning everything would leave nothing to fit: keep them
        except (UnstableModelError, IdentificationError) as err:
            raise type(err)(f"stage {k} ({stage.name!r}): {err}") from err
        used.update(n for n in free if n not in pruned)
        used.difference_update(pruned)
        current = res.structure
        results.append(res)
        log.append({"stage": k, "name": stage.name, "n_free": len(free) - len(pruned),
                    "free": ", ".join(n for n in free if n not in pruned), "n_pairs": len(res.cost_table),
                    "J_ave": res.J_ave, "J_max": float(res.cost_table.J.max()),
                    "condition_number": res.condition_number, "n_flat": len(res.flat_directions),
                    "pruned": ", ".join(pruned), "success": res.success,
                    "wall_s": time.perf_counter() - t0})
        if pairs is None:
            pairs = [(p.output, p.input) for p in res.pairs]
    return StagedFitResult(results[-1], results, pd.DataFrame(log))
