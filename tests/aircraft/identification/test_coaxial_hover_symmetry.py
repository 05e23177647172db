"""The coaxial hover structures' ties against hover's axisymmetry, in both frames.

A hover wake turned about the shaft by an azimuth psi is the same wake, so each
rotor's cyclic inflow and load harmonics rotate by psi and every matrix must be
unchanged by that change of coordinates. In the dissertation's common frame both
rotors' harmonics rotate by R(psi); in our per-rotor frames the lower rotor's
azimuth runs the other way (mirrored frame), so its harmonics rotate by R(-psi).
This checks the ties of :class:`Coaxial6State` (``m36 = -m25`` in our frames,
``+m25`` printed) and of :class:`Coaxial12State` (near and far wake, load and
flap-rate columns alike: the flap harmonics beta1s/beta1c turn as the inflow's)
from geometry alone, not from the frame conversion code.
"""
import numpy as np
import pytest

from aircraft.identification.structures import Coaxial6State, Coaxial12State

NAMES = [f"{p}{i}{j}" for p in "mlt" for i, j in [(1, 1), (2, 2), (1, 4), (2, 5), (4, 1), (5, 2), (4, 4), (5, 5)]]


def _rotation(psi):
    c, s = np.cos(psi), np.sin(psi)
    return np.array([[c, s], [-s, c]])


def _turn(psi, lower_sign):
    """Coordinates of the turned wake: upper 1s/1c by R(psi), lower by R(lower_sign psi)."""
    t = np.eye(6)
    t[1:3, 1:3] = _rotation(psi)
    t[4:6, 4:6] = _rotation(lower_sign * psi)
    return t


def _random_matrices(frame, seed=3):
    rng = np.random.default_rng(seed)
    values = {n: rng.uniform(0.05, 1.0) * (1.0 if n[0] == "t" else rng.choice([-1.0, 1.0])) for n in NAMES}
    return Coaxial6State(frame).build(values, 23.7).matrices()


@pytest.mark.parametrize("frame, lower_sign", [("rotor", -1.0), ("printed", 1.0)])
def test_ties_are_invariant_under_a_turn_of_the_hover_wake(frame, lower_sign):
    mats = _random_matrices(frame)
    for psi in (0.3, 1.1, 2.5):
        t = _turn(psi, lower_sign)
        for key in ("M", "Lbar"):
            np.testing.assert_allclose(t @ mats[key] @ np.linalg.inv(t), mats[key], atol=1e-12)


@pytest.mark.parametrize("frame, lower_sign", [("rotor", 1.0), ("printed", -1.0)])
def test_the_other_frame_convention_is_not_invariant(frame, lower_sign):
    # the negative control: each frame's ties under the other frame's turn of the lower rotor
    mats = _random_matrices(frame)
    t = _turn(0.7, lower_sign)
    assert np.abs(t @ mats["Lbar"] @ np.linalg.inv(t) - mats["Lbar"]).max() > 1e-2


def _turn_labels(labels, psi, lower_sign):
    """The turn on named signals: each ``...1s...`` / ``...1c...`` pair (inflow states,
    C_L/C_M loads, flap rates) by R(psi), the lower rotor's by R(lower_sign psi)."""
    labels = [n.replace("CL", "1s").replace("CM", "1c") for n in labels]
    t = np.eye(len(labels))
    for i, a in enumerate(labels):
        if "1s" in a:
            j = labels.index(a.replace("1s", "1c"))
            t[np.ix_([i, j], [i, j])] = _rotation((lower_sign if a.endswith("_L") else 1.0) * psi)
    return t


@pytest.mark.parametrize("far_wake_loads", [False, True])
@pytest.mark.parametrize("frame, lower_sign, invariant", [("rotor", -1.0, True), ("printed", 1.0, True),
                                                          ("rotor", 1.0, False), ("printed", -1.0, False)])
def test_twelve_state_ties_are_invariant_under_a_turn_of_the_hover_wake(frame, lower_sign, invariant,
                                                                        far_wake_loads):
    # far_wake_loads: the extra load columns of the cyclic far-wake rows follow the same ties
    st = Coaxial12State(frame, far_wake_loads=far_wake_loads)
    rng = np.random.default_rng(5)
    values = {n: rng.uniform(0.05, 1.0) * (1.0 if n[0] == "t" else rng.choice([-1.0, 1.0]))
              for n in st.parameter_names()}
    built = st.build(values, 23.7)
    mats = built.matrices()
    ts, tu = _turn_labels(list(built.states), 0.7, lower_sign), _turn_labels(st.inputs, 0.7, lower_sign)
    change = max(np.abs(ts @ mats["F"] @ np.linalg.inv(ts) - mats["F"]).max(),
                 np.abs(ts @ mats["G"] @ np.linalg.inv(tu) - mats["G"]).max())
    assert (change < 1e-12) if invariant else (change > 1e-2)
