"""The joint check of a multi-axis design: every axis's gains searched at once, every loop graded.

The plant is the hand-built roll/pitch pair of ``_plants.py`` without
cross-coupling (roll p/delta_lat = 5/(s+1.5), pitch q/delta_lon = -4/(s+1),
phi = int p, theta = int q): each axis's loop is then its own single-axis loop,
so the best joint design is the pair of single-axis optima, which the DMO (with
its multistart stage) reaches within its bisection tolerance. A joint search can
therefore not beat the DMO's design by more than that tolerance, and must beat a
detuned design (hand-picked gains that meet every spec with a clear margin and cross
at about half the optimum); its local stage must climb that design back to the optimum.
The detuned design is built by hand, not from the DMO's gains: halving an optimiser's
answer keeps every spec met only if the answer has no round-off residue (a 1e-13
integral gain leaves a pole at +-1e-13 1/s, and its sign then varies between machines).
"""
from dataclasses import replace

import control
import numpy as np
import pytest
from matplotlib.figure import Figure

from controllers import DMOSettings, PIDGains, design_multi_axis, evaluate_specs
from controllers.metrics import crossover_frequency
from controllers.multi_axis import AxisLoop, MultiAxisEMF
from controllers.multi_axis_design import AxisEMFDesign, axis_specs
from controllers.multi_axis_joint import JointCheckResult, _FeedbackModes, joint_check
from controllers.plants import first_order_actuator

from tests.controllers._plants import roll_pitch

# every test here shares a fixture that takes seconds to build: not in the quick set (make test-quick)
pytestmark = pytest.mark.slow

#: the DMO's bisection tolerance here: the design's crossovers are within this fraction of each axis's optimum
DMO_TOLERANCE = 0.05
#: small DMO settings with the multistart stage: without it the DMO stops short of the pitch optimum here
FAST = DMOSettings(global_samples=8, max_steps=8, tolerance=DMO_TOLERANCE, polish_evaluations=0, growth=2.0,
                   multistart=16)
#: a small search: the tests check the verdicts, not the search's resolution
BUDGET = {"maxiter": 2, "popsize": 2}
#: the detuned design: proportional attitude and rate gains only, crossing at about 11.6 (roll) and
#: 9.5 rad/s (pitch), half of what the DMO reaches; every spec met with a normalised margin of 0.054
#: (the slowest closed-loop pole, EigLcG1), far from any round-off
DETUNED = {"roll": PIDGains(0.15, 0.0, 2.5), "pitch": PIDGains(0.2, 0.0, 2.5)}
#: the smallest normalised design margin the detuned design must keep for the tests to mean anything
#: (CONDUIT's margin: 0 on the Level 1 boundary; 0.02 is 1e11 times the round-off of the poles here)
PREMISE_MARGIN = 0.02


@pytest.fixture(scope="module")
def designed():
    # decoupled: a second sweep would find every effective plant unchanged, so one is enough
    return design_multi_axis(roll_pitch(), axes=["roll", "pitch"], settings=FAST, progress=False, max_sweeps=1,
                             actuator=first_order_actuator(30.0), crossover_start={"roll": 2.5, "pitch": 2.5})


def _regraded(result, gains):
    """Every axis of ``result`` with ``gains``, graded from scratch: (all specs met, crossovers)."""
    emf = result.emf.with_gains(gains)
    met, wc = True, {}
    for a in emf.axes:
        t = evaluate_specs(emf.axis_view(a), result.spec_lists[a])
        t = t[(t.kind != "objective") & (t.spec != "CrsMnG2")]
        met = met and bool(t.met.all())
        wc[a] = crossover_frequency(emf.axis_view(a).broken_loop())
    return met, wc


def _detuned(designed, spec_lists=None):
    """``designed`` flown with the hand-picked :data:`DETUNED` gains (and ``spec_lists`` if given), after
    checking the premise: every spec met with at least :data:`PREMISE_MARGIN` on every axis."""
    detuned = replace(designed, emf=designed.emf.with_gains(DETUNED),
                      spec_lists=spec_lists if spec_lists is not None else designed.spec_lists)
    for a in detuned.emf.axes:
        t = evaluate_specs(detuned.emf.axis_view(a), detuned.spec_lists[a])
        t = t[(t.kind != "objective") & (t.spec != "CrsMnG2")]
        worst = t.loc[t.margin.astype(float).idxmin()]
        assert worst.margin >= PREMISE_MARGIN, (
            f"premise: the detuned {a} design must meet every spec with margin >= {PREMISE_MARGIN}; "
            f"{worst.spec} has {worst.margin:.3g}")
    return detuned


def test_a_decoupled_dmo_design_is_not_dominated(designed):
    check = joint_check(designed, tolerance=DMO_TOLERANCE, **BUDGET)
    assert isinstance(check, JointCheckResult)
    assert check.axes.dmo_feasible.all() and not check.dominated
    # the design's own gains are in the first generation (its zero integral gain searched as zero): the
    # best feasible point crosses at least as high (1e-12: the same loop graded twice)
    assert check.min_ratio >= 1.0 - 1e-12
    # the best candidate, graded again from scratch (exact closed-loop poles), meets every spec and crosses
    # where the check says (1e-9: the same crossover computation on the same loop)
    best = {a: PIDGains(*check.axes.loc[a, ["joint_K_phi", "joint_K_Iphi", "joint_K_p"]].astype(float))
            for a in check.axes.index}
    met, wc = _regraded(designed, best)
    assert met
    for a in check.axes.index:
        assert wc[a] == pytest.approx(check.axes.loc[a, "joint_crossover"], rel=1e-9)
    table = check.to_pandas()
    assert table.columns[:3].tolist() == ["dmo_crossover", "joint_crossover", "ratio"]
    assert (table.points == check.evaluations).all() and check.evaluations == len(check.points)
    assert 1 <= check.feasible_evaluations <= check.evaluations


def test_a_detuned_design_is_dominated(designed):
    # graded by specs at fixed boundaries (the axes' starting crossover, the roll DRB's 0.9 rad/s), not
    # at those the DMO raised: the premise then owes nothing to the optimiser
    fixed = {a: axis_specs(a, crossover_min=2.5, drb_min=0.9) for a in designed.emf.axes}
    detuned = _detuned(designed, fixed)
    met, wc = _regraded(detuned, {})
    assert met
    check = joint_check(detuned, **BUDGET)
    assert check.dominated and check.min_ratio > 1.01
    best = {a: PIDGains(*check.axes.loc[a, ["joint_K_phi", "joint_K_Iphi", "joint_K_p"]].astype(float))
            for a in check.axes.index}
    met, found = _regraded(detuned, best)
    assert met
    for a in detuned.emf.axes:
        # the same loop graded twice
        assert check.axes.loc[a, "dmo_crossover"] == pytest.approx(wc[a], rel=1e-12)
        assert found[a] > wc[a]
    assert isinstance(check.plot(), Figure)


def test_affine_feedback_modes_equal_the_exact_interconnection():
    # a coupled pair: the feedback system's state matrix mixes both axes' gains
    act = first_order_actuator(30.0)
    roll = AxisEMFDesign(control.ss(control.tf([5.0], [1, 1.5]), inputs="delta_lat", outputs="p"),
                         PIDGains(0.3, 0.1, 0.05), axis="roll", actuator=act)
    pitch = AxisEMFDesign(control.ss(control.tf([4.0], [1, 1.0]), inputs="delta_lon", outputs="-q"),
                          PIDGains(0.4, 0.0, 0.08), axis="pitch", actuator=act)
    emf = MultiAxisEMF(roll_pitch(0.5), {"roll": AxisLoop.from_design(roll), "pitch": AxisLoop.from_design(pitch)})
    emf.closed_loop()      # as a heave spec's grading would: the affine closed loop is then built too
    modes = _FeedbackModes(emf, ["roll", "pitch"])
    assert modes.ok
    # every gain non-zero, then a zero integral gain (one state fewer) and a zero rate gain
    for g in ([0.7, 0.2, 0.1, 1.3, 0.05, 0.3], [0.7, 0.0, 0.1, 1.3, 0.05, 0.0]):
        exact = np.sort_complex(emf.with_gains(modes._gains(np.array(g))).feedback_poles())
        fast = np.sort_complex(np.linalg.eigvals(modes.matrix(g)))
        # round-off of the affine sum and of two eigenvalue solves of a matrix of norm ~1e2
        np.testing.assert_allclose(fast, exact, atol=1e-9)
        # the whole closed loop (pilot path included), compared where state order cannot matter
        assert modes.closed.ok
        cl = emf.with_gains(modes._gains(np.array(g))).closed_loop()
        rebuilt = control.ss(*modes.closed.matrices(g))
        s = 1j * np.array([0.3, 3.0, 30.0])
        # round-off of the affine sum, relative to responses of order one
        np.testing.assert_allclose(rebuilt(s), cl(s), rtol=1e-8, atol=1e-10)


def test_the_local_stage_climbs_a_detuned_design_to_the_optimum_and_no_further(designed):
    # the joint NLP maximises the smallest crossover ratio over the axes (candidate over design): from
    # the detuned design it must raise that ratio to the smallest any feasible gains allow, that of the
    # axis whose own optimum is nearest (each decoupled axis's optimum is the full design's crossover,
    # within the DMO's bisection tolerance), and no axis may cross above its own optimum
    detuned = _detuned(designed)
    _, start = _regraded(detuned, {})
    check = joint_check(detuned, local_evaluations=80, **BUDGET)
    assert 0 < check.local_evaluations <= 80
    assert set(check.points.stage) == {"global", "local"}
    best = {a: PIDGains(*check.axes.loc[a, ["joint_K_phi", "joint_K_Iphi", "joint_K_p"]].astype(float))
            for a in check.axes.index}
    met, found = _regraded(detuned, best)
    assert met
    full = {a: crossover_frequency(designed.emf.axis_view(a).broken_loop()) for a in detuned.emf.axes}
    reachable = min(full[a] / start[a] for a in full)
    assert reachable * (1 - DMO_TOLERANCE) <= check.local_min_ratio <= reachable * (1 + DMO_TOLERANCE)
    for a in detuned.emf.axes:
        assert start[a] < found[a] <= full[a] * (1 + DMO_TOLERANCE)
    # the local stage starts from the global stage's best point: it can only add to it
    global_best = check.points[(check.points.stage == "global") & check.points.feasible.astype(bool)].min_ratio.max()
    assert check.local_min_ratio >= global_best - 1e-12
    assert check.to_pandas().local_points.eq(check.local_evaluations).all()


def test_the_local_stage_does_not_dominate_the_dmo_design(designed):
    check = joint_check(designed, tolerance=DMO_TOLERANCE, local_evaluations=60, **BUDGET)
    assert not check.dominated and check.local_min_ratio <= 1.0 + DMO_TOLERANCE


@pytest.mark.parametrize("kwargs, name", [({"maxiter": 0}, "maxiter"), ({"popsize": 1.5}, "popsize"),
                                          ({"local_evaluations": -1}, "local_evaluations"),
                                          ({"local_evaluations": 2.0}, "local_evaluations"),
                                          ({"local_evaluations": 8}, "at least 9 for 2 axes"),
                                          ({"maxiter": True}, "maxiter"), ({"tolerance": -0.1}, "tolerance"),
                                          ({"tolerance": float("nan")}, "tolerance"), ({"decades": 0}, "decades")])
def test_bad_arguments_are_named(designed, kwargs, name):
    with pytest.raises(ValueError, match=name):
        joint_check(designed, **kwargs)


def test_result_must_be_a_multi_axis_result():
    with pytest.raises(TypeError, match="result"):
        joint_check({"roll": None})
