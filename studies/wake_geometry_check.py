"""Hover tip-vortex trajectory of our free wake against Landgrebe's measured generalised wake.

The UH-60-like single rotor (4 blades, linear twist) is trimmed in hover at three
thrusts with the default wake settings and with the rigid near wake contracted by
Landgrebe's law (``WakeSettings.near_wake_contraction``); the tip-vortex markers,
averaged over the blades and over revolutions after trim, are compared with
Landgrebe's empirical fit to smoke-flow measurements of model rotors (J. American
Helicopter Society 17(4), 1972; as given by Leishman, Principles of Helicopter
Aerodynamics, Sec. 10.7) -- see :mod:`studies.analysis.wake_geometry`.

Writes ``results/wake_geometry_check/``: ``trajectory.csv`` (per variant, thrust
and wake age: r/R and z/R ours and Landgrebe's and their differences),
``summary.csv`` (per variant and thrust: r/R at the first blade passage and
averaged over the second revolution of age, descent rates k1 and k2 fitted to our
markers beside Landgrebe's), ``sensitivity.csv`` (the same at the middle thrust
with one wake setting changed at a time: what moves the trajectory),
``trajectory.png``.

Run: ``rotorwake wake-geometry-check`` (about two minutes: eleven hover trims;
``--small``: a coarse, short wake at one thrust, for the tests).
"""
from __future__ import annotations

import argparse
import math
from pathlib import Path

import pandas as pd

from aircraft.configs import uh60_single_rotor
from aircraft.wake import WakeSettings

from studies.analysis.wake_geometry import tip_vortex_geometry

__all__ = ["CT_VALUES", "VARIANTS", "SENSITIVITY", "run", "main"]

CT_VALUES = (0.004, 0.006, 0.008)
VARIANTS = {"default": {}, "contracted near wake": {"near_wake_contraction": True}}
#: one setting changed from the default at the middle thrust: what moves the trajectory
SENSITIVITY = {"peak tip-vortex circulation": {"tip_vortex_strength": "peak"},
               "free wake 8 rev": {"wake_revolutions": 8.0},
               "core radius 3x": {"core_radius": 0.30},
               "near wake 30 deg": {"near_wake_extent": math.radians(30.0)},
               "azimuth step 5 deg": {"azimuth_step": math.radians(5.0)}}


def run(out_dir="results/wake_geometry_check", small=False):
    base, cts, kw, sensitivity = {}, CT_VALUES, {}, SENSITIVITY
    if small:
        base = dict(azimuth_step=math.radians(30.0), wake_revolutions=1.0, n_elements=3, far_wake_revolutions=2.0)
        cts, kw = (0.006,), dict(settle_revs=1, average_revs=0.5, far_window=(math.pi, 2 * math.pi))
        sensitivity = {"core radius 3x": {"core_radius": 0.30}}
    results = {name: tip_vortex_geometry(uh60_single_rotor(), cts, WakeSettings(**base, **changes),
                                         progress=not small, **kw)
               for name, changes in VARIANTS.items()}
    middle = cts[len(cts) // 2]
    sens = [results["default"].summary[results["default"].summary.ct == middle].assign(change="none")]
    for name, changes in sensitivity.items():
        g = tip_vortex_geometry(uh60_single_rotor(), [middle], WakeSettings(**{**base, **changes}),
                                progress=not small, **kw)
        sens.append(g.summary.assign(change=name))
    sens = pd.concat(sens, ignore_index=True)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    table = pd.concat([g.table.assign(variant=name) for name, g in results.items()], ignore_index=True)
    summary = pd.concat([g.summary.assign(variant=name) for name, g in results.items()], ignore_index=True)
    first = ["variant"]
    table[first + [c for c in table.columns if c not in first]].to_csv(out / "trajectory.csv", index=False)
    summary = summary[first + [c for c in summary.columns if c not in first]]
    summary.to_csv(out / "summary.csv", index=False)
    sens = sens[["change"] + [c for c in sens.columns if c != "change"]]
    sens.to_csv(out / "sensitivity.csv", index=False)
    names = list(results)
    results[names[0]].plot(results[names[1]], labels=tuple(names)).savefig(out / "trajectory.png", dpi=90)
    print("hover tip-vortex geometry, UH-60-like rotor: ours against Landgrebe (1972)")
    shown = ["variant", "ct", "r_blade_passage_ours", "r_blade_passage_landgrebe", "r_far_ours", "r_far_landgrebe",
             "k1_ours", "k1_landgrebe", "k2_ours", "k2_landgrebe"]
    print(summary[shown].to_string(index=False, float_format=lambda v: f"{v:.4f}"))
    print(f"one setting changed at C_T = {middle}:")
    print(sens[["change"] + shown[2:]].to_string(index=False, float_format=lambda v: f"{v:.4f}"))
    return table, summary, sens


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--small", action="store_true", help="coarse, short wake at one thrust (for the tests)")
    parser.add_argument("--out", default="results/wake_geometry_check")
    args = parser.parse_args(argv)
    run(args.out, small=args.small)


if __name__ == "__main__":
    main()
