"""Tune every axis of a :class:`~controllers.multi_axis.MultiAxisEMF` with the single-axis DMO.

:class:`AxisEMFDesign` is the single-axis design of one channel (heave and the
signed pitch axis included) that the DMO tunes; :func:`design_multi_axis` runs the
sweeps and returns a :class:`~controllers.multi_axis_result.MultiAxisResult` (table, couplings, HQ windows).

Sequential loop closure with iteration. In a sweep each axis in turn is
designed by :func:`controllers.dmo` on its *effective* plant: its signed rate
per stick with every other loop closed at its current gains (an axis not yet
designed in the first sweep is left open), the inverse plant and tau_eq
re-fitted to that on-axis response. Sweeps repeat until no gain moves by more
than ``gain_tolerance`` (its share of the controller at crossover), at most ``max_sweeps`` times; the first
sweep runs the DMO's ray-sampling global stage, and every sweep its multistart
stage (seeded starts over the whole gain box and the current gains, polished on
the true specs), so that a later sweep cannot settle on a local optimum that a
continuation from the current gains alone would end on.

Why this and not one NLP over all twelve gains: each axis's specs read its own
loop broken at its actuator with the others closed (CONDUIT's convention), and
the existing DMO already raises one axis's crossover and DRB boundaries to the
design margin with every candidate re-checked by the true specs; at the fixed
point of the sweeps each axis's design plant *is* its loop in the simultaneous
closed loop, so the single-axis margins hold for the MIMO loop. That is then
checked, not assumed: every axis's specs are evaluated on the final
simultaneous closed loop (:meth:`MultiAxisEMF.axis_view`), and the table says
which are met and which limit each axis. Whether the sequential answer is also
the joint one is checked by :func:`controllers.multi_axis_joint.joint_check`: a
global search and a constrained NLP over all twelve gains at once, every axis's
specs its constraints.

Specs per axis come from :func:`controllers.specs_for` (``missing="skip"``: a
boundary not found printed is left out and the table says so); the crossover
(CrsMnG2) and, for roll, the DRB (DrbRoH1) boundaries are the ones the DMO
raises. Specs graded on time histories whose amplitude the linear model does
not fix (achievable yaw rate, yaw due to collective) are not in the DMO's list;
the closed loop's inter-axis couplings are tabulated by :meth:`~controllers.multi_axis_result.MultiAxisResult.coupling`.
"""
from __future__ import annotations

import time
from dataclasses import replace

import control
import numpy as np
import pandas as pd
from tqdm.auto import tqdm

from . import metrics as m
from .actuator_limits import ActuatorLimits, full_stick
from .dmo import dmo
from .dmo_settings import DMOSettings, InfeasibleDesignError
from .emf import EMFDesign, PIDGains, _as_delayed
from .hq.base import SPEEDS
from .hq.selector import specs_for
from .multi_axis import (AXIS_CHANNELS, AxisLoop, MultiAxisEMF, RateCommandModel, SignalNameError,
                         _default_command)
from .multi_axis_guard import axis_guards
from .multi_axis_result import MultiAxisResult
from .plants import second_order_actuator
from .specs import evaluate_specs

__all__ = ["AxisEMFDesign", "axis_specs", "design_multi_axis", "DEFAULT_CROSSOVER_START",
           "DEFAULT_SETTINGS"]

#: first crossover boundary the DMO tries per axis [rad/s] (heave loops cross lower)
DEFAULT_CROSSOVER_START = {"roll": 1.5, "pitch": 1.5, "yaw": 1.0, "heave": 0.5}
#: DMO settings of :func:`design_multi_axis` when none are given: the multistart stage on
#: (64 Sobol starts over every gain's log range, 3 polished), so that each axis's answer is
#: the global one and not the end of one continuation
DEFAULT_SETTINGS = DMOSettings(multistart=64)
#: spec families graded on time histories of a stated control amplitude: not DMO constraints
_TIME_HISTORY_FAMILIES = ("large_amplitude", "coupling")
#: families a multi-axis design cannot grade (no response of theirs is formed): supplying
#: boundaries for one is refused rather than ignored
_UNGRADED_FAMILIES = _TIME_HISTORY_FAMILIES + ("quickness",)
#: the DMO's own design parameters: their boundaries are the crossover/DRB starts
_DESIGN_PARAMETERS = ("CrsMnG2", "DrbRoH1")
#: later sweeps restart the boundary raise at this fraction of the boundary reached
_RESTART = 0.95


class AxisEMFDesign(EMFDesign):
    """A single-axis EMF design on any channel of :data:`AXIS_CHANNELS` (heave and signs included).

    :class:`~controllers.emf.EMFDesign` checks the signal names of the roll,
    pitch and yaw rate plants; this subclass checks them against the channel
    (``"-q"``/``delta_lon`` for the nose-down pitch axis, ``"-w"``/``delta_col``
    for heave), accepts :class:`RateCommandModel`, and leaves the rate command's
    integrator (a pole at the origin of the command model, by definition of a
    rate response type) out of the closed-loop poles. Everything else,
    the DMO included, is the base class's.

    Parameters
    ----------
    plant : DelayedLTI or control LTI
        Signed on-axis rate response (e.g. :meth:`MultiAxisEMF.effective_plant`).
    gains : PIDGains
    axis : str
        Key of :data:`AXIS_CHANNELS`.
    command_model : CommandModel or RateCommandModel, optional
        Default: attitude command for roll and pitch, rate command for yaw and heave.
    **kwargs
        Passed to :class:`~controllers.emf.EMFDesign` (actuator, sensor_delay [s], ...).

    Raises
    ------
    SignalNameError
        The plant's named signals are another channel's.

    Examples
    --------
    >>> import control
    >>> plant = control.ss(control.tf([2.0], [1.0, 1.0]), inputs="delta_col", outputs="-w")
    >>> d = AxisEMFDesign(plant, PIDGains(0.5, 0.1, 1.0), axis="heave")
    >>> d.axis, d.plant.system.output_labels
    ('heave', ['-w'])
    """

    def __init__(self, plant, gains, axis="roll", command_model=None, **kwargs):
        if axis not in AXIS_CHANNELS:
            raise ValueError(f"axis must be one of {list(AXIS_CHANNELS)}, got {axis!r}")
        channel = AXIS_CHANNELS[axis]
        named = _as_delayed(plant)
        _check_channel(named, channel)
        # the base class knows three unsigned axes; the channel's names were checked above
        sys = named.system
        anonymous = control.ss(control.ss(sys).A, control.ss(sys).B, control.ss(sys).C, control.ss(sys).D)
        super().__init__(type(named)(anonymous, named.delay, named.name), gains,
                         command_model or _default_command(channel), axis="roll", **kwargs)
        self.plant = named
        self.axis = axis
        self.channel = channel

    def _retyped(self, new):
        new.__class__ = type(self)
        return new

    def with_gains(self, gains):
        return self._retyped(super().with_gains(gains))

    def with_plant(self, plant):
        named = _as_delayed(plant)
        _check_channel(named, self.channel)
        new = object.__new__(type(self))
        new.__dict__.update(self.__dict__)
        new.plant = named
        new._cache = {k: v for k, v in self._cache.items() if k[0] == "fixed"}
        return new

    def _fixed_poles(self, pade_order):
        poles = super()._fixed_poles(pade_order)
        if isinstance(self.command_model, RateCommandModel):
            # the command block's integrator: the commanded heading/height ramps under a
            # held control by definition of a rate response type (not a closed-loop mode)
            k = int(np.argmin(np.abs(poles)))
            if abs(poles[k]) < 1e-8:
                poles = np.delete(poles, k)
        return poles

    def feedback_poles(self, pade_order=3):
        """Poles of the aircraft with this axis's feedback loop closed [rad/s] (no pilot-path blocks).

        The eigenvalues of ``feedback(L, 1)`` (:meth:`broken_loop_statespace`): plant,
        actuator, sensor and PID, without the command model, feed-forward and
        synchronisation prefilters, whose poles are not modes of the aircraft.
        What the forward-flight mode specs (dutch roll, spiral) grade.

        Examples
        --------
        >>> import control
        >>> plant = control.ss(control.tf([1.0], [1.0, 1.0]), inputs="delta_lat", outputs="p")
        >>> d = AxisEMFDesign(plant, PIDGains(2.0, 0.0, 1.0), axis="roll", actuator=control.tf(1, 1),
        ...                   sensor_delay=0.0)
        >>> [round(float(abs(p)), 6) for p in d.feedback_poles()]   # s^2 + 2 s + 2 = 0
        [1.414214, 1.414214]
        """
        return np.linalg.eigvals(control.feedback(self.broken_loop_statespace(pade_order), 1).A)

    def rate_response_system(self, pade_order=3):
        """Closed-loop signed rate per pilot stick as a SISO StateSpace (Padé delays).

        The same blocks as :meth:`closed_loop` (command, feed-forward, synchronisation,
        PID on the sensed attitude and rate, actuator, plant), joined by state-space
        series, parallel and feedback: the transfer function of ``closed_loop()[0, 0]``
        (tested) without ``interconnect``'s numerical linearisation, which costs most
        of a heave spec evaluation.
        """
        def pade(tau):
            return (control.ss(control.tf(*control.pade(tau, pade_order))) if tau > 0
                    else control.ss([], [], [], [[1.0]]))

        k = self.gains
        s = control.tf("s")
        cm = self.command_model.tf()
        sync = pade(self.equivalent_delay)
        attitude = control.ss(control.tf(np.array(cm.num[0][0]), cm.den[0][0])) * sync
        rate = control.ss(control.minreal(s * cm, verbose=False)) * sync
        feedforward = control.ss(control.minreal(s * cm / self.inverse_plant, verbose=False))
        # PID on the attitude error (K_phi + K_Iphi/s) and on the rate error (K_p)
        pi = control.ss([[0.0]], [[1.0]], [[k.K_Iphi]], [[k.K_phi]])
        command = feedforward + pi * attitude + control.ss([], [], [], [[k.K_p]]) * rate
        kinematics = control.ss([[0.0]], [[1.0]], [[1.0]], [[0.0]])
        sensed = pade(self.sensor_delay)
        feedback = pi * kinematics * sensed + control.ss([], [], [], [[k.K_p]]) * sensed
        forward = control.ss(self.plant.to_statespace(pade_order)) * control.ss(self.actuator)
        return control.feedback(forward, feedback) * command


def _check_channel(plant, channel):
    out, inp = plant.system.output_labels[0], plant.system.input_labels[0]
    for what, got, want in (("output", out, channel.rate_name), ("input", inp, channel.stick)):
        if not (got.startswith(("u[", "y[")) or got == want):
            raise SignalNameError(f"the plant {plant.name or ''} is {out}/{inp} but the {channel.axis} loop "
                                  f"needs {channel.rate_name}/{channel.stick}: its {what} {got!r} belongs to "
                                  "another axis")


def axis_specs(axis, crossover_min=None, drb_min=0.9, mte="all other", limits=None, **selector):
    """The specs the DMO and the final check grade ``axis`` by.

    Parameters
    ----------
    axis : {"roll", "pitch", "yaw", "heave"}
    crossover_min : float, optional
        CrsMnG2 Level 1 boundary [rad/s] (Level 2 at 80 %); default the axis's
        :data:`DEFAULT_CROSSOVER_START`.
    drb_min : float
        DrbRoH1 Level 1 boundary [rad/s] (roll only: the other axes' DRB boundaries
        were not found printed; Level 2 at min(0.5, 0.55 drb_min) as in
        :func:`controllers.default_specs`).
    mte : str
        ADS-33E-PRF MTE class.
    limits : ActuatorLimits, optional
        The axis's actuator rate/travel limits and full-stick amplitude: with them
        the open-loop onset point (``OlpOpG1.pilot``, and ``OlpOpG1.dist`` when a
        disturbance amplitude is given) is graded; without them it is left out.
    **selector
        Passed to :func:`controllers.specs_for` (``uce``, ``attention``, ``speed``,
        ``boundaries``, ...).

    Returns
    -------
    list of Spec
        Every available spec of the axis that grades a design; the heave
        height-response fit reads the closed-loop vertical rate per collective.

    Examples
    --------
    >>> [s.name for s in axis_specs("heave")][:2]
    ['HgtRsH1.heave', 'EigLcG1']
    >>> [s.level1 for s in axis_specs("pitch", crossover_min=3.0) if s.name == "CrsMnG2"]
    [3.0]
    """
    wc = DEFAULT_CROSSOVER_START.get(axis, 1.5) if crossover_min is None else float(crossover_min)
    out = []
    if limits is not None and not isinstance(limits, ActuatorLimits):
        raise TypeError(f"axis_specs: limits must be ActuatorLimits or None, got {type(limits).__name__}")
    _check_supplied(selector.get("boundaries"))
    for s in specs_for(axis, mte=mte, missing="skip", limits=limits, **selector):
        if getattr(s, "family", "") in _UNGRADED_FAMILIES and s.status == "supplied":
            raise ValueError(f"boundaries: {s.name} ({s.description}) is graded on time histories of a stated "
                             "amplitude, which a multi-axis design does not form: grade it on the closed loop's "
                             "responses (controllers.hq.quickness, large_amplitude, coupling)")
        if getattr(s, "family", "") in _TIME_HISTORY_FAMILIES:
            continue
        if s.name == "CrsMnG2":
            s = replace(s, level1=wc, level2=0.8 * wc)
        elif s.name == "DrbRoH1":
            s = replace(s, level1=float(drb_min), level2=min(0.5, 0.55 * float(drb_min)))
        elif s.name == "HgtRsH1.heave":
            s = replace(s, response=_rate_system)
        elif getattr(s, "family", "") == "forward_flight":
            # dutch roll, spiral, phugoid: modes of the augmented aircraft, not of the pilot-path prefilters
            s = replace(s, response=_feedback_poles)
        out.append(s)
    return out


def _check_supplied(boundaries):
    fixed = sorted(set(boundaries or ()) & set(_DESIGN_PARAMETERS))
    if fixed:
        raise ValueError(f"boundaries: {fixed} are the DMO's design parameters (raised from crossover_start "
                         "and drb_start), not supplied boundaries")


def _rate_system(design):
    return design.rate_response_system()


def _feedback_poles(design):
    return design.feedback_poles()


def _effective_plant(plant, loops, axis, channels):
    # the designed axis's own loop is absent from its effective plant: a placeholder fills the slot
    slot = AxisLoop(PIDGains(0.0, 0.0, 0.0), inverse_plant=control.tf([1.0], [1.0]))
    return MultiAxisEMF(plant, {**loops, axis: slot}, channels).effective_plant(axis)


def _same(a, b):
    return all(np.array_equal(np.asarray(x), np.asarray(y)) for x, y in zip((a.A, a.B, a.C, a.D), (b.A, b.B, b.C, b.D)))


def _relative_change(old, new, crossover):
    """Largest change of one gain's share of the controller at crossover, relative to |C(j w_c)|.

    K_p, K_phi and K_Iphi carry different units (per rad/s, rad, rad s); what they do to
    the loop is K_p, K_phi/w_c and K_Iphi/w_c^2 at the crossover w_c [rad/s]. A small
    integral gain jittering by the DMO's bisection tolerance is then not read as a
    design still moving, and a gain that matters is held to the tolerance.
    """
    wc = crossover if np.isfinite(crossover) and crossover > 0 else 1.0
    scale = np.array([1.0 / wc, 1.0 / wc ** 2, 1.0])               # (K_phi, K_Iphi, K_p)
    a, b = old.as_array() * scale, new.as_array() * scale
    c = abs(a[2] + a[0] / (1j * wc) + a[1] / (1j * wc) ** 2)
    return float(np.max(np.abs(b - a)) / max(c, 1e-12))


def design_multi_axis(plant, axes=("roll", "pitch", "yaw", "heave"), start_gains=None, command_models=None,
                      actuator=None, sensor_delay=0.01, mte="all other", crossover_start=None, drb_start=0.9,
                      settings=None, later_settings=None, max_sweeps=3, gain_tolerance=0.01, progress=True,
                      limits="hover", speed="hover", start_closed=False, guard_other_axes=False, guard_level="auto",
                      boundaries=None):
    """Design the EMF loops of several axes of one MIMO aircraft against every axis's specs.

    Parameters
    ----------
    plant : control.StateSpace
        Full linear aircraft (named signals, :data:`~controllers.multi_axis.AXIS_CHANNELS`),
        e.g. ``hold_states(linearize(trim(heli)), ["u", "v"])``.
    axes : sequence of str
        Axes designed, in the order of the sequential loop closure.
    start_gains : dict, optional
        Axis -> PIDGains to start the DMO from (default (0.3, 0.1, 0.05)).
    command_models : dict, optional
        Axis -> CommandModel / RateCommandModel (defaults: attitude command for roll and
        pitch, rate command for yaw (T 0.5 s) and heave (T 2 s)).
    actuator : control LTI, optional
        Every axis's actuator (default 35 rad/s, 0.7 second order).
    sensor_delay : float
        Sensor delay of every loop [s].
    mte : str
        ADS-33E-PRF MTE class of the specs.
    speed : {"hover", "forward"}
        Flight regime of the specs, passed to :func:`controllers.specs_for`: ``"hover"`` is
        hover and low speed, up to 45 [kt]; ``"forward"`` is above 45 [kt] and selects the
        forward-flight charts (and drops the hover/low-speed ones) for every axis.
    start_closed : bool
        False (default): in the first sweep an axis not yet designed is left open. True:
        every axis's loop is closed at its ``start_gains`` from the first sweep on (its
        inverse plant fitted to its own response with the other loops open), so that an
        aircraft with unstable modes that only another axis can stabilise (e.g. the
        pitch-heave divergence at speed, which no roll gains can remove) gives every
        axis a design plant whose closed loop can be stable; ``start_gains`` must then
        stabilise the aircraft together. An axis whose DMO then finds no gains meeting
        every spec keeps its current gains (not the DMO's best-scoring infeasible ones).
    guard_other_axes : bool
        False (default): an axis is tuned against its own specs. True: also against
        the stability margins of the other closed loops on the whole aircraft
        (:func:`controllers.multi_axis_guard.guard_specs`), so that raising one
        axis's crossover cannot take another loop's margin below its Level 1
        boundary if that loop is closed around an unstable plant, or below its
        Level 2 boundary otherwise (or below what it has, if that is lower; the
        next sweep re-tunes a stable loop eroded within Level 2): for an aircraft
        whose loops couple strongly, e.g. pitch and heave at speed.
    guard_level : {"auto", 1, 2}
        The other loops' boundary the guards keep: ``"auto"`` as just said, or
        Level 1 or 2 for every loop (Level 1 freezes an axis whose tuning erodes
        any loop left at its Level 1 edge).
    crossover_start : dict, optional
        Axis -> first crossover boundary [rad/s] (default :data:`DEFAULT_CROSSOVER_START`).
    drb_start : float
        First roll DRB boundary [rad/s].
    settings, later_settings : DMOSettings, optional
        DMO settings of the first sweep and of the later sweeps (default:
        :data:`DEFAULT_SETTINGS` for the first, with its ray-sampling global stage and
        the multistart stage; later ones without the ray sampling, the multistart
        stage polishing the current gains among its starts).
    max_sweeps : int
        Most sweeps over the axes.
    gain_tolerance : float
        Converged when, in a sweep, no gain's share of the controller at crossover
        (K_p, K_phi/w_c, K_Iphi/w_c^2) changes by more than this fraction of |C(j w_c)|.
    progress : bool
        tqdm bar over the axis designs.
    limits : "hover", dict or None
        Actuator limits graded by the open-loop onset point (OlpOpG1): ``"hover"``
        (default) uses :func:`controllers.actuator_limits.full_stick` per axis: the
        assumed swashplate actuator rate and travel of
        :data:`~controllers.actuator_limits.LIMITS_ASSUMPTIONS` and a full stick that
        commands :data:`~controllers.actuator_limits.HOVER_FULL_STICK_COMMAND` through the
        axis's command model; a dict maps axis -> ActuatorLimits (an axis left out
        gets no OLOP); None grades no OLOP.
    boundaries : mapping, optional
        Spec name -> Level boundaries supplied by the caller (e.g. read from their
        copy of ADS-33E-PRF), for every axis: see :func:`controllers.specs_for`.
        Each axis is tuned against and graded by them.

    Returns
    -------
    MultiAxisResult

    Raises
    ------
    SignalNameError
        The plant lacks an axis's signals.
    ValueError
        Unknown axis or ``speed``, ``max_sweeps`` not a positive integer, or
        ``boundaries`` naming an unknown spec, a DMO design parameter (CrsMnG2,
        DrbRoH1) or a spec graded on time histories (quickness, large amplitude,
        coupling).

    Notes
    -----
    An axis where the DMO finds no gains meeting every spec even at the starting
    boundaries keeps its best-scoring gains; its row in :meth:`MultiAxisResult.to_pandas`
    names the unmet specs and the message says so (no silent failure).

    Examples
    --------
    >>> import control
    >>> plant = control.ss([[-1.5, 0], [1.0, 0]], [[5.0], [0]], [[1.0, 0], [0, 1.0]], 0,
    ...                    inputs=["delta_lat"], outputs=["p", "phi"])
    >>> res = design_multi_axis(plant, axes=["roll"], settings=DMOSettings(global_samples=8), progress=False)
    >>> bool(res.to_pandas().loc["roll", "crossover"] > 1.5)
    True
    """
    t0 = time.perf_counter()
    axes = list(axes)
    unknown = [a for a in axes if a not in AXIS_CHANNELS]
    if unknown or not axes or len(set(axes)) != len(axes):
        raise ValueError(f"axes must be distinct names from {list(AXIS_CHANNELS)}, got {axes}")
    MultiAxisEMF(plant, {a: AxisLoop(PIDGains(0, 0, 0), inverse_plant=control.tf(1, 1)) for a in axes})  # names
    if speed not in SPEEDS:
        raise ValueError(f"speed must be one of {list(SPEEDS)}, got {speed!r}")
    if not isinstance(max_sweeps, int) or max_sweeps < 1:
        raise ValueError(f"max_sweeps must be an integer >= 1, got {max_sweeps!r}")
    chosen = {"mte": mte, "speed": speed, "boundaries": boundaries}
    for a in axes:      # bad boundaries are refused before any design work
        axis_specs(a, **chosen)
    settings = settings or DEFAULT_SETTINGS
    later_settings = later_settings or replace(settings, global_samples=0)
    actuator = second_order_actuator(35.0, 0.7) if actuator is None else actuator
    gains = {a: (start_gains or {}).get(a, PIDGains(0.3, 0.1, 0.05)) for a in axes}
    cms = {a: (command_models or {}).get(a) or _default_command(AXIS_CHANNELS[a]) for a in axes}
    wc0 = {**DEFAULT_CROSSOVER_START, **(crossover_start or {})}
    lims = _axis_limits(limits, axes, cms)
    loops, designs, results, messages, rows, plants = {}, {}, {}, {}, [], {}
    tuned_from, tuned_with = {}, {}
    if start_closed:
        for a in axes:
            start = AxisEMFDesign(_effective_plant(plant, {}, a, AXIS_CHANNELS), gains[a], axis=a,
                                  command_model=cms[a], actuator=actuator, sensor_delay=sensor_delay)
            loops[a] = AxisLoop.from_design(start)
    bar = tqdm(total=len(axes) * max_sweeps, desc="multi-axis DMO", disable=not progress)
    converged, sweep = False, 0
    for sweep in range(max_sweeps):
        change = 0.0
        for a in axes:
            bar.set_postfix(sweep=sweep + 1, axis=a)
            others = {b: loops[b] for b in axes if b != a and b in loops}
            eff = _effective_plant(plant, others, a, AXIS_CHANNELS)
            if a in plants and _same(plants[a], eff):
                # nothing this axis sees has changed (e.g. decoupled from the loops that moved): keep its design
                rows.append({**rows[-len(axes)], "sweep": sweep + 1, "relative_change": 0.0, "wall_s": 0.0,
                             "message": "effective plant unchanged: previous design kept"})
                bar.update(1)
                continue
            plants[a] = eff
            design = AxisEMFDesign(eff, gains[a], axis=a, command_model=cms[a], actuator=actuator,
                                   sensor_delay=sensor_delay)
            guards = (axis_guards(plant, others, design, {b: axis_specs(b, **chosen) for b in others},
                                  level=guard_level) if guard_other_axes else [])
            tuned_from[a], tuned_with[a] = gains[a], tuple(others)
            factory = (lambda wc, wd, a=a, guards=guards: axis_specs(a, wc, wd, limits=lims[a], **chosen) + guards)
            ts = time.perf_counter()
            prev = results.get(a)
            # later sweeps continue locally just below the boundaries the axis reached; the full
            # (global) DMO from the starting boundaries is the fallback when that start fails
            tries = [(settings, wc0[a], drb_start)]
            if prev is not None:
                drb_prev = prev.drb_boundary if np.isfinite(prev.drb_boundary) else drb_start / _RESTART
                tries.insert(0, (later_settings, _RESTART * prev.crossover_boundary, _RESTART * drb_prev))
            for k, (sett, wc_start, wd_start) in enumerate(tries):
                try:
                    res = dmo(design, specs_factory=factory, settings=sett, crossover_start=wc_start,
                              drb_start=wd_start, progress=False)
                    new, msg = res.design, res.message
                    break
                except InfeasibleDesignError as exc:
                    # say so, keep the best-scoring gains, and let the final table name the unmet specs
                    res = None
                    # start_closed: the current gains are known to stabilise the aircraft; the DMO's
                    # best-scoring infeasible gains need not, so the current ones are kept
                    new = exc.result.design if exc.result is not None and not start_closed else design
                    msg = (f"no gains meet every {a} spec at the starting boundaries (crossover "
                           f"{wc_start:.3g} rad/s); unmet: {', '.join(exc.unmet)}")
            results[a], messages[a] = res, msg
            moved = (_relative_change(gains[a], new.gains, m.crossover_frequency(new.broken_loop()))
                     if a in loops else np.inf)
            change = max(change, moved)
            gains[a], designs[a] = new.gains, new
            loops[a] = AxisLoop.from_design(new)
            rows.append({"sweep": sweep + 1, "axis": a, "K_phi": new.gains.K_phi, "K_Iphi": new.gains.K_Iphi,
                         "K_p": new.gains.K_p, "crossover": m.crossover_frequency(new.broken_loop()),
                         "relative_change": moved, "feasible": res is not None,
                         "crossover_boundary": res.crossover_boundary if res is not None else np.nan,
                         "wall_s": time.perf_counter() - ts, "message": msg})
            bar.update(1)
        if sweep > 0 and change < gain_tolerance:
            converged = True
            break
    bar.close()
    emf = MultiAxisEMF(plant, {a: loops[a] for a in axes})
    spec_lists, tables = {}, {}
    for a in axes:
        res = results[a]
        wc = res.crossover_boundary if res is not None else wc0[a]
        wd = res.drb_boundary if res is not None and np.isfinite(res.drb_boundary) else drb_start
        spec_lists[a] = axis_specs(a, wc, wd, limits=lims[a], **chosen)
        tables[a] = evaluate_specs(emf.axis_view(a), spec_lists[a])
    return MultiAxisResult(emf, designs, results, tables, spec_lists, pd.DataFrame(rows), converged, messages,
                           time.perf_counter() - t0, sweep + 1, limits=lims, guard_other_axes=bool(guard_other_axes),
                           guard_level=guard_level, tuned_from=tuned_from, tuned_with=tuned_with,
                           boundaries=boundaries, speed=speed)


def _axis_limits(limits, axes, command_models):
    """Axis -> ActuatorLimits or None from the ``limits`` argument of :func:`design_multi_axis`."""
    if limits is None:
        return {a: None for a in axes}
    if isinstance(limits, str):
        if limits != "hover":
            raise ValueError(f"limits must be 'hover', a dict of ActuatorLimits or None, got {limits!r}")
        return {a: full_stick(a, command_models[a].gain) for a in axes}
    if not isinstance(limits, dict):
        raise TypeError(f"limits must be 'hover', a dict of ActuatorLimits or None, got {type(limits).__name__}")
    unknown = sorted(set(limits) - set(axes))
    if unknown:
        raise ValueError(f"limits names axes not designed: {unknown} (designed: {axes})")
    for a, v in limits.items():
        if not isinstance(v, ActuatorLimits):
            raise TypeError(f"limits[{a!r}] must be ActuatorLimits, got {type(v).__name__}")
    return {a: limits.get(a) for a in axes}
