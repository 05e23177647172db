"""The `rotorwake` command line: fast help, dispatch to the studies, manifests."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

from aircraft.provenance import check_results
from studies import cli

ROOT = Path(__file__).resolve().parents[1]


def test_help_is_fast_and_lists_every_study():
    # `rotorwake --help` in < 1 s means: nothing heavy imported (numba alone takes
    # ~1 s). Checked by module, not by a timer, so a loaded CI machine cannot make
    # it flaky; the wall time itself is measured in the README's closing check.
    code = ("import sys; from studies import cli\n"
            "try:\n    cli.main(['--help'])\nexcept SystemExit:\n    pass\n"
            "heavy = [m for m in ('numba', 'casadi', 'control', 'scipy', 'pandas', 'matplotlib') if m in sys.modules]\n"
            "print('HEAVY', heavy)")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True)
    assert "HEAVY []" in out.stdout
    for name in cli.STUDIES:
        assert name in out.stdout
    assert "results" in out.stdout and "check-results" in out.stdout


def test_every_study_command_names_a_study_with_a_main():
    import importlib
    for study in cli.STUDIES.values():
        module = importlib.import_module(study.module)
        assert callable(module.main), study.module


def test_long_runs_say_so_and_how_long():
    minutes, folders, note = cli._plan(cli.STUDIES["main"], ["--identified", "wake"])
    assert minutes >= 10
    assert folders == [Path("results/identification_demo"), Path("results/hover_control_comparison_wake")]
    minutes, folders, _ = cli._plan(cli.STUDIES["main"], ["--out=/x", "--skip-identification"])
    assert folders == [Path("/x/hover_control_comparison")]


def test_study_run_writes_a_fresh_manifest_and_staleness_is_detected(tmp_path, capsys):
    out = tmp_path / "results" / "pitt_peters_hover_check"
    cli.main(["pitt-peters-hover-check", "--out", str(out)])
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["settings"] == {"command": "pitt-peters-hover-check", "options": []}   # --out not hashed
    assert len(manifest["settings_hash"]) == 64 and manifest["machine"]["cores"] >= 1
    assert manifest["wall_time_s"] > 0 and manifest["date"].endswith("+00:00")
    assert "studies/pitt_peters_hover_check.py" in manifest["sources"]
    assert "aircraft/inflow/pitt_peters.py" in manifest["sources"]
    assert set(manifest["files"]) == {"matrices.csv", "forward_flight.csv"}
    assert cli.main(["check-results", "--results", str(tmp_path / "results")]) == 0
    # a hand-edited table is "modified"
    (out / "matrices.csv").write_text("edited\n")
    assert check_results(tmp_path / "results").status.tolist() == ["modified"]
    # code that changed since the run makes it "stale" (manifest pointing at a changed source)
    manifest["files"]["matrices.csv"] = __import__("aircraft.provenance").provenance.file_sha256(out / "matrices.csv")
    manifest["sources"]["studies/pitt_peters_hover_check.py"] = "0" * 64
    (out / "manifest.json").write_text(json.dumps(manifest))
    table = check_results(tmp_path / "results")
    assert table.status.tolist() == ["stale"] and "pitt_peters_hover_check.py" in table.detail[0]
    assert cli.main(["check-results", "--results", str(tmp_path / "results")]) == 1


def test_results_folder_without_manifest_is_reported(tmp_path):
    (tmp_path / "old_study").mkdir()
    (tmp_path / "old_study" / "table.csv").write_text("a\n1\n")
    assert check_results(tmp_path).status.tolist() == ["no manifest"]


def test_unknown_command_is_an_error():
    with pytest.raises(SystemExit) as exc:
        cli.main(["no-such-study"])
    assert exc.value.code == 2


def test_study_help_shows_each_option_with_its_default(capsys):
    import argparse
    before = argparse.ArgumentParser.__init__
    with pytest.raises(SystemExit) as exc:
        cli.main(["identification-demo", "--help"])
    assert exc.value.code == 0
    text = capsys.readouterr().out
    assert "usage: rotorwake identification-demo" in text
    assert "default: 0" in text and "default: results/identification_demo" in text
    assert argparse.ArgumentParser.__init__ is before     # the help-only patch is undone
