"""Why the main job holds u and v in its roll design plants (README, "What the main job computes").

The design plant's minimal realisation (controllers.roll_design_plant, tolerance 1e-3)
removes the translational drift from the Dynamic-Climb aircraft's plant, but not from
an identified-inflow aircraft's; holding u and v (aircraft.helicopter.hold.hold_states)
treats every aircraft alike.
"""
import control
import numpy as np
import pytest

from aircraft.configs import coaxial_compound
from aircraft.helicopter import HelicopterSettings, linearize, trim
from aircraft.helicopter.hold import hold_states
from aircraft.helicopter.tilt_coupling import helicopter_for
from aircraft.identification.tilt_inputs import tilt_inflow_from_record
from aircraft.inflow import DynamicClimb
from controllers import roll_design_plant

W = np.array([0.01, 0.03, 0.1, 0.3, 1.0, 3.0])     # rad/s: below and into the design band


def _plants(inflow):
    sys = linearize(trim(helicopter_for(coaxial_compound(), inflow, HelicopterSettings(n_span=8, n_average=1))))
    free, held = roll_design_plant(sys), roll_design_plant(hold_states(sys, ["u", "v"]))
    return [np.array([complex(p.system(1j * w)) for w in W]) for p in (free, held)], held


def test_the_reduction_already_holds_the_drift_of_the_dynamic_climb_plant():
    (free, held), _ = _plants(DynamicClimb())
    # measured: 0.1 dB and 1 deg; 0.3 dB / 2 deg leaves room for round-off in the trim
    assert np.abs(20 * np.log10(np.abs(free / held))).max() < 0.3
    assert np.degrees(np.abs(np.angle(free / held))).max() < 2.0


def test_it_does_not_for_our_identified_12_state_and_holding_removes_the_slow_rhp_zero():
    (free, held), plant = _plants(tilt_inflow_from_record("coaxial_hover_12state_tilt"))
    # free drift: at 0.01 rad/s the reduced plant is ~40 dB below the held one
    assert 20 * np.log10(np.abs(held[0] / free[0])) > 20.0
    zeros = np.asarray(control.zeros(plant.system), dtype=complex)
    assert not np.any((zeros.real > 0) & (np.abs(zeros) < 0.5))
