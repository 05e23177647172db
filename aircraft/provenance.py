"""Provenance of computed results: manifests, and a check that says when they are stale.

Every results folder written through the ``rotorwake`` command line carries a
``manifest.json``:

* ``code``: package version, ``git describe --always --dirty`` and a dirty flag;
* ``sources``: the SHA-256 of the bytes of every project module the study can have run: the
  static import closure of the study's module (:func:`import_closure`, every
  ``import`` statement, those inside functions included) together with what the run
  newly put in ``sys.modules`` (dynamic imports). Neither depends on what an earlier
  study in the same process loaded, so ``rotorwake results`` (every study in one
  process) records for each study the code it can depend on, no more;
* ``code_digests`` (schema 2): for the same modules, the :func:`code_digest` of what
  the interpreter runs: the syntax tree with docstrings and comments left out, so an
  edit to documentation alone does not make results stale;
* ``settings`` and ``settings_hash``: the command and its explicit options;
* ``date`` (UTC, ISO 8601), ``wall_time_s`` [s], ``machine`` (cores, platform,
  Python / numpy / numba versions, ``versions``: those of every numerical package
  and the BLAS kernel family in use (:func:`numerical_environment`), and the Biot-Savart ``kernel_backend`` the wake
  runs used: a module of :data:`BACKEND_CODE`, the GPU kernel, can only have
  computed a folder's numbers if its run used that backend);
* ``files``: the SHA-256 of every file in the folder but its hand-written description
  (:data:`RESULTS_DESCRIPTION`).

:func:`aircraft.provenance_check.check_results` re-hashes those modules and files: a folder is *stale*
when the code of a module it was computed with has changed since (its bytes differ
and so does its code digest), and *modified* when one of its files no longer
matches the manifest; its ``versions`` column says whether the numerical packages
differ from those of the run (reported only: a version does not make a folder stale).
A schema-1 manifest (bytes only) is checked on bytes;
:func:`~aircraft.provenance_check.upgrade_manifests` adds the code digests to those whose modules are still
byte-identical, which is the only case where the digests are known to describe the
code that ran. ``rotorwake check-results`` (and
``make check-results``) prints that table and fails when anything is not fresh.

Module paths are stored relative to the project root, so a manifest written on
one machine is checked on another.
"""
from __future__ import annotations

import ast
import dataclasses
import datetime as _dt
import hashlib
import json
import os
import platform
import subprocess
import sys
from pathlib import Path

__all__ = ["MANIFEST_NAME", "PROJECT_PACKAGES", "BACKEND_CODE", "ResultsManifestError", "code_version",
           "settings_hash", "jsonable", "HASHED_IF_SET", "identity_repr", "identity_dict", "file_sha256", "code_digest", "imported_sources", "import_closure", "write_manifest",
           "read_manifest", "numerical_versions", "numerical_environment"]

#: File name of the manifest in each results folder.
MANIFEST_NAME = "manifest.json"
#: A results folder's own description (written by hand, not by the study): never hashed.
RESULTS_DESCRIPTION = "README.md"
#: Packages whose imported modules are recorded (the project's own code).
PROJECT_PACKAGES = ("flightid", "aircraft", "controllers", "studies")
# bookkeeping modules that cannot change a number: not recorded
_NOT_RESULTS_CODE = ("aircraft/provenance.py", "aircraft/provenance_check.py", "studies/cli.py",
                     "studies/commands.py", "aircraft/result_comparison.py")
# distributions whose version can move a computed number, in the order reported
_NUMERICAL_PACKAGES = ("numpy", "scipy", "control", "casadi", "numba", "slycot", "pandas", "matplotlib")
#: Modules that compute numbers only on one Biot-Savart kernel backend: ``{path:
#: backend}``. A change to one makes a folder stale only if its run used that
#: backend (``machine["kernel_backend"]``), as the wake cache keys only GPU runs on
#: the GPU kernel's source. A manifest that does not say which backend ran
#: counts every module.
BACKEND_CODE = {"aircraft/wake/gpu.py": "gpu"}
_SCHEMA = 2
_READABLE_SCHEMAS = (1, 2)


class ResultsManifestError(ValueError):
    """Raised for a missing, unreadable or wrong-schema ``manifest.json``."""


def _project_root():
    return Path(__file__).resolve().parents[1]


def file_sha256(path):
    """SHA-256 hex digest of a file's bytes.

    Parameters
    ----------
    path : str or pathlib.Path
        File to hash.

    Returns
    -------
    str
        64 hexadecimal characters.
    """
    digest = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _strip_docstrings(tree):
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if (body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant)
                    and isinstance(body[0].value.value, str)):
                node.body = body[1:] or [ast.Pass()]
    return tree


def _strip_package_face(tree):
    """A package ``__init__`` without its re-exports: top-level imports and ``__all__``."""
    def is_face(node):
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            return True
        targets = (node.targets if isinstance(node, ast.Assign) else
                   [node.target] if isinstance(node, (ast.AugAssign, ast.AnnAssign)) else [])
        return any(isinstance(t, ast.Name) and t.id == "__all__" for t in targets)
    tree.body = [n for n in tree.body if not is_face(n)] or [ast.Pass()]
    return tree


def code_digest(path):
    """SHA-256 of what a Python module runs: its syntax tree without docstrings.

    Comments, blank lines, line breaks inside brackets and docstrings do not change
    it; any change to a statement, name, constant or default does. In a package's
    ``__init__.py`` the package face is left out too: its top-level import
    statements and ``__all__`` (re-exports cannot change a number; a module they
    import is recorded and checked on its own when a study can run it). A module that
    reads ``__doc__`` keeps its docstrings in the digest (it may print them). The
    digest is prefixed with the interpreter's ``major.minor`` version, because the
    syntax tree's form is specific to it: on another Python the digests never
    match and the byte hash alone decides.

    Parameters
    ----------
    path : str or pathlib.Path
        A ``.py`` file.

    Returns
    -------
    str
        64 hexadecimal characters.

    Raises
    ------
    SyntaxError
        If the file is not valid Python.
    """
    source = Path(path).read_text()
    tree = ast.parse(source, filename=str(path))
    if "__doc__" not in source:
        tree = _strip_docstrings(tree)
    if Path(path).name == "__init__.py":
        tree = _strip_package_face(tree)
    text = f"python{sys.version_info.major}.{sys.version_info.minor}\n" + ast.dump(tree, include_attributes=False)
    return hashlib.sha256(text.encode()).hexdigest()


def _code_digests(sources, root):
    """``{path: code_digest}`` for the ``.py`` files among ``sources`` (paths relative to root)."""
    digests = {}
    for rel in sources:
        path = Path(root) / rel
        if rel.endswith(".py") and path.is_file():
            digests[rel] = code_digest(path)
    return digests


def code_version(root=None):
    """Version of the code: package version, ``git describe`` and dirty flag.

    Parameters
    ----------
    root : str or pathlib.Path, optional
        Project root (default: the folder above this package).

    Returns
    -------
    dict
        ``{"package": str | None, "git": str | None, "dirty": bool | None}``;
        the git entries are None outside a git checkout.
    """
    root = Path(root) if root is not None else _project_root()
    try:
        from importlib.metadata import PackageNotFoundError, version
        try:
            package = version("rotorwake-id")
        except PackageNotFoundError:
            package = None
    except ImportError:   # pragma: no cover - Python >= 3.8 always has it
        package = None
    try:
        described = subprocess.run(["git", "describe", "--always", "--dirty"], cwd=root,
                                   capture_output=True, text=True, timeout=10, check=True).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        described = None
    dirty = None if described is None else described.endswith("-dirty")
    return {"package": package, "git": described, "dirty": dirty}


def settings_hash(settings, digits=64):
    """SHA-256 of the canonical JSON form of ``settings``.

    The one hash of settings in the project: results manifests keep all 64 digits,
    model files the first 16.

    Parameters
    ----------
    settings : dict
        JSON-able settings; numpy arrays and scalars are converted to lists and
        numbers, non-finite floats to ``null``. Keys are sorted before hashing, so
        order does not matter.
    digits : int
        Number of leading hexadecimal digits returned (1-64).

    Returns
    -------
    str
        ``digits`` hexadecimal characters.

    Raises
    ------
    TypeError
        If ``settings`` holds something that is not JSON-able.
    ValueError
        If ``digits`` is not an integer in 1-64.

    Examples
    --------
    >>> settings_hash({"b": 1, "a": [0.5, 2]}, digits=16) == settings_hash({"a": [0.5, 2], "b": 1}, digits=16)
    True
    """
    if isinstance(digits, bool) or not isinstance(digits, int) or not 1 <= digits <= 64:
        raise ValueError(f"digits must be an integer in 1-64, got {digits!r}")
    text = json.dumps(jsonable(settings), sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:digits]


#: Metadata of a dataclass field added after identities were first hashed (a
#: configuration or settings field): it enters :func:`identity_repr` and
#: :func:`identity_dict` only when it differs from its default, so adding such a field
#: leaves every existing hash -- the shipped models' recipes, cache keys -- unchanged.
HASHED_IF_SET = {"hashed": "if_set"}


def _default_of(f):
    if f.default is not dataclasses.MISSING:
        return f.default
    if f.default_factory is not dataclasses.MISSING:
        return f.default_factory()
    return dataclasses.MISSING


def _at_default(f, value):
    """True when field ``f`` is marked :data:`HASHED_IF_SET` and ``value`` is its default."""
    if f.metadata.get("hashed") != "if_set":
        return False
    default = _default_of(f)
    if default is dataclasses.MISSING:
        return False
    try:
        return bool(value == default) if value is not None or default is None else False
    except (TypeError, ValueError):          # arrays and the like: compared by their repr
        return repr(value) == repr(default)


def _identity_fields(obj):
    return [f for f in dataclasses.fields(obj) if f.repr and not _at_default(f, getattr(obj, f.name))]


def identity_repr(obj, exclude=()):
    """``repr(obj)`` of nested dataclasses without the unset :data:`HASHED_IF_SET` fields.

    Equal to the dataclasses' own ``repr`` when no such field is set, so a hash of it
    does not change when a field with a neutral default is added to a class.

    Parameters
    ----------
    obj : object
        A dataclass instance, or tuples, lists and dicts of them; anything else is
        written with ``repr``.
    exclude : iterable of str
        Fields of ``obj`` itself (not of nested dataclasses) left out.

    Returns
    -------
    str

    Examples
    --------
    >>> import dataclasses
    >>> @dataclasses.dataclass
    ... class Rotor:
    ...     radius: float
    ...     tip_loss: str = dataclasses.field(default="none", metadata=HASHED_IF_SET)
    >>> identity_repr(Rotor(8.18)), identity_repr(Rotor(8.18, "prandtl"))
    ('Rotor(radius=8.18)', "Rotor(radius=8.18, tip_loss='prandtl')")
    """
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        items = ", ".join(f"{f.name}={identity_repr(getattr(obj, f.name))}" for f in _identity_fields(obj)
                          if f.name not in exclude)
        return f"{type(obj).__qualname__}({items})"
    if isinstance(obj, tuple) and type(obj) is tuple:
        inner = ", ".join(identity_repr(v) for v in obj)
        return f"({inner},)" if len(obj) == 1 else f"({inner})"
    if isinstance(obj, list) and type(obj) is list:
        return "[" + ", ".join(identity_repr(v) for v in obj) + "]"
    if isinstance(obj, dict) and type(obj) is dict:
        return "{" + ", ".join(f"{identity_repr(k)}: {identity_repr(v)}" for k, v in obj.items()) + "}"
    return repr(obj)


def identity_dict(obj):
    """:func:`dataclasses.asdict` without the unset :data:`HASHED_IF_SET` fields.

    Parameters
    ----------
    obj : dataclass instance

    Returns
    -------
    dict

    Examples
    --------
    >>> import dataclasses
    >>> @dataclasses.dataclass
    ... class Settings:
    ...     step: float = 0.1
    ...     perturbation: float = dataclasses.field(default=0.0, metadata=HASHED_IF_SET)
    >>> identity_dict(Settings()), identity_dict(Settings(perturbation=1e-7))
    ({'step': 0.1}, {'step': 0.1, 'perturbation': 1e-07})
    """
    if not (dataclasses.is_dataclass(obj) and not isinstance(obj, type)):
        raise TypeError(f"identity_dict needs a dataclass instance, got {type(obj).__name__}")
    return _identity_value(obj)


def _identity_value(v):
    import copy
    if dataclasses.is_dataclass(v) and not isinstance(v, type):
        return {f.name: _identity_value(getattr(v, f.name)) for f in dataclasses.fields(v)
                if not _at_default(f, getattr(v, f.name))}
    if isinstance(v, tuple) and hasattr(v, "_fields"):       # named tuple, as asdict does
        return type(v)(*[_identity_value(x) for x in v])
    if isinstance(v, (list, tuple)):
        return type(v)(_identity_value(x) for x in v)
    if isinstance(v, dict):
        return type(v)((_identity_value(k), _identity_value(x)) for k, x in v.items())
    return copy.deepcopy(v)


def jsonable(x):
    """``x`` as plain JSON data: arrays and numpy scalars to lists and numbers, tables to
    lists of records, non-finite floats to None.

    Parameters
    ----------
    x : object
        Nested dicts, lists and tuples of numbers, strings, numpy arrays and scalars and
        pandas DataFrames.

    Returns
    -------
    object
        The same structure in JSON types (dict keys as strings).

    Examples
    --------
    >>> import numpy as np
    >>> jsonable({"a": np.array([1.0, np.nan])})
    {'a': [1.0, None]}
    """
    import math
    if isinstance(x, dict):
        return {str(k): jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if hasattr(x, "to_dict") and hasattr(x, "columns"):        # a pandas DataFrame
        return jsonable(x.to_dict(orient="records"))
    if hasattr(x, "tolist") and not isinstance(x, (str, bytes)):  # numpy array or scalar
        return jsonable(x.tolist())
    if isinstance(x, bool) or x is None or isinstance(x, (str, int)):
        return x
    if isinstance(x, float):
        return x if math.isfinite(x) else None
    return x


def _module_file(name, root):
    """File of project module ``name`` under ``root`` (package ``__init__`` or module), or None."""
    base = root.joinpath(*name.split("."))
    for candidate in (base / "__init__.py", base.with_suffix(".py")):
        if candidate.is_file():
            return candidate
    return None


def _imported_names(path, name):
    """Absolute names of the modules ``path`` (module ``name``) imports, anywhere in it."""
    tree = ast.parse(path.read_text(), filename=str(path))
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                parts = package.split(".")
                stem = ".".join(parts[:len(parts) - node.level + 1])
                mod = f"{stem}.{node.module}" if node.module else stem
            else:
                mod = node.module or ""
            found.append(mod)
            # "from pkg import sub" may name a submodule
            found += [f"{mod}.{alias.name}" for alias in node.names if alias.name != "*"]
    return found


def import_closure(module, root=None, packages=PROJECT_PACKAGES):
    """Project modules ``module`` can import, directly or through others: its static closure.

    Every ``import`` and ``from ... import`` statement counts, inside functions too
    (the library imports lazily), and importing ``a.b.c`` imports the packages
    ``a`` and ``a.b``. The closure over-approximates what one run executes, which is
    the safe side for a staleness check: it is what a study's numbers can depend on,
    whatever an earlier study in the same process loaded.

    Parameters
    ----------
    module : str
        Dotted name of a project module (e.g. ``"studies.coaxial_quasi_steady"``).
    root : str or pathlib.Path, optional
        Project root (default: the folder above this package).
    packages : sequence of str
        Top-level packages that are the project's.

    Returns
    -------
    list of str
        Dotted module names, sorted, ``module`` included.

    Raises
    ------
    ModuleNotFoundError
        If ``module`` is not a project module under ``root``.
    """
    root = (Path(root) if root is not None else _project_root()).resolve()
    if module.split(".")[0] not in packages or _module_file(module, root) is None:
        raise ModuleNotFoundError(f"{module!r} is not a module of {tuple(packages)} under {root}")
    seen, todo = set(), [module]
    while todo:
        name = todo.pop()
        parts = name.split(".")
        for k in range(1, len(parts) + 1):        # parent packages run their __init__
            sub = ".".join(parts[:k])
            if sub in seen:
                continue
            path = _module_file(sub, root)
            if path is None:
                continue
            seen.add(sub)
            todo += [n for n in _imported_names(path, sub) if n.split(".")[0] in packages]
    return sorted(seen)


def imported_sources(root=None, packages=PROJECT_PACKAGES, modules=None):
    """SHA-256 of each project module now in ``sys.modules`` (or of ``modules``).

    Parameters
    ----------
    root : str or pathlib.Path, optional
        Project root; module files must lie under it (an installed, non-editable
        copy elsewhere is skipped).
    packages : sequence of str
        Top-level package names to record.
    modules : iterable of str, optional
        Dotted module names to record instead of everything in ``sys.modules``
        (e.g. :func:`import_closure` of a study plus what its run imported).

    Returns
    -------
    dict
        ``{relative posix path: sha256}``, sorted by path.
    """
    root = (Path(root) if root is not None else _project_root()).resolve()
    if modules is None:
        items = [(name, getattr(module, "__file__", None)) for name, module in list(sys.modules.items())]
    else:
        items = [(name, _module_file(name, root)) for name in modules]
    found = {}
    for name, path in items:
        if name.split(".")[0] not in packages:
            continue
        if not path:
            continue
        path = Path(path).resolve()
        try:
            rel = path.relative_to(root)
        except ValueError:
            continue
        if path.is_file() and rel.as_posix() not in _NOT_RESULTS_CODE:
            found[rel.as_posix()] = file_sha256(path)
    return dict(sorted(found.items()))


def _kernel_backend():
    """The Biot-Savart backend of this process's wake runs: ``"cpu"``, ``"gpu"``, or
    ``"none"`` when no wake code was loaded (then no kernel ran)."""
    biot_savart = sys.modules.get("aircraft.wake.biot_savart")
    if biot_savart is None:
        return "none"
    # the backend in force (resolved on first use); the executor refuses wake
    # results computed on another backend than the caller's, so this is every run's
    return biot_savart.kernel_backend()


def numerical_versions():
    """Versions of Python and of the numerical packages a result can depend on.

    Read from the installed distributions' metadata, so nothing heavy is imported.

    Returns
    -------
    dict
        ``{"python": str, "numpy": str | None, ...}``: Python, numpy, scipy, control
        (python-control), casadi, numba, slycot, pandas and matplotlib, in that order;
        None for a package that is not installed.

    Examples
    --------
    >>> versions = numerical_versions()
    >>> list(versions)[:4]
    ['python', 'numpy', 'scipy', 'control']
    >>> versions["python"] == platform.python_version()
    True
    """
    from importlib.metadata import PackageNotFoundError, version
    found = {"python": platform.python_version()}
    for name in _NUMERICAL_PACKAGES:
        try:
            found[name] = version(name)
        except PackageNotFoundError:
            found[name] = None
    return found


def numerical_environment():
    """:func:`numerical_versions` and the BLAS kernels in use: what a manifest records.

    Sums round differently from one BLAS kernel family to another (AVX-512, AVX2,
    ...), so a number computed with another can differ in its last digits, and an
    optimiser's path more. numpy is imported to read which kernels its BLAS loaded.

    Returns
    -------
    dict
        :func:`numerical_versions` plus ``"blas"``: each BLAS library loaded and its
        kernel family, e.g. ``"openblas 0.3.30 Haswell"`` (None when none is found).

    Examples
    --------
    >>> env = numerical_environment()
    >>> list(env)[-1], env["numpy"] == numerical_versions()["numpy"]
    ('blas', True)
    """
    import numpy  # noqa: F401  (loads numpy's BLAS, whose kernels are the ones recorded)
    from threadpoolctl import threadpool_info
    found = {f"{i.get('internal_api')} {i.get('version')} {i.get('architecture')}"
             for i in threadpool_info() if i.get("user_api") == "blas"}
    return {**numerical_versions(), "blas": ", ".join(sorted(found)) or None}


def write_manifest(folder, *, command, settings, wall_time_s, root=None, sources=None):
    """Write ``manifest.json`` into a results folder.

    Parameters
    ----------
    folder : str or pathlib.Path
        Results folder (must exist; every file in it is hashed).
    command : str
        What produced it, e.g. ``"rotorwake wake-identification"``.
    settings : dict
        JSON-serialisable settings of the run (hashed into ``settings_hash``).
    wall_time_s : float
        Wall-clock time of the run [s].
    root : str or pathlib.Path, optional
        Project root (default: the folder above this package).
    sources : dict, optional
        ``{path: sha256}`` of the code used; default :func:`imported_sources` now.

    Returns
    -------
    pathlib.Path
        Path of the manifest written.

    Raises
    ------
    FileNotFoundError
        If ``folder`` does not exist.
    """
    folder = Path(folder)
    if not folder.is_dir():
        raise FileNotFoundError(f"results folder {folder} does not exist")
    versions = numerical_environment()
    files = {p.name: file_sha256(p) for p in sorted(folder.iterdir())
             if p.is_file() and p.name not in (MANIFEST_NAME, RESULTS_DESCRIPTION)}
    root_path = Path(root) if root is not None else _project_root()
    sources = sources if sources is not None else imported_sources(root)
    manifest = {
        "schema": _SCHEMA,
        "command": command,
        "settings": settings,
        "settings_hash": settings_hash(settings),
        "code": code_version(root),
        "sources": sources,
        "code_digests": _code_digests(sources, root_path),
        "date": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "wall_time_s": round(float(wall_time_s), 2),
        "machine": {"cores": os.cpu_count(), "platform": platform.platform(),
                    # the top-level three for readers older than "versions"
                    **{k: versions[k] for k in ("python", "numpy", "numba")}, "versions": versions,
                    "kernel_backend": _kernel_backend()},
        "files": files,
    }
    path = folder / MANIFEST_NAME
    path.write_text(json.dumps(manifest, indent=2, sort_keys=False) + "\n")
    return path


def read_manifest(folder):
    """Read and validate ``folder/manifest.json``.

    Parameters
    ----------
    folder : str or pathlib.Path
        Results folder.

    Returns
    -------
    dict
        The manifest.

    Raises
    ------
    ResultsManifestError
        If the manifest is missing, is not JSON, or has another schema.
    """
    path = Path(folder) / MANIFEST_NAME
    if not path.is_file():
        raise ResultsManifestError(f"{path} is missing: results not written by `rotorwake`")
    try:
        manifest = json.loads(path.read_text())
    except json.JSONDecodeError as exc:
        raise ResultsManifestError(f"{path} is not valid JSON: {exc}") from exc
    if manifest.get("schema") not in _READABLE_SCHEMAS:
        raise ResultsManifestError(f"{path} has schema {manifest.get('schema')!r}, expected one of "
                                   f"{_READABLE_SCHEMAS}")
    return manifest

