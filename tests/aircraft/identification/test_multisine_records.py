"""Multisine records split between several runs: assembly, specs and settings.

The assembly is checked on a linear system whose frequency response is known in
closed form (first-order lags, simulated with scipy), driven by the same
:class:`aircraft.wake.MultisineSpec` inputs the pipeline marches; the specs the
pipeline builds are captured from a stand-in ``run_sweeps`` (no wake is run).
"""
import numpy as np
import pandas as pd
import pytest
import scipy.signal as sig

import aircraft.wake as wake_pkg
from aircraft.configs import coaxial_compound
from aircraft.identification import PipelineError, get_structure
from aircraft.identification.multisine import MultisineSettings, identify_inflow_multisine
from aircraft.identification.multisine_records import record_responses, split_controls
from aircraft.wake import MultisineSpec

CONTROLS = ["a", "b", "c", "d"]
OUTPUTS = ["y0", "y1"]
POLES = np.array([1.5, 4.0, 9.0, 20.0])                  # [rad/s], one lag per control
GAINS = np.array([[1.0, -2.0, 0.5, 3.0], [0.3, 1.2, -1.5, 0.8]])   # distinct: a swapped column shows


def _exact(w):
    """Closed-form response H_ij(jw) = g_ij p_j / (jw + p_j), shape (2, 4, n)."""
    return GAINS[:, :, None] * POLES[None, :, None] / (1j * w[None, None, :] + POLES[None, :, None])


def _record(spec, dt):
    """Time history of the linear system driven by ``spec``'s inputs (the other controls at zero)."""
    inputs = spec.inputs(dt)
    t = next(iter(inputs.values()))[0]
    u = {c: inputs[c][1] if c in inputs else np.zeros(t.size) for c in CONTROLS}
    y = np.zeros((t.size, 2))
    for j, c in enumerate(CONTROLS):
        _, x, _ = sig.lsim(sig.StateSpace([[-POLES[j]]], [[POLES[j]]], [[1.0]], [[0.0]]), u[c], t)
        y += np.outer(x, GAINS[:, j])
    return pd.DataFrame({"t": t, **u, **dict(zip(OUTPUTS, y.T))})


def test_split_records_assemble_the_exact_control_to_signal_matrix():
    dt = 0.01
    groups = split_controls(CONTROLS, 2)
    assert groups == [("a", "c"), ("b", "d")]
    specs = [MultisineSpec(g, amplitude=0.02, duration=30.0, w_min=0.7, w_max=30.0, seed=k,
                           label=f"r{k}") for k, g in enumerate(groups)]
    records = [(_record(spec, dt), spec.controls) for spec in specs]
    measured = record_responses(records, OUTPUTS, w_min=1.0, w_max=25.0, order=CONTROLS)
    assert measured.input_labels == CONTROLS and measured.output_labels == OUTPUTS
    exact = _exact(measured.omega)
    # noise-free and linear: what is left is the spectral estimate's error on a 30 s
    # record (window leakage, worst at the band edges and where another control's
    # output dominates); judged where the partial coherence is >= 0.9 in 2.5-20 rad/s
    # (every column has such points). Measured: max 9 %, median 1.2 %. Any two columns
    # of a row differ by >= 44 % there, so a misplaced column fails both
    rel = np.abs(measured.frdata - exact) / np.abs(exact)
    good = (measured.coherence >= 0.9) & (measured.omega >= 2.5) & (measured.omega <= 20.0)
    assert good.any(axis=(0, 2)).all()
    assert np.max(rel[good]) < 0.15 and np.median(rel[good]) < 0.03
    # the default order is the records' own: columns a, c, b, d
    own = record_responses(records, OUTPUTS, w_min=1.0, w_max=25.0)
    assert own.input_labels == ["a", "c", "b", "d"]
    np.testing.assert_array_equal(own.frdata[:, [0, 2, 1, 3]], measured.frdata)


def test_record_responses_and_split_reject_bad_input():
    df = pd.DataFrame({"t": np.arange(100) * 0.01, "a": 0.0, "y0": 0.0})
    with pytest.raises(ValueError, match="records"):
        record_responses([], ["y0"], w_min=1.0, w_max=5.0)
    with pytest.raises(ValueError, match="once"):
        record_responses([(df, ["a"]), (df, ["a"])], ["y0"], w_min=1.0, w_max=5.0)
    with pytest.raises(ValueError, match="order"):
        record_responses([(df, ["a"])], ["y0"], w_min=1.0, w_max=5.0, order=["b"])
    for bad in (0, 5, 1.5, True):
        with pytest.raises(ValueError, match="records"):
            split_controls(CONTROLS, bad)


@pytest.mark.parametrize("kwargs, match", [({"records": 0}, "records"), ({"records": 2.0}, "records"),
                                           ({"duration": -1.0}, "duration"), ({"amplitude": float("nan")}, "amplitude"),
                                           ({"spectrum": "pink"}, "spectrum"), ({"seed": 1.5}, "seed")])
def test_multisine_settings_validation(kwargs, match):
    with pytest.raises(ValueError, match=match):
        MultisineSettings(**kwargs)


def test_one_record_keeps_its_hash_fields():
    # the identification hash of one record is that of the settings before records existed
    assert MultisineSettings().hash_fields() == {"duration": 90.0, "amplitude": 0.02, "spectrum": "log",
                                                 "fade": 0.5, "trim_start": 0.5, "seed": 0}
    assert MultisineSettings(records=2).hash_fields()["records"] == 2


class _Captured(Exception):
    pass


@pytest.fixture()
def captured_specs(monkeypatch):
    seen = []

    def fake(config, settings, flight, specs, **kwargs):
        seen.extend(specs)
        raise _Captured

    monkeypatch.setattr(wake_pkg, "run_sweeps", fake)
    return seen


def test_specs_of_a_flap_rate_structure_and_of_the_default(captured_specs):
    tilt = get_structure("coaxial_12state_tilt")
    with pytest.raises(_Captured):
        identify_inflow_multisine(coaxial_compound(), None, tilt, ct=0.0096,
                                  multisine=MultisineSettings(duration=30.0, records=2), progress=False)
    ms = [s for s in captured_specs if isinstance(s, MultisineSpec)]
    # every excitation (six swashplate + four tip-path-plane inputs) in exactly one of two records
    assert [s.controls for s in ms] == split_controls(tilt.excitations, 2)
    assert sorted(c for s in ms for c in s.controls) == sorted(tilt.excitations)
    assert [s.name for s in ms] == ["multisine_1of2", "multisine_2of2"] and [s.seed for s in ms] == [0, 1]
    captured_specs.clear()
    six = get_structure("coaxial_6state")
    with pytest.raises(_Captured):
        identify_inflow_multisine(coaxial_compound(), None, six, ct=0.0096, progress=False)
    # the default: one record of the swashplate controls, as before records existed
    assert captured_specs[0] == MultisineSpec(tuple(six.controls), amplitude=0.02, duration=90.0, w_min=0.7,
                                              w_max=30.0, spectrum="log", fade=0.5, trim_start=0.5, seed=0)
    assert captured_specs[0].name == "multisine_6controls"


def test_more_records_than_controls_is_refused(captured_specs):
    with pytest.raises(PipelineError, match="records"):
        identify_inflow_multisine(coaxial_compound(), None, "coaxial_6state", ct=0.0096,
                                  multisine=MultisineSettings(records=7), progress=False)


def test_a_record_too_short_for_the_band_is_a_pipeline_error(monkeypatch):
    import math
    from aircraft.configs import uh60_single_rotor
    from aircraft.identification import IdentificationSettings
    from aircraft.wake import WakeSettings
    from tests.aircraft.identification._simulated_wake import simulated_runs

    def fake(config, settings, flight, specs, **kwargs):
        omega = float(config.rotors[0].omega)
        return simulated_runs(specs, settings.azimuth_step / omega, omega, np.eye(3), np.eye(3),
                              np.zeros((3, 3)), noise=0.01)

    monkeypatch.setattr(wake_pkg, "run_sweeps", fake)
    coarse = IdentificationSettings(wake=WakeSettings(azimuth_step=math.radians(20.0), wake_revolutions=1.5,
                                                      n_elements=5))
    # 20 s cannot hold two cycles of 0.7 rad/s in its longest window (>= 35.9 s needed)
    with pytest.raises(PipelineError, match="w_min"):
        identify_inflow_multisine(uh60_single_rotor(), None, "single_rotor_3state", ct=0.0061, settings=coarse,
                                  multisine=MultisineSettings(duration=20.0), n_jobs=1, progress=False)
