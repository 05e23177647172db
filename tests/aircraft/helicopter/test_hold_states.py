"""hold_states: states held at trim (a perfectly tight outer loop), checked by simulation."""
import control
import numpy as np
import pytest
from scipy import signal

from aircraft.helicopter.hold import hold_states


@pytest.fixture
def system():
    rng = np.random.default_rng(1)
    A = rng.standard_normal((4, 4)) - 3.0 * np.eye(4)
    B, C = rng.standard_normal((4, 2)), rng.standard_normal((3, 4))
    return control.ss(A, B, C, np.zeros((3, 2)), states=["u", "v", "p", "x"], inputs=["a", "b"],
                      outputs=["y1", "y2", "y3"])


def test_held_states_stay_at_trim_in_a_simulation_of_the_full_model(system):
    # scipy simulates the full model with the held states' derivatives zeroed (and
    # starting at zero, they stay there): the outputs must be the reduced model's
    A = np.asarray(system.A).copy()
    A[[0, 1], :] = 0.0
    B = np.asarray(system.B).copy()
    B[[0, 1], :] = 0.0
    t = np.linspace(0, 5, 1001)
    u = np.column_stack([np.sin(2 * t), np.where(t > 1, 1.0, 0.0)])
    _, y_full, _ = signal.lsim(signal.StateSpace(A, B, np.asarray(system.C), np.zeros((3, 2))), u, t)
    held = hold_states(system, ["u", "v"])
    assert list(held.state_labels) == ["p", "x"]
    assert list(held.input_labels) == ["a", "b"] and list(held.output_labels) == ["y1", "y2", "y3"]
    y = control.forced_response(held, t, u.T).outputs
    np.testing.assert_allclose(np.atleast_2d(y).T, y_full, atol=1e-9)


@pytest.mark.parametrize("names, match", [([], "distinct"), (["w"], "distinct"), (["u", "u"], "distinct"),
                                          (["u", "v", "p", "x"], "every state")])
def test_bad_names(system, names, match):
    with pytest.raises(ValueError, match=match):
        hold_states(system, names)
