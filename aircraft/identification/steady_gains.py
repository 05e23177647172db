"""The wake's own steady inflow gains: held swashplate steps, flap-rate ramps and held tilts.

An inflow model fitted over 1-25 rad/s says nothing about its gain at zero
frequency, and that gain is what an aircraft's slow modes see. Our coaxial
12-state models extrapolate a steady wake-curvature gain (lambda1s per
tip-path-plane rate) of K_R 6-7 on the upper rotor (theory 1.5) through a
far-wake pole below the fit band, and the hover aircraft flying them loses its
roll damping. :func:`wake_steady_gains` asks the wake itself:

* a held step of each swashplate control (theta0, theta1s, theta1c per rotor):
  loads and inflow settle, the flap rates are zero;
* a *ramp* of each prescribed tip-path-plane coordinate (beta1s, beta1c per
  rotor): a constant flap rate while the tilt grows, then the tilt held.

Over late windows of each record the changes satisfy, for a linear wake that has
settled, ``d_lambda = G_C d_C + G_R d_beta_dot + G_T d_beta``: steady gains per
load (``G_C``), per flap rate (``G_R``) and per tip-path-plane tilt (``G_T``).
The ramp window and the held-tilt window of each ramp separate rate from tilt;
with the steps, the observations determine all three by least squares::

    wake: 6 held steps + 4 ramps (ramp window, held-tilt window)
                     ---> window means (d_C, d_beta_dot, d_beta, d_lambda)
                                  |
        [G_C G_R G_T] = d_lambda @ pinv([d_C; d_beta_dot; d_beta])   (SteadyGains)
                                  |
         .equivalent_kr (-Omega G_R on-axis, Eq. 2.29 at zero frequency)
         .compare(model): the model driven by each record's loads and rates
                          (time domain, so its slow modes count) against the wake

The tilt term is the point: our wake's inflow answers a *held* tilt of the tip-path
plane (about -0.1 per rad on the upper rotor's on-axis lambda1s/lambda1c), and no
inflow structure of ours has a tilt input (Eqs. 6.2-6.3 take flap rates). A fit
on flap rates alone can mimic ``G_T beta = G_T beta_dot / s`` only by a slow pole,
an approximate integrator, which then reads as a large steady K_R. Estimated
without the tilt inputs (``tilts=()``), the same records give the upper rotor
K_R ~13; with them, ~0 (the ``twelve-state-variants`` study's ``steady_gains.csv``).

The estimate is quasi-static: a path lagging by ``tau`` biases a ramp's rate
gains by ``-tau (G_C dC/dt / beta_dot + G_T)`` (tested on a known system). The
comparison needs no estimate: it simulates the model on the measured inputs of
each record and compares window means. Records use the identification's wake
settings and trim, so the step records of theta0/theta1s are the cached ones of
:func:`~aircraft.identification.quasi_steady_check`.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from aircraft.inflow.base import flap_rate_names, inflow_names, load_names, rotor_suffix

__all__ = ["SteadyGains", "SteadyGainsError", "estimate_steady_gains", "steady_gain_specs", "wake_steady_gains"]


class SteadyGainsError(ValueError):
    """Records or windows from which no steady gain can be estimated."""


def steady_gain_specs(rotors, *, step_amplitude=0.02, hold_s=10.0, step_at=0.5, step_ramp_s=0.1,
                      ramp_amplitude=0.1, ramp_s=8.0, ramp_hold_s=12.0):
    """The held records of :func:`wake_steady_gains` as :class:`aircraft.wake.SweepSpec` s.

    Parameters
    ----------
    rotors : sequence of str
        Rotor names (``("U", "L")``; one rotor: its controls carry no suffix).
    step_amplitude : float
        Swashplate step [rad] (the identification's sweep amplitude).
    hold_s, step_at, step_ramp_s : float
        Step record length, step time and the step's ramp time [s] (the values of
        :func:`~aircraft.identification.quasi_steady_check`, so its records are reused).
    ramp_amplitude, ramp_s, ramp_hold_s : float
        Tip-path-plane ramp: ``ramp_amplitude`` [rad] reached over ``ramp_s`` [s] (a
        flap rate of their ratio [rad/s]), in a record of ``ramp_hold_s`` [s].

    Returns
    -------
    (steps, ramps) : two lists of SweepSpec
    """
    from aircraft.wake import SweepSpec
    sfx = [rotor_suffix(n) for n in _signal_rotors(rotors)]
    steps = [SweepSpec(f"{h}{x}", kind="step", amplitude=step_amplitude, duration=hold_s,
                       trim_start=step_at, pulse_width=step_ramp_s, label=f"step_{h}{x}")
             for x in sfx for h in ("theta0", "theta1s", "theta1c")]
    ramps = [SweepSpec(f"{b}{x}", kind="step", amplitude=ramp_amplitude, duration=ramp_hold_s,
                       trim_start=step_at, pulse_width=ramp_s, label=f"ramp_{b}{x}")
             for x in sfx for b in ("beta1s", "beta1c")]
    return steps, ramps


def _signal_rotors(rotors):
    """The rotor names as the signals carry them: a single rotor's signals have no suffix."""
    return tuple(rotors) if len(rotors) > 1 else ("",)


@dataclass
class SteadyGains:
    """Steady inflow gains of the wake, estimated from held records.

    Attributes
    ----------
    loads_gain : pandas.DataFrame
        ``G_C``: steady inflow change per unit load change [-/-], outputs x loads.
    rate_gain : pandas.DataFrame
        ``G_R``: steady inflow change per unit flap rate [1/(rad/s)], outputs x rates.
    changes : pandas.DataFrame
        Per observation (index ``observation``, ``record@start-end``): the
        window-mean change of every input and inflow [-, rad/s, rad, -], the
        record and its window [s].
    condition_number : float
        Of the regressor ``[d_C; d_beta_dot]`` scaled per input: above ~1e3 the
        records do not separate the inputs and the gains are not determined.
    omega : float
        Rotor speed [rad/s].
    rotors : tuple of str
    records : dict
        The wake records (DataFrames) by name, for :meth:`compare`.
    wall_s : float
    tilt_gain : pandas.DataFrame
        ``G_T``: steady inflow change per unit tip-path-plane tilt [1/rad],
        outputs x tilts (empty without tilts). No inflow structure of ours has
        this input: a fit on flap rates alone can only mimic it by a slow pole
        (an approximate integrator of the rate).
    """

    loads_gain: pd.DataFrame
    rate_gain: pd.DataFrame
    changes: pd.DataFrame
    condition_number: float
    omega: float
    rotors: tuple
    records: dict = field(default_factory=dict, repr=False)
    wall_s: float = float("nan")
    tilt_gain: pd.DataFrame = None

    @property
    def equivalent_kr(self) -> dict:
        """Each rotor's on-axis steady wake-curvature gain as the K_R of Eq. 2.29 [-].

        ``lambda1s = -K_R beta1s_dot / Omega`` at zero frequency, so
        ``K_R = -Omega G_R[lam1s_r, beta1s_dot_r]`` (and the same from the 1c pair;
        the mean of the two is returned, both are in :meth:`to_pandas`)."""
        out = {}
        for r, name in zip(self.rotors, _signal_rotors(self.rotors)):
            x = rotor_suffix(name)
            pair = [-self.omega * self.rate_gain.loc[f"lam1{h}{x}", f"beta1{h}_dot{x}"] for h in "sc"]
            out[r] = float(np.mean(pair))
        return out

    @property
    def windows(self) -> dict:
        """Averaging windows [s] of each record: ``{record: [(start, end), ...]}`` (from :attr:`changes`)."""
        out = {}
        for r in self.changes.itertuples():
            out.setdefault(r.record, []).append((r.window_start, r.window_end))
        return out

    def _input_time(self, record):
        return float(self.changes.t_input[self.changes.record == record].iloc[0])

    def rate_only(self) -> "SteadyGains":
        """The estimate a flap-rate-only structure implies: the same records without the
        tilt inputs and without the held-tilt windows (each record's first window), so
        a ramp's growing tilt is read as rate. The difference from this estimate is
        what the missing tilt input does to the steady K_R."""
        times = {n: self._input_time(n) for n in self.records}
        return estimate_steady_gains(self.records, {n: w[:1] for n, w in self.windows.items()}, times,
                                     list(self.loads_gain.columns), list(self.rate_gain.columns),
                                     list(self.loads_gain.index), omega=self.omega, rotors=self.rotors)

    def to_pandas(self) -> pd.DataFrame:
        """Long table: output, input, gain, kind (``load``, ``flap_rate`` or ``tilt``)."""
        parts = [(self.loads_gain, "load"), (self.rate_gain, "flap_rate"), (self.tilt_gain, "tilt")]
        parts = [g.stack().rename("gain").reset_index().assign(kind=k) for g, k in parts
                 if g is not None and g.size]
        return pd.concat(parts, ignore_index=True).rename(columns={"level_0": "output", "level_1": "input"})

    def compare(self, model, pade_order=2) -> pd.DataFrame:
        """The model driven by each record's measured loads and flap rates, against the wake.

        Parameters
        ----------
        model : IdentifiedModel or aircraft.inflow.IdentifiedInflow
            Its inputs must be among the records' columns (loads and flap rates).
        pade_order : int
            Padé order of the model's delays.

        Returns
        -------
        pandas.DataFrame
            Per record window and on-axis inflow output (the harmonic the
            record's input drives on its own rotor): ``record``, ``window``
            (``start-end`` [s]), ``output``, ``wake`` and ``model`` (window-mean
            change [-]), ``ratio`` (model / wake).
        """
        import control
        from .pipeline import IdentifiedModel
        if isinstance(model, IdentifiedModel):
            sys = model.fit.structure.to_statespace(pade_order=pade_order)
        else:
            sys = getattr(model, "system", None)
            if not isinstance(sys, control.StateSpace):
                raise SteadyGainsError(f"model must be an IdentifiedModel or an IdentifiedInflow, got "
                                       f"{type(model).__name__}")
        ins, outs = list(sys.input_labels), list(sys.output_labels)
        rows, windows = [], self.windows
        for name, df in self.records.items():
            missing = [c for c in ins + outs if c not in df]
            if missing:
                raise SteadyGainsError(f"record {name!r} lacks the model's signals {missing}")
            t = df.t.to_numpy()
            pre = df[t < self._input_time(name)]
            u = (df[ins] - pre[ins].mean()).to_numpy().T
            y = np.atleast_2d(control.forced_response(sys, t, u).outputs)
            for lo, hi in windows[name]:
                late = (t >= lo) & (t <= hi)
                for out in _on_axis_outputs(name, outs):
                    k = outs.index(out)
                    wake = float(df[out][late].mean() - pre[out].mean())
                    pred = float(np.mean(y[k][late]))
                    rows.append({"record": name, "window": f"{lo:g}-{hi:g}", "output": out, "wake": wake,
                                 "model": pred, "ratio": pred / wake if wake != 0 else math.inf})
        return pd.DataFrame(rows)

    def plot(self, fig=None, models=None):
        """On-axis steady inflow change per record, wake beside each model; a Figure.

        ``models``: optional ``{label: model}`` compared with :meth:`compare`."""
        from matplotlib.figure import Figure
        models = dict(models or {})
        tables = {lab: self.compare(m) for lab, m in models.items()}
        base = (next(iter(tables.values())) if tables else
                pd.DataFrame([{"record": r.record, "window": f"{r.window_start:g}-{r.window_end:g}", "output": o,
                               "wake": getattr(r, o)} for r in self.changes.itertuples()
                              for o in _on_axis_outputs(r.record, list(self.loads_gain.index))]))
        fig = fig or Figure(figsize=(max(6.0, 0.55 * len(base)), 3.8))
        ax = fig.subplots()
        x = np.arange(len(base))
        width = 0.8 / (1 + len(tables))
        ax.bar(x - 0.4 + width / 2, 1e3 * base.wake.to_numpy(), width, label="wake (held)")
        for k, (lab, t) in enumerate(tables.items(), start=1):
            ax.bar(x - 0.4 + width * (k + 0.5), 1e3 * t.model.to_numpy(), width, label=lab)
        ax.set_xticks(x, [f"{r} {w} s\n{o}" for r, w, o in zip(base.record, base.window, base.output)],
                      fontsize=6, rotation=60)
        ax.axhline(0.0, color="k", lw=0.5)
        ax.set_ylabel("steady inflow change x 1e3 [-]")
        kr = ", ".join(f"{r} {v:.2f}" for r, v in self.equivalent_kr.items())
        ax.set_title(f"held steps, flap-rate ramps and held tilts; wake's steady K_R: {kr} (theory 1.5)",
                     fontsize=9)
        ax.legend(fontsize=7)
        fig.tight_layout()
        return fig


def _on_axis_outputs(record, outputs):
    """The inflow harmonics a record's input drives on its own rotor (the quasi-steady
    check's rule; a tip-path-plane coordinate drives the harmonic of its swashplate twin)."""
    from .quasi_steady import _on_axis
    control = record.split("_", 1)[1].replace("beta", "theta", 1)   # ramp_beta1s_U -> theta1s_U
    return [o for o in outputs if _on_axis(control, o)]


def _windows_of(value):
    """A record's windows as a list of (lo, hi): one pair or a list of pairs [s]."""
    pairs = [value] if np.ndim(value) == 1 else list(value)
    try:
        return [(float(lo), float(hi)) for lo, hi in pairs]
    except (TypeError, ValueError) as err:
        raise SteadyGainsError(f"a window must be (t_start, t_end) in s, got {value!r}") from err


def estimate_steady_gains(records, windows, input_times, loads, rates, outputs, *, omega, rotors, tilts=()):
    """Steady gains ``[G_C G_R G_T]`` from held records (the estimator, without the wake).

    Each (record, window) pair is one observation of
    ``d_lambda = G_C d_C + G_R d_beta_dot + G_T d_beta`` (window means minus the
    mean before the record's input); the gains are their least-squares solution.
    A load path that lags by ``tau`` biases a ramp's observation by
    ``-G_C tau dC/dt`` (quasi-static estimate; tested on a known system).

    Parameters
    ----------
    records : dict of str to pandas.DataFrame
        Each with a time column ``t`` [s] and the ``loads``, ``rates``, ``tilts``
        and ``outputs`` columns.
    windows : dict of str to (float, float) or list of them
        Late averaging window(s) of each record [s]; each is an observation.
    input_times : dict of str to float
        Time at which each record's input starts [s]; the mean before it is the
        reference of the changes.
    loads, rates, outputs : list of str
    omega : float
        Rotor speed [rad/s] (for :attr:`SteadyGains.equivalent_kr`).
    rotors : tuple of str
    tilts : list of str, optional
        Tip-path-plane coordinates (``beta1s_U``, ...) [rad] as further inputs: the
        inflow's answer to a held tilt, which a flap-rate ramp mixes with its rate.

    Returns
    -------
    SteadyGains

    Raises
    ------
    SteadyGainsError
        Fewer observations than inputs, a window outside a record, missing columns,
        an input no record moves, or changes that are not finite.
    """
    inputs = list(loads) + list(rates) + list(tilts)
    rows = {}
    for name, df in records.items():
        missing = [c for c in ["t"] + inputs + list(outputs) if c not in df]
        if missing:
            raise SteadyGainsError(f"record {name!r} lacks columns {missing}")
        t0 = input_times[name]
        t = df.t.to_numpy()
        pre = df[t < t0]
        step = float(t[1] - t[0]) if t.size > 1 else 0.0
        for lo, hi in _windows_of(windows[name]):
            # a window may end at the record's nominal length (its last sample is one step short)
            if not (t[0] < t0 < lo < hi <= t[-1] + step):
                raise SteadyGainsError(f"record {name!r}: need t_start < input time {t0} < window {lo}-{hi} s "
                                       f"<= record end {t[-1]:.3g} s")
            late = df[(t >= lo) & (t <= hi)]
            d = late[inputs + list(outputs)].mean() - pre[inputs + list(outputs)].mean()
            rows[f"{name}@{lo:g}-{hi:g}"] = {**d.to_dict(), "record": name, "t_input": t0,
                                              "window_start": lo, "window_end": hi}
    if len(rows) < len(inputs):
        raise SteadyGainsError(f"{len(rows)} observations (record windows) cannot determine gains of "
                               f"{len(inputs)} inputs: hold one record per load and per flap rate")
    changes = pd.DataFrame.from_dict(rows, orient="index")
    changes.index.name = "observation"
    X = changes[inputs].to_numpy(float).T           # inputs x observations
    Y = changes[list(outputs)].to_numpy(float).T    # outputs x observations
    if not (np.isfinite(X).all() and np.isfinite(Y).all()):
        raise SteadyGainsError("a record's window-mean change is not finite")
    # scale each input to unit rms over the observations: loads (~1e-3), flap rates
    # (~1e-2 rad/s) and tilts (~0.1 rad) differ in size, and the condition number
    # should judge the records, not the units
    scale = np.sqrt(np.mean(X ** 2, axis=1))
    if np.any(scale == 0):
        idle = [inputs[k] for k in np.flatnonzero(scale == 0)]
        raise SteadyGainsError(f"no record moves {idle}: their gains are not determined")
    Xs = X / scale[:, None]
    cond = float(np.linalg.cond(Xs))
    G = (Y @ np.linalg.pinv(Xs)) / scale[None, :]
    gain = pd.DataFrame(G, index=list(outputs), columns=inputs)
    return SteadyGains(loads_gain=gain[list(loads)], rate_gain=gain[list(rates)], changes=changes,
                       condition_number=cond, omega=float(omega), rotors=tuple(rotors), records=dict(records),
                       tilt_gain=gain[list(tilts)])


def wake_steady_gains(config, ct=None, *, trim=None, settings=None, condition=None, step_window=(6.0, 10.0),
                      ramp_window=(4.5, 8.0), tilt_window=(10.0, 12.0), n_jobs=2, cache_dir="default",
                      progress=True, **spec_kwargs):
    """Hold steps and flap-rate ramps in the free wake and estimate its steady gains.

    Parameters
    ----------
    config : aircraft.AircraftConfig
        The rotor(s); prescribed tip-path-plane inputs need the rigid-flap wake
        (the identification's).
    ct, trim :
        Trim thrust or full trim request, as :func:`identify_inflow`.
    settings : IdentificationSettings, optional
        Wake resolution (default :class:`IdentificationSettings` ()).
    condition : aircraft.wake.FlightCondition, optional
        Default hover.
    step_window, ramp_window, tilt_window : (float, float)
        Late averaging windows [s]: of the step records; of the ramp records during
        the ramp (within ``step_at`` to ``step_at + ramp_s``, where the flap rate is
        constant, a few seconds in so the wake has settled); and of the ramp records
        after it, where the tip-path plane is held tilted (the tilt gain ``G_T``).
    n_jobs, cache_dir, progress :
        As :func:`aircraft.wake.run_sweeps`.
    **spec_kwargs :
        Passed to :func:`steady_gain_specs` (amplitudes, record lengths, ramp time).

    Returns
    -------
    SteadyGains
    """
    from aircraft.wake import FlightCondition, run_sweeps
    from .pipeline import IdentificationSettings, _trim_request

    t0 = time.perf_counter()
    settings = settings or IdentificationSettings()
    rotors = tuple(r.name for r in config.rotors)
    names = _signal_rotors(rotors)
    steps, ramps = steady_gain_specs(rotors, **spec_kwargs)
    step_at = steps[0].trim_start
    ramp_end = ramps[0].trim_start + ramps[0].pulse_width
    if not (step_at < ramp_window[0] < ramp_window[1] <= ramp_end):
        raise SteadyGainsError(f"ramp_window {ramp_window} s must lie within the ramp ({step_at:g}-{ramp_end:g} s), "
                               f"where the flap rate is constant")
    if not (ramp_end < tilt_window[0] < tilt_window[1] <= ramps[0].duration):
        raise SteadyGainsError(f"tilt_window {tilt_window} s must lie after the ramp ends ({ramp_end:g} s) and within "
                               f"the record ({ramps[0].duration:g} s)")
    runs = run_sweeps(config, settings.wake_settings, condition or FlightCondition(), steps + ramps,
                      trim=_trim_request(config, ct, trim), n_jobs=n_jobs, cache_dir=cache_dir, progress=progress)
    loads = load_names(names)
    outputs = inflow_names(names)
    records = {s.name: runs[s.name] for s in steps + ramps}
    windows = {**{s.name: [tuple(step_window)] for s in steps},
               **{s.name: [tuple(ramp_window), tuple(tilt_window)] for s in ramps}}
    times = {s.name: s.trim_start for s in steps + ramps}
    tilts = [f"{b}{rotor_suffix(r)}" for r in names for b in ("beta1s", "beta1c")]
    out = estimate_steady_gains(records, windows, times, loads, flap_rate_names(names), outputs,
                                omega=float(config.rotors[0].omega), rotors=rotors, tilts=tilts)
    out.wall_s = time.perf_counter() - t0
    return out
