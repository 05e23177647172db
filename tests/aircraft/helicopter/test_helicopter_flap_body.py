"""Flap-body coupling, wake-distortion inputs (Eq. 2.29), mode physics and bare-airframe comparisons."""
import dataclasses

import control
import numpy as np
import pandas as pd
import pytest

from aircraft import coaxial_compound, uh60_single_rotor
from aircraft.configs import LB
from aircraft.helicopter import (Helicopter, HelicopterSettings, classify_modes, compare_bare_airframe,
                                 coupling_numerator, flap_mode_damping, flap_mode_sensitivity, linearize,
                                 pair_modes, trim)
from aircraft.helicopter.rotor import RotorModel
from aircraft.inflow import KR_ANALYTICAL, ClimbingLowerRotor, DynamicClimb, RotorOperatingPoint

FAST = HelicopterSettings(n_span=6, n_average=1)   # hover is axisymmetric: one azimuth is exact
OMEGA = 23.7


@pytest.fixture(scope="module")
def clr_sys():
    return linearize(trim(Helicopter(coaxial_compound(), ClimbingLowerRotor(), FAST)))


def _rot_x(a):
    return np.array([[1, 0, 0], [0, np.cos(a), -np.sin(a)], [0, np.sin(a), np.cos(a)]])


def _rot_y(a):
    return np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])


def test_tpp_rates_are_the_space_fixed_tip_path_plane_rates():
    # independent: rotate the blade's span vector (rotor-frame geometry of rotor.py) by a small
    # body roll phi (right side down) and pitch theta (nose up), measure its elevation above the
    # space-fixed plane over azimuth and fit the first harmonics. Their time derivative, with
    # phi' = p and theta' = q, is what the inflow model must see.
    psi = np.linspace(0, 2 * np.pi, 72, endpoint=False)
    b0, b1c, b1s, phi, theta = 0.03, 0.004, -0.006, 0.002, -0.003
    beta = b0 + b1c * np.cos(psi) + b1s * np.sin(psi)
    e_r = np.stack([-np.cos(psi), np.sin(psi), 0 * psi], -1)
    span = np.cos(beta)[:, None] * e_r + np.sin(beta)[:, None] * np.array([0, 0, -1.0])
    span_space = span @ (_rot_y(theta) @ _rot_x(phi)).T
    elev = np.arcsin(-span_space[:, 2])
    a1c, a1s = 2 * np.mean(elev * np.cos(psi)), 2 * np.mean(elev * np.sin(psi))
    # small-angle kinematics: 1e-5 rad agreement for angles of a few mrad (second order terms)
    assert a1s == pytest.approx(b1s - phi, abs=1e-5)
    assert a1c == pytest.approx(b1c - theta, abs=1e-5)
    # hence the rates: d/dt of (beta1s - phi, beta1c - theta) with phi' = p_r, theta' = q_r
    flap_rate = np.array([0.0, 0.2, -0.1, 0.0])      # (b0, b1c, b1s, bd) rates [rad/s]
    rates = np.array([0.05, -0.03, 0.0])             # rotor-frame p, q, r [rad/s]
    np.testing.assert_allclose(RotorModel.tpp_rates(flap_rate, rates), [-0.1 - 0.05, 0.2 + 0.03])


def test_eq_2_29_body_rate_terms_in_the_aircraft_match_the_hand_derivative():
    cfg = coaxial_compound()
    sys_kr = linearize(trim(Helicopter(cfg, DynamicClimb(kr=KR_ANALYTICAL), FAST)))
    sys_0 = linearize(trim(Helicopter(cfg, DynamicClimb(kr=0.0), FAST)))
    names = list(sys_kr.state_labels)
    assert names == list(sys_0.state_labels)
    x = sys_kr.trim.x
    lu, ll = x[names.index("lam0_U")], x[names.index("lam0_L")]
    # hover Pitt-Peters in a climb mu_c (Eqs. 2.4-2.5, climb positive): Lbar22 = -(lam0 + lam_tot)/2,
    # M22 = -16/(45 pi); Eq. 2.29: M22 lam1s' + Lbar22 lam1s = dC_L + Lbar22 K_R (p_r/Omega - b1s*)
    # so in seconds d(lam1s')/dp_r = K_R Lbar22 / M22 and d(lam1s')/d(beta1s_dot) = -K_R Lbar22 / M22
    m22 = -16 / (45 * np.pi)
    g_u = KR_ANALYTICAL * (-(lu + lu + 0.86 * ll) / 2) / m22
    g_l = KR_ANALYTICAL * (-(ll + ll + 1.13 * lu) / 2) / m22
    diff = np.asarray(sys_kr.A) - np.asarray(sys_0.A)   # the K_R terms alone (same trim: rates are 0 there)
    i = names.index
    expected = {("lam1s_U", "p"): g_u, ("lam1c_U", "q"): g_u,          # upper rotor: p_r = p, q_r = q
                ("lam1s_L", "p"): -g_l, ("lam1c_L", "q"): g_l,         # lower (clockwise): p_r = -p
                ("lam1s_U", "beta1s_dot_U"): -g_u, ("lam1c_U", "beta1c_dot_U"): -g_u,
                ("lam1s_L", "beta1s_dot_L"): -g_l, ("lam1c_L", "beta1c_dot_L"): -g_l}
    for (row, col), value in expected.items():
        # central differences of a term linear in the rate: exact but for round-off on the larger
        # load-derivative part subtracted with it, hence 1e-4
        assert diff[i(row), i(col)] == pytest.approx(value, rel=1e-4), (row, col)
    mask = np.zeros_like(diff, bool)
    for row, col in expected:
        mask[i(row), i(col)] = True
    # nothing else moves: the two trims agree to their 1e-9 tolerance, which on A entries up to
    # ~1e3 leaves ~1e-7 differences elsewhere, 1e-5 of the K_R terms
    assert np.max(np.abs(diff[~mask])) < 1e-5 * np.max(np.abs(diff[mask]))


def test_dynamic_climb_carries_the_analytical_kr_and_its_dc_gain():
    model = DynamicClimb()
    assert model.kr == KR_ANALYTICAL and model.uses_flap_rates
    ops = tuple(RotorOperatingPoint(OMEGA) for _ in range(2))
    sys = model.linear(np.array([0.0053, 0, 0, 0.0043, 0, 0]), ops)
    dc = control.dcgain(sys)
    out, inp = list(sys.output_labels), list(sys.input_labels)
    # steady Eq. 2.29: lam1s = Lbar22^-1 dC_L - K_R beta1s_dot / Omega (closed form, independent of Lbar)
    for o, u in (("lam1s_U", "beta1s_dot_U"), ("lam1c_U", "beta1c_dot_U"),
                 ("lam1s_L", "beta1s_dot_L"), ("lam1c_L", "beta1c_dot_L")):
        assert dc[out.index(o), inp.index(u)] == pytest.approx(-KR_ANALYTICAL / OMEGA, rel=1e-6)
    assert abs(dc[out.index("lam0_U"), inp.index("beta1s_dot_U")]) < 1e-10
    assert abs(dc[out.index("lam1s_L"), inp.index("beta1s_dot_U")]) < 1e-10   # no cross-rotor distortion


def test_reactionless_flap_damping_is_the_closed_form_blade_damping(clr_sys):
    rc = coaxial_compound().rotors[0]
    # rigid blade about the hinge e, lift from r0: aerodynamic damping moment per flap rate
    # c = 1/2 rho a c Omega R^4 int_r0^1 r (r - e)^2 dr (U_T = Omega r R, U_P += (r - e) R beta');
    # the reactionless mode has no hub load and no inflow, so its pole is -c/(2 I_b) +- i...
    r0, e = rc.root_cutout, rc.hinge_offset
    integral = ((1 - r0 ** 4) / 4 - 2 * e * (1 - r0 ** 3) / 3 + e ** 2 * (1 - r0 ** 2) / 2)
    c = 0.5 * 1.225 * rc.lift_slope * rc.chord * rc.omega * rc.radius ** 4 * integral
    table = classify_modes(clr_sys)
    react = table[table.physics == "reactionless flap"]
    assert len(react) == 2
    # 3 %: the closed form drops U_P/U_T ~ lam0/r ~ 5-20 % corrections that partly cancel, and the
    # profile drag (cd0/a ~ 0.2 % of lift slope); n_span = 6 Gauss points integrate r^3 exactly
    np.testing.assert_allclose(react.real, -c / (2 * rc.blade_flap_inertia), rtol=0.03)
    # undamped frequency nu Omega (the hinge spring is the only stiffness in hover)
    np.testing.assert_allclose(react.frequency, rc.flap_frequency * rc.omega, rtol=2e-3)


def test_coaxial_inertias_follow_the_hand_build_up():
    cfg, uh = coaxial_compound(), uh60_single_rotor()
    blade = 1133.0 * LB                                  # Table B.1 blade weight
    hubs = [r.hub_position[2] for r in cfg.rotors]
    blades = 4 * blade * sum(h ** 2 for h in hubs)       # parallel axis, 4 blades per rotor
    assert cfg.Ixx > blades > 12000.0                    # the old Ixx was below the blades alone
    m_fus = cfg.mass - 8 * blade
    scale = cfg.rotors[0].radius / uh.rotors[0].radius
    k2 = {a: getattr(uh, a) / uh.mass * scale ** 2 for a in ("Ixx", "Iyy", "Izz")}
    # 0.5 %: the configured values are rounded to 100 kg m^2
    assert cfg.Ixx == pytest.approx(m_fus * k2["Ixx"] + blades, rel=5e-3)
    assert cfg.Iyy == pytest.approx(m_fus * k2["Iyy"] + blades, rel=5e-3)
    assert cfg.Izz == pytest.approx(m_fus * k2["Izz"] + 8 * cfg.rotors[0].blade_flap_inertia, rel=5e-3)


def test_modes_are_named_by_physics_and_the_flap_body_mode_by_its_whirl(clr_sys):
    table = classify_modes(clr_sys)
    counts = table.physics.value_counts()
    for lab in ("coning flap", "reactionless flap", "progressive flap"):
        assert counts[lab] == 2, lab
    assert counts["regressive flap (roll)"] == 1 and counts["regressive flap (pitch)"] == 1
    for lab in ("heave", "yaw", "heading"):
        assert counts[lab] == 1
    # the light-fuselage flap-body roll mode lies above Omega and still whirls against the rotation:
    # the old Ixx = 12,000 kg m^2 puts it at ~29 rad/s > 23.7; a frequency rule would call it progressive
    light = dataclasses.replace(coaxial_compound(), Ixx=12000.0)
    t_light = classify_modes(linearize(trim(Helicopter(light, ClimbingLowerRotor(), FAST))))
    roll = t_light[t_light.physics == "regressive flap (roll)"]
    assert len(roll) == 1 and roll.frequency.iloc[0] > OMEGA
    assert (t_light.physics == "progressive flap").sum() == 2


def test_pair_modes_pairs_by_label_not_by_rank():
    ours = pd.DataFrame({"physics": ["pitch subsidence", "regressive flap (pitch)", "regressive flap (roll)"],
                         "frequency": [4.0, 13.0, 20.0], "real": [-4.0, -4.0, -3.5], "damping": [1, 0.3, 0.17]})
    ref = pd.DataFrame({"physics": ["regressive flap", "regressive flap", "pitch subsidence"],
                        "frequency": [19.9, 13.7, 4.2], "real": [-3.7, -3.7, -4.2],
                        "description": ["RF", "RF", "pitch"]})
    p = pair_modes(ours, ref).set_index("physics")
    assert p.loc["regressive flap (pitch)", "ref_frequency"] == 13.7
    assert p.loc["regressive flap (roll)", "ref_frequency"] == 19.9
    assert p.loc["pitch subsidence", "ref_frequency"] == 4.2


def test_flap_mode_damping_tracks_the_mode_through_a_loop_closure(clr_sys):
    bare = flap_mode_damping(clr_sys)
    assert set(bare.physics) == {"regressive flap (pitch)", "regressive flap (roll)"}
    plant = coupling_numerator(clr_sys, "p", "delta_lat", {"q": "delta_lon", "r": "delta_ped", "w": "delta_col"})
    held = flap_mode_damping(plant, reference=bare)
    roll = held[held.physics == "regressive flap (roll)"].iloc[0]
    pitch = held[held.physics == "regressive flap (pitch)"].iloc[0]
    assert roll.tracked and not pitch.tracked and np.isnan(pitch.damping)   # q is held: no pitch flap mode
    # a copy without the trim attached (no rotor speed known) is named by whirl sense alone
    bare_copy = control.ss(clr_sys.A, clr_sys.B, clr_sys.C, clr_sys.D, states=clr_sys.state_labels,
                           inputs=clr_sys.input_labels, outputs=clr_sys.output_labels)
    pd.testing.assert_frame_equal(flap_mode_damping(bare_copy), bare)
    # closing a loop moves the pole; zero gain must find the plant's pole exactly
    ref = bare.set_index("physics").loc["regressive flap (roll)"]
    p_ref = complex(ref.real, np.sqrt(ref.frequency ** 2 - ref.real ** 2))
    for gain in (0.0, 0.02):
        loop = control.feedback(plant, gain)
        r = flap_mode_damping(loop, reference=bare).set_index("physics").loc["regressive flap (roll)"]
        # independent: brute-force nearest closed-loop eigenvalue to the bare roll flap pole
        poles = np.linalg.eigvals(np.asarray(loop.A))
        nearest = poles[np.argmin(np.abs(poles - p_ref))]
        assert r.frequency == pytest.approx(abs(nearest), rel=1e-12)
        assert r.damping == pytest.approx(-nearest.real / abs(nearest), rel=1e-12)
    # holding q, r, w barely moves the roll flap-body mode in hover (axisymmetric coaxial, the
    # pitch/roll cross-coupling of the two counter-rotating rotors cancels to first order)
    assert held[held.physics == "regressive flap (roll)"].distance.iloc[0] < 1e-3 * abs(p_ref)


def test_flap_mode_sensitivity_to_the_fuselage_roll_inertia():
    sens = flap_mode_sensitivity(coaxial_compound(), ClimbingLowerRotor, "Ixx", [20000.0, 40000.0], FAST)
    roll = sens[sens.physics == "regressive flap (roll)"].sort_values("value")
    assert len(roll) == 2 and roll.frequency.iloc[1] < roll.frequency.iloc[0]   # heavier body: lower
    pitch = sens[sens.physics == "regressive flap (pitch)"]
    assert np.ptp(pitch.frequency) < 1e-3 * pitch.frequency.mean()            # Ixx does not move pitch
    lock = flap_mode_sensitivity(coaxial_compound(), ClimbingLowerRotor, "lock_number", [9.0], FAST)
    assert lock.lock_number.iloc[0] == pytest.approx(9.0, rel=1e-12)
    with pytest.raises(ValueError, match="parameter must be"):
        flap_mode_sensitivity(coaxial_compound(), ClimbingLowerRotor, "mass", [1.0])


def test_bare_airframe_comparison_matches_python_control_and_takes_any_model(clr_sys):
    omega = np.logspace(-1, np.log10(30), 12)
    comp = compare_bare_airframe({"CLR (given)": clr_sys, "Dynamic Climb": DynamicClimb()},
                                 omega=omega, settings=FAST)
    t = comp.to_pandas()
    assert set(t.model) == {"CLR (given)", "Dynamic Climb"} and set(t.response) == {
        "p/delta_lat", "q/delta_lon", "r/delta_ped", "w/delta_col", "p/delta_lon"}
    # independent evaluation: python-control's frequency_response of the same channel, in deg/s per rad
    sys = comp.systems["Dynamic Climb"]
    fr = control.frequency_response(sys[sys.output_labels.index("p"), sys.input_labels.index("delta_lat")], omega)
    mag_db = 20 * np.log10(np.abs(np.asarray(fr.complex).ravel()) * np.degrees(1.0))
    got = t[(t.model == "Dynamic Climb") & (t.response == "p/delta_lat")].magnitude_db.values
    np.testing.assert_allclose(got, mag_db, atol=1e-9)
    coupled = compare_bare_airframe({"CLR": clr_sys}, omega=omega, coupled=True)
    cn = coupling_numerator(clr_sys, "p", "delta_lat", {"q": "delta_lon", "r": "delta_ped", "w": "delta_col"})
    fr = control.frequency_response(cn, omega)
    got = coupled.table[coupled.table.response == "p/delta_lat"].magnitude_db.values
    np.testing.assert_allclose(got, 20 * np.log10(np.abs(np.asarray(fr.complex).ravel()) * np.degrees(1.0)),
                               atol=1e-9)
    diff = comp.difference("CLR (given)")
    assert len(diff) == 5 and (diff.max_abs_magnitude_diff_db >= 0).all()
    fig = comp.plot()
    assert len(fig.axes) == 10
    with pytest.raises(ValueError, match="empty"):
        compare_bare_airframe({})
    with pytest.raises(ValueError, match="no channel"):
        compare_bare_airframe({"CLR": clr_sys}, omega=omega, pairs=[("x", "delta_lat")])
