"""Are the identification data converged in the wake's numerical settings?

:func:`wake_setting_sensitivity` sweeps the same controls with the same seeds on
wakes that differ in one or more :class:`aircraft.wake.WakeSettings` fields (the
free-wake length, the far-wake length, the time step, ...), and compares each
variant's single-input frequency responses (inflow over control, chirp-z, with
coherence) with the base wake's at chosen frequencies. A feature of the data that
moves with a numerical setting is the wake's, not the rotor's, and no inflow
model should be asked to fit it.

::

    base WakeSettings ─┬─ run_sweeps(controls) ─► frequency_response ─┐
    variant settings ──┴─ run_sweeps(controls) ─► frequency_response ─┴─► table of
                                                  |H| [dB], phase [deg], coherence,
                                                  differences to the base

Used by ``studies/wake_length_check.py`` (is the coaxial hover cyclic data's
low-frequency phase converged in wake length?).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, fields, replace

import numpy as np
import pandas as pd

__all__ = ["WakeSensitivityResult", "wake_setting_sensitivity"]


@dataclass
class WakeSensitivityResult:
    """Outcome of :func:`wake_setting_sensitivity`.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per variant, control, output and frequency: ``variant``, ``control``,
        ``output``, ``omega_rad_s``, ``mag_db``, ``phase_deg``, ``coherence``,
        ``d_mag_db`` and ``d_phase_deg`` (variant minus base, phase wrapped to
        +-180 deg; zero for the base).
    settings : dict
        ``{variant label: the WakeSettings fields it changes}``.
    wall_s : dict
        ``{variant label: wall time of its wake runs [s]}`` (about 0 when cached).
    """

    table: pd.DataFrame
    settings: dict
    wall_s: dict

    def to_pandas(self) -> pd.DataFrame:
        return self.table.copy()

    def max_difference(self, w_lo=0.0, w_hi=np.inf, coherence_min=0.0) -> pd.DataFrame:
        """Largest |d_mag_db| and |d_phase_deg| per variant, control and output over
        ``w_lo <= omega <= w_hi`` [rad/s], at points where both the variant's and the
        base's coherence reach ``coherence_min``."""
        t = self.table[(self.table.omega_rad_s >= w_lo) & (self.table.omega_rad_s <= w_hi)
                       & (self.table.coherence >= coherence_min) & (self.table.base_coherence >= coherence_min)]
        t = t[t.variant != "base"]
        return (t.assign(abs_d_mag_db=t.d_mag_db.abs(), abs_d_phase_deg=t.d_phase_deg.abs())
                .groupby(["variant", "control", "output"], sort=False)[["abs_d_mag_db", "abs_d_phase_deg"]]
                .max().reset_index())

    def plot(self, fig=None):
        """Magnitude, phase and coherence against frequency, one column per
        (control, output), every variant overlaid; a Figure."""
        from matplotlib.figure import Figure
        pairs = list(dict.fromkeys(zip(self.table.control, self.table.output)))
        fig = fig or Figure(figsize=(3.4 * len(pairs), 7.5), constrained_layout=True)
        axes = fig.subplots(3, len(pairs), squeeze=False, sharex=True)
        for k, (c, o) in enumerate(pairs):
            for label, t in self.table[(self.table.control == c) & (self.table.output == o)].groupby(
                    "variant", sort=False):
                axes[0, k].semilogx(t.omega_rad_s, t.mag_db, label=label)
                axes[1, k].semilogx(t.omega_rad_s, t.phase_deg)
                axes[2, k].semilogx(t.omega_rad_s, t.coherence)
            axes[0, k].set_title(f"{o} / {c}", fontsize=9)
            axes[2, k].set_xlabel("omega [rad/s]")
            for ax in axes[:, k]:
                ax.grid(True, which="both", alpha=0.3)
        axes[0, 0].set_ylabel("|H| [dB]")
        axes[1, 0].set_ylabel("phase [deg]")
        axes[2, 0].set_ylabel("coherence [-]")
        axes[0, 0].legend(fontsize=7)
        return fig


def _wrap_deg(x):
    return (np.asarray(x) + 180.0) % 360.0 - 180.0


def wake_setting_sensitivity(config, variants, *, base=None, ct=None, trim=None, controls, outputs,
                             seeds=None, frequencies=None, sweep_s=45.0, amplitude=math.radians(1.0), w_min=0.5,
                             w_max=30.0, n_jobs=2, cache_dir="default", progress=True):
    """Frequency responses of the same sweeps on wakes that differ in their settings.

    Parameters
    ----------
    config : aircraft.AircraftConfig
    variants : dict
        ``{label: {WakeSettings field: value, ...}}``: what each variant changes in
        ``base``. At least one; labels must not be ``"base"``.
    base : aircraft.wake.WakeSettings, optional
        The reference wake (default: the defaults).
    ct, trim
        Trim request, as for :func:`aircraft.identify_inflow` (system C_T of a
        coaxial: split equally, torques balanced).
    controls : list of str
        Controls swept, one record each.
    outputs : list of str
        Wake signals whose response to each control is compared.
    seeds : list of int, optional
        Sweep seed of each control (default 0, 1, ...), the same on every wake so
        that the inputs are identical; pass the identification's to reuse its records.
    frequencies : sequence of float, optional
        Frequencies [rad/s] tabulated (nearest response frequency); default every
        response frequency.
    sweep_s, amplitude, w_min, w_max
        Sweep length [s], amplitude [rad] and band [rad/s].
    n_jobs, cache_dir, progress
        As for :func:`aircraft.wake.run_sweeps`.

    Returns
    -------
    WakeSensitivityResult

    Raises
    ------
    ValueError
        No variant, a variant named ``"base"``, or a field WakeSettings lacks.
    """
    from aircraft.wake import FlightCondition, SweepSpec, WakeSettings, run_sweeps
    from flightid import frequency_response

    from .pipeline import _trim_request

    if not variants:
        raise ValueError("variants must name at least one changed wake setting")
    if "base" in variants:
        raise ValueError("'base' is the reference wake's label; name the variant otherwise")
    seeds = list(range(len(controls))) if seeds is None else [int(k) for k in seeds]
    if len(seeds) != len(controls):
        raise ValueError(f"seeds needs one value per control ({len(controls)}), got {len(seeds)}")
    known = {f.name for f in fields(WakeSettings)}
    for label, change in variants.items():
        bad = sorted(set(change) - known)
        if bad or not change:
            raise ValueError(f"variant {label!r}: {'unknown WakeSettings fields ' + str(bad) if bad else 'no change'}"
                             f" (fields: {sorted(known)})")
    base = base or WakeSettings()
    wakes = {"base": base, **{label: replace(base, **change) for label, change in variants.items()}}
    specs = [SweepSpec(c, kind="sweep", amplitude=amplitude, duration=sweep_s, w_min=w_min, w_max=w_max, seed=k)
             for k, c in zip(seeds, controls)]
    trim_req = _trim_request(config, ct, trim)
    rows, walls, ref = [], {}, {}
    for label, ws in wakes.items():
        t0 = time.perf_counter()
        runs = run_sweeps(config, ws, FlightCondition(), specs, trim=trim_req, n_jobs=n_jobs,
                          cache_dir=cache_dir, progress=progress)
        walls[label] = time.perf_counter() - t0
        for spec in specs:
            df = runs[spec.name]
            y = (df[outputs] - df[outputs].iloc[0]).to_numpy()
            u = (df[spec.control] - df[spec.control].iloc[0]).to_numpy()
            r = frequency_response(df["t"].to_numpy(), u, y, w_min=w_min, w_max=w_max, input_name=spec.control,
                                   output_names=list(outputs))
            w = np.asarray(r.omega)
            idx = (np.arange(w.size) if frequencies is None
                   else np.unique([int(np.argmin(abs(w - f))) for f in frequencies]))
            for i, out in enumerate(outputs):
                h, coh = r.frdata[i, 0, idx], r.coherence[i, 0, idx]
                if label == "base":
                    ref[(spec.control, out)] = (h, coh)
                h0, c0 = ref[(spec.control, out)]
                for k in range(idx.size):
                    rows.append({"variant": label, "control": spec.control, "output": out,
                                 "omega_rad_s": float(w[idx[k]]), "mag_db": 20 * np.log10(abs(h[k])),
                                 "phase_deg": float(np.degrees(np.angle(h[k]))), "coherence": float(coh[k]),
                                 "base_coherence": float(c0[k]),
                                 "d_mag_db": 20 * np.log10(abs(h[k]) / abs(h0[k])),
                                 "d_phase_deg": float(_wrap_deg(np.degrees(np.angle(h[k] / h0[k]))))})
    return WakeSensitivityResult(pd.DataFrame(rows), {k: dict(v) for k, v in variants.items()}, walls)
