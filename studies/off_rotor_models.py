"""Off-rotor induced-velocity models of the single rotor at the tail and a wing under the hub (§4.6).

The dissertation's off-rotor models, identified on our wake only, through the library
(:func:`aircraft.identification.identify_off_rotor`): wake trim of the UH-60-like
rotor at C_T = 0.0061, in hover and at mu = 0.1 -> one swashplate sweep per control
with the wake's velocity recorded at 7 points along the horizontal tail's quarter
chord (the configuration's ``htail_position``) and 7 along a wing 0.25 R under the
hub -> joint input-output vbar/lam (Eq. 4.9) -> Eq. 2.39 (tail) and Eq. 2.40 (wing)
fitted over 1-5 rad/s -> reduced (a delay or gain the data do not support is removed,
Fig. 6.1) and judged by the trust rule (CR, insensitivity and verdict per parameter) ->
verification on a doublet per control (not used in the
fit) beside the zero-input noise floor. Whether the tail sees the wake is computed
from the wake's skew (:func:`aircraft.identification.wake_exposure`), at the trimmed
inflow and over mu with momentum theory. The dissertation's hover models (§4.6.1,
Eq. 4.10) are written beside ours as reference columns.

Writes under ``results/off_rotor_models/``: gains_delays.csv, trust.csv (per parameter: value,
status, CR %, insensitivity %, verdict, reason), reduction_log.csv, verification.csv,
exposure.csv, exposure_vs_mu.csv, dissertation_hover.csv, wall_times.csv, verification_<surface>_mu<mu>.png,
bode_<surface>_mu<mu>.png, exposure.png.

Run: ``python -m studies.off_rotor_models`` (default wake resolution), ``--coarse``
(15 deg steps, 2 revs, 6 elements), ``--small`` (tiny wake, short records, hover:
a smoke test of the chain, not a result).
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
from aircraft.identification import OffRotorSettings, flight_condition, identify_off_rotor
from aircraft.identification.off_rotor import horizontal_tail, wake_exposure, wing_under_hub
from aircraft.identification.off_rotor.surfaces import PUBLISHED_HOVER
from aircraft.inflow.pitt_peters import momentum_inflow
from aircraft.wake import WakeSettings

CT = 0.0061


def exposure_curve(config, surface, ct, mus):
    """Fraction of the surface's points in the skewed wake over mu (momentum-theory inflow)."""
    rows = []
    for mu in mus:
        lam = momentum_inflow(ct, mu)
        ex = wake_exposure(surface, config, mu, lam)
        rows.append({"surface": surface.name, "mu": mu, "lam0_momentum": lam, "chi_deg": ex.chi_deg.iloc[0],
                     "fraction_in_wake": ex.in_wake.mean(),
                     "min_distance_over_rw": ex.distance_over_rw.min()})
    return pd.DataFrame(rows)


def _reference_table(models):
    """Our hover gains/delays beside the dissertation's (§4.6.1 tail, Eq. 4.10 wing)."""
    rows = []
    for name, model in models.items():
        ref = PUBLISHED_HOVER.get(name)
        if ref is None:
            continue
        ours = model.to_pandas()
        for r in ours.itertuples():
            i = ["vx", "vy", "vz"].index(r.output.split("_")[0])
            j = ["lam0", "lam1c", "lam1s"].index(r.input)
            rows.append({"surface": name, "output": r.output, "input": r.input, "K ours": r.K,
                         "K_cramer_rao_pct": r.K_cramer_rao_pct, "tau ours [s]": r.tau_s,
                         "dissertation: K (MFW)": ref["K"][i][j], "dissertation: tau [s]": ref["tau"][i][j]})
    return pd.DataFrame(rows)


def _exposure_figure(curves, results):
    from matplotlib.figure import Figure
    fig = Figure(figsize=(7, 3.6), constrained_layout=True)
    ax = fig.subplots()
    for name, df in curves.groupby("surface"):
        ax.plot(df.mu, 100 * df.fraction_in_wake, "-", label=f"{name}: skewed cylinder, momentum lam0")
    for res in results:
        for name, m in res.models.items():
            ax.plot(m.mu, 100 * m.in_wake, "o", label=f"{name}: trimmed free wake, mu = {m.mu:.2f}")
    ax.set_xlabel("advance ratio mu [-]")
    ax.set_ylabel("points in the wake [%]")
    ax.set_ylim(-5, 105)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    ax.set_title("When the surfaces see the rotor wake (skew chi = atan(mu / lam))", fontsize=9)
    return fig


def run_study(wake=None, *, mus=(0.0, 0.1), ct=CT, settings=None, out_dir="results/off_rotor_models",
              n_jobs=2, cache_dir="default", progress=True, verbose=True, aircraft=None):
    """Identify the tail and wing models at each mu; write the tables and figures.

    ``aircraft``: a single-rotor configuration, shipped name or TOML file
    (:func:`aircraft.config_files.load_aircraft`; default the UH-60-like rotor).

    Returns ``(gains/delays table, verification table, list of OffRotorResult)``.
    """
    t_start = time.perf_counter()
    cfg = uh60_single_rotor() if aircraft is None else load_aircraft(aircraft)
    settings = settings or OffRotorSettings(wake=wake or WakeSettings())
    surfaces = [horizontal_tail(cfg), wing_under_hub(cfg)]
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    results, walls = [], []
    for mu in mus:
        t0 = time.perf_counter()
        res = identify_off_rotor(cfg, flight_condition(cfg, mu), surfaces, ct=ct, settings=settings,
                                 n_jobs=n_jobs, cache_dir=cache_dir, progress=progress)
        walls.append(time.perf_counter() - t0)
        results.append(res)
        tag = f"mu{mu:.2f}".replace(".", "p")
        for name, m in res.models.items():
            m.plot().savefig(out / f"verification_{name}_{tag}.png", dpi=90)
            m.plot_bode().savefig(out / f"bode_{name}_{tag}.png", dpi=80)
        if verbose:
            print(res.summary())
            print(f"mu = {mu:.2f}: {walls[-1]:.0f} s (wake runs or cache reads, fits)")
    gains = pd.concat([r.to_pandas() for r in results], ignore_index=True)
    trust = pd.concat([r.parameter_table for r in results], ignore_index=True)
    logs = [m.reduction.log.assign(surface=name, mu=r.mu) for r in results for name, m in r.models.items()
            if m.reduction is not None]
    ver = pd.concat([r.verification_table for r in results], ignore_index=True)
    exposure = pd.concat([m.exposure.assign(surface=name, mu=r.mu, lam0_trim=m.trim_inflow["lam0"],
                                            vx_trim=m.trim_velocity["x"], vy_trim=m.trim_velocity["y"],
                                            vz_trim=m.trim_velocity["z"])
                          for r in results for name, m in r.models.items()], ignore_index=True)
    curves = pd.concat([exposure_curve(cfg, s, ct, np.round(np.linspace(0.0, 0.4, 41), 3)) for s in surfaces],
                       ignore_index=True)
    gains.to_csv(out / "gains_delays.csv", index=False)
    trust.to_csv(out / "trust.csv", index=False)
    if logs:
        pd.concat(logs, ignore_index=True).to_csv(out / "reduction_log.csv", index=False)
    # per condition: wake trim and records (or cache reads), fits, verification
    pd.DataFrame({"mu": list(mus), "wall_s": walls, "wake_cache": cache_dir is not None}).to_csv(
        out / "wall_times.csv", index=False)
    ver.to_csv(out / "verification.csv", index=False)
    exposure.to_csv(out / "exposure.csv", index=False)
    curves.to_csv(out / "exposure_vs_mu.csv", index=False)
    hover = [r for r in results if r.mu == 0.0]
    if hover:
        _reference_table(hover[0].models).to_csv(out / "dissertation_hover.csv", index=False)
    _exposure_figure(curves, results).savefig(out / "exposure.png", dpi=90)
    if verbose:
        fmt = lambda v: f"{v:.4g}"   # noqa: E731
        ws = settings.wake_settings
        print(f"wake: {math.degrees(ws.azimuth_step):g} deg steps, {ws.wake_revolutions:g} revs, "
              f"{ws.n_elements} elements; sweeps {settings.sweep_s:g} s; fit {settings.fit_range} rad/s")
        tic = ver.groupby(["surface", "mu", "output"]).agg(TIC=("TIC", "mean"), TIC_floor=("TIC_noise_floor", "mean"),
                                                           signal_to_floor=("signal_to_floor", "mean"))
        print("trust verdicts (free parameters after the reduction):")
        print(trust[trust.status == "free"][["surface", "mu", "parameter", "value", "cramer_rao_pct",
                                             "insensitivity_pct", "verdict"]].to_string(index=False, float_format=fmt))
        print("doublet TIC (mean over the three doublets):")
        print(tic.to_string(float_format=fmt))
        for name, df in curves.groupby("surface"):
            inside = df[df.fraction_in_wake > 0.5].mu
            span = f"mu = {inside.min():.2f} to {inside.max():.2f}" if len(inside) else "never (mu <= 0.4)"
            print(f"{name}: more than half its points in the skewed wake for {span}")
        print(f"tables and figures in {out}/  (wall {time.perf_counter() - t_start:.0f} s; per condition "
              + ", ".join(f"{w:.0f} s" for w in walls) + ")")
    return gains, ver, results


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--coarse", action="store_true", help="15 deg steps, 2 revs of wake, 6 elements")
    parser.add_argument("--small", action="store_true",
                        help="tiny wake (20 deg, 1.5 revs, 4 elements), 8 s sweeps, hover only: a smoke test")
    parser.add_argument("--mu", type=float, nargs="+", default=None, help="advance ratios (default 0 0.1)")
    parser.add_argument("--aircraft", default=None,
                        help="a shipped aircraft's name or an aircraft TOML file (default: uh60_single_rotor)")
    parser.add_argument("--out", default="results/off_rotor_models")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--no-cache", action="store_true",
                        help="do not read or write the wake cache (the printed wall times are then the data sets')")
    args = parser.parse_args(argv)
    if args.small:
        wake = WakeSettings(azimuth_step=math.radians(20.0), wake_revolutions=1.5, n_elements=4)
        settings = OffRotorSettings(wake=wake, sweep_s=8.0, w_min=3.2, w_max=15.0, fit_range=(3.2, 8.0),
                                    doublet_s=2.2, pulse_width=0.3, noise_floor_s=1.0, starts=2)
        mus = args.mu or (0.0,)
    else:
        wake = (WakeSettings(azimuth_step=math.radians(15.0), wake_revolutions=2.0, n_elements=6)
                if args.coarse else WakeSettings())
        settings = OffRotorSettings(wake=wake)
        mus = args.mu or (0.0, 0.1)
    run_study(settings=settings, mus=tuple(mus), out_dir=args.out, n_jobs=args.jobs, progress=not args.small,
              cache_dir=None if args.no_cache else "default", aircraft=args.aircraft)


if __name__ == "__main__":
    main()
