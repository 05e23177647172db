"""Main job: impact of inflow modelling on hover control design (dissertation §7.5).

Same explicit-model-following structure (Fig. 7.12), command model, actuator and
sensor in every case:

* (A) design optimised (DMO) on the Dynamic-Climb (DC) aircraft, applied to it;
* (B) the same design (gains, inverse plant, tau_eq) applied to the aircraft with
  the wake-identified inflow model;
* (C) design optimised on the wake-identified aircraft, applied to it;
* (D) one robust design (CONDUIT multi-case) meeting every spec on the
  Dynamic-Climb aircraft and each of our wake-identified aircraft that has a
  feasible design of its own (case C), started from those case C (then A) designs
  and keeping the first one's inverse plant and tau_eq.

The wake-identified inflow of cases B and C is, by default, **our 12-state
near/far-wake model with flap-rate inputs** (Eqs. 6.2-6.3 structure, as the
dissertation's §7.5 flew) **and tip-path-plane tilt inputs**
(:mod:`aircraft.identification.structures.tilt`: our coaxial wake's inflow answers a held
tilt), identified from our own free-vortex wake, shipped as
``aircraft/data/models/coaxial_hover_12state_tilt.json`` and flown by
:class:`aircraft.helicopter.tilt_coupling.TiltCoupledHelicopter` (the tilts are the
flapping states). Further rows fly our flap-rate-only 12-state
(``coaxial_hover_12state``), our 6-state
model (``coaxial_hover_6state``), our 6-state with every coupling hover's
axisymmetry allows and the collective apparent masses held at Pitt-Peters'
(``coaxial_hover_6state_axisymmetric``) and the dissertation's printed Eq. 5.3 and
Eq. 6.8-6.9 models (converted to our rotor frames by
:func:`aircraft.inflow.published.in_rotor_frames`; the 12-state from its shipped file
``published_eq6_8_6_9``) the same way: (B) the DC design on that aircraft, (C) a design optimised on it.
``--identified published`` puts Eq. 5.3 in cases B/C instead (the former default);
``--free-drift`` leaves u and v free in the roll design plants, as Eq. 7.21 literally
does. By default they are held (a perfectly tight position-hold outer loop,
:func:`aircraft.helicopter.hold.hold_states`): the plant reduction's minimal
realisation removes the translational drift from the Dynamic-Climb plant by its
tolerance anyway (its plant equals the held one within 0.1 dB and 1 deg), but not
from the identified-inflow plants, whose drift then leaves slow zero pairs near the
origin; holding it in every plant makes the comparison consistent;
``--regenerate`` rebuilds our four shipped coaxial models from the free wake first (about 55
minutes on 2 cores uncached; progress shown, wake runs cached).

Each aircraft is our coaxial model (:mod:`aircraft.helicopter`) trimmed in hover
and linearised; the roll-axis plant is the coupling numerator
p/delta_lat | q->delta_lon, r->delta_ped, w->delta_col (Eq. 7.21), built by
:func:`controllers.roll_design_plant`. All three PID gains are free (no K_Iphi
tie), bounded below by 0; the DMO raises its boundaries by bisection to 0.5 %.
Stage 1 also runs the identification pipeline end to end on an embedded truth
(:mod:`studies.identification_demo`).

The effective roll damping and control power of every aircraft against frequency
(``roll_derivatives.csv``/``.png``) show where the identified inflow models act
outside the band they were fitted on; ``slow_zeros.csv`` lists each roll plant's
zeros below 2 rad/s (a right-half-plane one there traps a closed-loop pole of a
design with integral action).

Writes tables (CSV) and figures (PNG) under ``results/hover_control_comparison/``
and prints Tables 7.4/7.5-style summaries with the dissertation's values in
separate columns (for cases A, B, C).  Run: ``make study`` or
``python -m studies.hover_control_comparison``.
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
from aircraft.helicopter import (HelicopterSettings, effective_derivative, flap_mode_damping,
                                 linearize, modes, trim)
from aircraft.helicopter.hold import hold_states
from aircraft.helicopter.tilt_coupling import helicopter_for
from aircraft.identification.structures.tilt import tilt_inflow_from_record
from aircraft.inflow import DynamicClimb, IdentifiedInflow
from aircraft.inflow.published import COAXIAL_HOVER_6STATE, in_rotor_frames
from controllers import (CommandModel, EMFDesign, InfeasibleDesignError, PIDGains, default_specs, dmo, evaluate_specs, hq_window, roll_design_plant)
from controllers.plants import second_order_actuator
from controllers.metrics import damping_in_band, gain_phase_margins

# reference values of Tables 7.4 / 7.5 (comparison columns only, never outputs)
DISSERTATION_74 = {"K_p": (0.0413, 0.0413, 0.0326), "K_phi": (0.303, 0.303, 0.582),
                   "K_Iphi": (0.212, 0.212, 0.626), "tau_eq": (0.0265, 0.0265, 0.0454)}
DISSERTATION_75 = {"crossover_rad_s": (3.53, 3.47, 5.38), "GM_dB": (7.2, 6.25, 6.00),
                   "PM_deg": (45.0, 73.0, 47.7), "min_zeta_4_20": (0.1048, 0.148, 0.193),
                   "DRB_rad_s": (1.89, 1.97, 2.91), "DRP_dB": (4.38, 2.35, 4.87)}


#: inflow keys of the printed models flown as comparison rows (never in case D)
PRINTED = ("Eq. 5.3", "Eq. 6.8-6.9")


def roll_plant(inflow, settings, hold=()):
    """Trim the coaxial in hover with ``inflow``; return (roll design plant, linear model, trim).

    ``hold``: states held at trim in the design plant only (u, v by default; none with ``--free-drift``)."""
    tr = trim(helicopter_for(coaxial_compound(), inflow, settings))
    sys = linearize(tr)
    return roll_design_plant(hold_states(sys, hold) if hold else sys), sys, tr


def slow_zeros(plants, limit=2.0):
    """Zeros of each roll plant's rational part with |s| < ``limit`` [rad/s], one row each."""
    rows = []
    for name, plant in plants.items():
        for z in np.sort_complex(np.asarray(control.zeros(plant.system), dtype=complex)):
            if abs(z) < limit:
                rows.append({"aircraft": name, "real_1_s": float(z.real), "imag_rad_s": float(z.imag)})
    return pd.DataFrame(rows, columns=["aircraft", "real_1_s", "imag_rad_s"])


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


DERIVATIVE_OMEGA = np.r_[0.0, np.geomspace(0.05, 20.0, 41)]   # rad/s; 1.0 is on the grid


def roll_derivatives(systems, omega=DERIVATIVE_OMEGA):
    """Effective roll damping L_p and control power L_delta_lat of each linear aircraft
    over ``omega`` [rad/s] (:func:`aircraft.helicopter.effective_derivative`), long form."""
    rows = []
    for name, sys in systems.items():
        lp = effective_derivative(sys, "p", "p", omega)
        ld = effective_derivative(sys, "p", "delta_lat", omega)
        rows += [{"aircraft": name, "omega_rad_s": w, "Lp_real_1_s": a.real, "Lp_imag_1_s": a.imag,
                  "Ldelta_real": b.real, "Ldelta_imag": b.imag} for w, a, b in zip(omega, lp, ld)]
    return pd.DataFrame(rows)


def derivative_figure(derivs, fit_range=(1.0, 25.0)):
    """Re L_p and |L_delta_lat| against frequency, the identified models' fit band shaded."""
    fig = Figure(figsize=(10, 4), constrained_layout=True)
    ax_p, ax_d = fig.subplots(1, 2)
    for name, d in derivs[derivs.omega_rad_s > 0].groupby("aircraft", sort=False):
        ax_p.semilogx(d.omega_rad_s, d.Lp_real_1_s, label=name)
        ax_d.semilogx(d.omega_rad_s, np.hypot(d.Ldelta_real, d.Ldelta_imag), label=name)
    for ax in (ax_p, ax_d):
        ax.axvspan(*fit_range, color="0.9", zorder=0)
        ax.set_xlabel("frequency [rad/s] (shaded: identified models' fit band)")
        ax.grid(True, which="both", alpha=0.3)
    ax_p.axhline(0.0, color="k", lw=0.8)
    ax_p.set_ylabel("Re L_p [1/s] (negative: damped)")
    ax_d.set_ylabel("|L_delta_lat| [rad/s^2 per stick unit]")
    ax_p.legend(fontsize=8)
    ax_p.set_title("effective roll damping, body rate held at exp(j omega t)")
    ax_d.set_title("effective roll control power")
    return fig


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

    fig = Figure(figsize=(11, 2.4 * len(names) + 0.4), constrained_layout=True)
    axes = fig.subplots(len(names), 3, sharex=True, squeeze=False)   # one row per case, none empty
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


def _design(plant, start, command, actuator, label, failures=None):
    """DMO on one plant (None, with the reason printed and added to ``failures``, if no
    design is feasible)."""
    base = EMFDesign(plant, start, command, actuator, sensor_delay=0.01)
    try:
        res = dmo(base, progress=True)
    except InfeasibleDesignError as err:
        print(f"  {label}: infeasible ({err})")
        if failures is not None:
            failures.append(f"{label}: {err}")
        return None
    print(f"  {label}: {res.message} ({res.wall_time:.0f} s)")
    return res


def main(argv=None):
    parser = argparse.ArgumentParser(description="Hover control comparison (dissertation §7.5)")
    parser.add_argument("--seed", type=int, default=0, help="seed of the identification stage")
    parser.add_argument("--out", default="results", help="output folder")
    parser.add_argument("--skip-identification", action="store_true")
    parser.add_argument("--n-span", type=int, default=8, help="blade-element Gauss points")
    parser.add_argument("--identified", choices=("ours", "published"), default="ours",
                        help="inflow of cases B and C: our 12-state model with tilt inputs identified from our free wake "
                             "(shipped file aircraft/data/models/coaxial_hover_12state_tilt.json; default), or the "
                             "dissertation's Eq. 5.3 6-state model converted to our rotor frames")
    parser.add_argument("--free-drift", action="store_true",
                        help="leave u and v free in the roll design plants, as Eq. 7.21 literally does (the "
                             "default holds them): writes hover_control_comparison_free_drift")
    parser.add_argument("--regenerate", action="store_true",
                        help="rebuild our four shipped 6- and 12-state models from the free wake first "
                             "(progress shown, wake runs cached; ~55 min on 2 cores uncached)")
    args = parser.parse_args(argv)
    t_start = time.perf_counter()
    if not args.skip_identification:
        from studies.identification_demo import run_demo
        print("[stage 1] identification pipeline on the embedded 6-state coaxial truth")
        cost = run_demo(seed=args.seed, out_dir=f"{args.out}/identification_demo")
        print(f"[stage 1] done: J_ave = {cost.J.mean():.2f} over {len(cost)} responses\n")
    if args.regenerate:
        from aircraft.identification.shipped import regenerate
        for name in ("coaxial_hover_6state", "coaxial_hover_6state_axisymmetric", "coaxial_hover_12state",
                     "coaxial_hover_12state_tilt"):
            print(f"[regenerate] {name} from the free wake")
            regenerate(name, progress=True)

    suffix = {"ours": "", "published": "_published"}[args.identified] + ("_free_drift" if args.free_drift else "")
    out = Path(args.out) / ("hover_control_comparison" + suffix)
    out.mkdir(parents=True, exist_ok=True)
    settings = HelicopterSettings(n_span=args.n_span, n_average=1)   # hover: axisymmetric
    # the inflow models flown: Dynamic Climb, the identified model of cases B/C, and
    # (with ours) our 6-state model and the printed Eq. 5.3 model as further rows
    published6 = IdentifiedInflow.from_published(in_rotor_frames(COAXIAL_HOVER_6STATE))
    if args.identified == "ours":
        from aircraft.inflow.model_files import load_record
        from aircraft.identification import trust_check
        inflows = {"ID": tilt_inflow_from_record("coaxial_hover_12state_tilt"),
                   "ID12R": IdentifiedInflow.from_file("coaxial_hover_12state"),
                   "ID6": IdentifiedInflow.from_file("coaxial_hover_6state"),
                   "IDA": IdentifiedInflow.from_file("coaxial_hover_6state_axisymmetric"), "Eq. 5.3": published6,
                   # the 12-state the dissertation's §7.5 flew, in our rotor frames (shipped file)
                   "Eq. 6.8-6.9": IdentifiedInflow.from_file("published_eq6_8_6_9")}
        for key, name in (("ID", "coaxial_hover_12state_tilt"), ("ID12R", "coaxial_hover_12state"),
                          ("ID6", "coaxial_hover_6state"),
                          ("IDA", "coaxial_hover_6state_axisymmetric")):
            rec = load_record(name)
            check = trust_check(rec)
            why = "trusted" if check.passes else "NOT trusted: " + check.failures[0][:110]
            print(f"  {key}: shipped {name} (J_ave {rec.cost_table.J.mean():.1f}, {why})")
    else:
        inflows = {"ID": published6}
    labels = {"ID": "our 12-state" if args.identified == "ours" else "Eq. 5.3",
              "ID12R": "our 12-state, flap rates only", "ID6": "our 6-state",
              "IDA": "our axisymmetric 6-state", "Eq. 5.3": "Eq. 5.3 (printed)",
              "Eq. 6.8-6.9": "Eq. 6.8-6.9 (printed)"}
    print("[stage 2] trim + linearise the coaxial in hover with each inflow model")
    hold = () if args.free_drift else ("u", "v")
    plant_dc, sys_dc, tr_dc = roll_plant(DynamicClimb(), settings, hold)
    plants, systems = {"DC": plant_dc}, {"DC": sys_dc}
    print(f"  DC: trim residual {tr_dc.max_residual:.1e}, C_T U/L = {tr_dc.loads['CT_U']:.5f}/{tr_dc.loads['CT_L']:.5f}")
    for key, inflow in inflows.items():
        plants[key], systems[key], tr = roll_plant(inflow, settings, hold)
        print(f"  {key} ({labels[key]}): trim residual {tr.max_residual:.1e}, "
              f"C_T U/L = {tr.loads['CT_U']:.5f}/{tr.loads['CT_L']:.5f}")
    aircraft_name = {k: ("Dynamic Climb" if k == "DC" else labels[k]) for k in systems}
    pd.concat([modes(systems[k]).assign(aircraft=aircraft_name[k]) for k in systems]) \
        .to_csv(out / "aircraft_modes.csv", index=False)
    # where each inflow model changes the roll damping and control power: the
    # identified models are fitted on 1-25 rad/s, and what they do below is extrapolation
    derivs = roll_derivatives({aircraft_name[k]: systems[k] for k in systems})
    derivs.to_csv(out / "roll_derivatives.csv", index=False)
    derivative_figure(derivs).savefig(out / "roll_derivatives.png", dpi=80)
    # a non-minimum-phase zero below crossover traps a closed-loop pole of any design
    # with integral action (EigLcG1 fails by about the zero): list each plant's slow ones
    slow = slow_zeros({aircraft_name[k]: plants[k] for k in plants})
    slow.to_csv(out / "slow_zeros.csv", index=False)
    rhp = slow[slow.real_1_s > 0]
    print("slow right-half-plane zeros of the roll plants p/delta_lat (|s| < 2 rad/s): "
          + ("; ".join(f"{r.aircraft} {r.real_1_s:+.3g}{r.imag_rad_s:+.3g}j" for r in rhp.itertuples())
             or "none"))
    print(derivs[derivs.omega_rad_s.isin([0.0, 1.0])].pivot(index="aircraft", columns="omega_rad_s",
                                                              values="Lp_real_1_s")
          .rename(columns=lambda w: f"Re L_p at {w:g} rad/s [1/s]").to_string(float_format="%.2f"))

    actuator = second_order_actuator(35.0, 0.7)
    command = CommandModel(frequency=4.0, damping=0.7, gain=0.05)
    start = PIDGains(0.3, 0.1, 0.05)
    print("[stage 3] DMO, case (A): design on the Dynamic-Climb aircraft")
    failures = []
    res_a = _design(plant_dc, start, command, actuator, "case (A)", failures)
    if res_a is None:
        # a result, not a crash: the plants' modes, derivatives and slow zeros are written above
        (out / "infeasible.txt").write_text("\n".join(failures) + "\n")
        print("case (A) has no feasible design: nothing to compare against (infeasible.txt)")
        return out
    results = {"A": res_a}
    for key in inflows:
        print(f"[stage 3] DMO on the {labels[key]} aircraft")
        results[key] = _design(plants[key], start, command, actuator, f"design on {labels[key]}", failures)
    for key in systems:
        unstable = [complex(p) for p in np.linalg.eigvals(np.asarray(systems[key].A)) if p.real > 1e-9]
        if unstable:
            print(f"  bare {labels.get(key, key)} aircraft: unstable poles "
                  + ", ".join(f"{p.real:.3g}{p.imag:+.3g}j" for p in unstable[:4]) + " 1/s")
    # an infeasible case is a result, not a crash: it is reported (infeasible.txt) and
    # the other rows are still flown
    res_c = results["ID"]
    # case D: one gain set for the DC aircraft and every identified aircraft of ours
    # that has a design of its own (case C feasible): where not even a design for that
    # aircraft alone meets every spec, no robust one can. The printed Eq. 5.3 and
    # Eq. 6.8-6.9 are comparison rows, not ours. The feed-forward (inverse plant, tau_eq) is the
    # first such case C's, as one controller would fly.
    ours = [k for k in inflows if k not in PRINTED]
    robust_keys = [k for k in ours if results[k] is not None]
    skipped = [labels[k] for k in ours if results[k] is None]
    robust_plants = {"DC": plant_dc, **{labels[k]: plants[k] for k in robust_keys}}
    robust_key_of = {"DC": "DC", **{labels[k]: k for k in robust_keys}}
    res_d, d_failures = None, []
    if skipped:
        print(f"  case (D) leaves out {', '.join(skipped)}: no design for that aircraft alone meets every spec")
        d_failures.append(f"left out of case (D) (case C infeasible on them): {', '.join(skipped)}")
    if robust_keys:
        print(f"[stage 3] DMO, case (D): robust design on {', '.join(robust_plants)}")
    # start from the optimised single-plant designs (their gains and feed-forward):
    # a robust design, if one exists, lies nearer those than the generic start
    starts = [(f"case C design on {labels[k]}", results[k].design) for k in robust_keys] + [
        ("case A design", res_a.design),
        ("starting gains", EMFDesign(plants[robust_keys[0]], start, command, actuator, sensor_delay=0.01))
    ] if robust_keys else []
    for label, start_design in starts:
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
    else:
        (out / "robust_infeasible.txt").unlink(missing_ok=True)
    # (case name, design, plant key of the bare airframe, dissertation column or None)
    rows_spec = [("(A) DC on DC", res_a.design, "DC", 0),
                 (f"(B) DC on {labels['ID']}", res_a.design.with_plant(plants["ID"]), "ID", 1)]
    if res_c is not None:
        rows_spec.append((f"(C) {labels['ID']} on {labels['ID']}", res_c.design, "ID", 2))
    for key in ("ID12R", "ID6", "IDA") + PRINTED:
        if key in inflows:
            rows_spec.append((f"(B) DC on {labels[key]}", res_a.design.with_plant(plants[key]), key, None))
            if results[key] is not None:
                rows_spec.append((f"(C) {labels[key]} on {labels[key]}", results[key].design, key, None))
    cases = {name: design for name, design, _, _ in rows_spec}
    bare_of = {name: key for name, _, key, _ in rows_spec}
    column = {name: col for name, _, _, col in rows_spec}
    specs_of = {name: ("A" if name.startswith("(A)") or name.startswith("(B)") else
                       next(k for k in inflows if name.endswith(f"on {labels[k]}"))) for name in cases}
    robust = ({f"(D) robust on {name}": d for name, d in zip(robust_plants, res_d.designs)}
              if res_d is not None else {})
    for name, key in zip(robust, robust_plants):
        bare_of[name] = robust_key_of[key]
        column[name] = None

    def final_specs(res):
        return default_specs(res.crossover_boundary, res.drb_boundary)

    specs_by_key = {"A": final_specs(res_a), **{k: final_specs(r) for k, r in results.items()
                                                 if k != "A" and r is not None}}
    specs_d = final_specs(res_d) if res_d is not None else specs_by_key["A"]
    spec_set = lambda name: specs_d if name.startswith("(D)") else specs_by_key[specs_of[name]]  # noqa: E731

    def gains(design):
        return [design.gains.K_p, design.gains.K_phi, design.gains.K_Iphi, design.equivalent_delay]

    t74 = pd.DataFrame({"parameter": ["K_p", "K_phi", "K_Iphi", "tau_eq"],
                        "ours (A)&(B)": gains(res_a.design),
                        f"ours (C) {labels['ID']}": gains(res_c.design) if res_c is not None else [np.nan] * 4,
                        **{f"ours (C) {labels[k]}": gains(results[k].design) for k in ("ID12R", "ID6", "IDA") + PRINTED
                           if k in results and results[k] is not None},
                        "ours (D) robust": gains(res_d.design) if res_d is not None else [np.nan] * 4,
                        "dissertation (A)&(B)": [DISSERTATION_74[k][0] for k in ("K_p", "K_phi", "K_Iphi", "tau_eq")],
                        "dissertation (C)": [DISSERTATION_74[k][2] for k in ("K_p", "K_phi", "K_Iphi", "tau_eq")]})
    rows = []
    for name, design in {**cases, **robust}.items():
        k = column[name]
        ch = characteristics(design, spec_set(name))
        rows.append({"case": name, **ch, **{f"dissertation {key}": (val[k] if k is not None else np.nan)
                                            for key, val in DISSERTATION_75.items()}})
    t75 = pd.DataFrame(rows)
    # where the regressive flap (flap-body) modes sit with the loop closed, each tracked
    # from its bare-airframe pole (the dissertation's "min zeta 4-20 rad/s" is this
    # mode; ours may sit just outside the band, and then the band minimum is the
    # command model's 0.7)
    flap_rows = []
    for name, design in {**cases, **robust}.items():
        bare = flap_mode_damping(systems[bare_of[name]]).reset_index(drop=True)
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
    pd.concat([r.history.assign(case=("A" if k == "A" else f"C {labels[k]}")) for k, r in results.items()
               if r is not None] + ([res_d.history.assign(case="D")] if res_d is not None else [])) \
        .to_csv(out / "dmo_history.csv", index=False)
    for old in out.glob("specs_*.csv"):
        old.unlink()
    spec_tables = [evaluate_specs(design, spec_set(name)).assign(case=name) for name, design in cases.items()]
    pd.concat(spec_tables).to_csv(out / "specs.csv", index=False)
    if res_d is not None:
        res_d.specs.assign(case="(D) robust").to_csv(out / "specs_D.csv", index=False)
    main_cases = {name: cases[name] for name, _, _, col in rows_spec if col is not None}
    figures(main_cases, out)
    hq_window(list(cases.values()), specs_by_key["A"], labels=list(cases)).savefig(out / "hq_window.png", dpi=80)
    if robust:
        hq_window(list(robust.values()), specs_d, labels=list(robust_plants)).savefig(out / "hq_window_robust.png",
                                                                                      dpi=80)
    else:                  # no robust design: no figure of an earlier one left behind
        (out / "hq_window_robust.png").unlink(missing_ok=True)

    fmt = lambda v: f"{v:.4g}"   # noqa: E731
    pd.set_option("display.width", 200)
    print("\n== Optimal controller parameters (cf. Table 7.4; stick units differ, compare trends) ==")
    print(t74.to_string(index=False, float_format=fmt))
    print("\n== Optimal controller characteristics (cf. Table 7.5) ==")
    ours = t75[["case", "crossover_rad_s", "GM_dB", "PM_deg", "min_zeta_4_20", "DRB_rad_s", "DRP_dB", "all_specs_met",
                "most_limiting_spec"]]
    print(ours.to_string(index=False, float_format=fmt))
    print("dissertation (A, B, C): " + "; ".join(f"{k} = {v}" for k, v in DISSERTATION_75.items()))
    print("\n== Regressive flap (flap-body) modes: bare airframe -> closed loop ==")
    print(flap[["case", "mode", "bare_frequency_rad_s", "bare_damping", "closed_loop_frequency_rad_s",
                "closed_loop_damping", "in_band_4_20"]].to_string(index=False, float_format=fmt))
    wc = t75.set_index("case").crossover_rad_s
    name_a = rows_spec[0][0]
    ratio_ref = DISSERTATION_75['crossover_rad_s'][2] / DISSERTATION_75['crossover_rad_s'][0]
    c_rows = [name for name in cases if name.startswith("(C)")]
    for name_c in c_rows:
        print(f"crossover gain from the identified-inflow design {name_c} over (A): "
              f"{wc[name_c] / wc[name_a]:.2f} (dissertation, its 12-state: {ratio_ref:.2f})")
    if res_c is None:
        print(f"case (C) on the {labels['ID']} aircraft: no feasible design (see infeasible.txt)")
    if failures:
        (out / "infeasible.txt").write_text("\n".join(failures) + "\n")
    else:
        (out / "infeasible.txt").unlink(missing_ok=True)
    if res_d is not None:
        for k in robust_keys:
            wc_c = wc[f"(C) {labels[k]} on {labels[k]}"]
            print(f"robustness cost, (D) over {', '.join(robust_plants)} vs (C) on {labels[k]}: crossover "
                  f"{res_d.crossover:.3f} vs {wc_c:.3f} rad/s ({res_d.crossover / wc_c - 1:+.1%})")
    else:
        print("robustness: no robust design (D) over " + ", ".join(robust_plants) + " at the starting boundaries")
    print(f"tables and figures in {out}/  (wall {time.perf_counter() - t_start:.0f} s)")


if __name__ == "__main__":
    main()
