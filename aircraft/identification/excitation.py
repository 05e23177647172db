"""The excitation every identification from the wake shares: sweeps, verification doublets, noise floor.

:class:`ExcitationSettings` is the one definition of the wake records an identification
asks for and of the band it fits; :class:`~aircraft.identification.IdentificationSettings`
(inflow models) and :class:`~aircraft.identification.OffRotorSettings` (off-rotor
models) add what is their own.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

__all__ = ["ExcitationSettings"]


@dataclass(frozen=True)
class ExcitationSettings:
    """Wake records and fit band of an identification (SI units, radians).

    Parameters
    ----------
    wake : WakeSettings, optional
        Free-wake resolution (default: :class:`aircraft.wake.WakeSettings` defaults).
    sweep_s : float
        Length of each frequency sweep [s].
    amplitude : float
        Sweep amplitude [rad].
    w_min, w_max : float
        Sweep band and response band [rad/s].
    fit_range : (float, float)
        Band of the fit [rad/s], inside ``(w_min, w_max)``.
    doublet_amplitude, doublet_s, pulse_width : float
        Verification doublet [rad], record [s], pulse [s]. It is larger than the
        sweeps: the hover wake's own unsteadiness (~0.002 in lam0) would otherwise be
        as large as its response.
    noise_floor_s : float
        Length of the zero-input run [s] whose TIC is the wake's noise floor.
    n_omega : int
        Frequencies per response in the cost (CIFER: 20).
    coherence_min : float
        Responses need this coherence on 5+ points to be fitted.
    pade_order : int
        Padé order of the delays in the aircraft (or verification) model.

    Raises
    ------
    ValueError
        A band that is not ordered or a fit band outside it, a non-positive length or
        amplitude, fewer than 3 frequencies, a coherence outside [0, 1).

    Examples
    --------
    >>> ExcitationSettings(fit_range=(1.0, 10.0)).w_max
    30.0
    >>> ExcitationSettings(fit_range=(0.1, 10.0))
    Traceback (most recent call last):
    ...
    ValueError: fit_range (0.1, 10.0) must lie inside (w_min, w_max) = (0.7, 30.0) rad/s
    """

    #: the error raised for bad settings (a subclass may name its own ValueError)
    error: ClassVar[type] = ValueError

    wake: object = None
    sweep_s: float = 45.0
    amplitude: float = 0.02
    w_min: float = 0.7
    w_max: float = 30.0
    fit_range: tuple = (1.0, 25.0)
    doublet_amplitude: float = 0.05
    doublet_s: float = 4.0
    pulse_width: float = 0.5
    noise_floor_s: float = 4.0
    n_omega: int = 20
    coherence_min: float = 0.6
    pade_order: int = 2

    def __post_init__(self):
        err = type(self).error
        if not (_finite(self.w_min) and _finite(self.w_max) and 0 < self.w_min < self.w_max):
            raise err(f"need 0 < w_min < w_max [rad/s], got {self.w_min}, {self.w_max}")
        try:
            lo, hi = self.fit_range
        except (TypeError, ValueError):
            raise err(f"fit_range must be (w_lo, w_hi) [rad/s], got {self.fit_range!r}") from None
        if not (_finite(lo) and _finite(hi) and self.w_min <= lo < hi <= self.w_max):
            raise err(f"fit_range {tuple(self.fit_range)} must lie inside (w_min, w_max) = "
                      f"({self.w_min}, {self.w_max}) rad/s")
        for name in ("sweep_s", "doublet_s", "noise_floor_s", "amplitude", "doublet_amplitude", "pulse_width"):
            value = getattr(self, name)
            if not (_finite(value) and value > 0):
                raise err(f"{type(self).__name__}.{name} must be a positive finite number, got {value!r}")
        if isinstance(self.n_omega, bool) or not isinstance(self.n_omega, int) or self.n_omega < 3:
            raise err(f"n_omega must be an integer >= 3, got {self.n_omega!r}")
        if not (_finite(self.coherence_min) and 0 <= self.coherence_min < 1):
            raise err(f"coherence_min must be in [0, 1), got {self.coherence_min!r}")

    @property
    def wake_settings(self):
        """The wake resolution used (the default :class:`aircraft.wake.WakeSettings` if none)."""
        from aircraft.wake import WakeSettings
        return self.wake if self.wake is not None else WakeSettings()


def _finite(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) or \
        (hasattr(x, "dtype") and bool(math.isfinite(float(x))))
