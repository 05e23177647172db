"""Coaxial 6-state hover inflow model across rotor spacing and thrust (design-space study).

Thin study over :func:`aircraft.identification.identify_design_space`: the coaxial
of :func:`aircraft.configs.coaxial_compound` with its lower rotor moved to each
spacing h/R, trimmed in hover at each system C_T (shared equally, torques
balanced), identified from our free wake (six sweeps, doublet, zero-input run per
point, through the wake executor, cached) on the COARSE wake (15 deg steps, 2
revolutions, 6 elements). Writes to ``results/coaxial_design_space/``:

* ``design_space.csv``   key coefficients per point (cross-rotor M and Lbar, diagonal
  Lbar) with CR %, insensitivity %, J_ave, trusted, trim thrusts, wall time;
* ``summary.csv``        one row per point (wide): J_ave, max CR %, max insensitivity %,
  trusted and ``trust_failures`` (:func:`aircraft.identification.trust_check`'s reasons);
* ``coefficients.png``   coefficients against spacing, one line per thrust;
* ``schedule.json``      the interpolated model (:class:`aircraft.inflow.ScheduledInflow`;
  load it with ``ScheduledInflow.from_file(path, spacing, ct)``) over the trusted points
  only (the largest all-trusted sub-grid, ``schedule(require_trusted=True)``; ``--all-points``:
  over every point), not written when fewer than two trusted points remain;
* ``timing.csv``         wall time per point and in all, and whether the wake cache was on;
* ``reproduction.csv``   the trust rule's reproduction part at each trusted point
  (:func:`studies.analysis.design_space.reproduction_table`).

Run: ``python -m studies.coaxial_design_space`` (4 spacings x 2 thrusts, 45 s sweeps from
0.7 rad/s, fit 1-12 rad/s (``--fit-max``: see :data:`FIT_MAX`); about 3 min per point on 2 idle
cores the first time, the fits only once cached);
``--structure`` picks the fitted structure (default the free-mass ``coaxial_6state``; or the
shipped model's ``coaxial_6state_axisymmetric_pp_collective_mass``, the same six sweeps).
``trusted`` in the tables is judged without the reproduction part; that part runs at the
trusted points only (``--reproduce``, on by default: a second data set per trusted point,
started 1e-7 R away) and is written to ``reproduction.csv``.
``--no-cache`` recomputes the wake runs (the committed results: their timing is the data
sets'); ``--small``: a tiny wake on 2 spacings x 1 thrust, for the tests.
"""
from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import pandas as pd

from aircraft.identification import IdentificationSettings, identify_design_space
from aircraft.identification.design_space import DesignSpaceError, SPACINGS, THRUSTS
from aircraft.wake import WakeSettings
from studies.analysis.design_space import reproduction_table

COARSE = WakeSettings(azimuth_step=math.radians(15.0), wake_revolutions=2.0, n_elements=6)
# --small: the tiny wake of tests/aircraft/identification/test_identification_pipeline.py (20 deg, 1.5 revs, 5 elements)
TINY = WakeSettings(azimuth_step=math.radians(20.0), wake_revolutions=1.5, n_elements=5)
#: The structures the study compares: the free-mass 6-state and the shipped model's
#: (every axisymmetric coupling, collective apparent masses held at Pitt-Peters').
STRUCTURES = ("coaxial_6state", "coaxial_6state_axisymmetric_pp_collective_mass")
STRUCTURE = "coaxial_6state"


#: Top of the fit band [rad/s]: about 0.45/rev, the band of the single rotor's forward-flight
#: models (studies.forward_flight_identification), where a first-order harmonic inflow model
#: is meant to hold. On 1-25 rad/s the 6-state misfits the coarse wake above it at every point
#: (J_ave 206-337, none trusted; the former default, ``--fit-max 25``).
FIT_MAX = 12.0


def settings_for(small=False, sweep_s=45.0, w_min=0.7, fit_max=FIT_MAX):
    """The identification settings of the study: coarse wake, ``sweep_s`` [s] sweeps from
    ``w_min`` [rad/s], fit from max(1, w_min) to ``fit_max`` [rad/s] (``small``: tiny wake,
    12 s sweeps from 2 rad/s, fit 2-20 rad/s)."""
    if small:
        # a 12 s sweep makes a 14 s record, whose longest window (7 s) resolves 2 rad/s, not 1.5
        return IdentificationSettings(wake=TINY, sweep_s=12.0, w_min=2.0, fit_range=(2.0, 20.0), doublet_s=2.0,
                                      noise_floor_s=2.0)
    return IdentificationSettings(wake=COARSE, sweep_s=sweep_s, w_min=w_min, fit_range=(max(1.0, w_min), fit_max))


def run_study(spacings, cts, settings, *, structure=STRUCTURE, out_dir="results/coaxial_design_space", n_jobs=2,
              scheduler=None, verbose=True, cache=True, trusted_only=True, reproduce=True):
    """Identify ``structure`` over the grid, write the tables, figure and schedule; return the
    DesignSpaceResult. ``cache=False`` recomputes every wake run (and stores none), so
    ``timing.csv`` holds the data sets' wall times rather than cache reads. ``trusted_only``:
    the schedule's nodes are the trusted points only (``schedule(require_trusted=True)``).
    ``reproduce``: run the trust rule's reproduction part at every trusted point
    (``reproduction.csv``; a second wake data set each)."""
    t0 = time.perf_counter()
    result = identify_design_space(spacings, cts, structure=structure, settings=settings, n_jobs=n_jobs,
                                   scheduler=scheduler, progress=verbose, cache_dir="default" if cache else None)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    table = result.to_pandas()
    table.to_csv(out / "design_space.csv", index=False)
    summary = result.summary_table()
    summary.to_csv(out / "summary.csv", index=False)
    result.plot().savefig(out / "coefficients.png", dpi=90)
    wall = time.perf_counter() - t0
    cache_state = "on (runs already cached cost nothing)" if cache else "off (every wake run computed)"
    timing = pd.DataFrame([{"spacing": p.spacing, "ct": p.ct, "wall_s": round(p.wall_s, 1), "wake_cache": cache_state}
                           for p in result.points]
                          + [{"spacing": None, "ct": None, "wall_s": round(wall, 1), "wake_cache": cache_state}])
    timing.to_csv(out / "timing.csv", index=False)
    nodes = []
    try:
        sched = result.schedule(require_trusted=trusted_only)
    except DesignSpaceError as err:      # too few trusted (or failed) points: say so, write no schedule
        schedule_note = f"no schedule ({err})"
        # a schedule of an earlier run would otherwise sit beside tables that disown it
        (out / "schedule.json").unlink(missing_ok=True)
    else:
        sched.save(out / "schedule.json")
        nodes = [(s, c) for s in sched.spacings for c in sched.cts]
        which = "trusted points only" if trusted_only else "every point"
        schedule_note = (f"schedule ({which}: h/R {', '.join(f'{v:g}' for v in sched.spacings)} x "
                         f"C_T {', '.join(f'{v:g}' for v in sched.cts)}) in {out / 'schedule.json'}")
    reproduction = None
    if reproduce:
        reproduction = reproduction_table(result, settings, n_jobs=n_jobs, cache_dir="default" if cache else None,
                                          progress=verbose)
        reproduction.to_csv(out / "reproduction.csv", index=False)
        done = {(r.spacing, r.ct): bool(r.reproduces) for r in reproduction.itertuples()}
        if nodes and not all(done.get(n, False) for n in nodes):
            # trusted_only=False puts untrusted points in, whose reproduction is not run
            schedule_note += " -- a node of it is not shown to reproduce (reproduction.csv)"
    if verbose:
        fmt = lambda v: f"{v:.4g}"   # noqa: E731
        ws = settings.wake_settings
        print(f"== Coaxial design space: {structure} hover model over rotor spacing x thrust ==")
        print(f"wake: {math.degrees(ws.azimuth_step):g} deg steps, {ws.wake_revolutions:g} revs, "
              f"{ws.n_elements} elements; sweeps {settings.sweep_s:g} s from {settings.w_min:g} rad/s; fit "
              f"{settings.fit_range[0]:g}-{settings.fit_range[1]:g} rad/s")
        print(summary.to_string(index=False, float_format=fmt))
        for p in result.failed:
            print(f"FAILED h/R {p.spacing:g}, C_T {p.ct:g}: {p.error}")
        print(f"trusted at {int(summary.trusted.sum())} of {len(summary)} points (trust_check, reproduction "
              "not checked)")
        if reproduction is not None:
            print("reproduction on a second wake data set at the trusted points (the trust rule's last part):")
            print(reproduction.drop(columns="trust_failures").to_string(index=False, float_format=fmt))
        print(f"{schedule_note}; tables and figure in {out}/  (wall {wall:.0f} s, wake cache {cache_state})")
    return result


def _floats(text):
    return tuple(float(v) for v in text.split(","))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--spacings", type=_floats, default=SPACINGS, help="rotor spacings h/R, comma-separated")
    parser.add_argument("--cts", type=_floats, default=THRUSTS, help="system thrust coefficients, comma-separated")
    parser.add_argument("--sweep-s", type=float, default=45.0,
                        help="sweep length [s]; the longest analysis window, half the record, must resolve --w-min (45 s: 0.53 rad/s)")
    parser.add_argument("--w-min", type=float, default=0.7, help="lowest sweep frequency [rad/s]")
    parser.add_argument("--fit-max", type=float, default=FIT_MAX, help="top of the fit band [rad/s] (at most 30)")
    parser.add_argument("--small", action="store_true",
                        help="tiny wake, 12 s sweeps from 2 rad/s, h/R 0.14,0.20 x C_T 0.0096 (for the tests)")
    parser.add_argument("--n-jobs", type=int, default=2, help="wake worker processes")
    parser.add_argument("--scheduler", default=None,
                        help="Dask scheduler address, passed to identify_inflow where it accepts one")
    parser.add_argument("--no-cache", action="store_true",
                        help="recompute every wake run (the committed timing is the data sets', not cache reads)")
    parser.add_argument("--structure", choices=STRUCTURES, default=STRUCTURE, help="structure fitted at every point")
    parser.add_argument("--reproduce", action=argparse.BooleanOptionalAction, default=True,
                        help="run the trust rule's reproduction part at every trusted point (a second wake data set "
                             "each)")
    parser.add_argument("--all-points", action="store_true",
                        help="schedule over every point, trusted or not (default: trusted points only)")
    parser.add_argument("--out", default="results/coaxial_design_space")
    args = parser.parse_args(argv)
    spacings, cts = args.spacings, args.cts
    if args.small:
        spacings = (0.14, 0.20) if args.spacings == SPACINGS else args.spacings
        cts = (0.0096,) if args.cts == THRUSTS else args.cts
    run_study(spacings, cts, settings_for(args.small, args.sweep_s, args.w_min, args.fit_max), structure=args.structure,
              out_dir=args.out, n_jobs=args.n_jobs, scheduler=args.scheduler, cache=not args.no_cache,
              trusted_only=not args.all_points, reproduce=args.reproduce)


if __name__ == "__main__":
    main()
