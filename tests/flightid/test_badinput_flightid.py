"""Bad inputs to flightid's public functions: each raises a ValueError subclass that
names the argument and what is allowed, never a vague numpy/pandas
error or a silent wrong answer."""
import numpy as np
import pandas as pd
import pytest
import control

from flightid import (DataError, IdentificationError, MeasuredResponse, combine_responses, doublet, frequency_response, frequency_sweep, joint_input_output, multistep_3211, verify)
from flightid.errors import InputValueError, SignalNameError
from flightid.sweeps import shaped_noise
from flightid.verification import theil_inequality

NAN, INF = float("nan"), float("inf")


@pytest.fixture(scope="module")
def record():
    """A first-order system swept 0.5-20 rad/s: t, u, y, its response, the system."""
    t, u = frequency_sweep(0.5, 20.0, 60.0, 0.01, 1.0)
    sys = control.ss([[-1.0]], [[1.0]], [[1.0]], [[0.0]], inputs=["u"], outputs=["y"])
    y = control.forced_response(sys, t, u).outputs
    r = frequency_response(t, u, y, w_min=0.5, w_max=10.0, input_name="u", output_names=["y"])
    return t, u, y, r, sys


SWEEP = dict(w_min=0.5, w_max=20.0, duration=60.0, dt=0.01)


@pytest.mark.parametrize("kwargs, match", [
    (dict(amplitude=NAN), "amplitude must be finite"),
    (dict(amplitude=1 + 1j), "amplitude must be real"),
    (dict(amplitude="1"), "amplitude must be a real number"),
    (dict(trim_start=NAN), "trim_start must be finite"),
    (dict(trim_end=-1.0), "trim_end must be non-negative"),
    (dict(noise_fraction=-0.1), "noise_fraction must be non-negative"),
    (dict(noise_fraction=NAN), "noise_fraction must be finite"),
    (dict(fade_cycles=0.0), "fade_cycles must be positive"),
    (dict(dt=INF), "dt must be finite"),
    (dict(dt=1e-9), "samples"),
    (dict(w_min=NAN), "w_min must be finite"),
    (dict(duration=-60.0), "duration must be positive"),
])
def test_frequency_sweep_rejects(kwargs, match):
    with pytest.raises(InputValueError, match=match):
        frequency_sweep(**{**SWEEP, **kwargs})


@pytest.mark.parametrize("call, match", [
    (lambda: shaped_noise(1.5, 0.01, 1.0, 10.0), "n must be an integer"),
    (lambda: shaped_noise(100, 0.01, 1.0, 10.0, rms=NAN), "rms must be finite"),
    (lambda: shaped_noise(100, 0.01, 10.0, 1.0), "w_max .* must exceed w_min"),
    (lambda: doublet(NAN, 0.5, 0.01, 5.0), "amplitude must be finite"),
    (lambda: doublet(1.0, 0.001, 0.01, 5.0), "pulse_width .* at least one sample"),
    (lambda: doublet(1.0, 0.5, 0.01, 5.0, start=NAN), "start must be finite"),
    (lambda: multistep_3211(1.0, 0.5j, 0.01, 5.0), "pulse_width must be real"),
])
def test_other_inputs_reject(call, match):
    with pytest.raises(InputValueError, match=match):
        call()


def test_multistep_longer_than_record_is_a_data_error():
    with pytest.raises(DataError, match="after the record"):
        multistep_3211(1.0, 2.0, 0.01, 5.0)


def test_complex_input_is_never_silently_made_real(record):
    t, u, y, _, _ = record
    with pytest.raises(DataError, match="u must be real: it holds complex values"):
        frequency_response(t, u + 1e-3j, y, w_min=0.5, w_max=10.0)
    # an exactly real complex array is fine (same answer as the real one)
    a = frequency_response(t, u.astype(complex), y, w_min=0.5, w_max=10.0)
    b = frequency_response(t, u, y, w_min=0.5, w_max=10.0)
    np.testing.assert_array_equal(a.frdata, b.frdata)


@pytest.mark.parametrize("change, error, match", [
    (dict(y="nan"), DataError, "y contains .* NaN or infinite"),
    (dict(t="text"), DataError, "t must hold numbers"),
    (dict(w_min=NAN), InputValueError, "w_min must be finite"),
    (dict(w_min=5.0, w_max=1.0), InputValueError, "need 0 < w_min < w_max"),
    (dict(w_max=300.0), DataError, "above half the Nyquist"),
    (dict(overlap=1.0), InputValueError, "overlap must be < 1"),
    (dict(overlap=NAN), InputValueError, "overlap must be finite"),
    (dict(n_points=1), InputValueError, "n_points must be an integer >= 2"),
    (dict(n_windows=0), InputValueError, "n_windows must be an integer >= 1"),
    (dict(windows=[-3.0, 20.0]), InputValueError, "windows must be .* positive"),
    (dict(windows=[NAN]), InputValueError, "windows contains"),
    (dict(output_names=["a", "b"]), DataError, "2 output names for 1 outputs"),
    (dict(output_names=["u"]), DataError, "differ from the input name"),
    (dict(input_name=""), InputValueError, "input_name must be a non-empty string"),
    (dict(u="const"), DataError, "u is constant"),
    (dict(t="nonuniform"), DataError, "uniformly sampled"),
    (dict(cycles_per_window=0.0), InputValueError, "cycles_per_window must be positive"),
])
def test_frequency_response_rejects(record, change, error, match):
    t, u, y, _, _ = record
    args = dict(t=t, u=u, y=y, w_min=0.5, w_max=10.0)
    special = {"nan": np.where(t > 5, np.nan, y), "text": ["a"] * t.size,
               "const": np.ones_like(u), "nonuniform": np.r_[t[:-1], t[-1] + 1.0]}
    for k, v in change.items():
        args[k] = special[v] if isinstance(v, str) and v in special else v
    with pytest.raises(error, match=match):
        frequency_response(args.pop("t"), args.pop("u"), args.pop("y"), **args)


@pytest.mark.parametrize("kwargs, match", [
    (dict(response=np.full((1, 1, 3), np.nan)), "response contains 3 NaN"),
    (dict(coherence=2 * np.ones((1, 1, 3))), r"coherence must lie in \[0, 1\]"),
    (dict(coherence=np.full((1, 1, 3), np.nan)), "coherence contains"),
    (dict(omega=[3.0, 2.0, 1.0]), "strictly increasing"),
    (dict(omega=[1.0, 2.0]), "omega must be 1-D with 3 frequencies"),
    (dict(inputs=["u", "v"]), "1 output and 2 input names"),
    (dict(response=np.ones((1, 3))), r"shape \(n_outputs, n_inputs, n_freq\)"),
])
def test_measured_response_rejects(kwargs, match):
    args = dict(response=np.ones((1, 1, 3)), omega=[1.0, 2.0, 3.0], coherence=np.ones((1, 1, 3)),
                inputs=["u"], outputs=["y"])
    args.update(kwargs)
    with pytest.raises(DataError, match=match):
        MeasuredResponse(**args)


def test_unknown_signal_names_name_what_exists(record):
    r = record[3]
    with pytest.raises(SignalNameError, match=r"unknown output name\(s\) \['nope'\]; available: \['y'\]"):
        r.select(["nope"])
    with pytest.raises(SignalNameError, match=r"unknown input name\(s\) \['x'\]"):
        r.element("y", "x")
    with pytest.raises(SignalNameError, match="output index 5 out of range"):
        r.element(5, 0)
    # backward compatible: code that caught KeyError still does
    with pytest.raises(KeyError):
        r.select(inputs=["x"])


def test_combine_responses_rejects(record):
    r, sys = record[3], record[4]
    with pytest.raises(DataError, match="must be a MeasuredResponse, got StateSpace"):
        combine_responses([sys])
    with pytest.raises(DataError, match="at least one response"):
        combine_responses([])
    with pytest.raises(DataError, match="appears in more than one response"):
        combine_responses([r, r])


def test_joint_input_output_refuses_a_nan_response(record):
    r = record[3]
    bad = r.select()
    bad.frdata[0, 0, 3] = np.nan          # overwritten after construction
    with pytest.raises(DataError, match="y_over_theta holds 1 NaN or infinite response value"):
        joint_input_output(bad, r)
    with pytest.raises(DataError, match="u_over_theta holds 1 NaN"):
        joint_input_output(r, bad)


def test_joint_input_output_rejects_arguments(record):
    r = record[3]
    with pytest.raises(DataError, match="must be a MeasuredResponse .* FrequencyResponseData"):
        joint_input_output(control.frd(np.ones(3), [1.0, 2.0, 3.0]), r)
    with pytest.raises(InputValueError, match="max_condition must be finite"):
        joint_input_output(r, r, max_condition=NAN)
    with pytest.raises(IdentificationError, match=r"structural_zeros must be 1 x 1"):
        joint_input_output(r, r, structural_zeros=[[True, False]])


def test_verify_with_a_dataframe_missing_columns(record):
    t, u, y, _, sys = record
    with pytest.raises(SignalNameError, match=r"unknown inputs column name\(s\) \['u'\]; available: \['x'\]"):
        verify(sys, t, pd.DataFrame({"x": u}), pd.DataFrame({"y": y}))
    with pytest.raises(SignalNameError, match=r"unknown outputs column name\(s\) \['y'\]"):
        verify(sys, t, pd.DataFrame({"u": u}), pd.DataFrame({"z": y}))
    with pytest.raises(SignalNameError, match="2 input names .* for a model with 1 inputs"):
        verify(sys, t, pd.DataFrame({"u": u}), pd.DataFrame({"y": y}), input_names=["u", "v"])


@pytest.mark.parametrize("change, match", [
    ("nan_input", "inputs contains .* NaN"),
    ("complex_input", "inputs must be real"),
    ("reversed_t", "increasing and uniformly sampled"),
    ("model_str", "python-control LTI system or a ModelStructure, got str"),
    ("nan_model", "model matrices contain NaN"),
    ("discrete", "continuous-time"),
])
def test_verify_rejects(record, change, match):
    t, u, y, _, sys = record
    args = [sys, t, u, y]
    if change == "nan_input":
        args[2] = np.where(t > 1, np.nan, u)
    elif change == "complex_input":
        args[2] = u + 1j
    elif change == "reversed_t":
        args[1] = t[::-1]
    elif change == "model_str":
        args[0] = "model"
    elif change == "nan_model":
        args[0] = control.ss([[np.nan]], [[1.0]], [[1.0]], [[0.0]])
    elif change == "discrete":
        args[0] = control.ss([[0.5]], [[1.0]], [[1.0]], [[0.0]], 0.01)
    with pytest.raises(DataError, match=match):
        verify(*args)


def test_theil_inequality_rejects_mismatched_or_nan():
    with pytest.raises(DataError, match="of one shape"):
        theil_inequality([1.0, 2.0], [1.0, 2.0, 3.0])
    with pytest.raises(DataError, match="predicted contains 1 NaN"):
        theil_inequality([1.0, np.nan], [1.0, 2.0])


def test_errors_are_value_errors():
    # the whole family subclasses ValueError, so `except ValueError` catches every bad input
    for cls in (DataError, InputValueError, SignalNameError, IdentificationError):
        assert issubclass(cls, ValueError)
