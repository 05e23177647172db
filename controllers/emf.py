"""Explicit model following (EMF, dissertation Fig. 7.12) for one axis (roll).

::

    delta_lat_s ─► command model ─► phi_cm, p_cm ─┬─► inverse plant ─► delta_ff ─┐
                                                   └─► e^{-tau_eq s} ─► PID ─► delta_fb ─┤
                                                                 ▲                      ▼
                                               sensor ◄─ phi, p ◄─ plant ◄─ actuator ◄─ delta_mx

Frequency-domain quantities are *exact* callables (pure delays as e^{-jw tau});
the state-space closed loop (:meth:`EMFDesign.closed_loop`) is assembled with
:func:`control.interconnect` from named blocks, with Padé delays.

Notation: G = actuator * plant (delta_mx -> p); S = sensor; C(s) = K_p + K_phi/s
+ K_Iphi/s^2 acting on p (phi = p/s in hover). Loop broken at the mixer input:
L = C G S.  phi'/phi_d = 1/(1+L).  p/delta = G s CM (Pinv + e^{-tau s} C)/(1+L).
"""
from __future__ import annotations

import re
import warnings

from dataclasses import dataclass

import control
import numpy as np
from scipy.optimize import least_squares

from .plants import DelayedLTI, _check_siso

__all__ = ["CommandModel", "PIDGains", "FrequencyFunction", "EMFDesign", "NegativeDelayWarning", "AXIS_SIGNALS",
           "fit_inverse_plant", "fit_equivalent_delay"]


@dataclass(frozen=True)
class CommandModel:
    """Second-order attitude command: phi_cm/delta = gain w^2/(s^2 + 2 zeta w s + w^2).

    frequency [rad/s], damping [-], gain [rad of roll per unit stick].
    """

    frequency: float = 4.0
    damping: float = 0.7
    gain: float = 0.05

    def __post_init__(self):
        for name in ("frequency", "damping", "gain"):
            v = getattr(self, name)
            if not np.isscalar(v) or isinstance(v, complex) or not np.isfinite(v) or v <= 0:
                raise ValueError(f"CommandModel.{name} must be a finite real number > 0, got {v!r}")

    def tf(self):
        w, z = self.frequency, self.damping
        return control.tf([self.gain * w ** 2], [1, 2 * z * w, w ** 2])


@dataclass(frozen=True)
class PIDGains:
    """Feedback gains: K_phi [stick/rad], K_Iphi [stick/(rad s)], K_p [stick/(rad/s)]."""

    K_phi: float
    K_Iphi: float
    K_p: float

    def __post_init__(self):
        for name in ("K_phi", "K_Iphi", "K_p"):
            v = getattr(self, name)
            if isinstance(v, (complex, np.complexfloating)) or not np.isscalar(v) or not np.isfinite(v):
                raise ValueError(f"PID gain {name} must be a finite real number, got {v!r}")
            object.__setattr__(self, name, float(v))

    def as_array(self):
        return np.array([self.K_phi, self.K_Iphi, self.K_p])


class FrequencyFunction:
    """A named, exact frequency response ``H(s)`` usable by every metric."""

    def __init__(self, fun, name=""):
        self._fun = fun
        self.name = name

    def __call__(self, s):
        return self._fun(np.asarray(s, dtype=complex))

    def response(self, omega):
        return self(1j * np.asarray(omega, dtype=float))


def _as_delayed(sys):
    if isinstance(sys, DelayedLTI):
        return sys
    if isinstance(sys, control.LTI):
        return DelayedLTI(sys, 0.0)
    raise TypeError(f"the plant must be a control LTI or DelayedLTI, got {type(sys).__name__}")


def _eval(sys, s):
    if isinstance(sys, DelayedLTI):
        return sys(s)
    return np.asarray(sys(s), dtype=complex).reshape(np.shape(s))


def fit_inverse_plant(response, fit_range=(1.0, 12.0), order="0/1", n_points=40):
    """Low-order fit of the bare airframe + actuator + sensor, for the inverse plant.

    ``order="0/1"`` fits K/(s + a); ``"1/2"`` fits (b1 s + b0)/(s^2 + a1 s + a0).
    The cost is CIFER-like: magnitude error in dB and 0.01745 x phase error in
    deg squared, on ``n_points`` log-spaced frequencies in ``fit_range``
    [rad/s] (1-12 rad/s in the dissertation).  Returns a :class:`control.TransferFunction`.
    """
    w = np.geomspace(*_checked_fit_range(fit_range, "fit_range"), n_points)
    h = FrequencyFunction(response).response(w) if callable(response) and not hasattr(response, "response") \
        else response.response(w) if hasattr(response, "response") else np.squeeze(control.frequency_response(response, w).complex)

    def model(x):
        s = 1j * w
        if order == "0/1":
            return x[0] / (s + x[1])
        return (x[0] * s + x[1]) / (s ** 2 + x[2] * s + x[3])

    def residual(x):
        hm = model(x)
        dmag = 20 * np.log10(np.abs(hm) / np.abs(h))
        dph = np.degrees(np.angle(hm / h))
        return np.concatenate([dmag, np.sqrt(0.01745) * dph])

    k0 = np.abs(h[0]) * fit_range[0]
    if order == "0/1":
        x0 = [k0, fit_range[0]]
        lb = [-np.inf, 1e-3]
    elif order == "1/2":
        x0 = [k0, k0, 2 * fit_range[0], fit_range[0] ** 2]
        lb = [-np.inf, -np.inf, 1e-3, 1e-6]
    else:
        raise ValueError(f"order must be '0/1' or '1/2', got {order!r}")
    sol = least_squares(residual, x0, bounds=(lb, np.inf))
    x = sol.x
    if order == "0/1":
        return control.tf([x[0]], [1, x[1]])
    return control.tf([x[0], x[1]], [1, x[2], x[3]])


def fit_equivalent_delay(response, fit_range=(1.0, 12.0), n_points=40):
    """Unit-gain + pure-delay fit e^{-tau s} of a nearly flat response (1-12 rad/s).

    Least squares on phase: tau = -sum(w phi) / sum(w^2), with phi the unwrapped
    phase [rad].  Returns tau [s].
    """
    w = np.geomspace(*_checked_fit_range(fit_range, "fit_range"), n_points)
    h = response.response(w)
    phase = np.unwrap(np.angle(h))
    # remove any 360-deg offset at the low end before the fit
    phase = phase - 2 * np.pi * np.round(phase[0] / (2 * np.pi))
    tau = float(-np.sum(w * phase) / np.sum(w ** 2))
    if tau < 0:
        # a phase lead over the band: the inverse-plant fit leaves more lag than the
        # response has. Synchronising with a negative delay is not realisable, so the
        # feed-forward uses none; say so rather than clip silently
        warnings.warn(f"equivalent delay fitted as {tau * 1e3:.3g} ms (< 0: the response leads the "
                      f"inverse-plant model over {fit_range[0]:g}-{fit_range[1]:g} rad/s); tau_eq = 0 "
                      "is used", NegativeDelayWarning, stacklevel=2)
        return 0.0
    return tau


class NegativeDelayWarning(UserWarning):
    """The fitted equivalent delay was negative and 0 is used instead."""


def _checked_fit_range(fit_range, name):
    """Validated (low, high) frequency band [rad/s] for a fit on a log grid."""
    try:
        lo, hi = (float(v) for v in fit_range)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be (low, high) in rad/s, got {fit_range!r}") from None
    if not (np.isfinite(lo) and np.isfinite(hi) and 0 < lo < hi):
        raise ValueError(f"{name} must be (low, high) with 0 < low < high rad/s (a log-spaced fit "
                         f"grid cannot include 0), got {fit_range!r}")
    return lo, hi


#: the rate output and stick input a single-axis design closes its loop on
AXIS_SIGNALS = {"roll": ("p", "delta_lat"), "pitch": ("q", "delta_lon"), "yaw": ("r", "delta_ped")}
_UNNAMED = re.compile(r"^[uy]\[\d+\]$")    # python-control's default signal names


def _check_axis(plant, axis):
    """Refuse a plant whose named signals belong to another axis (unnamed ones pass)."""
    output, stick = AXIS_SIGNALS[axis]
    got_out, got_in = plant.system.output_labels[0], plant.system.input_labels[0]
    for what, got, want in (("output", got_out, output), ("input", got_in, stick)):
        if not _UNNAMED.match(got) and got != want:
            raise ValueError(f"the plant {plant.name or ''} is {got_out}/{got_in} but a {axis}-axis design "
                             f"needs {output}/{stick}: its {what} {got!r} belongs to another axis "
                             f"(pass axis= for another axis, or name the plant's signals)")


class EMFDesign:
    """An explicit-model-following single-axis design (roll by default).

    Parameters
    ----------
    plant : DelayedLTI or control LTI
        Bare-airframe rate response of the axis, p/delta_lat for roll (any order; a
        coupling-numerator plant works). Named signals must be the axis's
        (:data:`AXIS_SIGNALS`); python-control's default names ``u[0]``/``y[0]`` pass.
    gains : PIDGains
    command_model : CommandModel
    actuator : control LTI
        delta_mx -> actuator output (unity DC gain).
    sensor_delay : float
        Pure delay of the attitude/rate sensors [s] (exact in frequency domain).
    inverse_plant : control TF, optional
        The fitted low-order model P_hat; fitted with :func:`fit_inverse_plant`
        (0th over 1st, 1-12 rad/s) if not given.
    equivalent_delay : float, optional
        tau_eq [s]; fitted with :func:`fit_equivalent_delay` if not given.
    fit_range : (float, float)
        Band of the inverse-plant and tau_eq fits [rad/s].
    axis : {"roll", "pitch", "yaw"}
        The axis designed: the plant's signal names are checked against it.

    Raises
    ------
    ValueError
        A plant named for another axis, a bad delay, or an invertible inverse plant missing.

    Examples
    --------
    >>> from controllers import EMFDesign, PIDGains, hover_roll_plant
    >>> design = EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.1, 0.05))
    >>> round(design.equivalent_delay, 3) >= 0
    True
    """

    def __init__(self, plant, gains, command_model=CommandModel(), actuator=None, sensor_delay=0.01,
                 inverse_plant=None, equivalent_delay=None, fit_range=(1.0, 12.0), axis="roll"):
        if axis not in AXIS_SIGNALS:
            raise ValueError(f"axis must be one of {sorted(AXIS_SIGNALS)}, got {axis!r}")
        self.axis = axis
        self.plant = _as_delayed(plant)
        _check_axis(self.plant, axis)
        if not isinstance(gains, PIDGains):
            raise TypeError(f"gains must be PIDGains, got {type(gains).__name__}")
        self.gains = gains
        self.command_model = command_model
        self.actuator = actuator if actuator is not None else control.tf([1.0], [1.0])
        if not isinstance(self.actuator, control.LTI):
            raise TypeError(f"actuator must be a control LTI, got {type(self.actuator).__name__}")
        _check_siso(self.actuator, "the actuator")
        if not np.isfinite(sensor_delay) or sensor_delay < 0:
            raise ValueError(f"sensor_delay must be >= 0 s and finite, got {sensor_delay}")
        self._cache = {}
        self.sensor_delay = float(sensor_delay)
        self.fit_range = fit_range
        bare = FrequencyFunction(lambda s: self._g(s) * self._sensor(s), "bare airframe + actuator + sensor")
        self.inverse_plant = inverse_plant if inverse_plant is not None else fit_inverse_plant(bare, fit_range)
        num, den = control.tfdata(self.inverse_plant)
        if np.ravel(num[0][0])[-1] == 0:
            raise ValueError("the inverse-plant model has a zero at the origin: cannot invert")
        if equivalent_delay is None:
            equivalent_delay = fit_equivalent_delay(
                FrequencyFunction(lambda s: bare(s) / _eval(self.inverse_plant, s)), fit_range)
        self.equivalent_delay = float(equivalent_delay)

    # -- building blocks (exact) ---------------------------------------------
    def _g(self, s):
        return self.plant(s) * _eval(self.actuator, s)

    def _sensor(self, s):
        return np.exp(-s * self.sensor_delay)

    def _c(self, s, gains=None):
        k = gains or self.gains
        return k.K_p + k.K_phi / s + k.K_Iphi / s ** 2

    def _cm(self, s):
        return _eval(self.command_model.tf(), s)

    def with_gains(self, gains):
        """Copy with other feedback gains (same inverse plant and tau_eq)."""
        if not isinstance(gains, PIDGains):
            raise TypeError(f"gains must be PIDGains, got {type(gains).__name__}")
        new = object.__new__(EMFDesign)
        new.__dict__.update(self.__dict__)
        new.gains = gains
        # gain-independent poles (command model, feed-forward, sync) live in the shared
        # dict, which the copy holds by reference: a search that scores hundreds of gain
        # sets from one parent design computes them once, not once per gain set
        new._cache = {k: v for k, v in self._cache.items() if k[0] == "fixed"}
        new._shared = self._shared_cache()
        return new

    def _shared_cache(self):
        """Gain-independent results shared by every :meth:`with_gains` copy (created on first use)."""
        return self.__dict__.setdefault("_shared", {})

    def with_plant(self, plant):
        """Copy evaluated on another bare airframe, keeping gains, inverse plant and
        tau_eq (the dissertation's case B: a design applied to a different aircraft)."""
        new = object.__new__(EMFDesign)
        new.__dict__.update(self.__dict__)
        new.plant = _as_delayed(plant)
        _check_axis(new.plant, self.axis)
        new._cache = {k: v for k, v in self._cache.items() if k[0] == "fixed"}
        return new

    # -- exact frequency responses --------------------------------------------
    def broken_loop(self):
        """delta_fb / delta_mx (sign so that L, not -L), loop broken at the mixer input."""
        return FrequencyFunction(lambda s: self._c(s) * self._g(s) * self._sensor(s), "broken loop")

    def disturbance_response(self):
        """phi'/phi_d = 1/(1+L): output-attitude disturbance rejection."""
        L = self.broken_loop()
        return FrequencyFunction(lambda s: 1.0 / (1.0 + L(s)), "phi'/phi_d")

    def _pilot_to_mixer(self, s):
        pinv = 1.0 / _eval(self.inverse_plant, s)
        return s * self._cm(s) * (pinv + np.exp(-s * self.equivalent_delay) * self._c(s))

    def roll_rate_response(self):
        """p / delta_lat_s (closed loop)."""
        L = self.broken_loop()
        return FrequencyFunction(lambda s: self._g(s) * self._pilot_to_mixer(s) / (1 + L(s)), "p/delta")

    def attitude_response(self):
        """phi / delta_lat_s (closed loop)."""
        p = self.roll_rate_response()
        return FrequencyFunction(lambda s: p(s) / s, "phi/delta")

    def mixer_response_pilot(self):
        """delta_mx / delta_lat_s: actuator activity for pilot input."""
        L = self.broken_loop()
        return FrequencyFunction(lambda s: self._pilot_to_mixer(s) / (1 + L(s)), "delta_mx/delta")

    def mixer_response_disturbance(self):
        """delta_mx / phi_d: actuator activity for an attitude disturbance."""
        L = self.broken_loop()
        return FrequencyFunction(lambda s: -self._c(s) * s * self._sensor(s) / (1 + L(s)), "delta_mx/phi_d")

    def commanded_attitude(self):
        """phi_cm delayed by tau_eq / delta: what perfect model following would give."""
        return FrequencyFunction(lambda s: self._cm(s) * np.exp(-s * self.equivalent_delay), "phi_cm/delta")

    # -- state space ------------------------------------------------------------
    def closed_loop(self, pade_order=3):
        """Closed loop as a named :class:`control.StateSpace` built with ``interconnect``.

        Inputs ``delta_lat_s`` (pilot) and ``phi_d`` (attitude disturbance at the
        measured output; its rate part enters p through s/(s/1000 + 1));
        outputs ``p, phi, phi_meas, delta_mx, delta_fb, phi_cm``.
        """
        def pade(tau):
            if tau <= 0:
                return control.tf([1.0], [1.0])
            return control.tf(*control.pade(tau, pade_order))

        k = self.gains
        cm = self.command_model.tf()
        s = control.tf("s")
        blocks = [
            control.ss(control.tf(np.array(cm.num[0][0]), cm.den[0][0]), inputs="delta_lat_s",
                       outputs="phi_cm", name="command"),
            control.ss(control.minreal(s * cm / self.inverse_plant, verbose=False), inputs="delta_lat_s",
                       outputs="delta_ff", name="feedforward"),
            control.ss(pade(self.equivalent_delay), inputs="phi_cm", outputs="phi_cm_d", name="sync"),
            control.ss(control.minreal(s * cm, verbose=False) * pade(self.equivalent_delay),
                       inputs="delta_lat_s", outputs="p_cm_d", name="sync_rate"),
            control.ss([[0.0]], [[1.0, -1.0]], [[k.K_Iphi]], [[k.K_phi, -k.K_phi]],
                       inputs=["phi_cm_d", "phi_m"], outputs="delta_fb_att", name="pi_attitude"),
            control.ss([], [], [], [[k.K_p, -k.K_p]], inputs=["p_cm_d", "p_m"], outputs="delta_fb_rate",
                       name="p_rate"),
            control.summing_junction(inputs=["delta_fb_att", "delta_fb_rate"], output="delta_fb", name="fb_sum"),
            control.summing_junction(inputs=["delta_ff", "delta_fb"], output="delta_mx", name="mixer"),
            control.ss(self.actuator, inputs="delta_mx", outputs="delta_act", name="actuator"),
            control.ss(self.plant.to_statespace(pade_order), inputs="delta_act", outputs="p", name="plant"),
            control.ss([[0.0]], [[1.0]], [[1.0]], [[0.0]], inputs="p", outputs="phi", name="kinematics"),
            control.ss(pade(self.sensor_delay), inputs="p", outputs="p_s", name="rate_sensor"),
            control.ss(pade(self.sensor_delay), inputs="phi", outputs="phi_s", name="attitude_sensor"),
            control.ss(control.tf([1.0, 0.0], [0.001, 1.0]), inputs="phi_d", outputs="p_d", name="dist_rate"),
            control.summing_junction(inputs=["phi_s", "phi_d"], output="phi_m", name="phi_meas_sum"),
            control.summing_junction(inputs=["p_s", "p_d"], output="p_m", name="p_meas_sum"),
        ]
        return control.interconnect(blocks, inplist=["delta_lat_s", "phi_d"],
                                    outlist=["p", "phi", "phi_m", "delta_mx", "delta_fb", "phi_cm"],
                                    inputs=["delta_lat_s", "phi_d"],
                                    outputs=["p", "phi", "phi_meas", "delta_mx", "delta_fb", "phi_cm"],
                                    name="EMF closed loop")

    def broken_loop_statespace(self, pade_order=3):
        """L = C G S as a StateSpace (Padé delays), for python-control's margins."""
        k = self.gains
        # K_Iphi = 0: no integrator state (it would be an unobservable pole at 0)
        c = (control.tf([k.K_p, k.K_phi, k.K_Iphi], [1.0, 0.0, 0.0]) if k.K_Iphi != 0
             else control.tf([k.K_p, k.K_phi], [1.0, 0.0]))
        sensor = (control.tf(*control.pade(self.sensor_delay, pade_order)) if self.sensor_delay > 0
                  else control.tf([1.0], [1.0]))
        return control.series(self.plant.to_statespace(pade_order), control.ss(self.actuator),
                              control.ss(sensor), control.ss(c))

    def _fixed_poles(self, pade_order):
        """Poles of the gain-independent blocks of :meth:`closed_loop` [rad/s].

        Command model, feed-forward s CM / P_hat, synchronisation delays, the
        second sensor Padé (the interconnect senses p and phi through one Padé
        each; the loop sees one of them) and the disturbance rate filter.
        """
        key = ("fixed", pade_order)
        shared = self._shared_cache()
        if key in shared and key not in self._cache:
            self._cache[key] = shared[key]
        if key not in self._cache:
            def pade(tau):
                return control.tf(*control.pade(tau, pade_order)) if tau > 0 else control.tf([1.0], [1.0])
            s = control.tf("s")
            cm = self.command_model.tf()
            blocks = [cm, control.minreal(s * cm / self.inverse_plant, verbose=False), pade(self.equivalent_delay),
                      control.minreal(s * cm, verbose=False) * pade(self.equivalent_delay),
                      pade(self.sensor_delay), control.tf([1.0, 0.0], [0.001, 1.0])]
            self._cache[key] = np.concatenate([np.linalg.eigvals(control.ss(b).A) if control.ss(b).nstates
                                               else np.zeros(0, complex) for b in blocks])
            shared[key] = self._cache[key]
        return self._cache[key]

    def closed_loop_poles(self, pade_order=3, cancel_radius=0.02, match_tol=0.25):
        """Poles of :meth:`closed_loop` [rad/s], less those the kinematics cancel.

        Computed as the eigenvalues of the feedback loop ``feedback(L, 1)``
        (:meth:`broken_loop_statespace`) together with the gain-independent
        poles of the command model, feed-forward and synchronisation blocks:
        the same spectrum as the full ``interconnect`` model (tested), at a
        fraction of the cost.

        The interconnect integrates p to get phi. A hovering airframe's p/delta
        has zeros at (or, after numerical linearisation, within ~1e-3 rad/s of)
        the origin -- lateral stick gives an attitude change, not a steady rate --
        and the integrator cancels them: the closed loop then has modes sitting on
        those zeros that no input excites and no output sees, which floating
        point may place at +1e-3. Such a mode is dropped when it lies within
        ``cancel_radius`` [rad/s] of the origin (time constant > 50 s, far below
        any handling-qualities band) *and* within ``match_tol`` (relative, or
        1e-4 rad/s absolute) of a zero of the plant; every other pole, however
        slow, is kept. A full eigen-decomposition is used rather than a
        tolerance-based minimal realisation, which is ill-conditioned for the
        30-50 state loops of the identified-inflow aircraft (it can turn a
        +0.003 1/s cancelled mode into a spurious +1.8 1/s pole).
        """
        key = ("poles", pade_order, cancel_radius, match_tol)
        if key in self._cache:
            return self._cache[key]
        loop = control.feedback(self.broken_loop_statespace(pade_order), 1)
        poles = np.concatenate([np.linalg.eigvals(loop.A), self._fixed_poles(pade_order)])
        zkey = ("fixed", "plant zeros", pade_order)
        shared = self._shared_cache()
        if zkey not in self._cache and zkey in shared and shared[zkey][0] is self.plant:
            self._cache[zkey] = shared[zkey]
        if zkey not in self._cache or self._cache[zkey][0] is not self.plant:
            self._cache[zkey] = shared[zkey] = (self.plant, self.plant.to_statespace(pade_order).zeros())
        plant_zeros = self._cache[zkey][1]
        slow_zeros = plant_zeros[np.abs(plant_zeros) < 2 * cancel_radius]
        keep = np.ones(poles.size, bool)
        used = np.zeros(slow_zeros.size, bool)
        for i in np.argsort(np.abs(poles)):
            if abs(poles[i]) >= cancel_radius or not slow_zeros.size:
                continue
            gap = np.abs(slow_zeros - poles[i]) - np.maximum(match_tol * np.abs(slow_zeros), 1e-4)
            gap[used] = np.inf
            j = int(np.argmin(gap))
            if gap[j] <= 0:
                keep[i], used[j] = False, True
        self._cache[key] = poles[keep]
        return self._cache[key]

    def stick_impulse(self, duration=6.0, dt=0.01, width=0.25, amplitude=1.0):
        """Response to a lateral-stick pulse: TimeResponseData with named signals."""
        t = np.arange(0, duration + dt / 2, dt)
        u = np.zeros((2, t.size))
        u[0, t < width] = amplitude
        return control.forced_response(self.closed_loop(), t, u)

    def step_disturbance(self, duration=6.0, dt=0.01, amplitude=np.radians(1.0)):
        """Response to a step attitude disturbance phi_d."""
        t = np.arange(0, duration + dt / 2, dt)
        u = np.zeros((2, t.size))
        u[1] = amplitude
        return control.forced_response(self.closed_loop(), t, u)
