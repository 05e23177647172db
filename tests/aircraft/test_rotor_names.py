"""Rotor names come from the aircraft: a coaxial with its rotors renamed gives the
same numbers as the default ``U``/``L`` one, with the new names on every signal.

The reference is the default-named model itself: renaming changes labels only, so
every matrix must agree exactly (same arithmetic in the same order), and every
signal name must be the default one with its rotor suffix replaced.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from aircraft.configs import coaxial_compound
from aircraft.helicopter import Helicopter, HelicopterSettings, TrimCondition, linearize, trim
from aircraft.identification.design_space import DesignSpaceError, _design_structure, _for_rotors, spaced_config
from aircraft.identification.structures import Coaxial6State, Coaxial12StateTilt
from aircraft.inflow import (DynamicClimb, IdentifiedInflow, InflowError, IsolatedRotors, ScheduledInflow,
                             check_rotor_names, config_rotor_names)
from aircraft.inflow.frames import COAXIAL_DIRECTIONS, FrameError, rotor_directions

NAMES = ("upper", "lower")


def _renamed(config, names=NAMES):
    upper, lower = config.rotors
    return dataclasses.replace(config, rotors=(dataclasses.replace(upper, name=names[0]),
                                               dataclasses.replace(lower, name=names[1])))


def _rename(label):
    """The default label with the new rotor names (``lam0_U`` -> ``lam0_upper``)."""
    for old, new in zip(("_U", "_L"), ("_upper", "_lower")):
        if label.endswith(old):
            return label[:-len(old)] + new
    return label


def _values(structure):
    """Fixed parameter values giving a stable model: F diagonals -1 per rev, the rest
    small and pseudo-random (a fixed seed), delays 20 ms."""
    rng = np.random.default_rng(7)
    out = {}
    for name in structure.parameter_names():
        row_col = name[1:].split("_")
        if name.startswith("t"):
            out[name] = 0.02
        elif name.startswith("f") and len(row_col) == 2 and row_col[0] == row_col[1]:
            out[name] = -1.0
        else:
            out[name] = 0.05 * float(rng.standard_normal())
    return out


# -- names --------------------------------------------------------------------------


def test_config_names_and_directions_follow_the_configuration():
    cfg = _renamed(coaxial_compound())
    assert config_rotor_names(cfg) == NAMES
    assert rotor_directions(cfg) == {"upper": 1, "lower": -1}
    assert rotor_directions(coaxial_compound()) == COAXIAL_DIRECTIONS


@pytest.mark.parametrize("bad, match", [(("U", "U"), "distinct"), (("U",), "2 rotor"), ("UL", "not the string"),
                                        (("U", "a_b"), "signal suffix"), (("U", ""), "signal suffix")])
def test_bad_rotor_names_are_refused(bad, match):
    with pytest.raises(ValueError, match=match):
        check_rotor_names(bad, 2)
    with pytest.raises(InflowError, match=match):
        DynamicClimb(rotors=bad)
    with pytest.raises(ValueError, match=match):
        Coaxial6State(rotors=bad)


def test_config_names_that_are_no_signal_suffix_are_refused():
    # AircraftConfig refuses repeated names itself; a name with "_" it accepts, but
    # "lam0_up_per" could not be split back into signal and rotor
    cfg = _renamed(coaxial_compound(), ("up_per", "lower"))
    with pytest.raises(FrameError, match="signal suffix"):
        rotor_directions(cfg)
    with pytest.raises(DesignSpaceError, match="signal suffix"):
        spaced_config(cfg, 0.2)
    with pytest.raises(ValueError, match="signal suffix"):
        config_rotor_names(cfg)


# -- structures -----------------------------------------------------------------------


def test_hover_6state_model_same_matrices_new_names():
    default, renamed = Coaxial6State(), Coaxial6State(rotors=NAMES)
    values = {"m11": 0.85, "m44": 0.85, "m22": -0.11, "m55": -0.11, "m14": 0.1, "m41": 0.2, "m25": 0.05,
              "m52": 0.04, "l11": 0.2, "l14": 0.05, "l41": 0.1, "l44": 0.25, "l22": -0.05, "l25": 0.01,
              "l52": 0.02, "l55": -0.06, "t11": 0.02, "t14": 0.05, "t22": 0.02, "t25": 0.05, "t41": 0.05,
              "t44": 0.02, "t52": 0.05, "t55": 0.02}
    a, b = default.to_inflow(values, 40.0), renamed.to_inflow(values, 40.0)
    for m in ("A", "B", "C", "D"):
        np.testing.assert_array_equal(getattr(a.system, m), getattr(b.system, m))
    assert b.system.input_labels == [_rename(n) for n in a.system.input_labels]
    assert b.system.output_labels == [_rename(n) for n in a.system.output_labels]
    assert b.rotors == NAMES
    assert renamed.controls == [_rename(c) for c in default.controls]
    # the default structure's hash input is unchanged; the renamed one says so
    assert "rotors" not in default.spec() and renamed.spec()["rotors"] == list(NAMES)
    assert Coaxial6State().with_rotors(NAMES).spec() == renamed.spec()


def test_tilt_12state_structure_and_model_same_numbers_new_names():
    default, renamed = Coaxial12StateTilt(), Coaxial12StateTilt(rotors=NAMES)
    values = _values(default)
    assert renamed.parameter_names() == default.parameter_names()
    fa, fb = default.build(values, 40.0), renamed.build(values, 40.0)
    ma, mb = fa.matrices(), fb.matrices()
    assert set(ma) == set(mb)
    for k in ma:
        np.testing.assert_array_equal(ma[k], mb[k])
    assert fb.inputs == [_rename(n) for n in fa.inputs] and fb.outputs == [_rename(n) for n in fa.outputs]
    assert renamed.states == [_rename(n) for n in default.states]
    a, b = default.to_inflow(values, 40.0), renamed.to_inflow(values, 40.0)
    for m in ("A", "B", "C"):
        np.testing.assert_array_equal(getattr(a.system, m), getattr(b.system, m))
    assert b.input_names == [_rename(n) for n in a.input_names]
    assert b.tilt_names == ["beta1s_upper", "beta1c_upper", "beta1s_lower", "beta1c_lower"]
    np.testing.assert_array_equal(a.tilt_matrix, b.tilt_matrix)


# -- the aircraft with Dynamic Climb ----------------------------------------------------------


@pytest.mark.parametrize("inputs", ["pilot", "rotor"])
def test_dynamic_climb_aircraft_same_linear_model_new_names(inputs):
    settings = HelicopterSettings(n_span=4, n_average=2)    # coarse: the comparison is exact at any resolution
    cfg = coaxial_compound()
    ren = _renamed(cfg)
    a = linearize(trim(Helicopter(cfg, DynamicClimb(), settings), TrimCondition()), inputs=inputs)
    b = linearize(trim(Helicopter(ren, DynamicClimb(rotors=config_rotor_names(ren)), settings), TrimCondition()),
                  inputs=inputs)
    np.testing.assert_array_equal(a.A, b.A)
    np.testing.assert_array_equal(a.B, b.B)
    assert b.state_labels == [_rename(n) for n in a.state_labels]
    assert b.input_labels == [_rename(n) for n in a.input_labels]
    assert "lam0_lower" in b.state_labels and "beta1s_upper" in b.state_labels
    if inputs == "rotor":
        assert b.input_labels[:3] == ["theta0_upper", "theta1s_upper", "theta1c_upper"]


def test_mode_physics_reads_the_aircraft_rotor_names():
    from aircraft.helicopter.mode_physics import classify_modes, state_group
    settings = HelicopterSettings(n_span=4, n_average=2)
    cfg = coaxial_compound()
    ren = _renamed(cfg)
    a = classify_modes(linearize(trim(Helicopter(cfg, DynamicClimb(), settings), TrimCondition())))
    b = classify_modes(linearize(trim(Helicopter(ren, DynamicClimb(rotors=NAMES), settings), TrimCondition())))
    assert list(b.physics) == list(a.physics)
    assert state_group("beta1s_upper", NAMES) == "cyclic_flap" and state_group("beta1s_upper") == "other"


def test_inflow_with_default_names_is_refused_by_a_renamed_aircraft():
    with pytest.raises(ValueError, match="do not match"):
        Helicopter(_renamed(coaxial_compound()), IsolatedRotors())


def test_identified_inflow_renamed_and_inferred():
    m = IdentifiedInflow.from_matrices(np.diag([0.8, -0.1, -0.1] * 2), np.diag([0.2, -0.05, -0.05] * 2),
                                       omega=40.0)
    r = m.with_rotors(NAMES)
    np.testing.assert_array_equal(m.system.A, r.system.A)
    assert r.output_names == [_rename(n) for n in m.output_names]
    assert IdentifiedInflow(r.system).rotors == NAMES      # inferred from the output names
    with pytest.raises(InflowError, match="2 rotor"):
        m.with_rotors(("a",))


# -- design space -------------------------------------------------------------------------


def test_spaced_config_keeps_renamed_rotors():
    cfg = _renamed(coaxial_compound())
    default, renamed = spaced_config(coaxial_compound(), 0.2), spaced_config(cfg, 0.2)
    assert [r.name for r in renamed.rotors] == list(NAMES)
    # only the names differ: the moved hub is where the default's is
    assert renamed.rotors[1].hub_position == default.rotors[1].hub_position
    assert renamed.rotors[0].hub_position == default.rotors[0].hub_position


def test_design_structure_takes_the_configuration_names():
    struct, _ = _design_structure("coaxial_6state")
    renamed = _for_rotors(struct, NAMES)
    assert renamed.outputs[0] == "lam0_upper" and struct.outputs[0] == "lam0_U"   # a copy, not the shared one
    with pytest.raises(DesignSpaceError, match="do not match"):
        _for_rotors(Coaxial6State(rotors=("a", "b")), NAMES)


def test_schedule_for_a_renamed_aircraft_has_its_names():
    n = 6
    grid = {"M": np.broadcast_to(np.diag([0.85, -0.11, -0.11] * 2), (2, 1, n, n)),
            "Lbar": np.broadcast_to(np.diag([0.2, -0.05, -0.05] * 2), (2, 1, n, n)),
            "tau": np.zeros((2, 1, n, n)), "loads_ref": np.zeros((2, 1, n)), "inflow_ref": np.zeros((2, 1, n))}
    sched = ScheduledInflow((0.1, 0.3), (0.0096,), omega=40.0, spacing=0.1, ct=0.0096, **grid)
    cfg = spaced_config(_renamed(coaxial_compound()), 0.2)
    a = sched.for_aircraft(spaced_config(coaxial_compound(), 0.2), ct=0.0096)
    b = sched.for_aircraft(cfg, ct=0.0096)
    np.testing.assert_array_equal(a.system.A, b.system.A)
    assert b.output_names == [_rename(x) for x in a.output_names]


def test_structure_for_rotors_renames_defaults_only():
    s = Coaxial12StateTilt()
    assert s.for_rotors(("U", "L")) is s
    assert s.for_rotors(NAMES).inputs[0] == "CT_upper"
    with pytest.raises(ValueError, match="has rotors"):
        Coaxial6State(rotors=("a", "b")).for_rotors(NAMES)


def test_pipeline_refuses_a_structure_named_for_other_rotors_before_any_wake_run():
    from aircraft.identification import PipelineError, identify_inflow
    with pytest.raises(PipelineError, match="has rotors"):
        identify_inflow(_renamed(coaxial_compound()), None, Coaxial6State(rotors=("a", "b")), cache_dir=None,
                        progress=False)
