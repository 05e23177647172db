"""Aircraft as data: an :class:`~aircraft.configs.AircraftConfig` written to and read from TOML.

A file holds one aircraft: its scalar fields at the top, one ``[[rotors]]`` table
per rotor (in the order of ``AircraftConfig.rotors``) and, if the aircraft has one,
a ``[propeller]`` table::

    # units: SI as in the dataclasses (m, kg, s, rad)
    format_version = 1
    name = "my helicopter"
    mass = 7780.0                 # kg
    Ixx = 6317.0                  # kg m^2
    Iyy = 52216.0
    Izz = 49889.0
    trim_ct = [0.0061]

    [[rotors]]
    name = ""                     # single rotor: no signal suffix
    radius = 8.18                 # m
    omega = 27.0                  # rad/s
    n_blades = 4
    chord = 0.527                 # m
    twist = -0.2967               # rad (twist_deg = -17.0 also accepted)
    root_cutout = 0.189           # r/R

Rules:

* **Units** are those of the dataclasses: SI, lengths [m], masses [kg], rotor
  speeds [rad/s], inertias [kg m^2], areas [m^2], density [kg/m^3] and **angles in
  radians**. For hand-written files an angle field may instead be given in degrees
  under its name with ``_deg`` appended (``twist_deg``, ``stall_angle_deg``,
  ``shaft_tilt_deg``, ``control_phase_deg``); giving both forms is an error. The
  writer always writes radians (with the value in degrees in a comment).
* A field left out takes the dataclass default; the fields without a default
  (``name``, ``mass``, ``Ixx``, ``Iyy``, ``Izz``, one ``[[rotors]]`` table or two,
  and in each rotor ``name``, ``radius``, ``omega``, ``n_blades``, ``chord``,
  ``twist``, ``root_cutout``) are required. ``None`` (``flap_inertia``,
  ``omega_cruise``, no propeller) is written as an absent key or table.
* A rotor's real blade (:class:`~aircraft.blade.BladeModel`) is a ``[rotors.blade]``
  table below its ``[[rotors]]`` table (``stations``, ``chord``, ``twist``,
  ``thickness`` arrays, ``compressibility``, ``tip_loss``), with a tabulated polar
  in ``[rotors.blade.polar]`` (``alpha``, ``cl``, ``cd``); no table: the classical
  blade.
* ``format_version`` is optional; if given it must be 1.
* The writer writes floats with :func:`repr`, so a file read back gives a
  configuration equal to the one written, field for field and bit for bit.

Every problem raises :class:`ConfigFileError` naming the file and the field:
TOML syntax (with the line), a missing required field (``rotors[1].radius``,
rotors counted from 0 in file order), an unknown field (with the valid ones), a
value of the wrong type. The dataclasses' own range checks then run; their
:class:`~aircraft.configs.ConfigError` comes back as a :class:`ConfigFileError`
(a subclass) whose message starts with the file.

The two aircraft of :mod:`aircraft.configs` are shipped as such files
(``aircraft/data/aircraft/*.toml``, :func:`load_shipped_aircraft`); the tests
check that they equal :func:`~aircraft.configs.coaxial_compound` and
:func:`~aircraft.configs.uh60_single_rotor` field for field.
"""
from __future__ import annotations

import dataclasses
import difflib
import math
import os
import re
from importlib import resources
from pathlib import Path

try:
    import tomllib as _toml
except ModuleNotFoundError:  # Python 3.10: the same parser as the tomli package
    import tomli as _toml

from .blade import BladeModel
from .configs import AircraftConfig, ConfigError, PropellerConfig, RotorConfig, TailRotorConfig

__all__ = ["ConfigFileError", "FORMAT_VERSION", "write_aircraft", "read_aircraft", "shipped_aircraft",
           "load_shipped_aircraft", "load_aircraft"]

#: Version of the file layout the writer writes and the reader reads.
FORMAT_VERSION = 1


class ConfigFileError(ConfigError):
    """An aircraft file cannot be read: bad TOML, a missing, unknown or mistyped field.

    A subclass of :class:`~aircraft.configs.ConfigError` (and so of
    :class:`ValueError`): the message starts with the file and names the field
    (``rotors[1].radius``) or, for a TOML syntax error, the line.
    """


# --- the schema: every dataclass field, its kind and its unit ---------------------
# kinds: "str", "float", "int", "vector" (array of numbers -> tuple of floats),
# "optional float" (absent key: None). ``rotors``, ``propeller`` and ``tail_rotor`` are tables.
_ROTOR = {
    "name": ("str", 'signal suffix: "U", "L", or "" for a single rotor'),
    "radius": ("float", "m"),
    "omega": ("float", "rad/s"),
    "n_blades": ("int", "-"),
    "chord": ("float", "m"),
    "twist": ("float", "rad, root to tip, negative: washout"),
    "root_cutout": ("float", "r/R"),
    "lift_slope": ("float", "1/rad"),
    "cd0": ("float", "-"),
    "stall_angle": ("float", "rad"),
    "flap_frequency": ("float", "per rev"),
    "lag_frequency": ("float", "per rev"),
    "hinge_offset": ("float", "e/R"),
    "blade_mass": ("float", "kg, one blade"),
    "direction": ("int", "+1 counter-clockwise seen from above, -1 clockwise"),
    "hub_position": ("vector", "m, body axes from the c.g.: x fwd, y stbd, z down"),
    "shaft_tilt": ("float", "rad, forward"),
    "flap_inertia": ("optional float", "kg m^2, one blade about the hinge"),
    "blade": ("blade", "a [rotors.blade] table: aircraft.blade.BladeModel"),
}
_PROPELLER = {
    "radius": ("float", "m"),
    "omega": ("float", "rad/s"),
    "position": ("vector", "m, body axes from the c.g."),
    "solidity": ("float", "-"),
    "lift_slope": ("float", "1/rad"),
    "cd0": ("float", "-"),
    "twist": ("float", "rad"),
}
_AIRCRAFT = {
    "name": ("str", ""),
    "rotors": ("rotors", ""),
    "mass": ("float", "kg"),
    "Ixx": ("float", "kg m^2"),
    "Iyy": ("float", "kg m^2"),
    "Izz": ("float", "kg m^2"),
    "Ixz": ("float", "kg m^2"),
    "rho": ("float", "kg/m^3"),
    "fuselage_fx": ("float", "m^2, forward flat-plate area"),
    "fuselage_fz": ("float", "m^2, vertical flat-plate area"),
    "htail_area": ("float", "m^2"),
    "htail_position": ("vector", "m, body axes from the c.g."),
    "htail_lift_slope": ("float", "1/rad"),
    "vtail_area": ("float", "m^2"),
    "vtail_position": ("vector", "m, body axes from the c.g."),
    "vtail_lift_slope": ("float", "1/rad"),
    "propeller": ("propeller", ""),
    "trim_ct": ("vector", "hover thrust coefficient per rotor, in rotor order"),
    "omega_cruise": ("optional float", "rad/s"),
    "control_phase": ("float", "rad"),
    "fuselage_lift_area": ("float", "m^2/rad, fuselage lift per angle of attack"),
    "tail_rotor": ("tail_rotor", ""),
}
_TAIL_ROTOR = {
    "radius": ("float", "m"),
    "omega": ("float", "rad/s"),
    "solidity": ("float", "-"),
    "lift_slope": ("float", "1/rad"),
    "cd0": ("float", "-"),
    "twist": ("float", "rad"),
    "position": ("vector", "m, body axes from the c.g."),
    "thrust_sign": ("int", "+1 thrust to starboard at positive collective, -1 to port"),
}
_SCHEMAS = {RotorConfig: _ROTOR, PropellerConfig: _PROPELLER, TailRotorConfig: _TAIL_ROTOR,
            AircraftConfig: _AIRCRAFT}
_DEG = "_deg"
#: fields written as their own TOML tables
_TABLES = ("rotors", "propeller", "tail_rotor")
_NOT_SET = {
    "flap_inertia": "not set (None): a uniform blade of blade_mass, m L^2 / 3",
    "omega_cruise": "not set (None): no separate cruise rotor speed",
    "blade": "not set (None): constant chord, linear twist, lift_slope and cd0 (no [rotors.blade] table)",
}
_HEADER = """\
# Aircraft configuration for rotorwake-id: aircraft.configs.AircraftConfig as TOML.
# Written by aircraft.write_aircraft; read with aircraft.read_aircraft(path).
# Units: SI as in the dataclasses: lengths m, masses kg, time s, rotor speeds rad/s,
# inertias kg m^2, areas m^2, density kg/m^3, ANGLES IN RADIANS. Positions are in body
# axes from the centre of gravity [m]: x forward, y starboard, z down.
# A field left out takes the dataclass default; an angle may be given in degrees as
# NAME_deg (e.g. twist_deg) instead. One [[rotors]] table per rotor, in order.
"""


def _schema(cls):
    """{field: (kind, unit)} of a dataclass, checked to cover every field."""
    schema = _SCHEMAS[cls]
    fields = [f.name for f in dataclasses.fields(cls)]
    missing = [f for f in fields if f not in schema]
    if missing:   # a field added to the dataclass must be added here (tests/test_config_files.py)
        raise TypeError(f"aircraft.config_files has no file schema for {cls.__name__}.{', '.join(missing)}")
    return {f: schema[f] for f in fields}


def _angle_fields(cls):
    return [f for f, (kind, unit) in _schema(cls).items() if kind == "float" and unit.startswith("rad")
            and not unit.startswith("rad/")]


def _required(cls):
    return [f.name for f in dataclasses.fields(cls)
            if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING]


# --- writing ----------------------------------------------------------------------
def _toml_string(text):
    out = []
    for ch in text:
        if ch == '"':
            out.append('\\"')
        elif ch == "\\":
            out.append("\\\\")
        elif ch in "\b\t\n\f\r":
            out.append({"\b": "\\b", "\t": "\\t", "\n": "\\n", "\f": "\\f", "\r": "\\r"}[ch])
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04X}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def _toml_float(value):
    # repr is the shortest text that reads back to the same double; TOML reads
    # inf and nan too (the dataclasses refuse them before a file is written)
    return repr(float(value))


def _toml_lines(obj, owner):
    """``key = value  # unit`` lines of the scalar and array fields of a dataclass."""
    rows = []
    for field, (kind, unit) in _schema(type(obj)).items():
        value = getattr(obj, field)
        if kind in _TABLES or (kind == "blade" and value is not None):
            continue
        if value is None:
            rows.append((f"# {field}", "", _NOT_SET.get(field, "not set (None)")))
            continue
        if kind == "str":
            if not isinstance(value, str):
                raise ConfigFileError(f"{owner}{field} must be a string, got {value!r}")
            text = _toml_string(value)
        elif kind == "int":
            text = repr(int(value))
        elif kind == "vector":
            text = "[" + ", ".join(_toml_float(v) for v in value) + "]"
        else:
            text = _toml_float(value)
            if field in _angle_fields(type(obj)):
                unit = f"{unit} ({math.degrees(value):.6g} deg)"
        rows.append((field, text, unit))
    width = max(len(k) for k, v, _ in rows if v)
    lines = []
    for key, text, unit in rows:
        if not text:
            lines.append(f"{key} {unit}")
        elif unit and unit != "-":
            lines.append(f"{key:<{width}} = {text}  # {unit}")
        else:
            lines.append(f"{key:<{width}} = {text}")
    return lines


def _toml_plain(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, list):
        return "[" + ", ".join(_toml_float(v) for v in value) + "]"
    return _toml_float(value)


def _blade_lines(blade, k):
    """The ``[rotors.blade]`` (and ``[rotors.blade.polar]``) tables of rotor ``k``."""
    data = blade.to_dict()
    polar = data.pop("polar", None)
    lines = ["", f"[rotors.blade]  # rotors[{k}].blade: r/R stations, chord m, twist rad, thickness t/c"]
    lines += [f"{key} = {_toml_plain(v)}" for key, v in data.items()]
    if polar is not None:
        lines += ["", f"[rotors.blade.polar]  # rotors[{k}].blade.polar: alpha rad, cl, cd"]
        lines += [f"{key} = {_toml_plain(v)}" for key, v in polar.items()]
    return lines


def _to_toml(config, header=None):
    if not isinstance(config, AircraftConfig):
        raise TypeError(f"write_aircraft needs an aircraft.configs.AircraftConfig, got {type(config).__name__}")
    lines = _HEADER.splitlines()
    if header:
        lines += [("# " + line).rstrip() for line in str(header).splitlines()]
    lines += ["", f"format_version = {FORMAT_VERSION}", ""]
    lines += _toml_lines(config, "AircraftConfig.")
    for k, rotor in enumerate(config.rotors):
        lines += ["", f"[[rotors]]  # rotors[{k}]"] + _toml_lines(rotor, f"rotors[{k}].")
        if rotor.blade is not None:
            lines += _blade_lines(rotor.blade, k)
    if config.propeller is None:
        lines += ["", "# no propeller (no [propeller] table)"]
    else:
        lines += ["", "[propeller]  # pusher propeller, thrust along body +x"]
        lines += _toml_lines(config.propeller, "propeller.")
    if config.tail_rotor is None:
        lines += ["", "# tail_rotor not set (no [tail_rotor] table)"]
    else:
        lines += ["", "[tail_rotor]  # anti-torque rotor, thrust along body +-y"]
        lines += _toml_lines(config.tail_rotor, "tail_rotor.")
    return "\n".join(lines) + "\n"


def write_aircraft(config, path, *, header=None):
    """Write an aircraft configuration to a TOML file.

    Every field of the :class:`~aircraft.configs.AircraftConfig`, of each of its
    :class:`~aircraft.configs.RotorConfig` and of its
    :class:`~aircraft.configs.PropellerConfig` (if any) is written, in SI units as
    in the dataclasses (angles in radians), each with its unit in a comment;
    floats are written with :func:`repr`, so :func:`read_aircraft` gives back a
    configuration equal to ``config``.

    Parameters
    ----------
    config : aircraft.configs.AircraftConfig
        The aircraft.
    path : str or os.PathLike
        File to write (UTF-8; replaced if it exists). Conventionally ``*.toml``.
    header : str, optional
        Extra comment lines written below the standard header (e.g. where the
        configuration comes from).

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    TypeError
        If ``config`` is not an ``AircraftConfig``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from aircraft import uh60_single_rotor, write_aircraft, read_aircraft
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "uh60.toml"
    >>> _ = write_aircraft(uh60_single_rotor(), path)
    >>> read_aircraft(path) == uh60_single_rotor()
    True
    """
    text = _to_toml(config, header)
    path = Path(os.fspath(path))
    path.write_text(text, encoding="utf-8")
    return path


# --- reading ----------------------------------------------------------------------
_TOML_TYPE = {bool: "boolean", int: "integer", float: "float", str: "string", list: "array", dict: "table"}


def _describe(value):
    kind = _TOML_TYPE.get(type(value), "date/time" if hasattr(value, "isoformat") else type(value).__name__)
    return f"{kind} {value!r}"


def _table_name(where):
    if not where:
        return "the top level"
    return "a [[rotors]] table" if where.startswith("rotors") else f"the [{where}] table"


class _Reader:
    """Converts the parsed TOML of one file into the dataclasses, naming fields in errors."""

    def __init__(self, source):
        self.source = source

    def error(self, message):
        return ConfigFileError(f"{self.source}: {message}")

    def number(self, where, value, unit):
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            unit = f" [{unit.split(',')[0]}]" if unit and unit != "-" else ""
            raise self.error(f"{where} must be a number{unit}, got {_describe(value)}")
        return float(value)

    def value(self, where, kind, value, unit):
        if kind == "str":
            if not isinstance(value, str):
                raise self.error(f'{where} must be a string (in quotes, e.g. "U"), got {_describe(value)}')
            return value
        if kind == "int":
            if isinstance(value, bool) or not isinstance(value, int):
                raise self.error(f"{where} must be an integer ({unit}), got {_describe(value)}")
            return value
        if kind == "vector":
            if not isinstance(value, list):
                raise self.error(f"{where} must be an array of numbers [{unit.split(',')[0]}], "
                                 f"e.g. [0.0, 0.0, -2.0], got {_describe(value)}")
            return tuple(self.number(f"{where}[{k}]", v, unit) for k, v in enumerate(value))
        if kind == "blade":
            try:
                return BladeModel.from_dict(value)
            except (TypeError, ValueError) as err:
                raise self.error(f"{where}: {err}") from err
        return self.number(where, value, unit)   # float, optional float

    def fields(self, cls, table, where):
        """Keyword arguments of ``cls`` from the TOML table ``table`` at ``where``."""
        prefix = f"{where}." if where else ""
        schema = {f: spec for f, spec in _schema(cls).items() if spec[0] not in _TABLES}
        angles = _angle_fields(cls)
        extra = {"format_version"} if cls is AircraftConfig else set()
        tables = set(_TABLES) if cls is AircraftConfig else set()
        degrees = [a + _DEG for a in angles]
        for key in table:
            if key not in schema and key not in extra and key not in tables and key not in degrees:
                close = difflib.get_close_matches(key, list(schema) + degrees + sorted(tables), n=1)
                hint = f" (did you mean {close[0]!r}?)" if close else ""
                also = f" (angles also in degrees: {', '.join(degrees)})" if degrees else ""
                raise self.error(f"unknown field {prefix}{key}{hint}; the valid fields of "
                                 f"{_table_name(where)} are {', '.join(list(schema) + sorted(tables))}{also}")
        kwargs = {}
        for field, (kind, unit) in schema.items():
            if field in angles and field + _DEG in table:
                if field in table:
                    raise self.error(f"{prefix}{field} is given twice, as {field} [rad] and as "
                                     f"{field}{_DEG} [deg]: keep one")
                kwargs[field] = math.radians(self.number(prefix + field + _DEG, table[field + _DEG], "deg"))
            elif field in table:
                kwargs[field] = self.value(prefix + field, kind, table[field], unit)
        for field in _required(cls):
            if field not in kwargs and field not in tables:
                unit = schema[field][1]
                unit = f" [{unit}]" if unit and schema[field][0] != "str" else ""
                raise self.error(f"missing required field {prefix}{field}{unit}; {_table_name(where)} needs "
                                 f"{', '.join(f for f in _required(cls) if f not in tables)}")
        return kwargs

    def build(self, cls, kwargs, where):
        try:
            return cls(**kwargs)
        except ConfigError as err:
            at = f"{where}: " if where else ""
            raise self.error(f"{at}{err}") from err

    def aircraft(self, data):
        version = data.get("format_version", FORMAT_VERSION)
        if isinstance(version, bool) or version != FORMAT_VERSION:
            raise self.error(f"format_version {version!r} is not supported: this reader reads "
                             f"format_version = {FORMAT_VERSION}")
        kwargs = self.fields(AircraftConfig, data, "")
        if "rotors" not in data:
            raise self.error("missing required field rotors: give one [[rotors]] table per rotor "
                             "(one, or two for a coaxial)")
        rotors = data["rotors"]
        if isinstance(rotors, dict):
            raise self.error("rotors must be an array of tables: write [[rotors]] (two brackets), "
                             "not [rotors]")
        if not isinstance(rotors, list) or not all(isinstance(r, dict) for r in rotors):
            raise self.error(f"rotors must be an array of tables ([[rotors]]), got {_describe(rotors)}")
        kwargs["rotors"] = tuple(self.build(RotorConfig, self.fields(RotorConfig, r, f"rotors[{k}]"),
                                            f"rotors[{k}]")
                                 for k, r in enumerate(rotors))
        if "propeller" in data:
            table = data["propeller"]
            if not isinstance(table, dict):
                raise self.error(f"propeller must be a table ([propeller]), got {_describe(table)}")
            kwargs["propeller"] = self.build(PropellerConfig, self.fields(PropellerConfig, table, "propeller"),
                                             "propeller")
        if "tail_rotor" in data:
            table = data["tail_rotor"]
            if not isinstance(table, dict):
                raise self.error(f"tail_rotor must be a table ([tail_rotor]), got {_describe(table)}")
            kwargs["tail_rotor"] = self.build(TailRotorConfig,
                                              self.fields(TailRotorConfig, table, "tail_rotor"), "tail_rotor")
        return self.build(AircraftConfig, kwargs, "")


def _parse(raw, source):
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as err:
        line = raw[:err.start].count(b"\n") + 1
        raise ConfigFileError(f"{source}, line {line}: not UTF-8 text ({err.reason})") from err
    try:
        data = _toml.loads(text)
    except _toml.TOMLDecodeError as err:
        match = re.search(r"line (\d+)", str(err))
        at = f", line {match.group(1)}" if match else ""
        raise ConfigFileError(f"{source}{at}: TOML syntax error: {err}") from err
    return _Reader(source).aircraft(data)


def read_aircraft(path):
    """Read an aircraft configuration from a TOML file.

    The file layout and its rules are described in :mod:`aircraft.config_files`:
    SI units as in the dataclasses, angles in radians (or in degrees under
    ``NAME_deg``), left-out fields at their dataclass defaults.

    Parameters
    ----------
    path : str or os.PathLike
        The TOML file (UTF-8), as written by :func:`write_aircraft` or by hand.

    Returns
    -------
    aircraft.configs.AircraftConfig
        The aircraft, with its rotors and (if the file has a ``[propeller]``
        table) its propeller.

    Raises
    ------
    ConfigFileError
        If the file does not exist, is not valid TOML (the message gives the line),
        lacks a required field, has an unknown field or a value of the wrong type
        (the message names it, e.g. ``rotors[1].radius``), or a value the
        dataclasses refuse (their :class:`~aircraft.configs.ConfigError` message,
        with the file in front).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from aircraft import read_aircraft
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "small.toml"
    >>> _ = path.write_text('''
    ... name = "small helicopter"
    ... mass = 1000.0     # kg
    ... Ixx = 500.0       # kg m^2
    ... Iyy = 1500.0
    ... Izz = 1200.0
    ... [[rotors]]
    ... name = ""
    ... radius = 4.0      # m
    ... omega = 50.0      # rad/s
    ... n_blades = 3
    ... chord = 0.2       # m
    ... twist_deg = -8.0  # degrees, read as radians
    ... root_cutout = 0.15
    ... ''')
    >>> config = read_aircraft(path)
    >>> config.rotors[0].radius, round(config.rotors[0].twist, 4)
    (4.0, -0.1396)
    """
    source = Path(os.fspath(path))
    try:
        raw = source.read_bytes()
    except FileNotFoundError:
        raise ConfigFileError(f"aircraft file {source} does not exist") from None
    except IsADirectoryError:
        raise ConfigFileError(f"{source} is a directory, not an aircraft file") from None
    return _parse(raw, str(source))


# --- the shipped aircraft ---------------------------------------------------------
def _shipped_dir():
    return resources.files("aircraft") / "data" / "aircraft"


def shipped_aircraft():
    """Names of the aircraft files shipped in ``aircraft/data/aircraft``.

    Returns
    -------
    list of str
        File stems, e.g. ``["coaxial_compound", "uh60_single_rotor"]``, each a
        name for :func:`load_shipped_aircraft`.

    Examples
    --------
    >>> from aircraft.config_files import shipped_aircraft
    >>> shipped_aircraft()
    ['coaxial_compound', 'uh60_single_rotor']
    """
    return sorted(p.name[:-len(".toml")] for p in _shipped_dir().iterdir() if p.name.endswith(".toml"))


def load_shipped_aircraft(name):
    """Read one of the aircraft shipped with the package as data.

    ``"coaxial_compound"`` is :func:`aircraft.coaxial_compound` (hover rotor speed)
    and ``"uh60_single_rotor"`` is :func:`aircraft.uh60_single_rotor`; the tests
    check that file and function agree field for field.

    Parameters
    ----------
    name : str
        Name of the shipped file without ``.toml`` (see :func:`shipped_aircraft`).

    Returns
    -------
    aircraft.configs.AircraftConfig

    Raises
    ------
    ConfigFileError
        If no aircraft of that name is shipped (the message lists those that are).

    Examples
    --------
    >>> from aircraft import load_shipped_aircraft, uh60_single_rotor
    >>> config = load_shipped_aircraft("uh60_single_rotor")
    >>> config == uh60_single_rotor()
    True
    >>> config.rotors[0].n_blades
    4
    """
    names = shipped_aircraft()
    if not isinstance(name, str) or name not in names:
        raise ConfigFileError(f"no shipped aircraft {name!r}; shipped: {names}")
    resource = _shipped_dir() / f"{name}.toml"
    return _parse(resource.read_bytes(), f"aircraft/data/aircraft/{name}.toml")


def load_aircraft(aircraft):
    """An aircraft named on a command line or in a settings file: a shipped name or a file.

    What the studies' ``--aircraft`` option accepts, so that every study runs on
    a user's aircraft as well as on the dissertation's.

    Parameters
    ----------
    aircraft : str, os.PathLike or aircraft.configs.AircraftConfig
        The name of a shipped aircraft (see :func:`shipped_aircraft`), the path of
        a TOML file (:func:`read_aircraft`; a name ending in ``.toml`` or an
        existing file), or a configuration, returned as it is.

    Returns
    -------
    aircraft.configs.AircraftConfig

    Raises
    ------
    ConfigFileError
        If the name is neither a shipped aircraft nor a file (the message lists the
        shipped names), or the file is not a valid aircraft (see :func:`read_aircraft`).

    See Also
    --------
    load_shipped_aircraft, read_aircraft

    Examples
    --------
    >>> from aircraft import coaxial_compound
    >>> from aircraft.config_files import load_aircraft
    >>> load_aircraft("coaxial_compound") == coaxial_compound()
    True
    """
    if isinstance(aircraft, AircraftConfig):
        return aircraft
    if not isinstance(aircraft, (str, os.PathLike)) or not str(aircraft):
        raise ConfigFileError(f"aircraft must be a shipped aircraft's name or a TOML file's path, "
                              f"got {aircraft!r}; shipped: {shipped_aircraft()}")
    text = str(aircraft)
    if text in shipped_aircraft():
        return load_shipped_aircraft(text)
    if text.endswith(".toml") or Path(text).is_file():
        return read_aircraft(text)
    raise ConfigFileError(f"aircraft {text!r} is neither a shipped aircraft nor a TOML file; "
                          f"shipped: {shipped_aircraft()}")
