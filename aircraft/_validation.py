"""Argument checks shared by the public boundaries of :mod:`aircraft` (private).

Every check names the field and what is allowed and raises the ``error`` class
it is given (a :class:`ValueError` subclass of the calling module), so a NaN,
an infinity, a complex number or an out-of-range value is caught where it is
passed, not later as a "loads contain NaN" or a diverged wake.
"""
from __future__ import annotations

from flightid._validation import integer as _integer
from flightid._validation import real_scalar


def real(error, name, value, *, positive=False, nonnegative=False, lo=None, hi=None, unit=""):
    """``value`` as a finite real float in range, else ``error`` naming ``name``
    (flightid's check; every complex value is refused here)."""
    return real_scalar(name, value, positive=positive, nonnegative=nonnegative, lo=lo, hi=hi, unit=unit,
                       error=error, complex_zero_ok=False)


def integer(error, name, value, *, minimum=None):
    """``value`` as an int (not a bool or a fractional float), at least ``minimum``."""
    return _integer(name, value, minimum=minimum, error=error)


def vector(error, name, value, size, unit=""):
    """A tuple of ``size`` finite real floats."""
    unit = f" [{unit}]" if unit else ""
    try:
        items = tuple(value)
    except TypeError:
        raise error(f"{name} must be a sequence of {size} real numbers{unit}, got {value!r}") from None
    if len(items) != size:
        raise error(f"{name} must have {size} entries{unit}, got {len(items)}")
    return tuple(real(error, f"{name}[{k}]", v, unit=unit.strip(" []")) for k, v in enumerate(items))
