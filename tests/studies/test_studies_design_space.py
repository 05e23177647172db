"""The design-space study runs as a user runs it (a program, never imported), on a tiny wake.

One coaxial identification (h/R 0.14) on the 20 deg, 1.5-revolution wake with 12 s
sweeps: about a minute of CPU with an empty wake cache, hence ``slow`` (the
interpolated schedule between points is tested on stand-in models in
tests/aircraft/identification/test_design_space.py); the wake runs go to
$ROTORWAKE_CACHE_DIR (or .cache/wake) like any run, so a second run takes seconds.
"""
import json
import os
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow
def test_design_space_study_writes_table_figure_and_schedule(tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-m", "studies.coaxial_design_space", "--small", "--spacings", "0.14",
                           "--out", str(tmp_path)],
                          cwd=ROOT, env=env, capture_output=True, text=True, timeout=1800)
    assert done.returncode == 0, done.stderr[-3000:]
    for name in ("design_space.csv", "summary.csv", "coefficients.png", "timing.csv", "reproduction.csv"):
        assert (tmp_path / name).stat().st_size > 0
    # the reproduction part runs at the trusted points only (none may be trusted on the tiny wake)
    rep = pd.read_csv(tmp_path / "reproduction.csv")
    assert {"spacing", "ct", "largest_shift_in_bounds", "reproduces", "trusted"} <= set(rep.columns)
    table = pd.read_csv(tmp_path / "design_space.csv")
    assert sorted(set(table.spacing)) == [0.14] and set(table.ct) == {0.0096}
    summary = pd.read_csv(tmp_path / "summary.csv")
    assert len(summary) == 1 and {"J_ave", "trusted", "l41", "m25"} <= set(summary.columns)
    # the trim shares the requested thrust equally (torque balanced to 1e-4 in C_T)
    ok = summary.dropna(subset=["CT_U"])
    assert ((ok.CT_U + ok.CT_L - 0.0096).abs() < 2e-4).all()
    timing = pd.read_csv(tmp_path / "timing.csv")
    assert len(timing) == 2 and timing.wall_s.iloc[-1] > 0      # the point and the total
    assert timing.wake_cache.str.startswith("on").all()          # the test runs with the cache
    assert "wall" in done.stdout
    if (tmp_path / "schedule.json").exists():     # written when the point identified a stable model
        doc = json.loads((tmp_path / "schedule.json").read_text())
        assert doc["spacings"] == [0.14] and doc["cts"] == [0.0096]


@pytest.mark.slow
def test_design_space_study_offers_both_structures_and_the_all_points_schedule():
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-m", "studies.coaxial_design_space", "--help"],
                          cwd=ROOT, env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    text = " ".join(done.stdout.split())
    assert "coaxial_6state_axisymmetric_pp_collective_mass" in text and "--all-points" in text
    bad = subprocess.run([sys.executable, "-m", "studies.coaxial_design_space", "--structure", "single_rotor_3state"],
                         cwd=ROOT, env=env, capture_output=True, text=True, timeout=300)
    assert bad.returncode == 2 and "invalid choice" in bad.stderr      # argparse refuses before any wake run
