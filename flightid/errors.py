"""Exceptions raised by :mod:`flightid` (all subclass built-ins)."""

__all__ = ["IdentificationError", "DataError", "SingularInputError", "UnstableModelError"]


class IdentificationError(ValueError):
    """Base class: the identification cannot proceed with the data or structure given."""


class DataError(IdentificationError):
    """Time histories unusable: NaNs, non-uniform sampling, mismatched lengths, too short."""


class SingularInputError(IdentificationError):
    """The input-output response matrix u/theta is singular at some frequencies.

    ``frequencies`` holds the offending frequencies [rad/s].
    """

    def __init__(self, message, frequencies=()):
        super().__init__(message)
        self.frequencies = tuple(frequencies)


class UnstableModelError(IdentificationError):
    """A fitted model has eigenvalues in the right half plane."""
