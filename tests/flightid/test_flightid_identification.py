import numpy as np
import pytest
import control

from aircraft.inflow.published import COAXIAL_HOVER_6STATE
from flightid import (IdentificationError, MLTauStructure, FGCStructure, GainDelayStructure, combine_responses, doublet, fit, frequency_response, frequency_sweep, joint_input_output, reduce, verify)
from flightid.errors import SingularInputError
from aircraft.identification.testing import (coaxial_sweep_set, simulate_mltau, printed_6state_structure as coaxial_6state_structure, printed_6state_values as truth_values)

# every test here shares a fixture that takes seconds to build: not in the quick set (make test-quick)
pytestmark = pytest.mark.slow

OMEGA = 27.0


def _single_rotor_truth():
    # first-order, inflow-like: Pitt-Peters-sized M and Lbar (azimuth time), 30 ms delay
    return dict(M=0.849, L=0.22, tau=0.03)


def test_first_order_model_with_delay_recovered_within_2_percent():
    # (a) one sweep, 3 % measurement noise on the output
    truth = _single_rotor_truth()
    t, c = frequency_sweep(0.5, 40.0, 90.0, 0.005, amplitude=1e-3, seed=11)
    lam = simulate_mltau([[truth["M"]]], [[truth["L"]]], [[truth["tau"]]], OMEGA, t, c[None, :])[0]
    lam = lam + 0.03 * lam.std() * np.random.default_rng(5).standard_normal(lam.size)
    data = frequency_response(t, c, lam, w_min=0.6, w_max=40.0, input_name="CT", output_names=["lam0"])
    structure = MLTauStructure([["M11"]], [["L11"]], [["t11"]], inputs=["CT"], outputs=["lam0"],
                               initial={"M11": 0.5, "L11": 0.5, "t11": 0.0}, omega=OMEGA)
    result = fit(structure, data)
    got = result.structure.values
    # 2 %: the requirement; noise is 3 % of RMS and the record has ~40
    # averages at low frequency, so the estimation error is well below that
    assert got["M11"] == pytest.approx(truth["M"], rel=0.02)
    assert got["L11"] == pytest.approx(truth["L"], rel=0.02)
    assert got["t11"] == pytest.approx(truth["tau"], rel=0.02)
    assert result.J_ave < 10
    assert set(result.parameters.columns) >= {"cramer_rao_pct", "insensitivity_pct"}
    assert result.cramer_rao.max() < 20 and result.insensitivity.max() < 10
    model = result.model
    assert isinstance(model, control.StateSpace)
    assert model.input_labels == ["CT"] and model.output_labels == ["lam0"]
    # DC gain of the state-space model (Padé delay has unit DC gain) = 1 / Lbar
    assert control.dcgain(model) == pytest.approx(1 / got["L11"], rel=1e-6)


def _coaxial_structure(initial):
    return coaxial_6state_structure(initial, COAXIAL_HOVER_6STATE.omega)


def _truth_values():
    return truth_values(COAXIAL_HOVER_6STATE)


@pytest.fixture(scope="module")
def coaxial_responses():
    runs = coaxial_sweep_set(COAXIAL_HOVER_6STATE, seed=0, noise=0.02)
    names_c = COAXIAL_HOVER_6STATE.input_names
    names_l = COAXIAL_HOVER_6STATE.output_names
    controls = ["theta0_U", "theta1s_U", "theta1c_U", "theta0_L", "theta1s_L", "theta1c_L"]
    simo = []
    for run in runs:
        y = np.vstack([run["loads"], run["lam"]]).T
        simo.append(frequency_response(run["t"], run["theta"], y, w_min=0.8, w_max=30.0,
                                       input_name=controls[run["control"]], output_names=names_c + names_l))
    all_resp = combine_responses(simo)
    return all_resp.select(names_l), all_resp.select(names_c), runs


def test_joint_input_output_recovers_6_state_coaxial_model(coaxial_responses):
    # (b) Eq. 5.3 as truth, correlated swashplate->loads mixing: the joint
    # input-output method is required; all 24 parameters within 5 %, J_ave < 10.
    lam_theta, c_theta, _ = coaxial_responses
    lam_c = joint_input_output(lam_theta, c_theta)
    assert lam_c.input_labels == COAXIAL_HOVER_6STATE.input_names
    truth = _truth_values()
    rng = np.random.default_rng(1)
    initial = {k: (v * rng.uniform(0.7, 1.3) if not k.startswith("t") else 0.05) for k, v in truth.items()}
    result = fit(_coaxial_structure(initial), lam_c, frequency_ranges=(1.0, 25.0))
    got = result.structure.values
    assert len(got) == 24
    for name, value in truth.items():
        if value == 0.0:
            # the printed tau41 and tau55 are zero: recovered within 2 ms absolute
            assert abs(got[name]) < 2e-3, name
        else:
            # 5 % as the issue asks; 2 % noise and 6 sweeps make errors ~1 %
            assert got[name] == pytest.approx(value, rel=0.05), name
    assert result.J_ave < 10
    assert len(result.cost_table) == 12   # the 12 structurally non-zero responses


def test_joint_input_output_names_singular_frequencies(coaxial_responses):
    lam_theta, c_theta, _ = coaxial_responses
    bad = c_theta.select(inputs=c_theta.input_labels)
    data = bad.frdata.copy()
    data[:, 1] = data[:, 0]          # two sweeps identical -> u/theta singular everywhere
    from flightid import MeasuredResponse
    singular = MeasuredResponse(data, bad.omega, bad.coherence, bad.input_labels, bad.output_labels)
    with pytest.raises(SingularInputError, match="singular") as err:
        joint_input_output(lam_theta, singular)
    assert len(err.value.frequencies) == bad.omega.size
    with pytest.raises(IdentificationError, match="one independent sweep per input-output"):
        joint_input_output(lam_theta.select(inputs=lam_theta.input_labels[:3]),
                           c_theta.select(inputs=c_theta.input_labels[:3]).select(outputs=c_theta.output_labels))


def test_joint_input_output_overdetermined_pseudo_inverse_is_exact_on_noise_free_data():
    # y = H u with u = K theta (3 controls, 2 input-outputs): pinv recovers H exactly
    from flightid import MeasuredResponse
    w = np.geomspace(1, 10, 5)
    H = np.array([[1.0, 2.0]])[:, :, None] / (1j * w + 3)
    K = np.array([[1.0, 0.5, 0.1], [0.2, 1.0, 0.7]])[:, :, None] * np.ones(w.size)
    Y = np.einsum("ijw,jkw->ikw", H, K)
    ones = lambda a: np.ones(a.shape)
    r = joint_input_output(MeasuredResponse(Y, w, ones(Y), ["a", "b", "c"], ["y"]),
                           MeasuredResponse(K, w, ones(K), ["a", "b", "c"], ["u1", "u2"]))
    np.testing.assert_allclose(r.frdata, H, rtol=1e-10)
    np.testing.assert_allclose(r.coherence, 1.0)


def test_redundant_parameter_is_flagged_and_removed_by_reduce():
    # (d) truth: one first-order mode; structure: two parallel modes, the second
    # (pole p2, gain g2) redundant. g2 must be flagged and reduce must remove it.
    t, u = frequency_sweep(0.5, 30.0, 80.0, 0.01, seed=2)
    import scipy.signal as sig
    _, y, _ = sig.lsim(sig.lti([4.0], [1, 2.0]), u, t)
    y = y + 0.01 * y.std() * np.random.default_rng(0).standard_normal(y.size)
    data = frequency_response(t, u, y, w_min=1.0, w_max=30, input_name="u", output_names=["y"])
    structure = FGCStructure([["-a", 0], [0, "-p2"]], [["g1"], ["g2"]], [[1.0, 1.0]], inputs=["u"],
                             outputs=["y"], initial={"a": 1.0, "p2": 10.0, "g1": 2.0, "g2": 0.3})
    first = fit(structure, data)
    flags = first.parameters.set_index("parameter")
    # the two modes are interchangeable: whichever gain the fit left redundant
    # must be flagged (Cramér-Rao > 20 % or insensitivity > 10 %) and removed
    flagged = {g for g in ("g1", "g2")
               if flags.loc[g, "cramer_rao_pct"] > 20 or flags.loc[g, "insensitivity_pct"] > 10}
    assert flagged
    red = reduce(structure, data)
    removed = set(red.removed) & {"g1", "g2"}
    assert len(removed) == 1 and removed <= flagged
    final = red.result.structure.values
    kept_gain, kept_pole = ("g2", "p2") if "g1" in removed else ("g1", "a")
    # 2 %: 1 % output noise, 80 s record
    assert final[kept_pole] == pytest.approx(2.0, rel=0.02)
    assert final[kept_gain] == pytest.approx(4.0, rel=0.02)
    assert red.result.J_ave <= first.J_ave + 2
    assert {"parameter", "reason", "accepted"} <= set(red.log.columns)


def test_batch_reduction_removes_redundant_modes_together():
    # truth: one first-order mode 4/(s+2); structure: that mode plus three redundant
    # modes of fixed poles whose gains (truth 0) are all insensitive. One at a time,
    # removing g4 first leaves g2 and g3 trading off along a flat direction, so that
    # removal is refused and g4 stays (insensitivity 555 %); removed together in one
    # refit, all three go and the kept mode is the truth.
    t, u = frequency_sweep(0.5, 30.0, 80.0, 0.01, seed=2)
    import scipy.signal as sig
    _, y, _ = sig.lsim(sig.lti([4.0], [1, 2.0]), u, t)
    y = y + 0.01 * y.std() * np.random.default_rng(0).standard_normal(y.size)
    data = frequency_response(t, u, y, w_min=1.0, w_max=30, input_name="u", output_names=["y"])
    F = [["-a", 0, 0, 0], [0, -5.0, 0, 0], [0, 0, -10.0, 0], [0, 0, 0, -20.0]]
    structure = FGCStructure(F, [["g1"], ["g2"], ["g3"], ["g4"]], [[1.0, 1.0, 1.0, 1.0]], inputs=["u"],
                             outputs=["y"], initial={"a": 1.0, "g1": 2.0, "g2": 0.3, "g3": 0.3, "g4": 0.3})
    single = reduce(structure, data, protected=["a", "g1"])
    batched = reduce(structure, data, protected=["a", "g1"], batch=3)
    assert set(single.removed) == {"g2", "g3"}
    assert set(batched.removed) == {"g2", "g3", "g4"}
    assert batched.log.note.str.startswith("removed with 2 others").all() and len(batched.log) == 3
    free = batched.result.parameters[batched.result.parameters.status == "free"]
    assert (free.cramer_rao_pct < 20).all() and (free.insensitivity_pct < 10).all()
    # 2 %: 1 % output noise, 80 s record (as above)
    assert batched.result.structure.values["a"] == pytest.approx(2.0, rel=0.02)
    assert batched.result.structure.values["g1"] == pytest.approx(4.0, rel=0.02)
    # a batch that fails a check is logged as refused and its worst member tried alone
    # in the same step (here every removal raises J_ave by more than the 1e-6 allowed)
    strict = reduce(structure, data, protected=["a", "g1"], batch=3, max_rise_average=1e-6, max_steps=2)
    assert strict.log.reason.tolist() == ["batch", "insensitivity"]
    assert strict.log.parameter.iloc[0] == "g4, g2, g3" and strict.log.parameter.iloc[1] == "g4"
    assert "one at a time" in strict.log.note.iloc[0] and not strict.log.accepted.any()
    assert strict.removed == []
    with pytest.raises(IdentificationError, match="batch must be an integer"):
        reduce(structure, data, batch=0)


def test_verify_gives_small_tic_on_the_truth_model():
    # (e) truth model converted with Padé delays vs exact-delay scipy simulation of a doublet
    P = COAXIAL_HOVER_6STATE
    structure = _coaxial_structure(_truth_values())
    t, d = doublet(1e-3, 0.5, 0.005, 6.0, start=0.5)
    # every load gets a doublet (different sizes, some delayed) so every inflow output moves
    loads = np.array([a * np.interp(t - lag, t, d, left=0.0)
                      for a, lag in [(1, 0), (0.8, 0.3), (-0.6, 0.6), (-0.5, 0.1), (0.7, 0.9), (0.4, 1.2)]])
    lam = simulate_mltau(P.M, P.Lbar, P.tau, P.omega, t, loads)
    result = verify(structure, t, loads, lam)
    assert result.metrics.TIC.max() < 0.1
    assert list(result.metrics.output) == P.output_names
    # a wrong model is caught: doubling Lbar halves the steady gains
    wrong = structure.with_values({"l11": 2 * P.Lbar[0, 0], "l44": 2 * P.Lbar[3, 3]})
    assert verify(wrong, t, loads, lam).metrics.TIC.iloc[0] > 0.1


def test_structures_validate_inputs():
    with pytest.raises(IdentificationError, match="no initial value"):
        MLTauStructure([["M11"]], [["L11"]], inputs=["CT"], outputs=["lam0"], initial={"M11": 1.0})
    with pytest.raises(IdentificationError, match="not a valid parameter name"):
        MLTauStructure([["M 11"]], [["L11"]], inputs=["CT"], outputs=["lam0"], initial={"L11": 1.0})
    with pytest.raises(IdentificationError, match="delay t must be >= 0"):
        GainDelayStructure([["K"]], [["t"]], inputs=["a"], outputs=["b"], initial={"K": 1, "t": -1})


def test_gain_delay_structure_statespace_matches_exact_response_at_low_frequency():
    s = GainDelayStructure([["K0", "K1"]], [["t0", "t1"]], inputs=["lam0", "lam1c"], outputs=["vz"],
                           initial={"K0": 1.5, "K1": -0.4, "t0": 0.2, "t1": 0.05})
    w = np.array([0.5, 1.0, 2.0])
    exact = s.frequency_response(w)
    approx = control.frequency_response(s.to_statespace(pade_order=2), w).complex
    # second-order Padé of a 0.2 s delay: phase error < 0.1 deg below 2 rad/s
    np.testing.assert_allclose(np.squeeze(approx), exact[0], rtol=2e-3)
