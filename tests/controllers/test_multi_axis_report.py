"""The report of a multi-axis design: files, columns and contents on a small roll/pitch design.

The plant is the hand-built roll/pitch pair of ``_plants.py`` (roll
p/delta_lat = 5/(s+1.5), pitch q/delta_lon = -4/(s+1), phi = int p, theta = int q,
symmetric rate cross-coupling 0.3). One DMO sweep with small settings and a small
global check: the tests check what is written, not the optimiser.
"""
import math
from dataclasses import replace

import numpy as np
import pandas as pd
import pytest

from controllers import DMOSettings, design_multi_axis
from controllers.actuator_limits import LIMITS_ASSUMPTIONS
from controllers.multi_axis_check import global_check
from controllers.multi_axis_report import (limits_assumptions_table, limits_table, multi_axis_summary,
                                           multi_axis_tables, write_multi_axis_report)
from tests.controllers._plants import roll_pitch

# every test here shares a fixture that takes seconds to build: not in the quick set (make test-quick)
pytestmark = pytest.mark.slow

#: small DMO settings (two boundary steps from the starting gains, no global stage): what is written is
#: under test, not the optimiser
FAST = DMOSettings(global_samples=0, max_steps=2, tolerance=0.2, polish_evaluations=0, growth=2.0)

#: the columns a reader of each file relies on, written out by hand from the study's documented files
AXES_COLUMNS = ["axis", "response_type", "K_phi", "K_Iphi", "K_p", "crossover", "crossover_design",
                "crossover_boundary", "drb", "drp_db", "gm_db", "pm_deg", "olop_margin_db", "olop_onset", "tau_eq",
                "specs_met", "unmet", "limiting"]
LIMITS_COLUMNS = ["axis", "stick", "rate_limit_deg_s", "travel_deg", "stick_amplitude", "command_gain",
                  "full_stick_command"]
COUPLING_COLUMNS = ["stick", "response", "peak_gain_ratio", "step_ratio", "off_peak", "off_rate_peak"]
SWEEPS_COLUMNS = ["sweep", "axis", "K_phi", "K_Iphi", "K_p", "crossover", "relative_change", "feasible",
                  "crossover_boundary", "wall_s", "message"]
JOINT_COLUMNS = ["axis", "dmo_crossover", "joint_crossover", "ratio", "dmo_feasible", "dmo_K_phi", "dmo_K_Iphi",
                 "dmo_K_p", "joint_K_phi", "joint_K_Iphi", "joint_K_p", "dominated", "min_ratio", "points",
                 "feasible_points", "local_points", "local_min_ratio", "wall_s"]
CHECK_COLUMNS = ["axis", "dmo_crossover", "search_crossover", "ratio", "beaten", "dmo_feasible", "dmo_K_phi",
                 "dmo_K_Iphi", "dmo_K_p", "search_K_phi", "search_K_Iphi", "search_K_p", "search_mimo_met",
                 "search_mimo_crossover", "points", "feasible_points", "search_wall_s", "guarded", "guard_specs",
                 "dmo_guards_met"]


@pytest.fixture(scope="module")
def designed():
    res = design_multi_axis(roll_pitch(0.3), axes=["roll", "pitch"], settings=FAST, max_sweeps=1, progress=False,
                            crossover_start={"roll": 2.5, "pitch": 2.5})
    check = global_check(res, maxiter=2, popsize=2, seed=7)
    return res, check


def _header(path):
    return path.read_text().splitlines()[0].split(",")


def test_report_writes_every_file_with_its_columns(designed, tmp_path):
    res, check = designed
    paths = write_multi_axis_report(res, tmp_path / "new", check=check, dpi=30)   # small figures: fast
    expected = {"axes", "specs", "limits", "limits_assumptions", "coupling", "sweeps", "global_check",
                "hq_window_roll", "hq_window_pitch"}
    assert set(paths) == expected
    assert sorted(p.name for p in (tmp_path / "new").iterdir()) == sorted(
        f"{n}.png" if n.startswith("hq_window") else f"{n}.csv" for n in expected)
    assert _header(paths["axes"]) == AXES_COLUMNS
    assert _header(paths["limits"]) == LIMITS_COLUMNS
    assert _header(paths["limits_assumptions"]) == ["item", "assumption"]
    assert _header(paths["coupling"]) == COUPLING_COLUMNS
    assert _header(paths["sweeps"]) == SWEEPS_COLUMNS
    assert _header(paths["global_check"]) == CHECK_COLUMNS
    specs = pd.read_csv(paths["specs"])
    assert specs.columns[-1] == "axis" and "spec" in specs.columns
    # one row per graded spec of each axis, in axis order
    assert list(specs.axis) == ["roll"] * len(res.specs["roll"]) + ["pitch"] * len(res.specs["pitch"])
    for axis in ("roll", "pitch"):
        assert paths[f"hq_window_{axis}"].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_report_contents_read_back(designed, tmp_path):
    res, check = designed
    paths = write_multi_axis_report(res, tmp_path, check=check, figures=False)
    axes = pd.read_csv(paths["axes"], index_col="axis")
    assert list(axes.index) == ["roll", "pitch"]
    # CSV floats are written with round-trip precision: the gains read back exactly
    for axis in ("roll", "pitch"):
        g = res.emf.loops[axis].gains
        assert (axes.loc[axis, "K_phi"], axes.loc[axis, "K_Iphi"], axes.loc[axis, "K_p"]) == (
            g.K_phi, g.K_Iphi, g.K_p)
    limits = pd.read_csv(paths["limits"]).set_index("axis")
    # hand values of the hover assumptions: 40 deg/s and 8 deg of blade pitch on both cyclics; a full stick
    # commands 30 deg of roll and 20 deg of pitch (tolerance: degrees <-> radians round-off only)
    np.testing.assert_allclose(limits.rate_limit_deg_s, [40.0, 40.0], rtol=1e-12)
    np.testing.assert_allclose(limits.travel_deg, [8.0, 8.0], rtol=1e-12)
    np.testing.assert_allclose(limits.full_stick_command, [math.radians(30.0), math.radians(20.0)], rtol=1e-12)
    assert list(limits.stick) == ["delta_lat", "delta_lon"]
    assumptions = pd.read_csv(paths["limits_assumptions"], index_col="item").assumption.to_dict()
    assert assumptions == LIMITS_ASSUMPTIONS
    sweeps = pd.read_csv(paths["sweeps"])
    assert list(sweeps.axis) == ["roll", "pitch"] and list(sweeps.sweep) == [1, 1]
    coupling = pd.read_csv(paths["coupling"])
    assert set(zip(coupling.stick, coupling.response)) == {("roll", "pitch"), ("pitch", "roll")}
    assert list(pd.read_csv(paths["global_check"], index_col="axis").index) == ["roll", "pitch"]


def test_report_files_are_the_studies_former_files_byte_for_byte(designed, tmp_path):
    # the recipe the three multi-axis studies used before the report moved into the library
    res, check = designed
    old = tmp_path / "old"
    old.mkdir()
    res.to_pandas().to_csv(old / "axes.csv")
    pd.concat([t.assign(axis=a) for a, t in res.specs.items()], ignore_index=True).to_csv(
        old / "specs.csv", index=False)
    rows = [{"axis": a, "stick": res.emf.channels[a].stick, "rate_limit_deg_s": math.degrees(lim.rate_limit),
             "travel_deg": math.degrees(lim.position_limit), "stick_amplitude": lim.stick_amplitude,
             "command_gain": res.emf.loops[a].command_model.gain,
             "full_stick_command": lim.stick_amplitude * res.emf.loops[a].command_model.gain}
            for a, lim in res.limits.items()]
    pd.DataFrame(rows).to_csv(old / "limits.csv", index=False)
    pd.Series(LIMITS_ASSUMPTIONS, name="assumption").rename_axis("item").to_csv(old / "limits_assumptions.csv")
    res.coupling().to_csv(old / "coupling.csv", index=False)
    res.history.to_csv(old / "sweeps.csv", index=False)
    check.to_csv(old / "global_check.csv")
    paths = write_multi_axis_report(res, tmp_path / "new", check=check, figures=False)
    assert len(paths) == 7
    for name, path in paths.items():
        assert path.read_bytes() == (old / f"{name}.csv").read_bytes(), name


def test_tables_summary_and_limits_without_olop(designed):
    res, check = designed
    assert list(multi_axis_tables(res)) == ["axes", "specs", "limits", "limits_assumptions", "coupling", "sweeps"]
    assert list(multi_axis_tables(res, check))[-1] == "global_check"
    text = multi_axis_summary(res, check)
    lines = text.splitlines()
    # column header, index name and 2 axes; the convergence line; the check's header, index name and 2 axes
    assert len(lines) == 9 and lines[4].startswith("converged: False after 1 sweep(s)")
    assert "limiting" in lines[0] and "search_crossover" in lines[5]
    assert multi_axis_summary(res, check, design=False).splitlines() == lines[5:]
    # an axis whose OLOP was not graded (no limits) is left out of the limits table
    partial = replace(res, limits={"roll": None, "pitch": res.limits["pitch"]})
    assert list(limits_table(partial).axis) == ["pitch"]
    empty = limits_table(replace(res, limits={"roll": None, "pitch": None}))
    assert empty.empty and list(empty.columns) == LIMITS_COLUMNS
    assert limits_table(res).attrs["assumptions"] is LIMITS_ASSUMPTIONS
    assert list(limits_assumptions_table().index) == list(LIMITS_ASSUMPTIONS)


def test_bad_arguments_are_named(designed, tmp_path):
    res, check = designed
    with pytest.raises(TypeError, match="result"):
        write_multi_axis_report(res.to_pandas(), tmp_path)
    with pytest.raises(TypeError, match="check"):
        write_multi_axis_report(res, tmp_path, check=check.to_dict())
    with pytest.raises(TypeError, match="joint"):
        write_multi_axis_report(res, tmp_path, joint=check)
    with pytest.raises(ValueError, match="dpi"):
        write_multi_axis_report(res, tmp_path, dpi=0)
    with pytest.raises(TypeError, match="axes_table"):
        multi_axis_summary(res, axes_table=[1, 2])
    assert not any(tmp_path.iterdir())          # nothing written before the arguments were checked


def test_the_joint_check_is_written_when_given(designed, tmp_path):
    from controllers.multi_axis_joint import joint_check
    res, _ = designed
    joint = joint_check(res, maxiter=1, popsize=1)      # a tiny budget: what is written is under test
    paths = write_multi_axis_report(res, tmp_path, joint=joint, figures=False)
    assert _header(paths["joint_check"]) == JOINT_COLUMNS
    back = pd.read_csv(paths["joint_check"], index_col="axis")
    assert list(back.index) == ["roll", "pitch"]
    assert (back.points == joint.evaluations).all() and back.dominated.dtype == bool
    assert "joint_check" not in write_multi_axis_report(res, tmp_path / "none", figures=False)
