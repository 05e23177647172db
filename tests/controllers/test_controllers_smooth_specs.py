"""The DMO's NLP is assembled from the spec list: every boundary has one definition, in its spec."""
from dataclasses import replace

import numpy as np
import pytest

from controllers import DMOSettings, EMFDesign, PIDGains, default_specs, dmo, evaluate_specs, hover_roll_plant
from controllers.plants import second_order_actuator
from controllers.specs import spec_by_name
from controllers import metrics as m
from controllers.nlp import _Problem, _gain_scale, _gains
from controllers.smooth import (CrossoverMinimum, DisturbanceBandwidthFloor, DisturbancePeakLimit,
                                GainMarginPastCritical, NicholsEllipse, PhaseMarginBand, SmoothConstraintError,
                                spec_with_constraint)


@pytest.fixture(scope="module")
def design():
    return EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.1, 0.2), actuator=second_order_actuator())


def _stricter(specs, name, level1, level2):
    """A copy of spec ``name`` with other boundaries: its smooth constraint comes with it."""
    return replace(spec_by_name(specs, name), name=name + ".strict", level1=level1, level2=level2)


def test_nlp_constraints_come_from_the_spec_list(design):
    specs = default_specs(2.0, 0.9)
    kinds = [type(c) for c in _Problem([design], DMOSettings(), specs).constraints]
    # the PM band lies inside the Nichols ellipse (45 deg, 6 dB): implied, left out
    assert kinds == [NicholsEllipse, GainMarginPastCritical, DisturbanceBandwidthFloor, DisturbancePeakLimit,
                     CrossoverMinimum]
    # without the Nichols spec the phase-margin spec enforces its own boundary
    no_nichols = [s for s in specs if s.name != "NicMgG1"]
    assert PhaseMarginBand in [type(c) for c in _Problem([design], DMOSettings(), no_nichols).constraints]
    # a stricter phase margin is not implied by the 45 deg ellipse: it enters the NLP
    strict = specs + [_stricter(specs, "StbMgG1.PM", 50.0, 40.0)]
    assert [type(c) for c in _Problem([design], DMOSettings(), strict).constraints].count(PhaseMarginBand) == 1
    # the settings carry no boundary numbers
    assert not any(hasattr(DMOSettings(), a) for a in ("gm_db", "pm_deg", "drp_db"))
    # the roles the DMO raises are found by constraint, not by name
    assert spec_with_constraint(specs, CrossoverMinimum).level1 == 2.0
    assert spec_with_constraint(specs, DisturbanceBandwidthFloor).level1 == 0.9
    with pytest.raises(SmoothConstraintError, match="CrossoverMinimum"):
        spec_with_constraint(no_nichols[:3], CrossoverMinimum)


def test_nichols_spec_metric_and_constraint_share_one_ellipse():
    nic = spec_by_name(default_specs(), "NicMgG1")
    assert nic.smooth == NicholsEllipse(45.0, 6.0)
    wider = replace(nic, smooth=NicholsEllipse(60.0, 6.0))
    assert wider.smooth != nic.smooth
    with pytest.raises(TypeError, match="SmoothConstraint"):
        replace(nic, smooth="ellipse")


def test_a_spec_added_to_the_list_enters_the_nlp_with_its_own_boundary(design):
    # the default NLP's solution meets every default smooth constraint; with a 47 deg
    # phase-margin spec added to the list (no other change) the same gains violate
    # the NLP's constraints, and they meet a 44 deg one (implied: left out)
    wc, settings = 2.0, DMOSettings()
    base = default_specs(wc, 0.9)
    scale = _gain_scale([design], wc)
    problem = _Problem([design], settings, base)
    x, slack, status = problem.solve(np.array([1.0, 0.2, 0.1]), base, wc, 0.5, scale)
    assert status == "Solve_Succeeded" and slack < 1e-5
    d = design.with_gains(PIDGains(*[float(v) for v in _gains(x, scale, wc, False)]))
    assert 45.0 <= m.gain_phase_margins(d.broken_loop())[1] < 47.0
    assert problem.constraint_values(x, base, wc, 0.5, scale).min() > -1e-5
    strict = base + [_stricter(base, "StbMgG1.PM", 47.0, 40.0)]
    assert problem.constraint_values(x, strict, wc, 0.5, scale).min() < -1e-3
    loose = base + [_stricter(base, "StbMgG1.PM", 44.0, 40.0)]
    assert problem.constraint_values(x, loose, wc, 0.5, scale).size == problem.constraint_values(
        x, base, wc, 0.5, scale).size


@pytest.mark.slow
def test_dmo_meets_a_stricter_phase_margin_added_only_to_the_spec_list(design):
    # local stage only (global_samples=0) to keep the test short; same settings for both runs
    settings = DMOSettings(global_samples=0)
    pm = lambda d: m.gain_phase_margins(d.broken_loop())[1]
    default = dmo(design, settings=settings, progress=False)
    # the stricter boundary is set 3 deg above the default answer's phase margin (not at a fixed 47 deg,
    # 0.8 deg above it here): that answer's margin is no spec's boundary, so it moves with the optimiser's
    # path; built this way the default answer fails the added spec whatever the path
    level1 = pm(default.design) + 3.0

    def strict_specs(wc, wd):
        return default_specs(wc, wd) + [_stricter(default_specs(wc, wd), "StbMgG1.PM", level1, 40.0)]

    graded = evaluate_specs(default.design, strict_specs(default.crossover_boundary, default.drb_boundary))
    row = graded.set_index("spec").loc["StbMgG1.PM.strict"]
    assert not row.met and row.value <= level1 - 3.0 + 1e-9, (
        f"premise: the default answer must fail the added {level1:.2f} deg phase margin by 3 deg; "
        f"graded {row.value:.3f} deg")
    strict = dmo(design, strict_specs, settings=settings, progress=False)
    assert pm(strict.design) >= level1                     # the answer with the spec added meets it
    assert strict.crossover < default.crossover            # ... at a price in crossover (5 % here)
    table = strict.specs
    assert "StbMgG1.PM.strict" in set(table.spec) and table[table.kind != "objective"].met.all()
    final = default_specs(strict.crossover_boundary, strict.drb_boundary)
    assert evaluate_specs(strict.design, final).query("kind != 'objective'").met.all()
