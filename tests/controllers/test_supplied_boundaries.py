"""Boundaries supplied by the caller: a spec whose values the library lacks becomes gradable.

Independent truths: the integrator-plus-delay closed form of bandwidth and phase
delay (w_BW = pi/(4 tau), tau_p = tau/2 for an attitude response), the sloped
chart edge evaluated by hand, the normalised-margin formula of a scalar spec
written out here, and the DMO's answer read back with python-control margins.
The numbers supplied are illustrative, not ADS-33E-PRF's.
"""
import json

import control
import numpy as np
import pytest

from controllers import DMOSettings, EMFDesign, PIDGains, design_multi_axis, hover_roll_plant, specs_for
from controllers import metrics as m
from controllers.hq import BoundaryNotPublishedError
from controllers.hq.charts import spec_chart
from controllers.hq.forward_flight import forward_flight_specs
from controllers.hq.generic import generic_specs
from controllers.multi_axis_design import axis_specs
from controllers.plants import second_order_actuator

FAR = 100.0
#: a sloped Level 1 edge from (2 rad/s, 0.08 s) to (4 rad/s, 0.14 s); Level 2 a rectangle
PITCH_L1 = [(2.0, -1.0), (FAR, -1.0), (FAR, 0.14), (4.0, 0.14), (2.0, 0.08)]
PITCH_L2 = [(1.0, -1.0), (FAR, -1.0), (FAR, 0.25), (1.0, 0.25)]


def _one(specs, name):
    found = [s for s in specs if s.name == name]
    assert len(found) == 1, (name, [s.name for s in specs])
    return found[0]


def _pitch_bandwidth():
    return _one(specs_for("pitch", mte="all other", missing="keep", generic=False), "BnwAtH1.pitch")


def _sloped_edge(bw):
    return 0.08 + (bw - 2.0) / 2.0 * 0.06


@pytest.mark.parametrize("tau, level", [(0.2, 1), (0.3, 2), (0.6, 3)])
def test_a_supplied_sloped_chart_grades_a_closed_form_point(tau, level):
    spec = _pitch_bandwidth()
    with pytest.raises(BoundaryNotPublishedError):
        spec.evaluate(lambda s: np.exp(-tau * s) / s)
    mine = spec.with_boundaries(PITCH_L1, PITCH_L2, source="test chart")
    bw, tau_p = np.pi / (4 * tau), tau / 2            # closed form of e^{-tau s}/s
    # by hand: tau = 0.2 lies below the sloped edge (a rectangle at its left corner, 0.08 s,
    # would call it Level 2), tau = 0.3 above it inside Level 2, tau = 0.6 left of Level 2
    hand = 1 if (bw >= 2.0 and tau_p <= _sloped_edge(min(bw, 4.0))) else 2 if (bw >= 1.0 and tau_p <= 0.25) else 3
    assert hand == level
    got = mine.evaluate(lambda s: np.exp(-tau * s) / s)
    # the metric's grid interpolation is ~1e-6 relative (see test_hq_specs' closed-form test)
    assert got["value"] == pytest.approx(bw, rel=1e-5) and got["phase_delay"] == pytest.approx(tau_p, rel=1e-5)
    assert got["level"] == level
    assert {1: got["margin"] >= 0, 2: -1 < got["margin"] < 0, 3: got["margin"] < -1}[level]
    assert mine.status == "supplied" and mine.available and mine.source.startswith("test chart (supplied;")
    assert mine.regions.x_label == "bandwidth w_BW [rad/s]" and mine.regions.scale == (1.0, 0.1)
    assert spec.status == "not found" and spec.regions is None      # the library's entry is untouched


def test_a_supplied_scalar_spec_grades_by_the_margin_formula():
    design = EMFDesign(hover_roll_plant(), PIDGains(0.3, 0.1, 0.2), actuator=second_order_actuator())
    drb = _one(generic_specs(), "DrbPiH1")
    v = drb.value(design)
    assert np.isfinite(v) and v > 0
    for l1, l2, level in ((0.9 * v, 0.5 * v, 1), (1.1 * v, 0.9 * v, 2), (1.3 * v, 1.1 * v, 3)):
        got = drb.with_boundaries(l1, l2, source="test").evaluate(design)
        assert got["level"] == level
        assert got["margin"] == pytest.approx((v - l1) / (l1 - l2), rel=1e-12)
    only_l1 = drb.with_boundaries(1.1 * v, source="test")             # Level 2 unknown
    assert only_l1.boundary_text().endswith("L2 not found printed")
    assert np.isnan(only_l1.evaluate(design)["level"])
    assert drb.with_boundaries(0.5 * v, source="test").evaluate(design)["level"] == 1
    # a "max" spec: Level 1 is the lower number
    drp = _one(generic_specs(), "DrpAvH1").with_boundaries(4.0, 6.0, source="test")
    assert drp.boundary_text() == "L1 <= 4 dB; L2 <= 6 dB"


def test_supplied_mode_bounds_grade_a_pole_pair():
    ldo = _one(forward_flight_specs(), "LatDirOscF.ADS-33")
    mine = ldo.with_boundaries({"zeta": (0.2, 0.05), "wn": (0.5, 0.3)}, source="test")
    zeta, wn = 0.3, 1.0                                  # poles -zeta wn +- j wn sqrt(1 - zeta^2)
    p = complex(-zeta * wn, wn * np.sqrt(1 - zeta ** 2))
    got = mine.evaluate([p, p.conjugate()])
    assert got["level"] == 1
    assert got["margin"] == pytest.approx(min((zeta - 0.2) / 0.15, (wn - 0.5) / 0.2), rel=1e-9)
    assert mine.boundary_text() == "zeta: L1 >= 0.2, L2 >= 0.05; w_n [rad/s]: L1 >= 0.5, L2 >= 0.3"


@pytest.mark.parametrize("call, match", [
    (lambda s: s.with_boundaries(1.0, 0.5, source=""), "need a source"),
    (lambda s: s.with_boundaries(0.5, 1.0, source="x"), "level1 must be at least level2"),
    (lambda s: s.with_boundaries(np.inf, 0.5, source="x"), "must be finite"),
    (lambda s: s.with_boundaries(True, 0.5, source="x"), "must be a number"),
    (lambda s: s.with_boundaries(np.nan, source="x"), "level1 must be a finite number"),
    (lambda s: s.with_boundaries(1.0, np.nan, level3=0.2, source="x"), "level3 given without level2"),
])
def test_bad_scalar_boundaries_are_refused(call, match):
    with pytest.raises(ValueError, match=match):
        call(_one(generic_specs(), "DrbPiH1"))


def test_bad_charts_mode_bounds_and_specs_without_boundaries_are_refused():
    spec = _pitch_bandwidth()
    with pytest.raises(ValueError, match="outside the Level 2 region"):
        spec.with_boundaries(PITCH_L2, PITCH_L1, source="x")           # swapped: Level 1 not inside Level 2
    with pytest.raises(ValueError, match="at least 3"):
        spec.with_boundaries([(1, 1), (2, 2)], PITCH_L2, source="x")
    ldo = _one(forward_flight_specs(), "LatDirOscF.ADS-33")
    with pytest.raises(ValueError, match="bad limit"):
        ldo.with_boundaries({"zeta": (0.05, 0.2)}, source="x")
    with pytest.raises(ValueError, match="bad limit"):
        ldo.with_boundaries({"damping": (0.2, 0.05)}, source="x")
    with pytest.raises(ValueError, match="non-empty mapping"):
        ldo.with_boundaries({}, source="x")
    with pytest.raises(ValueError, match="an objective"):
        _one(generic_specs(), "ModFoG2").with_boundaries(1.0, 2.0, source="x")


def test_specs_for_takes_boundaries_by_name_and_refuses_unknown_ones():
    with pytest.raises(BoundaryNotPublishedError, match="DrbPiH1"):
        specs_for("pitch", mte="all other")
    mine = {"DrbPiH1": {"level1": 0.5, "level2": 0.25, "source": "programme requirement"},
            "BnwAtH1.pitch": {"level1": PITCH_L1, "level2": PITCH_L2, "source": "test chart"},
            "DrbYaH1": {"level1": 0.4, "source": "programme requirement"}}       # another axis's: ignored here
    mine = json.loads(json.dumps(mine))                                         # a JSON file serves
    # the pitch specs still missing are named; the supplied ones no longer are
    with pytest.raises(BoundaryNotPublishedError) as err:
        specs_for("pitch", mte="all other", boundaries=mine)
    assert "DrbPiH1" not in str(err.value) and "BnwAtH1.pitch" not in str(err.value)
    assert "QikAtH1.pitch" in str(err.value)
    got = {s.name: s for s in specs_for("pitch", mte="all other", missing="skip", boundaries=mine)}
    assert got["DrbPiH1"].status == got["BnwAtH1.pitch"].status == "supplied" and "DrbYaH1" not in got
    assert got["DrbPiH1"].level1 == 0.5
    with pytest.raises(ValueError, match=r"no spec named 'BnwAtH1.pich'.*did you mean \['BnwAtH1.pitch'"):
        specs_for("pitch", boundaries={"BnwAtH1.pich": {"level1": 1.0, "source": "x"}})
    with pytest.raises(ValueError, match=r"\(chart polygons\): keys must be among"):
        specs_for("pitch", missing="skip", boundaries={"BnwAtH1.pitch": {"level1": PITCH_L1, "source": "x"}})
    with pytest.raises(ValueError, match=r"\(scalar\): keys must be among"):
        specs_for("pitch", missing="skip", boundaries={"DrbPiH1": {"level1": 1.0, "src": "x"}})
    with pytest.raises(TypeError, match="must be a mapping"):
        specs_for("pitch", missing="skip", boundaries=[("DrbPiH1", 1.0)])


def test_the_multi_axis_design_refuses_boundaries_it_cannot_honour():
    for name in ("CrsMnG2", "DrbRoH1"):
        with pytest.raises(ValueError, match="design parameters"):
            axis_specs("roll", boundaries={name: {"level1": 1.0, "source": "x"}})
    quick = {"QikAtH1.roll": {"level1": [(1, 5), (4, 5), (4, 60), (1, 60)],
                              "level2": [(0.5, 5), (4, 5), (4, 60), (0.5, 60)], "source": "x"}}
    with pytest.raises(ValueError, match="time histories"):
        axis_specs("roll", boundaries=quick)
    plant = control.ss([[-1.5, 0], [1.0, 0]], [[5.0], [0]], [[1.0, 0], [0, 1.0]], 0,
                       inputs=["delta_lat"], outputs=["p", "phi"])
    with pytest.raises(ValueError, match="time histories"):       # refused before any design work
        design_multi_axis(plant, axes=["roll"], boundaries=quick, progress=False)


@pytest.mark.slow
def test_the_multi_axis_dmo_honours_a_supplied_boundary():
    # the same design without and with a stricter phase margin supplied by name (no other edit);
    # local DMO stage and one sweep to keep the test short (about 30 s together)
    plant = control.ss([[-1.5, 0], [1.0, 0]], [[5.0], [0]], [[1.0, 0], [0, 1.0]], 0,
                       inputs=["delta_lat"], outputs=["p", "phi"])
    kw = dict(axes=["roll"], settings=DMOSettings(global_samples=0), progress=False, max_sweeps=1)
    pm = lambda res: m.gain_phase_margins(res.emf.axis_view("roll").broken_loop())[1]
    plain = design_multi_axis(plant, **kw)
    mine = {"StbMgG1.PM": {"level1": 60.0, "level2": 45.0, "source": "a stricter programme requirement"}}
    strict = design_multi_axis(plant, boundaries=mine, **kw)
    assert pm(plain) < 60.0                                    # the library's 45 deg design does not meet it
    assert pm(strict) >= 60.0                                  # the design given the boundary does
    table = strict.specs["roll"]
    assert table[table.kind != "objective"].met.all()
    assert _one(strict.spec_lists["roll"], "StbMgG1.PM").status == "supplied" and strict.boundaries == mine


def test_a_supplied_chart_is_drawn_with_its_source():
    mine = _pitch_bandwidth().with_boundaries(PITCH_L1, PITCH_L2, source="test chart")
    ax = spec_chart(mine, design=lambda s: np.exp(-0.2 * s) / s)
    assert len(ax.patches) == 3                                # Level 3 background, Level 2, Level 1
    assert "source [supplied]: test chart" in ax.get_title(loc="left")
    assert ax.lines[0].get_xydata()[0] == pytest.approx([np.pi / 0.8, 0.1], rel=1e-5)
