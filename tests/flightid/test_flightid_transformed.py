"""flightid.transformed: responses and structures in transformed signal coordinates.

Oracles: python-control's own frequency response of the same state space
(transformed by matrix products there), closed-form error propagation, and a
synthetic nearly rank-one system with known parameters.
"""
import control
import numpy as np
import pytest

from flightid import IdentificationError, MeasuredResponse, MLTauStructure, fit
from flightid.transformed import TransformedStructure, pair_costs, sum_difference_transform, transform_response

OMEGA = 27.0
M_TRUE = np.array([[0.85, -0.47], [0.67, 1.06]])
# Lbar of a nearly rank-one steady block (sigma_min/sigma_max 0.059, as our coaxial's collective)
L_TRUE = np.linalg.inv(np.array([[4.5, 2.25], [5.0, 3.3]]))
NAMES = ["m11", "m12", "m21", "m22", "l11", "l12", "l21", "l22"]


def _pattern(p):
    return [[f"{p}11", f"{p}12"], [f"{p}21", f"{p}22"]]


def _truth():
    vals = {f"m{i + 1}{j + 1}": M_TRUE[i, j] for i in range(2) for j in range(2)}
    vals.update({f"l{i + 1}{j + 1}": L_TRUE[i, j] for i in range(2) for j in range(2)})
    return vals


def _structure(values=None, tau=False):
    values = dict(values or _truth())
    pat_t = None
    if tau:
        pat_t = [["t1", 0], [0, "t2"]]
        values.update(t1=0.03, t2=0.05)
    return MLTauStructure(_pattern("m"), _pattern("l"), pat_t, inputs=["u1", "u2"], outputs=["y1", "y2"],
                          initial=values, omega=OMEGA)


def _sd():
    return sum_difference_transform([(("y1", "y2"), ("u1", "u2"), "y")], ["y1", "y2"], ["u1", "u2"])


def _noisy_data(rel, seed=1, w=None):
    w = np.geomspace(0.7, 30.0, 60) if w is None else w
    h = _structure().frequency_response(w)
    rng = np.random.default_rng(seed)
    noise = rel * (rng.standard_normal(h.shape) + 1j * rng.standard_normal(h.shape)) / np.sqrt(2)
    return MeasuredResponse(h * (1 + noise), w, np.full(h.shape, 1 / (1 + rel ** 2)), ["u1", "u2"],
                            ["y1", "y2"])


def test_sum_difference_transform_is_orthonormal_and_signed():
    t, s_inv, outs, ins = sum_difference_transform([(("a", "b"), ("p", "q"), "x")], ["a", "b", "c"],
                                                   ["p", "q"], signs=[-1.0])
    np.testing.assert_allclose(t @ t.T, np.eye(3), atol=1e-15)
    np.testing.assert_allclose(s_inv.T @ s_inv, np.eye(2), atol=1e-15)
    np.testing.assert_allclose(t[0, :2] * np.sqrt(2), [1.0, -1.0])      # a - b with sign -1
    np.testing.assert_allclose(t[2], [0.0, 0.0, 1.0])                    # c kept as it is
    assert outs == ["x_sum", "x_diff", "c"] and ins == ["x_sum", "x_diff"]


def test_transformed_structure_matches_python_control_with_delays():
    # the oracle: python-control's response of the inner state space (Pade delays,
    # compared well below the Pade's error band) multiplied by T and Sinv
    inner = _structure(tau=True)
    t, s_inv, outs, ins = _sd()
    ts = TransformedStructure(inner, t, s_inv, outs, ins)
    w = np.geomspace(0.5, 5.0, 15)
    ss = inner.to_statespace(pade_order=2)
    ref = np.einsum("ai,ijw,jb->abw", t, control.frequency_response(ss, w).complex, s_inv)
    np.testing.assert_allclose(ts.frequency_response(w), ref, rtol=2e-4, atol=1e-9)
    # and its own state space is the same transformed system
    got = control.frequency_response(ts.to_statespace(pade_order=2), w).complex
    np.testing.assert_allclose(got, ref, rtol=1e-8, atol=1e-10)
    assert ts.to_statespace().input_labels == ins


def test_parameters_are_shared_with_the_inner_structure():
    t, s_inv, outs, ins = _sd()
    ts = TransformedStructure(_structure(), t, s_inv, outs, ins)
    fixed = ts.fix("m12", 0.0).with_values({"l11": 2.0})
    assert fixed.inner.values["m12"] == 0.0 and "m12" in fixed.inner.fixed and fixed.inner.values["l11"] == 2.0
    assert "m12" not in fixed.free_names and ts.values["l11"] == pytest.approx(L_TRUE[0, 0])   # copies
    np.testing.assert_allclose(ts.poles(), _structure().poles())


def test_coherence_propagation_closed_forms():
    w = np.array([1.0, 2.0])
    h = np.ones((2, 2, 2), dtype=complex)
    h[1, 1] = 0.9
    g = np.full((2, 2, 2), 0.8)
    data = MeasuredResponse(h, w, g, ["u1", "u2"], ["y1", "y2"])
    # identity: the coherence comes back unchanged
    same = transform_response(data, np.eye(2), np.eye(2), ["a", "b"], ["p", "q"])
    np.testing.assert_allclose(same.coherence, g)
    np.testing.assert_allclose(same.data, h)
    # y1 - y2 over input u1: H_t = (1 - 1)/sqrt2 = 0: all error, no signal: coherence 0
    t = np.array([[1.0, 1.0], [1.0, -1.0]]) / np.sqrt(2)
    out = transform_response(data, t, np.eye(2), ["s", "d"], ["p", "q"])
    assert out.coherence[1, 0, 0] == pytest.approx(0.0, abs=1e-12)
    # (y1 + y2)/sqrt2 over u1: |H_t|^2 = 2, var = (0.25 + 0.25)/2 * 2 ... closed form
    eps2 = (1 - 0.8) / 0.8                      # per element, |H| = 1
    var = 0.5 * eps2 + 0.5 * eps2
    assert out.coherence[0, 0, 0] == pytest.approx(1 / (1 + var / 2.0), rel=1e-12)


def test_propagated_coherence_against_monte_carlo():
    # the variance propagation behind the coherence, checked by sampling the
    # element errors (complex Gaussian with the stated variance)
    rng = np.random.default_rng(4)
    h = np.array([[4.5, 2.25], [5.0, 3.3]], dtype=complex)[:, :, None]
    g = np.array([[0.95, 0.9], [0.92, 0.97]])[:, :, None]
    data = MeasuredResponse(h, np.array([1.0]), g, ["u1", "u2"], ["y1", "y2"])
    t, s_inv, outs, ins = _sd()
    out = transform_response(data, t, s_inv, outs, ins)
    sd = np.sqrt((1 - g) / g) * np.abs(h)
    draws = h[None] + sd[None] * (rng.standard_normal((20000,) + h.shape)
                                  + 1j * rng.standard_normal((20000,) + h.shape)) / np.sqrt(2)
    ht = np.einsum("ai,nijw,jb->nabw", t, draws, s_inv)
    var_mc = np.var(ht, axis=0)
    g_mc = 1 / (1 + var_mc / np.abs(out.data) ** 2)
    # 20000 draws: the sampled variance is good to ~1 %, so the coherence to < 1 %
    np.testing.assert_allclose(out.coherence, g_mc, rtol=0.01)


def test_pair_costs_reproduce_the_fit_cost_table():
    data = _noisy_data(0.03)
    res = fit(_structure({k: v * 1.2 for k, v in _truth().items()}), data, frequency_ranges=(1, 25))
    table = pair_costs(res.structure, data, list(zip(res.cost_table.output, res.cost_table.input)), (1, 25))
    np.testing.assert_allclose(table.J.to_numpy(), res.cost_table.J.to_numpy(), rtol=1e-9)
    assert table.attrs["J_ave"] == pytest.approx(res.J_ave, rel=1e-9)


def test_sum_difference_fit_of_a_nearly_rank_one_block():
    """Same data, same model, orthonormal coordinates: both fits recover the truth,
    and the Cramer-Rao bounds differ by a factor ~1.8.

    The CIFER bound is the curvature of the cost, not a calibrated standard
    deviation: in the rotors' coordinates the small singular direction hides in
    every element, in sum/difference coordinates it is an element of its own and
    the cost curves more along it. What does not change is the true error. So a
    bound is only comparable within one set of coordinates.
    """
    data = _noisy_data(0.03)
    start = {k: v * 1.3 for k, v in _truth().items()}
    plain = fit(_structure(start), data, frequency_ranges=(1, 25))
    t, s_inv, outs, ins = _sd()
    sd = fit(TransformedStructure(_structure(start), t, s_inv, outs, ins),
             transform_response(data, t, s_inv, outs, ins), frequency_ranges=(1, 25))
    truth = _truth()
    for res in (plain, sd):
        err = max(abs(res.structure.values[k] / truth[k] - 1) for k in NAMES)
        assert err < 0.12           # 3 % element noise on a 0.06 singular-value ratio: ~10 %
    cr_plain = plain.parameters.set_index("parameter").cramer_rao_pct
    cr_sd = sd.parameters.set_index("parameter").cramer_rao_pct
    assert cr_plain.max() > 30 and cr_sd.max() < 25
    assert 1.4 < cr_plain.max() / cr_sd.max() < 2.5
    assert sd.condition_number < plain.condition_number / 2


@pytest.mark.parametrize("kwargs, match", [
    (dict(T=np.ones((2, 2))), "T must have rank 2"),
    (dict(Sinv=np.zeros((2, 2))), "Sinv must have rank 2"),
    (dict(T=np.eye(3)), "T must have 2 columns"),
    (dict(T=np.array([[np.nan, 0], [0, 1]])), "finite"),
    (dict(outputs=["a", "a"]), "distinct transformed output names"),
])
def test_bad_transforms_are_refused(kwargs, match):
    args = dict(T=np.eye(2), Sinv=np.eye(2), outputs=["a", "b"], inputs=["p", "q"])
    args.update(kwargs)
    with pytest.raises(IdentificationError, match=match):
        transform_response(_noisy_data(0.01), **args)
    with pytest.raises(IdentificationError, match=match):
        TransformedStructure(_structure(), **args)


def test_other_bad_inputs():
    with pytest.raises(IdentificationError, match="must be a MeasuredResponse"):
        transform_response(np.ones((2, 2, 3)), np.eye(2), np.eye(2), ["a", "b"], ["p", "q"])
    with pytest.raises(IdentificationError, match="must be a ModelStructure"):
        TransformedStructure("M", np.eye(2), np.eye(2), ["a", "b"], ["p", "q"])
    with pytest.raises(IdentificationError, match="not among"):
        sum_difference_transform([(("y1", "zz"), ("u1", "u2"), "y")], ["y1", "y2"], ["u1", "u2"])
    with pytest.raises(IdentificationError, match="one \\+1 or -1 per group"):
        sum_difference_transform([(("y1", "y2"), ("u1", "u2"), "y")], ["y1", "y2"], ["u1", "u2"], signs=[0.5])
    with pytest.raises(IdentificationError, match="not a response of the structure"):
        pair_costs(_structure(), _noisy_data(0.01), [("y1", "nope")], (1, 25))
