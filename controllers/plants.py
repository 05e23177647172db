"""Hand-written single-axis plants for tests, benchmarks and examples.

The hover roll axis of a stiff-hingeless coaxial: a first-order roll-rate
response (roll damping ``roll_damping`` [1/s]) coupled with a lightly damped
regressive flap mode (in the non-rotating frame near (nu_beta - 1) Omega, about
12 rad/s for 1.5/rev at 23.7 rad/s), with a small transport delay.
"""
from __future__ import annotations

import control
import numpy as np

__all__ = ["hover_roll_plant", "first_order_actuator", "second_order_actuator", "DelayedLTI"]


class DelayedLTI:
    """An LTI system with an exact pure input delay ``delay`` [s].

    Frequency-domain metrics use ``system(jw) * exp(-jw delay)`` exactly;
    :meth:`to_statespace` absorbs the delay with a Padé approximant (state
    space only, as the specs require).
    """

    def __init__(self, system, delay=0.0, name=None):
        if delay < 0:
            raise ValueError(f"delay must be >= 0 s, got {delay}")
        self.system = system
        self.delay = float(delay)
        self.name = name

    def __call__(self, s):
        s = np.asarray(s, dtype=complex)
        return np.asarray(self.system(s)).reshape(s.shape) * np.exp(-s * self.delay)

    def response(self, omega):
        """Complex frequency response at ``omega`` [rad/s] (exact delay)."""
        return self(1j * np.asarray(omega, dtype=float))

    def to_statespace(self, pade_order=3):
        sys = control.ss(self.system)
        if self.delay > 0:
            num, den = control.pade(self.delay, pade_order)
            sys = control.series(control.ss(control.tf(num, den)), sys)
        return sys


def hover_roll_plant(gain=5.0, roll_damping=1.5, flap_frequency=11.9, flap_damping=0.175,
                     delay=0.01):
    """Bare-airframe roll-rate response p/delta_lat [rad/s per unit stick].

    ``P(s) = gain * roll_damping / (s + roll_damping) * wf^2 / (s^2 + 2 zf wf s + wf^2) * e^{-delay s}``

    Parameters
    ----------
    gain : float
        Steady roll rate per unit stick [rad/s].
    roll_damping : float
        -L_p [1/s].
    flap_frequency, flap_damping : float
        Regressive flap mode [rad/s], damping ratio.
    delay : float
        Transport delay [s].
    """
    if roll_damping <= 0 or flap_frequency <= 0 or not 0 < flap_damping < 1:
        raise ValueError("roll_damping and flap_frequency must be > 0 and 0 < flap_damping < 1")
    wf, zf = flap_frequency, flap_damping
    tf = control.tf([gain * roll_damping * wf ** 2],
                    np.polymul([1, roll_damping], [1, 2 * zf * wf, wf ** 2]),
                    inputs="delta_lat", outputs="p")
    return DelayedLTI(tf, delay, name="hover roll plant")


def first_order_actuator(bandwidth=30.0):
    """Actuator 1 / (s / bandwidth + 1), bandwidth [rad/s]."""
    return control.tf([bandwidth], [1, bandwidth])


def second_order_actuator(frequency=35.0, damping=0.7):
    """Actuator w^2 / (s^2 + 2 zeta w s + w^2)."""
    return control.tf([frequency ** 2], [1, 2 * damping * frequency, frequency ** 2])
