"""One boundary set: gains meeting every spec, found by the smooth NLP and scored by the true specs.

:func:`optimize` solves the NLP assembled from the specs' smooth constraints
(:mod:`controllers.nlp`, :mod:`controllers.smooth`) from the continuation start
and seeded random starts, scores every IPOPT answer with the true specs
(:func:`~controllers.scoring.design_margins`) and, if none is feasible, polishes
the best one derivative-free on the true design margins.  Feasible designs are
re-checked with python-control (:class:`~controllers.dmo_settings.VerificationError`).
"""
from __future__ import annotations

import control
import numpy as np
from scipy.optimize import minimize

from . import metrics as m
from .dmo_settings import DMOSettings, SolverError, VerificationError
from .emf import PIDGains
from .nlp import _Problem, _gain_scale, _gains
from .scoring import OptimizationResult, _as_designs, design_margins
from .specs import default_specs

__all__ = ["optimize"]

_IPOPT_OK = ("Solve_Succeeded", "Solved_To_Acceptable_Level")
#: IPOPT stopped on a budget: its last iterate is still scored by the true specs
_IPOPT_UNCONVERGED = ("Maximum_Iterations_Exceeded", "Maximum_CpuTime_Exceeded", "Maximum_WallTime_Exceeded",
                      "Search_Direction_Becomes_Too_Small", "Restoration_Failed", "Infeasible_Problem_Detected")
#: scaled gains (1 = the gain that crosses at the boundary) below this are an interior-point
#: iterate resting on its lower bound 0, not a gain: IPOPT leaves them at 1e-16 to 1e-9 depending
#: on the machine's round-off, and a 1e-13 integral gain adds a pole at +-1e-13 1/s whose sign
#: then decides the stability verdict (EigLcG1). They are set to exactly zero.
_ZERO_GAIN = 1e-8


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
        x = np.where(np.abs(np.asarray(x, float)) < _ZERO_GAIN, 0.0, x)
        return PIDGains(*[float(v) for v in _gains(x, scale, crossover_min, tie)])

    starts = [] if x0 is None else [to_x(x0)]
    starts.append(np.array([1.0, 0.1] if tie else [1.0, 0.2, 0.1]))
    for _ in range(settings.n_starts):
        lo, hi = np.log([0.3, 0.01, 0.01][:nvar]), np.log([3.0, 1.0, 1.0][:nvar])
        starts.append(np.exp(rng.uniform(lo, hi)))
    fractions = settings.phase_constraint_from
    fractions = (fractions,) if np.isscalar(fractions) else tuple(fractions)
    problem = problem or _Problem(designs, settings, specs)
    statuses, candidates, solved = [], [], 0
    for n_start, start in enumerate(starts):
        # the looser phase constraints (low-frequency modes of a free aircraft)
        # are tried from the first start only: each solve costs ~0.2-1 s
        for phase_from in (fractions if n_start < 1 else fractions[:1]):
            x1, slack, status = problem.solve(start, specs, crossover_min, phase_from, scale)
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

