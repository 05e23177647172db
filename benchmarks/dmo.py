"""Benchmark: DMO wall time per case and the independent search's time for the same answer.

Cases: the hand-written hover roll plant, the main job's case A (Dynamic Climb,
u and v held, control phase 90 deg), the same aircraft with the former pairing
(control phase 0), case C (identified 6-state, Eq. 5.3) and the robust case D (DC +
6-state). For each: DMO wall time (target < 60 s on 2 cores) with its global stage's
share, its final crossover and limiting spec, and whether the answer came from the
global stage; for the single-plant cases also the dense search
(controllers.search_designs, K_phi over 0.2-10 x the unit-crossover gain) with its
wall time and best crossover, and the DMO without its global stage (local only).
Run: ``python benchmarks/dmo.py`` (``--quick``: hand plant only).
"""
import argparse
import time
from dataclasses import replace

import pandas as pd

from aircraft import coaxial_compound
from aircraft.helicopter import Helicopter, HelicopterSettings, linearize, trim
from aircraft.helicopter.hold import hold_states
from aircraft.inflow import DynamicClimb, IdentifiedInflow
from aircraft.inflow.published import COAXIAL_HOVER_6STATE, in_rotor_frames
from controllers import (CommandModel, DMOSettings, EMFDesign, PIDGains, default_specs, dmo, hover_roll_plant, roll_design_plant, search_designs)
from controllers.plants import second_order_actuator


def _aircraft(inflow, config=None):
    sys = linearize(trim(Helicopter(config or coaxial_compound(), inflow, HelicopterSettings(n_span=8, n_average=1))))
    return EMFDesign(roll_design_plant(hold_states(sys, ("u", "v"))), PIDGains(0.3, 0.1, 0.05), CommandModel(4.0, 0.7, 0.05),
                     second_order_actuator(35.0, 0.7), sensor_delay=0.01)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--n-scale", type=int, default=15, help="search gains per ray")
    args = parser.parse_args(argv)
    cases = {"hand plant": EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.1, 0.2), actuator=second_order_actuator())}
    if not args.quick:
        cases["A (Dynamic Climb)"] = _aircraft(DynamicClimb())
        cases["A, control phase 0"] = _aircraft(DynamicClimb(), replace(coaxial_compound(), control_phase=0.0))
        cases["C (6-state Eq. 5.3)"] = _aircraft(IdentifiedInflow.from_published(in_rotor_frames(COAXIAL_HOVER_6STATE)))
        # case D as in the main job: DC and 6-state aircraft (with the published
        # 12-state added no start keeps every loop stable), started from case C's design
        robust_plants = [cases["A (Dynamic Climb)"].plant, cases["C (6-state Eq. 5.3)"].plant]
        cases["D (robust: DC, 6-state)"] = robust_plants
    rows, designs = [], {}
    for name, design in cases.items():
        t0 = time.perf_counter()
        labels = ["DC", "6-state"] if isinstance(design, list) else None
        if isinstance(design, list):      # start from the optimised case C design
            design = [designs["C (6-state Eq. 5.3)"].with_plant(p) for p in design]
        result = dmo(design, progress=False, labels=labels)
        designs[name] = result.design
        t_dmo = time.perf_counter() - t0
        row = {"case": name, "DMO wall [s]": t_dmo, "DMO steps": len(result.history),
               "DMO crossover [rad/s]": result.crossover, "from": result.origin.split(",")[0],
               "limiting": ", ".join(result.limiting), "target < 60 s": "met" if t_dmo < 60 else "NOT met"}
        if not isinstance(design, list):
            t1 = time.perf_counter()
            local = dmo(design, settings=DMOSettings(global_samples=0), progress=False)
            row["local-only wall [s]"] = time.perf_counter() - t1
            row["local-only crossover"] = local.crossover
            search = search_designs(design, default_specs(1.5, 0.9), n_scale=args.n_scale, zoom_rounds=2,
                                    scale_span=(0.2, 10.0))
            row.update({"search wall [s]": search.wall_time, "search points": len(search.points),
                        "search crossover [rad/s]": search.crossover,
                        "DMO / search": result.crossover / search.crossover})
        rows.append(row)
        print(f"{name}: DMO {t_dmo:.1f} s -> {result.crossover:.3f} rad/s ({result.message})", flush=True)
    pd.set_option("display.width", 220)
    print(pd.DataFrame(rows).to_string(index=False, float_format=lambda v: f"{v:.4g}"))


if __name__ == "__main__":
    main()
