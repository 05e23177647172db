"""Biot-Savart kernel of aircraft.wake: compiled vs numpy, and closed forms."""
import math

import numpy as np
import pytest

from aircraft.wake import segment_velocity, segment_velocity_numpy, core_radius


def test_compiled_matches_numpy_reference():
    rng = np.random.default_rng(1)
    tg = rng.normal(size=(50, 3))
    a = rng.normal(size=(80, 3))
    b = a + 0.3 * rng.normal(size=(80, 3))
    g = rng.normal(size=80)
    rc = rng.uniform(0.01, 0.1, size=80)
    v1 = segment_velocity(tg, a, b, g, rc)
    v2 = segment_velocity_numpy(tg, a, b, g, rc)
    # same formula, different evaluation order (fastmath): round-off level only
    np.testing.assert_allclose(v1, v2, rtol=1e-9, atol=1e-12 * np.abs(v2).max())


@pytest.mark.parametrize("h", [0.05, 0.2, 1.0])
def test_long_segment_is_vatistas_line_vortex(h):
    # A segment much longer than h approximates an infinite line vortex, whose
    # Vatistas n=2 swirl is Gamma/(2 pi) h / sqrt(rc^4 + h^4); the finite length
    # (+-1000 h) changes it by ~h^2/L^2 relative, far below the 1e-5 tolerance.
    gam, rc, L = 3.0, 0.1, 1000.0
    v = segment_velocity([[0.0, h, 0.0]], [[-L, 0, 0]], [[L, 0, 0]], [gam], [rc])[0]
    exact = gam / (2 * math.pi) * h / math.sqrt(rc ** 4 + h ** 4)
    # circulation along +x, point at +y: velocity along +z (right-hand rule)
    assert abs(v[0]) < 1e-12 and abs(v[1]) < 1e-12
    assert v[2] == pytest.approx(exact, rel=1e-5)


def test_ring_of_segments_gives_ring_centre_velocity():
    # Vortex ring radius R, Gamma: centre velocity Gamma/(2R) (closed form);
    # 720 chords of a circle differ from the arc by O(1/N^2) ~ 1e-5 relative.
    R, gam, n = 2.0, 5.0, 720
    th = np.linspace(0, 2 * np.pi, n + 1)
    pts = np.stack([R * np.cos(th), R * np.sin(th), np.zeros_like(th)], axis=1)
    v = segment_velocity([[0.0, 0.0, 0.0]], pts[:-1], pts[1:], gam, 1e-3)[0]
    assert v[2] == pytest.approx(gam / (2 * R), rel=1e-4)


def test_core_growth_and_input_validation():
    r = core_radius([0.0, 2 * np.pi], omega=25.0, rc0=0.05, delta=1000.0)
    assert r[0] == pytest.approx(0.05)
    # Squire's law: rc^2 - rc0^2 = 4 alpha delta nu t, t = 2 pi / Omega
    assert r[1] ** 2 - 0.05 ** 2 == pytest.approx(4 * 1.25643 * 1000 * 1.5e-5 * 2 * np.pi / 25.0)
    with pytest.raises(ValueError, match="targets must have shape"):
        segment_velocity(np.zeros((3, 2)), np.zeros((1, 3)), np.ones((1, 3)), 1.0, 0.1)
    with pytest.raises(ValueError, match="core radii must be >= 0"):
        segment_velocity(np.zeros((1, 3)), np.zeros((1, 3)), np.ones((1, 3)), 1.0, -0.1)


def test_single_precision_kernel_agrees_with_double():
    # wake-like scales: targets and segments tens of metres from the origin, cores of
    # centimetres; float32 carries ~7 digits, so 1e-5 relative bounds its round-off
    rng = np.random.default_rng(2)
    tg = 20.0 + 5.0 * rng.normal(size=(200, 3))
    a = 20.0 + 5.0 * rng.normal(size=(300, 3))
    b = a + 0.5 * rng.normal(size=(300, 3))
    g = rng.normal(size=300)
    rc = np.full(300, 0.05)
    v64 = segment_velocity(tg, a, b, g, rc)
    v32 = segment_velocity(tg, a, b, g, rc, precision="single")
    assert v32.dtype == np.float64
    np.testing.assert_allclose(v32, v64, rtol=0, atol=1e-5 * np.abs(v64).max())
    with pytest.raises(ValueError, match="precision must be"):
        segment_velocity(tg, a, b, g, rc, precision="half")
