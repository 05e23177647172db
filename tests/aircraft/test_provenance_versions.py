"""Numerical package versions in results manifests and the ``versions`` column of
``check_results``: reported, never a reason for a folder to be stale."""
import json
import platform

from aircraft.provenance import numerical_environment, numerical_versions, write_manifest
from aircraft.provenance_check import _versions_note, check_results

NOW = {"python": "3.11.7", "numpy": "2.4.6", "scipy": "1.17.1", "control": "0.10.2", "casadi": "3.8.2",
       "numba": "0.68.1", "slycot": "0.7.1", "pandas": "3.1.2", "matplotlib": "3.11.2"}


def test_numerical_versions_names_every_package_in_order():
    versions = numerical_versions()
    assert list(versions) == list(NOW)
    assert versions["python"] == platform.python_version()
    assert all(v is None or isinstance(v, str) for v in versions.values())


def test_versions_note_same_differs_and_partly_recorded():
    assert _versions_note({"versions": dict(NOW)}, NOW) == "same"
    older = {**NOW, "scipy": "1.16.0", "slycot": None}
    assert _versions_note({"versions": older}, NOW) == (
        "differs: scipy 1.16.0 (now 1.17.1), slycot not installed (now 0.7.1)")
    # a manifest from before "versions": only the top-level python/numpy/numba keys
    old_machine = {"cores": 2, "python": "3.11.7", "numpy": "2.4.6", "numba": "0.68.1"}
    assert _versions_note(old_machine, NOW) == (
        "partly recorded (python, numpy, numba same); not recorded: scipy, control, casadi, slycot, pandas, "
        "matplotlib")
    assert _versions_note({**old_machine, "numpy": "2.3.0"}, NOW) == (
        "partly recorded (differs: numpy 2.3.0 (now 2.4.6); python, numba same); not recorded: scipy, control, "
        "casadi, slycot, pandas, matplotlib")
    assert _versions_note({"cores": 2}, NOW) == "not recorded"


def test_a_manifest_records_the_versions_and_a_difference_leaves_the_folder_fresh(tmp_path):
    folder = tmp_path / "results" / "study"
    folder.mkdir(parents=True)
    (folder / "table.csv").write_text("a\n1\n")
    path = write_manifest(folder, command="test", settings={}, wall_time_s=1.0, root=tmp_path, sources={})
    manifest = json.loads(path.read_text())
    machine = manifest["machine"]
    # and the BLAS kernel family, whose round-off differs from one family to the next
    assert machine["versions"] == numerical_environment()
    assert (machine["python"], machine["numpy"], machine["numba"]) == tuple(
        machine["versions"][k] for k in ("python", "numpy", "numba"))          # kept for older readers
    table = check_results(tmp_path / "results", root=tmp_path)
    assert table.status.tolist() == ["fresh"] and table.versions.tolist() == ["same"]
    machine["versions"]["scipy"] = "0.1.0"
    path.write_text(json.dumps(manifest))
    table = check_results(tmp_path / "results", root=tmp_path)
    assert table.status.tolist() == ["fresh"]
    assert table.versions[0].startswith("differs: scipy 0.1.0 (now ")


def test_a_model_file_records_its_environment_and_still_loads(tmp_path):
    from aircraft.inflow.model_files import load_record, shipped_model_path
    from aircraft.provenance_check import environment_note, record_environment
    path = tmp_path / "model.json"
    path.write_text(shipped_model_path("published_eq5_3").read_text())
    assert environment_note(path) == "not recorded"
    before = load_record(path)
    env = record_environment(path)
    assert env == numerical_environment() and environment_note(path) == "same"
    after = load_record(path)
    # only the provenance gained an entry: matrices, hashes and code digests are untouched
    assert after.provenance["environment"] == env
    assert {k: v for k, v in after.provenance.items() if k != "environment"} == before.provenance
    assert after.settings_hash == before.settings_hash and after.code_digest == before.code_digest
    for key in before.matrices:
        assert (after.matrices[key] == before.matrices[key]).all()
    data = json.loads(path.read_text())
    data["provenance"]["environment"]["scipy"] = "0.1.0"
    path.write_text(json.dumps(data))
    assert environment_note(path).startswith("differs: scipy 0.1.0 (now ")
