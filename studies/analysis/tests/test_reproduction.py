"""One row of the reproduction verdict (studies.analysis.reproduction) on stub models."""
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from aircraft.identification.trust import ReproductionCheck
from studies.analysis.reproduction import reproduction_row


def _model(j_ave, table=None):
    rep = None if table is None else ReproductionCheck(table, J_ave=j_ave, J_ave_again=j_ave + 1.0, refit=table,
                                                      J_ave_refit=j_ave + 0.5, rule="refit")
    return SimpleNamespace(name="stub", J_ave=j_ave, reproduction=rep, trusted=True, trust_failures=lambda: [])


def test_the_largest_shift_and_the_verdict_are_the_tables():
    # shifts of a quarter and of one and a tenth of a bound: the second decides, and the check fails
    table = pd.DataFrame({"parameter": ["a", "b"], "value": [1.0, 2.0], "value_again": [1.025, 2.22],
                          "cramer_rao_pct": [10.0, 10.0], "shift_pct": [2.5, 11.0], "shift_in_bounds": [0.25, 1.1],
                          "reproduced": [True, False]})
    row = reproduction_row(_model(40.0, table), _model(40.0))
    assert row["parameter_of_largest"] == "b" and row["largest_shift_in_bounds"] == pytest.approx(1.1)
    assert row["reproduces"] is False and row["parameters"] == 2 and row["J_ave_refit"] == 40.5
    # the same first fit is the same cost to round-off; another cost is another model
    assert row["same_first_fit"] is True
    assert reproduction_row(_model(40.0, table), _model(40.0 * (1 + 1e-6)))["same_first_fit"] is False
    assert np.isfinite(row["largest_shift_in_bounds"])


def test_a_model_without_a_reproduction_check_is_refused():
    with pytest.raises(ValueError, match="reproduce=True"):
        reproduction_row(_model(40.0), _model(40.0))
