"""The code a shipped model file was computed with, by code digest, and its staleness.

A shipped model goes stale like a results folder: when the code that computed it
changes, not only when its recipe's settings do. The code is the static import
closure of :data:`IDENTIFICATION_ENTRY` (:func:`aircraft.provenance.import_closure`,
every ``import`` statement, lazy ones included): the identification pipeline, the
structures, ``flightid``, the wake, the configurations, the inflow models and
whatever they can import. Each module is summarised by
:func:`aircraft.provenance.code_digest` (syntax tree without docstrings and
comments; a package ``__init__`` without its re-exports), the same machinery the
results manifests use, so an edit to documentation alone leaves a model fresh.

A file records ``code_digest`` (one SHA-256 over the sorted per-module digests)
and ``code_digests`` (``{module path: digest}``, which lets a check name the modules
that changed). Both live outside the settings hash: the settings hash still says
whether the recipe changed, the code digest whether the code did, and a file
written before digests were recorded still loads (it is reported stale, "no code
digest").
"""
from __future__ import annotations

import hashlib
import sys
from pathlib import Path

from aircraft.provenance import BACKEND_CODE, PROJECT_PACKAGES, code_digest, import_closure

__all__ = ["IDENTIFICATION_ENTRY", "NO_CODE_DIGEST", "identification_code", "combined_digest",
           "kernel_backend_used", "code_changes", "staleness"]

#: Modules whose import closure is the code of a shipped model: the recipes and
#: :func:`~aircraft.identification.regenerate` (which runs the pipeline, or converts
#: a printed model).
IDENTIFICATION_ENTRY = ("aircraft.identification.shipped",)
#: Staleness reason of a file that records no code digest (written before they were).
NO_CODE_DIGEST = "no code digest"
# bookkeeping that cannot change a model's numbers (the manifests leave it out too)
_NOT_MODEL_CODE = ("aircraft/provenance.py",)
# changed modules named in a staleness reason, at most
_SHOWN = 8


def _root(root):
    return (Path(root) if root is not None else Path(__file__).resolve().parents[2]).resolve()


def identification_code(root=None, *, kernel_backend=None, entry=IDENTIFICATION_ENTRY):
    """Code digest of the identification pipeline's import closure.

    Parameters
    ----------
    root : str or pathlib.Path, optional
        Project root (default: the folder above the ``aircraft`` package).
    kernel_backend : {"cpu", "gpu", "none"}, optional
        Biot-Savart backend the model's wake runs used: a module of
        :data:`aircraft.provenance.BACKEND_CODE` counts only for its own backend.
        None counts every module (the safe side when it is unknown).
    entry : sequence of str
        Dotted names of the modules whose closure is digested.

    Returns
    -------
    code_digest : str
        SHA-256 (64 hex digits) over the sorted ``path digest`` lines.
    code_digests : dict
        ``{module path relative to root: code digest}``, sorted by path.

    Raises
    ------
    ModuleNotFoundError
        If an entry module is not under ``root``.

    Examples
    --------
    >>> digest, modules = identification_code()            # doctest: +SKIP
    >>> "flightid/fitting.py" in modules                     # doctest: +SKIP
    True
    """
    root = _root(root)
    names = sorted({m for e in entry for m in import_closure(e, root=root, packages=PROJECT_PACKAGES)})
    digests = {}
    for name in names:
        base = root.joinpath(*name.split("."))
        path = base / "__init__.py" if (base / "__init__.py").is_file() else base.with_suffix(".py")
        rel = path.relative_to(root).as_posix()
        if rel not in _NOT_MODEL_CODE:
            digests[rel] = code_digest(path)
    return combined_digest(digests, kernel_backend=kernel_backend)


def combined_digest(code_digests, *, kernel_backend=None):
    """One digest over per-module code digests.

    Parameters
    ----------
    code_digests : dict
        ``{module path: code digest}``.
    kernel_backend : {"cpu", "gpu", "none"}, optional
        Leave out the modules of :data:`aircraft.provenance.BACKEND_CODE` of another
        backend (they computed nothing on this one); None keeps every module.

    Returns
    -------
    code_digest : str
        SHA-256 (64 hex digits) of the sorted ``path digest`` lines kept.
    code_digests : dict
        The modules kept, sorted by path.

    Examples
    --------
    >>> digest, kept = combined_digest({"b.py": "2", "aircraft/wake/gpu.py": "1"}, kernel_backend="cpu")
    >>> kept
    {'b.py': '2'}
    >>> digest == combined_digest({"b.py": "2"})[0]
    True
    """
    kept = {rel: d for rel, d in sorted(code_digests.items())
            # code of a backend the runs did not use computed nothing here
            if kernel_backend is None or rel not in BACKEND_CODE or BACKEND_CODE[rel] == kernel_backend}
    text = "".join(f"{rel} {d}\n" for rel, d in kept.items())
    return hashlib.sha256(text.encode()).hexdigest(), kept


def kernel_backend_used():
    """Biot-Savart backend of this process's wake runs: ``"cpu"``, ``"gpu"``, or
    ``"none"`` when no wake code was loaded (then no kernel ran).

    Returns
    -------
    str

    Examples
    --------
    >>> kernel_backend_used() in ("cpu", "gpu", "none")
    True
    """
    biot_savart = sys.modules.get("aircraft.wake.biot_savart")
    return "none" if biot_savart is None else biot_savart.kernel_backend()


def code_changes(recorded, current):
    """Module paths whose code differs between two ``{path: digest}`` maps.

    Parameters
    ----------
    recorded, current : dict
        ``code_digests`` of a file and of the code now.

    Returns
    -------
    list of str
        Sorted paths changed, added (``+path``) or removed (``-path``).

    Examples
    --------
    >>> code_changes({"a.py": "1", "b.py": "2"}, {"a.py": "1", "b.py": "3", "c.py": "4"})
    ['+c.py', 'b.py']
    """
    changed = [p for p in recorded if p in current and recorded[p] != current[p]]
    added = [f"+{p}" for p in current if p not in recorded]
    removed = [f"-{p}" for p in recorded if p not in current]
    return sorted(changed + added + removed)


def staleness(record, want_hash, *, root=None, cache=None):
    """Why a model file no longer matches its recipe and the code, or ``[]`` if it does.

    Parameters
    ----------
    record : aircraft.inflow.model_files.ModelRecord
        The file's record.
    want_hash : str
        The settings hash its recipe gives now.
    root : str or pathlib.Path, optional
        Project root whose code is compared (default: this one).
    cache : dict, optional
        Reused across calls (e.g. over every shipped file) so that the code is
        digested once per root and backend.

    Returns
    -------
    list of str
        Reasons, each naming what differs: ``"settings hash: file X, recipe Y"``,
        ``"no code digest"``, or ``"code digest: changed a.py, +b.py"``.

    Examples
    --------
    >>> from aircraft.inflow.model_files import ModelRecord
    >>> rec = ModelRecord(name="x", form="statespace", rotors=("",), omega=1.0,
    ...                   matrices={"A": [[-1.0]], "B": [[1.0]], "C": [[1.0]]}, inputs=["CT"],
    ...                   outputs=["lam0"], loads_ref=[0.0], inflow_ref=[0.0], settings_hash="ab")
    >>> staleness(rec, "ab")
    ['no code digest']
    """
    reasons = []
    if record.settings_hash != want_hash:
        reasons.append(f"settings hash: file {record.settings_hash}, recipe {want_hash}")
    if not record.code_digest:
        reasons.append(NO_CODE_DIGEST)
        return reasons
    cache = {} if cache is None else cache
    backend = record.provenance.get("kernel_backend")
    if (root, backend) not in cache:
        cache[(root, backend)] = identification_code(root, kernel_backend=backend)
    digest, modules = cache[(root, backend)]
    if record.code_digest != digest:
        # a file written with its per-module digests names the modules; else only the total differs
        names = code_changes(record.code_digests, modules) if record.code_digests else []
        if len(names) > _SHOWN:        # e.g. another Python version: every module differs
            names = names[:_SHOWN] + [f"... ({len(names)} modules in all)"]
        reasons.append("code digest: " + (("changed " + ", ".join(names)) if names else
                                          f"file {record.code_digest[:16]}, code {digest[:16]}"))
    return reasons
