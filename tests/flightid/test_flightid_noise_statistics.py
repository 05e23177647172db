"""Residual-scaled standard errors under their conventions, against hand calculations and a
Monte Carlo scatter; the settling checks of the sweep design and the frequency response.

Monte Carlo truth: 2 e^{-0.05 s} / (s + 1.5) simulated with scipy from a 90 s CIFER sweep
(20 s lead-in), noise added to the output as a fraction of its standard deviation.
"""
import warnings

import numpy as np
import pytest
from scipy.signal import lsim

from flightid import (SettlingWarning, doublet, fit, frequency_response, frequency_sweep)
from flightid.response import excitation_span
from flightid.statistics import parameter_statistics, residual_scaled_errors
from flightid.transfer_function import TransferFunctionStructure


def test_a_constant_by_hand_white_sandwich_and_alone_agree():
    # least-squares constant through [1, 2, 3, 4]: SE = s / sqrt(n); HC2 with leverage 1/n
    # gives sum r^2 / ((1 - 1/n) n^2) = s^2 / n exactly, and alone = joint for one parameter
    r = np.array([1.0, 2.0, 3.0, 4.0]) - 2.5
    jac = np.ones((4, 1))
    hand = np.sqrt(np.var(r, ddof=1) / 4)
    for cov in ("white", "sandwich"):
        for alone in (False, True):
            assert residual_scaled_errors(jac, r, covariance=cov, alone=alone)[0] == pytest.approx(hand, rel=1e-12)


def test_differences_do_not_see_a_floor_linear_in_frequency():
    rng = np.random.default_rng(0)
    jac = rng.standard_normal((40, 2))
    e = 0.01 * rng.standard_normal(40)
    floor = np.concatenate([0.5 + 0.1 * np.arange(20), -0.3 + 0.02 * np.arange(20)])   # two runs
    for cov in ("white", "sandwich"):
        clean = residual_scaled_errors(jac, e, covariance=cov, noise="differences", segments=[20, 20])
        both = residual_scaled_errors(jac, e + floor, covariance=cov, noise="differences", segments=[20, 20])
        np.testing.assert_allclose(both, clean, rtol=1e-9)           # second differences of a line: 0
        assert np.all(residual_scaled_errors(jac, e + floor, covariance=cov) > 10 * clean)
    # the bias option takes the same floor out of the residual exactly
    np.testing.assert_allclose(residual_scaled_errors(jac, e + floor, bias=floor), residual_scaled_errors(jac, e),
                               rtol=1e-12)


@pytest.mark.parametrize("kwargs, match", [
    (dict(covariance="pink"), "covariance must be one of"),
    (dict(noise="smooth"), "noise must be one of"),
    (dict(noise="differences"), "segments"),
    (dict(noise="differences", segments=[3, 4]), "segments must be run lengths"),
    (dict(bias=np.zeros(3)), "bias must have"),
])
def test_bad_arguments_are_named(kwargs, match):
    with pytest.raises(ValueError, match=match):
        residual_scaled_errors(np.ones((6, 1)), np.arange(6.0), **kwargs)


def _record():
    dt = 0.01
    t, u = frequency_sweep(0.3, 30.0, 90.0, dt, trim_start=20.0, trim_end=5.0, noise_fraction=0.2, seed=0)
    y0 = lsim(([2.0], [1.0, 1.5]), np.concatenate([np.zeros(5), u[:-5]]), t)[1]
    return t, u, y0


@pytest.mark.slow
def test_standard_errors_against_monte_carlo_at_three_noise_levels():
    t, u, y0 = _record()
    s = TransferFunctionStructure(0, 1, initial={"b0": 2.0, "a0": 1.5, "tau": 0.05})
    n = 40
    for noise in (0.01, 0.10, 0.30):
        rng = np.random.default_rng(11)
        est, cr, se = [], [], {"white": [], "sandwich": [], "differences": []}
        for _ in range(n):
            y = y0 + noise * np.std(y0) * rng.standard_normal(t.size)
            r = fit(s, frequency_response(t, u, y, w_min=0.5, w_max=12.0), frequency_ranges=(0.5, 12.0))
            est.append([r.structure.values[k] for k in s.names])
            cr.append(r.parameters.cramer_rao_pct.to_numpy() / 100 * np.abs(est[-1]))
            se["white"].append(parameter_statistics(r).standard_error.to_numpy())
            se["sandwich"].append(parameter_statistics(r, covariance="sandwich").standard_error.to_numpy())
            se["differences"].append(parameter_statistics(r, covariance="sandwich", noise="differences")
                                     .standard_error.to_numpy())
        scatter = np.std(est, axis=0, ddof=1)
        ratio = {k: np.mean(v, axis=0) / scatter for k, v in se.items()}
        # the Monte Carlo scatter of 40 repeats has a relative sampling error 1 / sqrt(2 * 39) = 11 %:
        # the bands below are the measured 200-repeat ratios +- about 2.5 sampling errors
        if noise == 0.01:
            # the deterministic error of the spectral estimate dominates the residual: the white
            # error is 3-6 x the scatter, CIFER's bound two orders of magnitude above it
            assert np.all(ratio["white"] > 2.5) and np.all(np.mean(cr, axis=0) / scatter > 50)
            # the second differences take that floor out (200 repeats: 1.06 / 1.61 / 0.77)
            assert np.all((ratio["differences"] > 0.55) & (ratio["differences"] < 2.0)), ratio
        else:
            # the heteroscedastic sandwich holds the delay the white convention halves
            # (200 repeats: 0.95 / 1.10 / 0.86 at 10 %, 0.88 / 0.90 / 0.85 at 30 %)
            assert ratio["white"][2] < 0.7, ratio
            assert np.all((ratio["sandwich"] > 0.6) & (ratio["sandwich"] < 1.45)), ratio


def test_a_short_lead_in_or_a_short_excitation_warns():
    with pytest.warns(SettlingWarning, match="trim_start = 0.5 s shorter"):
        t, u = frequency_sweep(0.5, 10.0, 60.0, 0.01, trim_start=0.5)
    y = lsim(([4.0], [1.0, 2.0]), u, t)[1]
    # 0.5 s lead-in against the settling time 1 / w_min = 2 s (measured 1.7 s: the half-cosine
    # fade-in stays under 5 % of the amplitude for its first 1.2 s)
    with pytest.warns(SettlingWarning, match=r"lead-in 1\.7"):
        frequency_response(t, u, y, w_min=0.5, w_max=10.0)
    # a settling time given by the caller replaces the default
    with warnings.catch_warnings():
        warnings.simplefilter("error", SettlingWarning)
        frequency_response(t, u, y, w_min=0.5, w_max=10.0, settling_time=0.4)
        t2, u2 = frequency_sweep(0.5, 10.0, 60.0, 0.01)                 # 3 s trims >= 2 s: silent
        frequency_response(t2, u2, lsim(([4.0], [1.0, 2.0]), u2, t2)[1], w_min=0.5, w_max=10.0)
    # a 2 s doublet in a 60 s record (1.99 s: first to last sample off trim): long enough only
    # through its trims
    t3, u3 = doublet(1.0, 1.0, 0.01, 60.0, start=20.0)
    with pytest.warns(SettlingWarning, match=r"excitation lasts 1\.99 s"):
        frequency_response(t3, u3, lsim(([4.0], [1.0, 2.0]), u3, t3)[1], w_min=0.5, w_max=10.0)


def test_excitation_span_by_hand():
    t = np.arange(0.0, 10.01, 0.01)
    u = np.where((t >= 2.0) & (t <= 7.0), 1.0, 0.0) + 0.3       # a pulse on a trim offset
    lead_in, span, lead_out = excitation_span(t, u)
    assert (lead_in, span, lead_out) == pytest.approx((2.0, 5.0, 3.0), abs=0.011)   # one sample
    assert excitation_span(t, np.zeros_like(t)) == (10.0, 0.0, 0.0)


def test_a_reference_equal_to_the_data_leaves_no_noise():
    t, u, y0 = _record()
    y = y0 + 0.1 * np.std(y0) * np.random.default_rng(4).standard_normal(t.size)
    data = frequency_response(t, u, y, w_min=0.5, w_max=12.0)
    r = fit(TransferFunctionStructure(0, 1, initial={"b0": 2.0, "a0": 1.5, "tau": 0.05}), data)
    # the whole residual is then "deterministic": nothing is left to scale the errors with
    table = parameter_statistics(r, covariance="sandwich", reference=data)
    assert np.all(table.standard_error == 0) and np.all(table.standard_error_alone_pct == 0)
    assert np.all(parameter_statistics(r).standard_error > 0)
    with pytest.raises(ValueError, match="reference must be a MeasuredResponse"):
        parameter_statistics(r, reference=np.ones(3))
