"""Free-vortex wake: hover single rotor (momentum theory, Landgrebe), coaxial hover."""
import math

import numpy as np
import pandas as pd
import pytest

from aircraft.configs import uh60_single_rotor, coaxial_compound
from aircraft.wake import (FreeVortexWake, WakeSettings, FlightCondition, WakeSettingsError,
                           run_sweeps, SweepSpec)

# every test here shares a fixture that takes seconds to build: not in the quick set (make test-quick)
pytestmark = pytest.mark.slow

KAPPA = 1.15   # induced-power factor compared against: lambda_h = kappa sqrt(CT/2)
COARSE = dict(azimuth_step=math.radians(15.0), wake_revolutions=2.0, n_elements=6)


@pytest.fixture(scope="module")
def hover_single():
    w = FreeVortexWake(uh60_single_rotor(), WakeSettings(**COARSE))
    tr = w.trim(ct=0.0061)
    return w, tr


def test_hover_trim_and_momentum_inflow(hover_single):
    w, tr = hover_single
    assert tr.converged
    assert tr.outputs["CT"] == pytest.approx(0.0061, abs=2e-5)
    lam_mt = KAPPA * math.sqrt(0.0061 / 2)
    # issue requirement: mean inflow within 15 % of momentum theory with kappa
    assert abs(tr.outputs["lam0"] / lam_mt - 1) < 0.15
    # axisymmetric hover: harmonics and hub moments vanish to blade-passage noise
    assert abs(tr.outputs["lam1s"]) < 0.05 * tr.outputs["lam0"]
    assert abs(tr.outputs["CL"]) < 1e-4 and abs(tr.outputs["CM"]) < 1e-4


@pytest.mark.parametrize("landgrebe_near_wake, band", [(True, (0.70, 0.86)), (False, (0.80, 0.95))])
def test_tip_vortex_contraction(landgrebe_near_wake, band):
    # Landgrebe: r -> 0.78 R within about a revolution. Judged over 0.5-1.5
    # revolutions of age (later the hover wake's pairing instability and the join
    # to the buffer make the blade-mean radius wander). With the Landgrebe-
    # contracted near wake the coarse wake must be within 10 % of 0.78; the
    # default rigid near wake releases the tip vortex at r = R and is known to
    # contract less (~0.86-0.89 R measured): its band documents that.
    w = FreeVortexWake(uh60_single_rotor(),
                       WakeSettings(**COARSE, near_wake_contraction=landgrebe_near_wake))
    w.trim(ct=0.0061)
    ages, rad = w.tip_vortex_radius()
    window = (ages > np.pi) & (ages < 3 * np.pi)
    assert band[0] < rad[0, window].mean() < band[1]
    ages, z = w.tip_vortex_height()
    one_rev = np.argmin(abs(ages - 2 * np.pi))
    assert z[0, one_rev] < -0.1     # the wake has descended below the disk


def test_hover_wake_bounded_over_20_revs(hover_single):
    w, tr = hover_single
    df = w.run(duration=20 * 2 * math.pi / w.omega)
    per_rev = df.groupby((df["t"] * w.omega // (2 * math.pi)).astype(int))["CT"].mean()
    # the trimmed wake stays periodic: each revolution's mean thrust within 5 %
    assert np.all(np.abs(per_rev / 0.0061 - 1) < 0.05)
    assert np.all(np.isfinite(np.concatenate([x.ravel() for x in w.X])))
    ages, rad = w.tip_vortex_radius()
    assert rad.max() < 1.5


def test_azimuth_step_halving_changes_inflow_little():
    res = []
    for step in (15.0, 7.5):
        s = WakeSettings(**{**COARSE, "azimuth_step": math.radians(step)})
        w = FreeVortexWake(uh60_single_rotor(), s)
        w.controls["theta0"] = math.radians(9.0)
        w.march(3 * s.steps_per_rev)
        res.append(w.march(2 * s.steps_per_rev))
    # issue requirement: < 5 % change with the step halved (same controls)
    assert res[1]["CT"] == pytest.approx(res[0]["CT"], rel=0.05)
    assert res[1]["lam0"] == pytest.approx(res[0]["lam0"], rel=0.05)


def test_trimmed_inflow_converges_with_wake_length():
    # With the far-wake continuation the trimmed inflow no longer depends on how
    # much of the wake is free: 2 and 4 free revolutions agree within 5 % (measured
    # 1.4 %; without the continuation they differed by 18 % and the 4-revolution
    # wake's end rolled up to 1.1-1.2 R).
    # settle_revs=8: the radius check is on a developed wake; the default 3 settling
    # revolutions plus one trim iteration (5 revolutions) leave part of the initial
    # prescribed wake in the 4 + 1 revolution free wake and buffer (its end was
    # measured at 0.29 R, and the tip vortex bulging to 1.12 R mid-wake)
    lam = []
    for revs in (2.0, 4.0):
        w = FreeVortexWake(uh60_single_rotor(), WakeSettings(**{**COARSE, "wake_revolutions": revs}))
        tr = w.trim(ct=0.0061, settle_revs=8)
        assert tr.converged
        lam.append(tr.outputs["lam0"])
        assert w.tip_vortex_radius()[1].max() < 1.1
    assert lam[1] == pytest.approx(lam[0], rel=0.05)
    with pytest.raises(WakeSettingsError, match="far_wake_revolutions"):
        WakeSettings(far_wake_revolutions=-1.0)


def test_single_precision_kernel_trims_like_double(hover_single):
    # The hover wake's blade-passage unsteadiness is chaotic: any round-off change
    # shifts revolution-averaged outputs by about its per-revolution scatter (0.5 %
    # rms for CT and lam0 at this resolution), so 1.5 % (3 sigma) is the bound.
    w32, tr32 = hover_single
    assert w32.settings.kernel_precision == "single"
    w64 = FreeVortexWake(uh60_single_rotor(), WakeSettings(**COARSE, kernel_precision="double"))
    tr64 = w64.trim(ct=0.0061)
    assert tr32.outputs["lam0"] == pytest.approx(tr64.outputs["lam0"], rel=0.015)
    assert w32.controls["theta0"] == pytest.approx(w64.controls["theta0"], rel=0.015)


def test_low_frequency_inflow_gain(hover_single):
    # Quasi-steady momentum gain d lam0 / d CT = 1 / (4 lambda_h), lambda_h =
    # sqrt(CT / 2): the Pitt-Peters Lbar11 = 4 lambda_h against which the
    # dissertation compares its identified wake models (Table 4.1: MFW 0.187 vs
    # 0.214, i.e. a 14 % larger gain). Collective steps of +-0.02 rad from the same
    # trimmed wake, differenced (central, to cancel the quadratic part), averaged
    # over revolutions 3-8 once the wake has convected the change. Issue
    # requirement: within 30 %.
    w, tr = hover_single
    nrev = 2 * math.pi / w.omega
    up = w.run({"theta0": 0.02}, duration=8 * nrev)
    down = w.run({"theta0": -0.02}, duration=8 * nrev)
    late = up["t"] > 3 * nrev
    gain = (up["lam0"] - down["lam0"])[late].mean() / (up["CT"] - down["CT"])[late].mean()
    momentum = 1.0 / (4.0 * math.sqrt(tr.outputs["CT"] / 2.0))
    print(f"lam0/CT gain {gain:.3f}, momentum 1/(4 lam_h) {momentum:.3f}, ratio {gain / momentum:.3f}")
    assert abs(gain / momentum - 1) < 0.30


@pytest.fixture(scope="module")
def coaxial():
    w = FreeVortexWake(coaxial_compound(), WakeSettings(**COARSE))
    # tol: the coarse coaxial wake's revolution-averaged residuals scatter by
    # ~1e-4 (blade passage of both rotors' vortices; measured over 20 iterations),
    # so a tighter tolerance would only be met by chance
    tr = w.trim(ct=(0.0053, 0.0043), mode="torque_balance", tol=1e-4)
    return w, tr


def test_coaxial_torque_balance_and_inflow(coaxial):
    w, tr = coaxial
    o = tr.outputs
    assert tr.converged
    assert o["CT_U"] + o["CT_L"] == pytest.approx(0.0096, abs=1e-4)
    assert o["CQ_U"] == pytest.approx(o["CQ_L"], rel=0.05)     # torque balanced within 5 %
    assert o["lam0_L"] > o["lam0_U"]              # lower rotor works in the upper's wake
    # torque balance puts more thrust on the upper rotor (dissertation: 0.0053/0.0043)
    assert o["CT_U"] > o["CT_L"]


def test_coaxial_run_dataframe(coaxial):
    w, _ = coaxial
    df = w.run({"theta1s_L": lambda t: 0.02 * math.sin(10 * t)}, 0.3,
               points={"tail": (-7.5, 0.0, 0.0)})
    for c in ("t", "theta0_U", "theta1s_L", "CT_U", "CL_L", "CM_L", "lam0_U", "lam1s_L",
              "lam1c_L", "beta1s_dot_U", "beta1c_dot_L", "vx_tail", "vy_tail", "vz_tail"):
        assert c in df.columns
    assert df["theta1s_L"].abs().max() > 0.01
    # the lower rotor's lateral cyclic changes its own hub moments
    assert df["CL_L"].abs().max() + df["CM_L"].abs().max() > 1e-4
    with pytest.raises(ValueError, match="unknown control names"):
        w.run({"theta0": 0.1}, 0.1)


def test_sweep_driver_cache_with_sine(tmp_path):
    cfg = uh60_single_rotor()
    s = WakeSettings(azimuth_step=math.radians(20.0), wake_revolutions=1.5, n_elements=4)
    specs = [SweepSpec("theta0", kind="sine", amplitude=0.01, duration=0.3, w_min=5.0)]
    out1 = run_sweeps(cfg, s, FlightCondition(), specs, trim={"ct": 0.0061}, n_jobs=1,
                      cache_dir=tmp_path, progress=False)
    df = out1["sine_theta0"]
    assert isinstance(df, pd.DataFrame) and len(df) > 5
    files = list(tmp_path.glob("*.pkl"))
    assert len(files) == 2       # the run and the trim
    out2 = run_sweeps(cfg, s, FlightCondition(), specs, trim={"ct": 0.0061}, n_jobs=1,
                      cache_dir=tmp_path, progress=False)
    pd.testing.assert_frame_equal(out2["sine_theta0"], df)


def test_settings_validation():
    with pytest.raises(WakeSettingsError, match="divide 360"):
        WakeSettings(azimuth_step=math.radians(7.0))
    with pytest.raises(WakeSettingsError, match="kernel_precision"):
        WakeSettings(kernel_precision="half")
    with pytest.raises(WakeSettingsError, match="speed"):
        FlightCondition(speed=-1.0)



def _glauert_inflow(ct, mu, alpha):
    """Induced inflow of momentum theory in forward flight (Glauert), with KAPPA:
    lam_i = kappa CT / (2 sqrt(mu^2 + lam^2)), total inflow lam = lam_i - mu tan(alpha)
    (positive alpha tilts the disk back: the free stream flows up through it)."""
    mz = mu * math.tan(alpha)
    lam = 0.02
    for _ in range(200):
        lam = 0.5 * lam + 0.5 * (KAPPA * ct / (2.0 * math.hypot(mu, lam)) - mz)
    return lam + mz


def _ff_wake(cfg, mu=None, speed=None, alpha=math.radians(2.0)):
    rc = cfg.rotors[0]
    if speed is None:
        speed = mu * rc.omega * rc.radius / math.cos(alpha)
    s = WakeSettings(azimuth_step=math.radians(15.0), wake_revolutions=1.5, n_elements=6)
    return FreeVortexWake(cfg, s, FlightCondition(speed=speed, alpha=alpha))


def test_forward_flight_trim_converges():
    # Wind-tunnel trim at mu = 0.3, shaft tilted back 2 deg: thrust and zero hub
    # moments.  The forward-flight trim measures its Jacobian on the wake (the hover
    # blade-element estimate lacks the collective/cyclic coupling of forward flight).
    mu, alpha, ct = 0.3, math.radians(2.0), 0.0061
    w = _ff_wake(uh60_single_rotor(), mu=mu, alpha=alpha)
    tr = w.trim(ct=ct)
    o = tr.outputs
    assert tr.converged and tr.fd_jacobians >= 1
    assert tr.iterations <= 12            # measured 6
    assert o["CT"] == pytest.approx(ct, abs=2e-5)
    assert abs(o["CL"]) < 2e-5 and abs(o["CM"]) < 2e-5
    # Glauert momentum inflow, 15 % as in hover: measured 0.0116 vs 0.0117 (the
    # coarse wake is within 1-15 % of it from mu = 0.1 to 0.47)
    assert abs(o["lam0"] / _glauert_inflow(ct, mu, alpha) - 1) < 0.15
    # Hingeless rotor held unflapped: zero roll moment needs the classical lateral
    # cyclic theta1s = -(8/3) mu (theta75 - 3/4 lam) / (1 + 3/2 mu^2) (uniform
    # inflow, no root cut-out, no reverse flow), i.e. less pitch on the advancing
    # side.  Measured -4.5 deg vs -3.9 deg; 25 % for what the formula leaves out.
    lam_tot = o["lam0"] - mu * math.tan(alpha)
    th1s = -(8.0 / 3.0) * mu * (w.controls["theta0"] - 0.75 * lam_tot) / (1.0 + 1.5 * mu ** 2)
    assert w.controls["theta1s"] == pytest.approx(th1s, rel=0.25)


@pytest.mark.slow
def test_coaxial_torque_balance_trim_at_200_kt():
    # The case: coaxial compound at its cruise rotor speed, 200 kt (mu = 0.54),
    # shaft tilted back 2 deg, total thrust config.trim_ct, equal torques, zero hub
    # moments.  With the hover Jacobian estimate this trim oscillated with growing
    # amplitude (period 2, residual 1.5e-3 -> 2.9e-3 over 30 iterations).
    cfg = coaxial_compound(cruise=True)
    w = _ff_wake(cfg, speed=102.9)
    mu = 102.9 * math.cos(math.radians(2.0)) / (cfg.rotors[0].omega * cfg.rotors[0].radius)
    tr = w.trim(mode="torque_balance")
    o = tr.outputs
    assert tr.converged and tr.iterations <= 15      # measured 9
    assert o["CT_U"] + o["CT_L"] == pytest.approx(sum(cfg.trim_ct), abs=2e-5)
    for x in ("_U", "_L"):
        assert abs(o["CL" + x]) < 2e-5 and abs(o["CM" + x]) < 2e-5
    # torque balanced to 2 % (measured 0.2 %; CQ ~ 1e-4 near autorotation)
    assert o["CQ_U"] == pytest.approx(o["CQ_L"], rel=0.02)
    # Momentum brackets for two rotors 0.14 R apart in edgewise flight: each rotor's
    # inflow lies between Glauert's for its own thrust (isolated streamtubes) and
    # Glauert's for the pair's total thrust (one shared streamtube), the latter with
    # the 15 % allowed in hover. Measured 0.0083 / 0.0088 against 0.0051 and 0.0101.
    lam_shared = _glauert_inflow(o["CT_U"] + o["CT_L"], mu, math.radians(2.0))
    for x in ("_U", "_L"):
        lam_isolated = _glauert_inflow(o["CT" + x], mu, math.radians(2.0))
        assert lam_isolated < o["lam0" + x] < 1.15 * lam_shared
