"""Benchmark: identification of the 6-state coaxial model and frequency-response throughput.

Prints (one run, same machine):
* wall time to identify the 6-state coaxial model from six synthetic sweeps
  (frequency responses + joint input-output + 24-parameter fit), target < 60 s on 2 cores;
* frequency-response throughput in time-series samples per second;
* with ``--wake``: wall time of the whole library pipeline
  (:func:`aircraft.identify_inflow`, 3-state single rotor) on a coarse wake, uncached.
"""
import argparse
import math
import time

import numpy as np

from aircraft.identification import Coaxial6State
from aircraft.identification.synthetic import SWASHPLATE_CONTROLS, coaxial_sweep_set
from aircraft.inflow.published import COAXIAL_HOVER_6STATE
from flightid import combine_responses, fit, frequency_response, joint_input_output


def synthetic_6state():
    model = COAXIAL_HOVER_6STATE
    runs = coaxial_sweep_set(model, seed=0, noise=0.02)
    names_c, names_l = model.input_names, model.output_names
    t0 = time.perf_counter()
    simo = [frequency_response(r["t"], r["theta"], np.vstack([r["loads"], r["lam"]]).T,
                               w_min=0.8, w_max=30.0, input_name=SWASHPLATE_CONTROLS[r["control"]],
                               output_names=names_c + names_l) for r in runs]
    t_fr = time.perf_counter() - t0
    responses = combine_responses(simo)
    lam_c = joint_input_output(responses.select(names_l), responses.select(names_c))
    structure = Coaxial6State("printed")         # the truth is simulated in the printed frame
    truth = structure.published_values(model)
    rng = np.random.default_rng(100)
    initial = {k: (v * rng.uniform(0.7, 1.3) if not k.startswith("t") else 0.05) for k, v in truth.items()}
    t1 = time.perf_counter()
    result = fit(structure.build(initial, model.omega), lam_c, frequency_ranges=(1.0, 25.0))
    t_fit = time.perf_counter() - t1
    total = time.perf_counter() - t0
    samples = sum(r["t"].size * 12 for r in runs)   # 12 output channels per sweep
    print("== identification benchmark ==")
    print(f"6-state coaxial from six sweeps: total {total:.2f} s "
          f"(frequency responses {t_fr:.2f} s, fit {t_fit:.2f} s, J_ave {result.J_ave:.3f}); "
          f"target < 60 s -> {'met' if total < 60 else 'NOT met'}")
    print(f"frequency-response throughput: {samples / t_fr:,.0f} samples/s "
          f"({len(runs)} records x {runs[0]['t'].size} samples x 12 outputs, 5 windows each)")


def wake_pipeline():
    from aircraft import identify_inflow
    from aircraft.configs import uh60_single_rotor
    from aircraft.identification import IdentificationSettings
    from aircraft.wake import WakeSettings
    settings = IdentificationSettings(
        wake=WakeSettings(azimuth_step=math.radians(15.0), wake_revolutions=1.5, n_elements=5), sweep_s=36.0)
    t0 = time.perf_counter()
    model = identify_inflow(uh60_single_rotor(), None, "single_rotor_3state", ct=0.0061, settings=settings,
                            n_jobs=2, cache_dir=None, progress=False)
    print(f"identify_inflow, 3-state single rotor, coarse wake (15 deg, 1.5 revs, 5 elements, 3 x 36 s "
          f"sweeps + doublet + zero-input run, 2 jobs, uncached): {time.perf_counter() - t0:.1f} s, "
          f"J_ave {model.J_ave:.1f}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--wake", action="store_true", help="also time the wake pipeline")
    args = parser.parse_args(argv)
    synthetic_6state()
    if args.wake:
        wake_pipeline()


if __name__ == "__main__":
    main()
