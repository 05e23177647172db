"""GPU (numba.cuda) Biot-Savart kernel of aircraft.wake against the CPU kernel.

Three layers:

* on a real CUDA device (skipped without one): the kernel in single and double
  precision against the CPU kernel, and a whole tiny wake run on the GPU against
  the same run on the CPU;
* everywhere (this is what CI exercises): the same kernel source under numba's
  CUDA simulator, in a subprocess (``NUMBA_ENABLE_CUDASIM`` must be set before
  numba is imported), against the CPU kernel computed here; and the backend
  policy under the simulator (not a device for ``"auto"``; usable when asked for
  explicitly with ``ROTORWAKE_GPU_SIMULATOR=1``);
* without a device: asking for the GPU backend is a clear error.
"""
import json
import math
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from aircraft.configs import uh60_single_rotor
from aircraft.wake import FreeVortexWake, WakeSettings, gpu
from aircraft.wake import biot_savart
from aircraft.wake.biot_savart import CROSS_MACHINE_RTOL, segment_velocity

ROOT = Path(__file__).resolve().parents[3]
needs_device = pytest.mark.skipif(not gpu.available(), reason=f"no CUDA device: {gpu.unavailable_reason()}")
# a tiny single-rotor wake (as tests/aircraft/wake/test_reproducible.py): 20 deg steps, 1.5 revolutions, 4 elements
TINY_WAKE = dict(azimuth_step=math.radians(20.0), wake_revolutions=1.5, n_elements=4)


def _segments(seed, m, n):
    # wake-like scales: points tens of metres from the origin, segments of ~0.5 m,
    # cores of centimetres (float32 then carries ~1e-6 of a coordinate)
    rng = np.random.default_rng(seed)
    tg = 20.0 + 5.0 * rng.normal(size=(m, 3))
    a = 20.0 + 5.0 * rng.normal(size=(n, 3))
    b = a + 0.5 * rng.normal(size=(n, 3))
    return tg, a, b, rng.normal(size=n), rng.uniform(0.01, 0.1, size=n)


@pytest.fixture
def cpu_backend():
    """The CPU kernel for the test's references; the previous backend restored after."""
    before = biot_savart.kernel_backend()
    biot_savart.set_kernel_backend("cpu")
    yield
    biot_savart.set_kernel_backend(before)


# Tolerances relative to max |v| (sums with cancellation: relative to each
# component they would be meaningless where a component is near zero).
# single: both kernels round the inputs to float32 identically and then differ
# only in arithmetic rounding (the device fuses multiply-adds), a few float32
# ulps of the largest terms, ~1e-7..1e-6 of max |v|; 1e-5 leaves a factor 10 and
# still fails for any wrong term. (Against the double-precision kernel the input
# rounding itself shows: ~1.5e-5 of max |v| at these scales for the CPU's own
# single kernel, measured; so that comparison is relative to the CPU's.)
# double: the same argument in float64, ~1e-14 of max |v| here; 1e-10 is far
# below any formula error and far above that.
SINGLE_ATOL, DOUBLE_ATOL = 1e-5, 1e-10


@needs_device
@pytest.mark.parametrize("precision, rel", [("single", SINGLE_ATOL), ("double", DOUBLE_ATOL)])
def test_device_kernel_matches_cpu_kernel(cpu_backend, precision, rel):
    tg, a, b, g, rc = _segments(0, m=1000, n=1500)
    ref = segment_velocity(tg, a, b, g, rc, precision)
    got = gpu.segment_velocity(tg, a, b, g, rc, precision)
    assert got.dtype == np.float64 and got.shape == (1000, 3)
    np.testing.assert_allclose(got, ref, rtol=0, atol=rel * np.abs(ref).max())
    # as accurate as the CPU kernel of the same precision against exact-ish
    # (double) arithmetic: at most twice its error, plus the tolerance above
    exact = segment_velocity(tg, a, b, g, rc, "double")
    cpu_error = np.abs(ref - exact).max()
    assert np.abs(got - exact).max() <= 2.0 * cpu_error + rel * np.abs(exact).max()


@needs_device
def test_device_buffers_are_reused_and_sliced_right(cpu_backend):
    # a large call, then a smaller one (the buffers are larger than the data),
    # then a larger one than any before (the buffers grow)
    for m, n in ((300, 500), (17, 40), (2000, 3000)):
        tg, a, b, g, rc = _segments(m, m, n)
        ref = segment_velocity(tg, a, b, g, rc, "double")
        np.testing.assert_allclose(gpu.segment_velocity(tg, a, b, g, rc, "double"), ref,
                                   rtol=0, atol=DOUBLE_ATOL * np.abs(ref).max())


def _march(theta0, revs):
    w = FreeVortexWake(uh60_single_rotor(), WakeSettings(**TINY_WAKE))
    w.controls.update(theta0=theta0)
    return w.run({}, duration=revs * 2 * math.pi / w.omega, about_trim=False, from_trim=False)


@needs_device
def test_wake_run_on_gpu_matches_cpu_within_cross_machine_tolerance(cpu_backend):
    # the GPU's round-off differs from the CPU's (fused multiply-adds), like
    # another machine's: the run must hold the stated cross-machine tolerance on
    # the averages over the last 4 of 6 revolutions (tests/aircraft/wake/test_reproducible.py)
    revs = 6
    ref = _march(0.15, revs)
    assert biot_savart.set_kernel_backend("gpu") == "gpu"
    other = _march(0.15, revs)
    late = ref.t > (revs - 4) * ref.t.iloc[-1] / revs
    for name in ("CT", "lam0"):
        assert other[name][late].mean() == pytest.approx(ref[name][late].mean(), rel=CROSS_MACHINE_RTOL)
    for name in ("CL", "CM"):
        assert abs(other[name][late].mean() - ref[name][late].mean()) < CROSS_MACHINE_RTOL * ref.CT[late].mean()


_SIMULATOR_SCRIPT = textwrap.dedent("""
    import importlib, json, os, sys
    import numpy as np
    from aircraft.wake import biot_savart, gpu
    d = np.load(sys.argv[1])
    args = [d[k] for k in ("tg", "a", "b", "g", "rc")]
    facts = {"simulated": gpu.simulated(), "available": gpu.available(),
             "reason": gpu.unavailable_reason(), "auto": biot_savart.set_kernel_backend("auto")}
    try:
        biot_savart.set_kernel_backend("gpu")
        facts["gpu_error"] = None
    except ValueError as exc:
        facts["gpu_error"] = str(exc)
    out = {p: gpu.segment_velocity(*args, precision=p) for p in ("double", "single")}
    out["small"] = gpu.segment_velocity(*[x[:7] for x in args], precision="double")  # buffers reused
    # the explicit request: the simulator becomes the "gpu" backend, and
    # segment_velocity dispatches to it
    os.environ[gpu.SIMULATOR_ENV] = "1"
    importlib.reload(gpu)
    facts["explicit_available"] = gpu.available()
    facts["explicit_reason"] = gpu.unavailable_reason()
    facts["explicit_gpu"] = biot_savart.set_kernel_backend("gpu")
    facts["explicit_auto"] = biot_savart.set_kernel_backend("auto")
    out["dispatched"] = biot_savart.segment_velocity(*args, precision="double")
    np.savez(sys.argv[2], **out)
    print(json.dumps(facts))
""")


@pytest.mark.slow
def test_kernel_under_cuda_simulator_matches_cpu_kernel(tmp_path, cpu_backend):
    tg, a, b, g, rc = _segments(3, m=50, n=80)
    np.savez(tmp_path / "in.npz", tg=tg, a=a, b=b, g=g, rc=rc)
    # the checkout first, then whatever path the caller set (a device machine
    # may bring packages on PYTHONPATH)
    pythonpath = os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH", "")) if p)
    env = dict(os.environ, NUMBA_ENABLE_CUDASIM="1", PYTHONPATH=pythonpath)
    env.pop(gpu.SIMULATOR_ENV, None)
    env.pop(biot_savart.KERNEL_ENV, None)
    done = subprocess.run([sys.executable, "-c", _SIMULATOR_SCRIPT, str(tmp_path / "in.npz"),
                           str(tmp_path / "out.npz")], cwd=ROOT, env=env, capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    facts = json.loads(done.stdout.strip().splitlines()[-1])
    # the simulator is not a device: "auto" stays on the CPU, "gpu" is refused ...
    assert facts["simulated"] and not facts["available"]
    assert "simulator" in facts["reason"] and facts["auto"] == "cpu"
    assert facts["gpu_error"] is not None and "no CUDA device is usable" in facts["gpu_error"]
    # ... unless asked for explicitly (after the same self-check a device gets)
    assert facts["explicit_available"], facts["explicit_reason"]
    assert "explicitly enabled" in facts["explicit_reason"]
    assert facts["explicit_gpu"] == "gpu" and facts["explicit_auto"] == "gpu"
    out = np.load(tmp_path / "out.npz")
    for precision, rel in (("single", SINGLE_ATOL), ("double", DOUBLE_ATOL)):
        ref = segment_velocity(tg, a, b, g, rc, precision)
        assert out[precision].shape == (50, 3)
        np.testing.assert_allclose(out[precision], ref, rtol=0, atol=rel * np.abs(ref).max())
    ref = segment_velocity(tg, a, b, g, rc, "double")
    np.testing.assert_allclose(out["dispatched"], ref, rtol=0, atol=DOUBLE_ATOL * np.abs(ref).max())
    small = segment_velocity(tg[:7], a[:7], b[:7], g[:7], rc[:7], "double")
    np.testing.assert_allclose(out["small"], small, rtol=0, atol=DOUBLE_ATOL * np.abs(small).max())


def test_empty_inputs_need_no_device():
    assert gpu.segment_velocity(np.zeros((0, 3)), np.zeros((4, 3)), np.ones((4, 3)), 1.0, 0.1).shape == (0, 3)
    v = gpu.segment_velocity(np.zeros((5, 3)), np.zeros((0, 3)), np.zeros((0, 3)), 1.0, 0.1)
    np.testing.assert_array_equal(v, np.zeros((5, 3)))


def test_bad_input_is_refused_like_the_cpu_kernel():
    p, a, b = np.zeros((2, 3)), np.zeros((1, 3)), np.ones((1, 3))
    with pytest.raises(ValueError, match="precision must be"):
        gpu.segment_velocity(p, a, b, 1.0, 0.1, precision="half")
    with pytest.raises(ValueError, match="targets must have shape"):
        gpu.segment_velocity(np.zeros((2, 2)), a, b, 1.0, 0.1)
    with pytest.raises(ValueError, match="core radii must be >= 0"):
        gpu.segment_velocity(p, a, b, 1.0, -0.1)
    with pytest.raises(ValueError, match="gamma must be"):
        gpu.segment_velocity(p, a, b, None, 0.1)


@pytest.mark.skipif(gpu.available(), reason="a CUDA device is usable here")
def test_gpu_backend_without_device_is_a_clear_error(cpu_backend):
    assert isinstance(gpu.unavailable_reason(), str) and gpu.device_name() is None
    with pytest.raises(ValueError, match="kernel backend 'gpu' requested but no CUDA device is usable"):
        biot_savart.set_kernel_backend("gpu")
    assert biot_savart.kernel_backend() == "cpu"          # unchanged by the refusal
    assert biot_savart.set_kernel_backend("auto") == "cpu"
    if not gpu.simulated():
        with pytest.raises(RuntimeError, match="needs a CUDA device"):
            gpu.segment_velocity(np.zeros((2, 3)), np.zeros((1, 3)), np.ones((1, 3)), 1.0, 0.1)


@pytest.mark.parametrize("m, n", [(1, 1), (7, 31), (50, 80), (1160, 3008), (20000, 20000), (3, 100000)])
def test_segment_chunks_cover_every_segment_once(m, n):
    # the pair kernel's thread (i, c) sums segments [c chunk, min(n, (c + 1) chunk)):
    # the chunks must tile 0..n-1 exactly, whatever the sizes
    n_chunks = gpu._n_chunks(m, n)
    chunk = -(-n // n_chunks)
    covered = np.concatenate([np.arange(c * chunk, min(n, (c + 1) * chunk)) for c in range(n_chunks)])
    np.testing.assert_array_equal(covered, np.arange(n))
    assert 1 <= n_chunks <= max(1, -(-n // gpu.MIN_CHUNK))
    assert n_chunks == 1 or m * (n_chunks - 1) < gpu.TARGET_THREADS
