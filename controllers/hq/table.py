"""A table of every spec of the library: source, boundary values, status and checking test."""
from __future__ import annotations

import pandas as pd

from .selector import all_specs

__all__ = ["spec_table", "TABLE_COLUMNS"]

TABLE_COLUMNS = ("name", "family", "axis", "speeds", "mte", "agility", "uce_attention", "kind", "status",
                 "boundaries", "units", "needs", "source", "test", "description")


def _uce_attention(spec):
    combos = [f"UCE {u} {a}" for u in spec.uces for a in spec.attentions if (u, a) not in spec.excluded]
    every = len(spec.uces) * len(spec.attentions) == 6 and not spec.excluded
    return "any" if every else ", ".join(combos)


def spec_table(specs=None):
    """One row per spec: name, family, axis, where it applies, status, boundary values, source and test.

    Parameters
    ----------
    specs : list of HQSpec, optional
        Default: every spec of the library (:func:`~controllers.hq.selector.all_specs`).

    Returns
    -------
    pandas.DataFrame
        Columns :data:`TABLE_COLUMNS`; ``status`` tells how the boundary
        numbers are known (``printed``, ``approximate``, ``partial``,
        ``not found``, ``design``, ``objective``).

    Examples
    --------
    >>> t = spec_table()
    >>> t.loc[t.name == "HgtRsH1.heave", "status"].item()
    'printed'
    """
    rows = []
    for s in (all_specs() if specs is None else specs):
        rows.append({"name": s.name, "family": s.family, "axis": s.axis, "speeds": "/".join(s.speeds),
                     "mte": "any" if len(s.mtes) > 1 else s.mtes[0],
                     "agility": "any" if len(s.agilities) > 1 else s.agilities[0],
                     "uce_attention": _uce_attention(s), "kind": s.kind, "status": s.status,
                     "boundaries": s.boundary_text(), "units": s.units, "needs": s.missing_input, "source": s.source, "test": s.test,
                     "description": s.description})
    return pd.DataFrame(rows, columns=list(TABLE_COLUMNS))
