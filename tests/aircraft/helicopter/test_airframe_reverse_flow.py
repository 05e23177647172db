"""Fuselage cross-flow drag and lift, tail-rotor momentum theory and reverse-flow
blade sections, each against a hand calculation."""
import dataclasses
import math

import numpy as np
import pytest

from aircraft import coaxial_compound, uh60_single_rotor
from aircraft.configs import ConfigError, TailRotorConfig
from aircraft.helicopter.airframe import fuselage_loads, tail_rotor_loads
from aircraft.helicopter.rotor import RotorModel

RHO = 1.225


def _bare(cfg, **kw):
    """The aircraft without tails, so the fuselage terms stand alone."""
    return dataclasses.replace(cfg, htail_area=0.0, vtail_area=0.0, **kw)


def test_vertical_flat_plate_is_a_cross_flow_drag_not_a_lifting_surface():
    cfg = _bare(coaxial_compound())                     # f_x 2.5 m^2, f_z 20 m^2
    u, w = 200 * 0.514444, -3.6                          # 200 kt, 2 deg nose down
    f, m = fuselage_loads(cfg, [u, 0.0, w], [0.0, 0.0, 0.0])
    speed = math.hypot(u, w)
    # by hand: F_x = -1/2 rho f_x |V| u; F_z = -1/2 rho f_z |w| w = +158.8 N (down), not the
    # 4.5 kN of -1/2 rho f_z |V| w; exact formulas, so round-off only
    assert f[0] == pytest.approx(-0.5 * RHO * 2.5 * speed * u, rel=1e-12)
    assert f[2] == pytest.approx(0.5 * RHO * 20.0 * 3.6 ** 2, rel=1e-12)
    assert f[2] == pytest.approx(158.76, abs=0.01)
    assert f[1] == 0.0 and np.all(m == 0.0)


def test_cross_flow_uses_the_cross_flow_speed_in_sideslip():
    cfg = _bare(coaxial_compound())
    f, _ = fuselage_loads(cfg, [50.0, 3.0, 4.0], [0.0, 0.0, 0.0])
    # |v_c| = sqrt(3^2 + 4^2) = 5: F_y = -1/2 rho 20 * 5 * 3 = -183.75 N, F_z = -245 N
    assert f[1] == pytest.approx(-183.75, rel=1e-12)
    assert f[2] == pytest.approx(-245.0, rel=1e-12)


def test_fuselage_lift_has_its_own_area():
    cfg = _bare(coaxial_compound(), fuselage_lift_area=2.0)
    u, w = 50.0, 2.0
    f, _ = fuselage_loads(cfg, [u, 0.0, w], [0.0, 0.0, 0.0])
    f0, _ = fuselage_loads(_bare(coaxial_compound()), [u, 0.0, w], [0.0, 0.0, 0.0])
    alpha = math.atan(w / u)
    lift = 0.5 * RHO * (u * u + w * w) * 2.0 * alpha   # 49.06 N
    # lift normal to the x-z velocity, upward for wind from below (alpha > 0)
    assert f[0] - f0[0] == pytest.approx(lift * w / math.hypot(u, w), rel=1e-12)
    assert f[2] - f0[2] == pytest.approx(-lift * u / math.hypot(u, w), rel=1e-12)
    with pytest.raises(ConfigError, match="fuselage_lift_area"):
        dataclasses.replace(cfg, fuselage_lift_area=-1.0)


def test_tail_rotor_hover_thrust_and_inflow_derivative_match_momentum_theory():
    tr = TailRotorConfig()
    theta = math.radians(12.0)
    f, power = tail_rotor_loads(tr, theta, [0.0, 0.0, 0.0], RHO)
    scale = RHO * tr.disk_area * tr.tip_speed ** 2
    k = tr.solidity * tr.lift_slope / 4
    # hover, collective at 3/4 radius: C_T = K (2 theta / 3 - lam) = 2 lam^2, a quadratic in lam
    lam = (-k + math.sqrt(k * k + 16 * k * theta / 3)) / 4
    ct = 2 * lam ** 2
    assert f[1] / scale == pytest.approx(ct, rel=1e-10)
    cq = ct * lam + tr.solidity * tr.cd0 / 8
    assert power == pytest.approx(cq * scale * tr.radius * tr.omega, rel=1e-10)
    # axial flow: dC_T/dmu_c = -2 lam K / (K + 4 lam) at mu = 0; central difference O(h^2)
    h = 1e-3
    fp, _ = tail_rotor_loads(tr, theta, [0.0, h, 0.0], RHO)
    fm, _ = tail_rotor_loads(tr, theta, [0.0, -h, 0.0], RHO)
    slope = (fp[1] - fm[1]) / (2 * h) / scale * tr.tip_speed
    assert slope == pytest.approx(-2 * lam * k / (k + 4 * lam), rel=1e-6)
    # the mirror-image tail rotor thrusts to port
    fl, _ = tail_rotor_loads(dataclasses.replace(tr, thrust_sign=-1), theta, [0.0, 0.0, 0.0], RHO)
    assert fl[1] == pytest.approx(-f[1], rel=1e-14)


def test_tail_rotor_in_edgewise_flow_matches_glauert():
    tr = TailRotorConfig()
    theta, v = math.radians(6.0), 40.0
    f, _ = tail_rotor_loads(tr, theta, [v, 0.0, 0.0], RHO)
    mu = v / tr.tip_speed
    sa = tr.solidity * tr.lift_slope
    ct = f[1] / (RHO * tr.disk_area * tr.tip_speed ** 2)
    lam = ct / (2 * mu)                  # first guess, refined below
    for _ in range(50):   # Glauert: C_T = 2 lam sqrt(mu^2 + lam^2), solved by fixed point
        lam = ct / (2 * math.sqrt(mu * mu + lam * lam))
    th0 = theta - 0.75 * tr.twist
    be = sa / 2 * (th0 * (1 / 3 + mu * mu / 2) + tr.twist * (1 + mu * mu) / 4 - lam / 2)
    assert ct == pytest.approx(be, rel=1e-9)


def test_tail_rotor_config_is_checked():
    with pytest.raises(ConfigError, match="thrust_sign"):
        TailRotorConfig(thrust_sign=0)
    with pytest.raises(ConfigError, match="moment arm"):
        TailRotorConfig(position=(0.0, 0.0, -1.0))
    with pytest.raises(ConfigError, match="only a single-rotor aircraft"):
        dataclasses.replace(coaxial_compound(), tail_rotor=TailRotorConfig())


def _flat_rotor(mu):
    """Untwisted rotor at zero pitch, no inflow, no flapping, edgewise flow at ``mu``."""
    rc = dataclasses.replace(uh60_single_rotor().rotors[0], twist=0.0)
    rm = RotorModel(rc, n_span=8, n_average=4)
    out = rm.evaluate(np.zeros(4), np.zeros(4), np.zeros(3), np.zeros(3),
                      np.array([mu * rc.tip_speed, 0.0, 0.0]), np.zeros(3))
    return rc, rm, out


def test_a_flat_blade_edgewise_carries_no_lift_in_reverse_flow():
    # mu = 0.8 puts the inner 80 % of the retreating blade in reverse flow (x < mu sin psi)
    rc, rm, out = _flat_rotor(0.8)
    assert np.min(rm.r) < 0.8     # the Gauss points do reach into the reverse-flow circle
    # every section sees its chord edge-on (normal velocity exactly zero): zero lift, only
    # profile drag in the disc plane, whichever edge the air meets (without the wrap the
    # reversed sections sat at -180 deg, clipped to the stall angle: c_l,max of one sign)
    assert out["ct"] == 0.0
    assert out["cl"] == 0.0 and out["cm"] == 0.0


def test_reverse_flow_section_angle_is_the_flat_plate_angle():
    # one blade at psi = 270 deg (retreating) with mu = 0.8: at r = 0.4 the air meets the
    # trailing edge at U_T = Omega R (0.4 - 0.8) < 0. A small climb gives a normal velocity
    # U_P; the flat-plate normal force then opposes the flow through the disc, with the
    # angle of attack atan(U_P / |U_T|) (wrapped into +-90 deg): check the thrust sign and size
    rc = dataclasses.replace(uh60_single_rotor().rotors[0], twist=0.0)
    rm = RotorModel(rc, n_span=8, n_average=4)
    vt = rc.tip_speed
    climb = 0.02 * vt                     # hub moving up: air flows down through the disc
    base = rm.evaluate(np.zeros(4), np.zeros(4), np.zeros(3), np.zeros(3),
                       np.array([0.8 * vt, 0.0, 0.0]), np.zeros(3))
    up = rm.evaluate(np.zeros(4), np.zeros(4), np.zeros(3), np.zeros(3),
                     np.array([0.8 * vt, 0.0, -climb]), np.zeros(3))
    # every section, normal or reversed, now sees the air from above: the normal force on a
    # flat plate pushes down (negative thrust) -- with the old clip the reversed sections
    # (U_T < 0, inflow angle near 180 deg) pushed up at full c_l,max
    assert up["ct"] < base["ct"] == 0.0
    # hand check of the size: every section has c_l = a atan(U_P / |U_T|) (clipped) normal to the
    # flow, with the drag along it
    psi = rm.psi_ref[:, None] + rm.blade_offsets[None, :]
    ut = vt * (rm.r[None, None, :] + 0.8 * np.sin(psi)[..., None])
    alpha = np.minimum(np.arctan(climb / np.abs(ut)), rc.stall_angle)
    u = np.hypot(ut, climb)
    # lift normal to the relative wind, its thrust share |U_T| / U; drag's thrust share -U_P / U
    dt = 0.5 * RHO * rc.chord * u ** 2 * (rc.lift_slope * alpha * np.abs(ut) / u + rc.cd0 * climb / u)
    thrust = -(dt * rm.wr[None, None, :]).sum(axis=(1, 2)).mean()
    assert up["ct"] == pytest.approx(thrust / rm.scale_t, rel=1e-9)
