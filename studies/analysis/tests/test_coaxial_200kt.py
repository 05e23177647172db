"""The 200 kt isolated-rotor check (studies.analysis.coaxial_200kt)."""
import numpy as np
import pytest
from aircraft.inflow.published import COAXIAL_200KT_12STATE


def test_isolated_rotor_check_bad_input_and_single_rotor():
    from aircraft.configs import uh60_single_rotor
    from aircraft.identification.coaxial_forward_flight import identify_coaxial_forward
    from studies.analysis.coaxial_200kt import isolated_rotor_check
    with pytest.raises(ValueError, match="inflows is empty"):
        isolated_rotor_check({})
    with pytest.raises(ValueError, match="band"):
        isolated_rotor_check({"x": object()}, band=(5.0, 1.0))
    with pytest.raises(ValueError, match="thresholds"):
        isolated_rotor_check({"x": object()}, threshold_db=0.0)
    with pytest.raises(ValueError, match="coaxial"):
        identify_coaxial_forward(uh60_single_rotor(), ct=0.0124)
    with pytest.raises(TypeError, match="CoaxialForward12State"):
        identify_coaxial_forward(structure="coaxial_6state", ct=0.0124)


@pytest.mark.slow
def test_isolated_rotor_check_against_itself_and_the_printed_model():
    # Isolated Rotors entered as a model must coincide with the reference (0 dB, 0 deg):
    # the plumbing compares like with like. The printed Eqs. 6.12-6.13 were identified at
    # the lift offsets of the dissertation's trim; with the lift-offset input paired as
    # Eq. 7.19 says, our aircraft trims to lift offsets ~0.35 at 200 kt, where the printed
    # model finds no trim within the budget: the check reports that as a verdict, not a crash
    from studies.analysis.coaxial_200kt import isolated_rotor_check
    from aircraft.inflow import IdentifiedInflow, IsolatedRotors
    from aircraft.inflow.published import in_rotor_frames
    w = np.logspace(0.0, np.log10(20.0), 30)
    chk = isolated_rotor_check({"copy": IsolatedRotors(),
                                "Eqs. 6.12-6.13": IdentifiedInflow.from_published(
                                    in_rotor_frames(COAXIAL_200KT_12STATE))}, omega=w)
    d = chk.differences.set_index(["model", "response"])
    assert (d.loc["copy"].max_abs_magnitude_diff_db < 1e-9).all()
    assert chk.holds("copy")
    v = chk.verdicts().set_index("model")
    assert v.loc["copy", "isolated_rotors_hold"] and v.loc["copy", "trim"] == "converged"
    assert v.loc["Eqs. 6.12-6.13", "trim"].startswith("failed")
    with pytest.raises(KeyError, match="no model"):
        chk.holds("nothing")
    fig = chk.plot()
    assert len(fig.axes) == 8


@pytest.mark.slow
def test_isolated_rotor_check_reports_when_no_model_trims():
    # every model but the reference failing to trim is a verdict, not a KeyError
    from studies.analysis.coaxial_200kt import isolated_rotor_check
    from aircraft.inflow import IdentifiedInflow
    from aircraft.inflow.published import in_rotor_frames
    chk = isolated_rotor_check({"Eqs. 6.12-6.13": IdentifiedInflow.from_published(
        in_rotor_frames(COAXIAL_200KT_12STATE))}, omega=np.logspace(0.0, 1.0, 10))
    v = chk.verdicts()
    assert list(v.model) == ["Eqs. 6.12-6.13"] and v.trim.iloc[0].startswith("failed")


def test_structures_table_marks_the_largest_trusted_and_keeps_failures():
    # stand-ins with what the table reads of an IdentifiedModel; hand-counted expectations
    from types import SimpleNamespace
    import pandas as pd
    from aircraft.identification.coaxial_forward_candidates import (CANDIDATE_COLUMNS, CandidateStructures,
                                                                    candidate_structures_table)
    from aircraft.identification.structures import CoaxialForward12State
    from aircraft.identification.structures.coaxial_forward_small import CoaxialForward6State, CoaxialForwardIsolated
    from studies.analysis.coaxial_200kt import structures_table

    def fake(structure, n_free, failures):
        params = pd.DataFrame({"parameter": [f"p{k}" for k in range(n_free)], "status": "free",
                               "cramer_rao_pct": 5.0, "insensitivity_pct": 1.0})
        return SimpleNamespace(structure=structure, parameters=params, J_ave=50.0,
                               trust=SimpleNamespace(failures=failures))

    models = {"iso": fake(CoaxialForwardIsolated(), 10, []), "six": fake(CoaxialForward6State(), 20, [])}
    cands = CandidateStructures(models, candidate_structures_table(models), {"near": "ValueError: no stable start"})
    table = structures_table("main", fake(CoaxialForward12State(), 100, ["J_ave 120 > 100"]), 600.0, cands)
    assert table.columns.tolist() == list(CANDIDATE_COLUMNS) + ["largest_trusted"]
    assert table.structure.tolist() == ["iso", "six", "near", "main"]
    assert table.trusted.tolist() == [True, True, False, False]
    # the trusted row with the most free parameters (20 > 10); the larger main is not trusted
    assert table.largest_trusted.tolist() == [False, True, False, False]
    assert table.set_index("structure").loc["near", "reasons"].startswith("identification failed")
    assert table.set_index("structure").loc["main", "wall_s"] == 600.0
