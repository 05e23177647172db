"""IdentifiedInflow (M/Lbar/tau with Padé, F/G/C with flap rates) and the printed models."""
import control
import numpy as np
import pytest

from aircraft.inflow import IdentifiedInflow, InflowError, PittPeters, RotorOperatingPoint, published
from aircraft.inflow.identified import mltau_statespace


def _exact_delayed_response(M_az, L, tau, omega, w):
    """(M/Omega s + Lbar)^-1 with element-wise exp(-tau s), evaluated directly (Eq. 2.16)."""
    out = []
    for wk in w:
        s = 1j * wk
        out.append(np.linalg.inv(M_az / omega * s + L) * np.exp(-tau * s))
    return np.array(out)


def test_pade_realisation_matches_exact_delays_at_low_frequency():
    P = published.COAXIAL_HOVER_6STATE
    sys = mltau_statespace(P.M, P.Lbar, P.tau, omega=P.omega, pade_order=3)
    w = np.array([0.5, 1.0, 2.0, 5.0])                     # rad/s: the flight-dynamics range
    got = np.moveaxis(np.asarray(sys(1j * w)), -1, 0)
    want = _exact_delayed_response(P.M, P.Lbar, P.tau, P.omega, w)
    # 3rd-order Padé, omega tau <= 0.63: phase error < 1e-4 rad; minreal tolerance 1e-9
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-4 * np.max(np.abs(want)))
    assert sys.nstates < 6 + 3 * np.count_nonzero(P.tau) * 6      # minimal realisation shrank it


def test_identified_pitt_peters_matrices_reproduce_pitt_peters_linear():
    ct, omega = 0.0061, 27.0
    lam_h = np.sqrt(ct / 2)
    M = np.diag([8 / (3 * np.pi), -16 / (45 * np.pi), -16 / (45 * np.pi)])
    L = np.diag([4 * lam_h, -lam_h, -lam_h])
    ident = IdentifiedInflow.from_matrices(M, L, omega=omega, rotors=("",))
    ident_s = IdentifiedInflow.from_matrices(M / omega, L, omega=omega, rotors=("",), time="seconds")
    pp = PittPeters().linear([ct, 0, 0], (RotorOperatingPoint(omega),))
    w = np.array([0.3, 3.0, 30.0])
    for other in (ident.system, ident_s.system):
        # numerical linearisation (relative step 1e-6) against exact matrices: ~1e-8
        np.testing.assert_allclose(np.asarray(other(1j * w)), np.asarray(pp(1j * w)), rtol=1e-6)


def test_identified_inflow_is_a_perturbation_about_its_trim():
    P = published.COAXIAL_HOVER_6STATE
    model = IdentifiedInflow.from_published(P)
    ops = tuple(RotorOperatingPoint(P.omega) for _ in range(2))
    x_ref = model.steady_state(model.loads_ref, ops)
    np.testing.assert_allclose(x_ref, 0, atol=1e-15)
    np.testing.assert_allclose(model.inflow(x_ref, None, ops), model.inflow_ref)
    dC = np.array([1e-4, 0, 0, 0, 0, 2e-5])
    x = model.steady_state(model.loads_ref + dC, ops)
    # steady perturbation = inv(Lbar) dC, computed independently with numpy
    np.testing.assert_allclose(model.inflow(x, None, ops) - model.inflow_ref, np.linalg.solve(P.Lbar, dC),
                               rtol=1e-6, atol=1e-12)
    np.testing.assert_allclose(model.derivatives(x, model.loads_ref + dC, ops), 0, atol=1e-12)


def test_fgc_model_with_flap_rates_keeps_printed_columns_by_name():
    P = published.COAXIAL_HOVER_12STATE
    model = IdentifiedInflow.from_published(P)
    assert model.uses_flap_rates and model.n_states == 12
    assert model.input_names[-4:] == ["beta1s_dot_U", "beta1c_dot_U", "beta1s_dot_L", "beta1c_dot_L"]
    for name in ("CT_U", "CM_U", "beta1s_dot_U", "beta1c_dot_L"):
        np.testing.assert_array_equal(model.system.B[:, model.input_names.index(name)],
                                      P.G[:, P.input_order.index(name)])
    # lambda = lambda_N + lambda_F (Eq. 6.2)
    np.testing.assert_array_equal(model.system.C[0], [1, 1] + [0] * 10)


def test_printed_model_poles_and_eq_6_9_axis_signs():
    for model in published.ALL_MODELS:
        a = model.F if hasattr(model, "F") else -np.linalg.solve(model.M_seconds, model.Lbar)
        assert np.max(np.linalg.eigvals(a).real) < 0, model.name
    # Eq. 6.9 as printed: lateral and longitudinal on-axis DC gains have opposite signs
    # (a convention slip noted in published.py); Eq. 5.3 has both negative as in Pitt-Peters
    P = published.COAXIAL_HOVER_12STATE
    dc = -P.C @ np.linalg.solve(P.F, P.G)
    assert dc[1, 1] == pytest.approx(-dc[2, 3])
    assert dc[1, 1] > 0
    inv53 = np.linalg.inv(published.COAXIAL_HOVER_6STATE.Lbar)
    assert inv53[1, 1] < 0 and inv53[2, 2] < 0


def test_tables_4_1_4_2_as_data():
    t1, t2 = published.tables_4_1_4_2()
    assert t1.loc["Pitt-Peters (Ref. 25)", "Lbar11"] == 0.214
    assert t2.loc["MFW", "tau22"] == 0.0369
    m = published.UH60_HOVER_MFW
    assert m.time == "seconds" and m.M[1, 1] == m.M[2, 2] == -0.0063


def test_identified_inflow_errors():
    names = dict(inputs=["CT", "CL", "CM"], outputs=["lam0", "lam1s", "lam1c"])
    with pytest.raises(InflowError, match="unstable"):
        IdentifiedInflow(control.ss(np.eye(3), np.eye(3), np.eye(3), 0 * np.eye(3), **names), rotors=("",))
    with pytest.raises(InflowError, match="feedthrough"):
        IdentifiedInflow(control.ss(-np.eye(3), np.eye(3), np.eye(3), np.eye(3), **names), rotors=("",))
    with pytest.raises(InflowError, match="inputs"):
        IdentifiedInflow(control.ss(-np.eye(3), np.eye(3), np.eye(3), 0 * np.eye(3),
                                    inputs=["a", "b", "c"], outputs=names["outputs"]), rotors=("",))
    model = IdentifiedInflow(control.ss(-np.eye(3), np.eye(3), np.eye(3), 0 * np.eye(3), **names), rotors=("",))
    with pytest.raises(InflowError, match="loads must have 3"):
        model.derivatives(np.zeros(3), np.zeros(6), None)
    with pytest.raises(InflowError, match="x must have 3"):
        model.inflow(np.zeros(4), None, None)
    # rotors inferred from the canonical output names
    assert IdentifiedInflow(control.ss(-np.eye(3), np.eye(3), np.eye(3), 0 * np.eye(3), **names)).rotors == ("",)
    with pytest.raises(InflowError, match="non-negative delays"):
        mltau_statespace(np.eye(3), np.eye(3), -np.eye(3), omega=27.0)
    with pytest.raises(InflowError, match="azimuth"):
        mltau_statespace(np.eye(3), np.eye(3), omega=27.0, time="minutes")
    with pytest.raises(InflowError, match="permutation"):
        IdentifiedInflow.from_fgc(-np.eye(12), np.eye(12)[:, :6], rotors=("U", "L"),
                                  input_order=["CT_U"] * 6)


def test_input_delays_of_eq_2_15_versus_rowwise_delays_of_eq_2_16():
    P = published.UH60_MU01_MFW                      # coupled lam0/lam1c in forward flight
    tau = np.diag(np.diag(P.tau))                    # Eq. 2.15 form: one delay per input
    w = np.array([0.5, 2.0, 6.0])                    # rad/s
    h = [np.linalg.inv(P.M * 1j * wk + P.Lbar) for wk in w]          # M is M/Omega [s] here
    want_input = np.array([hk * np.exp(-np.diag(tau) * 1j * wk)[None, :] for hk, wk in zip(h, w)])
    want_row = np.array([hk * np.exp(-tau * 1j * wk) for hk, wk in zip(h, w)])
    for mode, want in (("input", want_input), ("rowwise", want_row)):
        sys = mltau_statespace(P.M, P.Lbar, tau, omega=P.omega, time="seconds", pade_order=3, delays=mode)
        got = np.moveaxis(np.asarray(sys(1j * w)), -1, 0)
        # 3rd-order Padé, omega tau <= 0.3: error ~ (omega tau)^7 / 1e4, far below 1e-4 of the peak
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-4 * np.max(np.abs(want)))
    # the two readings differ for a coupled H (the off-diagonal lam1c <- C_T picks up tau11 or not)
    assert np.max(np.abs(want_input - want_row)) > 1e-2 * np.max(np.abs(want_row))
    with pytest.raises(InflowError, match="diagonal tau"):
        mltau_statespace(P.M, P.Lbar, P.tau, omega=P.omega, time="seconds", delays="input")
    with pytest.raises(InflowError, match="rowwise"):
        mltau_statespace(P.M, P.Lbar, P.tau, omega=P.omega, time="seconds", delays="columns")


def test_without_inputs_disconnects_exactly_those_paths():
    # the printed 12-state (Eqs. 6.8-6.9, flap-rate inputs, delays by Padé): a
    # disconnected input's responses vanish, every other response is python-control's
    # own evaluation of the untouched model, and poles and trim references stay
    from aircraft.inflow.paths import without_inputs
    model = IdentifiedInflow.from_published(published.COAXIAL_HOVER_12STATE)
    cut = without_inputs(model, model.rate_names)
    w = np.array([0.0, 0.5, 3.0, 20.0])
    full = np.asarray(model.system(1j * w))
    part = np.asarray(cut.system(1j * w))
    inputs = list(model.system.input_labels)
    for j, name in enumerate(inputs):
        if name in model.rate_names:
            assert np.all(part[:, j, :] == 0.0)
        else:
            np.testing.assert_allclose(part[:, j, :], full[:, j, :], rtol=1e-12, atol=0)
    np.testing.assert_array_equal(np.asarray(cut.system.A), np.asarray(model.system.A))
    np.testing.assert_array_equal(cut.loads_ref, model.loads_ref)
    assert cut.uses_flap_rates and "without beta1s_dot_U" in cut.name
    only_rates = without_inputs(model, model.load_names)
    assert np.all(np.asarray(only_rates.system(1j * w))[:, :len(model.load_names), :] == 0.0)
    with pytest.raises(InflowError, match="among the model's inputs"):
        without_inputs(model, ["CT_X"])
    with pytest.raises(InflowError, match="among the model's inputs"):
        without_inputs(model, [])
    with pytest.raises(TypeError, match="must be an IdentifiedInflow"):
        without_inputs(PittPeters(), ["CT"])
