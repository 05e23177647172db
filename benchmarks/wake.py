"""Free-vortex wake benchmark (run: .venv/bin/python benchmarks/wake.py).

Prints, from one run: the Biot-Savart pair-interaction rate of the compiled kernel
in double and single precision and of the plain numpy version (same inputs) with
their ratios; the wall time of one coaxial revolution at the default resolution
(10 deg steps, 4 + 1 revolutions of wake, 10 elements) measured on all cores and
on one (the sweep workers run one kernel thread each); and the projected wall time
of the six-sweep coaxial hover identification set on 2 cores. The CPU figures
always use the CPU kernel (also on a machine with a GPU).

Then the GPU figures when :func:`aircraft.wake.gpu.available` (else it prints
"GPU: no device" and why): the agreement of the GPU kernel with the CPU kernel,
its pair rate (array in, array out: transfers included) at the benchmark size and
at a size that fills the device, and the wall time of a coaxial revolution
with the GPU kernel against the CPU kernel on 2 threads (the 2-core machine the
projection is for), the rest of the march on 2 host threads in both, at the
default resolution and two finer ones (:data:`GPU_RESOLUTIONS`), each with the
time inside the kernel calls and the bound an instant kernel would give.

The march itself: one default coaxial revolution with the compiled march and with
the former numpy march (:mod:`aircraft.wake.reference`, same numbers) on 1 and on
2 threads, their ratio, and the share of the revolution spent in the Biot-Savart
kernel calls (velocity kernel; bound/near-wake influence kernel) for each; the
ceiling the velocity kernel puts on a one-thread speed-up (the former march's time
over the compiled march's kernel time), with the kernel as shipped and compiled with
fastmath (measured, not used: it changes results at round-off); and
the estimated wake time of the 12-state coaxial data set from the 1-thread
revolution time (:data:`DATASET_REVS` revolutions on 2 single-thread workers).

Options: ``--gpu-only`` runs only the GPU part (and the 2-thread CPU revolution
it is compared with); ``--march-only`` only the compiled-vs-former march comparison.
"""
import argparse
import math
import os
import time

import numba
import numpy as np

from aircraft.configs import coaxial_compound
from aircraft.wake import (FreeVortexWake, WakeSettings, gpu, segment_velocity,
                           segment_velocity_numpy)
from aircraft.wake import blades as blades_module
from aircraft.wake import wake as wake_module
from aircraft.wake.biot_savart import set_kernel_backend

#: rotor revolutions marched for the 12-state coaxial hover data set (trim, ten
#: sweeps, doublet, zero-input run; benchmarks/results/coaxial_12state), on 2 workers
DATASET_REVS = 1803

#: resolutions of the GPU-vs-CPU revolution comparison: (label, WakeSettings fields).
#: The default is the studies' wake; the finer ones show where the kernel's share
#: of a revolution, and so what a faster kernel can gain, grows.
GPU_RESOLUTIONS = (
    ("default (10 deg, 4+1 revs)", {}),
    ("5 deg, 4+1 revs", {"azimuth_step": math.radians(5.0)}),
    ("5 deg, 8+1 revs", {"azimuth_step": math.radians(5.0), "wake_revolutions": 8.0}),
)


def pair_rates(m=1500, n=1800, seed=0):
    """Pairs/s of the compiled kernel (double, single) and of numpy, same inputs."""
    rng = np.random.default_rng(seed)
    tg = rng.normal(size=(m, 3))
    a = rng.normal(size=(n, 3))
    b = a + 0.1 * rng.normal(size=(n, 3))
    g = rng.normal(size=n)
    rc = np.full(n, 0.05)
    rates = {}
    for precision in ("double", "single"):
        segment_velocity(tg[:10], a, b, g, rc, precision)        # compile / load cache
        reps = 10
        t0 = time.perf_counter()
        for _ in range(reps):
            segment_velocity(tg, a, b, g, rc, precision)
        rates[precision] = reps * m * n / (time.perf_counter() - t0)
    mm = 300
    t0 = time.perf_counter()
    segment_velocity_numpy(tg[:mm], a, b, g, rc)
    rates["numpy"] = mm * n / (time.perf_counter() - t0)
    return rates


def revolution_time(threads, kernel_time=False, compiled=True, influence=None, cpu=None,
                    **settings):
    """Wall time [s] of the second coaxial revolution (the first warms up and compiles).

    ``settings`` are :class:`WakeSettings` fields (default resolution without).
    With ``kernel_time=True`` also the time spent inside the Biot-Savart calls of
    that revolution [s], measured by timing each call the march makes; else None.
    ``compiled=False`` marches with the former numpy march (same numbers). A list
    passed as ``influence`` receives the time [s] spent in the bound/near-wake
    influence kernel (``segment_influence``) calls of that revolution, and a list
    passed as ``cpu`` the process CPU time of the revolution [s] (on one thread
    the figure least disturbed by other load on a shared machine).
    """
    numba.set_num_threads(threads)
    s = WakeSettings(**settings)
    make = FreeVortexWake if compiled else FreeVortexWake._reference_march
    w = make(coaxial_compound(), s)
    w.controls.update(theta0_U=0.16, theta0_L=0.17)
    w.march(s.steps_per_rev)                                   # warm up
    spent = []
    # the march calls the kernels through its modules' own names (the wake for the
    # marker velocities, the blade solve for its panels): time each call there
    originals = [(wake_module, "segment_velocity"), (blades_module, "segment_velocity"),
                 (blades_module, "segment_influence")]
    saved = [getattr(mod, name) for mod, name in originals]

    def timer(func, store):
        def timed(*args, **kwargs):
            t = time.perf_counter()
            out = func(*args, **kwargs)
            store.append(time.perf_counter() - t)
            return out
        return timed
    for (mod, name), func in zip(originals, saved):
        if name == "segment_velocity" and kernel_time:
            setattr(mod, name, timer(func, spent))
        elif name == "segment_influence" and influence is not None:
            setattr(mod, name, timer(func, influence))
    try:
        t0, c0 = time.perf_counter(), time.process_time()
        w.march(s.steps_per_rev)
        elapsed = time.perf_counter() - t0
        if cpu is not None:
            cpu.append(time.process_time() - c0)
    finally:
        for (mod, name), func in zip(originals, saved):
            setattr(mod, name, func)
    if influence is not None:
        influence[:] = [sum(influence)]
    return elapsed, s, w, (sum(spent) if kernel_time else None)


def _inputs(m, n, seed=0):
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(n, 3))
    return (rng.normal(size=(m, 3)), a, a + 0.1 * rng.normal(size=(n, 3)), rng.normal(size=n),
            np.full(n, 0.05))


def gpu_pair_rate(m, n, precision, min_time=1.0):
    """Pairs/s of the GPU kernel, array in / array out (host-device copies included)."""
    args = _inputs(m, n)
    gpu.segment_velocity(*args, precision=precision)               # compile / load cache
    reps, t0 = 0, time.perf_counter()
    while reps < 3 or time.perf_counter() - t0 < min_time:
        gpu.segment_velocity(*args, precision=precision)
        reps += 1
    return reps * m * n / (time.perf_counter() - t0)


def gpu_agreement(m=1500, n=1800):
    """Max |GPU - CPU| / max |CPU| of the kernel, per precision (CPU kernel selected)."""
    args = _inputs(m, n, seed=1)
    out = {}
    for precision in ("double", "single"):
        ref = segment_velocity(*args, precision)
        out[precision] = float(np.abs(gpu.segment_velocity(*args, precision=precision) - ref).max()
                               / np.abs(ref).max())
    return out


def gpu_main():
    """Print the GPU figures, or that there is no device."""
    if not gpu.available():
        print(f"GPU: no device ({gpu.unavailable_reason()})")
        return
    set_kernel_backend("cpu")
    print(f"GPU: {gpu.device_name()}")
    agree = gpu_agreement()
    print(f"GPU kernel vs CPU kernel, max |dv| / max |v| (1500 x 1800 pairs): double "
          f"{agree['double']:.1e}, single {agree['single']:.1e} (target <= 1e-5)")
    for m, n in ((1500, 1800), (20000, 20000)):
        r = {p: gpu_pair_rate(m, n, p) for p in ("double", "single")}
        print(f"GPU Biot-Savart pairs/s at {m} x {n} (copies included): double {r['double']:.3e}, "
              f"single {r['single']:.3e}")
    threads = min(2, numba.config.NUMBA_NUM_THREADS)
    for label, settings in GPU_RESOLUTIONS:
        t_cpu, s, _, k_cpu = revolution_time(threads, kernel_time=True, **settings)
        set_kernel_backend("gpu")
        try:
            t_gpu, _, _, k_gpu = revolution_time(threads, kernel_time=True, **settings)
        finally:
            set_kernel_backend("cpu")
            numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
        # Amdahl: the rest of the march stays on the host whichever kernel runs
        bound = t_cpu / max(t_cpu - k_cpu, 1e-12)
        print(f"coaxial revolution, {label}, {s.kernel_precision} kernel, host on {threads} threads: "
              f"GPU kernel {t_gpu:.2f} s (kernel calls {k_gpu:.2f} s), CPU kernel {t_cpu:.2f} s "
              f"(kernel calls {k_cpu:.2f} s, {100 * k_cpu / t_cpu:.0f} %): {t_cpu / t_gpu:.1f}x "
              f"(bound with an instant kernel {bound:.1f}x)")


def fastmath_kernel_ratio(m=1504, n=1800, seed=0, reps=10):
    """Pairs/s of the chained velocity kernel as shipped and compiled with fastmath, 1 thread.

    The fastmath build (reassociation, FMA contraction, approximate reciprocals) is
    not used by the march: it changes results at round-off, and so every cached
    wake run and every number computed from one. It is measured here only to bound
    what a faster per-pair arithmetic could give.
    """
    from aircraft.wake import biot_savart as bs
    numba.set_num_threads(1)
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(n, 3))
    b = np.roll(a, -1, axis=0)                      # a chain: every segment starts where the last ended
    r0 = b - a
    rcl = (0.01 * np.einsum("ij,ij->i", r0, r0)) ** 2
    linked = np.ones(n, dtype=np.bool_)
    linked[0] = False
    cols = [np.ascontiguousarray(x) for x in (*rng.normal(size=(m, 3)).T, *a.T, *b.T, *r0.T)]
    args = (*cols, rng.normal(size=n) / (4 * np.pi), rcl, linked, 1.0, 1e-12)
    fast = numba.njit(parallel=True, fastmath=True)(bs._segment_velocity_chain.py_func)
    rates, outs = {}, {}
    for name, kernel in (("shipped", bs._segment_velocity_chain), ("fastmath", fast)):
        outs[name] = kernel(*args)                  # compile / load
        t0 = time.perf_counter()
        for _ in range(reps):
            kernel(*args)
        rates[name] = reps * m * n / (time.perf_counter() - t0)
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    scale = np.max(np.abs(outs["shipped"]))
    return rates, float(np.max(np.abs(outs["fastmath"] - outs["shipped"])) / scale)


def _kernel_ceiling(t_old, kernel_new):
    """Print the 1-thread bounds a kernel-bound revolution puts on the march's speed-up."""
    rates, diff = fastmath_kernel_ratio()
    gain = rates["fastmath"] / rates["shipped"]
    print(f"velocity kernel, 1 thread: shipped {rates['shipped']:.3e} pairs/s, fastmath build "
          f"{rates['fastmath']:.3e} pairs/s ({gain:.2f}x; largest difference {diff:.1e} of the largest "
          f"velocity: round-off, but every cached run would change)")
    print(f"ceiling on one thread with everything but the velocity kernel free: {t_old / kernel_new:.2f}x "
          f"with the shipped kernel, {t_old * gain / kernel_new:.2f}x with the fastmath build "
          f"(former march {t_old:.3f} s; kernel {kernel_new:.3f} s of the compiled revolution)")


def march_comparison(repeats=3):
    """Print the compiled against the former numpy march: revolution time on 1 and
    2 threads (best of ``repeats``, the two interleaved so that other load on a
    shared machine hits both alike), ratio, kernels' share; the kernel-bound ceiling; the
    data-set estimate."""
    best = {}
    for _ in range(repeats):
        for threads in (1, min(2, numba.config.NUMBA_NUM_THREADS)):
            for compiled in (False, True):
                infl, cpu = [], []
                t, s, _, k = revolution_time(threads, kernel_time=True, compiled=compiled,
                                             influence=infl, cpu=cpu)
                key = (threads, compiled)
                if key not in best or t < best[key][0]:
                    best[key] = (t, k, infl[0], best.get(key, (0, 0, 0, cpu[0]))[3])
                best[key] = best[key][:3] + (min(best[key][3], cpu[0]),)
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    for threads in sorted({k[0] for k in best}):
        (t_old, k_old, i_old, c_old), (t_new, k_new, i_new, c_new) = (best[(threads, False)],
                                                                      best[(threads, True)])
        print(f"coaxial revolution (default resolution), {threads} thread(s): former numpy march "
              f"{t_old:.3f} s (kernel {100 * k_old / t_old:.0f} %, influence {100 * i_old / t_old:.0f} %), "
              f"compiled march {t_new:.3f} s (kernel {100 * k_new / t_new:.0f} %, influence "
              f"{100 * i_new / t_new:.0f} %): {t_old / t_new:.2f}x faster (target >= 3x)"
              + (f"; CPU time {c_old:.3f} s -> {c_new:.3f} s: {c_old / c_new:.2f}x" if threads == 1 else ""))
    t1_old, t1_new = best[(1, False)][0], best[(1, True)][0]
    _kernel_ceiling(t1_old, best[(1, True)][1])
    print(f"12-state coaxial data set, wake part ({DATASET_REVS} revs on 2 workers x 1 thread), "
          f"estimated from the 1-thread revolution: former {DATASET_REVS * t1_old / 2 / 60:.1f} min, "
          f"compiled {DATASET_REVS * t1_new / 2 / 60:.1f} min")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--gpu-only", action="store_true",
                        help="only the GPU figures (and the 2-thread CPU revolution they are compared with)")
    parser.add_argument("--march-only", action="store_true",
                        help="only the compiled-vs-former march comparison (CPU kernel)")
    args = parser.parse_args(argv)
    if args.march_only:
        set_kernel_backend("cpu")
        march_comparison()
        return
    if args.gpu_only:
        gpu_main()
        return
    set_kernel_backend("cpu")                      # the CPU figures are the CPU kernel's
    cores = os.cpu_count() or 2
    print(f"cores visible: {cores} (shared machine: timings include other load)")
    r = pair_rates()
    print(f"Biot-Savart pairs/s: compiled double {r['double']:.3e}, compiled single "
          f"{r['single']:.3e}, numpy {r['numpy']:.3e}; ratio to numpy: double "
          f"{r['double'] / r['numpy']:.1f}x, single {r['single'] / r['numpy']:.1f}x (target >= 50x)")
    march_comparison()
    t_all, s, w, _ = revolution_time(numba.config.NUMBA_NUM_THREADS)
    t_one, _, _, _ = revolution_time(1)
    print(f"coaxial revolution, {math.degrees(s.azimuth_step):g} deg steps, "
          f"{s.wake_revolutions:g}+{s.buffer_revolutions:g} revs of wake, {s.n_elements} elements, "
          f"{s.kernel_precision} kernel: {t_all:.2f} s on {numba.config.NUMBA_NUM_THREADS} threads, "
          f"{t_one:.2f} s on 1 ({t_one / s.steps_per_rev * 1e3:.1f} ms/step)")
    rev_s = 2 * math.pi / w.omega
    sweep_s = 60.0                                  # one sweep record [s]; doublets are short
    n_sweeps, workers, trim_revs = 6, 2, 20
    revs = sweep_s / rev_s
    # run_sweeps: a pool of 2 processes, one kernel thread each, after one trim
    t_proj = math.ceil(n_sweeps / workers) * revs * t_one + trim_revs * t_all
    print(f"projected six-sweep coaxial hover set (6 x {sweep_s:.0f} s records = {revs:.0f} revs "
          f"each, {workers} workers x 1 thread, + {trim_revs}-rev trim): {t_proj / 60:.1f} min "
          f"(target < 10 min)")
    gpu_main()


if __name__ == "__main__":
    main()
