"""The roll design on the right aircraft: stick pairing, lift-offset trims, case-A sensitivity.

Three tables under ``results/roll_design_sensitivity/``:

* ``pairing.csv``: for the coaxial (Dynamic Climb) and the UH-60-like single rotor
  (Pitt-Peters) in hover, the share of each cyclic stick's steady hub moment on its
  own axis, rotor by rotor, with the configured control phase, with the former
  articulated pairing (0 deg) and with the phase derived from the aircraft's own
  response (:mod:`aircraft.helicopter.control_phase`);
* ``lift_offset_trims.csv``: the coaxial trimmed with Isolated Rotors at 100 and 200
  kt (2 deg rotor angle of attack), differential lateral cyclic 0 and 0.03 rad, with
  the lift-offset input paired as the configured control phase says and as the former
  own-frame theta1c pairing did: controls and per-rotor lift offsets;
* ``sensitivity.csv``: how much the rotor-physics assumptions move case A (the DMO's
  design on the Dynamic-Climb aircraft, u and v held): flap frequency, Lock number
  (through the blade flap inertia) and the control phase. The lag mode is not
  modelled (``RotorConfig.lag_frequency`` is documentation), so its effect cannot be
  measured here.

Run: ``rotorwake roll-design-sensitivity`` (about 6 min on 2 cores).
"""
from __future__ import annotations

import math
import time
from dataclasses import replace
from pathlib import Path

import pandas as pd

from aircraft import coaxial_compound, uh60_single_rotor
from aircraft.helicopter import Helicopter, HelicopterSettings, TrimCondition, linearize, trim
from aircraft.helicopter.control_phase import cyclic_moment_shares, derive_control_phase
from aircraft.helicopter.hold import hold_states
from aircraft.inflow import DynamicClimb, IsolatedRotors, PittPeters, config_rotor_names
from controllers import CommandModel, EMFDesign, InfeasibleDesignError, PIDGains, dmo, roll_design_plant, \
    second_order_actuator

KNOT = 0.514444     # m/s
HOVER = HelicopterSettings(n_span=8, n_average=1)


def pairing_table():
    rows = []
    for cfg, inflow in ((coaxial_compound(), DynamicClimb()), (uh60_single_rotor(), PittPeters())):
        sys = linearize(trim(Helicopter(cfg, inflow, HOVER)), inputs="rotor")
        derived = derive_control_phase(sys, cfg)
        for label, phase in (("configured", cfg.control_phase), ("articulated rule (0 deg)", 0.0),
                             ("derived from the response", derived)):
            rows.append(cyclic_moment_shares(sys, cfg, phase).assign(
                aircraft=cfg.name, pairing=label, control_phase_deg=math.degrees(phase),
                closed_form_deg=90 - math.degrees(cfg.rotors[0].flap_phase_lag())))
    return pd.concat(rows, ignore_index=True)


def lift_offset_trims():
    rows = []
    for label, phase in (("configured (90 deg, Eq. 7.19)", math.pi / 2), ("former (0 deg, own-frame theta1c)", 0.0)):
        cfg = replace(coaxial_compound(cruise=True), control_phase=phase)
        for knots in (100, 200):
            for difference in (0.0, 0.03):
                names = config_rotor_names(cfg)       # (upper, lower)
                tr = trim(Helicopter(cfg, IsolatedRotors(rotors=names), HelicopterSettings(n_span=8, n_average=4)),
                          TrimCondition(speed=knots * KNOT, rotor_aoa=math.radians(2.0),
                                        lateral_cyclic_difference=difference))
                row = {"pairing": label, "speed_kt": knots, "lateral_cyclic_difference_rad": difference}
                row.update({f"{n}_deg": math.degrees(v) for n, v in zip(tr.helicopter.input_names, tr.u)})
                row.update({f"lift_offset_{r}": -tr.loads[f"CL_{r}"] / tr.loads[f"CT_{r}"] for r in names})
                row.update({f"CT_{r}": tr.loads[f"CT_{r}"] for r in names})
                rows.append(row)
    return pd.DataFrame(rows)


def _case_a(cfg):
    sys = linearize(trim(Helicopter(cfg, DynamicClimb(), HOVER)))
    design = EMFDesign(roll_design_plant(hold_states(sys, ("u", "v"))), PIDGains(0.3, 0.1, 0.05),
                       CommandModel(frequency=4.0, damping=0.7, gain=0.05), second_order_actuator(35.0, 0.7),
                       sensor_delay=0.01)
    t0 = time.perf_counter()
    try:
        res = dmo(design, progress=False)
    except InfeasibleDesignError as err:
        return {"feasible": False, "crossover_rad_s": math.nan, "limiting": ", ".join(err.unmet),
                "dmo_wall_s": time.perf_counter() - t0}
    t = res.specs.set_index("spec")
    return {"feasible": True, "crossover_rad_s": res.crossover, "DRB_rad_s": t.loc["DrbRoH1", "value"],
            "DRP_dB": t.loc["DrpAvH1", "value"], "GM_dB": t.loc["StbMgG1.GM", "value"],
            "PM_deg": t.loc["StbMgG1.PM", "value"], "K_phi": res.design.gains.K_phi,
            "K_Iphi": res.design.gains.K_Iphi, "K_p": res.design.gains.K_p, "limiting": ", ".join(res.limiting),
            "origin": res.origin, "dmo_wall_s": time.perf_counter() - t0}


def _with_rotors(cfg, **changes):
    return replace(cfg, rotors=tuple(replace(r, **changes) for r in cfg.rotors))


def sensitivity_table():
    base = coaxial_compound()
    inertia = base.rotors[0].flap_inertia
    derived = derive_control_phase(linearize(trim(Helicopter(base, DynamicClimb(), HOVER)), inputs="rotor"), base)
    variants = [("baseline", "", base),
                ("flap frequency", "1.4/rev", _with_rotors(base, flap_frequency=1.4)),
                ("flap frequency", "1.6/rev", _with_rotors(base, flap_frequency=1.6)),
                ("Lock number", "x 1.25 (flap inertia / 1.25)", _with_rotors(base, flap_inertia=inertia / 1.25)),
                ("Lock number", "x 0.8 (flap inertia / 0.8)", _with_rotors(base, flap_inertia=inertia / 0.8)),
                ("control phase", "60 deg", replace(base, control_phase=math.radians(60))),
                ("control phase", f"{math.degrees(derived):.1f} deg (derived: both sticks on their own axes)",
                 replace(base, control_phase=derived)),
                ("control phase", "75 deg", replace(base, control_phase=math.radians(75)))]
    rows = []
    for what, value, cfg in variants:
        row = {"assumption": what, "value": value, "lock_number": cfg.rotors[0].lock_number(),
               **_case_a(cfg)}
        print(f"  {what} {value}: crossover {row['crossover_rad_s']:.3f} rad/s ({row['dmo_wall_s']:.0f} s)",
              flush=True)
        rows.append(row)
    table = pd.DataFrame(rows)
    table["crossover_vs_baseline"] = table.crossover_rad_s / table.crossover_rad_s.iloc[0]
    return table


def main(out_dir="results/roll_design_sensitivity"):
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    pd.set_option("display.width", 200)
    pairing = pairing_table()
    pairing.to_csv(out / "pairing.csv", index=False)
    print(pairing[["aircraft", "pairing", "control_phase_deg", "stick", "rotor", "on_axis_share"]]
          .to_string(index=False, float_format=lambda v: f"{v:.3f}"))
    trims = lift_offset_trims()
    trims.to_csv(out / "lift_offset_trims.csv", index=False)
    print(trims[["pairing", "speed_kt", "lateral_cyclic_difference_rad", "theta0_U_deg", "theta1s_U_deg",
                 "theta1c_U_deg", "lift_offset_U", "lift_offset_L"]].to_string(index=False,
                                                                              float_format=lambda v: f"{v:.3f}"))
    print("[case A sensitivity] DMO on the Dynamic-Climb aircraft per assumption")
    sens = sensitivity_table()
    sens.to_csv(out / "sensitivity.csv", index=False)
    print(sens[["assumption", "value", "lock_number", "crossover_rad_s", "crossover_vs_baseline", "limiting"]]
          .to_string(index=False, float_format=lambda v: f"{v:.3f}"))
    return out


if __name__ == "__main__":
    main()
