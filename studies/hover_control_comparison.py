"""Main job: impact of inflow modelling on hover control design (dissertation §7.5).

Four cases, same explicit-model-following structure (Fig. 7.12), same command
model, actuator and sensor:

* (A) design optimised (DMO) on the Dynamic-Climb (DC) aircraft, applied to it;
* (B) the same design (gains, inverse plant, tau_eq) applied to the aircraft with
  the wake-identified inflow model;
* (C) design optimised on the wake-identified aircraft, applied to it;
* (D) one robust design (CONDUIT multi-case) meeting every spec on the
  Dynamic-Climb and the identified 6-state (Eq. 5.3) aircraft at once, started
  from the case C (then A) design and keeping its inverse plant and tau_eq.
  Add a plant to ``robust_plants`` in :func:`main` to add it to case D.

Each aircraft is our coaxial model (:mod:`aircraft.helicopter`) trimmed in hover
and linearised; the roll-axis plant is the coupling numerator
p/delta_lat | q->delta_lon, r->delta_ped, w->delta_col (Eq. 7.21), built by
:func:`controllers.roll_design_plant`. All three PID gains are free (no K_Iphi
tie), bounded below by 0; the DMO raises its boundaries by bisection to 0.5 %.

Wake-identified inflow: ``--identified published`` (default, fast) uses the
dissertation's MFW-identified 6-state hover model (Eq. 5.3, reference data in
:mod:`aircraft.inflow.published`), converted to our rotor frames by
:func:`aircraft.inflow.published.in_rotor_frames`; ``--identified ours`` uses our
shipped file ``coaxial_hover_6state`` (seconds); ``--identified wake`` uses the 6-state model
identified from our own free wake by :mod:`studies.coaxial_wake_identification`
(six sweeps, about 8 minutes on 2 cores the first time, cached after). The
aircraft, trim, linearisation, EMF and DMO are ours either way. Stage 1 also runs
the identification pipeline end to end on an embedded truth
(:mod:`studies.identification_demo`).

Writes tables (CSV) and figures (PNG) under ``results/hover_control_comparison/``
and prints Tables 7.4/7.5-style summaries with the dissertation's values in
separate columns.  Run: ``make study`` or ``python -m studies.hover_control_comparison``.
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

import control
import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from aircraft import coaxial_compound
from aircraft.helicopter import Helicopter, HelicopterSettings, flap_mode_damping, linearize, modes, trim
from aircraft.inflow import DynamicClimb, IdentifiedInflow
from aircraft.inflow.published import COAXIAL_HOVER_12STATE, COAXIAL_HOVER_6STATE, in_rotor_frames
from controllers import (CommandModel, EMFDesign, InfeasibleDesignError, PIDGains, default_specs, dmo,
                         evaluate_specs, hq_window, roll_design_plant, second_order_actuator)
from controllers.metrics import damping_in_band, gain_phase_margins

# reference values of Tables 7.4 / 7.5 (comparison columns only, never outputs)
DISSERTATION_74 = {"K_p": (0.0413, 0.0413, 0.0326), "K_phi": (0.303, 0.303, 0.582),
                   "K_Iphi": (0.212, 0.212, 0.626), "tau_eq": (0.0265, 0.0265, 0.0454)}
DISSERTATION_75 = {"crossover_rad_s": (3.53, 3.47, 5.38), "GM_dB": (7.2, 6.25, 6.00),
                   "PM_deg": (45.0, 73.0, 47.7), "min_zeta_4_20": (0.1048, 0.148, 0.193),
                   "DRB_rad_s": (1.89, 1.97, 2.91), "DRP_dB": (4.38, 2.35, 4.87)}


def roll_plant(inflow, settings):
    """Trim the coaxial in hover with ``inflow``; return (roll design plant, linear model, trim)."""
    tr = trim(Helicopter(coaxial_compound(), inflow, settings))
    sys = linearize(tr)
    return roll_design_plant(sys), sys, tr


def characteristics(design, specs):
    table = evaluate_specs(design, specs).set_index("spec")
    limiting = table[(table.kind != "objective") & (table.index != "CrsMnG2")].margin.astype(float).idxmin()
    poles = design.closed_loop_poles()
    return {"crossover_rad_s": table.loc["CrsMnG2", "value"], "GM_dB": table.loc["StbMgG1.GM", "value"],
            "PM_deg": table.loc["StbMgG1.PM", "value"], "min_zeta_4_20": damping_in_band(poles, 4, 20),
            "DRB_rad_s": table.loc["DrbRoH1", "value"], "DRP_dB": table.loc["DrpAvH1", "value"],
            "bandwidth_rad_s": table.loc["BnwAtH1", "value"], "all_specs_met": bool(table[table.kind != "objective"].met.all()),
            "K_phi": design.gains.K_phi, "K_Iphi": design.gains.K_Iphi, "K_p": design.gains.K_p,
            "most_limiting_spec": limiting, "its_margin": table.loc[limiting, "margin"]}


def _bode(ax_mag, ax_ph, fun, w, label, style="-"):
    h = fun.response(w)
    mag, phase = 20 * np.log10(np.abs(h)), np.degrees(np.unwrap(np.angle(h)))
    lines = ax_mag.semilogx(w, mag, style, label=label)
    ax_ph.semilogx(w, phase, style, label=label)
    return mag, phase, lines[0].get_color()


def _mark_margins(ax_mag, ax_ph, w, mag, phase, color, loop):
    """Crossover, gain margin and phase margin of ``loop`` on its Bode plot: the
    values are controllers.gain_phase_margins' (the specs' own metric); the -180 deg
    line is drawn on the branch of the plotted (unwrapped) phase at crossover."""
    gm, pm, w180, wc = gain_phase_margins(loop)
    if np.isfinite(wc):
        ph_c = np.interp(np.log(wc), np.log(w), phase)
        ref = ph_c - pm
        ax_mag.axvline(wc, color=color, ls=":", lw=0.8)
        ax_ph.vlines(wc, ref, ph_c, color=color, lw=2.5, alpha=0.6)
        ax_ph.axhline(ref, color="0.4", lw=0.6, ls="--")
        ax_ph.annotate(f"PM {pm:.0f}°", (wc, 0.5 * (ref + ph_c)), fontsize=7, color=color,
                       xytext=(4, 0), textcoords="offset points")
    if np.isfinite(w180) and np.isfinite(gm):
        m180 = np.interp(np.log(w180), np.log(w), mag)
        ax_mag.vlines(w180, m180, 0.0, color=color, lw=2.5, alpha=0.6)
        ax_mag.annotate(f"GM {gm:.1f} dB", (w180, 0.5 * m180), fontsize=7, color=color,
                        xytext=(4, 0), textcoords="offset points")


def figures(cases, out):
    w = np.geomspace(0.1, 60, 600)
    names = list(cases)
    fig = Figure(figsize=(11, 7), constrained_layout=True)
    axes = fig.subplots(2, 3)
    for name in names:
        d = cases[name]
        mag, phase, color = _bode(axes[0, 0], axes[1, 0], d.broken_loop(), w, name)
        _mark_margins(axes[0, 0], axes[1, 0], w, mag, phase, color, d.broken_loop())
        _bode(axes[0, 1], axes[1, 1], d.roll_rate_response(), w, name)
        _bode(axes[0, 2], axes[1, 2], d.disturbance_response(), w, name)
    cmd = cases[names[0]]
    _bode(axes[0, 1], axes[1, 1], type(cmd.commanded_attitude())(lambda s: s * cmd.commanded_attitude()(s)),
          w, "command (A/B)", "k--")
    for ax, title in zip(axes[0], ["broken loop delta_fb/delta_mx (Fig. 7.13)", "closed loop p/delta_lat (Fig. 7.14)",
                                   "disturbance phi'/phi_d (Fig. 7.17)"]):
        ax.set_title(title, fontsize=9)
        ax.set_ylabel("dB")
    for ax in axes[1]:
        ax.set_xlabel("rad/s")
        ax.set_ylabel("deg")
    for ax in axes.ravel():
        ax.grid(True, which="both", alpha=0.3)
    axes[0, 0].axhline(0.0, color="0.4", lw=0.6, ls="--")
    axes[0, 0].text(0.02, 0.02, "dotted: crossover; bars: GM at the -180° crossing, PM at crossover\n"
                    "(controllers.gain_phase_margins)", transform=axes[0, 0].transAxes, fontsize=6.5)
    axes[0, 0].legend(fontsize=8)
    axes[0, 1].legend(fontsize=7)
    fig.savefig(out / "frequency_responses.png", dpi=90)

    fig = Figure(figsize=(11, 7), constrained_layout=True)
    axes = fig.subplots(3, 3, sharex=True)
    for k, name in enumerate(names):
        d = cases[name]
        imp = d.stick_impulse(duration=6.0, width=0.5, amplitude=np.radians(5.0))
        ip, iphi, icm = [imp.output_labels.index(n) for n in ("p", "phi", "phi_cm")]
        axes[k, 0].plot(imp.time, np.degrees(imp.outputs[ip]), label="p")
        axes[k, 1].plot(imp.time, np.degrees(imp.outputs[iphi]), label="phi")
        axes[k, 1].plot(imp.time, np.degrees(imp.outputs[icm]), "k--", label="phi_cm")
        st = d.step_disturbance(duration=6.0)
        axes[k, 2].plot(st.time, np.degrees(st.outputs[st.output_labels.index("phi_meas")]), label="phi'")
        axes[k, 0].set_ylabel(f"{name}\n[deg/s]")
        axes[k, 1].set_ylabel("[deg]")
        axes[k, 2].set_ylabel("[deg]")
    axes[0, 0].set_title("stick pulse: roll rate (Fig. 7.15)", fontsize=9)
    axes[0, 1].set_title("stick pulse: roll attitude (Fig. 7.16)", fontsize=9)
    axes[0, 2].set_title("1 deg step disturbance (Fig. 7.18)", fontsize=9)
    for ax in axes.ravel():
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    for ax in axes[-1]:
        ax.set_xlabel("t [s]")
    fig.savefig(out / "time_responses.png", dpi=90)


def main(argv=None):
    parser = argparse.ArgumentParser(description="Hover control comparison (dissertation §7.5)")
    parser.add_argument("--seed", type=int, default=0, help="seed of the identification stage")
    parser.add_argument("--out", default="results", help="output folder")
    parser.add_argument("--skip-identification", action="store_true")
    parser.add_argument("--n-span", type=int, default=8, help="blade-element Gauss points")
    parser.add_argument("--identified", choices=("published", "ours", "wake"), default="published",
                        help="wake-identified inflow: the dissertation's Eq. 5.3 model (converted to our "
                             "rotor frames), ours from the shipped file aircraft/data/models/"
                             "coaxial_hover_6state.json, or ours re-identified from the wake now")
    args = parser.parse_args(argv)
    t_start = time.perf_counter()
    if not args.skip_identification:
        from studies.identification_demo import run_demo
        print("[stage 1] identification pipeline on the embedded 6-state coaxial truth")
        cost = run_demo(seed=args.seed, out_dir=f"{args.out}/identification_demo")
        print(f"[stage 1] done: J_ave = {cost.J.mean():.2f} over {len(cost)} responses\n")

    suffix = {"published": "", "ours": "_ours", "wake": "_wake"}[args.identified]
    out = Path(args.out) / ("hover_control_comparison" + suffix)
    out.mkdir(parents=True, exist_ok=True)
    settings = HelicopterSettings(n_span=args.n_span, n_average=1)   # hover: axisymmetric
    print("[stage 2] trim + linearise the coaxial in hover with both inflow models")
    plant_dc, sys_dc, tr_dc = roll_plant(DynamicClimb(), settings)
    if args.identified == "wake":
        from studies.coaxial_wake_identification import identified_inflow, identify
        print("  identifying the 6-state inflow model from our free wake (cached after the first run)")
        reduction, wake_trim, _, omega = identify()
        print(f"  identified: J_ave = {reduction.result.J_ave:.1f}")
        inflow_id = identified_inflow(reduction, wake_trim, omega)
    elif args.identified == "ours":
        from aircraft.identification import load_record
        record = load_record("coaxial_hover_6state")
        print(f"  our 6-state model from its shipped file: {record.description}")
        inflow_id = IdentifiedInflow.from_file("coaxial_hover_6state")
    else:
        inflow_id = IdentifiedInflow.from_published(in_rotor_frames(COAXIAL_HOVER_6STATE))
    plant_id, sys_id, tr_id = roll_plant(inflow_id, settings)
    for name, tr in (("DC", tr_dc), ("ID", tr_id)):
        print(f"  {name}: trim residual {tr.max_residual:.1e}, C_T U/L = {tr.loads['CT_U']:.5f}/{tr.loads['CT_L']:.5f}")
    pd.concat([modes(sys_dc).assign(aircraft="Dynamic Climb"), modes(sys_id).assign(aircraft="identified")]) \
        .to_csv(out / "aircraft_modes.csv", index=False)

    plant_12, sys_12, tr_12 = roll_plant(IdentifiedInflow.from_published(in_rotor_frames(COAXIAL_HOVER_12STATE)), settings)
    print(f"  12-state (published Eqs. 6.2-6.3): trim residual {tr_12.max_residual:.1e}")

    actuator = second_order_actuator(35.0, 0.7)
    command = CommandModel(frequency=4.0, damping=0.7, gain=0.05)
    start = PIDGains(0.3, 0.1, 0.05)
    print("[stage 3] DMO, case (A): design on the Dynamic-Climb aircraft")
    base_a = EMFDesign(plant_dc, start, command, actuator, sensor_delay=0.01)
    res_a = dmo(base_a, progress=True)
    print(f"  {res_a.message} ({res_a.wall_time:.0f} s)")
    print("[stage 3] DMO, case (C): design on the wake-identified aircraft")
    base_c = EMFDesign(plant_id, start, command, actuator, sensor_delay=0.01)
    res_c = dmo(base_c, progress=True)
    print(f"  {res_c.message} ({res_c.wall_time:.0f} s)")
    # case D: one gain set for every plant in this list (one line adds a plant); the
    # feed-forward (inverse plant, tau_eq) is case C's, as one controller would fly
    # (the published 12-state aircraft is left out: with it no gain set keeps every
    # closed loop stable at the starting boundaries (EigLcG1 on that aircraft, from
    # every start tried); its frame and sign reading is still open, see the README)
    robust_plants = {"DC": plant_dc, "ID 6-state": plant_id}
    print(f"[stage 3] DMO, case (D): robust design on {', '.join(robust_plants)}")
    # start from the optimised single-plant designs (their gains and feed-forward):
    # a robust design, if one exists, lies nearer those than the generic start
    res_d, d_failures = None, []
    for label, start_design in (("case C design", res_c.design), ("case A design", res_a.design),
                                ("starting gains", base_c)):
        try:
            res_d = dmo([start_design.with_plant(p) for p in robust_plants.values()], progress=True,
                        labels=list(robust_plants))
            print(f"  from the {label}: {res_d.message} ({res_d.wall_time:.0f} s)")
            break
        except InfeasibleDesignError as err:
            d_failures.append(f"from the {label}: {err}")
            print(f"  from the {label}: infeasible ({err})")
    if res_d is None:
        print("  case (D): no gain set meets every spec on all plants at the starting boundaries; "
              "it is reported as infeasible (robust_infeasible.txt), not as a design")
        (out / "robust_infeasible.txt").write_text("\n".join(d_failures) + "\n")
    cases = {"(A) DC on DC": res_a.design,
             "(B) DC on ID": res_a.design.with_plant(plant_id),
             "(C) ID on ID": res_c.design}
    robust = ({f"(D) robust on {name}": d for name, d in zip(robust_plants, res_d.designs)}
              if res_d is not None else {})
    fa = res_a.history[res_a.history.feasible].iloc[-1]
    fc = res_c.history[res_c.history.feasible].iloc[-1]
    fd = res_d.history[res_d.history.feasible].iloc[-1] if res_d is not None else fc
    specs_a = default_specs(fa.crossover_min, fa.drb_min)
    specs_c = default_specs(fc.crossover_min, fc.drb_min)
    specs_d = default_specs(fd.crossover_min, fd.drb_min)
    spec_set = lambda name: specs_d if name.startswith("(D)") else specs_c if name.startswith("(C)") else specs_a

    t74 = pd.DataFrame({
        "parameter": ["K_p", "K_phi", "K_Iphi", "tau_eq"],
        "ours (A)&(B)": [res_a.design.gains.K_p, res_a.design.gains.K_phi, res_a.design.gains.K_Iphi,
                         res_a.design.equivalent_delay],
        "ours (C)": [res_c.design.gains.K_p, res_c.design.gains.K_phi, res_c.design.gains.K_Iphi,
                     res_c.design.equivalent_delay],
        "ours (D) robust": ([res_d.design.gains.K_p, res_d.design.gains.K_phi, res_d.design.gains.K_Iphi,
                             res_d.design.equivalent_delay] if res_d is not None else [np.nan] * 4),
        "dissertation (A)&(B)": [DISSERTATION_74[k][0] for k in ("K_p", "K_phi", "K_Iphi", "tau_eq")],
        "dissertation (C)": [DISSERTATION_74[k][2] for k in ("K_p", "K_phi", "K_Iphi", "tau_eq")]})
    rows = []
    for name, design in {**cases, **robust}.items():
        k = "ABC".find(name[1])
        ch = characteristics(design, spec_set(name))
        rows.append({"case": name, **ch, **{f"dissertation {key}": (val[k] if k >= 0 else np.nan)
                                            for key, val in DISSERTATION_75.items()}})
    t75 = pd.DataFrame(rows)
    # where the regressive flap (flap-body) modes sit with the loop closed, each tracked
    # from its bare-airframe pole (issue: the dissertation's "min zeta 4-20 rad/s" is
    # this mode; ours may sit just outside the band, and then the band minimum is the
    # command model's 0.7)
    flap_rows = []
    for name, design in {**cases, **robust}.items():
        bare_sys = sys_dc if name.endswith("on DC") else sys_12 if "12-state" in name else sys_id
        bare = flap_mode_damping(bare_sys).reset_index(drop=True)
        closed = flap_mode_damping(design.closed_loop(), reference=bare).reset_index(drop=True)
        for k in range(len(closed)):
            flap_rows.append({"case": name, "mode": closed.physics[k],
                              "bare_frequency_rad_s": bare.frequency[k], "bare_damping": bare.damping[k],
                              "closed_loop_frequency_rad_s": closed.frequency[k],
                              "closed_loop_damping": closed.damping[k], "tracked": bool(closed.tracked[k]),
                              "in_band_4_20": bool(closed.in_band[k]),
                              "min_zeta_4_20_any_mode": closed.min_damping_in_band[k]})
    flap = pd.DataFrame(flap_rows)
    flap.to_csv(out / "flap_modes.csv", index=False)
    t74.to_csv(out / "table_7_4_gains.csv", index=False)
    t75.to_csv(out / "table_7_5_characteristics.csv", index=False)
    pd.concat([res_a.history.assign(case="A"), res_c.history.assign(case="C")]
              + ([res_d.history.assign(case="D")] if res_d is not None else [])) \
        .to_csv(out / "dmo_history.csv", index=False)
    for name, design in cases.items():
        evaluate_specs(design, spec_set(name)).assign(case=name).to_csv(out / f"specs_{name[1]}.csv", index=False)
    if res_d is not None:
        res_d.specs.assign(case="(D) robust").to_csv(out / "specs_D.csv", index=False)
    figures(cases, out)
    hq_window(list(cases.values()), specs_a, labels=list(cases)).savefig(out / "hq_window.png", dpi=80)
    if robust:
        hq_window(list(robust.values()), specs_d, labels=list(robust_plants)).savefig(out / "hq_window_robust.png",
                                                                                      dpi=80)

    fmt = lambda v: f"{v:.4g}"
    pd.set_option("display.width", 200)
    print("\n== Optimal controller parameters (cf. Table 7.4; stick units differ, compare trends) ==")
    print(t74.to_string(index=False, float_format=fmt))
    print("\n== Optimal controller characteristics (cf. Table 7.5) ==")
    ours = t75[["case", "crossover_rad_s", "GM_dB", "PM_deg", "min_zeta_4_20", "DRB_rad_s", "DRP_dB", "all_specs_met",
                "most_limiting_spec"]]
    print(ours.to_string(index=False, float_format=fmt))
    print("dissertation: " + "; ".join(f"{k} = {v}" for k, v in DISSERTATION_75.items()))
    print("\n== Regressive flap (flap-body) modes: bare airframe -> closed loop ==")
    print(flap[["case", "mode", "bare_frequency_rad_s", "bare_damping", "closed_loop_frequency_rad_s",
                "closed_loop_damping", "in_band_4_20"]].to_string(index=False, float_format=fmt))
    wc = t75.crossover_rad_s.values
    print(f"\ncrossover gain from the identified-inflow design, (C)/(A): {wc[2] / wc[0]:.2f} "
          f"(dissertation {DISSERTATION_75['crossover_rad_s'][2] / DISSERTATION_75['crossover_rad_s'][0]:.2f})")
    if res_d is not None:
        print(f"robustness cost, (D) over all plants vs (C): crossover {res_d.crossover:.3f} vs {wc[2]:.3f} rad/s "
              f"({res_d.crossover / wc[2] - 1:+.1%})")
    else:
        print("robustness: no robust design (D) over " + ", ".join(robust_plants) + " at the starting boundaries")
    print(f"tables and figures in {out}/  (wall {time.perf_counter() - t_start:.0f} s)")


if __name__ == "__main__":
    main()
