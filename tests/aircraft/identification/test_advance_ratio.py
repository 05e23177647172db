"""identify_over_advance_ratio against known truths, the wake replaced by a scipy simulation.

``run_sweeps`` is swapped for a stand-in that drives a known M/Lbar/tau model
(simulated with scipy, :func:`aircraft.identification.testing.simulate_mltau`, not with
flightid's model code) through a fully populated control-to-load mixing: in hover the
printed diagonal hover form, in forward flight the printed mu = 0.2 model (the
forward-flight structure with its longitudinal couplings and delays). The pipeline
(sweeps -> chirp-z -> joint input-output -> fit) must recover each within 5 %.
"""
import math

import matplotlib
import numpy as np
import pytest

import aircraft.wake as wake_pkg
from aircraft.configs import uh60_single_rotor
from aircraft.identification import IdentificationSettings
from aircraft.identification.advance_ratio import AdvanceRatioSweep, identify_over_advance_ratio
from aircraft.identification.structures.forward import KEY_RESPONSES
from aircraft.inflow.published import UH60_HOVER_MFW, UH60_MU02_MFW
from aircraft.wake import WakeSettings
from tests.aircraft.identification._simulated_wake import simulated_runs

matplotlib.use("Agg")

SETTINGS = IdentificationSettings(wake=WakeSettings(azimuth_step=math.radians(20.0), wake_revolutions=1.5,
                                                    n_elements=5), reduce=False, sweep_s=45.0)
OMEGA = float(uh60_single_rotor().rotors[0].omega)

#: hover truth: the printed hover 3-state (Table 4.1: diagonal, cyclic rows equal), M per d/dpsi
HOVER = {"M": UH60_HOVER_MFW.M * UH60_HOVER_MFW.omega if UH60_HOVER_MFW.time == "seconds" else UH60_HOVER_MFW.M,
         "Lbar": UH60_HOVER_MFW.Lbar, "tau": UH60_HOVER_MFW.tau}
#: forward-flight truth: the printed mu = 0.2 model (M printed as M/Omega [s])
FORWARD = {"M": UH60_MU02_MFW.M * UH60_MU02_MFW.omega, "Lbar": UH60_MU02_MFW.Lbar, "tau": UH60_MU02_MFW.tau}


def _truth(flight):
    return HOVER if flight.speed == 0 else FORWARD


def _fake_run_sweeps(config, settings, flight, specs, **kwargs):
    truth = _truth(flight)
    # 0.5 % measurement noise of each signal's RMS (and a floor for the zero-input run)
    return simulated_runs(specs, settings.azimuth_step / OMEGA, OMEGA, truth["M"], truth["Lbar"], truth["tau"],
                          noise=0.005, trim_outputs={"CT": 0.0061, "lam0": 0.05})


@pytest.fixture()
def fake_wake(monkeypatch):
    monkeypatch.setattr(wake_pkg, "run_sweeps", _fake_run_sweeps)


def test_known_hover_and_forward_flight_models_are_recovered(fake_wake):
    # the truth is of the structure's form, so all five key responses (lam0/CM included) apply
    sweep = identify_over_advance_ratio(uh60_single_rotor(), [0.2, 0.0], settings={0.0: SETTINGS, 0.2: SETTINGS},
                                        n_jobs=1, progress=False, pairs=KEY_RESPONSES)
    assert isinstance(sweep, AdvanceRatioSweep) and sweep.mus == [0.0, 0.2]
    for mu, truth in ((0.0, HOVER), (0.2, FORWARD)):
        mats = sweep.models[mu].fit.structure.matrices()
        # the brief's target: every nonzero M and Lbar entry of the truth within 5 % (noise-free
        # data would give the truth to the fit's tolerance; 0.5 % noise moves it by well under 1 %)
        for mat in ("M", "Lbar"):
            for i, j in zip(*np.nonzero(truth[mat])):
                assert mats[mat][i, j] == pytest.approx(truth[mat][i, j], rel=0.05), (mu, mat, i, j)
            # entries the truth lacks stay zero (structural zeros of either structure)
            assert np.all(mats[mat][truth[mat] == 0] == 0)
        # delays within 5 ms: the sample time of the stand-in is 20 deg / 27 rad/s = 13 ms and the
        # delays are applied by interpolation, so a few ms is the resolution of the truth itself
        np.testing.assert_allclose(mats["tau"][truth["tau"] != 0], truth["tau"][truth["tau"] != 0], atol=5e-3)
    table = sweep.to_pandas()
    assert len(table) == 2 * 8 and set(table.mu) == {0.0, 0.2}
    # the table's M entries are M/Omega [s]: the printed Eq. 4.8 value comes back
    m11 = table[(table.mu == 0.2) & (table.coefficient == "M11/Omega [s]")].ours.item()
    assert m11 == pytest.approx(0.0254, rel=0.05)
    # hover: the couplings are not in the structure, Lbar33 is tied to Lbar22
    hover = table[table.mu == 0.0].set_index("coefficient")
    assert hover.loc["Lbar13", "status"] == "not in model" and hover.loc["Lbar33", "status"] == "tied"
    # Pitt-Peters beside it: its hover M11 is 8/(3 pi) per d/dpsi
    assert hover.loc["M11/Omega [s]", "pitt_peters"] == pytest.approx(8 / (3 * np.pi) / OMEGA, rel=1e-6)
    fig = sweep.plot(n_points=5)
    assert len(fig.axes) == 3


def test_bad_advance_ratios_are_refused():
    cfg = uh60_single_rotor()
    with pytest.raises(ValueError, match="at least one"):
        identify_over_advance_ratio(cfg, [])
    with pytest.raises(ValueError, match=">= 0"):
        identify_over_advance_ratio(cfg, [0.1, -0.1])
    with pytest.raises(ValueError, match="repeat"):
        identify_over_advance_ratio(cfg, [0.1, 0.1])
    with pytest.raises(ValueError, match=">= 0"):
        identify_over_advance_ratio(cfg, [True])
    with pytest.raises(ValueError, match="not in mus"):
        identify_over_advance_ratio(cfg, [0.1], settings={0.2: SETTINGS})


def test_forward_structure_start_and_pairs_options():
    from aircraft.identification import pitt_peters_forward
    from aircraft.identification.structures.forward import (FORWARD_FIT_PAIRS, SingleRotorForward,
                                                            pitt_peters_start)
    plain = SingleRotorForward()
    # without the options the structure (and so every settings hash) is what it was
    assert plain.spec() == {"key": "single_rotor_forward", "frame": "rotor", "form": plain.form,
                            "protected": ["m11", "m22"], "pattern": "eq4_3"}
    assert plain.fit_options == {} and plain.extra_starts(None, 27.0) == []
    M, L = pitt_peters_forward(0.0061, 0.2)
    start = pitt_peters_start(M, L)
    # the start is the Pitt-Peters matrices entry by entry (couplings included)
    assert start["l13"] == L[0, 2] and start["l31"] == L[2, 0] and start["m22"] == M[1, 1]
    s = SingleRotorForward(start=start, pairs=FORWARD_FIT_PAIRS)
    assert s.fit_options == {"pairs": list(FORWARD_FIT_PAIRS)} and ("lam0", "CM") not in s.pairs
    assert s.extra_starts(None, 27.0) == [("given start", start)]
    assert s.spec()["pairs"] == [list(p) for p in FORWARD_FIT_PAIRS] and "start" in s.spec()
    with pytest.raises(ValueError, match="start lacks"):
        SingleRotorForward(start={"m11": 1.0})
    with pytest.raises(ValueError, match="pairs must be"):
        SingleRotorForward(pairs=[("lam0", "CQ")])
    with pytest.raises(ValueError, match="3 x 3"):
        pitt_peters_start(np.eye(2), L)

