"""Real blades in the wake's blade solve, against hand blade-element sums.

The wake's own vortices are switched off (zero strengths) and a uniform inflow V
is imposed as an axial free stream, so that every element sees U_T = Omega r R and
U_P = V: the blade solve then has to reproduce the blade-element thrust and torque
integrated by hand from the planform, the polar and the tip loss.
"""
import math

import numpy as np
import pytest

from aircraft.blade import BladeModel, Polar, naca4_symmetric_drag
from aircraft.configs import AircraftConfig, ConfigError, RotorConfig
from aircraft.wake import FreeVortexWake, WakeSettings
from aircraft.wake.blades import solve_blades

R, OMEGA, NB, RHO = 5.0, 40.0, 3, 1.225
V = 4.0          # imposed uniform inflow [m/s], down through the disc
THETA0 = math.radians(8.0)


def _config(blade, root_cutout=0.2, chord=0.3, twist=0.0):
    rot = RotorConfig(name="", radius=R, omega=OMEGA, n_blades=NB, chord=chord, twist=twist,
                      root_cutout=root_cutout, hinge_offset=0.0, blade=blade)
    return AircraftConfig(name="t", rotors=(rot,), mass=1000.0, Ixx=1.0, Iyy=1.0, Izz=1.0, rho=RHO)


def _uniform_inflow_loads(config, n_elements=10):
    """(CT, CQ, element radii, edges) of the blade solve with uniform inflow V only."""
    wake = FreeVortexWake(config, WakeSettings(azimuth_step=math.radians(20.0), wake_revolutions=1.0,
                                               n_elements=n_elements, far_wake_revolutions=2.0))
    a, b, g, rc = wake._tip_sources()
    aa, bb, rcc, gmap = wake._attached_segments()
    wake._tip_sources = lambda X=None: (a, b, np.zeros_like(g), rc)          # no tip vortices
    wake._attached_segments = lambda: (aa, bb, rcc, np.zeros_like(gmap))     # no bound/near wake
    wake.v_inf = np.array([0.0, 0.0, -V])      # computational z is up: air flows down
    wake.controls["theta0"] = THETA0
    out = solve_blades(wake)[""]
    rot = wake.rotors[0]
    return out["CT"], out["CQ"], rot.r, rot.r_edge


def _coefficients(dT, dQr):
    """Hand sums of the elements' thrust [N] and torque [N m] of one blade, times N_b."""
    scale = RHO * math.pi * R ** 2 * (OMEGA * R) ** 2
    return NB * dT.sum() / scale, NB * dQr.sum() / (scale * R)


def test_planform_polar_and_tip_loss_match_a_hand_blade_element_sum():
    # chord tapering 0.4 -> 0.2 m, a kinked twist, a polar with a stall plateau, B = 0.95
    polar = Polar(alpha=(-0.4, -0.2, 0.0, 0.1, 0.2, 0.4), cl=(-1.0, -1.1, 0.0, 0.6, 1.1, 1.0),
                  cd=(0.10, 0.03, 0.008, 0.010, 0.025, 0.12))
    blade = BladeModel(stations=(0.2, 0.6, 1.0), chord=(0.4, 0.3, 0.2),
                       twist=(0.05, 0.0, -0.08), polar=polar, tip_loss=0.95)
    ct, cq, r, edge = _uniform_inflow_loads(_config(blade))
    # hand: the tables written out, linear between stations
    chord = np.where(r < 0.6, 0.4 - 0.25 * (r - 0.2), 0.3 - 0.25 * (r - 0.6))
    tw = np.where(r < 0.6, 0.05 - 0.125 * (r - 0.2), -0.2 * (r - 0.6))
    pitch = THETA0 + tw - (-0.2 * 0.15)                 # twist(0.75) = -0.03 rad
    ut, up = OMEGA * R * r, V
    alpha = pitch - up / ut
    cl, cd = np.interp(alpha, polar.alpha, polar.cl), np.interp(alpha, polar.alpha, polar.cd)
    lifting = np.clip((0.95 - edge[:-1]) / np.diff(edge), 0.0, 1.0)   # share of the element inboard of B
    assert lifting[-1] < 1.0 and lifting[0] == 1.0       # the tip element is cut, the root one is not
    gamma = 0.5 * chord * cl * ut * lifting              # Kutta-Joukowski: L' = rho U Gamma
    drdim = np.diff(edge) * R
    dT = RHO * gamma * ut * drdim
    dQr = (RHO * gamma * up + 0.5 * RHO * (ut ** 2 + up ** 2) * chord * cd) * drdim * r * R
    ct_hand, cq_hand = _coefficients(dT, dQr)
    # the same sums in another order: only round-off may differ
    assert ct == pytest.approx(ct_hand, rel=1e-12)
    assert cq == pytest.approx(cq_hand, rel=1e-12)


def test_linear_polar_gives_the_closed_form_blade_element_integrals():
    # constant chord, untwisted, c_l = a alpha, c_d = delta0: with U_P = V everywhere
    # CT = sigma a / 2 [theta (1 - r0^3)/3 - lam (1 - r0^2)/2] and
    # CQ = lam CT_inner + sigma delta0 / 2 int (r^2 + lam^2) r dr, lam = V / (Omega R)
    a, d0, c, r0 = 5.5, 0.011, 0.3, 0.2
    polar = Polar(alpha=(-0.5, 0.5), cl=(-0.5 * a, 0.5 * a), cd=(d0, d0))
    ct, cq, _, _ = _uniform_inflow_loads(_config(BladeModel(polar=polar), root_cutout=r0, chord=c),
                                         n_elements=40)
    sigma, lam = NB * c / (math.pi * R), V / (OMEGA * R)
    ct_exact = sigma * a / 2 * (THETA0 * (1 - r0 ** 3) / 3 - lam * (1 - r0 ** 2) / 2)
    cq_induced = sigma * a / 2 * lam * (THETA0 * (1 - r0 ** 3) / 3 - lam * (1 - r0 ** 2) / 2)
    cq_profile = sigma * d0 / 2 * ((1 - r0 ** 4) / 4 + lam ** 2 * (1 - r0 ** 2) / 2)
    # 40 midpoint panels of width 0.02: the midpoint rule's error on int r^2 dr is
    # (1 - r0) h^2 / 12 ~ 3e-5 against ~0.33, i.e. ~1e-4 relative; 1e-3 leaves margin
    assert ct == pytest.approx(ct_exact, rel=1e-3)
    assert cq == pytest.approx(cq_induced + cq_profile, rel=1e-3)


def test_thickness_default_drag_and_compressibility_against_the_hand_formula():
    blade = BladeModel(stations=(0.2, 1.0), thickness=(0.30, 0.15), compressibility=True)
    lift_slope, stall = 5.73, math.radians(12.0)
    ct, cq, r, edge = _uniform_inflow_loads(_config(blade))
    chord, nu = 0.3, WakeSettings().kinematic_viscosity
    ut, up = OMEGA * R * r, V
    t = 0.30 - 0.15 * (r - 0.2) / 0.8
    re = ut * chord / nu
    cf = 0.455 / np.log10(re) ** 2.58                         # Prandtl-Schlichting, written out
    alpha = THETA0 - up / ut
    cd = 2 * cf * (1 + 2 * t + 60 * t ** 4) - 0.0216 * np.abs(alpha) + 0.400 * alpha ** 2
    beta_pg = 1.0 / np.sqrt(1.0 - (ut / 340.3) ** 2)          # Prandtl-Glauert
    gamma = 0.5 * chord * lift_slope * beta_pg * np.clip(alpha, -stall, stall) * ut
    drdim = np.diff(edge) * R
    dT = RHO * gamma * ut * drdim
    dQr = (RHO * gamma * up + 0.5 * RHO * (ut ** 2 + up ** 2) * chord * cd) * drdim * r * R
    ct_hand, cq_hand = _coefficients(dT, dQr)
    assert ct == pytest.approx(ct_hand, rel=1e-12)            # same sums, other order: round-off
    assert cq == pytest.approx(cq_hand, rel=1e-12)


def test_an_empty_blade_model_is_the_classical_blade():
    # BladeModel() sets nothing: chord, twist, lift slope and cd0 come from the rotor
    ct0, cq0, _, _ = _uniform_inflow_loads(_config(None, twist=math.radians(-10.0)))
    ct1, cq1, _, _ = _uniform_inflow_loads(_config(BladeModel(), twist=math.radians(-10.0)))
    # the same products in another association: round-off only
    assert ct1 == pytest.approx(ct0, rel=1e-12)
    assert cq1 == pytest.approx(cq0, rel=1e-12)


def test_thickness_drag_default_brackets_bailey_naca0012_polar():
    # Bailey (NACA Rep. 716) rotor-blade NACA 0012, practical construction: c_d0 = 0.0087;
    # the turbulent form-factor default must give it within 6 % over Re = 3-5 million
    for re in (3e6, 4e6, 5e6):
        assert naca4_symmetric_drag(0.0, 0.12, re) == pytest.approx(0.0087, rel=0.06)
    # thicker is draggier, higher Reynolds number less so
    assert naca4_symmetric_drag(0.0, 0.20, 3e6) > naca4_symmetric_drag(0.0, 0.12, 3e6)
    assert naca4_symmetric_drag(0.0, 0.12, 6e6) < naca4_symmetric_drag(0.0, 0.12, 2e6)


@pytest.mark.parametrize("kwargs, field", [
    (dict(chord=(0.3, 0.2)), "BladeModel.chord needs BladeModel.stations"),
    (dict(stations=(0.2, 0.1), chord=(0.3, 0.2)), "BladeModel.stations"),
    (dict(stations=(0.2, 1.0), chord=(0.3, -0.2)), "BladeModel.chord"),
    (dict(stations=(0.2, 1.0), chord=(0.3,)), "BladeModel.chord needs 2"),
    (dict(stations=(0.2, 1.0), thickness=(0.3, 0.7)), "BladeModel.thickness"),
    (dict(tip_loss=0.5), "BladeModel.tip_loss"),
    (dict(compressibility="yes"), "BladeModel.compressibility"),
    (dict(stations=(0.2, 1.0), thickness=(0.3, 0.15),
          polar=Polar(alpha=(-1, 1), cl=(-1, 1), cd=(0.1, 0.1))), "either polar"),
])
def test_bad_blade_inputs_name_the_field(kwargs, field):
    with pytest.raises(ValueError, match=field):
        BladeModel(**kwargs)


def test_bad_polar_and_rotor_blade_are_refused():
    with pytest.raises(ValueError, match="Polar.alpha"):
        Polar(alpha=(0.1, 0.0), cl=(0.0, 0.0), cd=(0.0, 0.0))
    with pytest.raises(ValueError, match="Polar.cd"):
        Polar(alpha=(0.0, 0.1), cl=(0.0, 0.5), cd=(0.01, -0.01))
    with pytest.raises(ConfigError, match="RotorConfig.blade"):
        RotorConfig(name="", radius=R, omega=OMEGA, n_blades=NB, chord=0.3, twist=0.0,
                    root_cutout=0.2, blade={"tip_loss": 0.97})
