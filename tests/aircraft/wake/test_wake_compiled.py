"""The compiled/vectorised pieces of the wake march against the former numpy march.

Each compiled helper performs the same IEEE-754 operations, in the same order, as
the numpy code it replaces (:mod:`aircraft.wake.reference`, ``far_wake._helix_reference``
and the unchained Biot-Savart pair loop), without ``fastmath``. The tests hold
them to bit equality where both sides are compiled code (the two Biot-Savart pair
loops: nothing but IEEE arithmetic on the same numbers). Where numpy computes the
sines and cosines of differently shaped arrays (the blade loop of the reference
against one call for all blades), a libm or SIMD path could in principle round
the last bit differently on another machine; there the tolerance is a few units
in the last place of the coordinates (1e-12 m on positions of ~10 m, i.e.
~1e-13 relative: about 500 ulp of headroom, far below any physical scale), and
on this project's machines the results are in fact equal bit for bit.
"""
import math

import numpy as np
import pytest

from aircraft.configs import coaxial_compound
from aircraft.wake import FlightCondition, FreeVortexWake, WakeSettings
from aircraft.wake.biot_savart import segment_velocity
from aircraft.wake.far_wake import _helix, _helix_reference
from aircraft.wake.kinematics import near_wake_points
from aircraft.wake.reference import attached_segments_reference, near_wake_points_reference

COARSE = dict(azimuth_step=math.radians(20.0), wake_revolutions=1.5, n_elements=4)
ATOL_M = 1e-12     # [m]: see the module docstring


def _random_state(wake, seed):
    """Put the blades of ``wake`` at a random azimuth, flap and inflow."""
    rng = np.random.default_rng(seed)
    wake.psi = float(rng.uniform(0.0, 2.0 * math.pi))
    for ir, rot in enumerate(wake.rotors):
        wake.beta[ir] = rng.uniform(-0.1, 0.1, size=rot.nb)
        wake._lam0[ir] = float(rng.uniform(0.0, 0.1))
    return rng


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("contraction", [False, True])
def test_near_wake_points_match_reference(seed, contraction):
    w = FreeVortexWake(coaxial_compound(), WakeSettings(near_wake_contraction=contraction, **COARSE))
    _random_state(w, seed)
    for ir in range(len(w.rotors)):
        new = w._near_wake_points(ir, w.psi, w.beta[ir])
        ref = near_wake_points_reference(w, ir, w.psi, w.beta[ir])
        assert new.shape == ref.shape
        np.testing.assert_allclose(new, ref, rtol=0.0, atol=ATOL_M)


def test_near_wake_points_direct_call():
    """The public helper on random inputs (both senses of rotation) against a
    plain evaluation of the reference formula."""
    rng = np.random.default_rng(5)
    for direction in (1, -1):
        hub = rng.normal(size=3)
        r_edge = np.sort(rng.uniform(0.1, 1.0, size=6))
        psib = rng.uniform(0, 2 * np.pi, size=3)
        beta = rng.uniform(-0.1, 0.1, size=3)
        ages = np.arange(5) * 0.2
        contraction = rng.uniform(0.8, 1.0, size=5)
        drift = rng.normal(size=3)
        got = near_wake_points(hub, 7.0, 0.05, direction, r_edge, psib, beta, ages, contraction,
                               drift, 30.0)
        for m, age in enumerate(ages):
            ang = psib - age
            er = np.stack([-np.cos(ang), -direction * np.sin(ang), np.zeros_like(ang)], axis=1)
            span = np.cos(beta)[:, None] * er + np.sin(beta)[:, None] * np.array([0.0, 0.0, 1.0])
            p = hub + 7.0 * 0.05 * er[:, None, :] + 7.0 * (r_edge[None, :, None] - 0.05) * span[:, None, :]
            p[..., :2] = hub[:2] + contraction[m] * (p[..., :2] - hub[:2])
            np.testing.assert_allclose(got[:, :, m], p + drift * age / 30.0, rtol=0.0, atol=ATOL_M)


@pytest.mark.parametrize("seed", [0, 1])
def test_attached_segments_match_reference(seed):
    w = FreeVortexWake(coaxial_compound(), WakeSettings(**COARSE))
    _random_state(w, seed)
    a, b, rc, gmap = w._attached_segments()
    ra, rb, rrc, rgmap = attached_segments_reference(w)
    np.testing.assert_allclose(a, ra, rtol=0.0, atol=ATOL_M)
    np.testing.assert_allclose(b, rb, rtol=0.0, atol=ATOL_M)
    assert np.array_equal(rc, rrc) and np.array_equal(gmap, rgmap)


@pytest.mark.parametrize("seed", [0, 1])
def test_helix_matches_reference(seed):
    w = FreeVortexWake(coaxial_compound(), WakeSettings(**COARSE),
                       FlightCondition(speed=15.0, alpha=-0.05))
    _random_state(w, seed)
    for ir in range(len(w.rotors)):
        p, g = _helix(w, ir, w.X[ir], 9, 2)
        rp, rg = _helix_reference(w, ir, w.X[ir], 9, 2)
        np.testing.assert_allclose(p, rp, rtol=0.0, atol=ATOL_M)
        assert np.array_equal(g, rg)


@pytest.mark.parametrize("precision", ["single", "double"])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_chained_kernel_bit_identical(precision, seed):
    """Chains, broken chains, single segments and a target count that is not a
    multiple of the kernel's lane block: the chained pair loop equals the plain
    one bit for bit (the reused 1/|P - A| is the same computation)."""
    rng = np.random.default_rng(seed)
    chain = 10.0 + rng.normal(size=(40, 3))
    a = np.concatenate([chain[:-1], rng.normal(size=(7, 3)), chain[5:20]])
    b = np.concatenate([chain[1:], rng.normal(size=(7, 3)), chain[6:21]])
    gamma = rng.normal(size=a.shape[0])
    rc = rng.uniform(0.01, 0.1, size=a.shape[0])
    targets = np.concatenate([10.0 + rng.normal(size=(37, 3)), chain[:3]])  # on a node too
    got = segment_velocity(targets, a, b, gamma, rc, precision)
    want = segment_velocity(targets, a, b, gamma, rc, precision, chained=False)
    assert np.array_equal(got, want)


@pytest.mark.parametrize("flight", [None, FlightCondition(speed=20.0, alpha=-0.05)])
def test_march_matches_reference_march(flight):
    """A few coaxial steps (hover; forward flight with prescribed flapping inputs)."""
    cfg = coaxial_compound()
    free = flight is None
    s = WakeSettings(free_flapping=free, near_wake_contraction=free, **COARSE)
    runs = []
    for w in (FreeVortexWake(cfg, s, flight), FreeVortexWake._reference_march(cfg, s, flight)):
        w.controls.update(theta0_U=0.15, theta0_L=0.16, theta1s_U=0.02)
        if not free:
            w.set_flap_inputs({"beta1s_U": 0.01}, {"beta1c_L": 0.02})
        rows = [list(w.march(1).values()) for _ in range(6)]
        runs.append((np.array(rows), np.concatenate([x.ravel() for x in w.X])))
    (out, x), (rout, rx) = runs
    np.testing.assert_allclose(out, rout, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(x, rx, rtol=0.0, atol=ATOL_M)
