"""What one wake record computes: trim a fresh wake, or march one input record from it.

These two functions are the numbers-producing part of :func:`aircraft.wake.run_sweeps`;
the rest of :mod:`aircraft.wake.sweeps` (cache keys, the executor that runs the
records, progress) cannot change a result. That split is why the wake cache's
code digest (:func:`aircraft.wake.sweeps._wake_code_digest`) covers this module
and the marching modules but not the orchestration: a faster or distributed
executor must not throw away a cache of hours of wake runs, while any change
here or in the march does.
"""
from __future__ import annotations

import numpy as np

__all__: list[str] = []


def _trim(config, settings, flight, trim):
    """Trim a fresh wake; ``(snapshot, WakeTrim)``."""
    from .wake import FreeVortexWake
    wake = FreeVortexWake(config, settings, flight)
    trim_result = wake.trim(**trim)
    return wake._trim_state, trim_result


def _run_spec(config, settings, flight, snap, trim_result, spec, points):
    """One record from the trimmed wake state ``snap`` (a pandas.DataFrame).

    ``spec.inputs(dt)`` gives every control's time history ``{control: (t, u)}``
    [s, rad]; the record lasts until the end of the longest.
    """
    from .wake import FreeVortexWake
    wake = FreeVortexWake(config, settings, flight)
    wake.restore(snap)
    wake._trim_state = snap
    wake.trim_result = trim_result
    inputs = {c: (np.asarray(t), np.asarray(u)) for c, (t, u) in spec.inputs(wake.dt).items()}
    duration = max(float(t[-1]) for t, _ in inputs.values())
    return wake.run(inputs, duration=duration, points=points)
