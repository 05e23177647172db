"""Hover tip-vortex trajectory of our free wake against Landgrebe's generalised wake.

::

    landgrebe_radius(age, ct)                        r/R of the tip vortex [-]
    landgrebe_descent_rates(ct, sigma, n_blades, twist_deg)   k1, k2 [1/rad]
    landgrebe_height(age, ct, sigma, n_blades, twist_deg)     z/R of the tip vortex (up positive) [-]
    tip_vortex_geometry(config, ct_values, ...)      our trimmed wake beside Landgrebe's, table + summary

Reference: Landgrebe, A. J., "The Wake Geometry of a Hovering Helicopter Rotor
and Its Influence on Rotor Performance", Journal of the American Helicopter
Society 17(4), 1972 -- an empirical fit to smoke-flow visualisations of model
rotors of several blade numbers, twists and aspect ratios, in the form given by
Leishman, Principles of Helicopter Aerodynamics, 2nd ed., 2006, Sec. 10.7:

* radial contraction ``r/R = A + (1 - A) exp(-Lambda psi_w)``, ``A = 0.78``,
  ``Lambda = 0.145 + 27 C_T``;
* axial displacement ``z/R = k1 psi_w`` up to the first blade passage
  ``psi_w = 2 pi / N_b`` and ``k1 (2 pi / N_b) + k2 (psi_w - 2 pi / N_b)``
  beyond, ``k1 = -0.25 (C_T / sigma + 0.001 theta_tw)``,
  ``k2 = -(1.41 + 0.0141 theta_tw) sqrt(C_T / 2)``, with the linear twist
  ``theta_tw`` in degrees, negative nose-down (wash-out).

The same constants and sign conventions are used by the wake's own prescribed
starting geometry (:mod:`aircraft.wake.initial_wake`) and by independent public
free-wake codes. Our markers are averaged over blades and over the revolutions
after trim (the measured positions are time averages of smoke filaments), and
only the free part of the wake (not the buffer) is compared.
"""
from __future__ import annotations

import math
from numbers import Real

import numpy as np
import pandas as pd

from aircraft.wake import FreeVortexWake, WakeSettings

__all__ = ["CONTRACTION_A", "landgrebe_radius", "landgrebe_descent_rates", "landgrebe_height",
           "tip_vortex_geometry", "WakeGeometry"]

#: Landgrebe's asymptotic contraction ratio r/R [-]
CONTRACTION_A = 0.78


def _positive(name, value, hi=None):
    if isinstance(value, bool) or not isinstance(value, Real) or not math.isfinite(value) or value <= 0:
        raise ValueError(f"{name} must be a positive finite number, got {value!r}")
    if hi is not None and value > hi:
        raise ValueError(f"{name} must be at most {hi}, got {value!r}")
    return float(value)


def _ages(age):
    a = np.asarray(age, dtype=float)
    if not np.all(np.isfinite(a)) or np.any(a < 0):
        raise ValueError("age must be finite and non-negative (wake age [rad])")
    return a


def _twist(twist_deg):
    if isinstance(twist_deg, bool) or not isinstance(twist_deg, Real) or not -45.0 <= twist_deg <= 45.0:
        raise ValueError(f"twist_deg must be a linear twist in [-45, 45] deg, got {twist_deg!r}")
    return float(twist_deg)


def landgrebe_radius(age, ct):
    """Landgrebe's radial position of the tip vortex against wake age.

    Parameters
    ----------
    age : array_like
        Wake age psi_w >= 0 [rad].
    ct : float
        Rotor thrust coefficient C_T > 0 [-] (at most 0.05).

    Returns
    -------
    ndarray
        r/R [-], the shape of ``age``.

    Examples
    --------
    >>> float(landgrebe_radius(0.0, 0.006))
    1.0
    >>> round(float(landgrebe_radius(2 * np.pi, 0.006)), 4)
    0.812
    """
    a = _ages(age)
    lam = 0.145 + 27.0 * _positive("ct", ct, hi=0.05)
    return CONTRACTION_A + (1.0 - CONTRACTION_A) * np.exp(-lam * a)


def landgrebe_descent_rates(ct, sigma, n_blades, twist_deg):
    """Landgrebe's axial descent rates of the tip vortex before and after the first blade passage.

    Parameters
    ----------
    ct : float
        Thrust coefficient C_T > 0 [-] (at most 0.05).
    sigma : float
        Rotor solidity N_b c / (pi R) > 0 [-] (at most 1).
    n_blades : int
        Number of blades N_b >= 1 (not used by the rates; checked for symmetry with
        :func:`landgrebe_height`).
    twist_deg : float
        Linear blade twist, tip minus root [deg], negative nose-down.

    Returns
    -------
    k1, k2 : float
        d(z/R)/d(psi_w) before and after psi_w = 2 pi / N_b [1/rad] (negative: down).

    Examples
    --------
    >>> k1, k2 = landgrebe_descent_rates(0.006, 0.08, 4, -10.0)
    >>> round(k1, 6), round(k2, 6)
    (-0.01625, -0.069506)
    """
    _positive("ct", ct, hi=0.05)
    _positive("sigma", sigma, hi=1.0)
    _blades(n_blades)
    tw = _twist(twist_deg)
    k1 = -0.25 * (ct / sigma + 0.001 * tw)
    k2 = -(1.41 + 0.0141 * tw) * math.sqrt(ct / 2.0)
    return k1, k2


def _blades(n_blades):
    if isinstance(n_blades, bool) or not isinstance(n_blades, (int, np.integer)) or n_blades < 1:
        raise ValueError(f"n_blades must be an integer >= 1, got {n_blades!r}")
    return int(n_blades)


def landgrebe_height(age, ct, sigma, n_blades, twist_deg):
    """Landgrebe's axial position of the tip vortex (up positive, from the disc) against wake age.

    Parameters
    ----------
    age : array_like
        Wake age psi_w >= 0 [rad].
    ct, sigma, n_blades, twist_deg
        As in :func:`landgrebe_descent_rates`.

    Returns
    -------
    ndarray
        z/R [-], the shape of ``age`` (negative below the disc).

    Examples
    --------
    >>> z = landgrebe_height([np.pi / 2, np.pi], 0.006, 0.08, 4, -10.0)
    >>> np.round(z, 4).tolist()
    [-0.0255, -0.1347]
    """
    a = _ages(age)
    k1, k2 = landgrebe_descent_rates(ct, sigma, n_blades, twist_deg)
    zb = 2.0 * math.pi / _blades(n_blades)
    return np.where(a <= zb, k1 * a, k1 * zb + k2 * (a - zb))


class WakeGeometry:
    """Our tip-vortex trajectory beside Landgrebe's (returned by :func:`tip_vortex_geometry`).

    Attributes
    ----------
    table : pandas.DataFrame
        One row per thrust and wake age: ``ct`` (target), ``ct_trimmed``,
        ``age_rad``, ``age_deg``, ``r_ours``, ``r_landgrebe``, ``dr``
        (ours minus Landgrebe), ``z_ours``, ``z_landgrebe``, ``dz`` [-, per R].
    summary : pandas.DataFrame
        One row per thrust: r/R at the first blade passage and averaged over the
        far window (ours, Landgrebe's), the mean inflow ratio ``lam0`` over the
        averaging revolutions [-], k1 and k2 fitted to our markers and
        Landgrebe's, the rotor's sigma, N_b, twist [deg] and the wall time [s].
    """

    def __init__(self, table, summary):
        self.table = table
        self.summary = summary

    def plot(self, other=None, labels=("ours", "variant")):
        """r/R and z/R against wake age [deg]: ours (markers), Landgrebe (lines), one colour per C_T.

        Parameters
        ----------
        other : WakeGeometry, optional
            A second wake (e.g. other settings) drawn with crosses.
        labels : (str, str)
            Legend names of this wake and of ``other``.

        Returns
        -------
        matplotlib.figure.Figure
        """
        from matplotlib.figure import Figure
        fig = Figure(figsize=(10, 5.0))
        ax_r, ax_z = fig.subplots(1, 2)
        colours = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple"]
        for i, (ct, g) in enumerate(self.table.groupby("ct", sort=True)):
            c = colours[i % len(colours)]
            for ax, key in ((ax_r, "r"), (ax_z, "z")):
                ax.plot(g.age_deg, g[f"{key}_landgrebe"], "-", color=c, lw=1.2,
                        label=f"C_T = {ct:.4f} Landgrebe" if key == "r" else None)
                ax.plot(g.age_deg, g[f"{key}_ours"], "o", color=c, ms=3,
                        label=f"{labels[0]}" if key == "r" else None)
                if other is not None:
                    h = other.table[np.isclose(other.table.ct, ct)]
                    ax.plot(h.age_deg, h[f"{key}_ours"], "x", color=c, ms=3,
                            label=f"{labels[1]}" if key == "r" else None)
        nb = int(self.summary.n_blades.iloc[0])
        for ax in (ax_r, ax_z):
            ax.axvline(360.0 / nb, color="0.6", ls=":", lw=0.8)
            ax.set_xlabel("wake age [deg]")
            ax.grid(alpha=0.3)
        ax_r.axhline(CONTRACTION_A, color="0.4", ls="--", lw=0.8)
        ax_r.set_ylabel("r/R [-]")
        ax_z.set_ylabel("z/R [-] (up positive)")
        ax_r.set_title("radial contraction (dotted: first blade passage)")
        ax_z.set_title("axial descent")
        handles, names = ax_r.get_legend_handles_labels()
        fig.legend(handles, names, loc="lower center", ncol=len(self.summary), fontsize=7)
        fig.tight_layout(rect=(0.0, 0.14, 1.0, 1.0))
        return fig


def _fit_rates(age, z, zb, far_age):
    """k1 through the origin to the first blade passage, k2 the least-squares slope beyond."""
    k1 = float(np.interp(zb, age, z)) / zb
    sel = (age >= zb) & (age <= far_age)
    k2 = float(np.polyfit(age[sel], z[sel], 1)[0]) if sel.sum() >= 2 else float("nan")
    return k1, k2


def tip_vortex_geometry(config, ct_values, settings=None, *, settle_revs=8, average_revs=4.0,
                        far_window=(2 * math.pi, 4 * math.pi), progress=False):
    """Trim a single rotor's free wake at each thrust and compare its tip vortex with Landgrebe's.

    Parameters
    ----------
    config : aircraft.configs.AircraftConfig
        A single-rotor configuration.
    ct_values : sequence of float
        Target thrust coefficients C_T [-].
    settings : aircraft.wake.WakeSettings, optional
        Wake settings (default ``WakeSettings()``).
    settle_revs : int
        Revolutions marched at the starting collective before the trim iterations
        (passed to the trim), so that the free wake has convected its prescribed
        start away.
    average_revs : float
        Revolutions marched after trim over which the markers are averaged [rev].
    far_window : (float, float)
        Wake-age window [rad] of the "far" contraction average and of the k2 fit
        (from the first blade passage up to its upper end); clipped to the free wake.
    progress : bool
        Print one line per thrust.

    Returns
    -------
    WakeGeometry
        The table and the summary (see :class:`WakeGeometry`).

    Examples
    --------
    >>> import math
    >>> from aircraft.configs import uh60_single_rotor
    >>> from aircraft.wake import WakeSettings
    >>> s = WakeSettings(azimuth_step=math.radians(30.0), wake_revolutions=1.0, n_elements=3,
    ...                  far_wake_revolutions=2.0)
    >>> g = tip_vortex_geometry(uh60_single_rotor(), [0.006], s, settle_revs=1,
    ...                         average_revs=0.25, far_window=(math.pi, 2 * math.pi))  # doctest: +SKIP
    >>> sorted(g.summary.columns)[:2]  # doctest: +SKIP
    ['ct', 'ct_trimmed']
    """
    import time
    settings = WakeSettings() if settings is None else settings
    cts = [_positive("ct_values", c, hi=0.05) for c in np.atleast_1d(ct_values).tolist()]
    if not cts:
        raise ValueError("ct_values must hold at least one thrust coefficient")
    _positive("average_revs", average_revs, hi=50.0)
    lo, hi = far_window
    if not 0 <= lo < hi:
        raise ValueError(f"far_window must be (lo, hi) wake ages with 0 <= lo < hi [rad], got {far_window!r}")
    rows, summary = [], []
    for ct in cts:
        t0 = time.perf_counter()
        wake = FreeVortexWake(config, settings)
        if len(wake.rotors) != 1:
            raise ValueError(f"config must have a single rotor, got {len(wake.rotors)}")
        tr = wake.trim(ct=ct, settle_revs=settle_revs)
        if not tr.converged:
            raise RuntimeError(f"wake trim did not converge at C_T = {ct}")
        n_steps = max(1, int(round(average_revs * settings.steps_per_rev)))
        acc = {"r": 0.0, "z": 0.0}

        def collect(w):
            acc["r"] = acc["r"] + w.tip_vortex_radius()[1][0]
            acc["z"] = acc["z"] + w.tip_vortex_height()[1][0]

        out = wake.march(n_steps, callback=collect)
        ages = wake.tip_vortex_radius()[0]
        free = ages <= ages[0] + settings.n_free * settings.azimuth_step + 1e-9
        age, r, z = ages[free], (acc["r"] / n_steps)[free], (acc["z"] / n_steps)[free]
        rot = wake.rotors[0]
        sigma = rot.nb * rot.chord / (math.pi * rot.R)
        tw = math.degrees(rot.twist)
        r_l = landgrebe_radius(age, ct)
        z_l = landgrebe_height(age, ct, sigma, rot.nb, tw)
        rows.append(pd.DataFrame({"ct": ct, "ct_trimmed": out["CT"], "age_rad": age, "age_deg": np.degrees(age),
                                  "r_ours": r, "r_landgrebe": r_l, "dr": r - r_l,
                                  "z_ours": z, "z_landgrebe": z_l, "dz": z - z_l}))
        zb = 2.0 * math.pi / rot.nb
        far_hi = min(hi, float(age[-1]))
        far = (age >= lo) & (age <= far_hi)
        # the markers start at the end of the rigid near wake; before it the wake is prescribed
        k1, k2 = _fit_rates(age, z, zb, far_hi)
        k1_l, k2_l = landgrebe_descent_rates(ct, sigma, rot.nb, tw)
        summary.append({"ct": ct, "ct_trimmed": out["CT"], "lam0": out["lam0"], "n_blades": rot.nb, "sigma": sigma, "twist_deg": tw,
                        "first_age_deg": math.degrees(age[0]),
                        "r_blade_passage_ours": float(np.interp(zb, age, r)),
                        "r_blade_passage_landgrebe": float(landgrebe_radius(zb, ct)),
                        "r_far_ours": float(r[far].mean()) if far.any() else float("nan"),
                        "r_far_landgrebe": float(r_l[far].mean()) if far.any() else float("nan"),
                        "far_window_deg": f"{math.degrees(lo):.0f}-{math.degrees(far_hi):.0f}",
                        "k1_ours": k1, "k1_landgrebe": k1_l, "k2_ours": k2, "k2_landgrebe": k2_l,
                        "wall_s": time.perf_counter() - t0})
        if progress:
            s = summary[-1]
            print(f"C_T {ct:.4f}: r(2pi/Nb) {s['r_blade_passage_ours']:.3f} vs {s['r_blade_passage_landgrebe']:.3f}, "
                  f"k2 {k2:.4f} vs {k2_l:.4f} ({s['wall_s']:.0f} s)", flush=True)
    return WakeGeometry(pd.concat(rows, ignore_index=True), pd.DataFrame(summary))
