"""One call from a rotor to a trusted-or-not identified inflow model: :func:`identify_inflow`.

::

    wake trim ─► sweeps + doublet + zero-input run   (aircraft.wake.run_sweeps: parallel, cached)
      ─► chirp-z responses (lambda, C over theta) ─► joint input-output (lambda/C)
      ─► data-driven start (inverse of the low-frequency lambda/C)
      ─► CIFER-cost fit (staged, §6.4.3, for structures with a plan: the
         12-state model) ─► automatic reduction (Fig. 6.1)
      ─► verification on the doublet (not used in the fit), beside the wake's
         noise floor (the same TIC on a run with no input)

The result, :class:`IdentifiedModel`, carries the cost table, the parameters
with Cramér-Rao and insensitivity percentages, the verification, the settings
with their hash and the provenance; ``.to_inflow()`` puts it into the aircraft,
``.save(path)`` writes the versioned file of :mod:`aircraft.inflow.model_files`.
"""
from __future__ import annotations

import datetime
import time
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from aircraft.inflow.model_files import SCHEMA, ModelRecord
from aircraft.provenance import identity_dict, identity_repr, settings_hash
from .excitation import ExcitationSettings
from .trust import REPRODUCTION_RULES, refit_structure, reproduction_check, trust_check
from .structures.base import InflowStructure
from .structures import get_structure

__all__ = ["IdentificationSettings", "IdentifiedModel", "PipelineError", "identify_inflow",
           "identification_hash", "PIPELINE_VERSION", "REPRODUCTION_PERTURBATION"]

#: Version of the pipeline's numerical recipe; part of every settings hash. Bump it
#: when a change would alter an identified model (start, fit, reduction, signals).
PIPELINE_VERSION = "pipeline-4"   # 2: apparent-mass diagonals protected in the reduction;
#                                    3: the data-driven start uses the lowest *coherent* points;
#                                    4: structures may add starts (6-state: equation-error M)

#: Start displacement of the reproduction check's second wake [fraction of the radius]:
#: the relative rounding of the single-precision Biot-Savart kernel, i.e. the size of
#: the difference another machine's (or another backend's) records start from.
REPRODUCTION_PERTURBATION = 1e-7


class PipelineError(RuntimeError):
    """Raised when the identification cannot run (trim failure, missing excitation)."""


@dataclass(frozen=True)
class IdentificationSettings(ExcitationSettings):
    """Settings of :func:`identify_inflow` (SI units, radians).

    The wake records and the fit band are those of :class:`ExcitationSettings`
    (``wake, sweep_s, amplitude, w_min, w_max, fit_range, doublet_amplitude, doublet_s,
    pulse_width, noise_floor_s, n_omega, coherence_min, pade_order``); added here:

    Parameters
    ----------
    doublet_control : str, optional
        Control of the doublet (default: the structure's first, the collective).
    start_points : int
        Lowest frequencies averaged for the data-driven start.
    reduce : bool
        Run the automatic reduction (Fig. 6.1) after the first fit.
    insensitivity_max, cramer_rao_max : float
        Reduction thresholds [%] (guideline 10 % and 20 %).

    Examples
    --------
    >>> IdentificationSettings(sweep_s=30.0).fit_range
    (1.0, 25.0)
    """

    doublet_control: str | None = None
    start_points: int = 3
    reduce: bool = True
    insensitivity_max: float = 10.0
    cramer_rao_max: float = 20.0

    def __post_init__(self):
        super().__post_init__()
        if isinstance(self.start_points, bool) or not isinstance(self.start_points, int) or self.start_points < 1:
            raise ValueError(f"start_points must be an integer >= 1, got {self.start_points!r}")
        for name in ("insensitivity_max", "cramer_rao_max"):
            if not getattr(self, name) > 0:
                raise ValueError(f"{name} must be positive [%], got {getattr(self, name)!r}")

    def to_dict(self):
        # identity_dict: a settings field added later (neutral default) leaves the hash alone
        d = identity_dict(self)
        d["wake"] = identity_dict(self.wake_settings)
        d["fit_range"] = list(self.fit_range)
        return d


def _trim_request(config, ct, trim):
    if trim is not None:
        return dict(trim)
    if ct is None:
        raise PipelineError("give the trim thrust ct (system C_T) or a trim request dict")
    if len(config.rotors) == 1:
        return {"ct": ct}
    # coaxial: equal thrusts, torque-balanced (as in the dissertation's split, §5.4)
    return {"ct": (ct / 2, ct / 2), "mode": "torque_balance", "tol": 1e-4}


def identification_hash(config, condition, structure, settings=None, *, ct=None, trim=None):
    """Hash of everything that determines an identified model (not jobs or cache).

    Includes the configuration, flight condition, structure, trim request,
    :class:`IdentificationSettings` (with the wake resolution), this pipeline's
    :data:`PIPELINE_VERSION` and the wake code's cache version, so a shipped
    model goes stale when any of them changes.

    Parameters
    ----------
    config : aircraft.AircraftConfig
        Rotor(s) identified (hashed by its ``repr`` without the fields the wake never sees:
        the pilot mixing's ``control_phase``, the fuselage lift and the tail rotor).
    condition : aircraft.wake.FlightCondition
        Flight condition (a dataclass, hashed field by field).
    structure : InflowStructure or str
        Model structure or a key of :data:`STRUCTURES` (hashed by its ``spec()``).
    settings : IdentificationSettings, optional
        Identification settings (default ``IdentificationSettings()``).
    ct : float, optional
        Trim thrust coefficient of the system (coaxial: split equally, torques
        balanced); needed unless ``trim`` is given.
    trim : dict, optional
        Full trim request (overrides ``ct``).

    Returns
    -------
    hash : str
        :func:`settings_hash` of ``payload`` (16 hex digits).
    payload : dict
        The hashed content.

    Raises
    ------
    PipelineError
        If neither ``ct`` nor ``trim`` is given.
    """
    from aircraft.wake import sweeps as _sweeps
    settings = settings or IdentificationSettings()
    structure = get_structure(structure)
    payload = {"schema": SCHEMA, "pipeline": PIPELINE_VERSION,
               # the wake's own marker of result-changing code changes
               "wake_code": getattr(_sweeps, "_CACHE_VERSION", "unknown"),
               "config": _wake_repr(config), "condition": identity_dict(condition), "structure": structure.spec(),
               "trim": _trim_request(config, ct, trim), "settings": settings.to_dict()}
    return settings_hash(payload, digits=16), payload


#: aircraft fields the wake never sees (the pilot mixing): left out of the identification hash
_NOT_WAKE_INPUTS = ("control_phase", "fuselage_lift_area", "tail_rotor")


def _wake_repr(config):
    """The configuration's dataclass ``repr`` without the fields the wake does not use."""
    # identity_repr: configuration fields added later (neutral defaults) leave the hash alone
    return identity_repr(config, exclude=_NOT_WAKE_INPUTS)


def _code_version():
    try:
        from importlib.metadata import version
        return version("rotorwake-id")
    except Exception:   # noqa: BLE001 - not installed: the version is unknown, not an error
        return "unknown"


@dataclass
class IdentifiedModel:
    """Outcome of :func:`identify_inflow`.

    Attributes
    ----------
    name : str
    structure : InflowStructure
    fit : flightid.FitResult
        Final (reduced) fit.
    reduction : flightid.reduction.ReductionResult or None
    responses : flightid.MeasuredResponse
        The joint input-output lambda/C (and lambda/beta_dot) responses fitted.
    verification : flightid.verification.VerificationResult
        Doublet (not used in the fit).
    noise_floor : flightid.verification.VerificationResult
        The same on the zero-input run: the TIC the wake's own unsteadiness gives.
    trim : aircraft.wake.WakeTrim
    omega : float
        Rotor speed [rad/s].
    settings : IdentificationSettings
    settings_hash : str
    provenance : dict
    hash_payload : dict
        What the settings hash was computed from.
    staged : flightid.staging.StagedFitResult or None
        The staged fit (§6.4.3) before the reduction, for structures with a
        :meth:`~InflowStructure.staged_plan` (its ``.log`` lists the stages).
    reproduction : aircraft.identification.trust.ReproductionCheck or None
        The identification again and the final structure refitted on a second wake
        data set (``identify_inflow(..., reproduce=True)``); part of the trust verdict
        when present.
    fit_start : dict or None
        Parameter values the identification's fit started from (the reduction's first
        fit: the data-driven start, or the staged optimum of a staged structure); the
        reproduction's refit starts there.
    """

    name: str
    structure: InflowStructure
    fit: object
    reduction: object
    responses: object
    verification: object
    noise_floor: object
    trim: object
    omega: float
    settings: IdentificationSettings
    settings_hash: str
    provenance: dict = field(default_factory=dict)
    hash_payload: dict = field(default_factory=dict)
    staged: object = None
    reproduction: object = None
    fit_start: dict | None = None

    @property
    def cost_table(self) -> pd.DataFrame:
        return self.fit.cost_table.drop(columns="J_ave", errors="ignore")

    @property
    def J_ave(self) -> float:
        return float(self.fit.J_ave)

    @property
    def parameters(self) -> pd.DataFrame:
        """parameter, value, status, cramer_rao_pct, insensitivity_pct."""
        return self.fit.parameters.copy()

    @property
    def values(self) -> dict:
        return dict(self.fit.structure.values)

    @property
    def verification_table(self) -> pd.DataFrame:
        """Per output: doublet TIC beside the noise-floor TIC and the signal-to-floor ratio."""
        v = self.verification.metrics.set_index("output")
        f = self.noise_floor.metrics.set_index("output")
        out = pd.DataFrame({"TIC": v.TIC, "TIC_noise_floor": f.TIC, "rms_error": v.rms_error,
                            "rms_measured": v.rms_measured, "rms_noise_floor": f.rms_measured})
        # below ~3x the wake's own unsteadiness the doublet TIC says nothing about the model
        out["signal_to_floor"] = out.rms_measured / out.rms_noise_floor.where(out.rms_noise_floor > 0)
        return out.reset_index()

    @property
    def trust(self):
        """The trust verdict, parameter by parameter with its reasons
        (:func:`aircraft.identification.trust.trust_check`)."""
        return trust_check(self)

    @property
    def trusted(self) -> bool:
        """True when :func:`~aircraft.identification.trust.trust_check` trusts the model."""
        return self.trust.passes

    def trust_failures(self) -> list:
        """The reasons not to trust the model, as sentences; empty when it is trusted."""
        return self.trust.failures

    def to_pandas(self) -> pd.DataFrame:
        """The parameter table."""
        return self.parameters

    def plot(self, fig=None):
        """Bode overlay of the fitted responses (data, model, coherence); a Figure."""
        return self.fit.plot(fig=fig)

    def _refs(self):
        o = self.trim.outputs
        loads_ref = np.array([o.get(n, 0.0) if n.startswith("CT") else 0.0 for n in self.structure.loads])
        inflow_ref = np.array([o[n] for n in self.structure.outputs])
        return loads_ref, inflow_ref

    def to_inflow(self):
        """The identified model as an :class:`aircraft.inflow.IdentifiedInflow` about the wake's trim."""
        loads_ref, inflow_ref = self._refs()
        return self.structure.to_inflow(self.values, self.omega, loads_ref=loads_ref, inflow_ref=inflow_ref,
                                        pade_order=self.settings.pade_order, name=self.name)

    def to_record(self, description="") -> ModelRecord:
        """The versioned-file form (:class:`aircraft.inflow.model_files.ModelRecord`)."""
        mats = self.fit.structure.matrices()
        loads_ref, inflow_ref = self._refs()
        if self.structure.form == "mltau":
            matrices = {"M": mats["M"], "Lbar": mats["Lbar"], "tau": mats["tau"]}
        else:   # F, G per d/dpsi in the structure: store seconds
            matrices = {"F": self.omega * mats["F"], "G": self.omega * mats["G"], "C": self.fit.structure.C}
            if mats.get("tau") is not None and np.any(mats["tau"] > 0):
                matrices["tau"] = mats["tau"]
        return ModelRecord(
            name=self.name, form=self.structure.form, rotors=self.structure.rotors, omega=self.omega,
            matrices=matrices, inputs=self.structure.inputs, outputs=self.structure.outputs,
            loads_ref=loads_ref, inflow_ref=inflow_ref, frame=self.structure.frame, time="azimuth",
            pade_order=self.settings.pade_order, cost_table=self.cost_table, parameters=self.parameters,
            verification=self.verification_table, trim_outputs=dict(self.trim.outputs),
            reduction_log=self.reduction.log if self.reduction is not None else pd.DataFrame(),
            reproduction=self.reproduction.table if self.reproduction is not None else pd.DataFrame(),
            settings=self.hash_payload, settings_hash=self.settings_hash, provenance=self.provenance,
            description=description or f"{self.structure.key} identified from our free-vortex wake")

    def save(self, path, description=""):
        """Write the model file (JSON) to ``path``; returns the Path."""
        return self.to_record(description).save(path)

    def summary(self) -> str:
        fmt = lambda v: f"{v:.4g}"   # noqa: E731
        p = self.parameters
        free = p[p.status == "free"]
        lines = [f"== {self.name}: {self.structure.key} ({self.structure.frame} frames) ==",
                 f"J_ave = {self.J_ave:.1f} over {len(self.cost_table)} responses; "
                 f"max CR {free.cramer_rao_pct.max():.3g} %, max insensitivity "
                 f"{free.insensitivity_pct.max():.3g} % -> {'trusted' if self.trusted else 'NOT trusted'}",
                 *[f"  not trusted: {r}" for r in self.trust_failures()],
                 f"reproduction on a second wake data set: {self.trust.limits['reproduction']} (structure "
                 f"of the identification again: {self.trust.limits['reproduction_structure']})",
                 self.cost_table.to_string(index=False, float_format=fmt),
                 p.to_string(index=False, float_format=fmt),
                 self.verification_table.to_string(index=False, float_format=fmt)]
        return "\n".join(lines)


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


def _verify(model, run, ref, inputs, outputs):
    from flightid import verify
    # perturbations about the trim's revolution averages (a single sample carries
    # the wake's blade-passage scatter)
    u = (run[inputs] - ref[inputs]).to_numpy().T
    y = (run[outputs] - ref[outputs]).to_numpy().T
    return verify(model, run["t"].to_numpy(), u, y, remove_initial=False)


def _start_candidates(structure, responses, s, omega=None):
    """The data-driven starts: from the ``start_points`` lowest frequencies, and (when it
    differs) from the lowest points where every load element is coherent.

    A record whose lowest points are incoherent (a multisine's lowest harmonics) gives
    a noise start from the first; a record whose cross pairs are coherent only higher
    up (the default-wake six sweeps) can be led by the second into a worse optimum
    (J_ave 218 against 108). Neither is right every time, so both are fitted and the
    lower cost wins; the log says what each reached.
    """
    starts = [("lowest points", structure.initial_values(responses, s.start_points))]
    coherent = structure.initial_values(responses, s.start_points, coherence_min=s.coherence_min)
    if coherent != starts[0][1]:
        starts.append((f"lowest points with coherence >= {s.coherence_min:g}", coherent))
    if omega is not None:
        # structure-specific starts (the 6-state's equation-error M), when they exist
        starts += structure.extra_starts(responses, omega)
    return starts


def _fit_and_verify(structure, responses, runs, doublet_spec, zero_spec, wake_trim, omega, s, progress,
                    stages):
    """Start, (staged) fit, reduction and verification of ``structure`` on lambda/(C, beta_dot)
    ``responses``; shared by every excitation. Returns ``(staged, reduction, result,
    doublet verification, noise-floor verification, start log, fit start)``; the start log
    is one dict per data-driven start tried (:func:`_start_candidates`) with the J_ave its
    full fit reached and whether it was kept; the fit start the values the final fit (or
    the reduction's first) started from."""
    from flightid import fit, fit_staged, reduce
    fit_kwargs = dict(frequency_ranges=tuple(s.fit_range), n_omega=s.n_omega, coherence_min=s.coherence_min,
                      **structure.fit_options)
    staged, plan = None, structure.staged_plan()
    candidates = _start_candidates(structure, responses, s, omega)
    if len(candidates) == 1 and not plan:
        # one start: the reduction's own first fit is the full fit
        flight_structure = structure.build(candidates[0][1], omega)
        start_log = [{"start": candidates[0][0], "J_ave_full_fit": float("nan"), "kept": True}]
    else:
        tried, errors = [], []
        for label, init in candidates:
            start = structure.build(init, omega)
            try:
                if plan:
                    # large structures are built up stage by stage (§6.4.3); the reduction
                    # then starts from the staged optimum with every parameter free, on the
                    # last stage's responses
                    stage_fit = fit_staged(start, responses, plan, progress=progress, **fit_kwargs)
                    tried.append((label, stage_fit.result.J_ave, stage_fit.result, stage_fit, ""))
                else:
                    full = fit(start, responses, **fit_kwargs)
                    tried.append((label, full.J_ave, full, None, ""))
            except (ValueError, RuntimeError) as err:   # flightid's errors subclass these
                errors.append(err)
                tried.append((label, np.inf, None, None, f"{type(err).__name__}: {err}"[:200]))
        best = min(range(len(tried)), key=lambda k: tried[k][1] if np.isfinite(tried[k][1]) else np.inf)
        if tried[best][2] is None:
            raise errors[0]
        start_log = [{"start": t[0], "J_ave_full_fit": float(t[1]), "kept": k == best, "error": t[4]}
                     for k, t in enumerate(tried)]
        _, _, best_fit, staged, _ = tried[best]
        if plan:
            flight_structure = best_fit.structure.free(list(best_fit.structure.names))
            fit_kwargs["pairs"] = list(zip(best_fit.cost_table.output, best_fit.cost_table.input))
        else:
            flight_structure = best_fit.structure
    fit_start = dict(flight_structure.values)
    if s.reduce:
        reduction = reduce(flight_structure, responses, insensitivity_max=s.insensitivity_max,
                           cramer_rao_max=s.cramer_rao_max, protected=structure.protected,
                           progress=progress, **fit_kwargs)
        result = reduction.result
    else:
        reduction, result = None, fit(flight_structure, responses, **fit_kwargs)
    stages.update()
    stages.set_postfix_str("verify")
    model_ss = result.structure.to_statespace(pade_order=s.pade_order)
    ref = pd.Series(wake_trim.outputs)
    check = _verify(model_ss, runs[doublet_spec.name], ref, structure.inputs, structure.outputs)
    floor = _verify(model_ss, runs[zero_spec.name], ref, structure.inputs, structure.outputs)
    stages.update()
    stages.close()
    return staged, reduction, result, check, floor, start_log, fit_start


def _reproduction(model, again, rule):
    """Both parts of the reproduction check: ``again`` (the identification on the second
    data set) and the model's final structure refitted on ``again``'s responses."""
    try:
        refit, error = refit_structure(model, again.responses), ""
    except (ValueError, RuntimeError) as err:     # flightid's errors subclass these
        refit, error = None, f"{type(err).__name__}: {err}"[:200]
    if rule == "identification":
        return reproduction_check(model, again, refit=refit, rule=rule)
    return reproduction_check(model, again, refit=refit, rule=rule, refit_error=error)


def identify_inflow(config, condition=None, structure="single_rotor_3state", *, ct=None, trim=None,
                    settings=None, controls=None, name=None, n_jobs=2, cache_dir="default",
                    progress=True, scheduler=None, reproduce=False, reproduction_rule="refit"):
    """Identify an inflow model of ``config`` from the free-vortex wake.

    Parameters
    ----------
    config : aircraft.AircraftConfig
        Rotor(s) to identify (one rotor or a coaxial pair).
    condition : aircraft.wake.FlightCondition, optional
        Flight condition (default hover).
    structure : InflowStructure or str
        Model structure (:class:`SingleRotor3State`, :class:`Coaxial6State`,
        :class:`Coaxial12State` or a key of :data:`STRUCTURES`).
    ct : float, optional
        Trim thrust coefficient of the system (coaxial: split equally, torques
        balanced).
    trim : dict, optional
        Full trim request for :func:`aircraft.wake.trim_wake` (overrides ``ct``).
    settings : IdentificationSettings, optional
    controls : list of str, optional
        Controls to sweep, one record each (default ``structure.excitations``: the
        swashplate controls, plus the prescribed tip-path-plane inputs of every
        rotor for a structure with flap-rate inputs; the joint input-output needs
        as many independent excitations as the model has inputs).
    name : str, optional
    n_jobs : int
        Wake worker processes.
    cache_dir : str or None
        Wake run cache folder; "default" is $ROTORWAKE_CACHE_DIR, else .cache/wake (see :func:`aircraft.wake.run_sweeps`).
    progress : bool
        tqdm progress over the stages, the wake runs and the reduction.
    scheduler : str or dask.distributed.Client, optional
        Where the wake runs execute (see :func:`aircraft.wake.run_sweeps`); None:
        this machine (``n_jobs`` processes).
    reproduce : bool or "if_trusted"
        Also identify on a second wake data set, marched from a start displaced by
        :data:`REPRODUCTION_PERTURBATION` of the radius (what another machine's
        rounding would give), refit the final structure on it from the first fit's
        start (:func:`~aircraft.identification.trust.refit_structure`), and attach both comparisons as
        ``model.reproduction`` (:func:`~aircraft.identification.trust.reproduction_check`),
        which the trust verdict then includes. Doubles the cost; ``"if_trusted"`` spends
        it only on a model the rest of the rule trusts (for the others the verdict is
        already no).
    reproduction_rule : {"refit", "identification"}
        Which part the verdict requires: the refit's parameters within their bounds
        (default), or the former rule, the identification again keeping the same
        parameters within their bounds (both parts are reported either way).

    Returns
    -------
    IdentifiedModel

    Raises
    ------
    PipelineError
        If the wake trim fails or the excitation cannot separate the inputs.

    Examples
    --------
    The single-rotor hover 3-state of the UH-60-like rotor (about 5 min on 2 cores the
    first time; the wake runs are cached):

    >>> from aircraft import uh60_single_rotor
    >>> from aircraft.identification import identify_inflow
    >>> model = identify_inflow(uh60_single_rotor(), ct=0.0061)    # doctest: +SKIP
    >>> print(model.summary())                                       # doctest: +SKIP
    >>> model.trust.to_pandas()                                      # doctest: +SKIP
    >>> inflow = model.to_inflow()          # into the aircraft: Helicopter(config, inflow)  # doctest: +SKIP
    """
    from tqdm.auto import tqdm
    from aircraft.wake import FlightCondition, SweepSpec, run_sweeps
    from flightid import joint_input_output

    t_start = time.perf_counter()
    if not (isinstance(reproduce, bool) or reproduce == "if_trusted"):
        raise PipelineError(f"reproduce must be True, False or 'if_trusted', got {reproduce!r}")
    if reproduction_rule not in REPRODUCTION_RULES:
        raise PipelineError(f"reproduction_rule must be one of {REPRODUCTION_RULES}, got {reproduction_rule!r}")
    settings = settings or IdentificationSettings()
    condition = condition or FlightCondition()
    structure = get_structure(structure)
    rotor_names = tuple(r.name for r in config.rotors)
    if len(rotor_names) > 1 and len(rotor_names) == len(structure.rotors):
        # a structure with its default names takes the aircraft's (same numbers, its signals)
        try:
            structure = structure.for_rotors(rotor_names)
        except ValueError as err:
            raise PipelineError(str(err)) from None
    expected = ("",) if len(rotor_names) == 1 else structure.rotors
    if len(rotor_names) != len(structure.rotors) or (len(rotor_names) > 1 and rotor_names != expected):
        raise PipelineError(f"structure {structure.key} is for rotors {structure.rotors}; "
                            f"the configuration has {rotor_names}")
    controls = list(controls or structure.excitations)
    if len(controls) < len(structure.inputs):
        raise PipelineError(f"{structure.key} has {len(structure.inputs)} inputs {structure.inputs} but only "
                            f"{len(controls)} excitations {controls}: the joint input-output needs at least one "
                            "independent excitation per input (flap-rate inputs need prescribed tip-path-plane "
                            "sweeps, §6.3)")
    trim_req = _trim_request(config, ct, trim)
    digest, payload = identification_hash(config, condition, structure, settings, trim=trim_req)
    s = settings
    specs = [SweepSpec(c, kind="sweep", amplitude=s.amplitude, duration=s.sweep_s, w_min=s.w_min,
                       w_max=s.w_max, seed=k) for k, c in enumerate(controls)]
    dbl_control = s.doublet_control or controls[0]
    doublet_spec = SweepSpec(dbl_control, kind="doublet", amplitude=s.doublet_amplitude, duration=s.doublet_s,
                             pulse_width=s.pulse_width)
    # no input at all: what is left is the wake's own unsteadiness (the noise floor)
    zero_spec = SweepSpec(dbl_control, kind="sine", amplitude=0.0, duration=s.noise_floor_s, w_min=1.0,
                          label="zero_input")
    stages = tqdm(total=4, desc=f"identify {structure.key}", disable=not progress)
    stages.set_postfix_str("wake trim + runs")
    where = {} if scheduler is None else {"scheduler": scheduler}
    runs = run_sweeps(config, s.wake_settings, condition, specs + [doublet_spec, zero_spec], trim=trim_req,
                      n_jobs=n_jobs, cache_dir=cache_dir, progress=progress, **where)
    wake_trim = runs["trim"]
    if not wake_trim.converged:
        stages.close()
        raise PipelineError(f"wake trim did not converge (residual {wake_trim.residual:.2e})")
    stages.update()
    stages.set_postfix_str("responses")
    missing = [n for n in structure.inputs + structure.outputs if n not in runs[specs[0].name]]
    if missing:
        stages.close()
        raise PipelineError(f"the wake records lack signals {missing}")
    measured = _responses(runs, specs, structure.inputs + structure.outputs, s)
    responses = joint_input_output(measured.select(structure.outputs), measured.select(structure.inputs))
    stages.update()
    stages.set_postfix_str("fit + reduce")
    omega = float(config.rotors[0].omega)
    staged, reduction, result, check, floor, start_log, fit_start = _fit_and_verify(
        structure, responses, runs, doublet_spec, zero_spec, wake_trim, omega, s, progress, stages)
    provenance = {"source": "aircraft.identification.identify_inflow", "schema": SCHEMA, "starts": start_log,
                  "pipeline": PIPELINE_VERSION, "code_version": _code_version(),
                  "created": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
                  "wall_s": round(time.perf_counter() - t_start, 1), "config": config.name
                  if hasattr(config, "name") else repr(config)[:60]}
    model = IdentifiedModel(name=name or f"{structure.key} from the free wake", structure=structure,
                            fit=result, reduction=reduction, responses=responses, verification=check,
                            noise_floor=floor, trim=wake_trim, omega=omega, settings=s, settings_hash=digest,
                            provenance=provenance, hash_payload=payload, staged=staged, fit_start=fit_start)
    if reproduce is True or (reproduce == "if_trusted" and model.trusted):
        from dataclasses import replace
        second = replace(s, wake=replace(s.wake_settings, initial_perturbation=REPRODUCTION_PERTURBATION))
        again = identify_inflow(config, condition, structure, trim=trim_req, settings=second, controls=controls,
                                name=f"{model.name} (second data set)", n_jobs=n_jobs, cache_dir=cache_dir,
                                progress=progress, scheduler=scheduler)
        model.reproduction = _reproduction(model, again, reproduction_rule)
        model.provenance["reproduction"] = {"initial_perturbation": REPRODUCTION_PERTURBATION,
                                            "J_ave_again": again.J_ave, "J_ave_refit": model.reproduction.J_ave_refit,
                                            "rule": reproduction_rule, "same_structure": model.reproduction.same_structure,
                                            "parameters_reproduce": model.reproduction.parameters_reproduce,
                                            "passes": model.reproduction.passes}
    return model
