"""CUDA Biot-Savart kernel (numba.cuda): the GPU backend of ``segment_velocity``.

:func:`aircraft.wake.biot_savart.segment_velocity` hands its (already checked)
arrays to :func:`segment_velocity` here when the backend is ``"gpu"``
(:func:`~aircraft.wake.biot_savart.set_kernel_backend`, ``$ROTORWAKE_KERNEL``).
Same signature, same units, same result to the round-off of the chosen precision.

Kernel
------
One CUDA thread per target. Each thread sums the segments in index order, in the
operation order of the CPU kernel (same formula, same precomputed
target-independent terms ``r0 = B - A``, ``Gamma / 4 pi``, ``(r_c |r0|)^4``, the
same ``tiny`` guards), in float32 or float64. There is no reduction across
threads and no atomic, so a result is deterministic run to run. It is not
bit-identical to the CPU kernel: NVVM contracts multiply-adds into fused
multiply-adds (its default, even without ``fastmath``), which rounds once where
the CPU rounds twice; the difference is round-off of the working precision
(tested: within 1e-5 of max |v| in single precision, within 1e-10 in double).
The wake cache keys GPU runs apart from CPU runs (backend name and this file's
source, :func:`aircraft.wake.sweeps._kernel_key`), so the two never mix.

Device buffers (targets, packed segment records, result) are kept per precision
and grown when a call needs more, so a wake march does three host-device copies
and one launch per call and no allocation once the wake has reached its size.

Availability
------------
:func:`available` is True only for a usable CUDA device: numba.cuda imports, the
driver reports a device, and the kernel compiles, runs and agrees with the numpy
reference on a small problem. Any CUDA error (no driver, no toolkit for NVVM,
an unsupported device) makes it False, with the reason in
:func:`unavailable_reason`; the result is cached for the process.

numba's CUDA simulator (``NUMBA_ENABLE_CUDASIM=1``, set before numba is imported)
runs the same kernel source in Python threads, with numpy scalars and without
fused multiply-adds. It is not a device: under it :func:`available` is False, so
the ``"auto"`` backend stays on the CPU, unless ``ROTORWAKE_GPU_SIMULATOR=1``
(:data:`SIMULATOR_ENV`) asks for it explicitly (then the same self-check runs on
it). :func:`segment_velocity` itself runs under the simulator either way: that is
how CI checks the kernel without a device. The simulator is far too slow for a
wake march (~500 pairs/s).
"""
from __future__ import annotations

import math
import os
import threading
import warnings

import numpy as np

try:   # never fail to import: without numba.cuda the backend is simply unavailable
    from numba import cuda
    from numba.core.errors import NumbaPerformanceWarning
    _IMPORT_ERROR = None
except Exception as exc:   # pragma: no cover - numba always ships numba.cuda today
    cuda = None
    NumbaPerformanceWarning = Warning
    _IMPORT_ERROR = f"numba.cuda cannot be imported ({type(exc).__name__}: {exc})"

__all__ = ["available", "simulated", "unavailable_reason", "device_name", "segment_velocity",
           "SIMULATOR_ENV", "THREADS_PER_BLOCK"]

#: Environment variable: ``1`` makes :func:`available` True under numba's CUDA
#: simulator (an explicit request; the simulator is never chosen by ``"auto"``
#: otherwise).
SIMULATOR_ENV = "ROTORWAKE_GPU_SIMULATOR"
#: CUDA threads per block (one target each) [-]. Small blocks spread the wake's
#: few thousand targets over more multiprocessors.
THREADS_PER_BLOCK = 64

_FOUR_PI = 4.0 * math.pi
_TINY = 1e-12            # as in the CPU kernel
_PRECISIONS = {"double": np.float64, "single": np.float32}
_N_FIELDS = 11           # packed segment record: A, B, r0 (3 each), Gamma/4pi, (rc |r0|)^4

_probe_lock = threading.Lock()    # two locks: the probe launches the kernel
_launch_lock = threading.Lock()
_probe_result = None     # (available, reason), set once by available()
_buffers = {}            # dtype -> {"tg": dev (mcap, 3), "seg": dev (ncap, 11), "out": dev (mcap, 3)}


def simulated():
    """Whether numba.cuda is its CUDA simulator (``NUMBA_ENABLE_CUDASIM=1``).

    Returns
    -------
    bool
        True under the simulator, False for the real CUDA target or without numba.cuda.
    """
    if cuda is None:
        return False
    from numba import config
    return bool(config.ENABLE_CUDASIM)


if cuda is not None:
    @cuda.jit(fastmath=False, cache=not simulated())
    def _kernel(tg, seg, out, m, n, one, tiny):
        # tg (>= m, 3), seg (>= n, 11), out (>= m, 3): reused buffers, only the
        # first m / n rows are this call's. ``one`` and ``tiny`` carry the dtype.
        i = cuda.grid(1)
        if i >= m:
            return
        qx = tg[i, 0]
        qy = tg[i, 1]
        qz = tg[i, 2]
        ux = one - one
        uy = one - one
        uz = one - one
        for j in range(n):       # sequential, in index order, as on the CPU
            axj = seg[j, 0]
            ayj = seg[j, 1]
            azj = seg[j, 2]
            bxj = seg[j, 3]
            byj = seg[j, 4]
            bzj = seg[j, 5]
            r0xj = seg[j, 6]
            r0yj = seg[j, 7]
            r0zj = seg[j, 8]
            gj = seg[j, 9]
            rlj = seg[j, 10]
            r1x = qx - axj
            r1y = qy - ayj
            r1z = qz - azj
            r2x = qx - bxj
            r2y = qy - byj
            r2z = qz - bzj
            cx = r1y * r2z - r1z * r2y
            cy = r1z * r2x - r1x * r2z
            cz = r1x * r2y - r1y * r2x
            c2 = cx * cx + cy * cy + cz * cz
            i1 = one / (math.sqrt(r1x * r1x + r1y * r1y + r1z * r1z) + tiny)
            i2 = one / (math.sqrt(r2x * r2x + r2y * r2y + r2z * r2z) + tiny)
            dot = (r0xj * (r1x * i1 - r2x * i2) + r0yj * (r1y * i1 - r2y * i2)
                   + r0zj * (r1z * i1 - r2z * i2))
            f = gj * dot / (math.sqrt(c2 * c2 + rlj) + tiny)
            ux += f * cx
            uy += f * cy
            uz += f * cz
        out[i, 0] = ux
        out[i, 1] = uy
        out[i, 2] = uz


def _self_check(where):
    """(usable, reason) after compiling and running the kernel once on ``where``."""
    # a device without a working toolkit (NVVM, libdevice) must fall back here,
    # not in the middle of a march
    from .biot_savart import segment_velocity_numpy
    rng = np.random.default_rng(0)
    tg = rng.normal(size=(5, 3))
    a = rng.normal(size=(7, 3))
    b = a + 0.3 * rng.normal(size=(7, 3))
    g = rng.normal(size=7)
    rc = np.full(7, 0.05)
    got = _launch(tg, a, b, g, rc, np.float64)
    want = segment_velocity_numpy(tg, a, b, g, rc)
    # double precision, 7 terms per sum: agreement to 1e-9 of max |v| or the
    # device computes something else
    if not np.allclose(got, want, rtol=0.0, atol=1e-9 * np.abs(want).max()):
        return False, f"the CUDA kernel on {where} disagrees with the CPU reference"
    return True, where


def _probe():
    """(usable, reason) of the CUDA backend in this process."""
    if cuda is None:
        return False, _IMPORT_ERROR
    try:
        if simulated():
            if os.environ.get(SIMULATOR_ENV, "").strip() != "1":
                return False, ("numba's CUDA simulator is active (NUMBA_ENABLE_CUDASIM=1); it is "
                               f"not a device (set {SIMULATOR_ENV}=1 to use it explicitly)")
            return _self_check(f"numba CUDA simulator, explicitly enabled by {SIMULATOR_ENV}=1")
        if not cuda.is_available():
            return False, "no usable CUDA driver or device (numba.cuda.is_available() is False)"
        return _self_check(f"CUDA device {_device_name()}")
    except Exception as exc:   # any driver/toolkit/compile error: not usable
        return False, f"CUDA device not usable ({type(exc).__name__}: {exc})"


def available():
    """Whether the GPU kernel can be used in this process (probed once, cached).

    True for a CUDA device on which the kernel compiles and agrees with the numpy
    reference; under numba's CUDA simulator only if ``$ROTORWAKE_GPU_SIMULATOR``
    is ``1``. Never raises.

    Returns
    -------
    bool
        True if :func:`segment_velocity` runs on a device (or the requested simulator).
    """
    global _probe_result
    if _probe_result is None:
        with _probe_lock:
            if _probe_result is None:
                _probe_result = _probe()
    return _probe_result[0]


def unavailable_reason():
    """Why :func:`available` is False (or what it found when True).

    Returns
    -------
    str
        A one-line description: the device name, or the error that made it unusable.
    """
    available()
    return _probe_result[1]


def _device_name():
    dev = cuda.get_current_device()
    name = dev.name.decode() if isinstance(dev.name, bytes) else str(dev.name)
    return f"{name} (compute capability {dev.compute_capability[0]}.{dev.compute_capability[1]})"


def device_name():
    """Name and compute capability of the CUDA device in use, if any.

    Returns
    -------
    str or None
        E.g. ``"NVIDIA H200 (compute capability 9.0)"``; ``"CUDA simulator"``
        under the simulator; None when :func:`available` is False.
    """
    if not available():
        return None
    return "CUDA simulator" if simulated() else _device_name()


def _buffer(dtype, name, rows, cols):
    """A device array of at least ``rows`` rows for this precision, reused across calls."""
    store = _buffers.setdefault(dtype, {})
    buf = store.get(name)
    if buf is None or buf.shape[0] < rows:
        buf = cuda.device_array((max(rows, int(1.25 * rows) + 64), cols), dtype=dtype)
        store[name] = buf
    return buf


def _launch(targets, seg_a, seg_b, gamma, rc, dtype):
    """Pack, copy, run the kernel and copy back; float64 (M, 3) out. Inputs checked."""
    m, n = targets.shape[0], seg_a.shape[0]
    r0 = seg_b - seg_a
    rcl = rc * rc * np.einsum("ij,ij->i", r0, r0)
    seg = np.empty((n, _N_FIELDS), dtype=dtype)   # target-independent terms in float64, then cast
    seg[:, 0:3] = seg_a
    seg[:, 3:6] = seg_b
    seg[:, 6:9] = r0
    seg[:, 9] = gamma / _FOUR_PI
    seg[:, 10] = rcl * rcl
    tg = np.ascontiguousarray(targets, dtype=dtype)
    with _launch_lock:
        d_tg = _buffer(dtype, "tg", m, 3)
        d_seg = _buffer(dtype, "seg", n, _N_FIELDS)
        d_out = _buffer(dtype, "out", m, 3)
        d_tg[:m].copy_to_device(tg)
        d_seg[:n].copy_to_device(seg)
        blocks = (m + THREADS_PER_BLOCK - 1) // THREADS_PER_BLOCK
        with warnings.catch_warnings():   # small wakes under-fill the device: expected
            warnings.simplefilter("ignore", NumbaPerformanceWarning)
            _kernel[blocks, THREADS_PER_BLOCK](d_tg, d_seg, d_out, m, n, dtype(1.0), dtype(_TINY))
        out = d_out[:m].copy_to_host()
    return out.astype(np.float64)


def segment_velocity(targets, seg_a, seg_b, gamma, rc, precision="double"):
    """Velocity induced at ``targets`` by straight vortex segments, on the GPU.

    Same inputs, formula and result (to the round-off of ``precision``) as
    :func:`aircraft.wake.biot_savart.segment_velocity`, which calls this when the
    kernel backend is ``"gpu"``.

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
        Arithmetic of the pair loop on the device; inputs and result stay float64.

    Returns
    -------
    ndarray, shape (M, 3)
        Induced velocity [m/s], float64.

    Raises
    ------
    ValueError
        For an unknown precision or badly shaped inputs (as the CPU kernel).
    RuntimeError
        If there is neither a usable CUDA device nor numba's CUDA simulator.
    """
    from .biot_savart import _check
    if precision not in _PRECISIONS:
        raise ValueError(f"precision must be 'double' or 'single', got {precision!r}")
    targets, seg_a, seg_b, gamma, rc = _check(targets, seg_a, seg_b, gamma, rc)
    if gamma is None:
        raise ValueError("gamma must be a scalar or have shape (N,) [m^2/s], got None")
    if seg_a.shape[0] == 0 or targets.shape[0] == 0:
        return np.zeros((targets.shape[0], 3))
    if not (simulated() or available()):
        raise RuntimeError(f"the GPU Biot-Savart kernel needs a CUDA device: {unavailable_reason()}")
    return _launch(targets, seg_a, seg_b, gamma, rc, _PRECISIONS[precision])
