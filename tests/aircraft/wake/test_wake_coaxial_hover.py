"""Trimmed coaxial hover of the free wake: steadiness and induced power.

Steadiness: with no input the trimmed hover inflow must be steady up to the blade
passage; any low-frequency fluctuation is noise on every identified response.

Induced power against momentum theory:

Definitions (hover, each rotor's own C_T, C_Q on rho pi R^2 (Omega R)^2 (R)):
    C_Pi = C_Q - sigma c_d0 / 8 (1 - x0^4)      induced power of one rotor
    kappa_int = C_Pi,coax / (C_Pi,iso(C_T,U) + C_Pi,iso(C_T,L))
with the isolated powers measured by the same wake on one rotor of the pair alone
(so tip loss, non-uniform inflow and the wake's own discretisation cancel).

Momentum theory brackets kappa_int for the trimmed thrust split:
* coplanar limit (both rotors on one disc): (T_U + T_L)^1.5 / (T_U^1.5 + T_L^1.5)
  = 1.41 for our split;
* lower rotor in the upper's fully developed slipstream (area A/2, velocity 2 v_U;
  the simple coaxial momentum theory of Leishman, Principles of Helicopter
  Aerodynamics, 2nd ed., and Leishman & Ananthan, AHS Forum 62, 2006, re-derived
  in _contracted_momentum_power): 1.28 for equal thrusts, 1.276 for our split,
  i.e. 0.905 of the ideal
  power of ONE disc carrying the total thrust. That ideal is therefore not a lower
  bound of a separated coaxial; the issue's "kappa_int ~ 0.91 < 1" compared the
  coaxial against a single disc at the total thrust with the UH-60's kappa, and sits
  at this momentum value.

Measured (this branch): default resolution kappa_int 1.297 (isolated kappa 1.13-1.14,
coaxial / single-disc ideal 1.051); test resolution 1.262 (1.130, 1.010).
"""
import dataclasses
import math

import pytest
from scipy.optimize import brentq

from aircraft.configs import coaxial_compound
from aircraft.wake import FreeVortexWake, WakeSettings

# every test here shares a fixture that takes seconds to build: not in the quick set (make test-quick)
pytestmark = pytest.mark.slow

COARSE = dict(azimuth_step=math.radians(15.0), wake_revolutions=2.0, n_elements=6)
#: bound on the relative rms of the revolution-averaged trimmed lambda0: measured
#: 0.09-0.14 % (12-revolution windows) with the filtered common buffer velocity,
#: 1.15-1.7 % on the main branch; 0.4 % sits 3x from each
THRESHOLD = 0.004


def _contracted_momentum_power(ct_u, ct_l):
    """Ideal induced power of the coaxial with the lower rotor (uniform loading) in
    the upper's fully contracted slipstream (area A/2, velocity 2 v_u) [-].

    Units rho A = 1, Omega R = 1: lower-rotor momentum and energy,
    T_l = m w - 2 v_u^2 and T_l (v_u + v_l) = m w^2 / 2 - 2 v_u^3 with
    m = v_u + v_l the lower rotor's mass flow.
    """
    vu = math.sqrt(ct_u / 2.0)

    def residual(vl):
        w = (ct_l + 2.0 * vu ** 2) / (vu + vl)
        return ct_l * (vu + vl) - (0.5 * (vu + vl) * w ** 2 - 2.0 * vu ** 3)
    vl = brentq(residual, 1e-9, 10.0 * vu)
    return ct_u * vu + ct_l * (vu + vl)


def test_contracted_momentum_closed_form():
    # equal thrusts: (1 + u)^2 + (1 + u) - 4 = 0, u = v_l / v_u, kappa_int = (2 + u) / 2
    u = (math.sqrt(17.0) - 1.0) / 2.0 - 1.0
    ideal = 2 * 0.005 ** 1.5 / math.sqrt(2)
    assert _contracted_momentum_power(0.005, 0.005) / ideal == pytest.approx((2 + u) / 2, rel=1e-9)


def _profile(rc):
    sigma = rc.n_blades * rc.chord / (math.pi * rc.radius)
    return sigma * rc.cd0 / 8.0 * (1.0 - rc.root_cutout ** 4)


@pytest.fixture(scope="module")
def coaxial_and_isolated():
    cfg = coaxial_compound()
    s = WakeSettings(**COARSE)
    w = FreeVortexWake(cfg, s)
    tr = w.trim(ct=(0.0053, 0.0043), mode="torque_balance", tol=1e-4)
    assert tr.converged
    nrev = 2 * math.pi / w.omega
    run = w.run(duration=12 * nrev)          # zero input, from the trimmed wake
    co = run.iloc[1:].mean()
    single = dataclasses.replace(cfg, rotors=(cfg.rotors[0],), trim_ct=(0.005,))
    iso = {}
    for x in ("_U", "_L"):
        wi = FreeVortexWake(single, s)
        assert wi.trim(ct=co["CT" + x]).converged
        iso[x] = wi.march(6 * s.steps_per_rev)
    return cfg, co, iso, run, s


def test_trimmed_coaxial_hover_inflow_is_steady(coaxial_and_isolated):
    # Relative rms of the revolution-averaged lambda0 of each rotor over 12 zero-input
    # revolutions (the average removes the 4/rev blade passage). The main branch's
    # wake (buffer convected at each rotor's own, instantaneous end-of-wake
    # velocity) measured 1.3-1.6 % here, with a spectral peak at 10 rad/s (2.4 rev
    # period; 6 rad/s = 4 rev at the default 4 free revolutions) that scaled with
    # the wake length; see aircraft/wake/far_wake.py and WakeSettings.
    *_, run, s = coaxial_and_isolated
    n = s.steps_per_rev
    for x in ("_U", "_L"):
        lam = run["lam0" + x].to_numpy()[1:]
        per_rev = lam[:lam.size // n * n].reshape(-1, n).mean(axis=1)
        rel = per_rev.std() / per_rev.mean()
        print(f"lam0{x}: revolution-average relative rms {100 * rel:.2f} %")
        assert rel < THRESHOLD


def test_coaxial_induced_power_within_momentum_interference_range(coaxial_and_isolated):
    cfg, co, iso, *_ = coaxial_and_isolated
    cp0 = _profile(cfg.rotors[0])
    ct_u, ct_l = co["CT_U"], co["CT_L"]
    p_coax = co["CQ_U"] + co["CQ_L"] - 2 * cp0
    p_iso = (iso["_U"]["CQ_U"] - cp0) + (iso["_L"]["CQ_U"] - cp0)   # one rotor named U
    kappa_int = p_coax / p_iso
    iso_ideal = (ct_u ** 1.5 + ct_l ** 1.5) / math.sqrt(2)
    single_ideal = (ct_u + ct_l) ** 1.5 / math.sqrt(2)
    lower = _contracted_momentum_power(ct_u, ct_l) / iso_ideal     # 1.276
    upper = single_ideal / iso_ideal                              # 1.410
    kappa_iso = p_iso / iso_ideal
    print(f"kappa_int {kappa_int:.3f} in [{lower:.3f}, {upper:.3f}]; isolated kappa "
          f"{kappa_iso:.3f}; coaxial / single-disc ideal {p_coax / single_ideal:.3f}")
    # 3 % below the contracted bound: the revolution-averaged torques scatter by
    # ~1 % per rotor at this resolution (three trims, each differenced)
    assert 0.97 * lower < kappa_int < upper
    # against the ideal of one disc at the total thrust the wake's coaxial (with its
    # own non-ideal losses, kappa_iso ~ 1.1-1.2) needs more power: >= 1
    assert p_coax / single_ideal >= 1.0
