"""Tour, part 3: every loop of the aircraft designed at once (pitch, roll, yaw, heave).

The coaxial compound's hover linear model (all 31 states, the cross-couplings
included) gets one explicit-model-following loop per axis. Each axis's specs are
selected by axis and mission task element (ADS-33E-PRF boundaries as data); the
design-margin optimisation tunes the axes in turn, each on its effective plant
with the other loops closed, until no gain moves; every spec is then graded on
the simultaneous closed loop. A spec whose boundary values the library lacks
is graded once the user supplies them (the last step).

Runs in about half a minute with the small optimiser budgets below. ``rotorwake
multi-axis-hover-design`` runs it with the full ones, checks that no joint choice of
all twelve gains beats the sequential answer
(:func:`controllers.multi_axis_joint.joint_check`, a few minutes) and writes the
report (:func:`controllers.multi_axis_report.write_multi_axis_report`).
"""
from aircraft import coaxial_compound
from aircraft.helicopter import Helicopter, HelicopterSettings, linearize, trim
from aircraft.helicopter.hold import hold_states
from aircraft.inflow import DynamicClimb
from controllers import DMOSettings, design_multi_axis, evaluate_specs, specs_for

# 1. the full linear aircraft; the translational drift u, v held by an assumed
#    position-hold outer loop, as in the single-axis design of part 2
heli = Helicopter(coaxial_compound(), DynamicClimb(), HelicopterSettings(n_span=8, n_average=1))
aircraft = hold_states(linearize(trim(heli)), ["u", "v"])

# 2. what each axis is graded on: the spec library's selector (an unknown MTE is
#    refused with the valid names; specs whose boundaries are not printed are skipped,
#    controllers.spec_table() lists them)
for axis in ("roll", "heave"):
    print(axis, [s.name for s in specs_for(axis, mte="all other", speed="hover", missing="skip")])

# 3. all four loops, tuned in turn on the full aircraft (small optimiser budgets:
#    the boundaries raised to 5 %, a 16-point global stage, no polishing)
fast = DMOSettings(tolerance=0.05, global_samples=16, polish_evaluations=0)
result = design_multi_axis(aircraft, settings=fast, later_settings=fast, max_sweeps=2, progress=False)
table = result.to_pandas()
print(table[["crossover", "drb", "gm_db", "pm_deg", "specs_met", "limiting"]].to_string())
print(result.coupling()[["stick", "response", "step_ratio"]].to_string(index=False))

# 4. the HQ window of one axis: each spec on its Level chart, graded on the simultaneous closed loop
result.plot(axes=["roll"])["roll"].savefig("tour_hq_window_roll_multi_axis.png", dpi=70)

# 5. a boundary the library lacks (its value was not found printed), supplied by the user:
#    here a programme's own pitch disturbance-rejection requirement, graded on the same
#    closed loop; given as design_multi_axis(..., boundaries=mine) the DMO would honour it
mine = {"DrbPiH1": {"level1": 0.5, "level2": 0.25, "source": "programme requirement (example values)"}}
pitch_drb = [s for s in specs_for("pitch", missing="skip", boundaries=mine) if s.name == "DrbPiH1"]
graded = evaluate_specs(result.emf.axis_view("pitch"), pitch_drb)
print(graded[["spec", "value", "level", "met"]].to_string(index=False))
