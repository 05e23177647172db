"""The wake's steady gains from held records (aircraft.identification.steady_gains).

The oracle is a known linear system simulated with scipy (not python-control, which
:meth:`SteadyGains.compare` uses): steady gains ``[G_C G_R G_T]`` behind a fast
first-order lag, driven by records shaped like the wake's (held load steps with
correlated loads; flap-rate ramps whose tilt grows and whose loads drift, then a held
tilt). No wake runs.
"""
import numpy as np
import pandas as pd
import pytest
from scipy import signal

from aircraft.identification.steady_gains import (SteadyGains, SteadyGainsError, estimate_steady_gains,
                                                  steady_gain_specs)
from aircraft.inflow.base import flap_rate_names

OMEGA = 23.7                                  # rad/s, the coaxial compound's rotor speed
LOADS = ["CT_U", "CL_U", "CM_U", "CT_L", "CL_L", "CM_L"]
RATES = flap_rate_names(("U", "L"))
OUTS = ["lam0_U", "lam1s_U", "lam1c_U", "lam0_L", "lam1s_L", "lam1c_L"]
TILTS = ["beta1s_U", "beta1c_U", "beta1s_L", "beta1c_L"]
TAU = 0.05                                    # s, the truth's lag: fast against the windows
DT = 0.01


def _truth(seed=0):
    rng = np.random.default_rng(seed)
    g_c = rng.normal(0.0, 3.0, (6, 6)) + np.diag([5.0, -9.0, -9.0, 3.5, 3.4, 3.1])
    g_r = rng.normal(0.0, 0.05, (6, 4))
    # Eq. 2.29 at zero frequency: lambda1s_r = -K_R beta1s_dot_r / Omega, K_R 1.5 / 0.7
    for row, col, kr in ((1, 0, 1.5), (2, 1, 1.5), (4, 2, 0.7), (5, 3, 0.7)):
        g_r[row, col] = -kr / OMEGA
    # a held tilt's own answer, of the size the wake shows (-0.1 per rad on-axis)
    g_t = rng.normal(0.0, 0.02, (6, 4))
    for row, col in ((1, 0), (2, 1), (4, 2), (5, 3)):
        g_t[row, col] = -0.1
    return g_c, g_r, g_t


def _records(g_c, g_r, g_t, seed=1):
    """Six held steps (each control moves several loads) and four flap-rate ramps
    (constant rate, the loads drifting with the tilt), outputs by scipy's lsim."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, 12.0 + DT / 2, DT)
    lag = signal.StateSpace(-1.0 / TAU * np.eye(6), np.eye(6) / TAU, np.eye(6), np.zeros((6, 6)))
    records, windows, times, drift = {}, {}, {}, {}
    for k in range(10):
        u = np.zeros((t.size, 14))
        if k < 6:       # step at 0.5 s, ramped over 0.1 s, held
            shape = np.clip((t - 0.5) / 0.1, 0.0, 1.0)
            mix = 1e-3 * (np.eye(6)[k] + 0.3 * rng.normal(size=6))
            u[:, :6] = shape[:, None] * mix
            windows[f"step_{k}"] = [(6.0, 10.0)]
            name = f"step_{k}"
        else:           # rate 0.0125 rad/s from 0.5 s to 8.5 s, loads growing with the tilt
            ramp = np.clip((t - 0.5) / 8.0, 0.0, 1.0)
            rate = np.where((t > 0.5) & (t < 8.5), 0.1 / 8.0, 0.0)
            u[:, 6 + (k - 6)] = rate
            u[:, 10 + (k - 6)] = 0.1 * ramp                # the tilt the rate builds, then held
            mix = 1e-3 * rng.normal(size=6)
            u[:, :6] = ramp[:, None] * mix
            name = f"ramp_{k}"
            drift[k - 6] = mix / 8.0          # load drift rate [1/s] during the ramp
            windows[name] = [(4.5, 8.4), (10.0, 12.0)]     # during the ramp (clear of its end), then held
        steady = u @ np.hstack([g_c, g_r, g_t]).T
        _, y, _ = signal.lsim(lag, steady, t)
        df = pd.DataFrame(np.column_stack([t, u, y]), columns=["t"] + LOADS + RATES + TILTS + OUTS)
        records[name], times[name] = df, 0.5
    return records, windows, times, drift


def _estimate(records, windows, times):
    return estimate_steady_gains(records, windows, times, LOADS, RATES, OUTS, omega=OMEGA, rotors=("U", "L"),
                                 tilts=TILTS)


def test_recovers_the_steady_gains_and_K_R_of_a_known_system():
    g_c, g_r, g_t = _truth()
    records, windows, times, drift = _records(g_c, g_r, g_t)
    est = _estimate(records, windows, times)
    assert isinstance(est, SteadyGains) and est.condition_number < 100
    # the steps settle (exp(-5.5 s / tau) ~ 1e-48): the load gains are exact to the
    # lsim discretisation
    np.testing.assert_allclose(est.loads_gain.to_numpy(), g_c, rtol=0, atol=1e-6 * np.abs(g_c).max())
    # a ramp's loads drift at dC/dt and its tilt grows at beta_dot; a path lagging by
    # tau answers G (u - tau du/dt), so the rate gains carry the known quasi-static
    # bias -tau (G_C dC/dt / beta_dot + G_T) (here up to ~10 %), and nothing else
    rate = 0.1 / 8.0
    bias = np.column_stack([-TAU * (g_c @ drift[j] / rate + g_t[:, j]) for j in range(4)])
    assert np.abs(bias).max() > 0.05 * np.abs(g_r).max()          # the bias is real here...
    np.testing.assert_allclose(est.rate_gain.to_numpy(), g_r + bias, rtol=0, atol=1e-4 * np.abs(g_r).max())
    # the held tilts settle: the tilt gains are exact, and separate from the rate's
    np.testing.assert_allclose(est.tilt_gain.to_numpy(), g_t, rtol=0, atol=1e-6 * np.abs(g_t).max())
    kr = {r: -OMEGA * np.mean([g_r[row, col] + bias[row, col] for row, col in pairs])
          for r, pairs in (("U", ((1, 0), (2, 1))), ("L", ((4, 2), (5, 3))))}
    assert est.equivalent_kr == pytest.approx(kr, rel=1e-4)
    long = est.to_pandas()
    assert len(long) == 6 * 14 and set(long.kind) == {"load", "flap_rate", "tilt"}
    # without the tilt inputs the same records put the tilt's answer into the rate gains
    blind = estimate_steady_gains(records, windows, times, LOADS, RATES, OUTS, omega=OMEGA, rotors=("U", "L"))
    assert abs(blind.equivalent_kr["U"] - 1.5) > 1.0
    # rate_only() is that estimate on the ramp windows alone (exactly determined)
    ramp_only = {n: w[:1] for n, w in windows.items()}
    expect = estimate_steady_gains(records, ramp_only, times, LOADS, RATES, OUTS, omega=OMEGA, rotors=("U", "L"))
    np.testing.assert_allclose(est.rate_only().rate_gain.to_numpy(), expect.rate_gain.to_numpy(), rtol=1e-12)


def test_compare_simulates_a_model_on_each_record():
    import control
    g_c, g_r, g_t = _truth()
    records, windows, times, _ = _records(g_c, g_r, g_t)
    est = _estimate(records, windows, times)

    class Model:       # the truth without its tilt term (no structure of ours has one)
        system = control.ss(-1.0 / TAU * np.eye(6), np.hstack([g_c, g_r]) / TAU, np.eye(6), 0,
                            inputs=LOADS + RATES, outputs=OUTS)

    table = est.compare(Model())
    # the on-axis output of each record only (our synthetic records are named by
    # number, so none has an on-axis harmonic): rename two to the wake's names
    assert table.empty
    records = {("step_theta1s_U" if k == "step_1" else "ramp_beta1s_L" if k == "ramp_8" else k): v
               for k, v in records.items()}
    windows = {("step_theta1s_U" if k == "step_1" else "ramp_beta1s_L" if k == "ramp_8" else k): v
               for k, v in windows.items()}
    times = dict.fromkeys(records, 0.5)
    table = _estimate(records, windows, times).compare(Model())
    assert list(zip(table.record, table.window, table.output)) == [
        ("step_theta1s_U", "6-10", "lam1s_U"), ("ramp_beta1s_L", "4.5-8.4", "lam1s_L"),
        ("ramp_beta1s_L", "10-12", "lam1s_L")]
    # where no tilt is held (the step) the model matches the wake to the simulation's
    # accuracy; on the ramp and the held tilt it misses exactly the tilt term
    t = records["ramp_beta1s_L"].t.to_numpy()
    tilt = records["ramp_beta1s_L"].beta1s_L.to_numpy()
    # (the wake's tilt term lags by tau too: during the ramp by tau x the rate)
    lag_of = {(4.5, 8.4): TAU * 0.1 / 8.0, (10.0, 12.0): 0.0}
    miss = [g_t[4, 2] * (tilt[(t >= lo) & (t <= hi)].mean() - lag_of[(lo, hi)]) for lo, hi in lag_of]
    assert table.ratio.iloc[0] == pytest.approx(1.0, abs=2e-3)
    np.testing.assert_allclose((table.wake - table.model).iloc[1:], miss, rtol=2e-3)
    fig = _estimate(records, windows, times).plot(models={"truth": Model()})
    assert len(fig.axes[0].patches) == 6


def test_bad_records_are_refused():
    g_c, g_r, g_t = _truth()
    records, windows, times, _ = _records(g_c, g_r, g_t)
    few = dict(list(records.items())[:9])
    with pytest.raises(SteadyGainsError, match="12 observations .* cannot determine gains of 14 inputs"):
        _estimate(few, windows, times)
    late = dict(windows, step_0=(6.0, 13.0))
    with pytest.raises(SteadyGainsError, match="record 'step_0'.*window"):
        _estimate(records, late, times)
    idle = {k: v.assign(beta1c_dot_L=0.0) for k, v in records.items()}
    with pytest.raises(SteadyGainsError, match=r"no record moves \['beta1c_dot_L'\]"):
        _estimate(idle, windows, times)
    with pytest.raises(SteadyGainsError, match="lacks columns"):
        _estimate({k: v.drop(columns="lam0_U") for k, v in records.items()}, windows, times)
    nan = dict(records, step_0=records["step_0"].assign(lam0_U=np.nan))
    with pytest.raises(SteadyGainsError, match="not finite"):
        _estimate(nan, windows, times)
    with pytest.raises(SteadyGainsError, match="a window must be"):
        _estimate(records, dict(windows, step_0="6-10"), times)
    with pytest.raises(SteadyGainsError, match="must be an IdentifiedModel"):
        _estimate(records, windows, times).compare(object())


def test_specs_hold_one_record_per_input():
    steps, ramps = steady_gain_specs(("U", "L"), ramp_amplitude=0.1, ramp_s=8.0)
    assert [s.control for s in steps] == ["theta0_U", "theta1s_U", "theta1c_U", "theta0_L", "theta1s_L", "theta1c_L"]
    assert [s.control for s in ramps] == ["beta1s_U", "beta1c_U", "beta1s_L", "beta1c_L"]
    # a ramp is a "step" whose ramp lasts: the flap rate is amplitude / ramp time
    assert all(r.kind == "step" and r.amplitude / r.pulse_width == pytest.approx(0.0125) for r in ramps)
    # the steps are the quasi-steady check's records (same spec: its cache entries serve)
    assert (steps[0].amplitude, steps[0].duration, steps[0].trim_start, steps[0].pulse_width) == (0.02, 10.0, 0.5, 0.1)
    single_steps, single_ramps = steady_gain_specs(("main",))
    assert single_steps[0].control == "theta0" and single_ramps[0].control == "beta1s"


def test_wake_ramp_window_must_lie_within_the_ramp():
    from aircraft.configs import coaxial_compound
    from aircraft.identification.steady_gains import wake_steady_gains
    with pytest.raises(SteadyGainsError, match="must lie within the ramp"):
        wake_steady_gains(coaxial_compound(), 0.0096, ramp_window=(4.5, 9.5))
    with pytest.raises(SteadyGainsError, match="tilt_window .* after the ramp ends"):
        wake_steady_gains(coaxial_compound(), 0.0096, tilt_window=(8.0, 12.0))


@pytest.mark.slow
def test_wake_records_on_a_tiny_single_rotor_wake():
    # the wake glue end to end (names, the single rotor's unsuffixed signals, windows,
    # compare with a shipped model) on a coarse wake and short records; ~20 s
    import math
    from aircraft.configs import uh60_single_rotor
    from aircraft.identification import IdentificationSettings
    from aircraft.identification.steady_gains import wake_steady_gains
    from aircraft.inflow import IdentifiedInflow
    from aircraft.wake import WakeSettings
    settings = IdentificationSettings(wake=WakeSettings(azimuth_step=math.radians(20.0), wake_revolutions=1.5,
                                                        far_wake_revolutions=2.0, n_elements=5))
    g = wake_steady_gains(uh60_single_rotor(), 0.0061, settings=settings, step_window=(2.5, 4.0),
                          ramp_window=(1.5, 2.5), tilt_window=(3.2, 4.0), hold_s=4.0, ramp_s=2.5,
                          ramp_hold_s=4.0, cache_dir=None, progress=False, n_jobs=1)
    assert list(g.loads_gain.columns) == ["CT", "CL", "CM"]
    assert list(g.rate_gain.columns) == ["beta1s_dot", "beta1c_dot"]
    assert list(g.tilt_gain.columns) == ["beta1s", "beta1c"]
    assert len(g.changes) == 7 and np.isfinite(g.condition_number)
    # 7 observations, 7 inputs: the estimate reproduces every observation exactly
    X = g.changes[["CT", "CL", "CM", "beta1s_dot", "beta1c_dot", "beta1s", "beta1c"]].to_numpy().T
    G = np.hstack([g.loads_gain, g.rate_gain, g.tilt_gain])
    np.testing.assert_allclose(G @ X, g.changes[["lam0", "lam1s", "lam1c"]].to_numpy().T, atol=1e-9)
    # a more thrust gives more inflow: the collective's steady gain is positive
    assert g.loads_gain.loc["lam0", "CT"] > 0
    table = g.compare(IdentifiedInflow.from_file("uh60_hover_3state"))
    assert set(table.output) == {"lam0", "lam1s", "lam1c"} and np.isfinite(table.model).all()
