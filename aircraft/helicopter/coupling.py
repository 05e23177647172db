"""Coupling numerators (Eq. 7.21) for the aircraft package.

The operations are pure LTI algebra and live in :mod:`controllers.lti`, so
that the control-design package needs nothing from ``aircraft``; they are
re-exported here so that ``aircraft.helicopter.coupling`` callers keep working.
"""
from __future__ import annotations

from controllers.lti import CouplingError, coupling_numerator, residualize

__all__ = ["coupling_numerator", "residualize", "CouplingError"]
