"""The former (pure numpy) pieces of the wake march, kept as its reference.

:class:`aircraft.wake.wake.FreeVortexWake` marches with compiled and vectorised
helpers (:mod:`aircraft.wake.kinematics`, the chained Biot-Savart kernel, cached
segment maps). A wake made by ``FreeVortexWake._reference_march(...)``
(``_compiled = False``) runs these functions instead,
unchanged from the march before that rewrite: the benchmark
(``benchmarks/wake.py``) times both, and the tests hold the two to the same
numbers (``tests/aircraft/wake/test_wake_compiled.py``).
"""
from __future__ import annotations

import numpy as np

__all__ = ["near_wake_points_reference", "attached_segments_reference"]

__all__: list[str] = []


def near_wake_points_reference(wake, ir, psi, beta):
    """Rigid near-wake trailer points of rotor ``ir`` (loop over the ages).

    Parameters
    ----------
    wake : FreeVortexWake
        The wake (rotors, settings, free stream, inflow ``_lam0``).
    ir : int
        Rotor index.
    psi : float
        Azimuth of the first blade [rad].
    beta : ndarray, shape (Nb,)
        Blade flap angles [rad].

    Returns
    -------
    ndarray, shape (Nb, Ne + 1, n_near + 1, 3)
        Trailer points [m], age 0 first.
    """
    rot = wake.rotors[ir]
    s = wake.settings
    ages = np.arange(wake.n_near + 1) * s.azimuth_step
    pts = np.empty((rot.nb, rot.r_edge.size, ages.size, 3))
    # the near wake drifts with the free stream and half the rotor's mean
    # induced velocity (the tip vortex's initial descent is about that)
    drift = wake.v_inf - np.array([0.0, 0.0, 0.5 * wake._lam0[ir] * wake.omega * rot.R])
    contraction = wake._near_wake_contraction(ir, ages)
    for m, age in enumerate(ages):
        p = wake._blade_points(rot, wake._psi_blades(rot, psi) - age, beta, rot.r_edge)
        p[..., :2] = rot.hub[:2] + contraction[m] * (p[..., :2] - rot.hub[:2])
        pts[:, :, m, :] = p + drift * age / wake.omega
    return pts


def attached_segments_reference(wake):
    """Bound and near-wake segments of all blades with the map to panel circulation.

    Parameters
    ----------
    wake : FreeVortexWake
        The wake at its current step.

    Returns
    -------
    a, b : ndarray, shape (S, 3)
        Segment start and end points [m].
    rc : ndarray, shape (S,)
        Core radii [m].
    gmap : ndarray, shape (S, P)
        Segment strength = gmap @ gamma [-], gamma [m^2/s] stacked over rotors,
        blades, panels (P = sum Nb Ne).
    """
    s = wake.settings
    A, B, RC, rows, cols, vals = [], [], [], [], [], []
    seg = 0
    p0 = 0
    ne = s.n_elements
    for ir, rot in enumerate(wake.rotors):
        nw = wake._near_wake_points(ir, wake.psi, wake.beta[ir])
        rc = s.near_wake_core * rot.chord
        for b in range(rot.nb):
            pb = p0 + b * ne
            # bound vortex, root to tip, strength d * gamma_j
            A.append(nw[b, :-1, 0, :])
            B.append(nw[b, 1:, 0, :])
            for j in range(ne):
                rows.append(seg + j); cols.append(pb + j); vals.append(rot.d)
            seg += ne
            # trailer at edge j, younger -> older, strength d (gamma_{j-1} - gamma_j)
            for j in range(ne + 1):
                A.append(nw[b, j, :-1, :])
                B.append(nw[b, j, 1:, :])
                for m in range(wake.n_near):
                    if j - 1 >= 0:
                        rows.append(seg + m); cols.append(pb + j - 1); vals.append(rot.d)
                    if j < ne:
                        rows.append(seg + m); cols.append(pb + j); vals.append(-rot.d)
                seg += wake.n_near
            RC.append(np.full(ne + (ne + 1) * wake.n_near, rc))
        p0 += rot.nb * ne
    gmap = np.zeros((seg, p0))
    np.add.at(gmap, (np.array(rows), np.array(cols)), np.array(vals, dtype=float))
    return np.concatenate(A), np.concatenate(B), np.concatenate(RC), gmap
