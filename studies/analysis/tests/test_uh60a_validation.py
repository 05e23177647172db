"""The UH-60A trim reference (NASA TM-100991 Table B.1) and the power comparison against it."""
import math

import pandas as pd
import pytest
from matplotlib.figure import Figure

from aircraft import uh60_single_rotor
from studies.analysis.uh60a_validation import (FT_LBF, HP, KNOT, REFERENCE_FILE, compare_power, isa_density,
                                               ours_at_reference, plot_uh60a_validation, reference_trims,
                                               uh60a_validation)


def test_reference_file_reads_with_its_units():
    ref = reference_trims()
    assert ref["condition"].tolist() == ["hover", "level_80kt", "descent_80kt"]
    assert ref["level"].tolist() == [True, True, False]
    # 16825 lb x 0.45359237 kg/lb = 7631.69 kg; sea level, so true airspeed = equivalent: 80 kt = 41.156 m/s
    assert ref["mass"].tolist() == pytest.approx([7631.69] * 3, abs=0.01)
    assert ref["rho"].tolist() == pytest.approx([1.225] * 3)
    assert ref["speed"].tolist() == pytest.approx([0.0, 41.1556, 41.1556], abs=1e-4)
    # hand: 2 engines x 911.1 hp x 0.745700 kW/hp = 1358.8 kW; 2 x 552.6 x 0.7457 = 824.1 kW
    assert ref["power_engines"].iloc[:2].tolist() == pytest.approx([1358.8, 824.1], abs=0.1)
    # hand: 32865 ft lbf x 1.355818 N m / (ft lbf) = 44559 N m
    assert ref["torque_hub"].iloc[0] == pytest.approx(44559.0, abs=1.0)
    assert (HP, FT_LBF, KNOT) == pytest.approx((745.700, 1.355818, 0.514444), rel=1e-6)


def test_transcription_is_self_consistent():
    # each engine's printed torque times the printed power-turbine speed must give its printed
    # horsepower: independent of our code and of the transcription of the power column. The printed
    # power carries 0.1 hp (0.03 % of the smallest, 302.6 hp), the torque 4 figures: 0.05 % covers both
    ref = pd.read_csv(REFERENCE_FILE, comment="#")
    power = ref["engine_torque_shaft_ft_lbf"] * ref["power_turbine_speed_rpm"] * 2.0 * math.pi / 60.0 / 550.0
    assert power.tolist() == pytest.approx(ref["power_per_engine_hp"].tolist(), rel=5e-4)


def test_missing_column_and_bad_values_are_named(tmp_path):
    text = REFERENCE_FILE.read_text()
    bad = tmp_path / "bad.csv"
    bad.write_text(text.replace("power_per_engine_hp", "power_hp"))
    with pytest.raises(ValueError, match="power_per_engine_hp"):
        reference_trims(bad)
    bad.write_text(text.replace("911.1", "n/a"))
    with pytest.raises(ValueError, match="finite"):
        reference_trims(bad)


def test_equivalent_airspeed_becomes_true_airspeed_at_altitude(tmp_path):
    # ISA at 5000 ft (1524 m): 1.0555 kg/m^3 (standard-atmosphere table); TAS = EAS sqrt(rho0 / rho)
    assert isa_density(1524.0) == pytest.approx(1.0555, abs=1e-4)
    high = tmp_path / "high.csv"
    high.write_text(REFERENCE_FILE.read_text().replace("hover,16825.0,0.0,0.0,0.0", "hover,16825.0,0.0,0.0,5000.0")
                    .replace("level_80kt,16825.0,80.0,0.0,0.0", "level_80kt,16825.0,80.0,0.0,5000.0"))
    ref = reference_trims(high)
    assert ref["speed"].iloc[1] == pytest.approx(80.0 * KNOT * math.sqrt(1.225 / 1.0555), rel=1e-4)
    with pytest.raises(ValueError, match="altitude"):
        isa_density(-10.0)


def test_compare_power_against_hand_values():
    ref = reference_trims()
    ours = pd.DataFrame({"condition": ["hover", "level_80kt", "descent_80kt"], "converged": [True, False, True],
                         "power_total": [1300.0, 700.0, 400.0]})
    t = compare_power(ref, ours, omega=27.0, fuselage_fx=2.0)
    # the unconverged level trim is left out; every converged condition the reference holds is compared
    assert t["condition"].tolist() == ["hover", "hover", "descent_80kt", "descent_80kt"]
    hover = t[t["condition"] == "hover"].set_index("quantity")
    # hand: 1358.8 kW (engines); hub 44559 N m x 27.0 rad/s = 1203.1 kW
    assert hover.loc["power, engine output", "measured"] == pytest.approx(1358.8, abs=0.1)
    assert hover.loc["power, hub required torque x Omega", "measured"] == pytest.approx(1203.1, abs=0.1)
    assert (hover["difference"] == hover["ours"] - hover["measured"]).all()
    assert hover["relative_difference"].tolist() == pytest.approx((-58.8 / 1358.8, 96.9 / 1203.1), abs=1e-4)
    # 80 kt: 1/2 rho V^3 = 0.5 x 1.225 x 41.156^3 = 42.7 kW per m^2 of flat plate, 85 kW for 2.0 m^2
    assert "85 kW here, 43 kW per m^2" in t["explanation"].iloc[2]
    assert set(t["unit"]) == {"kW"}
    with pytest.raises(ValueError, match="omega"):
        compare_power(ref, ours, omega=0.0)
    with pytest.raises(ValueError, match="power_total"):
        compare_power(ref, ours.drop(columns=["power_total"]), omega=27.0)


def test_ours_is_trimmed_at_the_reference_weight_and_level_conditions_only():
    ref = reference_trims()
    ours = ours_at_reference(ref)
    assert ours["condition"].tolist() == ["hover", "level_80kt"]
    assert ours["mass"].tolist() == pytest.approx([7631.69, 7631.69], abs=0.01)
    assert ours["speed"].tolist() == pytest.approx([0.0, 41.1556], abs=1e-4)
    own = ours_at_reference(ref, match_weight=False)
    assert own["mass"].tolist() == pytest.approx([uh60_single_rotor().mass] * 2)
    # lighter by 325 lb (1.9 %): less hover power (induced power ~ W^1.5 to first order)
    assert (ours["power_total"] < own["power_total"]).all()
    with pytest.raises(ValueError, match="level"):
        ours_at_reference(ref[~ref["level"]])


def test_validation_table_and_figure():
    t = uh60a_validation()
    assert list(t.columns[:7]) == ["condition", "speed", "speed_kt", "quantity", "ours", "measured", "difference"]
    hover = t[t["condition"] == "hover"]
    # the reference's own two hover figures differ by 11 % (1203 against 1359 kW); a hover model
    # that lies more than 10 % outside either has a modelling error beyond the reference's spread
    assert (hover["relative_difference"].abs() < 0.10).all()
    fig = plot_uh60a_validation(t, sweep=pd.DataFrame({"speed": [0.0, 40.0], "converged": [True, True],
                                                       "power_total": [1300.0, 700.0]}))
    assert isinstance(fig, Figure) and len(fig.axes[0].lines) == 4
