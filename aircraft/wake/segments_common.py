"""What the CPU and GPU Biot-Savart kernels share: input checks and the numpy reference.

:mod:`aircraft.wake.biot_savart` (CPU kernel, backend choice) and
:mod:`aircraft.wake.gpu` (CUDA kernel) both import from here. The CPU module
loads the GPU one as a backend; the GPU module needs only these helpers, so it
imports nothing back and the two form no import circle.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["segment_velocity_numpy"]

#: 4 pi of the Biot-Savart law [-].
_FOUR_PI = 4.0 * math.pi
#: Added to distances [m] so that a target on a segment end point gives no 0/0.
_TINY = 1e-12


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


def segment_velocity_numpy(targets, seg_a, seg_b, gamma, rc):
    """Plain numpy reference of :func:`segment_velocity` (same inputs, same units).

    Vectorised over the segments, looping over the targets (memory stays O(N));
    used to check the compiled kernel and as the benchmark baseline.

    Parameters
    ----------
    targets : array_like, shape (M, 3)
        Evaluation points [m].
    seg_a, seg_b : array_like, shape (N, 3)
        Segment start and end points [m].
    gamma : array_like, shape (N,) or scalar
        Segment circulation [m^2/s].
    rc : array_like, shape (N,) or scalar
        Vatistas (n = 2) core radius [m].

    Returns
    -------
    ndarray, shape (M, 3)
        Induced velocity [m/s].
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
