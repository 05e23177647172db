"""Synthetic-truth test of the staged 12-state F/G/C fit (Eqs. 6.2-6.3, 6.8-6.9, §6.4.3).

Truth: the dissertation's hover 12-state near/far-wake model with flap-rate
inputs (Eqs. 6.8-6.9, reference data in :mod:`aircraft.inflow.published`),
simulated with scipy.signal.lsim -- not with flightid's model evaluation.
Ten one-at-a-time "control" sweeps drive the ten input-outputs (six loads,
four flap rates) through a random, fully populated mixing matrix and a 20 rad/s
lag, so every control moves every load and flap rate: lambda/C and
lambda/beta_dot are only available through the block joint input-output
method (Eq. 4.11). 1 % seeded measurement noise on every signal.
The staged plan follows §6.4.3 steps 1-3, 5 and 6 and must recover every one
of the 30 free parameters within 5 %.
"""
import numpy as np
import pandas as pd
import pytest
import scipy.signal as sig

from aircraft.inflow.published import COAXIAL_HOVER_12STATE
from flightid import (FGCStructure, combine_responses, fit_staged, frequency_response, frequency_sweep, joint_input_output)
from flightid.staging import Stage

# every test here shares a fixture that takes seconds to build: not in the quick set (make test-quick)
pytestmark = pytest.mark.slow

TRUTH = COAXIAL_HOVER_12STATE
INPUTS = list(TRUTH.input_order)            # G's columns as printed (Eq. 6.2 order)
OUTPUTS = list(TRUTH.output_names)
CONTROLS = [f"theta{k}" for k in range(len(INPUTS))]
#: lateral -> longitudinal maps (1-based, as the dissertation's F{i, j}): states, inputs
_STATE_1S_TO_1C = {3: 5, 4: 6, 9: 11, 10: 12}
_INPUT_1S_TO_1C = {2: 4, 3: 5, 7: 9, 8: 10}


def sweep_responses(F=None, G=None, *, seed=0, noise=0.01, duration=150.0, dt=0.015, w_min=1.0, w_max=30.0):
    """lambda/(C, beta_dot) from ten control sweeps through a random mixing.

    Returns (lambda/u MeasuredResponse, lambda/theta, u/theta).
    """
    F = TRUTH.F if F is None else np.asarray(F, float)
    G = TRUTH.G if G is None else np.asarray(G, float)
    n_u = G.shape[1]
    rng = np.random.default_rng(seed)
    mixing = np.eye(n_u) + 0.4 * rng.uniform(-1, 1, (n_u, n_u))
    # loads ~1e-3, flap rates ~1e-2 rad/s: the sizes do not matter to the joint
    # input-output method, but keep every signal well above the noise
    scale = np.array([1e-2 if "dot" in name else 1e-3 for name in INPUTS])
    lag = sig.StateSpace(-20.0 * np.eye(n_u), 20.0 * np.diag(scale) @ mixing, np.eye(n_u), np.zeros((n_u, n_u)))
    inflow = sig.StateSpace(F, G, TRUTH.C, np.zeros((TRUTH.C.shape[0], n_u)))
    simo = []
    for k in range(n_u):
        t, s = frequency_sweep(0.2, 40.0, duration, dt, amplitude=1.0, seed=seed + k)
        theta = np.zeros((t.size, n_u))
        theta[:, k] = s
        _, u, _ = sig.lsim(lag, theta, t)
        _, lam, _ = sig.lsim(inflow, u, t)
        y = np.hstack([u, lam])
        y = y + noise * y.std(axis=0) * rng.standard_normal(y.shape)
        simo.append(frequency_response(t, s, y, w_min=w_min, w_max=w_max, points_per_decade=20,
                                       input_name=CONTROLS[k], output_names=INPUTS + OUTPUTS))
    both = combine_responses(simo)
    lam_theta, u_theta = both.select(OUTPUTS), both.select(INPUTS)
    return joint_input_output(lam_theta, u_theta), lam_theta, u_theta


def parameter_names(F=None, G=None):
    """Pattern matrices with one name per non-zero truth element; the 1c axis is
    tied (with the printed sign) to the 1s axis wherever the printed magnitudes
    agree (hover axisymmetry). Returns (F pattern, G pattern, truth values)."""
    F = TRUTH.F if F is None else np.asarray(F, float)
    G = TRUTH.G if G is None else np.asarray(G, float)
    lon_to_lat_state = {v: k for k, v in _STATE_1S_TO_1C.items()}
    lon_to_lat_input = {v: k for k, v in _INPUT_1S_TO_1C.items()}
    truth = {}

    def pattern(mat, label, col_map):
        pat = [[0.0] * mat.shape[1] for _ in range(mat.shape[0])]
        for (i, j), v in np.ndenumerate(mat):
            if v == 0:
                continue
            r, c = i + 1, j + 1
            if r in lon_to_lat_state:          # a 1c row: tie to the matching 1s element
                r1, c1 = lon_to_lat_state[r], col_map.get(c, c)
                v1 = mat[r1 - 1, c1 - 1]
                if v1 != 0 and abs(v1) == abs(v):
                    pat[i][j] = ("" if np.sign(v1) == np.sign(v) else "-") + f"{label}{r1}_{c1}"
                    continue
            truth[f"{label}{r}_{c}"] = float(v)
            pat[i][j] = f"{label}{r}_{c}"
        return pat

    return pattern(F, "F", lon_to_lat_state), pattern(G, "G", lon_to_lat_input), truth


def structure(initial, F=None, G=None):
    """The 12-state structure of Eqs. 6.2-6.3 restricted to the truth's non-zero terms."""
    fp, gp, _ = parameter_names(F, G)
    return FGCStructure(fp, gp, TRUTH.C, inputs=INPUTS, outputs=OUTPUTS, initial=initial)


ON_ROTOR = [("lam0_U", "CT_U"), ("lam1s_U", "CL_U"), ("lam1c_U", "CM_U"),
            ("lam0_L", "CT_L"), ("lam1s_L", "CL_L"), ("lam1c_L", "CM_L")]
OFF_ROTOR = [("lam0_U", "CT_L"), ("lam1s_U", "CL_L"), ("lam1c_U", "CM_L"),
             ("lam0_L", "CT_U"), ("lam1s_L", "CL_U"), ("lam1c_L", "CM_U")]
FLAP = [(f"lam1{a}_{r}", f"beta1{a}_dot_{q}") for a in "sc" for r in "UL" for q in "UL"]


def staged_plan():
    """§6.4.3 for hover, restricted to the terms of Eqs. 6.8-6.9 (1c terms tied to 1s)."""
    return [
        # step 1: on-rotor first-order terms on the on-rotor responses
        Stage("1 on-rotor first order", free=["F1_1", "F3_3", "F7_7", "F9_9", "G1_1", "G3_2", "G7_6", "G9_7"],
              pairs=ON_ROTOR),
        # step 2: those fixed; cross-rotor first-order terms with the off-rotor responses
        Stage("2 off-rotor first order", free=["F1_7", "F3_9", "F7_1", "F9_3", "G1_6", "G9_2"],
              add_pairs=OFF_ROTOR),
        # step 3: all first-order terms together
        Stage("3 first order together", free="used"),
        # step 5: the rest fixed; near-wake flap-rate gains with the flap-rate responses
        Stage("5 flap-rate terms", free=["G3_3", "G3_8", "G9_8"], add_pairs=FLAP),
        # step 6: every parameter, far-wake states included
        Stage("6 all", free="all"),
    ]


def first_order_start(lam_u, truth_names):
    """Data-driven start: on-rotor poles at -5 1/s with the gain of the lowest-frequency
    data point; every other term zero, except the idle far-wake states, which are
    given stable dynamics (-3 1/s, and a damped x4/x10 coupling) so that the model
    is stable while their gains are still zero."""
    init = {k: 0.0 for k in truth_names}
    for (f, g), (o, u) in zip([("F1_1", "G1_1"), ("F3_3", "G3_2"), ("F7_7", "G7_6"), ("F9_9", "G9_7")],
                              [ON_ROTOR[0], ON_ROTOR[1], ON_ROTOR[3], ON_ROTOR[4]]):
        init[f] = -5.0
        init[g] = 5.0 * lam_u.element(o, u)[0][0].real
    init.update({"F2_2": -3.0, "F4_4": -3.0, "F8_8": -3.0, "F4_10": 1.0, "F10_4": -1.0})
    return init


@pytest.fixture(scope="module")
def staged_12state():
    lam_u, _, _ = sweep_responses(seed=0, noise=0.01)
    _, _, truth = parameter_names()
    # fit from 1 rad/s: below it the 150 s sweeps' windowed estimates are biased by
    # up to 5-12 % (slow far-wake pole at -0.51 1/s, few cycles per window)
    staged = fit_staged(structure(first_order_start(lam_u, truth)), lam_u, staged_plan(),
                        frequency_ranges=(1.0, 25.0), n_omega=15)
    return staged, truth


def test_structure_reproduces_the_printed_matrices():
    # the named pattern with its 1s/1c ties must rebuild Eqs. 6.8-6.9 exactly
    _, _, truth = parameter_names()
    assert len(truth) == 30
    mats = structure(truth).matrices()
    np.testing.assert_array_equal(mats["F"], TRUTH.F)
    np.testing.assert_array_equal(mats["G"], TRUTH.G)


def test_staged_12state_fit_recovers_every_parameter_within_5_percent(staged_12state):
    staged, truth = staged_12state
    got = staged.result.structure.values
    err = pd.Series({k: (got[k] - v) / v for k, v in truth.items()})
    # 5 %: the requirement. Measured: max 2.9 % (1 % noise, 150 s records);
    # noise-free data give 2.2 % (the windowed-estimate bias), so 5 % is not slack
    # that would hide a wrong structure: a 10 % perturbation of any term fails it
    assert err.abs().max() < 0.05, err.abs().sort_values().tail(5).to_string()
    log = staged.log
    assert list(log.name) == [s.name for s in staged_plan()]
    assert list(log.n_pairs) == [6, 12, 12, 20, 20]
    assert log.n_free.iloc[-1] == 30
    # the final stage is a good fit (noise-limited J_ave; guideline < 50) without a
    # flat direction, and a perturbed truth would not pass the 5 % check
    assert staged.result.J_ave < 10
    assert staged.result.flat_directions.empty
    perturbed = {k: v * (1.1 if k == "F4_10" else 1.0) for k, v in truth.items()}
    assert max(abs(got[k] - v) / abs(v) for k, v in perturbed.items()) > 0.05
    assert staged.result.structure.is_stable()


def test_staged_log_and_result_objects(staged_12state):
    staged, _ = staged_12state
    assert {"stage", "name", "n_free", "free", "n_pairs", "J_ave", "condition_number", "success"} <= set(
        staged.log.columns)
    assert isinstance(staged.to_pandas(), pd.DataFrame)
    assert len(staged.stages) == 5
    # each stage starts from the previous one: stage 2 holds stage 1's values fixed
    s1, s2 = staged.stages[0].structure.values, staged.stages[1].structure.values
    assert s2["F1_1"] == s1["F1_1"] and s2["G3_2"] == s1["G3_2"]
    from matplotlib.figure import Figure
    assert isinstance(staged.plot(), Figure)
