"""The quasi-steady guard: an identified model's steady gain against held steps of the wake.

A model fitted over 1-25 rad/s says nothing about what it does below its band, and
that is where an aircraft's slow modes live. Our coaxial 12-state model, fitted on
1-25 rad/s, had far-wake poles at -0.018 and -0.286 1/s and a steady
lambda1s/C_L block 60-140x the wake's; flown in the aircraft it left an unstable
inflow-rotor mode (the ``coaxial-quasi-steady`` study). The guard holds a small step of
each swashplate control in the wake, averages the loads and inflow over a late
window, and compares the inflow change with what the model's DC gain predicts from
the load change of the same record::

    identified model (DC gain G)       wake, step in control c
               |                               |
               +------ G @ delta C  vs  delta lambda ------+
                                     |
                         QuasiSteadyCheck.table / passes()

The comparison needs no inversion of the load matrix, so any subset of controls
works; with hover symmetry the sine steps cover the cosine channels.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

__all__ = ["QuasiSteadyCheck", "quasi_steady_check"]


@dataclass
class QuasiSteadyCheck:
    """Measured and predicted steady inflow changes, per step and inflow output.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per (step control, output): ``control``; ``output``; ``wake`` (the
        inflow change the wake settled to, late window minus pre-step mean [-]);
        ``model`` (the model's DC gain times the record's load changes [-]);
        ``ratio`` (model / wake); ``on_axis`` (the output is the harmonic the
        control drives on its own rotor: lam0 for theta0, lam1s for theta1s, lam1c
        for theta1c).
    window : tuple of float
        Averaging window after the step [s].
    settling : pandas.DataFrame
        Per step and on-axis output: the inflow change averaged over an early
        window (1-2 s after the step) and the late one, and their ratio: how far
        the wake itself is from steady at the end of the record.
    amplitude : float
        Step size [rad].
    load_changes : pandas.DataFrame
        Per step (index ``control``): the late-window change of every load input of
        the model [-], what its DC gain was multiplied by.
    model_name : str
    wall_s : float
        Wall time of the wake runs and the check [s].
    """

    table: pd.DataFrame
    window: tuple
    settling: pd.DataFrame
    amplitude: float
    load_changes: pd.DataFrame = None
    model_name: str = ""
    wall_s: float = float("nan")
    notes: dict = field(default_factory=dict)

    def passes(self, tolerance=0.3) -> bool:
        """True when every on-axis steady change is predicted within ``tolerance``
        (relative, default 30 %) and with the right sign."""
        on = self.table[self.table.on_axis]
        return bool(len(on) and (np.abs(on.ratio - 1.0) <= tolerance).all())

    def worst_on_axis(self) -> pd.Series:
        """The on-axis row whose ratio is farthest from 1."""
        on = self.table[self.table.on_axis]
        return on.loc[(np.abs(on.ratio - 1.0)).idxmax()]

    def to_pandas(self) -> pd.DataFrame:
        """The comparison table (see :attr:`table`)."""
        return self.table.copy()

    def summary(self) -> str:
        w = self.worst_on_axis()
        verdict = "passes" if self.passes() else "FAILS"
        return (f"quasi-steady check of {self.model_name or 'the model'}: {self.amplitude:g} rad steps, "
                f"window {self.window[0]:g}-{self.window[1]:g} s; worst on-axis {w.output}/{w.control} "
                f"model/wake {w.ratio:.3g} -> {verdict} (30 %)\n"
                + self.table.to_string(index=False, float_format=lambda v: f"{v:.4g}"))

    def plot(self, fig=None):
        """Bars of the wake's and the model's steady inflow change per step and output; a Figure."""
        import matplotlib.pyplot as plt
        controls = list(dict.fromkeys(self.table.control))
        fig = fig or plt.figure(figsize=(3.2 * len(controls), 3.4))
        axes = fig.subplots(1, len(controls), squeeze=False)[0]
        for ax, c in zip(axes, controls):
            t = self.table[self.table.control == c]
            x = np.arange(len(t))
            ax.bar(x - 0.2, t.wake, 0.4, label="wake (held step)")
            ax.bar(x + 0.2, t.model, 0.4, label="model DC gain")
            ax.set_xticks(x, t.output, rotation=60, fontsize=7)
            ax.set_title(f"step {c}", fontsize=9)
            ax.axhline(0.0, color="k", lw=0.5)
            # the model's steady gain can be 100x the wake's: clip to keep the wake visible
            lim = 3.0 * max(float(np.abs(t.wake).max()), 1e-12)
            ax.set_ylim(-lim, lim)
            ax.grid(True, alpha=0.3)
        axes[0].set_ylabel("steady inflow change [-]")
        axes[0].legend(fontsize=7)
        fig.tight_layout()
        return fig


def _on_axis(control, output):
    harmonic = {"theta0": "lam0", "theta1s": "lam1s", "theta1c": "lam1c"}
    base, _, rotor = control.partition("_")
    o_base, _, o_rotor = output.partition("_")
    return harmonic.get(base) == o_base and rotor == o_rotor


def quasi_steady_check(model, config, ct=None, *, trim=None, settings=None, condition=None, controls=None,
                       amplitude=0.02, hold_s=10.0, window=(6.0, 10.0), ramp_s=0.1, step_at=0.5,
                       n_jobs=2, cache_dir="default", progress=True):
    """Compare an identified model's steady gain with held steps of the free wake.

    Parameters
    ----------
    model : IdentifiedModel or aircraft.inflow.IdentifiedInflow
        The model; its DC gain (``-C A^-1 B`` of its state space) maps the loads
        (and flap rates, zero in a steady state) to the inflow.
    config : aircraft.AircraftConfig
        The rotor(s) the model was identified on.
    ct : float, optional
        Trim thrust of the system, as for :func:`identify_inflow`.
    trim : dict, optional
        Full trim request (overrides ``ct``).
    settings : IdentificationSettings, optional
        Wake resolution; default the model's own (an :class:`IdentifiedModel`) or
        :class:`IdentificationSettings` ().
    condition : aircraft.wake.FlightCondition, optional
        Default hover.
    controls : list of str, optional
        Controls stepped, one record each; default the swashplate controls of the
        model's rotors with sine cyclic only (``theta0``, ``theta1s`` per rotor: the
        cosine channels repeat them in hover).
    amplitude : float
        Step size [rad]; the identification's sweep amplitude is 0.02.
    hold_s : float
        Record length [s].
    window : (float, float)
        Averaging window [s] after the step: late enough for the near wake to have
        settled, and the record is as long as its end.
    ramp_s, step_at : float
        Ramp time and step time [s].
    n_jobs, cache_dir, progress
        As for :func:`aircraft.wake.run_sweeps`.

    Returns
    -------
    QuasiSteadyCheck

    Raises
    ------
    ValueError
        For a window outside the record, a non-positive amplitude or an unknown
        model type.
    """
    import time
    from aircraft.inflow import IdentifiedInflow
    from aircraft.inflow.base import flap_rate_names
    from aircraft.wake import FlightCondition, SweepSpec, run_sweeps
    from .pipeline import IdentificationSettings, IdentifiedModel, _trim_request

    t0 = time.perf_counter()
    if isinstance(model, IdentifiedModel):
        inflow, settings, name = model.to_inflow(), settings or model.settings, model.name
    elif isinstance(model, IdentifiedInflow):
        inflow, settings, name = model, settings or IdentificationSettings(), getattr(model, "name", "")
    else:
        raise ValueError(f"model must be an IdentifiedModel or an IdentifiedInflow, got {type(model).__name__}")
    try:
        lo, hi = (float(w) for w in window)
    except (TypeError, ValueError) as err:
        raise ValueError(f"window must be (t_start, t_end) in s, got {window!r}") from err
    if not (math.isfinite(amplitude) and amplitude > 0):
        raise ValueError(f"amplitude must be a positive step [rad], got {amplitude!r}")
    if not (step_at + ramp_s + 1.0 <= lo < hi <= hold_s):
        raise ValueError(f"window {window} s must start >= 1 s after the step ends ({step_at + ramp_s:g} s) "
                         f"and end within the record (hold_s {hold_s:g} s)")
    rotors = [r.name for r in config.rotors]
    suffix = (lambda r: f"_{r}") if len(rotors) > 1 else (lambda r: "")
    if controls is None:
        controls = [f"{h}{suffix(r)}" for r in rotors for h in ("theta0", "theta1s")]
    specs = [SweepSpec(c, kind="step", amplitude=amplitude, duration=hold_s, trim_start=step_at,
                       pulse_width=ramp_s, label=f"step_{c}") for c in controls]
    runs = run_sweeps(config, settings.wake_settings, condition or FlightCondition(), specs,
                      trim=_trim_request(config, ct, trim), n_jobs=n_jobs, cache_dir=cache_dir, progress=progress)
    sys = inflow.system
    # the loads are the inputs that are not flap rates (named as the inflow models name them)
    rates = set(flap_rate_names(["" if len(rotors) == 1 else r for r in rotors]))
    loads = [n for n in sys.input_labels if n not in rates]
    g = np.asarray(sys.dcgain()).reshape(len(sys.output_labels), len(sys.input_labels))
    g = g[:, [sys.input_labels.index(n) for n in loads]]
    rows, settle, d_loads = [], [], {}
    for spec in specs:
        df = runs[spec.name]
        pre = df[df.t < step_at]
        late = df[(df.t >= lo) & (df.t <= hi)]
        early = df[(df.t >= step_at + ramp_s + 1.0) & (df.t <= step_at + ramp_s + 2.0)]
        d_c = (late[loads].mean() - pre[loads].mean()).to_numpy()
        d_loads[spec.control] = d_c
        pred = g @ d_c
        for k, out in enumerate(sys.output_labels):
            wake = float(late[out].mean() - pre[out].mean())
            rows.append({"control": spec.control, "output": out, "wake": wake, "model": float(pred[k]),
                         "ratio": float(pred[k] / wake) if wake != 0 else np.inf,
                         "on_axis": _on_axis(spec.control, out)})
            if _on_axis(spec.control, out):
                e = float(early[out].mean() - pre[out].mean())
                settle.append({"control": spec.control, "output": out, "early_1_2s": e, "late": wake,
                               "late_over_early": wake / e if e != 0 else np.inf})
    changes = pd.DataFrame.from_dict(d_loads, orient="index", columns=loads)
    changes.index.name = "control"
    return QuasiSteadyCheck(table=pd.DataFrame(rows), window=(lo, hi), settling=pd.DataFrame(settle),
                            amplitude=float(amplitude), load_changes=changes, model_name=name,
                            wall_s=time.perf_counter() - t0)
