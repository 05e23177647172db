"""Design-margin optimisation (DMO) of EMF feedback gains with CasADi/IPOPT.

CasADi stays behind a physics-first API: :func:`optimize`
(:mod:`controllers.optimization`) finds gains meeting every spec for one set of
boundaries; :func:`dmo` raises the crossover (CrsMnG2)
and disturbance-rejection-bandwidth (DrbRoH1) Level 1 boundaries together,
by a growth factor until a step is infeasible and then by bisection to a
stated relative tolerance, and returns the last feasible design with a log
of every step (boundaries, gains, most limiting spec and its CONDUIT
normalised design margin, IPOPT status).  If the DRB boundary is what stops
the joint raise, the crossover boundary alone is raised further (DRB held).

Formulation.  The loop broken at the mixer input is L(jw) = C(jw) Q(jw) with
Q = actuator x plant x sensor (numbers, exact delays) and
C = K_p - K_Iphi/w^2 - j K_phi/w, linear in the gains, evaluated on a fixed
frequency grid as real/imaginary parts (CasADi has no complex type). Gains are
scaled so that K_phi = 1 puts |L| = 1 at the crossover boundary (IPOPT sees
O(1) variables whatever the plant's stick units) and bounded below by 0.
The NLP's constraints come from the specs themselves: every spec in the list
that carries a smooth constraint (:mod:`controllers.smooth`) adds it, with its
boundary read from the spec, each with a small back-off so the grid design also
meets the specs on the 4000-point evaluation grid.  The default Table 7.3 set
gives the Nichols exclusion ellipse (NicMgG1), no gain above -GM past -180 deg
above a fraction of the crossover boundary (StbMgG1.GM: no conditionally stable
loop), the phase margin near 0 dB (StbMgG1.PM), the DRB (``|1+L|^2 >= 2`` up to
the DRB boundary), the DRP peak and the crossover ``|L(j w_cmin)|^2 >= 1``.
Adding a spec with a smooth constraint to the list is enough for the NLP to
honour it; the crossover and DRB boundaries the DMO raises are the specs
carrying :class:`~controllers.smooth.CrossoverMinimum` and
:class:`~controllers.smooth.DisturbanceBandwidthFloor`.

Specs without a smooth form (closed-loop damping, stability, bandwidth, OLOP):
every candidate is scored by :func:`~controllers.specs.evaluate_specs`
(independent of the optimiser's formulas; margins re-checked with
python-control). Each step tries the previous design (continuation) and
``n_starts`` seeded random starts; if none is feasible, a derivative-free
polish maximises the smallest normalised design margin on the true specs.
One slack with an exact penalty keeps the NLP feasible from any start
(slack 0: every smooth constraint holds); the objective sums the crossover
and actuator-RMS proxies (CrsLnG1, RmsAcG1). IPOPT's return status is
checked: a solver error is not scored, an unconverged iterate is scored by
the true specs like any other candidate, and a step where IPOPT fails on
every start raises :class:`SolverError`. Several designs (plants) are
handled at once for robust multi-model design: one gain set, every spec on
every plant.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import pandas as pd
from tqdm.auto import tqdm

from .dmo_settings import DMOSettings, InfeasibleDesignError, SolverError, VerificationError
from .emf import EMFDesign, PIDGains
from .gain_sampling import extend_along_ray, sample_gains
from .multistart import multistart, ratio_polish
from .nlp import _Problem, _gain_scale
from .optimization import _verify_all, optimize
from .scoring import OptimizationResult, _as_designs, _scored, design_margins
from .smooth import CrossoverMinimum, DisturbanceBandwidthFloor, spec_with_constraint
from .specs import default_specs

# the settings, errors, scoring and single-step optimiser live in their own
# modules; they are re-exported here, where users of the DMO look for them
__all__ = ["DMOSettings", "OptimizationResult", "DMOResult", "VerificationError", "InfeasibleDesignError",
           "SolverError", "optimize", "dmo", "design_margins"]


@dataclass
class DMOResult:
    """Last feasible design, its spec table and the boundary-raising log."""

    design: EMFDesign
    designs: list
    specs: pd.DataFrame
    history: pd.DataFrame
    limiting: list
    wall_time: float
    message: str
    tolerance: float
    #: global stage: every Sobol sample scored (None without one)
    samples: pd.DataFrame | None = None
    #: global stage: the best samples pushed along their gain ratios
    candidates: pd.DataFrame | None = None
    #: multistart stage: every start scored and the polished ones (None without one)
    starts: pd.DataFrame | None = None
    polished: pd.DataFrame | None = None
    #: which path gave the answer ("starting gains" or "global candidate", ...)
    origin: str = ""
    #: True when no global stage ran: the answer is only local
    local_only: bool = False
    #: final crossover (CrsMnG2) and DRB (DrbRoH1) Level 1 boundaries [rad/s]
    crossover_boundary: float = float("nan")
    drb_boundary: float = float("nan")
    #: name of the spec whose boundary is the crossover boundary (its smooth
    #: constraint is a CrossoverMinimum)
    crossover_spec: str = "CrsMnG2"

    @property
    def feasible(self):
        return True

    @property
    def crossover(self):
        """Smallest crossover of the final design over its plants [rad/s]."""
        return _value(self.specs, self.crossover_spec)

    def to_pandas(self):
        return self.history.copy()

    def plot(self, fig=None):
        """Boundary history: crossover and DRB achieved per DMO step; returns a Figure."""
        from matplotlib.figure import Figure
        fig = fig or Figure(figsize=(6, 3.5), constrained_layout=True)
        ax = fig.subplots()
        h = self.history
        ax.plot(h.step, h.crossover, "o-", label="crossover achieved")
        ax.plot(h.step, h.drb, "s-", label="DRB achieved")
        ax.plot(h.step, h.crossover_min, "k--", lw=0.8, label="crossover boundary")
        bad = ~h.feasible.astype(bool)
        ax.plot(h.step[bad], h.crossover_min[bad], "rx", ms=10, label="infeasible boundary")
        ax.set_xlabel("DMO step")
        ax.set_ylabel("rad/s")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        return fig


def _value(table, name):
    """Smallest value of spec ``name`` over the plants (NaN when the list has no such spec)."""
    return float(table.loc[table.spec == name, "value"].min()) if name is not None else float("nan")


def _row(step, stage, scale, res, wall, roles):
    tab = res.specs
    g = res.design.gains
    return {"step": step, "stage": stage, "scale": scale, "crossover_min": res.crossover_min,
            "drb_min": res.drb_min, "feasible": res.feasible, "K_phi": g.K_phi, "K_Iphi": g.K_Iphi,
            "K_p": g.K_p, "crossover": _value(tab, roles[0]), "drb": _value(tab, roles[1]),
            "min_margin": res.min_margin,
            "limiting_spec": res.limiting_spec, "unmet": ", ".join(res.unmet), "starts": res.starts,
            "ipopt_status": res.ipopt_status[-1] if res.ipopt_status else "", "wall_s": wall}


def _global_candidates(designs, specs, settings, crossover_start):
    """Global stage: Sobol sample scored by the true specs, best ones extended along their rays."""
    scale = _gain_scale(designs, crossover_start)
    samples = sample_gains(designs, specs, scale, crossover_start, settings.global_samples, settings.seed,
                           scale_span=settings.global_scale_span)
    feasible = samples[samples.feasible].sort_values("crossover", ascending=False)
    extended, rows = [], []
    for r in feasible.itertuples():
        if len(extended) >= settings.global_candidates:
            break
        # one candidate per feasible piece: skip samples within 5 % of a kept one's crossover
        if any(abs(r.crossover / c - 1) < 0.05 for _, c in extended):
            continue
        g, wc, n = extend_along_ray(designs, specs, PIDGains(r.K_phi, r.K_Iphi, r.K_p), settings.tolerance)
        extended.append((g, wc))
        rows.append({"K_phi": g.K_phi, "K_Iphi": g.K_Iphi, "K_p": g.K_p, "crossover": wc,
                     "sampled_crossover": r.crossover, "evaluations": n})
    return samples, sorted(extended, key=lambda c: -c[1]), pd.DataFrame(rows)


def dmo(design, specs_factory=default_specs, settings=None, crossover_start=1.5, drb_start=0.9,
        progress=True, labels=None) -> DMOResult:
    """Raise the crossover and DRB Level 1 boundaries to the design margin.

    Three stages. (1) Global: a Sobol sample of the gain space
    (``settings.global_samples`` points) scored by the true specs at the starting
    boundaries, and the best feasible samples pushed along their gain ratios to the
    largest feasible gain (:mod:`controllers.gain_sampling`). (2) Local: from the
    starting gains and from the best global candidate, the crossover and DRB
    boundaries are raised together by the NLP (expansion, then bisection to
    ``settings.tolerance``); if DRB alone stops that, the crossover alone is raised
    with DRB held. (3) The winner's gains are pushed along their ratios once more under
    its final boundaries. The design with the highest crossover wins. With
    ``global_samples = 0`` only the local stage runs and the result says so
    (``local_only``). With ``settings.multistart`` > 0 (off by default) a multistart
    stage (:func:`controllers.multistart.multistart`: seeded starts over every gain's
    log range and the starting gains, each polished on the true specs) adds its best
    design to the candidates of stage (2), and a last stage follows the winner's gain
    ratios along the binding spec boundary (:func:`controllers.multistart.ratio_polish`),
    the crossover boundary then raised to what it reaches.

    Parameters
    ----------
    design : EMFDesign or list of EMFDesign
        Plant(s), command model, actuator, sensor, inverse plant, tau_eq; the
        gains are only a starting point.  A list asks for one gain set meeting
        every spec on every plant (robust multi-model design).
    specs_factory : callable(crossover_min, drb_min) -> list of Spec
        The spec list at given crossover and DRB boundaries [rad/s].  The NLP is
        assembled from the smooth constraints of these specs (a spec added to the
        list is honoured with no other change); the boundaries raised are those of
        the spec carrying a :class:`~controllers.smooth.CrossoverMinimum` (required)
        and the one carrying a :class:`~controllers.smooth.DisturbanceBandwidthFloor`.
    settings : DMOSettings, optional
    crossover_start, drb_start : float
        First boundaries [rad/s] (DRB Level 1 for roll: 0.9 rad/s).
    progress : bool
        tqdm bar over the steps.
    labels : list of str, optional
        Plant names in the tables (multi-model).

    Returns
    -------
    DMOResult
        Final design(s), its stacked spec table, the per-step log (``history``,
        with the most limiting spec named at every step and the path it belongs to),
        the unmet specs of the first infeasible boundary above it (``limiting``), the
        global stage's samples and candidates, and where the answer came from
        (``origin``).

    Raises
    ------
    InfeasibleDesignError
        Neither the starting gains nor any sampled gain set meets every spec at the
        starting boundaries (the unmet specs are named).
    SolverError
        IPOPT failed on every start of a step.

    Examples
    --------
    >>> from controllers import EMFDesign, PIDGains, DMOSettings, hover_roll_plant, dmo
    >>> design = EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.1, 0.05))
    >>> res = dmo(design, settings=DMOSettings(global_samples=16), progress=False)
    >>> res.crossover > 1.5
    True
    """
    designs = _as_designs(design)
    settings = settings or DMOSettings()
    for name, v in (("crossover_start", crossover_start), ("drb_start", drb_start)):
        if not np.isfinite(v) or v <= 0:
            raise ValueError(f"{name} must be a finite frequency > 0 rad/s, got {v!r}")
    labels = labels or ([d.plant.name or f"plant {k}" for k, d in enumerate(designs)] if len(designs) > 1 else None)
    rng = np.random.default_rng(settings.seed)
    t0 = time.perf_counter()
    rows = []
    bar = tqdm(total=None, desc="DMO", disable=not progress)
    specs0 = specs_factory(crossover_start, drb_start)
    # the boundaries raised are those of the specs carrying these smooth constraints
    drb_spec = spec_with_constraint(specs0, DisturbanceBandwidthFloor, required=False)
    roles = (spec_with_constraint(specs0, CrossoverMinimum).name, None if drb_spec is None else drb_spec.name)
    problem = _Problem(designs, settings, specs0)
    samples, candidates, extended = None, [], pd.DataFrame()
    if settings.global_samples:
        bar.set_postfix(stage="global sample")
        samples, candidates, extended = _global_candidates(designs, specs0, settings, crossover_start)
    starts = polished = None
    if settings.multistart:
        bar.set_postfix(stage="multistart")
        starts, polished_c, polished = multistart(
            designs, specs0, crossover_start, n_starts=settings.multistart, n_polish=settings.multistart_polish,
            decades=settings.multistart_decades, seed=settings.seed,
            polish_evaluations=settings.multistart_evaluations, extra_starts=[designs[0].gains])
        # the NLP continuation starts from the best of both stages
        candidates = sorted(candidates + polished_c, key=lambda c: -c[1])

    def attempt(path, stage, t_c, t_d, x0):
        wc, wd = crossover_start * t_c, drb_start * t_d
        ts = time.perf_counter()
        res = optimize(designs, wc, wd, specs_factory(wc, wd), settings, x0=x0, labels=labels, rng=rng,
                       problem=problem, verify=False)
        rows.append({**_row(len(rows), stage, t_c, res, time.perf_counter() - ts, roles), "path": path})
        bar.update(1)
        bar.set_postfix(wc=f"{wc:.3f}", feasible=res.feasible)
        return res

    def raise_boundary(path, stage, scales, lo, best, upper):
        """Expand then bisect the scale from ``lo``; ``scales(t)`` -> (crossover scale, DRB scale)."""
        hi = None
        for _ in range(settings.max_steps):
            t = lo * settings.growth
            res = attempt(path, stage + " (expand)", *scales(t), best.design.gains)
            if res.feasible:
                lo, best = t, res
            else:
                hi, upper = t, res
                break
        while hi is not None and hi / lo - 1 > settings.tolerance:
            t = np.sqrt(lo * hi)
            res = attempt(path, stage + " (bisect)", *scales(t), best.design.gains)
            if res.feasible:
                lo, best = t, res
            else:
                hi, upper = t, res
        return lo, hi, best, upper

    def run_path(path, first, t_start):
        """Joint raise from scale ``t_start``, then the crossover alone if DRB stopped it."""
        lo, hi, best, upper = raise_boundary(path, "crossover+DRB", lambda t: (t, t), t_start, first, None)
        if (hi is not None and upper is not None and upper.unmet and roles[1] is not None
                and all(u.split(" @ ")[0] == roles[1] for u in upper.unmet)):
            base = lo
            lo2, hi2, best, upper = raise_boundary(path, "crossover", lambda t: (base * t, base), 1.0, best, upper)
            hi = None if hi2 is None else lo * hi2
            lo = lo * lo2
        return {"lo": lo, "hi": hi, "best": best, "upper": upper, "path": path}

    paths = []
    first = attempt("starting gains", "start", 1.0, 1.0, designs[0].gains)
    if first.feasible:
        paths.append(run_path("starting gains", first, 1.0))
    if candidates:
        g, wc = candidates[0]
        # the candidate meets the starting boundaries; start the raise where it stands
        cand = _scored(designs, specs0, g, crossover_start, drb_start, labels)
        drb = _value(cand.specs, roles[1]) if roles[1] is not None else np.inf
        t_start = max(1.0, min(wc / crossover_start, drb / drb_start) * (1 - settings.tolerance))
        first_g = _scored(designs, specs_factory(crossover_start * t_start, drb_start * t_start), g,
                          crossover_start * t_start, drb_start * t_start, labels)
        rows.append({**_row(len(rows), "start", t_start, first_g, 0.0, roles), "path": "global candidate"})
        if first_g.feasible:
            paths.append(run_path("global candidate", first_g, t_start))
    if not paths:
        bar.close()
        raise InfeasibleDesignError(
            f"no gains meet every spec even at the starting boundaries (crossover {crossover_start:g} rad/s, "
            f"DRB {drb_start:g} rad/s); unmet: {', '.join(first.unmet)}; most limiting {first.limiting_spec} "
            f"(design margin {first.min_margin:.3g})"
            + (f"; none of {settings.global_samples} sampled gain sets is feasible either"
               if settings.global_samples else ""), first.unmet, first)
    win = max(paths, key=lambda p: (p["best"].crossover_min, _value(p["best"].specs, roles[0])))
    best = win["best"]
    # stage 3: push the winner along its gain ratios under its final boundaries
    final_specs = specs_factory(best.crossover_min, best.drb_min)
    g_ext, _, _ = extend_along_ray(best.designs, final_specs, best.design.gains, settings.tolerance)
    if g_ext is not best.design.gains:
        best = _scored(designs, final_specs, g_ext, best.crossover_min, best.drb_min, labels)
    polished_final = False
    if settings.multistart:
        # stage 4 (multistart only): a compass search over the winner's gain ratios on the true
        # specs, each ratio pushed to the feasible edge: it follows a spec boundary that runs
        # obliquely across the gains, where the NLP's back-off and a search over the gains stall
        g_pol, wc_pol, _ = ratio_polish(designs, final_specs, best.design.gains, tolerance=settings.tolerance,
                                        max_evaluations=3 * settings.multistart_evaluations)
        # the best other candidates too, at the final boundaries: the joint crossover/DRB raise
        # can end on another trade-off than the one the candidates were polished for
        for g0, _ in candidates[:settings.multistart_polish]:
            g1, wc1, _ = ratio_polish(designs, final_specs, g0, tolerance=settings.tolerance,
                                      max_evaluations=settings.multistart_evaluations)
            if np.isfinite(wc1) and not (np.isfinite(wc_pol) and wc_pol >= wc1):
                g_pol, wc_pol = g1, wc1
        wc_now = _value(best.specs, roles[0])
        if np.isfinite(wc_pol) and wc_pol > wc_now * (1 + settings.tolerance):
            boundary = wc_pol * (1 - settings.tolerance / 2)
            cand = _scored(designs, specs_factory(boundary, best.drb_min), g_pol, boundary, best.drb_min, labels)
            if cand.feasible:
                best, polished_final = cand, True
    bar.close()
    _verify_all(best.designs, settings)
    history = pd.DataFrame(rows)
    hi, upper = win["hi"], win["upper"]
    origin = win["path"] + (", pushed along its gain ratios" if g_ext is not win["best"].design.gains else "")
    origin += ", polished on the true specs" if polished_final else ""
    if hi is None:
        limiting = []
        msg = (f"DMO stopped at the step limit ({settings.max_steps} expanding steps): crossover boundary "
               f"{best.crossover_min:.4g} rad/s still feasible")
    else:
        limiting = upper.unmet
        msg = (f"DMO converged to {settings.tolerance:.1%}: crossover boundary {best.crossover_min:.4g} rad/s "
               f"feasible, {crossover_start * hi:.4g} not; limiting spec(s): {', '.join(limiting)}; "
               f"most limiting at the design: {best.limiting_spec} (margin {best.min_margin:.3g})")
    msg += f"; from the {origin}"
    if not (settings.global_samples or settings.multistart):
        msg += "; local answer only (no global stage)"
    return DMOResult(best.design, best.designs, best.specs, history, limiting, time.perf_counter() - t0, msg,
                     settings.tolerance, samples=samples, candidates=extended, starts=starts, polished=polished,
                     origin=origin, local_only=not (settings.global_samples or settings.multistart), crossover_boundary=best.crossover_min,
                     drb_boundary=best.drb_min, crossover_spec=roles[0])
