"""Benchmark: the whole 12-state coaxial hover data set from our free wake, and its fit.

One run prints, on this machine:

* the wake data set of :func:`aircraft.identify_inflow` for the shipped 12-state
  structure (``regenerate.RECIPES["coaxial_hover_12state"]``: Eq. 6.3 with the
  6-state's delays and the cyclic far-wake load terms) at the default resolution:
  trim, six swashplate sweeps, four prescribed tip-path-plane sweeps (45 s each),
  the verification doublet and the zero-input run, on ``--jobs`` local processes;
  wall time [s], rotor revolutions marched, revolutions per second;
* the identification from those records (responses, joint input-output, staged
  fit, reduction, verification) [s], the same for the shipped 12-state with
  tip-path-plane tilt inputs (``coaxial_hover_12state_tilt``: same records), and for
  the 6-state model that uses six of the ten sweeps.

By default the wake runs go to a fresh temporary cache, so the wall time is the
real cost (about 25-40 min on 2 cores); ``--cache DIR`` reuses a cache (then the
data-set time only measures cache reads).

Run: ``.venv/bin/python benchmarks/coaxial_12state.py [--jobs 2] [--cache DIR]``.
"""
import argparse
import tempfile
import time

from aircraft import identify_inflow
from aircraft.configs import coaxial_compound
from aircraft.identification.structures import Coaxial6State
from aircraft.identification import IdentificationSettings, get_structure
from aircraft.identification.pipeline import _trim_request
from aircraft.identification.shipped import RECIPES
from aircraft.wake import FlightCondition, SweepSpec, run_sweeps

CT = 0.0053 + 0.0043            # system C_T (the dissertation's split), shared equally


def data_set_specs(structure, settings):
    """The records identify_inflow runs for ``structure`` (same specs, same cache keys)."""
    s = settings
    specs = [SweepSpec(c, kind="sweep", amplitude=s.amplitude, duration=s.sweep_s, w_min=s.w_min,
                       w_max=s.w_max, seed=k) for k, c in enumerate(structure.excitations)]
    first = structure.excitations[0]
    return specs + [SweepSpec(first, kind="doublet", amplitude=s.doublet_amplitude, duration=s.doublet_s,
                              pulse_width=s.pulse_width),
                    SweepSpec(first, kind="sine", amplitude=0.0, duration=s.noise_floor_s, w_min=1.0,
                              label="zero_input")]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--jobs", type=int, default=2, help="wake worker processes")
    parser.add_argument("--cache", default=None, help="wake cache folder (default: a fresh temporary one)")
    args = parser.parse_args(argv)
    config, settings = coaxial_compound(), IdentificationSettings()
    structure = get_structure(RECIPES["coaxial_hover_12state"].structure)   # the shipped one
    specs = data_set_specs(structure, settings)
    with tempfile.TemporaryDirectory() as tmp:
        cache = args.cache or tmp
        t0 = time.perf_counter()
        runs = run_sweeps(config, settings.wake_settings, FlightCondition(), specs,
                          trim=_trim_request(config, CT, None), n_jobs=args.jobs, cache_dir=cache)
        t_data = time.perf_counter() - t0
        omega = config.rotors[0].omega
        revs = sum(float(runs[s.name]["t"].iloc[-1]) for s in specs) * omega / (2 * 3.141592653589793)
        t1 = time.perf_counter()
        m12 = identify_inflow(config, None, structure, ct=CT, settings=settings, n_jobs=args.jobs,
                              cache_dir=cache, progress=False)
        t_fit12 = time.perf_counter() - t1
        t3 = time.perf_counter()
        tilt = RECIPES["coaxial_hover_12state_tilt"]
        m12t = identify_inflow(config, None, get_structure(tilt.structure), ct=CT, settings=tilt.settings,
                               n_jobs=args.jobs, cache_dir=cache, progress=False)
        t_fit12t = time.perf_counter() - t3
        t2 = time.perf_counter()
        m6 = identify_inflow(config, None, Coaxial6State(), ct=CT, settings=settings, n_jobs=args.jobs,
                             cache_dir=cache, progress=False)
        t_fit6 = time.perf_counter() - t2
    print(f"12-state coaxial hover data set ({structure!r}): {len(specs)} records, {revs:.0f} rotor revolutions marched "
          f"({'cached' if args.cache else 'uncached'}), {args.jobs} processes")
    print(f"  wake data set (trim + runs): {t_data:.0f} s  ({revs / t_data:.2f} rev/s)")
    print(f"  12-state identification from the records (staged fit + reduction + verification): {t_fit12:.0f} s "
          f"(J_ave {m12.J_ave:.1f})")
    print(f"  12-state with tilt inputs from the same records: {t_fit12t:.0f} s (J_ave {m12t.J_ave:.1f})")
    print(f"  6-state identification from six of the records: {t_fit6:.0f} s (J_ave {m6.J_ave:.1f})")


if __name__ == "__main__":
    main()
