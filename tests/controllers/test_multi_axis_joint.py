"""The joint check of a multi-axis design: every axis's gains searched at once, every loop graded.

The plant is the hand-built roll/pitch pair of ``_plants.py`` without
cross-coupling (roll p/delta_lat = 5/(s+1.5), pitch q/delta_lon = -4/(s+1),
phi = int p, theta = int q): each axis's loop is then its own single-axis loop,
so the best joint design is the pair of single-axis optima, which the DMO (with
its multistart stage) reaches within its bisection tolerance. A joint search can
therefore not beat the DMO's design by more than that tolerance, and must beat a
design whose gains are all halved (still meeting every spec, crossing lower); its
local stage (the joint NLP) must climb that halved design back to the optimum.
"""
from dataclasses import replace

import control
import numpy as np
import pytest
from matplotlib.figure import Figure

from controllers import DMOSettings, PIDGains, design_multi_axis, evaluate_specs
from controllers.metrics import crossover_frequency
from controllers.multi_axis import AxisLoop, MultiAxisEMF
from controllers.multi_axis_design import AxisEMFDesign
from controllers.multi_axis_joint import JointCheckResult, _FeedbackModes, joint_check
from controllers.plants import first_order_actuator

from tests.controllers._plants import roll_pitch

#: the DMO's bisection tolerance here: the design's crossovers are within this fraction of each axis's optimum
DMO_TOLERANCE = 0.05
#: small DMO settings with the multistart stage: without it the DMO stops short of the pitch optimum here
FAST = DMOSettings(global_samples=8, max_steps=8, tolerance=DMO_TOLERANCE, polish_evaluations=0, growth=2.0,
                   multistart=16)
#: a small search: the tests check the verdicts, not the search's resolution
BUDGET = {"maxiter": 2, "popsize": 2}


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
    half = {a: PIDGains(*(0.5 * designed.emf.loops[a].gains.as_array())) for a in designed.emf.axes}
    detuned = replace(designed, emf=designed.emf.with_gains(half))
    met, wc = _regraded(detuned, {})
    assert met, "the halved gains must still meet every spec for the test to mean anything"
    check = joint_check(detuned, **BUDGET)
    assert check.dominated and check.min_ratio > 1.01
    best = {a: PIDGains(*check.axes.loc[a, ["joint_K_phi", "joint_K_Iphi", "joint_K_p"]].astype(float))
            for a in check.axes.index}
    met, found = _regraded(detuned, best)
    assert met
    for a in detuned.emf.axes:
        assert check.axes.loc[a, "dmo_crossover"] == pytest.approx(wc[a], rel=1e-12)
        # no feasible gains cross higher than the axis's own optimum, which the full design is within
        # the DMO's bisection tolerance of (decoupled axes)
        full = crossover_frequency(designed.emf.axis_view(a).broken_loop())
        assert wc[a] < found[a] <= full * (1 + DMO_TOLERANCE)
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
    # the halved design: the joint NLP from the global stage's best point must reach (within the DMO's
    # bisection tolerance) each decoupled axis's own optimum, which the full design is within that
    # tolerance of, and not beyond it (no feasible gains cross higher than the optimum)
    half = {a: PIDGains(*(0.5 * designed.emf.loops[a].gains.as_array())) for a in designed.emf.axes}
    detuned = replace(designed, emf=designed.emf.with_gains(half))
    check = joint_check(detuned, local_evaluations=80, **BUDGET)
    assert 0 < check.local_evaluations <= 80
    assert set(check.points.stage) == {"global", "local"}
    best = {a: PIDGains(*check.axes.loc[a, ["joint_K_phi", "joint_K_Iphi", "joint_K_p"]].astype(float))
            for a in check.axes.index}
    met, found = _regraded(detuned, best)
    assert met
    for a in detuned.emf.axes:
        full = crossover_frequency(designed.emf.axis_view(a).broken_loop())
        assert full * (1 - DMO_TOLERANCE) <= found[a] <= full * (1 + DMO_TOLERANCE)
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
