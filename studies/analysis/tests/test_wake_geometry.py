"""Landgrebe's generalised hover wake (hand-computed values) and the trimmed-wake comparison."""
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from aircraft.configs import uh60_single_rotor
from aircraft.wake import WakeSettings
from studies.analysis.wake_geometry import (CONTRACTION_A, landgrebe_descent_rates, landgrebe_height,
                                            landgrebe_radius, tip_vortex_geometry)

ROOT = Path(__file__).resolve().parents[3]
COARSE = WakeSettings(azimuth_step=math.radians(30.0), wake_revolutions=1.0, n_elements=3,
                      far_wake_revolutions=2.0)


def test_radius_against_hand_values():
    # C_T = 0.008: Lambda = 0.145 + 27 * 0.008 = 0.361; at psi_w = 2 rad
    # r/R = 0.78 + 0.22 exp(-0.722) = 0.78 + 0.22 * 0.485778 = 0.886871 (hand, 6 digits)
    r = landgrebe_radius([0.0, 2.0, 1e3], 0.008)
    assert r[0] == 1.0
    assert r[1] == pytest.approx(0.886871, abs=2e-6)      # hand value rounded to 6 digits
    assert r[2] == pytest.approx(CONTRACTION_A, abs=1e-12)  # exp(-361) underflows to the asymptote
    assert np.ndim(landgrebe_radius(1.0, 0.008)) == 0


def test_descent_rates_against_hand_values():
    # C_T = 0.005, sigma = 0.1, twist -8 deg:
    # k1 = -0.25 (0.05 - 0.008) = -0.0105
    # k2 = -(1.41 - 0.1128) sqrt(0.0025) = -1.2972 * 0.05 = -0.06486
    k1, k2 = landgrebe_descent_rates(0.005, 0.1, 2, -8.0)
    assert k1 == pytest.approx(-0.0105, abs=1e-15)
    assert k2 == pytest.approx(-0.06486, abs=1e-15)
    # untwisted: k2 = -1.41 sqrt(C_T / 2), the wake's descent at 1.41 lambda_h
    assert landgrebe_descent_rates(0.005, 0.1, 2, 0.0)[1] == pytest.approx(-1.41 * 0.05, abs=1e-15)


def test_height_two_rates_and_continuity():
    ct, sigma, nb, tw = 0.005, 0.1, 2, -8.0
    zb = math.pi                      # first blade passage of a 2-bladed rotor
    z = landgrebe_height([0.5 * zb, zb, zb + 1.0], ct, sigma, nb, tw)
    # hand: k1 zb / 2, k1 zb, k1 zb + k2 * 1 with the rates above
    assert z == pytest.approx([-0.0105 * zb / 2, -0.0105 * zb, -0.0105 * zb - 0.06486], abs=1e-12)


@pytest.mark.parametrize("call, match", [
    (lambda: landgrebe_radius(-0.1, 0.006), "age"),
    (lambda: landgrebe_radius([1.0, np.nan], 0.006), "age"),
    (lambda: landgrebe_radius(1.0, 0.0), "ct"),
    (lambda: landgrebe_radius(1.0, 0.5), "ct"),
    (lambda: landgrebe_descent_rates(0.006, -0.1, 4, 0.0), "sigma"),
    (lambda: landgrebe_descent_rates(0.006, 0.08, 0, 0.0), "n_blades"),
    (lambda: landgrebe_descent_rates(0.006, 0.08, 2.5, 0.0), "n_blades"),
    (lambda: landgrebe_descent_rates(0.006, 0.08, 4, math.nan), "twist_deg"),
    (lambda: landgrebe_height(1.0, 0.006, 0.08, 4, -90.0), "twist_deg"),
    (lambda: tip_vortex_geometry(uh60_single_rotor(), [], COARSE), "ct_values"),
    (lambda: tip_vortex_geometry(uh60_single_rotor(), [0.006], COARSE, far_window=(2.0, 1.0)), "far_window"),
    (lambda: tip_vortex_geometry(uh60_single_rotor(), [0.006], COARSE, average_revs=0.0), "average_revs"),
])
def test_validation_errors(call, match):
    with pytest.raises(ValueError, match=match):
        call()


@pytest.fixture(scope="module")
def coarse_geometry():
    return tip_vortex_geometry(uh60_single_rotor(), [0.006], COARSE, settle_revs=2, average_revs=0.5,
                               far_window=(math.pi, 2 * math.pi))


def test_end_to_end_on_a_coarse_wake(coarse_geometry):
    g = coarse_geometry
    t, s = g.table, g.summary.iloc[0]
    assert s.ct_trimmed == pytest.approx(0.006, rel=0.02)   # trim tolerance plus half a revolution's ripple
    # only the free wake: from the end of the 60 deg near wake over one revolution, 30 deg apart
    assert t.age_deg.iloc[0] == pytest.approx(60.0) and t.age_deg.iloc[-1] == pytest.approx(420.0)
    # Landgrebe's columns are the formulas at the rotor's own sigma, N_b, twist
    rot_sigma = 4 * uh60_single_rotor().rotors[0].chord / (math.pi * uh60_single_rotor().rotors[0].radius)
    assert s.sigma == pytest.approx(rot_sigma, rel=1e-12)
    assert t.z_landgrebe.to_numpy() == pytest.approx(
        landgrebe_height(t.age_rad.to_numpy(), 0.006, s.sigma, 4, s.twist_deg), abs=1e-15)
    assert (t.dr == t.r_ours - t.r_landgrebe).all()
    # even a coarse free wake contracts and descends: the tip vortex inside the
    # disc and below it by the first revolution (physics, not a tuned band)
    assert 0.7 < s.r_far_ours < 1.0
    assert t.z_ours.iloc[-1] < -0.1
    assert s.k2_ours < 0 and s.k2_landgrebe < 0
    # the trimmed inflow is of momentum-theory size: kappa sqrt(C_T / 2) with kappa in 1-1.5
    assert 1.0 < s.lam0 / math.sqrt(0.006 / 2) < 1.5


def test_fitted_rates_recover_a_landgrebe_trajectory():
    # the fit applied to Landgrebe's own trajectory returns its k1, k2 exactly (piecewise linear)
    from studies.analysis.wake_geometry import _fit_rates
    age = np.linspace(math.radians(60.0), 4 * math.pi, 45)
    z = landgrebe_height(age, 0.006, 0.08, 4, -10.0)
    k1, k2 = _fit_rates(age, z, math.pi / 2, 4 * math.pi)
    assert (k1, k2) == pytest.approx(landgrebe_descent_rates(0.006, 0.08, 4, -10.0), abs=1e-12)


@pytest.mark.slow
def test_study_small_writes_its_files(tmp_path):
    done = subprocess.run([sys.executable, "-m", "studies.wake_geometry_check", "--small", "--out", str(tmp_path)],
                          cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    summary = pd.read_csv(tmp_path / "summary.csv")
    assert set(summary.variant) == {"default", "contracted near wake"}
    assert (tmp_path / "trajectory.png").stat().st_size > 0
    assert list(pd.read_csv(tmp_path / "sensitivity.csv").change) == ["none", "core radius 3x"]
    assert len(pd.read_csv(tmp_path / "trajectory.csv")) > 0
