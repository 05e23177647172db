"""Settings and errors of the design-margin optimiser (:func:`controllers.dmo`).

The settings say how the optimiser searches (grid, starts, continuation,
bisection tolerance, IPOPT options); they carry no spec boundary: every
boundary the optimiser honours is read from the spec objects it is given
(see :mod:`controllers.smooth`).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["DMOSettings", "VerificationError", "SolverError", "InfeasibleDesignError"]


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
    multistart : int
        Sobol starts of the multistart stage (:func:`controllers.multistart.multistart`:
        every gain free on its own log scale over ``multistart_decades``, the best
        feasible starts and the starting gains polished on the true specs; the NLP
        continuation then also runs from the best). 0 (default) leaves it out.
    multistart_polish : int
        Best feasible starts (one per basin) polished by the multistart stage.
    multistart_evaluations : int
        Spec evaluations per polished start.
    multistart_decades : (float, float)
        log10 range of each gain in its natural unit (as :func:`controllers.search.global_search`).
    """

    omega: np.ndarray = field(default_factory=lambda: np.geomspace(0.05, 80.0, 250))
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
    multistart: int = 0
    multistart_polish: int = 3
    multistart_evaluations: int = 60
    multistart_decades: tuple = (-3.0, 2.0)
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
        for name in ("tolerance", "gain_upper", "actuator_weight"):
            v = getattr(self, name)
            if not np.isfinite(v) or v <= 0:
                raise ValueError(f"DMOSettings.{name} must be finite and > 0, got {v}")
        if not np.isfinite(self.growth) or self.growth <= 1:
            raise ValueError(f"DMOSettings.growth must be > 1, got {self.growth}")
        if self.n_starts < 0 or self.max_steps < 1:
            raise ValueError("DMOSettings.n_starts must be >= 0 and max_steps >= 1")
        for name in ("global_samples", "global_candidates", "multistart", "multistart_polish",
                     "multistart_evaluations"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 0:
                raise ValueError(f"DMOSettings.{name} must be an integer >= 0, got {v!r}")
        lo, hi = self.multistart_decades
        if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
            raise ValueError(f"DMOSettings.multistart_decades must be (low, high) with low < high, "
                             f"got {self.multistart_decades!r}")
        lo, hi = self.global_scale_span
        if not (np.isfinite(lo) and np.isfinite(hi) and 0 < lo < hi):
            raise ValueError(f"DMOSettings.global_scale_span must be (low, high) with 0 < low < high, "
                             f"got {self.global_scale_span!r}")

