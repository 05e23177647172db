"""The smaller 200 kt candidate structures: exact-data recovery and the candidates' table.

The data are the structures' own exact frequency responses, computed here with numpy,
``(M s/Omega + Lbar)^-1 exp(-s tau)`` with elementwise delays, from forward-flight-sized
values (per rotor the size of Eq. 4.7's model; cross-rotor terms a fraction of them).
"""
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from aircraft.identification import IdentificationSettings
from aircraft.identification.coaxial_forward_candidates import (CANDIDATE_COLUMNS, DEFAULT_CANDIDATES,
                                                                CandidateStructures, candidate_structures_table,
                                                                default_candidates)
from aircraft.identification.pipeline import _start_candidates
from aircraft.identification.structures.coaxial_forward_small import CoaxialForward6State, CoaxialForwardIsolated
from flightid import MeasuredResponse, fit

OMEGA = 20.3          # cruise rotor speed [rad/s]
W = np.geomspace(0.7, 30.0, 40)
ROTORS = {"m11": 0.85, "m22": -0.11, "l11": 0.12, "l13": 0.23, "l22": -0.05, "l31": 0.21, "l33": -0.17,
          "t11": 0.03, "t13": 0.06, "t22": 0.02, "t31": 0.05, "t33": 0.025,
          "m44": 0.9, "m55": -0.13, "l44": 0.15, "l46": 0.2, "l55": -0.06, "l64": 0.18, "l66": -0.2,
          "t44": 0.025, "t46": 0.07, "t55": 0.03, "t64": 0.04, "t66": 0.02}
INTERFERENCE = {"m14": -0.2, "m41": 0.3, "m25": -0.03, "m52": -0.05, "m36": -0.04, "m63": -0.02,
                "l14": -0.05, "l41": -0.08, "l25": 0.01, "l52": -0.015, "l36": 0.012, "l63": -0.01,
                "t14": 0.1, "t41": 0.08, "t25": 0.12, "t52": 0.09, "t36": 0.07, "t63": 0.11}


def _exact(structure, truth):
    mats = structure.build(truth, OMEGA).matrices()
    s = 1j * W / OMEGA
    h = np.moveaxis(np.linalg.inv(mats["M"][None] * s[:, None, None] + mats["Lbar"][None]), 0, -1)
    h = h * np.exp(-1j * W[None, None, :] * mats["tau"][:, :, None])
    return MeasuredResponse(h, W, np.ones(h.shape), structure.inputs, structure.outputs)


def test_patterns_hand_counted():
    # per rotor Eq. 4.3: M11, M22 (= M33), 5 Lbar, 5 tau = 12; interference: 6 entries x (M, Lbar, tau)
    iso, six = CoaxialForwardIsolated(), CoaxialForward6State()
    assert len(iso.parameter_names()) == 24 and len(six.parameter_names()) == 42
    m = iso.build(ROTORS, OMEGA).matrices()
    assert m["M"][2, 2] == m["M"][1, 1] == ROTORS["m22"] and m["M"][5, 5] == ROTORS["m55"]
    # no interference: the cross-rotor blocks are exactly zero
    for name in ("M", "Lbar", "tau"):
        assert not m[name][:3, 3:].any() and not m[name][3:, :3].any()
    m6 = six.build({**ROTORS, **INTERFERENCE}, OMEGA).matrices()
    assert m6["Lbar"][2, 5] == INTERFERENCE["l36"] and m6["tau"][4, 1] == INTERFERENCE["t52"]
    with pytest.raises(KeyError, match="no initial value"):
        six.build(ROTORS, OMEGA)


def test_without_lam0_cm_pairs_hand_counted():
    # the pattern produces lam0, lam1c on CT, CM and lam1s on CL: isolated, per rotor
    # 2 x 2 + 1 = 5 less lam0/CM = 4, two rotors 8; 6-state: (4 x 4 + 2 x 2) = 20 less the
    # four lam0/CM (both rotors' lam0 on both rotors' CM) = 16
    assert CoaxialForwardIsolated().pairs is None and "pairs" not in CoaxialForwardIsolated().fit_options
    iso = CoaxialForwardIsolated(without_lam0_cm=True).fit_options["pairs"]
    six = CoaxialForward6State(without_lam0_cm=True).fit_options["pairs"]
    assert (len(iso), len(six)) == (8, 16)
    assert ("lam1c_U", "CT_U") in iso and ("lam1c_U", "CT_L") not in iso and ("lam1c_U", "CT_L") in six
    assert ("lam0_U", "CL_U") not in six and ("lam1s_L", "CL_U") in six
    assert not any(o.startswith("lam0") and i.startswith("CM") for o, i in six)
    # the option is part of what identifies the structure (settings hashes, model files)
    assert CoaxialForward6State(without_lam0_cm=True).spec() != CoaxialForward6State().spec()
    with pytest.raises(TypeError, match="without_lam0_cm"):
        CoaxialForward6State(without_lam0_cm="yes")


@pytest.mark.parametrize("structure, truth", [(CoaxialForwardIsolated(), ROTORS),
                                              (CoaxialForward6State(), {**ROTORS, **INTERFERENCE})],
                         ids=["isolated", "6state"])
def test_pipeline_starts_recover_exact_data(structure, truth):
    # what identify_inflow does: fit every data-driven start, keep the lowest cost
    data = _exact(structure, truth)
    candidates = _start_candidates(structure, data, IdentificationSettings(), OMEGA)
    fits = [fit(structure.build(init, OMEGA), data, frequency_ranges=(1.0, 25.0), n_omega=20, **structure.fit_options)
            for _, init in candidates]
    best = min(fits, key=lambda r: r.J_ave)
    # exact data: the optimum is the truth, J_ave ~1e-3 (measured 1e-4 and 9e-4: the cost's
    # 20-point interpolation, not a misfit); 1 is far below the ~80 of a wrong optimum
    assert best.J_ave < 1.0
    for name, value in truth.items():
        # measured worst 0.4 % (the 6-state's smallest cross delay); 2 % or 2e-4 absolute
        # leaves room for the optimiser's tolerance and flags a wrong optimum (errors of O(1))
        assert best.structure.values[name] == pytest.approx(value, rel=0.02, abs=2e-4), name
    if structure.interference:
        # the low-frequency start alone ends in a wrong optimum on these data (J_ave ~80):
        # the equation-error start is what recovers the interference masses
        assert [label for label, _ in candidates][-1].startswith("equation-error M")


def _fake_model(structure, free, J, failures):
    """A stand-in with what the table reads of an IdentifiedModel."""
    params = pd.DataFrame({"parameter": [f"p{k}" for k in range(len(free))], "value": 1.0, "status": "free",
                           "cramer_rao_pct": [c for c, _ in free], "insensitivity_pct": [i for _, i in free]})
    params.loc[len(params)] = {"parameter": "fixed", "value": 0.0, "status": "fixed", "cramer_rao_pct": 1e9,
                               "insensitivity_pct": 1e9}
    return SimpleNamespace(structure=structure, parameters=params, J_ave=J,
                           trust=SimpleNamespace(failures=failures), provenance={},
                           verification_table=pd.DataFrame({"output": ["a", "b"], "TIC": [0.2, 0.7]}))


def test_candidate_table_columns_and_the_largest_trusted():
    from aircraft.identification.structures import CoaxialForward12State
    models = {"iso": _fake_model(CoaxialForwardIsolated(), [(5.0, 1.0), (12.0, 3.0)], 40.0, []),
              "six": _fake_model(CoaxialForward6State(), [(5.0, 1.0), (15.0, 2.0), (8.0, 9.0)], 30.0, []),
              "near": _fake_model(CoaxialForward12State(near_wake_only=True), [(50.0, 1.0)] * 5, 20.0,
                                  ["J_ave 120 > 100", "parameters outside the bounds"])}
    models["six"].provenance["verification_error"] = "the reduced model's doublet simulation failed"
    table = candidate_structures_table(models, {"iso": 1.5})
    assert table.columns.tolist() == list(CANDIDATE_COLUMNS)
    t = table.set_index("structure")
    # hand counts: the fixed row is not free and its bounds are not the maxima
    assert t.loc["iso", "free_parameters"] == 2 and t.loc["six", "free_parameters"] == 3
    assert t.loc["six", "max_cramer_rao_pct"] == 15.0 and t.loc["six", "max_insensitivity_pct"] == 9.0
    assert (t.states.tolist(), t.parameters_start.tolist()) == ([6, 6, 12], [24, 42, 72])
    assert t.trusted.tolist() == [True, True, False]
    assert t.loc["near", "reasons"] == "J_ave 120 > 100 | parameters outside the bounds"
    assert t.loc["iso", "wall_s"] == 1.5 and np.isnan(t.loc["six", "wall_s"])
    # the worst doublet TIC; none where the reduced model's doublet simulation failed
    assert t.loc["iso", "max_doublet_tic"] == 0.7 and np.isnan(t.loc["six", "max_doublet_tic"])
    assert t.loc["six", "note"].startswith("the reduced model") and t.loc["iso", "note"] == ""
    result = CandidateStructures(models, table)
    assert result.largest_trusted == "six"
    assert CandidateStructures({}, candidate_structures_table({})).largest_trusted is None


def test_default_candidates_and_bad_structures():
    from aircraft.identification.coaxial_forward_flight import identify_coaxial_forward
    from aircraft.identification.coaxial_forward_candidates import identify_candidate_structures
    from aircraft.identification.structures import Coaxial12State
    got = default_candidates()
    assert tuple(got) == DEFAULT_CANDIDATES
    sizes = [len(s.parameter_names()) for s in got.values()]
    assert sizes == sorted(sizes) == [24, 24, 42, 42, 72]
    # the records are the 12-state's: the same six swashplate sweeps in the same order
    from aircraft.identification.structures import CoaxialForward12State
    assert all(s.excitations == CoaxialForward12State().excitations for s in got.values())
    with pytest.raises(ValueError, match="at least one"):
        identify_candidate_structures({})
    # flap-rate inputs need tip-path-plane sweeps the 200 kt records do not have
    with pytest.raises(TypeError, match="flap-rate"):
        identify_coaxial_forward(structure=Coaxial12State(), ct=0.0124)
    with pytest.raises(ValueError, match="verification_failure"):
        identify_coaxial_forward(ct=0.0124, verification_failure="ignore")
