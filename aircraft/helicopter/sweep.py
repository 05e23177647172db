"""Trim and linearisation of one aircraft across speed: ``trim_sweep(heli, speeds)``.

Each speed is trimmed from the momentum-theory start first and, if that fails,
again from the neighbouring converged trim (continuation); a speed that still
fails is a row with ``converged = False`` and the solver's message, not an
error, so one hard speed does not hide the rest. Every converged trim is
linearised (pilot inputs) and its eigenvalues tabulated with their dominant
states (:func:`~aircraft.helicopter.modes`).

Power: main rotor(s) ``torque * Omega``, the tail rotor's shaft power and the
propeller's ``torque * Omega``, all in kW.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..inflow.base import rotor_suffix
from .airframe import propeller_loads
from .linearize import linearize, modes
from .mixing import pilot_inputs
from .model import Helicopter
from .trim import TrimCondition, TrimError, TrimInputError, trim

__all__ = ["TrimSweep", "trim_sweep"]


@dataclass
class TrimSweep:
    """Trims, linear models and eigenvalues of one aircraft against speed.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per speed: ``speed`` [m/s], ``converged``, ``max_residual``, the pilot
        controls and rotor controls [deg], ``phi``, ``theta`` [deg], ``power_main``,
        ``power_tail``, ``power_prop``, ``power_total`` [kW], ``message``.
    eigenvalues : pandas.DataFrame
        One row per real eigenvalue or complex pair: ``speed`` and the columns of
        :func:`~aircraft.helicopter.modes`.
    trims : dict
        ``{speed: TrimResult}`` of the converged speeds (the inflow model is left
        trimmed at the last one: re-trim before linearising an earlier one again).
    systems : dict
        ``{speed: control.StateSpace}`` (pilot inputs) of the converged speeds.
    """

    table: pd.DataFrame
    eigenvalues: pd.DataFrame
    trims: dict = field(default_factory=dict)
    systems: dict = field(default_factory=dict)

    def plot(self, title=None):
        """Figure: pilot controls, attitudes and power against speed.

        Parameters
        ----------
        title : str, optional
            Figure title.

        Returns
        -------
        matplotlib.figure.Figure
        """
        from matplotlib.figure import Figure
        t = self.table[self.table["converged"]]
        fig = Figure(figsize=(11, 3.6), layout="constrained")
        ax = fig.subplots(1, 3)
        for name in [c for c in t.columns if c.startswith("delta_")]:
            ax[0].plot(t["speed"], t[name], "o-", ms=3, label=name)
        ax[0].set(xlabel="speed [m/s]", ylabel="pilot control [deg]", title="controls")
        for name, label in (("phi", "roll phi"), ("theta", "pitch theta")):
            ax[1].plot(t["speed"], t[name], "o-", ms=3, label=label)
        ax[1].set(xlabel="speed [m/s]", ylabel="attitude [deg]", title="attitudes")
        for name in ("power_main", "power_tail", "power_prop", "power_total"):
            if np.any(t[name] != 0):
                ax[2].plot(t["speed"], t[name], "o-", ms=3, label=name.replace("power_", ""))
        ax[2].set(xlabel="speed [m/s]", ylabel="power [kW]", title="power")
        for a in ax:
            a.grid(True, alpha=0.3)
            a.legend(fontsize=7)
        if title:
            fig.suptitle(title)
        return fig

    def plot_eigenvalues(self, title=None, max_frequency=15.0):
        """Figure: eigenvalues in the complex plane, coloured by speed.

        Parameters
        ----------
        title : str, optional
            Figure title.
        max_frequency : float
            Eigenvalues of larger magnitude [rad/s] (flap and inflow modes) are left out.

        Returns
        -------
        matplotlib.figure.Figure
        """
        from matplotlib.figure import Figure
        e = self.eigenvalues[self.eigenvalues["frequency"] <= max_frequency]
        fig = Figure(figsize=(6.5, 4.5), layout="constrained")
        ax = fig.subplots()
        sc = ax.scatter(e["real"], e["imag"], c=e["speed"], cmap="viridis", s=14)
        ax.scatter(e["real"], -e["imag"], c=e["speed"], cmap="viridis", s=14)
        fig.colorbar(sc, ax=ax, label="speed [m/s]")
        ax.axvline(0.0, color="k", lw=0.6)
        ax.set(xlabel="real [1/s]", ylabel="imaginary [rad/s]",
               title=title or f"eigenvalues below {max_frequency:g} rad/s against speed")
        ax.grid(True, alpha=0.3)
        return fig


def _row(heli, speed, result):
    cfg = heli.config
    row = {"speed": float(speed), "converged": True, "max_residual": result.max_residual}
    for name, value in zip(pilot_inputs(cfg), result.pilot):
        row[name] = np.degrees(value)
    for name, value in zip(heli.input_names, result.u):
        row[name] = np.degrees(value)
    row["phi"], row["theta"] = np.degrees(result.x[6]), np.degrees(result.x[7])
    _, extra = heli.evaluate(result.x, result.u)
    main = sum(extra[f"torque{rotor_suffix(rm.config.name)}"] * rm.config.omega for rm in heli.rotors)
    prop = 0.0
    if cfg.is_coaxial and cfg.propeller is not None:
        prop = propeller_loads(cfg.propeller, result.u[6], result.x[0], cfg.rho,
                               model=heli.settings.propeller_model)[1] * cfg.propeller.omega
    tail = extra.get("power_tr", 0.0)
    row.update(power_main=main / 1e3, power_tail=tail / 1e3, power_prop=prop / 1e3,
               power_total=(main + tail + prop) / 1e3, message="")
    return row


def trim_sweep(heli, speeds, *, condition=None, linearise=True, max_time=60.0) -> TrimSweep:
    """Trim (and linearise) ``heli`` at each speed, hover to the aircraft's maximum.

    Parameters
    ----------
    heli : Helicopter
    speeds : sequence of float
        Level-flight speeds [m/s], each >= 0, in the order to trim them (ascending
        makes the continuation start useful).
    condition : TrimCondition, optional
        Template for the other trim settings (the compound's ``rotor_aoa`` and
        ``lateral_cyclic_difference``); its speed is replaced.
    linearise : bool
        Linearise every converged trim and tabulate the eigenvalues.
    max_time : float
        Wall-clock budget of each trim attempt [s].

    Returns
    -------
    TrimSweep

    Raises
    ------
    TrimInputError
        ``heli`` is no Helicopter, ``speeds`` is empty or holds a bad speed.

    Examples
    --------
    >>> from aircraft import uh60_single_rotor
    >>> from aircraft.helicopter import Helicopter
    >>> from aircraft.inflow import PittPeters
    >>> sweep = trim_sweep(Helicopter(uh60_single_rotor(), PittPeters()), [0.0, 40.0], linearise=False)
    >>> sweep.table["converged"].tolist(), bool(sweep.table["phi"].iloc[0] < -1.0)
    ([True, True], True)
    """
    if not isinstance(heli, Helicopter):
        raise TrimInputError(f"heli must be a Helicopter, got {type(heli).__name__}")
    try:
        speeds = [float(v) for v in speeds]
    except (TypeError, ValueError) as err:
        raise TrimInputError(f"speeds must be a sequence of numbers [m/s], got {speeds!r}") from err
    if not speeds:
        raise TrimInputError("speeds must hold at least one speed [m/s]")
    template = condition if condition is not None else TrimCondition()
    if not isinstance(template, TrimCondition):
        raise TrimInputError(f"condition must be a TrimCondition, got {type(template).__name__}")
    conditions = [TrimCondition(speed=v, rotor_aoa=template.rotor_aoa,
                                lateral_cyclic_difference=template.lateral_cyclic_difference) for v in speeds]
    rows, eig, trims, systems = [], [], {}, {}
    previous = None
    for speed, cond in zip(speeds, conditions):
        result, message = None, ""
        try:
            result = trim(heli, cond, max_time=max_time)
        except TrimError as err:
            message = str(err)
            # the compound's unknowns differ in hover and forward flight: continue only within one kind
            if previous is not None and (previous.condition.speed > 0) == (speed > 0):
                try:
                    result = trim(heli, cond, max_time=max_time, start=previous)
                except TrimError as err2:
                    message = str(err2)
        if result is None:
            rows.append({"speed": speed, "converged": False, "max_residual": np.nan, "message": message})
            continue
        previous = result
        rows.append(_row(heli, speed, result))
        trims[speed] = result
        if linearise:
            sys = linearize(result)
            systems[speed] = sys
            table = modes(sys)
            table.insert(0, "speed", speed)
            eig.append(table)
    eigenvalues = pd.concat(eig, ignore_index=True) if eig else pd.DataFrame(
        columns=["speed", "pole", "real", "imag", "frequency", "damping", "dominant_states"])
    return TrimSweep(pd.DataFrame(rows), eigenvalues, trims, systems)
