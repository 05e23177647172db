"""The `rotorwake` command line: fast help, dispatch to the studies, manifests.

The command line lives with the studies it dispatches to; like every study it is
run here as a program (a subprocess), never imported by the tests.
"""
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from aircraft.provenance_check import check_results

ROOT = Path(__file__).resolve().parents[2]
ENV = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=str(ROOT))


def _python(code):
    """Run ``code`` in a fresh interpreter at the repository root; its stdout."""
    return subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=ENV, capture_output=True, text=True,
                          check=True, timeout=300).stdout


def _rotorwake(*args):
    """``rotorwake ARGS`` as a user runs it; the completed process."""
    return subprocess.run([sys.executable, "-m", "studies.cli", *map(str, args)], cwd=ROOT, env=ENV,
                          capture_output=True, text=True, timeout=300)


_STUDY_NAMES = "from studies import cli; print(' '.join(cli.STUDIES))"


def test_help_is_fast_and_lists_every_study():
    # `rotorwake --help` in < 1 s means: nothing heavy imported (numba alone takes
    # ~1 s). Checked by module, not by a timer, so a loaded CI machine cannot make
    # it flaky (the wall time itself is for a person to measure).
    code = ("import sys; from studies import cli\n"
            "try:\n    cli.main(['--help'])\nexcept SystemExit:\n    pass\n"
            "heavy = [m for m in ('numba', 'casadi', 'control', 'scipy', 'pandas', 'matplotlib') if m in sys.modules]\n"
            "print('HEAVY', heavy)")
    out = _python(code)
    assert "HEAVY []" in out
    for name in _python(_STUDY_NAMES).split():
        assert name in out
    assert "results" in out and "check-results" in out


@pytest.mark.slow
def test_every_study_command_names_a_study_with_a_main():
    out = _python("import importlib\nfrom studies import cli\n"
                  "for study in cli.STUDIES.values():\n"
                  "    print(study.module, callable(importlib.import_module(study.module).main))")
    rows = [line.split() for line in out.splitlines()]
    assert len(rows) >= 8 and all(ok == "True" for _, ok in rows), rows


def test_long_runs_say_so_and_how_long():
    out = _python("from studies import cli\n"
                  "for argv in (['--regenerate'], ['--out=/x', '--skip-identification']):\n"
                  "    minutes, folders, note = cli._plan(cli.STUDIES['main'], argv)\n"
                  "    print(minutes, *folders)")
    wake, skip = [line.split() for line in out.splitlines()]
    assert float(wake[0]) >= 10
    assert wake[1:] == ["results/identification_demo", "results/hover_control_comparison"]
    assert skip[1:] == ["/x/hover_control_comparison"]


@pytest.mark.slow
def test_study_run_writes_a_fresh_manifest_and_staleness_is_detected(tmp_path, capsys):
    out = tmp_path / "results" / "pitt_peters_hover_check"
    assert _rotorwake("pitt-peters-hover-check", "--out", out).returncode == 0
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["settings"] == {"command": "pitt-peters-hover-check", "options": []}   # --out not hashed
    assert len(manifest["settings_hash"]) == 64 and manifest["machine"]["cores"] >= 1
    assert manifest["wall_time_s"] > 0 and manifest["date"].endswith("+00:00")
    assert "studies/pitt_peters_hover_check.py" in manifest["sources"]
    assert "aircraft/inflow/pitt_peters.py" in manifest["sources"]
    assert set(manifest["files"]) == {"matrices.csv", "forward_flight.csv"}
    assert _rotorwake("check-results", "--results", tmp_path / "results").returncode == 0
    # a hand-edited table is "modified"
    (out / "matrices.csv").write_text("edited\n")
    assert check_results(tmp_path / "results").status.tolist() == ["modified"]
    # code that changed since the run makes it "stale" (manifest pointing at a changed
    # source: its bytes and its code digest both differ)
    manifest["files"]["matrices.csv"] = __import__("aircraft.provenance").provenance.file_sha256(out / "matrices.csv")
    manifest["sources"]["studies/pitt_peters_hover_check.py"] = "0" * 64
    manifest["code_digests"]["studies/pitt_peters_hover_check.py"] = "0" * 64
    (out / "manifest.json").write_text(json.dumps(manifest))
    table = check_results(tmp_path / "results")
    assert table.status.tolist() == ["stale"] and "pitt_peters_hover_check.py" in table.detail[0]
    assert _rotorwake("check-results", "--results", tmp_path / "results").returncode == 1


def test_results_folder_without_manifest_is_reported(tmp_path):
    (tmp_path / "old_study").mkdir()
    (tmp_path / "old_study" / "table.csv").write_text("a\n1\n")
    assert check_results(tmp_path).status.tolist() == ["no manifest"]


AIRCRAFT_STUDIES = ("wake-identification", "forward-flight-identification", "off-rotor-models",
                    "coaxial-wake-identification", "wake-length-check")


@pytest.mark.slow
def test_studies_take_the_aircraft_from_the_command_line():
    for command in AIRCRAFT_STUDIES:
        shown = _rotorwake(command, "--help")
        assert shown.returncode == 0 and "--aircraft" in shown.stdout, command
    # a name that is neither shipped nor a file stops the run before any wake work, naming the choices
    bad = _rotorwake("wake-identification", "--aircraft", "my_heli", "--out", "/nonexistent/never")
    assert bad.returncode != 0
    assert "'my_heli' is neither a shipped aircraft nor a TOML file" in bad.stderr
    assert "uh60_single_rotor" in bad.stderr


def test_unknown_command_is_an_error():
    assert _rotorwake("no-such-study").returncode == 2


@pytest.mark.slow
def test_study_help_shows_each_option_with_its_default():
    text = _python("import argparse\nfrom studies import cli\nbefore = argparse.ArgumentParser.__init__\n"
                   "try:\n    cli.main(['identification-demo', '--help'])\nexcept SystemExit as exc:\n"
                   "    print('EXIT', exc.code)\n"
                   "print('RESTORED', argparse.ArgumentParser.__init__ is before)")
    assert "EXIT 0" in text
    assert "usage: rotorwake identification-demo" in text
    assert "default: 0" in text and "default: results/identification_demo" in text
    assert "RESTORED True" in text     # the help-only patch is undone


@pytest.mark.slow
def test_results_reruns_each_study_with_the_options_of_its_committed_manifest(tmp_path):
    # `rotorwake results` must reproduce what is committed (e.g. a --coarse run), not
    # the study's defaults; without a manifest it falls back to the defaults
    folder = tmp_path / "off_rotor_models"
    folder.mkdir()
    (folder / "gains_delays.csv").write_text("a\n1\n")
    code = ("from pathlib import Path\n"
            "from aircraft.provenance import write_manifest\n"
            "from studies import cli\n"
            f"root = Path({str(tmp_path)!r})\n"
            "write_manifest(root / 'off_rotor_models', command='rotorwake off-rotor-models --coarse',\n"
            "               settings={'command': 'off-rotor-models', 'options': ['--coarse']}, wall_time_s=1.0)\n"
            "print('OFF', cli.committed_options('off-rotor-models', results=root))\n"
            "print('FWD', cli.committed_options('forward-flight-identification', results=root))\n"
            "print('MAIN', cli.committed_options('main', results=root))\n")
    out = _python(code)
    assert "OFF ['--coarse']" in out
    assert "FWD []" in out and "MAIN []" in out


@pytest.mark.slow
def test_the_shipped_models_command_prints_progress_and_wall_time():
    # regenerate is replaced by a stand-in (no wake run): the command's own lines are checked
    out = _python("import types\nfrom studies import cli\nfrom aircraft.identification import shipped\n"
                  "done = []\nshipped.regenerate = lambda name, **kw: done.append(name)\n"
                  "args = types.SimpleNamespace(list=False, check=False, published=False, names=['a', 'b'], "
                  "jobs=1, cache=None)\n"
                  "print('RC', cli._shipped_models(args), done)")
    assert "RC 0 ['a', 'b']" in out
    for line in ("[1/2] a: regenerating", "[2/2] b: regenerating", "[2/2] wrote ", "regenerated 2 model file(s) in"):
        assert line in out, out
