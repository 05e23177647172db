"""Names and bandwidth limits shared by the spec library and the roll specs (a leaf: imports nothing).

:func:`controllers.specs.default_specs` and :mod:`controllers.hq` both read the MTE class
names and the roll bandwidth/phase-delay rectangles from here, so each is defined once and
neither package imports the other's modules to get them.
"""
from __future__ import annotations

__all__ = ["MTE_CLASSES", "MTE_ALIASES", "BANDWIDTH_LIMITS", "canonical_mte"]

#: mission-task-element classes of the bandwidth charts
MTE_CLASSES = ("target acquisition and tracking", "all other")
#: other exact spellings accepted for the MTE classes
MTE_ALIASES = {"all other mtes": "all other", "all other mte": "all other"}

#: rectangles carried over from the toolkit's earlier specs: (w_BW L1, w_BW L2, tau_p L1, tau_p L2)
BANDWIDTH_LIMITS = {
    ("roll", "target acquisition and tracking"): (2.5, 1.5, 0.12, 0.20),
    ("roll", "all other"): (2.0, 1.0, 0.20, 0.30),
}


def _choice(argument, value, valid, aliases=None):
    if not isinstance(value, str):
        raise TypeError(f"{argument} must be a string, one of {list(valid)}; got {type(value).__name__}")
    key = " ".join(value.strip().lower().split())
    key = (aliases or {}).get(key, key)
    if key not in valid:
        extra = f" (also accepted: {sorted(aliases)})" if aliases else ""
        raise ValueError(f"unknown {argument} {value!r}; valid names (case-insensitive, exact): {list(valid)}{extra}")
    return key


def canonical_mte(mte):
    """The MTE class named by ``mte`` (case-insensitive exact name or alias).

    Parameters
    ----------
    mte : str
        ``"target acquisition and tracking"`` or ``"all other"`` (alias ``"all other MTEs"``).

    Returns
    -------
    str

    Raises
    ------
    ValueError
        Unknown name; the message lists the valid ones.

    Examples
    --------
    >>> canonical_mte("Target Acquisition and Tracking")
    'target acquisition and tracking'
    """
    return _choice("mte", mte, MTE_CLASSES, MTE_ALIASES)
