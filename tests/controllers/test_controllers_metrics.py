import numpy as np
import pytest
import control
from scipy.optimize import brentq

from controllers import DelayedLTI, attitude_bandwidth, gain_phase_margins
from controllers.metrics import (damping_in_band, disturbance_rejection_bandwidth, disturbance_rejection_peak, nichols_margin)

DENSE = np.geomspace(0.01, 300.0, 20000)


@pytest.mark.parametrize("K", [0.5, 0.9, 2.0, 5.0])
def test_drb_of_integrator_loop_is_exactly_its_gain(K):
    # L = K/s -> S = s/(s+K): |S| = -3.01 dB exactly at w = K.
    # 20000-point log grid: interpolation error < 1e-5 relative.
    S = control.feedback(1, control.tf([K], [1, 0]))
    assert disturbance_rejection_bandwidth(S, DENSE) == pytest.approx(K, rel=1e-4)
    # |S| -> 1 from below: at the grid's end (300 rad/s) the peak is -20log10(sqrt(1+(K/300)^2)) < 0.002 dB
    assert disturbance_rejection_peak(S, DENSE) == pytest.approx(0.0, abs=2e-3)


@pytest.mark.parametrize("K, tau", [(1.0, 0.1), (3.0, 0.05), (6.0, 0.12)])
def test_integrator_with_pure_delay_textbook_margins(K, tau):
    # L = K e^{-tau s}/s: w_c = K, PM = 90 - K tau (deg), w_180 = pi/(2 tau),
    # GM = 20 log10(w_180 / K). Delay applied exactly (no Padé).
    L = DelayedLTI(control.tf([K], [1, 0]), tau)
    gm, pm, w180, wc = gain_phase_margins(L, DENSE)
    assert wc == pytest.approx(K, rel=1e-4)
    assert pm == pytest.approx(90 - np.degrees(K * tau), abs=0.02)
    assert w180 == pytest.approx(np.pi / (2 * tau), rel=1e-4)
    assert gm == pytest.approx(20 * np.log10(np.pi / (2 * tau) / K), abs=0.01)


def test_bandwidth_and_phase_delay_of_delayed_integrator_with_lag_match_hand_calculation():
    tau, a = 0.05, 4.0
    H = DelayedLTI(control.tf([1.0], [1 / a, 1, 0]), tau)
    phase = lambda w: -np.pi / 2 - np.arctan(w / a) - w * tau        # rad, exact
    gain_db = lambda w: -20 * np.log10(w * np.sqrt(1 + (w / a) ** 2))
    w180 = brentq(lambda w: phase(w) + np.pi, 0.1, 100)
    w135 = brentq(lambda w: phase(w) + 0.75 * np.pi, 0.1, 100)
    wgain = brentq(lambda w: gain_db(w) - (gain_db(w180) + 6.0), 0.01, w180)
    tau_p = -(np.degrees(phase(2 * w180)) + 180) / (57.2958 * 2 * w180)
    bw, tp, wbp, wbg, w180m = attitude_bandwidth(H, DENSE, response_type="rate")
    assert w180m == pytest.approx(w180, rel=1e-4)
    assert wbp == pytest.approx(w135, rel=1e-4)
    assert wbg == pytest.approx(wgain, rel=1e-4)
    assert bw == pytest.approx(min(w135, wgain), rel=1e-4)
    assert tp == pytest.approx(tau_p, abs=1e-4)
    assert attitude_bandwidth(H, DENSE)[0] == pytest.approx(w135, rel=1e-4)   # ACAH: phase bandwidth
    with pytest.raises(ValueError, match="response_type"):
        attitude_bandwidth(H, DENSE, response_type="acceleration")


@pytest.mark.parametrize("seed", range(6))
def test_margins_equal_python_control_on_random_stable_loops(seed):
    rng = np.random.default_rng(seed)
    # random stable plant (3 real/complex poles) times a gain giving a finite crossover
    poles = -rng.uniform(0.5, 10, 3)
    L = control.tf([rng.uniform(5, 40)], np.poly(poles))
    gm, pm, _, wg, wp, _ = control.stability_margins(L)   # (gm, pm, sm, w_pc, w_gc, w_ms)
    mg, mp, w180, wc = gain_phase_margins(L, DENSE)
    if np.isfinite(gm):
        assert mg == pytest.approx(20 * np.log10(gm), abs=0.01)
        assert w180 == pytest.approx(wg, rel=1e-3)
    if np.isfinite(pm):
        assert mp == pytest.approx(pm, abs=0.05)
        assert wc == pytest.approx(wp, rel=1e-3)


def test_nichols_margin_and_damping_band():
    # a loop passing exactly through GM = 6 dB at -180 deg touches the ellipse
    w180 = np.pi / (2 * 0.1)
    L = DelayedLTI(control.tf([w180 * 10 ** (-6 / 20)], [1, 0]), 0.1)
    assert nichols_margin(L, DENSE) <= 1e-3
    poles = [-0.2 + 1j, -0.2 - 1j, -5.0, -1 + 10j, -1 - 10j]
    assert damping_in_band(poles, 0.5, 4) == pytest.approx(0.2 / np.hypot(0.2, 1), rel=1e-12)
    assert damping_in_band(poles, 4, 20) == pytest.approx(1 / np.hypot(1, 10), rel=1e-12)
    assert damping_in_band(poles, 30, 40) == np.inf


def test_phase_unwrapping_prevents_wrong_w180():
    # a fifth-order lag wraps the raw phase several times before -180 x 3
    L = control.tf([200.0], np.poly([-1, -2, -3, -4, -5]))
    _, _, w180, _ = gain_phase_margins(L, DENSE)
    _, _, _, wg, _, _ = control.stability_margins(L)
    assert w180 == pytest.approx(wg, rel=1e-3)


def test_open_loop_onset_point_of_a_first_order_actuator_path():
    from controllers.metrics import open_loop_onset_point
    # pilot -> mixer = 1 (flat): rate = w * A reaches R at w = R / A exactly
    loop = control.tf([2.0], [1, 0])
    w_on_expected = 4.0 / 0.5
    phase, gain, w_on = open_loop_onset_point(loop, control.tf([1.0], [1.0]), 0.5, 4.0, DENSE)
    assert w_on == pytest.approx(w_on_expected, rel=1e-4)
    assert gain == pytest.approx(20 * np.log10(2.0 / w_on_expected), abs=1e-3)
    assert phase == pytest.approx(-90.0, abs=1e-6)
    assert np.isinf(open_loop_onset_point(loop, control.tf([1.0], [1.0]), 0.5, 1e6, DENSE)[2])
