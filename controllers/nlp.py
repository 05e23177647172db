"""The smooth CasADi/IPOPT problem behind :func:`controllers.dmo` (private).

The loop broken at the mixer input is L(jw) = C(jw) Q(jw), Q = actuator x plant
x sensor (numbers on a grid, exact delays), C = K_p - K_Iphi/w^2 - j K_phi/w
linear in the gains; see :mod:`controllers.dmo` for the constraints.
"""
from __future__ import annotations

import casadi as ca
import numpy as np

from . import metrics as m

__all__ = []


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


class _Problem:
    """The smooth NLP, built once per DMO: boundaries enter as parameters.

    Variables: scaled gains and a slack (exact penalty: the problem is always
    feasible, slack 0 means every smooth constraint holds).  Parameters per
    plant: the scale, the boundaries, 0/1 masks selecting the grid points of
    the DRB, phase and crossover constraints, and the loop phase branch.
    """

    _PENALTY = 1e3

    def __init__(self, designs, settings):
        self.settings = settings
        self.designs = designs
        w = settings.omega
        n = w.size
        bo = settings.backoff
        self.nvar = nvar = 2 if settings.tie_integral else 3
        self.q = [_loop_factor(d, w, k) for k, d in enumerate(designs)]
        x = ca.SX.sym("x", nvar)
        slack = ca.SX.sym("slack")
        scale, wc = ca.SX.sym("scale"), ca.SX.sym("wc")
        mask_hi, mask_low = ca.SX.sym("mask_hi", n), ca.SX.sym("mask_low", n)
        e_kc, e_kx = ca.SX.sym("e_kc", n), ca.SX.sym("e_kx", n)
        phases = [ca.SX.sym(f"phase_q{k}", n) for k in range(len(designs))]
        params = ca.vertcat(scale, wc, mask_hi, mask_low, e_kc, e_kx, *phases)
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
            ang = ca.atan2(-li, -lr)
            gdb = 10 * ca.log10(mag2 + 1e-12)
            ellipse = ((ang / np.radians(settings.pm_deg * (1 + bo))) ** 2
                       + (gdb / (settings.gm_db * (1 + bo))) ** 2)
            # unwrapped loop phase: Im C = -K_phi/w < 0, so atan2(Im C, Re C) is
            # continuous in (-pi, 0) and adds smoothly to the unwrapped phase of Q
            beyond = 1.0 / (1.0 + ca.exp((phase_q + ca.atan2(ci, cr) + np.pi) / np.radians(3.0)))
            cons.append(ellipse + slack - 1.0)
            cons.append(dist2 + slack - 10 ** (-settings.drp_db * (1 - bo) / 10))
            cons.append(slack - mask_hi * (gdb + settings.gm_db) * beyond)
            cons.append(mask_low * (dist2 - 2.0 * (1 + bo)) + slack)
            cons.append(ca.dot(e_kc, mag2) + slack - 1.0)
            act = ca.sum1((cr ** 2 + ci ** 2) * dm(w ** 2 * np.gradient(w)) / dist2) / np.pi
            objective = objective + ca.dot(e_kx, mag2) + settings.actuator_weight * act / scale ** 2
        g = ca.vertcat(*cons)
        self.solver = ca.nlpsol("dmo", "ipopt", {"x": ca.vertcat(x, slack), "p": params,
                                                  "f": objective + self._PENALTY * slack, "g": g},
                                settings.ipopt)
        self.ng = g.shape[0]

    def parameters(self, crossover_min, drb_min, phase_from, scale):
        w = self.settings.omega
        bo = self.settings.backoff
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
        return np.concatenate([[scale, crossover_min], (w >= phase_from * crossover_min).astype(float),
                               (w <= drb_min * (1 + bo)).astype(float),
                               onehot(int(np.searchsorted(w, crossover_min * (1 + bo)))),
                               onehot(int(np.searchsorted(w, 1.5 * crossover_min))), *phases])

    def solve(self, x0, crossover_min, drb_min, phase_from, scale):
        """Returns (scaled gains, slack, IPOPT return status)."""
        lbx = np.zeros(self.nvar + 1)
        ubx = np.r_[np.full(self.nvar, self.settings.gain_upper), np.inf]
        z0 = np.r_[np.clip(x0, 0.0, self.settings.gain_upper), 1.0]
        sol = self.solver(x0=z0, p=self.parameters(crossover_min, drb_min, phase_from, scale), lbx=lbx,
                          ubx=ubx, lbg=np.zeros(self.ng), ubg=np.full(self.ng, np.inf))
        status = self.solver.stats()["return_status"]
        z = np.clip(np.asarray(sol["x"], float).ravel(), lbx, ubx)   # IPOPT relaxes bounds by ~1e-8
        return z[:-1], float(z[-1]), status
