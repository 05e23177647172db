"""Identify the 6-state coaxial hover inflow model (§5.3 structure) from our own free wake.

Thin study over the library pipeline :func:`aircraft.identify_inflow` with
:class:`aircraft.identification.Coaxial6State` in our rotor frames: the coaxial of
:func:`aircraft.configs.coaxial_compound` is trimmed in hover (system C_T of the
dissertation's split, shared equally, torques balanced), swept once per control
(six sweeps, parallel, cached), and identified from a data-driven start (inverse
of the low-frequency lambda/C), reduced and verified on an upper-collective
doublet beside the wake's noise floor. Tables beside Table 5.1 and Eq. 5.3 (the
latter converted to our frames, :func:`aircraft.inflow.published.in_rotor_frames`)
go to ``results/coaxial_wake_identification/``; :func:`identified_inflow` returns
the model as an :class:`aircraft.inflow.IdentifiedInflow` (the main job's
``--identified wake``).

Run: ``python -m studies.coaxial_wake_identification`` (default wake resolution;
about 7-9 minutes on 2 cores the first time, seconds once cached). The shipped
file ``aircraft/data/models/coaxial_hover_6state.json`` is written by
``python -m aircraft.identification.regenerate coaxial_hover_6state``.
"""
from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import pandas as pd

from aircraft import identify_inflow
from aircraft.configs import coaxial_compound
from aircraft.identification import Coaxial6State, IdentificationSettings
from aircraft.inflow.published import COAXIAL_HOVER_6STATE
from aircraft.wake import WakeSettings

#: Table 5.1 (cost of the dissertation's fit per response), reference data only.
TABLE_5_1 = {("lam0_U", "CT_U"): 3.7, ("lam0_L", "CT_U"): 17.2, ("lam1c_U", "CM_U"): 204.0,
             ("lam1c_L", "CM_U"): 178.1, ("lam1s_U", "CL_U"): 204.1, ("lam1s_L", "CL_U"): 177.7,
             ("lam0_U", "CT_L"): 85.3, ("lam0_L", "CT_L"): 28.8, ("lam1c_U", "CM_L"): 115.8,
             ("lam1c_L", "CM_L"): 463.6, ("lam1s_U", "CL_L"): 115.1, ("lam1s_L", "CL_L"): 462.5}
STRUCTURE = Coaxial6State("rotor")


def identify(settings=None, *, sweep_s=45.0, n_jobs=2, cache_dir="default", progress=True):
    """Wake runs -> reduced 6-state fit. Returns ``(reduction, trim, model, omega)``
    (``model``: the :class:`aircraft.identification.IdentifiedModel`)."""
    ct = COAXIAL_HOVER_6STATE.condition["CT_U"] + COAXIAL_HOVER_6STATE.condition["CT_L"]
    model = identify_inflow(coaxial_compound(), None, STRUCTURE, ct=ct,
                            settings=IdentificationSettings(wake=settings or WakeSettings(), sweep_s=sweep_s),
                            name="coaxial hover 6-state from our wake", n_jobs=n_jobs, cache_dir=cache_dir,
                            progress=progress)
    return model.reduction, model.trim, model, model.omega


def identified_inflow(reduction, trim, omega, pade_order=2):
    """The identified model as an aircraft inflow model about the wake's trim."""
    import numpy as np
    o = trim.outputs
    loads_ref = np.array([o["CT_U"], 0.0, 0.0, o["CT_L"], 0.0, 0.0])
    inflow_ref = np.array([o[n] for n in STRUCTURE.outputs])
    return STRUCTURE.to_inflow(reduction.result.structure.values, omega, loads_ref=loads_ref,
                               inflow_ref=inflow_ref, pade_order=pade_order, name="identified from our free wake")


def tables(model):
    """(cost table beside Table 5.1, parameter table beside Eq. 5.3 in our frames)."""
    cost = model.cost_table.copy()
    cost["dissertation_table_5_1"] = [TABLE_5_1.get((o, i)) for o, i in zip(cost.output, cost.input)]
    params = model.parameters
    params["eq_5_3_our_frames"] = params.parameter.map(STRUCTURE.published_values(COAXIAL_HOVER_6STATE))
    params["eq_5_3_printed"] = params.parameter.map(Coaxial6State("printed").published_values(COAXIAL_HOVER_6STATE))
    return cost, params


def run_study(settings=None, *, out_dir="results/coaxial_wake_identification", verbose=True, model=None,
              **kwargs):
    """Identify (unless ``model``, an IdentifiedModel, is given), write tables and figures;
    return the IdentifiedModel."""
    t0 = time.perf_counter()
    if model is None:
        model = identify(settings, **kwargs)[2]
    trim = model.trim
    cost, params = tables(model)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    for suffix in ("", "_6state"):
        params.to_csv(out / f"parameters{suffix}.csv", index=False)
        cost.to_csv(out / f"cost_table{suffix}.csv", index=False)
    if model.reduction is not None:
        model.reduction.log.to_csv(out / "reduction_log.csv", index=False)
    model.verification_table.to_csv(out / "verification.csv", index=False)
    mats = model.fit.structure.matrices()
    for name, key in (("M_azimuth", "M"), ("Lbar", "L"), ("tau_s", "tau")):
        pd.DataFrame(mats[key], index=STRUCTURE.outputs, columns=STRUCTURE.loads).to_csv(out / f"{name}.csv")
    model.plot().savefig(out / "bode_fit.png", dpi=80)
    model.verification.plot().savefig(out / "verification.png", dpi=80)
    if verbose:
        fmt = lambda v: f"{v:.4g}"   # noqa: E731
        o = trim.outputs
        print("== Coaxial wake identification: 6-state hover model (structure of §5.3, our frames) ==")
        ws = model.settings.wake_settings
        print(f"wake: {math.degrees(ws.azimuth_step):g} deg steps, {ws.wake_revolutions:g}"
              f"+{ws.buffer_revolutions:g} revs, {ws.n_elements} elements")
        print(f"wake trim: C_T U/L {o['CT_U']:.5f}/{o['CT_L']:.5f}, C_Q U/L {o['CQ_U']:.3g}/{o['CQ_L']:.3g}, "
              f"lam0 U/L {o['lam0_U']:.4f}/{o['lam0_L']:.4f}")
        print(cost.to_string(index=False, float_format=fmt))
        print(f"J_ave = {model.J_ave:.1f} (dissertation, Table 5.1: 171.3)")
        print(params.to_string(index=False, float_format=fmt))
        print(model.verification_table.to_string(index=False, float_format=fmt))
        print(f"trusted (all CR < 20 %, insensitivity < 10 %): {model.trusted}")
        print(f"tables and figures in {out}/  (wall {time.perf_counter() - t0:.0f} s)")
    return model


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--coarse", action="store_true", help="15 deg steps, 2 revs of wake, 6 elements")
    parser.add_argument("--sweep-s", type=float, default=45.0, help="sweep record length [s]")
    parser.add_argument("--out", default="results/coaxial_wake_identification")
    args = parser.parse_args(argv)
    settings = (WakeSettings(azimuth_step=math.radians(15.0), wake_revolutions=2.0, n_elements=6)
                if args.coarse else WakeSettings())
    run_study(settings, sweep_s=args.sweep_s, out_dir=args.out)


if __name__ == "__main__":
    main()
