"""When an identified model is trusted (aircraft.identification.trust), on stub models and logs.

Each branch of the rule is exercised on a stand-in with only what trust_check reads:
free parameters with bounds, the reduction log, the settings' bounds, J_ave and the
degeneracy report. The expected verdicts are written out by hand from the rule.
"""
from types import SimpleNamespace

import pandas as pd
import pytest

from aircraft.identification.trust import TRUST_J_AVE_MAX, trust_check

LOG_COLUMNS = ["parameter", "reason", "metric_pct", "J_ave_before", "J_ave_after", "max_single_rise",
               "accepted", "runaway", "note"]


def _model(params, log_rows=None, J_ave=40.0, flat=None):
    parameters = pd.DataFrame([{"parameter": n, "status": "free", "cramer_rao_pct": cr,
                                "insensitivity_pct": ins} for n, cr, ins in params],
                              columns=["parameter", "status", "cramer_rao_pct", "insensitivity_pct"])
    degeneracy = None if flat is None else SimpleNamespace(flat_directions=pd.DataFrame({"parameters": flat}))
    return SimpleNamespace(name="stub", settings=SimpleNamespace(cramer_rao_max=20.0, insensitivity_max=10.0),
                           fit=SimpleNamespace(parameters=parameters, degeneracy=degeneracy), J_ave=J_ave,
                           reduction=None if log_rows is None else
                           SimpleNamespace(log=pd.DataFrame(log_rows, columns=LOG_COLUMNS)))


def test_a_parameter_whose_removal_spoils_one_response_is_kept_with_the_measured_rise():
    m = _model([("a", 5.0, 1.0), ("b", 31.0, 2.0)],
               [("b", "cramer_rao", 31.0, 40.0, 41.0, 16.7, False, False, "cost rise too large; kept")])
    g = trust_check(m)
    assert g.passes and g.failures == []
    assert g.table.set_index("parameter").verdict.to_dict() == {"a": "ok", "b": "kept"}
    row = g.table.set_index("parameter").loc["b"]
    assert "16.7" in row.reason and "limit 10" in row.reason


def test_the_average_rise_alone_also_keeps():
    m = _model([("b", 31.0, 2.0)], [("b", "cramer_rao", 31.0, 40.0, 42.5, 3.0, False, False, "")])
    assert trust_check(m).passes
    # ... but not when the caller allows a larger rise
    assert not trust_check(m, max_rise_average=3.0).passes


@pytest.mark.parametrize("log_rows, why", [
    ([], "did not try"),
    ([("b", "cramer_rao", 31.0, 40.0, 41.0, 5.0, False, False, "")], "never found its removal too costly"),
    ([("b", "cramer_rao", 31.0, 40.0, 41.0, 50.0, False, True, "runaway")], "ran away"),
])
def test_a_parameter_not_kept_by_the_rule_fails(log_rows, why):
    g = trust_check(_model([("b", 31.0, 2.0)], log_rows))
    assert not g.passes
    assert g.table.verdict.tolist() == ["fails"] and why in g.table.reason.iloc[0]


def test_an_insensitive_parameter_is_never_kept():
    m = _model([("c", 5.0, 14.0)], [("c", "insensitivity", 14.0, 40.0, 52.0, 30.0, False, False, "")])
    g = trust_check(m)
    assert not g.passes and "insensitivity" in g.table.reason.iloc[0]


def test_without_a_reduction_log_the_bounds_are_strict():
    g = trust_check(_model([("a", 5.0, 1.0), ("b", 31.0, 2.0)], log_rows=None))
    assert not g.passes and "no reduction log" in g.table.set_index("parameter").loc["b", "reason"]
    assert not g.limits["keep_rule"]


def test_j_ave_and_flat_directions_count():
    g = trust_check(_model([("a", 5.0, 1.0)], [], flat=["+a -b"]))
    assert g.failures == ["1 flat direction(s) of the cost: +a -b"]
    g = trust_check(_model([("a", 5.0, 1.0)], [], J_ave=1.5 * TRUST_J_AVE_MAX))
    assert not g.passes and g.failures[0].startswith("J_ave 150")
    # a published reference cost replaces the default limit
    assert trust_check(_model([("a", 5.0, 1.0)], [], J_ave=150.0), j_ave_max=171.0).passes


def test_a_model_file_record_is_judged_from_its_table():
    rec = SimpleNamespace(name="file", parameters=pd.DataFrame(
        [{"parameter": "m", "status": "free", "cramer_rao_pct": 3.0, "insensitivity_pct": 1.0},
         {"parameter": "t", "status": "fixed", "cramer_rao_pct": float("nan"), "insensitivity_pct": float("nan")}]),
        settings={"cramer_rao_max": 20.0, "insensitivity_max": 10.0}, J_ave=12.0)
    g = trust_check(rec)
    assert g.passes and g.table.parameter.tolist() == ["m"]


def test_bad_inputs():
    m = _model([("a", 5.0, 1.0)], [])
    with pytest.raises(ValueError, match="positive"):
        trust_check(m, max_rise_single=0.0)
    with pytest.raises(ValueError, match="positive"):
        trust_check(m, j_ave_max=-1.0)
    with pytest.raises(ValueError, match="no parameter table"):
        trust_check(SimpleNamespace(name="x"))
    assert trust_check(_model([], [])).failures[0] == "no free parameter"


def _fitted(values, cr=5.0, J_ave=40.0, status=None):
    """A stub with a parameter table holding values (as reproduction_check reads it)."""
    rows = [{"parameter": n, "value": v, "status": (status or {}).get(n, "free"), "cramer_rao_pct": cr,
             "insensitivity_pct": 1.0} for n, v in values.items()]
    return SimpleNamespace(name="stub", fit=SimpleNamespace(parameters=pd.DataFrame(rows), degeneracy=None),
                           J_ave=J_ave, settings=None, reduction=None)


def test_reproduction_within_the_bounds_passes_and_outside_fails():
    from aircraft.identification.trust import reproduction_check
    first = _fitted({"m": 1.0, "l": -2.0})
    # 4.9 % and 4.5 % moves against a 5 % bound: reproduced
    check = reproduction_check(first, _fitted({"m": 1.049, "l": -2.09}))
    assert check.passes and check.failures == []
    assert check.table.shift_in_bounds.round(6).tolist() == [0.98, 0.9]
    # a 6 % move of l fails, with its numbers in the reason
    check = reproduction_check(first, _fitted({"m": 1.0, "l": -2.12}))
    assert not check.passes and check.table.reproduced.tolist() == [True, False]
    assert "l moved 6 %" in check.failures[0]


def test_reproduction_fails_when_the_two_fits_keep_different_parameters():
    from aircraft.identification.trust import reproduction_check
    first = _fitted({"m": 1.0, "l": -2.0})
    removed = reproduction_check(first, _fitted({"m": 1.0, "l": 0.0}, status={"l": "fixed"}))
    assert removed.failures == ["l is not free in the second fit"]
    extra = reproduction_check(first, _fitted({"m": 1.0, "l": -2.0, "t": 0.02}))
    assert extra.failures == ["t is free only in the second fit"]


def test_trust_includes_the_reproduction_when_there_is_one():
    from aircraft.identification.trust import reproduction_check
    first = _fitted({"m": 1.0, "l": -2.0})
    assert trust_check(first).limits["reproduction"] == "not checked" and trust_check(first).passes
    good = reproduction_check(first, _fitted({"m": 1.01, "l": -2.0}))
    assert trust_check(first, reproduction=good).passes
    assert trust_check(first, reproduction=good).limits["reproduction"] == "reproduced"
    bad = reproduction_check(first, _fitted({"m": 1.5, "l": -2.0}))
    g = trust_check(first, reproduction=bad)
    assert not g.passes and g.limits["reproduction"] == "not reproduced"
    assert any("does not reproduce" in f and "m moved 50 %" in f for f in g.failures)
    # the model's own reproduction is used when none is passed
    first.reproduction = bad
    assert not trust_check(first).passes


def test_the_refit_rule_judges_the_parameters_and_reports_the_structure_apart():
    from aircraft.identification.trust import reproduction_check
    first = _fitted({"m": 1.0, "l": -2.0})
    # the reduction on the second data set dropped l, but the first structure refitted
    # there moves m by 3 % and l by 4 % against 5 % bounds: the fit reproduces
    again = _fitted({"m": 1.4, "l": 0.0}, status={"l": "fixed"})
    check = reproduction_check(first, again, refit=_fitted({"m": 1.03, "l": -2.08}, J_ave=41.0))
    assert check.rule == "refit" and check.passes and check.failures == []
    assert check.same_structure is False and check.parameters_reproduce is True
    assert check.structure_failures == ["l is not free in the second fit"]
    # the verdict's table is the refit's (0.6 and 0.8 bounds, by hand: 3/5, 4/5) ...
    assert check.table.shift_in_bounds.round(6).tolist() == [0.6, 0.8]
    assert (check.J_ave, check.J_ave_again, check.J_ave_refit) == (40.0, 40.0, 41.0)
    # ... the identification's is kept beside it, and the former rule still fails on it
    assert check.identification.reproduced.tolist() == [False, False]
    old = reproduction_check(first, again, refit=_fitted({"m": 1.03, "l": -2.08}), rule="identification")
    assert not old.passes and old.parameters_reproduce is True
    assert old.failures == ["m moved 40 % (its bound 5 %)", "l is not free in the second fit"]
    assert trust_check(first, reproduction=check).passes
    assert trust_check(first, reproduction=check).limits["reproduction_structure"] == "different"
    assert not trust_check(first, reproduction=old).passes
    assert "same structure False" in check.summary()


def test_the_refit_rule_fails_on_a_refit_outside_the_bounds_or_one_that_failed():
    from aircraft.identification.trust import reproduction_check
    first = _fitted({"m": 1.0, "l": -2.0})
    same = _fitted({"m": 1.0, "l": -2.0})
    # the reduction keeps the structure, the refit moves l 7.5 % against its 5 % bound
    check = reproduction_check(first, same, refit=_fitted({"m": 1.0, "l": -2.15}))
    assert check.same_structure is True and not check.passes and check.parameters_reproduce is False
    assert check.failures == ["l moved 7.5 % (its bound 5 %)"]
    g = trust_check(first, reproduction=check)
    assert any("(the first structure refitted)" in f and "l moved 7.5 %" in f for f in g.failures)
    assert g.limits["reproduction_structure"] == "same"
    # a refit that could not run (unstable, no coherent point) is a failure, with its reason
    failed = reproduction_check(first, same, refit_error="UnstableModelError: poles [0.1]")
    assert failed.rule == "refit" and not failed.passes and failed.parameters_reproduce is False
    assert failed.failures == ["the refit on the second data set failed: UnstableModelError: poles [0.1]"]
    assert failed.table.reproduced.tolist() == [False, False] and "failed" in failed.summary()
    # the refit alone (no second identification): the structure is not checked
    alone = reproduction_check(first, refit=_fitted({"m": 1.01, "l": -2.0}))
    assert alone.passes and alone.same_structure is None and alone.structure_failures == []
    assert trust_check(first, reproduction=alone).limits["reproduction_structure"] == "not checked"


def test_reproduction_check_refuses_what_it_cannot_judge():
    from aircraft.identification.trust import reproduction_check
    first = _fitted({"m": 1.0})
    with pytest.raises(ValueError, match="again"):
        reproduction_check(first)
    with pytest.raises(ValueError, match="rule"):
        reproduction_check(first, first, rule="both")
    with pytest.raises(ValueError, match="'refit' rule needs"):
        reproduction_check(first, first, rule="refit")
    with pytest.raises(ValueError, match="'identification' rule needs"):
        reproduction_check(first, refit=first, rule="identification")


def test_a_synthetic_identification_refitted_on_slightly_different_data_reproduces():
    """A known 2-state truth fitted by flightid, its structure refitted on a second record
    whose measurement noise differs: the refit must stay well inside the bounds."""
    import control
    import numpy as np
    from flightid import FGCStructure, fit, frequency_response, frequency_sweep
    from aircraft.identification.trust import refit_structure, reproduction_check
    t, u = frequency_sweep(1.0, 20.0, 40.0, 0.01, seed=0)
    truth = control.ss([[-2.0, 0.0], [0.0, -5.0]], [[4.0], [3.0]], np.eye(2), np.zeros((2, 1)))
    y = control.forced_response(truth, t, u).outputs.T
    rng = np.random.default_rng(1)
    # two records of the same truth, differing only in 1e-3 noise (~0.1 % of the signals)
    records = [frequency_response(t, u, y + 1e-3 * rng.standard_normal(y.shape), w_min=1.0, w_max=20.0,
                                  output_names=["y1", "y2"]) for _ in range(2)]
    start = FGCStructure([["f1", "f12"], ["f21", "f2"]], [["g1"], ["g2"]], np.eye(2), inputs=["u"],
                         outputs=["y1", "y2"], initial={"f1": -1.0, "f12": 0.0, "f21": 0.0, "f2": -3.0, "g1": 1.0,
                                                        "g2": 1.0}, fixed=["f12", "f21"])
    first = fit(start, records[0])
    model = SimpleNamespace(fit=first, J_ave=first.J_ave, settings=SimpleNamespace(n_omega=20, coherence_min=0.6),
                            structure=SimpleNamespace(fit_options={}), fit_start=dict(start.values))
    # the fit finds the truth (within 2 % = well inside its bounds of ~5-8 %) ...
    v = first.structure.values
    assert np.allclose([v["f1"], v["f2"], v["g1"], v["g2"]], [-2.0, -5.0, 4.0, 3.0], rtol=0.02)
    # ... the refit on the same record from the same start is the same optimum (to the
    # optimizer's rounding), the fixed couplings stay fixed at their values
    same = refit_structure(model, records[0])
    assert np.allclose([same.structure.values[n] for n in start.names], [v[n] for n in start.names],
                       rtol=1e-9, atol=0)
    assert same.structure.fixed == {"f12", "f21"}
    # ... and on the second record it moves, but by a small fraction of the bounds
    again = refit_structure(model, records[1])
    check = reproduction_check(model, refit=again)
    assert check.passes and check.parameters_reproduce and check.same_structure is None
    assert (check.table.shift_pct > 0).all()
    # 1e-3 noise against unit signals: the shifts measured ~1e-3..1e-2 bounds; 0.1 leaves
    # room for another noise draw and still fails a fit that jumps to another optimum
    assert (check.table.shift_in_bounds < 0.1).all()


def test_the_table_of_both_parts_puts_the_judged_part_first():
    from aircraft.identification.trust import reproduction_check
    first = _fitted({"m": 1.0, "l": -2.0})
    again = _fitted({"m": 1.0})
    check = reproduction_check(first, again, refit=_fitted({"m": 1.0, "l": -2.0}))
    t = check.to_pandas()
    assert t.part.tolist() == ["refit"] * 2 + ["identification"] * 2
    assert t.judged.tolist() == [True, True, False, False]
    old = reproduction_check(first, again, refit=_fitted({"m": 1.0, "l": -2.0}), rule="identification")
    assert old.to_pandas().part.tolist()[:2] == ["identification"] * 2
    failed = reproduction_check(first, refit_error="no coherent point").to_pandas()
    assert failed.part.tolist() == ["refit"] * 2 and not failed.reproduced.any()


def test_relative_rise_rule_keeps_by_the_first_fits_cost():
    from flightid import ReductionRule
    # first fit J_ave 0.1; removing b raised J_ave to 0.16 and one J by 0.05
    m = _model([("b", 31.0, 2.0)], [("b", "cramer_rao", 31.0, 0.1, 0.16, 0.05, False, False, "")], J_ave=0.1)
    # absolute limits (+2, +10): the rise is nothing, b fails
    assert trust_check(m).table.verdict.tolist() == ["fails"]
    # relative 0.5: limits 0.5 * 0.1 = 0.05 on J_ave and 0.25 on one J: 0.06 > 0.05 keeps b
    g = trust_check(m, rule=ReductionRule(relative_rise=0.5))
    assert g.passes and g.table.verdict.tolist() == ["kept"]
    assert g.limits["max_rise_average"] == pytest.approx(0.05) and g.limits["max_rise_single"] == pytest.approx(0.25)
    with pytest.raises(ValueError, match="rule must be"):
        trust_check(m, rule={"relative_rise": 0.5})


def test_residual_statistic_rule_judges_by_the_standard_errors():
    import numpy as np
    from scipy.signal import lsim
    from flightid import ReductionRule, fit, frequency_response, frequency_sweep
    from flightid.transfer_function import TransferFunctionStructure
    # 2 e^{-0.005 s} / (s + 1.5) at 1 % output noise: the delay is ~16 standard errors from zero
    t, u = frequency_sweep(0.3, 30.0, 90.0, 0.005, trim_start=20.0, trim_end=5.0, noise_fraction=0.2, seed=0)
    y = lsim(([2.0], [1.0, 1.5]), np.concatenate([[0.0], u[:-1]]), t)[1]
    y = y + 0.01 * np.std(y) * np.random.default_rng(1).standard_normal(t.size)
    r = fit(TransferFunctionStructure(0, 1, initial={"b0": 1.5, "a0": 1.0, "tau": 0.01}),
            frequency_response(t, u, y, w_min=0.5, w_max=12.0))
    m = SimpleNamespace(name="fit", settings=None, fit=r, J_ave=r.J_ave, reduction=None)
    # CIFER's bounds do not follow the noise: tau fails them (insensitivity ~87 %)
    assert trust_check(m).table.set_index("parameter").verdict["tau"] == "fails"
    g = trust_check(m, rule=ReductionRule(statistic="residual"))
    assert g.passes and list(g.table.columns[1:3]) == ["standard_error_pct", "standard_error_alone_pct"]
    assert g.table.set_index("parameter").standard_error_pct["tau"] < 10
    # a stand-in without a fit to compute them from is refused, by name
    with pytest.raises(ValueError, match="residual-scaled"):
        trust_check(_model([("b", 5.0, 1.0)]), rule=ReductionRule(statistic="residual"))
