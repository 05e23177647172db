"""Design-margin optimisation (DMO) of EMF feedback gains with CasADi.

CasADi stays behind a physics-first API: :func:`optimize` takes an
:class:`~controllers.emf.EMFDesign` and spec boundaries, :func:`dmo` raises the
crossover and disturbance-rejection-bandwidth Level 1 boundaries until no
design meets every spec, and returns the last feasible design with its history.

Formulation.  The loop broken at the mixer input is L(jw) = C(jw) Q(jw) with
Q = actuator x plant x sensor (numbers, exact delays) and
C = K_p - K_Iphi/w^2 - j K_phi/w, linear in the gains, evaluated on a fixed
frequency grid as real/imaginary parts (CasADi has no complex type).
Smooth constraints on the grid:

* Nichols/gain-phase exclusion ellipse around (-180 deg, 0 dB) with semi-axes
  45 deg and 6 dB (``atan2`` of -L, squared so the branch cut is harmless);
* disturbance-rejection peak ``|1+L|^2 >= 10^(-DRP/10)`` at every grid point;
* DRB: ``|1+L|^2 >= 2`` at every grid frequency up to the DRB boundary;
* crossover: ``|L(j w_cmin)|^2 >= 1``.

Closed-loop damping, stability and bandwidth are not smooth on a frequency grid:
they are checked after every solve with python-control on the state-space loop
(``interconnect`` with Padé delays); a design that fails them is infeasible.
Phase 1 minimises a slack to find a feasible point (IPOPT does not keep iterates
feasible, unlike CONDUIT's FSQP); phase 2 minimises the summed objectives
(crossover and actuator RMS proxies) from it.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import casadi as ca
import control
import numpy as np
import pandas as pd
from tqdm.auto import tqdm

from . import metrics as m
from .emf import EMFDesign, PIDGains
from .specs import default_specs, evaluate_specs

__all__ = ["DMOSettings", "OptimizationResult", "DMOResult", "VerificationError", "optimize", "dmo"]


class VerificationError(RuntimeError):
    """The optimiser's own numbers disagree with python-control's re-check."""


@dataclass
class DMOSettings:
    """Settings: frequency grid [rad/s], margins, boundary steps, IPOPT options."""

    omega: np.ndarray = field(default_factory=lambda: np.geomspace(0.05, 80.0, 300))
    gm_db: float = 6.0
    pm_deg: float = 45.0
    drp_db: float = 5.0
    tie_integral: bool = True          #: K_Iphi = K_phi * crossover_min / 5 (§7.5)
    step: float = 0.25                 #: boundary increase per DMO step [rad/s]
    max_steps: int = 40
    verify_tolerance_db: float = 0.5   #: optimiser vs python-control GM agreement
    verify_tolerance_deg: float = 2.0  #: ... PM agreement
    actuator_weight: float = 0.1
    #: the "gain below -GM past -180 deg" constraint applies above these fractions
    #: of the crossover boundary (below, the integrator's -180 deg region is
    #: allowed); :func:`optimize` tries them in turn and keeps the first design that
    #: passes the python-control re-check (low-frequency phugoid modes of a free
    #: aircraft may need the lower values)
    phase_constraint_from: tuple = (0.5, 0.2, 0.1)
    ipopt: dict = field(default_factory=lambda: {"ipopt.print_level": 0, "print_time": False,
                                                 "ipopt.max_iter": 500, "ipopt.tol": 1e-8})


@dataclass
class OptimizationResult:
    design: EMFDesign
    feasible: bool
    specs: pd.DataFrame
    unmet: list
    slack: float
    crossover_min: float
    drb_min: float


@dataclass
class DMOResult:
    """Last feasible design, its spec table and the boundary-raising history."""

    design: EMFDesign | None
    specs: pd.DataFrame | None
    history: pd.DataFrame
    limiting: list
    wall_time: float
    message: str

    @property
    def feasible(self):
        return self.design is not None

    def to_pandas(self):
        return self.history.copy()

    def plot(self, fig=None):
        """Boundary history: crossover and DRB achieved per DMO step."""
        from matplotlib.figure import Figure
        fig = fig or Figure(figsize=(6, 3.5), constrained_layout=True)
        ax = fig.subplots()
        h = self.history
        ax.plot(h.step, h.crossover, "o-", label="crossover achieved")
        ax.plot(h.step, h.drb, "s-", label="DRB achieved")
        ax.plot(h.step, h.crossover_min, "k--", lw=0.8, label="crossover boundary")
        bad = ~h.feasible
        ax.plot(h.step[bad], h.crossover[bad], "rx", ms=10, label="infeasible")
        ax.set_xlabel("DMO step")
        ax.set_ylabel("rad/s")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        return fig


def _problem(design, crossover_min, drb_min, settings, phase, phase_from):
    w = np.asarray(settings.omega, float)
    s = 1j * w
    q = design._g(s) * design._sensor(s)
    qr, qi = q.real, q.imag
    opti = ca.Opti()
    if settings.tie_integral:
        x = opti.variable(2)
        k_phi, k_p = x[0], x[1]
        k_i = k_phi * crossover_min / 5.0
    else:
        x = opti.variable(3)
        k_phi, k_i, k_p = x[0], x[1], x[2]
    opti.subject_to(x >= 0)
    cr = k_p - k_i / w ** 2
    ci = -k_phi / w
    lr = cr * qr - ci * qi
    li = cr * qi + ci * qr
    mag2 = lr ** 2 + li ** 2
    one_r, one_i = 1 + lr, li
    dist2 = one_r ** 2 + one_i ** 2
    ang = ca.atan2(-li, -lr)
    gdb = 10 * ca.log10(mag2 + 1e-12)
    ellipse = (ang / np.radians(settings.pm_deg)) ** 2 + (gdb / settings.gm_db) ** 2
    # unwrapped loop phase: Im C = -K_phi/w < 0, so atan2(Im C, Re C) is continuous
    # in (-pi, 0) and adds smoothly to the (numerically unwrapped) phase of Q.
    # np.unwrap anchors at the lowest frequency, where a free aircraft's
    # near-cancelling pole/zero pairs at the origin put the phase of Q close to
    # +-180 deg with an arbitrary branch; anchor instead at the crossover boundary,
    # where any design meeting the phase margin has |phase Q| < 180 deg.
    k_anchor = min(int(np.searchsorted(w, crossover_min)), w.size - 1)
    phase_q = np.unwrap(np.angle(q))
    phase_q -= 2 * np.pi * np.round((phase_q[k_anchor] - np.angle(q[k_anchor])) / (2 * np.pi))
    phase_l = phase_q + ca.atan2(ci, cr)
    beyond = 1.0 / (1.0 + ca.exp((phase_l + np.pi) / np.radians(3.0)))   # ~1 where phase < -180 deg
    slack = opti.variable() if phase == 1 else 0
    if phase == 1:
        opti.subject_to(slack >= 0)
    opti.subject_to(ellipse + slack >= 1.0)
    opti.subject_to(dist2 + slack >= 10 ** (-settings.drp_db / 10))
    # past the phase crossover the gain must be below -GM (no conditionally stable
    # loop above half the crossover boundary; the integrator's low-frequency
    # -180 deg region is allowed and checked by the eigenvalue spec)
    hi = np.flatnonzero(w >= phase_from * crossover_min)
    opti.subject_to((gdb[hi] + settings.gm_db) * beyond[hi] <= slack)
    low = w <= drb_min
    if low.any():
        opti.subject_to(dist2[np.flatnonzero(low)] + slack >= 2.0)
    # crossover boundary, at the grid point nearest above w_cmin
    kc = int(np.searchsorted(w, crossover_min))
    kc = min(kc, w.size - 1)
    opti.subject_to(mag2[kc] + slack >= 1.0)
    if phase == 1:
        opti.minimize(slack + 1e-6 * ca.sumsqr(x))
    else:
        # objectives: crossover (loop gain just above the boundary) + actuator RMS proxy
        kx = min(w.size - 1, int(np.searchsorted(w, 1.5 * crossover_min)))
        c2 = cr ** 2 + ci ** 2
        act = ca.sum1(c2 * (w ** 2) * np.abs(q / q) ** 2 / dist2 * np.gradient(w)) / np.pi
        opti.minimize(mag2[kx] + settings.actuator_weight * act)
    return opti, x, slack


def _gains_from(x, crossover_min, settings):
    x = np.atleast_1d(np.asarray(x, float))
    if settings.tie_integral:
        return PIDGains(K_phi=float(x[0]), K_Iphi=float(x[0] * crossover_min / 5.0), K_p=float(x[1]))
    return PIDGains(K_phi=float(x[0]), K_Iphi=float(x[1]), K_p=float(x[2]))


def _verify(design, settings):
    """Re-check margins with python-control on the Padé state-space loop."""
    gm_exact, pm_exact, _, _ = m.gain_phase_margins(design.broken_loop())
    # python-control's 'poly' method forms the loop's polynomials, which overflow
    # for the 40-60 state identified-inflow loops; its 'frd' method interpolates
    # the (well-conditioned) state-space frequency response on a dense grid instead
    loop = design.broken_loop_statespace(pade_order=4)
    grid = control.frd(loop, np.logspace(-2, 3, 4000))
    gm, pm, _, _, _, _ = control.stability_margins(grid, method="frd")
    gm_db = 20 * np.log10(gm) if np.isfinite(gm) and gm > 0 else np.inf
    if np.isfinite(gm_exact) and np.isfinite(gm_db) and abs(gm_db - gm_exact) > settings.verify_tolerance_db:
        raise VerificationError(f"gain margin: exact {gm_exact:.3f} dB vs python-control {gm_db:.3f} dB")
    if np.isfinite(pm_exact) and np.isfinite(pm) and abs(pm - pm_exact) > settings.verify_tolerance_deg:
        raise VerificationError(f"phase margin: exact {pm_exact:.3f} deg vs python-control {pm:.3f} deg")


def optimize(design, crossover_min, drb_min, specs=None, settings=None, x0=None) -> OptimizationResult:
    """Feasibility then objective phase for one set of boundaries.

    Returns the design with optimised gains, its spec table (python-control /
    exact evaluation, independent of the optimiser's formulas) and the list of
    unmet hard/soft specs (empty when feasible).
    """
    settings = settings or DMOSettings()
    specs = specs if specs is not None else default_specs(crossover_min, drb_min)
    fractions = settings.phase_constraint_from
    fractions = (fractions,) if np.isscalar(fractions) else tuple(fractions)
    best = None
    for phase_from in fractions:
        res = _optimize_once(design, crossover_min, drb_min, specs, settings, x0, phase_from)
        if res.feasible:
            return res
        if best is None or len(res.unmet) < len(best.unmet):
            best = res
    return best


def _optimize_once(design, crossover_min, drb_min, specs, settings, x0, phase_from):
    nvar = 2 if settings.tie_integral else 3
    start = np.full(nvar, 0.1) if x0 is None else np.asarray(x0, float)
    opti, x, slack = _problem(design, crossover_min, drb_min, settings, 1, phase_from)
    opti.set_initial(x, start)
    opti.solver("ipopt", settings.ipopt)
    try:
        sol = opti.solve()
        x1, s1 = sol.value(x), float(sol.value(slack))
    except RuntimeError:
        x1, s1 = opti.debug.value(x), float(opti.debug.value(slack))
    xbest = x1
    if s1 <= 1e-6:
        opti2, x2v, _ = _problem(design, crossover_min, drb_min, settings, 2, phase_from)
        opti2.set_initial(x2v, x1)
        opti2.solver("ipopt", settings.ipopt)
        try:
            xbest = opti2.solve().value(x2v)
        except RuntimeError:
            xbest = x1
    candidate = design.with_gains(_gains_from(xbest, crossover_min, settings))
    table = evaluate_specs(candidate, specs)
    unmet = list(table.loc[(table.kind != "objective") & (~table.met), "spec"])
    if not unmet:
        _verify(candidate, settings)
    return OptimizationResult(candidate, not unmet, table, unmet, s1, crossover_min, drb_min)


def dmo(design, specs_factory=default_specs, settings=None, crossover_start=1.5, drb_start=0.9,
        progress=True) -> DMOResult:
    """Raise the crossover and DRB Level 1 boundaries until infeasible.

    Parameters
    ----------
    design : EMFDesign
        Plant, command model, actuator, sensor, inverse plant, tau_eq (its
        gains are only the starting point).
    specs_factory : callable(crossover_min, drb_min) -> list of Spec
    crossover_start, drb_start : float
        First boundaries [rad/s] (DRB Level 1 for roll: 0.9 rad/s).

    Returns
    -------
    DMOResult
        ``design`` is None (and ``message`` names the unmet specs) when not even
        the starting boundaries can be met.
    """
    settings = settings or DMOSettings()
    t0 = time.perf_counter()
    rows, last, last_table, limiting = [], None, None, []
    x0 = None
    bar = tqdm(range(settings.max_steps), desc="DMO", disable=not progress)
    for step in bar:
        wc = crossover_start + step * settings.step
        wd = drb_start + step * settings.step * drb_start / crossover_start
        res = optimize(design, wc, wd, specs_factory(wc, wd), settings, x0=x0)
        tab = res.specs.set_index("spec")
        g = res.design.gains
        rows.append({"step": step, "crossover_min": wc, "drb_min": wd, "feasible": res.feasible,
                     "K_phi": g.K_phi, "K_Iphi": g.K_Iphi, "K_p": g.K_p,
                     "crossover": tab.loc["CrsMnG2", "value"], "drb": tab.loc["DrbRoH1", "value"],
                     "unmet": ", ".join(res.unmet)})
        bar.set_postfix(wc=f"{wc:.2f}", feasible=res.feasible)
        if not res.feasible:
            limiting = res.unmet
            break
        last, last_table = res.design, res.specs
        x0 = [g.K_phi, g.K_p] if settings.tie_integral else g.as_array()
    bar.close()
    history = pd.DataFrame(rows)
    wall = time.perf_counter() - t0
    if last is None:
        msg = ("no design meets every spec even at the starting boundaries; unmet: "
               + ", ".join(limiting))
    else:
        msg = (f"DMO stopped after {len(history) - 1} feasible steps; limiting spec(s): "
               f"{', '.join(limiting) if limiting else 'none (step limit reached)'}")
    return DMOResult(last, last_table, history, limiting, wall, msg)
