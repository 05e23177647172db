"""The 12-state coaxial structure as the pipeline uses it: excitations, staged plan,
the 6-state nested in its near wake, and its delays realised for the aircraft.

Independent references: the 6-state M/Lbar/tau structure's own frequency response
(flightid.MLTauStructure) for the nesting, and ``C (sI - F)^-1 G exp(-s tau)``
evaluated with numpy for the Padé realisation.
"""
import numpy as np
import pytest

from aircraft.identification.structures import Coaxial6State, Coaxial12State
from aircraft.inflow import IdentifiedInflow
from aircraft.inflow.pitt_peters import InflowError

OMEGA = 37.0          # rotor speed [rad/s] (any positive value: both structures use it alike)
W = np.array([0.3, 1.0, 3.0, 8.0, 20.0])


def _six_state_values():
    """A physically sized, fully populated 6-state hover model in our frames
    (collective and cyclic 2 x 2 blocks, own and cross delays) [azimuth time, s]."""
    return {"m11": 0.85, "m14": -0.4, "m41": 0.6, "m44": 1.05, "m22": -0.25, "m25": -0.07, "m52": -0.33,
            "m55": -0.27, "l11": 0.44, "l14": -0.18, "l41": -0.73, "l44": 0.67, "l22": -0.045, "l25": 0.011,
            "l52": -0.036, "l55": -0.061, "t11": 0.03, "t14": 0.10, "t41": 0.02, "t44": 0.026, "t22": 0.023,
            "t25": 0.13, "t52": 0.08, "t55": 0.01}


def _nested_12state(six):
    """The 12-state values whose near wake is ``six`` (F_N = -M^-1 Lbar, G_N = M^-1)
    and whose far wake is switched off, computed here from the 6-state matrices."""
    st6, st12 = Coaxial6State(), Coaxial12State(delays=True)
    mats = st6.build(six, OMEGA).matrices()
    minv = np.linalg.inv(mats["M"])
    f_near, g_near = -minv @ mats["Lbar"], minv
    near, load_cols = (1, 3, 5, 7, 9, 11), (1, 2, 4, 6, 7, 9)
    vals = {n: 0.0 for n in st12.parameter_names()}
    for name in vals:
        p, (i, j) = name[0], (int(a) for a in name[1:].split("_")) if "_" in name else (None, None)
        if p == "f" and i in near and j in near:
            vals[name] = f_near[near.index(i), near.index(j)]
        elif p == "f" and i == j:
            vals[name] = -0.3                     # far-wake poles: stable, unobserved (zero gains)
        elif p == "g" and i in near and j in load_cols:
            vals[name] = g_near[near.index(i), load_cols.index(j)]
        elif p == "t":
            vals[name] = six[name]
    return vals


def test_twelve_state_with_far_wake_off_is_the_six_state_model():
    six = _six_state_values()
    h6 = Coaxial6State().build(six, OMEGA).frequency_response(W)
    st12 = Coaxial12State(delays=True)
    h12 = st12.build(_nested_12state(six), OMEGA).frequency_response(W)
    loads = [st12.inputs.index(c) for c in Coaxial6State().inputs]
    # the same model in two parametrisations: round-off only (the 6-state's M^-1 is
    # well conditioned here)
    np.testing.assert_allclose(h12[:, loads, :], h6, rtol=1e-9, atol=1e-12)
    # and the flap-rate columns are exactly zero with the far wake and flap gains off
    assert np.abs(h12[:, [st12.inputs.index(r) for r in st12.rates], :]).max() == 0.0


def test_delays_are_realised_for_the_aircraft_within_pade_accuracy():
    st12 = Coaxial12State(delays=True)
    vals = _nested_12state(_six_state_values())
    vals.update({"g3_3": 0.05, "g9_8": -0.04, "f2_1": 0.2, "g2_6": -0.3})   # far wake and flap rates on
    mats = st12.build(vals, OMEGA).matrices()
    F, G, C, tau = OMEGA * mats["F"], OMEGA * mats["G"], st12.build(vals, OMEGA).C, mats["tau"]
    w_pade = np.array([0.3, 1.0, 3.0])
    exact = np.stack([(C @ np.linalg.solve(1j * w * np.eye(12) - F, G)) * np.exp(-1j * w * tau)
                      for w in w_pade], axis=-1)
    sys = st12.to_inflow(vals, OMEGA, pade_order=2).system
    got = np.stack([sys(1j * w) for w in w_pade], axis=-1)
    # second-order Padé: phase error 2 atan(x/2 / (1 - x^2/12)) - x = 1e-4 rad at x = w tau = 0.39
    # (3 rad/s x 0.13 s), the largest here; a wrong delay or a lost column is off by far more
    np.testing.assert_allclose(got, exact, rtol=3e-4, atol=1e-6 * np.abs(exact).max())
    assert sys.ninputs == 10 and sys.noutputs == 6


def test_fgc_delays_are_checked():
    F, G = -np.eye(12), np.ones((12, 6))
    with pytest.raises(InflowError, match="tau must be"):
        IdentifiedInflow.from_fgc(F, G, tau=-0.1 * np.ones((6, 6)))
    with pytest.raises(InflowError, match="tau must be"):
        IdentifiedInflow.from_fgc(F, G, tau=np.zeros((6, 5)))


def test_excitations_and_staged_plan_name_real_parameters():
    st = Coaxial12State(delays=True)
    assert st.excitations[-4:] == ["beta1s_U", "beta1c_U", "beta1s_L", "beta1c_L"]
    names = set(st.parameter_names())
    plan = st.staged_plan()
    freed = [n for stage in plan if isinstance(stage.free, list) for n in stage.free]
    assert set(freed) <= names and len(freed) == len(set(freed))
    # every parameter is freed by some stage before the last ("all together")
    assert set(freed) == names
    assert plan[-1].free == "all"
    # the delays belong to the first (quasi-steady) stage, and the structure's hash knows them
    assert {"t11", "t41", "t52"} <= set(plan[0].free)
    assert st.spec()["delays"] is True and "delays" not in Coaxial12State().spec()


def test_far_wake_loads_add_the_cyclic_load_columns_of_the_far_wake():
    plain, extra = Coaxial12State(delays=True), Coaxial12State(delays=True, far_wake_loads=True)
    added = set(extra.parameter_names()) - set(plain.parameter_names())
    # lam1sF <- CL_U, CL_L of each rotor (Eq. 6.2 rows 4 and 10, columns 2 and 7); the
    # lam1c rows are tied to them
    assert added == {"g4_2", "g4_7", "g10_2", "g10_7"}
    assert set(plain.parameter_names()) <= set(extra.parameter_names())
    # the far-wake stage frees them; the hash knows the option, the default's stays
    assert added <= set(extra.staged_plan()[2].free)
    assert extra.spec()["far_wake_loads"] is True and "far_wake_loads" not in plain.spec()
    rng = np.random.default_rng(1)
    values = {n: rng.uniform(0.1, 1.0) for n in extra.parameter_names()}
    G = extra.build(values, 23.7).matrices()["G"]
    cols = extra.inputs
    # row 6 (lam1cF_U) takes CM_U with the tied value, CM_L with the cross-rotor sign flip
    assert G[5, cols.index("CM_U")] == pytest.approx(values["g4_2"])
    assert G[5, cols.index("CM_L")] == pytest.approx(-values["g4_7"])
