"""Benchmark: one refit of the 200 kt coaxial structure (Eq. 6.5, 180 parameters) and its reduction.

One run prints, on this machine (wall and CPU seconds; the CPU time is the one to
compare on a machine shared with other work):

* the 200 kt data set and first fit (:func:`identify_coaxial_forward` without the
  reduction: coarse wake, the aircraft's thrust and lift offsets, six 40 s sweeps),
  served from the wake cache when it holds the records;
* one refit of the 180-parameter structure from that fit, and one after removing its
  worst-bounded parameter (what every step of the reduction does), with scipy's
  finite-difference Jacobian (the default of :func:`flightid.fit`) and with the
  analytic one (``jacobian="analytic"``), and their ratio;
* with ``--reduction``: the whole automatic reduction (Fig. 6.1, analytic Jacobian,
  ``--batch`` candidates per refit, no bound on the steps) against the target of
  15 min on 2 cores, and the trust verdict of the result.

Run: ``.venv/bin/python benchmarks/coaxial_forward_refit.py [--reduction] [--batch 10]``
(``ROTORWAKE_CACHE_DIR`` selects the wake cache; without the records the wake runs
add about 1-2 min).
"""
import argparse
import math
import time
from types import SimpleNamespace

from aircraft.configs import coaxial_compound
from aircraft.identification import IdentificationSettings
from aircraft.identification.coaxial_forward_flight import (aircraft_lift_offset, aircraft_thrust_at,
                                                            identify_coaxial_forward)
from aircraft.identification.structures import CoaxialForward12State
from aircraft.identification.trust import trust_check
from aircraft.wake import WakeSettings
from flightid import fit, reduce

#: the study's coarse wake and settings at 200 kt (studies/coaxial_forward_flight.py)
COARSE = WakeSettings(azimuth_step=math.radians(15.0), wake_revolutions=2.0, n_elements=6)
SETTINGS = IdentificationSettings(wake=COARSE, sweep_s=40.0, doublet_control="theta1s_L", doublet_amplitude=0.035)
DIFFERENTIAL_LATERAL_CYCLIC = 0.03


def _clock(fn):
    t0, c0 = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - t0, time.process_time() - c0


def data_set():
    config = coaxial_compound(cruise=True)
    ct = aircraft_thrust_at(config, lateral_cyclic_difference=DIFFERENTIAL_LATERAL_CYCLIC)
    los = aircraft_lift_offset(config, lateral_cyclic_difference=DIFFERENTIAL_LATERAL_CYCLIC)
    model, wall, cpu = _clock(lambda: identify_coaxial_forward(
        config, ct=ct, structure=CoaxialForward12State(), settings=SETTINGS, n_jobs=2, progress=False,
        max_reduction_steps=0, lift_offset=los))
    print(f"200 kt data set and first fit: {wall:.1f} s wall, {cpu:.1f} s CPU of this process "
          f"(J_ave {model.J_ave:.3f}, {len(model.fit.structure.free_names)} free parameters)")
    return model


def refits(model):
    s = SETTINGS
    kwargs = dict(frequency_ranges=tuple(s.fit_range), n_omega=s.n_omega, coherence_min=s.coherence_min,
                  max_nfev=150, pairs=[(p.output, p.input) for p in model.fit.pairs])
    table = model.fit.parameters[model.fit.parameters.status == "free"]
    worst = table.sort_values("cramer_rao_pct").parameter.iloc[-1]
    times = {}
    for jac in ("finite-difference", "analytic"):
        first, w1, c1 = _clock(lambda: fit(model.fit.structure, model.responses, jacobian=jac, **kwargs))
        removal, w2, c2 = _clock(lambda: fit(model.fit.structure.fix([worst], 0.0), model.responses,
                                             jacobian=jac, **kwargs))
        times[jac] = (w1, c1, w2, c2)
        print(f"  {jac:>17}: refit {w1:6.1f} s wall {c1:6.1f} s CPU (J_ave {first.J_ave:.4f}); "
              f"refit without {worst} {w2:6.1f} s wall {c2:6.1f} s CPU (J_ave {removal.J_ave:.4f})")
    fd, an = times["finite-difference"], times["analytic"]
    print(f"  analytic / finite-difference speed-up: refit x{fd[1] / an[1]:.1f} (CPU), x{fd[0] / an[0]:.1f} (wall); "
          f"removal refit x{fd[3] / an[3]:.1f} (CPU), x{fd[2] / an[2]:.1f} (wall)")


def reduction(model, batch):
    s = SETTINGS
    structure = CoaxialForward12State()
    red, wall, cpu = _clock(lambda: reduce(
        model.fit.structure, model.responses, insensitivity_max=s.insensitivity_max,
        cramer_rao_max=s.cramer_rao_max, protected=structure.protected, max_steps=10_000, batch=batch,
        frequency_ranges=tuple(s.fit_range), n_omega=s.n_omega, coherence_min=s.coherence_min,
        **structure.fit_options))
    result = red.result
    free = result.parameters[result.parameters.status == "free"]
    check = trust_check(SimpleNamespace(fit=result, J_ave=result.J_ave, settings=s, reduction=red))
    print(f"whole reduction (batch {batch}, to completion): {wall:.0f} s wall, {cpu:.0f} s CPU; target < 900 s "
          f"on 2 cores -> {'met' if wall < 900 else 'NOT met'}; {len(red.log)} log rows, {len(red.removed)} "
          f"removed, {len(free)} free, J_ave {result.J_ave:.3f}; verdicts "
          f"{check.table.verdict.value_counts().to_dict()}; {'trusted' if check.passes else 'NOT trusted'}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--reduction", action="store_true", help="also time the whole reduction")
    parser.add_argument("--batch", type=int, default=10, help="candidates removed together per refit")
    args = parser.parse_args(argv)
    print("== 200 kt coaxial (Eq. 6.5) refit benchmark ==")
    model = data_set()
    refits(model)
    if args.reduction:
        reduction(model, args.batch)


if __name__ == "__main__":
    main()
