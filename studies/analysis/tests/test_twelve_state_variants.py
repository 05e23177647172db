"""Constrained 12-state structures: held and removed entries are constants of the model.

The oracle is the unconstrained :class:`Coaxial12State` (its own build code) with the
same values set: a constraint must change which numbers are parameters, never the
model those numbers describe.
"""
import numpy as np
import pandas as pd
import pytest

from aircraft.identification.structures import Coaxial12State
from aircraft.identification import get_structure
from aircraft.identification.structures.constrained import (PITT_PETERS_COLLECTIVE_GAIN, VARIANTS, Coaxial12StateConstrained)
from studies.analysis.twelve_state_variants import TwelveStateComparison, compare_twelve_state_variants

OMEGA = 23.7                              # rad/s, the coaxial compound's rotor speed
W = np.array([0.5, 2.0, 8.0, 25.0])       # rad/s, across and beyond the fit band


def _values(names, seed=0):
    rng = np.random.default_rng(seed)
    # delays >= 0 s; the rest O(0.1-1) with a stable diagonal (-0.3 per rad of azimuth)
    return {n: (0.02 * rng.random() if n.startswith("t") else
                (-0.3 if n.split("_")[0][1:] == n.split("_")[1] and n.startswith("f") else 0.2 * rng.standard_normal()))
            for n in names}


def _base():
    return Coaxial12State(delays=True, far_wake_loads=True)


def test_unconstrained_is_the_shipped_structure():
    base, free = _base(), Coaxial12StateConstrained()
    assert free.parameter_names() == base.parameter_names()
    vals = _values(base.parameter_names())
    h0 = base.build(vals, OMEGA).frequency_response(W)
    h1 = free.build(vals, OMEGA).frequency_response(W)
    np.testing.assert_allclose(h1, h0, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("label", list(VARIANTS))
def test_each_variant_is_the_base_model_with_its_constants(label):
    kw = VARIANTS[label]
    s = Coaxial12StateConstrained(**kw)
    base = _base()
    vals = _values(s.parameter_names(), seed=1)
    full = {**{n: 0.0 for n in base.parameter_names()}, **vals, **s.a_priori}
    full.update({n: 0.0 for n in s.without})
    if not s.collective_far_wake:
        # the far-wake collective rows zero, their poles the constant -1 per radian
        for n in base.parameter_names():
            if n.startswith(("f2_", "g2_", "f8_", "g8_")):
                full[n] = -1.0 if n in ("f2_2", "f8_8") else 0.0
    h0 = base.build(full, OMEGA).frequency_response(W)
    h1 = s.build(vals, OMEGA).frequency_response(W)
    np.testing.assert_allclose(h1, h0, rtol=1e-12, atol=1e-15)
    assert not set(s.parameter_names()) & (set(s.a_priori) | set(s.without))


def test_parameter_counts_and_tied_partner_follow():
    counts = [len(Coaxial12StateConstrained(**kw).parameter_names()) for kw in VARIANTS.values()]
    # 54 shipped; 10 far-wake collective entries off; 2 gains held; 2 couplings removed
    assert counts == [54, 44, 42, 40]
    s = Coaxial12StateConstrained(without=("f4_10",), a_priori={"g3_7": 0.5})
    m = s.build({n: 0.1 for n in s.parameter_names()}, OMEGA).matrices()
    F, G = m["F"], m["G"]
    assert F[3, 9] == 0.0 and F[5, 11] == 0.0          # f4_10 and its tied 1c partner
    col = s.inputs.index("CL_L")
    col_c = s.inputs.index("CM_L")
    # g3_7: upper lam1sN from the lower rotor's C_L; its 1c partner (upper lam1cN from
    # C_M_L) carries the cross-rotor minus sign of our rotor frames
    assert G[2, col] == 0.5 and G[4, col_c] == -0.5


@pytest.mark.parametrize("kwargs", [dict(without=("t52",)), dict(a_priori={"t52": 0.03}),
                                    dict(without=("t41", "f1_7"), a_priori={"t52": 0.01})])
def test_delays_held_or_removed_are_constants_of_the_model(kwargs):
    # delays carry no tie sign: a removed one is zero, a held one its value, in the
    # same model the unconstrained structure gives with those numbers
    s = Coaxial12StateConstrained(**kwargs)
    base = _base()
    vals = _values(s.parameter_names(), seed=2)
    full = {**vals, **s.a_priori, **{n: 0.0 for n in s.without}}
    h0 = base.build(full, OMEGA).frequency_response(W)
    h1 = s.build(vals, OMEGA).frequency_response(W)
    np.testing.assert_allclose(h1, h0, rtol=1e-12, atol=1e-15)
    assert not set(s.parameter_names()) & (set(s.a_priori) | set(s.without))


def test_spec_and_registry():
    a = Coaxial12StateConstrained()
    b = Coaxial12StateConstrained(a_priori=PITT_PETERS_COLLECTIVE_GAIN)
    assert a.spec() != b.spec()
    assert b.spec()["constrained"]["a_priori"] == pytest.approx({"g1_1": 3 * np.pi / 8, "g7_6": 3 * np.pi / 8})
    s = get_structure("coaxial_12state_first_order_collective_pp")
    assert not s.collective_far_wake and s.without == ("f10_4", "f4_10")
    plan = s.staged_plan()
    assert all(set(st.free) <= set(s.parameter_names()) for st in plan if not isinstance(st.free, str))


@pytest.mark.parametrize("kwargs, match", [
    (dict(a_priori={"g99_1": 1.0}), "not a parameter"),
    (dict(a_priori={"g1_1": float("nan")}), "finite real number"),
    (dict(a_priori={"g1_1": "big"}), "finite real number"),
    (dict(without=["f1_99"]), "not parameters"),
    (dict(a_priori={"g1_1": 1.0}, without=["g1_1"]), "both held a priori and removed"),
    (dict(collective_far_wake=False, without=["f2_2"]), "not parameters"),
])
def test_bad_constraints_are_refused(kwargs, match):
    with pytest.raises(ValueError, match=match):
        Coaxial12StateConstrained(**kwargs)


def test_comparison_validation_and_plot():
    with pytest.raises(ValueError, match="variants is empty"):
        compare_twelve_state_variants({})
    with pytest.raises(TypeError, match="IdentificationSettings"):
        compare_twelve_state_variants(settings={"sweep_s": 10})
    # references are checked before any wake run
    with pytest.raises(TypeError, match="reference 'x' must be an IdentifiedInflow"):
        compare_twelve_state_variants(references={"x": 3.0})
    table = pd.DataFrame({"variant": ["a", "b"], "max_cramer_rao_pct": [999.0, 31.0], "n_flat": [4, 0],
                          "J_ave": [42.0, 52.0]})
    res = TwelveStateComparison(table)
    assert res.to_pandas().equals(table)
    assert len(res.plot().axes) == 3
    flown = TwelveStateComparison(table.assign(Lp_real_0=[5.9, 1.1]))
    assert len(flown.plot().axes) == 4
    paths = TwelveStateComparison(table.assign(Lp_real_0=[5.9, 1.1], Lp_real_0_load_path_only=[-16.1, -18.4],
                                               Lp_real_0_flap_rate_path_only=[3.2, 3.6]))
    ax = paths.plot().axes[-1]
    assert len(ax.patches) == 6 and len(ax.get_legend().get_texts()) == 3


def test_steady_curvature_gain_is_the_K_R_of_eq_2_29():
    # a hand-built F/G/C model whose DC answer is lambda1s_r = -K_R,r beta1s_dot_r / Omega
    # on each rotor (Eq. 2.29 at zero frequency): the reported equivalent K_R is K_R
    from aircraft.configs import coaxial_compound
    from aircraft.inflow import IdentifiedInflow
    from aircraft.inflow.base import flap_rate_names, load_names
    from studies.analysis.twelve_state_variants import _steady_curvature
    omega = float(coaxial_compound().rotors[0].omega)
    order = load_names(("U", "L")) + flap_rate_names(("U", "L"))
    F, G = -2.0 * np.eye(12), np.zeros((12, len(order)))
    for row, rotor, kr in ((2, "U", 1.5), (8, "L", 0.7)):      # lam1sN of each rotor
        G[row, order.index(f"beta1s_dot_{rotor}")] = 2.0 * (-kr / omega)
        G[row, order.index(f"CL_{rotor}")] = 1.0                  # a load path it must ignore
    model = IdentifiedInflow.from_fgc(F, G, input_order=order)
    got = _steady_curvature(model)
    assert got == pytest.approx({"KR_equivalent_steady_U": 1.5, "KR_equivalent_steady_L": 0.7}, rel=1e-12)
