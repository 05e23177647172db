"""Inflow model structures: the dissertation's models as parametric :mod:`flightid` structures.

Each structure knows its signals, builds the :mod:`flightid` structure from initial
values, proposes a data-driven start, maps a printed model onto its parameters and
turns fitted values into an :class:`aircraft.inflow.IdentifiedInflow`.

=====================================  ==========================================================
key                                    structure
=====================================  ==========================================================
``single_rotor_3state``                :class:`SingleRotor3State` (Tables 4.1-4.2)
``single_rotor_forward``               :class:`SingleRotorForward` (Eq. 4.3)
``coaxial_6state``                     :class:`Coaxial6State` (Eq. 5.3)
``coaxial_6state_axisymmetric``        :class:`Coaxial6StateAxisymmetric` (Eq. 5.3 + 1s/1c terms)
``coaxial_12state``                    :class:`Coaxial12State` (Eqs. 6.2-6.3)
``coaxial_12state_constrained``        :class:`Coaxial12StateConstrained` (freedoms removed by name)
``coaxial_12state_tilt``               :class:`Coaxial12StateTilt` (plus tip-path-plane tilt inputs)
``coaxial_forward_12state``            :class:`CoaxialForward12State` (Eqs. 6.4-6.7, 200 kt)
=====================================  ==========================================================

plus the named variants in :data:`STRUCTURES` (e.g. ``coaxial_12state_delays``).
:data:`STRUCTURES` is the one registry: it is written here, in full, and
:func:`register_structure` adds a user's own structure to it.

Examples
--------
>>> from aircraft.identification.structures import get_structure
>>> get_structure("single_rotor_3state").key
'single_rotor_3state'
"""
from .base import InflowStructure, low_frequency_gain, low_frequency_points
from .hover import Coaxial6State, Coaxial12State, SingleRotor3State
from .axisymmetric import PITT_PETERS_COLLECTIVE_MASS, Coaxial6StateAxisymmetric
from .constrained import VARIANTS, Coaxial12StateConstrained
from .tilt import Coaxial12StateTilt
from .forward import SingleRotorForward
from .coaxial_forward import CoaxialForward12State

__all__ = ["InflowStructure", "SingleRotor3State", "SingleRotorForward", "Coaxial6State", "Coaxial6StateAxisymmetric",
           "Coaxial12State", "Coaxial12StateConstrained", "Coaxial12StateTilt", "CoaxialForward12State",
           "STRUCTURES", "get_structure", "register_structure", "low_frequency_gain", "low_frequency_points"]

#: Every structure by key: a class or a factory returning an instance.
STRUCTURES = {
    SingleRotor3State.key: SingleRotor3State,
    SingleRotorForward.key: SingleRotorForward,
    Coaxial6State.key: Coaxial6State,
    Coaxial6StateAxisymmetric.key: Coaxial6StateAxisymmetric,
    # the structure shipped as coaxial_hover_6state_axisymmetric
    "coaxial_6state_axisymmetric_pp_collective_mass":
        lambda: Coaxial6StateAxisymmetric(a_priori=PITT_PETERS_COLLECTIVE_MASS),
    Coaxial12State.key: Coaxial12State,
    # Eq. 6.2 plus the 6-state's lambda/C delays: the structure shipped from our wake
    "coaxial_12state_delays": lambda: Coaxial12State(delays=True),
    # the same with the cyclic far wake fed by the loads (in our wake the lower
    # rotor's cyclic inflow reverses sign slowly after a cyclic step)
    "coaxial_12state_far_loads": lambda: Coaxial12State(delays=True, far_wake_loads=True),
    Coaxial12StateConstrained.key: Coaxial12StateConstrained,
    "coaxial_12state_first_order_collective_pp": lambda: Coaxial12StateConstrained(
        **VARIANTS["first-order collective, Pitt-Peters collective gain, without far-far cross-rotor cyclic"]),
    Coaxial12StateTilt.key: Coaxial12StateTilt,
    CoaxialForward12State.key: CoaxialForward12State,
}


def register_structure(key, factory):
    """Add a structure to :data:`STRUCTURES` under ``key``.

    Parameters
    ----------
    key : str
        Registry key (what settings and model files name the structure by).
    factory : type or callable
        An :class:`InflowStructure` subclass, or a callable returning an instance.

    Raises
    ------
    ValueError
        ``key`` is empty or already registered to something else.
    TypeError
        ``factory`` is not callable.

    Examples
    --------
    >>> register_structure("my_3state", lambda: SingleRotor3State())
    >>> get_structure("my_3state").key
    'single_rotor_3state'
    >>> del STRUCTURES["my_3state"]
    """
    if not isinstance(key, str) or not key:
        raise ValueError(f"structure key must be a non-empty string, got {key!r}")
    if not callable(factory):
        raise TypeError(f"factory must be an InflowStructure class or a callable, got {factory!r}")
    if key in STRUCTURES and STRUCTURES[key] is not factory:
        raise ValueError(f"structure key {key!r} is already registered")
    STRUCTURES[key] = factory


def get_structure(structure):
    """A structure instance from an instance, a class or a key of :data:`STRUCTURES`.

    Parameters
    ----------
    structure : InflowStructure, type or str
        An instance (returned as is), a subclass (instantiated with defaults)
        or a key of :data:`STRUCTURES`.

    Returns
    -------
    InflowStructure

    Raises
    ------
    ValueError
        If ``structure`` is none of these.

    Examples
    --------
    >>> get_structure("coaxial_12state_tilt").key
    'coaxial_12state_tilt'
    """
    if isinstance(structure, InflowStructure):
        return structure
    if isinstance(structure, type) and issubclass(structure, InflowStructure):
        return structure()
    if isinstance(structure, str) and structure in STRUCTURES:
        return STRUCTURES[structure]()
    raise ValueError(f"unknown inflow structure {structure!r}; use one of {sorted(STRUCTURES)} "
                     "or an InflowStructure")
