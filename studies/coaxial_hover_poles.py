"""Coaxial hover pole tables (cf. dissertation Tables 7.1 and 7.2).

Trims and linearises our coaxial in hover with the Climbing-Lower-Rotor inflow
and with the published MFW-identified 6-state model (Eq. 5.3), and prints each
pole table next to the flap/body poles the dissertation printed (reference
columns, typed from Tables 7.1/7.2; our model differs in structure: no lag
dynamics, rigid blades, different fuselage inertias, see aircraft.configs.ASSUMPTIONS).
Writes CSV and a pole-map PNG under ``results/coaxial_hover_poles/``.

Run: ``python -m studies.coaxial_hover_poles``
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from aircraft import coaxial_compound
from aircraft.helicopter import Helicopter, HelicopterSettings, linearize, modes, trim
from aircraft.inflow import ClimbingLowerRotor, IdentifiedInflow
from aircraft.inflow.published import COAXIAL_HOVER_6STATE

# reference: flap modes of Tables 7.1 (CLR) and 7.2 (MFW ID): (frequency rad/s, real part, description)
TABLE_7_1_FLAP = [(13.68, -3.705, "Regressive Flap"), (19.87, -3.747, "Regressive Flap"),
                  (34.71, -7.631, "Coning Flap"), (35.36, -7.975, "Reactionless Flap"),
                  (35.43, -7.34, "Reactionless Flap"), (35.53, -6.849, "Coning Flap"),
                  (57.92, -7.262, "Progressive Flap"), (58.34, -6.572, "Progressive Flap")]
TABLE_7_2_FLAP = [(14.94, -4.736, "Regressive Flap"), (21.05, -4.601, "Regressive Flap"),
                  (34.83, -8.367, "Coning Flap"), (35.36, -7.804, "Reactionless Flap"),
                  (35.39, -7.576, "Reactionless Flap"), (35.92, -7.663, "Coning Flap")]


def _is_inflow(state_label):
    # momentum-type models name their states lam*, identified ones inflow_x*
    return "lam" in state_label or state_label.strip().startswith("inflow_")


def _classify(row, omega):
    s = row.dominant_states
    if abs(row.imag) < 5.0:
        # non-oscillatory: body, inflow, or quasi-static flap-body (real) modes
        first = s.split(",")[0]
        return "inflow" if _is_inflow(first) else ("flap-body (real)" if "beta" in first else "body")
    if "beta0" in s.split(",")[0]:
        return "coning flap"
    if "betad" in s.split(",")[0]:
        return "reactionless flap"
    if "beta1" in s or (row.frequency > 5 and ("p (" in s or "q (" in s)):
        return "regressive flap" if row.frequency < 1.0 * omega + 10 and row.frequency < 45 else "progressive flap"
    if _is_inflow(s.split(",")[0]):
        return "inflow"
    return "body"


def pole_table(inflow, n_span=8):
    heli = Helicopter(coaxial_compound(), inflow, HelicopterSettings(n_span=n_span, n_average=1))
    tr = trim(heli)
    table = modes(linearize(tr))
    omega = heli.config.rotors[0].omega
    table["description"] = [_classify(r, omega) for r in table.itertuples()]
    return table, tr


def main(out_dir="results/coaxial_hover_poles"):
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    fig = Figure(figsize=(9, 5), constrained_layout=True)
    ax = fig.subplots()
    pd.set_option("display.width", 200)
    for label, inflow, ref in (("Climbing Lower Rotor", ClimbingLowerRotor(), TABLE_7_1_FLAP),
                               ("MFW ID 6-state (Eq. 5.3)", IdentifiedInflow.from_published(COAXIAL_HOVER_6STATE),
                                TABLE_7_2_FLAP)):
        table, tr = pole_table(inflow)
        tag = "clr" if "Climbing" in label else "id6"
        table.assign(pole=table.pole.astype(str)).to_csv(out / f"poles_{tag}.csv", index=False)
        print(f"\n== {label}: trim residual {tr.max_residual:.1e} ==")
        print(table[["real", "imag", "frequency", "damping", "description", "dominant_states"]]
              .to_string(index=False, float_format=lambda v: f"{v:.4g}"))
        ref_df = pd.DataFrame(ref, columns=["dissertation frequency", "dissertation real", "dissertation description"])
        flap = table[table.description.str.contains("flap")][["frequency", "real", "description"]].reset_index(drop=True)
        print("flap modes, ours vs the dissertation's table:")
        print(pd.concat([flap, ref_df], axis=1).to_string(index=False, float_format=lambda v: f"{v:.4g}"))
        ax.plot(table.real, table.imag, "o", mfc="none", label=f"ours: {label}")
        ax.plot([r[1] for r in ref], [np.sqrt(r[0] ** 2 - r[1] ** 2) for r in ref], "x",
                label=f"dissertation: {label} (flap modes)")
    ax.set_xlabel("real [1/s]")
    ax.set_ylabel("imag [rad/s]")
    ax.set_xlim(-25, 1)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.savefig(out / "pole_map.png", dpi=90)
    print(f"\ntables and figure in {out}/")


if __name__ == "__main__":
    main()
