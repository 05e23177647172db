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


# -- the coaxial structures of studies.analysis.six_state_diagnostics -----------------

def _rotation(psi):
    c, s = np.cos(psi), np.sin(psi)
    return np.array([[c, s], [-s, c]])






