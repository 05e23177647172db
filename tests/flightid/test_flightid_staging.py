"""Staged fitting (§6.4.3) on a closed-form two-input problem."""
import numpy as np
import pandas as pd
import pytest

from flightid import FGCStructure, IdentificationError, MeasuredResponse, fit, fit_staged
from flightid.staging import Stage, StagedFitResult

# 39 points: the default 20-point fit grid is every other one (no interpolation error)
W = np.geomspace(0.5, 30.0, 39)
S = 1j * W


def _data():
    # y = 4/(s + 2) u - 2/(s + 5) v, exact, coherence 1
    h = np.stack([4.0 / (S + 2.0), -2.0 / (S + 5.0)])[None, :, :]
    return MeasuredResponse(h, W, np.ones(h.shape), ["u", "v"], ["y"])


def _structure(**initial):
    init = {"a": 1.0, "gu": 1.0, "b": 1.0, "gv": 0.0, "du": 0.5, **initial}
    return FGCStructure([["-a", 0], [0, "-b"]], [["gu", 0], [0, "gv"]], [[1.0, 1.0]], D=[["du", 0]],
                        inputs=["u", "v"], outputs=["y"], initial=init)


def _plan(prune=None):
    # gv starts at 0, so y/v starts identically zero (-inf dB, zero gradient):
    # the stage asks fit to revive it from the data
    return [Stage("u path", free=["a", "gu", "du"], pairs=[("y", "u")], prune_insensitive=prune),
            Stage("add v path", free=["b", "gv"], add_pairs=[("y", "v")],
                  fit_kwargs={"revive_dead_pairs": True}),
            Stage("all used", free="used")]


def test_stages_freeze_free_and_add_responses_in_order():
    staged = fit_staged(_structure(), _data(), _plan())
    assert isinstance(staged, StagedFitResult)
    log = staged.log
    assert list(log.n_pairs) == [1, 2, 2]
    assert list(log.n_free) == [3, 2, 5]
    assert log.free.iloc[1] == "b, gv"
    s1, s2 = (r.structure.values for r in staged.stages[:2])
    # stage 1 sees only y/u and fits it exactly (noise-free, on-grid: 1e-6);
    # the v-path parameters are untouched
    assert s1["a"] == pytest.approx(2.0, rel=1e-6) and s1["gu"] == pytest.approx(4.0, rel=1e-6)
    assert s1["b"] == 1.0 and s1["gv"] == 0.0
    # stage 2 holds stage 1's values and fits the v path
    assert s2["a"] == s1["a"] and s2["gu"] == s1["gu"]
    assert s2["b"] == pytest.approx(5.0, rel=1e-6) and s2["gv"] == pytest.approx(-2.0, rel=1e-6)
    final = staged.result.structure.values
    assert final["du"] == pytest.approx(0.0, abs=1e-6)
    assert staged.result.J_ave < 1e-8
    # the log's J_ave is each stage's own fit
    np.testing.assert_allclose(log.J_ave, [r.J_ave for r in staged.stages])
    assert isinstance(staged.to_pandas(), pd.DataFrame)


def test_revival_starts_a_dead_pair_from_the_data():
    # from gv = 0 the dB cost of y/v is -inf with zero gradient; revival starts gv
    # at the data's median magnitude with the sign whose phase fits (here negative)
    s = _structure(a=2.0, gu=4.0, du=0.0)
    from flightid.fitting import _Problem, _prepare_pairs
    # explicit pairs: by default a pair whose model is zero at the start counts as
    # structurally zero and is not fitted
    both = [("y", "u"), ("y", "v")]
    pairs, _ = _prepare_pairs(s, [_data()], both, None, 20, 0.6)
    problem = _Problem(s.fix(["a", "gu", "du"]), pairs, 0.0)
    x = problem.revive(np.array([1.0, 0.0]))          # (b, gv)
    assert x[0] == 1.0 and x[1] < 0
    revived = fit(s.fix(["a", "gu", "du"]), _data(), pairs=both, revive_dead_pairs=True)
    assert revived.structure.values["gv"] == pytest.approx(-2.0, rel=1e-6)


def test_prune_insensitive_sets_back_to_zero_parameters_without_effect():
    # du's true value is 0: after stage 1 its relative insensitivity is enormous,
    # so a loose step-4(d) threshold (100 %) removes it and the stage is re-fitted
    staged = fit_staged(_structure(), _data(), _plan(prune=100.0))
    assert staged.log.pruned.iloc[0] == "du"
    final = staged.result.structure
    assert final.values["du"] == 0.0 and "du" in final.fixed
    assert "du" not in staged.log.free.iloc[2].split(", ")   # "used" excludes pruned ones
    assert final.values["a"] == pytest.approx(2.0, rel=1e-6)


def test_the_same_result_as_fitting_by_hand():
    # the facility is bookkeeping around fit(): stage 1 by hand gives the same numbers
    s = _structure()
    by_hand = fit(s.fix(["b", "gv"]), _data(), pairs=[("y", "u")])
    staged = fit_staged(s, _data(), _plan()[:1])
    for n in ("a", "gu", "du"):
        assert staged.result.structure.values[n] == by_hand.structure.values[n]


def test_staged_plan_validation():
    with pytest.raises(IdentificationError, match="frees unknown parameters"):
        fit_staged(_structure(), _data(), [Stage("bad", free=["nope"])])
    with pytest.raises(IdentificationError, match="one of"):
        fit_staged(_structure(), _data(), [Stage("bad", free="everything")])
    with pytest.raises(IdentificationError, match="non-empty sequence of flightid.staging.Stage"):
        fit_staged(_structure(), _data(), [])
    # an error inside a stage names the stage
    with pytest.raises(IdentificationError, match=r"stage 0 \('v only'\)"):
        fit_staged(_structure(), _data(), [Stage("v only", free=["b"], pairs=[("y", "w")])])
