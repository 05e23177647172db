"""Benchmark: four-axis EMF design (roll, pitch, yaw, heave) of the coaxial in hover.

The full linear aircraft (Dynamic Climb inflow, 31 states; translational drift u, v
held by an assumed outer loop, as the single-axis hover designs hold it) with one EMF
loop per axis closed simultaneously, tuned by :func:`controllers.multi_axis_design.design_multi_axis`
(sequential loop closure with the single-axis DMO, repeated until the gains move < 1 %),
the open-loop onset point graded with the assumed hover actuator limits (the design's default).
Prints the wall time (target < 5 min on 2 cores), the per-axis table and the
inter-axis coupling of the final closed loop.
Run: ``python benchmarks/multi_axis.py`` (``--free-drift`` leaves u and v free;
``--figures DIR`` saves one HQ window per axis; ``--joint-check`` also times
:func:`controllers.multi_axis_joint.joint_check` with the hover study's budget: its
global stage and its local constrained search over all twelve gains, candidates per
second of each).
"""
import argparse
import time

import pandas as pd

from aircraft import coaxial_compound
from aircraft.helicopter import Helicopter, TrimCondition, linearize, trim
from aircraft.helicopter.hold import hold_states
from aircraft.inflow import DynamicClimb
from controllers.multi_axis_design import design_multi_axis


def coaxial_hover_plant(free_drift=False):
    """The coaxial's hover linear model, u and v held unless ``free_drift``."""
    sys = linearize(trim(Helicopter(coaxial_compound(), DynamicClimb()), TrimCondition(speed=0.0)))
    return sys if free_drift else hold_states(sys, ["u", "v"])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--free-drift", action="store_true")
    parser.add_argument("--figures", default=None, help="folder for the HQ windows (PNG)")
    parser.add_argument("--joint-check", action="store_true",
                        help="also time the joint check (12 generations of 32, then 200 local evaluations)")
    args = parser.parse_args(argv)
    t0 = time.perf_counter()
    plant = coaxial_hover_plant(args.free_drift)
    t_model = time.perf_counter() - t0
    result = design_multi_axis(plant, progress=True)
    t_total = time.perf_counter() - t0
    pd.set_option("display.width", 200)
    pd.set_option("display.max_colwidth", 60)
    print(result.history.drop(columns="message").to_string())
    print(result.to_pandas().T.to_string())
    print(result.coupling().to_string())
    for axis, msg in result.messages.items():
        print(f"{axis}: {msg}")
    print(f"converged: {result.converged} after {result.sweeps} sweep(s)")
    if args.figures:
        import pathlib
        out = pathlib.Path(args.figures)
        out.mkdir(parents=True, exist_ok=True)
        for axis, fig in result.plot().items():
            fig.savefig(out / f"hq_window_{axis}.png", dpi=110)
    print(f"model {t_model:.1f} s; four-axis design {result.wall_time:.1f} s; total {t_total:.1f} s "
          f"(target < 300 s on 2 cores: {'met' if t_total < 300 else 'NOT met'})")
    if args.joint_check:
        from controllers.multi_axis_joint import joint_check
        t1 = time.perf_counter()
        glob = joint_check(result, maxiter=12, popsize=2, seed=1)
        t_global = time.perf_counter() - t1
        t1 = time.perf_counter()
        both = joint_check(result, maxiter=12, popsize=2, seed=1, local_evaluations=200)
        t_local = time.perf_counter() - t1 - t_global      # the same global stage again, then the local one
        n_local = both.local_evaluations
        print(f"joint check: global stage {glob.evaluations} candidates in {t_global:.1f} s "
              f"({glob.evaluations / t_global:.1f}/s, best smallest ratio {glob.min_ratio:.4f}); local stage "
              f"{n_local} candidates in {t_local:.1f} s ({n_local / max(t_local, 1e-9):.1f}/s, best smallest ratio "
              f"{both.local_min_ratio:.4f}); dominated: {both.dominated}")


if __name__ == "__main__":
    main()
