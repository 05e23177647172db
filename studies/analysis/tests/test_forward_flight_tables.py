"""The forward-flight comparison tables (studies.analysis.forward_flight)."""
import numpy as np
import pytest

from studies.analysis.forward_flight import forward_comparison_table, sign_note
from aircraft.identification import pitt_peters_forward


def test_comparison_table_needs_a_model():
    with pytest.raises(ValueError, match="at least one"):
        forward_comparison_table({})


def test_pitt_peters_reference_is_the_hover_closed_form_at_mu_zero():
    # Pitt-Peters hover: M11 = 8 / (3 pi) (azimuth time); momentum theory C_T = 2 lam^2 gives
    # Lbar11 = dC_T/dlam = 4 lam with lam = sqrt(C_T / 2) (the mass-flow perturbation included)
    ct = 0.0061
    M, L = pitt_peters_forward(ct, 0.0)
    assert M[0, 0] == pytest.approx(8.0 / (3.0 * np.pi), rel=1e-6)
    assert L[0, 0] == pytest.approx(4.0 * np.sqrt(ct / 2.0), rel=1e-3)


def test_sign_notes_say_why_and_compare_with_pitt_peters():
    assert "wake skew" in sign_note("Lbar31", 0.1, 0.06) and "same sign" in sign_note("Lbar31", 0.1, 0.06)
    assert "OPPOSITE" in sign_note("Lbar11", -0.02, 0.16)
    assert "moment signs" in sign_note("M22/Omega [s]", -0.007, -0.004)
    assert "not identified" in sign_note("Lbar13", 0.0, 0.08)
