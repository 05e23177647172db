"""Reproducibility of wake results: bit-identical on one machine, a stated tolerance across.

The Biot-Savart kernel is compiled without fastmath and without parallel
reductions (see :mod:`aircraft.wake.biot_savart`), so its result is the IEEE-754
value of the sum written in its source. The first test checks exactly that, bit
for bit, against an independent numpy evaluation of the same sequential sum.
"""
import math

import numba
import numpy as np
import pytest

from aircraft.configs import uh60_single_rotor
from aircraft.wake import FreeVortexWake, WakeSettings, segment_velocity
from aircraft.wake.biot_savart import CROSS_MACHINE_RTOL

TINY = 1e-12
# a tiny single-rotor wake: 20 deg steps, 1.5 revolutions, 4 elements (~0.3 s/rev)
TINY_WAKE = dict(azimuth_step=math.radians(20.0), wake_revolutions=1.5, n_elements=4)
SIGNALS = ["CT", "CL", "CM", "lam0", "lam1s", "lam1c"]


def _segments(seed, m=37, n=53):
    rng = np.random.default_rng(seed)
    tg = 20.0 + 5.0 * rng.normal(size=(m, 3))
    a = 20.0 + 5.0 * rng.normal(size=(n, 3))
    b = a + 0.5 * rng.normal(size=(n, 3))
    return tg, a, b, rng.normal(size=n), rng.uniform(0.01, 0.1, size=n)


def _sequential_reference(tg, a, b, gamma, rc):
    """Same formula and operation order as the kernel, summed strictly left to right."""
    r0 = b - a
    rcl = rc * rc * np.einsum("ij,ij->i", r0, r0)
    g4 = gamma / (4.0 * math.pi)
    rcl2 = rcl * rcl
    out = np.zeros((tg.shape[0], 3))
    for i, p in enumerate(tg):
        r1 = p - a
        r2 = p - b
        cx = r1[:, 1] * r2[:, 2] - r1[:, 2] * r2[:, 1]
        cy = r1[:, 2] * r2[:, 0] - r1[:, 0] * r2[:, 2]
        cz = r1[:, 0] * r2[:, 1] - r1[:, 1] * r2[:, 0]
        c2 = cx * cx + cy * cy + cz * cz
        i1 = 1.0 / (np.sqrt(r1[:, 0] * r1[:, 0] + r1[:, 1] * r1[:, 1] + r1[:, 2] * r1[:, 2]) + TINY)
        i2 = 1.0 / (np.sqrt(r2[:, 0] * r2[:, 0] + r2[:, 1] * r2[:, 1] + r2[:, 2] * r2[:, 2]) + TINY)
        dot = (r0[:, 0] * (r1[:, 0] * i1 - r2[:, 0] * i2) + r0[:, 1] * (r1[:, 1] * i1 - r2[:, 1] * i2)
               + r0[:, 2] * (r1[:, 2] * i1 - r2[:, 2] * i2))
        f = g4 * dot / (np.sqrt(c2 * c2 + rcl2) + TINY)
        for k, c in enumerate((cx, cy, cz)):
            acc = 0.0
            for term in f * c:        # strictly sequential, as in the kernel
                acc += term
            out[i, k] = acc
    return out


def test_kernel_is_the_ieee_value_of_its_sequential_sum():
    # Bit-for-bit: any reassociation (fastmath), FMA contraction or
    # vector-width-dependent reduction would change the last bits somewhere in
    # 37 x 3 sums of 53 terms. Equality here is what makes the kernel the same
    # on every IEEE-754 CPU.
    tg, a, b, g, rc = _segments(0)
    np.testing.assert_array_equal(segment_velocity(tg, a, b, g, rc, "double"),
                                  _sequential_reference(tg, a, b, g, rc))


def test_kernel_does_not_depend_on_threads_or_batching():
    tg, a, b, g, rc = _segments(1, m=70, n=40)
    threads = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        one = segment_velocity(tg, a, b, g, rc, "single")
        # `make test` runs with NUMBA_NUM_THREADS=1; with more allowed, compare
        numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
        many = segment_velocity(tg, a, b, g, rc, "single")
    finally:
        numba.set_num_threads(threads)
    np.testing.assert_array_equal(one, many)
    # each target alone (another padding, another SIMD lane) gives the same bits
    alone = np.vstack([segment_velocity(tg[i:i + 1], a, b, g, rc, "single") for i in (0, 17, 69)])
    np.testing.assert_array_equal(alone, one[[0, 17, 69]])


def _march(theta0, revs):
    w = FreeVortexWake(uh60_single_rotor(), WakeSettings(**TINY_WAKE))
    w.controls.update(theta0=theta0)
    return w.run({}, duration=revs * 2 * math.pi / w.omega, about_trim=False, from_trim=False)


def test_two_identical_wake_runs_are_bit_identical():
    first = _march(0.15, 3)
    second = _march(0.15, 3)
    np.testing.assert_array_equal(first[SIGNALS + ["t"]].to_numpy(), second[SIGNALS + ["t"]].to_numpy())


@pytest.mark.parametrize("relative_perturbation", [1e-13, 1e-11])
def test_round_off_perturbations_stay_within_the_cross_machine_tolerance(relative_perturbation):
    # Another machine's libm/BLAS rounds the march's trigonometry and small solves
    # differently in the last bits. Emulate that by perturbing the collective at
    # 1e-13 (stays at round-off level here) and 1e-11 (measured: past a discrete
    # flip, instantaneous C_T then differs by ~4 %) and hold the averages over the
    # last 4 of 6 revolutions to the stated CROSS_MACHINE_RTOL.
    revs = 6
    ref = _march(0.15, revs)
    other = _march(0.15 * (1.0 + relative_perturbation), revs)
    late = ref.t > (revs - 4) * ref.t.iloc[-1] / revs
    for name in ("CT", "lam0"):
        assert other[name][late].mean() == pytest.approx(ref[name][late].mean(), rel=CROSS_MACHINE_RTOL)
    # the hub moments fluctuate by ~4 % of C_T in this untrimmed hover wake after
    # a flip; their averages must agree to the same tolerance, on the C_T scale
    for name in ("CL", "CM"):
        assert abs(other[name][late].mean() - ref[name][late].mean()) < CROSS_MACHINE_RTOL * ref.CT[late].mean()


@pytest.mark.slow
def test_wake_cache_never_serves_results_of_other_code(tmp_path, monkeypatch):
    # The cache key includes a digest of the wake's source: with another digest
    # (what any edit of aircraft/wake/*.py gives) the runs are recomputed, not
    # served, and the recomputation is bit-identical to the first run.
    import pandas as pd
    from aircraft.wake import FlightCondition, SweepSpec, run_sweeps
    from aircraft.wake import sweeps as sweeps_module
    specs = [SweepSpec("theta0", kind="sine", amplitude=0.01, duration=0.3, w_min=5.0)]
    args = (uh60_single_rotor(), WakeSettings(**TINY_WAKE), FlightCondition(), specs)
    first = run_sweeps(*args, trim={"ct": 0.0061}, n_jobs=1, cache_dir=tmp_path, progress=False)
    assert len(list(tmp_path.glob("*.pkl"))) == 2          # the run and the trim
    monkeypatch.setattr(sweeps_module, "_wake_code_digest", lambda: "other code")
    second = run_sweeps(*args, trim={"ct": 0.0061}, n_jobs=1, cache_dir=tmp_path, progress=False)
    assert len(list(tmp_path.glob("*.pkl"))) == 4          # recomputed under new keys
    pd.testing.assert_frame_equal(second["sine_theta0"], first["sine_theta0"], check_exact=True)


def test_real_blade_source_keys_the_cache_only_for_bladed_rotors():
    # aircraft/blade.py computes a real blade's section lift and drag outside the wake
    # package, so its source must key those runs; the classical blade's numbers are all
    # in the wake's own modules, so the dissertation's aircraft keep their entries
    import dataclasses
    import hashlib
    from pathlib import Path
    import aircraft
    from aircraft.blade import BladeModel, Polar
    from aircraft.wake import sweeps as sweeps_module
    classic = uh60_single_rotor()
    assert sweeps_module._blade_key(classic) == {}
    blade = BladeModel(polar=Polar(alpha=(-0.3, 0.0, 0.3), cl=(-1.2, 0.0, 1.2), cd=(0.05, 0.008, 0.05)))
    bladed = dataclasses.replace(classic, rotors=(dataclasses.replace(classic.rotors[0], blade=blade),))
    source = (Path(aircraft.__file__).parent / "blade.py").read_bytes()
    assert sweeps_module._blade_key(bladed) == {"blade_code": hashlib.sha256(source).hexdigest()}


def test_initial_perturbation_gives_another_machines_records():
    # the reproduction check's second data set: a start displaced by 1e-7 R (single-precision
    # rounding) must change the records (else the check compares a data set with itself) and
    # keep the revolution averages within the cross-machine tolerance (else it is another wake)
    revs = 6
    ref = _march(0.15, revs)
    w = FreeVortexWake(uh60_single_rotor(), WakeSettings(**TINY_WAKE, initial_perturbation=1e-7))
    w.controls.update(theta0=0.15)
    other = w.run({}, duration=revs * 2 * math.pi / w.omega, about_trim=False, from_trim=False)
    assert not np.array_equal(ref[SIGNALS].to_numpy(), other[SIGNALS].to_numpy())
    late = ref.t > (revs - 4) * ref.t.iloc[-1] / revs
    for name in ("CT", "lam0"):
        assert other[name][late].mean() == pytest.approx(ref[name][late].mean(), rel=CROSS_MACHINE_RTOL)


@pytest.mark.parametrize("bad", [-1e-7, 1e-2, float("nan"), "1e-7"])
def test_initial_perturbation_is_validated(bad):
    from aircraft.wake import WakeSettingsError
    with pytest.raises(WakeSettingsError, match="initial_perturbation"):
        WakeSettings(initial_perturbation=bad)


def test_an_unset_new_setting_leaves_identity_hashes_alone():
    # identity_repr / identity_dict must equal the dataclasses' own repr / asdict while the
    # fields added later are at their defaults: the shipped models' recipe hashes use them
    from dataclasses import asdict
    from aircraft.configs import coaxial_compound
    from aircraft.provenance import identity_dict, identity_repr
    for obj in (uh60_single_rotor(), coaxial_compound(), WakeSettings()):
        # the fields added with a neutral default (HASHED_IF_SET) are the only difference
        assert identity_repr(obj) == repr(obj).replace(", initial_perturbation=0.0", "").replace(", blade=None", "")
    d = asdict(WakeSettings())
    d.pop("initial_perturbation")
    assert identity_dict(WakeSettings()) == d
    assert identity_dict(WakeSettings(initial_perturbation=1e-7))["initial_perturbation"] == 1e-7
