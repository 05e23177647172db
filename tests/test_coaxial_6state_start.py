"""A known defect, pinned: the 6-state fit from the pipeline's data-driven start does
not recover a model from its own exact frequency response.

The data are computed here with numpy, ``(M s/Omega + Lbar)^-1 exp(-s tau)``,
elementwise delays, from a physically sized hover model in our frames (the values
of ``tests/test_coaxial_12state_structure.py``). From the truth itself the fit stays
at J_ave ~1e-4, so the data and the cost agree; from
:meth:`Coaxial6State.initial_values` (Lbar within 5 % of the truth, M from Pitt-Peters,
cross M zero) it stops at J_ave ~690 with the collective cross masses of the wrong
sign, and eight scattered starts do not help (J_ave 643). The pipeline uses this
start on our wake, so its optimum there (J_ave 107.8) may be a local one too. The
test is a strict xfail: it fails the suite the day the start is fixed, so that this
note goes with it.
"""
import numpy as np
import pytest

from aircraft.identification import Coaxial6State
from flightid import MeasuredResponse, fit

OMEGA = 23.7          # rotor speed [rad/s]
W = np.geomspace(0.7, 30.0, 40)
TRUTH = {"m11": 0.85, "m14": -0.4, "m41": 0.6, "m44": 1.05, "m22": -0.25, "m25": -0.07, "m52": -0.33,
         "m55": -0.27, "l11": 0.44, "l14": -0.18, "l41": -0.73, "l44": 0.67, "l22": -0.045, "l25": 0.011,
         "l52": -0.036, "l55": -0.061, "t11": 0.03, "t14": 0.10, "t41": 0.02, "t44": 0.026, "t22": 0.023,
         "t25": 0.13, "t52": 0.08, "t55": 0.01}


def _exact_data():
    st = Coaxial6State()
    mats = st.build(TRUTH, OMEGA).matrices()
    s = 1j * W / OMEGA
    h = np.moveaxis(np.linalg.inv(mats["M"][None] * s[:, None, None] + mats["L"][None]), 0, -1)
    h = h * np.exp(-1j * W[None, None, :] * mats["tau"][:, :, None])
    return st, MeasuredResponse(h, W, np.ones(h.shape), st.inputs, st.outputs)


def test_exact_data_are_fitted_exactly_from_the_truth():
    st, data = _exact_data()
    r = fit(st.build(TRUTH, OMEGA), data, frequency_ranges=(1.0, 25.0), n_omega=20)
    assert r.J_ave < 0.01          # the numpy data and the structure agree


@pytest.mark.xfail(strict=True, reason="the data-driven start ends in a local optimum (J_ave ~690) "
                                       "on exact data; see the module docstring")
def test_data_driven_start_recovers_exact_data():
    st, data = _exact_data()
    r = fit(st.build(st.initial_values(data), OMEGA), data, frequency_ranges=(1.0, 25.0), n_omega=20)
    assert r.J_ave < 1.0
    for name, value in TRUTH.items():
        assert r.structure.values[name] == pytest.approx(value, rel=0.02, abs=2e-4), name
