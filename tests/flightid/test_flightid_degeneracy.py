"""Degeneracy guards of flightid (what J cannot see), each against a closed form:
flat directions, rank-deficient square blocks, multi-start agreement, reduce's
runaway guard, and refusal of data without information."""
import numpy as np
import pandas as pd
import pytest

from flightid import FGCStructure, MeasuredResponse, IdentificationError, fit, reduce
from flightid.degeneracy import NoInformationError

# 39 points: the default 20-point fit grid is every other one, so no interpolation error
W = np.geomspace(0.5, 30.0, 39)
S = 1j * W


def _data(h, outputs, inputs, coherence=1.0):
    """Exact (analytic) response matrix as a MeasuredResponse with constant coherence."""
    h = np.asarray(h, dtype=complex)
    if h.ndim == 1:
        h = h[None, None, :]
    return MeasuredResponse(h, W, np.full(h.shape, coherence), inputs, outputs)


def _lag():
    return _data(4.0 / (S + 2.0), ["y"], ["u"])


def _single_mode(**initial):
    return FGCStructure([["-a"]], [["g"]], [[1.0]], inputs=["u"], outputs=["y"],
                        initial={"a": 1.0, "g": 1.0, **initial})


def _redundant_pair():
    # two identical modes (pole tied) summed: y = (g1 + g2) / (s + a); only g1 + g2
    # is identifiable, so J is exactly flat along g1 - g2
    return FGCStructure([["-a", 0], [0, "-a"]], [["g1"], ["g2"]], [[1.0, 1.0]], inputs=["u"],
                        outputs=["y"], initial={"a": 1.0, "g1": 1.0, "g2": 3.0})


def test_exactly_redundant_pair_is_reported_flat_with_both_names():
    res = fit(_redundant_pair(), _lag())
    flat = res.flat_directions
    assert len(flat) == 1
    comps = flat.components.iloc[0]
    assert set(comps) == {"g1", "g2"}            # a is determined and does not move
    # closed form: the null direction is d(g1, g2) ~ (1, -1); in relative units
    # z = d / |theta| this is (1/|g1|, -1/|g2|), so z_g2 / z_g1 = -|g1| / |g2|
    g1, g2 = res.structure.values["g1"], res.structure.values["g2"]
    assert comps["g2"] / comps["g1"] == pytest.approx(-abs(g1) / abs(g2), rel=1e-4)
    assert g1 + g2 == pytest.approx(4.0, rel=1e-6)
    # exact redundancy: eigenvalue ratio at rounding level, condition >= 1e10
    assert flat.eigenvalue_ratio.iloc[0] < 1e-10
    assert res.condition_number > 1e10
    assert any("g1" in w and "g2" in w and "move together" in w for w in res.warnings)


def test_well_posed_fit_has_no_flat_direction():
    res = fit(_single_mode(), _lag())
    assert res.structure.values["a"] == pytest.approx(2.0, rel=1e-6)
    assert res.flat_directions.empty and res.degeneracy.no_influence == []
    # two parameters, pole and gain: the relative-unit Hessian is far from singular
    assert res.condition_number < 1e4
    assert res.success and res.warnings == []


def test_rank_one_square_block_gets_a_singular_value_warning():
    # 2 x 2 block of first-order elements, y = K u / (s + 1)
    structure = FGCStructure([["-a1", 0, 0, 0], [0, "-a2", 0, 0], [0, 0, "-a3", 0], [0, 0, 0, "-a4"]],
                             [["g11", 0], [0, "g12"], ["g21", 0], [0, "g22"]],
                             [[1.0, 1.0, 0, 0], [0, 0, 1.0, 1.0]], inputs=["u1", "u2"], outputs=["y1", "y2"],
                             initial={"a1": 2, "a2": 2, "a3": 2, "a4": 2, "g11": 1, "g12": 1, "g21": 1,
                                      "g22": 1})
    lag = 1.0 / (S + 1.0)
    rank_one = np.array([[1.0, 2.0], [2.0, 4.0]])            # sigma_2 = 0 exactly
    res = fit(structure, _data(rank_one[:, :, None] * lag, ["y1", "y2"], ["u1", "u2"]))
    sv = res.singular_value_ratios
    assert set(sv.block) == {"[y1, y2] / [u1, u2]"}
    assert sv.sv_ratio_data.max() < 1e-12
    assert any("nearly rank-deficient in the data" in w for w in res.warnings)
    # a well-conditioned block: no warning, and the ratios match numpy's SVD of the
    # constant matrix (the scalar lag cancels in sigma_min / sigma_max)
    full = np.array([[1.0, 0.2], [0.3, 1.0]])
    ok = fit(structure, _data(full[:, :, None] * lag, ["y1", "y2"], ["u1", "u2"]))
    sv_c = np.linalg.svd(full, compute_uv=False)
    np.testing.assert_allclose(ok.singular_value_ratios.sv_ratio_data, sv_c[1] / sv_c[0], rtol=1e-9)
    # the fit is exact, so the model's ratio agrees (1e-3: optimizer tolerance)
    np.testing.assert_allclose(ok.singular_value_ratios.sv_ratio_model, sv_c[1] / sv_c[0], rtol=1e-3)
    assert not any("square block" in w for w in ok.warnings)


def test_multistart_agrees_on_a_well_posed_problem_and_not_on_a_redundant_one():
    good = fit(_single_mode(), _lag(), starts=5, seed=3)
    ms = good.multistart
    assert len(ms.table) == 5 and ms.table.best.sum() == 1
    assert ms.agree, ms.summary()
    assert ms.parameter_spread.max() < 1e-4 and ms.cost_spread < 1e-6
    # seeded: the same seed gives the same starts
    again = fit(_single_mode(), _lag(), starts=5, seed=3)
    pd.testing.assert_frame_equal(ms.table, again.multistart.table)
    # redundant pair: every start reaches J = 0 with a different split of g1 + g2
    bad = fit(_redundant_pair(), _lag(), starts=4, seed=1)
    assert bad.multistart.cost_spread < 1e-6
    assert not bad.multistart.agree
    assert bad.multistart.parameter_spread[["g1", "g2"]].min() > 0.02
    assert any("DISAGREE" in w for w in bad.warnings)
    with pytest.raises(IdentificationError, match="starts must be a positive integer"):
        fit(_single_mode(), _lag(), starts=0)


def test_fit_refuses_data_without_coherent_points():
    # coherence zero everywhere with coherence_min = 0 used to return
    # J_ave = 0 and success with the initial guess
    dead = _data(4.0 / (S + 2.0), ["y"], ["u"], coherence=0.0)
    with pytest.raises(NoInformationError, match="no response has a coherent point"):
        fit(_single_mode(), dead, coherence_min=0.0)
    with pytest.raises(NoInformationError, match="y/u has no coherent point"):
        fit(_single_mode(), dead, coherence_min=0.0, pairs=[("y", "u")])
    assert issubclass(NoInformationError, IdentificationError)


def test_a_parameter_without_influence_marks_the_fit_failed():
    # the second state is not observed (C = [1, 0]): b and h cannot affect y
    s = FGCStructure([["-a", 0], [0, "-b"]], [["g"], ["h"]], [[1.0, 0.0]], inputs=["u"], outputs=["y"],
                     initial={"a": 1.0, "b": 3.0, "g": 1.0, "h": 1.0})
    res = fit(s, _lag())
    assert not res.success
    assert res.degeneracy.no_influence == ["b", "h"]
    assert "no influence" in res.message and "['b', 'h']" in res.message
    assert "FIT FAILED" in res.summary()


def _gain_plus_lag_problem():
    # data: a static gain with a small, fast lag, h = 2 + 0.4 / (s + 40): exactly
    # y = d + g/(s + a) with d = 2, g = 0.4, a = 40. Without d, a first-order lag
    # g/(s + a) can only approach the (nearly) flat response as a -> infinity with
    # g/a -> 2: there is no finite optimum near the previous one.
    data = _data(2.0 + 0.4 / (S + 40.0), ["y"], ["u"])
    s = FGCStructure([["-a"]], [["g"]], [[1.0]], D=[["d"]], inputs=["u"], outputs=["y"],
                     initial={"a": 30.0, "g": 0.3, "d": 1.5})
    return s, data


def test_feedthrough_structure_fits_gain_plus_lag_exactly():
    s, data = _gain_plus_lag_problem()
    res = fit(s, data)
    got = res.structure.values
    assert got["a"] == pytest.approx(40.0, rel=1e-5)
    assert got["g"] == pytest.approx(0.4, rel=1e-5)
    assert got["d"] == pytest.approx(2.0, rel=1e-5)
    assert res.model.D[0, 0] == pytest.approx(2.0, rel=1e-5)


def test_reduce_refuses_a_removal_after_which_a_parameter_runs_away():
    s, data = _gain_plus_lag_problem()
    # d the only candidate (a, g protected), cost rises allowed: only the guard can refuse
    kw = dict(insensitivity_max=-1.0, cramer_rao_max=-1.0, max_rise_average=1e6, max_rise_single=1e6,
              protected=("a", "g"))
    guarded = reduce(s, data, **kw)
    row = guarded.log.set_index("parameter").loc["d"]
    assert not row.accepted and row.runaway
    assert "ran away" in row.note and "no finite optimum" in row.note
    assert "d" not in guarded.removed
    # the same reduction without the guard accepts removing d, and the pole runs
    # off by orders of magnitude -- the failure the cost cannot see
    blind = reduce(s, data, runaway_factor=None, max_condition=None, refuse_flat=False, **kw)
    assert blind.removed == ["d"]
    # a: 40 -> ~1e4, g: 0.4 -> ~2e4, at a cost J_ave < 0.01 (measured 4e-4)
    assert blind.result.structure.values["a"] > 100 * 40.0
    assert blind.result.J_ave < 0.01
