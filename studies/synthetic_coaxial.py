"""Synthetic truth experiments (moved to :mod:`aircraft.identification.testing`).

Kept as a thin re-export for existing scripts; new code imports from the library.
"""
from aircraft.identification.testing import coaxial_sweep_set, mixing_matrix, simulate_mltau  # noqa: F401

__all__ = ["coaxial_sweep_set", "mixing_matrix", "simulate_mltau"]
