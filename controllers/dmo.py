"""Design-margin optimisation (DMO) of EMF feedback gains with CasADi/IPOPT.

CasADi stays behind a physics-first API: :func:`optimize` finds gains meeting
every spec for one set of boundaries; :func:`dmo` raises the crossover (CrsMnG2)
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
Smooth constraints on the grid, each with a small back-off so the grid design
also meets the specs on the 4000-point evaluation grid:

* Nichols/gain-phase exclusion ellipse around (-180 deg, 0 dB) with semi-axes
  45 deg and 6 dB (``atan2`` of -L, squared so the branch cut is harmless);
* disturbance-rejection peak ``|1+L|^2 >= 10^(-DRP/10)`` at every grid point;
* DRB: ``|1+L|^2 >= 2`` at every grid frequency up to the DRB boundary;
* crossover: ``|L(j w_cmin)|^2 >= 1``;
* no gain above -GM where the phase is past -180 deg above a fraction of the
  crossover boundary (no conditionally stable loop).

Closed-loop damping, stability, bandwidth and OLOP are not smooth on a grid:
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
from dataclasses import dataclass, field

import control
import numpy as np
import pandas as pd
from scipy.optimize import minimize
from tqdm.auto import tqdm

from . import metrics as m
from .emf import EMFDesign, PIDGains
from .gain_sampling import extend_along_ray, sample_gains
from .nlp import _Problem, _gain_scale, _gains, _loop_factor  # noqa: F401  (re-exported for search)
from .specs import default_specs, evaluate_specs

__all__ = ["DMOSettings", "OptimizationResult", "DMOResult", "VerificationError", "InfeasibleDesignError",
           "SolverError", "optimize", "dmo", "design_margins"]

_IPOPT_OK = ("Solve_Succeeded", "Solved_To_Acceptable_Level")
#: IPOPT stopped on a budget: its last iterate is still scored by the true specs
_IPOPT_UNCONVERGED = ("Maximum_Iterations_Exceeded", "Maximum_CpuTime_Exceeded", "Maximum_WallTime_Exceeded",
                      "Search_Direction_Becomes_Too_Small", "Restoration_Failed", "Infeasible_Problem_Detected")


class VerificationError(RuntimeError):
    """The optimiser's own numbers disagree with python-control's re-check."""


class SolverError(RuntimeError):
    """IPOPT failed (its return status is in the message) on every start of a step."""


class InfeasibleDesignError(ValueError):
    """No gains meet every spec at the starting boundaries; ``unmet`` names the specs."""

    def __init__(self, message, unmet=(), result=None):
        super().__init__(message)
        self.unmet = list(unmet)
        self.result = result


@dataclass
class DMOSettings:
    """DMO settings.

    Attributes
    ----------
    omega : array
        Optimiser frequency grid [rad/s], increasing, finite, > 0.
    gm_db, pm_deg, drp_db : float
        Level 1 margins used in the smooth constraints.
    tie_integral : bool
        K_Iphi = K_phi * crossover_min / 5 (§7.5); default False: all three gains free.
    growth : float
        Boundary factor per expanding step (> 1).
    tolerance : float
        Relative bisection tolerance on the boundaries (stop when hi/lo - 1 < tolerance).
    max_steps : int
        Steps of the expanding stage before the step limit is reported.
    n_starts : int
        Random (seeded) starts per step after the continuation start.
    seed : int
        Seed of the random starts.
    polish_evaluations : int
        Spec evaluations of the derivative-free polish (0 disables it).
    gain_upper : float
        Upper bound of each scaled gain (K_phi = 1 crosses at the boundary).
    backoff : float
        Relative back-off of the smooth constraints (grid vs evaluation grid).
    global_samples : int
        Sobol samples of the gain space scored by the true specs before the NLP
        (the global stage); 0 runs the local continuation only.
    global_candidates : int
        Best feasible samples (one per feasible piece) pushed along their gain ratios;
        the NLP continuation then also starts from the best of them.
    global_scale_span : (float, float)
        Range of K_phi sampled, in units of the gain that puts |L| = 1 at the starting
        crossover boundary.
    """

    omega: np.ndarray = field(default_factory=lambda: np.geomspace(0.05, 80.0, 250))
    gm_db: float = 6.0
    pm_deg: float = 45.0
    drp_db: float = 5.0
    tie_integral: bool = False
    growth: float = 1.2
    tolerance: float = 0.005
    max_steps: int = 20
    n_starts: int = 1
    seed: int = 0
    polish_evaluations: int = 25
    gain_upper: float = 50.0
    backoff: float = 0.01
    global_samples: int = 64
    global_candidates: int = 2
    global_scale_span: tuple = (0.2, 10.0)
    verify_tolerance_db: float = 0.5   #: optimiser vs python-control GM agreement
    verify_tolerance_deg: float = 2.0  #: ... PM agreement
    actuator_weight: float = 0.1
    #: the "gain below -GM past -180 deg" constraint applies above these fractions
    #: of the crossover boundary (below, the integrator's -180 deg region is allowed)
    phase_constraint_from: tuple = (0.5, 0.2)
    ipopt: dict = field(default_factory=lambda: {"ipopt.print_level": 0, "print_time": False,
                                                 "ipopt.max_iter": 40, "ipopt.tol": 1e-7,
                                                 "ipopt.hessian_approximation": "limited-memory",
                                                 "ipopt.mu_strategy": "adaptive",
                                                 "ipopt.acceptable_tol": 1e-5, "ipopt.acceptable_iter": 5,
                                                 "ipopt.sb": "yes"})

    def __post_init__(self):
        w = np.asarray(self.omega, dtype=float)
        if w.ndim != 1 or w.size < 10:
            raise ValueError("DMOSettings.omega must be a 1-D grid of at least 10 frequencies [rad/s]")
        if not np.all(np.isfinite(w)):
            raise ValueError("DMOSettings.omega contains NaN or inf")
        if np.any(w <= 0):
            raise ValueError(f"DMOSettings.omega must be > 0 rad/s (got {w.min():g}): the PID "
                             "term K_Iphi/w^2 is infinite at w = 0")
        if np.any(np.diff(w) <= 0):
            raise ValueError("DMOSettings.omega must be strictly increasing")
        self.omega = w
        for name in ("gm_db", "pm_deg", "drp_db", "tolerance", "gain_upper", "actuator_weight"):
            v = getattr(self, name)
            if not np.isfinite(v) or v <= 0:
                raise ValueError(f"DMOSettings.{name} must be finite and > 0, got {v}")
        if not np.isfinite(self.growth) or self.growth <= 1:
            raise ValueError(f"DMOSettings.growth must be > 1, got {self.growth}")
        if self.n_starts < 0 or self.max_steps < 1:
            raise ValueError("DMOSettings.n_starts must be >= 0 and max_steps >= 1")
        for name in ("global_samples", "global_candidates"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 0:
                raise ValueError(f"DMOSettings.{name} must be an integer >= 0, got {v!r}")
        lo, hi = self.global_scale_span
        if not (np.isfinite(lo) and np.isfinite(hi) and 0 < lo < hi):
            raise ValueError(f"DMOSettings.global_scale_span must be (low, high) with 0 < low < high, "
                             f"got {self.global_scale_span!r}")


@dataclass
class OptimizationResult:
    """One boundary set: the design found, its spec tables and what is unmet."""

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
    #: which path gave the answer ("starting gains" or "global candidate", ...)
    origin: str = ""
    #: True when no global stage ran: the answer is only local
    local_only: bool = False
    #: final CrsMnG2 and DrbRoH1 Level 1 boundaries [rad/s]
    crossover_boundary: float = float("nan")
    drb_boundary: float = float("nan")

    @property
    def feasible(self):
        return True

    @property
    def crossover(self):
        """Smallest crossover of the final design over its plants [rad/s]."""
        return float(self.specs.loc[self.specs.spec == "CrsMnG2", "value"].min())

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


def design_margins(designs, specs, labels=None, exclude=("CrsMnG2",), stop_at_first_unmet=False):
    """Spec table of one gain set over several designs, and its summary.

    Returns ``(table, unmet, min_margin, limiting_spec)``: the stacked
    :func:`evaluate_specs` tables (column ``plant``), the unmet hard/soft spec
    names (``"spec @ plant"`` when several; specs not applicable on an unstable
    loop are left out, EigLcG1 names the instability), the smallest CONDUIT normalised
    design margin over every non-objective spec and plant except ``exclude``
    (the crossover boundary the DMO drives its design onto), and the spec that has it.

    Parameters
    ----------
    designs : EMFDesign or list of EMFDesign
        One gain set on one or several plants.
    specs : list of Spec
        Specs evaluated on each design (:func:`evaluate_specs`).
    labels : list of str, optional
        Plant labels (default ``"plant 0"``, ``"plant 1"``, ...).
    exclude : sequence of str
        Specs left out of the minimum margin.
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


def _verify(design, settings):
    """Re-check margins with python-control on the Padé state-space loop."""
    gm_exact, pm_exact, _, _ = m.gain_phase_margins(design.broken_loop())
    # python-control's 'frd' method interpolates the (well-conditioned) state-space
    # frequency response; its 'poly' method overflows for 40-60 state loops
    loop = design.broken_loop_statespace(pade_order=4)
    grid = control.frd(loop, np.logspace(-2, 3, 4000))
    gm, pm, _, _, _, _ = control.stability_margins(grid, method="frd")
    gm_db = 20 * np.log10(gm) if np.isfinite(gm) and gm > 0 else np.inf
    if np.isfinite(gm_exact) and np.isfinite(gm_db) and abs(gm_db - gm_exact) > settings.verify_tolerance_db:
        raise VerificationError(f"gain margin: exact {gm_exact:.3f} dB vs python-control {gm_db:.3f} dB")
    if np.isfinite(pm_exact) and np.isfinite(pm) and abs(pm - pm_exact) > settings.verify_tolerance_deg:
        raise VerificationError(f"phase margin: exact {pm_exact:.3f} deg vs python-control {pm:.3f} deg")


def _as_designs(design):
    designs = list(design) if isinstance(design, (list, tuple)) else [design]
    if not designs:
        raise ValueError("at least one EMFDesign is needed")
    for d in designs:
        if not isinstance(d, EMFDesign):
            raise TypeError(f"expected EMFDesign objects, got {type(d).__name__}")
    return designs


def optimize(design, crossover_min, drb_min, specs=None, settings=None, x0=None, labels=None,
             rng=None, problem=None, verify=True) -> OptimizationResult:
    """Find gains meeting every spec for one set of boundaries (several starts).

    Parameters
    ----------
    design : EMFDesign or list of EMFDesign
        One plant, or several (robust design: one gain set for all).
    crossover_min, drb_min : float
        CrsMnG2 and DrbRoH1 Level 1 boundaries [rad/s].
    specs : list of Spec, optional
        Default ``default_specs(crossover_min, drb_min)``.
    settings : DMOSettings, optional
    x0 : PIDGains, optional
        Continuation start (e.g. the previous DMO step's design).
    labels : list of str, optional
        Plant names used in the spec tables.
    rng : numpy.random.Generator, optional
        Source of the random starts (default seeded by ``settings.seed``).
    problem : internal
        The NLP built for these designs and settings (reused by :func:`dmo`).
    verify : bool
        Re-check GM/PM of a feasible design with python-control (VerificationError
        on disagreement); :func:`dmo` does it once, on its final design.

    Returns
    -------
    OptimizationResult
        ``feasible`` False (with ``unmet``) when no start reaches every spec.

    Raises
    ------
    SolverError
        IPOPT failed on every start (its statuses are named).
    """
    designs = _as_designs(design)
    settings = settings or DMOSettings()
    for name, v in (("crossover_min", crossover_min), ("drb_min", drb_min)):
        if not np.isfinite(v) or v <= 0:
            raise ValueError(f"{name} must be a finite frequency > 0 rad/s, got {v}")
    specs = specs if specs is not None else default_specs(crossover_min, drb_min)
    rng = rng if rng is not None else np.random.default_rng(settings.seed)
    tie = settings.tie_integral
    scale = _gain_scale(designs, crossover_min)
    nvar = 2 if tie else 3

    def to_x(g):
        x = np.array([g.K_phi / scale, g.K_p * crossover_min / scale] if tie else
                     [g.K_phi / scale, g.K_Iphi / (scale * crossover_min), g.K_p * crossover_min / scale])
        return np.clip(x, 0.0, settings.gain_upper)

    def to_gains(x):
        return PIDGains(*[float(v) for v in _gains(x, scale, crossover_min, tie)])

    starts = [] if x0 is None else [to_x(x0)]
    starts.append(np.array([1.0, 0.1] if tie else [1.0, 0.2, 0.1]))
    for _ in range(settings.n_starts):
        lo, hi = np.log([0.3, 0.01, 0.01][:nvar]), np.log([3.0, 1.0, 1.0][:nvar])
        starts.append(np.exp(rng.uniform(lo, hi)))
    fractions = settings.phase_constraint_from
    fractions = (fractions,) if np.isscalar(fractions) else tuple(fractions)
    problem = problem or _Problem(designs, settings)
    statuses, candidates, solved = [], [], 0
    for n_start, start in enumerate(starts):
        # the looser phase constraints (low-frequency modes of a free aircraft)
        # are tried from the first start only: each solve costs ~0.2-1 s
        for phase_from in (fractions if n_start < 1 else fractions[:1]):
            x1, slack, status = problem.solve(start, crossover_min, drb_min, phase_from, scale)
            statuses.append(status)
            if status not in _IPOPT_OK + _IPOPT_UNCONVERGED:
                continue     # a solver error (e.g. Invalid_Number_Detected): nothing to score
            solved += 1
            gains = to_gains(x1)
            cands = [d.with_gains(gains) for d in designs]
            table, unmet, margin, limiting = design_margins(cands, specs, labels)
            candidates.append((margin, x1, cands, table, unmet, limiting))
            if not unmet:
                if verify:
                    _verify_all(cands, settings)
                return OptimizationResult(cands[0], cands, True, table, unmet, crossover_min, drb_min, margin,
                                          limiting, statuses, len(candidates))
            if slack <= 1e-6:
                break    # the smooth constraints hold: another phase fraction gives the same point
    if not solved:
        raise SolverError(f"IPOPT failed on all {len(statuses)} starts at crossover boundary "
                          f"{crossover_min:.4g} rad/s, DRB {drb_min:.4g} rad/s: " + "; ".join(sorted(set(statuses))))
    # the candidate closest to feasible: the polish continues from it
    margin, xbest, cands, table, unmet, limiting = max(
        candidates, key=lambda c: float(c[3][c[3].kind != "objective"].margin.astype(float).min()))
    if settings.polish_evaluations > 0:
        polished = _polish(designs, specs, xbest, to_gains, labels, settings)
        if polished is not None:
            cands, table, unmet, margin, limiting = polished
            if not unmet and verify:
                _verify_all(cands, settings)
    return OptimizationResult(cands[0], cands, not unmet, table, unmet, crossover_min, drb_min, margin, limiting,
                              statuses, len(candidates))


def _verify_all(designs, settings):
    for d in designs:
        _verify(d, settings)


def _polish(designs, specs, x_start, to_gains, labels, settings):
    """Nelder-Mead on the smallest true design margin (capped at 0.02: feasibility is enough)."""
    best = {"margin": -np.inf}

    def merit(x):
        x = np.clip(x, 0.0, settings.gain_upper)
        cands = [d.with_gains(to_gains(x)) for d in designs]
        table, unmet, margin, limiting = design_margins(cands, specs, labels)
        overall = max(float(table[table.kind != "objective"].margin.astype(float).min()), -1e3)
        if overall > best["margin"]:
            best.update(margin=overall, result=(cands, table, unmet, margin, limiting))
        return -min(overall, 0.02)

    x_start = np.maximum(np.asarray(x_start, float), 1e-3)
    simplex = [x_start] + [x_start * np.where(np.arange(x_start.size) == k, 1.3, 1.0) for k in range(x_start.size)]
    minimize(merit, x_start, method="Nelder-Mead", bounds=[(0.0, settings.gain_upper)] * x_start.size,
             options={"maxfev": settings.polish_evaluations, "initial_simplex": np.array(simplex),
                      "xatol": 1e-4, "fatol": 1e-6})
    return best.get("result")


def _row(step, stage, scale, res, wall):
    tab = res.specs
    g = res.design.gains
    return {"step": step, "stage": stage, "scale": scale, "crossover_min": res.crossover_min,
            "drb_min": res.drb_min, "feasible": res.feasible, "K_phi": g.K_phi, "K_Iphi": g.K_Iphi,
            "K_p": g.K_p, "crossover": tab.loc[tab.spec == "CrsMnG2", "value"].min(),
            "drb": tab.loc[tab.spec == "DrbRoH1", "value"].min(), "min_margin": res.min_margin,
            "limiting_spec": res.limiting_spec, "unmet": ", ".join(res.unmet), "starts": res.starts,
            "ipopt_status": res.ipopt_status[-1] if res.ipopt_status else "", "wall_s": wall}


def _scored(designs, specs, gains, crossover_min, drb_min, labels):
    """An OptimizationResult for a gain set scored by the true specs (no NLP)."""
    cands = [d.with_gains(gains) for d in designs]
    table, unmet, margin, limiting = design_margins(cands, specs, labels)
    return OptimizationResult(cands[0], cands, not unmet, table, unmet, crossover_min, drb_min, margin,
                              limiting, [], 0)


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
    (``local_only``).

    Parameters
    ----------
    design : EMFDesign or list of EMFDesign
        Plant(s), command model, actuator, sensor, inverse plant, tau_eq; the
        gains are only a starting point.  A list asks for one gain set meeting
        every spec on every plant (robust multi-model design).
    specs_factory : callable(crossover_min, drb_min) -> list of Spec
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
    problem = _Problem(designs, settings)
    rows = []
    bar = tqdm(total=None, desc="DMO", disable=not progress)
    specs0 = specs_factory(crossover_start, drb_start)
    samples, candidates, extended = None, [], pd.DataFrame()
    if settings.global_samples:
        bar.set_postfix(stage="global sample")
        samples, candidates, extended = _global_candidates(designs, specs0, settings, crossover_start)

    def attempt(path, stage, t_c, t_d, x0):
        wc, wd = crossover_start * t_c, drb_start * t_d
        ts = time.perf_counter()
        res = optimize(designs, wc, wd, specs_factory(wc, wd), settings, x0=x0, labels=labels, rng=rng,
                       problem=problem, verify=False)
        rows.append({**_row(len(rows), stage, t_c, res, time.perf_counter() - ts), "path": path})
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
        if hi is not None and upper is not None and upper.unmet and all(u.startswith("DrbRoH1") for u in upper.unmet):
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
        drb = float(cand.specs.loc[cand.specs.spec == "DrbRoH1", "value"].min())
        t_start = max(1.0, min(wc / crossover_start, drb / drb_start) * (1 - settings.tolerance))
        first_g = _scored(designs, specs_factory(crossover_start * t_start, drb_start * t_start), g,
                          crossover_start * t_start, drb_start * t_start, labels)
        rows.append({**_row(len(rows), "start", t_start, first_g, 0.0), "path": "global candidate"})
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
    win = max(paths, key=lambda p: (p["best"].crossover_min, _achieved(p["best"])))
    best = win["best"]
    # stage 3: push the winner along its gain ratios under its final boundaries
    final_specs = specs_factory(best.crossover_min, best.drb_min)
    g_ext, _, _ = extend_along_ray(best.designs, final_specs, best.design.gains, settings.tolerance)
    if g_ext is not best.design.gains:
        best = _scored(designs, final_specs, g_ext, best.crossover_min, best.drb_min, labels)
    bar.close()
    _verify_all(best.designs, settings)
    history = pd.DataFrame(rows)
    hi, upper = win["hi"], win["upper"]
    origin = win["path"] + (", pushed along its gain ratios" if g_ext is not win["best"].design.gains else "")
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
    if not settings.global_samples:
        msg += "; local answer only (no global stage)"
    return DMOResult(best.design, best.designs, best.specs, history, limiting, time.perf_counter() - t0, msg,
                     settings.tolerance, samples=samples, candidates=extended, origin=origin,
                     local_only=not settings.global_samples, crossover_boundary=best.crossover_min,
                     drb_boundary=best.drb_min)


def _achieved(res):
    return float(res.specs.loc[res.specs.spec == "CrsMnG2", "value"].min())
