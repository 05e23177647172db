"""Synthetic-truth experiments for the identification, generated WITHOUT flightid's model code.

The truth ``M/Lbar/tau`` model (azimuth time, row-wise delays of Eq. 2.16) is
simulated with :func:`scipy.signal.lsim`: for each state i the full system is
driven by the inputs delayed by row i of tau (delays applied by interpolating the
input history at t - tau), and only component i is kept. Used by tests and
benchmarks as an independent check of :mod:`flightid` and of the structures.
"""
from __future__ import annotations

import numpy as np
import scipy.signal as sig

from flightid.sweeps import frequency_sweep

__all__ = ["simulate_mltau", "mixing_matrix", "coaxial_sweep_set", "SWASHPLATE_CONTROLS",
           "printed_6state_structure", "printed_6state_values", "COAXIAL_6STATE_TRUTH"]

#: The six coaxial swashplate controls, in load order.
SWASHPLATE_CONTROLS = ["theta0_U", "theta1s_U", "theta1c_U", "theta0_L", "theta1s_L", "theta1c_L"]

#: A coaxial 6-state truth in the parameter names of
#: :class:`aircraft.identification.structures.Coaxial6State` (masses ``m``, inverse
#: static gains ``l`` in the rotor's non-dimensional units, delays ``t`` in seconds):
#: values of the size the wake identifies, with both cross-rotor blocks non-zero so that
#: every parameter shapes the response.
COAXIAL_6STATE_TRUTH = {
    "m11": 0.85, "m14": -0.4, "m41": 0.6, "m44": 1.05, "m22": -0.25, "m25": -0.07, "m52": -0.33,
    "m55": -0.27, "l11": 0.44, "l14": -0.18, "l41": -0.73, "l44": 0.67, "l22": -0.045, "l25": 0.011,
    "l52": -0.036, "l55": -0.061, "t11": 0.03, "t14": 0.10, "t41": 0.02, "t44": 0.026, "t22": 0.023,
    "t25": 0.13, "t52": 0.08, "t55": 0.01}


def simulate_mltau(M, Lbar, tau, omega, t, u):
    """Time response of ``M lam' + Lbar lam = u(t - tau)`` (d/dpsi, psi = omega t).

    Parameters
    ----------
    M, Lbar, tau : (n, n) array_like
        Apparent mass and Lbar (azimuth time, dimensionless) and delays [s].
    omega : float
        Rotor speed [rad/s].
    t : (n_t,) array_like
        Uniform time [s].
    u : (n, n_t) array_like
        Inputs (loads).

    Returns
    -------
    ndarray (n, n_t)
        lambda(t), starting from rest.
    """
    M = np.asarray(M, float)
    Lbar = np.asarray(Lbar, float)
    tau = np.asarray(tau, float)
    n = M.shape[0]
    a = -omega * np.linalg.solve(M, Lbar)
    b = omega * np.linalg.inv(M)
    system = sig.StateSpace(a, b, np.eye(n), np.zeros((n, n)))
    out = np.zeros((n, np.size(t)))
    for i in range(n):
        delayed = np.array([np.interp(t - tau[i, j], t, u[j], left=0.0) for j in range(n)])
        _, y, _ = sig.lsim(system, delayed.T, t)
        y = np.atleast_2d(y.T) if n > 1 else y[None, :]
        out[i] = y[i]
    return out


def mixing_matrix(n, seed):
    """A well-conditioned, fully populated 'swashplate -> loads' mixing matrix (seeded).

    Parameters
    ----------
    n : int
        Size (square ``n`` x ``n``).
    seed : int
        Seed of :func:`numpy.random.default_rng`.

    Returns
    -------
    ndarray, shape (n, n)
        Identity plus seeded uniform entries in [-0.4, 0.4].
    """
    rng = np.random.default_rng(seed)
    return np.eye(n) + 0.4 * rng.uniform(-1, 1, size=(n, n))


def coaxial_sweep_set(model, *, seed=0, dt=0.01, duration=100.0, noise=0.02, w_min=0.4, w_max=40.0):
    """Six one-at-a-time control sweeps through correlated mixing and a loads lag.

    Loads = first-order lag (actuator-like, 0.05 s) of ``K_mix @ theta``, so every
    control excites all loads: the lambda/C responses cannot be measured directly
    and need the joint input-output method.

    Parameters
    ----------
    model : object with ``M``, ``Lbar``, ``tau``, ``omega`` (azimuth-time M)
    seed : int
    dt, duration : float
        Sample time and record length [s].
    noise : float
        Measurement noise as a fraction of each signal's RMS.
    w_min, w_max : float
        Sweep band [rad/s].

    Returns
    -------
    list of dict
        ``t``, ``theta`` (control swept), ``control`` (index), ``loads`` (6, n),
        ``lam`` (6, n) with noise, and the clean ``loads_clean``, ``lam_clean``.
    """
    k_mix = mixing_matrix(6, seed)
    lag = sig.StateSpace(-20.0 * np.eye(6), 20.0 * k_mix, np.eye(6), np.zeros((6, 6)))
    rng = np.random.default_rng(seed + 1)
    runs = []
    for j in range(6):
        t, s = frequency_sweep(w_min, w_max, duration, dt, amplitude=1e-3, seed=seed + j)
        theta = np.zeros((6, t.size))
        theta[j] = s
        _, loads, _ = sig.lsim(lag, theta.T, t)
        loads = loads.T
        lam = simulate_mltau(model.M, model.Lbar, model.tau, model.omega, t, loads)
        lam_n = lam + noise * rng.standard_normal(lam.shape) * lam.std(axis=1, keepdims=True)
        loads_n = loads + noise * rng.standard_normal(loads.shape) * loads.std(axis=1, keepdims=True)
        runs.append({"t": t, "theta": s, "control": j, "loads": loads_n, "lam": lam_n,
                     "loads_clean": loads, "lam_clean": lam})
    return runs


def printed_6state_structure(initial, omega):
    """The §5.3 structure in the printed (common) frame, for truths simulated from Eq. 5.3 as
    printed (:class:`aircraft.identification.Coaxial6State` with ``frame="printed"``).

    Parameters
    ----------
    initial : dict
        Initial values of the 24 parameters (name -> value).
    omega : float
        Rotor speed [rad/s].

    Returns
    -------
    flightid.MLTauStructure
    """
    from .structures.hover import Coaxial6State
    return Coaxial6State("printed").build(initial, omega)


def printed_6state_values(model):
    """A printed 6-state model's values on the 24 parameters of §5.3 (printed frame).

    Parameters
    ----------
    model : object
        Printed 6-state M-L-tau model (``M``, ``Lbar``, ``tau`` matrices, ``frame``).

    Returns
    -------
    dict
        Parameter name -> value.
    """
    from .structures.hover import Coaxial6State
    return Coaxial6State("printed").published_values(model)
