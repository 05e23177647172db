"""Code digests in results manifests: documentation edits do not make results stale,
code edits do, and old byte-only manifests are upgraded only where that is honest."""
import json

import pytest

from aircraft.provenance import code_digest, file_sha256, write_manifest
from aircraft.provenance_check import check_results, upgrade_manifests

MODULE = '''"""Module docstring."""
# a comment


def f(x):
    """Return twice x.

    Parameters
    ----------
    x : float
    """
    return 2 * x


class C:
    """A class."""

    def g(self):
        """Only a docstring."""
'''


@pytest.fixture
def project(tmp_path):
    """A project root with one module and one results folder written from it."""
    (tmp_path / "pkg").mkdir()
    (tmp_path / "pkg" / "m.py").write_text(MODULE)
    folder = tmp_path / "results" / "study"
    folder.mkdir(parents=True)
    (folder / "table.csv").write_text("a\n1\n")
    sources = {"pkg/m.py": file_sha256(tmp_path / "pkg" / "m.py")}
    write_manifest(folder, command="test", settings={}, wall_time_s=1.0, root=tmp_path, sources=sources)
    return tmp_path


def _status(project):
    table = check_results(project / "results", root=project)
    return table.status.tolist()[0], table.detail.tolist()[0]


@pytest.mark.parametrize("edit", [
    lambda s: s.replace("Return twice x.", "Twice x [m]."),               # a docstring
    lambda s: s.replace('"""A class."""\n', ""),                           # a docstring removed
    lambda s: s.replace("# a comment", "# another comment\n# and more"),  # comments, blank lines
    lambda s: s.replace("return 2 * x", "return (2\n            * x)"),   # a line break
])
def test_documentation_edits_leave_results_fresh(project, edit):
    path = project / "pkg" / "m.py"
    path.write_text(edit(MODULE))
    status, detail = _status(project)
    assert status == "fresh" and "documentation only changed" in detail and "pkg/m.py" in detail


@pytest.mark.parametrize("edit", [
    lambda s: s.replace("2 * x", "3 * x"),                                  # a constant
    lambda s: s.replace("def f(x):", "def f(x, y=1):"),                     # a signature
    lambda s: s.replace('"""Only a docstring."""', '"""Only a docstring."""\n        return 1'),
    lambda s: s.replace('"""Module docstring."""', '"""Module docstring."""\nX = 1'),
])
def test_code_edits_make_results_stale(project, edit):
    (project / "pkg" / "m.py").write_text(edit(MODULE))
    status, detail = _status(project)
    assert status == "stale" and "pkg/m.py" in detail


def test_a_module_that_reads_its_docstring_keeps_it_in_the_digest(tmp_path):
    # argparse help and printed docstrings come from __doc__: there a docstring is output
    a, b = tmp_path / "a.py", tmp_path / "b.py"
    a.write_text('"""One."""\nprint(__doc__)\n')
    b.write_text('"""Two."""\nprint(__doc__)\n')
    assert code_digest(a) != code_digest(b)
    a.write_text('"""One."""\nprint(1)\n')
    b.write_text('"""Two."""\nprint(1)\n')
    assert code_digest(a) == code_digest(b)


def test_a_deleted_module_is_stale(project):
    (project / "pkg" / "m.py").unlink()
    assert _status(project)[0] == "stale"


def _downgrade(project):
    """Turn the fixture's manifest into the schema-1 form (bytes only)."""
    path = project / "results" / "study" / "manifest.json"
    manifest = json.loads(path.read_text())
    manifest["schema"] = 1
    del manifest["code_digests"]
    path.write_text(json.dumps(manifest))
    return path


def test_schema_1_manifests_are_checked_on_bytes_and_upgraded_only_when_unchanged(project):
    path = _downgrade(project)
    module = project / "pkg" / "m.py"
    # bytes only: a docstring edit is stale (nothing says the code is the same)
    module.write_text(MODULE.replace("Return twice x.", "Twice x."))
    assert _status(project)[0] == "stale"
    assert upgrade_manifests(project / "results", root=project) == []     # not the code that ran
    assert json.loads(path.read_text())["schema"] == 1
    # back to the bytes that ran: upgraded, then a docstring edit stays fresh
    module.write_text(MODULE)
    assert upgrade_manifests(project / "results", root=project) == ["study"]
    upgraded = json.loads(path.read_text())
    assert upgraded["schema"] == 2 and upgraded["code_digests"] == {"pkg/m.py": code_digest(module)}
    module.write_text(MODULE.replace("Return twice x.", "Twice x."))
    assert _status(project)[0] == "fresh"
    module.write_text(MODULE.replace("2 * x", "3 * x"))
    assert _status(project)[0] == "stale"


def test_unknown_schema_is_refused(project):
    path = project / "results" / "study" / "manifest.json"
    manifest = json.loads(path.read_text())
    manifest["schema"] = 99
    path.write_text(json.dumps(manifest))
    assert _status(project)[0] == "no manifest"


@pytest.fixture
def gpu_project(tmp_path):
    """A project with a 'GPU kernel' module at the path BACKEND_CODE names, and one
    results folder computed from it and another module, on the CPU backend."""
    from aircraft.provenance import BACKEND_CODE
    gpu_rel = next(rel for rel, backend in BACKEND_CODE.items() if backend == "gpu")
    for rel in (gpu_rel, "pkg/m.py"):
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_text(MODULE)
    folder = tmp_path / "results" / "study"
    folder.mkdir(parents=True)
    (folder / "table.csv").write_text("a\n1\n")
    sources = {rel: file_sha256(tmp_path / rel) for rel in (gpu_rel, "pkg/m.py")}
    write_manifest(folder, command="test", settings={}, wall_time_s=1.0, root=tmp_path, sources=sources)
    return tmp_path, gpu_rel, folder


def _set_backend(folder, backend):
    path = folder / "manifest.json"
    manifest = json.loads(path.read_text())
    if backend is None:
        manifest["machine"].pop("kernel_backend", None)
    else:
        manifest["machine"]["kernel_backend"] = backend
    path.write_text(json.dumps(manifest))


@pytest.mark.parametrize("backend, expected", [("cpu", "fresh"), ("none", "fresh"), ("gpu", "stale"),
                                               (None, "stale")])
def test_gpu_kernel_code_counts_only_for_runs_on_the_gpu(gpu_project, backend, expected):
    root, gpu_rel, folder = gpu_project
    _set_backend(folder, backend)
    (root / gpu_rel).write_text(MODULE.replace("return 2 * x", "return 3 * x"))
    status, detail = _status(root)
    assert status == expected
    if expected == "stale":
        assert gpu_rel in detail
    # any other module's code change stales the folder whatever the backend
    (root / "pkg" / "m.py").write_text(MODULE.replace("return 2 * x", "return 4 * x"))
    status, detail = _status(root)
    assert status == "stale" and "pkg/m.py" in detail


def test_write_manifest_records_the_kernel_backend(tmp_path):
    from aircraft.wake import biot_savart
    folder = tmp_path / "r"
    folder.mkdir()
    write_manifest(folder, command="test", settings={}, wall_time_s=1.0, root=tmp_path, sources={})
    recorded = json.loads((folder / "manifest.json").read_text())["machine"]["kernel_backend"]
    assert recorded == biot_savart.kernel_backend()          # the wake code is loaded here


def test_record_kernel_backend_is_explicit_and_only_where_it_makes_a_folder_fresh(gpu_project):
    from aircraft.provenance_check import record_kernel_backend
    root, gpu_rel, folder = gpu_project
    _set_backend(folder, None)                               # an older manifest: says nothing
    (root / gpu_rel).write_text(MODULE.replace("return 2 * x", "return 3 * x"))
    assert _status(root)[0] == "stale"                       # never assumed
    with pytest.raises(ValueError, match="backend must be 'cpu' or 'gpu'"):
        record_kernel_backend(root / "results", "tpu", root=root)
    # stale for another module as well: left as it is
    (root / "pkg" / "m.py").write_text(MODULE.replace("return 2 * x", "return 4 * x"))
    assert record_kernel_backend(root / "results", "cpu", root=root) == []
    (root / "pkg" / "m.py").write_text(MODULE)
    assert record_kernel_backend(root / "results", "cpu", root=root) == ["study"]
    assert _status(root)[0] == "fresh"
    manifest = json.loads((folder / "manifest.json").read_text())
    assert manifest["machine"]["kernel_backend"] == "cpu"
    assert record_kernel_backend(root / "results", "cpu", root=root) == []   # already says


def test_package_face_changes_leave_the_digest_alone(tmp_path):
    """Re-exports of a package ``__init__`` cannot change a number: a new import or a
    longer ``__all__`` keeps its digest; a statement that runs code does not."""
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    init = pkg / "__init__.py"
    init.write_text('"""face"""\nfrom .a import f\n__all__ = ["f"]\nSCALE = 2.0\n')
    before = code_digest(init)
    init.write_text('"""face"""\nfrom .a import f\nfrom .b import g, h\n__all__ = ["f", "g"]\n'
                    '__all__ += ["h"]\nSCALE = 2.0\n')
    assert code_digest(init) == before
    init.write_text('"""face"""\nfrom .a import f\n__all__ = ["f"]\nSCALE = 3.0\n')
    assert code_digest(init) != before
    # an ordinary module keeps its imports in the digest
    mod = pkg / "m.py"
    mod.write_text("from math import pi\n")
    first = code_digest(mod)
    mod.write_text("from math import pi, tau\n")
    assert code_digest(mod) != first
