"""flightid.feedthrough and the coaxial 6-state diagnostics built on it.

Oracles: python-control's response of ``ss(A, B, C, D)`` assembled here from
the matrices by hand; a synthetic model with known feedthrough; hover's
axisymmetry for the coaxial ties.
"""
import control
import numpy as np
import pytest

from flightid import IdentificationError, MeasuredResponse, fit
from flightid.feedthrough import MLTauFeedthroughStructure

OMEGA = 25.0
TRUTH = {"m1": 0.9, "m2": 1.3, "l1": 0.8, "l2": 1.1, "l12": -0.3, "d1": 0.4, "d2": -0.25}


def _structure(values=None, tau=None):
    values = dict(values or TRUTH)
    if tau is not None:
        values["t1"] = tau
    return MLTauFeedthroughStructure([["m1", 0], [0, "m2"]], [["l1", "l12"], [0, "l2"]],
                                     None if tau is None else [["t1", 0], [0, "t1"]],
                                     [["d1", 0], [0, "d2"]], inputs=["u1", "u2"], outputs=["y1", "y2"],
                                     initial=values, omega=OMEGA)


def test_response_matches_a_state_space_assembled_by_hand():
    m = np.diag([TRUTH["m1"], TRUTH["m2"]])
    lb = np.array([[TRUTH["l1"], TRUTH["l12"]], [0.0, TRUTH["l2"]]])
    d = np.diag([TRUTH["d1"], TRUTH["d2"]])
    # azimuth time: x' = dx/dpsi, so dx/dt = Omega x'
    ref_sys = control.ss(-OMEGA * np.linalg.solve(m, lb), OMEGA * np.linalg.inv(m), np.eye(2), d)
    w = np.geomspace(0.3, 100.0, 25)
    st = _structure()
    np.testing.assert_allclose(st.frequency_response(w), control.frequency_response(ref_sys, w).complex,
                               rtol=1e-12, atol=1e-14)
    # the high-frequency limit is D
    np.testing.assert_allclose(st.frequency_response([1e7])[:, :, 0], d, atol=1e-4)
    np.testing.assert_allclose(control.frequency_response(st.to_statespace(), w).complex,
                               st.frequency_response(w), rtol=1e-9, atol=1e-12)


def test_delay_acts_on_the_direct_part_too():
    st = _structure(tau=0.02)
    w = np.array([1e6])
    # far above the dynamics the element is D e^{-s tau}
    np.testing.assert_allclose(st.frequency_response(w)[0, 0, 0], TRUTH["d1"] * np.exp(-1j * w[0] * 0.02),
                               rtol=1e-4)


def test_fit_recovers_a_known_feedthrough():
    w = np.geomspace(0.7, 30.0, 50)
    h = _structure().frequency_response(w)
    rng = np.random.default_rng(2)
    h = h * (1 + 0.01 * (rng.standard_normal(h.shape) + 1j * rng.standard_normal(h.shape)) / np.sqrt(2))
    data = MeasuredResponse(h, w, np.full(h.shape, 0.999), ["u1", "u2"], ["y1", "y2"])
    start = {k: v * 1.25 for k, v in TRUTH.items()}
    res = fit(_structure(start), data, frequency_ranges=(1, 25))
    for k, v in TRUTH.items():
        # 1 % element noise: the parameters to a few per cent
        assert res.structure.values[k] == pytest.approx(v, rel=0.05), k


def test_bad_patterns_are_refused():
    with pytest.raises(IdentificationError, match="needs a D pattern"):
        MLTauFeedthroughStructure([["m"]], [["l"]], None, None, inputs=["u"], outputs=["y"],
                                  initial={"m": 1, "l": 1})
    with pytest.raises(IdentificationError, match="D must be 1 x 1"):
        MLTauFeedthroughStructure([["m"]], [["l"]], None, [["d", 0]], inputs=["u"], outputs=["y"],
                                  initial={"m": 1, "l": 1, "d": 0})
    with pytest.raises(IdentificationError, match="no initial value"):
        MLTauFeedthroughStructure([["m"]], [["l"]], None, [["d"]], inputs=["u"], outputs=["y"],
                                  initial={"m": 1, "l": 1})


# -- the coaxial structures of aircraft.identification.six_state_diagnostics -----------------

def _rotation(psi):
    c, s = np.cos(psi), np.sin(psi)
    return np.array([[c, s], [-s, c]])


@pytest.mark.parametrize("frame, lower_sign", [("rotor", -1.0), ("printed", 1.0)])
def test_feedthrough_ties_are_invariant_under_a_turn_of_the_hover_wake(frame, lower_sign):
    from aircraft.identification.six_state_diagnostics import Coaxial6StateFeedthrough
    st = Coaxial6StateFeedthrough(frame)
    rng = np.random.default_rng(3)
    names = [f"{p}{i}{j}" for p in "mltd" for i, j in [(1, 1), (2, 2), (1, 4), (2, 5), (4, 1), (5, 2),
                                                       (4, 4), (5, 5)]]
    values = {n: rng.uniform(0.05, 1.0) * (1.0 if n[0] == "t" else rng.choice([-1.0, 1.0])) for n in names}
    mats = st.build(values, 23.7).matrices()
    t = np.eye(6)
    t[1:3, 1:3] = _rotation(0.8)
    t[4:6, 4:6] = _rotation(lower_sign * 0.8)
    for key in ("M", "L", "D"):
        np.testing.assert_allclose(t @ mats[key] @ np.linalg.inv(t), mats[key], atol=1e-12)


def test_coaxial_sum_difference_signs_follow_the_data():
    from aircraft.identification import Coaxial6State
    from aircraft.identification.six_state_diagnostics import coaxial_sum_difference
    st = Coaxial6State()
    w = np.geomspace(0.7, 30.0, 30)
    # a lateral cross-rotor response of opposite sign to the own one (our mirrored
    # frames), collective and longitudinal of the same sign
    h = np.zeros((6, 6, w.size), dtype=complex)
    for i, j, v in [(0, 0, 4.5), (0, 3, 2.2), (3, 0, 5.0), (3, 3, 3.3), (1, 1, -15.0), (4, 1, 16.0),
                    (1, 4, 7.0), (4, 4, -11.0), (2, 2, -14.0), (5, 2, -15.0), (2, 5, -5.0), (5, 5, -11.0)]:
        h[i, j] = v / (1 + 1j * w / 8.0)
    data = MeasuredResponse(h, w, np.full(h.shape, 0.95), st.inputs, st.outputs)
    t, s_inv, outs, ins, signs = coaxial_sum_difference(data, st)
    assert signs == [1.0, -1.0, 1.0]
    assert outs[:3] == ["lam0_sum", "lam1s_sum", "lam1c_sum"]
    np.testing.assert_allclose(t @ t.T, np.eye(6), atol=1e-15)


def test_six_state_diagnostics_pinned_mass_row_recovers_eq_5_3_on_its_own_data():
    """Exact data from the printed Eq. 5.3 (in our frames): with the apparent-mass
    diagonal held at its true value and every other parameter started 10 % off, the
    fourth row must land on the truth (J ~ 0, Lbar within 0.1 %). The pinned
    parameters must be reported as not free."""
    import json
    from pathlib import Path
    from aircraft.identification import Coaxial6State
    from aircraft.identification.six_state_diagnostics import six_state_diagnostics
    rec = json.loads((Path(__file__).resolve().parents[2] / "aircraft/data/models/published_eq5_3.json")
                     .read_text())
    mats = {k: np.array(v) for k, v in rec["matrices"].items()}
    idx = {"11": (0, 0), "14": (0, 3), "22": (1, 1), "25": (1, 4), "41": (3, 0), "44": (3, 3),
           "52": (4, 1), "55": (4, 4)}
    truth = {f"{p}{k}": float(mats[key][i, j]) for p, key in (("m", "M"), ("l", "L"), ("t", "tau"))
             for k, (i, j) in idx.items()}
    omega = float(rec["omega_rad_s"])
    st = Coaxial6State()
    w = np.geomspace(0.7, 30.0, 60)
    h = st.build(truth, omega).frequency_response(w)
    data = MeasuredResponse(h, w, np.ones(h.shape), st.inputs, st.outputs)
    start = {k: v if k in st.protected else v * 1.1 + (0.005 if k[0] == "t" else 0.0) for k, v in truth.items()}
    summary, pairs = six_state_diagnostics(data, omega, start=start, feedthrough_max_nfev=20)
    row = summary.iloc[3]
    assert row.fit.startswith("Eq. 5.3, M diagonal fixed")
    assert row.J_ave_rotor_pairs < 1e-3
    assert row.free_parameters == 24 - len(st.protected)
    for k in ("l11", "l14", "l41", "l44", "l22"):
        assert row[k] == pytest.approx(truth[k], rel=1e-3)
    assert set(pairs.fit) == set(summary.fit)
