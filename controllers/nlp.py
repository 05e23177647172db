"""The smooth CasADi/IPOPT problem behind :func:`controllers.dmo` (private).

The loop broken at the mixer input is L(jw) = C(jw) Q(jw), Q = actuator x plant
x sensor (numbers on a grid, exact delays), C = K_p - K_Iphi/w^2 - j K_phi/w
linear in the gains.  The constraints are not written here: they come from the
specs the problem is given (each spec's :class:`~controllers.smooth.SmoothConstraint`),
with their boundaries as NLP parameters read from the specs at every solve.
"""
from __future__ import annotations

import casadi as ca
import numpy as np

from . import metrics as m
from .smooth import LoopGrid, SolvePoint

__all__ = []


# a plant pole further right than this [1/s] makes the plant unstable (a pole at the origin,
# e.g. an attitude integrator, computed a round-off to the right, does not)
_UNSTABLE_POLE = 1e-6


def _unstable(design):
    """Whether the design's plant has a pole in the right half plane (a loop around it is conditionally stable)."""
    system = design.plant.system
    poles = system.poles() if hasattr(system, "poles") else np.roots(np.atleast_1d(system))
    return bool(np.size(poles) and np.max(np.real(poles)) > _UNSTABLE_POLE)


def _loop_factor(design, omega, index=0):
    s = 1j * omega
    q = design._g(s) * design._sensor(s)
    bad = ~np.isfinite(q)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise m.NonFiniteResponseError(
            f"plant {index} ({design.plant.name or 'unnamed'}): actuator x plant x sensor is {q[k]} at "
            f"omega = {omega[k]:.6g} rad/s", float(omega[k]))
    return q


def _gain_scale(designs, crossover_min):
    """K_phi [stick/rad] that puts |K_phi/w Q| = 1 at the crossover boundary (mean over plants)."""
    w = np.array([crossover_min])
    mags = [abs(_loop_factor(d, w, i)[0]) for i, d in enumerate(designs)]
    return float(crossover_min / np.exp(np.mean(np.log(mags))))


def _gains(x, scale, crossover_min, tie):
    """Physical gains from scaled variables (works on numbers and CasADi symbols)."""
    k_phi = x[0] * scale
    k_i = k_phi * crossover_min / 5.0 if tie else x[1] * scale * crossover_min
    k_p = x[1 if tie else 2] * scale / crossover_min
    return k_phi, k_i, k_p


def _smooth_specs(specs):
    """The specs whose smooth constraints enter the NLP, in list order.

    A constraint implied by another one of the list (e.g. a phase-margin band
    inside the Nichols ellipse) is left out: same feasible set, fewer rows.  Of
    two constraints that imply each other the first is kept.
    """
    cands = [s for s in specs if getattr(s, "smooth", None) is not None]

    def implied(a, b):
        return a.smooth.implied_by(a, b.smooth, b)

    return [a for i, a in enumerate(cands)
            if not any(j != i and implied(a, b) and not (j > i and implied(b, a)) for j, b in enumerate(cands))]


class _Problem:
    """The smooth NLP for one spec structure: boundaries enter as parameters.

    Variables: scaled gains and a slack (exact penalty: the problem is always
    feasible, slack 0 means every smooth constraint holds).  Parameters: the
    gain scale and crossover boundary, the objective's crossover-proxy mask,
    per plant the loop phase branch, then each smooth constraint's parameters
    (shared by the plants).  The problem is built for the smooth constraints
    of the spec list it is given and rebuilt if a later list has others.
    """

    _PENALTY = 1e3

    def __init__(self, designs, settings, specs):
        self.settings = settings
        self.designs = designs
        self.q = [_loop_factor(d, settings.omega, k) for k, d in enumerate(designs)]
        self.unstable_plant = any(_unstable(d) for d in designs)
        self._build(specs)

    def _build(self, specs):
        settings = self.settings
        w = settings.omega
        n = w.size
        self.key = self.constraints = self._key(specs)
        self.nvar = nvar = 2 if settings.tie_integral else 3
        x = ca.SX.sym("x", nvar)
        slack = ca.SX.sym("slack")
        scale, wc = ca.SX.sym("scale"), ca.SX.sym("wc")
        e_kx = ca.SX.sym("e_kx", n)
        phases = [ca.SX.sym(f"phase_q{k}", n) for k in range(len(self.designs))]
        cpars = [ca.SX.sym(f"c{k}", c.n_parameters(n)) for k, c in enumerate(self.constraints)]
        params = ca.vertcat(scale, wc, e_kx, *phases, *cpars)
        k_phi, k_i, k_p = _gains(x, scale, wc, settings.tie_integral)
        dm = lambda a: ca.DM(np.asarray(a, float).reshape(-1, 1))
        # CasADi column vectors (numpy arrays times SX scalars would build one
        # scalar expression per grid point)
        cr = k_p - k_i * dm(1.0 / w ** 2)
        ci = -k_phi * dm(1.0 / w)
        cons, objective = [], 0.0
        for q, phase_q in zip(self.q, phases):
            qr, qi = dm(q.real), dm(q.imag)
            lr = cr * qr - ci * qi
            li = cr * qi + ci * qr
            mag2 = lr ** 2 + li ** 2
            dist2 = (1 + lr) ** 2 + li ** 2
            # unwrapped loop phase: Im C = -K_phi/w < 0, so atan2(Im C, Re C) is
            # continuous in (-pi, 0) and adds smoothly to the unwrapped phase of Q
            loop = LoopGrid(omega=w, backoff=settings.backoff, re=lr, im=li, mag2=mag2, dist2=dist2,
                            angle=ca.atan2(-li, -lr), gain_db=10 * ca.log10(mag2 + 1e-12),
                            phase=phase_q + ca.atan2(ci, cr))
            for c, p in zip(self.constraints, cpars):
                cons.extend(e + slack for e in c.expressions(loop, p))
            act = ca.sum1((cr ** 2 + ci ** 2) * dm(w ** 2 * np.gradient(w)) / dist2) / np.pi
            objective = objective + ca.dot(e_kx, mag2) + settings.actuator_weight * act / scale ** 2
        g = ca.vertcat(*cons) if cons else ca.SX(0, 1)
        self._g = ca.Function("g", [ca.vertcat(x, slack), params], [g])
        self.solver = ca.nlpsol("dmo", "ipopt", {"x": ca.vertcat(x, slack), "p": params,
                                                  "f": objective + self._PENALTY * slack, "g": g},
                                settings.ipopt)
        self.ng = g.shape[0]

    @staticmethod
    def _key(specs):
        """What fixes the NLP's structure: the smooth constraints that enter it (compared by value)."""
        return tuple(s.smooth for s in _smooth_specs(specs))

    def parameters(self, specs, crossover_min, phase_from, scale):
        w = self.settings.omega
        point = SolvePoint(w, self.settings.backoff, crossover_min, phase_from, self.unstable_plant)
        onehot = lambda k: np.eye(1, w.size, min(k, w.size - 1)).ravel()
        phases = []
        k_anchor = min(int(np.searchsorted(w, crossover_min)), w.size - 1)
        for q in self.q:
            # branch anchored at the crossover boundary, where any design meeting the
            # phase margin has |phase Q| < 180 deg (not at the lowest frequency, where a
            # free aircraft's near-cancelling pole/zero pairs give an arbitrary branch)
            ph = np.unwrap(np.angle(q))
            ph -= 2 * np.pi * np.round((ph[k_anchor] - np.angle(q[k_anchor])) / (2 * np.pi))
            phases.append(ph)
        cvals = [s.smooth.parameters(s, point) for s in _smooth_specs(specs)]
        return np.concatenate([[scale, crossover_min], onehot(int(np.searchsorted(w, 1.5 * crossover_min))),
                               *phases, *cvals])

    def constraint_values(self, x, specs, crossover_min, phase_from, scale):
        """The smooth constraints at scaled gains ``x`` with zero slack (>= 0: met)."""
        if self._key(specs) != self.key:
            self._build(specs)
        z = np.r_[np.asarray(x, float), 0.0]
        return np.asarray(self._g(z, self.parameters(specs, crossover_min, phase_from, scale)), float).ravel()

    def solve(self, x0, specs, crossover_min, phase_from, scale):
        """Returns (scaled gains, slack, IPOPT return status) for the boundaries of ``specs``."""
        if self._key(specs) != self.key:
            self._build(specs)      # another spec structure: another NLP
        lbx = np.zeros(self.nvar + 1)
        ubx = np.r_[np.full(self.nvar, self.settings.gain_upper), np.inf]
        z0 = np.r_[np.clip(x0, 0.0, self.settings.gain_upper), 1.0]
        sol = self.solver(x0=z0, p=self.parameters(specs, crossover_min, phase_from, scale), lbx=lbx,
                          ubx=ubx, lbg=np.zeros(self.ng), ubg=np.full(self.ng, np.inf))
        status = self.solver.stats()["return_status"]
        z = np.clip(np.asarray(sol["x"], float).ravel(), lbx, ubx)   # IPOPT relaxes bounds by ~1e-8
        return z[:-1], float(z[-1]), status
