"""Why the main job holds u and v in its roll design plants.

With the lateral stick on theta1s (Eq. 7.19) the design plant's minimal realisation
(controllers.roll_design_plant, tolerance 1e-3) no longer removes the translational
drift from any aircraft's plant, the Dynamic-Climb one included (with the former
theta1c pairing it happened to remove it from that plant alone); holding u and v
(aircraft.helicopter.hold.hold_states) treats every aircraft alike and leaves the
design band as it is.
"""
import control
import numpy as np

from aircraft.configs import coaxial_compound
from aircraft.helicopter import HelicopterSettings, linearize, trim
from aircraft.helicopter.hold import hold_states
from aircraft.helicopter.tilt_coupling import helicopter_for
from aircraft.identification.structures.tilt import tilt_inflow_from_record
from aircraft.inflow import DynamicClimb
from controllers import roll_design_plant

W = np.array([0.01, 0.03, 0.1, 0.3, 1.0, 3.0])     # rad/s: below and into the design band


def _plants(inflow):
    sys = linearize(trim(helicopter_for(coaxial_compound(), inflow, HelicopterSettings(n_span=8, n_average=1))))
    free, held = roll_design_plant(sys), roll_design_plant(hold_states(sys, ["u", "v"]))
    return [np.array([complex(p.system(1j * w)) for w in W]) for p in (free, held)], held


def test_the_dynamic_climb_plant_keeps_its_drift_unless_held():
    (free, held), _ = _plants(DynamicClimb())
    ratio_db = 20 * np.log10(np.abs(free / held))
    # measured: -62 dB at 0.01 rad/s (the drift's zero at the origin), 1.2-1.4 dB at
    # 1-3 rad/s: the hold changes the plant below the design band, hardly inside it
    assert ratio_db[0] < -20.0
    assert np.abs(ratio_db[W >= 1.0]).max() < 2.0


def test_it_does_not_for_our_identified_12_state_and_holding_removes_the_slow_rhp_zero():
    (free, held), plant = _plants(tilt_inflow_from_record("coaxial_hover_12state_tilt"))
    # free drift: at 0.01 rad/s the reduced plant is ~40 dB below the held one
    assert 20 * np.log10(np.abs(held[0] / free[0])) > 20.0
    zeros = np.asarray(control.zeros(plant.system), dtype=complex)
    assert not np.any((zeros.real > 0) & (np.abs(zeros) < 0.5))
