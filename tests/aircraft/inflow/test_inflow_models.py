import numpy as np
import pytest
import control
from scipy.integrate import solve_ivp
from scipy.optimize import fsolve

from aircraft.inflow import (ClimbingLowerRotor, DynamicClimb, IdentifiedInflow, InflowError,
                             IsolatedRotors, PittPeters, RotorOperatingPoint, mlbar_from_statespace,
                             momentum_inflow)
from aircraft.inflow import inflow_names, published
from aircraft.inflow.published import COAXIAL_HOVER_6STATE

OMEGA = 27.0
CT = 0.0061


def test_pitt_peters_hover_linearisation_matches_closed_form():
    # closed form (dissertation §1.2.2.1 / Tables 4.1-4.2 Pitt-Peters rows), written here
    lam_h = np.sqrt(CT / 2)
    expected_m = np.diag([8 / (3 * np.pi), -16 / (45 * np.pi), -16 / (45 * np.pi)])
    expected_l = np.diag([4 * lam_h, -lam_h, -lam_h])
    sys = PittPeters().linear(np.array([CT, 0, 0]), (RotorOperatingPoint(OMEGA),))
    M, L = mlbar_from_statespace(sys, OMEGA)
    # central differences with relative step 1e-6 on a smooth model: ~1e-9 relative error
    np.testing.assert_allclose(M, expected_m, atol=1e-7)
    np.testing.assert_allclose(L, expected_l, atol=1e-8)
    assert sys.input_labels == ["CT", "CL", "CM"] and sys.output_labels == ["lam0", "lam1s", "lam1c"]


@pytest.mark.parametrize("ct, mu_c", [(0.0061, 0.0), (0.0043, 0.04), (0.005, 0.1)])
def test_momentum_inflow_in_climb_solves_the_quadratic(ct, mu_c):
    lam = momentum_inflow(ct, 0.0, mu_c)
    # Eq. 2.5: lam (lam + mu_c) = C_T / 2 -> positive root of the quadratic
    assert lam == pytest.approx((-mu_c + np.sqrt(mu_c ** 2 + 2 * ct)) / 2, rel=1e-12)
    steady = PittPeters().steady_state(np.array([ct, 0, 0]), (RotorOperatingPoint(OMEGA, mu_z=mu_c),))
    assert steady[0] == pytest.approx(lam, rel=1e-9)


def test_forward_flight_steady_state_is_momentum_theory_with_glauert_skew():
    op = (RotorOperatingPoint(OMEGA, mu=0.2),)
    x = PittPeters().steady_state(np.array([CT, 0, 0]), op)
    assert x[0] == pytest.approx(momentum_inflow(CT, 0.2), rel=1e-9)
    assert x[2] > 0          # more inflow at the rear of the disk (psi = 0 aft)


def test_dynamic_climb_steady_state_satisfies_coupled_eq_2_7():
    loads = np.array([0.0053, 0, 0, 0.0043, 0, 0])
    ops = tuple(RotorOperatingPoint(23.7) for _ in range(2))
    x = DynamicClimb().steady_state(loads, ops)

    # independent: momentum theory of each rotor in the other's climb, solved with fsolve
    def eqs(v):
        lu, ll = v
        return [lu * (lu + 0.86 * ll) - 0.0053 / 2, ll * (ll + 1.13 * lu) - 0.0043 / 2]
    lu, ll = fsolve(eqs, [0.04, 0.04], xtol=1e-12)
    assert x[0] == pytest.approx(lu, rel=1e-8) and x[3] == pytest.approx(ll, rel=1e-8)
    total = DynamicClimb().inflow(x, loads, ops)
    assert total[3] > total[0]                 # lower rotor sees more inflow
    assert total[3] == pytest.approx(ll + 1.13 * lu, rel=1e-10)


def test_climbing_lower_rotor_freezes_climb_at_trim():
    loads = np.array([0.0053, 0, 0, 0.0043, 0, 0])
    ops = tuple(RotorOperatingPoint(23.7) for _ in range(2))
    model = ClimbingLowerRotor()
    x = model.steady_state(loads, ops)
    assert x[3] == pytest.approx(momentum_inflow(0.0043, 0.0, x[0]), rel=1e-9)
    model.set_trim(x, loads, ops)
    sys = model.linear(loads, ops)
    # static interference: no lam0^L <- lam0^U coupling in the linear model
    assert abs(sys.A[3, 0]) < 1e-9
    dyn = DynamicClimb().linear(loads, ops)
    assert abs(dyn.A[3, 0]) > 1e-3             # dynamic interference couples them


def test_linear_model_matches_nonlinear_step_response():
    model = DynamicClimb()
    loads = np.array([0.0053, 0, 0, 0.0043, 0, 0])
    ops = tuple(RotorOperatingPoint(23.7) for _ in range(2))
    sys = model.linear(loads, ops)
    x0 = sys.trim_states
    step = np.array([2e-5, 1e-5, 0, 0, 0, 1e-5])   # small: linear regime
    # the default Dynamic Climb carries K_R (Eq. 2.29): step the flap-rate inputs too [rad/s]
    rate_step = np.array([0.01, 0.0, 0.0, -0.01])
    assert sys.input_labels[6:] == model.rate_names
    t = np.linspace(0, 1.0, 201)
    nl = solve_ivp(lambda _t, x: model.derivatives(x, loads + step, ops, rate_step), (0, 1), x0, t_eval=t,
                   rtol=1e-10, atol=1e-13)
    u_step = np.concatenate([step, rate_step])
    lin = control.forced_response(sys, t, np.repeat(u_step[:, None], t.size, axis=1))
    y_nl = np.array([model.inflow(x, loads + step, ops) for x in nl.y.T]).T - sys.trim_outputs[:, None]
    # 1e-5 steps on lam ~ 0.04: nonlinearity O(step/lam) ~ 0.1 %
    np.testing.assert_allclose(lin.outputs[:, -1], y_nl[:, -1], rtol=5e-3, atol=1e-9)


def test_published_6_state_model_as_identified_inflow():
    P = COAXIAL_HOVER_6STATE
    model = IdentifiedInflow.from_published(P)
    assert model.input_names == P.input_names and model.output_names == P.output_names
    # steady-state gain equals inv(Lbar) computed independently (Padé delays have unit DC gain)
    np.testing.assert_allclose(control.dcgain(model.system), np.linalg.inv(P.Lbar), rtol=1e-6, atol=1e-9)
    ops = tuple(RotorOperatingPoint(P.omega) for _ in range(2))
    x = model.steady_state(model.loads_ref, ops)
    np.testing.assert_allclose(model.inflow(x, model.loads_ref, ops), model.inflow_ref, atol=1e-12)


def test_inflow_models_reject_bad_inputs():
    op = (RotorOperatingPoint(OMEGA),)
    with pytest.raises(InflowError, match="positive thrust"):
        PittPeters().steady_state(np.array([-0.001, 0, 0]), op)
    with pytest.raises(InflowError, match="loads must have 3"):
        PittPeters().derivatives(np.zeros(3), np.zeros(6), op)
    with pytest.raises(ValueError, match="omega must be positive"):
        RotorOperatingPoint(omega=0.0)
    unstable = control.ss(np.eye(6), np.eye(6), np.eye(6), 0 * np.eye(6),
                          inputs=COAXIAL_HOVER_6STATE.input_names, outputs=COAXIAL_HOVER_6STATE.output_names)
    with pytest.raises(InflowError, match="unstable"):
        IdentifiedInflow(unstable)
    assert IsolatedRotors().rotors == ("U", "L")


@pytest.mark.parametrize("model", published.ALL_MODELS, ids=lambda m: m.name)
def test_every_published_model_is_usable_as_identified_inflow(model):
    inflow = IdentifiedInflow.from_published(model)
    assert inflow.output_names == inflow_names(model.rotors)
    assert np.all(np.linalg.eigvals(inflow.system.A).real < 0)
    if hasattr(model, "F"):
        # DC gain of the F/G/C model equals -C F^-1 G (columns reordered by name), computed here
        g = np.asarray(model.G)
        cols = [list(model.inputs).index(n) for n in inflow.input_names]
        expected = -model.C @ np.linalg.solve(model.F, g[:, cols])
        # same linear algebra, different path (control.dcgain): round-off only
        np.testing.assert_allclose(control.dcgain(inflow.system), expected, rtol=1e-8, atol=1e-12)
        assert inflow.uses_flap_rates == ("beta1s_dot_U" in model.inputs)
    else:
        # Padé approximants have unit DC gain: the steady state is inv(Lbar); minreal tol 1e-9
        np.testing.assert_allclose(control.dcgain(inflow.system), np.linalg.inv(model.Lbar), rtol=1e-6, atol=1e-9)


def test_published_model_without_trim_thrust_needs_trim_loads():
    import dataclasses
    bare = dataclasses.replace(published.COAXIAL_FORWARD_12STATE, condition={"flight": "forward", "mu": 0.54})
    with pytest.raises(InflowError, match="no trim thrust"):
        IdentifiedInflow.from_published(bare)
    model = IdentifiedInflow.from_published(bare, loads_ref=np.array([0.0073, 0, 0, 0.0065, 0, 0]))
    np.testing.assert_allclose(model.loads_ref, [0.0073, 0, 0, 0.0065, 0, 0])
