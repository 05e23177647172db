"""Jobs for the killed-worker tests of :mod:`test_wake_faults`.

Kept apart from the test module on purpose: a spawned pool worker imports the
module of the function it runs, and this one needs nothing but the standard
library (the test module would pull in the whole toolkit in every worker).
"""
import os
import signal
import time


def kill_on(job):
    """Return ``job``; a job ``"kill"`` SIGKILLs its own worker process (no clean-up
    handler runs, as with the out-of-memory killer), after the others had time to finish."""
    if job == "kill":
        time.sleep(0.5)
        os.kill(os.getpid(), signal.SIGKILL)
    return job
