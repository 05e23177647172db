"""Forward-flight regime of the spec selector and of the multi-axis design.

Hand-computable cases: the 45 kt boundary of ADS-33E-PRF's hover/low-speed regime
(45 x 1852 / 3600 m/s), the names of the forward-flight charts, and the printed
MIL-F-8785C dutch roll values (Nelson Table 10.2) the forward-flight yaw axis carries.
"""
import control
import numpy as np
import pytest

from controllers import DMOSettings, PIDGains, specs_for
from controllers.hq.selector import LOW_SPEED_LIMIT, flight_regime
from controllers.multi_axis_design import AxisEMFDesign, axis_specs, design_multi_axis

#: the tests check the plumbing, not the optimiser's resolution
FAST = DMOSettings(global_samples=8, max_steps=6, tolerance=0.05, polish_evaluations=0, growth=2.0)


def test_flight_regime_switches_at_45_knots():
    assert LOW_SPEED_LIMIT == pytest.approx(23.15, abs=1e-12)   # 45 kt x 0.514444 m/s per kt, exact decimal
    assert flight_regime(0.0) == "hover" and flight_regime(23.14) == "hover"
    assert flight_regime(23.15) == "forward" and flight_regime(np.float64(50.0)) == "forward"
    for bad in (-1.0, float("nan"), float("inf"), True, "50"):
        with pytest.raises(ValueError, match="speed"):
            flight_regime(bad)


@pytest.mark.parametrize("axis, forward, hover_only", [
    ("roll", {"BnwAtF1.roll", "SpiralF.MIL-F-8785C"}, {"BnwAtH1.roll", "QikAtH1.roll", "LrgRtH1.roll"}),
    ("pitch", {"BnwAtF1.pitch", "PhugoidF.pitch"}, {"BnwAtH1.pitch", "QikAtH1.pitch", "LrgRtH1.pitch"}),
    ("yaw", {"LatDirOscF.MIL-F-8785C", "LatDirOscF.ADS-33"}, {"BnwAtH1.yaw", "LrgRtH1.yaw", "CouYCH1.yaw"}),
    ("heave", set(), {"HgtRsH1.heave"}),
])
def test_selector_at_speed_returns_the_forward_flight_charts(axis, forward, hover_only):
    names = {s.name for s in specs_for(axis, speed=flight_regime(50.0), missing="keep")}
    assert forward <= names and not (hover_only & names)
    assert hover_only <= {s.name for s in specs_for(axis, speed=flight_regime(0.0), missing="keep")}


def test_forward_yaw_axis_grades_the_dutch_roll_of_the_feedback_loop():
    ldo = [s for s in axis_specs("yaw", speed="forward") if s.name == "LatDirOscF.MIL-F-8785C"]
    assert len(ldo) == 1
    # r/delta_ped = 1/(s + 0.2), static actuator, no delays, K_phi 1.44, K_p 0.4 on heading and rate:
    # s (s + 0.2) + 0.4 s + 1.44 = s^2 + 0.6 s + 1.44 -> w_n 1.2 rad/s, zeta 0.25, zeta w_n 0.3 rad/s,
    # below the printed Level 1 0.35 and above Level 2 0.05 -> Level 2, margin (0.3 - 0.35)/(0.35 - 0.05)
    plant = control.ss(control.tf([1.0], [1.0, 0.2]), inputs="delta_ped", outputs="r")
    design = AxisEMFDesign(plant, PIDGains(1.44, 0.0, 0.4), axis="yaw", actuator=control.tf(1, 1), sensor_delay=0.0)
    r = ldo[0].evaluate(design)
    # 1e-9: two roots of a quadratic, exact to rounding
    assert r["level"] == 2 and r["value"] == pytest.approx(0.25, rel=1e-9) and r["wn"] == pytest.approx(1.2, rel=1e-9)
    assert r["margin"] == pytest.approx((0.3 - 0.35) / (0.35 - 0.05), rel=1e-9)
    # the command model (rate command, a pole at -2 rad/s) is a prefilter, not a mode: two poles only
    assert design.feedback_poles().size == 2


def _roll_plant():
    return control.ss([[-1.5, 0], [1.0, 0]], [[5.0], [0]], [[1.0, 0], [0, 1.0]], 0,
                      inputs=["delta_lat"], outputs=["p", "phi"])


@pytest.mark.slow
def test_design_grades_the_regime_asked_for_and_hover_stays_the_default():
    fwd = design_multi_axis(_roll_plant(), axes=["roll"], settings=FAST, progress=False, speed="forward")
    hov = design_multi_axis(_roll_plant(), axes=["roll"], settings=FAST, progress=False)
    fwd_names, hov_names = ({s.name for s in r.spec_lists["roll"]} for r in (fwd, hov))
    assert "SpiralF.MIL-F-8785C" in fwd_names and "SpiralF.MIL-F-8785C" not in hov_names
    assert "BnwAtH1.roll" in hov_names and "BnwAtH1.roll" not in fwd_names
    # plant 5/(s(s+1.5)): no real pole other than the command and loop ones; the spiral spec is graded
    assert "SpiralF.MIL-F-8785C" in set(fwd.specs["roll"].spec)


@pytest.mark.slow
def test_global_check_grades_the_specs_the_design_was_graded_on():
    from controllers.multi_axis_check import global_check
    fwd = design_multi_axis(_roll_plant(), axes=["roll"], settings=FAST, progress=False, speed="forward")
    used = []
    import controllers.multi_axis_check as check_module
    real = check_module.evaluate_specs

    def spy(design, specs):
        used.append({s.name for s in specs})
        return real(design, specs)
    check_module.evaluate_specs = spy
    try:
        global_check(fwd, maxiter=1, popsize=2)
    finally:
        check_module.evaluate_specs = real
    # the forward-flight design is checked on its forward-flight charts, not the hover ones
    assert used and used[0] == {s.name for s in fwd.spec_lists["roll"]}
    assert "BnwAtH1.roll" not in used[0]


def test_unknown_speed_is_named():
    with pytest.raises(ValueError, match="speed"):
        design_multi_axis(_roll_plant(), axes=["roll"], settings=FAST, progress=False, speed="cruise")


def test_sideslip_yaw_channel_reads_the_nose_angle_from_the_flight_path():
    from aircraft.helicopter.hold import sideslip_yaw_channel
    # v_dot = -0.5 v + 0.2 r + 2 delta_ped, r_dot = 0.3 v - r + 4 delta_ped, psi_dot = r; V = 20 m/s
    A = [[-0.5, 0.2, 0.0], [0.3, -1.0, 0.0], [0.0, 1.0, 0.0]]
    B = [[2.0], [4.0], [0.0]]
    sys = control.ss(A, B, np.eye(3), 0, states=["v", "r", "psi"], inputs=["delta_ped"], outputs=["v", "r", "psi"])
    out = sideslip_yaw_channel(sys, 20.0)
    # by hand: -v_dot/V = (0.5 v - 0.2 r - 2 delta_ped)/20; -v/V = -v/20; v unchanged. Exact decimals: 1e-15
    np.testing.assert_allclose(out.C, [[1, 0, 0], [0.025, -0.01, 0], [-0.05, 0, 0]], atol=1e-15)
    np.testing.assert_allclose(out.D, [[0.0], [-0.1], [0.0]], atol=1e-15)
    np.testing.assert_array_equal(out.A, sys.A)
    assert list(out.output_labels) == ["v", "r", "psi"]
    for bad in (0.0, -5.0, float("nan"), True):
        with pytest.raises(ValueError, match="speed"):
            sideslip_yaw_channel(sys, bad)
    with pytest.raises(ValueError, match="lacks"):
        sideslip_yaw_channel(control.ss(A, B, np.eye(3), 0, states=["u", "r", "psi"], outputs=["u", "r", "psi"]), 20.0)


def _unstable_pitch(c=0.3):
    # roll p/delta_lat = 5/(s + 1.5); pitch q/delta_lon = -4/(s - 0.5), a divergence only pitch can remove;
    # symmetric rate coupling c; phi, theta integrate p, q
    A = np.zeros((4, 4))
    A[0, 0], A[1, 0], A[2, 2], A[3, 2] = -1.5, 1.0, 0.5, 1.0
    A[0, 2] = A[2, 0] = c
    B = np.zeros((4, 2))
    B[0, 0], B[2, 1] = 5.0, -4.0
    return control.ss(A, B, np.eye(4), 0, inputs=["delta_lat", "delta_lon"], outputs=["p", "phi", "q", "theta"])


@pytest.mark.slow
def test_start_closed_designs_an_axis_on_the_aircraft_its_partner_stabilises():
    plant = _unstable_pitch()
    # pitch alone at K_phi 0.3, K_p 0.5: s (s - 0.5) + 4 (0.5 s + 0.3) = s^2 + 1.5 s + 1.2, by hand stable and
    # damped (zeta 0.68 > the EigDpG1 Level 1 0.35), so the roll DMO meets the whole-aircraft specs
    start = {"roll": PIDGains(0.3, 0.1, 0.05), "pitch": PIDGains(0.3, 0.0, 0.5)}
    kw = dict(axes=["roll", "pitch"], start_gains=start, settings=FAST, progress=False, max_sweeps=1,
              crossover_start={"roll": 1.0, "pitch": 1.0})
    opened = design_multi_axis(plant, **kw)
    closed = design_multi_axis(plant, start_closed=True, **kw)
    # open pitch loop: the roll loop's plant carries the divergence, no roll gains can remove it
    assert opened.dmo_results["roll"] is None and "EigLcG1" in opened.messages["roll"]
    assert closed.dmo_results["roll"] is not None


@pytest.mark.slow
def test_global_check_at_another_mte_keeps_the_designs_regime_and_boundaries(monkeypatch):
    # global_check(..., mte=...) rebuilds each axis's specs: a forward-flight design must be
    # re-checked on the forward-flight charts, with the boundaries the design was given
    import controllers.multi_axis_check as check
    plant = control.ss([[-1.5, 0], [1.0, 0]], [[5.0], [0]], [[1.0, 0], [0, 1.0]], 0,
                       inputs=["delta_lat"], outputs=["p", "phi"])
    mine = {"StbMgG1.PM": {"level1": 50.0, "level2": 40.0, "source": "test"}}
    res = design_multi_axis(plant, axes=["roll"], settings=FAST, progress=False, max_sweeps=1, speed="forward",
                            limits=None, boundaries=mine)
    assert res.speed == "forward" and "SpiralF.MIL-F-8785C" in {s.name for s in res.spec_lists["roll"]}
    built = []

    def recording(*args, **kw):
        built.append(axis_specs(*args, **kw))
        return built[-1]

    monkeypatch.setattr(check, "axis_specs", recording)
    check.global_check(res, maxiter=1, popsize=2, mte="target acquisition and tracking")
    names = {s.name: s for s in built[0]}
    assert "SpiralF.MIL-F-8785C" in names and "BnwAtH1.roll" not in names
    assert names["StbMgG1.PM"].status == "supplied" and names["StbMgG1.PM"].level1 == 50.0
