"""The wake-settings sensitivity check: argument validation, and the wake-length study
end to end on a tiny wake (two 12 s sweeps per wake, about 15 s of two cores)."""
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from aircraft.configs import coaxial_compound
from aircraft.identification.wake_sensitivity import wake_setting_sensitivity

ROOT = Path(__file__).resolve().parents[3]


@pytest.mark.parametrize("variants, match", [({}, "at least one"), ({"base": {"wake_revolutions": 2.0}}, "'base'"),
                                             ({"x": {"no_such_field": 1.0}}, "unknown WakeSettings fields"),
                                             ({"x": {}}, "no change")])
def test_bad_variants_are_refused(variants, match):
    with pytest.raises(ValueError, match=match):
        wake_setting_sensitivity(coaxial_compound(), variants, ct=0.0096, controls=["theta0_U"], outputs=["lam0_U"])


def test_seeds_need_one_per_control():
    with pytest.raises(ValueError, match="one value per control"):
        wake_setting_sensitivity(coaxial_compound(), {"x": {"wake_revolutions": 2.0}}, ct=0.0096,
                                 controls=["theta0_U"], outputs=["lam0_U"], seeds=[0, 1])


@pytest.mark.slow
def test_wake_length_study_runs_small(tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-m", "studies.wake_length_check", "--small", "--no-cache", "--out",
                           str(tmp_path)], cwd=ROOT, env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    table = pd.read_csv(tmp_path / "table.csv")
    base = table[table.variant == "base"]
    # the base against itself: differences exactly zero
    assert np.all(base.d_mag_db == 0.0) and np.all(base.d_phase_deg == 0.0)
    # the variant's differences are its own response over the base's, recomputed here
    var = table[table.variant != "base"].set_index(["control", "output", "omega_rad_s"])
    ref = base.set_index(["control", "output", "omega_rad_s"]).loc[var.index]
    np.testing.assert_allclose(var.d_mag_db, var.mag_db - ref.mag_db, atol=1e-9)
    d_phase = (var.phase_deg - ref.phase_deg + 180.0) % 360.0 - 180.0
    np.testing.assert_allclose(var.d_phase_deg, d_phase, atol=1e-6)
    for name in ("max_difference.csv", "responses.png", "wall_times.csv"):
        assert (tmp_path / name).stat().st_size > 0
    assert "lam1s_L/theta1s_L phase" in done.stdout
