"""From a flight-test CSV to a verified model: the workflow of a CIFER / SIDPAC user.

The script writes its own "flight-test" files first (a pitch axis simulated with
scipy, logged with time-stamp jitter and measurement noise, two frequency-sweep
runs and a 2-1-1 for verification) so that it runs anywhere; replace them with
your own CSV files (a time column and one column per channel, "name [unit]").
It saves the figures a CIFER user expects: Bode of data and model with
coherence, the time-domain verification, and prints the cost and parameter tables.
"""
import numpy as np
import pandas as pd
from scipy.signal import lsim

from flightid import (StateSpaceStructure, concatenated_response, fit, fit_transfer_function, frequency_sweep, identify, read_flight_data, verify)

# --- the aircraft we pretend to fly: short period with a 40 ms delay ----------------
ZA, MA, MQ, ZDE, MDE, TAU = -1.2, -6.0, -2.5, -0.15, -9.0, 0.04
A = np.array([[ZA, 1.0], [MA, MQ]])
B = np.array([[ZDE], [MDE]])
C = np.array([[0.0, 1.0], [ZA, 0.0]])          # outputs: q [rad/s], az / V [1/s]
D = np.array([[0.0], [ZDE]])


def fly(t, de, seed, path):
    """Simulate, add 2 % noise and 1 ms time-stamp jitter, write a CSV."""
    rng = np.random.default_rng(seed)
    shift = int(round(TAU / (t[1] - t[0])))
    delayed = np.concatenate([np.zeros(shift), de[:de.size - shift]])
    y = lsim((A, B, C, D), delayed, t)[1]
    y += 0.02 * y.std(axis=0) * rng.standard_normal(y.shape)
    stamp = t + rng.uniform(-0.001, 0.001, t.size)
    pd.DataFrame({"time": stamp, "de [rad]": de, "q [rad/s]": y[:, 0], "azV [1/s]": y[:, 1]}).to_csv(
        path, index=False)


dt = 0.01
for run in (1, 2):
    t, de = frequency_sweep(0.4, 25.0, 70.0, dt, amplitude=0.02, trim_start=10.0, noise_fraction=0.2, seed=run)
    fly(t, de, run, f"sweep_run{run}.csv")
t = np.arange(0.0, 15.0, dt)
de = 0.02 * (((t >= 1) & (t < 2)) * 1.0 - ((t >= 2) & (t < 2.5)) + ((t >= 2.5) & (t < 3)))   # 2-1-1
fly(t, de, 3, "verification_211.csv")

# --- 1. flight data in: named channels and units, resampled onto a uniform 0.01 s grid
runs = [read_flight_data(f"sweep_run{k}.csv", time="time", resample=0.01, name=f"run {k}") for k in (1, 2)]
print("channels:", runs[0].units)
# CIFER multi-run concatenation: spectra pooled over both runs before H and coherence
data = concatenated_response(runs, "de", ["q", "azV"], w_min=0.5, w_max=20.0, name="pitch sweeps")

# --- 2. NAVFIT-like: q/de as (b1 s + b0) e^{-tau s} / (s^2 + a1 s + a0) in one call
tf_fit = fit_transfer_function(data.select("q", "de"), 1, 2)
print("\nq/de transfer function\n", tf_fit.statistics.round(4).to_string(index=False))

# --- 3. DERIVID-like: one set of derivatives fitted to q and az jointly (C and D parametrised)
structure = StateSpaceStructure([["Za", 1.0], ["Ma", "Mq"]], [["Zde"], ["Mde"]], [[0.0, 1.0], ["Za", 0.0]],
                                D=[[0.0], ["Zde"]], tau=[["tau"], ["tau"]], inputs=["de"], outputs=["q", "azV"],
                                states=["alpha", "q"],
                                initial={"Za": -1.0, "Ma": -4.0, "Mq": -1.0, "Zde": -0.1, "Mde": -5.0, "tau": 0.0})
model = fit(structure, data)
print("\ncost table (CIFER: J < 100 per response is acceptable)\n", model.cost_table.round(3).to_string(index=False))
print("\nparameters: CIFER bounds and residual-scaled standard errors\n",
      model.statistics.round(4).to_string(index=False))
model.plot().savefig("flight_test_bode.png", dpi=90)

# --- 4. the short 2-1-1 record: too short for spectral windows, fitted by frequency-domain output error
check = read_flight_data("verification_211.csv", time="time", resample=0.01)
short = identify(structure.with_values(model.structure.values), check, method="output_error",
                 w_min=0.5, w_max=12.0)
print("\n2-1-1 by frequency-domain output error\n", short.statistics.round(4).to_string(index=False))

# --- 5. time-domain verification of the sweep model on the 2-1-1 it never saw
result = verify(model.structure, check.t, check["de"][None, :], np.vstack([check["q"], check["azV"]]))
print("\nverification (TIC < 0.25-0.3 is acceptable)\n", result.metrics.round(3).to_string(index=False))
result.plot().savefig("flight_test_verification.png", dpi=90)
