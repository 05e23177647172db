"""The static import closure that manifests record (``aircraft.provenance.import_closure``)."""
import sys

import pytest

from aircraft.provenance import import_closure, imported_sources


@pytest.fixture
def toy_project(tmp_path):
    """Package ``pkg``: ``a`` imports ``b`` lazily (inside a function) and ``c.d`` at the top;
    ``e`` is imported by nobody."""
    pkg = tmp_path / "pkg"
    (pkg / "c").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("import math\nfrom .c import d\n\ndef f():\n    from . import b\n    return b\n")
    (pkg / "b.py").write_text("X = 1\n")
    (pkg / "c" / "__init__.py").write_text("")
    (pkg / "c" / "d.py").write_text("from ..b import X\n")
    (pkg / "e.py").write_text("import pkg.a\n")
    return tmp_path


def test_closure_follows_lazy_and_relative_imports(toy_project):
    got = import_closure("pkg.a", root=toy_project, packages=("pkg",))
    # b only through a function body, c through d's parent package; e imports a, not the reverse
    assert got == ["pkg", "pkg.a", "pkg.b", "pkg.c", "pkg.c.d"]


def test_closure_does_not_depend_on_what_is_loaded(toy_project):
    before = import_closure("pkg.c.d", root=toy_project, packages=("pkg",))
    sys.path.insert(0, str(toy_project))
    try:
        import pkg.e  # noqa: F401  loads a, b, c, d, e into sys.modules
        after = import_closure("pkg.c.d", root=toy_project, packages=("pkg",))
    finally:
        sys.path.remove(str(toy_project))
        for name in [n for n in sys.modules if n == "pkg" or n.startswith("pkg.")]:
            del sys.modules[name]
    assert before == after == ["pkg", "pkg.b", "pkg.c", "pkg.c.d"]


def test_imported_sources_of_named_modules(toy_project):
    names = import_closure("pkg.c.d", root=toy_project, packages=("pkg",))
    got = imported_sources(root=toy_project, packages=("pkg",), modules=names)
    assert sorted(got) == ["pkg/__init__.py", "pkg/b.py", "pkg/c/__init__.py", "pkg/c/d.py"]
    assert all(len(h) == 64 for h in got.values())


def test_a_study_closure_leaves_out_other_studies():
    # the quirk this fixes: one study's manifest picked up modules an earlier study loaded
    got = import_closure("studies.pitt_peters_hover_check")
    assert "studies.pitt_peters_hover_check" in got and "aircraft" in got
    assert not [m for m in got if m.startswith("studies.") and m != "studies.pitt_peters_hover_check"]


def test_unknown_module_is_an_error(toy_project):
    with pytest.raises(ModuleNotFoundError, match="not a module of"):
        import_closure("pkg.nope", root=toy_project, packages=("pkg",))
    with pytest.raises(ModuleNotFoundError, match="not a module of"):
        import_closure("numpy", root=toy_project, packages=("pkg",))
