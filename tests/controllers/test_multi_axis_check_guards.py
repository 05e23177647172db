"""The global check of a guarded multi-axis design grades the guards the design was tuned against.

The plant is the roll/pitch pair of ``test_multi_axis_guard.py``: roll p/delta_lat = 4/(s+1),
pitch q/delta_lon = -4/(s+2), attitudes the integrals, each stick driving the other axis's rate
with ``coupling``. Coupling 2: roll tuned to its own highest crossover takes the pitch loop's
margins below Level 1, so a design with Level 1 guards stops roll lower than its own specs allow.
"""
import time
from dataclasses import replace

import numpy as np
import pytest

from controllers import DMOSettings, PIDGains, design_multi_axis
from controllers.multi_axis_check import global_check
from controllers.multi_axis_design import axis_specs
from controllers.multi_axis_result import MultiAxisResult
from controllers.multi_axis_guard import GUARD_TOLERANCE, GUARDED_SPECS
from controllers.specs import evaluate_specs

from .test_multi_axis_guard import _plant

# every test here shares a fixture that takes seconds to build: not in the quick set (make test-quick)
pytestmark = pytest.mark.slow

#: starting gains near the DMO's answer and a boundary raise from just below it: the DMO starts
#: feasible and needs a few steps (7 s instead of 20 s from the default start); no ray sampling
START = {"pitch": PIDGains(4.0, 0.0, 3.0), "roll": PIDGains(3.0, 0.1, 1.0)}
QUICK = DMOSettings(global_samples=0, polish_evaluations=5)
#: a small differential evolution (5 generations of 4 x 3 candidates, then the compass polish)
SEARCH = {"maxiter": 5, "popsize": 4}


@pytest.fixture(scope="module")
def guarded():
    res = design_multi_axis(_plant(2.0), axes=["pitch", "roll"], settings=QUICK, start_gains=START,
                            crossover_start={"pitch": 11.0, "roll": 6.0}, max_sweeps=1, progress=False,
                            guard_other_axes=True, guard_level=1, limits=None)
    t0 = time.perf_counter()
    free = global_check(res, guards=False, **SEARCH)
    t1 = time.perf_counter()
    held = global_check(res, **SEARCH)                 # None: as designed, i.e. guarded
    t2 = time.perf_counter()
    print(f"global_check wall time: unguarded {t1 - t0:.2f} s, guarded {t2 - t1:.2f} s")
    return res, free, held


def _pitch_margins_met(res, roll_gains):
    # the pitch loop's own Level 1 margin specs, graded on the whole two-loop aircraft with the roll gains
    # given: the metrics' default grid and the design's spec objects, not the guards' machinery
    view = res.emf.with_gains({"roll": roll_gains}).axis_view("pitch")
    table = evaluate_specs(view, axis_specs("pitch")).set_index("spec")
    return table.loc[list(GUARDED_SPECS), "met"].astype(bool)


def _search_gains(row):
    return PIDGains(row.search_K_phi, row.search_K_Iphi, row.search_K_p)


def test_result_records_how_it_was_designed(guarded):
    res = guarded[0]
    assert res.guard_other_axes is True and res.guard_level == 1
    # pitch was tuned first with roll still open (one sweep): no loop to guard; roll with pitch closed
    assert res.tuned_with == {"pitch": (), "roll": ("pitch",)}
    assert res.tuned_from == START
    # a result built without them (older code) reads as an unguarded design
    old = MultiAxisResult(res.emf, res.designs, res.dmo_results, res.specs, res.spec_lists, res.history,
                          res.converged, res.messages, res.wall_time)
    assert old.guard_other_axes is False and old.guard_level == "auto" and old.tuned_from == {}


def test_unguarded_search_beats_the_guarded_design_by_taking_the_pitch_margins(guarded):
    res, free, _ = guarded
    row = free.loc["roll"]
    assert not row.guarded and row.guard_specs == 0
    assert row.beaten                                  # 8.9 vs 7.4 rad/s
    assert not _pitch_margins_met(res, _search_gains(row)).all()
    # the DMO's roll gains keep the pitch loop's Level 1 margins: what its guards asked
    assert _pitch_margins_met(res, res.emf.loops["roll"].gains).all()


def test_guarded_search_does_not_beat_the_guarded_design_and_keeps_the_margins(guarded):
    res, free, held = guarded
    row = held.loc["roll"]
    assert row.guarded and row.guard_specs == len(GUARDED_SPECS) and row.dmo_guards_met
    assert not row.beaten
    assert row.search_crossover < free.loc["roll", "search_crossover"]
    assert _pitch_margins_met(res, _search_gains(row)).all()
    # pitch was tuned with no other loop closed: nothing to guard, the same search as unguarded
    assert held.loc["pitch", "guard_specs"] == 0
    assert held.loc["pitch", "search_crossover"] == free.loc["pitch", "search_crossover"]


def test_guards_cannot_bind_on_a_decoupled_plant():
    # no coupling: the pitch loop's margins do not depend on the roll gains, so the guards on it are
    # constants above their boundaries and the two searches score the same feasible set
    quick = DMOSettings(global_samples=0, max_steps=1, polish_evaluations=0)
    res = design_multi_axis(_plant(0.0), axes=["pitch", "roll"], settings=quick, start_gains=START,
                            crossover_start={"pitch": 6.0, "roll": 6.0}, max_sweeps=1, progress=False,
                            guard_other_axes=True, guard_level=1, limits=None)
    # the pitch loop flown at its hand-picked START gains, not the DMO's: the DMO's pitch design sits on
    # its Nichols boundary (5e-4 above it, under the guard's 1e-3 tolerance), so that guard's floor would
    # be the value now, met with no margin, and a last-bit difference between candidates would split
    # the two searches
    pitch = START["pitch"]
    res = replace(res, emf=res.emf.with_gains({"pitch": pitch}),
                  designs={**res.designs, "pitch": res.designs["pitch"].with_gains(pitch)})
    specs = {s.name: s for s in res.spec_lists["pitch"]}
    table = evaluate_specs(res.emf.axis_view("pitch"), [specs[n] for n in GUARDED_SPECS]).set_index("spec")
    for name in GUARDED_SPECS:
        # a guard's boundary is then Level 1 + its tolerance, met by 10 tolerances or more (each
        # tolerance is already 10x the guard grid's error): far from round-off
        floor = specs[name].level1 + GUARD_TOLERANCE[name]
        assert table.loc[name, "value"] >= floor + 10 * GUARD_TOLERANCE[name], (
            f"premise: the hand-picked pitch loop must keep {name} clear of its guard boundary {floor:g}; "
            f"it has {table.loc[name, 'value']:.4g}")
    on = global_check(res, guards=True, maxiter=3, popsize=3)
    off = global_check(res, guards=False, maxiter=3, popsize=3)
    assert on.loc["roll", "guard_specs"] == len(GUARDED_SPECS) and off.loc["roll", "guard_specs"] == 0
    assert np.isfinite(on.loc["roll", "search_crossover"])
    # the same seed and the same feasible set: the same points, to the last bit
    assert on.loc["roll", "search_crossover"] == off.loc["roll", "search_crossover"]
    assert on.loc["roll", "feasible_points"] == off.loc["roll", "feasible_points"]


def test_guards_argument_is_checked(guarded):
    with pytest.raises(ValueError, match="guards"):
        global_check(guarded[0], guards="yes", **SEARCH)
