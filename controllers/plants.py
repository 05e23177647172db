"""Single-axis plants: delayed LTI wrapper, hand-written plants, aircraft roll plants.

The hand-written hover roll axis of a stiff-hingeless coaxial: a first-order
roll-rate response (roll damping ``roll_damping`` [1/s]) coupled with a lightly
damped regressive flap mode (in the non-rotating frame near (nu_beta - 1) Omega,
about 12 rad/s for 1.5/rev at 23.7 rad/s), with a small transport delay.

:func:`roll_design_plant` turns a linearised aircraft (``linearize(trim(heli))``)
into the single-axis roll plant the EMF design uses (Eq. 7.21).
"""
from __future__ import annotations

import control
import numpy as np

from flightid.lti import coupling_numerator, residualize

__all__ = ["hover_roll_plant", "first_order_actuator", "second_order_actuator", "DelayedLTI",
           "roll_design_plant", "HOVER_ROLL_CONSTRAINTS"]

#: Eq. 7.21: pitch, yaw and heave held by lateral-free coupling numerators
HOVER_ROLL_CONSTRAINTS = {"q": "delta_lon", "r": "delta_ped", "w": "delta_col"}


def _check_siso(sys, what):
    if isinstance(sys, control.LTI) and (sys.ninputs != 1 or sys.noutputs != 1):
        raise ValueError(f"{what} must be SISO, got {sys.ninputs} inputs x {sys.noutputs} outputs; "
                         "take one channel first (e.g. controllers.roll_design_plant or "
                         "flightid.lti.coupling_numerator)")


class DelayedLTI:
    """A SISO LTI system with an exact pure input delay ``delay`` [s].

    Frequency-domain metrics use ``system(jw) * exp(-jw delay)`` exactly;
    :meth:`to_statespace` absorbs the delay with a Padé approximant (state
    space only, as the specs require).  The last few frequency grids are
    cached (the system is treated as immutable): spec evaluation asks for the
    same grid many times.
    """

    _CACHE_SIZE = 6

    def __init__(self, system, delay=0.0, name=None):
        if not isinstance(system, control.LTI):
            raise TypeError(f"system must be a python-control LTI object, got {type(system).__name__}")
        _check_siso(system, "the plant")
        if not np.isfinite(delay) or np.iscomplexobj(delay) or delay < 0:
            raise ValueError(f"delay must be >= 0 s and finite, got {delay}")
        mats = [np.asarray(m) for m in ((system.A, system.B, system.C, system.D)
                                        if isinstance(system, control.StateSpace) else ())]
        if any(m.size and not np.all(np.isfinite(m)) for m in mats):
            raise ValueError("the plant's state-space matrices contain NaN or inf")
        self.system = system
        self.delay = float(delay)
        self.name = name
        self._cache = {}

    def __call__(self, s):
        s = np.asarray(s, dtype=complex)
        key = (s.shape, s.tobytes())
        hit = self._cache.get(key)
        if hit is None:
            hit = np.asarray(self.system(s)).reshape(s.shape) * np.exp(-s * self.delay)
            if len(self._cache) >= self._CACHE_SIZE:
                self._cache.pop(next(iter(self._cache)))
            self._cache[key] = hit
        return hit

    def response(self, omega):
        """Complex frequency response at ``omega`` [rad/s] (exact delay)."""
        return self(1j * np.asarray(omega, dtype=float))

    def to_statespace(self, pade_order=3):
        """State space with the delay replaced by a Padé approximant of ``pade_order``."""
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

    Returns
    -------
    DelayedLTI
    """
    if roll_damping <= 0 or flap_frequency <= 0 or not 0 < flap_damping < 1:
        raise ValueError("roll_damping and flap_frequency must be > 0 and 0 < flap_damping < 1")
    if not np.isfinite(gain) or gain == 0:
        raise ValueError(f"gain must be finite and non-zero, got {gain}")
    wf, zf = flap_frequency, flap_damping
    tf = control.tf([gain * roll_damping * wf ** 2],
                    np.polymul([1, roll_damping], [1, 2 * zf * wf, wf ** 2]),
                    inputs="delta_lat", outputs="p")
    return DelayedLTI(tf, delay, name="hover roll plant")


def roll_design_plant(sys, output="p", input="delta_lat", constrained=None, drop_states=("psi",),
                      residualize_above=60.0, minreal_tol=1e-3, delay=0.0, name=None):
    """Single-axis roll plant for EMF design from a linearised aircraft (Eq. 7.21).

    Steps (each explained where it matters for the design band 0.1-20 rad/s):

    1. drop the states in ``drop_states`` (heading ``psi`` feeds back into
       nothing: a pure integrator the roll loop cannot see);
    2. coupling numerator ``output/input`` with ``constrained`` held
       (default :data:`HOVER_ROLL_CONSTRAINTS`: q, r, w by lon, ped, col);
    3. residualise modes faster than ``residualize_above`` [rad/s]: the exact
       coupling numerator inherits non-minimum-phase zeros of the constraint loops
       as unstable poles near 100 rad/s (flap-body coupling of the hingeless
       coaxial); DC gain is kept, < 1 % / 1 deg error up to 10 rad/s;
    4. minimal realisation with ``minreal_tol``: a neutral translational drift
       mode (|pole| ~ 3e-4 1/s) nearly cancels a zero at the origin.

    Parameters
    ----------
    sys : control.StateSpace
        Linear aircraft with named states, inputs and outputs (outputs = states),
        e.g. ``aircraft.helicopter.linearize(trim(heli))``.
    output, input : str
        Signal names of the free axis.
    constrained : dict, optional
        Held output name -> control name.
    drop_states : sequence of str
        States removed before the coupling numerator (must exist).
    residualize_above : float or None
        Cutoff [rad/s]; None skips step 3.
    minreal_tol : float or None
        Tolerance of step 4; None skips it.
    delay : float
        Pure delay added to the plant [s].
    name : str, optional
        Plant name (default ``"output/input | held->control, ..."``).

    Returns
    -------
    DelayedLTI
        ``output/input`` plant [rad/s per stick unit].
    """
    if not isinstance(sys, control.StateSpace):
        raise TypeError(f"sys must be a control.StateSpace, got {type(sys).__name__}")
    constrained = dict(HOVER_ROLL_CONSTRAINTS if constrained is None else constrained)
    states, inputs, outputs = list(sys.state_labels), list(sys.input_labels), list(sys.output_labels)
    for kind, names, pool in (("state", drop_states, states), ("output", [output, *constrained], outputs),
                              ("input", [input, *constrained.values()], inputs)):
        missing = [n for n in names if n not in pool]
        if missing:
            raise ValueError(f"unknown {kind} name(s) {missing}; available: {pool}")
    held = list(constrained.values())
    if input in held or len(set(held)) != len(held):
        raise ValueError(f"each held output needs its own control, distinct from the free input {input!r}; "
                         f"got {constrained}")
    if output in constrained:
        raise ValueError(f"the free output {output!r} cannot also be held")
    if drop_states:
        keep = [i for i, n in enumerate(states) if n not in drop_states]
        out_keep = [i for i, n in enumerate(outputs) if n not in drop_states]
        sys = control.ss(sys.A[np.ix_(keep, keep)], sys.B[keep, :], sys.C[np.ix_(out_keep, keep)],
                         sys.D[out_keep, :], states=[states[i] for i in keep], inputs=inputs,
                         outputs=[outputs[i] for i in out_keep])
    plant = coupling_numerator(sys, output, input, constrained)
    if residualize_above is not None:
        plant = residualize(plant, cutoff=residualize_above)
    if minreal_tol is not None:
        plant = control.minreal(plant, tol=minreal_tol, verbose=False)
    # the reductions drop the signal names: the design checks them against its axis
    plant = control.ss(plant)
    plant = control.ss(plant.A, plant.B, plant.C, plant.D, inputs=[input], outputs=[output])
    return DelayedLTI(plant, delay, name=name or f"{output}/{input} | " + ", ".join(
        f"{o}->{i}" for o, i in constrained.items()))


def first_order_actuator(bandwidth=30.0):
    """Actuator 1 / (s / bandwidth + 1), bandwidth [rad/s]."""
    if not np.isfinite(bandwidth) or bandwidth <= 0:
        raise ValueError(f"bandwidth must be a finite positive frequency [rad/s], got {bandwidth}")
    return control.tf([bandwidth], [1, bandwidth])


def second_order_actuator(frequency=35.0, damping=0.7):
    """Actuator w^2 / (s^2 + 2 zeta w s + w^2), frequency [rad/s], damping [-]."""
    if not np.isfinite(frequency) or frequency <= 0 or not np.isfinite(damping) or damping <= 0:
        raise ValueError(f"frequency and damping must be finite and > 0, got {frequency}, {damping}")
    return control.tf([frequency ** 2], [1, 2 * damping * frequency, frequency ** 2])
