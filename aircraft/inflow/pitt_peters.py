"""Pitt-Peters dynamic inflow (Eq. 1.10) for one or more independent rotors.

Per rotor, in rotor-azimuth time (' = d/dpsi)::

    [M] {lam}' + [V] [Lhat]^-1 {lam} = {C_T, C_L, C_M} + [V][Lhat]^-1 {0, -K_R b1s', -K_R b1c'}
                                                                   (Eqs. 1.10, 2.29)

in our sign convention (:mod:`aircraft.inflow.base`), which is the dissertation's
Eq. 2.11 convention. Eq. 1.10 is the Peters & HaQuang form with positive M and
[L] and forcing ``(C_T, -C_L, -C_M)``; multiplying its rows 2-3 by -1 gives the
forcing ``(C_T, C_L, C_M)`` and negates rows 2-3 of M and of ``[L]^-1`` (i.e. columns
2-3 of ``[L]``), which is where the negative M22 = M33 and Lbar22 = Lbar33 of
Eq. 2.11 and Tables 4.1-4.2 come from. The matrices used here:

* apparent mass: ``M = diag(8/(3 pi), -16/(45 pi), -16/(45 pi))`` (the dissertation's
  values; Pitt & Peters 1981 print 128/(75 pi) for M11, Peters & HaQuang 1988 use
  8/(3 pi));
* wake-skew influence matrix, **Pitt & Peters (1981)** form, written in the
  Eq. 2.11 moment-sign convention (negative 22 and 33 entries), with the wake
  angle ``sin(a) = lam_tot / V_T`` (``a`` = angle of the resultant flow to the disk;
  the wake skew from the shaft is ``chi = pi/2 - a``, ``cos(chi) = sin(a)``,
  ``tan(chi/2) = sqrt((1 - sin a)/(1 + sin a))``)::

      Lhat = [[1/2,   0,              X],
              [0,     -4/(1+sin a),   0],
              [X,     0,              -4 sin a/(1+sin a)]],   X = 15 pi/64 tan(chi/2)

  Open codes disagree on the sign of X relative to the moment signs. Ours is
  fixed by two independent checks (both in ``tests/aircraft/inflow/test_inflow_pitt_peters.py``):
  a positive thrust gives more inflow at the rear of the disk (steady
  ``lam1c = (15 pi/32) tan(chi/2) lam0 > 0``, Glauert/Coleman), and Lbar13, Lbar31
  have the signs (both positive) of the free-wake identifications of Eqs.
  4.7-4.8. (X with opposite signs in rows 1 and 3 would make Lbar13 and Lbar31
  of opposite sign.) In hover ``a = pi/2``, ``X = 0`` and Lhat = diag(1/2, -2, -2);
* mass-flow matrix, **Peters & HaQuang (1988)**: ``[V] = diag(V_T, V, V)`` with
  ``V_T = sqrt(mu^2 + lam_tot^2)`` (thrust row) and
  ``V = (mu^2 + lam_tot (lam_tot + lam0)) / V_T`` (moment rows),
  ``lam_tot = mu_z + mu_c + lam0`` (free-stream climb ``mu_z`` of
  :class:`~aircraft.inflow.base.RotorOperatingPoint` plus the interference climb
  ``mu_c`` of the coaxial models).

Steady state: ``lam0`` from momentum theory ``C_T = 2 lam0 sqrt(mu^2 + lam_tot^2)``.

Hover, and why Lbar11 = 4 lambda_h (not 2 lambda_h)
---------------------------------------------------
In hover [V][Lhat]^-1 = diag(2 lam0, -lam0, -lam0). The classical *linear*
Pitt-Peters model freezes [V] at trim and so has Lbar11 = 2 lambda_h. The
aircraft uses the *nonlinear* model, and its numerical linearisation also
perturbs the mass flow: d(V_T lam0)/d lam0 = 2 d(lam0^2)/d lam0 = 4 lambda_h
(``dV/dlambda`` adds another 2 lambda_h); the moment rows have no such term at
trim because lam1s = lam1c = 0 there. Hence, in the (dC_T, dC_L, dC_M) form of
Eq. 2.11::

    M11 = 8/(3 pi), M22 = M33 = -16/(45 pi), Lbar11 = 4 lambda_h, Lbar22 = Lbar33 = -lambda_h

(azimuth time; Tables 4.1-4.2 print M/Omega). :func:`mlbar_from_statespace`
recovers (M, Lbar) from a linear model in seconds.

Climb (Eqs. 2.4-2.5): with ``mu = 0`` the diagonal of [V][Lhat]^-1 is
``(2 lam_tot, -(lam0 + lam_tot)/2, ·)`` = ``(2 lam0 + 2 mu_c, -(lam0 + mu_c/2), ·)``
and momentum theory gives ``lam0 (lam0 + mu_c) = C_T/2``, with the climb
``mu_c`` positive when the rotor climbs, i.e. when the free stream flows *down*
through the disk (:class:`RotorOperatingPoint`). The dissertation prints
``2 lam_m - 2 mu_c``, ``lam_m - mu_c/2`` and ``lam_m (lam_m - mu_c) = C_T/2``: those
three are mutually consistent only with mu_c counted positive in *descent*, yet
its Eq. 2.6 *adds* mu_c^L to the lower rotor's downwash (mu_c positive down through
the disk, a climb) and §2.2.2.3 calls it a climb. We take this as a sign slip in
Eqs. 2.4-2.5 and follow momentum theory and Eq. 2.6: a lower rotor in the upper
rotor's slipstream has a *larger* total flow and a *smaller* induced inflow.
(Either way the magnitudes of Eq. 2.4 are what the code gives for |mu_c|.)

Wake distortion (Eq. 2.29): with ``kr`` != 0 the model takes the tip-path-plane
rates ``beta1s_dot, beta1c_dot`` [rad/s] as inputs, relative to space (flap rate
minus body rate in the rotor frame, ``beta1s_dot = d beta1s/dt - p_r``,
``beta1c_dot = d beta1c/dt - q_r``, :mod:`aircraft.inflow.base`; the aircraft
supplies them so). The forcing ``[V][Lhat]^-1 (0, -K_R beta1s_dot, -K_R beta1c_dot)/Omega``
is then exactly Eq. 2.29's ``[L]^-1 K_R (Delta p/Omega - Delta beta1s*)`` and
``(Delta q/Omega - Delta beta1c*)``; at steady state ``lam1s = Lbar22^-1 dC_L -
K_R beta1s_dot / Omega`` (DC gain ``-K_R/Omega`` per rad/s of rate).

Time: the equations above are in azimuth; :meth:`PittPeters.derivatives` is the
one place they become seconds (``d/dt = Omega d/dpsi``).
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import fsolve

from .base import InflowModel, RotorOperatingPoint, check_rotor_names, rotor_suffix

__all__ = ["PittPeters", "IsolatedRotors", "pitt_peters_matrices", "momentum_inflow",
           "mlbar_from_statespace", "InflowError", "KR_ANALYTICAL"]

M_PITT_PETERS = np.diag([8 / (3 * np.pi), -16 / (45 * np.pi), -16 / (45 * np.pi)])

#: Analytical (potential-flow) wake-distortion parameter K_R of Ref. 82, quoted in
#: §2.2.2.5 (flight-identified UH-60 values are 2.2-3.0; §4.7 identifies 1.44
#: from the free wake). The dissertation's Dynamic Climb model uses "standard
#: analytical values" for it: ``DynamicClimb(kr=KR_ANALYTICAL)``.
KR_ANALYTICAL = 1.5


class InflowError(ValueError):
    """Inputs an inflow model cannot handle (no momentum solution, wrong sizes)."""


def momentum_inflow(ct, mu=0.0, mu_c=0.0, tol=1e-14):
    """Induced inflow lam0 from momentum theory: C_T = 2 lam0 sqrt(mu^2 + (mu_c + lam0)^2).

    Parameters
    ----------
    ct : float
        Thrust coefficient C_T. Must be > 0 in axial flight (``mu = 0``); in
        edgewise flight (``mu > 0``) zero or negative thrust has a solution
        (lam0 of the sign of C_T) and is accepted.
    mu : float
        Advance ratio (in-plane free stream / Omega R, >= 0).
    mu_c : float
        Climb ratio (positive: climb; the flow through the disk is mu_c + lam0).

    Returns
    -------
    float
        lam0 (dimensionless on Omega R, positive down).

    Raises
    ------
    InflowError
        C_T <= 0 in axial flight (no momentum-theory solution: windmill/vortex-ring
        states are outside the model), or no converged solution.
    """
    if not np.isfinite(ct) or not np.isfinite(mu) or not np.isfinite(mu_c):
        raise InflowError(f"momentum theory needs finite inputs, got C_T={ct!r}, mu={mu!r}, mu_c={mu_c!r}")
    if mu < 0:
        raise InflowError(f"advance ratio mu must be >= 0, got {mu!r}")
    if mu == 0.0:
        if not ct > 0:
            raise InflowError(f"momentum theory in axial flight needs a positive thrust coefficient, "
                              f"got C_T = {ct!r} (mu = 0, mu_c = {mu_c!r})")
        # hover/axial climb: closed form of lam0 (lam0 + mu_c) = C_T/2 (Eq. 2.5, climb positive)
        return float(-mu_c / 2 + np.sqrt(mu_c ** 2 / 4 + ct / 2))
    # Newton from the hover value (C_T > 0) or the high-speed limit C_T / (2 V) (C_T <= 0)
    lam = np.sqrt(ct / 2) if ct > 0 else ct / (2 * np.hypot(mu, mu_c))
    for _ in range(200):
        vt = np.sqrt(mu ** 2 + (mu_c + lam) ** 2)
        f = 2 * lam * vt - ct
        df = 2 * vt + 2 * lam * (mu_c + lam) / vt
        step = f / df
        lam -= step
        if abs(step) < tol:
            break
    residual = abs(2 * lam * np.hypot(mu, mu_c + lam) - ct)
    if not (np.isfinite(lam) and np.sign(lam) == np.sign(ct) and residual <= 1e-10 * max(abs(ct), 1e-6)):
        raise InflowError(f"no momentum-theory inflow for C_T = {ct}, mu = {mu}, mu_c = {mu_c}")
    return float(lam)


def pitt_peters_matrices(lam0, mu=0.0, mu_c=0.0):
    """(M, [V][Lhat]^-1) of one rotor at induced inflow lam0 (azimuth time)."""
    lam_tot = mu_c + lam0
    vt = np.sqrt(mu ** 2 + lam_tot ** 2)
    if vt <= 0:
        raise InflowError("zero total flow through the disk: the Pitt-Peters mass flow vanishes")
    v = (mu ** 2 + lam_tot * (lam_tot + lam0)) / vt
    sin_a = lam_tot / vt
    if sin_a <= -1 + 1e-12:
        # axial flow *up* through the disk (windmill brake / vortex ring): Lhat is singular
        raise InflowError(f"flow up through the disk in axial flight (lam_tot = {lam_tot:.4g}): "
                          "outside the Pitt-Peters model")
    x = np.sqrt(max(0.0, 1 - sin_a) / (1 + sin_a))
    lhat = np.array([[0.5, 0.0, 15 * np.pi / 64 * x],
                     [0.0, -4 / (1 + sin_a), 0.0],
                     [15 * np.pi / 64 * x, 0.0, -4 * sin_a / (1 + sin_a)]])
    return M_PITT_PETERS, np.diag([vt, v, v]) @ np.linalg.inv(lhat)


def mlbar_from_statespace(sys, omega):
    """(M, Lbar) in azimuth time from a first-order inflow StateSpace in seconds.

    With x' = A x + B u [1/s]: M = Omega B^-1, Lbar = -B^-1 A (only for models
    whose first inputs are the loads, one per state; flap-rate columns after
    them are ignored).

    Parameters
    ----------
    sys : control.StateSpace
        Inflow model in seconds (e.g. from :meth:`PittPeters.linear`).
    omega : float
        Rotor speed [rad/s].

    Returns
    -------
    M, Lbar : ndarray
        Azimuth-time matrices of ``M lam' + Lbar lam = dC``.
    """
    a = np.asarray(sys.A, float)
    b = np.asarray(sys.B, float)
    if b.shape[1] < b.shape[0]:
        raise InflowError(f"need at least one load input per state to recover M/Lbar, got B {b.shape}")
    b = b[:, :b.shape[0]]
    binv = np.linalg.inv(b)
    return omega * binv, -binv @ a


class PittPeters(InflowModel):
    """Pitt-Peters inflow for independent rotors (nonlinear, Eq. 1.10).

    Parameters
    ----------
    rotor_names : tuple of str
        Rotor names (``("",)`` single rotor, ``("U", "L")`` isolated coaxial rotors).
    kr : float
        Wake-distortion parameter K_R (Eq. 2.29, dimensionless); 0 disables the
        flap-rate inputs.
    rotors : tuple of str, optional
        Alias of ``rotor_names`` (keyword only).

    Examples
    --------
    >>> from aircraft.inflow import PittPeters, RotorOperatingPoint
    >>> sys = PittPeters().linear([0.0061, 0, 0], (RotorOperatingPoint(27.0),))
    >>> sys.input_labels
    ['CT', 'CL', 'CM']
    """

    def __init__(self, rotor_names=("",), kr=0.0, *, rotors=None):
        names = rotor_names if rotors is None else rotors
        if isinstance(names, str):
            names = (names,)
        self.rotors = tuple(names)
        if len(set(self.rotors)) != len(self.rotors) or not self.rotors:
            raise InflowError(f"rotor names must be distinct and non-empty, got {self.rotors}")
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
        if x.shape != (self.n_states,):
            raise InflowError(f"x must have {self.n_states} entries {self.state_names}, got shape {x.shape}")
        if rates is not None and self.kr:
            rates = np.asarray(rates, dtype=float)
            if rates.shape != (2 * len(self.rotors),):
                raise InflowError(f"rates must have {2 * len(self.rotors)} entries {self.rate_names} [rad/s], "
                                  f"got shape {rates.shape}")
        climbs = self._climbs(x, ops)
        out = np.empty_like(x)
        for k, op in enumerate(ops):
            lam = x[3 * k:3 * k + 3]
            # the one place azimuth time becomes seconds: d/dt = Omega d/dpsi
            out[3 * k:3 * k + 3] = op.omega * self._rotor_rhs(k, lam, loads, op, climbs[k], rates)
        return out

    def inflow(self, x, loads, ops):
        """Total inflow: states plus the interference climb on lam0 (Eqs. 2.6, 2.8-2.9).

        ``loads`` is not used (may be None)."""
        x = np.asarray(x, dtype=float).copy()
        if x.shape != (self.n_states,):
            raise InflowError(f"x must have {self.n_states} entries {self.state_names}, got shape {x.shape}")
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
    """Two non-interfering Pitt-Peters rotors ("Isolated Rotor" model, §2.2.2.2).

    Parameters
    ----------
    kr : float
        Wake-distortion parameter K_R (Eq. 2.29).
    rotors : (str, str)
        Names of the upper and the lower rotor (default ``("U", "L")``, the
        :func:`~aircraft.configs.coaxial_compound` names); give the aircraft's
        (:func:`~aircraft.inflow.base.config_rotor_names`) for another naming.
    """

    def __init__(self, kr=0.0, *, rotors=("U", "L")):
        super().__init__(rotors=check_rotor_names(rotors, 2, error=InflowError), kr=kr)
