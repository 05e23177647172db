"""Select the specs that apply to an axis, MTE class, UCE, attention, agility and speed.

Names are matched exactly and case-insensitively (surrounding blanks ignored);
anything else raises :class:`ValueError` naming the argument and listing the
valid names.  No prefix matching: ``"tracking"`` is not an MTE class.
"""
from __future__ import annotations

import difflib
import math
import numbers
from collections.abc import Mapping

from .base import AGILITIES, ATTENTIONS, AXES, SPEEDS, RegionSpec
from .bandwidth import bandwidth_specs
from .boundaries import BoundaryNotPublishedError
from .limits import MTE_ALIASES, _choice, canonical_mte
from .coupling import coupling_specs
from .forward_flight import DampingFrequencySpec, forward_flight_specs
from .generic import generic_specs
from .heave import heave_specs
from .large_amplitude import large_amplitude_specs
from .quickness import quickness_specs

__all__ = ["specs_for", "all_specs", "canonical_mte", "MTE_ALIASES", "flight_regime", "LOW_SPEED_LIMIT"]

_MISSING = ("raise", "skip", "keep")
#: ADS-33E-PRF's hover and low-speed regime ends at 45 kt [m/s] (1 kt = 1852/3600 m/s)
LOW_SPEED_LIMIT = 45.0 * 1852.0 / 3600.0


def flight_regime(speed):
    """The ``speed`` name of :func:`specs_for` for an airspeed: hover/low speed below 45 kt, else forward.

    Parameters
    ----------
    speed : float
        Airspeed [m/s], >= 0.

    Returns
    -------
    str
        ``"hover"`` below :data:`LOW_SPEED_LIMIT` (45 kt, about 23 m/s), ``"forward"`` at and above it.

    Raises
    ------
    ValueError
        ``speed`` negative or not a finite number.

    Examples
    --------
    >>> flight_regime(0.0), flight_regime(50.0)
    ('hover', 'forward')
    """
    if isinstance(speed, bool) or not isinstance(speed, numbers.Real) or not math.isfinite(speed) or speed < 0:
        raise ValueError(f"flight_regime: speed must be a finite airspeed >= 0 [m/s], got {speed!r}")
    return "hover" if speed < LOW_SPEED_LIMIT else "forward"


def all_specs(limits=None, response_type="attitude"):
    """Every spec of the library, in family order.

    Parameters
    ----------
    limits : ActuatorLimits, optional
        Actuator limits for the OLOP specs.
    response_type : {"attitude", "rate"}
        Response type for the bandwidth definition (ADS-33E-PRF §3.2).

    Returns
    -------
    list of HQSpec

    Examples
    --------
    >>> len(all_specs()) > 30
    True
    """
    return (bandwidth_specs(response_type) + quickness_specs() + large_amplitude_specs() + coupling_specs()
            + heave_specs() + forward_flight_specs() + generic_specs(limits))


def specs_for(axis, mte="all other", uce=1, attention="fully attended", speed="hover", agility="moderate",
              limits=None, missing="raise", generic=True, response_type="attitude", boundaries=None):
    """The library's specs that apply to one axis and mission task element.

    Parameters
    ----------
    axis : {"pitch", "roll", "yaw", "heave"}
    mte : str
        ADS-33E-PRF MTE class of the bandwidth and quickness charts:
        ``"target acquisition and tracking"`` or ``"all other"``.
    uce : {1, 2, 3}
        Usable cue environment.
    attention : {"fully attended", "divided"}
    speed : {"hover", "forward"}
        Flight regime [a name, not a number]: hover/low speed or forward flight.
    agility : {"limited", "moderate", "aggressive"}
        Agility class of the large-amplitude and coupling requirements.
    limits : ActuatorLimits, optional
        Actuator limits for the OLOP specs.
    missing : {"raise", "skip", "keep"}
        What to do with applicable specs whose boundaries were not found
        printed (or that miss an input, e.g. the OLOP's actuator limits):
        raise :class:`BoundaryNotPublishedError` naming them (default), leave them out (``"skip"``, an explicit choice), or
        return them (``"keep"``, for tables and charts; evaluating one raises).
    generic : bool
        Include the CONDUIT generic specs (stability, margins, DRB/DRP, ...).
    response_type : {"attitude", "rate"}
        Response type for the bandwidth definition.
    boundaries : mapping, optional
        Spec name -> Level boundaries the caller supplies (e.g. read from their
        copy of ADS-33E-PRF) for the chart this call selects: a mapping with
        ``source`` and ``level1`` (and ``level2``, ``level3``) for a scalar spec,
        or ``level1``/``level2`` polygons (and ``scale``, ``limits``) for a
        chart; see :meth:`HQSpec.with_boundaries` and
        :meth:`~controllers.hq.base.RegionSpec.with_boundaries`.  A supplied
        spec is available (status ``"supplied"``); a name the library does not
        have is refused, one that does not apply to this selection is ignored
        (a mapping may serve every axis).  JSON-ready: ``json.load`` gives one.

    Returns
    -------
    list of HQSpec
        Usable in :func:`controllers.evaluate_specs` (names are unique per call).

    Raises
    ------
    ValueError
        Unknown axis, MTE, attention, speed, agility or UCE (the valid values are listed).
    BoundaryNotPublishedError
        ``missing="raise"`` and some applicable spec has no printed boundary.

    See Also
    --------
    controllers.hq.base.HQSpec.with_boundaries : one spec's supplied boundaries.

    Examples
    --------
    >>> [s.name for s in specs_for("heave", missing="skip", generic=False)]
    ['HgtRsH1.heave']
    >>> specs_for("roll", mte="tracking")
    Traceback (most recent call last):
    ...
    ValueError: unknown mte 'tracking'; valid names (case-insensitive, exact): ['target acquisition and tracking', 'all other'] (also accepted: ['all other mte', 'all other mtes'])

    A boundary read from one's own copy of the standard makes a spec usable:

    >>> mine = {"DrbPiH1": {"level1": 0.5, "level2": 0.25, "source": "programme requirement"}}
    >>> [(s.name, s.status) for s in specs_for("pitch", missing="skip", boundaries=mine) if s.name == "DrbPiH1"]
    [('DrbPiH1', 'supplied')]
    """
    axis = _choice("axis", axis, AXES)
    mte = canonical_mte(mte)
    attention = _choice("attention", attention, ATTENTIONS)
    speed = _choice("speed", speed, SPEEDS)
    agility = _choice("agility", agility, AGILITIES)
    if isinstance(uce, bool) or uce not in (1, 2, 3):
        raise ValueError(f"unknown uce {uce!r}; valid values: [1, 2, 3]")
    if missing not in _MISSING:
        raise ValueError(f"missing must be one of {list(_MISSING)}, got {missing!r}")
    pool = all_specs(limits, response_type) if generic else (
        bandwidth_specs(response_type) + quickness_specs() + large_amplitude_specs() + coupling_specs()
        + heave_specs() + forward_flight_specs())
    chosen = [s for s in pool if (generic or s.family != "generic")
              and s.applies_to(axis, mte, agility, uce, attention, speed)]
    if boundaries is not None:
        chosen = _supplied(chosen, boundaries, {s.name for s in all_specs(limits, response_type)})
    absent = [s for s in chosen if not s.available]
    if absent and missing == "raise":
        lines = "\n".join(f"  {s.name}: {s.description} -- " + (f"needs {s.missing_input}" if s.missing_input
                                                                   else s.source) for s in absent)
        raise BoundaryNotPublishedError(
            f"{len(absent)} spec(s) for axis={axis!r}, mte={mte!r}, uce={uce}, attention={attention!r}, "
            f"speed={speed!r}, agility={agility!r} have no printed boundary values or miss inputs:\n{lines}\n"
            "pass missing='skip' to leave them out or missing='keep' to list them")
    if missing == "skip":
        chosen = [s for s in chosen if s.available]
    names = [s.name for s in chosen]
    dupes = sorted({n for n in names if names.count(n) > 1})
    if dupes:   # guards the registry: a spec list must name each spec once
        raise RuntimeError(f"specs_for: several applicable specs share the names {dupes}")
    return chosen


#: per kind of spec: the keys a supplied entry may have, and those it must have
_KEYS = {"scalar": ({"source", "level1", "level2", "level3"}, ["level1", "source"]),
         "chart polygons": ({"source", "level1", "level2", "scale", "limits"}, ["level1", "level2", "source"]),
         "mode bounds": ({"source", "limits"}, ["limits", "source"])}


def _supplied(chosen, boundaries, library):
    """``chosen`` with the specs named in ``boundaries`` replaced by their supplied copies."""
    if not isinstance(boundaries, Mapping):
        raise TypeError(f"boundaries must be a mapping of spec name -> boundary values, got {type(boundaries).__name__}")
    for name, values in boundaries.items():
        if name not in library:
            close = difflib.get_close_matches(str(name), sorted(library), n=3)
            raise ValueError(f"boundaries: no spec named {name!r} in the library"
                             + (f" (did you mean {close}?)" if close else f"; names: {sorted(library)}"))
        if not isinstance(values, Mapping):
            raise TypeError(f"boundaries[{name!r}] must be a mapping (source, level1, level2, ...), "
                            f"got {type(values).__name__}")
    out = []
    for s in chosen:
        values = boundaries.get(s.name)
        if values is None:
            out.append(s)
            continue
        kind = ("chart polygons" if isinstance(s, RegionSpec) else
                "mode bounds" if isinstance(s, DampingFrequencySpec) else "scalar")
        keys, needed = _KEYS[kind]
        if set(values) - keys or set(needed) - set(values):
            raise ValueError(f"boundaries[{s.name!r}] ({kind}): keys must be among {sorted(keys)}, with {needed} "
                             f"given; got {sorted(values)}")
        out.append(s.with_boundaries(**values))
    return out
