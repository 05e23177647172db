import pytest

from aircraft.configs import RotorConfig, coaxial_compound, uh60_single_rotor


def test_uh60_solidity_and_thrust_coefficient_match_appendix_b1():
    cfg = uh60_single_rotor()
    rotor = cfg.rotors[0]
    # Appendix B.1 prints sigma = 0.0821 and C_T = 0.0061 at 17,150 lb, sea level.
    assert rotor.solidity == pytest.approx(0.0821, abs=5e-5)
    assert cfg.weight / rotor.thrust_scale(cfg.rho) == pytest.approx(0.0061, rel=0.01)


def test_coaxial_weight_split_matches_hover_trim_thrusts():
    cfg = coaxial_compound()
    upper, lower = cfg.rotors
    total_ct = cfg.weight / upper.thrust_scale(cfg.rho)
    # Table B.1 weight on the two rotors must equal C_T^U + C_T^L of the hover trim (0.0053 + 0.0043).
    assert total_ct == pytest.approx(sum(cfg.trim_ct), rel=0.01)
    assert upper.direction == -lower.direction
    spacing = lower.hub_position[2] - upper.hub_position[2]
    assert spacing == pytest.approx(0.14 * upper.radius)
    assert coaxial_compound(cruise=True).rotors[0].omega == 20.3


def test_rotor_config_rejects_bad_values():
    with pytest.raises(ValueError, match="radius must be positive"):
        RotorConfig(name="", radius=-1.0, omega=20.0, n_blades=4, chord=0.5, twist=0.0, root_cutout=0.1)
    with pytest.raises(ValueError, match="n_blades"):
        RotorConfig(name="", radius=8.0, omega=20.0, n_blades=1, chord=0.5, twist=0.0, root_cutout=0.1)
    with pytest.raises(KeyError, match="no rotor named"):
        coaxial_compound().rotor("X")
