"""Candidate structures at 200 kt: which inflow structure does the trust rule accept?

::

    identify_candidate_structures(structures, ...)   each structure: wake records (shared) ->
        -> CandidateStructures                        fit -> reduce -> trust verdict
    candidate_structures_table(models)               one row per structure

Every candidate is identified by :func:`identify_coaxial_forward` with the same
trim request and settings, so that its sweeps are the same wake records (the
records are keyed by content in the wake cache: computed once, read by the
others). The structures go from small to large (:data:`DEFAULT_CANDIDATES`):
two isolated Eq. 4.3 rotors, the coaxial 6-state with Eq. 5.3's interference
(each also without the ``lam0 / C_M`` responses, as §4.4.1.2 allows for one
rotor), the near-wake half of Eq. 6.5; the table names the largest one the trust
rule (:attr:`IdentifiedModel.trusted`) accepts.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

__all__ = ["DEFAULT_CANDIDATES", "CANDIDATE_COLUMNS", "CandidateStructures", "default_candidates",
           "candidate_structures_table", "identify_candidate_structures"]

#: Keys of the default candidates, smallest first.
DEFAULT_CANDIDATES = ("coaxial_forward_isolated", "coaxial_forward_isolated_without_lam0_cm", "coaxial_forward_6state",
                      "coaxial_forward_6state_without_lam0_cm", "coaxial_forward_12state_near_wake")

#: Columns of :func:`candidate_structures_table`.
CANDIDATE_COLUMNS = ("structure", "states", "parameters_start", "free_parameters", "J_ave", "max_cramer_rao_pct",
                     "max_insensitivity_pct", "max_doublet_tic", "trusted", "reasons", "wall_s", "note")


def default_candidates():
    """The default candidate structures, smallest first (keys :data:`DEFAULT_CANDIDATES`).

    Returns
    -------
    dict
        Key -> structure instance: :class:`CoaxialForwardIsolated` (24 parameters), the same
        fitted without the ``lam0 / C_M`` responses, :class:`CoaxialForward6State` (42) with
        and without them, ``CoaxialForward12State(near_wake_only=True)`` (72).

    Examples
    --------
    >>> list(default_candidates()) == list(DEFAULT_CANDIDATES)
    True
    """
    from .structures.coaxial_forward import CoaxialForward12State
    from .structures.coaxial_forward_small import CoaxialForward6State, CoaxialForwardIsolated
    structures = (CoaxialForwardIsolated(), CoaxialForwardIsolated(without_lam0_cm=True), CoaxialForward6State(),
                  CoaxialForward6State(without_lam0_cm=True), CoaxialForward12State(near_wake_only=True))
    return dict(zip(DEFAULT_CANDIDATES, structures))


def _n_states(structure):
    states = getattr(structure, "states", None)
    return len(states) if states is not None else len(structure.outputs)


def _n_start(structure):
    return len(structure.parameter_names()) if hasattr(structure, "parameter_names") else np.nan


def candidate_structures_table(models, wall_s=None):
    """One row per identified candidate: size, cost, bounds and trust verdict.

    Parameters
    ----------
    models : dict
        Label -> :class:`IdentifiedModel`.
    wall_s : dict, optional
        Label -> wall time of the candidate's identification [s] (NaN where absent).

    Returns
    -------
    pandas.DataFrame
        Columns :data:`CANDIDATE_COLUMNS`: ``states`` of the model, ``parameters_start``
        (the structure's pattern) and ``free_parameters`` (after the reduction),
        ``J_ave``, the largest normalised Cramér-Rao bound and insensitivity of the
        free parameters [%], ``max_doublet_tic`` (the largest Theil inequality coefficient
        of the doublet verification, 0 perfect, 1 no better than zero; NaN without one),
        ``trusted`` (:attr:`IdentifiedModel.trusted`) and
        ``reasons`` (its failures joined by " | ", empty when trusted), ``wall_s``, and
        ``note`` (why the reduced model has no doublet verification, else empty).

    Examples
    --------
    >>> candidate_structures_table({}).columns.tolist() == list(CANDIDATE_COLUMNS)
    True
    """
    wall_s = wall_s or {}
    rows = []
    for label, model in models.items():
        p = model.parameters
        free = p[p.status == "free"]
        failures = model.trust.failures
        note = str(getattr(model, "provenance", {}).get("verification_error", ""))
        # the doublet check is not part of the trust rule, but it shows a degenerate model
        # (a singular apparent mass fits the frequency responses and diverges in time)
        tic = np.nan if note or not hasattr(model, "verification_table") else \
            float(model.verification_table.TIC.max())
        rows.append({"structure": label, "states": _n_states(model.structure),
                     "parameters_start": _n_start(model.structure), "free_parameters": len(free),
                     "J_ave": model.J_ave, "max_cramer_rao_pct": float(free.cramer_rao_pct.max()),
                     "max_insensitivity_pct": float(free.insensitivity_pct.max()), "max_doublet_tic": tic,
                     "trusted": not failures,
                     "reasons": " | ".join(failures), "wall_s": wall_s.get(label, np.nan),
                     "note": note})
    return pd.DataFrame(rows, columns=list(CANDIDATE_COLUMNS))


@dataclass
class CandidateStructures:
    """The candidates identified on one data set.

    Attributes
    ----------
    models : dict
        Label -> :class:`IdentifiedModel` (the reduced fit with its trust verdict).
    table : pandas.DataFrame
        :func:`candidate_structures_table`, in the order identified.
    errors : dict
        Label -> message, for a candidate whose identification failed (not in ``table``).
    """

    models: dict
    table: pd.DataFrame
    errors: dict = field(default_factory=dict)

    @property
    def largest_trusted(self):
        """Label of the trusted candidate with the most free parameters, or None if none is trusted."""
        t = self.table[self.table.trusted]
        if t.empty:
            return None
        return str(t.sort_values(["free_parameters", "states"], kind="stable").structure.iloc[-1])


def identify_candidate_structures(structures=None, *, config=None, ct=None, lift_offset=0.0, settings=None,
                                  n_jobs=2, cache_dir="default", progress=True, max_reduction_steps=1000,
                                  reduction_batch=1, **kwargs):
    """Identify each candidate structure on the same 200 kt wake records, with its trust verdict.

    Parameters
    ----------
    structures : dict or sequence, optional
        Label -> structure, or structures (labelled by their key); default
        :func:`default_candidates`. Each must be a coaxial structure without flap-rate
        inputs (see :func:`identify_coaxial_forward`).
    config : AircraftConfig, optional
        Default ``coaxial_compound(cruise=True)``.
    ct : float, optional
        System thrust coefficient of the wake trim [-] (default: the aircraft's).
    lift_offset : float or (float, float)
        Lift offset of the wake trim [-].
    settings : IdentificationSettings, optional
        Shared by every candidate (so are the records).
    n_jobs : int
        Wake worker processes (the records are computed once, then read from the cache).
    cache_dir : str or None
        Wake cache; None recomputes the records for every candidate.
    progress : bool
        Progress bars.
    max_reduction_steps, reduction_batch : int
        Bounds of each candidate's automatic reduction (see :func:`identify_coaxial_forward`).
    **kwargs
        Further arguments of :func:`identify_coaxial_forward` (``speed``, ``rotor_aoa``).

    Returns
    -------
    CandidateStructures
        ``table`` has each candidate's wall time (records, fit, reduction, verification) [s].

    Raises
    ------
    ValueError
        ``structures`` is empty.
    TypeError
        A structure the 200 kt identification cannot take.

    Examples
    --------
    The default candidates on the coarse 200 kt wake (minutes the first time; see the
    study ``coaxial-forward-flight --candidate-structures``):

    >>> result = identify_candidate_structures(lift_offset=(0.337, 0.32))   # doctest: +SKIP
    >>> result.table[["structure", "free_parameters", "J_ave", "trusted"]]   # doctest: +SKIP
    >>> result.largest_trusted                                              # doctest: +SKIP
    """
    from .coaxial_forward_flight import identify_coaxial_forward
    if structures is None:
        structures = default_candidates()
    elif not isinstance(structures, dict):
        structures = {getattr(s, "key", repr(s)): s for s in structures}
    if not structures:
        raise ValueError("structures must name at least one candidate structure")
    models, wall, errors = {}, {}, {}
    for label, structure in structures.items():
        t0 = time.perf_counter()
        try:
            models[label] = identify_coaxial_forward(
                config, ct=ct, structure=structure, settings=settings, n_jobs=n_jobs, cache_dir=cache_dir,
                progress=progress, max_reduction_steps=max_reduction_steps, lift_offset=lift_offset,
                reduction_batch=reduction_batch, name=f"coaxial forward candidate {label}",
                verification_failure="record", **kwargs)
        except (ValueError, RuntimeError, np.linalg.LinAlgError) as err:
            # one candidate's failed fit (e.g. no stable start) leaves the others standing
            errors[label] = f"{type(err).__name__}: {err}"[:300]
            continue
        wall[label] = round(time.perf_counter() - t0, 1)
    return CandidateStructures(models, candidate_structures_table(models, wall), errors)
