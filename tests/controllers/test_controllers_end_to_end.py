"""The control half of the library end to end: trim -> linearize -> roll design plant -> EMF -> DMO -> specs.

Library calls only, on the Dynamic-Climb coaxial in hover (a shorter path than
``examples/aircraft_to_design.py``, which the tour runs in full).
"""
import pytest
import numpy as np


@pytest.mark.slow
def test_from_linearize_to_a_dmo_design():
    import controllers
    from aircraft import coaxial_compound
    from aircraft.inflow import DynamicClimb
    from aircraft.helicopter import Helicopter, HelicopterSettings, trim, linearize
    from aircraft.helicopter.hold import hold_states

    heli = Helicopter(coaxial_compound(), DynamicClimb(), HelicopterSettings(n_span=8, n_average=1))
    sys = linearize(trim(heli))                         # control.StateSpace, named signals
    # p/delta_lat | q, r, w held (Eq. 7.21), u and v held by an assumed outer loop
    plant = controllers.roll_design_plant(hold_states(sys, ["u", "v"]))
    design = controllers.EMFDesign(plant, controllers.PIDGains(0.3, 0.1, 0.05),
                                   controllers.CommandModel(4.0, 0.7, 0.05),
                                   controllers.second_order_actuator(35.0, 0.7), sensor_delay=0.01)
    result = controllers.dmo(design)                    # raises InfeasibleDesignError if nothing is feasible
    result.history                                      # boundaries, gains, most limiting spec per step
    table = controllers.evaluate_specs(result.design)   # Table 7.3 specs: value, level, margin, status
    fig = controllers.hq_window([result.design], controllers.default_specs())
    assert result.crossover > 1.5 and np.all(result.design.gains.as_array() >= 0)
    assert {"value", "level", "margin", "met", "status"} <= set(table.columns)
    assert fig.axes
