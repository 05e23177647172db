"""Pitt-Peters model: closed forms, momentum theory, wake skew, K_R, errors."""
import control
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from aircraft.inflow import (ClimbingLowerRotor, InflowError, PittPeters, RotorOperatingPoint,
                             mlbar_from_statespace, momentum_inflow, pitt_peters_matrices)

OMEGA = 27.0


@pytest.mark.parametrize("ct", [0.003, 0.0061, 0.01])
def test_hover_linearisation_closed_form_and_time_scaling(ct):
    lam_h = np.sqrt(ct / 2)
    sys = PittPeters().linear([ct, 0, 0], (RotorOperatingPoint(OMEGA),))
    m, lbar = mlbar_from_statespace(sys, OMEGA)
    # closed form, Eq. 2.11 convention: written here, not taken from the package
    np.testing.assert_allclose(np.diag(m), [8 / (3 * np.pi), -16 / (45 * np.pi), -16 / (45 * np.pi)], rtol=1e-8)
    np.testing.assert_allclose(np.diag(lbar), [4 * lam_h, -lam_h, -lam_h], rtol=1e-7)
    # seconds: A = -Omega M^-1 Lbar, poles -Omega * (3 pi/2) lam_h and -Omega (45 pi/16) lam_h
    np.testing.assert_allclose(np.sort(np.linalg.eigvals(sys.A).real),
                               np.sort(-OMEGA * lam_h * np.array([4 * 3 * np.pi / 8, 45 * np.pi / 16, 45 * np.pi / 16])),
                               rtol=1e-7)


@pytest.mark.parametrize("mu_c", [0.01, 0.03])
def test_climb_linearisation_follows_eqs_2_4_2_5(mu_c):
    ct = 0.0043
    op = (RotorOperatingPoint(23.7, mu_z=mu_c),)
    lam = (-mu_c + np.sqrt(mu_c ** 2 + 2 * ct)) / 2        # quadratic formula of lam (lam + mu_c) = C_T/2
    _, lbar = mlbar_from_statespace(PittPeters().linear([ct, 0, 0], op), 23.7)
    # d/dlam [2 lam (lam + mu_c)] = 4 lam + 2 mu_c ; moment rows -(lam + mu_c/2)  (Eq. 2.4, climb positive up)
    np.testing.assert_allclose(np.diag(lbar), [4 * lam + 2 * mu_c, -(lam + mu_c / 2), -(lam + mu_c / 2)], rtol=1e-7)


@pytest.mark.parametrize("mu", [0.1, 0.2, 0.35])
def test_forward_flight_steady_inflow_has_pitt_peters_skew(mu):
    ct = 0.0061
    x = PittPeters().steady_state([ct, 0, 0], (RotorOperatingPoint(OMEGA, mu=mu),))
    lam = momentum_inflow(ct, mu)
    # momentum theory solved here independently: 2 lam sqrt(mu^2 + lam^2) = C_T
    assert 2 * lam * np.hypot(mu, lam) == pytest.approx(ct, rel=1e-12)
    assert x[0] == pytest.approx(lam, rel=1e-9)
    chi = np.arctan2(mu, lam)                               # wake skew angle from the shaft
    # classical Pitt-Peters result: lam1c = (15 pi/32) tan(chi/2) lam0, lam1s = 0
    assert x[2] == pytest.approx(15 * np.pi / 32 * np.tan(chi / 2) * lam, rel=1e-8)
    assert abs(x[1]) < 1e-12


def test_forward_flight_coupling_signs_match_identified_free_wake():
    # Eqs. 4.7 (mu = 0.1) and 4.8 (mu = 0.2): identified Lbar13 and Lbar31 are both positive
    for mu in (0.1, 0.2):
        _, lbar = mlbar_from_statespace(PittPeters().linear([0.0061, 0, 0], (RotorOperatingPoint(OMEGA, mu=mu),)), OMEGA)
        assert lbar[0, 2] > 0 and lbar[2, 0] > 0
        assert abs(lbar[0, 1]) < 1e-9 and abs(lbar[1, 2]) < 1e-9     # lam1s stays uncoupled (Eq. 2.12)


def test_kr_wake_distortion_steady_gain():
    kr = 1.5
    model = PittPeters(kr=kr)
    assert model.input_names == ["CT", "CL", "CM", "beta1s_dot", "beta1c_dot"]
    sys = model.linear([0.0061, 0, 0], (RotorOperatingPoint(OMEGA),))
    dc = control.dcgain(sys)
    # Eq. 2.29 at steady state: lam1s = Lbar^-1 dC_L - K_R beta1s* with beta1s* = beta1s_dot / Omega
    assert dc[1, 3] == pytest.approx(-kr / OMEGA, rel=1e-6)
    assert dc[2, 4] == pytest.approx(-kr / OMEGA, rel=1e-6)
    assert abs(dc[0, 3]) < 1e-9


def test_linear_matches_nonlinear_small_step_forward_flight():
    model = PittPeters()
    ops = (RotorOperatingPoint(OMEGA, mu=0.15),)
    loads = np.array([0.0061, 0.0, 0.0])
    sys = model.linear(loads, ops)
    step = np.array([3e-5, 1e-5, -1e-5])
    t = np.linspace(0, 0.6, 121)
    nl = solve_ivp(lambda _t, x: model.derivatives(x, loads + step, ops), (0, t[-1]), sys.trim_states,
                   t_eval=t, rtol=1e-10, atol=1e-13, method="LSODA")
    y_nl = nl.y - sys.trim_states[:, None]
    y_lin = control.forced_response(sys, t, np.repeat(step[:, None], t.size, axis=1)).outputs
    # step 0.5 % of C_T: second-order terms ~ 0.5 % of the response; allow 2 % of its peak
    scale = np.max(np.abs(np.asarray(y_lin)), axis=1, keepdims=True)
    assert np.all(np.abs(np.asarray(y_nl) - np.asarray(y_lin)) <= 0.02 * scale + 1e-12)


def test_pitt_peters_errors():
    op = (RotorOperatingPoint(OMEGA),)
    with pytest.raises(InflowError, match="positive thrust"):
        momentum_inflow(0.0)
    with pytest.raises(InflowError, match="NaN or infinite"):
        PittPeters().derivatives(np.zeros(3) + 0.05, [np.nan, 0, 0], op)
    with pytest.raises(InflowError, match="1 RotorOperatingPoint"):
        PittPeters().steady_state([0.006, 0, 0], op * 2)
    with pytest.raises(InflowError, match="distinct"):
        PittPeters(("U", "U"))
    with pytest.raises(InflowError, match="x must have 3"):
        PittPeters().inflow(np.zeros(6), None, op)
    with pytest.raises(InflowError, match="flow up through the disk"):
        pitt_peters_matrices(-0.05)
    with pytest.raises(InflowError, match="load input per state"):
        mlbar_from_statespace(control.ss(-np.eye(3), np.ones((3, 1)), np.eye(3), 0), OMEGA)
    with pytest.raises(InflowError, match="x must have 3"):
        PittPeters().derivatives(np.zeros(2), [0.006, 0, 0], op)
    with pytest.raises(InflowError, match="rates must have 2"):
        PittPeters(kr=1.5).derivatives(np.array([0.05, 0, 0]), [0.006, 0, 0], op, rates=np.zeros(3))
    assert PittPeters(rotors=("U",)).rotors == ("U",)


def test_climbing_lower_rotor_linear_is_static_even_before_set_trim():
    loads = np.array([0.0053, 0, 0, 0.0043, 0, 0])
    ops = tuple(RotorOperatingPoint(23.7) for _ in range(2))
    model = ClimbingLowerRotor()
    sys = model.linear(loads, ops)
    assert abs(sys.A[3, 0]) < 1e-12 and model.frozen_climb is None
    x = model.steady_state(loads, ops)
    # the lower rotor's total downwash is its own lam0 plus the upper trimmed lam0 (Eq. 2.6)
    assert model.inflow(x, None, ops)[3] == pytest.approx(x[3] + x[0], rel=1e-12)
    model.set_trim(x, loads, ops)
    assert model.frozen_climb == pytest.approx(x[0])
    model.release_trim()
    assert model.frozen_climb is None


@pytest.mark.parametrize("ct", [-0.002, 0.0, 0.004])
def test_edgewise_momentum_solution_accepts_zero_and_negative_thrust(ct):
    from scipy.optimize import brentq
    mu, mu_c = 0.3, -0.02          # disk tilted back: free stream up through the disk
    # independent root: bracket the momentum equation written here
    lam_ref = brentq(lambda l: 2 * l * np.sqrt(mu ** 2 + (mu_c + l) ** 2) - ct, -0.05, 0.05, xtol=1e-15)
    assert momentum_inflow(ct, mu, mu_c) == pytest.approx(lam_ref, abs=1e-13)
    x = PittPeters().steady_state([ct, 0, 0], (RotorOperatingPoint(OMEGA, mu=mu, mu_z=mu_c),))
    assert x[0] == pytest.approx(lam_ref, abs=1e-11)
    # still no solution for zero/negative thrust in axial flight
    with pytest.raises(InflowError, match="axial flight needs a positive thrust"):
        momentum_inflow(min(ct, 0.0) - 1e-4, 0.0, mu_c)
