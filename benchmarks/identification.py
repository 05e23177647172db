"""Benchmark: identification of the 6-state coaxial model and frequency-response throughput.

Prints (one run, same machine):
* wall time to identify the 6-state coaxial model from six synthetic sweeps
  (frequency responses + joint input-output + 24-parameter fit), target < 60 s on 2 cores;
* frequency-response throughput in time-series samples per second;
* wall time of each flight-test method on its test case (loader + multi-run
  concatenation, transfer-function fit, LOES, DERIVID state space, frequency-domain
  output error and equation error on a 2-1-1, reduction with relative rise limits);
* with ``--wake``: wall time of the whole library pipeline
  (:func:`aircraft.identify_inflow`, 3-state single rotor) on a coarse wake, uncached.
"""
import argparse
import math
import time

import numpy as np

from aircraft.identification.structures import Coaxial6State
from aircraft.identification.testing import SWASHPLATE_CONTROLS, coaxial_sweep_set
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


def _timed(label, fn):
    t0 = time.perf_counter()
    out = fn()
    print(f"  {label}: {time.perf_counter() - t0:.3f} s")
    return out


def flight_test_methods():
    """Each flight-test method on the case its tests use (tests/flightid/)."""
    import control
    import pandas as pd
    from scipy.signal import lsim
    from flightid import (StateSpaceStructure, concatenated_response, fit_transfer_function, frequency_sweep, identify, read_flight_data, reduce)
    from flightid.transfer_function import loes_fit
    from flightid.transfer_function import TransferFunctionStructure
    print("flight-test methods (wall time of one call):")
    rng = np.random.default_rng(0)
    runs = []
    for seed in (3, 4):
        t = np.arange(0.0, 80.0, 0.02)
        u = np.random.default_rng(seed).standard_normal(t.size)
        y = lsim(([2.0], [1.0, 1.5]), u, t)[1] + 0.02 * rng.standard_normal(t.size)
        runs.append(pd.DataFrame({"t": t + rng.uniform(-0.002, 0.002, t.size), "u": u, "y": y}))
    records = _timed("read_flight_data x 2 (4000 samples, resample linear)",
                     lambda: [read_flight_data(df, resample=0.02) for df in runs])
    _timed("concatenated_response (2 runs)",
           lambda: concatenated_response(records, "u", "y", w_min=0.5, w_max=12.0))
    dt = 0.01
    t, u = frequency_sweep(0.3, 30.0, 90.0, dt, trim_start=10.0, trim_end=5.0, noise_fraction=0.2, seed=0)
    ud = np.concatenate([np.zeros(6), u[:-6]])
    y = lsim(([3.0, 3.0], [1.0, 3.0, 9.0]), ud, t)[1]
    data = frequency_response(t, u, y, w_min=0.5, w_max=25.0)
    _timed("fit_transfer_function (1/2 + delay, 90 s sweep)", lambda: fit_transfer_function(data, 1, 2))
    hos = control.tf([3.0, 3.0], [1.0, 3.0, 9.0]) * control.tf([25.0], [1.0, 25.0])
    _timed("loes_fit (1/2 + delay of a 3rd-order system)", lambda: loes_fit(hos, 1, 2))
    a = np.array([[-1.2, 1.0], [-6.0, -2.5]])
    b = np.array([[-0.15], [-9.0]])
    c = np.array([[0.0, 1.0], [-1.2, 0.0]])
    dd = np.array([[0.0], [-0.15]])
    ysp = lsim((a, b, c, dd), u, t)[1]
    spdata = frequency_response(t, u, ysp, w_min=0.5, w_max=25.0, input_name="de", output_names=["q", "az"])
    truth = {"Za": -1.2, "Ma": -6.0, "Mq": -2.5, "Zde": -0.15, "Mde": -9.0}
    sp = StateSpaceStructure([["Za", 1.0], ["Ma", "Mq"]], [["Zde"], ["Mde"]], [[0.0, 1.0], ["Za", 0.0]],
                             D=[[0.0], ["Zde"]], inputs=["de"], outputs=["q", "az"],
                             initial={k: 0.5 * v for k, v in truth.items()})
    _timed("fit, DERIVID state space (C, D parametrised, 2 outputs)", lambda: fit(sp, spdata))
    t2 = np.arange(0.0, 15.0, 0.02)
    u2 = ((t2 >= 1) & (t2 < 2)) * 1.0 - ((t2 >= 2) & (t2 < 2.5)) + ((t2 >= 2.5) & (t2 < 3))
    x2 = lsim((a, b, np.eye(2), np.zeros((2, 1))), u2, t2)[1]
    rec = read_flight_data(pd.DataFrame({"t": t2, "u": u2, "y0": x2[:, 0], "y1": x2[:, 1]}))
    ss = StateSpaceStructure([["Za", 1.0], ["Ma", "Mq"]], [["Zde"], ["Mde"]], np.eye(2).tolist(),
                             inputs=["u"], outputs=["y0", "y1"], initial={k: 0.6 * v for k, v in truth.items()})
    _timed("identify, frequency-domain output error (2-1-1, 15 s)",
           lambda: identify(ss, rec, method="output_error", w_min=0.4, w_max=12.0))
    _timed("identify, frequency-domain equation error (2-1-1, 15 s)",
           lambda: identify(ss, rec, method="equation_error", w_min=0.4, w_max=12.0))
    t3, u3 = frequency_sweep(0.3, 30.0, 90.0, 0.005, trim_start=20.0, trim_end=5.0, noise_fraction=0.2, seed=0)
    y3 = lsim(([2.0], [1.0, 1.5]), np.concatenate([[0.0], u3[:-1]]), t3)[1]
    y3 = y3 + 0.01 * np.std(y3) * np.random.default_rng(1).standard_normal(t3.size)
    d3 = frequency_response(t3, u3, y3, w_min=0.5, w_max=12.0)
    s3 = TransferFunctionStructure(0, 1, initial={"b0": 1.5, "a0": 1.0, "tau": 0.01})
    _timed("reduce, relative_rise=0.5 (first order + 5 ms delay)", lambda: reduce(s3, d3, relative_rise=0.5))


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
    flight_test_methods()
    if args.wake:
        wake_pipeline()


if __name__ == "__main__":
    main()
