"""Exceptions raised by :mod:`flightid` (all subclass built-ins).

Every bad argument raises a :class:`ValueError` subclass whose message names the
argument and what is allowed:

* :class:`InputValueError` -- a numeric argument is NaN, infinite, complex,
  negative or out of range;
* :class:`SignalNameError` -- a signal name that selects something (an output,
  an input, a DataFrame column) does not exist (also a :class:`KeyError`, so
  code that caught the old ``KeyError`` keeps working);
* :class:`DataError` -- time histories or responses unusable (NaN samples,
  non-uniform sampling, mismatched lengths, too short).
"""

__all__ = ["IdentificationError", "DataError", "InputValueError", "SignalNameError",
           "SingularInputError", "UnstableModelError", "SettlingWarning"]


class IdentificationError(ValueError):
    """Base class: the identification cannot proceed with the data or structure given."""


class DataError(IdentificationError):
    """Time histories unusable: NaNs, non-uniform sampling, mismatched lengths, too short."""


class InputValueError(IdentificationError):
    """An argument is NaN, infinite, complex, of the wrong sign or out of its range."""


class SignalNameError(IdentificationError, KeyError):
    """A signal or column name that selects something does not exist.

    Subclasses both :class:`ValueError` (through :class:`IdentificationError`)
    and :class:`KeyError`.
    """

    def __str__(self):
        # KeyError quotes its message; keep the plain sentence
        return str(self.args[0]) if self.args else ""


class SingularInputError(IdentificationError):
    """The input-output response matrix u/theta is singular at some frequencies.

    ``frequencies`` holds the offending frequencies [rad/s].
    """

    def __init__(self, message, frequencies=()):
        super().__init__(message)
        self.frequencies = tuple(frequencies)


class UnstableModelError(IdentificationError):
    """A fitted model has eigenvalues in the right half plane."""


class SettlingWarning(UserWarning):
    """A record's lead-in or lead-out (input at trim before and after the excitation) is
    shorter than the response needs to settle, or its excitation holds fewer than two
    periods of the lowest analysed frequency."""
