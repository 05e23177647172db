"""The README API tour's control half, run as written (library calls only)."""
import numpy as np


def test_readme_api_tour_from_linearize_to_a_dmo_design():
    # --- README snippet (keep identical to the README's API tour) ---
    import controllers
    from aircraft import coaxial_compound
    from aircraft.inflow import DynamicClimb
    from aircraft.helicopter import Helicopter, HelicopterSettings, trim, linearize

    heli = Helicopter(coaxial_compound(), DynamicClimb(), HelicopterSettings(n_span=8, n_average=1))
    sys = linearize(trim(heli))                         # control.StateSpace, named signals
    plant = controllers.roll_design_plant(sys)          # p/delta_lat | q, r, w held (Eq. 7.21)
    design = controllers.EMFDesign(plant, controllers.PIDGains(0.3, 0.1, 0.05),
                                   controllers.CommandModel(4.0, 0.7, 0.05),
                                   controllers.second_order_actuator(35.0, 0.7), sensor_delay=0.01)
    result = controllers.dmo(design)                    # raises InfeasibleDesignError if nothing is feasible
    result.history                                      # boundaries, gains, most limiting spec per step
    table = controllers.evaluate_specs(result.design)   # Table 7.3 specs: value, level, margin, status
    fig = controllers.hq_window([result.design], controllers.default_specs())
    # --- end of snippet ---
    assert result.crossover > 1.5 and np.all(result.design.gains.as_array() >= 0)
    assert {"value", "level", "margin", "met", "status"} <= set(table.columns)
    assert fig.axes
