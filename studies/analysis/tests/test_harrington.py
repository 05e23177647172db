"""Harrington's rotor 2: the configuration from the report's geometry and the comparison plumbing."""
import math

import numpy as np
import pandas as pd
import pytest

from aircraft.configs import FT
from studies.analysis.harrington import (HARRINGTON_BLADE, MOMENTUM_BOUNDS, errors_at_points, faired_curves,
                                         harrington_rotor2, induced_interference, interference, measured_points,
                                         profile_split)


def test_configuration_follows_the_report_geometry():
    cfg = harrington_rotor2(392.0, coaxial=True)
    up, low = cfg.rotors
    # report: R = 12.5 ft, 18 in chord, 2 blades: sigma = 2 x 1.5 / (pi 12.5) = 0.0764 (printed 0.076)
    assert up.radius == pytest.approx(12.5 * FT) and up.solidity == pytest.approx(3.0 / (math.pi * 12.5))
    assert up.omega * up.radius == pytest.approx(392.0 * FT)
    # spacing 2 ft = 0.16 R, upper above (body z down), upper clockwise seen from above
    assert (low.hub_position[2] - up.hub_position[2]) / up.radius == pytest.approx(0.16)
    assert (up.direction, low.direction) == (-1, 1)
    # aerofoil from r = 30 in; t/c = 30.6 - 0.104 r [%] with r in inches: 27.48 % there, 15.0 % at 150 in
    assert up.root_cutout == pytest.approx(0.2)
    assert HARRINGTON_BLADE.thickness == pytest.approx((0.2748, 0.15))
    assert len(harrington_rotor2(262.0, coaxial=False).rotors) == 1


def test_measured_data_are_the_digitised_points_and_curves():
    pts = measured_points()
    # the digitised data: coaxial 8 + 12 points, single 12 + 2
    assert pts.groupby(["configuration", "tip_speed_ft_s"]).size().to_dict() == {
        ("coaxial", 327): 12, ("coaxial", 392): 8, ("single_lower", 262): 12, ("single_lower", 392): 2}
    assert set(faired_curves().configuration) == {"coaxial", "single"}


def test_errors_at_points_interpolate_our_curve():
    # our curve C_Q = k C_T^1.5 sampled every 0.0005: the monotone cubic recovers it
    # between samples to ~1e-3 (its error on this smooth curve is O(h^3))
    ct = np.arange(0.0015, 0.0071, 0.0005)
    ours = pd.DataFrame({"CT": ct, "CQ": 0.8 * ct ** 1.5})
    pts = pd.DataFrame({"CT": [0.00213, 0.00477, 0.009], "CQ": 0.8 * np.array([0.00213, 0.00477, 0.009]) ** 1.5})
    err = errors_at_points(ours, pts)
    assert np.all(np.abs(err.error[:2]) < 1e-3)
    assert np.isnan(err.error[2])                         # beyond our thrusts: no extrapolation
    assert err.in_band.tolist() == [True, True, False]


def test_interference_ratio_of_the_faired_curves_by_hand():
    faired = faired_curves()
    ours = pd.DataFrame({"CT": np.arange(0.0005, 0.0091, 0.0005)})
    ours["CQ"] = ours.CT ** 1.5
    ratio = interference(ours, ours, faired)
    # measured at C_T = 0.004: coaxial faired 0.0004051, single faired at 0.002: 0.0001854
    row = ratio[ratio.CT == 0.004].iloc[0]
    assert row.ratio_measured == pytest.approx(0.0004051 / (2 * 0.0001854), rel=1e-9)
    # ours: C_T^1.5 against 2 (C_T/2)^1.5, i.e. sqrt(2) (interpolation error ~1e-3)
    assert row.ratio_ours == pytest.approx(math.sqrt(2.0), rel=2e-3)


def test_induced_interference_by_hand():
    single = pd.DataFrame({"CT": np.arange(0.0005, 0.0051, 0.00025)})
    single["CQ"] = single.CT ** 1.5 / math.sqrt(2.0)
    coax = pd.DataFrame({"CT": [0.004], "CT_U": [0.0022], "CT_L": [0.0018], "CQ": [1.3e-4]})
    kappa = induced_interference(coax, single).kappa_int.iloc[0]
    assert kappa == pytest.approx(1.3e-4 / ((0.0022 ** 1.5 + 0.0018 ** 1.5) / math.sqrt(2.0)), rel=1e-3)
    # the coplanar bound: total thrust on one disc against two halves in isolation
    assert MOMENTUM_BOUNDS["rotors in one plane"] == pytest.approx(2 ** 1.5 / 2)


def test_profile_split_by_hand():
    # drag-free power: ideal momentum with kappa = 1.15, C_Qi = 1.15 C_T^1.5 / sqrt 2, sampled finely
    inv = pd.DataFrame({"CT": np.arange(0.001, 0.0071, 0.00025)})
    inv["CQ"] = 1.15 * inv.CT ** 1.5 / math.sqrt(2.0)
    # "measured": that plus the profile power of a mean c_d = 0.012 at sigma = 0.076, C_Q0 = sigma c_d / 8;
    # ours: the same with c_d = 0.010
    ct = np.array([0.0025, 0.005])
    pts = pd.DataFrame({"CT": ct, "CQ": 1.15 * ct ** 1.5 / math.sqrt(2.0) + 0.076 * 0.012 / 8})
    ours = inv.assign(CQ=inv.CQ + 0.076 * 0.010 / 8)
    s = profile_split(pts, inv, 0.076, ours=ours)
    # the monotone cubic reproduces C_T^1.5 between samples 0.00025 apart to ~1e-9 in C_Q, i.e. ~1e-7 in c_d
    assert s.cd_eq.to_numpy() == pytest.approx([0.012, 0.012], abs=1e-6)
    assert s.cd_eq_ours.to_numpy() == pytest.approx([0.010, 0.010], abs=1e-6)
    assert s.profile_ratio.to_numpy() == pytest.approx([1.2, 1.2], abs=1e-3)
    # the 5 % window: c_d that moves the power by +-5 % of the measured C_Q, 8 (0.05 C_Q) / sigma either side
    half = 8 * 0.05 * pts.CQ.to_numpy() / 0.076
    assert (s.cd_eq_high - s.cd_eq).to_numpy() == pytest.approx(half, rel=1e-12)
    assert (s.cd_eq - s.cd_eq_low).to_numpy() == pytest.approx(half, rel=1e-12)
    with pytest.raises(ValueError, match="sigma"):
        profile_split(pts, inv, 0.0)
    with pytest.raises(ValueError, match="tolerance"):
        profile_split(pts, inv, 0.076, tolerance=1.5)


@pytest.mark.slow
def test_the_study_runs_small_and_writes_its_files(tmp_path):
    # a coarse wake and three thrusts: the plumbing end to end (numbers not judged)
    import subprocess
    import sys
    done = subprocess.run([sys.executable, "-m", "studies.harrington_hover_power", "--small", "--out",
                           str(tmp_path)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    for name in ("points.csv", "points_classical_blade.csv", "curves.csv", "faired.csv", "interference.csv",
                 "kappa_int.csv", "profile_split.csv", "hover_power.png"):
        assert (tmp_path / name).is_file(), name
    pts = pd.read_csv(tmp_path / "points.csv")
    assert len(pts) == len(measured_points()) and {"CQ_ours", "error", "in_band"} <= set(pts.columns)
    assert set(pd.read_csv(tmp_path / "curves.csv").blade) == {"real", "classical"}
    split = pd.read_csv(tmp_path / "profile_split.csv")
    assert len(split) == len(measured_points()) and {"cd_eq", "cd_eq_low", "cd_eq_high"} <= set(split.columns)
