"""Hover bare-airframe responses of the coaxial with five inflow models (cf. Figs. 7.3-7.11).

On-axis p/delta_lat, q/delta_lon, r/delta_ped, w/delta_col and the off-axis
p/delta_lon over 0.1-30 rad/s for Dynamic Climb (with the analytical K_R),
Climbing Lower Rotor, Isolated Rotors and the dissertation's identified 6- and
12-state models (:mod:`aircraft.inflow.published`), once bare and once as the
single-axis plants of Eq. 7.21 (the other axes held, as in Fig. 7.11). Also
lists each model's regressive flap modes (physics-paired,
:func:`aircraft.helicopter.flap_mode_damping`) beside the §7.4.2.2 values.

Writes ``results/bare_airframe/``: ``responses.csv``, ``responses_coupled.csv``
(long tables), ``differences.csv`` (largest dB/deg difference from Dynamic
Climb over 1-10 rad/s), ``flap_modes.csv``, ``bare_airframe.png``,
``bare_airframe_coupled.png``.

Run: ``python -m studies.bare_airframe``
"""
from __future__ import annotations

from pathlib import Path

import pandas as pd

from aircraft.helicopter import coupling_numerator, compare_bare_airframe, flap_mode_damping
from aircraft.inflow import ClimbingLowerRotor, DynamicClimb, IdentifiedInflow, IsolatedRotors, KR_ANALYTICAL
from aircraft.inflow.published import COAXIAL_HOVER_6STATE, COAXIAL_HOVER_12STATE, in_rotor_frames

#: §7.4.2.2 (Fig. 7.11, p/delta_lat with the other axes held): regressive flap [zeta, omega_n] (reference)
SECTION_7422 = {"Dynamic Climb": (0.175, 17.7), "MFW ID 12-state": (0.288, 19.7)}


def inflow_models():
    """The inflow models compared; add one here (or pass your own dict to compare_bare_airframe)."""
    return {"Dynamic Climb (K_R = 1.5)": DynamicClimb(kr=KR_ANALYTICAL),
            "Climbing Lower Rotor": ClimbingLowerRotor(),
            "Isolated Rotors": IsolatedRotors(),
            "MFW ID 6-state (Eq. 5.3)": IdentifiedInflow.from_published(in_rotor_frames(COAXIAL_HOVER_6STATE)),
            "MFW ID 12-state (Eqs. 6.8-6.9)": IdentifiedInflow.from_published(in_rotor_frames(COAXIAL_HOVER_12STATE))}


def main(out_dir="results/bare_airframe"):
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    pd.set_option("display.width", 200)
    fmt = lambda v: f"{v:.3g}"          # noqa: E731
    bare = compare_bare_airframe(inflow_models())
    coupled = compare_bare_airframe(dict(bare.systems), coupled=True)
    bare.to_pandas().to_csv(out / "responses.csv", index=False)
    coupled.to_pandas().to_csv(out / "responses_coupled.csv", index=False)
    ref = next(iter(bare.systems))
    diff = pd.concat([bare.difference(ref).assign(plant="bare"),
                      coupled.difference(ref).assign(plant="Eq. 7.21")], ignore_index=True)
    diff.to_csv(out / "differences.csv", index=False)
    print(f"largest difference from {ref}, 1-10 rad/s:")
    print(diff.pivot_table(index=["plant", "model"], columns="response",
                           values="max_abs_magnitude_diff_db").to_string(float_format=fmt))
    rows = []
    for name, sys in bare.systems.items():
        flap = flap_mode_damping(sys)
        roll = coupling_numerator(sys, "p", "delta_lat", {"q": "delta_lon", "r": "delta_ped", "w": "delta_col"})
        held = flap_mode_damping(roll, reference=flap)
        for r, h in zip(flap.itertuples(), held.itertuples()):
            rows.append({"model": name, "physics": r.physics, "bare_frequency": r.frequency,
                         "bare_damping": r.damping, "roll_plant_frequency": h.frequency,
                         "roll_plant_damping": h.damping, "tracked": h.tracked})
    flap = pd.DataFrame(rows)
    flap.to_csv(out / "flap_modes.csv", index=False)
    print("\nregressive flap modes, bare and in the p/delta_lat plant of Eq. 7.21:")
    print(flap.to_string(index=False, float_format=fmt))
    print("§7.4.2.2 (reference, Eq. 7.21 roll plant): Dynamic Climb zeta 0.175 at 17.7 rad/s, "
          "MFW ID zeta 0.288 at 19.7 rad/s")
    bare.plot().savefig(out / "bare_airframe.png", dpi=90)
    coupled.plot().savefig(out / "bare_airframe_coupled.png", dpi=90)
    print(f"\ntables and figures in {out}/")


if __name__ == "__main__":
    main()
