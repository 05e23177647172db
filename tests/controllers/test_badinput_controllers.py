"""Bad and edge inputs to the controllers package: each gets a clear error naming what is wrong."""
import numpy as np
import pytest
import control

from controllers import (CommandModel, DelayedLTI, DMOSettings, EMFDesign, InfeasibleDesignError, PIDGains, SpecEvaluationError, default_specs, dmo, evaluate_specs, hover_roll_plant, roll_design_plant)
from controllers.plants import second_order_actuator
from controllers.specs import spec_by_name
from controllers.specs import UNSTABLE_NOTE


@pytest.fixture(scope="module")
def design():
    return EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.1, 0.2), actuator=second_order_actuator())


@pytest.mark.parametrize("gains", [(np.nan, 0.1, 0.1), (0.3, np.inf, 0.1), (0.3, 0.1, 1j)])
def test_non_finite_or_complex_gains_are_named(gains):
    with pytest.raises(ValueError, match=r"PID gain K_\w+ must be a finite real number"):
        PIDGains(*gains)


def test_mimo_plant_and_actuator_are_rejected():
    mimo = control.rss(4, 2, 2)
    with pytest.raises(ValueError, match="plant must be SISO, got 2 inputs x 2 outputs"):
        EMFDesign(mimo, PIDGains(0.3, 0.1, 0.1))
    with pytest.raises(ValueError, match="actuator must be SISO"):
        EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.1, 0.1), actuator=mimo)
    with pytest.raises(TypeError, match="gains must be PIDGains"):
        EMFDesign(hover_roll_plant(), (0.3, 0.1, 0.1))


@pytest.mark.parametrize("grid, match", [(np.r_[0.0, np.geomspace(0.1, 50, 50)], "must be > 0 rad/s"),
                                         (np.r_[np.nan, np.geomspace(0.1, 50, 50)], "NaN or inf"),
                                         (np.geomspace(50, 0.1, 50), "strictly increasing")])
def test_dmo_grid_with_zero_nan_or_decreasing_frequencies_is_rejected(grid, match):
    with pytest.raises(ValueError, match=match):
        DMOSettings(omega=grid)


def test_bad_settings_and_boundaries(design):
    with pytest.raises(ValueError, match="growth must be > 1"):
        DMOSettings(growth=1.0)
    with pytest.raises(ValueError, match="tolerance must be finite and > 0"):
        DMOSettings(tolerance=np.nan)
    from controllers import optimize
    with pytest.raises(ValueError, match="crossover_min must be a finite frequency"):
        optimize(design, np.nan, 0.9)
    with pytest.raises(TypeError, match="expected EMFDesign"):
        dmo([design, "plant"], progress=False)


def test_nan_in_the_plant_response_names_the_spec_and_frequency(design):
    # a plant whose response is NaN at one frequency (a user callable gone wrong)
    class Broken(DelayedLTI):
        def __call__(self, s):
            h = super().__call__(s)
            h = np.array(h, copy=True)
            h[np.abs(np.abs(s) - 1.0) < 2e-3] = np.nan
            return h
    bad = design.with_plant(Broken(hover_roll_plant().system, 0.01))
    with pytest.raises(SpecEvaluationError, match=r"spec 'NicMgG1'.*omega = 0\.99\d* rad/s"):
        evaluate_specs(bad, default_specs())


def test_nan_state_space_plant_is_rejected():
    sys = control.ss([[np.nan]], [[1.0]], [[1.0]], [[0.0]])
    with pytest.raises(ValueError, match="NaN or inf"):
        DelayedLTI(sys)
    with pytest.raises(ValueError, match="delay must be >= 0 s and finite"):
        DelayedLTI(control.tf([1], [1, 1]), np.inf)


def test_unstable_loop_reads_frequency_specs_not_applicable_never_met(design):
    # K_phi 30x too large: the flap mode goes unstable (checked on the poles)
    wild = design.with_gains(PIDGains(9.0, 1.0, 2.0))
    assert np.max(wild.closed_loop_poles().real) > 0
    table = evaluate_specs(wild, default_specs()).set_index("spec")
    assert not table.loc["EigLcG1", "met"]
    for name in ("NicMgG1", "StbMgG1.GM", "StbMgG1.PM", "DrbRoH1", "DrpAvH1", "BnwAtH1", "CrsMnG2"):
        assert not table.loc[name, "met"] and table.loc[name, "status"] == UNSTABLE_NOTE


@pytest.mark.slow
def test_dmo_on_a_plant_where_nothing_is_feasible_raises_naming_the_unmet_specs(design):
    # DRB >= 20 rad/s is out of reach: the closest candidates are unstable loops, so
    # the error names the instability (frequency-domain specs are n/a there, not met)
    with pytest.raises(InfeasibleDesignError, match=r"starting boundaries .*DRB 20 rad/s.*unmet: \w+") as info:
        dmo(design, crossover_start=2.0, drb_start=20.0, progress=False,
            settings=DMOSettings(n_starts=0, polish_evaluations=0))
    assert info.value.unmet and all(name in str(info.value) for name in info.value.unmet)
    assert "design margin -inf" not in str(info.value)


def test_roll_design_plant_names_unknown_signals():
    sys = control.ss(-np.eye(3), np.eye(3, 2), np.eye(3), np.zeros((3, 2)), states=["p", "q", "psi"],
                     inputs=["delta_lat", "delta_lon"], outputs=["p", "q", "psi"])
    with pytest.raises(ValueError, match=r"unknown output name\(s\) \['w'\]"):
        roll_design_plant(sys, constrained={"w": "delta_lon"})
    with pytest.raises(ValueError, match=r"unknown input name\(s\) \['delta_ped'\]"):
        roll_design_plant(sys, constrained={"q": "delta_ped"})
    with pytest.raises(ValueError, match="distinct from the free input"):
        roll_design_plant(sys, constrained={"q": "delta_lat"})
    with pytest.raises(TypeError, match="control.StateSpace"):
        roll_design_plant(control.tf([1], [1, 1]))


def test_spec_and_command_model_fields_are_checked():
    with pytest.raises(KeyError, match="no spec named 'Nope'; available"):
        spec_by_name(default_specs(), "Nope")
    with pytest.raises(ValueError, match=r"CommandModel.frequency must be a finite real number > 0"):
        CommandModel(frequency=-4.0)
    from controllers import Spec
    with pytest.raises(ValueError, match="direction must be 'min' or 'max'"):
        Spec("X", "x", lambda d: 0.0, "up", 1.0, 0.5)
    with pytest.raises(ValueError, match="boundaries must be finite"):
        Spec("X", "x", lambda d: 0.0, "min", np.nan, 0.5)


def test_zero_sensor_delay_builds_every_loop():
    # a zero delay is a unit gain: the Padé blocks must be float systems (control.ss
    # refuses the integer 1 that the zero-delay branch used to return)
    from controllers import EMFDesign, PIDGains, hover_roll_plant
    d = EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.1, 0.05), sensor_delay=0)
    assert d.broken_loop_statespace().nstates > 0
    assert d.closed_loop().nstates > 0


def test_negative_equivalent_delay_is_reported_not_clipped_silently():
    import warnings as _w
    from controllers.emf import FrequencyFunction, fit_equivalent_delay
    from controllers.emf import NegativeDelayWarning
    lead = FrequencyFunction(lambda s: np.exp(0.02 * s))      # a 20 ms phase lead
    with pytest.warns(NegativeDelayWarning, match="-20"):
        assert fit_equivalent_delay(lead) == 0.0
    with _w.catch_warnings():
        _w.simplefilter("error")
        assert fit_equivalent_delay(FrequencyFunction(lambda s: np.exp(-0.03 * s))) == pytest.approx(0.03)


@pytest.mark.parametrize("kwargs, match", [
    (dict(scale_span=(5.0, 0.2)), "scale_span"), (dict(integral_ratios=(0.0, 1.0)), "integral_ratios"),
    (dict(rate_ratios=(np.nan, 1.0)), "rate_ratios"), (dict(reference_frequency=0.0), "reference_frequency")])
def test_search_refuses_bad_spans(kwargs, match):
    from controllers import EMFDesign, PIDGains, hover_roll_plant, search_designs
    with pytest.raises(ValueError, match=match):
        search_designs(EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.1, 0.05)), **kwargs)


@pytest.mark.parametrize("band", [(0.0, 12.0), (12.0, 1.0), (np.inf, 1.0), "1-12"])
def test_fit_ranges_that_cannot_be_log_spaced_are_refused(band):
    from controllers.emf import FrequencyFunction, fit_equivalent_delay, fit_inverse_plant
    h = FrequencyFunction(lambda s: 2.0 / (s + 1.0))
    with pytest.raises(ValueError, match="fit_range"):
        fit_inverse_plant(h, band)
    with pytest.raises(ValueError, match="fit_range"):
        fit_equivalent_delay(h, band)


def test_a_plant_named_for_another_axis_is_refused():
    # a pitch plant used as the roll plant used to be accepted (13 of 14 specs "met")
    from controllers import EMFDesign, PIDGains, hover_roll_plant
    pitch = DelayedLTI(control.tf([5.0], [1.0, 2.0], inputs="delta_lon", outputs="q"), 0.01, name="pitch")
    with pytest.raises(ValueError, match="q/delta_lon but a roll-axis design needs p/delta_lat"):
        EMFDesign(pitch, PIDGains(0.3, 0.1, 0.05))
    assert EMFDesign(pitch, PIDGains(0.3, 0.1, 0.05), axis="pitch").axis == "pitch"
    roll = EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.1, 0.05))
    with pytest.raises(ValueError, match="another axis"):
        roll.with_plant(pitch)
    with pytest.raises(ValueError, match="axis must be one of"):
        EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.1, 0.05), axis="heave")
    # unnamed signals (python-control's u[0]/y[0]) are accepted for any axis
    EMFDesign(control.tf([5.0], [1.0, 2.0]), PIDGains(0.3, 0.1, 0.05), axis="yaw")
