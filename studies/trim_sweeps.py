"""Trim sweeps, hover to maximum speed: controls, attitudes, power and eigenvalues.

Both aircraft are trimmed in level flight at each speed and linearised there
(:func:`aircraft.helicopter.sweep.trim_sweep`):

* ``uh60``: the UH-60-like single rotor with Pitt-Peters inflow and its tail
  rotor, hover to 80 m/s;
* ``coaxial_dynamic_climb``: the coaxial compound at its cruise rotor speed with
  the Dynamic Climb inflow of the main job, hover to 110 m/s (the propeller trims
  the speed at a rotor angle of attack of 2 deg);
* ``coaxial_isolated``: the same aircraft with isolated-rotor inflow (no
  interference), the model the forward-flight study compares against.

A speed whose trim does not converge is a row with ``converged = False`` and the
solver's message, so the tables show where a model has no trim.

The modes are named by their participation factors and followed from speed to
speed (:func:`aircraft.helicopter.mode_tracking.modes_over_speed`): phugoid,
short period, dutch roll (the hover lateral pendulum at low speed), spiral,
roll-flap and the subsidences, each on one track so that a mode that changes
character with speed stays one line in the root-locus figure.

The coaxial's propeller at 200 kt: the default propeller is the uniform-inflow,
small-angle blade-element rotor with the pitch at three-quarter radius; the
blade-element propeller (``HelicopterSettings(propeller_model="blade_element")``)
uses its twist and the exact inflow angles (about 28 deg at three-quarter
radius at 200 kt). ``propeller_200kt.csv`` trims the aircraft at 200 kt with
both, beside the dissertation's rotor thrusts (C_T 0.0073 upper, 0.0065
lower): at the prescribed 2 deg rotor angle of attack the rotors' thrust is
set by the weight and the drag, not by the propeller model, which changes the
propeller's trimmed pitch and power only
(:func:`studies.analysis.propeller_200kt.propeller_models_at_200kt`).

The UH-60-like aircraft is the dissertation's (Appendix B.1: 17,150 lb, C_T
0.0061, uniform blades of 1.73 ft chord, -17 deg linear twist, our own
fuselage, tail and inertia assumptions), not a UH-60A (whose blades carry
SC1095/SC1094R8 sections, a swept tip, -18 deg non-linear twist, a canted
tail rotor and a scheduled stabilator). The only published UH-60A level-flight
trim with readable numbers found is the GENHEL UH-60A simulation's power in
hover and at 80 kt at 16,825 lb, sea level (NASA TM-100991, Table B.1; no
control positions or attitudes): ``uh60a_validation.csv`` trims our aircraft at
that weight and compares its power with the table's two power figures
(engines' output and hub required torque), with the differences explained
(:mod:`studies.analysis.uh60a_validation`). The collective, cyclics and pitch
attitude stay unvalidated against the UH-60A.

Writes ``results/trim_sweeps/``: per case ``trims_<case>.csv`` (controls [deg],
attitudes [deg], power [kW], residual), ``eigenvalues_<case>.csv`` (poles with
their dominant states), ``modes_<case>.csv`` (speed, track, mode name,
eigenvalue, frequency [rad/s], damping, dominant states), ``trims_<case>.png``,
``eigenvalues_<case>.png`` and ``modes_<case>.png`` (root loci, frequency and
damping against speed), ``propeller_200kt.csv``, ``uh60a_validation.csv`` and
``uh60a_validation.png`` (power against NASA TM-100991's GENHEL UH-60A trims).

Run: ``python -m studies.trim_sweeps``
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from aircraft import coaxial_compound, uh60_single_rotor
from aircraft.helicopter import Helicopter
from aircraft.helicopter.mode_tracking import modes_over_speed
from aircraft.helicopter.sweep import trim_sweep
from aircraft.inflow import DynamicClimb, IsolatedRotors, PittPeters
from studies.analysis.propeller_200kt import DISSERTATION_CT_200KT, propeller_models_at_200kt
from studies.analysis.uh60a_validation import plot_uh60a_validation, uh60a_validation

__all__ = ["CASES", "main"]

#: case -> (title, aircraft factory, inflow factory, speeds [m/s])
CASES = {
    "uh60": ("UH-60-like single rotor, Pitt-Peters inflow", uh60_single_rotor, PittPeters,
             np.arange(0.0, 80.1, 5.0)),
    "coaxial_dynamic_climb": ("coaxial compound (cruise rotor speed), Dynamic Climb inflow",
                              lambda: coaxial_compound(cruise=True), DynamicClimb, np.arange(0.0, 110.1, 5.0)),
    "coaxial_isolated": ("coaxial compound (cruise rotor speed), isolated-rotor inflow",
                         lambda: coaxial_compound(cruise=True), IsolatedRotors, np.arange(0.0, 110.1, 5.0)),
}

_MODE_COLUMNS = ["speed", "track", "track_mode", "mode", "physics", "real", "imag", "frequency", "damping",
                 "dominant_states"]


def main(out_dir="results/trim_sweeps"):
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    pd.set_option("display.width", 200)
    tables = {}
    for case, (title, aircraft, inflow, speeds) in CASES.items():
        sweep = trim_sweep(Helicopter(aircraft(), inflow()), speeds)
        tables[case] = sweep.table
        sweep.table.to_csv(out / f"trims_{case}.csv", index=False)
        sweep.eigenvalues.drop(columns=["pole"]).to_csv(out / f"eigenvalues_{case}.csv", index=False)
        sweep.plot(title).savefig(out / f"trims_{case}.png", dpi=120)
        sweep.plot_eigenvalues(title).savefig(out / f"eigenvalues_{case}.png", dpi=120)
        tracked = modes_over_speed(sweep)
        tracked.table[_MODE_COLUMNS].to_csv(out / f"modes_{case}.csv", index=False)
        tracked.plot(title).savefig(out / f"modes_{case}.png", dpi=120)
        t = sweep.table
        print(f"[{case}] {title}: {int(t['converged'].sum())}/{len(t)} speeds trimmed")
        cols = [c for c in ("speed", "delta_col", "delta_lon", "delta_lat", "delta_ped", "delta_prop", "phi",
                            "theta", "power_total") if c in t.columns]
        print(t[t["converged"]][cols].to_string(index=False, float_format=lambda v: f"{v:.2f}"))
        body = tracked.table[(tracked.table["frequency"] < 5.0) & (tracked.table["mode"] != "heading")]
        print(body.pivot_table(index="speed", columns="mode", values="damping", aggfunc="first")
              .to_string(float_format=lambda v: f"{v:.2f}"))
        failed = t[~t["converged"]]["speed"].tolist()
        if failed:
            print(f"  no trim at {failed} m/s")
    prop = propeller_models_at_200kt()
    prop.to_csv(out / "propeller_200kt.csv", index=False)
    print("[coaxial at 200 kt] rotor thrust and propeller with each propeller model")
    print(prop.drop(columns=["CT_U_dissertation", "CT_L_dissertation"]).to_string(
        index=False, float_format=lambda v: f"{v:.5g}"))
    print(f"  dissertation: CT_U {DISSERTATION_CT_200KT[0]}, CT_L {DISSERTATION_CT_200KT[1]}")
    validation = uh60a_validation()
    validation.to_csv(out / "uh60a_validation.csv", index=False)
    plot_uh60a_validation(validation, sweep=tables["uh60"]).savefig(out / "uh60a_validation.png", dpi=120)
    print("[uh60] trimmed power at the reference weight against NASA TM-100991 Table B.1 (GENHEL UH-60A)")
    print(validation[["condition", "speed_kt", "quantity", "ours", "measured", "difference",
                      "relative_difference"]].to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    return out


if __name__ == "__main__":
    main()
