"""Guard specs: another closed loop's stability margins graded while one axis is tuned."""
import control
import numpy as np
import pytest

from controllers import PIDGains
from controllers import metrics as m
from controllers.multi_axis import AxisLoop
from controllers.multi_axis_design import AxisEMFDesign, _effective_plant, axis_specs
from controllers.multi_axis_guard import GUARD_OMEGA, GUARD_TOLERANCE, GUARDED_SPECS, guard_specs


def _plant(coupling):
    # roll and pitch rate/attitude pairs (stick forward pitches the nose down: q/delta_lon < 0);
    # ``coupling`` puts each stick into the other axis's rate
    A = np.array([[-1.0, 0, 0, 0], [1, 0, 0, 0], [0, 0, -2.0, 0], [0, 0, 1, 0]])
    B = np.array([[4.0, coupling], [0, 0], [coupling, -4.0], [0, 0]])
    return control.ss(A, B, np.eye(4), 0, inputs=["delta_lat", "delta_lon"], outputs=["p", "phi", "q", "theta"])


def _setup(coupling, roll_gains):
    plant = _plant(coupling)
    pitch = AxisEMFDesign(_effective_plant(plant, {}, "pitch", None), PIDGains(1.0, 0.1, 0.3), axis="pitch")
    loops = {"pitch": AxisLoop.from_design(pitch)}
    roll = AxisEMFDesign(_effective_plant(plant, loops, "roll", None), roll_gains, axis="roll")
    return plant, pitch, loops, roll


def test_decoupled_guard_is_the_other_axis_own_margins_whatever_the_tuned_gains():
    # no coupling: the pitch loop broken at its mixer input is the single-axis pitch loop, whatever roll does;
    # its single-axis design's margins are computed by another path (no MultiAxisEMF)
    plant, pitch, loops, roll = _setup(0.0, PIDGains(1.0, 0.1, 0.3))
    guards = {g.name: g for g in guard_specs(plant, loops, roll, {"pitch": axis_specs("pitch")})}
    assert sorted(guards) == sorted(f"{n}@pitch" for n in GUARDED_SPECS)
    gm, pm, _, _ = m.gain_phase_margins(pitch.broken_loop(), GUARD_OMEGA)
    nm = m.nichols_margin(pitch.broken_loop(), GUARD_OMEGA)
    for gains in (PIDGains(1.0, 0.1, 0.3), PIDGains(3.0, 0.0, 1.0)):
        cand = roll.with_gains(gains)
        # same loop, two routes to its frequency response: agreement to round-off of the grid interpolation
        assert guards["StbMgG1.GM@pitch"].metric(cand) == pytest.approx(abs(gm), abs=1e-6)
        assert guards["StbMgG1.PM@pitch"].metric(cand) == pytest.approx(pm, abs=1e-6)
        assert guards["NicMgG1@pitch"].metric(cand) == pytest.approx(nm, abs=1e-6)


def test_coupled_guard_moves_with_the_tuned_gains():
    plant, pitch, loops, roll = _setup(1.5, PIDGains(1.0, 0.1, 0.3))
    pm = {g.name: g for g in guard_specs(plant, loops, roll, {"pitch": axis_specs("pitch")})}["StbMgG1.PM@pitch"]
    a, b = pm.metric(roll), pm.metric(roll.with_gains(PIDGains(4.0, 0.0, 2.0)))
    assert abs(a - b) > 0.1          # deg: the roll loop changes what the pitch loop sees


@pytest.mark.parametrize("level", [1, 2])
def test_guard_boundary_is_the_level_or_what_the_other_axis_has_now(level):
    plant, pitch, loops, roll = _setup(1.5, PIDGains(1.0, 0.1, 0.3))
    specs = axis_specs("pitch")
    bound = {s.name: (s.level1 if level == 1 else s.level2) + GUARD_TOLERANCE[s.name] for s in specs
             if s.name in GUARD_TOLERANCE}
    for g in guard_specs(plant, loops, roll, {"pitch": specs}, level=level):
        now = g.metric(roll)
        assert g.level1 == g.level2 == pytest.approx(min(bound[g.name.split("@")[0]], now))
        assert g.kind == "hard"


def test_guard_refuses_the_tuned_axis_among_the_other_loops_and_a_bad_level():
    plant, pitch, loops, roll = _setup(0.0, PIDGains(1.0, 0.1, 0.3))
    with pytest.raises(ValueError, match="tuned axis"):
        guard_specs(plant, {**loops, "roll": AxisLoop.from_design(roll)}, roll, {"pitch": axis_specs("pitch")})
    with pytest.raises(ValueError, match="level"):
        guard_specs(plant, loops, roll, {"pitch": axis_specs("pitch")}, level=3)


def test_unlisted_axis_is_not_guarded():
    plant, pitch, loops, roll = _setup(0.0, PIDGains(1.0, 0.1, 0.3))
    assert guard_specs(plant, loops, roll, {}) == []


@pytest.mark.slow
@pytest.mark.parametrize("guard", [True, False])
def test_design_with_guards_keeps_the_first_axis_margins(guard):
    from controllers import DMOSettings, design_multi_axis
    # strong coupling: roll tuned to its own highest crossover takes the pitch loop's Nichols and phase
    # margins below Level 1 (unguarded); Level 1 guards stop the roll DMO where pitch would lose them
    res = design_multi_axis(_plant(2.0), axes=["pitch", "roll"], settings=DMOSettings(global_samples=8),
                            max_sweeps=1, progress=False, guard_other_axes=guard, guard_level=1, limits=None)
    assert res.dmo_results["pitch"] is not None and res.dmo_results["roll"] is not None
    met = res.specs["pitch"].set_index("spec").loc[["NicMgG1", "StbMgG1.GM", "StbMgG1.PM"], "met"]
    assert met.all() == guard            # graded on the final two-loop aircraft


@pytest.mark.parametrize("pitch_pole, level", [(-2.0, 2), (0.5, 1)])
def test_auto_level_keeps_level1_for_a_loop_around_an_unstable_plant(pitch_pole, level):
    # pitch rate pole at -2 1/s (stable plant: Level 2 kept) or +0.5 1/s (unstable: Level 1 kept); the
    # pitch gains leave a margin between the two boundaries (Nichols, resp. gain margin), so the two differ
    plant = _plant(0.5)
    A = np.array(plant.A)
    A[2, 2] = pitch_pole
    plant = control.ss(A, plant.B, plant.C, plant.D, inputs=plant.input_labels, outputs=plant.output_labels)
    pitch = AxisEMFDesign(_effective_plant(plant, {}, "pitch", None), PIDGains(2.0, 0.1, 0.6), axis="pitch")
    loops = {"pitch": AxisLoop.from_design(pitch)}
    roll = AxisEMFDesign(_effective_plant(plant, loops, "roll", None), PIDGains(1.0, 0.1, 0.3), axis="roll")
    specs = axis_specs("pitch")
    bound = {s.name: (s.level1 if level == 1 else s.level2) + GUARD_TOLERANCE[s.name] for s in specs
             if s.name in GUARD_TOLERANCE}
    other = {s.name: (s.level2 if level == 1 else s.level1) + GUARD_TOLERANCE[s.name] for s in specs
             if s.name in GUARD_TOLERANCE}
    guards = guard_specs(plant, loops, roll, {"pitch": specs})
    for g in guards:
        assert g.level1 == pytest.approx(min(bound[g.name.split("@")[0]], g.metric(roll)))
    # at least one guard's boundary tells the two levels apart
    assert any(g.level1 != pytest.approx(min(other[g.name.split("@")[0]], g.metric(roll))) for g in guards)
