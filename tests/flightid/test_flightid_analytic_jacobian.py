"""The opt-in analytic Jacobian of the CIFER residual (``fit(..., jacobian="analytic")``).

Checked against central differences of the residual itself (the default's route,
independent of the derivative formulas) on every structure form that provides it:
F/G/C with azimuth time, ties of both signs, delays and a feedthrough; M/Lbar with
tied delays; gain/delay; the DERIVID state space with parametrised C and D.
"""
import numpy as np
import pytest

from flightid import (FGCStructure, GainDelayStructure, MLTauStructure, StateSpaceStructure,
                      fit, frequency_response, frequency_sweep)
from flightid.errors import InputValueError
from flightid.feedthrough import MLTauFeedthroughStructure
from flightid.fitting import _jacobian, _PairData, _Problem


def _pairs(structure, seed=0):
    """Every (output, input) pair with 'data' scattered around the model (the residual is
    then not zero, so both of its halves, dB and degrees, are exercised)."""
    rng = np.random.default_rng(seed)
    w = np.geomspace(0.5, 20.0, 20)
    h = structure.frequency_response(w)
    out = []
    for i, o in enumerate(structure.outputs):
        for j, u in enumerate(structure.inputs):
            data = h[i, j] * (1 + 0.1 * rng.standard_normal(w.size)) * np.exp(0.1j * rng.standard_normal(w.size))
            out.append(_PairData(o, u, i, j, w, data, rng.uniform(0.5, 1.0, w.size)))
    return out


STRUCTURES = {
    "fgc, delays, signed tie": lambda: FGCStructure(
        [["f1", "f2"], ["-f2", "f3"]], [["g1", 0], [0.3, "g2"]], [[1.0, 0.0], [0.5, 1.0]],
        tau=[["t1", 0], [0, "t2"]], inputs=["a", "b"], outputs=["y", "z"],
        initial=dict(f1=-2.0, f2=0.7, f3=-3.0, g1=1.2, g2=-0.8, t1=0.05, t2=0.1)),
    "fgc, azimuth time, feedthrough": lambda: FGCStructure(
        [["f1", "f2"], ["-f2", "f3"]], [["g1", 0], [0.3, "g2"]], [[1.0, 0.0], [0.5, 1.0]],
        inputs=["a", "b"], outputs=["y", "z"], omega=20.0, D=[["d", 0], [0, 0]],
        initial=dict(f1=-0.2, f2=0.07, f3=-0.3, g1=1.2, g2=-0.8, d=0.3)),
    "M/Lbar, tied delay": lambda: MLTauStructure(
        [["m1", 0], [0, "m2"]], [["l1", "l2"], ["l2", "l3"]], tau=[["t", "t"], [0, 0]], inputs=["a", "b"],
        outputs=["y", "z"], omega=27.0, initial=dict(m1=0.8, m2=0.5, l1=0.4, l2=0.1, l3=0.6, t=0.03)),
    "gain/delay": lambda: GainDelayStructure(
        [["k1", "k2"], ["k3", 0]], tau=[["t1", "t2"], ["t1", 0]], inputs=["a", "b"], outputs=["y", "z"],
        initial=dict(k1=1.0, k2=-0.5, k3=0.3, t1=0.1, t2=0.2)),
    "state space, C and D parameters": lambda: StateSpaceStructure(
        [["Za", 1.0], ["Ma", "Mq"]], [["Zde"], ["Mde"]], [[0.0, 1.0], ["Za", 0.0]], D=[[0.0], ["Zde"]],
        inputs=["de"], outputs=["q", "az"], initial=dict(Za=-1.2, Ma=-6.0, Mq=-2.5, Zde=-0.15, Mde=-9.0)),
}


@pytest.mark.parametrize("name", list(STRUCTURES))
def test_analytic_jacobian_matches_central_differences(name):
    structure = STRUCTURES[name]()
    problem = _Problem(structure, _pairs(structure), 0.0, "analytic")
    assert problem.analytic
    x = np.array([structure.values[n] for n in structure.free_names])
    analytic = problem.jacobian(x, with_penalty=False)
    numeric = _jacobian(lambda v: problem.residuals(v, with_penalty=False), x)
    # central differences with step 1e-6 |x|: truncation ~ h^2 ~ 1e-12 and round-off
    # ~ eps / h ~ 1e-10 of the largest entry (measured 2e-10 at worst); 1e-7 leaves margin
    # while a wrong sign, factor or missed tie is an O(1) error
    np.testing.assert_allclose(analytic, numeric, rtol=0, atol=1e-7 * np.abs(numeric).max())


def test_stability_penalty_row_is_differentiated():
    structure = STRUCTURES["fgc, delays, signed tie"]()
    problem = _Problem(structure, _pairs(structure), 0.0, "analytic")
    x = np.array([structure.values[n] for n in structure.free_names])
    x[0] = 0.5                        # f1 > 0: an unstable pole, the penalty is active
    analytic = problem.jacobian(x)
    numeric = _jacobian(problem.residuals, x)
    assert np.any(analytic[-1] != 0)
    # the penalty row is itself central differences of the eigenvalues: same error budget
    np.testing.assert_allclose(analytic, numeric, rtol=0, atol=1e-7 * np.abs(numeric).max())


def test_structure_without_derivatives_falls_back_to_differences():
    # the feedthrough form adds D to the M/Lbar response without giving its derivative
    structure = MLTauFeedthroughStructure([["m"]], [["l"]], D=[["d"]], inputs=["a"], outputs=["y"],
                                          initial=dict(m=1.0, l=2.0, d=0.1))
    assert not structure._has_sensitivities()
    problem = _Problem(structure, _pairs(structure), 0.0, "analytic")
    assert not problem.analytic


def test_fit_with_analytic_jacobian_reaches_the_same_optimum():
    t, u = frequency_sweep(0.5, 20.0, 60.0, 0.01, seed=0)
    import control
    y = control.forced_response(control.tf([4.0], [1.0, 2.0]), t, u).outputs       # 4 / (s + 2)
    data = frequency_response(t, u, y, w_min=0.5, w_max=20.0, output_names=["y"])
    structure = FGCStructure([["f"]], [["g"]], [[1.0]], tau=[["tau"]], inputs=["u"], outputs=["y"],
                             initial={"f": -1.0, "g": 1.0, "tau": 0.05})
    default = fit(structure, data)
    analytic = fit(structure, data, jacobian="analytic")
    # both converge to the optimizer's tolerances on the same cost: the parameters agree to
    # well below their Cramér-Rao bounds (a few per cent here); 1e-4 relative is far tighter
    for n in ("f", "g"):
        assert analytic.structure.values[n] == pytest.approx(default.structure.values[n], rel=1e-4)
    assert analytic.J_ave == pytest.approx(default.J_ave, rel=1e-4, abs=1e-6)
    # the bounds use the same Gauss-Newton Hessian from either Jacobian
    np.testing.assert_allclose(analytic.cramer_rao.loc[["f", "g"]], default.cramer_rao.loc[["f", "g"]], rtol=1e-3)


def test_bad_jacobian_named():
    structure = STRUCTURES["gain/delay"]()
    with pytest.raises(InputValueError, match="jacobian"):
        fit(structure, None, jacobian="exact")
