"""Shipped model files go stale when the code that computed them changes (code digest)."""
import shutil
from pathlib import Path

import pytest

from aircraft.identification import shipped
from aircraft.identification.model_code import NO_CODE_DIGEST, combined_digest, identification_code, staleness
from aircraft.inflow.model_files import ModelRecord, load_record

ROOT = Path(__file__).resolve().parents[3]


@pytest.fixture(scope="module")
def here():
    """``{module path: code digest}`` of this checkout, every backend's modules included
    (digesting the closure takes seconds: once for the module)."""
    return identification_code(ROOT)[1]


@pytest.fixture
def project(tmp_path):
    """A copy of the library's Python sources, to edit without touching the checkout."""
    def ignore(folder, names):
        return [n for n in names if n in ("__pycache__", "data") or
                (Path(folder, n).is_file() and not n.endswith(".py"))]
    root = tmp_path / "project"
    for package in ("flightid", "aircraft", "controllers"):
        shutil.copytree(ROOT / package, root / package, ignore=ignore)
    return root


def _record(code, settings_hash="0123456789abcdef", backend="cpu"):
    """A tiny synthetic model file's record, stamped with the code ``code`` (``{path: digest}``)
    as :func:`aircraft.identification.regenerate` stamps it."""
    digest, modules = combined_digest(code, kernel_backend=backend)
    return ModelRecord(name="tiny", form="statespace", rotors=("",), omega=27.0,
                       matrices={"A": [[-2.0]], "B": [[1.5]], "C": [[1.0]]}, inputs=["CT"], outputs=["lam0"],
                       loads_ref=[0.0061], inflow_ref=[0.055], settings_hash=settings_hash,
                       provenance={"kernel_backend": backend}, code_digest=digest, code_digests=modules)


def _append(path, text):
    path.write_text(path.read_text() + text)


def test_the_digest_covers_the_identification_code_and_not_the_bookkeeping(here):
    modules = here
    # the pipeline, the fitting, the wake, the configurations and the inflow models
    for rel in ("aircraft/identification/pipeline.py", "flightid/fitting.py", "flightid/reduction.py",
                "aircraft/wake/wake.py", "aircraft/configs.py", "aircraft/inflow/model_files.py"):
        assert rel in modules, rel
    assert "aircraft/provenance.py" not in modules
    assert not any(rel.startswith("studies/") for rel in modules)


@pytest.mark.slow
def test_a_freshly_written_record_is_fresh_and_keeps_its_digest(here, project, tmp_path):
    # stamped with this checkout's code, checked against the copy's: the digest does not
    # depend on where the project lies
    rec = _record(here)
    back = load_record(rec.save(tmp_path / "tiny.json"))
    assert back.code_digest == rec.code_digest and back.code_digests == rec.code_digests
    assert staleness(back, rec.settings_hash, root=project) == []


@pytest.mark.slow
def test_an_edit_to_a_flightid_module_makes_the_record_stale_naming_it(here, project, tmp_path):
    back = load_record(_record(here).save(tmp_path / "tiny.json"))
    # a comment or a docstring is not code: still fresh
    _append(project / "flightid" / "reduction.py", "\n# a note on the reduction\n")
    assert staleness(back, back.settings_hash, root=project) == []
    # one statement more in the fitting code is
    _append(project / "flightid" / "fitting.py", "\n_SOMETHING_NEW = 1\n")
    assert staleness(back, back.settings_hash, root=project) == ["code digest: changed flightid/fitting.py"]


@pytest.mark.slow
def test_a_gpu_kernel_edit_stales_only_records_whose_runs_used_it(here, project):
    cpu, unknown = _record(here, backend="cpu"), _record(here, backend=None)
    unknown.provenance = {}          # a file that does not say which backend ran
    _append(project / "aircraft" / "wake" / "gpu.py", "\n_SOMETHING_NEW = 1\n")
    assert staleness(cpu, cpu.settings_hash, root=project) == []
    assert staleness(unknown, unknown.settings_hash, root=project) == ["code digest: changed aircraft/wake/gpu.py"]


def test_a_file_without_a_code_digest_is_stale_and_each_reason_is_named(project, tmp_path):
    rec = _record({})
    rec.code_digest = ""
    back = load_record(rec.save(tmp_path / "old.json"))      # as an old-schema file: it still loads
    assert staleness(back, back.settings_hash, root=project) == [NO_CODE_DIGEST]
    assert staleness(back, "fedcba9876543210", root=project) == [
        "settings hash: file 0123456789abcdef, recipe fedcba9876543210", NO_CODE_DIGEST]


@pytest.mark.slow
def test_stale_models_reports_each_shipped_file_with_its_reasons(here, monkeypatch):
    want = shipped.RECIPES["uh60_hover_3state"].hash()
    fresh = _record(here, settings_hash=want)
    files = {"uh60_hover_3state": fresh, "coaxial_hover_6state": _record(here, settings_hash="0" * 16)}
    files["coaxial_hover_6state"].code_digest = ""
    monkeypatch.setattr(shipped, "shipped_models", lambda: sorted(files))
    monkeypatch.setattr(shipped, "load_record", files.__getitem__)
    got = shipped.stale_models()
    assert set(got) == {"coaxial_hover_6state"}
    assert got["coaxial_hover_6state"][0].startswith("settings hash: file 0000000000000000, recipe ")
    assert got["coaxial_hover_6state"][1] == NO_CODE_DIGEST


@pytest.mark.slow
def test_regenerate_records_the_code_digest_of_a_printed_model(tmp_path):
    # a printed model's file: written by regenerate (no wake run), fresh against the code now
    rec = shipped.regenerate("published_eq5_3", path=tmp_path / "eq5_3.json")
    back = load_record(tmp_path / "eq5_3.json")
    assert back.code_digest == rec.code_digest and len(back.code_digest) == 64
    assert "flightid/fitting.py" in back.code_digests
    assert back.provenance["kernel_backend"] in ("cpu", "gpu", "none")
    assert staleness(back, rec.settings_hash) == []


@pytest.mark.slow
def test_a_reason_names_at_most_a_few_modules(here):
    # a file written on another Python differs in every module: the reason stays one line
    rec = _record(here)
    rec.code_digests = {p: "0" * 64 for p in rec.code_digests}
    rec.code_digest = "f" * 64
    (reason,) = staleness(rec, rec.settings_hash)
    assert reason.count(".py") == 8 and reason.endswith(f"({len(rec.code_digests)} modules in all)")
