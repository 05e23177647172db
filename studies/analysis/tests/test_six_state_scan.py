"""The 6-state family scan (:mod:`studies.analysis.six_state_scan`) on exact data.

The data are computed here with numpy, independently of the structures:
``lambda/C = ((M s/Omega + Lbar)^-1 + D) exp(-s tau)`` elementwise, from a
physically sized hover 6-state in our frames (``tests/aircraft/identification/test_coaxial_6state_start.py``'s
values) with a cross-rotor feedthrough added (sized as our wake's fit asks). On
exact data the true structure, given the truth among its starts, fits to
J_ave ~1e-4 and returns every parameter within 1 %; Eq. 5.3 without the
feedthrough cannot reach the same cost. The Cramér-Rao bounds at the exact truth
are not small (up to ~200 % on the unreduced 28 parameters; Eq. 5.3's own 24 at
its exact truth: up to 54 %, t41): CIFER's bound is a curvature of the weighted
cost, set by the structure, not by the residual.
"""
import numpy as np
import pytest

from aircraft.identification.structures import Coaxial6State
from studies.analysis.six_state_scan import (A_PRIORI_MASSES, CROSS_ROTOR_FEEDTHROUGH, FEEDTHROUGH_NAMES, SIX_STATE_FAMILY, Coaxial6StateVariant, SixStateCandidate, plot_cyclic_pairs, six_state_scan)
from aircraft.identification.structures.base import PITT_PETERS_M11
from flightid import MeasuredResponse

OMEGA = 23.7
W = np.geomspace(0.7, 30.0, 40)
TRUTH = {"m11": 0.85, "m14": -0.4, "m41": 0.6, "m44": 1.05, "m22": -0.25, "m25": -0.07, "m52": -0.33,
         "m55": -0.27, "l11": 0.44, "l14": -0.18, "l41": -0.73, "l44": 0.67, "l22": -0.045, "l25": 0.011,
         "l52": -0.036, "l55": -0.061, "t11": 0.03, "t14": 0.10, "t41": 0.02, "t44": 0.026, "t22": 0.023,
         "t25": 0.13, "t52": 0.08, "t55": 0.01}
D_TRUTH = {"d14": 0.5, "d41": -0.8, "d25": 2.0, "d52": -5.0}   # sized as our wake asks (d52 -5.2)


def _matrix(values, p, rotor_frame=True):
    """Eq. 5.3's 6x6 pattern filled by hand (1c rows repeat 1s; cross-rotor 1c opposite in our frames)."""
    s = -1.0 if rotor_frame else 1.0
    g = lambda n: values.get(f"{p}{n}", 0.0)   # noqa: E731
    return np.array([[g(11), 0, 0, g(14), 0, 0],
                     [0, g(22), 0, 0, g(25), 0],
                     [0, 0, g(22), 0, 0, s * g(25)],
                     [g(41), 0, 0, g(44), 0, 0],
                     [0, g(52), 0, 0, g(55), 0],
                     [0, 0, s * g(52), 0, 0, g(55)]])


def _exact(values, d):
    m, lb, tau = _matrix(values, "m"), _matrix(values, "l"), _matrix(values, "t", rotor_frame=False)
    dm = _matrix(d, "d")
    s = 1j * W / OMEGA
    h = np.moveaxis(np.linalg.inv(m[None] * s[:, None, None] + lb[None]), 0, -1) + dm[:, :, None]
    return h * np.exp(-1j * W[None, None, :] * tau[:, :, None])


def _data(d=D_TRUTH):
    st = Coaxial6State()
    h = _exact(TRUTH, d)
    return MeasuredResponse(h, W, np.ones(h.shape), st.inputs, st.outputs)


def test_variant_without_feedthrough_is_eq_5_3():
    plain = Coaxial6State().build(TRUTH, OMEGA).frequency_response(W)
    variant = Coaxial6StateVariant().build(TRUTH, OMEGA).frequency_response(W)
    np.testing.assert_allclose(variant, plain, rtol=1e-12, atol=1e-14)
    # the default is Eq. 5.3 itself
    registered = Coaxial6StateVariant()
    assert registered.feedthrough == () and registered.a_priori == {}
    # with no D it offers Eq. 5.3's equation-error start (here: the exact data's, stable)
    assert [label for label, _ in registered.extra_starts(_data({}), OMEGA)] == ["equation-error M (1-10 rad/s)"]
    assert Coaxial6StateVariant(("d25",)).extra_starts(_data(), OMEGA) == []


def test_variant_feedthrough_matches_numpy_composition():
    # the hand-built D pattern (ties and our frames' signs) against the structure's
    h = Coaxial6StateVariant(CROSS_ROTOR_FEEDTHROUGH).build({**TRUTH, **D_TRUTH}, OMEGA).frequency_response(W)
    np.testing.assert_allclose(h, _exact(TRUTH, D_TRUTH), rtol=1e-10, atol=1e-12)
    # entries not named stay zero whatever the start says
    st = Coaxial6StateVariant(("d25",)).build({**TRUTH, **D_TRUTH, "d11": 5.0}, OMEGA)
    np.testing.assert_allclose(st.matrices()["D"], _matrix({"d25": D_TRUTH["d25"]}, "d"), atol=0.0)
    assert set(st.free_names) >= {"d25"} and "d14" not in st.names


def test_a_priori_values_are_held_and_fixed():
    st = Coaxial6StateVariant(a_priori=A_PRIORI_MASSES["collective"])
    built = st.build({**TRUTH, "m11": 9.0}, OMEGA)
    assert built.values["m11"] == pytest.approx(PITT_PETERS_M11) and built.values["m44"] == pytest.approx(PITT_PETERS_M11)
    assert "m11" not in built.free_names and "m44" not in built.free_names
    assert st.initial_values(_data(), 3)["m11"] == pytest.approx(PITT_PETERS_M11)
    assert st.spec()["a_priori"] == {"m11": pytest.approx(PITT_PETERS_M11), "m44": pytest.approx(PITT_PETERS_M11)}


@pytest.mark.parametrize("kwargs, match", [
    (dict(feedthrough=("d99",)), "not entries of D"),
    (dict(a_priori={"x1": 1.0}), "not an M, Lbar or tau"),
    (dict(a_priori={"m11": float("nan")}), "finite real number"),
    (dict(a_priori={"m11": True}), "finite real number"),
])
def test_variant_rejects_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        Coaxial6StateVariant(**kwargs)


@pytest.mark.parametrize("kwargs, match", [
    (dict(a_priori="some"), "a_priori must be one of"),
    (dict(band=(3.0, 1.0)), "0 < low < high"),
])
def test_candidate_rejects_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        SixStateCandidate(**kwargs)


def test_scan_rejects_empty_family_and_bad_jobs():
    with pytest.raises(ValueError, match="at least one candidate"):
        six_state_scan(_data(), OMEGA, [])
    with pytest.raises(ValueError, match="n_jobs"):
        six_state_scan(_data(), OMEGA, n_jobs=0)


def test_default_family_covers_every_setting():
    labels = [c.label for c in SIX_STATE_FAMILY]
    assert len(set(labels)) == len(labels) == 15
    assert {c.a_priori for c in SIX_STATE_FAMILY} == set(A_PRIORI_MASSES)
    assert {tuple(c.feedthrough) for c in SIX_STATE_FAMILY} == {(), CROSS_ROTOR_FEEDTHROUGH}
    assert set(FEEDTHROUGH_NAMES) >= set(CROSS_ROTOR_FEEDTHROUGH)


def _meets(row):
    return (row.n_cramer_rao_over == 0 and row.n_insensitivity_over == 0 and row.n_flat == 0
            and row.J_ave <= 100.0)


@pytest.mark.slow
def test_scan_finds_the_true_structure_on_exact_data():
    data = _data()
    cands = [SixStateCandidate((1.0, 25.0)), SixStateCandidate((1.0, 25.0), "none", CROSS_ROTOR_FEEDTHROUGH)]
    scan = six_state_scan(data, OMEGA, cands, starts={"truth": {**TRUTH, **D_TRUTH}}, reduce=False)
    t = scan.table.set_index("label")
    with_d, plain = t.loc[cands[1].label], t.loc[cands[0].label]
    # the true structure: exact data fitted exactly, every parameter recovered
    assert with_d.J_ave < 0.01 and with_d.pareto and with_d.n_removed == 0
    fitted = scan.models[cands[1].label].values
    for name, value in {**TRUTH, **D_TRUTH}.items():
        assert fitted[name] == pytest.approx(value, rel=0.01, abs=1e-4), name
    # Eq. 5.3 cannot carry a direct part: its best cost stays far above
    assert plain.J_ave > 100 * with_d.J_ave
    # the bounds are a property of the structure and the cost's weighting, not of
    # the residual: at the exact truth the unreduced 28 parameters have bounds far
    # over 20 % (small delays, weak cross terms), so even the truth does not meet the
    # target before the guideline's reduction; the verdict is the stated rule
    assert with_d.max_cramer_rao_pct > 20.0
    for _, row in t.iterrows():
        assert row.meets_target == _meets(row)
    assert scan.any_meets_target == bool(t.meets_target.any())
    assert set(scan.pair_costs.label) == set(t.index) and len(scan.pair_costs) == 24
    # the figures draw and show both rotors' lateral pairs
    assert len(plot_cyclic_pairs(scan, data).axes) == 8
    assert scan.plot().get_ylabel().startswith("largest")


@pytest.mark.slow
def test_scan_reduction_follows_the_guideline_thresholds():
    # with the reduction on (the study's setting) each removal may raise J_ave by at
    # most 2 (flightid.reduce's max_rise_average), so the reduced cost is bounded by
    # the full fit's plus 2 per removed parameter
    cand = SixStateCandidate((1.0, 25.0), "collective", CROSS_ROTOR_FEEDTHROUGH)
    row = six_state_scan(_data(), OMEGA, [cand], starts={"truth": {**TRUTH, **D_TRUTH}}).table.iloc[0]
    assert row.a_priori == "collective" and row.m11 == pytest.approx(PITT_PETERS_M11)
    assert row.J_ave <= row.J_ave_full_fit + 2.0 * row.n_removed + 1e-9
    assert row.meets_target == _meets(row)
