"""Flight data in: DataFrame/CSV loader, resampling, detrending, multi-run concatenation.

Truths are closed forms (a first-order lag K/(s + a) simulated with scipy) and
exact properties of the operations (a removed line, an aliased tone).
"""
import numpy as np
import pandas as pd
import pytest
from scipy.signal import lsim

from flightid import DataError, frequency_response
from flightid.errors import InputValueError, SignalNameError
from flightid.flight_data import concatenated_response, read_flight_data

K, A = 2.0, 1.5          # truth: y = K / (s + A) u


def _truth(w):
    return K / (1j * w + A)


def _run(seed, t_end=80.0, dt=0.02, band=None, noise=0.0):
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, t_end, dt)
    u = rng.standard_normal(t.size)
    if band is not None:        # band-limited input: power only in [lo, hi] rad/s
        spec = np.fft.rfft(u)
        w = 2 * np.pi * np.fft.rfftfreq(t.size, dt)
        spec[(w < band[0]) | (w > band[1])] = 0
        u = np.fft.irfft(spec, t.size)
    y = lsim(([K], [1.0, A]), u, t)[1] + noise * rng.standard_normal(t.size)
    return t, u, y


def test_dataframe_and_csv_with_units(tmp_path):
    t, u, y = _run(0)
    df = pd.DataFrame({"time": t, "de [deg]": u, "q (deg/s)": y})
    rec = read_flight_data(df, time="time", units={"de": "rad"})
    assert rec.names == ["de", "q"] and rec.units == {"de": "rad", "q": "deg/s"}
    assert rec.dt == pytest.approx(0.02)
    path = tmp_path / "run.csv"
    df.to_csv(path, index=False)
    rec2 = read_flight_data(path, time="time")
    np.testing.assert_allclose(rec2["q"], y, rtol=1e-12)     # CSV round trip: text precision only
    assert list(rec2.to_pandas().columns) == ["t", "de", "q"]
    r = rec2.response("de", "q", w_min=1.0, w_max=10.0)   # above the leakage-biased lowest band
    h, coh = r.element("q", "de")
    # noise-free linear system: coherence near 1 (Hann leakage and window-edge transients of a
    # random input leave a few 1e-2), the response within the
    # random error those leave, sqrt((1-g2)/(2 n_d g2)) ~ 0.05 -> 0.5 dB / 3 deg at the worst point
    assert np.all(coh > 0.95)
    assert np.max(np.abs(20 * np.log10(np.abs(h / _truth(r.omega))))) < 0.6
    assert np.max(np.abs(np.degrees(np.angle(h / _truth(r.omega))))) < 4.0


def test_non_uniform_is_refused_naming_resample_and_resampled_on_request():
    t, u, y = _run(1, dt=0.01)
    rng = np.random.default_rng(2)
    tj = t + rng.uniform(-0.003, 0.003, t.size)     # logging jitter, still increasing
    df = pd.DataFrame({"t": tj, "u": u, "y": y})
    with pytest.raises(DataError, match="resample"):
        read_flight_data(df)
    with pytest.raises(InputValueError, match="method"):
        read_flight_data(df, resample=0.02, method="cubic")
    with pytest.raises(InputValueError, match="resample"):
        read_flight_data(df, resample=-1.0)
    rec = read_flight_data(df, resample=0.02)
    assert rec.dt == pytest.approx(0.02, rel=1e-9)
    with pytest.raises(SignalNameError, match="time"):
        read_flight_data(df, time="clock")


def test_antialias_removes_a_tone_above_the_new_nyquist():
    dt = 0.005
    t = np.arange(0.0, 40.0, dt)
    tone = np.sin(2 * np.pi * 17.0 * t)          # 17 Hz: aliases to 3 Hz at 20 Hz sampling
    df = pd.DataFrame({"t": t, "x": tone + np.sin(2 * np.pi * 0.5 * t)})

    def alias_amplitude(rec):
        x = rec["x"] - np.sin(2 * np.pi * 0.5 * rec.t)
        spec = np.abs(np.fft.rfft(x)) * 2 / x.size
        f = np.fft.rfftfreq(x.size, rec.dt)
        return spec[np.argmin(np.abs(f - 3.0))]
    plain = alias_amplitude(read_flight_data(df, resample=0.05, method="linear"))
    filtered = alias_amplitude(read_flight_data(df, resample=0.05, method="antialias"))
    # linear sampling keeps the tone's full amplitude at the alias; an 8th-order
    # Butterworth at 8 Hz attenuates 17 Hz by (17/8)^16 ~ 1e5 (edge effects aside)
    assert plain > 0.5
    assert filtered < 0.01


def test_detrend_mean_and_linear():
    t = np.linspace(0, 10, 501)
    df = pd.DataFrame({"t": t, "x": 3.0 + 0.5 * t + np.sin(2 * np.pi * t)})
    lin = read_flight_data(df, detrend="linear")
    # SIDPAC-style: the least-squares line (numpy.polyfit, independent code) is removed
    x = df.x.to_numpy()
    np.testing.assert_allclose(lin["x"], x - np.polyval(np.polyfit(t, x, 1), t), atol=1e-12)
    line = read_flight_data(pd.DataFrame({"t": t, "x": 3.0 + 0.5 * t}), detrend="linear")
    np.testing.assert_allclose(line["x"], 0.0, atol=1e-12)
    mean = read_flight_data(df, detrend="mean")
    assert abs(mean["x"].mean()) < 1e-12
    with pytest.raises(InputValueError, match="detrend"):
        read_flight_data(df, detrend="quadratic")


def test_concatenation_pools_spectra_not_responses():
    # run 1 excites only 0.3-3 rad/s, run 2 only 3-20 rad/s, each with 5 % output noise
    ra = read_flight_data(pd.DataFrame(dict(zip("tuy", _run(3, band=(0.3, 3.0), noise=0.02)))))
    rb = read_flight_data(pd.DataFrame(dict(zip("tuy", _run(4, band=(3.0, 20.0), noise=0.02)))))
    kw = dict(w_min=0.5, w_max=12.0)
    joint = concatenated_response([ra, rb], "u", "y", **kw)
    h, coh = joint.element("y", "u")
    err_db = np.abs(20 * np.log10(np.abs(h / _truth(joint.omega))))
    # pooled spectra: every frequency is excited by one run, so H follows the truth
    # (0.5 dB: estimator bias and noise at gamma^2 > 0.9) and coherence stays high
    assert np.max(err_db) < 0.5 and np.median(coh) > 0.9
    # the average of the two runs' H's is wrong wherever one run has no input power
    ha = ra.response("u", "y", **kw).element("y", "u")[0]
    hb = rb.response("u", "y", **kw).element("y", "u")[0]
    err_avg = np.abs(20 * np.log10(np.abs(0.5 * (ha + hb) / _truth(joint.omega))))
    assert np.max(err_avg) > 3.0
    # one record: exactly frequency_response
    single = concatenated_response([ra], "u", "y", **kw)
    direct = frequency_response(ra.t, ra["u"], ra["y"], input_name="u", output_names=["y"], **kw)
    np.testing.assert_array_equal(single.frdata, direct.frdata)


def test_concatenation_refuses_mixed_sample_times_and_missing_channels():
    ra = read_flight_data(pd.DataFrame(dict(zip("tuy", _run(5)))))
    rb = read_flight_data(pd.DataFrame(dict(zip("tuy", _run(6, dt=0.01)))))
    with pytest.raises(DataError, match="sample time"):
        concatenated_response([ra, rb], "u", "y", w_min=0.5, w_max=10.0)
    with pytest.raises(SignalNameError, match="records\\[0\\]"):
        concatenated_response([ra], "u", "z", w_min=0.5, w_max=10.0)


def test_sweep_edge_cases_name_their_argument():
    import warnings
    from flightid import frequency_sweep
    # fades longer than the sweep would overlap and make the envelope jump
    with pytest.raises(InputValueError, match="fade_cycles"):
        frequency_sweep(0.5, 10.0, 30.0, 0.01, fade_cycles=3.0)
    # fades that fit: no step larger than the sine's own (amplitude w_max dt) between samples
    t, u = frequency_sweep(0.5, 10.0, 60.0, 0.01, fade_cycles=2.0)
    assert np.max(np.abs(np.diff(u))) <= 10.0 * 0.01 * 1.01
    # 2 periods of w_min (what the sweep requires) are not the 4 frequency_response needs
    with pytest.warns(UserWarning, match="frequency_response needs"):
        t, u = frequency_sweep(0.5, 10.0, 4 * np.pi / 0.5, 0.01, trim_start=0.0, trim_end=0.0)
    with pytest.raises(DataError, match="too short"):
        frequency_response(t, u, u, w_min=0.5, w_max=10.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        frequency_sweep(0.5, 10.0, 60.0, 0.01)            # long enough: silent


def test_fit_refuses_nan_initial_value():
    from flightid import fit
    from flightid.transfer_function import TransferFunctionStructure
    t, u, y = _run(8)
    data = frequency_response(t, u, y, w_min=1.0, w_max=10.0)
    s = TransferFunctionStructure(0, 1, delay=False)
    s.values["a0"] = float("nan")            # set behind the constructor's check
    with pytest.raises(InputValueError, match="a0"):
        fit(s, data)
