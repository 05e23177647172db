"""Coupling numerators and residualisation: pure LTI operations of flightid.lti."""
import control
import numpy as np
import pytest

from flightid.lti import CouplingError, coupling_numerator, residualize


def _two_axis():
    # x1 driven by u1 and coupled to x2; x2 driven by u2: holding x2 = 0 with u2
    # leaves dx1/dt = -x1 + u1, i.e. y1/u1 = 1/(s + 1) exactly
    a = np.array([[-1.0, 0.5], [0.2, -2.0]])
    return control.ss(a, np.eye(2), np.eye(2), np.zeros((2, 2)), states=["x1", "x2"], inputs=["u1", "u2"],
                      outputs=["y1", "y2"])


def test_coupling_numerator_holds_the_constrained_output():
    plant = coupling_numerator(_two_axis(), "y1", "u1", {"y2": "u2"})
    assert plant.input_labels == ["u1"] and plant.output_labels == ["y1"]
    np.testing.assert_allclose(np.sort(np.linalg.eigvals(plant.A)), [-1.0], atol=1e-12)
    w = np.array([0.1, 1.0, 10.0])
    h = np.squeeze(control.frequency_response(plant, w).complex)
    np.testing.assert_allclose(h, 1.0 / (1j * w + 1.0), rtol=1e-10)
    with pytest.raises(CouplingError, match="unknown output"):
        coupling_numerator(_two_axis(), "nope", "u1", {"y2": "u2"})
    with pytest.raises(CouplingError):
        coupling_numerator(_two_axis(), "y1", "u1", {"y2": "u1"})


def test_residualize_keeps_slow_modes_and_the_dc_gain():
    sys = control.ss(control.tf([100.0], [1.0, 101.0, 100.0]))     # poles -1 and -100
    slow = residualize(sys, cutoff=10.0)
    assert slow.nstates == 1
    np.testing.assert_allclose(np.linalg.eigvals(slow.A), [-1.0], rtol=1e-10)
    np.testing.assert_allclose(control.dcgain(slow), control.dcgain(sys), rtol=1e-10)
    assert residualize(sys, cutoff=1e3) is sys
    with pytest.raises(CouplingError, match="cutoff"):
        residualize(sys, cutoff=-1.0)


def test_aircraft_keeps_importing_the_same_functions():
    from aircraft.helicopter import coupling as aircraft_coupling
    import aircraft.helicopter as helicopter
    assert aircraft_coupling.coupling_numerator is coupling_numerator is helicopter.coupling_numerator
    assert aircraft_coupling.residualize is residualize and aircraft_coupling.CouplingError is CouplingError
