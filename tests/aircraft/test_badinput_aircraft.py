"""Bad inputs to aircraft's public boundaries: configurations, wake
settings and flight conditions, sweep specs, wake trim/run, aircraft trim,
linearisation and coupling numerators.  Each raises a ValueError subclass naming
the field and what is allowed, and trims fail fast in their own words."""
import dataclasses
import math
import warnings

import control
import numpy as np
import pytest

from aircraft import ConfigError, PropellerConfig, coaxial_compound, uh60_single_rotor
from aircraft.helicopter import (CouplingError, Helicopter, HelicopterSettings, LinearizeInputError,
                                 NotAtTrimError, NotAtTrimWarning, TrimCondition, TrimError,
                                 TrimInputError, coupling_numerator, default_steps, linearize, modes,
                                 residualize, trim, trim_derivatives)
from aircraft.inflow import ClimbingLowerRotor, DynamicClimb, IsolatedRotors, PittPeters
from aircraft.wake import (FlightCondition, FreeVortexWake, SweepSpec, SweepSpecError, WakeInputError,
                           WakeSettings, WakeSettingsError, WakeTrimError, run_sweeps)

NAN, INF = float("nan"), float("inf")
UH60 = uh60_single_rotor()
ROTOR = UH60.rotors[0]
FAST = HelicopterSettings(n_span=6, n_average=1)     # hover is axisymmetric: one azimuth is exact
TINY_WAKE = WakeSettings(azimuth_step=math.radians(30.0), wake_revolutions=1.0, n_elements=4,
                         far_wake_revolutions=2.0)


# --------------------------------------------------------------- configurations
@pytest.mark.parametrize("field, value, match", [
    ("twist", NAN, r"RotorConfig.twist must be finite \[rad\]"),
    ("twist", 2.0, r"RotorConfig.twist must be <= 0.785398 \[rad\]"),
    ("radius", -1.0, r"RotorConfig.radius must be positive \(> 0\) \[m\]"),
    ("omega", 27 + 1j, "RotorConfig.omega must be real"),
    ("chord", "0.5", "RotorConfig.chord must be a real number"),
    ("n_blades", 4.0, "RotorConfig.n_blades must be a Python int"),
    ("n_blades", True, "RotorConfig.n_blades must be an integer"),
    ("cd0", NAN, "RotorConfig.cd0 must be finite"),
    ("stall_angle", 0.0, "RotorConfig.stall_angle must be positive"),
    ("hub_position", (0.0, NAN, 0.0), r"RotorConfig.hub_position\[1\] must be finite"),
    ("hub_position", (0.0, 0.0), "RotorConfig.hub_position must have 3 entries"),
    ("flap_frequency", NAN, "RotorConfig.flap_frequency must be finite"),
    ("flap_frequency", 0.9, "RotorConfig.flap_frequency must be >= 1"),
    ("direction", 0, r"RotorConfig.direction must be \+1 or -1"),
    ("lag_frequency", INF, "RotorConfig.lag_frequency must be finite"),
    ("blade_mass", -5.0, "RotorConfig.blade_mass must be positive"),
    ("flap_inertia", NAN, "RotorConfig.flap_inertia must be finite"),
    ("root_cutout", 1.0, r"RotorConfig.root_cutout must be in \[0, 1\)"),
    ("hinge_offset", 0.5, r"RotorConfig.hinge_offset must lie in \[0, root_cutout"),
])
def test_rotor_config_rejects(field, value, match):
    with pytest.raises(ConfigError, match=match):
        dataclasses.replace(ROTOR, **{field: value})


@pytest.mark.parametrize("field, value, match", [
    ("mass", NAN, r"AircraftConfig.mass must be finite \[kg\]"),
    ("Ixx", 0.0, "AircraftConfig.Ixx must be positive"),
    ("Ixz", 1e6, "inertia tensor must be positive definite"),
    ("rotors", ROTOR, r"got a single RotorConfig \(write rotors=\(rotor,\)\)"),
    ("rotors", ("U",), r"AircraftConfig.rotors\[0\] must be a RotorConfig"),
    ("trim_ct", (NAN,), r"AircraftConfig.trim_ct\[0\] must be finite"),
    ("trim_ct", (0.006, 0.005), "one thrust coefficient per rotor"),
    ("rho", 0.0, "AircraftConfig.rho must be positive"),
    ("propeller", "big", "AircraftConfig.propeller must be a PropellerConfig or None"),
    ("htail_position", (1.0, INF, 0.0), r"AircraftConfig.htail_position\[1\] must be finite"),
    ("fuselage_fx", -1.0, "AircraftConfig.fuselage_fx must be non-negative"),
])
def test_aircraft_config_rejects(field, value, match):
    with pytest.raises(ConfigError, match=match):
        dataclasses.replace(UH60, **{field: value})


def test_propeller_config_rejects():
    with pytest.raises(ConfigError, match="PropellerConfig.radius must be finite"):
        PropellerConfig(radius=NAN)
    with pytest.raises(ConfigError, match="PropellerConfig.solidity must be <= 1"):
        PropellerConfig(solidity=3.0)


def test_default_configurations_still_build():
    # the checks accept every shipped configuration (values unchanged)
    for cfg in (uh60_single_rotor(), coaxial_compound(), coaxial_compound(cruise=True)):
        assert cfg.mass > 0


# ----------------------------------------------------- wake settings / flight
@pytest.mark.parametrize("make, match", [
    (lambda: FlightCondition(alpha=NAN), r"FlightCondition.alpha must be finite \[rad\]"),
    (lambda: FlightCondition(alpha=1.0), r"FlightCondition.alpha must be within \+-30 deg"),
    (lambda: FlightCondition(speed=-1.0), "FlightCondition.speed must be non-negative"),
    (lambda: FlightCondition(speed=1j), "FlightCondition.speed must be real"),
    (lambda: WakeSettings(azimuth_step=NAN), "WakeSettings.azimuth_step must be finite"),
    (lambda: WakeSettings(wake_revolutions=INF), "WakeSettings.wake_revolutions must be finite"),
    (lambda: WakeSettings(initial_wake_kappa=0.5), "WakeSettings.initial_wake_kappa must be >= 1"),
    (lambda: WakeSettings(core_delta=NAN), "WakeSettings.core_delta must be finite"),
    (lambda: WakeSettings(buffer_revolutions=NAN), "WakeSettings.buffer_revolutions must be finite"),
    (lambda: WakeSettings(free_flapping="yes"), "WakeSettings.free_flapping must be True or False"),
    (lambda: WakeSettings(n_elements=3.5), "WakeSettings.n_elements must be an integer"),
])
def test_wake_settings_and_flight_condition_reject(make, match):
    with pytest.raises(WakeSettingsError, match=match):
        make()


@pytest.mark.parametrize("kwargs, match", [
    (dict(amplitude=NAN), r"SweepSpec.amplitude must be finite \[rad\]"),
    (dict(amplitude=2.0), r"SweepSpec.amplitude must be within \+-0.5 rad"),
    (dict(w_min=5.0, w_max=1.0), r"SweepSpec.w_max \(1.0\) must exceed w_min \(5.0\)"),
    (dict(duration=INF), "SweepSpec.duration must be finite"),
    (dict(seed=1.5), "SweepSpec.seed must be an integer or None"),
    (dict(noise_fraction=-0.1), "SweepSpec.noise_fraction must be non-negative"),
    (dict(kind="chirp"), "SweepSpec.kind must be"),
    (dict(kind="step", duration=1.0, trim_start=0.95, pulse_width=0.1), "must end before duration"),
])
def test_sweep_spec_rejects(kwargs, match):
    with pytest.raises(SweepSpecError, match=match):
        SweepSpec("theta0", **kwargs)


@pytest.mark.parametrize("kwargs, error, match", [
    (dict(specs=[SweepSpec("theta0_U")]), SweepSpecError,
     r"unknown control 'theta0_U'; this configuration has \['theta0', 'theta1s', 'theta1c', 'beta1s', 'beta1c'\]"),
    (dict(specs=[SweepSpec("theta0"), SweepSpec("theta0")]), SweepSpecError, "names must be unique"),
    (dict(specs=[]), SweepSpecError, "at least one SweepSpec"),
    (dict(specs=["theta0"]), SweepSpecError, r"specs\[0\] must be a SweepSpec"),
    (dict(n_jobs=0), ValueError, "n_jobs must be an integer >= 1"),
    (dict(points={"tail": (0.0, NAN, 0.0)}), ValueError, "point 'tail' must be three finite"),
    (dict(config="uh60"), TypeError, "config must be an aircraft AircraftConfig"),
])
def test_run_sweeps_rejects_before_any_work(kwargs, error, match):
    args = dict(config=UH60, settings=TINY_WAKE, flight=FlightCondition(), specs=[SweepSpec("theta0")],
                n_jobs=1, cache_dir=None, progress=False)
    args.update(kwargs)
    with pytest.raises(error, match=match):
        run_sweeps(args.pop("config"), args.pop("settings"), args.pop("flight"), args.pop("specs"), **args)


# --------------------------------------------------------------- wake trim/run
@pytest.fixture(scope="module")
def tiny_wake():
    return FreeVortexWake(UH60, TINY_WAKE)


@pytest.mark.parametrize("kwargs, match", [
    (dict(max_iter=0), "max_iter must be an integer >= 1, got 0"),
    (dict(ct=NAN), "ct must be finite"),
    (dict(ct=0.006 + 1j), "ct must be real"),
    (dict(tol=-1.0), r"tol must be positive \(> 0\)"),
    (dict(settle_revs=1.5), "settle_revs must be an integer"),
    (dict(revs_per_iter=0), "revs_per_iter must be an integer >= 1"),
    (dict(mode="torque"), "mode must be 'thrust' or 'torque_balance'"),
    (dict(damping=NAN), "damping must be finite"),
    (dict(max_time=0.0), "max_time must be positive"),
    (dict(ct=(0.006, 0.005)), r"ct needs one value per rotor \(1\)"),
])
def test_wake_trim_rejects(tiny_wake, kwargs, match):
    args = {"ct": 0.0061, **kwargs}
    with pytest.raises(WakeInputError, match=match):
        tiny_wake.trim(**args)


def test_wake_trim_refuses_an_impossible_thrust_at_once(tiny_wake):
    # 30x the UH-60 thrust: C_T/sigma = 2.2, far above what a stalling blade carries
    with pytest.raises(WakeTrimError, match=r"blade loading C_T/sigma = 2.23, above the 0.25") as info:
        tiny_wake.trim(ct=0.0061 * 30)
    assert info.value.residuals == {"CT": pytest.approx(0.183)}


def test_unconverged_wake_trim_raises_with_its_residuals():
    wake = FreeVortexWake(UH60, TINY_WAKE)
    with pytest.raises(WakeTrimError, match=r"not converged in max_iter = 1 iterations .* CT = ") as info:
        wake.trim(ct=0.0061, max_iter=1, settle_revs=1, revs_per_iter=1)
    assert info.value.result is not None and not info.value.result.converged
    assert set(info.value.residuals) == {"CT"} and abs(info.value.residuals["CT"]) > 2e-5
    assert wake._trim_state is None               # nothing to run sweeps from


@pytest.mark.parametrize("controls, duration, points, match", [
    ({"theta0": NAN}, 0.05, None, r"control 'theta0' must be finite \[rad\]"),
    ({"theta0": 0.01j}, 0.05, None, "control 'theta0' must be real"),
    ({"theta0": lambda t: NAN}, 0.05, None, "the callable returned nan"),
    ({"theta0": (np.array([0.0, 1.0]), np.array([0.0, NAN]))}, 0.05, None, r"\(t, u\) contain NaN"),
    ({"theta0_U": 0.01}, 0.05, None, r"unknown control names \['theta0_U'\]"),
    ({}, NAN, None, r"duration must be finite \[s\]"),
    ({}, 0.05, {"tail": (NAN, 0.0, 0.0)}, "points must map labels to three finite coordinates"),
])
def test_wake_run_rejects(tiny_wake, controls, duration, points, match):
    with pytest.raises(WakeInputError, match=match):
        tiny_wake.run(controls, duration, points=points)


# ------------------------------------------------------------ aircraft trim
class Counting:
    """Wraps Helicopter.derivatives to count model evaluations."""

    def __init__(self, heli):
        self.n, self._f = 0, heli.derivatives
        heli.derivatives = self

    def __call__(self, x, u):
        self.n += 1
        return self._f(x, u)


@pytest.fixture(scope="module")
def uh60_trim():
    heli = Helicopter(UH60, PittPeters(), FAST)
    return trim(heli)


@pytest.mark.parametrize("kwargs, match", [
    (dict(max_iter=0), "max_iter must be an integer >= 1, got 0"),
    (dict(tol=NAN), "tol must be finite"),
    (dict(condition={"speed": 0.0}), "condition must be a TrimCondition, got dict"),
    (dict(max_nfev=0), "max_nfev must be an integer >= 1"),
])
def test_aircraft_trim_rejects(uh60_trim, kwargs, match):
    with pytest.raises(TrimInputError, match=match):
        trim(uh60_trim.helicopter, **kwargs)


@pytest.mark.parametrize("kwargs, match", [
    (dict(speed=NAN), r"TrimCondition.speed must be finite \[m/s\]"),
    (dict(speed=-3.0), "TrimCondition.speed must be non-negative"),
    (dict(rotor_aoa=2.0), r"TrimCondition.rotor_aoa must be <= 0.523599 \[rad\]"),
    (dict(lateral_cyclic_difference=INF), "TrimCondition.lateral_cyclic_difference must be finite"),
])
def test_trim_condition_rejects(kwargs, match):
    with pytest.raises(TrimInputError, match=match):
        TrimCondition(**kwargs)


@pytest.mark.parametrize("inflow", [ClimbingLowerRotor, DynamicClimb, IsolatedRotors])
def test_thirty_times_the_weight_fails_as_a_trim_error_before_any_solving(inflow):
    # an earlier trim spent 104-150 s here and raised InflowError or a bare TrimError;
    # now a TrimError from the blade-loading check, with no model evaluation at
    # all (measured < 1 ms)
    cfg = coaxial_compound()
    heli = Helicopter(dataclasses.replace(cfg, mass=30 * cfg.mass), inflow(), FAST)
    count = Counting(heli)
    with pytest.raises(TrimError, match=r"blade loading C_T/sigma = 2.2\d on rotor 'U', above the 0.25"):
        trim(heli)
    assert count.n == 0


def test_an_unreachable_trim_stops_within_its_evaluation_budget():
    # 2.8x the weight passes the blade-loading check (C_T/sigma 0.21) but has no
    # trim with this inflow; an earlier solver had 4000 LM iterations'
    # worth of evaluations plus 30 unguarded Newton steps (9,600 evaluations and
    # 104 s at 30x, measured)
    cfg = coaxial_compound()
    heli = Helicopter(dataclasses.replace(cfg, mass=2.8 * cfg.mass), ClimbingLowerRotor(), FAST)
    count = Counting(heli)
    with pytest.raises(TrimError, match="evaluation budget max_nfev = 60 ran out") as info:
        trim(heli, max_nfev=60)
    # the budget counts every model evaluation; +2 for the square check and the
    # report of the residuals
    assert count.n <= 60 + 2
    assert info.value.residuals and all(np.isfinite(v) for v in info.value.residuals.values())


def test_a_spent_time_budget_is_a_trim_error(uh60_trim):
    with pytest.raises(TrimError, match=r"time budget max_time = 1e-06 s ran out"):
        trim(uh60_trim.helicopter, max_time=1e-6)


# --------------------------------------------------------------- linearize
def test_linearize_refuses_a_point_that_is_not_a_trim(uh60_trim):
    bad = dataclasses.replace(uh60_trim, x=uh60_trim.x.copy())
    bad.x[2] = 5.0                                  # w = 5 m/s: w-dot of several m/s^2
    wdot = trim_derivatives(bad)["wdot"]
    assert abs(wdot) > 1.0
    with pytest.raises(NotAtTrimError, match=r"not a trim: .* wdot = ") as info:
        linearize(bad, inputs="rotor")
    assert info.value.derivatives["wdot"] == pytest.approx(wdot)
    with pytest.warns(NotAtTrimWarning, match="not a trim"):
        sys = linearize(bad, inputs="rotor", off_trim="warn")
    assert sys.nstates == uh60_trim.helicopter.n_states
    # the real trim passes silently
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        linearize(uh60_trim, inputs="rotor")


@pytest.mark.parametrize("kwargs, match", [
    (dict(step_scale=NAN), "step_scale must be finite"),
    (dict(control_step=-1e-5), "control_step must be positive"),
    (dict(inputs="pilots"), "inputs must be 'pilot' or 'rotor', got 'pilots'"),
    (dict(off_trim="ignore"), "off_trim must be 'raise' or 'warn'"),
])
def test_linearize_rejects(uh60_trim, kwargs, match):
    with pytest.raises(LinearizeInputError, match=match):
        linearize(uh60_trim, **{"inputs": "rotor", **kwargs})


def test_modes_and_default_steps_reject(uh60_trim):
    with pytest.raises(LinearizeInputError, match="sys must be a control.StateSpace"):
        modes(control.tf([1], [1, 1]))
    with pytest.raises(LinearizeInputError, match="n_dominant must be an integer >= 1"):
        modes(control.ss([[-1.0]], [[1.0]], [[1.0]], [[0.0]]), n_dominant=0)
    with pytest.raises(LinearizeInputError, match="sys.A must be a non-empty matrix of finite values"):
        modes(control.ss([[np.nan]], [[1.0]], [[1.0]], [[0.0]]))
    with pytest.raises(LinearizeInputError, match="scale must be finite"):
        default_steps(uh60_trim.helicopter, NAN)


def test_linearize_needs_a_trim_result(uh60_trim):
    with pytest.raises(LinearizeInputError, match="must be the TrimResult .* got StateSpace"):
        linearize(control.ss([[-1.0]], [[1.0]], [[1.0]], [[0.0]]))


# ---------------------------------------------------------- coupling numerator
@pytest.fixture(scope="module")
def pilot_plant():
    """A strictly proper 4-state plant with the coaxial's pilot-input and body names."""
    rng = np.random.default_rng(13)
    a = -np.eye(4) + 0.1 * rng.standard_normal((4, 4))
    b = rng.standard_normal((4, 4))
    return control.ss(a, b, np.eye(4), np.zeros((4, 4)), states=["w", "p", "q", "r"],
                      inputs=["delta_col", "delta_lon", "delta_lat", "delta_ped"],
                      outputs=["w", "p", "q", "r"])


def test_the_coupling_numerator_itself_works(pilot_plant):
    g = coupling_numerator(pilot_plant, "p", "delta_lat", {"q": "delta_lon"})
    assert g.ninputs == 1 and g.noutputs == 1 and np.any(np.asarray(g.B) != 0)


@pytest.mark.parametrize("output, input, constrained, match", [
    ("p", "delta_lat", {"q": "delta_lat"},
     r"the swept input 'delta_lat' is also the control holding \['q'\]"),
    ("pp", "delta_lat", {}, r"unknown output 'pp'; the system has outputs \['w', 'p', 'q', 'r'\]"),
    ("p", "delta_x", {}, "unknown input 'delta_x'"),
    ("p", "delta_lat", {"qq": "delta_lon"}, r"constrained names unknown: outputs \['qq'\]"),
    ("p", "delta_lat", {"q": "delta_lon", "r": "delta_lon"}, "each constrained output needs its own control"),
    ("p", "delta_lat", {"p": "delta_lon"}, "the plant output 'p' cannot also be a constrained output"),
    ("p", "delta_lat", ["q"], "constrained must be a dict"),
])
def test_coupling_numerator_rejects(pilot_plant, output, input, constrained, match):
    with pytest.raises(CouplingError, match=match):
        coupling_numerator(pilot_plant, output, input, constrained)


def test_coupling_numerator_rejects_bad_systems(pilot_plant):
    with pytest.raises(CouplingError, match="must be a control.StateSpace .* TransferFunction"):
        coupling_numerator(control.tf([1], [1, 1]), "p", "delta_lat", {})
    nan_plant = control.ss(np.full((4, 4), np.nan), pilot_plant.B, pilot_plant.C, pilot_plant.D,
                           inputs=pilot_plant.input_labels, outputs=pilot_plant.output_labels)
    with pytest.raises(CouplingError, match="NaN or infinite"):
        coupling_numerator(nan_plant, "p", "delta_lat", {"q": "delta_lon"})
    with pytest.raises(CouplingError, match=r"cutoff must be a positive finite frequency \[rad/s\]"):
        residualize(pilot_plant, NAN)
