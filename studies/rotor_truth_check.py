"""Rotor-level truth check of the inflow models (§7.2.2: "MFW only" vs "state-space inflow").

The same swashplate doublets and a sweep drive

* (a) the free-vortex wake with free flapping (the "truth", shaft fixed), and
* (b)/(c) our blade-element rotors on a fixed shaft
  (:class:`aircraft.helicopter.ShaftFixedRotors`) with an identified inflow model
  (the dissertation's Eq. 5.3, and ours identified from this wake if
  ``results/coaxial_wake_identification`` holds it), with Dynamic Climb
  (analytical K_R) and with isolated Pitt-Peters rotors.

Identified models run about the wake's trim (Eq. 7.2: trim inflow from the
wake, perturbations from the model); the momentum models about their own trim
(Eq. 7.4). All rotors are trimmed to the wake's total thrust with equal torques
and zero cyclic. Perturbation responses (about each trim) are compared: Theil
inequality coefficient (TIC) of flap-rate and load responses against (a) on
the doublets (all signals about their pre-input mean and averaged over one
blade passage alike), and Bode overlays from the sweep (same chirp-z processing).
Our rotors run their linearisation about the trim (0.02 rad inputs; the
nonlinear run agrees to TIC < 1e-4, ``tests/aircraft/helicopter/test_rotor_stand.py``).

Wake resolution: 15 deg steps, 3 free revolutions, 6 elements (coarser than the
identification's defaults, for 2 shared cores); cached in ``.cache/wake``.

Writes ``results/rotor_truth_check/``: ``tic.csv``, ``tic_summary.csv``,
``tic_mean.csv``, ``bode.csv``, ``doublets.png``, ``bode.png``.

Run: ``python -m studies.rotor_truth_check``
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from aircraft import coaxial_compound
from aircraft.helicopter import ShaftFixedRotors
from aircraft.inflow import DynamicClimb, IdentifiedInflow, IsolatedRotors, KR_ANALYTICAL
from aircraft.inflow.published import COAXIAL_HOVER_6STATE, in_rotor_frames
from aircraft.wake import FlightCondition, SweepSpec, WakeSettings, run_sweeps
from flightid import frequency_response
from flightid.verification import theil_inequality

SETTINGS = WakeSettings(azimuth_step=math.radians(15.0), wake_revolutions=3.0, n_elements=6, free_flapping=True)
AMPLITUDE = 0.02
DOUBLETS = [SweepSpec(c, kind="doublet", amplitude=AMPLITUDE * (2.5 if c == "theta0_U" else 1.0), duration=3.0,
                      pulse_width=0.4) for c in ("theta0_U", "theta1s_U", "theta1c_U")]
SWEEP = SweepSpec("theta1c_U", kind="sweep", amplitude=AMPLITUDE, duration=25.0, w_min=1.0, w_max=25.0, seed=3)
OUTPUTS = ["CT_U", "CL_U", "CM_U", "CT_L", "CL_L", "CM_L",
           "beta1s_dot_U", "beta1c_dot_U", "beta1s_dot_L", "beta1c_dot_L"]
CONTROLS = ["theta0_U", "theta1s_U", "theta1c_U", "theta0_L", "theta1s_L", "theta1c_L"]


def _our_wake_model(trim_outputs, path="results/coaxial_wake_identification"):
    p = Path(path)
    if not (p / "M_azimuth_6state.csv").exists():
        return None
    read = lambda n: pd.read_csv(p / n, index_col=0).to_numpy()   # noqa: E731
    o = trim_outputs
    return IdentifiedInflow.from_matrices(
        read("M_azimuth_6state.csv"), read("Lbar_6state.csv"), read("tau_s_6state.csv"), omega=coaxial_compound().rotors[0].omega,
        loads_ref=np.array([o["CT_U"], 0, 0, o["CT_L"], 0, 0]),
        inflow_ref=np.array([o[k] for k in ("lam0_U", "lam1s_U", "lam1c_U", "lam0_L", "lam1s_L", "lam1c_L")]),
        name="identified from our free wake")


def models(wake_trim):
    """Inflow models for (b)/(c); identified ones about the wake's trim (Eq. 7.2)."""
    o = wake_trim.outputs
    loads = np.array([o["CT_U"], 0, 0, o["CT_L"], 0, 0])
    inflow = np.array([o[k] for k in ("lam0_U", "lam1s_U", "lam1c_U", "lam0_L", "lam1s_L", "lam1c_L")])
    pub = IdentifiedInflow.from_published(in_rotor_frames(COAXIAL_HOVER_6STATE))
    out = {"(b) ID 6-state, Eq. 5.3": IdentifiedInflow(pub.system, pub.rotors, loads, inflow, name=pub.name)}
    ours = _our_wake_model(o)
    if ours is not None:
        out["(b) ID 6-state, our wake"] = ours
    out["(c) Dynamic Climb, K_R 1.5"] = DynamicClimb(kr=KR_ANALYTICAL)
    out["(c) Pitt-Peters, isolated"] = IsolatedRotors()
    return out


def _perturbation(df, cols, t_start, n_avg):
    """Perturbation about the pre-input mean, averaged over one blade passage.

    The blade-sum loads of the wake carry N_b/rev blade-vortex content that no
    inflow model of this kind represents; truth and models are filtered alike
    (centred moving average over ``n_avg`` samples = 360/N_b deg of azimuth).
    """
    y = df[cols].to_numpy()
    y = y - y[df.t.to_numpy() < t_start].mean(axis=0)
    kernel = np.ones(n_avg) / n_avg
    return np.column_stack([np.convolve(np.pad(c, (n_avg // 2, n_avg - 1 - n_avg // 2), mode="edge"),
                                        kernel, mode="valid") for c in y.T])


def main(out_dir="results/rotor_truth_check", n_jobs=1):
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    pd.set_option("display.width", 200)
    config = coaxial_compound()
    ct = COAXIAL_HOVER_6STATE.condition["CT_U"] + COAXIAL_HOVER_6STATE.condition["CT_L"]
    print("[a] free wake, free flapping: trim + doublets + sweep (cached after the first run)")
    runs = run_sweeps(config, SETTINGS, FlightCondition(), DOUBLETS + [SWEEP],
                      trim={"ct": (ct / 2, ct / 2), "mode": "torque_balance", "tol": 1e-4},
                      n_jobs=n_jobs, cache_dir="default", progress=True)
    wtrim = runs["trim"]
    ct_wake = wtrim.outputs["CT_U"] + wtrim.outputs["CT_L"]
    print(f"    wake trim: C_T U/L {wtrim.outputs['CT_U']:.5f}/{wtrim.outputs['CT_L']:.5f}")
    tic_rows, bode_rows, histories = [], [], {}
    for name, inflow in models(wtrim).items():
        stand = ShaftFixedRotors(config, inflow)
        o = stand.trim(ct_wake)
        print(f"[{name[1]}] {name}: C_T U/L {o['CT_U']:.5f}/{o['CT_L']:.5f}")
        for spec in DOUBLETS + [SWEEP]:
            wdf = runs[spec.name]
            t = wdf.t.to_numpy()
            du = {c: wdf[c].to_numpy() - wdf[c].iloc[0] for c in CONTROLS if c in wdf}
            mdf = stand.run_linear(du, t)
            n_avg = int(round(2 * np.pi / config.rotors[0].n_blades / SETTINGS.azimuth_step))
            y_w = _perturbation(wdf, OUTPUTS, spec.trim_start, n_avg)
            y_m = _perturbation(mdf, OUTPUTS, spec.trim_start, n_avg)
            if spec.kind == "doublet":
                histories[(name, spec.name)] = (t, y_m)
                histories[("(a) free wake", spec.name)] = (t, y_w)
                for k, o_name in enumerate(OUTPUTS):
                    tic_rows.append({"model": name, "run": spec.name, "output": o_name,
                                     "tic": theil_inequality(y_m[:, k], y_w[:, k]),
                                     "rms_wake": float(np.sqrt(np.mean(y_w[:, k] ** 2)))})
            else:
                labels = [name] if bode_rows else ["(a) free wake", name]
                for label in labels:
                    y = y_w if label.startswith("(a)") else y_m
                    fr = frequency_response(t, du[spec.control], y, w_min=spec.w_min, w_max=spec.w_max,
                                            input_name=spec.control, output_names=OUTPUTS)
                    bode_rows += fr.to_pandas().assign(model=label).to_dict("records")
    tic = pd.DataFrame(tic_rows)
    # scored: the channels a doublet excites physically (collective: thrusts; cyclic: hub moments and
    # cyclic flap rates of both rotors). The rest is wake noise (blade-passage scatter ~0.5 % of C_T)
    # against a model response of zero, which would score 1 for every model alike.
    tic["kind"] = np.where(tic.output.str.startswith("C"), "load", "flap rate")
    excited = {"doublet_theta0_U": ("CT_U", "CT_L")}
    cyclic = tuple(o for o in OUTPUTS if not o.startswith("CT"))
    tic["scored"] = [o in excited.get(r, cyclic) for r, o in zip(tic.run, tic.output)]
    tic.to_csv(out / "tic.csv", index=False)
    summary = tic[tic.scored].pivot_table(index=["run", "output"], columns="model", values="tic")
    summary.to_csv(out / "tic_summary.csv")
    print("\nTIC against the free wake (doublets; 0 = perfect, outputs the doublet moves):")
    print(summary.to_string(float_format=lambda v: f"{v:.3f}"))
    print("\nmean TIC per model (loads, flap rates, all):")
    mean = tic[tic.scored].pivot_table(index="model", columns="kind", values="tic", aggfunc="mean")
    mean["all"] = tic[tic.scored].groupby("model").tic.mean()
    mean.to_csv(out / "tic_mean.csv")
    print(mean.to_string(float_format=lambda v: f"{v:.3f}"))
    bode = pd.DataFrame(bode_rows)
    bode.to_csv(out / "bode.csv", index=False)
    _figures(histories, bode, out)
    print(f"\ntables and figures in {out}/")


def _figures(histories, bode, out):
    runs = [s.name for s in DOUBLETS]
    show = {"doublet_theta0_U": ["CT_U", "CT_L"], "doublet_theta1s_U": ["CL_U", "beta1s_dot_U"],
            "doublet_theta1c_U": ["CM_U", "beta1c_dot_U"]}
    fig = Figure(figsize=(12, 7), constrained_layout=True)
    axes = fig.subplots(2, len(runs), squeeze=False)
    for j, run in enumerate(runs):
        for i, o_name in enumerate(show.get(run, OUTPUTS[:2])):
            k = OUTPUTS.index(o_name)
            for (model, r), (t, y) in histories.items():
                if r == run:
                    axes[i, j].plot(t, y[:, k], "k-" if model.startswith("(a)") else "-", lw=1.6 if
                                    model.startswith("(a)") else 1.0, label=model)
            axes[i, j].set_title(f"{run}: {o_name}")
            axes[i, j].grid(alpha=0.3)
            axes[i, j].set_xlabel("t [s]")
    axes[0, 0].legend(fontsize=7)
    fig.savefig(out / "doublets.png", dpi=90)
    sel = ["CL_U", "CM_U", "beta1c_dot_U", "beta1s_dot_U"]
    fig = Figure(figsize=(12, 6), constrained_layout=True)
    axes = fig.subplots(2, len(sel), squeeze=False)
    for j, o_name in enumerate(sel):
        for model, g in bode[bode.output == o_name].groupby("model", sort=False):
            style = "k-" if model.startswith("(a)") else "-"
            axes[0, j].semilogx(g.omega, g.magnitude_db, style, label=model)
            axes[1, j].semilogx(g.omega, g.phase_deg, style, label=model)
        axes[0, j].set_title(f"{o_name}/{SWEEP.control}")
        axes[1, j].set_xlabel("frequency [rad/s]")
        for ax in axes[:, j]:
            ax.grid(alpha=0.3, which="both")
    axes[0, 0].set_ylabel("magnitude [dB]")
    axes[1, 0].set_ylabel("phase [deg]")
    axes[0, 0].legend(fontsize=7)
    fig.savefig(out / "bode.png", dpi=90)


if __name__ == "__main__":
    main()
