"""The free wake flown with the aircraft ("MFW only", §7.2): hover coning response to collective.

The UH-60-like single rotor in hover at C_T = 0.0061 flown three ways on the same
blade-element rotor, flap equations and body (:mod:`aircraft.identification.free_wake_flight`):
with the free-vortex wake supplying the inflow, with the shipped identified
3-state model (``uh60_hover_3state``) and with Pitt-Peters; shaft fixed (Fig. 7.1)
and with the body free in heave. For each: the response to a small collective
step and the beta0/theta0 frequency response from a collective sweep (Figs.
7.1-7.2). Writes CSV and PNG under ``results/free_wake_flight/``.

Run: ``python -m studies.free_wake_flight`` (a few minutes on one core; nothing cached).
"""
from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np
import pandas as pd

from aircraft import load_aircraft
from aircraft.configs import uh60_single_rotor
from aircraft.helicopter.rotor_stand import ShaftFixedRotors
from aircraft.identification.free_wake_flight import fly_free_wake, fly_inflow_model
from aircraft.inflow import IdentifiedInflow, PittPeters
from aircraft.inflow.model_files import load_record
from aircraft.wake import WakeSettings
from flightid import frequency_response, frequency_sweep

MODELS = ("free wake", "identified 3-state", "Pitt-Peters")
BODIES = ("held", "heave")


def _inflow(model):
    return PittPeters() if model == "Pitt-Peters" else IdentifiedInflow.from_record(load_record("uh60_hover_3state"))


def _fly(model, config, collective, duration, body, ct, wake_settings):
    if model == "free wake":
        return fly_free_wake(config, collective, duration, body=body, ct=ct, wake_settings=wake_settings,
                             progress=False)
    inflow = _inflow(model)
    dt = wake_settings.azimuth_step / config.rotors[0].omega     # the wake's step: same grid for all
    return fly_inflow_model(config, inflow, collective, duration, body=body, ct=ct, dt=dt)


def phase_crossing(resp, target=-90.0):
    """First frequency [rad/s] where the phase [deg] falls through ``target`` (log interpolation), or NaN."""
    w, ph = resp["omega"].to_numpy(), resp["phase_deg"].to_numpy()
    for k in range(len(w) - 1):
        if ph[k] >= target > ph[k + 1]:
            f = (ph[k] - target) / (ph[k] - ph[k + 1])
            return float(np.exp(np.log(w[k]) + f * (np.log(w[k + 1]) - np.log(w[k]))))
    return float("nan")


def linear_coning_modes(config, inflow, ct):
    """Coning modes of the shaft-fixed rotor linearised with an inflow model.

    Returns ``(natural frequency [rad/s], damping ratio)`` of the oscillatory mode
    and the rate [1/s] of the real mode with the largest coning in their
    eigenvectors (each scaled to its largest entry), and the frequency [rad/s] of
    the peak of the linear beta0/theta0 response (1 to 100 rad/s, 2000 points).
    """
    stand = ShaftFixedRotors(config, inflow)
    stand.trim(ct)
    sys = stand.linearize()
    w, v = np.linalg.eig(sys.A)
    share = np.abs(v[list(sys.state_labels).index("beta0")]) / np.abs(v).max(axis=0)
    osc = [k for k in range(w.size) if w[k].imag > 1e-9]
    real = [k for k in range(w.size) if abs(w[k].imag) <= 1e-9]
    k_osc = max(osc, key=lambda k: share[k])
    k_real = max(real, key=lambda k: share[k])
    sub = sys[list(sys.output_labels).index("beta0"), list(sys.input_labels).index("theta0")]
    grid = np.logspace(0, 2, 2000)
    mag = np.abs(sub(1j * grid))
    return (float(abs(w[k_osc])), float(-w[k_osc].real / abs(w[k_osc])), float(-w[k_real].real),
            float(grid[np.argmax(mag)]))


def run_study(*, ct=0.0061, step_deg=0.5, sweep_deg=0.5, sweep_s=14.0, w_min=2.0, w_max=60.0,
              out_dir="results/free_wake_flight", wake_settings=None, aircraft=None, verbose=True):
    """Step and sweep responses of the three inflow models, body held and free in heave.

    Returns ``(summary DataFrame, step DataFrame, frequency-response DataFrame)``.
    """
    t_start = time.perf_counter()
    config = uh60_single_rotor() if aircraft is None else load_aircraft(aircraft)
    ws = wake_settings or WakeSettings()
    dt = ws.azimuth_step / config.rotors[0].omega
    amp = math.radians(step_deg)
    t_sw, u_sw = frequency_sweep(w_min, w_max, sweep_s, dt, math.radians(sweep_deg), trim_start=1.0,
                                 trim_end=1.0, settling_time=1.0)
    steps, bodes, rows = [], [], []
    for body in BODIES:
        for model in MODELS:
            t0 = time.perf_counter()
            st = _fly(model, config, lambda t: amp * (t >= 0.1), 2.0, body, ct, ws)
            sw = _fly(model, config, (t_sw, u_sw), float(t_sw[-1]), body, ct, ws)
            wall = time.perf_counter() - t0
            st = st.assign(model=model, body=body)
            steps.append(st)
            du = sw["theta0"].to_numpy() - sw["theta0"].iloc[0]
            db = sw["beta0"].to_numpy() - sw["beta0"].iloc[0]
            fr = frequency_response(sw["t"].to_numpy(), du, db, w_min=w_min, w_max=w_max, input_name="theta0",
                                    output_names=["beta0"], settling_time=1.0).to_pandas()
            fr = fr.assign(model=model, body=body)
            bodes.append(fr)
            # coning per collective at the end of the step (mean of its last quarter second:
            # the wake's blade-passage ripple); body held it has settled, free in heave not yet
            tail = st["t"] > st["t"].iloc[-1] - 0.25
            gain = float((st.loc[tail, "beta0"].mean() - st["beta0"].iloc[0]) / amp)
            rows.append({"body": body, "model": model, "trim_CT": st.attrs["trim"]["CT"],
                         "step_beta0_per_theta0_at_2s": gain,
                         "sweep_gain_at_w_min": float(10 ** (fr["magnitude_db"].iloc[0] / 20)),
                         "peak_rad_s": float(fr["omega"].iloc[int(np.argmax(fr["magnitude_db"]))]),
                         "peak_db": float(fr["magnitude_db"].max()),
                         "phase_minus_90_rad_s": phase_crossing(fr),
                         "mean_coherence": float(fr["coherence"].mean()), "wall_s": wall})
            if body == "held" and model != "free wake":
                # the linearised shaft-fixed rotor with the same inflow model: an independent
                # reading of the mode the sweep's peak shows
                wn, zeta, rate, peak = linear_coning_modes(config, _inflow(model), ct)
                rows[-1].update(linear_coning_mode_rad_s=wn, linear_coning_damping=zeta, linear_peak_rad_s=peak,
                                linear_inflow_coning_real_mode_1_s=rate)
            if verbose:
                print(f"{body:5s} {model:20s} done in {wall:.0f} s", flush=True)
    summary = pd.DataFrame(rows)
    steps, bodes = pd.concat(steps, ignore_index=True), pd.concat(bodes, ignore_index=True)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    summary.to_csv(out / "summary.csv", index=False)
    steps.to_csv(out / "step.csv", index=False)
    bodes.to_csv(out / "bode.csv", index=False)
    _plot(steps, bodes, out, step_deg)
    if verbose:
        print(summary.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
        print(f"tables and figures in {out}/  (wall {time.perf_counter() - t_start:.0f} s)")
    return summary, steps, bodes


def _plot(steps, bodes, out, step_deg):
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, len(BODIES), figsize=(11, 6), sharex="col", squeeze=False)
    for j, body in enumerate(BODIES):
        for model in MODELS:
            d = steps[(steps.body == body) & (steps.model == model)]
            axes[0, j].plot(d.t, np.degrees(d.beta0 - d.beta0.iloc[0]), label=model)
            axes[1, j].plot(d.t, d.lam0 - d.lam0.iloc[0], label=model)
        axes[0, j].set_title(f"body {body}: {step_deg:g} deg collective step")
        axes[0, j].set_ylabel("beta0 change [deg]")
        axes[1, j].set_ylabel("lam0 change [-]")
        axes[1, j].set_xlabel("t [s]")
    axes[0, 0].legend()
    fig.tight_layout()
    fig.savefig(out / "step.png", dpi=90)
    plt.close(fig)
    fig, axes = plt.subplots(3, len(BODIES), figsize=(11, 8), sharex=True, squeeze=False)
    for j, body in enumerate(BODIES):
        for model in MODELS:
            d = bodes[(bodes.body == body) & (bodes.model == model)]
            axes[0, j].semilogx(d.omega, d.magnitude_db, label=model)
            axes[1, j].semilogx(d.omega, d.phase_deg, label=model)
            axes[2, j].semilogx(d.omega, d.coherence, label=model)
        axes[0, j].set_title(f"beta0 / theta0, body {body}")
        axes[0, j].set_ylabel("magnitude [dB]")
        axes[1, j].set_ylabel("phase [deg]")
        axes[2, j].set_ylabel("coherence")
        axes[2, j].set_xlabel("frequency [rad/s]")
    axes[0, 0].legend()
    fig.tight_layout()
    fig.savefig(out / "bode.png", dpi=90)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--aircraft", default=None,
                        help="a shipped aircraft's name or an aircraft TOML file (default: uh60_single_rotor)")
    parser.add_argument("--sweep-s", type=float, default=14.0, help="swept part of the sweep record [s]")
    parser.add_argument("--coarse", action="store_true",
                        help="15 deg steps, 2 revs of wake, 6 elements (quick look)")
    parser.add_argument("--out", default="results/free_wake_flight")
    args = parser.parse_args(argv)
    ws = (WakeSettings(azimuth_step=math.radians(15.0), wake_revolutions=2.0, n_elements=6)
          if args.coarse else WakeSettings())
    run_study(sweep_s=args.sweep_s, out_dir=args.out, wake_settings=ws, aircraft=args.aircraft)


if __name__ == "__main__":
    main()
