"""The trust rule's reproduction part at the trusted points of a design-space identification."""
from __future__ import annotations

import time

import pandas as pd

from .reproduction import reproduction_row

__all__ = ["reproduction_table"]


def reproduction_table(result, settings, *, config=None, n_jobs=2, cache_dir="default", progress=True):
    """Run each trusted point of ``result`` again with ``reproduce=True``; one row per point.

    The point's identification is repeated with the same call
    :func:`aircraft.identification.identify_design_space` makes (the spaced
    configuration, hover, the fitted structure, its thrust and ``settings``), then a
    second wake data set started 1e-7 R away is run and the first model's final
    structure refitted on it (:func:`aircraft.identification.identify_inflow`).

    Parameters
    ----------
    result : aircraft.identification.design_space.DesignSpaceResult
        The design-space identification.
    settings : aircraft.identification.IdentificationSettings
        The settings it was run with.
    config : aircraft.AircraftConfig, optional
        The configuration it was run on (default the coaxial compound).

    Returns
    -------
    pandas.DataFrame
        spacing, ct, :func:`studies.analysis.reproduction.reproduction_row`'s columns and
        wall_s [s] (both data sets and fits); empty (those columns) when no point is trusted.
    """
    from aircraft.identification import identify_inflow
    from aircraft.identification.design_space import spaced_config

    rows = []
    for p in result.points:
        if not (p.ok and p.model.trusted):
            continue
        t0 = time.perf_counter()
        model = identify_inflow(spaced_config(config, p.spacing), None, result.fitted_structure, ct=p.ct,
                                settings=settings, name=f"{p.model.name} (reproduction)", n_jobs=n_jobs,
                                cache_dir=cache_dir, progress=progress, reproduce=True)
        rows.append({"spacing": p.spacing, "ct": p.ct, **reproduction_row(model, p.model),
                     "wall_s": time.perf_counter() - t0})
    columns = ["spacing", "ct", "J_ave", "J_ave_refit", "same_first_fit", "parameters", "largest_shift_in_bounds",
               "parameter_of_largest", "reproduces", "same_structure", "trusted", "trust_failures", "wall_s"]
    return pd.DataFrame(rows, columns=columns)
