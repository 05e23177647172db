"""Identified inflow models as versioned data files (JSON, one file per model).

A file holds everything needed to use and to judge a model without re-running
the wake: the matrices (``M, Lbar, tau`` or ``F, G, C`` or ``A, B, C``), signal
names, rotor speed, the trim it is a perturbation about, the cost table,
parameters with Cramér-Rao and insensitivity percentages, the verification,
the settings and their hash, and the code/schema version.

Shipped models live in ``aircraft/data/models/<name>.json`` (package data);
:func:`load_record` / :meth:`aircraft.inflow.IdentifiedInflow.from_file` take a
path or such a name. ``rotorwake shipped-models NAME``
rebuilds one (see :mod:`aircraft.identification.shipped`).
"""
from __future__ import annotations

import json
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

import numpy as np
import pandas as pd

from aircraft.provenance import jsonable as _jsonable

__all__ = ["SCHEMA", "ModelRecord", "ModelFileError", "load_record", "shipped_models",
           "shipped_model_path"]

#: File schema; bump when the layout changes (readers check it).
SCHEMA = "rotorwake-id/inflow-model/1"


class ModelFileError(ValueError):
    """Raised for a missing, unreadable or inconsistent model file."""


def _table(rows):
    df = pd.DataFrame(rows or [])
    return df.astype({c: float for c in df.columns if df[c].dtype == object and
                      all(v is None or isinstance(v, (int, float)) for v in df[c])})


# The file schema stores Lbar under "L" (its name before the rename); changing the
# key would be a schema change, which stales every shipped model's recipe hash.
_FILE_KEY = {"Lbar": "L"}
_MEMORY_KEY = {v: k for k, v in _FILE_KEY.items()}


@dataclass
class ModelRecord:
    """One identified inflow model as stored on disk.

    Attributes
    ----------
    name : str
    form : {"mltau", "fgc", "statespace"}
    rotors : tuple of str
    omega : float
        Rotor speed [rad/s].
    matrices : dict of ndarray
        ``M, Lbar, tau`` (``M`` per d/dpsi, ``tau`` [s]); or ``F, G, C`` [1/s]; or
        ``A, B, C`` [1/s] of a ready state-space model. (On disk ``Lbar`` is stored
        under the key ``"L"``, which the file schema fixed before the rename.)
    inputs, outputs : list of str
        Canonical signal names (loads then flap rates; inflow).
    loads_ref, inflow_ref : ndarray
        Trim loads and total inflow the model is a perturbation about.
    frame : str
        ``"rotor"`` (ours) or ``"printed"``.
    cost_table, parameters, verification : DataFrame
    reduction_log : DataFrame
        The reduction's log (one row per removal tried; empty for a model that
        was not reduced or was written before logs were stored): what lets the
        trust rule keep a parameter over its bound when its removal was too costly.
    reproduction : DataFrame
        The reproduction check's table (empty if not checked).
    settings : dict
    settings_hash : str
    code_digest : str
        SHA-256 of the code the model was computed with (see
        :mod:`aircraft.identification.model_code`); empty in a file written before
        digests were recorded. Not part of the settings hash.
    code_digests : dict
        ``{module path: code digest}`` behind ``code_digest`` (names what changed).
    provenance : dict
        ``code_version``, ``schema``, ``source``, ``created``, ``wall_s``, ...
    description : str
    """

    name: str
    form: str
    rotors: tuple
    omega: float
    matrices: dict
    inputs: list
    outputs: list
    loads_ref: np.ndarray
    inflow_ref: np.ndarray
    frame: str = "rotor"
    time: str = "azimuth"
    pade_order: int = 2
    cost_table: pd.DataFrame = field(default_factory=pd.DataFrame)
    parameters: pd.DataFrame = field(default_factory=pd.DataFrame)
    verification: pd.DataFrame = field(default_factory=pd.DataFrame)
    reduction_log: pd.DataFrame = field(default_factory=pd.DataFrame)
    reproduction: pd.DataFrame = field(default_factory=pd.DataFrame)
    trim_outputs: dict = field(default_factory=dict)
    settings: dict = field(default_factory=dict)
    settings_hash: str = ""
    provenance: dict = field(default_factory=dict)
    description: str = ""
    code_digest: str = ""
    code_digests: dict = field(default_factory=dict)

    def __post_init__(self):
        if self.form not in ("mltau", "fgc", "statespace"):
            raise ModelFileError(f"{self.name}: unknown model form {self.form!r}")
        need = {"mltau": ("M", "Lbar", "tau"), "fgc": ("F", "G", "C"), "statespace": ("A", "B", "C")}[self.form]
        missing = [k for k in need if k not in self.matrices]
        if missing:
            raise ModelFileError(f"{self.name}: form {self.form!r} needs matrices {missing}")
        self.matrices = {k: np.asarray(v, float) for k, v in self.matrices.items()}
        self.rotors = tuple(self.rotors)
        self.loads_ref = np.asarray(self.loads_ref, float)
        self.inflow_ref = np.asarray(self.inflow_ref, float)

    @property
    def J_ave(self):
        """Mean CIFER cost of the fit (NaN for a model without a cost table)."""
        return float(self.cost_table.J.mean()) if "J" in self.cost_table else float("nan")

    # -- conversion ------------------------------------------------------------------
    def to_dict(self):
        return _jsonable({
            "schema": SCHEMA, "name": self.name, "description": self.description, "form": self.form,
            "rotors": list(self.rotors), "omega_rad_s": self.omega, "time": self.time, "frame": self.frame,
            "pade_order": self.pade_order, "inputs": self.inputs, "outputs": self.outputs,
            "matrices": {_FILE_KEY.get(k, k): v for k, v in self.matrices.items()},
            "trim": {"loads_ref": self.loads_ref, "inflow_ref": self.inflow_ref, "outputs": self.trim_outputs},
            "J_ave": self.J_ave, "cost_table": self.cost_table, "parameters": self.parameters,
            "verification": self.verification, "settings": self.settings,
            "settings_hash": self.settings_hash, "provenance": self.provenance,
            # optional entries, written only when there is one (older files have none)
            **{k: v for k, v in (("reduction_log", self.reduction_log), ("reproduction", self.reproduction),
                                 ("code_digest", self.code_digest), ("code_digests", self.code_digests))
               if len(v)}})

    def save(self, path):
        """Write the record as JSON to ``path`` (a file name); returns the Path."""
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(self.to_dict(), indent=1) + "\n")
        return path

    @classmethod
    def from_dict(cls, d, source="<dict>"):
        if d.get("schema") != SCHEMA:
            raise ModelFileError(f"{source}: schema {d.get('schema')!r}, this code reads {SCHEMA!r}")
        try:
            trim = d["trim"]
            return cls(name=d["name"], form=d["form"], rotors=tuple(d["rotors"]), omega=float(d["omega_rad_s"]),
                       matrices={_MEMORY_KEY.get(k, k): _finite_matrix(source, k, v)
                                 for k, v in d["matrices"].items()},
                       inputs=list(d["inputs"]), outputs=list(d["outputs"]),
                       loads_ref=np.array(trim["loads_ref"], float), inflow_ref=np.array(trim["inflow_ref"], float),
                       frame=d.get("frame", "rotor"), time=d.get("time", "azimuth"),
                       pade_order=int(d.get("pade_order", 2)), cost_table=_table(d.get("cost_table")),
                       parameters=_table(d.get("parameters")), verification=_table(d.get("verification")),
                       reduction_log=_table(d.get("reduction_log")), reproduction=_table(d.get("reproduction")),
                       trim_outputs=dict(trim.get("outputs") or {}), settings=d.get("settings") or {},
                       settings_hash=d.get("settings_hash", ""), provenance=d.get("provenance") or {},
                       description=d.get("description", ""), code_digest=d.get("code_digest", ""),
                       code_digests=dict(d.get("code_digests") or {}))
        except KeyError as err:
            raise ModelFileError(f"{source}: missing field {err}") from err


def _finite_matrix(source, key, value):
    """Matrix ``key`` of a model file as floats; a missing (null), non-numeric or infinite
    entry is refused with its position (the file is damaged or was written from a failed fit)."""
    try:
        m = np.array([[np.nan if x is None else x for x in row] if isinstance(row, list) else
                      (np.nan if row is None else row) for row in value], float)
    except (TypeError, ValueError) as err:
        raise ModelFileError(f"{source}: matrix {key!r} holds a non-numeric entry ({err})") from err
    bad = np.argwhere(~np.isfinite(m))
    if len(bad):
        where = tuple(int(i) for i in bad[0])
        raise ModelFileError(f"{source}: matrix {key!r} entry {where} is not finite ({m[where]!r}); "
                             f"{len(bad)} such entr{'y' if len(bad) == 1 else 'ies'}")
    return m


def _models_dir():
    return Path(str(resources.files("aircraft") / "data" / "models"))


def shipped_models():
    """Names of the model files shipped in ``aircraft/data/models``."""
    return sorted(p.stem for p in _models_dir().glob("*.json"))


def shipped_model_path(name):
    """Path of the shipped model file ``name`` (whether it exists or not).

    Parameters
    ----------
    name : str
        Model name (file stem).

    Returns
    -------
    pathlib.Path
    """
    return _models_dir() / f"{name}.json"


def load_record(path_or_name):
    """Read a model file: a path to a ``.json`` file or the name of a shipped model.

    Parameters
    ----------
    path_or_name : str or pathlib.Path
        Path of a model file, or (no suffix, no such file) a shipped model name.

    Returns
    -------
    ModelRecord

    Raises
    ------
    ModelFileError
        If the file does not exist, is not JSON or has another schema.
    """
    p = Path(path_or_name)
    if not p.suffix and not p.exists():
        p = shipped_model_path(str(path_or_name))
        if not p.exists():
            raise ModelFileError(f"no shipped model {path_or_name!r}; shipped: {shipped_models()}")
    if not p.exists():
        raise ModelFileError(f"model file {p} does not exist")
    try:
        d = json.loads(p.read_text())
    except json.JSONDecodeError as err:
        raise ModelFileError(f"{p} is not valid JSON: {err}") from err
    return ModelRecord.from_dict(d, source=str(p))
