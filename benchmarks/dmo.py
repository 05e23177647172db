"""Benchmark: a full design-margin optimisation on the hand-written hover roll plant.

Prints the wall time (target < 60 s on 2 cores), the DMO history, the final
gains, crossover, DRB and the limiting spec.
"""
import time

import pandas as pd

from controllers import EMFDesign, PIDGains, default_specs, dmo, evaluate_specs, hover_roll_plant, \
    second_order_actuator


def main():
    design = EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.1, 0.2), actuator=second_order_actuator())
    t0 = time.perf_counter()
    result = dmo(design, progress=False)
    wall = time.perf_counter() - t0
    pd.set_option("display.width", 160)
    print("== DMO benchmark: hover roll plant with a regressive flap mode (11.9 rad/s, zeta 0.175) ==")
    print(result.history.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    g = result.design.gains
    last = result.history[result.history.feasible].iloc[-1]
    table = evaluate_specs(result.design, default_specs(last.crossover_min, last.drb_min)).set_index("spec")
    print(f"final gains: K_phi = {g.K_phi:.4g}, K_Iphi = {g.K_Iphi:.4g}, K_p = {g.K_p:.4g}; "
          f"tau_eq = {result.design.equivalent_delay:.4g} s")
    print(f"crossover {table.loc['CrsMnG2', 'value']:.3f} rad/s, DRB {table.loc['DrbRoH1', 'value']:.3f} rad/s, "
          f"DRP {table.loc['DrpAvH1', 'value']:.2f} dB, GM {table.loc['StbMgG1.GM', 'value']:.2f} dB, "
          f"PM {table.loc['StbMgG1.PM', 'value']:.1f} deg")
    print(result.message)
    print(f"DMO wall time: {wall:.2f} s (target < 60 s -> {'met' if wall < 60 else 'NOT met'})")


if __name__ == "__main__":
    main()
