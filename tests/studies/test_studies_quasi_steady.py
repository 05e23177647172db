"""The quasi-steady study runs as a user runs it (a program), on a tiny wake: four 4 s
held steps of the coaxial (about 15 s of two cores: ``--no-cache`` computes them afresh)."""
import os
import subprocess
import sys
from pathlib import Path

import pytest
import numpy as np
import pandas as pd

from aircraft.inflow import IdentifiedInflow

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow
def test_quasi_steady_study_compares_each_model_with_the_same_steps(tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-m", "studies.coaxial_quasi_steady", "--small", "--no-cache", "--out",
                           str(tmp_path)],
                          cwd=ROOT, env=env, capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stderr[-3000:]
    for name in ("table.csv", "settling.csv", "load_changes.csv", "steps.png", "wall_times.csv"):
        assert (tmp_path / name).stat().st_size > 0
    table = pd.read_csv(tmp_path / "table.csv")
    assert set(table.file) == {"coaxial_hover_6state", "coaxial_hover_12state", "coaxial_hover_6state_axisymmetric",
                               "published_eq5_3"}
    # one set of wake records for every model: the wake column is the same for all
    wake = table.pivot_table(index=["control", "output"], columns="file", values="wake")
    assert np.allclose(wake.to_numpy(), wake.to_numpy()[:, :1])
    # the model column is the file's DC gain times the record's load changes (python-control's dcgain)
    loads = pd.read_csv(tmp_path / "load_changes.csv").set_index("control")
    sys6 = IdentifiedInflow.from_file("coaxial_hover_6state").system
    g = np.asarray(sys6.dcgain())
    cols = [sys6.input_labels.index(c) for c in loads.columns]
    row = table[(table.file == "coaxial_hover_6state") & (table.control == "theta0_U")
                & (table.output == "lam0_U")].iloc[0]
    expect = g[sys6.output_labels.index("lam0_U"), cols] @ loads.loc["theta0_U"].to_numpy()
    assert abs(row.model / expect - 1) < 1e-9
    assert table.on_axis.sum() == table.file.nunique() * 4     # four on-axis steps per model
    # --no-cache: the first model's call computed the records, the others read them back
    walls = pd.read_csv(tmp_path / "wall_times.csv")
    assert list(walls.wake_records) == ["computed"] + ["cache"] * (table.file.nunique() - 1)
    assert walls.wall_s.iloc[0] > walls.wall_s.iloc[1:].max()
    assert "the guard" in done.stdout and "wall times" in done.stdout
