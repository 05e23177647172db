"""A study runs as a user runs it: as a program, never imported by the tests.

The identification chain itself is tested on the library (tests/flightid/,
tests/aircraft/identification/test_identification_pipeline.py: aircraft.identify_inflow on a tiny wake);
this checks that the demo study, a thin layer over it, runs and writes its tables.
"""
import os
import subprocess
import sys
from pathlib import Path

import pytest
import pandas as pd

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow
def test_identification_demo_writes_tables_and_figures(tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-m", "studies.identification_demo", "--seed", "3",
                           "--out", str(tmp_path)], cwd=ROOT, env=env, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    for name in ("cost_table.csv", "parameters.csv", "verification.csv", "reduction_log.csv",
                 "bode_fit.png", "verification.png"):
        assert (tmp_path / name).stat().st_size > 0
    cost = pd.read_csv(tmp_path / "cost_table.csv")
    # 12 responses of the 6-state truth with 2 % noise: an excellent fit (guideline < 50)
    assert len(cost) == 12 and cost.J.mean() < 10
