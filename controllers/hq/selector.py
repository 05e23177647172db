"""Select the specs that apply to an axis, MTE class, UCE, attention, agility and speed.

Names are matched exactly and case-insensitively (surrounding blanks ignored);
anything else raises :class:`ValueError` naming the argument and listing the
valid names.  No prefix matching: ``"tracking"`` is not an MTE class.
"""
from __future__ import annotations

import math
import numbers

from .base import AGILITIES, ATTENTIONS, AXES, SPEEDS
from .bandwidth import bandwidth_specs
from .boundaries import BoundaryNotPublishedError
from .limits import MTE_ALIASES, _choice, canonical_mte
from .coupling import coupling_specs
from .forward_flight import forward_flight_specs
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
              limits=None, missing="raise", generic=True, response_type="attitude"):
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

    Examples
    --------
    >>> [s.name for s in specs_for("heave", missing="skip", generic=False)]
    ['HgtRsH1.heave']
    >>> specs_for("roll", mte="tracking")
    Traceback (most recent call last):
    ...
    ValueError: unknown mte 'tracking'; valid names (case-insensitive, exact): ['target acquisition and tracking', 'all other'] (also accepted: ['all other mte', 'all other mtes'])
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
