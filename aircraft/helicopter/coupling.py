"""Coupling numerators (Eq. 7.21) for the aircraft package.

The operations are pure LTI algebra and live in :mod:`flightid.lti`, the lowest
layer, which the aircraft and the control-design package both use: neither needs
the other (a change to the control design leaves the aircraft's code, and so the
identified models computed with it, untouched). They are re-exported here so that
``aircraft.helicopter.coupling`` callers keep working.
"""
from __future__ import annotations

from flightid.lti import CouplingError, coupling_numerator, residualize

__all__ = ["coupling_numerator", "residualize", "CouplingError"]
