"""One row of the trust rule's reproduction part, for the studies that tabulate it per model."""
from __future__ import annotations

import numpy as np

__all__ = ["reproduction_row"]


def reproduction_row(model, first):
    """The reproduction verdict of ``model`` (identified with ``reproduce=True``) as a table row.

    Parameters
    ----------
    model : aircraft.identification.IdentifiedModel
        The identification run again with ``reproduce=True`` (its ``reproduction`` set).
    first : aircraft.identification.IdentifiedModel
        The model the study tabulated from the same first data set: ``same_first_fit``
        says whether ``model`` is it again (the same cost to round-off).

    Returns
    -------
    dict
        J_ave, J_ave_refit (the first structure on the second data set), same_first_fit,
        parameters (compared), largest_shift_in_bounds (shift over the first fit's
        Cramér-Rao bound, the largest), parameter_of_largest, reproduces (every parameter
        within its bound), same_structure (the whole identification again keeps the same
        free parameters), trusted (the whole rule) and trust_failures.
    """
    rep = model.reproduction
    if rep is None:
        raise ValueError(f"model {model.name!r} has no reproduction check: identify it with reproduce=True")
    t = rep.table
    shifts = t.shift_in_bounds.astype(float)
    worst = t.loc[shifts.idxmax()] if len(t) and shifts.notna().any() else None
    return {"J_ave": model.J_ave, "J_ave_refit": rep.J_ave_refit,
            # cached (or recomputed, deterministic) data and a deterministic fit give the tabulated model again
            "same_first_fit": bool(np.isclose(model.J_ave, first.J_ave, rtol=1e-9, atol=0.0)),
            "parameters": len(t),
            "largest_shift_in_bounds": float(worst.shift_in_bounds) if worst is not None else np.nan,
            "parameter_of_largest": worst.parameter if worst is not None else "",
            "reproduces": rep.passes, "same_structure": rep.same_structure, "trusted": model.trusted,
            "trust_failures": " | ".join(model.trust_failures())}
