"""Biot-Savart velocity of straight vortex segments with a Vatistas (n = 2) core.

The kernel is the hot spot of the free-vortex wake: every time step evaluates the
velocity that every vortex segment induces at every Lagrangian marker.  It is
written array-in / array-out (``targets (M, 3)``, segment end points ``(N, 3)``,
circulation and core radius ``(N,)`` -> velocities ``(M, 3)``) so that a GPU
implementation (CuPy, numba.cuda) can replace it behind the same signature.

Segment formula
---------------
For a segment from A to B with circulation Gamma (vector along B - A) and a target P,
``r1 = P - A``, ``r2 = P - B``, ``r0 = B - A``::

    v = Gamma / (4 pi) * (r1 x r2) * r0 . (r1/|r1| - r2/|r2|)
        / sqrt(|r1 x r2|^4 + (r_c |r0|)^4)

which is the singular Biot-Savart law multiplied by the Vatistas n = 2
desingularisation factor ``h^2 / sqrt(r_c^4 + h^4)`` (h: distance from the segment
line, ``|r1 x r2| = h |r0|``).  Far from the core it tends to the potential result,
on the axis it is zero.

Viscous core growth (Squire / Bhagwat-Leishman)::

    r_c(zeta) = sqrt(r_c0^2 + 4 alpha delta nu zeta / Omega),  alpha = 1.25643
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

__all__ = ["segment_velocity", "segment_velocity_numpy", "segment_influence",
           "core_radius", "VATISTAS_ALPHA"]

#: Lamb-Oseen constant alpha in the core-growth law [-].
VATISTAS_ALPHA = 1.25643
_FOUR_PI = 4.0 * math.pi
_TINY = 1e-12


@njit(parallel=True, fastmath=True, cache=True)
def _segment_velocity_soa(px, py, pz, ax, ay, az, bx, by, bz, r0x, r0y, r0z, g4, rcl2,
                          one, tiny):
    # Structure-of-arrays inputs: the inner loop reads contiguous 1-D arrays only,
    # which lets LLVM vectorise it (AVX) -- about 2x over (N, 3) rows in double,
    # 9x in single precision. The target-independent parts (r0 = B - A,
    # Gamma / 4 pi, (rc |r0|)^4) are precomputed once per call. ``one`` and
    # ``tiny`` carry the working dtype so float32 inputs stay float32.
    m = px.shape[0]
    n = ax.shape[0]
    out = np.empty((m, 3), dtype=px.dtype)
    for i in prange(m):
        xi = px[i]
        yi = py[i]
        zi = pz[i]
        ux = 0.0 * one
        uy = 0.0 * one
        uz = 0.0 * one
        for j in range(n):
            r1x = xi - ax[j]
            r1y = yi - ay[j]
            r1z = zi - az[j]
            r2x = xi - bx[j]
            r2y = yi - by[j]
            r2z = zi - bz[j]
            cx = r1y * r2z - r1z * r2y
            cy = r1z * r2x - r1x * r2z
            cz = r1x * r2y - r1y * r2x
            c2 = cx * cx + cy * cy + cz * cz
            i1 = one / (math.sqrt(r1x * r1x + r1y * r1y + r1z * r1z) + tiny)
            i2 = one / (math.sqrt(r2x * r2x + r2y * r2y + r2z * r2z) + tiny)
            dot = (r0x[j] * (r1x * i1 - r2x * i2) + r0y[j] * (r1y * i1 - r2y * i2)
                   + r0z[j] * (r1z * i1 - r2z * i2))
            f = g4[j] * dot / (math.sqrt(c2 * c2 + rcl2[j]) + tiny)
            ux += f * cx
            uy += f * cy
            uz += f * cz
        out[i, 0] = ux
        out[i, 1] = uy
        out[i, 2] = uz
    return out


@njit(parallel=True, fastmath=True, cache=True)
def _segment_influence_numba(targets, seg_a, seg_b, rc):
    m = targets.shape[0]
    n = seg_a.shape[0]
    out = np.zeros((m, n, 3))
    for i in prange(m):
        for j in range(n):
            r1x = targets[i, 0] - seg_a[j, 0]
            r1y = targets[i, 1] - seg_a[j, 1]
            r1z = targets[i, 2] - seg_a[j, 2]
            r2x = targets[i, 0] - seg_b[j, 0]
            r2y = targets[i, 1] - seg_b[j, 1]
            r2z = targets[i, 2] - seg_b[j, 2]
            cx = r1y * r2z - r1z * r2y
            cy = r1z * r2x - r1x * r2z
            cz = r1x * r2y - r1y * r2x
            c2 = cx * cx + cy * cy + cz * cz
            r0x = seg_b[j, 0] - seg_a[j, 0]
            r0y = seg_b[j, 1] - seg_a[j, 1]
            r0z = seg_b[j, 2] - seg_a[j, 2]
            l2 = r0x * r0x + r0y * r0y + r0z * r0z
            n1 = math.sqrt(r1x * r1x + r1y * r1y + r1z * r1z) + _TINY
            n2 = math.sqrt(r2x * r2x + r2y * r2y + r2z * r2z) + _TINY
            dot = (r0x * (r1x / n1 - r2x / n2) + r0y * (r1y / n1 - r2y / n2)
                   + r0z * (r1z / n1 - r2z / n2))
            rcl = rc[j] * rc[j] * l2
            f = dot / (_FOUR_PI * (math.sqrt(c2 * c2 + rcl * rcl) + _TINY))
            out[i, j, 0] = f * cx
            out[i, j, 1] = f * cy
            out[i, j, 2] = f * cz
    return out


def _check(targets, seg_a, seg_b, gamma, rc):
    targets = np.ascontiguousarray(targets, dtype=np.float64)
    seg_a = np.ascontiguousarray(seg_a, dtype=np.float64)
    seg_b = np.ascontiguousarray(seg_b, dtype=np.float64)
    if targets.ndim != 2 or targets.shape[1] != 3:
        raise ValueError(f"targets must have shape (M, 3), got {targets.shape}")
    if seg_a.shape != seg_b.shape or seg_a.ndim != 2 or seg_a.shape[1] != 3:
        raise ValueError(f"segment end points must both have shape (N, 3), got "
                         f"{seg_a.shape} and {seg_b.shape}")
    n = seg_a.shape[0]
    rc = np.ascontiguousarray(np.broadcast_to(np.asarray(rc, dtype=np.float64), (n,)))
    if gamma is not None:
        gamma = np.ascontiguousarray(np.broadcast_to(np.asarray(gamma, dtype=np.float64), (n,)))
    if np.any(rc < 0):
        raise ValueError("core radii must be >= 0 [m]")
    return targets, seg_a, seg_b, gamma, rc


_PRECISIONS = {"double": np.float64, "single": np.float32}


def segment_velocity(targets, seg_a, seg_b, gamma, rc, precision="double"):
    """Velocity induced at ``targets`` by straight vortex segments (compiled kernel).

    Parameters
    ----------
    targets : array_like, shape (M, 3)
        Evaluation points [m].
    seg_a, seg_b : array_like, shape (N, 3)
        Segment start and end points [m]; the circulation vector points from A to B.
    gamma : array_like, shape (N,) or scalar
        Segment circulation [m^2/s].
    rc : array_like, shape (N,) or scalar
        Vatistas (n = 2) core radius [m].
    precision : {"double", "single"}
        Arithmetic of the pair loop. ``"single"`` is about 4x faster on AVX
        CPUs; its relative error is ~1e-6 (float32 round-off of coordinates of
        tens of metres against cores of centimetres), far below the wake
        model's discretisation error. Inputs and result stay float64.

    Returns
    -------
    ndarray, shape (M, 3)
        Induced velocity [m/s].
    """
    if precision not in _PRECISIONS:
        raise ValueError(f"precision must be 'double' or 'single', got {precision!r}")
    targets, seg_a, seg_b, gamma, rc = _check(targets, seg_a, seg_b, gamma, rc)
    if seg_a.shape[0] == 0 or targets.shape[0] == 0:
        return np.zeros((targets.shape[0], 3))
    dtype = _PRECISIONS[precision]
    r0 = seg_b - seg_a
    rcl = rc * rc * np.einsum("ij,ij->i", r0, r0)

    def col(x):
        return np.ascontiguousarray(x, dtype=dtype)

    out = _segment_velocity_soa(col(targets[:, 0]), col(targets[:, 1]), col(targets[:, 2]),
                                col(seg_a[:, 0]), col(seg_a[:, 1]), col(seg_a[:, 2]),
                                col(seg_b[:, 0]), col(seg_b[:, 1]), col(seg_b[:, 2]),
                                col(r0[:, 0]), col(r0[:, 1]), col(r0[:, 2]),
                                col(gamma / _FOUR_PI), col(rcl * rcl), dtype(1.0), dtype(_TINY))
    return out.astype(np.float64, copy=False)


def segment_influence(targets, seg_a, seg_b, rc):
    """Velocity per unit circulation, shape (M, N, 3) [1/m] (compiled kernel).

    Used for the small bound/near-wake circulation system of the blades.
    """
    targets, seg_a, seg_b, _, rc = _check(targets, seg_a, seg_b, None, rc)
    return _segment_influence_numba(targets, seg_a, seg_b, rc)


def segment_velocity_numpy(targets, seg_a, seg_b, gamma, rc):
    """Plain numpy reference of :func:`segment_velocity` (same inputs, same units).

    Vectorised over the segments, looping over the targets (memory stays O(N));
    used to check the compiled kernel and as the benchmark baseline.
    """
    targets, seg_a, seg_b, gamma, rc = _check(targets, seg_a, seg_b, gamma, rc)
    out = np.zeros((targets.shape[0], 3))
    r0 = seg_b - seg_a
    l2 = np.einsum("ij,ij->i", r0, r0)
    rcl = rc ** 2 * l2
    for i, p in enumerate(targets):
        r1 = p - seg_a
        r2 = p - seg_b
        c = np.cross(r1, r2)
        c2 = np.einsum("ij,ij->i", c, c)
        n1 = np.sqrt(np.einsum("ij,ij->i", r1, r1))[:, None] + _TINY
        n2 = np.sqrt(np.einsum("ij,ij->i", r2, r2))[:, None] + _TINY
        dot = np.einsum("ij,ij->i", r0, r1 / n1 - r2 / n2)
        f = gamma * dot / (_FOUR_PI * (np.sqrt(c2 ** 2 + rcl ** 2) + _TINY))
        out[i] = f @ c
    return out


def core_radius(age, omega, rc0, delta, nu=1.5e-5):
    """Vortex core radius after viscous growth [m].

    Parameters
    ----------
    age : array_like
        Wake age zeta [rad].
    omega : float
        Rotor speed [rad/s] (converts age to time).
    rc0 : float
        Initial core radius [m].
    delta : float
        Turbulent (eddy) viscosity coefficient [-] (Squire's delta).
    nu : float
        Kinematic viscosity [m^2/s].
    """
    age = np.asarray(age, dtype=float)
    return np.sqrt(rc0 ** 2 + 4.0 * VATISTAS_ALPHA * delta * nu * np.maximum(age, 0.0) / omega)
