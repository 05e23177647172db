"""Design space: spaced configurations, the result object on
stand-in identifications, and the scheduled (interpolated) inflow model.

The wake identification itself is exercised by the study's subprocess test
(tests/studies/test_studies_design_space.py); here everything runs in milliseconds to seconds.
"""
import inspect
import math
from types import SimpleNamespace

import control
import numpy as np
import pandas as pd
import pytest
from matplotlib.figure import Figure

from aircraft import coaxial_compound, uh60_single_rotor
from aircraft.helicopter import Helicopter, HelicopterSettings, trim
from aircraft.identification.structures import Coaxial6State
from aircraft.identification.design_space import DesignPoint, DesignSpaceError, spaced_config
from aircraft.identification import (DesignSpaceResult, IdentificationSettings, identify_design_space, identify_inflow)
from aircraft.identification.design_space import KEY_PARAMETERS
from aircraft.inflow import IdentifiedInflow, InflowError, ScheduledInflow
from aircraft.inflow.published import COAXIAL_HOVER_6STATE, in_rotor_frames

FAST = HelicopterSettings(n_span=6, n_average=1)   # hover is axisymmetric: one azimuth is exact
EQ53 = in_rotor_frames(COAXIAL_HOVER_6STATE)
OMEGA = COAXIAL_HOVER_6STATE.omega
SPACINGS = (0.10, 0.14, 0.20, 0.30)
CTS = (0.0075, 0.0096)
rng = np.random.default_rng(14)
# matrices linear in (h/R, C_T): base (Eq. 5.3 in our frames) + slopes. The slopes keep
# the sparsity of Eq. 5.3 and are small enough that every point of the grid stays stable.
MASK = {"M": EQ53.M != 0, "Lbar": EQ53.Lbar != 0, "tau": EQ53.tau != 0}
SLOPES = {k: (rng.normal(size=(6, 6)) * MASK[k] * scale_s, rng.normal(size=(6, 6)) * MASK[k] * scale_c)
          for k, scale_s, scale_c in (("M", 0.3, 8.0), ("Lbar", 0.05, 2.0), ("tau", 0.02, 1.0))}
BASE = {"M": EQ53.M, "Lbar": EQ53.Lbar, "tau": EQ53.tau}


def _linear(key, s, c):
    """The closed form the interpolation must reproduce: P0 + (s - 0.14) dP/ds + (c - 0.0096) dP/dC_T."""
    ds, dc = SLOPES[key]
    return BASE[key] + (s - 0.14) * ds + (c - 0.0096) * dc


def _refs(s, c):
    loads = np.array([c / 2, 0, 0, c / 2, 0, 0])
    lam = np.array([0.05, 0, 0, 0.07, 0, 0]) * (1 + s) * math.sqrt(c / 0.0096)
    return loads, lam


def _grid(fun_tau=_linear):
    shape = (len(SPACINGS), len(CTS))
    g = {k: np.zeros(shape + (6, 6)) for k in ("M", "Lbar", "tau")}
    g["loads_ref"], g["inflow_ref"] = np.zeros(shape + (6,)), np.zeros(shape + (6,))
    for i, s in enumerate(SPACINGS):
        for j, c in enumerate(CTS):
            for k in ("M", "Lbar"):
                g[k][i, j] = _linear(k, s, c)
            g["tau"][i, j] = fun_tau("tau", s, c)
            g["loads_ref"][i, j], g["inflow_ref"][i, j] = _refs(s, c)
    assert (g["tau"] >= 0).all()      # the slopes are small enough to keep the delays durations
    return g


def _schedule(spacing=0.14, ct=0.0096, **kw):
    return ScheduledInflow(SPACINGS, CTS, omega=OMEGA, spacing=spacing, ct=ct, **{**_grid(), **kw})


# -- spaced configurations ------------------------------------------------------------
def test_spaced_config_moves_only_the_lower_hub():
    base = coaxial_compound()
    for s in SPACINGS:
        cfg = spaced_config(base, s)
        up, lo = cfg.rotors
        assert (lo.hub_position[2] - up.hub_position[2]) / up.radius == pytest.approx(s, rel=1e-12)
        assert up == base.rotors[0] and lo.hub_position[:2] == base.rotors[1].hub_position[:2]
        assert lo.radius == base.rotors[1].radius and cfg.mass == base.mass
    # Table B.1's spacing: the very same configuration (its cached wake runs are reused)
    assert spaced_config(base, 0.14) is base
    assert "h/R 0.3" in spaced_config(base, 0.30).name


def test_spaced_config_refuses_bad_input():
    with pytest.raises(DesignSpaceError, match="coaxial"):
        spaced_config(uh60_single_rotor(), 0.2)
    for bad in (0.0, -0.1, float("nan"), "0.2", True):
        with pytest.raises(DesignSpaceError, match="spacing must be a positive number"):
            spaced_config(None, bad)


# -- the scheduled model --------------------------------------------------------------
@pytest.mark.parametrize("s, c", [(0.12, 0.0080), (0.27, 0.0090), (0.10, 0.0096), (0.30, 0.0075),
                                  (0.14, 0.0096), (0.2, 0.00855)])
def test_schedule_reproduces_matrices_linear_in_spacing_and_thrust(s, c):
    mats = _schedule().matrices(s, c)
    loads, _ = _refs(s, c)
    # bilinear interpolation is exact for functions linear in each variable: only
    # round-off (1e-12 of entries of order 1) separates it from the closed form
    for k in ("M", "Lbar", "tau"):
        np.testing.assert_allclose(mats[k], _linear(k, s, c), rtol=0, atol=1e-12)
    np.testing.assert_allclose(mats["loads_ref"], loads, rtol=0, atol=1e-15)


def test_scheduled_model_is_the_identified_model_of_the_interpolated_matrices():
    s, c = 0.17, 0.0088
    model = _schedule(s, c)
    direct = IdentifiedInflow.from_matrices(_linear("M", s, c), _linear("Lbar", s, c), _linear("tau", s, c),
                                            omega=OMEGA, rotors=("U", "L"), loads_ref=_refs(s, c)[0],
                                            inflow_ref=model.inflow_ref)
    # same realisation path (from_matrices, Padé 2, minreal): equal DC gains and poles
    g_model, g_direct = control.dcgain(model.system), control.dcgain(direct.system)
    # structural zeros come out as round-off (~1e-12 against gains of ~20): absolute
    # tolerance relative to the largest gain
    np.testing.assert_allclose(g_model, g_direct, rtol=1e-9, atol=1e-9 * np.abs(g_direct).max())
    np.testing.assert_allclose(np.sort_complex(model.system.poles()), np.sort_complex(direct.system.poles()),
                               rtol=1e-8)
    assert model.n_states == direct.n_states and model.input_names == direct.input_names
    # quasi-steady check independent of control: lambda = Lbar^-1 dC at s -> 0
    dloads = np.array([1e-4, 0, 0, 0, 0, 0])
    x = model.steady_state(model.loads_ref + dloads, None)
    lam = model.inflow(x, None, None) - model.inflow_ref
    np.testing.assert_allclose(lam, np.linalg.solve(_linear("Lbar", s, c), dloads), rtol=1e-8, atol=1e-14)


def test_schedule_is_not_linear_where_the_nodes_are_not():
    # a quadratic in spacing is reproduced at the nodes only: between them the
    # interpolation lies on the chord (the error of linear interpolation, exactly)
    quad = lambda k, s, c: BASE["tau"] + (s - 0.14) ** 2 * np.abs(SLOPES["tau"][0])   # noqa: E731
    g = _grid(fun_tau=quad)
    model = ScheduledInflow(SPACINGS, CTS, omega=OMEGA, spacing=0.14, ct=0.0096, **g)
    s = 0.25   # between 0.20 and 0.30: chord error (s - 0.2)(s - 0.3) * curvature
    chord = quad("tau", s, 0.0096) - (s - 0.20) * (s - 0.30) * np.abs(SLOPES["tau"][0])
    np.testing.assert_allclose(model.matrices(s, 0.0096)["tau"], chord, atol=1e-14)
    np.testing.assert_allclose(model.matrices(0.20, 0.0096)["tau"], quad("tau", 0.20, 0.0096), atol=1e-15)


def test_schedule_refuses_to_extrapolate():
    model = _schedule()
    with pytest.raises(InflowError, match=r"spacing = 0.35 R is outside the grid \[0.1, 0.3\]"):
        model.at(0.35, 0.0096)
    with pytest.raises(InflowError, match="ct = 0.0074 is outside the grid"):
        model.matrices(0.2, 0.0074)
    with pytest.raises(InflowError, match="does not extrapolate"):
        _schedule(spacing=0.05)
    # one thrust only: that thrust and no other
    g = {k: v[:, 1:] for k, v in _grid().items()}
    one = ScheduledInflow(SPACINGS, CTS[1:], omega=OMEGA, spacing=0.2, ct=0.0096, **g)
    assert one.ct == 0.0096
    with pytest.raises(InflowError, match="outside the grid node 0.0096"):
        one.at(0.2, 0.0095)


def test_schedule_refuses_bad_input():
    g = _grid()
    with pytest.raises(InflowError, match="strictly increasing"):
        ScheduledInflow((0.1, 0.1, 0.2, 0.3), CTS, omega=OMEGA, spacing=0.2, ct=0.009, **g)
    with pytest.raises(InflowError, match=r"M must have shape \(4, 2, 6, 6\)"):
        ScheduledInflow(SPACINGS, CTS, omega=OMEGA, spacing=0.2, ct=0.009, **{**g, "M": g["M"][:, :, :3, :3]})
    bad = g["Lbar"].copy()
    bad[1, 1, 0, 0] = np.nan
    with pytest.raises(InflowError, match="Lbar has non-finite entries"):
        ScheduledInflow(SPACINGS, CTS, omega=OMEGA, spacing=0.2, ct=0.009, **{**g, "Lbar": bad})
    with pytest.raises(InflowError, match="tau must be non-negative"):
        ScheduledInflow(SPACINGS, CTS, omega=OMEGA, spacing=0.2, ct=0.009, **{**g, "tau": -g["tau"] - 1e-3})
    with pytest.raises(InflowError, match="omega must be a positive number"):
        ScheduledInflow(SPACINGS, CTS, omega=0.0, spacing=0.2, ct=0.009, **g)
    with pytest.raises(InflowError, match="spacing must be a finite number"):
        ScheduledInflow(SPACINGS, CTS, omega=OMEGA, spacing=None, ct=0.009, **g)
    with pytest.raises(InflowError, match="trusted must have shape"):
        ScheduledInflow(SPACINGS, CTS, omega=OMEGA, spacing=0.2, ct=0.009, trusted=[True], **g)
    # an unstable node (Lbar11 < 0: lam0 runs away) poisons the cells around it
    unstable = g["Lbar"].copy()
    unstable[0, 0, 0, 0] = -1.0
    model = ScheduledInflow(SPACINGS, CTS, omega=OMEGA, spacing=0.3, ct=0.0096, **{**g, "Lbar": unstable})
    with pytest.raises(InflowError, match="unstable"):
        model.at(0.10, 0.0075)


def test_schedule_file_round_trip(tmp_path):
    model = _schedule(0.22, 0.0081)
    path = model.save(tmp_path / "schedule.json")
    back = ScheduledInflow.from_file(path, 0.22, 0.0081)
    for k in ("M", "Lbar", "tau", "loads_ref", "inflow_ref"):
        np.testing.assert_array_equal(back.matrices(0.22, 0.0081)[k], model.matrices(0.22, 0.0081)[k])
    assert back.name == model.name and back.n_states == model.n_states
    assert list(back.to_pandas().columns[:3]) == ["spacing", "ct", "trusted"] and len(back.to_pandas()) == 8
    (tmp_path / "other.json").write_text('{"schema": "something else"}')
    with pytest.raises(InflowError, match="not an inflow schedule"):
        ScheduledInflow.from_file(tmp_path / "other.json", 0.2, 0.009)
    with pytest.raises(InflowError, match="cannot read"):
        ScheduledInflow.from_file(tmp_path / "missing.json", 0.2, 0.009)


def test_the_aircraft_loads_and_trims_with_the_scheduled_model():
    config = spaced_config(coaxial_compound(), 0.17)
    model = _schedule().for_aircraft(config)           # spacing from the hubs, C_T from trim_ct
    assert model.spacing == pytest.approx(0.17, rel=1e-12)
    assert model.ct == pytest.approx(0.0096, rel=1e-12)
    heli = Helicopter(config, model, FAST)
    assert set(model.state_names) <= set(heli.state_names)
    tr = trim(heli)
    assert tr.max_residual < 1e-8                      # the trim-residual requirement of test_helicopter
    with pytest.raises(InflowError, match="rotors"):
        _schedule().for_aircraft(uh60_single_rotor())
    far = spaced_config(coaxial_compound(), 0.4)
    with pytest.raises(InflowError, match="spacing = 0.4 R is outside"):
        _schedule().for_aircraft(far)


# -- the result object on stand-in identifications -------------------------------------
def _fake_model(s, c, trusted=True):
    """What DesignSpaceResult reads of an IdentifiedModel, built from the linear matrices."""
    struct = Coaxial6State("rotor")
    m, l, t = _linear("M", s, c), _linear("Lbar", s, c), _linear("tau", s, c)
    values = {}
    for name, mat in (("m", m), ("l", l), ("t", t)):
        for i, j in ((1, 1), (2, 2), (1, 4), (2, 5), (4, 1), (5, 2), (4, 4), (5, 5)):
            values[f"{name}{i}{j}"] = float(mat[i - 1, j - 1])
    flight = struct.build(values, OMEGA)
    params = pd.DataFrame({"parameter": list(values), "value": list(values.values()), "status": "free",
                           "cramer_rao_pct": 5.0 if trusted else 40.0, "insensitivity_pct": 1.0})
    loads, lam = _refs(s, c)
    return SimpleNamespace(parameters=params, J_ave=50.0 + 100 * s, trusted=trusted, omega=OMEGA,
                           fit=SimpleNamespace(structure=flight), _refs=lambda: (loads, lam),
                           trim=SimpleNamespace(outputs={"CT_U": c / 2, "CT_L": c / 2}))


def _result(trusted=lambda s, c: True, fail=None):
    points = [DesignPoint(s, c, None if (s, c) == fail else _fake_model(s, c, trusted(s, c)),
                          "PipelineError: trim" if (s, c) == fail else None, 1.0)
              for s in SPACINGS for c in CTS]
    return DesignSpaceResult(SPACINGS, CTS, points, 8.0, IdentificationSettings())


def test_result_table_plot_and_schedule():
    res = _result(trusted=lambda s, c: s < 0.3)
    table = res.to_pandas()
    assert len(table) == 8 * len(KEY_PARAMETERS)
    row = table[(table.spacing == 0.2) & (table.ct == 0.0075) & (table.parameter == "l41")].iloc[0]
    assert row.value == pytest.approx(_linear("Lbar", 0.2, 0.0075)[3, 0], rel=1e-12)
    assert {"cramer_rao_pct", "insensitivity_pct", "J_ave", "trusted"} <= set(table.columns)
    assert res.summary_table().trusted.tolist() == [True] * 6 + [False] * 2
    fig = res.plot()
    assert isinstance(fig, Figure) and len([a for a in fig.axes if a.get_visible()]) == 8
    # the schedule's nodes are the structures' matrices; between them the linear closed form
    # (the structure ties row 3 to row 2 and row 6 to row 5: compare with the tied matrices)
    sched = res.schedule(0.25, 0.009)
    tied = _fake_model(0.25, 0.009).fit.structure.matrices()
    for k in ("M", "Lbar", "tau"):
        np.testing.assert_allclose(sched.matrices(0.25, 0.009)[k], tied[k], rtol=0, atol=1e-12)
    np.testing.assert_allclose(sched.matrices(0.25, 0.009)["Lbar"][:2, :2], _linear("Lbar", 0.25, 0.009)[:2, :2],
                               rtol=0, atol=1e-12)
    assert not sched.trusted.all()
    # trusted points only: the untrusted h/R 0.3 row is left out of the nodes
    only = res.schedule(0.2, 0.009, require_trusted=True)
    assert tuple(only.spacings) == (0.10, 0.14, 0.20) and tuple(only.cts) == CTS and only.trusted.all()
    with pytest.raises(DesignSpaceError, match="unknown parameters"):
        res.plot(parameters=("m99",))
    with pytest.raises(DesignSpaceError, match="no grid point"):
        res.point(0.15, 0.0096)


def test_result_with_a_failed_point_refuses_a_schedule():
    res = _result(fail=(0.2, 0.0096))
    assert [(p.spacing, p.ct) for p in res.failed] == [(0.2, 0.0096)]
    assert res.to_pandas().status.eq("failed").sum() == 1
    assert isinstance(res.plot(), Figure)
    with pytest.raises(DesignSpaceError, match=r"failed points: h/R 0.2, C_T 0.0096: PipelineError: trim"):
        res.schedule()


def test_identify_design_space_refuses_bad_input_before_any_wake_run():
    for bad, match in (((0.2, 0.1), "strictly increasing"), ((), "non-empty"), ((-0.1,), "positive"),
                       ("ab", "numbers")):
        with pytest.raises(DesignSpaceError, match=match):
            identify_design_space(bad, CTS, cache_dir=None, progress=False)
    with pytest.raises(DesignSpaceError, match="cts must be strictly increasing"):
        identify_design_space(SPACINGS, (0.0096, 0.0075), cache_dir=None, progress=False)
    with pytest.raises(DesignSpaceError, match="on_error"):
        identify_design_space(SPACINGS, CTS, on_error="ignore", cache_dir=None, progress=False)
    with pytest.raises(DesignSpaceError, match="settings must be an IdentificationSettings"):
        identify_design_space(SPACINGS, CTS, settings={"sweep_s": 10}, cache_dir=None, progress=False)
    with pytest.raises(DesignSpaceError, match="coaxial"):
        identify_design_space(SPACINGS, CTS, config=uh60_single_rotor(), cache_dir=None, progress=False)
    if "scheduler" not in inspect.signature(identify_inflow).parameters:
        with pytest.raises(DesignSpaceError, match="takes no scheduler"):
            identify_design_space(SPACINGS, CTS, scheduler="tcp://127.0.0.1:8786", cache_dir=None,
                                  progress=False)


# -- the schedule from trusted points only ---------------------------------------------
def test_trusted_subgrid_leaves_out_an_untrusted_point_and_its_row():
    # one untrusted point (0.2, 0.0075): dropping its spacing keeps 3 x 2 = 6 nodes,
    # dropping its thrust only 4 x 1 = 4, so the spacing goes
    res = _result(trusted=lambda s, c: (s, c) != (0.2, 0.0075))
    assert res.trusted_subgrid() == ((0.10, 0.14, 0.30), CTS)
    sched = res.schedule(0.14, 0.0096, require_trusted=True)
    assert tuple(sched.spacings) == (0.10, 0.14, 0.30) and sched.trusted.all()
    # the nodes are those points' own matrices (the tied structure's, as in the full grid)
    node = _fake_model(0.30, 0.0075).fit.structure.matrices()
    np.testing.assert_allclose(sched.matrices(0.30, 0.0075)["Lbar"], node["Lbar"], rtol=0, atol=1e-12)
    # the full-grid schedule still has every point as a node, the untrusted one flagged
    full = res.schedule(0.14, 0.0096)
    assert tuple(full.spacings) == SPACINGS and int((~full.trusted).sum()) == 1


def test_trusted_only_schedule_skips_a_failed_point_that_the_full_grid_refuses():
    res = _result(fail=(0.10, 0.0096))
    with pytest.raises(DesignSpaceError, match="failed points"):
        res.schedule()
    sched = res.schedule(0.2, 0.0096, require_trusted=True)
    assert tuple(sched.spacings) == (0.14, 0.20, 0.30) and tuple(sched.cts) == CTS


def test_trusted_only_schedule_refuses_too_few_trusted_points():
    with pytest.raises(DesignSpaceError, match=r"0 trusted point\(s\) of 8 \(none\)"):
        _result(trusted=lambda s, c: False).schedule(require_trusted=True)
    with pytest.raises(DesignSpaceError, match=r"1 trusted point\(s\) of 8 \(h/R 0.14, C_T 0.0096\)"):
        _result(trusted=lambda s, c: (s, c) == (0.14, 0.0096)).schedule(require_trusted=True)
    # two trusted points on a diagonal share no row or column: no rectangle of two nodes
    diagonal = _result(trusted=lambda s, c: (s, c) in ((0.10, 0.0075), (0.30, 0.0096)))
    assert diagonal.trusted_subgrid() == ((0.10,), (0.0075,))
    with pytest.raises(DesignSpaceError, match="at least two trusted nodes"):
        diagonal.schedule(require_trusted=True)
    with pytest.raises(DesignSpaceError, match="require_trusted must be True or False"):
        _result().schedule(require_trusted="yes")
    # two trusted points at one spacing: a schedule in thrust alone
    pair = _result(trusted=lambda s, c: s == 0.20)
    sched = pair.schedule(0.20, 0.009, require_trusted=True)
    assert tuple(sched.spacings) == (0.20,) and tuple(sched.cts) == CTS
    with pytest.raises(InflowError, match="outside the grid node"):
        pair.schedule(0.14, 0.009, require_trusted=True)


# -- the structure argument -------------------------------------------------------------
def test_identify_design_space_fits_the_structure_it_is_given(monkeypatch):
    import aircraft.identification.design_space as ds
    seen = []

    def fake_identify(config, condition, structure, *, ct, name, **kw):
        seen.append((structure, name))
        return SimpleNamespace(to_inflow=lambda: None)

    monkeypatch.setattr(ds, "identify_inflow", fake_identify)
    res = identify_design_space((0.14, 0.2), (0.0096,), structure="coaxial_6state_axisymmetric_pp_collective_mass",
                                progress=False, cache_dir=None)
    assert len(seen) == 2 and not res.failed
    struct = seen[0][0]
    # the shipped model's structure: collective apparent masses held a priori (m11, m44 fixed)
    assert type(struct).__name__ == "Coaxial6StateAxisymmetric" and struct.a_priori
    assert res.structure is struct and res.meta["structure"] == "coaxial_6state_axisymmetric_pp_collective_mass"
    assert seen[0][1].startswith("coaxial_6state_axisymmetric_pp_collective_mass, h/R 0.14")
    # the default is the free-mass 6-state, the very instance fitted before the argument existed
    seen.clear()
    res = identify_design_space((0.14,), (0.0096,), progress=False, cache_dir=None)
    assert seen[0][0] is ds._STRUCTURE and seen[0][1] == "coaxial 6-state, h/R 0.14, C_T 0.0096"
    with pytest.raises(DesignSpaceError, match="coaxial 6-state M/Lbar/tau"):
        identify_design_space((0.14,), (0.0096,), structure="single_rotor_3state", progress=False, cache_dir=None)
    with pytest.raises(DesignSpaceError, match="structure"):
        identify_design_space((0.14,), (0.0096,), structure="no_such_structure", progress=False, cache_dir=None)
    assert len(seen) == 1          # the refused structures ran nothing
