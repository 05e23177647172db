"""The guideline's keep rule read from a reduction log (aircraft.identification.guideline)."""
from types import SimpleNamespace

import pandas as pd
import pytest

from aircraft.identification.guideline import guideline_check

LOG_COLUMNS = ["parameter", "reason", "metric_pct", "J_ave_before", "J_ave_after", "max_single_rise",
               "accepted", "runaway", "note"]


def _model(params, log_rows, other_failures=()):
    """A stand-in with what guideline_check reads: free parameters with bounds, the
    reduction log, the settings' bounds and the strict check's sentences."""
    parameters = pd.DataFrame([{"parameter": n, "status": "free", "cramer_rao_pct": cr,
                                "insensitivity_pct": ins} for n, cr, ins in params])
    strict = [f"Cramer-Rao bound >= 20 % (or undefined) on [...]"] + list(other_failures)
    return SimpleNamespace(name="stub", settings=SimpleNamespace(cramer_rao_max=20.0, insensitivity_max=10.0),
                           fit=SimpleNamespace(parameters=parameters),
                           reduction=SimpleNamespace(log=pd.DataFrame(log_rows, columns=LOG_COLUMNS)),
                           trust_failures=lambda: strict)


def test_a_parameter_whose_removal_spoils_one_response_is_kept_with_the_measured_rise():
    m = _model([("a", 5.0, 1.0), ("b", 31.0, 2.0)],
               [("b", "cramer_rao", 31.0, 40.0, 41.0, 16.7, False, False, "cost rise too large; kept")])
    g = guideline_check(m)
    assert g.passes and g.failures == []
    row = g.table.set_index("parameter").loc["b"]
    assert row.verdict == "kept" and "16.7" in row.reason and "limit 10" in row.reason
    assert list(g.table.parameter) == ["b"]          # parameters within the bounds are not listed


@pytest.mark.parametrize("log_rows, why", [
    ([], "did not try"),
    ([("b", "cramer_rao", 31.0, 40.0, 41.0, 5.0, False, False, "")], "never found its removal too costly"),
    ([("b", "cramer_rao", 31.0, 40.0, 41.0, 50.0, False, True, "runaway")], "ran away"),
])
def test_a_parameter_not_kept_by_the_rule_fails(log_rows, why):
    g = guideline_check(_model([("b", 31.0, 2.0)], log_rows))
    assert not g.passes
    assert g.table.verdict.tolist() == ["fails"] and why in g.table.reason.iloc[0]


def test_an_insensitive_parameter_is_never_kept():
    m = _model([("c", 5.0, 14.0)], [("c", "insensitivity", 14.0, 40.0, 52.0, 30.0, False, False, "")])
    g = guideline_check(m)
    assert not g.passes and "insensitivity" in g.table.reason.iloc[0]


def test_j_ave_and_flat_directions_still_count():
    m = _model([("a", 5.0, 1.0)], [], other_failures=["1 flat direction(s) of the cost: +a -b"])
    g = guideline_check(m)
    assert g.failures == ["1 flat direction(s) of the cost: +a -b"]


def test_bad_inputs():
    m = _model([("a", 5.0, 1.0)], [])
    with pytest.raises(ValueError, match="positive"):
        guideline_check(m, max_rise_single=0.0)
    m.reduction = None
    with pytest.raises(ValueError, match="no reduction log"):
        guideline_check(m)
