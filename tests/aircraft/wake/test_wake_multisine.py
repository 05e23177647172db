"""MultisineSpec: one wake record that moves several controls at once."""
import math

import numpy as np
import pytest

from aircraft.configs import uh60_single_rotor
from aircraft.wake import FlightCondition, MultisineSpec, SweepSpecError, WakeSettings, run_sweeps
from flightid import orthogonal_multisine

CONTROLS = ("theta0", "theta1s", "theta1c")


def test_multisine_spec_inputs_are_the_flightid_multisine_after_the_lead_in():
    spec = MultisineSpec(CONTROLS, amplitude=0.01, duration=10.0, w_min=1.0, w_max=20.0, trim_start=0.5,
                         fade=0.0, spectrum="flat", seed=3)
    dt = 0.01
    inputs = spec.inputs(dt)
    assert list(inputs) == list(CONTROLS) and spec.name == "multisine_3controls"
    ms = orthogonal_multisine(3, 10.0, dt, 1.0, 20.0, 0.01, spectrum="flat", seed=3)
    for j, c in enumerate(CONTROLS):
        t, u = inputs[c]
        np.testing.assert_array_equal(u[:50], 0.0)                 # 0.5 s at trim
        np.testing.assert_array_equal(u[50:50 + ms.t.size], ms.U[:, j])
        assert u[-1] == 0.0 and t.size == u.size
        np.testing.assert_allclose(np.diff(t), dt)


@pytest.mark.parametrize("kwargs, match", [
    (dict(controls="theta0"), "tuple of control names"),
    (dict(controls=("theta0", "theta0")), "unique"),
    (dict(controls=()), "non-empty"),
    (dict(amplitude=0.8), "0.5 rad"),
    (dict(amplitude=-0.01), "amplitude"),
    (dict(w_min=5.0, w_max=2.0), "exceed"),
    (dict(duration=float("nan")), "duration"),
    (dict(spectrum="white"), "spectrum"),
    (dict(seed=1.5), "seed"),
])
def test_multisine_spec_rejects_bad_fields(kwargs, match):
    args = dict(controls=CONTROLS)
    args.update(kwargs)
    with pytest.raises(SweepSpecError, match=match):
        MultisineSpec(**args)


def test_multisine_spec_band_too_narrow_for_its_controls():
    spec = MultisineSpec(CONTROLS, duration=1.0, w_min=5.0, w_max=8.0)
    with pytest.raises(SweepSpecError, match="harmonics"):
        spec.inputs(0.01)


def test_run_sweeps_checks_every_control_of_a_multisine():
    spec = MultisineSpec(("theta0", "theta9", "theta8"), duration=1.0, w_min=10.0, w_max=60.0)
    with pytest.raises(SweepSpecError, match=r"unknown controls \['theta9', 'theta8'\]"):
        run_sweeps(uh60_single_rotor(), WakeSettings(), FlightCondition(), [spec], trim={"ct": 0.0061},
                   n_jobs=1, cache_dir=None, progress=False)


def test_multisine_record_on_a_tiny_wake(tmp_path):
    cfg = uh60_single_rotor()
    s = WakeSettings(azimuth_step=math.radians(20.0), wake_revolutions=1.5, n_elements=4)
    spec = MultisineSpec(CONTROLS, amplitude=0.01, duration=0.6, w_min=10.0, w_max=60.0, trim_start=0.1,
                         fade=0.0)
    out = run_sweeps(cfg, s, FlightCondition(), [spec], trim={"ct": 0.0061}, n_jobs=1, cache_dir=tmp_path,
                     progress=False)
    df = out[spec.name]
    dt = s.azimuth_step / cfg.rotors[0].omega
    inputs = spec.inputs(dt)
    for c in CONTROLS:
        t, u = inputs[c]
        # the record holds the prescribed perturbation about the trim value
        du = df[c].to_numpy() - out["trim"].controls[c]
        np.testing.assert_allclose(du, np.interp(df["t"].to_numpy(), t, u), atol=1e-9)
    assert df["t"].iloc[-1] >= 0.6
    assert np.ptp(df["CT"].to_numpy()) > 0      # the thrust answered
    again = run_sweeps(cfg, s, FlightCondition(), [spec], trim={"ct": 0.0061}, n_jobs=1, cache_dir=tmp_path,
                       progress=False)          # served from the cache, same record
    np.testing.assert_array_equal(again[spec.name].to_numpy(), df.to_numpy())


def test_step_input_is_a_ramp_then_held():
    from aircraft.wake import SweepSpec
    from aircraft.wake.sweeps import sweep_inputs
    t, u = sweep_inputs(SweepSpec("theta1s", kind="step", amplitude=0.02, duration=2.0, trim_start=0.5,
                                  pulse_width=0.1), 0.01)
    assert u[t < 0.5].max() == 0.0
    assert u[t >= 0.6].min() == pytest.approx(0.02) and u.max() == pytest.approx(0.02)
    # halfway up the ramp, half the step
    assert u[np.argmin(abs(t - 0.55))] == pytest.approx(0.01, abs=1e-12)
