"""Checks of recorded provenance: which results folders the code no longer produces, and under what.

:func:`check_results` re-hashes the modules and files a results folder's manifest
records (:mod:`aircraft.provenance`) and says, folder by folder, whether it is
*fresh*, *stale* (the code of a module it was computed with changed: bytes and
:func:`~aircraft.provenance.code_digest` both differ) or *modified* (a file no
longer matches the manifest), and whether the numerical packages and BLAS kernels
of its run differ from those installed now (reported, never a reason to be stale).
:func:`upgrade_manifests` and :func:`record_kernel_backend` complete older
manifests where the facts are known; :func:`record_environment` adds the numerical
environment to a model file just written, and :func:`environment_note` compares it.

Only the command line and the tests import this module, never the library: it
stays out of the code a result or a shipped model is computed with (its import
closure), so a change here stales nothing.
"""
from __future__ import annotations

import json
from pathlib import Path

from aircraft.provenance import (BACKEND_CODE, MANIFEST_NAME, RESULTS_DESCRIPTION, _SCHEMA, ResultsManifestError,
                                 _code_digests, _project_root, code_digest, file_sha256, numerical_environment,
                                 read_manifest)

__all__ = ["check_results", "upgrade_manifests", "record_kernel_backend", "record_environment", "environment_note"]


def _versions_note(machine, now):
    """``versions`` column of :func:`check_results`: the run's versions (``machine``
    of its manifest) against ``now``; the older top-level python/numpy/numba count."""
    recorded = {k: machine[k] for k in ("python", "numpy", "numba") if k in machine}
    recorded.update(machine.get("versions") or {})
    known = [k for k in now if k in recorded]
    differs = [f"{k} {recorded[k] or 'not installed'} (now {now[k] or 'not installed'})"
               for k in known if recorded[k] != now[k]]
    same = [k for k in known if recorded[k] == now[k]]
    missing = [k for k in now if k not in recorded]
    if not missing:
        return "differs: " + ", ".join(differs) if differs else "same"
    if not known:
        return "not recorded"
    inner = "; ".join(([f"differs: {', '.join(differs)}"] if differs else [])
                      + ([f"{', '.join(same)} same"] if same else []))
    return f"partly recorded ({inner}); not recorded: {', '.join(missing)}"


def record_environment(path):
    """Add this process's :func:`numerical_environment` to a model file's provenance.

    A shipped model file (``aircraft/data/models/*.json``) records the code and
    settings it was computed with; this adds the packages and BLAS kernels, as
    ``provenance["environment"]``. ``rotorwake shipped-models NAME`` calls it right
    after writing the file, in the process that computed it (the library's writer
    is part of every model's code digest, so recording it there would make every
    shipped model stale until all are regenerated).

    Parameters
    ----------
    path : str or pathlib.Path
        A model file just written by this process.

    Returns
    -------
    dict
        The environment recorded.

    Raises
    ------
    aircraft.inflow.model_files.ModelFileError
        If ``path`` does not exist or is not a readable model file.

    See Also
    --------
    environment_note : the recorded environment against this one.
    """
    from aircraft.inflow.model_files import load_record
    # read and written by the model files' own reader and writer (their round trip is lossless)
    record = load_record(Path(path))
    env = numerical_environment()
    record.provenance = {**record.provenance, "environment": env}
    record.save(path)
    return env


def environment_note(path):
    """The environment a model file records against this process's.

    Parameters
    ----------
    path : str or pathlib.Path
        A model file (``aircraft/data/models/*.json`` or one written by
        :meth:`aircraft.inflow.model_files.ModelRecord.save`).

    Returns
    -------
    str
        ``"same"``, ``"differs: scipy 1.16.0 (now 1.17.1), ..."``, or ``"not
        recorded"`` for a file written before the environment was recorded.

    See Also
    --------
    record_environment : records it.

    Examples
    --------
    >>> import shutil, tempfile
    >>> from aircraft.inflow.model_files import shipped_model_path
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     copy = shutil.copy(shipped_model_path("published_eq5_3"), tmp)
    ...     env = record_environment(copy)
    ...     note = environment_note(copy)
    >>> note
    'same'
    """
    from aircraft.inflow.model_files import load_record
    recorded = load_record(Path(path)).provenance.get("environment") or {}
    return _versions_note({"versions": recorded}, numerical_environment())


def check_results(results_root="results", root=None):
    """Say, folder by folder, whether committed results are what the code gives now.

    Parameters
    ----------
    results_root : str or pathlib.Path
        Folder holding one sub-folder per study.
    root : str or pathlib.Path, optional
        Project root the manifests' module paths are relative to.

    Returns
    -------
    pandas.DataFrame
        One row per results folder: ``folder``, ``status`` (``"fresh"``,
        ``"stale"``: a module it was computed with changed or is gone,
        ``"modified"``: a file differs from the manifest, ``"no manifest"``),
        ``date`` of the run, ``detail`` (which modules or files) and ``versions``
        (``"same"``, ``"differs: scipy 1.16.0 (now 1.17.1)"``, or ``"partly
        recorded (...); not recorded: ..."`` for an older manifest): the
        numerical packages of the run against :func:`numerical_versions` now. A
        version difference is reported, it does not make a folder stale.
    """
    import pandas as pd
    root = Path(root) if root is not None else _project_root()
    rows, now = [], numerical_environment()
    for folder in sorted(p for p in Path(results_root).iterdir() if p.is_dir()):
        try:
            manifest = read_manifest(folder)
        except ResultsManifestError as exc:
            rows.append({"folder": folder.name, "status": "no manifest", "date": None, "detail": str(exc),
                         "versions": None})
            continue
        changed, documentation = _changed_sources(manifest, root)
        edited = [name for name, digest in manifest["files"].items()
                  if not (folder / name).is_file() or file_sha256(folder / name) != digest]
        extra = sorted(p.name for p in folder.iterdir()
                       if p.is_file() and p.name not in (MANIFEST_NAME, RESULTS_DESCRIPTION)
                       and p.name not in manifest["files"])
        if changed:
            status, detail = "stale", "code changed since the run: " + ", ".join(changed)
        elif edited or extra:
            status, detail = "modified", "files differ from the manifest: " + ", ".join(edited + extra)
        else:
            status, detail = "fresh", f"{manifest['command']} ({manifest['code']['git']})"
            if documentation:
                detail += "; documentation only changed since in: " + ", ".join(documentation)
        rows.append({"folder": folder.name, "status": status, "date": manifest["date"], "detail": detail,
                     "versions": _versions_note(manifest.get("machine", {}), now)})
    return pd.DataFrame(rows, columns=["folder", "status", "date", "detail", "versions"])


def _changed_sources(manifest, root):
    """(modules whose code changed, modules whose bytes changed but code did not)."""
    digests = manifest.get("code_digests", {})
    backend = manifest.get("machine", {}).get("kernel_backend")
    changed, documentation = [], []
    for rel, digest in manifest["sources"].items():
        if backend is not None and rel in BACKEND_CODE and BACKEND_CODE[rel] != backend:
            continue      # code of a backend the run did not use: it computed nothing here
        path = root / rel
        if not path.is_file():
            changed.append(rel)
        elif file_sha256(path) != digest:
            try:
                same_code = rel in digests and code_digest(path) == digests[rel]
            except SyntaxError:
                same_code = False
            (documentation if same_code else changed).append(rel)
    return changed, documentation


def _readable_manifests(results_root):
    """(folder, manifest) of each results folder whose manifest reads (others are skipped)."""
    for folder in sorted(p for p in Path(results_root).iterdir() if p.is_dir()):
        try:
            yield folder, read_manifest(folder)
        except ResultsManifestError:
            continue


def upgrade_manifests(results_root="results", root=None):
    """Add code digests to the schema-1 manifests whose modules are byte-identical now.

    A schema-1 manifest records only the bytes of each module. Where every module
    it lists still has those bytes, the code that ran is the code on disk, so its
    :func:`code_digest` can be recorded honestly; the manifest is rewritten as
    schema 2 (nothing else in it changes). Any other folder is left as it is.

    Parameters
    ----------
    results_root : str or pathlib.Path
        Folder holding one sub-folder per study.
    root : str or pathlib.Path, optional
        Project root the manifests' module paths are relative to.

    Returns
    -------
    list of str
        Names of the folders upgraded.
    """
    root = Path(root) if root is not None else _project_root()
    upgraded = []
    for folder, manifest in _readable_manifests(results_root):
        if manifest["schema"] != 1:
            continue
        if any(not (root / rel).is_file() or file_sha256(root / rel) != digest
               for rel, digest in manifest["sources"].items()):
            continue
        manifest["schema"] = _SCHEMA
        upgraded_manifest = {}
        for key, value in manifest.items():
            upgraded_manifest[key] = value
            if key == "sources":
                upgraded_manifest["code_digests"] = _code_digests(value, root)
        (folder / MANIFEST_NAME).write_text(json.dumps(upgraded_manifest, indent=2, sort_keys=False) + "\n")
        upgraded.append(folder.name)
    return upgraded


def record_kernel_backend(results_root="results", backend="cpu", root=None):
    """Say which kernel backend the runs of older manifests used, where it is known.

    Manifests written before ``machine["kernel_backend"]`` existed do not say, so
    :func:`check_results` counts every module for them, the GPU kernel's too. Who
    knows where they were computed can record it here: it is an attestation, not
    a measurement, so it is never done implicitly. Only folders that are not stale
    but for modules of :data:`BACKEND_CODE` of another backend are marked (a
    folder that is stale for any other reason stays as it is), and only the
    ``machine`` entry changes.

    Parameters
    ----------
    results_root : str or pathlib.Path
        Folder holding one sub-folder per study.
    backend : {"cpu", "gpu"}
        The backend the runs used.
    root : str or pathlib.Path, optional
        Project root the manifests' module paths are relative to.

    Returns
    -------
    list of str
        Names of the folders marked.

    Raises
    ------
    ValueError
        For a backend other than ``"cpu"`` or ``"gpu"``.
    """
    if backend not in ("cpu", "gpu"):
        raise ValueError(f"backend must be 'cpu' or 'gpu', got {backend!r}")
    root = Path(root) if root is not None else _project_root()
    marked = []
    for folder, manifest in _readable_manifests(results_root):
        if "kernel_backend" in manifest.get("machine", {}):
            continue
        attested = {**manifest, "machine": {**manifest.get("machine", {}), "kernel_backend": backend}}
        changed, _ = _changed_sources(attested, root)
        if changed:
            continue
        (folder / MANIFEST_NAME).write_text(json.dumps(attested, indent=2, sort_keys=False) + "\n")
        marked.append(folder.name)
    return marked
