"""Guard specs: the stability margins of the other closed loops, graded while one axis is tuned.

A sequential multi-axis design tunes one axis with the others closed. Its DMO
raises that axis's crossover until one of *its own* specs fails; a loop that
couples strongly into another axis can meanwhile take the other loop's margins
away (at speed, a tight vertical-rate loop on the collective moves the pitch
loop's unstable pole from about 0.5 to 1.6 rad/s, beyond what any pitch gains
can hold with Level 1 margins). A guard spec reads another axis's stability
margin -- Nichols margin, gain margin (rise or fall) and phase margin, loop
broken at that axis's mixer input -- on the whole aircraft with the candidate
gains of the axis being tuned, so the DMO stops raising where the other axis
would lose its margin. CONDUIT grades every loop's specs on every gain at once;
this is the same constraint in the sequential loop closure.

Each guard's boundary is the other axis's own Level 1 boundary if that axis's
loop is closed around an unstable plant (its effective plant, the tuned axis
in the loop, has a pole in the right half plane) and its Level 2 boundary
otherwise, or the value it
has when the guard is built if that is already lower (a guard never asks for a
margin the other axis does not have: it only forbids taking margin away). Not
Level 1: the sequential DMO leaves every loop at the edge of its own Level 1
margins, so a Level 1 guard on every loop freezes every later axis: a stable
loop eroded a little is re-tuned in the next sweep, and Level 2 only forbids its
collapse. A loop around an unstable plant cannot be re-tuned back: the margins
any gains can reach fall as its unstable pole moves out, which is what the other
loops do to it; so it keeps its Level 1 boundary.
"""
from __future__ import annotations

from collections import OrderedDict

import control
import numpy as np

from . import metrics as m
from .emf import PIDGains
from .multi_axis import AxisLoop, MultiAxisEMF
from .specs import Spec

__all__ = ["GUARDED_SPECS", "GUARD_OMEGA", "GUARD_TOLERANCE", "axis_guards", "guard_specs"]

#: the other axes' specs a guard grades: the hard stability margins, loop broken at the mixer input
GUARDED_SPECS = ("NicMgG1", "StbMgG1.GM", "StbMgG1.PM")
# guard values kept per axis design (the DMO grades one candidate's specs several times)
_CACHE_SIZE = 64
#: how far inside its boundary a guard holds another loop [spec units]: the guards read the margins
#: on :data:`GUARD_OMEGA`, the final tables on the metrics' default grid, and the two differ by up to
#: 1e-5 (Nichols), 1e-5 dB and 2e-3 deg on the forward-flight loops; ten times that and more keeps a
#: loop the guard holds at its boundary met on the final grid too
GUARD_TOLERANCE = {"NicMgG1": 1e-3, "StbMgG1.GM": 0.01, "StbMgG1.PM": 0.05}
#: grid of the guards' margins [rad/s]: an eighth of the metrics' default points (the DMO grades
#: hundreds of candidates, each with every other axis); on the forward-flight aircraft's pitch loop
#: the margins it gives differ from the default grid's by < 1e-5 dB and < 2e-3 deg
GUARD_OMEGA = np.geomspace(0.02, 100.0, 500)


# a plant pole further right than this [1/s] makes the plant unstable (not an integrator at the origin)
_UNSTABLE_POLE = 1e-6


def _unstable_plant(plant, loops, current, other, kwargs):
    """Whether ``other``'s loop is closed around an unstable plant (the tuned axis at its current gains)."""
    slot = AxisLoop(PIDGains(0.0, 0.0, 0.0), inverse_plant=control.tf([1.0], [1.0]))
    others = {b: lp for b, lp in loops.items() if b != other}
    emf = MultiAxisEMF(plant, {**others, current.axis: AxisLoop.from_design(current), other: slot}, **kwargs)
    poles = emf.effective_plant(other).poles()
    return bool(np.size(poles) and np.max(np.real(poles)) > _UNSTABLE_POLE)


def _margins(view):
    """(Nichols margin, |gain margin| [dB], phase margin [deg]) of one axis's broken loop."""
    loop = view.broken_loop()
    gm, pm, _, _ = m.gain_phase_margins(loop, GUARD_OMEGA)
    return m.nichols_margin(loop, GUARD_OMEGA), abs(gm), pm


def guard_specs(plant, loops, current, spec_lists, channels=None, level="auto"):
    """Specs that keep the other closed loops' stability margins while ``axis`` is tuned.

    Parameters
    ----------
    plant : control.StateSpace
        The full linear aircraft (named signals).
    loops : dict
        Axis -> :class:`~controllers.multi_axis.AxisLoop` of the *other* closed loops.
    current : controllers.multi_axis_design.AxisEMFDesign
        The tuned axis's design at its current gains (on its effective plant with
        ``loops`` closed): each candidate design of the DMO is put into the loop in
        its place to grade the guards, and the margins it gives now set the floor
        of each guard's boundary.
    spec_lists : dict
        Axis -> its spec list: the Level 1/2 boundaries of :data:`GUARDED_SPECS`
        are read from it (an axis or spec missing from it is not guarded).
    channels : dict, optional
        Axis channels (default :data:`~controllers.multi_axis.AXIS_CHANNELS`).
    level : {"auto", 1, 2}
        Which of the other axis's boundaries a guard keeps (see the module notes):
        ``"auto"`` (default) Level 1 for a loop around an unstable plant, Level 2
        for the others.

    Returns
    -------
    list of Spec
        Hard specs named ``"<spec>@<other axis>"``, each graded on the whole
        aircraft; boundaries ``min(boundary of level + GUARD_TOLERANCE, value now)``
        (see the module notes).

    Raises
    ------
    ValueError
        If the tuned axis is among ``loops``, or ``level`` is not "auto", 1 or 2.

    Examples
    --------
    >>> import control
    >>> from controllers import PIDGains
    >>> from controllers.multi_axis_design import AxisEMFDesign, _effective_plant, axis_specs
    >>> plant = control.ss([[-1.0, 0, 0, 0], [1, 0, 0, 0], [0, 0, -2.0, 0], [0, 0, 1, 0]],
    ...                    [[4.0, 0.5], [0, 0], [0.5, -4.0], [0, 0]], np.eye(4), 0,
    ...                    inputs=["delta_lat", "delta_lon"], outputs=["p", "phi", "q", "theta"])
    >>> pitch = AxisEMFDesign(_effective_plant(plant, {}, "pitch", None), PIDGains(1.0, 0.1, 0.3), axis="pitch")
    >>> loops = {"pitch": AxisLoop.from_design(pitch)}
    >>> roll = AxisEMFDesign(_effective_plant(plant, loops, "roll", None), PIDGains(1.0, 0.1, 0.3), axis="roll")
    >>> guards = guard_specs(plant, loops, roll, {"pitch": axis_specs("pitch")})
    >>> [g.name for g in guards]
    ['NicMgG1@pitch', 'StbMgG1.GM@pitch', 'StbMgG1.PM@pitch']
    """
    axis = current.axis
    if isinstance(level, bool) or level not in ("auto", 1, 2):
        raise ValueError(f"guard_specs: level must be 'auto', 1 or 2, got {level!r}")
    if axis in loops:
        raise ValueError(f"guard_specs: the tuned axis {axis!r} must not be among the other loops")
    kwargs = {} if channels is None else {"channels": channels}
    cache = OrderedDict()

    def values(design, other):
        key = (design.gains.as_array().tobytes(), id(design.plant), other)
        if key not in cache:
            emf = MultiAxisEMF(plant, {**loops, axis: AxisLoop.from_design(design)}, **kwargs)
            cache[key] = _margins(emf.axis_view(other))
            if len(cache) > _CACHE_SIZE:
                cache.popitem(last=False)
        return cache[key]

    out = []
    for other in loops:
        by_name = {s.name: s for s in spec_lists.get(other, ())}
        now = values(current, other)
        keep = level if level != "auto" else (1 if _unstable_plant(plant, loops, current, other, kwargs) else 2)
        for k, name in enumerate(GUARDED_SPECS):
            s = by_name.get(name)
            if s is None:
                continue
            # at Level 2 the tuned axis may take another loop's margin down to its Level 2 (that loop
            # is re-tuned in the next sweep), never below it; at Level 1 it may take none of it
            l1 = l2 = s.level2 if keep == 2 else s.level1
            # the boundary a tolerance inside the level, but never above what the loop has now
            l1 = l2 = l1 + GUARD_TOLERANCE[name]
            if np.isfinite(now[k]):
                l1 = l2 = min(l1, now[k])
            out.append(Spec(f"{name}@{other}", f"{s.description} of the {other} loop, {axis} gains varied",
                            lambda d, other=other, k=k: values(d, other)[k], s.direction, l1, l2,
                            kind="hard", units=s.units, source=f"guard: {s.source}"))
    return out



def axis_guards(plant, loops, current, spec_lists, closed=None, level="auto"):
    """The guards of the tuned axis: :func:`guard_specs` on the other closed loops, none if there are none.

    The one construction of an axis's guard list, used by
    :func:`controllers.multi_axis_design.design_multi_axis` while it tunes the axis
    and by :func:`controllers.multi_axis_check.global_check` when it searches the
    axis again, so that the check grades the guards the design was tuned against.

    Parameters
    ----------
    plant : control.StateSpace
        The full linear aircraft (named signals).
    loops : dict
        Axis -> :class:`~controllers.multi_axis.AxisLoop` of the closed loops; the
        tuned axis's own entry, if any, is left out.
    current : controllers.multi_axis_design.AxisEMFDesign
        The tuned axis's design at the gains its tuning starts from (the guards'
        floor, see :func:`guard_specs`).
    spec_lists : dict
        Axis -> spec list of the other axes; only the Level 1/2 boundaries of
        :data:`GUARDED_SPECS` are read, which do not depend on the crossover or DRB
        boundaries nor on the actuator limits of the list.
    closed : iterable of str, optional
        The other axes whose loops were closed when the axis was tuned (default every
        other axis of ``loops``); an axis of ``loops`` not among them is not guarded.
    level : {"auto", 1, 2}
        Passed to :func:`guard_specs`.

    Returns
    -------
    list of Spec
        :func:`guard_specs`'s list, empty when no other loop is closed.

    Examples
    --------
    >>> import control
    >>> from controllers import PIDGains
    >>> from controllers.multi_axis_design import AxisEMFDesign, _effective_plant, axis_specs
    >>> plant = control.ss([[-1.0, 0, 0, 0], [1, 0, 0, 0], [0, 0, -2.0, 0], [0, 0, 1, 0]],
    ...                    [[4.0, 0.5], [0, 0], [0.5, -4.0], [0, 0]], np.eye(4), 0,
    ...                    inputs=["delta_lat", "delta_lon"], outputs=["p", "phi", "q", "theta"])
    >>> pitch = AxisEMFDesign(_effective_plant(plant, {}, "pitch", None), PIDGains(1.0, 0.1, 0.3), axis="pitch")
    >>> loops = {"pitch": AxisLoop.from_design(pitch)}
    >>> roll = AxisEMFDesign(_effective_plant(plant, loops, "roll", None), PIDGains(1.0, 0.1, 0.3), axis="roll")
    >>> len(axis_guards(plant, loops, roll, {"pitch": axis_specs("pitch")})), axis_guards(plant, {}, roll, {})
    (3, [])
    """
    others = {b: lp for b, lp in loops.items() if b != current.axis and (closed is None or b in closed)}
    if not others:
        return []
    return guard_specs(plant, others, current, {b: spec_lists.get(b, ()) for b in others}, level=level)
