"""On-disk cache of wake runs that cannot serve garbage.

Every entry is one file ``<key>.pkl`` in the cache folder::

    ROTORWAKE-CACHE\\n
    {"schema": 1, "code": "wake-3", "key": "...", "kind": "run", "length": N, "sha256": "..."}\\n
    <N bytes: the pickled value>

and is

* written atomically: to a temporary file in the same folder, flushed to disk,
  then renamed over the final name with :func:`os.replace`, so a reader sees
  either the whole old entry, the whole new one, or none (a run killed while
  writing leaves only a ``*.tmp`` file, which is never read);
* checked on every read: the header, the schema version and the code version
  (a *stale* entry from older marching code), the key the entry was stored under
  (an entry copied or renamed onto another key has the *wrong contents*), the
  payload length (*truncated*) and its SHA-256 (*corrupt*), then the value itself
  (finite numbers, a converged trim);
* never trusted when a check fails: a :class:`CacheWarning` says which check and
  which file, the entry is deleted and the caller recomputes it.

Faults
------
* Several processes may fill the same entry at once (two studies sharing a
  folder): each writes its own temporary file (process id + random suffix, so
  no two writers ever share one) and the last :func:`os.replace` wins; both
  values are whole, checked entries of the same key, so no lock is needed.  An
  entry found bad is deleted only if it is still the file that was read, not a
  good one another process has just put in its place.
* A write that fails (full disk, quota, read-only folder) removes its temporary
  file and raises :class:`CacheWriteError` (an :class:`OSError` keeping the
  ``errno``); :func:`aircraft.wake.run_sweeps` turns a *full* disk into a
  :class:`CacheStoreWarning` and keeps the computed value.

Values are also checked to be finite *before* they are stored: a run with NaN in
it is an error (:class:`WakeCacheError`), never an entry.

Location
--------
:func:`resolve_cache_dir` picks the folder: an explicit argument wins; otherwise
the environment variable ``ROTORWAKE_CACHE_DIR``; otherwise ``.cache/wake``
relative to the working directory.  Set the variable to an empty string, ``0``
or ``off`` to disable the cache (an explicit ``cache_dir=None`` does the same).

Entries are pickles: keep the cache folder private (unpickling runs code).
"""
from __future__ import annotations

import errno
import hashlib
import json
import math
import os
import pickle
import time
import uuid
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

__all__ = ["CACHE_ENV", "DEFAULT_CACHE_DIR", "SCHEMA_VERSION", "CacheWarning", "CacheStoreWarning",
           "WakeCacheError", "CacheWriteError", "WakeCache", "resolve_cache_dir", "check_finite_frame"]

#: environment variable naming the cache folder
CACHE_ENV = "ROTORWAKE_CACHE_DIR"
#: folder used when neither an argument nor the environment variable names one
DEFAULT_CACHE_DIR = ".cache/wake"
#: layout of an entry file; bump when the file format changes
SCHEMA_VERSION = 1
_MAGIC = b"ROTORWAKE-CACHE\n"
_MAX_HEADER = 4096
#: temporary files older than this [s] are left-overs of killed runs and are removed
_STALE_TMP_AGE = 24 * 3600.0
#: errno values meaning "no room left": the value is fine, only the storage is exhausted
_NO_SPACE_ERRNOS = frozenset(e for e in (getattr(errno, n, None) for n in ("ENOSPC", "EDQUOT", "EFBIG"))
                            if e is not None)


class CacheWarning(UserWarning):
    """A cache entry failed a check (corrupt, truncated, stale, wrong contents, non-finite)
    and is being recomputed."""


class CacheStoreWarning(CacheWarning):
    """A computed value could not be stored (the disk is full); it is returned, not cached."""


class WakeCacheError(ValueError):
    """A value cannot be stored: it holds NaN/inf, or is not what the cache keeps."""


class CacheWriteError(OSError):
    """Writing a cache entry failed (full disk, quota, read-only or vanished folder).

    ``errno`` is the failed call's (e.g. :data:`errno.ENOSPC`); the temporary
    file has been removed and no entry was written.
    """

    @property
    def no_space(self):
        """True when the storage is full (ENOSPC, EDQUOT, EFBIG), not misconfigured."""
        return self.errno in _NO_SPACE_ERRNOS


def resolve_cache_dir(cache_dir="default"):
    """The cache folder to use, or None for no cache.

    Parameters
    ----------
    cache_dir : str, Path, None or "default"
        A folder; None disables the cache; ``"default"`` means: the environment
        variable ``ROTORWAKE_CACHE_DIR`` if set (empty, ``0`` or ``off``
        disable the cache), else ``.cache/wake``.

    Returns
    -------
    pathlib.Path or None
    """
    if cache_dir is None:
        return None
    if isinstance(cache_dir, str) and cache_dir == "default":
        env = os.environ.get(CACHE_ENV)
        if env is None:
            return Path(DEFAULT_CACHE_DIR)
        if env.strip().lower() in ("", "0", "off", "none", "false"):
            return None
        return Path(env).expanduser()
    if not isinstance(cache_dir, (str, os.PathLike)):
        raise WakeCacheError(f"cache_dir must be a folder path, None or 'default', got {cache_dir!r}")
    return Path(cache_dir).expanduser()


def check_finite_frame(df, what="run"):
    """Raise :class:`WakeCacheError` unless ``df`` is a non-empty DataFrame of finite numbers.

    Parameters
    ----------
    df : pandas.DataFrame
        Frame to check (every column numeric and finite).
    what : str
        Label starting the error message.

    Returns
    -------
    pandas.DataFrame
        ``df`` itself.

    Raises
    ------
    WakeCacheError
        If ``df`` is not a DataFrame, is empty, or has non-numeric or non-finite columns.
    """
    if not isinstance(df, pd.DataFrame):
        raise WakeCacheError(f"{what}: expected a pandas.DataFrame, got {type(df).__name__}")
    if df.empty:
        raise WakeCacheError(f"{what}: the DataFrame is empty")
    num = df.select_dtypes(include=[np.number])
    if num.shape[1] != df.shape[1]:
        other = [c for c in df.columns if c not in num.columns]
        raise WakeCacheError(f"{what}: non-numeric columns {other}")
    bad = [c for c in num.columns if not np.all(np.isfinite(num[c].to_numpy()))]
    if bad:
        raise WakeCacheError(f"{what}: NaN or infinite values in columns {bad}")
    return df


def _finite_tree(value, path="value"):
    """Names of the non-finite numbers inside nested dicts/lists/arrays (for trim snapshots)."""
    bad = []
    if isinstance(value, dict):
        for k, v in value.items():
            bad += _finite_tree(v, f"{path}[{k!r}]")
    elif isinstance(value, (list, tuple)):
        for k, v in enumerate(value):
            bad += _finite_tree(v, f"{path}[{k}]")
    elif isinstance(value, np.ndarray):
        if np.issubdtype(value.dtype, np.number) and not np.all(np.isfinite(value)):
            bad.append(path)
    elif isinstance(value, (float, np.floating)) and not math.isfinite(value):
        bad.append(path)
    return bad


class WakeCache:
    """A folder of checked, atomically written entries (see the module docstring).

    Parameters
    ----------
    directory : str or Path
        Cache folder (created if missing).
    code_version : str
        Version of the code that computes the entries; an entry written by
        another version is stale and is recomputed.
    """

    def __init__(self, directory, code_version):
        self.directory = Path(directory)
        self.code_version = str(code_version)
        self.directory.mkdir(parents=True, exist_ok=True)
        self._remove_stale_tmp()

    def path(self, key):
        """File of the entry ``key``."""
        return self.directory / f"{key}.pkl"

    def _remove_stale_tmp(self):
        now = time.time()
        for p in self.directory.glob(".*.tmp"):
            try:
                if now - p.stat().st_mtime > _STALE_TMP_AGE:
                    p.unlink()
            except OSError:   # another process removed or is renaming it
                pass

    # ------------------------------------------------------------------ write
    def store(self, key, value, kind="run", check=None):
        """Write ``value`` under ``key`` atomically.

        Parameters
        ----------
        key : str
            Entry name.
        value : object
            Picklable value.
        kind : str
            Kind of entry (``"run"``, ``"trim"``), checked on reading.
        check : callable, optional
            ``check(value)`` (e.g. :func:`check_finite_frame`) must pass first;
            it raises :class:`WakeCacheError` for a value that may not be stored.

        Returns
        -------
        pathlib.Path
            The entry's file.

        Raises
        ------
        WakeCacheError
            ``check`` refused the value; nothing is written.
        CacheWriteError
            The file could not be written (full disk, quota, read-only folder):
            its temporary file is removed and any older entry is left untouched.
        """
        if check is not None:
            check(value)
        payload = pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
        header = {"schema": SCHEMA_VERSION, "code": self.code_version, "key": str(key),
                  "kind": kind, "length": len(payload),
                  "sha256": hashlib.sha256(payload).hexdigest()}
        final = self.path(key)
        # a name no other writer can pick (pid + random): two processes filling the
        # same entry never write into one file; the last os.replace wins, whole
        tmp = self.directory / f".{final.name}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp"
        try:
            with open(tmp, "wb") as f:
                f.write(_MAGIC)
                f.write(json.dumps(header, sort_keys=True).encode() + b"\n")
                f.write(payload)
                f.flush()
                os.fsync(f.fileno())
            os.replace(tmp, final)
        except OSError as e:
            if e.errno is None:
                raise CacheWriteError(f"cannot write wake cache entry {final}: {e}") from e
            raise CacheWriteError(e.errno, f"cannot write wake cache entry {final}: "
                                  f"{e.strerror or e}") from e
        finally:
            try:
                tmp.unlink()     # still there only if the write or the rename failed
            except FileNotFoundError:
                pass
            except OSError:      # e.g. the folder went read-only: the name is never read anyway
                pass
        return final

    # ------------------------------------------------------------------- read
    def load(self, key, kind="run", check=None):
        """The value stored under ``key``, or None when absent or failing a check.

        A failing entry is reported with a :class:`CacheWarning` naming the
        check, deleted, and None returned so the caller recomputes it.
        """
        p = self.path(key)
        if not p.exists():
            return None
        read = {}
        try:
            try:
                value = self._read(p, key, kind, read)
            except _LegacyEntry as legacy:
                value = self._migrate(p, key, kind, check, legacy.args[0])
            if check is not None:
                check(value)
        except _BadEntry as e:
            self._discard(p, str(e), read.get("identity"))
            return None
        except WakeCacheError as e:
            self._discard(p, f"wrong contents: {e}", read.get("identity"))
            return None
        return value

    def _migrate(self, p, key, kind, check, blob):
        """An entry in the plain-pickle format of earlier versions (no header, no checksum).

        Hour-long runs are not thrown away for their format: the pickle is read,
        and kept only if it passes the same content check as a new entry (finite
        values, the spec it was computed for); it is then rewritten in the
        checked format.  Anything else is reported and recomputed.
        """
        if check is None:
            raise _BadEntry("not a rotorwake cache entry (corrupt, or an unchecked older format)")
        try:
            value = pickle.loads(blob)
        except Exception:
            raise _BadEntry("corrupt: neither a rotorwake cache entry nor a readable "
                            "older-format pickle") from None
        try:
            check(value)
        except WakeCacheError as e:
            raise _BadEntry(f"older-format entry with wrong contents: {e}") from None
        try:
            self.store(key, value, kind=kind, check=check)
        except CacheWriteError as e:
            if not e.no_space:
                raise
            # the old file still holds the value: serve it, rewrite it another time
            warnings.warn(f"wake cache entry {p} is in the older unchecked format and could not be "
                          f"rewritten ({e}); it is used as it is", CacheStoreWarning, stacklevel=4)
            return value
        warnings.warn(f"wake cache entry {p} was in the older unchecked format; it passed the "
                      "content checks and was rewritten with a checksum", CacheWarning, stacklevel=4)
        return value

    def _discard(self, p, why, identity=None):
        warnings.warn(f"wake cache entry {p} is unusable ({why}); recomputing it",
                      CacheWarning, stacklevel=3)
        try:
            # another process may have replaced the bad file by a good entry since it
            # was read: delete only the file that failed (same inode, size and time)
            if identity is not None and _identity(os.stat(p)) != identity:
                return
            p.unlink()
        except OSError:
            pass

    def _read(self, p, key, kind, read=None):
        try:
            with open(p, "rb") as f:
                if read is not None:
                    read["identity"] = _identity(os.fstat(f.fileno()))
                blob = f.read()
        except OSError as e:
            raise _BadEntry(f"unreadable: {e}") from None
        if not blob.startswith(_MAGIC):
            raise _LegacyEntry(blob)
        end = blob.find(b"\n", len(_MAGIC), len(_MAGIC) + _MAX_HEADER)
        if end < 0:
            raise _BadEntry("corrupt or truncated header")
        try:
            header = json.loads(blob[len(_MAGIC):end])
        except (ValueError, UnicodeDecodeError):
            raise _BadEntry("corrupt header") from None
        if not isinstance(header, dict):
            raise _BadEntry("corrupt header")
        if header.get("schema") != SCHEMA_VERSION:
            raise _BadEntry(f"stale: schema {header.get('schema')!r}, this code reads {SCHEMA_VERSION}")
        if header.get("code") != self.code_version:
            raise _BadEntry(f"stale: written by code version {header.get('code')!r}, "
                            f"this is {self.code_version!r}")
        if header.get("key") != str(key) or header.get("kind") != kind:
            raise _BadEntry(f"wrong contents: the file holds {header.get('kind')!r} entry "
                            f"{header.get('key')!r}, not {kind!r} entry {key!r}")
        payload = blob[end + 1:]
        if len(payload) != header.get("length"):
            raise _BadEntry(f"truncated: {len(payload)} of {header.get('length')} payload bytes")
        if hashlib.sha256(payload).hexdigest() != header.get("sha256"):
            raise _BadEntry("corrupt: the payload checksum (SHA-256) does not match")
        try:
            return pickle.loads(payload)
        except Exception as e:   # checksum passed, so this is a version mismatch of a library
            raise _BadEntry(f"cannot be unpickled ({type(e).__name__}: {e})") from None


def _identity(st):
    """What tells one file from another put at the same path (an os.stat result)."""
    return (st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns)


class _BadEntry(Exception):
    """Internal: an entry failed a file-level check."""


class _LegacyEntry(Exception):
    """Internal: the file has no header (plain pickle of earlier versions); args[0] is its bytes."""
