"""Flight-dynamics mode names (hand-built block-diagonal systems whose modes are known
in closed form) and mode tracks against speed (continuity through an eigenvalue crossing)."""
import control
import numpy as np
import pytest
from matplotlib.figure import Figure
from scipy.linalg import block_diag

from aircraft import uh60_single_rotor
from aircraft.helicopter import Helicopter
from aircraft.helicopter.mode_tracking import ModeTrackingError, flight_modes, modes_over_speed
from aircraft.helicopter.sweep import trim_sweep
from aircraft.inflow import PittPeters


def pair(sigma, omega):
    """2x2 block with eigenvalues sigma +- j omega."""
    return np.array([[sigma, omega], [-omega, sigma]])


def system(blocks, states):
    a = block_diag(*blocks)
    n = a.shape[0]
    return control.ss(a, np.ones((n, 1)), np.eye(n), np.zeros((n, 1)), states=states)


# a similarity transform inside a block changes its eigenvectors but not its
# eigenvalues, and the participation stays inside the block
SKEW = np.array([[2.0, 0.7], [-0.3, 1.5]])


def skewed(block):
    return SKEW @ block @ np.linalg.inv(SKEW)


CASE_A = ([skewed(pair(-0.05, 0.3)), skewed(pair(-1.5, 2.0)), pair(-0.3, 1.5), [[-3.0]], [[-0.04]], [[0.0]],
           [[-12.0]]],
          ["u", "theta", "q", "w", "v", "r", "p", "phi", "psi", "lam0"],
          {"phugoid": -0.05 + 0.3j, "short period": -1.5 + 2.0j, "dutch roll": -0.3 + 1.5j,
           "roll subsidence": -3.0, "spiral": -0.04, "heading": 0.0, "inflow (mean)": -12.0})
CASE_B = ([pair(0.05, 0.45), [[-0.2]], [[-0.3]], [[0.4]], [[-0.1]]],
          ["v", "phi", "r", "w", "q", "u"],
          {"lateral phugoid": 0.05 + 0.45j, "yaw subsidence": -0.2, "heave subsidence": -0.3,
           "pitch divergence": 0.4, "phugoid (aperiodic)": -0.1})


@pytest.mark.parametrize("case", [CASE_A, CASE_B], ids=["A", "B"])
def test_block_diagonal_modes_are_named_and_placed(case):
    blocks, states, expected = case
    table = flight_modes(system(blocks, states))
    assert sorted(table["mode"]) == sorted(expected)
    for _, row in table.iterrows():
        # eigenvalues of 2x2 blocks by numpy's eig: round-off only
        assert complex(row["real"], row["imag"]) == pytest.approx(expected[row["mode"]], abs=1e-10)


def test_a_flap_mode_that_carries_the_body_is_roll_flap():
    # p and beta1s coupled as in an articulated rotor's roll-flap mode (about 6.6 rad/s):
    # the body takes half of the participation, above the 0.3 needed, below 0.5 Omega = 13.5 rad/s
    sys = control.ss(block_diag(pair(-3.0, 5.8), [[0.0]]), np.ones((3, 1)), np.eye(3), np.zeros((3, 1)),
                     states=["p", "beta1s", "psi"])
    table = flight_modes(sys, omega=27.0)
    assert "roll-flap" in table["mode"].tolist()


def heave_pitch(v):
    # pitch subsidence -1 - 0.02 V and heave subsidence -2 + 0.02 V: equal at 25 m/s
    return system([[[-1.0 - 0.02 * v]], [[-2.0 + 0.02 * v]]], ["q", "w"])


def test_tracks_follow_the_mode_through_an_eigenvalue_crossing():
    speeds = (0.0, 10.0, 20.0, 30.0, 40.0)
    table = modes_over_speed({v: heave_pitch(v) for v in speeds}).table
    assert table["track"].nunique() == 2
    for track, g in table.groupby("track"):
        g = g.sort_values("speed")
        # a track keeps its name and its closed-form eigenvalue at every speed; matching by
        # eigenvalue alone would swap the tracks between 20 and 30 m/s (-1.4 and -1.6 swap places)
        assert g["mode"].nunique() == 1
        law = (lambda v: -1 - 0.02 * v) if g["mode"].iloc[0] == "pitch subsidence" else (lambda v: -2 + 0.02 * v)
        np.testing.assert_allclose(g["real"], [law(v) for v in g["speed"]], atol=1e-12)


def test_tracks_are_continuous_along_speed():
    # a dutch roll whose frequency rises linearly with speed (0.5 + 0.03 V rad/s) and a
    # phugoid whose damping falls: |d lambda / dV| <= 0.03 + 0.002, so one 5 m/s step moves
    # an eigenvalue by at most 0.16 (plus round-off)
    def heli(v):
        return system([pair(-0.2, 0.5 + 0.03 * v), pair(-0.05 + 0.002 * v, 0.3)], ["v", "r", "u", "theta"])
    speeds = np.arange(0.0, 50.1, 5.0)
    table = modes_over_speed({v: heli(v) for v in speeds}).table
    assert sorted(table["track_mode"].unique()) == ["dutch roll", "phugoid"]
    for _, g in table.groupby("track"):
        assert len(g) == len(speeds)
        lam = (g["real"] + 1j * g["imag"]).to_numpy()
        assert np.max(np.abs(np.diff(lam))) <= 0.16 + 1e-9


@pytest.fixture(scope="module")
def uh60_modes():
    # 10 m/s steps at low speed, where the hover pendulum turns into the dutch roll
    sweep = trim_sweep(Helicopter(uh60_single_rotor(), PittPeters()), [0.0, 10.0, 20.0, 40.0, 60.0])
    return modes_over_speed(sweep)


def test_uh60_body_modes_are_tracked_from_hover_to_cruise(uh60_modes):
    t = uh60_modes.table
    phugoid = t[t["track_mode"] == "phugoid"]
    assert phugoid["speed"].tolist() == [0.0, 10.0, 20.0, 40.0, 60.0]
    dutch = t[(t["mode"] == "dutch roll")].sort_values("speed")
    assert dutch["speed"].tolist() == [10.0, 20.0, 40.0, 60.0]
    # the fin's weathercock stiffness N_v grows with speed, so the dutch roll frequency does too
    assert np.all(np.diff(dutch["frequency"]) > 0)
    # the hover lateral pendulum (v, phi) is the same track as the forward-flight dutch roll
    assert t[t["track"] == dutch["track"].iloc[0]]["mode"].tolist()[0] == "lateral phugoid"


def test_plot_returns_a_figure(uh60_modes):
    fig = uh60_modes.plot("UH-60-like")
    assert isinstance(fig, Figure) and len(fig.axes) == 3


@pytest.mark.parametrize("bad, match", [({}, "non-empty"), ([1, 2], "non-empty"),
                                        ({"fast": heave_pitch(0.0)}, "speeds"),
                                        ({np.nan: heave_pitch(0.0)}, "finite")])
def test_bad_systems_are_refused(bad, match):
    with pytest.raises(ModeTrackingError, match=match):
        modes_over_speed(bad)


def test_bad_arguments_are_refused():
    with pytest.raises(ModeTrackingError, match="max_cost"):
        modes_over_speed({0.0: heave_pitch(0.0)}, max_cost=0.0)
    with pytest.raises(ValueError, match="finite matrix A"):
        flight_modes("not a system")
