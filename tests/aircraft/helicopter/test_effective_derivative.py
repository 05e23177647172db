"""effective_derivative against a closed form and against python-control's own frequency response."""
import control
import numpy as np
import pytest

from aircraft.helicopter import DerivativeError, effective_derivative

W = np.array([0.0, 0.3, 1.0, 5.0, 30.0])


def _toy():
    # body roll rate p and attitude phi, one fast "flap" state b:
    #   p_dot = -0.5 p + 40 b + 2 u,  phi_dot = p,  b_dot = -10 b - 0.8 p + 12 u
    a = np.array([[-0.5, 0.0, 40.0], [1.0, 0.0, 0.0], [-0.8, 0.0, -10.0]])
    b = np.array([[2.0], [0.0], [12.0]])
    return control.ss(a, b, np.eye(3), np.zeros((3, 1)), states=["p", "phi", "beta"], inputs=["delta_lat"],
                      outputs=["p", "phi", "beta"])


def test_closed_form_of_a_one_lag_rotor():
    sys = _toy()
    s = 1j * W
    # L_p(s) = -0.5 + 40 (-0.8)/(s + 10);  L_delta(s) = 2 + 40 * 12/(s + 10)
    lp = effective_derivative(sys, "p", "p", W, body_states=["p", "phi"])
    ld = effective_derivative(sys, "p", "delta_lat", W, body_states=["p", "phi"])
    np.testing.assert_allclose(lp, -0.5 - 32.0 / (s + 10.0), rtol=1e-12)
    np.testing.assert_allclose(ld, 2.0 + 480.0 / (s + 10.0), rtol=1e-12)
    # quasi-static value: -0.5 - 3.2 (the flap lag's steady moment)
    assert lp[0].real == pytest.approx(-3.7) and lp[0].imag == 0


def test_equals_python_control_on_a_random_aircraft_sized_system():
    rng = np.random.default_rng(3)
    n_body, n_fast = 3, 6
    a = rng.normal(size=(n_body + n_fast,) * 2)
    a[n_body:, n_body:] -= 8.0 * np.eye(n_fast)          # stable fast block
    b = rng.normal(size=(n_body + n_fast, 2))
    names = ["p", "q", "phi"] + [f"x{k}" for k in range(n_fast)]
    sys = control.ss(a, b, np.eye(len(names)), 0, states=names, inputs=["d1", "d2"], outputs=names)
    # the fast subsystem driven by q, seen in p_dot, by python-control's own evaluation
    sub = control.ss(a[n_body:, n_body:], a[n_body:, [1]], a[[0], n_body:], a[[0], [1]])
    ref = np.array([complex(sub(1j * w)) for w in W])
    got = effective_derivative(sys, "p", "q", W, body_states=["p", "q", "phi"])
    np.testing.assert_allclose(got, ref, rtol=1e-10)


@pytest.mark.parametrize("kwargs, match", [
    (dict(rate="beta", cause="p"), "must be one of the body states"),
    (dict(rate="p", cause="nope"), "neither a state nor an input"),
    (dict(rate="p", cause="p", omega=[-1.0]), "finite frequencies >= 0"),
    (dict(rate="p", cause="p", omega=[np.nan]), "finite frequencies >= 0"),
    (dict(rate="p", cause="p", body_states=["p", "r"]), "unknown body state"),
])
def test_bad_arguments_are_refused(kwargs, match):
    args = {"omega": W, "body_states": ["p", "phi"], **kwargs}
    with pytest.raises(DerivativeError, match=match):
        effective_derivative(_toy(), args.pop("rate"), args.pop("cause"), args.pop("omega"), **args)


def test_a_fast_pole_on_the_axis_is_reported():
    a = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 2.0], [0.0, -4.0, 0.0]])   # fast pair at +-2j
    sys = control.ss(a, np.zeros((3, 1)), np.eye(3), 0, states=["p", "x", "y"], inputs=["u"],
                     outputs=["p", "x", "y"])
    with pytest.raises(DerivativeError, match="pole at j"):
        effective_derivative(sys, "p", "p", [2.0 * np.sqrt(2.0)], body_states=["p"])
