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

With ``--excitation multisine`` the data set is instead that of
:func:`aircraft.identification.identify_inflow_multisine` for the shipped 12-state
with tilt inputs: the six swashplate controls and the four prescribed
tip-path-plane inputs excited with orthogonal multisines, divided between
``--records`` records marched in parallel (``--duration`` [s] each, peak
``--amplitude`` [rad]), plus the same doublet and zero-input run. It prints the
same lines (wall time, revolutions, identification time, J_ave) and each
parameter of the fit beside the shipped sweep-based model: the difference in
Cramer-Rao bounds of the shipped model (absolute), and each model's J_ave on the
other's data (:func:`flightid.evaluate_model` style cost of the fixed model).

Run: ``.venv/bin/python benchmarks/coaxial_12state.py [--jobs 2] [--cache DIR]
[--excitation multisine --duration 36 --records 2 --amplitude 0.02]``.
"""
import argparse
import tempfile
import time
from pathlib import Path

import pandas as pd

from _costs import cost_on   # benchmarks/ is on the path when a benchmark runs as a script

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
    parser.add_argument("--excitation", choices=("sweeps", "multisine"), default="sweeps",
                        help="one sweep per control (default) or orthogonal multisines")
    parser.add_argument("--duration", type=float, default=36.0,
                        help="multisine record length [s] (>= 35.4 s resolves w_min = 0.7 rad/s)")
    parser.add_argument("--records", type=int, default=2, help="multisine records marched in parallel")
    parser.add_argument("--amplitude", type=float, default=0.02, help="multisine peak [rad]")
    parser.add_argument("--fit-cache", default=None,
                        help="multisine: wake cache for the fit (default: the data-set cache)")
    args = parser.parse_args(argv)
    if args.excitation == "multisine":
        return run_multisine(args)
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


def _shipped_parameters(key):
    """Parameters table of a shipped model file (value, status, Cramer-Rao %)."""
    import json
    from pathlib import Path
    import aircraft
    path = Path(aircraft.__file__).parent / "data" / "models" / f"{key}.json"
    record = json.loads(path.read_text())
    return pd.DataFrame(record["parameters"]).set_index("parameter"), record["J_ave"]


def compare_with_shipped(model, shipped):
    """``model``'s parameters beside the shipped sweep-based ones: |difference| in the
    shipped model's (absolute) Cramer-Rao bounds, for the parameters free in both."""
    mine = model.parameters.set_index("parameter")
    df = pd.DataFrame({"sweep_value": shipped.value, "sweep_status": shipped.status,
                       "sweep_CR_pct": shipped.cramer_rao_pct, "multisine_value": mine.value,
                       "multisine_status": mine.status, "multisine_CR_pct": mine.cramer_rao_pct})
    bound = (df.sweep_CR_pct.astype(float) / 100 * df.sweep_value.abs())
    df["diff_in_bounds"] = (df.multisine_value - df.sweep_value).abs() / bound.where(bound > 0)
    df["kept_in_both"] = (df.sweep_status == "free") & (df.multisine_status == "free")
    return df


def _cpu_seconds():
    """CPU time [s] of this process and of its children that have finished (pool workers)."""
    import resource
    me, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return me.ru_utime + me.ru_stime + kids.ru_utime + kids.ru_stime


def run_multisine(args):
    """The multisine data set of the shipped 12-state with tilt inputs, timed, fitted, compared."""
    from aircraft.identification import identify_inflow_multisine
    from aircraft.identification.multisine import MultisineSettings, record_revolutions
    from aircraft.identification.multisine_records import split_controls
    from aircraft.identification.pipeline import _responses
    from aircraft.wake import MultisineSpec
    from flightid import joint_input_output
    config = coaxial_compound()
    recipe = RECIPES["coaxial_hover_12state_tilt"]
    structure, settings = get_structure(recipe.structure), recipe.settings or IdentificationSettings()
    ms = MultisineSettings(duration=args.duration, amplitude=args.amplitude, records=args.records)
    s = settings
    controls = list(structure.excitations)
    groups = split_controls(controls, ms.records)
    # the records identify_inflow_multisine runs (same specs, same cache keys)
    specs = [MultisineSpec(g, amplitude=ms.amplitude, duration=ms.duration, w_min=s.w_min, w_max=s.w_max,
                           spectrum=ms.spectrum, fade=ms.fade, trim_start=ms.trim_start, seed=ms.seed + k,
                           label="" if len(groups) == 1 else f"multisine_{k + 1}of{len(groups)}")
             for k, g in enumerate(groups)] + data_set_specs(structure, s)[-2:]
    with tempfile.TemporaryDirectory() as tmp:
        cache = args.cache or tmp
        cold = not any(Path(cache).glob("**/*.*"))
        t0, cpu0 = time.perf_counter(), _cpu_seconds()
        runs = run_sweeps(config, s.wake_settings, FlightCondition(), specs,
                          trim=_trim_request(config, recipe.ct, None), n_jobs=args.jobs, cache_dir=cache)
        t_data, cpu_data = time.perf_counter() - t0, _cpu_seconds() - cpu0
        omega = config.rotors[0].omega
        revs = record_revolutions({sp.name: runs[sp.name] for sp in specs}, omega)
        t1 = time.perf_counter()
        model = identify_inflow_multisine(config, None, structure, ct=recipe.ct, settings=s, multisine=ms,
                                          n_jobs=args.jobs, cache_dir=args.fit_cache or cache, progress=False)
        t_fit = time.perf_counter() - t1
    print(f"12-state coaxial hover data set from multisines ({structure!r}): {len(specs)} records "
          f"({ms.records} multisine records of {ms.duration:g} s, peak {ms.amplitude:g} rad, + doublet + "
          f"zero input), {sum(revs.values()):.0f} rotor revolutions marched "
          f"({'uncached' if cold else 'cache not empty'}), {args.jobs} processes")
    print("  revolutions per record: " + ", ".join(f"{k} {v:.0f}" for k, v in revs.items()))
    print(f"  wake data set (trim + runs): {t_data:.0f} s  ({sum(revs.values()) / t_data:.2f} rev/s); "
          f"CPU {cpu_data:.0f} s in all (this process and its finished workers: the cost on idle cores, "
          f"whatever else the machine ran)")
    print(f"  12-state with tilt inputs from the multisine records (staged fit + reduction + verification): "
          f"{t_fit:.0f} s (J_ave {model.J_ave:.1f})")
    shipped, j_shipped = _shipped_parameters("coaxial_hover_12state_tilt")
    cmp = compare_with_shipped(model, shipped)
    kept = cmp[cmp.kept_in_both]
    print(f"  parameters against the shipped sweep-based model (J_ave {j_shipped:.1f}): {len(kept)} kept in both, "
          f"{int((kept.diff_in_bounds <= 1).sum())} within one Cramer-Rao bound of the sweep model, "
          f"{int((kept.diff_in_bounds <= 2).sum())} within two")
    with pd.option_context("display.width", 200):
        print(cmp.to_string(float_format=lambda v: f"{v:.4g}"))
    # each model on each data set: the sweep responses from the (shared) wake cache
    sweep_specs = data_set_specs(structure, s)[:-2]
    sweep_runs = run_sweeps(config, s.wake_settings, FlightCondition(), sweep_specs,
                            trim=_trim_request(config, recipe.ct, None), n_jobs=args.jobs,
                            cache_dir=args.fit_cache or "default")
    measured = _responses(sweep_runs, sweep_specs, structure.inputs + structure.outputs, s)
    sweep_data = joint_input_output(measured.select(structure.outputs), measured.select(structure.inputs))
    fitted = model.fit.structure
    as_shipped = fitted.with_values({k: float(v) for k, v in shipped.value.items() if k in fitted.names})
    for label, st in (("multisine model", fitted), ("shipped sweep model", as_shipped)):
        costs = {d: cost_on(st, data, model.cost_table) for d, data in
                 (("multisine data", model.responses), ("sweep data", sweep_data))}
        print(f"  J_ave of the {label}: " + ", ".join(f"{k} {v:.1f}" for k, v in costs.items()))
    print("  verification (doublet) of the multisine model:")
    print(model.verification_table.to_string(float_format=lambda v: f"{v:.3g}"))


if __name__ == "__main__":
    main()
