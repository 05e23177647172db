"""The printed models as data: internal consistency of the dissertation's numbers,
and the coaxial models (DynamicClimb with K_R, IsolatedRotors) against closed forms."""
import control
import numpy as np
import pytest

from aircraft.inflow import (KR_ANALYTICAL, DynamicClimb, IsolatedRotors, PittPeters, RotorOperatingPoint,
                             published)

OMEGA_UH60 = 27.0


def test_table_pitt_peters_rows_are_the_closed_form_at_a_lower_thrust():
    t1, t2 = published.TABLE_4_1["Pitt-Peters (Ref. 25)"], published.TABLE_4_2["Pitt-Peters (Ref. 25)"]
    # M/Omega rows: 8/(3 pi)/27 = 0.03144 and -16/(45 pi)/27 = -0.00419, printed to 3 and 2 figures
    assert t1["M11/Omega"] == pytest.approx(8 / (3 * np.pi) / OMEGA_UH60, abs=5e-5)
    assert t2["M22/Omega"] == pytest.approx(-16 / (45 * np.pi) / OMEGA_UH60, abs=5e-5)
    # Lbar11 = 4 lam_h and Lbar22 = -lam_h give the same lam_h to print rounding (0.0005 / 4)...
    assert t1["Lbar11"] / 4 == pytest.approx(-t2["Lbar22"], abs=2e-4)
    # ...but not the nominal C_T = 0.0061 (lam_h = 0.0552): documented as a suspected slip
    assert abs(-t2["Lbar22"] - np.sqrt(0.0061 / 2)) > 1e-3


def test_eqs_4_7_4_8_are_m_over_omega_as_the_section_4_5_averages_say():
    # §4.5: "the average of the identified M22 and M33 values is -0.0052"
    m22 = [published.UH60_HOVER_MFW.M[1, 1], published.UH60_MU01_MFW.M[1, 1], published.UH60_MU02_MFW.M[1, 1]]
    assert np.mean(m22) == pytest.approx(-0.0052, abs=5e-5)       # printed to 2 figures
    for model in (published.UH60_MU01_MFW, published.UH60_MU02_MFW):
        assert model.time == "seconds"
        np.testing.assert_allclose(model.M_seconds, model.M)


def test_every_published_model_has_named_signals_and_consistent_shapes():
    for key, model in published.PUBLISHED_MODELS.items():
        n = 3 * len(model.rotors)
        assert model.output_names[:3] == [f"lam0{'_U' if model.rotors[0] == 'U' else ''}",
                                          f"lam1s{'_U' if model.rotors[0] == 'U' else ''}",
                                          f"lam1c{'_U' if model.rotors[0] == 'U' else ''}"], key
        assert model.omega > 0 and "flight" in model.condition, key
        if hasattr(model, "F"):
            assert model.F.shape == (2 * n, 2 * n) and model.G.shape == (2 * n, len(model.input_order)), key
            assert sorted(model.input_order) == sorted(model.input_names), key
        else:
            assert model.M.shape == model.Lbar.shape == model.tau.shape == (n, n), key
            assert np.all(model.tau >= 0), key


def test_isolated_rotors_are_two_independent_pitt_peters_rotors():
    loads = np.array([0.0053, 0.0, 0.0, 0.0043, 0.0, 0.0])
    ops = tuple(RotorOperatingPoint(23.7, mu=0.05) for _ in range(2))
    both = IsolatedRotors().linear(loads, ops)
    upper = PittPeters().linear(loads[:3], ops[:1])
    lower = PittPeters().linear(loads[3:], ops[1:])
    # the oracle is the single-rotor model: block-diagonal, no cross terms (round-off of the FD Jacobian)
    np.testing.assert_allclose(both.A[:3, :3], upper.A, rtol=1e-7)
    np.testing.assert_allclose(both.A[3:, 3:], lower.A, rtol=1e-7)
    assert np.max(np.abs(both.A[:3, 3:])) == 0 and np.max(np.abs(both.A[3:, :3])) == 0
    assert both.input_labels == ["CT_U", "CL_U", "CM_U", "CT_L", "CL_L", "CM_L"]


def test_dynamic_climb_coupling_term_matches_hand_derivative():
    ct_u, ct_l, omega = 0.0053, 0.0043, 23.7
    loads = np.array([ct_u, 0, 0, ct_l, 0, 0])
    ops = tuple(RotorOperatingPoint(omega) for _ in range(2))
    sys = DynamicClimb().linear(loads, ops)
    lu, ll = sys.trim_states[0], sys.trim_states[3]
    m11 = 8 / (3 * np.pi)
    # hover thrust row of the upper rotor: M11 lam0U' = C_T^U - 2 (lam0U + 0.86 lam0L) lam0U (azimuth)
    # d/d lam0L = -2 * 0.86 * lam0U ; d/d lam0U = -(4 lam0U + 2 * 0.86 lam0L); seconds: times Omega
    assert sys.A[0, 3] == pytest.approx(-omega / m11 * 2 * 0.86 * lu, rel=1e-6)
    assert sys.A[0, 0] == pytest.approx(-omega / m11 * (4 * lu + 2 * 0.86 * ll), rel=1e-6)
    assert sys.A[3, 0] == pytest.approx(-omega / m11 * 2 * 1.13 * ll, rel=1e-6)
    # the harmonics stay uncoupled between rotors (§2.2.2.4)
    assert abs(sys.A[1, 4]) < 1e-9 and abs(sys.A[2, 5]) < 1e-9
    # the blade sees the state plus the other rotor's climb (Eqs. 2.8-2.9): C row 0 = [1, 0, 0, 0.86, 0, 0]
    np.testing.assert_allclose(sys.C[0], [1, 0, 0, 0.86, 0, 0], atol=1e-8)


def test_dynamic_climb_with_analytical_kr_takes_flap_rates():
    model = DynamicClimb(kr=KR_ANALYTICAL)
    assert model.uses_flap_rates
    assert model.input_names[6:] == ["beta1s_dot_U", "beta1c_dot_U", "beta1s_dot_L", "beta1c_dot_L"]
    ops = tuple(RotorOperatingPoint(23.7) for _ in range(2))
    dc = control.dcgain(model.linear(np.array([0.0053, 0, 0, 0.0043, 0, 0]), ops))
    # Eq. 2.29 at steady state: lam1s = Lbar^-1 dC_L - K_R beta1s_dot / Omega on each rotor
    for k, (i_out, i_in) in enumerate(((1, 6), (2, 7), (4, 8), (5, 9))):
        assert dc[i_out, i_in] == pytest.approx(-1.5 / 23.7, rel=1e-6), k
    assert abs(dc[0, 6]) < 1e-9 and abs(dc[4, 6]) < 1e-9       # no cross-rotor wake distortion
