import os
import platform
from pathlib import Path

# the same OpenBLAS kernels on every x86-64 machine with AVX2 (as the rotorwake command line sets
# them, see docs/reproducibility.rst): set before numpy loads OpenBLAS, which reads it once
if "OPENBLAS_CORETYPE" not in os.environ and platform.machine().lower() in ("x86_64", "amd64"):
    _flags = set(Path("/proc/cpuinfo").read_text().split()) if Path("/proc/cpuinfo").is_file() else set()
    if {"avx2", "fma"} <= _flags:
        os.environ["OPENBLAS_CORETYPE"] = "Haswell"

import matplotlib  # noqa: E402  (after the BLAS kernels are chosen)

# Library code never touches global pyplot state, but tests that call .plot()
# need a non-interactive backend on headless CI machines.
matplotlib.use("Agg")
