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

Reproducibility
---------------
All kernels are compiled without ``fastmath`` and contain no parallel
reduction: ``prange`` runs over blocks of targets and each target's sum over the
segments is the sequential sum written in the source (SIMD lanes hold different
targets). LLVM may therefore neither reorder the sum nor fuse multiply-adds, and
a kernel result is bit-identical for the same inputs whatever the number of
threads, and on any IEEE-754 CPU with the same numba/LLVM (AVX2 and AVX-512
alike). The chained variants (the default: tip vortices, far wake and
near-wake trailers are chains whose segment j starts exactly where segment j - 1
ends) keep 1 / |P - A_j| from the previous pair instead of recomputing the same
operations on the same numbers, so they equal the plain loops bit for bit
(``chained=False``, kept for the reference march and tested against it). The former ``fastmath`` loop vectorised each sum across the segments, so
its rounding depended on the vector width of the machine.

A whole wake run is bit-identical on one machine (tested in
``tests/aircraft/wake/test_reproducible.py``). Across machines the numpy/BLAS/libm parts of the
march (trigonometry, small dense solves) may round differently in the last bit;
the test there perturbs the inputs at that level and holds the marched loads and
inflow to the stated cross-machine tolerance :data:`CROSS_MACHINE_RTOL`.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from .segments_common import _FOUR_PI, _TINY, _check, segment_velocity_numpy

__all__ = ["kernel_backend", "set_kernel_backend", "KERNEL_ENV", "segment_velocity", "segment_velocity_numpy", "segment_influence",
           "core_radius", "VATISTAS_ALPHA", "CROSS_MACHINE_RTOL"]

#: Lamb-Oseen constant alpha in the core-growth law [-].
VATISTAS_ALPHA = 1.25643
#: Stated cross-machine tolerance of wake results [-]: relative agreement of
#: revolution-averaged loads and inflow (C_T, lambda_0) of the same run on two
#: machines. Round-off-level differences (1e-16..1e-13, what another libm or BLAS
#: gives) stay at that level through the march until a discrete event flips; after
#: it the instantaneous outputs differ by the wake's own blade-passage
#: unsteadiness (a few %) and revolution averages by ~0.1 %. 1.5 % is 3x the
#: per-revolution scatter of a trimmed hover wake (0.5 % rms). Identified model
#: parameters inherit this through the fit at about their Cramer-Rao bounds.
CROSS_MACHINE_RTOL = 0.015


#: Targets per vector block of the pair loop (see "Reproducibility" above).
_LANES = 16


@njit(parallel=True, fastmath=False, cache=True)
def _segment_velocity_soa(px, py, pz, ax, ay, az, bx, by, bz, r0x, r0y, r0z, g4, rcl2,
                          one, tiny):
    # Structure-of-arrays inputs; the target-independent parts (r0 = B - A,
    # Gamma / 4 pi, (rc |r0|)^4) are precomputed once per call. ``one`` and
    # ``tiny`` carry the working dtype so float32 inputs stay float32.
    #
    # Vectorised over a block of _LANES targets, not over the segments: each
    # target's sum over j stays the sequential sum of the source, so LLVM may use
    # SIMD lanes without reassociating anything (fastmath off). The result is
    # then fixed by IEEE-754 arithmetic alone -- independent of the thread count,
    # the chunking of prange and the CPU's vector width -- and is as fast in
    # single precision as the former fastmath segment-vectorised loop.
    m = px.shape[0]            # a multiple of _LANES (the caller pads)
    n = ax.shape[0]
    out = np.empty((m, 3), dtype=px.dtype)
    for ib in prange(m // _LANES):
        i0 = ib * _LANES
        qx = px[i0:i0 + _LANES].copy()
        qy = py[i0:i0 + _LANES].copy()
        qz = pz[i0:i0 + _LANES].copy()
        ux = np.zeros(_LANES, dtype=px.dtype)
        uy = np.zeros(_LANES, dtype=px.dtype)
        uz = np.zeros(_LANES, dtype=px.dtype)
        for j in range(n):
            axj = ax[j]
            ayj = ay[j]
            azj = az[j]
            bxj = bx[j]
            byj = by[j]
            bzj = bz[j]
            r0xj = r0x[j]
            r0yj = r0y[j]
            r0zj = r0z[j]
            gj = g4[j]
            rlj = rcl2[j]
            for k in range(_LANES):
                r1x = qx[k] - axj
                r1y = qy[k] - ayj
                r1z = qz[k] - azj
                r2x = qx[k] - bxj
                r2y = qy[k] - byj
                r2z = qz[k] - bzj
                cx = r1y * r2z - r1z * r2y
                cy = r1z * r2x - r1x * r2z
                cz = r1x * r2y - r1y * r2x
                c2 = cx * cx + cy * cy + cz * cz
                i1 = one / (math.sqrt(r1x * r1x + r1y * r1y + r1z * r1z) + tiny)
                i2 = one / (math.sqrt(r2x * r2x + r2y * r2y + r2z * r2z) + tiny)
                dot = (r0xj * (r1x * i1 - r2x * i2) + r0yj * (r1y * i1 - r2y * i2)
                       + r0zj * (r1z * i1 - r2z * i2))
                f = gj * dot / (math.sqrt(c2 * c2 + rlj) + tiny)
                ux[k] += f * cx
                uy[k] += f * cy
                uz[k] += f * cz
        for k in range(_LANES):
            out[i0 + k, 0] = ux[k]
            out[i0 + k, 1] = uy[k]
            out[i0 + k, 2] = uz[k]
    return out


@njit(parallel=True, fastmath=False, cache=True)
def _segment_velocity_chain(px, py, pz, ax, ay, az, bx, by, bz, r0x, r0y, r0z, g4, rcl2,
                            linked, one, tiny):
    # The pair loop of _segment_velocity_soa with one saving: most segments are
    # links of a chain (tip vortex, far wake, near-wake trailers), whose start A_j
    # is, bit for bit, the previous segment's end B_{j-1} (``linked[j]``). Then
    # 1 / |P - A_j| is the previous pair's 1 / |P - B_{j-1}|: the same operations
    # on the same numbers, so it is kept from that pair instead of recomputed. One
    # square root and one division of three per pair go; every sum, and so the
    # result, is bit-identical to _segment_velocity_soa.
    m = px.shape[0]            # a multiple of _LANES (the caller pads)
    n = ax.shape[0]
    out = np.empty((m, 3), dtype=px.dtype)
    for ib in prange(m // _LANES):
        i0 = ib * _LANES
        # one block for the lane state (targets, sums, 1 / |P - B| of the previous
        # segment): rows of one array at constant offsets, which LLVM can tell
        # apart, so both branches below vectorise without run-time alias checks
        st = np.zeros((7, _LANES), dtype=px.dtype)
        for k in range(_LANES):
            st[0, k] = px[i0 + k]
            st[1, k] = py[i0 + k]
            st[2, k] = pz[i0 + k]
        for j in range(n):
            axj = ax[j]
            ayj = ay[j]
            azj = az[j]
            bxj = bx[j]
            byj = by[j]
            bzj = bz[j]
            r0xj = r0x[j]
            r0yj = r0y[j]
            r0zj = r0z[j]
            gj = g4[j]
            rlj = rcl2[j]
            if linked[j]:
                for k in range(_LANES):
                    r1x = st[0, k] - axj
                    r1y = st[1, k] - ayj
                    r1z = st[2, k] - azj
                    r2x = st[0, k] - bxj
                    r2y = st[1, k] - byj
                    r2z = st[2, k] - bzj
                    cx = r1y * r2z - r1z * r2y
                    cy = r1z * r2x - r1x * r2z
                    cz = r1x * r2y - r1y * r2x
                    c2 = cx * cx + cy * cy + cz * cz
                    i1 = st[6, k]
                    i2 = one / (math.sqrt(r2x * r2x + r2y * r2y + r2z * r2z) + tiny)
                    st[6, k] = i2
                    dot = (r0xj * (r1x * i1 - r2x * i2) + r0yj * (r1y * i1 - r2y * i2)
                           + r0zj * (r1z * i1 - r2z * i2))
                    f = gj * dot / (math.sqrt(c2 * c2 + rlj) + tiny)
                    st[3, k] += f * cx
                    st[4, k] += f * cy
                    st[5, k] += f * cz
            else:
                for k in range(_LANES):
                    r1x = st[0, k] - axj
                    r1y = st[1, k] - ayj
                    r1z = st[2, k] - azj
                    r2x = st[0, k] - bxj
                    r2y = st[1, k] - byj
                    r2z = st[2, k] - bzj
                    cx = r1y * r2z - r1z * r2y
                    cy = r1z * r2x - r1x * r2z
                    cz = r1x * r2y - r1y * r2x
                    c2 = cx * cx + cy * cy + cz * cz
                    i1 = one / (math.sqrt(r1x * r1x + r1y * r1y + r1z * r1z) + tiny)
                    i2 = one / (math.sqrt(r2x * r2x + r2y * r2y + r2z * r2z) + tiny)
                    st[6, k] = i2
                    dot = (r0xj * (r1x * i1 - r2x * i2) + r0yj * (r1y * i1 - r2y * i2)
                           + r0zj * (r1z * i1 - r2z * i2))
                    f = gj * dot / (math.sqrt(c2 * c2 + rlj) + tiny)
                    st[3, k] += f * cx
                    st[4, k] += f * cy
                    st[5, k] += f * cz
        for k in range(_LANES):
            out[i0 + k, 0] = st[3, k]
            out[i0 + k, 1] = st[4, k]
            out[i0 + k, 2] = st[5, k]
    return out


# fastmath off: no FMA contraction or approximate division, so the influence
# matrix is the same on every IEEE-754 machine (no reduction here to reorder)
@njit(parallel=True, fastmath=False, cache=True)
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


@njit(parallel=True, fastmath=False, cache=True)
def _segment_influence_lanes(px, py, pz, ax, ay, az, bx, by, bz, rc, linked):
    # _segment_influence_numba's arithmetic, element for element, arranged like
    # the velocity kernel: a block of _LANES targets in SIMD lanes, the segments
    # in sequence, the result (3, N, M) with the targets contiguous (the caller
    # transposes). Where A_j is bit for bit B_{j-1} (``linked[j]``), r1 / |r1| of
    # this pair is r2 / |r2| of the previous one -- the same operations on the
    # same numbers -- and is kept instead of recomputed. Same result, bit for bit.
    m = px.shape[0]            # a multiple of _LANES (the caller pads)
    n = ax.shape[0]
    out = np.empty((3, n, m))
    for ib in prange(m // _LANES):
        i0 = ib * _LANES
        # lane state in one array (targets, previous r2 / |r2|): see the chain kernel
        st = np.zeros((6, _LANES))
        # this block's results: indices from range() only, so no wrap-around
        # checks in the pair loop and it vectorises
        blk = np.empty((3, n, _LANES))
        for k in range(_LANES):
            st[0, k] = px[i0 + k]
            st[1, k] = py[i0 + k]
            st[2, k] = pz[i0 + k]
        for j in range(n):
            axj = ax[j]
            ayj = ay[j]
            azj = az[j]
            bxj = bx[j]
            byj = by[j]
            bzj = bz[j]
            r0x = bxj - axj
            r0y = byj - ayj
            r0z = bzj - azj
            l2 = r0x * r0x + r0y * r0y + r0z * r0z
            rcl = rc[j] * rc[j] * l2
            rcl2 = rcl * rcl
            if linked[j]:
                for k in range(_LANES):
                    r1x = st[0, k] - axj
                    r1y = st[1, k] - ayj
                    r1z = st[2, k] - azj
                    r2x = st[0, k] - bxj
                    r2y = st[1, k] - byj
                    r2z = st[2, k] - bzj
                    cx = r1y * r2z - r1z * r2y
                    cy = r1z * r2x - r1x * r2z
                    cz = r1x * r2y - r1y * r2x
                    c2 = cx * cx + cy * cy + cz * cz
                    n2 = math.sqrt(r2x * r2x + r2y * r2y + r2z * r2z) + _TINY
                    q2x = r2x / n2
                    q2y = r2y / n2
                    q2z = r2z / n2
                    dot = (r0x * (st[3, k] - q2x) + r0y * (st[4, k] - q2y)
                           + r0z * (st[5, k] - q2z))
                    st[3, k] = q2x
                    st[4, k] = q2y
                    st[5, k] = q2z
                    f = dot / (_FOUR_PI * (math.sqrt(c2 * c2 + rcl2) + _TINY))
                    blk[0, j, k] = f * cx
                    blk[1, j, k] = f * cy
                    blk[2, j, k] = f * cz
            else:
                for k in range(_LANES):
                    r1x = st[0, k] - axj
                    r1y = st[1, k] - ayj
                    r1z = st[2, k] - azj
                    r2x = st[0, k] - bxj
                    r2y = st[1, k] - byj
                    r2z = st[2, k] - bzj
                    cx = r1y * r2z - r1z * r2y
                    cy = r1z * r2x - r1x * r2z
                    cz = r1x * r2y - r1y * r2x
                    c2 = cx * cx + cy * cy + cz * cz
                    n1 = math.sqrt(r1x * r1x + r1y * r1y + r1z * r1z) + _TINY
                    n2 = math.sqrt(r2x * r2x + r2y * r2y + r2z * r2z) + _TINY
                    q2x = r2x / n2
                    q2y = r2y / n2
                    q2z = r2z / n2
                    dot = (r0x * (r1x / n1 - q2x) + r0y * (r1y / n1 - q2y)
                           + r0z * (r1z / n1 - q2z))
                    st[3, k] = q2x
                    st[4, k] = q2y
                    st[5, k] = q2z
                    f = dot / (_FOUR_PI * (math.sqrt(c2 * c2 + rcl2) + _TINY))
                    blk[0, j, k] = f * cx
                    blk[1, j, k] = f * cy
                    blk[2, j, k] = f * cz
        for c in range(3):
            for j in range(n):
                for k in range(_LANES):
                    out[c, j, i0 + k] = blk[c, j, k]
    return out


_PRECISIONS = {"double": np.float64, "single": np.float32}

#: Environment variable choosing the Biot-Savart backend: ``auto`` (default: the
#: GPU kernel of :mod:`aircraft.wake.gpu` when a CUDA device is present, else the
#: CPU kernel), ``cpu`` or ``gpu``.
KERNEL_ENV = "ROTORWAKE_KERNEL"
_BACKENDS = ("auto", "cpu", "gpu")
_backend = None        # resolved once: reading the environment per call would cost


def _gpu_module():
    try:
        from . import gpu
    except ImportError:   # no GPU kernel in this installation
        return None
    return gpu


def set_kernel_backend(name="auto"):
    """Choose the Biot-Savart backend for this process.

    Parameters
    ----------
    name : {"auto", "cpu", "gpu"}
        ``"auto"``: the GPU kernel when a CUDA device is usable, else the CPU
        kernel; ``"gpu"`` raises if no device is usable.

    Returns
    -------
    str
        The backend now in use, ``"cpu"`` or ``"gpu"``.

    Raises
    ------
    ValueError
        For an unknown name, or ``"gpu"`` without a usable device.
    """
    global _backend
    if name not in _BACKENDS:
        raise ValueError(f"kernel backend must be one of {_BACKENDS}, got {name!r}")
    gpu = _gpu_module()
    usable = gpu is not None and gpu.available()
    if name == "gpu" and not usable:
        raise ValueError("kernel backend 'gpu' requested but no CUDA device is usable "
                         "(aircraft.wake.gpu.available() is False)")
    _backend = "gpu" if (name == "gpu" or (name == "auto" and usable)) else "cpu"
    return _backend


def kernel_backend():
    """The Biot-Savart backend in use, ``"cpu"`` or ``"gpu"`` (first call: from
    ``$ROTORWAKE_KERNEL``, default ``auto``; see :func:`set_kernel_backend`)."""
    if _backend is None:
        import os
        set_kernel_backend(os.environ.get(KERNEL_ENV, "auto").strip().lower() or "auto")
    return _backend


def segment_velocity(targets, seg_a, seg_b, gamma, rc, precision="double", *, chained=True):
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
    chained : bool
        Reuse 1 / |P - A_j| from the previous segment where A_j equals B_{j-1}
        exactly (chains of segments: about a third less work per pair). The
        result is bit-identical either way; ``False`` runs the former pair loop
        (the reference march and the benchmark's baseline).

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
    if kernel_backend() == "gpu":
        return _gpu_module().segment_velocity(targets, seg_a, seg_b, gamma, rc, precision)
    dtype = _PRECISIONS[precision]
    r0 = seg_b - seg_a
    rcl = rc * rc * np.einsum("ij,ij->i", r0, r0)

    m = targets.shape[0]
    pad = -m % _LANES
    if pad:   # repeat the last target: finite, discarded below
        targets = np.concatenate([targets, np.repeat(targets[-1:], pad, axis=0)])

    def rows(x):   # (K, 3) -> three contiguous columns in the working dtype
        return tuple(np.ascontiguousarray(x.T, dtype=dtype))

    def col(x):
        return np.ascontiguousarray(x, dtype=dtype)

    args = (*rows(targets), *rows(seg_a), *rows(seg_b), *rows(r0),
            col(gamma / _FOUR_PI), col(rcl * rcl))
    if chained:
        # A_j == B_{j-1} exactly in the working precision (what the kernel sees)
        ax, ay, az, bx, by, bz = args[3:9]
        linked = np.zeros(ax.shape[0], dtype=np.bool_)
        linked[1:] = (ax[1:] == bx[:-1]) & (ay[1:] == by[:-1]) & (az[1:] == bz[:-1])
        out = _segment_velocity_chain(*args, linked, dtype(1.0), dtype(_TINY))
    else:
        out = _segment_velocity_soa(*args, dtype(1.0), dtype(_TINY))
    return out[:m].astype(np.float64)


def segment_influence(targets, seg_a, seg_b, rc, *, chained=True):
    """Velocity per unit circulation of each segment at each target (compiled kernel).

    Used for the small bound/near-wake circulation system of the blades.

    Parameters
    ----------
    targets : array_like, shape (M, 3)
        Evaluation points [m].
    seg_a, seg_b : array_like, shape (N, 3)
        Segment start and end points [m].
    rc : array_like, shape (N,) or scalar
        Vatistas (n = 2) core radius [m].
    chained : bool
        Vectorised over targets, reusing r1 / |r1| where a segment starts exactly
        where the previous one ends (see :func:`segment_velocity`); ``False``: the
        former loop (reference march). Bit-identical results either way.

    Returns
    -------
    ndarray, shape (M, N, 3)
        Induced velocity per unit circulation [1/m].
    """
    targets, seg_a, seg_b, _, rc = _check(targets, seg_a, seg_b, None, rc)
    if not chained:
        return _segment_influence_numba(targets, seg_a, seg_b, rc)
    m, n = targets.shape[0], seg_a.shape[0]
    if m == 0 or n == 0:
        return np.zeros((m, n, 3))
    pad = -m % _LANES
    if pad:   # repeat the last target: finite, discarded below
        targets = np.concatenate([targets, np.repeat(targets[-1:], pad, axis=0)])
    linked = np.zeros(n, dtype=np.bool_)
    linked[1:] = np.all(seg_a[1:] == seg_b[:-1], axis=1)
    cols = [np.ascontiguousarray(x) for x in (*targets.T, *seg_a.T, *seg_b.T)]
    out = _segment_influence_lanes(*cols, rc, linked)
    return np.ascontiguousarray(out[:, :, :m].transpose(2, 1, 0))


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

    Returns
    -------
    ndarray
        Core radius [m], shape of ``age``.
    """
    age = np.asarray(age, dtype=float)
    return np.sqrt(rc0 ** 2 + 4.0 * VATISTAS_ALPHA * delta * nu * np.maximum(age, 0.0) / omega)
