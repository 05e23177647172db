"""Multi-axis EMF: every loop closed on one MIMO plant, broken loops, coupling, DMO sweeps.

Hand-built plants with known answers: a roll/pitch pair (roll p/delta_lat = 5/(s+1.5),
pitch q/delta_lon = -4/(s+1), phi = int p, theta = int q) with a symmetric rate
cross-coupling ``c``, and a four-axis version adding yaw (r/delta_ped = 3/(s+0.5))
and heave (w/delta_col = -8/(s+0.4)) with yaw due to collective.
"""
import control
import numpy as np
import pytest
from matplotlib.figure import Figure

from controllers import DMOSettings, PIDGains, dmo, evaluate_specs
from controllers.multi_axis import AXIS_CHANNELS, AxisLoop, MultiAxisEMF, RateCommandModel, SignalNameError
from controllers.multi_axis_design import AxisEMFDesign, axis_specs, design_multi_axis
from controllers.plants import first_order_actuator

from tests.controllers._plants import roll_pitch

W = np.geomspace(0.1, 30.0, 25)
#: small DMO settings: the tests check the plumbing, not the optimiser's resolution
FAST = DMOSettings(global_samples=8, max_steps=6, tolerance=0.05, polish_evaluations=0, growth=2.0)
START = {"roll": 2.5, "pitch": 2.5}


def four_axis(c=0.2, yaw_col=0.4):
    names = ["p", "phi", "q", "theta", "r", "psi", "w"]
    A = np.zeros((7, 7))
    A[0, 0], A[1, 0], A[2, 2], A[3, 2], A[4, 4], A[5, 4], A[6, 6] = -1.5, 1, -1.0, 1, -0.5, 1, -0.4
    A[0, 2] = A[2, 0] = c
    B = np.zeros((7, 4))   # inputs: delta_col, delta_lon, delta_lat, delta_ped
    B[0, 2], B[2, 1], B[4, 3], B[6, 0], B[4, 0] = 5.0, -4.0, 3.0, -8.0, yaw_col
    return control.ss(A, B, np.eye(7), 0, inputs=["delta_col", "delta_lon", "delta_lat", "delta_ped"],
                      outputs=names)


def siso(num, den, inp, out):
    return control.ss(control.tf(num, den), inputs=inp, outputs=out)


def single_designs(sensor_delay=0.01):
    act = first_order_actuator(30.0)
    roll = AxisEMFDesign(siso([5.0], [1, 1.5], "delta_lat", "p"), PIDGains(0.3, 0.1, 0.05), axis="roll",
                         actuator=act, sensor_delay=sensor_delay)
    pitch = AxisEMFDesign(siso([4.0], [1, 1.0], "delta_lon", "-q"), PIDGains(0.4, 0.1, 0.08), axis="pitch",
                          actuator=act, sensor_delay=sensor_delay)
    return roll, pitch


def test_decoupled_axes_reproduce_the_single_axis_designs_exactly():
    roll, pitch = single_designs()
    emf = MultiAxisEMF(roll_pitch(0.0), {"roll": AxisLoop.from_design(roll), "pitch": AxisLoop.from_design(pitch)})
    for axis, single in (("roll", roll), ("pitch", pitch)):
        view = emf.axis_view(axis)
        for got, want in ((view.broken_loop(), single.broken_loop()),
                          (view.attitude_response(), single.attitude_response()),
                          (view.disturbance_response(), single.disturbance_response()),
                          (view.mixer_response_pilot(), single.mixer_response_pilot()),
                          (view.mixer_response_disturbance(), single.mixer_response_disturbance())):
            np.testing.assert_allclose(got.response(W), want.response(W), rtol=1e-10, atol=1e-14)
        # no coupling: the other stick moves nothing on this axis
        other = "pitch" if axis == "roll" else "roll"
        assert np.max(np.abs(emf.command_response(axis, other).response(W))) == 0.0
        # the effective plant is exactly the axis's own plant (structural reduction)
        eff = emf.effective_plant(axis)
        assert eff.nstates == 1
        np.testing.assert_allclose(np.squeeze(control.frequency_response(eff, W).complex),
                                   single.plant.response(W), rtol=1e-12)
    # the simultaneous closed loop's poles are the two single-axis loops' poles
    both = np.concatenate([roll.closed_loop_poles(), pitch.closed_loop_poles()])
    got = emf.closed_loop_poles()
    assert got.size == both.size
    np.testing.assert_allclose(np.sort_complex(got[np.abs(got) < 50]), np.sort_complex(both[np.abs(both) < 50]),
                               rtol=1e-6, atol=1e-8)


def test_coupled_broken_loop_equals_a_hand_computation_with_feedback():
    c = 0.4
    P = roll_pitch(c)
    act = first_order_actuator(30.0)
    gains = {"roll": PIDGains(0.5, 0.2, 0.1), "pitch": PIDGains(0.6, 0.15, 0.12)}
    loops = {a: AxisLoop(g, inverse_plant=control.tf([4.0], [1.0, 1.0]), actuator=act, sensor_delay=0.0)
             for a, g in gains.items()}
    emf = MultiAxisEMF(P, loops)
    # pitch loop by hand: signed variables -theta, -q; delta_fb = -(K_att(-theta) + K_p(-q)) = K_att theta + K_p q
    g = gains["pitch"]
    k_att = control.tf([g.K_phi, g.K_Iphi], [1.0, 0.0])
    F = control.ss(control.tf([[[0], [0], [0], [0]],
                               [[0], [0], (act * g.K_p).num[0][0], (act * k_att).num[0][0]]],
                              [[[1], [1], [1], [1]],
                               [[1], [1], (act * g.K_p).den[0][0], (act * k_att).den[0][0]]]))
    closed = control.feedback(P, F, sign=+1)           # pitch loop closed, inputs [delta_lat, delta_lon]
    r = gains["roll"]
    h = control.frequency_response(closed, W).complex   # (outputs p, phi, q, theta) x inputs
    a_r = np.squeeze(control.frequency_response(act, W).complex)
    s = 1j * W
    hand = a_r * ((r.K_phi + r.K_Iphi / s) * h[1, 0] + r.K_p * h[0, 0])
    np.testing.assert_allclose(emf.broken_loop("roll").response(W), hand, rtol=1e-9)
    # ... and python-control's state space of the same loop agrees
    bl = emf.broken_loop_statespace("roll")
    np.testing.assert_allclose(np.squeeze(control.frequency_response(bl, W).complex), hand, rtol=1e-7)
    # the coupling changes the loop: it is not the roll plant's own
    own = a_r * ((r.K_phi + r.K_Iphi / s) * 5 / (s + 1.5) / s + r.K_p * 5 / (s + 1.5))
    assert np.max(np.abs(hand / own - 1)) > 0.01


def test_exact_responses_agree_with_the_interconnected_state_space():
    loops = {a: AxisLoop(g, inverse_plant=control.tf([k], [1.0, p]), equivalent_delay=0.03,
                         actuator=first_order_actuator(30.0), sensor_delay=0.01)
             for a, g, k, p in (("roll", PIDGains(0.5, 0.2, 0.1), 5.0, 1.5), ("pitch", PIDGains(0.6, 0.1, 0.1), 4.0, 1.0),
                                ("yaw", PIDGains(0.8, 0.1, 0.3), 3.0, 0.5), ("heave", PIDGains(0.3, 0.05, 0.4), 8.0, 0.4))}
    emf = MultiAxisEMF(four_axis(), loops)
    cl = emf.closed_loop(pade_order=5)
    w = np.geomspace(0.1, 10.0, 15)
    h = control.frequency_response(cl, w).complex
    for out in ("roll", "yaw", "heave"):
        for stick in ("roll", "pitch", "heave"):
            exact = emf.command_response(out, stick).response(w)
            ss = h[cl.output_labels.index(f"att_{out}"), cl.input_labels.index(f"stick_s_{stick}")]
            np.testing.assert_allclose(ss, exact, rtol=2e-3, atol=1e-9)   # roll from heave: exactly 0
    # the closed loop is stable and its poles are the feedback system's plus the pilot path's
    poles = emf.closed_loop_poles()
    assert np.max(poles.real) < 0
    all_poles = np.linalg.eigvals(emf.closed_loop(pade_order=3).A)
    assert all_poles.size == poles.size + 2        # the yaw and heave rate commands' integrators
    assert np.sum(np.abs(all_poles) < 1e-9) == 2


def _four_loops():
    return {a: AxisLoop(g, inverse_plant=control.tf([k], [1.0, p]), equivalent_delay=0.03,
                        actuator=first_order_actuator(30.0), sensor_delay=0.01)
            for a, g, k, p in (("roll", PIDGains(0.5, 0.2, 0.1), 5.0, 1.5), ("pitch", PIDGains(0.6, 0.1, 0.1), 4.0, 1.0),
                               ("yaw", PIDGains(0.8, 0.1, 0.3), 3.0, 0.5), ("heave", PIDGains(0.3, 0.05, 0.4), 8.0, 0.4))}


def test_given_interconnections_are_used_as_given_and_checked():
    emf = MultiAxisEMF(four_axis(), _four_loops())
    assert not emf.has_closed_loop()
    fb, cl = emf.feedback_poles(), emf.closed_loop()
    assert emf.has_closed_loop()
    same = emf.with_interconnections(feedback_poles=fb, closed_loop=cl)
    assert same.closed_loop() is cl and same.has_closed_loop()
    np.testing.assert_array_equal(same.closed_loop_poles(), emf.closed_loop_poles())
    a, b = evaluate_specs(emf.axis_view("roll"), axis_specs("roll")), evaluate_specs(same.axis_view("roll"),
                                                                                     axis_specs("roll"))
    np.testing.assert_array_equal(a.value.to_numpy(float), b.value.to_numpy(float))
    # what is given is what is used (not rebuilt), also after many frequency grids have come and gone
    moved = emf.with_interconnections(feedback_poles=fb - 1.0)
    for k in range(12):
        moved.broken_loop("roll").response(np.geomspace(0.1, 10.0, 5 + k))
    np.testing.assert_array_equal(moved.feedback_poles(), fb - 1.0)
    np.testing.assert_array_equal(moved.closed_loop_poles()[fb.size:], emf.closed_loop_poles()[fb.size:])
    with pytest.raises(ValueError, match="finite"):
        emf.with_interconnections(feedback_poles=np.r_[fb, np.nan])
    with pytest.raises(ValueError, match="inputs"):
        emf.with_interconnections(closed_loop=control.ss(cl.A, cl.B, cl.C, cl.D))


@pytest.mark.slow
def test_new_gains_keep_the_pilot_path_poles_and_match_a_fresh_build():
    emf = MultiAxisEMF(four_axis(), _four_loops())
    emf.closed_loop_poles()
    gains = {"roll": PIDGains(0.9, 0.0, 0.2), "yaw": PIDGains(1.2, 0.3, 0.5)}
    copy = emf.with_gains(gains)
    fresh = MultiAxisEMF(four_axis(), {a: (AxisLoop(gains[a], l.command_model, l.inverse_plant, l.equivalent_delay,
                                                    l.actuator, l.sensor_delay) if a in gains else l)
                                       for a, l in copy.loops.items()})
    np.testing.assert_array_equal(copy.closed_loop_poles(), fresh.closed_loop_poles())
    # the closed loop's own eigenvalues: the same set (the rate commands' integrators aside)
    eig = np.linalg.eigvals(fresh.closed_loop().A)
    eig = eig[np.abs(eig) > 1e-9]
    poles = copy.closed_loop_poles()
    assert eig.size == poles.size
    # each eigenvalue's nearest pole, relative to its size (eigenvalue round-off of two assemblies)
    gap = np.min(np.abs(eig[:, None] - poles[None, :]), axis=1) / np.maximum(np.abs(eig), 1.0)
    assert np.max(gap) < 1e-6


def test_rate_command_axes_hold_the_commanded_rate():
    loops = {a: AxisLoop(g, inverse_plant=control.tf([k], [1.0, p]), actuator=first_order_actuator(30.0))
             for a, g, k, p in (("roll", PIDGains(0.5, 0.2, 0.1), 5.0, 1.5), ("pitch", PIDGains(0.6, 0.1, 0.1), 4.0, 1.0),
                                ("yaw", PIDGains(0.8, 0.1, 0.3), 3.0, 0.5), ("heave", PIDGains(0.3, 0.05, 0.4), 8.0, 0.4))}
    emf = MultiAxisEMF(four_axis(), loops)
    assert isinstance(emf.loops["yaw"].command_model, RateCommandModel)
    cl = emf.closed_loop()
    t = np.linspace(0.0, 40.0, 2001)
    for axis in ("yaw", "heave"):
        u = np.zeros((cl.ninputs, t.size))
        u[cl.input_labels.index(f"stick_s_{axis}")] = 1.0
        y = control.forced_response(cl, t, u).outputs
        rate = y[cl.output_labels.index(f"rate_{axis}")]
        # rate command: the steady rate is the command model's gain (heave: up positive, -w)
        assert rate[-1] == pytest.approx(emf.loops[axis].command_model.gain, rel=1e-3)
    # heave's height is the integral of -w: the plant has no height state
    assert AXIS_CHANNELS["heave"].attitude is None and AXIS_CHANNELS["heave"].sign == -1


def test_signal_name_errors_name_the_signal():
    loop = AxisLoop(PIDGains(0.5, 0.1, 0.1), inverse_plant=control.tf([1.0], [1.0, 1.0]))
    no_theta = control.ss(roll_pitch().A[:3, :3], roll_pitch().B[:3], np.eye(3), 0,
                          inputs=["delta_lat", "delta_lon"], outputs=["p", "phi", "q"])
    with pytest.raises(SignalNameError, match="theta"):
        MultiAxisEMF(no_theta, {"roll": loop, "pitch": loop})
    with pytest.raises(SignalNameError, match="delta_ped"):
        MultiAxisEMF(roll_pitch(), {"yaw": loop})
    with pytest.raises(ValueError, match="unknown axis"):
        MultiAxisEMF(roll_pitch(), {"spin": loop})
    # a heave design on a pitch-named plant, and an unsigned pitch plant, are refused
    with pytest.raises(SignalNameError, match="-w/delta_col"):
        AxisEMFDesign(siso([4.0], [1, 1.0], "delta_lon", "-q"), PIDGains(0.3, 0.1, 0.1), axis="heave")
    with pytest.raises(SignalNameError, match="'q'"):
        AxisEMFDesign(siso([4.0], [1, 1.0], "delta_lon", "q"), PIDGains(0.3, 0.1, 0.1), axis="pitch")
    assert issubclass(SignalNameError, ValueError)
    emf = MultiAxisEMF(roll_pitch(), {"roll": loop})
    with pytest.raises(ValueError, match="this design has"):
        emf.broken_loop("pitch")


@pytest.mark.slow
def test_decoupled_design_reproduces_the_single_axis_dmo():
    res = design_multi_axis(roll_pitch(0.0), axes=["roll", "pitch"], settings=FAST, progress=False,
                            actuator=first_order_actuator(30.0), crossover_start=START)
    assert res.converged and res.sweeps == 2
    # the second sweep found every effective plant unchanged and kept the designs
    assert (res.history[res.history.sweep == 2].relative_change == 0).all()
    singles = {}
    for axis, (num, den, inp, out) in {"roll": ([5.0], [1, 1.5], "delta_lat", "p"),
                                       "pitch": ([4.0], [1, 1.0], "delta_lon", "-q")}.items():
        single = AxisEMFDesign(siso(num, den, inp, out), PIDGains(0.3, 0.1, 0.05), axis=axis,
                               actuator=first_order_actuator(30.0))
        # the same actuator limits (the hover defaults through each axis's command model): OLOP graded alike
        ref = dmo(single, specs_factory=lambda wc, wd, a=axis: axis_specs(a, wc, wd, limits=res.limits[a]),
                  settings=FAST, crossover_start=START[axis], progress=False)
        np.testing.assert_allclose(res.emf.loops[axis].gains.as_array(), ref.design.gains.as_array(), rtol=1e-6)
        table = res.specs[axis].set_index("spec")
        single_table = evaluate_specs(ref.design, axis_specs(axis, ref.crossover_boundary, ref.drb_boundary,
                                                             limits=res.limits[axis])).set_index("spec")
        # the eigenvalue specs grade the whole aircraft: every closed-loop pole, both axes'
        poles = [n for n in table.index if n.startswith("Eig")]
        np.testing.assert_allclose(table.value.drop(poles).astype(float),
                                   single_table.value.drop(poles).astype(float), rtol=1e-6)
        singles[axis] = ref.design
    both = np.concatenate([d.closed_loop_poles() for d in singles.values()])
    for axis in ("roll", "pitch"):
        table = res.specs[axis].set_index("spec")
        assert table.loc["EigLcG1", "value"] == pytest.approx(np.max(both.real), rel=1e-6)


@pytest.mark.slow
def test_coupled_design_reports_every_axis():
    res = design_multi_axis(roll_pitch(0.5), axes=["roll", "pitch"], settings=FAST, progress=False,
                            actuator=first_order_actuator(30.0), max_sweeps=2, crossover_start=START)
    table = res.to_pandas()
    assert list(table.index) == ["roll", "pitch"]
    for col in ("K_phi", "K_Iphi", "K_p", "crossover", "drb", "gm_db", "pm_deg", "specs_met", "unmet", "limiting"):
        assert col in table.columns
    assert np.all(np.isfinite(table.crossover.astype(float)))
    # at the sweeps' fixed point the design plant's crossover is the MIMO loop's
    if res.converged:
        np.testing.assert_allclose(table.crossover, table.crossover_design, rtol=0.02)
    coupling = res.coupling()
    assert set(zip(coupling.stick, coupling.response)) == {("roll", "pitch"), ("pitch", "roll")}
    assert (coupling.peak_gain_ratio > 0).all() and (coupling.peak_gain_ratio < 1).all()
    figs = res.plot()
    assert set(figs) == {"roll", "pitch"} and all(isinstance(f, Figure) for f in figs.values())
    legend = " ".join(t.get_text() for leg in figs["roll"].legends for t in leg.get_texts())
    assert "roll axis" in legend and figs["pitch"].get_label() == "pitch axis HQ window"


def test_an_axis_the_dmo_cannot_satisfy_is_named():
    # a 0.4 s sensor delay leaves no gains with 45 deg of phase margin at a 1.5 rad/s crossover
    res = design_multi_axis(roll_pitch(0.0), axes=["roll"], settings=FAST, progress=False, sensor_delay=0.4,
                            max_sweeps=1)
    assert "no gains meet every roll spec" in res.messages["roll"]
    row = res.to_pandas().loc["roll"]
    assert row.unmet != "" and "unmet" in row.limiting


def test_axis_specs_carry_the_boundaries_asked_for():
    names = [s.name for s in axis_specs("yaw")]
    assert "LrgRtH1.yaw" not in names and "CouYCH1.yaw" not in names   # time-history specs: not DMO constraints
    assert [s.level1 for s in axis_specs("roll", 2.5, 1.1) if s.name in ("CrsMnG2", "DrbRoH1")] == [1.1, 2.5]


@pytest.mark.slow
def test_four_axis_design_of_the_coaxial_in_hover():
    from aircraft import coaxial_compound
    from aircraft.helicopter import Helicopter, TrimCondition, linearize, trim
    from aircraft.helicopter.hold import hold_states
    from aircraft.inflow import DynamicClimb
    sys = hold_states(linearize(trim(Helicopter(coaxial_compound(), DynamicClimb()), TrimCondition(speed=0.0))),
                      ["u", "v"])
    # one sweep keeps the suite short; the benchmark runs the sweeps to convergence
    res = design_multi_axis(sys, settings=DMOSettings(global_samples=16), max_sweeps=1, progress=False)
    table = res.to_pandas()
    assert list(table.index) == ["roll", "pitch", "yaw", "heave"]
    assert np.max(res.emf.closed_loop_poles().real) < 0          # the simultaneous closed loop is stable
    assert np.all(table.crossover.astype(float) > 0.3)
    assert len(res.coupling()) == 12
