"""CUDA Biot-Savart kernel (numba.cuda): the GPU backend of ``segment_velocity``.

:func:`aircraft.wake.biot_savart.segment_velocity` hands its (already checked)
arrays to :func:`segment_velocity` here when the backend is ``"gpu"``
(:func:`~aircraft.wake.biot_savart.set_kernel_backend`, ``$ROTORWAKE_KERNEL``).
Same signature, same units, same result to the round-off of the chosen precision.

Kernel
------
Each target's sum over the segments is split into chunks of consecutive
segments (:func:`_n_chunks`: enough chunks that targets x chunks reach
:data:`TARGET_THREADS`, none shorter than :data:`MIN_CHUNK`). One CUDA thread per
(target, chunk) sums its chunk in index order, in the operation order of the
CPU kernel (same formula, same precomputed target-independent terms
``r0 = B - A``, ``Gamma / 4 pi``, ``(r_c |r0|)^4``, the same ``tiny`` guards), in
float32 or float64; a second kernel adds each target's partial sums in chunk
order. One thread per target alone left an H200 nearly idle on a wake's ~1e3
targets (1.35 ms for 1160 x 3008 pairs; 68 us in 64 chunks, measured). There is
no atomic and the order of every sum is fixed by the sizes alone, so a result is
deterministic run to run. It is not bit-identical to the CPU kernel: the chunks
are added apart and then together (the CPU adds every segment into one running
sum), and NVVM contracts multiply-adds into fused multiply-adds (its default,
even without ``fastmath``), which rounds once where the CPU rounds twice; the
difference is round-off of the working precision (tested: within 1e-5 of max
|v| in single precision, within 1e-10 in double).
The wake cache keys GPU runs apart from CPU runs (backend name and this file's
source, :func:`aircraft.wake.sweeps._kernel_key`), so the two never mix.

Buffers (a pinned host staging buffer holding the targets and packed segment
records, its device copy, the partial sums, the result on the device and in
pinned host memory) are kept per precision and grown when a call needs more, so
a wake march does one copy in, two launches and one copy out per call and no
allocation once the wake has reached its size.

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

from .segments_common import _check, segment_velocity_numpy

try:   # never fail to import: without numba.cuda the backend is simply unavailable
    from numba import cuda
    from numba.core.errors import NumbaPerformanceWarning
    _IMPORT_ERROR = None
except Exception as exc:   # pragma: no cover - numba always ships numba.cuda today
    cuda = None
    NumbaPerformanceWarning = Warning
    _IMPORT_ERROR = f"numba.cuda cannot be imported ({type(exc).__name__}: {exc})"

__all__ = ["available", "simulated", "unavailable_reason", "device_name", "segment_velocity",
           "SIMULATOR_ENV", "THREADS_PER_BLOCK", "BLOCK", "TARGET_THREADS",
           "MIN_CHUNK"]

#: Environment variable: ``1`` makes :func:`available` True under numba's CUDA
#: simulator (an explicit request; the simulator is never chosen by ``"auto"``
#: otherwise).
SIMULATOR_ENV = "ROTORWAKE_GPU_SIMULATOR"
#: CUDA threads per block of the kernel that adds the chunks' partial sums [-].
THREADS_PER_BLOCK = 64
#: Block of the pair kernel: 32 targets (a warp, whose threads then read the same
#: segment record at once) x 4 segment chunks [-].
BLOCK = (32, 4)
#: Threads the pair kernel aims to run at once [-]: the targets times the chunks
#: each target's sum is split into (an H200 has 132 multiprocessors of up to
#: 2048 resident threads).
TARGET_THREADS = 1 << 17
#: Fewest segments one thread sums [-].
MIN_CHUNK = 32

_FOUR_PI = 4.0 * math.pi
_TINY = 1e-12            # as in the CPU kernel
_PRECISIONS = {"double": np.float64, "single": np.float32}
_N_FIELDS = 11           # packed segment record: A, B, r0 (3 each), Gamma/4pi, (rc |r0|)^4

_probe_lock = threading.Lock()    # two locks: the probe launches the kernel
_launch_lock = threading.Lock()
_probe_result = None     # (available, reason), set once by available()
_buffers = {}            # dtype -> {"stage"/"host_out": pinned host, "in"/"part"/"out": device}


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


def _n_chunks(m, n):
    """How many segment chunks each target's sum is split into (a function of the sizes only)."""
    # enough threads to fill a large device (TARGET_THREADS), but no chunk shorter
    # than MIN_CHUNK segments: past that the partial sums cost more than they save
    return max(1, min(-(-TARGET_THREADS // m), -(-n // MIN_CHUNK)))


if cuda is not None:
    @cuda.jit(fastmath=False, cache=not simulated())
    def _chunk_kernel(buf, part, m, n, n_chunks, chunk, one, tiny):
        # buf: this call's inputs packed flat, targets (m x 3) then segment
        # records (n x 11); part (>= n_chunks, >= m, 3): thread (i, c) writes the
        # sum over segments [c chunk, (c + 1) chunk) at target i, in index order
        # (why chunks: the module docstring); ``one`` and ``tiny`` carry the dtype.
        i, c = cuda.grid(2)
        if i >= m or c >= n_chunks:     # the grid rounds both up to whole blocks
            return
        j0 = c * chunk
        j1 = min(n, j0 + chunk)      # empty past n: the partial sum is then zero
        qx = buf[3 * i]
        qy = buf[3 * i + 1]
        qz = buf[3 * i + 2]
        ux = one - one
        uy = one - one
        uz = one - one
        for j in range(j0, j1):       # sequential, in index order, as on the CPU
            k = 3 * m + _N_FIELDS * j
            r1x = qx - buf[k]
            r1y = qy - buf[k + 1]
            r1z = qz - buf[k + 2]
            r2x = qx - buf[k + 3]
            r2y = qy - buf[k + 4]
            r2z = qz - buf[k + 5]
            cx = r1y * r2z - r1z * r2y
            cy = r1z * r2x - r1x * r2z
            cz = r1x * r2y - r1y * r2x
            c2 = cx * cx + cy * cy + cz * cz
            i1 = one / (math.sqrt(r1x * r1x + r1y * r1y + r1z * r1z) + tiny)
            i2 = one / (math.sqrt(r2x * r2x + r2y * r2y + r2z * r2z) + tiny)
            dot = (buf[k + 6] * (r1x * i1 - r2x * i2) + buf[k + 7] * (r1y * i1 - r2y * i2)
                   + buf[k + 8] * (r1z * i1 - r2z * i2))
            f = buf[k + 9] * dot / (math.sqrt(c2 * c2 + buf[k + 10]) + tiny)
            ux += f * cx
            uy += f * cy
            uz += f * cz
        part[c, i, 0] = ux
        part[c, i, 1] = uy
        part[c, i, 2] = uz

    @cuda.jit(fastmath=False, cache=not simulated())
    def _sum_kernel(part, out, m, n_chunks, one):
        # out[i] = the partial sums of target i added in chunk order: a fixed
        # order, so a result is the same run to run (no atomics)
        i = cuda.grid(1)
        if i >= m:
            return
        for k in range(3):
            s = one - one
            for c in range(n_chunks):
                s += part[c, i, k]
            out[i, k] = s


def _self_check(where):
    """(usable, reason) after compiling and running the kernel once on ``where``."""
    # a device without a working toolkit (NVVM, libdevice) must fall back here,
    # not in the middle of a march
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


def _buffer(dtype, name, shape, pinned=False):
    """A device (or pinned host) array for this precision, reused across calls.

    Every dimension but a last one of 3 (x, y, z) is at least ``shape``'s; the
    kernels are told how much of it is this call's.
    """
    store = _buffers.setdefault(dtype, {})
    buf = store.get(name)
    grow = len(shape) if len(shape) == 1 else len(shape) - 1
    if buf is None or any(have < want for have, want in zip(buf.shape, shape)):
        # a quarter past what is asked, so a growing wake reallocates rarely
        grown = tuple(max(want, int(1.25 * want) + 64) for want in shape[:grow]) + tuple(shape[grow:])
        if buf is not None:
            grown = tuple(max(g, have) for g, have in zip(grown, buf.shape))
        buf = (cuda.pinned_array if pinned else cuda.device_array)(grown, dtype=dtype)
        store[name] = buf
    return buf


def _launch(targets, seg_a, seg_b, gamma, rc, dtype):
    """Pack, copy, run the kernels and copy back; float64 (M, 3) out. Inputs checked."""
    m, n = targets.shape[0], seg_a.shape[0]
    r0 = seg_b - seg_a
    rcl = rc * rc * np.einsum("ij,ij->i", r0, r0)
    n_chunks = _n_chunks(m, n)
    chunk = -(-n // n_chunks)
    size = 3 * m + _N_FIELDS * n
    with _launch_lock:
        # one pinned staging buffer and one copy in, one copy out: on a wake's
        # ~1e3 x 3e3 pairs each transfer costs more than the kernel itself
        stage = _buffer(dtype, "stage", (size,), pinned=True)
        tg = stage[:3 * m].reshape(m, 3)
        seg = stage[3 * m:size].reshape(n, _N_FIELDS)
        tg[:] = targets                 # target-independent terms in float64, then cast
        seg[:, 0:3] = seg_a
        seg[:, 3:6] = seg_b
        seg[:, 6:9] = r0
        seg[:, 9] = gamma / _FOUR_PI
        seg[:, 10] = rcl * rcl
        d_in = _buffer(dtype, "in", (size,))
        d_part = _buffer(dtype, "part", (n_chunks, m, 3))
        d_out = _buffer(dtype, "out", (m, 3))
        host_out = _buffers[dtype].get("host_out")
        if host_out is None or host_out.shape != d_out.shape:   # copy_to_host needs equal shapes
            host_out = _buffers[dtype]["host_out"] = cuda.pinned_array(d_out.shape, dtype=dtype)
        d_in[:size].copy_to_device(stage[:size])
        grid = ((m + BLOCK[0] - 1) // BLOCK[0], (n_chunks + BLOCK[1] - 1) // BLOCK[1])
        with warnings.catch_warnings():   # small wakes under-fill the device: expected
            warnings.simplefilter("ignore", NumbaPerformanceWarning)
            _chunk_kernel[grid, BLOCK](d_in, d_part, m, n, n_chunks, chunk, dtype(1.0),
                                       dtype(_TINY))
            _sum_kernel[(m + THREADS_PER_BLOCK - 1) // THREADS_PER_BLOCK, THREADS_PER_BLOCK](
                d_part, d_out, m, n_chunks, dtype(1.0))
        d_out.copy_to_host(host_out)    # the whole buffer: no device view to build
        return host_out[:m].astype(np.float64)


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
