"""Tour, part 1: from a rotor to an identified state-space inflow model.

The UH-60-like rotor is trimmed in hover in the free-vortex wake, driven with one
swashplate frequency sweep per control, and a 3-state inflow model of the
Pitt-Peters form (M, Lbar, tau of Tables 4.1-4.2) is identified from the
responses by the CIFER-cost fit with automatic parameter reduction, then checked
on a doublet it was not fitted to.

This tour uses a coarse wake and short sweeps so that it runs in about a minute;
``rotorwake wake-identification`` does the same at full resolution.
"""
import math

import numpy as np

import flightid
from aircraft import uh60_single_rotor
from aircraft.wake import FlightCondition, SweepSpec, WakeSettings, run_sweeps

CONTROLS = ["theta0", "theta1s", "theta1c"]   # swashplate inputs [rad]
LOADS = ["CT", "CL", "CM"]                    # rotor load coefficients [-]
INFLOW = ["lam0", "lam1s", "lam1c"]           # inflow harmonics, on Omega R [-]

# 1. the rotor and its wake: 20 deg steps, 1.5 revolutions of free wake, 4 blade
#    elements (the studies use 10 deg, 4 + 1 revolutions, 10 elements)
rotor = uh60_single_rotor()
omega = rotor.rotors[0].omega                 # rotor speed [rad/s]
settings = WakeSettings(azimuth_step=math.radians(20.0), wake_revolutions=1.5, n_elements=4)

# 2. trim to C_T = 0.0061, then one 30 s sweep per control (0.02 rad, 0.7-30 rad/s)
#    and a collective doublet for verification, run from the trimmed wake
sweeps = [SweepSpec(c, kind="sweep", amplitude=0.02, duration=30.0, w_min=0.7, w_max=30.0, seed=k)
          for k, c in enumerate(CONTROLS)]
doublet = SweepSpec("theta0", kind="doublet", amplitude=0.05, duration=4.0, pulse_width=0.5)
runs = run_sweeps(rotor, settings, FlightCondition(), sweeps + [doublet], trim={"ct": 0.0061},
                  n_jobs=1, cache_dir=".cache/wake", progress=False)
trim = runs["trim"]
print(f"trim: C_T = {trim.outputs['CT']:.5f}, lam0 = {trim.outputs['lam0']:.5f}")

# 3. non-parametric responses of loads and inflow to each control, by chirp-z
#    over composite windows, with coherence (1-30 rad/s: a 30 s sweep resolves
#    down to 1 rad/s); then lambda/C by joint input-output (Eq. 3.22): the inflow
#    response to the loads the wake actually produced
responses = []
for spec in sweeps:
    df = runs[spec.name]
    y = df[LOADS + INFLOW].to_numpy() - df[LOADS + INFLOW].iloc[0].to_numpy()
    responses.append(flightid.frequency_response(
        df["t"].to_numpy(), df[spec.control].to_numpy() - df[spec.control].iloc[0], y,
        w_min=1.0, w_max=30.0, input_name=spec.control, output_names=LOADS + INFLOW))
measured = flightid.combine_responses(responses)
lam_over_c = flightid.joint_input_output(measured.select(INFLOW), measured.select(LOADS))

# 4. the model structure: diagonal M, Lbar, tau in rotor-azimuth time, the two
#    cyclic rows tied by hover symmetry, started from the closed-form Pitt-Peters
lam_h = math.sqrt(trim.outputs["CT"] / 2.0)
diagonal = lambda p: [[f"{p}11", 0, 0], [0, f"{p}22", 0], [0, 0, f"{p}22"]]   # noqa: E731
structure = flightid.MLTauStructure(
    diagonal("m"), diagonal("l"), diagonal("t"), inputs=LOADS, outputs=INFLOW, omega=omega,
    initial={"m11": 8 / (3 * math.pi), "m22": -16 / (45 * math.pi), "l11": 4 * lam_h, "l22": -lam_h,
             "t11": 0.02, "t22": 0.02})

# 5. CIFER-cost fit with the automatic reduction of Fig. 6.1 (drops parameters the
#    data cannot determine, e.g. the delays), then a look at what J cannot see
reduction = flightid.reduce(structure, lam_over_c, frequency_ranges=(1.0, 25.0))
fit = reduction.result
print(f"J_ave = {fit.J_ave:.1f} (guideline < 100)")
print(fit.parameters[["parameter", "value", "cramer_rao_pct", "insensitivity_pct"]].to_string(index=False))
model = fit.model      # python-control StateSpace, loads in, inflow out; delays as Pade states
print(f"identified model: {model.nstates} states, inputs {list(model.input_labels)}")

# 6. time-domain verification on the doublet (perturbations about the trim)
ref = trim.outputs
dbl = runs[doublet.name]
loads = np.array([dbl[n] - ref[n] for n in LOADS])
lam = np.array([dbl[n] - ref[n] for n in INFLOW])
check = flightid.verify(model, dbl["t"].to_numpy(), loads, lam, remove_initial=False)
print(check.metrics[check.metrics.output == "lam0"].to_string(index=False))

fit.plot().savefig("tour_bode_fit.png", dpi=80)   # model vs data, with coherence
