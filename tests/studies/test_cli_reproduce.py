"""``rotorwake reproduce`` and the comparison a study run prints with what it replaced.

Run on the cheapest study (``pitt-peters-hover-check``, seconds) written into a
temporary results root; the differences are made by hand in its CSV files, so the
test knows which file, column and row moved. Like the other command-line tests,
the command line runs as a program (a subprocess).
"""
import csv
import hashlib
import os
import subprocess
import sys
from pathlib import Path
import pytest

ROOT = Path(__file__).resolve().parents[2]
ENV = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=str(ROOT))
STUDY, FOLDER = "pitt-peters-hover-check", "pitt_peters_hover_check"
COLUMN, ROW = "ours (linearised)", 3                 # Lbar11 in matrices.csv


def _rotorwake(*args):
    """``rotorwake ARGS`` as a user runs it; the completed process."""
    return subprocess.run([sys.executable, "-m", "studies.cli", *map(str, args)], cwd=ROOT, env=ENV,
                          capture_output=True, text=True, timeout=300)


def _hashes(folder):
    return {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def _scale(path, column, row, factor):
    """Multiply one entry of a CSV file by ``factor``; (old, new) value."""
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    k = rows[0].index(column)
    old = float(rows[row + 1][k])
    rows[row + 1][k] = repr(old * factor)
    with open(path, "w", newline="") as fh:
        csv.writer(fh, lineterminator="\n").writerows(rows)
    return old, old * factor


@pytest.mark.slow
def test_reproduce_passes_on_a_fresh_folder_and_fails_naming_what_moved(tmp_path):
    results = tmp_path / "results"
    first = _rotorwake(STUDY, "--out", results / FOLDER)
    assert first.returncode == 0, first.stderr
    assert "compared with the files this run replaced" not in first.stdout      # nothing was there before
    before = _hashes(results)

    same = _rotorwake("reproduce", FOLDER, "--results", results)
    assert same.returncode == 0, same.stdout + same.stderr
    assert "1 of 1 folder(s) reproduced within tolerance" in same.stdout
    assert _hashes(results) == before                                           # the reference is untouched

    old, new = _scale(results / FOLDER / "matrices.csv", COLUMN, ROW, 1.01)
    edited = _hashes(results)
    keep = tmp_path / "rerun"
    moved = _rotorwake("reproduce", FOLDER, "--results", results, "--keep", keep)
    assert moved.returncode == 1, moved.stdout + moved.stderr
    assert f"matrices.csv, column '{COLUMN}': 1 of 6 rows beyond rtol 1e-06, atol 1e-09" in moved.stdout
    # the reference holds the edited value, the rerun the study's own
    assert f"at row {ROW}: {new!r} -> {old!r}" in moved.stdout
    assert f"moved or missing in: {results / FOLDER}" in moved.stdout
    assert _hashes(results) == edited
    assert (keep / FOLDER / "matrices.csv").is_file()                           # --keep keeps the rerun

    # --rtol replaces the default tolerance: a 1 % change passes at 2 %
    wider = _rotorwake("reproduce", FOLDER, "--results", results, "--rtol", "0.02")
    assert wider.returncode == 0, wider.stdout

    # a study run over the edited folder compares what it wrote with what it replaced
    again = _rotorwake(STUDY, "--out", results / FOLDER)
    assert again.returncode == 0
    assert f"{results / FOLDER}: compared with the files this run replaced" in again.stdout
    assert f"matrices.csv, column '{COLUMN}'" in again.stdout and "1 moved" in again.stdout


@pytest.mark.slow
def test_a_study_may_widen_the_tolerance_of_its_columns(tmp_path):
    # RESULT_TOLERANCES of the study module (pattern -> (rtol, atol)) applies on top of the default
    results = tmp_path / "results"
    assert _rotorwake(STUDY, "--out", results / FOLDER).returncode == 0
    _scale(results / FOLDER / "matrices.csv", COLUMN, ROW, 1.01)
    code = ("import studies.pitt_peters_hover_check as study\nfrom studies import cli\n"
            "study.RESULT_TOLERANCES = {'matrices.csv:ours*': (0.02, 0.0)}\n"
            f"print('RC', cli.main(['reproduce', {FOLDER!r}, '--results', {str(results)!r}]))")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=ENV, capture_output=True, text=True,
                         timeout=300)
    assert "RC 0" in out.stdout, out.stdout + out.stderr
    assert "within tolerance" in out.stdout


@pytest.mark.slow
def test_reproduce_refuses_what_it_cannot_rerun(tmp_path):
    results = tmp_path / "results"
    # by default the main job's folders: none here
    missing = _rotorwake("reproduce", "--results", results)
    assert missing.returncode == 2
    assert "'hover_control_comparison'" in missing.stderr and "'identification_demo'" in missing.stderr
    # a folder written by a script, not by a rotorwake study; and one a study wrote
    for name, settings in (("spec_table", {"options": []}), (FOLDER, {"command": STUDY, "options": []})):
        (results / name).mkdir(parents=True)
        (results / name / "table.csv").write_text("a\n1\n")
        code = ("from aircraft.provenance import write_manifest\n"
                f"write_manifest({str(results / name)!r}, command='made by hand', settings={settings!r}, "
                "wall_time_s=0.0)")
        subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=ENV, check=True, timeout=300)
    script = _rotorwake("reproduce", "spec_table", "--results", results)
    assert script.returncode == 2 and "not written by a rotorwake study" in script.stderr
    # the rerun never goes under the committed results
    inside = _rotorwake("reproduce", FOLDER, "--results", results, "--keep", results / "rerun")
    assert inside.returncode == 2 and "lies inside the committed results" in inside.stderr
    assert not (results / "rerun").exists()


@pytest.mark.slow
def test_check_results_prints_the_versions_column(tmp_path):
    results = tmp_path / "results"
    assert _rotorwake(STUDY, "--out", results / FOLDER).returncode == 0
    shown = _rotorwake("check-results", "--results", results)
    assert shown.returncode == 0
    header = shown.stdout.splitlines()[0].split()
    assert header[-1] == "versions" and shown.stdout.splitlines()[1].split()[-1] == "same"
