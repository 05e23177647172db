import numpy as np
import pytest
import scipy.signal as sig

from flightid import (DataError, doublet, frequency_response, frequency_sweep, multistep_3211, combine_responses)
from flightid.sweeps import shaped_noise


def test_sweep_starts_and_ends_at_trim_and_covers_band():
    t, u = frequency_sweep(0.5, 20.0, 60.0, 0.01, amplitude=2.0, trim_start=3, trim_end=2)
    assert t[-1] == pytest.approx(65.0)
    assert np.all(u[t < 3.0] == 0) and np.all(u[t > 63.0] == 0)
    assert np.abs(u).max() <= 2.0 + 1e-12
    # zero crossings: local period near the end ~ 2 pi / 20 s -> spacing ~ 0.157 s
    inside = (t > 3) & (t < 63)
    ui = u[inside]
    crossings = t[inside][np.flatnonzero(ui[:-1] * ui[1:] < 0)]
    assert np.diff(crossings)[-5:].mean() == pytest.approx(np.pi / 20.0, rel=0.15)
    # first zero crossing: where the numerically integrated growth law
    # w(t) = w_min + 0.0187 (e^{4 t/T} - 1)(w_max - w_min) reaches a phase of pi
    tau = np.linspace(0, 60, 600001)
    w = 0.5 + 0.0187 * (np.exp(4 * tau / 60) - 1) * 19.5
    phase = np.concatenate([[0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(tau))])
    assert crossings[0] - 3.0 == pytest.approx(tau[np.searchsorted(phase, np.pi)], abs=0.02)


@pytest.mark.parametrize("kwargs, match", [
    (dict(w_min=2.0, w_max=1.0, duration=60, dt=0.01), "must exceed"),
    (dict(w_min=0.1, w_max=10.0, duration=30, dt=0.01), "fewer than two periods"),
    (dict(w_min=1.0, w_max=100.0, duration=60, dt=0.05), "samples per period"),
    (dict(w_min=-1.0, w_max=10.0, duration=60, dt=0.01), "positive"),
])
def test_sweep_rejects_bad_parameters(kwargs, match):
    with pytest.raises(ValueError, match=match):
        frequency_sweep(**kwargs)


def test_noise_companion_is_reproducible_and_band_limited():
    a = shaped_noise(4096, 0.01, 1.0, 10.0, rms=0.5, seed=3)
    b = shaped_noise(4096, 0.01, 1.0, 10.0, rms=0.5, seed=3)
    assert np.array_equal(a, b) and a.std() == pytest.approx(0.5)
    spec = np.abs(np.fft.rfft(a))
    w = 2 * np.pi * np.fft.rfftfreq(a.size, 0.01)
    assert spec[(w < 0.9) | (w > 11)].max() < 1e-9 * spec.max()


def test_doublet_and_3211_shapes():
    t, u = doublet(1.0, 0.5, 0.01, 5.0, start=1.0)
    assert u[(t >= 1.0) & (t < 1.49)].min() == 1.0 and u[(t >= 1.5) & (t < 1.99)].max() == -1.0
    assert np.all(u[t >= 2.0] == 0)
    t, u = multistep_3211(1.0, 0.2, 0.01, 5.0, start=0.0)
    assert np.sum(u > 0) * 0.01 == pytest.approx(0.8, abs=0.02)   # 3 + 1 widths up
    with pytest.raises(DataError, match="after the record"):
        doublet(1.0, 3.0, 0.01, 5.0, start=1.0)


def _first_order_with_delay(a=3.0, tau=0.05, dt=0.01, noise=0.0, seed=0):
    t, u = frequency_sweep(0.5, 30.0, 90.0, dt, seed=seed)
    _, y, _ = sig.lsim(sig.lti([a], [1, a]), u, t)
    y = np.interp(t - tau, t, y, left=0.0)
    y = y + noise * y.std() * np.random.default_rng(seed).standard_normal(y.size)
    return t, u, y


def test_frequency_response_matches_exact_where_coherent():
    # (c): within 0.5 dB and 3 deg of the exact response wherever coherence > 0.9.
    # The truth is scipy's lsim of a/(s+a) e^{-tau s}, independent of flightid.
    a, tau = 3.0, 0.05
    t, u, y = _first_order_with_delay(a, tau)
    r = frequency_response(t, u, y, w_min=0.6, w_max=30.0, input_name="u", output_names=["y"])
    assert r.data.shape == (1, 1, r.omega.size)
    assert np.log10(30 / 0.6) * 20 <= r.omega.size   # >= 20 points per decade
    exact = a / (1j * r.omega + a) * np.exp(-1j * r.omega * tau)
    ok = r.coherence[0, 0] > 0.9
    assert ok.mean() > 0.9
    h = r.data[0, 0, ok]
    assert np.max(np.abs(20 * np.log10(np.abs(h / exact[ok])))) < 0.5
    assert np.max(np.abs(np.degrees(np.angle(h / exact[ok])))) < 3.0
    table = r.to_pandas()
    assert list(table.columns) == ["omega", "output", "input", "magnitude_db", "phase_deg", "coherence"]


def test_frequency_response_works_at_other_sampling_rates_and_simo():
    t, u, y = _first_order_with_delay(dt=0.004)
    y2 = 2.0 * y
    r = frequency_response(t, u, np.column_stack([y, y2]), w_min=1.0, w_max=20.0,
                           input_name="u", output_names=["y", "y2"])
    h1, _ = r.element("y", "u")
    h2, _ = r.element("y2", "u")
    np.testing.assert_allclose(h2, 2 * h1, rtol=1e-9)   # linear in the output, exactly
    # a second SISO record to another input combines into a 2-output x 2-input matrix
    t2, v, yv = _first_order_with_delay(a=5.0, dt=0.004, seed=1)
    r2 = frequency_response(t2, v, np.column_stack([yv, -yv]), w_min=1.0, w_max=20.0,
                            input_name="v", output_names=["y", "y2"])
    both = combine_responses([r, r2])
    assert both.input_labels == ["u", "v"] and both.data.shape == (2, 2, r.omega.size)
    np.testing.assert_array_equal(both.data[:, 1], r2.data[:, 0])
    with pytest.raises(ValueError, match="more than one response"):
        combine_responses([r, r])


def test_frequency_response_noise_lowers_coherence():
    t, u, y = _first_order_with_delay(noise=1.0)
    r = frequency_response(t, u, y, w_min=0.6, w_max=30.0)
    clean = frequency_response(*_first_order_with_delay()[:3], w_min=0.6, w_max=30.0)
    assert r.coherence.mean() < clean.coherence.mean() - 0.1


@pytest.mark.parametrize("mutate, match", [
    (lambda t, u, y: (t, u, np.where(np.arange(y.size) == 100, np.nan, y)), "NaN"),
    (lambda t, u, y: (t, u[:-1], y), "lengths must match"),
    (lambda t, u, y: (t * np.linspace(1, 1.01, t.size), u, y), "uniformly sampled"),
    (lambda t, u, y: (t[:2000], u[:2000], y[:2000]), "too short"),
    (lambda t, u, y: (t, np.zeros_like(u), y), "constant"),
])
def test_frequency_response_rejects_bad_data(mutate, match):
    t, u, y = _first_order_with_delay()
    with pytest.raises(DataError, match=match):
        frequency_response(*mutate(t, u, y), w_min=0.6, w_max=30.0)
