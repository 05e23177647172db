"""Pitt-Peters dynamic inflow (Eq. 1.10) for one or more independent rotors.

Per rotor, in rotor-azimuth time (' = d/dpsi)::

    [M] {lam}' + [V] [Lhat]^-1 {lam} = {C_T, C_L, C_M} + K_R forcing        (Eqs. 1.10, 2.29)

with, in our sign convention (see :mod:`aircraft.inflow.base`; the dissertation
writes the classical form with forcing (C_T, -C_L, -C_M) and positive M, L):

* M = diag(8/(3 pi), -16/(45 pi), -16/(45 pi))
* Lhat (Pitt & Peters 1981, with the wake angle alpha, sin(alpha) = lam_tot / V_T)::

      [[1/2,                         0,                  15 pi/64 sqrt((1-sin a)/(1+sin a))],
       [0,                           -4/(1+sin a),       0                                 ],
       [15 pi/64 sqrt((1-sin a)/(1+sin a)), 0,            -4 sin a/(1+sin a)               ]]

* mass-flow matrix [V] = diag(V_T, V, V) (Peters & HaQuang 1988):
  V_T = sqrt(mu^2 + lam_tot^2), V = (mu^2 + lam_tot (lam_tot + lam0)) / V_T,
  lam_tot = mu_c + lam0 (mu_c: climb, incl. interference climb of coaxial models).

In hover (mu = 0, mu_c = 0) this gives [V][Lhat]^-1 = diag(2 lam0, -lam0, -lam0): the
steady state is momentum theory, C_T = 2 lam0^2, and the numerical linearisation
gives Lbar11 = d(2 lam0^2)/d lam0 = 4 lam_h (the mass-flow perturbation doubles the
classical 2 lam_h), Lbar22 = Lbar33 = -lam_h, M11 = 8/(3 pi), M22 = M33 = -16/(45 pi):
the Pitt-Peters rows of Tables 4.1-4.2.  In climb Eq. 2.4 follows:
Lbar^-1 diag entries 2 lam_tot and -(lam0 + mu_c/2).

Wake distortion (Eq. 2.29): with ``kr`` > 0 the model takes the tip-path-plane
rates ``beta1s_dot, beta1c_dot`` [rad/s] (relative to space, i.e. flap rate minus
body rate in the rotor frame) and adds ``[V][Lhat]^-1 {0, -K_R b1s', -K_R b1c'}``
to the forcing (b' = rate / Omega).
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import fsolve

from .base import InflowModel, RotorOperatingPoint, rotor_suffix

__all__ = ["PittPeters", "IsolatedRotors", "pitt_peters_matrices", "momentum_inflow",
           "mlbar_from_statespace", "InflowError"]

M_PITT_PETERS = np.diag([8 / (3 * np.pi), -16 / (45 * np.pi), -16 / (45 * np.pi)])


class InflowError(ValueError):
    """Inputs an inflow model cannot handle (no momentum solution, wrong sizes)."""


def momentum_inflow(ct, mu=0.0, mu_c=0.0, tol=1e-14):
    """Induced inflow lam0 from momentum theory: C_T = 2 lam0 sqrt(mu^2 + (mu_c + lam0)^2).

    ``mu_c`` is the climb ratio (positive: climb; the flow through the disk is
    mu_c + lam0).  Requires C_T > 0.
    """
    if not ct > 0:
        raise InflowError(f"momentum theory needs a positive thrust coefficient, got C_T = {ct!r}")
    if mu == 0.0:
        # hover/axial climb: closed form of lam0 (lam0 + mu_c) = C_T/2 (Eq. 2.5)
        return float(-mu_c / 2 + np.sqrt(mu_c ** 2 / 4 + ct / 2))
    lam = np.sqrt(ct / 2)
    for _ in range(200):
        f = 2 * lam * np.sqrt(mu ** 2 + (mu_c + lam) ** 2) - ct
        df = 2 * np.sqrt(mu ** 2 + (mu_c + lam) ** 2) + 2 * lam * (mu_c + lam) / np.sqrt(mu ** 2 + (mu_c + lam) ** 2)
        step = f / df
        lam -= step
        if abs(step) < tol:
            break
    return float(lam)


def pitt_peters_matrices(lam0, mu=0.0, mu_c=0.0):
    """(M, [V][Lhat]^-1) of one rotor at induced inflow lam0 (azimuth time)."""
    lam_tot = mu_c + lam0
    vt = np.sqrt(mu ** 2 + lam_tot ** 2)
    if vt <= 0:
        raise InflowError("zero total flow through the disk: the Pitt-Peters mass flow vanishes")
    v = (mu ** 2 + lam_tot * (lam_tot + lam0)) / vt
    sin_a = lam_tot / vt
    x = np.sqrt(max(0.0, (1 - sin_a)) / (1 + sin_a)) if sin_a > -1 else 0.0
    lhat = np.array([[0.5, 0.0, 15 * np.pi / 64 * x],
                     [0.0, -4 / (1 + sin_a), 0.0],
                     [15 * np.pi / 64 * x, 0.0, -4 * sin_a / (1 + sin_a)]])
    return M_PITT_PETERS, np.diag([vt, v, v]) @ np.linalg.inv(lhat)


def mlbar_from_statespace(sys, omega):
    """(M, Lbar) in azimuth time from a first-order inflow StateSpace in seconds.

    With x' = A x + B u [1/s]: M = Omega B^-1, Lbar = -B^-1 A (only for models
    whose inputs are the loads, one per state).
    """
    b = np.asarray(sys.B, float)
    a = np.asarray(sys.A, float)
    if b.shape[0] != b.shape[1]:
        raise InflowError(f"B must be square to recover M/Lbar, got {b.shape}")
    binv = np.linalg.inv(b)
    return omega * binv, -binv @ a


class PittPeters(InflowModel):
    """Pitt-Peters inflow for independent rotors (nonlinear, Eq. 1.10).

    Parameters
    ----------
    rotors : tuple of str
        Rotor names (``("",)`` single rotor, ``("U", "L")`` isolated coaxial rotors).
    kr : float
        Wake-distortion parameter K_R (Eq. 2.29); 0 disables the flap-rate inputs.
    """

    def __init__(self, rotors=("",), kr=0.0):
        self.rotors = tuple(rotors)
        self.kr = float(kr)
        self.uses_flap_rates = self.kr != 0.0

    @property
    def state_names(self):
        return [f"{c}{rotor_suffix(r)}" for r in self.rotors for c in ("lam0", "lam1s", "lam1c")]

    # -- hooks for coaxial interference ---------------------------------------
    def _climbs(self, x, ops):
        """Interference climb mu_c per rotor (on top of the free-stream climb)."""
        return np.zeros(len(self.rotors))

    # -- interface --------------------------------------------------------------
    def _check(self, loads, ops):
        loads = np.asarray(loads, dtype=float)
        n = len(self.rotors)
        if loads.shape != (3 * n,):
            raise InflowError(f"loads must have {3 * n} entries {self.load_names}, got shape {loads.shape}")
        if len(ops) != n or not all(isinstance(o, RotorOperatingPoint) for o in ops):
            raise InflowError(f"ops must be {n} RotorOperatingPoint(s)")
        if not np.all(np.isfinite(loads)):
            raise InflowError("loads contain NaN or infinite values")
        return loads

    def _rotor_rhs(self, k, lam, loads, op, mu_c, rates):
        m, lbar = pitt_peters_matrices(lam[0], op.mu, op.mu_z + mu_c)
        forcing = loads[3 * k:3 * k + 3].copy()
        if rates is not None and self.kr:
            b = np.asarray(rates[2 * k:2 * k + 2], float) / op.omega
            forcing = forcing + lbar @ np.array([0.0, -self.kr * b[0], -self.kr * b[1]])
        return np.linalg.solve(m, forcing - lbar @ lam)

    def derivatives(self, x, loads, ops, rates=None):
        loads = self._check(loads, ops)
        x = np.asarray(x, dtype=float)
        climbs = self._climbs(x, ops)
        out = np.empty_like(x)
        for k, op in enumerate(ops):
            lam = x[3 * k:3 * k + 3]
            # the one place azimuth time becomes seconds: d/dt = Omega d/dpsi
            out[3 * k:3 * k + 3] = op.omega * self._rotor_rhs(k, lam, loads, op, climbs[k], rates)
        return out

    def inflow(self, x, loads, ops):
        x = np.asarray(x, dtype=float).copy()
        climbs = self._climbs(x, ops)
        for k in range(len(self.rotors)):
            x[3 * k] += climbs[k]
        return x

    def steady_state(self, loads, ops):
        loads = self._check(loads, ops)
        guess = []
        for k, op in enumerate(ops):
            lam0 = momentum_inflow(loads[3 * k], op.mu, op.mu_z)
            guess += [lam0, 0.0, 0.0]
        guess = np.array(guess)
        scale = np.array([o.omega for o in ops for _ in range(3)])
        residual = lambda x: self.derivatives(x, loads, ops) / scale
        sol, info, ier, msg = fsolve(residual, guess, full_output=True, xtol=1e-12)
        # judge by the residual (fsolve's own flag complains near machine precision)
        if not np.all(np.isfinite(sol)) or np.max(np.abs(residual(sol))) > 1e-12:
            raise InflowError(f"no steady inflow for loads {loads}: {msg}")
        return sol


class IsolatedRotors(PittPeters):
    """Two non-interfering Pitt-Peters rotors ("Isolated Rotor" model, §2.2.2.2)."""

    def __init__(self, kr=0.0):
        super().__init__(rotors=("U", "L"), kr=kr)
