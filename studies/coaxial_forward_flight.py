"""The coaxial at 200 kt: Eq. 6.5 inflow model from our free wake, and the isolated-rotor check.

Thin study over :mod:`aircraft.identification.coaxial_forward_flight`:

1. :func:`identify_coaxial_forward`: the coaxial of ``coaxial_compound(cruise=True)``
   at 200 kt (mu = 0.54, rotor AoA 2 deg), the wake trimmed to the thrust the
   aircraft needs there (torque-balanced) and to the aircraft's own per-rotor
   lift offsets at its differential lateral cyclic (``--lateral-cyclic-difference``; zero
   pitch moments), six control sweeps, the Eq. 6.5 structure
   (:class:`CoaxialForward12State`, 180 parameters at the start) fitted from a
   data-driven start and reduced automatically (Fig. 6.1), verified on a
   lower-rotor lateral doublet (Figs. 6.29-6.33) beside the wake's noise floor;
2. its cost table beside Table 6.3 and its parameters (CR %, insensitivity %)
   beside Eqs. 6.12-6.13 (printed and in our frames);
3. :func:`isolated_rotor_check`: the aircraft at 200 kt with lift offset, bare
   airframe q/delta_lon, p/delta_lat, w/delta_col, r/delta_ped (Figs. 7.7-7.10)
   with our identified inflow and with Eqs. 6.12-6.13 against Isolated Rotors.

Writes ``results/coaxial_forward_flight/``: ``cost_table.csv``,
``parameters.csv``, ``verification.csv``, ``reduction_log.csv``, ``trim.csv``, ``wall_times.csv``,
``responses.csv``, ``differences.csv``, ``verdicts.csv``, ``poles.csv``,
``structures.csv`` (with ``--candidate-structures``: each candidate structure's size,
cost, bounds and trust verdict beside the study's own, the quasi-steady and held-mass
candidates of :mod:`studies.analysis.coaxial_200kt_quasi_steady` included),
``time_constants.csv`` (with it: Pitt-Peters' inflow lags at the wake trim against the fit band),
``bode_fit.png`` (not with ``--small``), ``verification.png``, ``bare_airframe_200kt.png``.

Run: ``python -m studies.cli coaxial-forward-flight`` (coarse wake; ``--small``:
a tiny wake, short sweeps and the near-wake half of the structure without
reduction, for the tests).
"""
from __future__ import annotations

import argparse
import math
import tempfile
import time
from pathlib import Path

import pandas as pd

from aircraft.configs import coaxial_compound
from aircraft.identification.structures import CoaxialForward12State
from aircraft.identification import IdentificationSettings
from aircraft.identification.coaxial_forward_flight import (aircraft_lift_offset, aircraft_thrust_at, identify_coaxial_forward)
from studies.analysis.coaxial_200kt import cost_table_beside_dissertation, isolated_rotor_check, structures_table
from studies.analysis.coaxial_200kt_quasi_steady import quasi_steady_candidates, trim_time_constants
from aircraft.inflow import IdentifiedInflow
from aircraft.inflow.published import COAXIAL_200KT_12STATE, in_rotor_frames
from aircraft.wake import WakeSettings

#: Whether the study identifies the candidate structures unless told (``--[no-]candidate-structures``):
#: off, the five candidates' fits and reductions take about 4.5 min on 2 busy cores (records
#: cached): 82 s for the four first-order ones, 90-190 s for the near-wake half of Eq. 6.5;
#: the seven quasi-steady and held-mass candidates add about 10 s.
CANDIDATES_DEFAULT = False

#: The coarse wake of the 200 kt runs (about 20x cheaper than the default).
COARSE = WakeSettings(azimuth_step=math.radians(15.0), wake_revolutions=2.0, n_elements=6)


def settings_for(small=False, sweep_s=40.0, reduce=True, near_wake_only=False):
    """(IdentificationSettings, structure) of the full or the ``--small`` run.

    Parameters
    ----------
    small : bool
        Tiny wake (30 deg steps, 1 rev, 4 elements, 2 revs of far wake), 10 s sweeps
        from 2.2 rad/s, the near-wake half of Eq. 6.5 (72 parameters), no reduction.
    sweep_s : float
        Sweep length of the full run [s] (the response needs >= 36 s for 0.7 rad/s;
        a 30 s record stops at 0.79 rad/s and the pipeline refuses it).
    reduce : bool
        Reduce the full run (Fig. 6.1).
    near_wake_only : bool
        Fit only the near-wake half of Eq. 6.5 in the full run (72 parameters;
        the full structure's 180-parameter fit and reduction take hours on a
        busy 2-core machine).
    """
    if small:
        # 2 revs of far-wake helix instead of 10: at mu = 0.54 it is swept ~7 R downstream
        # either way, and the 10-rev helix was half of the tiny wake's cost
        wake = WakeSettings(azimuth_step=math.radians(30.0), wake_revolutions=1.0, n_elements=4,
                            far_wake_revolutions=2.0)
        # a 12 s record (10 s sweep + 2 s lead-in/out) resolves down to 8 pi / 12 = 2.09 rad/s
        return (IdentificationSettings(wake=wake, sweep_s=10.0, w_min=2.2, w_max=20.0, fit_range=(2.2, 15.0),
                                       doublet_control="theta1s_L", doublet_amplitude=0.035, doublet_s=2.0,
                                       noise_floor_s=2.0, reduce=False),
                CoaxialForward12State(near_wake_only=True))
    return (IdentificationSettings(wake=COARSE, sweep_s=sweep_s, doublet_control="theta1s_L",
                                   doublet_amplitude=0.035, reduce=reduce),
            CoaxialForward12State(near_wake_only=near_wake_only))


def candidate_structures(model, t_id, config, ct, los, settings, args):
    """The smaller candidates on the study's records beside its own structure (``structures.csv``).

    The study's structure itself is left out of the candidates (the ``--small`` and
    ``--near-wake-only`` runs identify the near-wake half already).
    """
    from aircraft.identification.coaxial_forward_candidates import (default_candidates,
                                                                    identify_candidate_structures)
    main = model.structure
    label = main.key + ("_near_wake" if getattr(main, "near_wake_only", False) else "")
    # the library's first-order candidates, then the quasi-steady ones of the analysis
    cands = {k: s for k, s in {**default_candidates(), **quasi_steady_candidates()}.items()
             if s.spec() != main.spec()}
    with tempfile.TemporaryDirectory() as tmp:
        # without the cache the records are still computed once: a private cache serves
        # the other candidates (and is thrown away)
        result = identify_candidate_structures(cands, config=config, ct=ct, lift_offset=los, settings=settings,
                                               n_jobs=args.jobs, progress=False,
                                               cache_dir=tmp if args.no_cache else "default",
                                               max_reduction_steps=args.max_reduction_steps)
    table = structures_table(label, model, round(t_id, 1), result)
    table.to_csv(Path(args.out) / "structures.csv", index=False)
    return table


def parameter_table(model):
    """Our parameters (value, status, CR %, insensitivity %, trust verdict and its reason)
    beside Eqs. 6.12-6.13 per d/dpsi."""
    params = model.parameters
    verdicts = model.trust.table.set_index("parameter")
    params["verdict"] = params.parameter.map(verdicts.verdict).fillna("")
    params["reason"] = params.parameter.map(verdicts.reason).fillna("")
    # the printed model fills the whole pattern: map it with the full structure (the
    # near-wake-only half's parameters carry the same names)
    ours = CoaxialForward12State("rotor")
    printed = CoaxialForward12State("printed")
    params["eq_6_12_13_our_frames"] = params.parameter.map(ours.published_values(COAXIAL_200KT_12STATE))
    params["eq_6_12_13_printed"] = params.parameter.map(printed.published_values(COAXIAL_200KT_12STATE))
    return params


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--small", action="store_true", help="tiny configuration (tests)")
    parser.add_argument("--sweep-s", type=float, default=40.0, help="sweep record length [s] (>= 36 s for 0.7 rad/s)")
    parser.add_argument("--near-wake-only", action="store_true",
                        help="fit the near-wake half of Eq. 6.5 only (72 parameters instead of 180)")
    parser.add_argument("--no-reduce", action="store_true", help="skip the automatic reduction")
    parser.add_argument("--lateral-cyclic-difference", type=float, default=0.03,
                        help="differential lateral cyclic of the aircraft trim [rad]; the wake is trimmed to "
                             "the per-rotor lift offsets the aircraft has there")
    parser.add_argument("--balanced-wake", action="store_true",
                        help="trim the wake to zero hub moments instead (the earlier study)")
    parser.add_argument("--max-reduction-steps", type=int, default=1000,
                        help="removals tried by the automatic reduction (one refit each); the default lets "
                             "it run to completion")
    parser.add_argument("--reduction-batch", type=int, default=10,
                        help="parameters the reduction removes together per refit (1: one at a time)")
    parser.add_argument("--jobs", type=int, default=2, help="wake worker processes")
    parser.add_argument("--no-cache", action="store_true",
                        help="do not read or write the wake cache (the printed wall times are then the data set's)")
    parser.add_argument("--candidate-structures", action=argparse.BooleanOptionalAction, default=CANDIDATES_DEFAULT,
                        help="also identify the smaller candidate structures (isolated rotors, coaxial 6-state, "
                             "near-wake half of Eq. 6.5, quasi-steady gain/delay rotors, isolated rotors with "
                             "Pitt-Peters' masses held) on the same records, reduce each, and write their trust "
                             "verdicts to structures.csv")
    parser.add_argument("--out", default="results/coaxial_forward_flight")
    args = parser.parse_args(argv)
    t0 = time.perf_counter()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    fmt = lambda v: f"{v:.4g}"   # noqa: E731
    pd.set_option("display.width", 200)
    settings, structure = settings_for(args.small, args.sweep_s, not args.no_reduce, args.near_wake_only)
    config = coaxial_compound(cruise=True)
    ct = aircraft_thrust_at(config, lateral_cyclic_difference=args.lateral_cyclic_difference)
    dlat = args.lateral_cyclic_difference
    los = (0.0, 0.0) if args.balanced_wake else aircraft_lift_offset(config, lateral_cyclic_difference=dlat)
    model = identify_coaxial_forward(config, ct=ct, structure=structure, settings=settings,
                                     n_jobs=args.jobs, progress=False, cache_dir=None if args.no_cache else "default",
                                     max_reduction_steps=args.max_reduction_steps, lift_offset=los,
                                     reduction_batch=args.reduction_batch)
    t_id = time.perf_counter() - t0
    if args.candidate_structures:
        structures = candidate_structures(model, t_id, config, ct, los, settings, args)
        lags = trim_time_constants(model.trim.outputs, config, settings.fit_range)
        lags.to_csv(out / "time_constants.csv", index=False)
    cost = cost_table_beside_dissertation(model)
    params = parameter_table(model)
    cost.to_csv(out / "cost_table.csv", index=False)
    params.to_csv(out / "parameters.csv", index=False)
    model.verification_table.to_csv(out / "verification.csv", index=False)
    if model.reduction is not None:
        model.reduction.log.to_csv(out / "reduction_log.csv", index=False)
    pd.Series(model.trim.outputs).rename("value").to_csv(out / "trim.csv", index_label="signal")
    pd.DataFrame([{"stage": "identification (wake trim and records or cache reads, fit, reduction, verification)",
                   "wall_s": t_id, "wake_cache": not args.no_cache},
                  {"stage": "of which the reduction", "wall_s": model.provenance.get("reduction_wall_s"),
                   "wake_cache": not args.no_cache}]).to_csv(out / "wall_times.csv", index=False)
    if not args.small:   # 37 panels with constrained layout: a third of the --small run's time
        model.plot().savefig(out / "bode_fit.png", dpi=70)
    model.verification.plot().savefig(out / "verification.png", dpi=70)

    o = model.trim.outputs
    free = params[params.status == "free"]
    print("== Coaxial 200 kt: Eq. 6.5 structure identified from our free wake ==")
    ws = settings.wake_settings
    print(f"wake: {math.degrees(ws.azimuth_step):g} deg steps, {ws.wake_revolutions:g} revs, "
          f"{ws.n_elements} elements; sweeps {settings.sweep_s:g} s; structure {structure!r}")
    print(f"wake trim (system C_T {ct:.5f} from the aircraft trim): C_T U/L {o['CT_U']:.5f}/{o['CT_L']:.5f}"
          f" (dissertation ~0.0073/0.0065), lam0 U/L {o['lam0_U']:.4f}/{o['lam0_L']:.4f}")
    print(f"lift offset: target U/L {los[0]:.3f}/{los[1]:.3f} (the aircraft's at {dlat:g} rad "
          f"differential lateral cyclic{'; not used, --balanced-wake' if args.balanced_wake else ''}), "
          f"wake -C_L/C_T U/L {-o['CL_U'] / o['CT_U']:.3f}/{-o['CL_L'] / o['CT_L']:.3f}")
    print(cost.to_string(index=False, float_format=fmt))
    print(f"J_ave = {model.J_ave:.1f} over {len(model.cost_table)} responses (Table 6.3: 77.0); "
          f"{len(free)} free parameters of {len(params)} (dissertation: ~90 of 180 kept)")
    print(f"max CR {free.cramer_rao_pct.max():.3g} %, max insensitivity {free.insensitivity_pct.max():.3g} % "
          f"-> {'trusted' if model.trusted else 'NOT trusted'}; verdicts {free.verdict.value_counts().to_dict()}")
    for why in model.trust.failures:
        print(f"  not trusted: {why[:300]}")
    untried = model.provenance.get("reduction_untried")
    if untried:
        print(f"the reduction stopped at its step bound with {len(untried)} candidates untried: {untried[:10]}")
    print(model.verification_table.to_string(index=False, float_format=fmt))
    if args.candidate_structures:
        print("\n== Candidate structures on the same records (reduced, trust rule) ==")
        print(structures.drop(columns=["reasons", "note"]).to_string(index=False, float_format=fmt))
        for row in structures.itertuples():
            if not row.trusted:
                print(f"  {row.structure} not trusted: {str(row.reasons)[:300]}")
            if isinstance(row.note, str) and row.note:
                print(f"  {row.structure}: {row.note[:300]}")
        print(f"Pitt-Peters inflow lags at the wake trim against the fit band {settings.fit_range} rad/s "
              "(a lag below its corner is a delay of the same T: the apparent masses cannot be told from "
              "the delays there):")
        print(lags.to_string(index=False, float_format=fmt))
        best = structures[structures.largest_trusted]
        print("largest structure the trust rule accepts at 200 kt: "
              + (f"{best.structure.iloc[0]} ({best.free_parameters.iloc[0]} free parameters)" if len(best)
                 else "none"))
    red = model.provenance.get("reduction_wall_s")
    print(f"identification wall time {t_id:.0f} s" + (f" (reduction {red:.0f} s)" if red is not None else ""))

    inflows = {"Eqs. 6.12-6.13 (dissertation)": IdentifiedInflow.from_published(in_rotor_frames(COAXIAL_200KT_12STATE))}
    try:
        inflows = {"MFW ID (ours)": model.to_inflow(), **inflows}
    except ValueError as err:      # an unstable identified model is refused by the aircraft
        print(f"our identified model cannot go into the aircraft: {err}")
    check = isolated_rotor_check(inflows, config=config, lateral_cyclic_difference=dlat)
    check.to_pandas().to_csv(out / "responses.csv", index=False)
    # the band §7.4.2.1 discusses (2-3 dB between 5 and 20 rad/s), beside the 1-20 rad/s verdict band
    diff = pd.concat([check.differences.assign(band="1-20 rad/s"),
                      check.comparison.difference(check.reference, band=(5.0, 20.0)).assign(band="5-20 rad/s")],
                     ignore_index=True)
    diff.to_csv(out / "differences.csv", index=False)
    verdicts = check.verdicts()
    verdicts.to_csv(out / "verdicts.csv", index=False)
    check.poles.to_csv(out / "poles.csv", index=False)
    check.plot().savefig(out / "bare_airframe_200kt.png", dpi=70)
    print(f"\nbare airframe at 200 kt (differential lateral cyclic {dlat:g} rad), largest difference from "
          f"Isolated Rotors (verdict over {check.band[0]:g}-{check.band[1]:g} rad/s, "
          f"{check.threshold_db:g} dB / {check.threshold_deg:g} deg):")
    print(diff.to_string(index=False, float_format=fmt))
    print(verdicts.to_string(index=False, float_format=fmt))
    for name, msg in check.failed.items():
        print(f"no aircraft trim with {name}: {msg[:300]}")
    print("§7.4.2.1 (reference): 2-3 dB between 5 and 20 rad/s in p/delta_lat and r/delta_ped; conclusion 3: "
          "the isolated-rotor assumption does not hold for the dissertation's rotor")
    print(f"tables and figures in {out}/  (wall {time.perf_counter() - t0:.0f} s)")
    return model, check


if __name__ == "__main__":
    main()
