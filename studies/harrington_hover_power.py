"""Hover power of a full-scale coaxial rotor and of its lower rotor alone, ours against the measured.

Harrington's rotor 2 (NACA TN-2318, 1951: two 2-bladed untwisted rigid rotors,
R = 12.5 ft, spacing 0.16 R, thick symmetric sections) in static thrust: our
free-vortex wake with the real blade of :mod:`studies.analysis.harrington`
(report geometry and published section data, the same inputs at every point),
trimmed to each thrust (the coaxial to equal torques), against the report's
digitised Fig. 8: single rotor at 262 and 392 ft/s, coaxial at 327 and 392 ft/s.
Also the coaxial's power against twice the single rotor's at half its thrust
(ours and measured) and our induced-power interference factor from drag-free
runs beside momentum theory's bounds.

Writes ``results/harrington_hover_power/``: ``points.csv`` (each measured point
with our C_Q at its C_T and the error), ``points_classical_blade.csv`` (the same with the classical blade, constant
``cd0`` = 0.010, for two of the cases), ``curves.csv`` (our trimmed points),
``faired.csv`` (the report's faired curves with ours at the same C_T),
``interference.csv`` (coaxial against twice the single rotor, ours and measured),
``kappa_int.csv`` (our induced-power interference beside momentum theory),
``profile_split.csv`` (each measured point less our drag-free power: the profile power
and mean drag coefficient the data ask of the blade, and the window of it within 5 %),
``hover_power.png``.

Run: ``rotorwake harrington-hover-power`` (about 8 minutes on one core at the
default wake resolution, C_T and C_Q averaged over six revolutions after each trim; ``--small``: a coarse wake and three thrusts, for the tests).
"""
from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np
import pandas as pd

from aircraft.wake import WakeSettings
from studies.analysis.harrington import (INVISCID_BLADE, MOMENTUM_BOUNDS, errors_at_points, faired_curves,
                                         harrington_rotor2, hover_power, induced_interference, interference,
                                         measured_points, profile_split)

#: (configuration, tip speed [ft/s]) of the report's tests
CASES = (("single", 262.0), ("single", 392.0), ("coaxial", 327.0), ("coaxial", 392.0))
#: the cases also run with the classical blade (constant cd0 = 0.010, no thickness, no compressibility)
BASELINE_CASES = (("single", 262.0), ("coaxial", 392.0))


def _inviscid_grid(small, kind):
    """Thrusts of the drag-free runs of the profile split: the comparison band and a little beyond."""
    if small:
        return _grids(True)[kind]
    return _grids(False)[kind] if kind == "single" else np.arange(0.0015, 0.00651, 0.0005)


def _grids(small):
    if small:
        return {"single": np.array([0.001, 0.002, 0.003]), "coaxial": np.array([0.002, 0.004, 0.006])}
    return {"single": np.arange(0.00075, 0.00601, 0.00075), "coaxial": np.arange(0.0015, 0.00901, 0.0005)}


def run(out_dir="results/harrington_hover_power", small=False):
    settings = (WakeSettings(azimuth_step=math.radians(30.0), wake_revolutions=1.0, n_elements=4,
                             far_wake_revolutions=2.0) if small else WakeSettings())
    revs = 1 if small else 6
    grids = _grids(small)
    points, faired = measured_points(), faired_curves()
    curves, errors, against_faired = [], [], []
    for kind, vt in CASES:
        ours = hover_power(harrington_rotor2(vt, kind == "coaxial"), grids[kind], settings, progress=print,
                           average_revs=revs)
        curves.append(ours.assign(configuration=kind, tip_speed_ft_s=vt, blade="real"))
        mine = points[(points.configuration.str.startswith(kind)) & (points.tip_speed_ft_s == vt)]
        errors.append(errors_at_points(ours, mine))
        f = faired[faired.configuration == kind]
        against_faired.append(errors_at_points(ours, f[["CT", "CQ"]]).assign(configuration=kind,
                                                                             tip_speed_ft_s=vt))
    errors = pd.concat(errors, ignore_index=True)
    against_faired = pd.concat(against_faired, ignore_index=True)
    baseline = []
    for kind, vt in BASELINE_CASES:
        ours = hover_power(harrington_rotor2(vt, kind == "coaxial", blade=None), grids[kind], settings,
                           average_revs=revs)
        curves.append(ours.assign(configuration=kind, tip_speed_ft_s=vt, blade="classical"))
        mine = points[(points.configuration.str.startswith(kind)) & (points.tip_speed_ft_s == vt)]
        baseline.append(errors_at_points(ours, mine))
    baseline = pd.concat(baseline, ignore_index=True)
    curves = pd.concat(curves, ignore_index=True)
    real = curves[curves.blade == "real"]
    ratio = interference(real[(real.configuration == "coaxial") & (real.tip_speed_ft_s == 392.0)],
                         real[(real.configuration == "single") & (real.tip_speed_ft_s == 392.0)], faired)
    coax_i = hover_power(harrington_rotor2(392.0, True, INVISCID_BLADE), grids["coaxial"][1::2][:4], settings,
                         average_revs=revs)
    single_i = hover_power(harrington_rotor2(392.0, False, INVISCID_BLADE),
                           np.arange(0.0005, 0.00401, 0.0005), settings, average_revs=revs)
    kappa = induced_interference(coax_i, single_i)
    for name, value in MOMENTUM_BOUNDS.items():
        kappa[f"momentum: {name}"] = value
    split = []
    for kind, vt in CASES:
        inv = hover_power(harrington_rotor2(vt, kind == "coaxial", INVISCID_BLADE), _inviscid_grid(small, kind),
                          settings, average_revs=revs)
        mine = points[(points.configuration.str.startswith(kind)) & (points.tip_speed_ft_s == vt)]
        real_case = real[(real.configuration == kind) & (real.tip_speed_ft_s == vt)]
        split.append(profile_split(mine, inv, float(mine.sigma.iloc[0]), ours=real_case))
    split = pd.concat(split, ignore_index=True)
    split["in_band"] = (split.CT >= 0.002) & (split.CT <= 0.006)

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    errors.to_csv(out / "points.csv", index=False)
    baseline.to_csv(out / "points_classical_blade.csv", index=False)
    curves.to_csv(out / "curves.csv", index=False)
    against_faired.to_csv(out / "faired.csv", index=False)
    ratio.to_csv(out / "interference.csv", index=False)
    kappa.to_csv(out / "kappa_int.csv", index=False)
    split.to_csv(out / "profile_split.csv", index=False)
    _figure(curves, points, faired, errors).savefig(out / "hover_power.png", dpi=90)

    band = errors[errors.in_band]
    print("\nHarrington rotor 2, C_Q error of our wake at each measured point with 0.002 <= C_T <= 0.006:")
    print(band[["configuration", "tip_speed_ft_s", "CT", "CQ", "CQ_ours", "error"]].to_string(
        index=False, float_format=lambda v: f"{v:.5g}"))
    summary = band.groupby(["configuration", "tip_speed_ft_s"]).error.agg(["min", "max", "mean"])
    print(summary.to_string(float_format=lambda v: f"{v:+.3f}"))
    print("the same with the classical blade (constant chord, cd0 = 0.010):")
    print(baseline[baseline.in_band].groupby(["configuration", "tip_speed_ft_s"]).error.agg(["min", "max", "mean"])
          .to_string(float_format=lambda v: f"{v:+.3f}"))
    print("\ncoaxial C_Q / (2 x single C_Q at half the thrust), 392 ft/s:")
    print(ratio.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    print("\nour induced-power interference factor (drag-free sections), 392 ft/s:")
    print(kappa.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    print("\nprofile power the measured points ask of the blade (measured less our drag-free power), as a mean "
          "c_d = 8 C_Q0 / sigma; low/high: the window within 5 %:")
    print(split[split.in_band][["configuration", "tip_speed_ft_s", "CT", "cd_eq", "cd_eq_low", "cd_eq_high",
                                "cd_eq_ours", "profile_ratio"]].to_string(index=False,
                                                                          float_format=lambda v: f"{v:.4g}"))
    return errors


def _figure(curves, points, faired, errors):
    from matplotlib.figure import Figure
    fig = Figure(figsize=(13, 4.2))
    axes = fig.subplots(1, 3)
    colours = {262.0: "C0", 327.0: "C2", 392.0: "C3"}
    for ax, kind in zip(axes[:2], ("single", "coaxial")):
        f = faired[faired.configuration == kind]
        ax.plot(f.CT, f.CQ, "k--", lw=1, label="measured, faired")
        for vt in sorted(curves[curves.configuration == kind].tip_speed_ft_s.unique()):
            c = curves[(curves.configuration == kind) & (curves.tip_speed_ft_s == vt)
                       & (curves.blade == "real")].sort_values("CT")
            p = points[points.configuration.str.startswith(kind) & (points.tip_speed_ft_s == vt)]
            ax.plot(c.CT, c.CQ, "-", color=colours[vt], label=f"ours, {vt:g} ft/s")
            ax.plot(p.CT, p.CQ, "o", mfc="none", color=colours[vt], label=f"measured, {vt:g} ft/s")
            b = curves[(curves.configuration == kind) & (curves.tip_speed_ft_s == vt)
                       & (curves.blade == "classical")].sort_values("CT")
            if len(b):
                ax.plot(b.CT, b.CQ, ":", color=colours[vt], label=f"classical blade, {vt:g} ft/s")
        ax.axvspan(0.002, 0.006, color="0.92", zorder=0)
        ax.set(xlabel="C_T", ylabel="C_Q", title=f"{kind} rotor (totals on one disc)")
        ax.legend(fontsize=7)
    ax = axes[2]
    for (kind, vt), e in errors.groupby(["configuration", "tip_speed_ft_s"]):
        ax.plot(e.CT, 100 * e.error, "o" if kind == "coaxial" else "s", color=colours[vt],
                label=f"{kind} {vt:g} ft/s")
    ax.axhspan(-5, 5, color="0.92", zorder=0)
    ax.axhline(0, color="k", lw=0.5)
    ax.set(xlabel="C_T", ylabel="C_Q ours / measured - 1 [%]", title="error at each measured point")
    ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--small", action="store_true", help="coarse wake, three thrusts (for the tests)")
    parser.add_argument("--out", default="results/harrington_hover_power")
    args = parser.parse_args(argv)
    run(args.out, small=args.small)


if __name__ == "__main__":
    main()
