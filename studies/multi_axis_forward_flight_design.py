"""Four-axis control design of the coaxial compound in forward flight, with its propeller.

The coaxial compound trimmed at :data:`SPEED` (50 m/s, about 97 kt) with Dynamic
Climb inflow (the hover study's inflow model) and its pusher propeller in the
trim; the full linear aircraft, with the forward speed u held by an assumed
outer loop (the propeller's speed hold: on a compound the propeller, not the
pitch attitude, sets the speed) and the sideslip v left free. One EMF loop per
axis is closed simultaneously and tuned by :func:`controllers.design_multi_axis`
with ``speed="forward"``: every axis's specs come from :func:`controllers.specs_for`
for the forward-flight regime (:func:`controllers.hq.selector.flight_regime` of
the speed), so the hover/low-speed charts drop out and the forward-flight ones
(dutch roll and spiral, MIL-F-8785C proxies, graded on the modes of the aircraft
with its feedback loops closed) come in; forward-flight charts whose boundaries
were not found printed (attitude bandwidth, phugoid) are skipped and listed in
``skipped_specs.csv``.

At this speed the aircraft has a pitch-heave divergence (M_w > 0) that only the
pitch loop removes: the loops are closed pitch first, and every loop is closed at
:data:`START_GAINS` from the first sweep (``start_closed``), so that no axis is
designed on a plant it cannot stabilise.

The loops couple: the vertical-rate loop on the collective moves the pitch loop's
unstable pole out (about 0.5 1/s with the other loops open, over 1.5 1/s with the
heave loop at its own highest crossover), beyond what any pitch gains can hold
with Level 1 margins; designed each against its own specs alone, the heave loop
takes the pitch axis's margins away. So every axis is also tuned against the
other closed loops' stability margins on the whole aircraft
(``guard_other_axes``, :mod:`controllers.multi_axis_guard`): a loop closed around
an unstable plant (here pitch) keeps its Level 1 margins, the others their Level 2
ones (the next sweep re-tunes them). The global check grades the same guards
(:func:`controllers.multi_axis_check.global_check` follows the design), and the
joint check (:func:`controllers.multi_axis_joint.joint_check`, ``--joint-check``,
on by default) searches every axis's gains at once with every loop graded on its
own specs on the simultaneous closed loop, then runs its local constrained search
over all twelve gains from the best point found (``--joint-local`` evaluations).

Commanded responses, the ones a forward-flight explicit-model-following design uses
within the library's four channels:

* roll and pitch: attitude command / attitude hold (bank angle for turns, pitch
  attitude for the flight path, with the propeller holding the speed);
* yaw: sideslip-rate command / sideslip hold on the pedals
  (:func:`aircraft.helicopter.hold.sideslip_yaw_channel`: the yaw channel reads the
  nose's angle from the flight path, -beta, and its rate); a heading hold on the
  pedals was tried first and rejected: at this speed any heading feedback on the
  pedals gives a real unstable pole (the heading changes through bank, not pedal),
  and the heading, an ignorable coordinate, is held out of the model;
* heave: vertical-rate command on the collective: with the pitch attitude held
  by its loop and u by the propeller, the body vertical velocity -w is the
  rate of climb (hdot = -w + U theta to first order), so this is the flight-path
  (vertical rate) hold.

Why 50 m/s: with Dynamic Climb inflow the linear model at 60 m/s has a pair of
unstable rotor-inflow modes near 51 rad/s (a model artefact above the actuator
bandwidth that no control law should be tuned around) and the trim does not
converge at 70 m/s; at 50 m/s the only unstable modes are slow ones (with u
held, the pitch-heave divergence, near 0.5 1/s) that the loops are there to
stabilise, and the speed is well above the 45 kt boundary of the forward-flight specs.

Files under ``results/multi_axis_forward_flight_design/``: the hover study's
``axes.csv``, ``specs.csv``, ``limits.csv``, ``coupling.csv``, ``sweeps.csv``,
``global_check.csv``, ``joint_check.csv`` and ``hq_window_<axis>.png``, plus ``trim.csv`` (the trim
condition and the open-loop unstable poles) and ``skipped_specs.csv``.
The actuator limits and full-stick commands of the OLOP are the hover study's
assumptions (:data:`controllers.actuator_limits.LIMITS_ASSUMPTIONS`).

Run: ``rotorwake multi-axis-forward-flight-design``.
"""
from __future__ import annotations

import argparse
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
import pandas as pd

from aircraft import coaxial_compound
from aircraft.helicopter import Helicopter, TrimCondition, linearize, trim
from aircraft.helicopter.hold import hold_states, sideslip_yaw_channel
from aircraft.inflow import DynamicClimb
from controllers import PIDGains, design_multi_axis, specs_for
from controllers.hq.selector import flight_regime
from controllers.multi_axis_design import DEFAULT_SETTINGS
from controllers.multi_axis_report import multi_axis_summary
from studies.multi_axis_hover_design import add_check_arguments, run_checks

__all__ = ["SPEED", "HELD", "AXES", "START_GAINS", "SETTINGS", "forward_flight_plant", "skipped_specs", "main"]

#: trim airspeed [m/s] (about 97 kt): see the module docstring for why not faster
SPEED = 50.0
#: states held: u by the propeller's speed hold (an assumed outer loop); psi is ignorable (its column of
#: the body-axis model is zero), so holding it only removes the heading integrator's pole at the origin
HELD = ("u", "psi")
#: order of the sequential loop closure: pitch first, the axis that removes the pitch-heave divergence
AXES = ("pitch", "roll", "heave", "yaw")
#: gains every loop is closed at from the first sweep (start_closed): together they stabilise the
#: aircraft with the modes of 0.5-4 and 4-20 rad/s damped above the EigDpG1 Level 1 lines, so that no
#: axis starts on a plant whose other loops leave a whole-aircraft spec unmet (found by a seeded random
#: search over the pitch and roll gains, then the pitch rate gain lowered; heave gains per metre are small)
#: DMO settings: the multi-axis default with the optimiser-vs-python-control gain-margin check widened from
#: 0.5 to 2 dB: on the roll loop at this speed the two pick different phase crossings (exact 12.0 dB against
#: python-control's 10.8 dB, both above the 6 dB Level 1 line); the final table's margins are python-control's
SETTINGS = replace(DEFAULT_SETTINGS, verify_tolerance_db=2.0)
START_GAINS = {"pitch": PIDGains(0.6, 0.3, 0.1), "roll": PIDGains(0.17, 0.079, 0.054),
               "yaw": PIDGains(1.0, 0.3, 1.0), "heave": PIDGains(0.003, 0.0003, 0.003)}


def forward_flight_plant(speed=SPEED):
    """The coaxial compound's linear model at ``speed`` [m/s] (Dynamic Climb, propeller trimmed).

    The yaw channel reads sideslip (:func:`~aircraft.helicopter.hold.sideslip_yaw_channel`);
    u and psi held (:data:`HELD`).

    Returns
    -------
    (control.StateSpace, TrimResult)
    """
    tr = trim(Helicopter(coaxial_compound(), DynamicClimb()), TrimCondition(speed=float(speed)))
    return hold_states(sideslip_yaw_channel(linearize(tr), float(speed)), list(HELD)), tr


def skipped_specs(regime):
    """Per axis, the applicable specs of ``regime`` left out because their boundaries were not found printed."""
    rows = []
    for axis in ("roll", "pitch", "yaw", "heave"):
        for s in specs_for(axis, speed=regime, missing="keep"):
            # the OLOP's missing input (actuator limits) is supplied by the design: not skipped
            if not s.available and not s.missing_input:
                rows.append({"axis": axis, "spec": s.name, "description": s.description, "why": s.source})
    return pd.DataFrame(rows)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--out", default="results/multi_axis_forward_flight_design", help="results folder")
    parser.add_argument("--speed", type=float, default=SPEED, help="trim airspeed [m/s]")
    # the guarded loop closure settles in five sweeps at this speed (the largest relative gain
    # change after three is still above the one-per-cent tolerance); six leave one in hand
    parser.add_argument("--max-sweeps", type=int, default=6, help="most sweeps of the sequential loop closure")
    add_check_arguments(parser)
    args = parser.parse_args(argv)
    regime = flight_regime(args.speed)
    if regime != "forward":
        parser.error(f"--speed {args.speed} m/s is in the hover/low-speed regime: use multi-axis-hover-design")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    pd.set_option("display.width", 200)
    t0 = time.perf_counter()
    plant, tr = forward_flight_plant(args.speed)
    poles = np.linalg.eigvals(plant.A)
    unstable = poles[poles.real > 0]
    pd.DataFrame({"speed_m_s": args.speed, "regime": regime, "held": ", ".join(HELD),
                  "unstable_open_loop_poles": "; ".join(f"{p:.3g}" for p in unstable)}, index=[0]).to_csv(
        out / "trim.csv", index=False)
    skipped = skipped_specs(regime)
    skipped.to_csv(out / "skipped_specs.csv", index=False)
    result = design_multi_axis(plant, axes=AXES, start_gains=START_GAINS, start_closed=True, settings=SETTINGS,
                               max_sweeps=args.max_sweeps, limits="hover", speed=regime, progress=True,
                               guard_other_axes=True)
    print(f"{args.speed:g} m/s ({regime}), {', '.join(HELD)} held; open-loop unstable poles: "
          f"{', '.join(f'{p:.3g}' for p in unstable)}")
    print("skipped (not found printed):", ", ".join(sorted(set(skipped.spec))) if len(skipped) else "none")
    print(multi_axis_summary(result))
    run_checks(result, args, out)
    print(f"total {time.perf_counter() - t0:.0f} s")
    return out


if __name__ == "__main__":
    main()
