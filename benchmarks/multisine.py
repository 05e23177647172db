"""Benchmark: an inflow model from ONE multisine record vs one sweep per control.

Identifies :class:`aircraft.identification.Coaxial6State` on the coaxial compound
rotor (hover, system C_T 0.0053 + 0.0043 split equally, torques balanced), or with
``--rotor single`` the 3-state model of the UH-60-like rotor (C_T 0.0061, the
shipped ``uh60_hover_3state``'s recipe), on the same wake twice (``--wake coarse``, the default, or ``--wake default``, the
resolution of the shipped models):

(a) one sweep per control (six on the coaxial; :func:`aircraft.identification.identify_inflow`);
(b) ONE record of all the swashplate controls with orthogonal multisines
    (:func:`aircraft.identification.identify_inflow_multisine`).

Prints the wake revolutions each needs (target (b) <= 1/3 of (a)), the parameter
differences (target < 5 % on the well-identified parameters, CR < 20 % in both),
J_ave of each (target within 20 %) and writes a Bode overlay of both measured
lambda/C responses and fitted models. It first runs the same comparison on the
synthetic truth (the published model simulated with scipy; ``--synthetic-only``
runs just that, in a minute, and writes ``synthetic.txt``). Outputs go to ``--out``
(default ``benchmarks/results/multisine``): ``summary.txt``, ``parameters.csv``,
``bode.png``, ``parameters_same_structure.csv`` (the multisine data refitted on the
six-sweep reduction's parameter set), ``cross_costs.csv`` (each model's J_ave on
each experiment's data: how flat the valley between the two estimates is),
``data_difference.csv`` (the two measured lambda/C against each other, per pair and
band, where both are coherent) and ``weighting.csv``: the six-sweep structure refitted, from the six-sweep optimum, on
each data set with each data set's coherence weighting and with unit weights. It
separates what the data differ in from what the CIFER weighting (coherence) does
to a structure that does not fit them (J_ave ~ 200). ``--second-amplitude A``
adds a multisine of peak A [rad]: if the differences were noise they would shrink
with a larger input.
"""
import argparse
import io
import math
import time
from contextlib import redirect_stdout
from pathlib import Path

import numpy as np
import pandas as pd

from _costs import cost_on   # benchmarks/ is on the path when a benchmark runs as a script

CT_SYSTEM = 0.0053 + 0.0043
PAIRS = [("lam0_U", "CT_U"), ("lam1s_U", "CL_U"), ("lam0_L", "CT_L"), ("lam1s_L", "CL_L"),
         ("lam0_L", "CT_U"), ("lam0_U", "CT_L"), ("lam1s_L", "CL_U"), ("lam1s_U", "CL_L")]
#: ``--rotor``: (configuration function in aircraft.configs, default structure key,
#: system trim C_T, Bode pairs). ``single`` is the UH-60-like rotor of the shipped,
#: trusted ``uh60_hover_3state`` (its recipe's structure and C_T): the comparison on
#: a structure that fits its wake, beside the coaxial one on structures that do not.
ROTORS = {
    "coaxial": ("coaxial_compound", "coaxial_6state", CT_SYSTEM, PAIRS),
    "single": ("uh60_single_rotor", "single_rotor_3state", 0.0061,
               [("lam0", "CT"), ("lam1s", "CL"), ("lam1c", "CM")]),
}


def _sweep_revolutions(settings, controls, omega, dt):
    """Revolutions of the six sweep records identify_inflow marches (same specs as it builds)."""
    from aircraft.wake import SweepSpec
    from aircraft.wake.sweeps import sweep_inputs
    s = settings
    total = 0.0
    for k, c in enumerate(controls):
        t, _ = sweep_inputs(SweepSpec(c, kind="sweep", amplitude=s.amplitude, duration=s.sweep_s,
                                      w_min=s.w_min, w_max=s.w_max, seed=k), dt)
        total += t[-1] * omega / (2 * np.pi)
    return total


def _compare(pa, pb, cr_max):
    a = pa.set_index("parameter")
    b = pb.set_index("parameter")
    df = pd.DataFrame({"value_sweeps": a.value, "status_sweeps": a.status, "CR_sweeps_pct": a.cramer_rao_pct,
                       "value_multisine": b.value, "status_multisine": b.status,
                       "CR_multisine_pct": b.cramer_rao_pct})
    df["diff_pct"] = 100 * (df.value_multisine - df.value_sweeps) / df.value_sweeps.abs().where(
        df.value_sweeps != 0)
    df["well_identified"] = ((df.status_sweeps == "free") & (df.status_multisine == "free")
                             & (df.CR_sweeps_pct < cr_max) & (df.CR_multisine_pct < cr_max))
    return df.reset_index()


def _same_structure(model_a, model_b, settings):
    """Fit the multisine data with the six-sweep model's reduced structure: the same free
    and fixed parameters (fixed ones at the sweep model's values), started from the
    multisine model's own optimum. Compares estimates of one parameter set, not of two
    reductions' different sets."""
    from flightid import fit
    sa, sb = model_a.fit.structure, model_b.fit.structure
    fixed = [n for n in sa.names if n not in sa.free_names]
    start = sb.with_values({n: sa.values[n] for n in fixed}).free(sa.free_names).fix(fixed)
    pairs = list(zip(model_a.cost_table.output, model_a.cost_table.input))
    return fit(start, model_b.responses, pairs=pairs, frequency_ranges=tuple(settings.fit_range),
               n_omega=settings.n_omega, coherence_min=settings.coherence_min)


def _data_difference(model_a, model_b, settings, bands=((1.0, 5.0), (5.0, 12.0), (12.0, 25.0))):
    """How far apart the two measured lambda/C are, per fitted pair and band: the median
    |magnitude difference| [dB] and |phase difference| [deg] over the points where both
    are coherent (>= coherence_min). Lbar is set by the low band, M by the upper ones."""
    ra, rb = model_a.responses, model_b.responses
    rows = []
    for o, i in zip(model_a.cost_table.output, model_a.cost_table.input):
        ha, ca = ra.element(o, i)
        hb, cb = rb.element(o, i)
        for lo, hi in bands:
            sel = (ra.omega >= lo) & (ra.omega <= hi) & (ca >= settings.coherence_min) & (cb >= settings.coherence_min)
            if not sel.any():
                rows.append({"output": o, "input": i, "band": f"{lo:g}-{hi:g}", "points": 0,
                             "median_abs_dmag_db": np.nan, "median_abs_dphase_deg": np.nan})
                continue
            dmag = 20 * np.log10(np.abs(hb[sel]) / np.abs(ha[sel]))
            dph = np.degrees(np.angle(hb[sel] / ha[sel]))
            rows.append({"output": o, "input": i, "band": f"{lo:g}-{hi:g}", "points": int(sel.sum()),
                         "median_abs_dmag_db": float(np.median(np.abs(dmag))),
                         "median_abs_dphase_deg": float(np.median(np.abs(dph)))})
    return pd.DataFrame(rows)


def _sweeps_label(n):
    """'six sweeps', 'three sweeps': the label of the one-sweep-per-control experiment."""
    return {3: "three sweeps", 6: "six sweeps"}.get(n, f"{n} sweeps")


def _weighting(model_a, model_b, settings, label="six sweeps"):
    """The six-sweep reduced structure refitted (from its own optimum) on each data set
    with each weighting; the largest parameter difference from the six-sweep model."""
    from flightid import MeasuredResponse, fit
    sa = model_a.fit.structure
    pairs = list(zip(model_a.cost_table.output, model_a.cost_table.input))
    ra, rb = model_a.responses, model_b.responses
    if not np.array_equal(ra.omega, rb.omega):
        return pd.DataFrame()

    def weighted(r, coh):
        return MeasuredResponse(r.frdata, r.omega, coh, r.input_labels, r.output_labels)
    cases = [(label, f"{label}'", ra), ("multisine", "multisine's", rb),
             ("multisine", f"{label}'", weighted(rb, ra.coherence)),
             (label, "multisine's", weighted(ra, rb.coherence)),
             (label, "unit", weighted(ra, np.ones_like(ra.coherence))),
             ("multisine", "unit", weighted(rb, np.ones_like(rb.coherence)))]
    rows = []
    for data, weights, resp in cases:
        f = fit(sa, resp, pairs=pairs, frequency_ranges=tuple(settings.fit_range), n_omega=settings.n_omega,
                coherence_min=settings.coherence_min)
        v = f.structure.values
        diffs = {n: 100 * (v[n] - sa.values[n]) / abs(sa.values[n]) for n in sa.free_names if not n.startswith("t")}
        worst = max(diffs, key=lambda n: abs(diffs[n]))
        rows.append({"data": data, "coherence_weights": weights, "J_ave": f.J_ave,
                     "max_abs_diff_pct_M_Lbar": abs(diffs[worst]), "worst_parameter": worst,
                     **{f"diff_{n}_pct": d for n, d in diffs.items()}})
    return pd.DataFrame(rows)


def run(duration, out, n_jobs, amplitude, wake_name="coarse", second_amplitude=None,
        structure_key=None, rotor="coaxial"):
    from aircraft import configs
    from aircraft.identification import IdentificationSettings, get_structure, identify_inflow
    from aircraft.identification.multisine import MultisineSettings, identify_inflow_multisine
    from aircraft.wake import WakeSettings
    from flightid.plotting import bode_with_coherence

    config_name, default_key, ct_system, bode_pairs = ROTORS[rotor]
    structure_key = structure_key or default_key
    config = getattr(configs, config_name)()
    structure = get_structure(structure_key)
    n_sweeps = len(structure.controls)
    label = _sweeps_label(n_sweeps)
    experiment = label.replace(" sweeps", "-sweep")               # "six-sweep"
    model_label = f"{experiment} model"
    # default: the resolution of the shipped coaxial models (its six sweeps are the
    # first six records of the 12-state data set, so they come from the wake cache)
    wake = (WakeSettings() if wake_name == "default"
            else WakeSettings(azimuth_step=math.radians(15), wake_revolutions=2.0, n_elements=6))
    settings = IdentificationSettings(wake=wake)
    ms = MultisineSettings(duration=duration, amplitude=amplitude)
    omega = float(config.rotors[0].omega)
    dt = wake.azimuth_step / omega
    print(f"== multisine benchmark: {rotor} hover model ({structure_key}), {n_sweeps} sweeps vs ONE "
          "multisine record ==")
    print(f"configuration: {config_name}() (omega {omega} rad/s), hover, system C_T {ct_system:.4f}"
          f"{' split equally, torque balanced' if len(config.rotors) > 1 else ''}; {wake_name} wake {wake}, "
          f"dt {dt:.5f} s; default IdentificationSettings "
          f"(sweeps {settings.sweep_s} s x {n_sweeps} at {settings.amplitude} rad, band {settings.w_min}-{settings.w_max} "
          f"rad/s, fit {settings.fit_range}); multisine {ms}")
    t0 = time.perf_counter()
    model_a = identify_inflow(config, None, structure, ct=ct_system, settings=settings, n_jobs=n_jobs,
                              progress=False)
    wall_a = time.perf_counter() - t0
    t0 = time.perf_counter()
    model_b = identify_inflow_multisine(config, None, structure, ct=ct_system, settings=settings, multisine=ms,
                                        n_jobs=n_jobs, progress=False)
    wall_b = time.perf_counter() - t0
    revs_a = _sweep_revolutions(settings, structure.controls, omega, dt)
    revs = model_b.provenance["revolutions"]
    revs_b = next(v for k, v in revs.items() if k.startswith("multisine"))
    shared = sum(v for k, v in revs.items() if k.startswith("doublet_")) + revs["zero_input"]
    ratio = revs_b / revs_a
    print(f"\nwall time (runs already in the wake cache cost nothing): {n_sweeps} sweeps {wall_a:.0f} s, "
          f"multisine {wall_b:.0f} s")
    print(f"excitation: {model_b.provenance['excitation']}")
    print(f"\nwake revolutions of the identification records: {n_sweeps} sweeps {revs_a:.0f}, one multisine "
          f"{revs_b:.0f} -> ratio {ratio:.3f} (target <= 1/3: {'met' if ratio <= 1 / 3 else 'NOT met'}); "
          f"both also march the same doublet + zero-input runs ({shared:.0f} revs): totals "
          f"{revs_a + shared:.0f} vs {revs_b + shared:.0f} ({(revs_b + shared) / (revs_a + shared):.3f})")
    cmp = _compare(model_a.parameters, model_b.parameters, settings.cramer_rao_max)
    well = cmp[cmp.well_identified]
    max_diff = well.diff_pct.abs().max() if len(well) else float("nan")
    print(f"\nJ_ave: {n_sweeps} sweeps {model_a.J_ave:.1f}, multisine {model_b.J_ave:.1f} -> ratio "
          f"{model_b.J_ave / model_a.J_ave:.3f} (target within 20 %: "
          f"{'met' if abs(model_b.J_ave / model_a.J_ave - 1) <= 0.2 else 'NOT met'})")
    print(f"parameters: {len(well)} well identified in both (free, CR < {settings.cramer_rao_max:g} %); "
          f"largest difference {max_diff:.2f} % (target < 5 %: {'met' if max_diff < 5 else 'NOT met'}); "
          f"{int((well.diff_pct.abs() < 5).sum())} of {len(well)} within 5 %")
    with pd.option_context("display.width", 200, "display.max_columns", 20):
        print(cmp.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    # why the estimates differ: (1) refit on one parameter set; (2) each model's cost on
    # the other experiment's data -- a model that costs little more on the other data
    # than that data's own optimum sits in the same (flat) valley of its cost
    same = _same_structure(model_a, model_b, settings)
    cmp_same = _compare(model_a.parameters, same.parameters, settings.cramer_rao_max)
    well_same = cmp_same[cmp_same.well_identified]
    print(f"\nsame structure (multisine data, the {experiment} reduction's free set): J_ave {same.J_ave:.1f}; "
          f"{len(well_same)} well identified, largest difference {well_same.diff_pct.abs().max():.2f} %, "
          f"{int((well_same.diff_pct.abs() < 5).sum())} of {len(well_same)} within 5 %")
    sa, sb = model_a.fit.structure, model_b.fit.structure
    cross = pd.DataFrame([
        {"model": m, "data": d, "J_ave_native_points": cost_on(st, resp, model_a.cost_table)}
        for m, st in ((model_label, sa), ("multisine model", sb))
        for d, resp in ((label, model_a.responses), ("multisine", model_b.responses))])
    print(f"cross costs (each model on each experiment's lambda/C, the {experiment} pairs and bands):")
    print(cross.to_string(index=False, float_format=lambda v: f"{v:.1f}"))
    diff = _data_difference(model_a, model_b, settings) if np.array_equal(
        model_a.responses.omega, model_b.responses.omega) else pd.DataFrame()
    if len(diff):
        print("\nthe measured lambda/C of the two experiments, where both are coherent (median |difference|):")
        piv = diff.pivot_table(index=["output", "input"], columns="band",
                               values=["median_abs_dmag_db", "median_abs_dphase_deg"])
        print(piv.to_string(float_format=lambda v: f"{v:.2f}"))
        by_band = diff.groupby("band")[["median_abs_dmag_db", "median_abs_dphase_deg"]].median()
        print("median over the pairs: " + "; ".join(f"{b} rad/s {r.median_abs_dmag_db:.2f} dB / "
                                                     f"{r.median_abs_dphase_deg:.1f} deg"
                                                     for b, r in by_band.iterrows()))
    weights = _weighting(model_a, model_b, settings, label)
    if len(weights):
        print(f"\nweighting (the {experiment} structure refitted from its optimum; M and Lbar differences "
              "from it):")
        print(weights[["data", "coherence_weights", "J_ave", "max_abs_diff_pct_M_Lbar", "worst_parameter"]]
              .to_string(index=False, float_format=lambda v: f"{v:.1f}"))
    if second_amplitude:
        ms2 = MultisineSettings(duration=duration, amplitude=second_amplitude)
        model_c = identify_inflow_multisine(config, None, structure, ct=ct_system, settings=settings, multisine=ms2,
                                            n_jobs=n_jobs, progress=False)
        cmp2 = _compare(model_a.parameters, model_c.parameters, settings.cramer_rao_max)
        well2 = cmp2[cmp2.well_identified]
        cmp3 = _compare(model_b.parameters, model_c.parameters, settings.cramer_rao_max)
        well3 = cmp3[cmp3.well_identified]
        print(f"\nsecond multisine, peak {second_amplitude:g} rad: J_ave {model_c.J_ave:.1f}; against the {n_sweeps} sweeps "
              f"{len(well2)} well identified, largest difference {well2.diff_pct.abs().max():.1f} %; against the "
              f"{amplitude:g} rad multisine {len(well3)} well identified, largest difference "
              f"{well3.diff_pct.abs().max():.1f} %")
        out.mkdir(parents=True, exist_ok=True)
        cmp2.to_csv(out / "parameters_second_amplitude.csv", index=False)
    out.mkdir(parents=True, exist_ok=True)
    weights.to_csv(out / "weighting.csv", index=False)
    diff.to_csv(out / "data_difference.csv", index=False)
    cmp_same.to_csv(out / "parameters_same_structure.csv", index=False)
    cross.to_csv(out / "cross_costs.csv", index=False)
    print(f"\ncost table ({n_sweeps} sweeps | multisine):")
    ct = model_a.cost_table.merge(model_b.cost_table, on=["output", "input"], how="outer",
                                  suffixes=("_sweeps", "_multisine"))
    print(ct.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    print(f"\nverification on the doublet ({n_sweeps} sweeps):")
    print(model_a.verification_table.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    print("verification on the doublet (multisine):")
    print(model_b.verification_table.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    cmp.to_csv(out / "parameters.csv", index=False)
    w = model_a.responses.omega
    sources = [(model_a.responses, f"{label} (data)"), (model_b.responses, "multisine (data)"),
               (model_a.fit.structure.to_frd(w, name=model_label), model_label),
               (model_b.fit.structure.to_frd(w, name="multisine model"), "multisine model")]
    fig = bode_with_coherence(sources, bode_pairs, max_columns=4)
    fig.suptitle(f"{rotor} ({structure_key}) lambda/C: {n_sweeps} sweeps ({revs_a:.0f} revs) vs one multisine "
                 f"({revs_b:.0f} revs), {wake_name} wake")
    fig.savefig(out / "bode.png", dpi=110)
    print(f"\nwrote {out / 'parameters.csv'} and {out / 'bode.png'}")


def synthetic(duration_sweep=100.0, duration_multisine=200.0, noise=0.02, seed=0):
    """The same comparison on the synthetic truth (the published Eq. 5.3 model, simulated with
    scipy through a fully populated mixing and a 0.05 s loads lag; seconds of CPU, no wake)."""
    import scipy.signal as sig
    from aircraft.identification.structures import Coaxial6State
    from aircraft.identification.testing import (SWASHPLATE_CONTROLS, coaxial_sweep_set, mixing_matrix, simulate_mltau)
    from aircraft.inflow.published import COAXIAL_HOVER_6STATE
    from flightid import (combine_responses, fit, frequency_response, joint_input_output, mimo_response, orthogonal_multisine)
    model = COAXIAL_HOVER_6STATE
    names_c, names_l = model.input_names, model.output_names
    dt, w_min, w_max = 0.01, 0.4, 40.0
    t0 = time.perf_counter()
    runs = coaxial_sweep_set(model, seed=seed, dt=dt, duration=duration_sweep, noise=noise, w_min=w_min,
                             w_max=w_max)
    simo = [frequency_response(r["t"], r["theta"], np.vstack([r["loads"], r["lam"]]).T, w_min=0.8, w_max=30.0,
                               input_name=SWASHPLATE_CONTROLS[r["control"]], output_names=names_c + names_l)
            for r in runs]
    sweeps = combine_responses(simo)
    # one record of all six controls: the same mixing, lag, model and noise as coaxial_sweep_set
    ms = orthogonal_multisine(6, duration_multisine, dt, w_min, w_max, 1e-3, spectrum="log", seed=seed)
    k_mix = mixing_matrix(6, seed)
    lag = sig.StateSpace(-20.0 * np.eye(6), 20.0 * k_mix, np.eye(6), np.zeros((6, 6)))
    _, loads, _ = sig.lsim(lag, ms.U, ms.t)
    loads = loads.T
    lam = simulate_mltau(model.M, model.Lbar, model.tau, model.omega, ms.t, loads)
    rng = np.random.default_rng(seed + 1)
    lam = lam + noise * rng.standard_normal(lam.shape) * lam.std(axis=1, keepdims=True)
    loads = loads + noise * rng.standard_normal(loads.shape) * loads.std(axis=1, keepdims=True)
    multi = mimo_response(ms.t, ms.U, np.vstack([loads, lam]).T, w_min=0.8, w_max=30.0,
                          input_names=SWASHPLATE_CONTROLS, output_names=names_c + names_l)
    structure = Coaxial6State("printed")
    truth = structure.published_values(model)
    start = np.random.default_rng(100)
    initial = {k: (v * start.uniform(0.7, 1.3) if not k.startswith("t") else 0.05) for k, v in truth.items()}
    results = {}
    for label, resp in (("sweeps", sweeps), ("multisine", multi)):
        lam_c = joint_input_output(resp.select(names_l), resp.select(names_c))
        results[label] = fit(structure.build(initial, model.omega), lam_c, frequency_ranges=(1.0, 25.0))
    wall = time.perf_counter() - t0
    pa, pb = results["sweeps"].parameters, results["multisine"].parameters
    cmp = _compare(pa, pb, 20.0)
    cmp["truth"] = cmp.parameter.map(truth)
    well = cmp[cmp.well_identified]
    secs_a = sum(r["t"][-1] for r in runs)
    print("\n== synthetic truth (published Eq. 5.3 model, scipy; no wake) ==")
    print(f"six sweeps of {duration_sweep:g} s (+3 s trim each) = {secs_a:.0f} s vs one multisine of "
          f"{duration_multisine:g} s: ratio {duration_multisine / secs_a:.3f}; noise {noise:.0%} of RMS; "
          f"multisine RPF {np.round(ms.relative_peak_factor, 2).tolist()}; wall {wall:.1f} s")
    ja, jb = results["sweeps"].J_ave, results["multisine"].J_ave
    print(f"J_ave: sweeps {ja:.2f}, multisine {jb:.2f}; {len(well)} well-identified parameters, largest "
          f"difference {well.diff_pct.abs().max():.2f} %, largest multisine error vs truth "
          f"{(100 * (well.value_multisine - well.truth) / well.truth.abs()).abs().max():.2f} % "
          f"(sweeps {(100 * (well.value_sweeps - well.truth) / well.truth.abs()).abs().max():.2f} %)")
    print(cmp.to_string(index=False, float_format=lambda v: f"{v:.4g}"))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=90.0, help="multisine record [s]")
    parser.add_argument("--amplitude", type=float, default=0.02, help="multisine peak per control [rad]")
    parser.add_argument("--second-amplitude", type=float, default=None,
                        help="also identify from a multisine of this peak [rad] (e.g. 0.04)")
    parser.add_argument("--jobs", type=int, default=2, help="wake worker processes")
    parser.add_argument("--wake", choices=("coarse", "default"), default="coarse",
                        help="wake resolution (coarse: 15 deg steps, 2 revs, 6 elements; default: WakeSettings())")
    parser.add_argument("--out", type=Path, default=Path("benchmarks/results/multisine"))
    parser.add_argument("--rotor", choices=sorted(ROTORS), default="coaxial",
                        help="coaxial (default structure coaxial_6state) or the UH-60-like single rotor "
                             "(single_rotor_3state, the shipped trusted model's structure)")
    parser.add_argument("--structure", default=None,
                        help="key of aircraft.identification.STRUCTURES (default: the rotor's; e.g. "
                             "coaxial_6state_axisymmetric_pp_collective_mass: the shipped axisymmetric model)")
    parser.add_argument("--synthetic-only", action="store_true",
                        help="only the synthetic-truth comparison (seconds; no wake)")
    args = parser.parse_args(argv)
    buf = io.StringIO()

    class _Tee(io.TextIOBase):
        def write(self, s):
            buf.write(s)
            return __import__("sys").__stdout__.write(s)

    with redirect_stdout(_Tee()):
        synthetic()
        if not args.synthetic_only:
            run(args.duration, args.out, args.jobs, args.amplitude, args.wake, args.second_amplitude,
                args.structure, args.rotor)
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / ("synthetic.txt" if args.synthetic_only else "summary.txt")).write_text(buf.getvalue())


if __name__ == "__main__":
    main()
