"""The blade-element propeller: the classical small-angle annulus solution in its limit, the
exact-angle element loads when the induced velocity vanishes, and the opt-in setting."""
import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import quad

from aircraft import coaxial_compound
from aircraft.configs import PropellerConfig
from aircraft.helicopter import Helicopter, HelicopterSettings
from aircraft.helicopter.airframe import propeller_loads
from aircraft.helicopter.propeller import propeller_blade_element
from aircraft.inflow import IsolatedRotors

RHO = 1.225


def coefficients(prop, thrust, torque):
    scale = RHO * math.pi * prop.radius ** 2 * (prop.omega * prop.radius) ** 2
    return thrust / scale, torque / (scale * prop.radius)


def test_small_angle_limit_is_the_classical_annulus_solution():
    # untwisted, drag-free blades at static thrust: the classical annulus solution has
    # lambda(r) ~ theta r near the axis, so every inflow angle is below theta and the exact
    # angles differ from the small-angle ones by O(theta^2)
    prop = dataclasses.replace(PropellerConfig(), twist=0.0, cd0=0.0)
    sa = prop.solidity * prop.lift_slope
    errors = []
    for theta in (math.radians(4.0), math.radians(2.0)):
        b = sa / 16

        def lam(r):   # Leishman, Principles of Helicopter Aerodynamics, Eq. 3.59 (lambda_c = 0)
            return math.sqrt(b ** 2 + sa * theta * r / 8) - b

        ct_hand = quad(lambda r: 4 * lam(r) ** 2 * r, 0, 1)[0]
        ct, _ = coefficients(prop, *propeller_blade_element(prop, theta, 0.0, RHO))
        errors.append(ct / ct_hand - 1)
    # theta^2 = 0.5 % at 4 deg
    assert abs(errors[0]) < 5e-3
    # and it is a higher-order difference of the angles: halving theta cuts it by more than
    # half (O(theta^2) alone would quarter it; measured 0.34)
    assert 0 < errors[1] < 0.45 * errors[0]


def test_lightly_loaded_blades_have_the_exact_angle_element_loads():
    # solidity 1e-6: the induced velocity (~ sigma) is negligible, so each element sees
    # phi = atan(mu / r) and the loads are the element integrals, evaluated here by quad at
    # the cruise pitch of 45 deg with the -30 deg twist (local angles to 60 deg)
    prop = dataclasses.replace(PropellerConfig(), solidity=1e-6)
    theta, mu = math.radians(45.0), 0.38
    a, cd = prop.lift_slope, prop.cd0

    def element(r, torque):
        phi = math.atan2(mu, r)
        cl = a * (theta + prop.twist * (r - 0.75) - phi)
        u2 = r * r + mu * mu
        if torque:
            return 0.5 * u2 * (cl * math.sin(phi) + cd * math.cos(phi)) * r
        return 0.5 * u2 * (cl * math.cos(phi) - cd * math.sin(phi))

    ct_hand = prop.solidity * quad(element, 0, 1, args=(False,))[0]
    cq_hand = prop.solidity * quad(element, 0, 1, args=(True,))[0]
    ct, cq = coefficients(prop, *propeller_blade_element(prop, theta, mu * prop.omega * prop.radius, RHO))
    # relative error of the neglected induced velocity ~ sigma a / mu ~ 2e-5
    assert ct == pytest.approx(ct_hand, rel=1e-4)
    assert cq == pytest.approx(cq_hand, rel=1e-4)
    # the small-angle uniform-inflow formula is far off there (its thrust is about a third lower)
    ct_small, _ = coefficients(prop, *propeller_loads(prop, theta, mu * prop.omega * prop.radius, RHO))
    assert abs(ct_small / ct_hand - 1) > 0.2


def test_loads_are_smooth_for_linearisation():
    # the Newton solution converges to round-off: central differences at two steps agree
    prop = PropellerConfig()
    f = lambda th: propeller_blade_element(prop, th, 100.0, RHO)[0]
    th = math.radians(40.0)
    d1 = (f(th + 1e-4) - f(th - 1e-4)) / 2e-4
    d2 = (f(th + 1e-5) - f(th - 1e-5)) / 2e-5
    # truncation error O(h^2) of a function with O(1) curvature on the rad scale
    assert d1 == pytest.approx(d2, rel=1e-5)


def test_the_setting_selects_the_model_and_the_default_is_unchanged():
    cfg = coaxial_compound(cruise=True)
    x = np.zeros(len(Helicopter(cfg, IsolatedRotors()).state_names))
    x[0] = 90.0
    u = np.array([0.2, 0.0, 0.0, 0.2, 0.0, 0.0, math.radians(40.0)])
    default = Helicopter(cfg, IsolatedRotors())
    be = Helicopter(cfg, IsolatedRotors(), HelicopterSettings(propeller_model="blade_element"))
    xd_default, xd_be = default.evaluate(x, u)[0], be.evaluate(x, u)[0]
    thrust_mom = propeller_loads(cfg.propeller, u[6], 90.0, cfg.rho)[0]
    thrust_be = propeller_loads(cfg.propeller, u[6], 90.0, cfg.rho, model="blade_element")[0]
    # only the propeller force differs: u_dot changes by the thrust difference over the mass
    assert xd_be[0] - xd_default[0] == pytest.approx((thrust_be - thrust_mom) / cfg.mass, rel=1e-9)


def test_bad_models_and_arguments_are_refused():
    with pytest.raises(ValueError, match="propeller_model"):
        HelicopterSettings(propeller_model="vortex")
    with pytest.raises(ValueError, match="model must be one of"):
        propeller_loads(PropellerConfig(), 0.1, 50.0, RHO, model="vortex")
    with pytest.raises(ValueError, match="forward_speed"):
        propeller_blade_element(PropellerConfig(), 0.1, float("nan"), RHO)
    with pytest.raises(ValueError, match="rho"):
        propeller_blade_element(PropellerConfig(), 0.1, 50.0, 0.0)
