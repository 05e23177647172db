"""Off-rotor gain-and-delay models (Eqs. 2.39-2.40): aircraft.identification.off_rotor.

The synthetic truth is simulated here with numpy/scipy only (scipy.signal.lsim for
the inflow dynamics, np.interp for exact delays); the library only sees the time
histories, as it would see the wake's.
"""
import math
import os
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest
from scipy import signal

from aircraft.configs import coaxial_compound, uh60_single_rotor
from aircraft.identification.off_rotor import (OffRotorError, fit_off_rotor, gain_delay_structure, horizontal_tail,
                                               reduce_off_rotor, wake_exposure, wing_under_hub)
from aircraft.identification import OffRotorSettings, OffRotorSurface, identify_off_rotor
from flightid import combine_responses, frequency_response, frequency_sweep, joint_input_output

LAM = ["lam0", "lam1c", "lam1s"]
# a truth of the dissertation's size (§4.6.1 tail model); delays 0-0.3 s
K_TRUE = np.array([[-0.29, -0.31, 0.05], [-0.14, -0.14, 0.34], [0.31, 0.54, -0.11]])
TAU_TRUE_239 = np.array([0.06, 0.21, 0.30])          # one per inflow state (Eq. 2.39)


def _simulate(tau, dt=0.01, seed=3):
    """Three control sweeps -> coupled first-order inflow -> vbar = K o lam(t - tau)."""
    rng = np.random.default_rng(seed)
    # inflow dynamics lam' = A lam + B theta (coupled, stable; rad/s)
    A = np.array([[-4.0, 0.5, 0.0], [0.3, -6.0, 1.0], [0.0, -1.0, -6.0]])
    B = np.array([[2.0, 0.2, 0.1], [0.1, 1.5, -0.3], [0.2, 0.3, 1.5]])
    sys_l = signal.StateSpace(A, B, np.eye(3), np.zeros((3, 3)))
    records = []
    for k in range(3):
        t, u = frequency_sweep(0.5, 20.0, 60.0, dt, 0.02, trim_start=1.0, trim_end=1.0, seed=k)
        theta = np.zeros((t.size, 3))
        theta[:, k] = u
        _, lam, _ = signal.lsim(sys_l, theta, t)
        v = np.zeros((t.size, 3))
        for i in range(3):
            for j in range(3):
                v[:, i] += K_TRUE[i, j] * np.interp(t - tau[i, j], t, lam[:, j], left=0.0)
        v += 1e-5 * rng.standard_normal(v.shape)      # measurement noise, 1-3 % of the signals
        records.append((t, u, lam, v))
    return records


def _responses(records):
    names = ["vx", "vy", "vz"] + LAM
    simo = [frequency_response(t, u, np.column_stack([v, lam]), w_min=0.5, w_max=20.0,
                               input_name=f"theta{k}", output_names=names)
            for k, (t, u, lam, v) in enumerate(records)]
    m = combine_responses(simo)
    return joint_input_output(m.select(["vx", "vy", "vz"]), m.select(LAM))


@pytest.mark.parametrize("form", ["2.39", "2.40"])
def test_synthetic_gain_delay_recovered(form):
    tau = np.tile(TAU_TRUE_239, (3, 1)) if form == "2.39" else \
        np.array([[0.20, 0.50, 0.35], [0.0, 0.45, 0.50], [0.07, 0.15, 0.0]])    # Eq. 4.10's pattern
    res = fit_off_rotor(_responses(_simulate(tau)), form, fit_range=(1.0, 5.0))
    mats = res.structure.matrices()
    # The only errors are the spectral estimate's (windowing, 1e-5 noise) and the linear
    # interpolation of the delayed signals (relative error (w dt)^2/8 < 1e-4 at 5 rad/s):
    # measured below 1 % on the gains; 2 % of the largest gain leaves margin for the
    # smallest (0.05), whose response is 10x weaker.
    np.testing.assert_allclose(mats["K"], K_TRUE, atol=0.02 * np.abs(K_TRUE).max())
    # a delay of a gain g is seen through its phase g*w*tau; over 1-5 rad/s a 5 ms error
    # is 1.4 deg at 5 rad/s: below the spectral estimate's phase scatter for the weak gains
    big = np.abs(K_TRUE) > 0.1
    np.testing.assert_allclose(mats["tau"][big], tau[big], atol=0.01)
    assert res.J_ave < 5.0      # CIFER: J_ave < 100 is a good fit; a noise-free truth is near 0


def test_reduction_removes_zero_delays_and_keeps_real_ones():
    """Eq. 2.40 on a truth with two zero delays (Eq. 4.10's pattern): the fit leaves them a
    hair above their 0 s bound with unbounded relative bounds; the reduction removes
    exactly those (fixed at 0 s, logged as accepted) and keeps the real delays."""
    tau = np.array([[0.20, 0.50, 0.35], [0.0, 0.45, 0.50], [0.07, 0.15, 0.0]])
    data = _responses(_simulate(tau))
    first = fit_off_rotor(data, "2.40", fit_range=(1.0, 5.0))
    reduction = reduce_off_rotor(first, data)
    assert sorted(reduction.removed) == ["tau0y", "tau1sz"]
    values = reduction.result.structure.values
    assert values["tau0y"] == 0.0 and values["tau1sz"] == 0.0
    assert {"tau0y", "tau1sz"} <= reduction.result.structure.fixed
    mats = reduction.result.structure.matrices()
    # the error budget of test_synthetic_gain_delay_recovered (spectral estimate, interpolated
    # delays): 10 ms on the delays of the strong gains, 2 % of the largest gain on the gains
    big = np.abs(K_TRUE) > 0.1
    np.testing.assert_allclose(mats["tau"][big], tau[big], atol=0.01)
    np.testing.assert_allclose(mats["K"], K_TRUE, atol=0.02 * np.abs(K_TRUE).max())
    # removing two parameters that were at zero cannot raise the cost measurably (< 0.01 of a
    # J_ave ~ 0.1 of a noise-free truth)
    assert reduction.result.J_ave - first.J_ave < 0.01


def test_delay_held_at_its_bound_is_reported_removed():
    """The reduction holds a parameter a removal left without influence where it is; a
    delay held a hair above 0 s (the wake's hover tail: 6e-58 s) is no delay: reported
    removed at exactly 0 s, with the cost unchanged (exp(-1e-30 j w) is 1 in double)."""
    import pandas as pd
    from flightid import fit
    from flightid.reduction import ReductionResult
    from aircraft.identification.off_rotor.surfaces import _delays_at_bound_removed
    tau = np.array([[0.20, 0.50, 0.35], [0.0, 0.45, 0.50], [0.07, 0.15, 0.0]])
    data = _responses(_simulate(tau))
    first = fit_off_rotor(data, "2.40", fit_range=(1.0, 5.0), starts=1)
    pairs = [(p.output, p.input) for p in first.pairs]
    held = fit(first.structure.with_values({"tau0y": 1e-30}).fix(["tau0y"]), data, pairs=pairs,
               frequency_ranges=(1.0, 5.0))
    log = pd.DataFrame(columns=["parameter", "reason", "metric_pct", "J_ave_before", "J_ave_after",
                                "max_single_rise", "accepted", "runaway", "note"])
    j_before = held.J_ave
    out = _delays_at_bound_removed(ReductionResult(held, first, log), first)
    assert out.removed == ["tau0y"]
    assert out.result.structure.values["tau0y"] == 0.0
    assert out.result.parameters.set_index("parameter").loc["tau0y", "value"] == 0.0
    assert out.result.J_ave == j_before


def test_gain_delay_structure_names_and_forms():
    s239 = gain_delay_structure("2.39")
    assert {"K0z", "K1cx", "K1sy", "tau0", "tau1c", "tau1s"} <= set(s239.names)
    assert len(s239.names) == 12
    assert len(gain_delay_structure("2.40").names) == 18
    with pytest.raises(OffRotorError, match="form must be '2.39' or '2.40'"):
        gain_delay_structure("2.41")


def test_surfaces_from_configuration():
    cfg = uh60_single_rotor()
    tail = horizontal_tail(cfg)
    pts = tail.points()
    assert len(pts) == 7 and tail.center == tuple(cfg.htail_position)
    ys = [p[1] for p in pts.values()]
    assert ys[0] == pytest.approx(-tail.span / 2) and ys[-1] == pytest.approx(tail.span / 2)
    # span from the area with the UH-60A stabilator aspect ratio 14.4^2/45 = 4.61
    assert tail.span == pytest.approx(math.sqrt(14.4 ** 2 / 45.0 * cfg.htail_area))
    wing = wing_under_hub(cfg)
    hub = cfg.rotors[0].hub_position
    assert wing.center[2] == pytest.approx(hub[2] + 0.25 * cfg.rotors[0].radius)
    assert wing.form == "2.40" and tail.form == "2.39"


def test_wake_exposure_geometry():
    """Against the skewed-cylinder geometry worked by hand."""
    cfg = uh60_single_rotor()
    R = cfg.rotors[0].radius
    point = OffRotorSurface("p", (-8.0, 0.0, 0.0), 1.0, n_points=1)
    h = 0.0 - cfg.rotors[0].hub_position[2]          # 1.9 m below the hub
    hover = wake_exposure(point, cfg, 0.0, 0.06).iloc[0]
    assert hover.chi_deg == 0.0 and hover.wake_center_x_m == 0.0
    assert hover.distance_over_rw == pytest.approx(8.0 / (0.86 * R))
    assert not hover.in_wake                          # 8 m aft, hover wake 0.86 R = 7.0 m
    fwd = wake_exposure(point, cfg, 0.1, 0.03).iloc[0]
    chi = math.atan(0.1 / 0.03)
    assert fwd.chi_deg == pytest.approx(math.degrees(chi))
    assert fwd.wake_center_x_m == pytest.approx(-h * math.tan(chi))
    assert fwd.in_wake
    fast = wake_exposure(point, cfg, 0.4, 0.008).iloc[0]   # wake swept back above the tail
    assert not fast.in_wake


@pytest.mark.parametrize("kwargs, match", [
    (dict(fit_range=(5.0, 1.0)), "fit_range"),
    (dict(w_min=-1.0), "0 < w_min < w_max"),
    (dict(controls=("theta0", "theta1s")), "at least 3 swept controls"),
    (dict(doublet_s=1.5), "shorter than the doublet"),
    (dict(sweep_s=float("nan")), "sweep_s must be a positive finite"),
])
def test_bad_settings(kwargs, match):
    with pytest.raises(OffRotorError, match=match):
        OffRotorSettings(**kwargs)


@pytest.mark.parametrize("kwargs, match", [
    (dict(name="tail 1", center=(0, 0, 0), span=1.0), "identifier"),
    (dict(name="t", center=(0, float("nan"), 0), span=1.0), "three finite|3 finite"),
    (dict(name="t", center=(0, 0), span=1.0), "3 finite"),
    (dict(name="t", center=(0, 0, 0), span=-1.0), "span must be a positive"),
    (dict(name="t", center=(0, 0, 0), span=1.0, n_points=0), "n_points"),
    (dict(name="t", center=(0, 0, 0), span=1.0, form="2.38"), "form must be"),
])
def test_bad_surface(kwargs, match):
    with pytest.raises(OffRotorError, match=match):
        OffRotorSurface(**kwargs)


def test_bad_inputs_identify_and_fit():
    with pytest.raises(OffRotorError, match="single rotor"):
        identify_off_rotor(coaxial_compound(), progress=False)
    cfg = uh60_single_rotor()
    tail = horizontal_tail(cfg)
    with pytest.raises(OffRotorError, match="unique"):
        identify_off_rotor(cfg, surfaces=[tail, tail], progress=False)
    with pytest.raises(OffRotorError, match="MeasuredResponse"):
        fit_off_rotor(np.zeros(3))
    resp = _responses(_simulate(np.zeros((3, 3))))
    with pytest.raises(OffRotorError, match="missing"):
        fit_off_rotor(resp, outputs=["vx", "vy", "vw"])
    with pytest.raises(OffRotorError, match="fit_range"):
        fit_off_rotor(resp, fit_range=(50.0, 90.0))
    with pytest.raises(OffRotorError, match="mu must be >= 0"):
        wake_exposure(tail, cfg, -0.1, 0.05)
    with pytest.raises(OffRotorError, match="hover_contraction"):
        wake_exposure(tail, cfg, 0.1, 0.05, hover_contraction=1.5)


def _fake_run_sweeps(tau, seed=5):
    """A stand-in for aircraft.wake.run_sweeps: the same record names and columns, with
    inflow from scipy-simulated dynamics and point velocities from the Eq. 2.39 truth
    (each point's scaled by its own factor, the factors averaging to one)."""
    from aircraft.wake import WakeTrim
    A = np.array([[-4.0, 0.5, 0.0], [0.3, -6.0, 1.0], [0.0, -1.0, -6.0]])
    B = np.array([[2.0, 0.2, 0.1], [0.1, 1.5, -0.3], [0.2, 0.3, 1.5]])
    lam_trim = np.array([0.06, 0.001, -0.002])            # constant trim values to be removed
    controls = ["theta0", "theta1s", "theta1c"]

    def fake(config, settings, flight, specs, *, trim=None, points=None, **_):
        rng = np.random.default_rng(seed)
        dt = 0.01
        out = {}
        for spec in specs:
            (t, u), = spec.inputs(dt).values()
            theta = np.zeros((t.size, 3))
            theta[:, controls.index(spec.control)] = u
            _, lam, _ = signal.lsim(signal.StateSpace(A, B, np.eye(3), np.zeros((3, 3))), theta, t)
            lam = np.atleast_2d(lam).reshape(t.size, 3)
            vel = np.zeros((t.size, 3))
            for i in range(3):
                for j in range(3):
                    vel[:, i] += K_TRUE[i, j] * np.interp(t - tau[i, j], t, lam[:, j], left=0.0)
            cols = {"t": t, **{c: theta[:, k] for k, c in enumerate(controls)},
                    **{n: lam[:, k] + lam_trim[k] for k, n in enumerate(LAM)}}
            labels = list(points)
            for k, lab in enumerate(labels):
                scale = 1.0 + 0.2 * (k - (len(labels) - 1) / 2) / max(len(labels) - 1, 1)
                for i, c in enumerate("xyz"):
                    cols[f"v{c}_{lab}"] = scale * vel[:, i] + 0.01 * (i + 1) + 1e-6 * rng.standard_normal(t.size)
            out[spec.name] = pd.DataFrame(cols)
        out["trim"] = WakeTrim(controls={}, outputs={"CT": 0.0061, "lam0": 0.06, "lam1c": 0.001, "lam1s": -0.002},
                               converged=True, iterations=1, residual=0.0)
        return out
    return fake


def test_identify_off_rotor_pipeline_on_a_synthetic_wake(monkeypatch):
    """identify_off_rotor end to end (records -> point averages -> joint input-output ->
    fit -> doublet verification) with the wake replaced by a known truth."""
    import aircraft.wake
    cfg = uh60_single_rotor()
    tail = OffRotorSurface("tail", cfg.htail_position, 3.0, n_points=4, form="2.39")
    tau = np.tile(TAU_TRUE_239, (3, 1))
    monkeypatch.setattr(aircraft.wake, "run_sweeps", _fake_run_sweeps(tau))
    settings = OffRotorSettings(sweep_s=60.0, w_min=0.5, w_max=20.0, doublet_s=6.0, noise_floor_s=2.0, starts=1)
    res = identify_off_rotor(cfg, surfaces=[tail], settings=settings, progress=False)
    m = res.models["tail"]
    # same error budget as test_synthetic_gain_delay_recovered (the truth's spectra and
    # interpolated delays only); the point averaging is exact (factors average to 1)
    np.testing.assert_allclose(m.gains.to_numpy(), K_TRUE, atol=0.02 * np.abs(K_TRUE).max())
    np.testing.assert_allclose(m.delays.to_numpy()[0], TAU_TRUE_239, atol=0.01)
    vt = m.verification_table
    assert set(vt.doublet) == {"theta0", "theta1s", "theta1c"}
    # the model is the truth but for the 2nd-order Pade delays: a doublet is reproduced to a
    # few per cent (TIC 0 perfect, 1 worst); the zero-input run has nothing but 1e-6 noise
    assert vt.TIC.max() < 0.1
    assert m.trim_velocity["z"] == pytest.approx(0.03, abs=1e-4)     # the constant offset
    table = res.to_pandas()
    assert len(table) == 9 and set(table.K_status) == {"free"}
    # reduced and judged: every delay of this truth is real (60-300 ms), so nothing is removed,
    # and every free parameter carries its bounds and a verdict of the trust rule
    assert m.reduction is not None and m.reduction.removed == []
    params = res.parameter_table
    free = params[params.status == "free"]
    assert len(free) == 12 and free.verdict.isin(["ok", "kept", "fails"]).all()
    assert np.isfinite(free[["cramer_rao_pct", "insensitivity_pct"]].to_numpy()).all()
    assert params.model_trusted.iloc[0] == m.trusted == m.trust.passes
    assert {"K_verdict", "tau_verdict"} <= set(table.columns)
    fig = m.plot()
    assert len(fig.axes) == 9
    assert "tail (Eq. 2.39)" in res.summary()


@pytest.mark.slow
def test_study_small_end_to_end(tmp_path):
    """The study on a tiny wake (hover), run as a program: the whole chain writes its tables.

    The tiny wake (20 deg steps, 1.5 revolutions, 4 elements, 8 s sweeps) checks the
    plumbing, not the numbers; the physics checked here is robust even there."""
    root = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=root, ROTORWAKE_CACHE_DIR=str(tmp_path / "cache"))
    out = tmp_path / "out"
    done = subprocess.run([sys.executable, "-m", "studies.off_rotor_models", "--small", "--jobs", "1",
                           "--out", str(out)], cwd=root, env=env, capture_output=True, text=True, timeout=1800)
    assert done.returncode == 0, done.stderr[-3000:]
    for name in ("gains_delays.csv", "verification.csv", "exposure.csv", "exposure_vs_mu.csv",
                 "dissertation_hover.csv", "verification_tail_mu0p00.png", "verification_wing_mu0p00.png",
                 "exposure.png"):
        assert (out / name).stat().st_size > 0, name
    gains = pd.read_csv(out / "gains_delays.csv")
    assert set(gains.surface) == {"tail", "wing"} and len(gains) == 18
    assert (gains.tau_s >= 0).all()
    wing = gains[(gains.surface == "wing") & (gains.input == "lam0")].set_index("output")
    # under the hub the wake's downwash follows lam0 (z down: a positive gain); momentum
    # theory puts the far-wake velocity at 2 lam0, the disk at 1: 0.3-3 bounds a wrong sign
    # or a lost factor even on the tiny wake
    assert 0.3 < wing.loc["vz_wing", "K"] < 3.0
    ver = pd.read_csv(out / "verification.csv")
    assert set(ver.doublet) == {"theta0", "theta1s", "theta1c"} and ver.TIC.between(0, 1).all()
    curve = pd.read_csv(out / "exposure_vs_mu.csv")
    tail = curve[curve.surface == "tail"].set_index("mu")
    assert tail.loc[0.0, "fraction_in_wake"] == 0.0 and tail.loc[0.1, "fraction_in_wake"] > 0.5
