"""The UH-60-like aircraft's trim power against published UH-60A trims (GENHEL, NASA TM-100991).

::

    reference_trims()              the report's trims (data/uh60a_trim_ballin1988.csv) in SI units
    ours_at_reference(reference)   our aircraft trimmed at the reference's level-flight speeds, weight, density
    compare_power(reference, ours) one row per condition and power figure: ours, reference, difference
    uh60a_validation()             the three above in one call
    plot_uh60a_validation(table)   power against speed: the reference's two figures and ours

The reference is the only UH-60A level-flight trim with printed numbers found in
the sources reachable here: Table B.1 of Ballin's T700 engine report (NASA
TM-100991, 1988) gives, for the GENHEL UH-60A blade-element simulation at
16,825 lb on a sea-level standard day, the trimmed power in hover and in level
flight at 80 kt (equivalent airspeed), and a descent at 80 kt that a level-flight
comparison leaves out. It prints no control positions and no attitudes, so only
the power is compared; the collective, cyclics and pitch attitude stay
unvalidated.

The table prints power twice and the two figures do not agree: the engines'
output (horsepower per engine, two engines) and the required torque referred to
the rotor hub, which the report defines as all vehicle load contributions (main
rotor, tail rotor, accessories, drive). Converted at the rotor speed the hub
figure is 11 % below the engines' in hover and 8 % at 80 kt; the report does
not reconcile them, so both are compared and their spread is the reference's
own uncertainty.

Our aircraft is the dissertation's UH-60-like (Appendix B.1), not a UH-60A:
uniform blades with a constant profile drag coefficient and -17 deg linear
twist (the UH-60A's SC1095/SC1094R8 sections, non-linear twist and swept tip
are not modelled), a 2.0 m^2 fuselage flat plate of our own, no ground effect,
no transmission or accessory losses (our ``power_total`` is the main rotor's
torque times its speed plus the tail rotor's shaft power). It is trimmed at the
reference's weight and density (``match_weight``), so the differences are the
model's, not the loading's.
"""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pandas as pd

from aircraft import uh60_single_rotor
from aircraft.configs import LB, RHO_SEA_LEVEL, AircraftConfig
from aircraft.helicopter import Helicopter
from aircraft.helicopter.sweep import trim_sweep
from aircraft.inflow import PittPeters

__all__ = ["REFERENCE_FILE", "HP", "FT_LBF", "KNOT", "isa_density", "reference_trims", "ours_at_reference",
           "compare_power", "uh60a_validation", "plot_uh60a_validation"]

REFERENCE_FILE = Path(__file__).resolve().parent / "data" / "uh60a_trim_ballin1988.csv"
HP = 550.0 * 0.3048 * 0.45359237 * 9.80665   #: watts per mechanical horsepower (550 ft lbf/s)
FT_LBF = 0.3048 * 0.45359237 * 9.80665       #: newton metres per foot pound-force
KNOT = 1852.0 / 3600.0                       #: metres per second per knot

_COLUMNS = ("condition", "gross_weight_lb", "equivalent_airspeed_kt", "flight_path_angle_deg", "altitude_ft",
            "required_torque_hub_ft_lbf", "engine_torque_shaft_ft_lbf", "power_per_engine_hp",
            "power_turbine_speed_rpm")
_N_ENGINES = 2   # the UH-60A's two T700 engines: the table prints power per engine


def isa_density(altitude):
    """ISA troposphere density at a pressure altitude.

    Parameters
    ----------
    altitude : float
        Pressure altitude [m], 0 to 11,000.

    Returns
    -------
    float
        Density [kg/m^3].

    Raises
    ------
    ValueError
        ``altitude`` is outside the troposphere or not a number.

    Examples
    --------
    >>> round(isa_density(0.0), 4), round(isa_density(1524.0), 4)
    (1.225, 1.0555)
    """
    h = float(altitude)
    if not 0.0 <= h <= 11000.0:
        raise ValueError(f"altitude must lie in the troposphere, 0 to 11000 m, got {altitude!r}")
    # ISA lapse rate 6.5 K/km from 288.15 K; exponent g / (R L) - 1 = 4.2559
    return RHO_SEA_LEVEL * (1.0 - 0.0065 * h / 288.15) ** 4.255876


def reference_trims(path=REFERENCE_FILE):
    """The published UH-60A trims, with SI columns added.

    Parameters
    ----------
    path : str or Path
        A CSV in the layout of ``data/uh60a_trim_ballin1988.csv`` (``#`` comment
        lines, then the columns of that file, units in their names).

    Returns
    -------
    pandas.DataFrame
        The file's columns and ``mass`` [kg], ``rho`` [kg/m^3] (ISA at the
        altitude), ``speed`` [m/s] (true airspeed from the equivalent airspeed),
        ``level`` (flight-path angle zero), ``power_engines`` [kW] (all engines'
        output) and ``torque_hub`` [N m].

    Raises
    ------
    ValueError
        A column is missing or a value is not a finite number.

    Examples
    --------
    >>> ref = reference_trims()
    >>> ref[["condition", "speed", "power_engines"]].round(1).values.tolist()[:2]
    [['hover', 0.0, 1358.8], ['level_80kt', 41.2, 824.1]]
    """
    df = pd.read_csv(path, comment="#")
    missing = [c for c in _COLUMNS if c not in df.columns]
    if missing:
        raise ValueError(f"path {str(path)!r} lacks the column(s) {missing}")
    numbers = df[list(_COLUMNS[1:])].apply(pd.to_numeric, errors="coerce")
    if not np.all(np.isfinite(numbers.to_numpy(dtype=float))):
        raise ValueError(f"path {str(path)!r} holds a value that is not a finite number")
    df[list(_COLUMNS[1:])] = numbers
    df["mass"] = df["gross_weight_lb"] * LB
    df["rho"] = [isa_density(h * 0.3048) for h in df["altitude_ft"]]
    df["speed"] = df["equivalent_airspeed_kt"] * KNOT * np.sqrt(RHO_SEA_LEVEL / df["rho"])
    df["level"] = df["flight_path_angle_deg"] == 0.0
    df["power_engines"] = _N_ENGINES * df["power_per_engine_hp"] * HP / 1e3
    df["torque_hub"] = df["required_torque_hub_ft_lbf"] * FT_LBF
    return df


def ours_at_reference(reference, *, aircraft=uh60_single_rotor, inflow=PittPeters, match_weight=True):
    """Our aircraft trimmed in level flight at each level condition of ``reference``.

    Parameters
    ----------
    reference : pandas.DataFrame
        From :func:`reference_trims`.
    aircraft : callable
        Returns the :class:`~aircraft.configs.AircraftConfig` to trim.
    inflow : callable
        Returns the inflow model.
    match_weight : bool
        Trim at the reference's mass and density (True) or at the aircraft's own.

    Returns
    -------
    pandas.DataFrame
        The rows of :func:`~aircraft.helicopter.sweep.trim_sweep`'s table, with
        ``condition``, ``mass`` [kg] and ``rho`` [kg/m^3] in front.

    Raises
    ------
    ValueError
        ``reference`` has no level-flight condition, or ``aircraft`` returns no AircraftConfig.

    Examples
    --------
    >>> ours = ours_at_reference(reference_trims())
    >>> ours["condition"].tolist(), bool(ours["converged"].all())
    (['hover', 'level_80kt'], True)
    """
    level = reference[reference["level"]]
    if level.empty:
        raise ValueError("reference holds no level-flight condition (flight_path_angle_deg == 0)")
    rows = []
    for _, ref in level.iterrows():
        cfg = aircraft()
        if not isinstance(cfg, AircraftConfig):
            raise ValueError(f"aircraft must return an AircraftConfig, got {type(cfg).__name__}")
        if match_weight:
            cfg = dataclasses.replace(cfg, mass=float(ref["mass"]), rho=float(ref["rho"]))
        row = trim_sweep(Helicopter(cfg, inflow()), [float(ref["speed"])], linearise=False).table.iloc[0]
        rows.append({"condition": ref["condition"], "mass": cfg.mass, "rho": cfg.rho, **row.to_dict()})
    return pd.DataFrame(rows)


def compare_power(reference, ours, omega, fuselage_fx=None):
    """Our trimmed power against the reference's two power figures, per condition.

    Parameters
    ----------
    reference : pandas.DataFrame
        From :func:`reference_trims`.
    ours : pandas.DataFrame
        ``condition``, ``converged`` and ``power_total`` [kW] per level condition
        (:func:`ours_at_reference`).
    omega : float
        Main rotor speed [rad/s] that turns the reference's hub torque into power.
    fuselage_fx : float, optional
        Our fuselage flat-plate area [m^2]: the explanation then states the
        parasite power per square metre of it at the condition's speed.

    Returns
    -------
    pandas.DataFrame
        ``condition``, ``speed`` [m/s], ``speed_kt``, ``quantity``, ``ours``,
        ``measured``, ``difference`` (ours - measured), ``relative_difference``
        (difference / measured), ``unit``, ``source``, ``explanation``; our
        unconverged conditions are left out.

    Raises
    ------
    ValueError
        ``omega`` is not positive, or ``ours`` lacks a column.

    Examples
    --------
    >>> ref = reference_trims()
    >>> ours = pd.DataFrame({"condition": ["hover"], "converged": [True], "power_total": [1300.0]})
    >>> t = compare_power(ref, ours, omega=27.0)
    >>> t[["quantity", "measured", "difference"]].round(1).values.tolist()
    [['power, engine output', 1358.8, -58.8], ['power, hub required torque x Omega', 1203.1, 96.9]]
    """
    if not (isinstance(omega, (int, float)) and math.isfinite(omega) and omega > 0.0):
        raise ValueError(f"omega must be a positive rotor speed [rad/s], got {omega!r}")
    missing = [c for c in ("condition", "converged", "power_total") if c not in ours.columns]
    if missing:
        raise ValueError(f"ours lacks the column(s) {missing}")
    rows = []
    for _, o in ours[ours["converged"].astype(bool)].iterrows():
        match = reference[reference["condition"] == o["condition"]]
        if match.empty:
            continue
        ref = match.iloc[0]
        speed = float(ref["speed"])
        common = "ours: uniform blades, constant cd0, linear twist, no ground effect"
        if speed > 0.0 and fuselage_fx is not None:
            per_m2 = 0.5 * float(ref["rho"]) * speed ** 3 / 1e3
            common += (f"; our flat plate {fuselage_fx:.1f} m^2 costs {per_m2 * fuselage_fx:.0f} kW here, "
                       f"{per_m2:.0f} kW per m^2")
        figures = (
            ("power, engine output", float(ref["power_engines"]),
             "GENHEL: both engines' output, includes drive and accessory losses ours lacks"),
            ("power, hub required torque x Omega", float(ref["torque_hub"]) * omega / 1e3,
             "GENHEL: all load torque referred to the hub, at our rotor speed"),
        )
        for quantity, measured, note in figures:
            value = float(o["power_total"])
            rows.append({"condition": o["condition"], "speed": speed, "speed_kt": speed / KNOT,
                         "quantity": quantity, "ours": value, "measured": measured,
                         "difference": value - measured, "relative_difference": (value - measured) / measured,
                         "unit": "kW", "source": "NASA TM-100991 Table B.1 (GENHEL UH-60A)",
                         "explanation": f"{note}; {common}"})
    return pd.DataFrame(rows, columns=["condition", "speed", "speed_kt", "quantity", "ours", "measured",
                                       "difference", "relative_difference", "unit", "source", "explanation"])


def uh60a_validation(*, aircraft=uh60_single_rotor, inflow=PittPeters, match_weight=True, path=REFERENCE_FILE):
    """Our UH-60-like trim power against the published UH-60A trims, in one call.

    Parameters
    ----------
    aircraft, inflow, match_weight
        As :func:`ours_at_reference`.
    path : str or Path
        The reference file (:func:`reference_trims`).

    Returns
    -------
    pandas.DataFrame
        :func:`compare_power`'s table, at the aircraft's main rotor speed.

    Examples
    --------
    >>> t = uh60a_validation()
    >>> len(t), sorted(set(t["condition"]))
    (4, ['hover', 'level_80kt'])
    """
    reference = reference_trims(path)
    ours = ours_at_reference(reference, aircraft=aircraft, inflow=inflow, match_weight=match_weight)
    cfg = aircraft()
    return compare_power(reference, ours, omega=float(cfg.rotors[0].omega), fuselage_fx=float(cfg.fuselage_fx))


def plot_uh60a_validation(table, sweep=None):
    """Figure: trimmed power against speed, the reference's two figures and ours.

    Parameters
    ----------
    table : pandas.DataFrame
        From :func:`compare_power` or :func:`uh60a_validation`.
    sweep : pandas.DataFrame, optional
        A trim sweep table (``speed`` [m/s], ``converged``, ``power_total`` [kW]) drawn
        as a line, e.g. our aircraft at its own weight.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> t = pd.DataFrame({"condition": ["hover"] * 2, "speed_kt": [0.0, 0.0], "ours": [1300.0] * 2,
    ...                   "measured": [1358.8, 1203.1], "quantity": ["power, engine output",
    ...                   "power, hub required torque x Omega"]})
    >>> len(plot_uh60a_validation(t).axes)
    1
    """
    from matplotlib.figure import Figure
    fig = Figure(figsize=(6.5, 4.2), layout="constrained")
    ax = fig.subplots()
    if sweep is not None:
        s = sweep[sweep["converged"].astype(bool)]
        ax.plot(s["speed"] / KNOT, s["power_total"], "-", color="0.6", lw=1.2,
                label="ours, trim sweep (own weight)")
    for (quantity, group), marker in zip(table.groupby("quantity", sort=False), ("s", "D")):
        ax.plot(group["speed_kt"], group["measured"], marker, mfc="none", ms=8, ls="none",
                label=f"GENHEL UH-60A, {quantity.removeprefix('power, ')}")
    ours = table.drop_duplicates("condition")
    ax.plot(ours["speed_kt"], ours["ours"], "o", color="C3", ms=7, ls="none", label="ours at the reference weight")
    ax.set(xlabel="true airspeed [kt]", ylabel="power [kW]",
           title="UH-60-like trim power against NASA TM-100991 Table B.1")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return fig
