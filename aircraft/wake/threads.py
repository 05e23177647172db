"""Thread control for the wake's mixed numba / BLAS work."""
from __future__ import annotations

from threadpoolctl import ThreadpoolController

__all__ = ["single_threaded_blas"]

_THREADPOOLS = None


def single_threaded_blas():
    """Context manager limiting BLAS to one thread while the wake marches.

    Each step does a few small dense solves (tens to hundreds of unknowns) between
    calls to the multi-threaded numba kernel; idle OpenBLAS threads left spinning
    after those solves compete with numba's threads for the cores (on 2 cores a
    coaxial revolution took 0.82 s instead of 0.28 s).
    """
    global _THREADPOOLS
    if _THREADPOOLS is None:
        _THREADPOOLS = ThreadpoolController()
    return _THREADPOOLS.limit(limits=1, user_api="blas")
