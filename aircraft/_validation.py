"""Argument checks shared by the public boundaries of :mod:`aircraft` (private).

Every check names the field and what is allowed and raises the ``error`` class
it is given (a :class:`ValueError` subclass of the calling module), so a NaN,
an infinity, a complex number or an out-of-range value is caught where it is
passed, not later as a "loads contain NaN" or a diverged wake.
"""
from __future__ import annotations

import math
import numbers

import numpy as np


def real(error, name, value, *, positive=False, nonnegative=False, lo=None, hi=None, unit=""):
    """``value`` as a finite real float in range, else ``error`` naming ``name``."""
    unit = f" [{unit}]" if unit else ""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Number):
        raise error(f"{name} must be a real number{unit}, got {value!r}")
    if isinstance(value, numbers.Complex) and not isinstance(value, numbers.Real):
        raise error(f"{name} must be real{unit}, got the complex value {value!r}")
    v = float(value)
    if not math.isfinite(v):
        raise error(f"{name} must be finite{unit}, got {value!r}")
    if positive and not v > 0:
        raise error(f"{name} must be positive (> 0){unit}, got {v!r}")
    if nonnegative and v < 0:
        raise error(f"{name} must be non-negative (>= 0){unit}, got {v!r}")
    if lo is not None and v < lo:
        raise error(f"{name} must be >= {lo:g}{unit}, got {v!r}")
    if hi is not None and v > hi:
        raise error(f"{name} must be <= {hi:g}{unit}, got {v!r}")
    return v


def integer(error, name, value, *, minimum=None):
    """``value`` as an int (not a bool or a fractional float), at least ``minimum``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        if isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_)) \
                and math.isfinite(value) and float(value).is_integer():
            value = int(value)
        else:
            raise error(f"{name} must be an integer, got {value!r}")
    value = int(value)
    if minimum is not None and value < minimum:
        raise error(f"{name} must be an integer >= {minimum}, got {value}")
    return value


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
