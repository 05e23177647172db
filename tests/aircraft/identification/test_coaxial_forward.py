"""The 200 kt coaxial structure (Eqs. 6.4-6.7), its frames, a synthetic-truth fit, bad input.

Independent references: the printed Eqs. 6.12-6.13 evaluated with
scipy.linalg (never flightid's model code), and synthetic truths whose
responses scipy computes.
"""
import numpy as np
import pytest
import scipy.linalg

from aircraft.identification import STRUCTURES, get_structure
from aircraft.identification.structures import CoaxialForward12State
from aircraft.identification.structures.coaxial_forward import F_PATTERN, G_PATTERN
from aircraft.inflow.base import inflow_names, load_names
from aircraft.inflow.published import COAXIAL_200KT_12STATE, COAXIAL_HOVER_12STATE
from flightid import MeasuredResponse, fit

W = np.logspace(0.0, np.log10(25.0), 15)            # rad/s, the fit band of the pipeline
LOADS, LAMS = load_names(("U", "L")), inflow_names(("U", "L"))


def _scipy_response(F, G, C, w):
    """(n_out, n_in, n_w) response C (j w I - F)^-1 G of x' = F x + G u [1/s], by
    scipy.linalg.solve at each frequency (flightid uses a modal form instead)."""
    n = F.shape[0]
    return np.stack([C @ scipy.linalg.solve(1j * wk * np.eye(n) - F, G) for wk in w], axis=-1)


def test_pattern_is_eq_6_6_and_6_7_and_registered():
    # §6.4.4: "Eq. (6.7) shows 180 parameters"; near rows see near states only
    assert len(F_PATTERN) == 108 and len(G_PATTERN) == 72
    assert all(j % 2 == 1 for i, j in F_PATTERN if i % 2 == 1)
    s = CoaxialForward12State()
    assert len(s.parameter_names()) == 180
    assert len(CoaxialForward12State(near_wake_only=True).parameter_names()) == 72
    assert STRUCTURES["coaxial_forward_12state"] is CoaxialForward12State
    assert isinstance(get_structure("coaxial_forward_12state"), CoaxialForward12State)
    assert s.inputs == LOADS and s.outputs == LAMS and s.rates == []
    # every printed F entry lies in the pattern (published_values would raise otherwise)
    printed = set(zip(*[a + 1 for a in np.nonzero(COAXIAL_200KT_12STATE.F)]))
    assert printed <= set(F_PATTERN)


def test_frame_conversion_against_the_printed_model():
    # The printed Eqs. 6.12-6.13 with scipy (per second) against the structure at the
    # printed values: in the printed frame the same responses, in our rotor frames the
    # lower rotor's lateral rows (lam1s_L) and columns (CL_L) negated, nothing else.
    P = COAXIAL_200KT_12STATE
    h_d = _scipy_response(P.F, P.G, P.C, W)
    printed = CoaxialForward12State("printed")
    h_p = printed.build(printed.published_values(P), P.omega).frequency_response(W)
    ours = CoaxialForward12State("rotor")
    h_o = ours.build(ours.published_values(P), P.omega).frequency_response(W)
    # round-off of two eigen-decompositions of a stiff F (poles -1.2 ... -1100 1/s)
    np.testing.assert_allclose(h_p, h_d, rtol=1e-8, atol=1e-12 * np.abs(h_d).max())
    s = np.array([-1.0 if n in ("lam1s_L", "CL_L") else 1.0 for n in LAMS])
    np.testing.assert_allclose(h_o, s[:, None, None] * h_d * s[None, :, None], rtol=1e-8,
                               atol=1e-12 * np.abs(h_d).max())
    # the conversion is not the identity: a cross-rotor lateral response flips
    i, j = LAMS.index("lam1s_L"), LOADS.index("CT_U")
    assert np.abs(h_d[i, j]).max() > 1e-3 * np.abs(h_d).max()
    np.testing.assert_allclose(h_o[i, j], -h_d[i, j], rtol=1e-8)
    # values: a lower-rotor lateral row entry from an upper-rotor column changes sign
    vp, vo = printed.published_values(P), ours.published_values(P)
    assert vo["g9_1"] == 0.0 and vo["g9_2"] == pytest.approx(-vp["g9_2"])   # lam1sN_L <- CL_U
    assert vo["g1_1"] == pytest.approx(vp["g1_1"]) == pytest.approx(17.13 / P.omega)


def _truth_response(truth_values, structure, omega_rotor, w):
    """Response of a truth given as structure values, computed with scipy from its matrices."""
    m = structure.build(truth_values, omega_rotor).matrices()
    F, G = omega_rotor * m["F"], omega_rotor * m["G"]             # per d/dpsi -> per second
    return _scipy_response(F, G, structure._summing_matrix(), w)


@pytest.mark.slow
def test_synthetic_truth_near_wake_fit_recovers_the_parameters():
    # Truth: a fully coupled first-order model (the near-wake half, 72 parameters),
    # stable, responses from scipy with 0.5 % seeded complex noise and coherence 0.98.
    # The fit starts from the structure's own data-driven start.
    rng = np.random.default_rng(12)
    s = CoaxialForward12State(near_wake_only=True)
    omega = 20.3
    names = s.parameter_names()
    truth = {}
    for n in names:
        i, j = (int(k) for k in n[1:].split("_"))
        if n.startswith("f"):
            truth[n] = -rng.uniform(0.2, 0.5) if i == j else 0.05 * rng.uniform(-1, 1)
        else:
            k = (i - 1) // 2
            truth[n] = (0.3 if k == j - 1 else 0.08) * rng.uniform(0.5, 1.0) * rng.choice([-1, 1])
    assert s.build(truth, omega).is_stable()
    w = np.logspace(-0.3, np.log10(30.0), 60)
    h = _truth_response(truth, s, omega, w)
    h = h * (1 + 0.005 * (rng.standard_normal(h.shape) + 1j * rng.standard_normal(h.shape)))
    data = MeasuredResponse(h, w, np.full(h.shape, 0.98), LOADS, LAMS)
    start = s.initial_values(data)
    assert set(start) == set(names)
    res = fit(s.build(start, omega), data, frequency_ranges=(1.0, 25.0))
    assert res.J_ave < 1.0              # 0.5 % noise gives J ~ 0.1 (J ~ 100 is a fair fit)
    got = res.structure.values
    big = [n for n in names if abs(truth[n]) > 0.05]
    # 0.5 % noise on 36 responses x 15 points: parameters within 3 % (measured < 1 %)
    for n in big:
        assert got[n] == pytest.approx(truth[n], rel=0.03), n


def test_full_structure_start_is_stable_with_the_data_steady_response():
    # On the printed model's responses (rotor frames, scipy) the data-driven start
    # of the full structure is stable and has the data's steady response.
    from aircraft.inflow.published import in_rotor_frames
    P = in_rotor_frames(COAXIAL_200KT_12STATE)
    s = CoaxialForward12State()
    w = np.logspace(-0.3, np.log10(30.0), 40)
    h = _scipy_response(P.F, P.G, P.C, w)
    data = MeasuredResponse(h, w, np.ones(h.shape), LOADS, LAMS)
    start = s.build(s.initial_values(data, n_points=1), P.omega)
    assert start.is_stable()
    # the start's DC gain is the data's lowest-frequency real part, within the 0.5 %
    # routed through the far wake (relative to each response's largest entry)
    g_start = np.real(start.frequency_response([1e-6])[:, :, 0])
    g_data = np.real(h[:, :, 0])
    np.testing.assert_allclose(g_start, g_data, atol=0.01 * np.abs(g_data).max())


def test_bad_input():
    with pytest.raises(TypeError, match="near_wake_only"):
        CoaxialForward12State(near_wake_only="yes")
    with pytest.raises(ValueError, match="frame must be"):
        CoaxialForward12State(frame="body")
    s = CoaxialForward12State()
    with pytest.raises(ValueError, match="not the six loads"):
        s.published_values(COAXIAL_HOVER_12STATE)
    with pytest.raises(KeyError, match="no initial value"):
        s.build({"f1_1": -0.3}, 20.3)
    from aircraft.inflow.published import in_rotor_frames
    with pytest.raises(ValueError, match="printed frame"):
        CoaxialForward12State("printed").published_values(in_rotor_frames(COAXIAL_200KT_12STATE))


# -- the 200 kt library functions and the study -------------------------------------------
def test_table_6_3_is_the_printed_table():
    from aircraft.inflow.published import TABLE_6_3
    assert len(TABLE_6_3) == 36 and set(o for o, _ in TABLE_6_3) == set(LAMS)
    # printed "Average Cost 77.0"; the printed entries average 34.7: the printed average
    # is not the mean of its own table (kept as printed, reported beside ours)
    assert np.mean(list(TABLE_6_3.values())) == pytest.approx(34.68, abs=0.01)
    assert TABLE_6_3[("lam0_L", "CL_U")] == 337.4


def test_trim_request_and_condition():
    import math
    from aircraft.identification.coaxial_forward_flight import SPEED_200KT, forward_trim_request
    from aircraft.identification.conditions import flight_condition
    req = forward_trim_request(0.01248)
    assert req["mode"] == "torque_balance" and req["ct"] == (0.00624, 0.00624)
    fc = flight_condition(speed=SPEED_200KT, alpha=math.radians(2.0))
    assert fc.speed == pytest.approx(102.89, abs=0.01) and fc.alpha == pytest.approx(math.radians(2.0))
    # mu = V cos(alpha) / (Omega R) = 0.54 at the cruise rotor speed (§6.2.2)
    from aircraft.configs import coaxial_compound
    rot = coaxial_compound(cruise=True).rotors[0]
    assert SPEED_200KT * math.cos(fc.alpha) / (rot.omega * rot.radius) == pytest.approx(0.54, abs=0.01)
    with pytest.raises(ValueError, match="ct"):
        forward_trim_request(-0.01)
    # a lift offset joins the request only when it is not zero (cached balanced runs stay valid)
    assert "lift_offset" not in forward_trim_request(0.01248, lift_offset=0.0)
    assert forward_trim_request(0.01248, lift_offset=0.1)["lift_offset"] == (0.1, 0.1)
    assert forward_trim_request(0.01248, lift_offset=(0.02, -0.01))["lift_offset"] == (0.02, -0.01)
    with pytest.raises(ValueError, match="one value or two"):
        forward_trim_request(0.01248, lift_offset=(0.1, 0.1, 0.1))
    with pytest.raises(ValueError, match="lift_offset"):
        forward_trim_request(0.01248, lift_offset=0.9)
    with pytest.raises(ValueError, match="speed"):
        flight_condition(speed=-1.0)
    with pytest.raises(ValueError, match="exactly one"):
        flight_condition(coaxial_compound(), 0.1, speed=50.0)


def test_aircraft_lift_offset_follows_the_differential_cyclic():
    # the aircraft's per-rotor LOS = -C_L/C_T from its own trim, recomputed here from the
    # trim loads; more differential lateral cyclic moves both rotors' lift to their
    # advancing sides. Paired as Eq. 7.19 (theta1s, control phase 90 deg) the trim already
    # carries lift offset without it (measured 0.0 rad: 0.319/0.298, 0.06 rad: 0.376/0.357;
    # with the former own-frame theta1c pairing -0.042/-0.069 and 0.096/0.078)
    from aircraft.helicopter import Helicopter, HelicopterSettings, TrimCondition, trim
    from aircraft.identification.coaxial_forward_flight import SPEED_200KT, aircraft_lift_offset
    from aircraft.inflow import IsolatedRotors
    from aircraft.configs import coaxial_compound
    cfg = coaxial_compound(cruise=True)
    low, high = aircraft_lift_offset(cfg, lateral_cyclic_difference=0.0), \
        aircraft_lift_offset(cfg, lateral_cyclic_difference=0.06)
    assert all(lo > 0.25 for lo in low)
    assert all(h > lo + 0.04 for h, lo in zip(high, low))
    tr = trim(Helicopter(cfg, IsolatedRotors(), HelicopterSettings(n_span=8, n_average=4)),
              TrimCondition(speed=SPEED_200KT, lateral_cyclic_difference=0.06))
    for r, los in zip("UL", high):
        assert los == pytest.approx(-tr.loads[f"CL_{r}"] / tr.loads[f"CT_{r}"], abs=5e-4)   # the rounding






@pytest.mark.slow
def test_study_small_end_to_end(tmp_path):
    # The study as a user runs it (subprocess), tiny wake, near-wake half of Eq. 6.5.
    import os
    import subprocess
    import sys
    from pathlib import Path
    import pandas as pd
    root = Path(__file__).resolve().parents[3]
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=str(root),
               ROTORWAKE_CACHE_DIR=str(tmp_path / "cache"))
    done = subprocess.run([sys.executable, "-m", "studies.coaxial_forward_flight", "--small", "--jobs", "1",
                           "--candidate-structures", "--out", str(tmp_path / "out")], cwd=root, env=env,
                          capture_output=True, text=True, timeout=1500)
    assert done.returncode == 0, done.stderr[-3000:]
    out = tmp_path / "out"
    for name in ("cost_table.csv", "parameters.csv", "verification.csv", "trim.csv", "responses.csv",
                 "differences.csv", "verdicts.csv", "poles.csv", "verification.png", "bare_airframe_200kt.png"):
        assert (out / name).stat().st_size > 0, name
    cost = pd.read_csv(out / "cost_table.csv")
    assert len(cost) == 37 and cost.J_table_6_3.notna().all()
    verdicts = pd.read_csv(out / "verdicts.csv")
    assert "Eqs. 6.12-6.13 (dissertation)" in set(verdicts.model)
    assert "J_ave" in done.stdout and "Isolated Rotors" in done.stdout
    # the candidates on the same records, the study's own structure last
    from aircraft.identification.coaxial_forward_candidates import CANDIDATE_COLUMNS
    structures = pd.read_csv(out / "structures.csv")
    assert structures.columns.tolist() == list(CANDIDATE_COLUMNS) + ["largest_trusted"]
    # the library's candidates, then the study's quasi-steady and held-mass ones, the study's structure last
    assert structures.structure.tolist() == [
        "coaxial_forward_isolated", "coaxial_forward_isolated_without_lam0_cm",
        "coaxial_forward_6state", "coaxial_forward_6state_without_lam0_cm",
        "coaxial_forward_quasi_steady", "coaxial_forward_quasi_steady_without_lam0_cm",
        "coaxial_forward_quasi_steady_without_lam0_cm_shared_delays", "coaxial_forward_quasi_steady_interference",
        "coaxial_forward_quasi_steady_interference_without_lam0_cm", "coaxial_forward_isolated_pitt_peters_m",
        "coaxial_forward_isolated_pitt_peters_m_without_lam0_cm", "coaxial_forward_12state_near_wake"]
    assert structures.largest_trusted.sum() <= 1 and "largest structure the trust rule accepts" in done.stdout




@pytest.mark.slow
def test_refits_use_the_analytic_jacobian_and_it_is_exact_on_eq_6_5():
    """The 180-parameter structure fits with the analytic Jacobian (its refits are the
    reduction's hot spot); on the printed 200 kt model it equals central differences of
    the CIFER residual (the default's route, independent of the derivative formulas)."""
    from flightid.fitting import _jacobian, _PairData, _Problem
    s = CoaxialForward12State("printed")
    assert s.fit_options["jacobian"] == "analytic"
    m = COAXIAL_200KT_12STATE
    structure = s.build(s.published_values(m), m.omega)
    h = structure.frequency_response(W)
    rng = np.random.default_rng(1)
    pairs = [_PairData(o, u, i, j, W, h[i, j] * np.exp(0.05 * rng.standard_normal(W.size) * (1 + 1j)),
                       np.full(W.size, 0.9)) for i, o in enumerate(LAMS) for j, u in enumerate(LOADS)
             if np.all(h[i, j] != 0)]
    problem = _Problem(structure, pairs, 0.0, "analytic")
    x = np.array([structure.values[n] for n in structure.free_names])
    analytic = problem.jacobian(x, with_penalty=False)
    numeric = _jacobian(lambda v: problem.residuals(v, with_penalty=False), x)
    assert analytic.shape == (2 * W.size * len(pairs), 180)
    # central differences (step 1e-6 |x|): round-off ~1e-9 of the largest entry; near a
    # deep notch of a response (the dB residual's derivatives reach 5e4 there) their
    # truncation error, h^2 f'''/6, was measured at up to 1.4e-3 of the entry (falling 100x per
    # 10x smaller step onto the analytic value, as h^2 does): 5e-3 relative
    # covers it, while a wrong entry map, sign or factor is an O(1) error
    np.testing.assert_allclose(analytic, numeric, rtol=5e-3, atol=1e-6 * np.abs(numeric).max())
