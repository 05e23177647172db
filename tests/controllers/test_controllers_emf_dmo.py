import numpy as np
import pytest
import control

from controllers import (DMOSettings, EMFDesign, PIDGains, default_specs, dmo, evaluate_specs, hover_roll_plant, hq_window, optimize)
from controllers.emf import fit_equivalent_delay, fit_inverse_plant
from controllers.plants import second_order_actuator
from controllers.emf import FrequencyFunction
from controllers.plants import DelayedLTI


@pytest.fixture(scope="module")
def design():
    return EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.1, 0.2), actuator=second_order_actuator())


def test_inverse_plant_fit_recovers_first_order_plant_and_delay_fit_recovers_delay():
    # K/(s+a) with no delay is recovered exactly; a pure delay is recovered by the unit-gain fit
    plant = control.tf([6.0], [1, 1.5])
    fitted = fit_inverse_plant(plant)
    num, den = control.tfdata(fitted)
    assert num[0][0][-1] == pytest.approx(6.0, rel=1e-6) and den[0][0][-1] == pytest.approx(1.5, rel=1e-6)
    tau = fit_equivalent_delay(FrequencyFunction(lambda s: np.exp(-0.037 * s)))
    assert tau == pytest.approx(0.037, rel=1e-9)


def test_state_space_closed_loop_matches_exact_frequency_responses(design):
    cl = design.closed_loop()
    assert cl.input_labels == ["delta_lat_s", "phi_d"]
    w = np.array([0.3, 1.0, 3.0])
    # Padé (3rd order) of 10-30 ms delays: < 0.1 % error below 3 rad/s;
    # the disturbance path's rate filter s/(s/1000+1) adds < 0.3 % at 3 rad/s.
    pr = np.squeeze(control.frequency_response(cl[cl.output_labels.index("p"), 0], w).complex)
    np.testing.assert_allclose(pr, design.roll_rate_response().response(w), rtol=2e-3)
    dist = np.squeeze(control.frequency_response(cl[cl.output_labels.index("phi_meas"), 1], w).complex)
    np.testing.assert_allclose(dist, design.disturbance_response().response(w), rtol=5e-3)


def test_with_plant_keeps_gains_inverse_plant_and_delay(design):
    other = design.with_plant(hover_roll_plant(flap_damping=0.3))
    assert other.gains == design.gains and other.inverse_plant is design.inverse_plant
    assert other.equivalent_delay == design.equivalent_delay
    assert other.plant is not design.plant


def test_fast_closed_loop_poles_equal_the_interconnect_spectrum(design):
    # closed_loop_poles uses feedback(L) + the gain-independent blocks; the full
    # interconnect model (built independently from named blocks) must have the
    # same eigenvalues (1e-8 relative: eigenvalue round-off of a 29-state matrix)
    full = np.linalg.eigvals(design.closed_loop().A)
    fast = design.closed_loop_poles()
    assert fast.size == full.size
    assert max(np.min(np.abs(fast - f)) / max(1.0, abs(f)) for f in full) < 1e-8


@pytest.mark.slow
def test_robust_dmo_meets_every_spec_on_every_plant_and_costs_crossover(design):
    other = design.with_plant(hover_roll_plant(gain=4.0, roll_damping=1.8, flap_damping=0.2))
    settings = DMOSettings(tolerance=0.01)
    alone = dmo(design, progress=False, settings=settings)
    robust = dmo([design, other], progress=False, settings=settings, labels=["nominal", "other"])
    assert len(robust.designs) == 2 and robust.designs[0].gains == robust.designs[1].gains
    final = robust.history[robust.history.feasible].iloc[-1]
    table = robust.specs
    assert set(table.plant) == {"nominal", "other"}
    assert table[table.kind != "objective"].met.all()
    # one gain set for two plants cannot beat the best for the nominal alone
    # (beyond the two bisection tolerances)
    assert robust.crossover <= alone.crossover * 1.02
    specs = default_specs(final.crossover_min, final.drb_min)
    for d in robust.designs:
        assert evaluate_specs(d, specs).query("kind != 'objective'").met.all()
    fig = hq_window(robust.designs, specs, labels=["nominal", "other"])
    assert all(ax.has_data() for ax in fig.axes)      # no empty axes
    assert len(fig.axes) == len([s for s in specs if s.kind != "objective"]) + 1   # + Nichols chart
    assert fig.legends and "Level 1" in [t.get_text() for t in fig.legends[0].get_texts()]


def test_bad_inputs_are_rejected():
    with pytest.raises(ValueError, match="delay must be >= 0"):
        hover_roll_plant(delay=-0.1)
    with pytest.raises(ValueError, match="sensor_delay"):
        EMFDesign(hover_roll_plant(), PIDGains(1, 1, 1), sensor_delay=-1)
    with pytest.raises(ValueError, match="order must be"):
        fit_inverse_plant(control.tf([1], [1, 1]), order="2/3")


def _with_low_frequency_factor(factor):
    base = hover_roll_plant()
    plant = control.series(factor, base.system)
    return EMFDesign(DelayedLTI(plant, base.delay), PIDGains(0.3, 0.1, 0.2), actuator=second_order_actuator())


def test_closed_loop_poles_drop_the_mode_phi_integrator_cancels_but_keep_instability():
    # a p/delta zero at +1e-3 rad/s (round-off of a hovering airframe's zero at the
    # origin) is cancelled by phi = integral(p): the full eigenvalues contain it ...
    design = _with_low_frequency_factor(control.tf([0.5, -0.5e-3], [1, 0.5]))
    full = np.linalg.eigvals(design.closed_loop().A)
    assert np.any(np.abs(full - 1e-3) < 1e-4)
    # ... the reported poles do not, and everything else is kept
    poles = design.closed_loop_poles()
    assert poles.size == full.size - 1 and np.all(poles.real < 0)
    # a genuinely unstable loop (an unstable plant pole the gains cannot hold) is reported
    unstable = _with_low_frequency_factor(control.tf([0.005], [1, -0.005]))
    assert np.max(unstable.closed_loop_poles().real) > 0.01


@pytest.mark.slow
def test_dmo_does_not_depend_on_the_phase_branch_at_the_lowest_grid_frequency():
    # zeros at +0.02 and -0.01 rad/s below a lightly damped 0.23 rad/s mode (a free
    # aircraft in hover): the phase at 0.05 rad/s is about -173 deg, so unwrapping from
    # there puts the crossover region 360 deg low; the optimiser anchors the branch
    # at the crossover boundary instead (before the fix this case was infeasible)
    factor = control.tf(np.polymul([1, -0.02], [1, 0.01]), [1, 2 * 0.04 * 0.23, 0.23 ** 2])
    design = _with_low_frequency_factor(factor)
    w = DMOSettings().omega
    q = design._g(1j * w) * design._sensor(1j * w)
    assert np.degrees(np.angle(q[0])) < -170
    # the +0.02 rad/s zero needs integral action to hold the slow mode: with all gains
    # free the smooth NLP (blind below the phase-constraint band) drops K_Iphi to 0 and
    # the loop is unstable; the dissertation's tie K_Iphi = K_phi w_c/5 keeps it
    settings = DMOSettings(tie_integral=True, phase_constraint_from=(0.5, 0.2, 0.1))
    settings.ipopt = {**settings.ipopt, "ipopt.max_iter": 300}    # this start needs ~100-200 iterations
    result = optimize(design, 1.5, 0.9, settings=settings)
    assert result.feasible, result.unmet
    assert result.design.gains.K_Iphi == pytest.approx(result.design.gains.K_phi * 1.5 / 5)
