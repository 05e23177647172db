"""Errors of the wake march, in a leaf module.

:mod:`aircraft.wake.wake` raises them and :mod:`aircraft.wake.trim` catches them;
both import them from here, so trim does not import the wake module that calls it
(no import circle).
"""
from __future__ import annotations

__all__ = ["WakeDivergedError"]


class WakeDivergedError(RuntimeError):
    """Raised when the wake geometry or the loads become non-finite."""
