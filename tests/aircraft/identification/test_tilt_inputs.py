"""Tip-path-plane tilt inputs: the 16-state fit structure, TiltInflow, and the aircraft that flies it."""
import numpy as np
import pytest
from scipy import signal

from aircraft.configs import coaxial_compound
from aircraft.helicopter import Helicopter, HelicopterSettings
from aircraft.helicopter.tilt_coupling import TiltCoupledHelicopter, helicopter_for
from aircraft.inflow.model_files import ModelFileError
from aircraft.identification.structures.tilt import (ON_AXIS_TILT_GAINS, TILT_GAIN_NAMES, Coaxial12StateTilt, tilt_inflow_from_record)
from aircraft.inflow.pitt_peters import InflowError
from aircraft.inflow.tilt import TiltInflow

OMEGA = coaxial_compound().rotors[0].omega


def _values(structure, seed=0):
    """Stable random parameter values: near/far diagonals -0.4 per rad, small couplings."""
    rng = np.random.default_rng(seed)
    vals = {}
    for n in structure.parameter_names():
        if n.startswith("f"):
            i, j = n[1:].split("_")
            vals[n] = -0.4 if i == j else 0.02 * rng.standard_normal()
        elif n.startswith("t"):
            vals[n] = 0.01 * rng.random()
        else:
            vals[n] = 0.1 * rng.standard_normal()
    return vals


@pytest.fixture(scope="module")
def model():
    st = Coaxial12StateTilt(tilt=TILT_GAIN_NAMES)
    vals = _values(st)
    return st, vals, st.build(vals, OMEGA), st.to_inflow(vals, OMEGA)


def test_flown_model_reproduces_the_fitted_tilt_structure(model):
    # the fit sees lambda / beta_dot through the integrators; the aircraft's model has
    # the tilt as an input: C (sI - A)^-1 (B + B_T E / s) composed here by hand must
    # equal the structure's own response (Padé-2 of <= 0.01 s delays: < 1e-6)
    st, _, fgc, inflow = model
    w = np.array([0.3, 1.0, 5.0, 20.0])
    h = np.asarray(fgc.frequency_response(w))
    A, B, C = (np.asarray(m) for m in (inflow.system.A, inflow.system.B, inflow.system.C))
    ins = list(inflow.system.input_labels)
    E = np.zeros((4, len(ins)))
    for m, name in enumerate(inflow.tilt_names):
        b, r = name.split("_")
        E[m, ins.index(f"{b}_dot_{r}")] = 1.0
    for k, wk in enumerate(w):
        s = 1j * wk
        hk = C @ np.linalg.solve(s * np.eye(A.shape[0]) - A, B + inflow.tilt_matrix @ E / s)
        assert np.abs(hk - h[..., k]).max() < 1e-6 * np.abs(h[..., k]).max()


def test_tilt_gain_is_the_held_tilt_answer_of_an_independent_simulation(model):
    # scipy simulates the 16-state structure through a flap-rate ramp and hold: the
    # integrators make the tilt, and the late inflow change is tilt_gain @ beta
    st, _, fgc, inflow = model
    sys = fgc.to_statespace(pade_order=2)
    ins, outs = list(sys.input_labels), list(sys.output_labels)
    t = np.linspace(0.0, 30.0, 6001)
    rate = np.where(t < 2.0, 0.05, 0.0)              # 0.1 rad of beta1s_U, then held
    u = np.zeros((t.size, len(ins)))
    u[:, ins.index("beta1s_dot_U")] = rate
    lin = signal.StateSpace(np.asarray(sys.A), np.asarray(sys.B), np.asarray(sys.C), np.asarray(sys.D))
    _, y, _ = signal.lsim(lin, u, t)
    # lsim interpolates the input linearly between samples, so the tilt it makes is
    # the trapezoidal integral of the rate (0.1 rad less half a step's ramp)
    tilt = np.trapezoid(rate, t)
    want = inflow.tilt_gain()["beta1s_U"].to_numpy() * tilt
    got = y[-1]
    np.testing.assert_allclose(got[[outs.index(o) for o in inflow.tilt_gain().index]], want,
                               atol=1e-6 * np.abs(want).max())


def test_tilt_gains_follow_hover_symmetry_in_rotor_frames(model):
    g = model[3].tilt_gain()
    # same rotor: equal on-axis, opposite cross-axis; cross-rotor (mirrored frames):
    # opposite on-axis, equal cross-axis (as the flap-rate ties of Eq. 6.3)
    assert g.loc["lam1s_U", "beta1s_U"] == pytest.approx(g.loc["lam1c_U", "beta1c_U"])
    assert g.loc["lam1c_U", "beta1s_U"] == pytest.approx(-g.loc["lam1s_U", "beta1c_U"])
    assert g.loc["lam1s_U", "beta1s_L"] == pytest.approx(-g.loc["lam1c_U", "beta1c_L"])
    assert g.loc["lam1c_U", "beta1s_L"] == pytest.approx(g.loc["lam1s_U", "beta1c_L"])
    assert np.all(g.loc[["lam0_U", "lam0_L"]].to_numpy() == 0.0)       # axisymmetry: no collective answer


def test_integrators_are_not_inflow_poles_and_enter_with_the_flap_rate_stage(model):
    st, vals, fgc, inflow = model
    assert fgc.poles().size == 12 and fgc.is_stable()
    np.testing.assert_allclose(np.sort_complex(fgc.poles()),
                               np.sort_complex(np.linalg.eigvals(OMEGA * fgc.matrices()["F"][:12, :12])))
    stage = next(s for s in Coaxial12StateTilt().staged_plan() if "tilt" in s.name)
    assert set(ON_AXIS_TILT_GAINS) <= set(stage.free)
    assert any("beta" in inp for _, inp in stage.add_pairs)


def test_linear_model_carries_the_tilt_inputs(model):
    # a linearisation that dropped the tilts would be a silently wrong model
    import control
    inflow = model[3]
    sys = inflow.linear(inflow.loads_ref, None)
    assert list(sys.input_labels)[-4:] == inflow.tilt_names
    dc = np.real(control.dcgain(sys))[:, -4:]
    np.testing.assert_allclose(dc, inflow.tilt_gain().to_numpy(), rtol=1e-9, atol=1e-12)
    np.testing.assert_array_equal(sys.trim_inputs[-4:], inflow.tilt_ref)


def test_tilt_structure_rejects_bad_names():
    with pytest.raises(ValueError, match="not tilt gains"):
        Coaxial12StateTilt(tilt=["kon_UX"])
    with pytest.raises(ValueError, match="tilt is empty"):
        Coaxial12StateTilt(tilt=[])


def test_tilt_inflow_validation(model):
    inflow = model[3]
    with pytest.raises(InflowError, match="columns"):
        TiltInflow(inflow.system, np.zeros((12, 3)))
    with pytest.raises(InflowError, match="non-finite"):
        TiltInflow(inflow.system, np.full((12, 4), np.nan))
    with pytest.raises(InflowError, match="TiltCoupledHelicopter"):
        inflow.derivatives(np.zeros(inflow.system.nstates), inflow.loads_ref, None, np.zeros(4))


@pytest.fixture(scope="module")
def shipped():
    return tilt_inflow_from_record("coaxial_hover_12state_tilt")


def test_tilt_coupled_helicopter_feeds_the_flapping_states(shipped):
    # the only difference from the same model without tilts, flown by the plain
    # helicopter, is tilt_matrix @ (beta1s_U, beta1c_U, beta1s_L, beta1c_L)
    cfg, st = coaxial_compound(), HelicopterSettings(n_span=4, n_average=1)
    heli = TiltCoupledHelicopter(cfg, shipped, st)
    plain = Helicopter(cfg, shipped.without_tilts(), st)
    x = np.zeros(heli.n_states)
    x[0] = 1.0
    tilts = {"beta1s_U": 0.02, "beta1c_U": -0.03, "beta1s_L": 0.01, "beta1c_L": 0.04}
    for name, v in tilts.items():
        x[heli.state_names.index(name)] = v
    u = np.array([0.2, 0.0, 0.0, 0.2, 0.0, 0.0, 0.0])
    d = heli.derivatives(x, u) - plain.derivatives(x, u)
    np.testing.assert_allclose(d[:heli.n_rigid], 0.0, atol=1e-12)
    np.testing.assert_allclose(d[heli.n_rigid:], shipped.tilt_matrix @ np.array(list(tilts.values())), rtol=1e-12)
    assert isinstance(helicopter_for(cfg, shipped, st), TiltCoupledHelicopter)
    assert type(helicopter_for(cfg, shipped.without_tilts(), st)) is Helicopter


def test_plain_helicopter_refuses_a_tilt_model_instead_of_dropping_the_tilts(shipped):
    heli = Helicopter(coaxial_compound(), shipped, HelicopterSettings(n_span=4, n_average=1))
    with pytest.raises(InflowError, match="tilts"):
        heli.derivatives(np.zeros(heli.n_states), np.zeros(7))
    with pytest.raises(TypeError, match="no tip-path-plane tilts"):
        TiltCoupledHelicopter(coaxial_compound(), shipped.without_tilts())


def test_record_loader_checks_the_structure():
    with pytest.raises(ModelFileError, match="not a coaxial_12state_tilt"):
        tilt_inflow_from_record("coaxial_hover_12state")


def test_shipped_tilt_model_answers_a_held_upper_tilt_as_the_wake_does(shipped):
    # our wake's held records: upper-rotor on-axis answer to its own held tilt
    # -0.104 (beta1s) / -0.092 (beta1c) per rad, from the lower rotor's induced
    # velocity gradient (results/twelve_state_variants/steady_gains.csv); the fit saw
    # only 1-25 rad/s sweeps, so 30 % is the check that the tilt path is the wake's
    g = shipped.tilt_gain()
    assert -0.135 < g.loc["lam1s_U", "beta1s_U"] < -0.065


@pytest.mark.slow
def test_rate_and_tilt_gains_are_recovered_from_lambda_over_beta_dot_sweeps():
    # Synthetic truth: the shipped tilt model's values, simulated by scipy (a
    # hand-built 16-state system: xi' = beta_dot exactly, not flightid's code),
    # four one-at-a-time flap-rate sweeps, 1 % noise. The fit frees only the
    # near-wake flap-rate gains and the tilt gains, which both act on lambda /
    # beta_dot; that they come back within 5 % is the claim that rate and tilt
    # separate by phase (tilt = beta_dot / j omega) on a 1-25 rad/s band.
    from aircraft.inflow.model_files import load_record
    from flightid import combine_responses, fit, frequency_response, frequency_sweep
    rec = load_record("coaxial_hover_12state_tilt")
    st = Coaxial12StateTilt()
    truth = dict(zip(rec.parameters.parameter, rec.parameters.value.astype(float)))
    truth = {k: v for k, v in truth.items() if k in st.parameter_names()}
    free = [k for k in truth if (k.startswith("kon") or k in ("g3_3", "g3_8", "g9_8")) and truth[k] != 0.0]
    assert len(free) >= 5
    F, G, C = (np.asarray(rec.matrices[k], float) for k in ("F", "G", "C"))     # [1/s]
    # every input is swept (the structure needs them all in the data); the load
    # sweeps run without their delays, which is harmless: no load pair is fitted
    truth_sys = signal.StateSpace(F, G, C, np.zeros((C.shape[0], G.shape[1])))
    rng = np.random.default_rng(3)
    simo = []
    for j in range(G.shape[1]):
        t, s = frequency_sweep(0.3, 40.0, 120.0, 0.01, amplitude=0.01, seed=j)
        u = np.zeros((t.size, G.shape[1]))
        u[:, j] = s
        _, y, _ = signal.lsim(truth_sys, u, t)
        y = y + 0.01 * y.std(axis=0) * rng.standard_normal(y.shape)
        simo.append(frequency_response(t, s, y, w_min=1.0, w_max=25.0, points_per_decade=20,
                                       input_name=rec.inputs[j], output_names=list(rec.outputs)))
    data = combine_responses(simo)
    start = {k: (0.5 * v if k in free else v) for k, v in truth.items()}
    model = st.build(start, OMEGA, fixed=[k for k in truth if k not in free])
    pairs = [(f"lam1{a}_{r}", f"beta1{a}_dot_{q}") for a in "sc" for r in "UL" for q in "UL"]
    res = fit(model, data, pairs=pairs, frequency_ranges=(1.0, 25.0), n_omega=15)
    got = res.structure.values
    err = {k: abs(got[k] - truth[k]) / abs(truth[k]) for k in free}
    # 5 %: the synthetic-truth bound; started 50 % low. Measured: max 1.4 %
    # (kon_UU). The same fit with the tilt gains held at zero returns the rate gains
    # 16-680 % off (scratch run): the tilt is not something the rate gains can absorb
    assert max(err.values()) < 0.05, err
