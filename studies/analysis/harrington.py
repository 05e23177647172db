"""Hover power of Harrington's rotor 2 (NACA TN-2318), single and coaxial, against our wake.

::

    harrington_rotor2(tip_speed, coaxial)   the rotor as an AircraftConfig (real blades)
    measured_points(), faired_curves()      the report's digitised Fig. 8 (data/harrington_rotor2)
    hover_power(config, ct_values)          trimmed C_T, C_Q of our wake at each thrust
    errors_at_points(ours, points)          our C_Q at each measured C_T and the error
    interference(...)                       coaxial against isolated rotors, beside momentum theory
    profile_split(points, inviscid, sigma)  the measured power less our induced power: the profile power
                                            and mean drag coefficient the data ask of the blade

The blade inputs come from the report's geometry and published section data,
the same for every point and both tip speeds (nothing is fitted to the power data):

* planform: constant chord 18 in, untwisted, rigid hub (no flapping), root
  cut-out 0.20 R where the aerofoil starts (r = 30 in);
* sections: symmetric NACA 4-digit, t/c = 30.6 - 0.104 r [%] (r in inches) from
  the report, so 27.5 % at the root cut-out and 15 % at the tip; drag from
  :func:`aircraft.blade.naca4_symmetric_drag` (fully turbulent skin friction with
  Hoerner's thickness form factor and Bailey's angle-of-attack terms) at each
  section's Reynolds number; lift slope 5.73 per rad (0.9 x 2 pi) with the
  Prandtl-Glauert factor (tip Mach number 0.35 at 392 ft/s);
* tip loss: none imposed (B = 1): the lifting line's free tip vortex carries the
  tip loss itself; the report's B = 0.97 belongs to its momentum theory.

The coaxial is trimmed to its total thrust with equal torques (the test's yaw
trim); C_T and C_Q are the totals of both rotors on one disc, as in the report.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd

from aircraft.blade import BladeModel, Polar
from aircraft.configs import FT, AircraftConfig, RotorConfig
from aircraft.wake import FreeVortexWake, WakeSettings
from aircraft.wake.trim import run_wake, trim_wake

__all__ = ["RADIUS", "CHORD", "SPACING", "HARRINGTON_BLADE", "harrington_rotor2", "measured_points",
           "faired_curves", "hover_power", "errors_at_points", "interference", "induced_interference",
           "MOMENTUM_BOUNDS", "INVISCID_BLADE", "profile_split"]

DATA = Path(__file__).resolve().parent / "data" / "harrington_rotor2"
RADIUS = 12.5 * FT            #: rotor radius [m]
CHORD = 18.0 / 12.0 * FT      #: blade chord [m]
SPACING = 2.0 * FT            #: rotor spacing [m] (0.16 R)
ROOT_CUTOUT = 30.0 / 150.0    #: r/R where the aerofoil starts [-]


def _thickness(r):
    """The report's t/c = 30.6 - 0.104 r [%], r in inches, at r/R = ``r`` [-]."""
    return (30.6 - 0.104 * 150.0 * r) / 100.0


#: the blade of rotor 2: NACA 4-digit thickness taper, turbulent drag, Prandtl-Glauert lift
HARRINGTON_BLADE = BladeModel(stations=(ROOT_CUTOUT, 1.0),
                              thickness=(_thickness(ROOT_CUTOUT), _thickness(1.0)), compressibility=True)

#: the same lift with drag-free sections: the induced power alone
INVISCID_BLADE = BladeModel(polar=Polar(alpha=(-math.radians(12.0), math.radians(12.0)),
                                        cl=(-5.73 * math.radians(12.0), 5.73 * math.radians(12.0)), cd=(0.0, 0.0)),
                            compressibility=True)

#: momentum theory's induced-power interference factor kappa_int of a coaxial with
#: equal thrusts (Leishman & Syal, J. AHS 53(3), 2008): lower rotor in the upper's
#: fully contracted wake (large spacing), and the two rotors in one plane
MOMENTUM_BOUNDS = {"lower rotor in the contracted upper wake": 1.2808, "rotors in one plane": math.sqrt(2.0)}


def harrington_rotor2(tip_speed_ft_s, coaxial, blade=HARRINGTON_BLADE):
    """Rotor 2 of NACA TN-2318 as an aircraft configuration.

    Parameters
    ----------
    tip_speed_ft_s : float
        Tip speed Omega R [ft/s].
    coaxial : bool
        Both rotors (upper clockwise seen from above, 0.16 R above the lower) or
        the lower rotor alone.
    blade : BladeModel or None
        The blade (default :data:`HARRINGTON_BLADE`); None: the classical blade
        with the default ``cd0``.

    Returns
    -------
    AircraftConfig

    Examples
    --------
    >>> cfg = harrington_rotor2(392.0, coaxial=True)
    >>> [r.name for r in cfg.rotors], round(cfg.rotors[0].solidity, 4)
    (['U', 'L'], 0.0764)
    """
    omega = tip_speed_ft_s * FT / RADIUS
    common = dict(radius=RADIUS, omega=omega, n_blades=2, chord=CHORD, twist=0.0, root_cutout=ROOT_CUTOUT,
                  hinge_offset=0.0, flap_frequency=5.0, blade=blade)
    lower = RotorConfig(name="L" if coaxial else "", direction=1, hub_position=(0.0, 0.0, -2.0), **common)
    rotors = (lower,)
    if coaxial:
        upper = RotorConfig(name="U", direction=-1, hub_position=(0.0, 0.0, -2.0 - SPACING), **common)
        rotors = (upper, lower)
    return AircraftConfig(name=f"Harrington rotor 2 {'coaxial' if coaxial else 'single'} {tip_speed_ft_s:g} ft/s",
                          rotors=rotors, mass=1000.0, Ixx=1.0, Iyy=1.0, Izz=1.0,
                          trim_ct=(0.002,) * len(rotors))


def measured_points():
    """The report's test points: configuration, tip_speed_ft_s, sigma, CQ, CT, flag."""
    return pd.read_csv(DATA / "fig8_rotor2_points.csv")


def faired_curves():
    """The report's faired curves: configuration (coaxial or single), CT, CQ."""
    df = pd.read_csv(DATA / "fig8_rotor2_curves.csv")
    df["configuration"] = np.where(df.configuration.str.startswith("coaxial"), "coaxial", "single")
    return df


def hover_power(config, ct_values, settings=None, progress=None, average_revs=6):
    """Trimmed hover thrust and torque coefficients of our wake.

    Parameters
    ----------
    config : AircraftConfig
        One rotor (trimmed to thrust) or a coaxial (total thrust, equal torques).
    ct_values : sequence of float
        Thrust-coefficient targets [-] (totals on one disc for a coaxial).
    settings : WakeSettings, optional
        Default: the default resolution.
    progress : callable, optional
        Called with a line of text after each point.
    average_revs : float
        Revolutions marched at the trimmed controls over which C_T and C_Q are
        averaged: the hover wake of a two-bladed rotor is not periodic (its
        revolution averages scatter by a few per cent), so the pairs are
        averaged over more than the trim's two revolutions.

    Returns
    -------
    pandas.DataFrame
        ``CT_target, CT, CQ`` (totals) and, for a coaxial, ``CT_U, CT_L, CQ_U, CQ_L``;
        ``converged`` [bool].
    """
    settings = settings if settings is not None else WakeSettings()
    coaxial = len(config.rotors) == 2
    rows = []
    for ct in ct_values:
        wake = FreeVortexWake(config, settings)
        if coaxial:
            tr = trim_wake(wake, ct=float(ct), mode="torque_balance", raise_on_failure=False)
        else:
            tr = trim_wake(wake, ct=float(ct), raise_on_failure=False)
        o = run_wake(wake, duration=average_revs * 2.0 * math.pi / wake.omega).mean()
        row = {"CT_target": float(ct), "converged": bool(tr.converged)}
        if coaxial:
            row.update(CT=o["CT_U"] + o["CT_L"], CQ=o["CQ_U"] + o["CQ_L"], CT_U=o["CT_U"], CT_L=o["CT_L"],
                       CQ_U=o["CQ_U"], CQ_L=o["CQ_L"])
        else:
            row.update(CT=o["CT"], CQ=o["CQ"])
        rows.append(row)
        if progress is not None:
            progress(f"{config.name}: C_T {row['CT']:.5f} C_Q {row['CQ']:.7f}")
    return pd.DataFrame(rows)


def _interpolate(ours, ct):
    """Our C_Q at ``ct`` by monotone cubic interpolation of the trimmed (C_T, C_Q) pairs."""
    from scipy.interpolate import PchipInterpolator
    d = ours.sort_values("CT")
    return PchipInterpolator(d.CT.to_numpy(), d.CQ.to_numpy(), extrapolate=False)(ct)


def errors_at_points(ours, points):
    """Our C_Q at each measured C_T and the relative error.

    Parameters
    ----------
    ours : pandas.DataFrame
        :func:`hover_power` of one configuration and tip speed.
    points : pandas.DataFrame
        Measured ``CT, CQ`` of the same configuration and tip speed.

    Returns
    -------
    pandas.DataFrame
        ``points`` with ``CQ_ours`` and ``error = CQ_ours / CQ - 1`` (NaN outside the
        thrusts we ran) and ``in_band`` (0.002 <= C_T <= 0.006).

    Examples
    --------
    >>> ours = pd.DataFrame({"CT": [0.002, 0.003, 0.004], "CQ": [2e-4, 3e-4, 4e-4]})
    >>> pts = pd.DataFrame({"CT": [0.0025, 0.005], "CQ": [2.5e-4, 5e-4]})
    >>> errors_at_points(ours, pts).error.round(6).tolist()
    [0.0, nan]
    """
    out = points.copy()
    out["CQ_ours"] = _interpolate(ours, out.CT.to_numpy())
    out["error"] = out.CQ_ours / out.CQ - 1.0
    out["in_band"] = (out.CT >= 0.002) & (out.CT <= 0.006)
    return out


def interference(coaxial, single, faired):
    """Coaxial power against the two rotors working in isolation.

    The ratio ``CQ_coax(C_T) / (2 CQ_single(C_T / 2))`` (total power, both rotors
    on one disc, the same definition for ours and the measured faired curves), and
    for ours the induced-power interference factor ``kappa_int`` when the
    inputs carry the inviscid runs.

    Parameters
    ----------
    coaxial, single : pandas.DataFrame
        :func:`hover_power` of the coaxial and of the single rotor at one tip speed.
    faired : pandas.DataFrame
        :func:`faired_curves`.

    Returns
    -------
    pandas.DataFrame
        ``CT, ratio_ours, ratio_measured``.
    """
    fc = faired[faired.configuration == "coaxial"].sort_values("CT")
    fs = faired[faired.configuration == "single"].sort_values("CT")
    rows = []
    for ct in np.arange(0.002, 0.00601, 0.0005):
        ours = _interpolate(coaxial, ct) / (2.0 * _interpolate(single, ct / 2.0))
        meas = np.interp(ct, fc.CT, fc.CQ) / (2.0 * np.interp(ct / 2.0, fs.CT, fs.CQ))
        rows.append({"CT": round(ct, 4), "ratio_ours": float(ours), "ratio_measured": float(meas)})
    return pd.DataFrame(rows)


def induced_interference(coaxial_inviscid, single_inviscid):
    """kappa_int = coaxial induced power / the two rotors' isolated induced powers.

    Parameters
    ----------
    coaxial_inviscid : pandas.DataFrame
        :func:`hover_power` of the coaxial with drag-free sections (``CT_U, CT_L``).
    single_inviscid : pandas.DataFrame
        :func:`hover_power` of the single rotor with drag-free sections, over thrusts
        covering each rotor's share.

    Returns
    -------
    pandas.DataFrame
        ``CT, CT_U, CT_L, kappa_int``.
    """
    rows = []
    for _, r in coaxial_inviscid.iterrows():
        isolated = _interpolate(single_inviscid, r.CT_U) + _interpolate(single_inviscid, r.CT_L)
        rows.append({"CT": r.CT, "CT_U": r.CT_U, "CT_L": r.CT_L, "kappa_int": float(r.CQ / isolated)})
    return pd.DataFrame(rows)


def profile_split(points, inviscid, sigma, ours=None, tolerance=0.05):
    """Split each measured power into our induced power and the profile power left for the blade.

    At each measured point ``C_Q0 = C_Q - C_Qi`` with ``C_Qi`` our drag-free wake's
    torque at the same thrust, and the profile power's equivalent mean drag
    coefficient ``c_d,eq = 8 C_Q0 / sigma`` (uniform drag on a full-span rectangular
    blade, ``C_Q0 = sigma c_d / 8``).  ``cd_eq_low, cd_eq_high`` bound the mean drag
    coefficient that puts our power within ``tolerance`` of the point's (our induced
    power held): one section polar can meet every point only if these windows,
    read at each point's blade loading and Reynolds number, admit it.

    Parameters
    ----------
    points : pandas.DataFrame
        Measured ``CT, CQ`` of one configuration and tip speed.
    inviscid : pandas.DataFrame
        :func:`hover_power` of the same rotor with :data:`INVISCID_BLADE`.
    sigma : float
        Solidity of the C_Q normalisation [-] (coaxial: both rotors, 0.152).
    ours : pandas.DataFrame, optional
        :func:`hover_power` with the real blade: adds our profile power
        ``CQ0_ours = C_Q - C_Qi`` and ``profile_ratio`` (the factor on it the point asks for).
    tolerance : float
        Relative power error of the ``cd_eq`` window [-].

    Returns
    -------
    pandas.DataFrame
        ``points`` with ``CQ_induced, CQ0, cd_eq, cd_eq_low, cd_eq_high`` (NaN outside
        the thrusts run) and, with ``ours``, ``CQ0_ours, cd_eq_ours, profile_ratio``.

    Examples
    --------
    >>> inv = pd.DataFrame({"CT": [0.002, 0.004], "CQ": [1e-4, 2e-4]})
    >>> pts = pd.DataFrame({"CT": [0.003], "CQ": [2.5e-4]})
    >>> s = profile_split(pts, inv, 0.08)
    >>> round(float(s.CQ0[0]), 7), round(float(s.cd_eq[0]), 4)
    (0.0001, 0.01)
    """
    if not (isinstance(sigma, (int, float)) and not isinstance(sigma, bool) and sigma > 0):
        raise ValueError(f"sigma must be a positive solidity, got {sigma!r}")
    if not (isinstance(tolerance, (int, float)) and 0 <= tolerance < 1):
        raise ValueError(f"tolerance must be a fraction in [0, 1), got {tolerance!r}")
    out = points.copy()
    ct = out.CT.to_numpy()
    out["CQ_induced"] = _interpolate(inviscid, ct)
    out["CQ0"] = out.CQ - out.CQ_induced
    out["cd_eq"] = 8.0 * out.CQ0 / sigma
    out["cd_eq_low"] = 8.0 * ((1.0 - tolerance) * out.CQ - out.CQ_induced) / sigma
    out["cd_eq_high"] = 8.0 * ((1.0 + tolerance) * out.CQ - out.CQ_induced) / sigma
    if ours is not None:
        out["CQ0_ours"] = _interpolate(ours, ct) - out.CQ_induced
        out["cd_eq_ours"] = 8.0 * out.CQ0_ours / sigma
        out["profile_ratio"] = out.CQ0 / out.CQ0_ours
    return out
