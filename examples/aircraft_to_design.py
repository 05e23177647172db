"""Tour, part 2: from an aircraft to a flight-control design.

The coaxial compound is trimmed in hover with the Dynamic-Climb inflow model and
linearised; the roll-axis plant is the coupling numerator p/delta_lat with pitch,
yaw and heave constrained (Eq. 7.21); an explicit-model-following design is
tuned by the CasADi design-margin optimisation against ADS-33-style specs and
re-checked with python-control.

Runs in about a minute; ``rotorwake main`` does this for three cases A/B/C.
"""
import controllers
from aircraft import coaxial_compound
from aircraft.helicopter import Helicopter, HelicopterSettings, linearize, modes, trim
from aircraft.helicopter.hold import hold_states
from aircraft.inflow import DynamicClimb

# 1. aircraft + inflow model -> trim -> linear model with named signals
heli = Helicopter(coaxial_compound(), DynamicClimb(), HelicopterSettings(n_span=8, n_average=1))
hover = trim(heli)                            # hover by default
print(f"trim residual {hover.max_residual:.1e}, C_T upper/lower "
      f"{hover.loads['CT_U']:.5f}/{hover.loads['CT_L']:.5f}")
aircraft = linearize(hover)                   # control.StateSpace: pilot inputs delta_col ... delta_prop
print(modes(aircraft)[["frequency", "damping", "dominant_states"]].head(8).to_string(index=False))

# 2. the single-axis roll plant p/delta_lat with pitch, yaw and heave held
#    (Eq. 7.21), and the translational drift u, v held by an assumed position-hold
#    outer loop (left free, the hover phugoid and the drift's zero at the origin
#    leave no design). roll_design_plant drops psi (a pure integrator that feeds
#    back into nothing), takes the exact coupling numerator, residualises its fast
#    constraint-loop poles above 60 rad/s and takes a minimal realisation.
plant = controllers.roll_design_plant(hold_states(aircraft, ["u", "v"]))

# 3. explicit model following (Fig. 7.12): command model, actuator, sensor delay,
#    PID starting gains; then DMO raises the crossover and DRB boundaries
design = controllers.EMFDesign(
    plant, controllers.PIDGains(0.3, 0.1, 0.05),
    controllers.CommandModel(frequency=4.0, damping=0.7, gain=0.05),   # [rad/s], [-], [rad/s per stick]
    controllers.second_order_actuator(35.0, 0.7),                      # [rad/s], [-]
    sensor_delay=0.01)                                                 # [s]
result = controllers.dmo(design, progress=False)   # raises InfeasibleDesignError if nothing is feasible
print(result.message)

# 4. the design's specs (Table 7.3), re-checked with python-control, and its HQ window
specs = controllers.default_specs(result.crossover_boundary, result.drb_boundary)
table = controllers.evaluate_specs(result.design, specs)
print(table[["spec", "value", "level", "met"]].to_string(index=False))
controllers.hq_window([result.design], specs, labels=["DC design"]).savefig("tour_hq_window.png", dpi=70)
