"""Identify a 3-state inflow model of the single rotor in hover from our own free wake.

Mission steps 1-2 on our models only, through the library pipeline
:func:`aircraft.identify_inflow` (wake trim at C_T = 0.0061 -> one swashplate
sweep per control -> joint input-output lambda/C -> fit of the Tables 4.1-4.2
structure from a data-driven start -> automatic reduction -> verification on a
collective doublet beside the wake's noise floor). The identified M/Omega, Lbar and
tau are printed beside the closed-form Pitt-Peters values at the trimmed C_T and,
in separate comparison columns, the dissertation's Table 4.1-4.2 rows. Writes CSV
and PNG under ``results/wake_identification/``.

Run: ``python -m studies.wake_identification`` (default resolution: a few minutes
on 2 cores the first time, seconds once cached; ``--coarse`` for a quick look).
"""
from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import pandas as pd

from aircraft import identify_inflow, load_aircraft
from aircraft.configs import uh60_single_rotor
from aircraft.identification import IdentificationSettings
from aircraft.identification.structures import SingleRotor3State
from aircraft.inflow.published import UH60_HOVER_MFW, UH60_HOVER_PITT_PETERS
from aircraft.wake import WakeSettings


def coefficient_table(model):
    """M/Omega [s], Lbar, tau [s] beside Pitt-Peters at the trimmed C_T and Tables 4.1-4.2."""
    omega = model.omega
    val = model.parameters.set_index("parameter")
    lam_h = math.sqrt(model.trim.outputs["CT"] / 2.0)
    rows = []
    for key, name, scale, pp, i, mat in (
            ("m11", "M11/Omega [s]", 1 / omega, 8 / (3 * math.pi) / omega, (0, 0), "M"),
            ("m22", "M22/Omega [s]", 1 / omega, -16 / (45 * math.pi) / omega, (1, 1), "M"),
            ("l11", "Lbar11", 1.0, 4 * lam_h, (0, 0), "Lbar"), ("l22", "Lbar22", 1.0, -lam_h, (1, 1), "Lbar"),
            ("t11", "tau11 [s]", 1.0, 0.0, (0, 0), "tau"), ("t22", "tau22 [s]", 1.0, 0.0, (1, 1), "tau")):
        rows.append({"coefficient": name, "identified from our wake": val.loc[key, "value"] * scale,
                     "cramer_rao_pct": val.loc[key, "cramer_rao_pct"],
                     "insensitivity_pct": val.loc[key, "insensitivity_pct"],
                     "Pitt-Peters closed form (C_T trim)": pp,
                     "dissertation: identified from MFW": getattr(UH60_HOVER_MFW, mat)[i],
                     "dissertation: Pitt-Peters row": getattr(UH60_HOVER_PITT_PETERS, mat)[i]})
    return pd.DataFrame(rows)


def run_study(settings=None, *, ct=0.0061, sweep_s=45.0, out_dir="results/wake_identification", n_jobs=2,
              cache_dir="default", progress=True, verbose=True, aircraft=None):
    """Run the identification; return ``(coefficient table, IdentifiedModel)``.

    ``aircraft``: a single-rotor configuration, shipped name or TOML file
    (:func:`aircraft.config_files.load_aircraft`; default the UH-60-like rotor).
    """
    t_start = time.perf_counter()
    id_settings = IdentificationSettings(wake=settings or WakeSettings(), sweep_s=sweep_s)
    config = uh60_single_rotor() if aircraft is None else load_aircraft(aircraft)
    model = identify_inflow(config, None, SingleRotor3State(), ct=ct, settings=id_settings,
                            name="UH-60 hover 3-state from our wake", n_jobs=n_jobs, cache_dir=cache_dir,
                            progress=progress, reproduce=True)
    table = coefficient_table(model)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    table.to_csv(out / "coefficients.csv", index=False)
    model.cost_table.to_csv(out / "cost_table.csv", index=False)
    model.parameters.to_csv(out / "parameters.csv", index=False)
    if model.reduction is not None:
        model.reduction.log.to_csv(out / "reduction_log.csv", index=False)
    model.verification_table.to_csv(out / "verification.csv", index=False)
    model.trust.to_pandas().to_csv(out / "trust.csv", index=False)
    model.reproduction.to_pandas().to_csv(out / "reproduction.csv", index=False)
    model.plot().savefig(out / "bode_fit.png", dpi=90)
    model.verification.plot().savefig(out / "verification.png", dpi=90)
    if verbose:
        fmt = lambda v: f"{v:.4g}"   # noqa: E731
        ws = id_settings.wake_settings
        lam_h = math.sqrt(model.trim.outputs["CT"] / 2.0)
        gain = 1.0 / model.values["l11"]
        print(f"wake: {math.degrees(ws.azimuth_step):g} deg steps, {ws.wake_revolutions:g}"
              f"+{ws.buffer_revolutions:g} revs, {ws.n_elements} elements; trim C_T "
              f"{model.trim.outputs['CT']:.5f}, lam0 {model.trim.outputs['lam0']:.5f} (momentum {lam_h:.5f})")
        print(model.summary())
        rep = model.reproduction
        print("on a second wake (start displaced by 1e-7 R): " + rep.summary())
        print(table.to_string(index=False, float_format=fmt))
        print(f"quasi-steady lam0/C_T gain 1/Lbar11 = {gain:.3f}; momentum 1/(4 lam_h) = "
              f"{1 / (4 * lam_h):.3f}; ratio {gain * 4 * lam_h:.2f} (dissertation's MFW: "
              f"{UH60_HOVER_PITT_PETERS.Lbar[0, 0] / UH60_HOVER_MFW.Lbar[0, 0]:.2f})")
        print(f"tables and figures in {out}/  (wall {time.perf_counter() - t_start:.0f} s)")
    return table, model


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--coarse", action="store_true",
                        help="15 deg steps, 2 revs of wake, 6 elements (quick look)")
    parser.add_argument("--aircraft", default=None,
                        help="a shipped aircraft's name or an aircraft TOML file (default: uh60_single_rotor)")
    parser.add_argument("--sweep-s", type=float, default=45.0, help="sweep record length [s]")
    parser.add_argument("--out", default="results/wake_identification")
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args(argv)
    settings = (WakeSettings(azimuth_step=math.radians(15.0), wake_revolutions=2.0, n_elements=6)
                if args.coarse else WakeSettings())
    run_study(settings, sweep_s=args.sweep_s, out_dir=args.out, n_jobs=args.jobs, aircraft=args.aircraft)


if __name__ == "__main__":
    main()
