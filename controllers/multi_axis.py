"""Explicit model following on several axes of one MIMO aircraft at once.

One EMF loop per axis (dissertation Fig. 7.12, :class:`~controllers.emf.EMFDesign`)
is closed on the *full* linear aircraft, cross-couplings included::

    pilot stick_a ─► command model_a ─► feed-forward s CM_a / P_hat_a ──────┐
                                   └─► e^{-tau_eq s} ─► PID_a ─► delta_fb_a ─┤
          sensor_a ◄── (att_a, rate_a) ◄── MIMO plant ◄── actuator_a ◄── delta_mx_a
                          ▲  every other axis's loop acts on the same plant  │

Axes (:data:`AXIS_CHANNELS`): roll (phi, p via delta_lat) and pitch (theta, q via
delta_lon) are attitude command / attitude hold, as in the dissertation's roll
design. Yaw (psi, r via delta_ped) and heave (height, vertical rate via
delta_col) are *rate* command with heading / height hold: in hover the pilot
turns and climbs at a commanded rate for as long as the control is held (ADS-33E-PRF
rate response types for heading and the first-order height-rate response
of §3.3.9), so an attitude command would make little sense there; the command
model is then ``rate_cm/delta = K/(T s + 1)`` (:class:`RateCommandModel`) and
the hold loops act on its integral. The pitch axis is signed nose-down
positive (forward stick, positive delta_lon, pitches the nose down) and heave
up positive (``hdot = -w``, exact to first order about a hover trim with zero
attitude; the linear aircraft has no height state, so height is the integral of
``-w``). Signs make every on-axis plant positive, as the DMO's non-negative gains need.

Exact frequency responses (pure delays as e^{-jw tau}) come from the plant's
(A, B, C, D) at every frequency; state space (Padé delays) is assembled with
:func:`control.interconnect` from named blocks. Notation at a frequency:
``L`` is the n x n loop matrix at the mixer inputs (``L[i, j]``: delta_mx_j to
-delta_fb_i); the loop of axis i broken at its actuator with every other loop
closed is ``L_i = L_ii - L_io (I + L_oo)^{-1} L_oi``.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import control
import numpy as np

from .emf import CommandModel, FrequencyFunction, PIDGains, _eval
from .multi_axis_view import AxisView

__all__ = ["AxisChannel", "AXIS_CHANNELS", "RateCommandModel", "AxisLoop", "MultiAxisEMF", "SignalNameError"]


class SignalNameError(ValueError):
    """A plant lacks (or misnames) a signal an axis loop needs; the message names it."""


@dataclass(frozen=True)
class AxisChannel:
    """The signals of one axis loop.

    Attributes
    ----------
    axis : str
        ``"roll"``, ``"pitch"``, ``"yaw"`` or ``"heave"``.
    stick : str
        Plant input the loop drives (pilot control name).
    rate : str
        Plant output fed back as the rate [rad/s or m/s].
    attitude : str or None
        Plant output fed back as the attitude [rad]; None: the integral of the
        signed rate (heave: height [m], the aircraft has no height state).
    sign : float
        +1 or -1: the loop's variables are ``sign * output`` (pitch nose-down,
        heave up positive).
    response_type : str
        ``"attitude"`` (attitude command) or ``"rate"`` (rate command, attitude hold).
    """

    axis: str
    stick: str
    rate: str
    attitude: str | None
    sign: float = 1.0
    response_type: str = "attitude"

    @property
    def rate_name(self):
        """Name of the signed rate signal (``"-q"`` for pitch)."""
        return self.rate if self.sign > 0 else f"-{self.rate}"


#: the four hover axes of the coaxial (names of :func:`aircraft.helicopter.linearize`)
AXIS_CHANNELS = {
    "roll": AxisChannel("roll", "delta_lat", "p", "phi", 1.0, "attitude"),
    "pitch": AxisChannel("pitch", "delta_lon", "q", "theta", -1.0, "attitude"),
    "yaw": AxisChannel("yaw", "delta_ped", "r", "psi", 1.0, "rate"),
    "heave": AxisChannel("heave", "delta_col", "w", None, -1.0, "rate"),
}


@dataclass(frozen=True)
class RateCommandModel:
    """First-order rate command ``rate_cm/delta = gain/(T s + 1)``.

    :meth:`tf` returns the commanded *attitude* (heading, height), the integral
    ``gain/(s (T s + 1))``, the quantity an EMF command model provides.

    Parameters
    ----------
    time_constant : float
        T [s].
    gain : float
        Steady rate per unit stick [rad/s or m/s per stick unit].

    Examples
    --------
    >>> RateCommandModel(0.5, 0.3).tf().den[0][0].tolist()
    [0.5, 1.0, 0.0]
    """

    time_constant: float = 0.5
    gain: float = 0.3

    def __post_init__(self):
        for name in ("time_constant", "gain"):
            v = getattr(self, name)
            if not np.isscalar(v) or isinstance(v, complex) or not np.isfinite(v) or v <= 0:
                raise ValueError(f"RateCommandModel.{name} must be a finite real number > 0, got {v!r}")

    def tf(self):
        return control.tf([self.gain], [self.time_constant, 1.0, 0.0])


def _default_command(channel):
    if channel.response_type == "rate":
        # yaw: 0.5 s heading-rate lag; heave: 2 s height-rate lag (ADS-33E-PRF Level 1 T <= 5 s)
        return RateCommandModel(0.5, 0.3) if channel.axis == "yaw" else RateCommandModel(2.0, 3.0)
    return CommandModel()


@dataclass
class AxisLoop:
    """One axis's EMF loop: gains, command model, feed-forward and hardware.

    Attributes
    ----------
    gains : PIDGains
        K_phi [stick/rad] on the attitude error, K_Iphi [stick/(rad s)] on its
        integral, K_p [stick/(rad/s)] on the rate error (heave: per m, m s, m/s).
    command_model : CommandModel or RateCommandModel
    inverse_plant : control TF
        Low-order fit P_hat of the on-axis response (actuator, plant, sensor).
    equivalent_delay : float
        tau_eq [s] synchronising the feedback command with the response.
    actuator : control LTI
        delta_mx -> stick (unity DC gain).
    sensor_delay : float
        Pure delay of the attitude and rate sensors [s].
    """

    gains: PIDGains
    command_model: object = None
    inverse_plant: object = None
    equivalent_delay: float = 0.0
    actuator: object = None
    sensor_delay: float = 0.01

    def __post_init__(self):
        if not isinstance(self.gains, PIDGains):
            raise TypeError(f"gains must be PIDGains, got {type(self.gains).__name__}")
        self.actuator = control.tf([1.0], [1.0]) if self.actuator is None else self.actuator
        if not np.isfinite(self.sensor_delay) or self.sensor_delay < 0:
            raise ValueError(f"sensor_delay must be >= 0 s and finite, got {self.sensor_delay}")
        if not np.isfinite(self.equivalent_delay) or self.equivalent_delay < 0:
            raise ValueError(f"equivalent_delay must be >= 0 s and finite, got {self.equivalent_delay}")

    @classmethod
    def from_design(cls, design):
        """The loop of a single-axis :class:`~controllers.emf.EMFDesign` (same gains, fits, hardware)."""
        return cls(design.gains, design.command_model, design.inverse_plant, design.equivalent_delay,
                   design.actuator, design.sensor_delay)


def _structural_part(A, B, C, D):
    """States reachable from B and seen by C through the nonzeros of A (an exact reduction)."""
    n = A.shape[0]
    nz = A != 0

    def closure(start, step):
        seen = set(np.flatnonzero(start))
        todo = list(seen)
        while todo:
            k = todo.pop()
            for j in np.flatnonzero(step(k)):
                if j not in seen:
                    seen.add(j)
                    todo.append(j)
        return seen
    reach = closure(np.any(B != 0, axis=1), lambda k: nz[:, k])    # x_k drives x_j where A[j, k] != 0
    seen = closure(np.any(C != 0, axis=0), lambda k: nz[k, :])     # x_j drives x_k where A[k, j] != 0
    keep = sorted(reach & seen) if n else []
    return A[np.ix_(keep, keep)], B[keep], C[:, keep], D


#: inputs of every loop when its pilot path is left out (references, disturbance, stick)
_LOOP_INPUTS = ("att_ref", "rate_ref", "att_d", "stick_s")


def _pade(tau, order):
    return control.tf(*control.pade(tau, order)) if tau > 0 else control.tf([1.0], [1.0])


class MultiAxisEMF:
    """EMF loops on several axes of one MIMO linear aircraft, closed simultaneously.

    Parameters
    ----------
    plant : control.StateSpace
        Full linear aircraft with named inputs (the channels' sticks) and outputs
        (their rates and attitudes), e.g. ``linearize(trim(heli))`` or with the
        translational drift held (``aircraft.helicopter.hold.hold_states``).
    loops : dict
        Axis name (key of :data:`AXIS_CHANNELS`) -> :class:`AxisLoop`; the
        order is kept in every matrix and table. Each loop's inverse plant is a
        low-order fit of its on-axis response (:func:`~controllers.multi_axis_design.design_multi_axis`
        fits it on the axis's effective plant, the other loops closed).
    channels : dict, optional
        Axis name -> :class:`AxisChannel` (default :data:`AXIS_CHANNELS`).

    Raises
    ------
    SignalNameError
        The plant lacks a stick or an output a loop needs (the names are listed).

    Examples
    --------
    >>> import control
    >>> plant = control.ss([[-1.0, 0], [1.0, 0]], [[2.0], [0]], [[1.0, 0], [0, 1.0]], 0,
    ...                    inputs=["delta_lat"], outputs=["p", "phi"])
    >>> loop = AxisLoop(PIDGains(1.0, 0.2, 0.3), inverse_plant=control.tf([2.0], [1.0, 1.0]))
    >>> emf = MultiAxisEMF(plant, {"roll": loop})
    >>> round(float(abs(emf.broken_loop("roll").response([2.0])[0])), 3) > 0
    True
    """

    def __init__(self, plant, loops, channels=None):
        if not isinstance(plant, control.StateSpace):
            raise TypeError(f"plant must be a control.StateSpace, got {type(plant).__name__}")
        channels = dict(AXIS_CHANNELS if channels is None else channels)
        if not loops:
            raise ValueError("at least one axis loop is needed")
        self.axes = list(loops)
        for a in self.axes:
            if a not in channels:
                raise ValueError(f"unknown axis {a!r}; known: {list(channels)}")
            if not isinstance(loops[a], AxisLoop):
                raise TypeError(f"loops[{a!r}] must be an AxisLoop, got {type(loops[a]).__name__}")
        self.channels = {a: channels[a] for a in self.axes}
        self.loops = dict(loops)
        ins, outs = list(plant.input_labels), list(plant.output_labels)
        sticks = [self.channels[a].stick for a in self.axes]
        if len(set(sticks)) != len(sticks):
            raise SignalNameError(f"two axes drive the same stick: {sticks}")
        need_out = [n for a in self.axes for n in (self.channels[a].rate, self.channels[a].attitude) if n]
        for kind, names, pool in (("input", sticks, ins), ("output", need_out, outs)):
            missing = [n for n in names if n not in pool]
            if missing:
                raise SignalNameError(f"the plant has no {kind}(s) {missing} (needed by the "
                                      f"{', '.join(self.axes)} loops); its {kind}s: {pool}")
        for a in self.axes:
            if self.loops[a].command_model is None:   # a copy: the caller's loop is left as given
                self.loops[a] = replace(self.loops[a], command_model=_default_command(self.channels[a]))
            if self.loops[a].inverse_plant is None:
                raise ValueError(f"the {a} loop needs an inverse plant (fit it on the on-axis response, "
                                 "e.g. with design_multi_axis or AxisEMFDesign)")
        self.plant = plant
        self._cols = [ins.index(s) for s in sticks]
        self._cache = {}

    def with_gains(self, gains):
        """Copy with new gains for some axes (dict axis -> PIDGains); fits and hardware kept."""
        loops = {a: (AxisLoop(gains[a], l.command_model, l.inverse_plant, l.equivalent_delay, l.actuator,
                              l.sensor_delay) if a in gains else l) for a, l in self.loops.items()}
        new = MultiAxisEMF(self.plant, loops, self.channels)
        # the pilot-path blocks hold no gain: their poles carry over
        new._cache.update({k: v for k, v in self._cache.items() if k[0] == "pilot poles"})
        return new

    def with_interconnections(self, feedback_poles=None, closed_loop=None, pade_order=3):
        """Copy that uses the given feedback poles and closed loop instead of building them.

        For a caller that forms them faster for these gains than
        :func:`control.interconnect` does (e.g. the joint check's state matrices,
        affine in the gains). What is given is used as is by :meth:`feedback_poles`,
        :meth:`closed_loop_poles`, :meth:`closed_loop` and every spec that reads
        them; what is not given is built on demand as usual.

        Parameters
        ----------
        feedback_poles : array_like, optional
            What :meth:`feedback_poles` returns at ``pade_order`` [rad/s].
        closed_loop : control.StateSpace, optional
            What :meth:`closed_loop` returns at ``pade_order``: its signal names must be
            the same.
        pade_order : int, optional
            Padé order they were formed with (default 3).

        Returns
        -------
        MultiAxisEMF

        Raises
        ------
        ValueError
            Poles not finite, or a closed loop whose inputs or outputs differ from
            :meth:`closed_loop`'s.

        Examples
        --------
        >>> import control
        >>> plant = control.ss([[-1.0, 0], [1.0, 0]], [[2.0], [0]], [[1.0, 0], [0, 1.0]], 0,
        ...                    inputs=["delta_lat"], outputs=["p", "phi"])
        >>> loop = AxisLoop(PIDGains(1.0, 0.2, 0.3), inverse_plant=control.tf([2.0], [1.0, 1.0]))
        >>> emf = MultiAxisEMF(plant, {"roll": loop})
        >>> same = emf.with_interconnections(feedback_poles=emf.feedback_poles(), closed_loop=emf.closed_loop())
        >>> bool(np.all(same.closed_loop_poles() == emf.closed_loop_poles()))
        True
        """
        new = self.with_gains({})
        if feedback_poles is not None:
            poles = np.asarray(feedback_poles, dtype=complex).ravel()
            if not np.all(np.isfinite(poles)):
                raise ValueError("with_interconnections: feedback_poles must be finite")
            new._cache[("feedback poles", pade_order)] = poles
        if closed_loop is not None:
            inp, out = self._closed_loop_names()
            if (not isinstance(closed_loop, control.StateSpace) or list(closed_loop.input_labels) != inp
                    or list(closed_loop.output_labels) != out):
                raise ValueError(f"with_interconnections: closed_loop must be a StateSpace with inputs {inp} "
                                 f"and outputs {out}")
            new._cache[("cl", pade_order)] = closed_loop
        return new

    def has_closed_loop(self, pade_order=3):
        """Whether :meth:`closed_loop` has been built (or given) at ``pade_order``."""
        return ("cl", pade_order) in self._cache

    # -- exact frequency responses --------------------------------------------
    def _rows(self):
        """Output-row combinations: (n_axes x 2) signed attitude/rate rows; None = integral of rate."""
        outs = list(self.plant.output_labels)
        rows = []
        for a in self.axes:
            ch = self.channels[a]
            rows.append((None if ch.attitude is None else outs.index(ch.attitude), outs.index(ch.rate), ch.sign))
        return rows

    def _plant_response(self, s):
        """(N, 2n, n) signed [att_a; rate_a] per stick at complex frequencies s (exact)."""
        key = ("Y", s.shape, s.tobytes())
        if key in self._cache:
            return self._cache[key]
        A, B = np.asarray(self.plant.A), np.asarray(self.plant.B)[:, self._cols]
        C, D = np.asarray(self.plant.C), np.asarray(self.plant.D)[:, self._cols]
        n = A.shape[0]
        X = np.linalg.solve(s[:, None, None] * np.eye(n) - A, np.broadcast_to(B, (s.size,) + B.shape))
        H = np.einsum("ij,kjl->kil", C, X) + D
        Y = np.empty((s.size, 2 * len(self.axes), len(self.axes)), complex)
        for k, (att, rate, sign) in enumerate(self._rows()):
            Y[:, 2 * k + 1] = sign * H[:, rate]
            Y[:, 2 * k] = sign * (H[:, rate] / s[:, None] if att is None else H[:, att])
        return self._remember_response(key, Y)

    def _parts(self, s):
        s = np.atleast_1d(np.asarray(s, dtype=complex))
        key = ("parts", s.shape, s.tobytes())
        if key in self._cache:
            return self._cache[key]
        Y = self._plant_response(s)
        n = len(self.axes)
        act = np.stack([_eval(self.loops[a].actuator, s) for a in self.axes], axis=1)          # (N, n)
        sens = np.stack([np.exp(-s * self.loops[a].sensor_delay) for a in self.axes], axis=1)
        katt = np.stack([self.loops[a].gains.K_phi + self.loops[a].gains.K_Iphi / s for a in self.axes], 1)
        krate = np.stack([np.full(s.shape, self.loops[a].gains.K_p, complex) for a in self.axes], 1)
        # L[i, j]: delta_mx_j -> actuator_j -> plant -> axis i's sensors and PID -> -delta_fb_i
        L = (sens * katt)[:, :, None] * Y[:, 0::2] + (sens * krate)[:, :, None] * Y[:, 1::2]
        L = L * act[:, None, :]
        M = np.linalg.inv(np.eye(n) + L)                                                         # (I + L)^-1
        c = katt / s[:, None] + krate                                         # C(s) = K_p + K_phi/s + K_I/s^2
        cm = np.stack([_eval(self.loops[a].command_model.tf(), s) for a in self.axes], 1)
        pinv = np.stack([1.0 / _eval(self.loops[a].inverse_plant, s) for a in self.axes], 1)
        tau = np.array([self.loops[a].equivalent_delay for a in self.axes])
        pilot = s[:, None] * cm * (pinv + np.exp(-s[:, None] * tau) * c)     # pilot_j -> mixer_j (open loop)
        out = {"s": s, "Y": Y, "act": act, "sens": sens, "c": c, "L": L, "M": M, "pilot": pilot, "cm": cm}
        return self._remember_response(key, out)

    def _remember_response(self, key, value):
        # frequency grids come and go; the gain-specific interconnections stay
        grids = [k for k in self._cache if k[0] in ("Y", "parts")]
        if len(grids) > 8:
            for k in grids:
                del self._cache[k]
        self._cache[key] = value
        return value

    def _index(self, axis):
        if axis not in self.axes:
            raise ValueError(f"unknown axis {axis!r}; this design has {self.axes}")
        return self.axes.index(axis)

    def broken_loop(self, axis):
        """L_i: loop broken at ``axis``'s actuator input with every other loop closed (exact)."""
        i = self._index(axis)

        def fun(s):
            p = self._parts(s)
            L = p["L"]
            o = [k for k in range(len(self.axes)) if k != i]
            li = L[:, i, i]
            if o:
                inner = np.linalg.solve(np.eye(len(o)) + L[:, o][:, :, o], L[:, o][:, :, [i]])
                li = li - np.einsum("kj,kj->k", L[:, i, o], inner[:, :, 0])
            return li.reshape(np.shape(s))
        return FrequencyFunction(fun, f"{axis} broken loop (other loops closed)")

    def mixer_response(self, axis, pilot_axis):
        """delta_mx of ``axis`` per pilot stick of ``pilot_axis`` (all loops closed)."""
        i, j = self._index(axis), self._index(pilot_axis)
        return FrequencyFunction(lambda s: (self._parts(s)["M"][:, i, j] * self._parts(s)["pilot"][:, j])
                                 .reshape(np.shape(s)), f"delta_mx_{axis}/{pilot_axis} stick")

    def command_response(self, output_axis, pilot_axis, kind="attitude"):
        """Signed attitude (or rate) of ``output_axis`` per pilot stick of ``pilot_axis``, all loops closed.

        ``output_axis == pilot_axis``: the on-axis command response; otherwise the
        inter-axis coupling. Units: rad (m for heave) per stick unit; rates per s.
        """
        i, j = self._index(output_axis), self._index(pilot_axis)
        row = 2 * i + (1 if kind == "rate" else 0)
        if kind not in ("attitude", "rate"):
            raise ValueError(f"kind must be 'attitude' or 'rate', got {kind!r}")

        def fun(s):
            p = self._parts(s)
            u = p["M"][:, :, j] * p["pilot"][:, j][:, None]              # mixer inputs (N, n)
            return np.einsum("kl,kl->k", p["Y"][:, row], p["act"] * u).reshape(np.shape(s))
        return FrequencyFunction(fun, f"{kind} {output_axis}/{pilot_axis} stick")

    def _disturbance(self, axis, what):
        i = self._index(axis)

        def fun(s):
            p = self._parts(s)
            # attitude disturbance d_i at axis i's sensors (its rate s d_i at the rate sensor)
            inject = -p["sens"][:, i] * p["s"] * p["c"][:, i]
            u = p["M"][:, :, i] * inject[:, None]
            if what == "mixer":
                return u[:, i].reshape(np.shape(s))
            att = np.einsum("kl,kl->k", p["Y"][:, 2 * i], p["act"] * u)
            return (1.0 + att).reshape(np.shape(s))
        return fun

    def disturbance_response(self, axis):
        """att'/att_d of ``axis``: an attitude disturbance at its output, all loops closed (exact)."""
        return FrequencyFunction(self._disturbance(axis, "output"), f"{axis} att'/att_d")

    def axis_view(self, axis):
        """``axis`` seen as a single-axis design (every loop closed): grade it with ``evaluate_specs``."""
        return AxisView(self, axis)

    # -- state space ------------------------------------------------------------
    def _blocks(self, mode="closed", axis=None, pade_order=3):
        """Named blocks. mode: "closed"; "broken" (at ``axis``'s mixer); "plant" (axis loop absent);
        "feedback" (no pilot path: references are inputs)."""
        sticks = [self.channels[a].stick for a in self.axes]
        outs = sorted({n for a in self.axes for n in (self.channels[a].rate, self.channels[a].attitude) if n},
                      key=list(self.plant.output_labels).index)
        oi = [list(self.plant.output_labels).index(n) for n in outs]
        P = self.plant
        blocks = [control.ss(P.A, np.asarray(P.B)[:, self._cols], np.asarray(P.C)[oi],
                             np.asarray(P.D)[np.ix_(oi, self._cols)], inputs=sticks, outputs=outs, name="plant")]
        for a in self.axes:
            ch, lp, k = self.channels[a], self.loops[a], self.loops[a].gains
            blocks.append(control.ss([], [], [], [[ch.sign]], inputs=ch.rate, outputs=f"rate_{a}", name=f"sign_{a}"))
            if mode == "plant" and a == axis:
                continue
            if ch.attitude is None:   # kinematic: height = integral of the vertical rate
                blocks.append(control.ss([[0.0]], [[1.0]], [[1.0]], [[0.0]], inputs=f"rate_{a}",
                                         outputs=f"att_{a}", name=f"kinematics_{a}"))
            else:
                blocks.append(control.ss([], [], [], [[ch.sign]], inputs=ch.attitude, outputs=f"att_{a}",
                                         name=f"sign_att_{a}"))
            blocks += [
                control.ss(_pade(lp.sensor_delay, pade_order), inputs=f"att_{a}", outputs=f"att_s_{a}",
                           name=f"att_sensor_{a}"),
                control.ss(_pade(lp.sensor_delay, pade_order), inputs=f"rate_{a}", outputs=f"rate_s_{a}",
                           name=f"rate_sensor_{a}"),
                control.ss(control.tf([1.0, 0.0], [0.001, 1.0]), inputs=f"att_d_{a}", outputs=f"rate_d_{a}",
                           name=f"dist_rate_{a}"),
                control.summing_junction(inputs=[f"att_s_{a}", f"att_d_{a}"], output=f"att_m_{a}",
                                         name=f"att_meas_{a}"),
                control.summing_junction(inputs=[f"rate_s_{a}", f"rate_d_{a}"], output=f"rate_m_{a}",
                                         name=f"rate_meas_{a}"),
                # K_Iphi = 0: no integrator state (it would be an unobservable pole at the origin)
                control.ss(*(([[0.0]], [[1.0, -1.0]], [[k.K_Iphi]]) if k.K_Iphi != 0 else ([], [], [])),
                           [[k.K_phi, -k.K_phi]], inputs=[f"att_ref_{a}", f"att_m_{a}"], outputs=f"fb_att_{a}",
                           name=f"pi_att_{a}"),
                control.ss([], [], [], [[k.K_p, -k.K_p]], inputs=[f"rate_ref_{a}", f"rate_m_{a}"],
                           outputs=f"fb_rate_{a}", name=f"p_rate_{a}"),
                control.summing_junction(inputs=[f"fb_att_{a}", f"fb_rate_{a}"], output=f"delta_fb_{a}",
                                         name=f"fb_sum_{a}"),
                control.ss(lp.actuator, inputs=f"delta_mx_{a}", outputs=ch.stick, name=f"actuator_{a}"),
            ]
            if mode == "closed":
                blocks += self._pilot_blocks(a, pade_order)
            else:   # the pilot path is outside every loop: references are inputs, no feed-forward
                blocks.append(control.ss([], [], [], [[0.0]], inputs=f"stick_s_{a}", outputs=f"delta_ff_{a}",
                                         name=f"no_ff_{a}"))
            if not (mode == "broken" and a == axis):
                blocks.append(control.summing_junction(inputs=[f"delta_ff_{a}", f"delta_fb_{a}"],
                                                       output=f"delta_mx_{a}", name=f"mixer_{a}"))
        return blocks

    def _pilot_blocks(self, a, pade_order):
        lp = self.loops[a]
        s = control.tf("s")
        cm = lp.command_model.tf()
        sync = _pade(lp.equivalent_delay, pade_order)
        return [control.ss(cm, inputs=f"stick_s_{a}", outputs=f"att_cm_{a}", name=f"command_{a}"),
                control.ss(control.minreal(s * cm / lp.inverse_plant, verbose=False), inputs=f"stick_s_{a}",
                           outputs=f"delta_ff_{a}", name=f"feedforward_{a}"),
                control.ss(sync, inputs=f"att_cm_{a}", outputs=f"att_ref_{a}", name=f"sync_{a}"),
                control.ss(control.minreal(s * cm, verbose=False) * sync, inputs=f"stick_s_{a}",
                           outputs=f"rate_ref_{a}", name=f"sync_rate_{a}")]

    def closed_loop(self, pade_order=3):
        """Every loop closed, as a named StateSpace (Padé delays).

        Inputs ``stick_s_<axis>`` (pilot) and ``att_d_<axis>`` (attitude disturbance at
        the sensors); outputs ``rate_<axis>``, ``att_<axis>`` (signed), ``delta_mx_<axis>``,
        ``delta_fb_<axis>``, ``att_cm_<axis>`` for every axis.
        """
        key = ("cl", pade_order)
        if key not in self._cache:
            inp, out = self._closed_loop_names()
            self._cache[key] = control.interconnect(self._blocks("closed", pade_order=pade_order), inplist=inp,
                                                    outlist=out, inputs=inp, outputs=out, check_unused=False,
                                                    name="multi-axis EMF closed loop")
        return self._cache[key]

    def _closed_loop_names(self):
        return ([f"{x}_{a}" for a in self.axes for x in ("stick_s", "att_d")],
                [f"{x}_{a}" for a in self.axes for x in ("rate", "att", "delta_mx", "delta_fb", "att_cm")])

    def effective_plant(self, axis, pade_order=3):
        """Signed rate of ``axis`` per its stick (actuator output) with every other loop closed.

        The single-axis plant the DMO designs ``axis`` on (sequential loop closure):
        a StateSpace named ``<rate_name>``/``<stick>`` (Padé for the other loops' delays).
        States the stick cannot reach or the rate cannot see *structurally* (exact
        zeros in A, B, C: a loop decoupled from this axis) are removed; no
        tolerance decides it, so a coupled aircraft keeps every state and a
        decoupled axis gets exactly its own plant.
        """
        self._index(axis)
        ch = self.channels[axis]
        others = [f"{x}_{a}" for a in self.axes if a != axis for x in _LOOP_INPUTS]
        sys = control.interconnect(self._blocks("plant", axis, pade_order), inplist=[ch.stick] + others,
                                   outlist=[f"rate_{axis}"], check_unused=False)
        A, B, C, D = _structural_part(np.asarray(sys.A), np.asarray(sys.B)[:, :1], np.asarray(sys.C),
                                      np.asarray(sys.D)[:, :1])
        return control.ss(A, B, C, D, inputs=[ch.stick], outputs=[ch.rate_name])

    def broken_loop_statespace(self, axis, pade_order=3):
        """L_i as a StateSpace: -delta_fb per delta_mx of ``axis``, other loops closed (Padé)."""
        self._index(axis)
        inp = [f"delta_mx_{axis}"] + [f"{x}_{a}" for a in self.axes for x in _LOOP_INPUTS]
        sys = control.interconnect(self._blocks("broken", axis, pade_order), inplist=inp,
                                   outlist=[f"delta_fb_{axis}"], check_unused=False)
        return control.ss(sys.A, sys.B[:, :1], -sys.C, -sys.D[:, :1])

    def feedback_poles(self, pade_order=3):
        """Poles of the aircraft with every feedback loop closed [rad/s], the pilot-path blocks left out.

        The modes of the augmented aircraft (plant, actuators, sensors, PID loops):
        the command models, feed-forward and synchronisation blocks are prefilters
        outside the loops, so their poles are not modes of the aircraft (what the
        forward-flight dutch roll and spiral specs grade).
        """
        key = ("feedback poles", pade_order)
        if key not in self._cache:
            inp = [f"{x}_{a}" for a in self.axes for x in _LOOP_INPUTS]
            fb = control.interconnect(self._blocks("feedback", pade_order=pade_order), inplist=inp,
                                      outlist=[f"delta_mx_{a}" for a in self.axes], check_unused=False)
            self._cache[key] = np.linalg.eigvals(fb.A)
        return self._cache[key]

    def closed_loop_poles(self, pade_order=3):
        """Poles of the closed loop [rad/s]: the feedback system's and the pilot-path blocks'.

        The rate commands' integrators (pole at the origin of a
        :class:`RateCommandModel`) are left out: a held control commands a
        steady heading or height rate by definition, not an unstable mode.
        """
        return np.concatenate([self.feedback_poles(pade_order), self._pilot_poles(pade_order)])

    def _pilot_poles(self, pade_order):
        key = ("pilot poles", pade_order)
        if key not in self._cache:
            poles = [np.zeros(0, complex)]
            for a in self.axes:
                for b in self._pilot_blocks(a, pade_order):
                    if b.nstates:
                        p = np.linalg.eigvals(b.A)
                        if b.name == f"command_{a}" and isinstance(self.loops[a].command_model, RateCommandModel):
                            p = np.delete(p, int(np.argmin(np.abs(p))))
                        poles.append(p)
            self._cache[key] = np.concatenate(poles)
        return self._cache[key]

