"""Statistics that follow the noise on the CIFER path: residual-scaled standard errors beside
CIFER's bounds, and the reduction's relative rise limits counted from the first fit.

Truth: a first-order-plus-delay system 2 e^{-tau s} / (s + 1.5) simulated with scipy
from a 90 s CIFER sweep, and the Monte Carlo scatter of noisy repeats.
"""
import numpy as np
import pytest
from scipy.signal import lsim

from flightid import ReductionRule, fit, frequency_response, frequency_sweep, reduce
from flightid.transfer_function import TransferFunctionStructure


def _sweep_record(dt, delay_samples):
    t, u = frequency_sweep(0.3, 30.0, 90.0, dt, trim_start=20.0, trim_end=5.0, noise_fraction=0.2, seed=0)
    ud = np.concatenate([np.zeros(delay_samples), u[:u.size - delay_samples]])
    return t, u, lsim(([2.0], [1.0, 1.5]), ud, t)[1]


@pytest.mark.slow
def test_scaled_standard_errors_follow_the_noise_and_leave_cifer_bounds_unchanged():
    t, u, y0 = _sweep_record(0.01, 5)                          # tau = 0.05 s
    s = TransferFunctionStructure(0, 1, initial={"b0": 2.0, "a0": 1.5, "tau": 0.05})
    out = {}
    for noise in (0.10, 0.30):
        rng = np.random.default_rng(11)
        est, se, cr = [], [], []
        for _ in range(30):
            y = y0 + noise * np.std(y0) * rng.standard_normal(t.size)
            r = fit(s, frequency_response(t, u, y, w_min=0.5, w_max=12.0), frequency_ranges=(0.5, 12.0))
            stats = r.statistics
            # the CIFER columns are the fit's own, untouched
            assert stats.cramer_rao_pct.tolist() == r.parameters.cramer_rao_pct.tolist()
            est.append([r.structure.values[n] for n in s.names])
            se.append(stats.standard_error.to_numpy())
            cr.append(stats.cramer_rao_pct.to_numpy())
        out[noise] = (np.std(est, axis=0, ddof=1), np.mean(se, axis=0), np.mean(cr, axis=0))
    for noise, (scatter, se, _) in out.items():
        # residuals of neighbouring CIFER points are correlated (overlapping windows, 20
        # interpolated points): measured ratios 0.45-1.3, so a factor-2 band -- the CIFER
        # bound, in contrast, is 4-23 x the scatter here
        assert np.all((se / scatter > 0.4) & (se / scatter < 2.0)), (noise, se / scatter)
    # tripling the noise triples the scaled error (within 30 %: 30 repeats, sampling error
    # ~13 % on each scatter) but leaves CIFER's relative bound within 25 %
    np.testing.assert_allclose(out[0.30][1] / out[0.10][1], 3.0, rtol=0.3)
    assert np.all(out[0.30][2] / out[0.10][2] < 1.25)


def test_relative_rise_keeps_a_delay_the_data_pin_down():
    t, u, y = _sweep_record(0.005, 1)                          # tau = 5 ms
    y = y + 0.01 * np.std(y) * np.random.default_rng(1).standard_normal(t.size)
    data = frequency_response(t, u, y, w_min=0.5, w_max=12.0)
    s = TransferFunctionStructure(0, 1, initial={"b0": 1.5, "a0": 1.0, "tau": 0.01})
    default = reduce(s, data)
    relative = reduce(s, data, relative_rise=0.5)
    first = default.initial.statistics.set_index("parameter")
    # the data pin tau many standard errors from zero (measured ~16)
    assert first.loc["tau", "value"] / first.loc["tau", "standard_error"] > 10
    # absolute step limits (J_ave +2) accept its removal at J_ave ~ 0.09 -> 0.66 ...
    assert "tau" in default.removed
    moved = abs(default.result.structure.values["a0"] - first.loc["a0", "value"])
    assert moved > 3 * first.loc["a0", "standard_error"]       # ... moving a0 by > 3 SE
    # relative limits (J_ave may rise by 50 % of the first fit's) keep it, at its truth
    assert relative.removed == []
    assert relative.result.structure.values["tau"] == pytest.approx(0.005, rel=0.1)   # 10 %: ~2 SE
    # the residual statistic sees it pinned down too (the CIFER bound and insensitivity of
    # 186 % and 87 % do not follow the 1 % noise): it is no candidate at all
    for rule in (ReductionRule(statistic="residual"), ReductionRule(statistic="residual", noise="differences",
                                                                    covariance="sandwich")):
        residual = reduce(s, data, rule=rule)
        assert residual.removed == [] and len(residual.log) == 0 and residual.rule == rule
    assert first.loc["tau", "insensitivity_pct"] > 10 and first.loc["tau", "cramer_rao_pct"] > 20
    # the same rule still removes a delay the data do not hold (4 / (s + 2), no delay)
    t2, u2 = frequency_sweep(0.5, 20.0, 60.0, 0.01, seed=0)
    y2 = lsim(([4.0], [1.0, 2.0]), u2, t2)[1] * (1 + 0.01 * np.random.default_rng(2).standard_normal(t2.size))
    none = reduce(s, frequency_response(t2, u2, y2, w_min=0.5, w_max=20.0), rule=ReductionRule(statistic="residual"))
    assert none.removed == ["tau"]


def test_the_rule_is_one_place():
    data = frequency_response(*_sweep_record(0.01, 5)[:3], w_min=0.5, w_max=12.0)
    s = TransferFunctionStructure(0, 1, initial={"b0": 2.0, "a0": 1.5, "tau": 0.05})
    with pytest.raises(ValueError, match="contradicts rule.relative_rise"):
        reduce(s, data, relative_rise=0.5, rule=ReductionRule(relative_rise=0.2))
    for bad, match in ((dict(statistic="bayes"), "statistic must be"), (dict(noise="x"), "noise must be"),
                       (dict(relative_rise=-1.0), "relative_rise")):
        with pytest.raises(ValueError, match=match):
            ReductionRule(**bad)
    # the keyword is shorthand for the rule
    assert reduce(s, data, relative_rise=0.5).rule == ReductionRule(relative_rise=0.5)


def test_joint_input_output_propagated_coherence_against_monte_carlo():
    from flightid import MeasuredResponse, joint_input_output
    # u/theta with condition number 2.7, every element at coherence 0.95; y/theta likewise
    # up to the same coherence; n_d = 20 averages
    U0 = np.array([[1.0, 0.45], [0.35, 0.8]], dtype=complex) * np.exp(0.3j)
    H0 = np.array([[2.0, 0.05]], dtype=complex)                     # a small off-axis element
    Y0 = H0 @ U0
    coh, n_d = 0.95, 20
    eps = np.sqrt((1 - coh) / (2 * n_d * coh))                        # Bendat & Piersol
    rng = np.random.default_rng(3)
    n = 4000

    def noisy(x):     # radial and tangential relative errors of std eps
        return x * (1 + eps * (rng.standard_normal((n,) + x.shape) + 1j * rng.standard_normal((n,) + x.shape)))
    H = noisy(Y0) @ np.linalg.inv(noisy(U0))
    mc_eps = np.sqrt(np.mean(np.abs(H - H0) ** 2, axis=0) / 2) / np.abs(H0)    # per-component std
    w = np.array([1.0])
    yt = MeasuredResponse(Y0[:, :, None], w, np.full((1, 2, 1), coh), ["t1", "t2"], ["y"])
    ut = MeasuredResponse(U0[:, :, None], w, np.full((2, 2, 1), coh), ["t1", "t2"], ["u1", "u2"])
    prop = joint_input_output(yt, ut, coherence="propagated").coherence[0, :, 0]
    pred_eps = np.sqrt((1 - prop) / (2 * n_d * prop))
    # first-order propagation vs 4000 repeats: 15 % (second-order terms at eps ~ 0.16 and
    # Monte Carlo sampling error ~2 %)
    np.testing.assert_allclose(pred_eps, mc_eps.ravel(), rtol=0.15)
    # the weighted coherence reports 0.95 for the amplified off-axis element
    weighted = joint_input_output(yt, ut).coherence[0, :, 0]
    assert weighted[1] == pytest.approx(0.95) and prop[1] < 0.5
