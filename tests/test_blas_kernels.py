"""The tests run on one OpenBLAS kernel family on every x86-64 machine with AVX2.

OpenBLAS picks its kernels by processor, and their sums round differently: the
design-margin optimiser's path through unconverged IPOPT iterates turns that
round-off into designs a few per cent apart, so a test could pass on one machine
and fail on another. ``tests/conftest.py`` (and the ``rotorwake`` command line)
choose the AVX2 ("Haswell") kernels before numpy loads OpenBLAS, on a processor
that has them; this checks that the choice took effect in the process that runs
the tests (OpenBLAS reads it once, when it loads).
"""
import os

import pytest
from threadpoolctl import threadpool_info


@pytest.mark.skipif("OPENBLAS_CORETYPE" not in os.environ,
                    reason="no kernel family chosen: not an x86-64 processor with AVX2 and FMA")
def test_every_loaded_openblas_uses_the_chosen_kernels():
    import numpy  # noqa: F401  (loads numpy's OpenBLAS)
    import scipy.linalg  # noqa: F401  (and scipy's)
    wanted = os.environ["OPENBLAS_CORETYPE"]
    found = {i["filepath"]: i.get("architecture") for i in threadpool_info() if i.get("internal_api") == "openblas"}
    assert found, "no OpenBLAS loaded"
    assert all(arch.lower() == wanted.lower() for arch in found.values()), found
