"""Compare two results folders table by table, within a stated tolerance.

Used by the ``rotorwake`` command line (:mod:`studies.cli`) to say what a study run
changed in the folder it replaced, and by ``rotorwake reproduce`` to rerun the study
of a committed results folder and hold the rerun to it. Only the command line and
the tests import this module, never a library module: a library import would put
it into the import closure that decides whether a shipped model is stale (see
:mod:`aircraft.identification.model_code`), and a results manifest never records it
(:mod:`aircraft.provenance` lists it as bookkeeping), since comparing numbers cannot
change one. For the same reason a study states its wider tolerances,
``RESULT_TOLERANCES``, as plain ``(rtol, atol)`` pairs rather than importing
:class:`Tolerance`.

What is compared (:func:`compare_folders`):

* every ``*.csv`` file, column by column, the columns matched by name. A column
  whose every entry, on both sides, reads as a number (an empty entry is NaN) is
  numeric and passes where ``|a - b| <= atol + rtol * |a|``, ``a`` the reference; a
  column of complex numbers as Python writes them (``(1+2j)``) likewise, on the
  modulus. NaN equals NaN, NaN against a number is a difference, an infinity equals
  only the same infinity. Any other column is text and must match exactly;
* ``*.txt`` files, exactly, line by line;
* not compared: columns that record how the run went rather than what it computed:
  wall-clock times (``wall_s``, ``wall_time_s``, ``wall_time``, and any name ending
  in ``_wall_s``, e.g. ``search_wall_s`` and ``dmo_wall_s`` in the committed tables)
  and ``wake_cache`` (whether the wall time beside it was measured with the wake
  cache); and every other file (figures, ``manifest.json``, the folder's hand-written
  description), whose bytes differ from run to run;
* a table or text file on one side only, a column on one side only and a table
  whose number of rows differs are differences (reported, never raised).
"""
from __future__ import annotations

import dataclasses
import fnmatch
import math
from pathlib import Path

__all__ = ["Tolerance", "ResultsComparison", "compare_folders", "TIMING_COLUMNS", "COMPARED_SUFFIXES"]

#: The files compared: tables column by column, text files line by line; others are listed only.
COMPARED_SUFFIXES = (".csv", ".txt")

#: Column names never compared: they record the run's circumstances, not its results.
TIMING_COLUMNS = ("wall_s", "wall_time_s", "wall_time", "wake_cache")
_TIMING_SUFFIX = "_wall_s"
_FAILING = ("moved", "missing")
# entries that read as NaN in a numeric column (pandas writes NaN as an empty entry)
_NAN_TEXT = ("", "nan", "-nan", "+nan")


@dataclasses.dataclass(frozen=True)
class Tolerance:
    """How far a number may move: ``|a - b| <= atol + rtol * |a|``, ``a`` the reference.

    Parameters
    ----------
    rtol : float
        Relative tolerance (a fraction of the reference value, e.g. 1e-6).
    atol : float
        Absolute tolerance, in the column's own unit, for values near zero.

    Raises
    ------
    ValueError
        If either is not a finite number >= 0.

    Examples
    --------
    >>> Tolerance()
    Tolerance(rtol=1e-06, atol=1e-09)
    >>> Tolerance(rtol=-1)
    Traceback (most recent call last):
    ...
    ValueError: Tolerance rtol must be a finite number >= 0, got -1
    """

    rtol: float = 1e-6
    atol: float = 1e-9

    def __post_init__(self):
        for name in ("rtol", "atol"):
            value = getattr(self, name)
            if (isinstance(value, bool) or not isinstance(value, (int, float))
                    or not math.isfinite(value) or value < 0):
                raise ValueError(f"Tolerance {name} must be a finite number >= 0, got {value!r}")


def _as_tolerance(value, where):
    """A :class:`Tolerance` from a Tolerance, an ``(rtol, atol)`` pair or a dict."""
    if isinstance(value, Tolerance):
        return value
    if isinstance(value, dict):
        return Tolerance(**value)
    if isinstance(value, (tuple, list)) and len(value) == 2:
        return Tolerance(*value)
    raise ValueError(f"tolerance {where} must be a Tolerance, an (rtol, atol) pair or a dict, got {value!r}")


def _is_timing(column):
    return column in TIMING_COLUMNS or column.endswith(_TIMING_SUFFIX)


def _tolerance_for(file, column, tolerances, default):
    """The file-qualified pattern first, then the first generic one, in insertion order."""
    generic = None
    for key, tol in tolerances.items():
        head, sep, pattern = key.partition(":")
        if sep and head.endswith(".csv"):
            if fnmatch.fnmatchcase(file, head) and fnmatch.fnmatchcase(column, pattern):
                return tol
        elif generic is None and fnmatch.fnmatchcase(column, key):
            generic = tol
    return generic if generic is not None else default


@dataclasses.dataclass(frozen=True)
class _Entry:
    """One compared column (or a whole file), as a row of :meth:`ResultsComparison.to_pandas`."""

    file: str
    column: str
    kind: str
    verdict: str
    rows: int | None = None
    max_abs: float = math.nan
    max_rel: float = math.nan
    beyond: int = 0
    rtol: float = math.nan
    atol: float = math.nan
    row: int | None = None          # first entry beyond tolerance
    reference: object = None
    candidate: object = None
    largest_row: int | None = None  # entry with the largest change beyond tolerance
    largest_reference: object = None
    largest_candidate: object = None
    detail: str = ""


@dataclasses.dataclass(frozen=True)
class ResultsComparison:
    """What :func:`compare_folders` found, column by column.

    Parameters
    ----------
    reference : pathlib.Path
        The folder held to (e.g. the committed results).
    candidate : pathlib.Path
        The folder compared with it (e.g. a rerun).
    entries : tuple
        One record per file and column (read them with :meth:`to_pandas`).
    default : Tolerance
        The tolerance of columns that no pattern names.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as ref, tempfile.TemporaryDirectory() as new:
    ...     _ = Path(ref, "t.csv").write_text("x,label\\n1.0,a\\n2.0,b\\n")
    ...     _ = Path(new, "t.csv").write_text("x,label\\n1.0,a\\n2.5,b\\n")
    ...     result = compare_folders(ref, new)
    >>> result.passes
    False
    >>> result.moved()[["file", "column", "row", "reference", "candidate"]].to_dict("records")
    [{'file': 't.csv', 'column': 'x', 'row': 1, 'reference': 2.0, 'candidate': 2.5}]
    """

    reference: Path
    candidate: Path
    entries: tuple
    default: Tolerance = Tolerance()

    @property
    def passes(self):
        """True when nothing moved beyond its tolerance and nothing is missing."""
        return not any(e.verdict in _FAILING for e in self.entries)

    def to_pandas(self):
        """One row per file and column.

        Returns
        -------
        pandas.DataFrame
            ``file``, ``column`` (empty for a whole file), ``kind`` (``"numeric"``,
            ``"complex"``, ``"text"``, ``"timing"``, ``"missing"``, ``"rows"`` or
            ``"file"``), ``rows``, ``max_abs`` and ``max_rel`` (largest absolute and
            relative change of a numeric column, in its unit and as a fraction),
            ``beyond`` (entries beyond tolerance), ``rtol``, ``atol``, ``verdict``
            (``"same"``, ``"within tolerance"``, ``"moved"``, ``"missing"`` or
            ``"not compared"``) and ``detail``.
        """
        import pandas as pd
        names = ["file", "column", "kind", "rows", "max_abs", "max_rel", "beyond", "rtol", "atol",
                 "verdict", "detail"]
        return pd.DataFrame([{n: getattr(e, n) for n in names} for e in self.entries], columns=names)

    def moved(self):
        """The columns and files that did not pass, and where.

        Returns
        -------
        pandas.DataFrame
            ``file``, ``column``, ``kind``, ``verdict``, ``beyond``, ``max_abs``,
            ``max_rel``, ``row`` (the first offending data row, counted from 0 below
            the header), ``reference`` and ``candidate`` (its two values),
            ``largest_row``, ``largest_reference``, ``largest_candidate`` (the entry
            that moved most) and ``detail``.
        """
        import pandas as pd
        names = ["file", "column", "kind", "verdict", "beyond", "max_abs", "max_rel", "row", "reference",
                 "candidate", "largest_row", "largest_reference", "largest_candidate", "detail"]
        return pd.DataFrame([{n: getattr(e, n) for n in names} for e in self.entries
                             if e.verdict in _FAILING], columns=names)

    def report(self, max_rows=20):
        """A readable summary: counts, then each column that moved with its largest change.

        Parameters
        ----------
        max_rows : int
            Most moved or missing columns listed one by one (the rest are counted).

        Returns
        -------
        str
        """
        compared = [e for e in self.entries if e.kind in ("numeric", "complex", "text")]
        count = {v: sum(e.verdict == v for e in compared) for v in ("same", "within tolerance", "moved")}
        failing = [e for e in self.entries if e.verdict in _FAILING]
        timing = [e for e in self.entries if e.kind == "timing"]
        others = [e for e in self.entries if e.kind == "file"]
        missing = sum(e.verdict == "missing" for e in self.entries)
        resized = sum(e.kind == "rows" for e in self.entries)
        tables = len({e.file for e in compared})
        lines = [f"{len(compared)} columns of {tables} files compared "
                 f"(rtol {self.default.rtol:g}, atol {self.default.atol:g} unless stated): "
                 f"{count['same']} identical, {count['within tolerance']} within tolerance, "
                 f"{count['moved']} moved" + (f"; {resized} files of another length" if resized else "")
                 + (f"; {missing} missing" if missing else "")]
        for e in failing[:max_rows]:
            lines.append("  " + _describe(e))
        if len(failing) > max_rows:
            lines.append(f"  ... and {len(failing) - max_rows} more (see .moved())")
        if timing:
            lines.append(f"not compared: {len(timing)} timing column(s) ("
                         + _names([f"{e.file}:{e.column}" for e in timing]) + ")")
        if others:
            lines.append(f"not compared: {len(others)} other file(s) (" + _names([e.file for e in others]) + ")")
        lines.append("result: " + ("reproduced within tolerance" if self.passes else
                                   f"{len(failing)} column(s) or file(s) moved or missing"))
        return "\n".join(lines)


def _names(names, most=6):
    return ", ".join(names[:most]) + (f", ... ({len(names) - most} more)" if len(names) > most else "")


def _describe(e):
    """One line of :meth:`ResultsComparison.report` for an entry that did not pass."""
    where = f"{e.file}" + (f", column {e.column!r}" if e.column else "")
    if e.detail:
        return f"{where}: {e.detail}"
    if e.kind == "text":
        what, at = ("entries", "row") if e.column else ("lines", "line")
        return (f"{where}: {e.beyond} of {e.rows} {what} differ; first at {at} {e.row}: "
                f"{e.reference!r} -> {e.candidate!r}")
    return (f"{where}: {e.beyond} of {e.rows} rows beyond rtol {e.rtol:g}, atol {e.atol:g}; largest change "
            f"{e.max_abs:.3g} (relative {e.max_rel:.3g}) at row {e.largest_row}: "
            f"{e.largest_reference!r} -> {e.largest_candidate!r}")


def _parse_numbers(raw):
    """``(values, kind)`` of a column of strings: float or complex array, or None if text."""
    import numpy as np
    import pandas as pd
    stripped = raw.str.strip()
    values = pd.to_numeric(stripped, errors="coerce").to_numpy(dtype=float, na_value=np.nan)
    if not (np.isnan(values) & ~stripped.str.lower().isin(_NAN_TEXT).to_numpy()).any():
        return values, "numeric"
    first = next((s for s in stripped if s), "")
    if not first.rstrip(")").endswith("j"):
        return None, "text"
    try:
        return np.array([complex(s) if s else complex(math.nan, 0) for s in stripped]), "complex"
    except ValueError:
        return None, "text"


def _compare_numbers(file, column, a, b, kind, tol):
    import numpy as np
    both_nan = np.isnan(a) & np.isnan(b)
    finite = np.isfinite(a) & np.isfinite(b)
    with np.errstate(invalid="ignore"):
        exact = (a == b) | both_nan
        diff = np.where(finite, np.abs(a - b), 0.0)
        ok = exact | (finite & (diff <= tol.atol + tol.rtol * np.abs(a)))
        # relative to the reference; a change from an exact zero is infinitely large
        rel = np.where(finite & (diff > 0), diff / np.where(a == 0, 1.0, np.abs(a)), 0.0)
        rel = np.where(finite & (diff > 0) & (a == 0), math.inf, rel)
    bad = np.flatnonzero(~ok)
    verdict = "moved" if bad.size else ("same" if exact.all() else "within tolerance")
    record = dict(file=file, column=column, kind=kind, verdict=verdict, rows=len(a),
                  max_abs=float(diff.max(initial=0.0)), max_rel=float(rel.max(initial=0.0)),
                  beyond=int(bad.size), rtol=tol.rtol, atol=tol.atol)
    if bad.size:
        # the largest change beyond tolerance; a non-finite mismatch counts as the largest
        size = np.where(finite[bad], diff[bad], math.inf)
        worst = int(bad[int(np.argmax(size))])
        first = int(bad[0])
        record.update(row=first, reference=a[first].item(), candidate=b[first].item(), largest_row=worst,
                      largest_reference=a[worst].item(), largest_candidate=b[worst].item())
    return _Entry(**record)


def _compare_text(file, column, a, b):
    bad = [k for k, (x, y) in enumerate(zip(a, b)) if x != y]
    if not bad:
        return _Entry(file, column, "text", "same", rows=len(a))
    k = bad[0]
    return _Entry(file, column, "text", "moved", rows=len(a), beyond=len(bad), row=k, reference=a[k],
                  candidate=b[k], largest_row=k, largest_reference=a[k], largest_candidate=b[k])


def _read_table(path):
    """The table as strings (None if it is not a readable table)."""
    import pandas as pd
    try:
        return pd.read_csv(path, dtype=str, keep_default_na=False)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError):
        return None


def _compare_tables(name, ref_path, new_path, tolerances, default):
    ref, new = _read_table(ref_path), _read_table(new_path)
    if ref is None or new is None:
        # not a table pandas reads (e.g. empty): the two files' text must match
        same = ref_path.read_bytes() == new_path.read_bytes()
        return [_Entry(name, "", "text", "same" if same else "moved", beyond=0 if same else 1,
                       detail="" if same else "not a readable table; the files' bytes differ")]
    if len(ref) != len(new):
        return [_Entry(name, "", "rows", "moved", beyond=abs(len(ref) - len(new)),
                       detail=f"{len(ref)} rows in the reference, {len(new)} in the candidate")]
    entries = []
    for column in list(ref.columns) + [c for c in new.columns if c not in ref.columns]:
        if column not in new.columns or column not in ref.columns:
            side = "reference" if column in ref.columns else "candidate"
            entries.append(_Entry(name, column, "missing", "missing", rows=len(ref), detail=f"only in the {side}"))
        elif _is_timing(column):
            entries.append(_Entry(name, column, "timing", "not compared", rows=len(ref)))
        else:
            a, kind_a = _parse_numbers(ref[column])
            b, kind_b = _parse_numbers(new[column])
            if kind_a == kind_b != "text" or {kind_a, kind_b} == {"numeric", "complex"}:
                kind = "complex" if "complex" in (kind_a, kind_b) else "numeric"
                tol = _tolerance_for(name, column, tolerances, default)
                entries.append(_compare_numbers(name, column, a, b, kind, tol))
            else:
                entries.append(_compare_text(name, column, ref[column].tolist(), new[column].tolist()))
    return entries


def compare_folders(reference, candidate, tolerances=None, default=Tolerance()):
    """Compare every table of ``reference`` with the same-named table of ``candidate``.

    The rules (which columns are numeric, text or timing; which files are compared)
    are those of this module's description.

    Parameters
    ----------
    reference : str or pathlib.Path
        The folder held to, e.g. a committed results folder.
    candidate : str or pathlib.Path
        The folder compared with it, e.g. a rerun of its study.
    tolerances : dict, optional
        ``{pattern: tolerance}``: a column-name glob (:mod:`fnmatch`, case-sensitive),
        or ``"file.csv:pattern"`` for that file's columns only, mapped to a
        :class:`Tolerance`, an ``(rtol, atol)`` pair or a dict of them. A
        file-qualified pattern wins over a generic one; among either, the first that
        matches in insertion order.
    default : Tolerance
        Tolerance of every numeric column no pattern names.

    Returns
    -------
    ResultsComparison

    Raises
    ------
    FileNotFoundError
        If either folder does not exist.
    ValueError
        If a tolerance is not a valid :class:`Tolerance` or pair.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as ref, tempfile.TemporaryDirectory() as new:
    ...     _ = Path(ref, "t.csv").write_text("x,wall_s\\n1.0,3.1\\n")
    ...     _ = Path(new, "t.csv").write_text("x,wall_s\\n1.0000000001,2.7\\n")
    ...     result = compare_folders(ref, new)
    >>> result.passes, result.to_pandas().verdict.tolist()
    (True, ['within tolerance', 'not compared'])
    """
    reference, candidate = Path(reference), Path(candidate)
    for folder in (reference, candidate):
        if not folder.is_dir():
            raise FileNotFoundError(f"results folder {folder} does not exist")
    default = _as_tolerance(default, "default")
    tolerances = {str(k): _as_tolerance(v, repr(k)) for k, v in (tolerances or {}).items()}
    names = sorted({p.name for folder in (reference, candidate) for p in folder.iterdir()
                    if p.is_file() and not p.name.startswith(".")})
    entries = []
    for name in names:
        ref_path, new_path = reference / name, candidate / name
        suffix = Path(name).suffix.lower()
        if suffix not in COMPARED_SUFFIXES:
            entries.append(_Entry(name, "", "file", "not compared"))
        elif not (ref_path.is_file() and new_path.is_file()):
            side = "reference" if ref_path.is_file() else "candidate"
            entries.append(_Entry(name, "", "missing", "missing", detail=f"only in the {side}"))
        elif suffix == ".txt":
            a, b = ref_path.read_text().splitlines(), new_path.read_text().splitlines()
            if len(a) != len(b):
                entries.append(_Entry(name, "", "rows", "moved", beyond=abs(len(a) - len(b)),
                                      detail=f"{len(a)} lines in the reference, {len(b)} in the candidate"))
            else:
                entries.append(_compare_text(name, "", a, b))
        else:
            entries += _compare_tables(name, ref_path, new_path, tolerances, default)
    return ResultsComparison(reference, candidate, tuple(entries), default)
