"""Sphinx configuration: the rotorwake-id site, built from the numpydoc docstrings."""
import os
import re
import sys

sys.path.insert(0, os.path.abspath(".."))
os.environ.setdefault("MPLBACKEND", "Agg")

project = "rotorwake-id"
author = "rotorwake-id contributors"
copyright = "2026, rotorwake-id contributors"
try:
    from importlib.metadata import version as _version
    release = _version("rotorwake-id")
except Exception:   # not installed: building from a bare checkout
    release = "0.1.0"

extensions = ["sphinx.ext.autodoc", "sphinx.ext.mathjax", "sphinx.ext.viewcode", "numpydoc"]
numpydoc_show_class_members = False       # members are listed by autodoc itself
numpydoc_class_members_toctree = False
autodoc_member_order = "bysource"
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
# re-exported names would be documented twice (package and module): document modules only
autodoc_typehints = "none"
exclude_patterns = ["_build", "studies/_notes"]   # notes are included by the study pages
html_theme = "alabaster"
html_static_path = ["_static"]
html_theme_options = {"description": "rotor wake identification and coaxial flight control"}


# The docstrings are numpydoc, written as plain text: ``|x|`` means an absolute
# value, a section underline may be a few characters short, and a bullet list
# may follow its lead-in line directly. Read them that way (before numpydoc).
_LITERAL = re.compile(r"(``.*?``)")
_UNDERLINE = re.compile(r"^\s*([-=~^])\1{2,}\s*$")
_BULLET = re.compile(r"^\s*[*-] \S")


def _plain_text_docstring(app, what, name, obj, options, lines):
    fixed = []
    for k, line in enumerate(lines):
        if "|" in line:
            line = "".join(part if part.startswith("``") else part.replace("|", r"\|")
                           for part in _LITERAL.split(line))
        if _UNDERLINE.match(line) and fixed and fixed[-1].strip():
            title = fixed[-1]
            indent = len(line) - len(line.lstrip())
            line = " " * indent + line.strip()[0] * max(len(title.strip()), len(line.strip()))
        elif (_BULLET.match(line) and fixed and fixed[-1].strip() and not _BULLET.match(fixed[-1])
              and len(fixed[-1]) - len(fixed[-1].lstrip()) == len(line) - len(line.lstrip())):
            fixed.append("")
        fixed.append(line)
    lines[:] = fixed


def setup(app):
    app.connect("autodoc-process-docstring", _plain_text_docstring, priority=100)


def _write_api_page(path="api.rst"):
    """Write the API page: one section per package, every public module with __all__.

    Generated at each build so that new modules appear without editing the docs.
    Packages are shown with their docstring only (their names are re-exports),
    modules with their members.
    """
    import importlib
    import pkgutil

    lines = ["API reference", "=============", "",
             "Generated from the numpydoc docstrings at build time. Each package re-exports",
             "its public names in its ``__init__``; they are documented in the module that",
             "defines them.", "", ".. contents::", "   :local:", "   :depth: 1", ""]
    for package in ("flightid", "aircraft", "controllers", "studies.cli", "studies.analysis"):
        root = importlib.import_module(package)
        lines += [package, "-" * len(package), ""]
        if not hasattr(root, "__path__"):
            lines += [f".. automodule:: {package}", ""]
            continue
        lines += [f".. automodule:: {package}", "   :no-members:", ""]
        for info in sorted(pkgutil.walk_packages(root.__path__, package + "."), key=lambda m: m.name):
            if any(part.startswith("_") for part in info.name.split(".")):
                continue
            module = importlib.import_module(info.name)
            if info.ispkg:
                lines += [info.name, "~" * len(info.name), "", f".. automodule:: {info.name}",
                          "   :no-members:", ""]
            elif getattr(module, "__all__", None):
                lines += [f".. automodule:: {info.name}", ""]
    text = "\n".join(lines) + "\n"
    target = os.path.join(os.path.dirname(os.path.abspath(__file__)), path)
    if not os.path.exists(target) or open(target).read() != text:
        with open(target, "w") as fh:
            fh.write(text)


_write_api_page()

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import _studies  # noqa: E402

# the single generated page of earlier versions, if a checkout still has it
_old_page = os.path.join(os.path.dirname(os.path.abspath(__file__)), "studies.rst")
if os.path.exists(_old_page):
    os.remove(_old_page)
_studies.write()   # docs/studies/: one page per command of studies.cli.STUDIES
