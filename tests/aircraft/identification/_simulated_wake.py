"""A stand-in for :func:`aircraft.wake.run_sweeps` shared by the pipeline tests.

It drives a known M/Lbar/tau inflow model (simulated with scipy by
:func:`aircraft.identification.testing.simulate_mltau`, not with flightid's model
code) through a first-order, fully populated control-to-load mixing, with each
sweep spec's own input signals and seeded measurement noise.
"""
from types import SimpleNamespace

import numpy as np
import pandas as pd
import scipy.signal as sig

from aircraft.identification.testing import mixing_matrix, simulate_mltau

CONTROLS = ["theta0", "theta1s", "theta1c"]
LOADS = ["CT", "CL", "CM"]
LAMS = ["lam0", "lam1s", "lam1c"]


def simulated_runs(specs, dt, omega, M, Lbar, tau, *, noise, trim_outputs=None):
    """``run_sweeps``'s output for ``specs`` from the truth ``M, Lbar, tau`` (M per d/dpsi).

    ``noise`` is the measurement noise as a fraction of each signal's RMS (plus a
    floor for the zero-input run); spec k's noise has seed k. ``trim_outputs``
    overrides entries of the trim's (zero) outputs.
    """
    lag = sig.StateSpace(-20.0 * np.eye(3), 20.0 * mixing_matrix(3, 5), np.eye(3), np.zeros((3, 3)))
    out = {}
    for k, spec in enumerate(specs):
        inputs = spec.inputs(dt)
        t = max((tt for tt, _ in inputs.values()), key=len)
        theta = np.zeros((t.size, 3))
        for c, (tc, u) in inputs.items():
            theta[:, CONTROLS.index(c)] = np.interp(t, tc, u, right=0.0)
        _, loads, _ = sig.lsim(lag, theta, t)
        lam = simulate_mltau(M, Lbar, tau, omega, t, loads.T).T
        rng = np.random.default_rng(k)
        noisy = [x + noise * (x.std(axis=0) + 1e-6) * rng.standard_normal(x.shape) for x in (loads, lam)]
        out[spec.name] = pd.DataFrame({"t": t, **dict(zip(CONTROLS, theta.T)), **dict(zip(LOADS, noisy[0].T)),
                                       **dict(zip(LAMS, noisy[1].T))})
    out["trim"] = SimpleNamespace(converged=True, residual=0.0, controls=dict.fromkeys(CONTROLS, 0.0),
                                  outputs={**dict.fromkeys(LOADS + LAMS, 0.0), **(trim_outputs or {})})
    return out
