"""Off-rotor models from the free wake: :func:`identify_off_rotor` and its results.

Runs the recipe of :mod:`aircraft.identification.off_rotor.surfaces` on
:func:`aircraft.wake.run_sweeps` records: sweeps, doublets and a zero-input run with
the wake's velocity recorded at every surface point; the averaged velocities over
the inflow states by joint input-output (Eq. 4.9); the Eq. 2.39/2.40 fit in the
flight-dynamics band; the doublet verification beside the zero-input noise floor.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import pandas as pd

from ..trust import trust_check
from .surfaces import (_KEY, INFLOW_STATES, VELOCITY_COMPONENTS, OffRotorError, OffRotorSettings,
                        OffRotorSurface, fit_off_rotor, horizontal_tail, reduce_off_rotor, wake_exposure,
                        wing_under_hub)

__all__ = ["OffRotorModel", "OffRotorResult", "identify_off_rotor"]


@dataclass
class OffRotorModel:
    """An identified off-rotor model (Eq. 2.39 or 2.40) of one surface, one flight condition.

    Attributes
    ----------
    surface : OffRotorSurface
    mu : float
        Advance ratio of the flight condition [-].
    fit : flightid.FitResult
        The (reduced) fit (gains [-], delays [s], Cramér-Rao and insensitivity %, costs).
    responses : flightid.MeasuredResponse
        The joint input-output ``vbar / lam`` responses fitted.
    verification : dict
        ``{control: flightid.verification.VerificationResult}``: each doublet (not used in the fit).
    noise_floor : flightid.verification.VerificationResult
        The same on the zero-input run: the TIC of the wake's own unsteadiness.
    trim_velocity : dict
        Mean ``vx, vy, vz`` [-] at the surface on the zero-input run (trim).
    trim_inflow : dict
        Mean ``lam0, lam1c, lam1s`` [-] on that run.
    exposure : pandas.DataFrame
        :func:`wake_exposure` of the surface's points at the trimmed inflow.
    settings : OffRotorSettings
    reduction : flightid.ReductionResult or None
        The reduction (its log names what was removed and why), None when
        ``settings.reduce`` is False.
    """

    surface: OffRotorSurface
    mu: float
    fit: object
    responses: object
    verification: dict
    noise_floor: object
    trim_velocity: dict
    trim_inflow: dict
    exposure: pd.DataFrame
    settings: OffRotorSettings
    reduction: object = None

    @property
    def form(self):
        """"2.39" or "2.40"."""
        return self.surface.form

    def _matrix(self, label):
        mats = self.fit.structure.matrices()
        return pd.DataFrame(mats[label], index=list(self.fit.structure.outputs), columns=list(INFLOW_STATES))

    @property
    def gains(self) -> pd.DataFrame:
        """K [-]: rows vx, vy, vz; columns lam0, lam1c, lam1s."""
        return self._matrix("K")

    @property
    def delays(self) -> pd.DataFrame:
        """tau [s] element by element (Eq. 2.39: equal down each column)."""
        return self._matrix("tau")

    @property
    def trust(self):
        """:func:`aircraft.identification.trust_check` of the model: per-parameter verdicts
        (ok / kept / fails) and the reasons it is not trusted."""
        return trust_check(self)

    @property
    def trusted(self) -> bool:
        """Whether the model passes the trust rule (:attr:`trust`)."""
        return self.trust.passes

    def _statuses(self):
        """{parameter: free / removed / held / not fitted}: removed by the reduction (at 0),
        held by it at its value (no influence left), or never fitted (no coherent response)."""
        removed = set(self.reduction.removed) if self.reduction is not None else set()
        first = self.reduction.initial.structure if self.reduction is not None else self.fit.structure
        out = {}
        for n in self.fit.structure.names:
            if n not in self.fit.structure.fixed:
                out[n] = "free"
            elif n in removed:
                out[n] = "removed"
            elif n not in first.fixed:
                out[n] = "held"
            else:
                out[n] = "not fitted"
        return out

    @property
    def parameter_table(self) -> pd.DataFrame:
        """One row per parameter: value, status (free / removed / held / not fitted), the
        Cramér-Rao bound and insensitivity [%] of the free ones, the trust verdict and reason."""
        p = self.fit.parameters.set_index("parameter")
        verdicts = self.trust.table.set_index("parameter")
        status = self._statuses()
        rows = []
        for n in self.fit.structure.names:
            v = verdicts.loc[n] if n in verdicts.index else None
            rows.append({"surface": self.surface.name, "form": self.form, "mu": self.mu, "parameter": n,
                         "kind": "delay" if n.startswith("tau") else "gain", "value": p.loc[n, "value"],
                         "status": status[n], "cramer_rao_pct": p.loc[n, "cramer_rao_pct"],
                         "insensitivity_pct": p.loc[n, "insensitivity_pct"],
                         "verdict": v.verdict if v is not None else "", "reason": v.reason if v is not None else "",
                         "model_trusted": self.trusted})
        return pd.DataFrame(rows)

    @property
    def cost_table(self) -> pd.DataFrame:
        """output, input, band [rad/s] and J of each fitted response."""
        return self.fit.cost_table.drop(columns="J_ave", errors="ignore")

    @property
    def J_ave(self) -> float:
        """Mean CIFER cost over the fitted responses."""
        return float(self.fit.J_ave)

    @property
    def in_wake(self) -> float:
        """Fraction of the surface's points inside the skewed wake cylinder [-]."""
        return float(self.exposure.in_wake.mean())

    @property
    def verification_table(self) -> pd.DataFrame:
        """Per doublet and output: TIC beside the zero-input TIC and the signal-to-floor ratio."""
        floor = self.noise_floor.metrics.set_index("output")
        rows = []
        for control, ver in self.verification.items():
            for r in ver.metrics.itertuples():
                rows.append({"surface": self.surface.name, "mu": self.mu, "doublet": control, "output": r.output,
                             "TIC": r.TIC, "TIC_noise_floor": floor.loc[r.output, "TIC"],
                             "rms_measured": r.rms_measured, "rms_noise_floor": floor.loc[r.output, "rms_measured"]})
        out = pd.DataFrame(rows)
        # below ~3x the wake's own unsteadiness a doublet TIC says little about the model
        out["signal_to_floor"] = out.rms_measured / out.rms_noise_floor.where(out.rms_noise_floor > 0)
        return out

    def to_pandas(self) -> pd.DataFrame:
        """One row per gain: surface, mu, output, input, K [-], its status (free / removed /
        held / not fitted), CR/insensitivity [%] and trust verdict, the same for its delay tau [s]."""
        p = self.parameter_table.set_index("parameter")
        tau_name = (lambda j, c: f"tau{_KEY[j]}") if self.form == "2.39" else (lambda j, c: f"tau{_KEY[j]}{c}")
        rows = []
        for o, c in zip(self.fit.structure.outputs, VELOCITY_COMPONENTS):
            for j in INFLOW_STATES:
                k, t = p.loc[f"K{_KEY[j]}{c}"], p.loc[tau_name(j, c)]
                rows.append({"surface": self.surface.name, "form": self.form, "mu": self.mu, "output": o,
                             "input": j, "K": k.value, "K_status": k.status, "K_cramer_rao_pct": k.cramer_rao_pct,
                             "K_insensitivity_pct": k.insensitivity_pct, "K_verdict": k.verdict,
                             "tau_s": t.value, "tau_status": t.status, "tau_cramer_rao_pct": t.cramer_rao_pct,
                             "tau_insensitivity_pct": t.insensitivity_pct, "tau_verdict": t.verdict})
        return pd.DataFrame(rows)

    def plot(self, fig=None):
        """Time-domain verification: wake (black) and model (red) per output and doublet; a Figure."""
        from matplotlib.figure import Figure
        ctrls = list(self.verification)
        n_out = len(self.fit.structure.outputs)
        fig = fig or Figure(figsize=(3.6 * len(ctrls), 1.9 * n_out + 0.6), constrained_layout=True)
        axes = fig.subplots(n_out, len(ctrls), squeeze=False, sharex="col")
        for jc, control in enumerate(ctrls):
            ver = self.verification[control]
            for k, name in enumerate(ver.output_names):
                ax = axes[k, jc]
                ax.plot(ver.t, ver.measured[k], "k-", lw=1.0, label="free wake")
                ax.plot(ver.t, ver.predicted[k], "r--", lw=1.2, label=f"Eq. {self.form}")
                ax.set_title(f"{control} doublet: {name}, TIC {ver.metrics.loc[k, 'TIC']:.2f}", fontsize=8)
                ax.grid(alpha=0.3)
                if jc == 0:
                    ax.set_ylabel(f"{name} [-]")
            axes[-1, jc].set_xlabel("t [s]")
        axes[0, 0].legend(fontsize=7)
        fig.suptitle(f"{self.surface.name}, mu = {self.mu:.2f}: off-rotor model verification", fontsize=10)
        return fig

    def plot_bode(self, fig=None):
        """Bode overlay of the fitted responses (data, model, coherence); a Figure."""
        return self.fit.plot(fig=fig)

    def summary(self) -> str:
        """Gains, delays, the cost and the verification TICs as text."""
        fmt = lambda v: f"{v:.4g}"   # noqa: E731
        vt = self.verification_table
        trust = self.trust
        verdict = "trusted" if trust.passes else "NOT trusted: " + "; ".join(trust.failures)
        removed = self.reduction.removed if self.reduction is not None else []
        return "\n".join([
            f"== {self.surface.name} (Eq. {self.form}), mu = {self.mu:.3f}: J_ave = {self.J_ave:.1f}; {verdict}; "
            f"removed by the reduction: {removed or 'none'}; "
            f"{100 * self.in_wake:.0f} % of its points in the skewed wake cylinder ==",
            "gains K [-]:", self.gains.to_string(float_format=fmt),
            "delays tau [s]:", self.delays.to_string(float_format=fmt),
            vt[["doublet", "output", "TIC", "TIC_noise_floor", "signal_to_floor"]].to_string(
                index=False, float_format=fmt)])


@dataclass
class OffRotorResult:
    """Outcome of :func:`identify_off_rotor`: one :class:`OffRotorModel` per surface.

    Attributes
    ----------
    models : dict
        ``{surface name: OffRotorModel}``.
    condition : aircraft.wake.FlightCondition
    mu : float
        Advance ratio [-].
    trim : aircraft.wake.WakeTrim
    wall_s : float
        Wall time of the call [s] (wake runs, or cache reads, and fits).
    """

    models: dict
    condition: object
    mu: float
    trim: object
    wall_s: float
    settings: OffRotorSettings = field(default=None)

    def to_pandas(self) -> pd.DataFrame:
        """Every surface's gain/delay table (:meth:`OffRotorModel.to_pandas`), stacked."""
        return pd.concat([m.to_pandas() for m in self.models.values()], ignore_index=True)

    @property
    def parameter_table(self) -> pd.DataFrame:
        """Every surface's parameter table with trust verdicts (:attr:`OffRotorModel.parameter_table`)."""
        return pd.concat([m.parameter_table for m in self.models.values()], ignore_index=True)

    @property
    def verification_table(self) -> pd.DataFrame:
        """Every surface's doublet TICs, stacked."""
        return pd.concat([m.verification_table for m in self.models.values()], ignore_index=True)

    def plot(self, surface=None, fig=None):
        """Time-domain verification of ``surface`` (default: the first); a Figure."""
        name = surface or next(iter(self.models))
        if name not in self.models:
            raise OffRotorError(f"no surface {name!r}; have {list(self.models)}")
        return self.models[name].plot(fig=fig)

    def summary(self) -> str:
        """Text summary of every surface."""
        o = self.trim.outputs
        head = (f"mu = {self.mu:.3f}: trim C_T {o['CT']:.5f}, lam0 {o['lam0']:.5f}, lam1c {o['lam1c']:.5f}, "
                f"lam1s {o['lam1s']:.5f}; {self.wall_s:.0f} s")
        return "\n".join([head] + [m.summary() for m in self.models.values()])


# --------------------------------------------------------------------------- pipeline
def _responses(runs, specs, signals, settings):
    from flightid import combine_responses, frequency_response
    simo = []
    for spec in specs:
        df = runs[spec.name]
        y = (df[signals] - df[signals].iloc[0]).to_numpy()
        u = (df[spec.control] - df[spec.control].iloc[0]).to_numpy()
        simo.append(frequency_response(df["t"].to_numpy(), u, y, w_min=settings.w_min, w_max=settings.w_max,
                                       input_name=spec.control, output_names=signals))
    return combine_responses(simo)


def _frame(df, surfaces):
    """A wake record with each surface's averaged velocity ``vx_<name>`` etc. added."""
    parts = [df[["t", *INFLOW_STATES] + [c for c in df.columns if c.startswith("theta")]].copy()]
    for s in surfaces:
        avg = s.average(df)
        avg.columns = [f"{c}_{s.name}" for c in avg.columns]
        parts.append(avg)
    return pd.concat(parts, axis=1)


def identify_off_rotor(config, condition=None, surfaces=None, *, ct=None, trim=None, settings=None,
                       n_jobs=2, cache_dir="default", progress=True):
    """Identify Eq. 2.39/2.40 models of the induced velocity at off-rotor surfaces.

    Parameters
    ----------
    config : aircraft.AircraftConfig
        A single-rotor configuration (e.g. :func:`aircraft.configs.uh60_single_rotor`).
    condition : aircraft.wake.FlightCondition, optional
        Flight condition (default hover).
    surfaces : sequence of OffRotorSurface, optional
        Default: :func:`horizontal_tail` (Eq. 2.39) and :func:`wing_under_hub` (Eq. 2.40).
    ct : float, optional
        Trim thrust coefficient [-] (default ``config.trim_ct``).
    trim : dict, optional
        Full trim request of :func:`aircraft.wake.trim_wake` (overrides ``ct``).
    settings : OffRotorSettings, optional
    n_jobs : int
        Wake worker processes.
    cache_dir : str or None
        Wake cache folder; "default" is $ROTORWAKE_CACHE_DIR, else .cache/wake.
    progress : bool
        tqdm progress of the wake runs.

    Returns
    -------
    OffRotorResult

    Raises
    ------
    OffRotorError
        A coaxial configuration, bad surfaces (duplicate names or points), or no
        coherent off-rotor response.
    aircraft.wake.WakeTrimError
        The wake trim did not converge.
    """
    from aircraft.wake import FlightCondition, run_sweeps
    from flightid import joint_input_output, verify

    t_start = time.perf_counter()
    settings = settings or OffRotorSettings()
    if not isinstance(settings, OffRotorSettings):
        raise OffRotorError(f"settings must be an OffRotorSettings, got {type(settings).__name__}")
    condition = condition or FlightCondition()
    if len(getattr(config, "rotors", ())) != 1:
        raise OffRotorError("identify_off_rotor models a single rotor's inflow (lam0, lam1c, lam1s); "
                            f"the configuration has {len(getattr(config, 'rotors', ()))} rotors")
    surfaces = list(surfaces) if surfaces is not None else [horizontal_tail(config), wing_under_hub(config)]
    if not surfaces or not all(isinstance(s, OffRotorSurface) for s in surfaces):
        raise OffRotorError("surfaces must be a non-empty sequence of OffRotorSurface")
    names = [s.name for s in surfaces]
    if len(set(names)) != len(names):
        raise OffRotorError(f"surface names must be unique, got {names}")
    points = {}
    for s in surfaces:
        points.update(s.points())
    if ct is None and trim is None:
        ct = float(config.trim_ct[0])
    trim_req = dict(trim) if trim is not None else {"ct": ct}
    specs = settings.specs()
    runs = run_sweeps(config, settings.wake_settings, condition, specs, trim=trim_req, points=points,
                      n_jobs=n_jobs, cache_dir=cache_dir, progress=progress)
    frames = {spec.name: _frame(runs[spec.name], surfaces) for spec in specs}
    rotor = config.rotors[0]
    tip_speed = rotor.omega * rotor.radius
    mu = condition.speed * math.cos(condition.alpha) / tip_speed
    mu_z = condition.speed * math.sin(condition.alpha) / tip_speed
    sweeps = specs[:len(settings.controls)]
    doublets = specs[len(settings.controls):-1]
    zero = frames[specs[-1].name]
    ref = zero.drop(columns="t").mean()      # trim: the zero-input run's average
    vel = [f"v{c}_{s.name}" for s in surfaces for c in VELOCITY_COMPONENTS]
    measured = _responses(frames, sweeps, vel + list(INFLOW_STATES), settings)
    lam_theta = measured.select(list(INFLOW_STATES))
    models = {}
    for s in surfaces:
        outs = [f"v{c}_{s.name}" for c in VELOCITY_COMPONENTS]
        resp = joint_input_output(measured.select(outs), lam_theta, name=f"{s.name} vbar/lam")
        result = fit_off_rotor(resp, s.form, fit_range=settings.fit_range, outputs=outs,
                               n_omega=settings.n_omega, coherence_min=settings.coherence_min,
                               starts=settings.starts, seed=0)
        reduction = None
        if settings.reduce:
            reduction = reduce_off_rotor(result, resp, insensitivity_max=settings.insensitivity_max,
                                         cramer_rao_max=settings.cramer_rao_max, starts=settings.starts, seed=0)
            result = reduction.result
        model_ss = result.structure.to_statespace(pade_order=settings.pade_order)

        def check(df):
            u = (df[list(INFLOW_STATES)] - ref[list(INFLOW_STATES)]).to_numpy().T
            y = (df[outs] - ref[outs]).to_numpy().T
            return verify(model_ss, df["t"].to_numpy(), u, y, remove_initial=False)

        verification = {d.control: check(frames[d.name]) for d in doublets}
        models[s.name] = OffRotorModel(
            surface=s, mu=mu, fit=result, responses=resp, verification=verification, noise_floor=check(zero),
            trim_velocity={c: float(ref[f"v{c}_{s.name}"]) for c in VELOCITY_COMPONENTS},
            trim_inflow={j: float(ref[j]) for j in INFLOW_STATES},
            exposure=wake_exposure(s, config, mu, float(ref["lam0"]), mu_z=mu_z), settings=settings,
            reduction=reduction)
    return OffRotorResult(models=models, condition=condition, mu=mu, trim=runs["trim"],
                          wall_s=time.perf_counter() - t_start, settings=settings)
