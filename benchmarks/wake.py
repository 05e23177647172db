"""Free-vortex wake benchmark (run: .venv/bin/python benchmarks/wake.py).

Prints the Biot-Savart pair-interaction rate of the compiled kernel and of the plain
numpy version (same inputs, same run) and their ratio, the wall time of one coaxial
revolution at the default resolution, and the projected wall time of the six-sweep
coaxial hover identification set on 2 cores.
"""
import math
import os
import time

import numpy as np

from aircraft.configs import coaxial_compound
from aircraft.wake import (FreeVortexWake, WakeSettings, segment_velocity,
                           segment_velocity_numpy)


def pair_rates(m=1500, n=1800, seed=0):
    rng = np.random.default_rng(seed)
    tg = rng.normal(size=(m, 3))
    a = rng.normal(size=(n, 3))
    b = a + 0.1 * rng.normal(size=(n, 3))
    g = rng.normal(size=n)
    rc = np.full(n, 0.05)
    segment_velocity(tg[:10], a, b, g, rc)          # compile / load cache
    reps = 5
    t0 = time.perf_counter()
    for _ in range(reps):
        segment_velocity(tg, a, b, g, rc)
    fast = reps * m * n / (time.perf_counter() - t0)
    mm = 200
    t0 = time.perf_counter()
    segment_velocity_numpy(tg[:mm], a, b, g, rc)
    slow = mm * n / (time.perf_counter() - t0)
    return fast, slow


def main():
    print(f"cores visible: {os.cpu_count()} (machine shared; timings inflated by other load)")
    fast, slow = pair_rates()
    print(f"Biot-Savart pairs/s: compiled {fast:.3e}, numpy {slow:.3e}, ratio {fast / slow:.1f}x")
    s = WakeSettings()      # default: 10 deg steps, 4 + 1 (buffer) revs, 10 elements
    w = FreeVortexWake(coaxial_compound(), s)
    w.controls.update(theta0_U=0.16, theta0_L=0.17)
    w.march(s.steps_per_rev)                                   # warm up
    t0 = time.perf_counter()
    w.march(s.steps_per_rev)
    t_rev = time.perf_counter() - t0
    print(f"coaxial revolution, 10 deg, {s.wake_revolutions:g}+{s.buffer_revolutions:g} revs of "
          f"wake, {s.n_elements} elements: {t_rev:.2f} s "
          f"({t_rev / s.steps_per_rev * 1e3:.1f} ms/step)")
    rev_s = 2 * math.pi / w.omega
    sweep_s = 60.0                                  # one sweep record [s] (+ doublets small)
    n_sweeps = 6
    runs_per_core = math.ceil(n_sweeps / 2)
    trim_revs = 20
    # each worker process runs with one core
    t_proj = runs_per_core * sweep_s / rev_s * t_rev * (os.cpu_count() or 2) / 1 + trim_revs * t_rev
    print(f"projected six-sweep coaxial hover set (6 x {sweep_s:.0f} s records = "
          f"{sweep_s / rev_s:.0f} revs each, 2 workers, one core each, + {trim_revs}-rev trim): "
          f"{t_proj / 60:.1f} min (target < 10 min); dominated by the Biot-Savart evaluation "
          "of the free markers (2 per step, predictor + corrector)")


if __name__ == "__main__":
    main()
