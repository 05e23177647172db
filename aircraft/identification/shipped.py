"""Recipes of the shipped model files, and their regeneration.

Each shipped model has a *recipe* here (configuration, flight condition,
structure, trim thrust, :class:`IdentificationSettings`). Regenerating runs
:func:`aircraft.identification.identify_inflow` with it (wake runs cached in
``.cache/wake``) and writes ``aircraft/data/models/NAME.json``. Each file records
the settings hash of its recipe and the code digest of the code that computed it
(:mod:`aircraft.identification.model_code`: the import closure of this module,
``flightid`` and the wake included). :func:`stale_models` (and the tests) compare
both with the recipe and the code now, so a change of any input (settings, wake
code, fitting code, pipeline) shows up as a stale file, with the reason, instead of
a silently outdated model.

From the command line::

    rotorwake shipped-models --list
    rotorwake shipped-models uh60_hover_3state        # ~5 min on 2 cores
    rotorwake shipped-models coaxial_hover_6state     # ~25 min on 2 cores (wake runs)
    rotorwake shipped-models coaxial_hover_12state    # ~40 min, or the fit only once cached
    rotorwake shipped-models --published              # the printed models
    rotorwake shipped-models --check                  # which files are stale
"""
from __future__ import annotations

from dataclasses import dataclass, field

from .model_code import combined_digest, identification_code, kernel_backend_used, staleness
from .pipeline import IdentificationSettings, identification_hash, identify_inflow
from aircraft.inflow.model_files import ModelRecord, load_record, shipped_model_path, shipped_models
from aircraft.provenance import settings_hash

__all__ = ["Recipe", "RECIPES", "PUBLISHED_FILES", "published_record", "regenerate", "stale_models"]


@dataclass(frozen=True)
class Recipe:
    """How one shipped model is made (see :func:`identify_inflow`)."""

    config: str                    # name of a function in aircraft.configs
    structure: str                 # key of aircraft.identification.STRUCTURES
    ct: float                      # system trim C_T
    description: str
    settings: IdentificationSettings = field(default_factory=IdentificationSettings)

    def arguments(self):
        import aircraft.configs
        from aircraft.wake import FlightCondition
        return getattr(aircraft.configs, self.config)(), FlightCondition(), self.structure

    def hash(self):
        config, condition, structure = self.arguments()
        return identification_hash(config, condition, structure, self.settings, ct=self.ct)[0]


#: The models shipped from our own wake (default wake resolution, 45 s sweeps).
RECIPES = {
    "uh60_hover_3state": Recipe(
        "uh60_single_rotor", "single_rotor_3state", 0.0061,
        "UH-60-like single rotor, hover, C_T 0.0061: 3-state M/Lbar/tau (Tables 4.1-4.2 form) "
        "identified from our free-vortex wake"),
    # total of the dissertation's split (0.0053 + 0.0043, §5.4), shared equally, torques
    # balanced; default wake resolution. Both coaxial models come from one data set
    # (the 6-state uses its six swashplate sweeps, the 12-state adds the four
    # tip-path-plane sweeps), so regenerating both costs the 12-state's wake runs.
    "coaxial_hover_6state": Recipe(
        "coaxial_compound", "coaxial_6state", 0.0053 + 0.0043,
        "Coaxial compound (Table B.1), hover, system C_T 0.0096: 6-state M/Lbar/tau (Eq. 5.3 "
        "structure, our rotor frames) identified from our free-vortex wake (default resolution)"),
    "coaxial_hover_12state": Recipe(
        "coaxial_compound", "coaxial_12state_far_loads", 0.0053 + 0.0043,
        "Coaxial compound (Table B.1), hover, system C_T 0.0096: 12-state near/far-wake F/G/C model "
        "with flap-rate inputs (Eqs. 6.2-6.3 structure plus the 6-state's lambda/C delays and the "
        "cyclic loads feeding the cyclic far wake, our rotor frames), fitted in stages (§6.4.3) "
        "from six swashplate and four prescribed tip-path-plane sweeps of our free-vortex wake "
        "(default resolution)"),
    # the same ten sweeps as coaxial_hover_12state; the inflow also answers each rotor's
    # tip-path-plane tilt (held records of our wake: the upper blades move through the
    # lower rotor's induced-velocity gradient), see aircraft.identification.structures.tilt
    "coaxial_hover_12state_tilt": Recipe(
        "coaxial_compound", "coaxial_12state_tilt", 0.0053 + 0.0043,
        "Coaxial compound (Table B.1), hover, system C_T 0.0096: 12-state near/far-wake F/G/C model "
        "with flap-rate inputs and tip-path-plane tilt inputs (four integrator states of the flap "
        "rates feeding the near-wake cyclic rows; fly it with "
        "aircraft.identification.structures.tilt.tilt_inflow_from_record), first-order collective with "
        "Pitt-Peters' gain, flap rates into the near wake only, our rotor frames; fitted in stages "
        "from six swashplate and four prescribed tip-path-plane sweeps of our free-vortex wake "
        "(default resolution)"),
    # the same six sweeps as coaxial_hover_6state, every coupling hover's axisymmetry
    # allows, and the collective apparent-mass diagonal held at Pitt-Peters' (a priori:
    # our nearly rank-one collective block fixes M and Lbar only in combination)
    "coaxial_hover_6state_axisymmetric": Recipe(
        "coaxial_compound", "coaxial_6state_axisymmetric_pp_collective_mass", 0.0053 + 0.0043,
        "Coaxial compound (Table B.1), hover, system C_T 0.0096: 6-state M/Lbar/tau with every "
        "coupling hover's axisymmetry allows (Eq. 5.3 plus the 1s/1c terms, our rotor frames), the "
        "collective apparent masses m11, m44 held at Pitt-Peters' 8/(3 pi) a priori, identified from "
        "the six swashplate sweeps of our free-vortex wake (default resolution)"),
}

#: Printed models shipped as files (converted to our rotor frames), by file name.
PUBLISHED_FILES = {"published_table4_mfw": "table4_mfw", "published_table4_pitt_peters": "table4_pitt_peters",
                   "published_eq5_3": "eq5_3", "published_eq6_8_6_9": "eq6_8_6_9"}


def published_record(key):
    """A printed model (:data:`aircraft.inflow.published.PUBLISHED_MODELS` key) as a
    :class:`ModelRecord` in our rotor frames, trim from
    :meth:`IdentifiedInflow.from_published`'s momentum reference.

    Parameters
    ----------
    key : str
        Key of :data:`aircraft.inflow.published.PUBLISHED_MODELS`.

    Returns
    -------
    ModelRecord
        The printed matrices (``fgc`` or ``mltau`` form) in our rotor frames.
    """
    from aircraft.inflow import IdentifiedInflow
    from aircraft.inflow.published import PUBLISHED_MODELS, in_rotor_frames
    printed = PUBLISHED_MODELS[key]
    model = in_rotor_frames(printed)
    ref = IdentifiedInflow.from_published(model)      # trim loads and momentum reference inflow
    if hasattr(model, "F"):
        form, mats = "fgc", {"F": model.F, "G": model.G, "C": model.C}
        inputs = list(model.input_order)
    else:
        form, mats = "mltau", {"M": model.M, "Lbar": model.Lbar, "tau": model.tau}
        inputs = list(model.input_names)
    # hashed under the file's matrix keys (Lbar is "L" on disk), so the hash of a
    # published file does not depend on the in-memory name
    payload = {"printed": key, "matrices": {("L" if k == "Lbar" else k): v for k, v in mats.items()},
               "frame_conversion": "aircraft.inflow.frames/1"}
    return ModelRecord(name=key, form=form, rotors=model.rotors, omega=model.omega, matrices=mats,
                       inputs=inputs, outputs=list(model.output_names), loads_ref=ref.loads_ref,
                       inflow_ref=ref.inflow_ref, frame="rotor", time=getattr(model, "time", "azimuth"),
                       settings=payload, settings_hash=settings_hash(payload, digits=16),
                       provenance={"source": model.source, "printed_name": printed.name,
                                   "reference_inflow": "momentum steady state (IdentifiedInflow.from_published)"},
                       description=f"{printed.name}: printed in the dissertation (reference data, not our "
                                   f"output), converted to our rotor frames. {model.notes}")


def regenerate(name, *, n_jobs=2, cache_dir="default", progress=True, path=None):
    """Rebuild one shipped model file, recording the code digest of the code that ran.

    The digest (:func:`~aircraft.identification.model_code.identification_code`) is
    taken before the identification starts, so it describes the code the run
    imported; the Biot-Savart backend the wake runs used is recorded in the
    provenance (``kernel_backend``).

    Parameters
    ----------
    name : str
        Shipped model name: a key of :data:`RECIPES` (identified from the wake)
        or of :data:`PUBLISHED_FILES` (a printed model, converted).
    n_jobs : int
        Wake worker processes.
    cache_dir : str or None
        Wake run cache directory.
    progress : bool
        Show tqdm progress.
    path : str or pathlib.Path, optional
        Where to write (default :func:`shipped_model_path` of ``name``).

    Returns
    -------
    IdentifiedModel or ModelRecord
        The identified model, or the record of a printed model.

    Raises
    ------
    KeyError
        If ``name`` has no recipe.
    """
    if name not in RECIPES and name not in PUBLISHED_FILES:
        raise KeyError(f"no recipe {name!r}; have {sorted(RECIPES) + sorted(PUBLISHED_FILES)}")
    # every module (GPU kernel included) is digested now; the kernel's module is dropped
    # below if the runs did not use it, as stale_models compares
    _, modules = identification_code()
    if name in PUBLISHED_FILES:
        rec = published_record(PUBLISHED_FILES[name])
        rec.name = name
        _record_code(rec, modules)
        rec.save(path or shipped_model_path(name))
        return rec
    r = RECIPES[name]
    config, condition, structure = r.arguments()
    # the file keeps the reduction log and, for a model the rest of the rule trusts, the
    # reproduction on a second data set: a reader judges it as the identification did
    model = identify_inflow(config, condition, structure, ct=r.ct, settings=r.settings, name=name,
                            n_jobs=n_jobs, cache_dir=cache_dir, progress=progress, reproduce="if_trusted")
    rec = model.to_record(r.description)
    _record_code(rec, modules)
    model.provenance["kernel_backend"] = rec.provenance["kernel_backend"]
    rec.save(path or shipped_model_path(name))
    return model


def _record_code(rec, modules):
    """Put the code digest of ``modules`` (less any backend module that did not run) into ``rec``."""
    backend = kernel_backend_used()
    rec.code_digest, rec.code_digests = combined_digest(modules, kernel_backend=backend)
    rec.provenance = {**rec.provenance, "kernel_backend": backend}


def stale_models(root=None):
    """Shipped files that no longer match their recipe or the code, with the reasons.

    Parameters
    ----------
    root : str or pathlib.Path, optional
        Project root whose code is compared (default: this one).

    Returns
    -------
    dict
        ``{name: [reason, ...]}`` for each stale shipped file; a reason names the
        settings hash (the recipe changed), the modules whose code changed, or
        ``"no code digest"`` (a file written before digests were recorded).

    Examples
    --------
    >>> stale_models()                    # doctest: +SKIP
    {'uh60_hover_3state': ['code digest: changed flightid/fitting.py']}
    """
    out, cache = {}, {}
    for name in shipped_models():
        rec = load_record(name)
        if name in RECIPES:
            want = RECIPES[name].hash()
        elif name in PUBLISHED_FILES:
            want = published_record(PUBLISHED_FILES[name]).settings_hash
        else:
            continue
        reasons = staleness(rec, want, root=root, cache=cache)
        if reasons:
            out[name] = reasons
    return out
