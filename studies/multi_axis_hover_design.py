"""Four-axis hover control design: each axis's HQ window, actuator limits in the OLOP, a global check.

The full linear aircraft in hover -- the coaxial (Dynamic Climb inflow) or, with
``--aircraft single-rotor``, the UH-60-like single rotor (Pitt-Peters inflow);
translational drift u, v held by an assumed outer loop, as the single-axis hover
designs hold it -- with one EMF loop per axis (roll, pitch, yaw, heave) closed simultaneously,
tuned by :func:`controllers.design_multi_axis` (sequential loop closure with the
single-axis DMO and its multistart stage, repeated until the gains settle). The open-loop onset point
(OlpOpG1) is graded with the actuators' rate and travel limits and a full-stick
sinusoid (:data:`controllers.actuator_limits.LIMITS_ASSUMPTIONS`: assumed values,
none is printed for this aircraft). Then :func:`controllers.multi_axis_check.global_check`
hands each axis's design plant and specs to an independent differential-evolution
search over the same three gains, seeded differently from every seed the DMO uses,
and asks whether it can beat the DMO's crossover (a tie is within 1 %). With
``--joint-check`` (on by default) :func:`controllers.multi_axis_joint.joint_check` searches every
axis's gains at once, every loop graded on its own specs, and asks whether the
design is dominated: every axis crossing more than 1 % higher, every spec met; its
local stage (``--joint-local``, 200 evaluations by default) then runs the joint
constrained NLP over all twelve gains from the best point found.

Files under ``results/multi_axis_hover_design/`` (coaxial) or
``results/multi_axis_hover_design_single_rotor/``, written by
:func:`controllers.multi_axis_report.write_multi_axis_report`:

* ``axes.csv``: per axis the gains, crossover, DRB, DRP, GM/PM, OLOP margin and
  onset frequency, specs met, unmet and limiting specs (simultaneous closed loop);
* ``specs.csv``: every spec of every axis on the simultaneous closed loop;
* ``limits.csv``: the actuator limits and full-stick amplitude of each axis;
* ``limits_assumptions.csv``: the assumptions behind those limits, with their reasons;
* ``coupling.csv``: inter-axis coupling of the closed loop (peak-gain and step ratios);
* ``sweeps.csv``: the sequential loop closure, sweep by sweep;
* ``global_check.csv``: DMO against the global search, per axis;
* ``joint_check.csv``: the joint search's crossovers per axis and its verdict (with ``--joint-check``);
* ``hq_window_<axis>.png``: one HQ window per axis.

Run: ``rotorwake multi-axis-hover-design`` and ``rotorwake multi-axis-hover-design-single-rotor``.
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

import pandas as pd

from aircraft import coaxial_compound, uh60_single_rotor
from aircraft.helicopter import Helicopter, TrimCondition, linearize, trim
from aircraft.helicopter.hold import hold_states
from aircraft.inflow import DynamicClimb, PittPeters
from controllers import design_multi_axis
from controllers.multi_axis_check import global_check
from controllers.multi_axis_joint import joint_check
from controllers.multi_axis_report import multi_axis_summary, write_multi_axis_report

__all__ = ["AIRCRAFT", "CHECK_SEED", "hover_plant", "add_check_arguments", "run_checks", "main"]


#: aircraft -> (configuration, inflow model) of the hover plant
AIRCRAFT = {"coaxial": (coaxial_compound, DynamicClimb), "single-rotor": (uh60_single_rotor, PittPeters)}
#: seed of the global check's search: the DMO uses DMOSettings.seed (0) for its samples and starts
CHECK_SEED = 7


def hover_plant(aircraft="coaxial"):
    """The hover linear model (coaxial: Dynamic Climb; single rotor: Pitt-Peters), u and v held."""
    config, inflow = AIRCRAFT[aircraft]
    return hold_states(linearize(trim(Helicopter(config(), inflow()), TrimCondition(speed=0.0))), ["u", "v"])


def add_check_arguments(parser):
    """The options of the checks every multi-axis study runs: the per-axis global search and the
    joint check (global and local stages)."""
    parser.add_argument("--search-iterations", type=int, default=15, help="global search: generations")
    parser.add_argument("--search-population", type=int, default=6, help="global search: population per gain")
    parser.add_argument("--search-seed", type=int, default=CHECK_SEED,
                        help="global search: seed (keep it different from the DMO's)")
    parser.add_argument("--joint-check", action=argparse.BooleanOptionalAction, default=True,
                        help="also search every axis's gains at once (joint check: is the design dominated?)")
    parser.add_argument("--joint-iterations", type=int, default=12, help="joint check: generations")
    parser.add_argument("--joint-population", type=int, default=2, help="joint check: population per gain")
    parser.add_argument("--joint-local", type=int, default=200,
                        help="joint check: evaluations of its local constrained search over every gain (0: none)")


def run_checks(result, args, out):
    """Run the global and (with ``--joint-check``) joint checks on ``result``, write the report
    to ``out`` and print both; return ``(check, joint or None)``."""
    check = global_check(result, maxiter=args.search_iterations, popsize=args.search_population,
                         seed=args.search_seed, progress=True)
    joint = (joint_check(result, maxiter=args.joint_iterations, popsize=args.joint_population,
                         seed=args.search_seed, local_evaluations=args.joint_local, progress=True)
             if args.joint_check else None)
    write_multi_axis_report(result, out, check=check, joint=joint)
    print(multi_axis_summary(result, check, design=False))
    if joint is not None:
        print(joint.to_pandas()[["dmo_crossover", "joint_crossover", "ratio", "dominated", "points",
                                 "feasible_points", "local_points", "local_min_ratio", "wall_s"]]
              .to_string(float_format="{:.3g}".format))
    return check, joint


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--aircraft", choices=sorted(AIRCRAFT), default="coaxial", help="aircraft designed")
    parser.add_argument("--out", default=None,
                        help="results folder (default results/multi_axis_hover_design, with _single_rotor "
                             "appended for the single rotor)")
    parser.add_argument("--max-sweeps", type=int, default=3, help="most sweeps of the sequential loop closure")
    add_check_arguments(parser)
    args = parser.parse_args(argv)
    out = Path(args.out or "results/multi_axis_hover_design" + ("" if args.aircraft == "coaxial" else
                                                                "_single_rotor"))
    out.mkdir(parents=True, exist_ok=True)
    pd.set_option("display.width", 200)
    t0 = time.perf_counter()
    result = design_multi_axis(hover_plant(args.aircraft), max_sweeps=args.max_sweeps, limits="hover", progress=True)
    print(multi_axis_summary(result))
    run_checks(result, args, out)
    print(f"total {time.perf_counter() - t0:.0f} s")
    return out


if __name__ == "__main__":
    main()
