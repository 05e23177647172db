"""GPU Biot-Savart kernel per call at a wake's sizes (run on a machine with an NVIDIA GPU).

Prints, for the target/segment counts of a default-resolution coaxial revolution
(1160 x 3008) and of a finer wake (2300 x 12000), in single and double precision:
the wall time of one :func:`aircraft.wake.gpu.segment_velocity` call (array in,
array out: packing and host-device copies included) [us], the number of segment
chunks each target's sum is split into, its largest difference from the CPU kernel
relative to max |v|, and the CPU kernel's time on all this host's threads [us].
Without a device it says so and exits. ``bash benchmarks/gpu_device_check.sh``
runs it after the device tests and ``benchmarks/wake.py --gpu-only``.
"""
import time
import warnings

import numba
import numpy as np

from aircraft.wake import gpu
from aircraft.wake.biot_savart import segment_velocity, set_kernel_backend


def inputs(m, n, seed=0):
    """Wake-like random targets and segments (tens of metres, ~0.5 m segments) [m, m^2/s]."""
    rng = np.random.default_rng(seed)
    a = 20 + 5 * rng.normal(size=(n, 3))
    return (20 + 5 * rng.normal(size=(m, 3)), a, a + 0.5 * rng.normal(size=(n, 3)),
            rng.normal(size=n), np.full(n, 0.05))


def per_call_us(f, reps):
    """Mean wall time of ``f()`` [us] after one warm-up call, the device synchronised."""
    from numba import cuda
    f()
    cuda.synchronize()
    t = time.perf_counter()
    for _ in range(reps):
        f()
    cuda.synchronize()
    return (time.perf_counter() - t) / reps * 1e6


def main():
    set_kernel_backend("cpu")                      # the references are the CPU kernel's
    if not gpu.available():
        print(f"GPU: no device ({gpu.unavailable_reason()})")
        return
    warnings.simplefilter("ignore")                # numba's occupancy hints on small launches
    for m, n in ((1160, 3008), (2300, 12000)):
        args = inputs(m, n)
        for p in ("single", "double"):
            ref = segment_velocity(*args, p)
            got = gpu.segment_velocity(*args, precision=p)
            t_gpu = per_call_us(lambda: gpu.segment_velocity(*args, precision=p), 100)
            t_cpu = per_call_us(lambda: segment_velocity(*args, p), 20)
            print(f"m={m} n={n} {p}: gpu.segment_velocity {t_gpu:.0f} us/call, chunks "
                  f"{gpu._n_chunks(m, n)}, err {np.abs(got - ref).max() / np.abs(ref).max():.1e}; "
                  f"cpu kernel ({numba.get_num_threads()} threads) {t_cpu:.0f} us")


if __name__ == "__main__":
    main()
