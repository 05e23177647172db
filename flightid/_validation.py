"""Argument checks shared by the public functions of :mod:`flightid` (private).

Each check names the argument and what is allowed, and raises an
:class:`~flightid.errors.InputValueError` / :class:`~flightid.errors.DataError`
(both :class:`ValueError`) instead of letting a NaN, a complex number or a wrong
name travel into numpy/scipy and come out as a vague error or a wrong answer.
"""
from __future__ import annotations

import numbers

import numpy as np

from .errors import DataError, InputValueError, SignalNameError


def real_scalar(name, value, *, positive=False, nonnegative=False, lo=None, hi=None,
                lo_open=False, hi_open=False, unit="", error=InputValueError, complex_zero_ok=True):
    """``value`` as a finite real float, or ``error`` (a ValueError subclass) naming ``name``.

    ``complex_zero_ok``: a complex value with zero imaginary part is taken as real
    (flightid's convention for computed quantities); False refuses every complex
    value (the aircraft configurations' convention for typed-in parameters).
    """
    unit = f" [{unit}]" if unit else ""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Number, np.ndarray)):
        raise error(f"{name} must be a real number{unit}, got {value!r}")
    if isinstance(value, np.ndarray):
        if value.ndim != 0:
            raise error(f"{name} must be a scalar{unit}, got an array of shape {value.shape}")
        value = value[()]
    if isinstance(value, numbers.Complex) and not isinstance(value, numbers.Real):
        if np.imag(value) != 0 or not complex_zero_ok:
            raise error(f"{name} must be real{unit}, got the complex value {value!r}")
        value = np.real(value)
    v = float(value)
    if not np.isfinite(v):
        raise error(f"{name} must be finite{unit}, got {value!r}")
    if positive and not v > 0:
        raise error(f"{name} must be positive (> 0){unit}, got {v!r}")
    if nonnegative and v < 0:
        raise error(f"{name} must be non-negative (>= 0){unit}, got {v!r}")
    if lo is not None and (v < lo or (lo_open and v == lo)):
        raise error(f"{name} must be {'>' if lo_open else '>='} {lo:g}{unit}, got {v!r}")
    if hi is not None and (v > hi or (hi_open and v == hi)):
        raise error(f"{name} must be {'<' if hi_open else '<='} {hi:g}{unit}, got {v!r}")
    return v


def integer(name, value, *, minimum=None, error=InputValueError):
    """``value`` as an int (no bool, no non-integral float), at least ``minimum``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        if isinstance(value, numbers.Real) and float(value).is_integer():
            value = int(value)
        else:
            raise error(f"{name} must be an integer, got {value!r}")
    value = int(value)
    if minimum is not None and value < minimum:
        raise error(f"{name} must be an integer >= {minimum}, got {value}")
    return value


def real_array(name, values, *, error=DataError):
    """``values`` as a float ndarray; complex, non-numeric or non-finite data raise ``error``."""
    arr = np.asarray(values)
    if arr.dtype == object:
        try:
            arr = arr.astype(complex)
        except (TypeError, ValueError):
            raise error(f"{name} must hold numbers, got objects of type "
                        f"{type(arr.flat[0]).__name__ if arr.size else '?'}") from None
    if np.iscomplexobj(arr):
        if np.any(np.imag(arr) != 0):
            raise error(f"{name} must be real: it holds complex values (pass the real signal; "
                        "a complex array is never silently made real)")
        arr = np.real(arr)
    if not (np.issubdtype(arr.dtype, np.number) or arr.dtype == bool):
        raise error(f"{name} must hold numbers, got dtype {arr.dtype}")
    arr = arr.astype(float)
    if not np.all(np.isfinite(arr)):
        bad = np.flatnonzero(~np.isfinite(arr.ravel()))
        raise error(f"{name} contains {bad.size} NaN or infinite value(s) (first at flat index "
                    f"{bad[0]}); remove or interpolate them first")
    return arr


def names_in(kind, names, available):
    """Check every name of ``names`` is in ``available``; SignalNameError listing both."""
    available = list(available)
    missing = [n for n in names if n not in available]
    if missing:
        raise SignalNameError(f"unknown {kind} name(s) {missing}; available: {available}")
