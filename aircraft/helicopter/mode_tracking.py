"""Flight-dynamics mode names and their eigenvalues tracked against speed.

::

    flight_modes(sys)                 classify_modes + a ``mode`` column (phugoid, short period, ...)
    modes_over_speed(systems)         one tidy table over speed, each mode on a continuous track
    ModesOverSpeed.plot()             root loci against speed, frequency and damping against speed

:func:`~aircraft.helicopter.mode_physics.classify_modes` labels a mode by the
state group that dominates its participation (rotor, inflow or body). This
module adds the handling-qualities name of the body modes. A mode is
oscillatory when its damping ratio is below 0.98 (a pair more damped than that
behaves as two subsidences and is named like one); the longitudinal states are
``u, theta, q, w`` and the lateral-directional ones ``v, phi, p, r, psi``:

=====================  =====================================================
oscillatory, longit.   ``phugoid`` (u, theta dominate) or ``short period``
                       (q, w dominate: the pitch-flap mode of a helicopter)
oscillatory, lateral   ``dutch roll`` (yaw rate takes at least 0.2 of the
                       participation) or ``lateral phugoid`` (v, phi: the
                       hover pendulum)
aperiodic              ``phugoid (aperiodic)`` (u, theta), ``spiral`` (v,
                       phi), ``pitch/roll/heave/yaw subsidence`` (q, p, w,
                       r); ``divergence`` instead of ``subsidence`` when
                       unstable
rotor / inflow         the label of ``classify_modes`` (``regressive flap
                       (pitch)``, ``inflow (mean)``, ...) unless the body
                       states take at least 0.4 of the participation and
                       the mode is slower than 0.3 Omega: then a body mode;
                       a flap mode below 0.5 Omega in which the body takes
                       at least 0.3 is ``roll-flap`` or ``pitch-flap``
=====================  =====================================================

Along speed, the modes of neighbouring speeds are matched by an assignment on
a cost that adds the eigenvalue distance (relative to the eigenvalues' size)
and the distance between the participation shares of the state groups, so a
track follows one physical mode through eigenvalue crossings and through the
speed where its name changes (e.g. a hover lateral phugoid that becomes the
dutch roll).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy.optimize import linear_sum_assignment

from .mode_physics import STATE_GROUPS, classify_modes

__all__ = ["flight_modes", "modes_over_speed", "ModesOverSpeed", "ModeTrackingError"]

_SHARES = [f"share_{g}" for g in list(STATE_GROUPS) + ["other"]]
_LON = ("longitudinal", "pitch", "heave")
_LAT = ("lateral", "roll", "yaw", "heading")
_BODY = _LON + _LAT
#: a pair more damped than this behaves as two subsidences
_OSCILLATORY_DAMPING = 0.98
#: body share above which a rotor-labelled slow mode is named as a body mode
_BODY_SHARE = 0.4
#: body share above which a flap mode faster than that is a roll-flap / pitch-flap mode
_FLAP_BODY_SHARE = 0.3
#: yaw-rate share above which a lateral oscillation is the dutch roll
_DUTCH_ROLL_YAW = 0.2
_APERIODIC = {"pitch": "pitch", "roll": "roll", "heave": "heave", "yaw": "yaw"}


class ModeTrackingError(ValueError):
    """A bad argument to :func:`modes_over_speed` or :func:`flight_modes`."""


def _name(row, omega):
    phys = row["physics"]
    if phys == "heading":
        return "heading"
    share = {g: float(row[f"share_{g}"]) for g in _BODY}
    body = sum(share.values())
    slow = row["frequency"] < (0.3 * omega if omega else 5.0)
    rotor_like = any(k in phys for k in ("flap", "inflow"))
    if rotor_like and not (body >= _BODY_SHARE and slow):
        # a flap mode that carries the body with it (the roll-flap mode of an
        # articulated rotor) keeps one name as its whirl sense changes with speed
        if "flap" in phys and body >= _FLAP_BODY_SHARE and row["frequency"] < (0.5 * omega if omega else 10.0):
            return "roll-flap" if share["roll"] >= share["pitch"] else "pitch-flap"
        return phys
    oscillatory = row["imag"] > 1e-9 and row["damping"] < _OSCILLATORY_DAMPING
    if oscillatory:
        lon = sum(share[g] for g in _LON)
        lat = sum(share[g] for g in _LAT)
        if lon >= lat:
            return "phugoid" if share["longitudinal"] >= share["pitch"] + share["heave"] else "short period"
        if share["roll"] > share["lateral"] + share["yaw"]:
            return "roll-flap" if rotor_like else "roll oscillation"
        return "dutch roll" if share["yaw"] >= _DUTCH_ROLL_YAW else "lateral phugoid"
    top = max(_BODY, key=share.get)
    if top == "heading":
        return "heading"
    if top == "longitudinal":
        return "phugoid (aperiodic)"
    if top == "lateral":
        return "spiral"
    return _APERIODIC[top] + (" subsidence" if row["real"] < 0 else " divergence")


def flight_modes(sys, omega=None):
    """Pole table of a linear aircraft with the flight-dynamics name of each mode.

    Parameters
    ----------
    sys : control.StateSpace
        Named states (body states ``u v w p q r phi theta psi``, rotor and inflow
        states as :func:`aircraft.helicopter.linearize` names them).
    omega : float, optional
        Rotor speed [rad/s] (see :func:`~aircraft.helicopter.classify_modes`);
        modes slower than ``0.3 * omega`` in which the body states take most
        of the participation are named as body modes. Default: the trim's
        rotor speed when ``sys`` carries a trim, else 5 rad/s is the bound.

    Returns
    -------
    pandas.DataFrame
        The columns of :func:`~aircraft.helicopter.classify_modes` (``real, imag,
        frequency`` [rad/s], ``damping``, ``physics``, ``dominant_states``,
        ``share_<group>``) with ``mode`` inserted after ``damping``.

    Raises
    ------
    ModeTrackingError
        ``sys`` has no state-space matrix ``A`` of finite values.

    Examples
    --------
    >>> import control
    >>> a = [[-0.05, 0.3], [-0.3, -0.05]]          # u, theta: a lightly damped pair
    >>> sys = control.ss(a, [[1], [0]], [[1, 0]], [[0]], states=["u", "theta"])
    >>> flight_modes(sys)["mode"].tolist()
    ['phugoid']
    """
    a = getattr(sys, "A", None)
    if a is None or np.asarray(a).size == 0 or not np.all(np.isfinite(np.asarray(a, float))):
        raise ModeTrackingError(f"sys must be a state space with a finite matrix A, got {type(sys).__name__}")
    if omega is None and hasattr(sys, "trim"):
        omega = sys.trim.helicopter.config.rotors[0].omega
    table = classify_modes(sys, omega=omega)
    table.insert(table.columns.get_loc("damping") + 1, "mode",
                 [_name(row, omega) for _, row in table.iterrows()])
    return table


def _cost(prev, cur):
    lp = prev["real"].to_numpy() + 1j * prev["imag"].to_numpy()
    lc = cur["real"].to_numpy() + 1j * cur["imag"].to_numpy()
    scale = np.abs(lp)[:, None] + np.abs(lc)[None, :] + 1e-6
    dist = np.abs(lp[:, None] - lc[None, :]) / scale
    sp, sc = prev[_SHARES].to_numpy(), cur[_SHARES].to_numpy()
    shares = np.abs(sp[:, None, :] - sc[None, :, :]).sum(axis=2)
    return dist + shares


@dataclass
class ModesOverSpeed:
    """Modes of one aircraft against speed, each on a continuous track.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per mode (real pole or complex pair with positive imaginary part)
        and speed: ``speed`` [m/s], ``track`` (int, one physical mode), ``mode``
        (its name at this speed), ``track_mode`` (the name it has at most speeds),
        ``physics``, ``real`` [1/s], ``imag``, ``frequency`` [rad/s], ``damping``,
        ``dominant_states`` and the ``share_<group>`` participation columns.
    """

    table: pd.DataFrame

    def plot(self, title=None, max_frequency=10.0):
        """Figure: root loci against speed; frequency and damping against speed.

        Parameters
        ----------
        title : str, optional
            Figure title.
        max_frequency : float
            Eigenvalues of larger magnitude [rad/s] (flap and inflow modes) are
            left out.

        Returns
        -------
        matplotlib.figure.Figure
        """
        from matplotlib.figure import Figure
        t = self.table
        t = t[(t["frequency"] <= max_frequency) & (t["mode"] != "heading")]
        names = list(dict.fromkeys(t.sort_values("frequency")["track_mode"]))
        colors = {n: f"C{i % 10}" for i, n in enumerate(names)}
        fig = Figure(figsize=(13, 4.2), layout="constrained")
        ax = fig.subplots(1, 3)
        labelled = set()
        for track, g in t.groupby("track"):
            g = g.sort_values("speed")
            name = g["track_mode"].iloc[0]
            c = colors[name]
            label = None if name in labelled else name
            labelled.add(name)
            ax[0].plot(g["real"], g["imag"], "-", color=c, lw=1, label=label)
            ax[0].scatter(g["real"], g["imag"], c=g["speed"], cmap="viridis", s=10, zorder=3)
            ax[0].plot(g["real"].iloc[0], g["imag"].iloc[0], "o", mfc="none", color=c, ms=7)
            ax[1].plot(g["speed"], g["frequency"], "o-", ms=2, color=c)
            ax[2].plot(g["speed"], g["damping"], "o-", ms=2, color=c)
        ax[0].axvline(0.0, color="k", lw=0.6)
        ax[0].set(xlabel="real [1/s]", ylabel="imaginary [rad/s]",
                  title="root loci (open circle: lowest speed)")
        ax[1].set(xlabel="speed [m/s]", ylabel="frequency |lambda| [rad/s]", title="frequency")
        ax[2].axhline(0.0, color="k", lw=0.6)
        ax[2].set(xlabel="speed [m/s]", ylabel="damping ratio [-]", title="damping (< 0: unstable)",
                  ylim=(-1.05, 1.05))
        ax[0].legend(fontsize=7)
        for a in ax:
            a.grid(True, alpha=0.3)
        if title:
            fig.suptitle(title)
        return fig


def modes_over_speed(systems, omega=None, max_cost=1.0) -> ModesOverSpeed:
    """Named modes of linear models at several speeds, matched into tracks.

    Parameters
    ----------
    systems : mapping or TrimSweep
        ``{speed [m/s]: control.StateSpace}`` or an object with such a
        ``systems`` attribute (:class:`~aircraft.helicopter.sweep.TrimSweep`).
        All systems should have the same states.
    omega : float, optional
        Rotor speed [rad/s], passed to :func:`flight_modes`.
    max_cost : float
        Largest matching cost (relative eigenvalue distance plus the L1 distance
        of the participation shares, which ranges 0 to 2) at which a mode
        continues a track of the previous speed; above it a new track starts.

    Returns
    -------
    ModesOverSpeed

    Raises
    ------
    ModeTrackingError
        ``systems`` is empty, a speed is not a finite number, or ``max_cost`` is
        not positive.

    Examples
    --------
    >>> import control
    >>> def heli(v):   # pitch subsidence and heave subsidence that cross at 25 m/s
    ...     return control.ss([[-1 - 0.02 * v, 0], [0, -2 + 0.02 * v]], [[1], [1]], [[1, 1]], [[0]],
    ...                       states=["q", "w"])
    >>> t = modes_over_speed({v: heli(v) for v in (0.0, 20.0, 30.0)}).table
    >>> t[t["mode"] == "pitch subsidence"]["real"].round(2).tolist()
    [-1.0, -1.4, -1.6]
    """
    mapping = getattr(systems, "systems", systems)
    if not hasattr(mapping, "items") or len(mapping) == 0:
        raise ModeTrackingError("systems must be a non-empty {speed: StateSpace} mapping or a TrimSweep")
    if isinstance(max_cost, bool) or not isinstance(max_cost, (int, float)) or not max_cost > 0:
        raise ModeTrackingError(f"max_cost must be a positive number, got {max_cost!r}")
    try:
        speeds = sorted((float(v), sys) for v, sys in mapping.items())
    except (TypeError, ValueError) as err:
        raise ModeTrackingError("systems' keys must be speeds [m/s]") from err
    if not all(np.isfinite(v) for v, _ in speeds):
        raise ModeTrackingError("systems' speeds must be finite [m/s]")
    tables, prev, next_track = [], None, 0
    for speed, sys in speeds:
        cur = flight_modes(sys, omega=omega)
        track = np.full(len(cur), -1)
        if prev is not None:
            cost = _cost(prev, cur)
            rows, cols = linear_sum_assignment(cost)
            for i, j in zip(rows, cols):
                if cost[i, j] <= max_cost:
                    track[j] = prev["track"].iloc[i]
        for j in np.flatnonzero(track < 0):
            track[j], next_track = next_track, next_track + 1
        cur.insert(0, "track", track)
        cur.insert(0, "speed", speed)
        tables.append(cur)
        prev = cur
    table = pd.concat(tables, ignore_index=True)
    # the name a track has at most speeds; a tie goes to the name met first (lowest speed)
    common = table.groupby("track")["mode"].agg(lambda s: max(dict.fromkeys(s), key=list(s).count))
    table.insert(3, "track_mode", table["track"].map(common))
    return ModesOverSpeed(table.sort_values(["track", "speed"]).reset_index(drop=True))
