#!/usr/bin/env bash
# GPU Biot-Savart kernel check on a machine with an NVIDIA GPU, in one command
# from the repository root (about 1-3 minutes, at most ~5):
#
#     bash benchmarks/gpu_device_check.sh
#
# Prints: the device and the CUDA toolkit numba found, whether
# aircraft.wake.gpu.available() and why, the device tests of tests/aircraft/wake/test_wake_gpu.py
# (GPU kernel vs CPU kernel in single and double precision, a whole tiny wake run
# on the GPU vs the CPU within CROSS_MACHINE_RTOL), then the GPU figures of
# benchmarks/wake.py (kernel agreement, pairs/s, one default-resolution coaxial
# revolution with the GPU kernel vs the CPU kernel on 2 threads, at three
# resolutions), then benchmarks/gpu_per_call.py (one call at a wake's sizes).
#
# Python: $PYTHON, else .venv/bin/python, else python3 (numba, numpy, pandas,
# scipy and pytest needed; the package is imported from this checkout).
# numba's built-in CUDA target needs NVVM/libdevice: a CUDA toolkit under
# $CUDA_HOME or /usr/local/cuda, or the pip wheel nvidia-cuda-nvcc-cu12 in the
# same environment (CUDA_HOME is pointed at it below when nothing else is set).
set -u
cd "$(dirname "$0")/.."
PY=${PYTHON:-}
if [ -z "$PY" ]; then
    if [ -x .venv/bin/python ]; then PY=.venv/bin/python; else PY=python3; fi
fi
export PYTHONPATH="$PWD${PYTHONPATH:+:$PYTHONPATH}"
export ROTORWAKE_CACHE_DIR=${ROTORWAKE_CACHE_DIR:-off}   # no wake cache: every number is computed here
unset NUMBA_ENABLE_CUDASIM ROTORWAKE_GPU_SIMULATOR ROTORWAKE_KERNEL
if [ -z "${CUDA_HOME:-}" ]; then
    if [ -d /usr/local/cuda/nvvm ]; then
        export CUDA_HOME=/usr/local/cuda
    else
        wheel=$("$PY" -c "import nvidia.cuda_nvcc, os; print(os.path.dirname(nvidia.cuda_nvcc.__file__))" 2>/dev/null || true)
        [ -n "$wheel" ] && [ -d "$wheel/nvvm" ] && export CUDA_HOME="$wheel"
    fi
fi

echo "== device"
command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader
echo "python: $PY ($("$PY" -c 'import sys; print(sys.version.split()[0])'))  CUDA_HOME=${CUDA_HOME:-unset}"
"$PY" - <<'EOF'
import numba
from numba import cuda
print(f"numba {numba.__version__}, numba.cuda {getattr(cuda, 'implementation', '?')}")
try:
    cuda.detect()
except Exception as exc:
    print(f"numba.cuda.detect() failed: {type(exc).__name__}: {exc}")
from aircraft.wake import gpu
print(f"aircraft.wake.gpu.available() = {gpu.available()}: {gpu.unavailable_reason()}")
EOF

echo "== tests/aircraft/wake/test_wake_gpu.py (device tests must pass, not skip)"
timeout 150 "$PY" -m pytest -q -rs tests/aircraft/wake/test_wake_gpu.py
echo "pytest exit status: $?"

echo "== benchmarks/wake.py --gpu-only"
timeout 120 "$PY" benchmarks/wake.py --gpu-only
echo "benchmark exit status: $?"

echo "== benchmarks/gpu_per_call.py"
timeout 60 "$PY" benchmarks/gpu_per_call.py
echo "per-call benchmark exit status: $?"
