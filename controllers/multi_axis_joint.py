"""Is a multi-axis design dominated? One search over every axis's gains at once, every loop graded.

:func:`controllers.multi_axis_design.design_multi_axis` tunes the axes one at a
time (sequential loop closure), and :func:`controllers.multi_axis_check.global_check`
searches one axis's gains with the other axes held. Neither grades the design
the way CONDUIT does: every loop's specs on every gain at once. :func:`joint_check`
does: differential evolution (scipy, seeded) over the three gains of every axis
together, each candidate closed into the simultaneous loop
(:meth:`MultiAxisEMF.with_gains`) and every axis graded by
:func:`~controllers.specs.evaluate_specs` on its own specs
(``result.spec_lists``), the crossover boundary excepted. The objective is the
smallest over the axes of the candidate's crossover over the design's: a
feasible candidate scoring above one by more than ``tolerance`` raises every
axis's crossover at once with every spec of every axis still met, so the
design is dominated.

With ``local_evaluations`` a local constrained search follows (COBYLA, the
joint NLP over every gain at once): from the best feasible point found, raise
the smallest crossover ratio with every graded spec's normalised margin of every
axis held at or above zero; it answers whether the design could be improved by
moving all gains together a little, where the global stage answers whether it
could be by moving them far.

Per axis the search runs over the overall gain and the integral and rate gains'
ratios to it, on log scales around the design's (zero gains included); its first
generation is a cloud around the design, the design its first member. Each
candidate's closed-loop modes come from state spaces affine in the gains
(:class:`_AffineSystem`, checked against the exact interconnection), which makes a
candidate several times cheaper to grade.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import control
import numpy as np
import pandas as pd
from scipy.optimize import Bounds, NonlinearConstraint, differential_evolution, minimize
from scipy.stats import qmc
from tqdm.auto import tqdm

from . import metrics as m
from .emf import PIDGains
from .multi_axis_result import MultiAxisResult
from .nlp import _gain_scale
from .smooth import CrossoverMinimum, spec_with_constraint
from .specs import SpecEvaluationError, evaluate_specs

__all__ = ["JointCheckResult", "joint_check"]

#: the integral and rate gains' ratios to the overall gain at or below this [decades] are zero
#: (the ranges reach below it: a zero gain, e.g. the DMO's integral gain, is searched too)
_FLOOR_DECADES = -3.0
_GAIN_NAMES = ("K_phi", "K_Iphi", "K_p")
#: width of the band of zero integral and rate gains below the floor [decades]
_ZERO_BAND = 0.5
#: half-width of the first generation's cloud around the design [decades]
_START_SPREAD = 0.3


@dataclass
class JointCheckResult:
    """Outcome of :func:`joint_check`.

    Attributes
    ----------
    axes : pandas.DataFrame
        Index axis: ``dmo_crossover`` and ``joint_crossover`` [rad/s] (the design's and the
        best feasible candidate's, each on the simultaneous closed loop), their ``ratio``,
        ``dmo_K_*`` and ``joint_K_*`` gains, ``dmo_feasible`` (the design's own gains meet
        every spec graded here).
    dominated : bool
        A feasible candidate crosses higher on every axis by more than ``tolerance``.
    min_ratio : float
        The best feasible candidate's smallest crossover ratio over the axes (NaN: none feasible).
    tolerance : float
        The fraction used for ``dominated``.
    points : pandas.DataFrame
        Every candidate scored: its gains (``<axis>.K_phi``, ...), ``stage`` ("global"
        or "local"), ``feasible``,
        ``min_ratio`` (NaN when infeasible) and ``penalty`` (0 when feasible, else 1 + the
        sum over the axes of the unmet specs' normalised margins, each capped at 10).
    wall_time : float
        [s].
    local_min_ratio : float
        The local stage's best feasible smallest crossover ratio (NaN: no local stage,
        or none of its points feasible).
    """

    axes: pd.DataFrame
    dominated: bool
    min_ratio: float
    tolerance: float
    points: pd.DataFrame
    wall_time: float
    local_min_ratio: float = np.nan

    @property
    def evaluations(self):
        """Candidates scored."""
        return len(self.points)

    @property
    def feasible_evaluations(self):
        """Candidates that met every spec of every axis."""
        return int(self.points.feasible.sum()) if len(self.points) else 0

    @property
    def local_evaluations(self):
        """Candidates scored by the local stage."""
        return int((self.points.stage == "local").sum()) if len(self.points) else 0

    def to_pandas(self):
        """Per axis: the comparison, with the verdict and the search's size on every row.

        Returns
        -------
        pandas.DataFrame
            :attr:`axes` plus ``dominated``, ``min_ratio``, ``points`` (evaluations scored),
            ``feasible_points``, ``local_points`` (of them, the local stage's),
            ``local_min_ratio`` and ``wall_s`` [s] (the same on every row).
        """
        return self.axes.assign(dominated=self.dominated, min_ratio=self.min_ratio, points=self.evaluations,
                                feasible_points=self.feasible_evaluations, local_points=self.local_evaluations,
                                local_min_ratio=self.local_min_ratio, wall_s=self.wall_time)

    def plot(self, fig=None):
        """Feasible candidates' crossover ratio per axis, the design's at one; returns a Figure.

        Parameters
        ----------
        fig : matplotlib.figure.Figure, optional
            Drawn into (default a new one).

        Returns
        -------
        matplotlib.figure.Figure
        """
        from matplotlib.figure import Figure
        fig = fig or Figure(figsize=(6, 3.5), constrained_layout=True)
        ax = fig.subplots()
        p = self.points[self.points.feasible.astype(bool)]
        axes = list(self.axes.index)
        for k, a in enumerate(axes):
            if len(p):
                ax.plot(np.full(len(p), k) + np.linspace(-0.2, 0.2, len(p)), p[f"{a}.crossover_ratio"], ".",
                        ms=3, alpha=0.5)
            ax.plot(k, self.axes.loc[a, "ratio"], "r*", ms=12, label="best feasible" if k == 0 else None)
        ax.axhline(1.0, color="k", lw=0.8, label="design")
        ax.axhline(1.0 + self.tolerance, color="k", ls=":", lw=0.8, label="dominance threshold")
        ax.set_xticks(range(len(axes)), axes)
        ax.set_ylabel("crossover / design's crossover")
        ax.set_title(f"{'dominated' if self.dominated else 'not dominated'}: {self.feasible_evaluations} "
                     f"feasible of {self.evaluations} scored", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        return fig


def _graded(specs):
    """The specs a candidate must meet: every hard/soft spec but the crossover boundary."""
    crossover = spec_with_constraint(specs, CrossoverMinimum, required=False)
    skip = {"CrsMnG2"} if crossover is None else {"CrsMnG2", crossover.name}
    return [s for s in specs if s.kind != "objective" and s.name not in skip]


def _grade(emf, specs):
    """Per axis (crossover [rad/s], unmet margins, every graded spec's margin); the margins are
    -inf on an unstable loop."""
    out = {}
    for a, graded in specs.items():
        view = emf.axis_view(a)
        table = evaluate_specs(view, graded)
        met = table.met.astype(bool).to_numpy()
        margins = table.margin.astype(float).to_numpy()
        out[a] = (m.crossover_frequency(view.broken_loop()), margins[~met], margins)
    return out


class _AffineSystem:
    """A state space whose matrices are affine in the gains, rebuilt from 1 + 3 n exact ones.

    ``build(g)`` is the exact interconnection at the gains ``g`` (3 per axis, axis
    order). With no algebraic loop (plant, actuators and sensors strictly proper) every
    signal path passes one gain at most, so A, B, C and D are M0 + sum_j g_j M_j with
    every PI block holding its integrator state; where an integral gain is zero the
    exact interconnection has no such state, and it is removed again. ``ok`` is False
    when two probe gain sets (one with the integral gains zero) are not reproduced.
    """

    def __init__(self, build, n_gains):
        self.build = build
        ones = np.ones(n_gains)
        m1 = self._exact(ones)
        self.slopes = [np.array([self._exact(ones + np.eye(n_gains)[j])[k] - m1[k] for j in range(n_gains)])
                       for k in range(4)]
        self.base = [m1[k] - np.tensordot(ones, self.slopes[k], 1) for k in range(4)]
        # each PI block's integrator state: the one column of A its integral gain enters
        cols = [np.flatnonzero(np.any(self.slopes[0][j] != 0, axis=0)) for j in range(1, n_gains, 3)]
        self.ok = all(c.size == 1 for c in cols)
        self.integrators = [int(c[0]) if c.size == 1 else -1 for c in cols]
        probe = np.geomspace(0.3, 3.0, n_gains)
        no_integral = probe.copy()
        no_integral[1::3] = 0.0
        for g in (probe, no_integral):
            if self.ok:
                # round-off of the affine sum, relative to the matrices' size
                self.ok = all(e.shape == f.shape and np.allclose(
                    f, e, rtol=1e-9, atol=1e-9 * max(np.abs(e).max(initial=0.0), 1.0))
                    for e, f in zip(self._exact(g), self.matrices(g)))

    def _exact(self, g):
        sys = self.build(g)
        self.inputs, self.outputs = list(sys.input_labels), list(sys.output_labels)
        return [np.asarray(sys.A, float), np.asarray(sys.B, float), np.asarray(sys.C, float),
                np.asarray(sys.D, float)]

    def matrices(self, g):
        """(A, B, C, D) at the gains ``g``."""
        g = np.asarray(g, float)
        a, b, c, d = (self.base[k] + np.tensordot(g, self.slopes[k], 1) for k in range(4))
        drop = [k for i, k in enumerate(self.integrators) if g[3 * i + 1] == 0.0]
        keep = np.setdiff1d(np.arange(a.shape[0]), drop)
        return a[np.ix_(keep, keep)], b[keep], c[:, keep], d


class _FeedbackModes:
    """What a candidate's grading would interconnect, from affine state spaces (exact, much faster).

    Building the interconnections (:meth:`MultiAxisEMF.feedback_poles` and
    :meth:`MultiAxisEMF.closed_loop`) dominates a candidate's grading; here they are
    built 1 + 3 n times (:class:`_AffineSystem`) and each candidate's are given to
    :meth:`MultiAxisEMF.with_interconnections` (default Padé order). The pilot-path
    blocks' poles do not depend on the gains. Where an affine form does not reproduce the
    exact interconnection (an algebraic loop), that part is graded by the exact path.
    """

    def __init__(self, emf, axes):
        self.emf, self.axes = emf, axes
        n = 3 * len(axes)
        self.feedback = _AffineSystem(
            lambda g: control.interconnect(emf.with_gains(self._gains(g))._blocks("feedback"), inplist=[],
                                           outlist=[], check_unused=False), n)
        # the whole closed loop only where the specs read it (e.g. a heave height-response fit):
        # grading the design left it in the design's cache then
        self.closed = (_AffineSystem(lambda g: emf.with_gains(self._gains(g)).closed_loop(), n)
                       if emf.has_closed_loop() else None)
        self.ok = self.feedback.ok
        emf.closed_loop_poles()   # the pilot-path poles hold no gain: every candidate's copy carries them

    def _gains(self, g):
        return {a: PIDGains(*g[3 * i:3 * i + 3]) for i, a in enumerate(self.axes)}

    def matrix(self, g):
        """State matrix of the feedback system at the gains ``g`` (3 per axis, in axis order)."""
        return self.feedback.matrices(g)[0]

    def seed(self, emf, g):
        """``emf`` (at the gains ``g``) with the candidate's feedback poles and closed loop given."""
        fb = np.linalg.eigvals(self.matrix(g)) if self.feedback.ok else None
        cl = (control.ss(*self.closed.matrices(g), inputs=self.closed.inputs, outputs=self.closed.outputs,
                         name="multi-axis EMF closed loop") if self.closed is not None and self.closed.ok else None)
        return emf.with_interconnections(feedback_poles=fb, closed_loop=cl)


def _check_int(name, v):
    if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 1:
        raise ValueError(f"joint_check: {name} must be an integer >= 1, got {v!r}")


def joint_check(result, maxiter=12, popsize=2, seed=0, tolerance=0.01, decades=1.5, local_evaluations=0,
                progress=False):
    """Search every axis's gains at once for a design that beats this one on every axis.

    Parameters
    ----------
    result : MultiAxisResult
        From :func:`controllers.multi_axis_design.design_multi_axis`.
    maxiter, popsize : int
        Differential-evolution generations after the first and population per gain: a
        generation holds ``popsize`` x 3 x the number of axes candidates, rounded up to a
        power of two (balanced Sobol points), so ``maxiter + 1`` generations are scored.
        The defaults keep the coaxial four-axis hover design's check within a few minutes
        on two cores.
    seed : int
        Seed of the Sobol initial population and of the evolution (reproducible).
    tolerance : float
        The design is dominated when a feasible candidate's smallest crossover ratio
        exceeds ``1 + tolerance`` (the DMO stops its boundary bisection at a fraction of
        a percent).
    decades : float
        Half-width of each searched variable's log10 range around the design's value. Per
        axis the variables are the overall gain in its natural unit, K_phi / k0 with
        ``k0 = w_c / |Q(j w_c)|`` at the design's crossover ``w_c``, and the ratios
        K_Iphi / (K_phi w_c) and K_p w_c / K_phi (the rays of
        :func:`controllers.search.search_designs`: along a ray the crossover grows with
        the overall gain). The ratios' ranges also reach below a thousandth, where the gain
        is zero (a zero gain of the design sits there). The design's own gains
        are one member of the first generation.
    local_evaluations : int
        Budget of the local stage (0: none; else at least 3 per axis + 3, COBYLA's
        least budget for its variables): a COBYLA search (scipy) from the best
        feasible point of the global stage (the design when none beats it) over the
        same variables and box, maximising the smallest crossover ratio subject to
        every graded spec's normalised margin >= 0 on every axis (each clipped to
        +-10, so that an unstable candidate, whose margins are -inf, is a finite
        violation). Its initial step is a tenth of a decade.
    progress : bool
        Show a tqdm counter of the evaluated candidates.

    Returns
    -------
    JointCheckResult
        Per axis the design's and the best feasible candidate's crossovers on the
        simultaneous closed loop, the verdict, and every candidate scored.

    Raises
    ------
    TypeError
        ``result`` is not a MultiAxisResult.
    ValueError
        ``maxiter``, ``popsize``, ``tolerance``, ``decades`` or ``local_evaluations``
        out of range (the argument is named).

    Examples
    --------
    >>> import control
    >>> from controllers import DMOSettings, design_multi_axis
    >>> plant = control.ss([[-1.5, 0], [1.0, 0]], [[5.0], [0]], [[1.0, 0], [0, 1.0]], 0,
    ...                    inputs=["delta_lat"], outputs=["p", "phi"])
    >>> quick = DMOSettings(global_samples=0, max_steps=1, polish_evaluations=0)   # one DMO step, no search
    >>> res = design_multi_axis(plant, axes=["roll"], settings=quick, crossover_start={"roll": 10.0},
    ...                         max_sweeps=1, progress=False)    # one DMO step from 10 rad/s
    >>> check = joint_check(res, maxiter=1, popsize=2)   # a tiny budget: two generations of 8
    >>> check.evaluations, check.to_pandas().columns[:3].tolist()
    (16, ['dmo_crossover', 'joint_crossover', 'ratio'])
    """
    if not isinstance(result, MultiAxisResult):
        raise TypeError(f"joint_check: result must be a MultiAxisResult, got {type(result).__name__}")
    _check_int("maxiter", maxiter)
    _check_int("popsize", popsize)
    if isinstance(tolerance, bool) or not isinstance(tolerance, (int, float, np.floating)) or not (
            np.isfinite(tolerance) and tolerance >= 0):
        raise ValueError(f"joint_check: tolerance must be a finite number >= 0, got {tolerance!r}")
    if isinstance(decades, bool) or not isinstance(decades, (int, float, np.floating)) or not (
            np.isfinite(decades) and decades > 0):
        raise ValueError(f"joint_check: decades must be a finite number > 0, got {decades!r}")
    if isinstance(local_evaluations, bool) or not isinstance(local_evaluations, (int, np.integer)) or \
            local_evaluations < 0:
        raise ValueError(f"joint_check: local_evaluations must be an integer >= 0, got {local_evaluations!r}")
    t0 = time.perf_counter()
    emf, axes = result.emf, list(result.emf.axes)
    if 0 < local_evaluations < 3 * len(axes) + 3:
        # COBYLA's least budget: its variables (every gain and the smallest ratio) + 2
        raise ValueError(f"joint_check: local_evaluations must be 0 or at least {3 * len(axes) + 3} for "
                         f"{len(axes)} axes (COBYLA needs its {3 * len(axes) + 1} variables + 2), "
                         f"got {local_evaluations}")
    specs = {a: _graded(result.spec_lists[a]) for a in axes}
    base = _grade(emf, specs)
    dmo_wc = {a: base[a][0] for a in axes}
    dmo_ok = {a: base[a][1].size == 0 for a in axes}
    for a in axes:
        if not (np.isfinite(dmo_wc[a]) and dmo_wc[a] > 0 and emf.loops[a].gains.K_phi > 0):
            raise ValueError(f"joint_check: the design's {a} loop has no crossover (got {dmo_wc[a]!r} rad/s); "
                             "nothing to compare against")
    # per axis: the overall gain in its natural unit at the design's crossover w_c (k0, the
    # gain putting |K_phi/w Q| = 1 there) and the integral and rate gains as ratios to it (the
    # rays of controllers.search.search_designs): along a ray the crossover grows with the
    # overall gain, the long direction of the feasible set
    scales, x0, bounds = [], [], []
    for a in axes:
        wc = dmo_wc[a]
        k0 = _gain_scale([result.designs[a]], wc)
        scales.append((k0, wc))
        g = emf.loops[a].gains
        for k, v in enumerate((g.K_phi / k0, g.K_Iphi / (g.K_phi * wc), g.K_p * wc / g.K_phi)):
            # a zero gain sits at the floor; below it a band of zero gains is always searched
            c = np.log10(v) if v > 0 else _FLOOR_DECADES
            lo = c - decades if k == 0 else min(c - decades, _FLOOR_DECADES - _ZERO_BAND)
            bounds.append((lo, c + decades))
            x0.append(float(np.clip(c, lo, c + decades)))
    modes = _FeedbackModes(emf, axes)

    def physical(x):
        x = np.asarray(x, float)
        # a ratio at or below the floor is a zero gain (no integrator state, no rate feedback)
        v = np.where((x <= _FLOOR_DECADES) & (np.arange(x.size) % 3 > 0), 0.0, 10.0 ** x)
        out = []
        for i, (k0, wc) in enumerate(scales):
            k_phi = k0 * v[3 * i]
            out += [k_phi, k_phi * wc * v[3 * i + 1], k_phi / wc * v[3 * i + 2]]
        return np.array(out)

    rows, best, stage = [], None, ["global"]
    bar = tqdm(desc="joint check", disable=not progress)
    memo = {}

    def score(x):
        """(feasible, crossover ratios, every graded margin) of the candidate ``x``, recorded once."""
        nonlocal best
        key = np.asarray(x, float).tobytes()
        if key in memo:
            return memo[key]
        gains = physical(x)
        cand = {a: PIDGains(*gains[3 * i:3 * i + 3]) for i, a in enumerate(axes)}
        try:
            graded = _grade(modes.seed(emf.with_gains(cand), gains), specs)
        except (SpecEvaluationError, np.linalg.LinAlgError):
            # a response that cannot be evaluated (non-finite) ranks below every graded candidate
            graded = {a: (np.nan, np.full(len(specs[a]), -np.inf), np.full(len(specs[a]), -np.inf)) for a in axes}
        ratios = np.array([graded[a][0] / dmo_wc[a] for a in axes])
        unmet = np.concatenate([graded[a][1] for a in axes])
        ok = unmet.size == 0 and bool(np.all(np.isfinite(ratios)))
        # infeasible candidates are ranked by how far they are from every boundary (graded, capped)
        penalty = 0.0 if ok else 1.0 + float(np.sum(np.minimum(-unmet, 10.0)))
        row = {f"{a}.{n}": float(v) for a in axes for n, v in zip(_GAIN_NAMES, cand[a].as_array())}
        row.update({f"{a}.crossover_ratio": float(r) for a, r in zip(axes, ratios)})
        row.update({"stage": stage[0], "feasible": ok, "min_ratio": float(ratios.min()) if ok else np.nan,
                    "penalty": penalty})
        rows.append(row)
        bar.update(1)
        if ok and (best is None or ratios.min() > best[0]):
            best = (float(ratios.min()), cand, ratios, np.asarray(x, float).copy())
        memo[key] = (ok, ratios, np.concatenate([graded[a][2] for a in axes]), penalty)
        return memo[key]

    def cost(x):
        ok, ratios, _, penalty = score(x)
        return -float(ratios.min()) if ok else penalty

    # the first generation is a Sobol cloud around the design (the design itself its first
    # member): the feasible set is thin across the rays, so a generation spread over the whole
    # box is almost all infeasible and its differences throw every trial out of it
    lo, hi = np.array(bounds).T
    # scipy's own Sobol start rounds the population up to a power of two (balanced points)
    cloud = qmc.Sobol(len(x0), seed=seed).random_base2(int(np.ceil(np.log2(int(popsize) * len(x0)))))
    start = np.clip(np.array(x0) + (2.0 * cloud - 1.0) * _START_SPREAD, lo, hi)
    start[0] = x0
    differential_evolution(cost, bounds, maxiter=int(maxiter), seed=seed, tol=0.0, polish=False, init=start)
    local_best = np.nan
    if local_evaluations:
        local_best = _local_stage(score, best, np.array(x0), lo, hi, int(local_evaluations), stage, rows)
    bar.close()
    table = []
    for i, a in enumerate(axes):
        g = emf.loops[a].gains
        found = best[1][a] if best is not None else None
        ratio = float(best[2][i]) if best is not None else np.nan
        table.append({"axis": a, "dmo_crossover": dmo_wc[a], "joint_crossover": ratio * dmo_wc[a], "ratio": ratio,
                      "dmo_feasible": dmo_ok[a], "dmo_K_phi": g.K_phi, "dmo_K_Iphi": g.K_Iphi, "dmo_K_p": g.K_p,
                      **{f"joint_{n}": (getattr(found, n) if found is not None else np.nan) for n in _GAIN_NAMES}})
    min_ratio = best[0] if best is not None else np.nan
    dominated = bool(best is not None and min_ratio > 1.0 + tolerance)
    return JointCheckResult(pd.DataFrame(table).set_index("axis"), dominated, min_ratio, float(tolerance),
                            pd.DataFrame(rows), time.perf_counter() - t0, local_best)


def _local_stage(score, best, x0, lo, hi, budget, stage, rows):
    """COBYLA from the best feasible point (else the design): maximise t, the smallest crossover
    ratio, over (x, t) with every ratio >= t and every graded margin >= 0; returns the best
    feasible smallest ratio among the local stage's points (NaN: none feasible)."""
    stage[0] = "local"
    first = len(rows)
    start = best[3] if best is not None else x0
    _, ratios, _, _ = score(start)
    t0 = float(np.nanmin(ratios)) if np.all(np.isfinite(ratios)) else 0.0
    n = start.size

    def ratio_gaps(z):
        r = score(z[:n])[1]
        return np.where(np.isfinite(r), r, 0.0) - z[n]

    def margins(z):
        return np.clip(score(z[:n])[2], -10.0, 10.0)

    cons = [NonlinearConstraint(ratio_gaps, 0.0, np.inf), NonlinearConstraint(margins, 0.0, np.inf)]
    # t is bounded by the crossover ratios through the constraints; its box only keeps COBYLA's
    # simplex finite
    box = Bounds(np.append(lo, 0.0), np.append(hi, 10.0))
    minimize(lambda z: -z[n], np.append(start, t0), method="COBYLA", bounds=box, constraints=cons,
             options={"maxiter": budget, "rhobeg": 0.1, "tol": 1e-4})
    local = [r["min_ratio"] for r in rows[first:] if r["feasible"]]
    return float(max(local)) if local else np.nan
