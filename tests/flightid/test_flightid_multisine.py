"""Orthogonal multisines and MIMO response estimation from simultaneous inputs.

The references are independent of flightid: analytic transfer matrices
``C (jwI - A)^-1 B`` of systems simulated with :func:`scipy.signal.lsim`, numpy
FFTs and dot products, and the SISO estimator :func:`flightid.frequency_response`.
"""
import numpy as np
import pytest
import scipy.signal as sig

from flightid import (DataError, MeasuredResponse, frequency_response, joint_input_output, mimo_response, orthogonal_multisine)
from flightid.errors import InputValueError, SingularInputError
from flightid.mimo import MIMOResponse, harmonic_response
from flightid.multisine import relative_peak_factor
from flightid.sweeps import shaped_noise

DT = 0.01
# well-damped 2-state, 2-input, 3-output system (poles -2 +- 2j, zeta 0.71)
A = np.array([[-2.0, 2.0], [-2.0, -2.0]])
B = np.array([[1.0, 0.5], [0.0, 2.0]])
C = np.array([[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
D = np.zeros((3, 2))


def _truth(omega, a=A, b=B, c=C):
    n = a.shape[0]
    return np.array([c @ np.linalg.solve(1j * w * np.eye(n) - a, b) for w in omega]).transpose(1, 2, 0)


def _correlated_record(seconds=150.0, mix=0.6):
    t = np.arange(0.0, seconds, DT)
    u1 = shaped_noise(t.size, DT, 0.2, 40.0, seed=1)
    u2 = mix * u1 + shaped_noise(t.size, DT, 0.2, 40.0, seed=2)
    u = np.column_stack([u1, u2])
    _, y, _ = sig.lsim(sig.StateSpace(A, B, C, D), u, t)
    return t, u, y


# --- orthogonal_multisine ------------------------------------------------------------------

def test_multisine_harmonic_sets_are_disjoint_and_cover_the_band():
    ms = orthogonal_multisine(3, 20.0, DT, 1.0, 20.0, 0.05, seed=3)
    t, U, harmonics = ms
    dw = 2 * np.pi / ms.period
    all_k = np.sort(np.concatenate(harmonics))
    expected = np.arange(int(np.ceil(1.0 / dw)), int(np.floor(20.0 / dw)) + 1)
    np.testing.assert_array_equal(all_k, expected)          # every harmonic used exactly once
    assert U.shape == (t.size, 3) and t.size == round(20.0 / DT)
    np.testing.assert_allclose(np.abs(U).max(axis=0), 0.05, rtol=1e-12)   # the given peak
    # numpy FFT of one period: each input has power only at its own harmonics
    F = np.fft.rfft(U, axis=0)
    for j, k in enumerate(harmonics):
        others = np.setdiff1d(np.arange(F.shape[0]), k)
        assert np.abs(F[others, j]).max() < 1e-9 * np.abs(F[k, j]).min()
    # orthogonal over the period: zero cross-products (round-off only)
    gram = U.T @ U
    off = gram - np.diag(np.diag(gram))
    assert np.abs(off).max() < 1e-10 * np.diag(gram).min()


def test_multisine_peak_factor_is_low_and_matches_its_definition():
    ms = orthogonal_multisine(4, 30.0, DT, 0.5, 25.0, 1.0, spectrum="log", seed=0)
    u = ms.U
    rpf = (u.max(0) - u.min(0)) / (2 * np.sqrt(2) * np.sqrt(np.mean((u - u.mean(0)) ** 2, axis=0)))
    np.testing.assert_allclose(ms.relative_peak_factor, rpf, rtol=1e-12)
    # equal phases of N harmonics give about sqrt(2 N); Schroeder phases and clipping give ~1.1-1.5
    # (Morelli 2003 reports 1.0-1.2 with his optimiser); 1.6 leaves margin for a small N
    assert np.all(ms.relative_peak_factor < 1.6)
    plain = orthogonal_multisine(4, 30.0, DT, 0.5, 25.0, 1.0, spectrum="log", seed=0, iterations=0)
    assert np.all(ms.relative_peak_factor <= plain.relative_peak_factor + 1e-12)
    k = ms.harmonics[0]
    same_phase = np.sum(np.sin(2 * np.pi * np.outer(np.arange(ms.t.size) / ms.t.size, k)), axis=1)
    assert relative_peak_factor(same_phase) > 2 * ms.relative_peak_factor[0]
    # log spectrum: amplitude ~ w^-1/2
    a = ms.harmonic_amplitudes[1]
    w = ms.omega[1]
    np.testing.assert_allclose(a * np.sqrt(w), a[0] * np.sqrt(w[0]), rtol=1e-12)


def test_multisine_is_reproducible_and_periodic():
    a = orthogonal_multisine(2, 10.0, DT, 1.0, 10.0, [0.1, 0.2], n_periods=3, seed=7)
    b = orthogonal_multisine(2, 10.0, DT, 1.0, 10.0, [0.1, 0.2], n_periods=3, seed=7)
    np.testing.assert_array_equal(a.U, b.U)
    n = round(10.0 / DT)
    np.testing.assert_array_equal(a.U[:n], a.U[n:2 * n])
    np.testing.assert_allclose(np.abs(a.U).max(axis=0), [0.1, 0.2])
    assert set(a.harmonic_table().columns) >= {"input", "k", "omega", "amplitude", "phase"}
    assert list(a.to_pandas().columns) == ["t", "u0", "u1"]


def test_multisine_plot(monkeypatch):
    monkeypatch.setenv("MPLBACKEND", "Agg")
    from matplotlib.figure import Figure
    assert isinstance(orthogonal_multisine(2, 10.0, DT, 1.0, 10.0).plot(), Figure)


@pytest.mark.parametrize("kwargs, match", [
    (dict(n_inputs=0), "n_inputs"),
    (dict(duration=-1.0), "duration"),
    (dict(w_min=5.0, w_max=2.0), "w_min < w_max"),
    (dict(w_max=1000.0), "Nyquist"),
    (dict(n_inputs=40, duration=2.0, w_min=5.0, w_max=20.0), "harmonics"),
    (dict(amplitude=[1.0, 2.0, 3.0]), "one per input"),
    (dict(amplitude=float("nan")), "amplitude"),
    (dict(spectrum="pink"), "spectrum"),
    (dict(seed=1.5), "seed"),
    (dict(fade=20.0), "fade"),
])
def test_multisine_rejects_bad_input(kwargs, match):
    args = dict(n_inputs=2, duration=10.0, dt=DT, w_min=1.0, w_max=10.0)
    args.update(kwargs)
    with pytest.raises(InputValueError, match=match):
        orthogonal_multisine(**args)


# --- mimo_response ------------------------------------------------------------------------

def test_mimo_with_one_input_is_frequency_response():
    t, u, y = _correlated_record(60.0)
    a = mimo_response(t, u[:, 0], y, w_min=0.5, w_max=20.0)
    b = frequency_response(t, u[:, 0], y, w_min=0.5, w_max=20.0)
    # the same composite-window algebra: equal to round-off
    np.testing.assert_allclose(a.frdata, b.frdata, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(a.coherence, b.coherence, atol=1e-10)
    np.testing.assert_allclose(a.multiple_coherence, b.coherence[:, 0], atol=1e-10)


def test_mimo_recovers_a_3x2_system_from_correlated_inputs_without_noise():
    t, u, y = _correlated_record()
    r = mimo_response(t, u, y, w_min=0.5, w_max=20.0, input_names=["a", "b"], output_names=["x1", "x2", "s"])
    assert isinstance(r, MIMOResponse) and isinstance(r, MeasuredResponse)
    assert r.input_labels == ["a", "b"] and r.output_labels == ["x1", "x2", "s"]
    truth = _truth(r.omega)
    err = np.abs(r.frdata - truth) / np.abs(truth).max(axis=2, keepdims=True)
    # no noise: what is left is leakage. Inside each Hann window the response to input from
    # before the window is uncorrelated with the window's input and acts like noise: the SISO
    # estimator shows up to 3 % on this system; the inversion of the correlated G_uu amplifies
    # it (measured up to 10 %, median 2 %), so 12 % / 3 % are the bounds, far below an error
    # from a wrong formula (a transposed or uncorrected H is off by O(100 %)).
    assert err.max() < 0.12
    assert np.median(err) < 0.03
    # the inputs really are correlated (coherence 0.6^2 / (0.6^2 + 1) = 0.26 by construction)
    assert 0.15 < np.median(r.input_coherence[0, 1]) < 0.4
    # coherence -> 1 without noise (partial: the other input removed; multiple: both inputs)
    assert np.median(r.coherence) > 0.98 and np.median(r.multiple_coherence) > 0.99
    assert "multiple_coherence" in r.to_pandas().columns


def test_mimo_with_noise_stays_within_its_random_error():
    t, u, y = _correlated_record(300.0)
    rng = np.random.default_rng(11)
    noisy = y + 0.1 * y.std(axis=0) * rng.standard_normal(y.shape)
    r = mimo_response(t, u, noisy, w_min=0.5, w_max=20.0)
    clean = mimo_response(t, u, y, w_min=0.5, w_max=20.0)
    truth = _truth(r.omega)
    err = np.abs(r.frdata - truth) / np.abs(truth).max(axis=2, keepdims=True)
    # 10 % white output noise on a 300 s record: the Bendat-Piersol random error
    # sqrt(1 - g^2) / (|g| sqrt(2 n_d)) is a few % at the worst-excited frequencies
    assert err.max() < 0.1 and np.median(err) < 0.02
    assert np.median(r.coherence) < np.median(clean.coherence)     # noise lowers the coherence
    assert np.all(r.multiple_coherence <= 1.0) and np.median(r.multiple_coherence) > 0.8


def test_mimo_partial_coherence_of_an_input_that_does_not_drive_the_output_is_low():
    # y depends on u1 only; u2 is correlated with u1, so y's ORDINARY coherence with u2 is high
    # but its PARTIAL coherence (u1 removed) is ~0: the conditioned (MISO) analysis separates them
    t = np.arange(0.0, 150.0, DT)
    u1 = shaped_noise(t.size, DT, 0.2, 40.0, seed=4)
    u2 = 0.9 * u1 + 0.3 * shaped_noise(t.size, DT, 0.2, 40.0, seed=5)
    _, y, _ = sig.lsim(sig.StateSpace([[-3.0]], [[3.0, 0.0]], [[1.0]], [[0.0, 0.0]]),
                       np.column_stack([u1, u2]), t)
    y = y + 0.02 * np.random.default_rng(6).standard_normal(t.size)
    r = mimo_response(t, np.column_stack([u1, u2]), y, w_min=0.5, w_max=10.0)
    ordinary = frequency_response(t, u2, y, w_min=0.5, w_max=10.0).coherence[0, 0]
    assert np.median(ordinary) > 0.8
    assert np.median(r.coherence[0, 1]) < 0.1 and np.median(r.coherence[0, 0]) > 0.95
    assert np.median(np.abs(r.frdata[0, 1])) < 0.05 * np.median(np.abs(r.frdata[0, 0]))


def test_mimo_refuses_fully_correlated_inputs():
    t = np.arange(0.0, 40.0, DT)
    u1 = shaped_noise(t.size, DT, 0.5, 30.0, seed=1)
    _, y, _ = sig.lsim(sig.StateSpace([[-1.0]], [[1.0]], [[1.0]], [[0.0]]), u1, t)
    with pytest.raises(SingularInputError, match="fully correlated"):
        mimo_response(t, np.column_stack([u1, 2 * u1]), y, w_min=1.0, w_max=10.0)


@pytest.mark.parametrize("call, match", [
    (lambda t, u, y: mimo_response(t, u[:-1], y, w_min=1.0, w_max=10.0), "u must have shape"),
    (lambda t, u, y: mimo_response(t, u, y, w_min=0.01, w_max=10.0), "too short"),
    (lambda t, u, y: mimo_response(t, np.column_stack([u[:, 0], 0 * u[:, 1]]), y, w_min=1.0, w_max=10.0),
     "constant"),
    (lambda t, u, y: mimo_response(t, u, y, w_min=1.0, w_max=10.0, input_names=["a"]), "input names"),
    (lambda t, u, y: mimo_response(t, u, y, w_min=1.0, w_max=10.0, input_names=["a", "b"],
                                   output_names=["a", "c", "d"]), "unique"),
])
def test_mimo_rejects_bad_input(call, match):
    t, u, y = _correlated_record(30.0)
    with pytest.raises(DataError, match=match):
        call(t, u, y)


def test_joint_input_output_carries_over_to_a_mimo_record():
    # "loads" c = K theta (2 x 2, static mixing), inflow lam = G(s) c with G = C (sI - A)^-1 B
    # (rows 0-1 of C): lam / c from ONE record of both controls, via lam/theta and c/theta
    t, theta, _ = _correlated_record(150.0, mix=0.3)
    K = np.array([[1.0, 0.4], [-0.3, 0.8]])
    c = theta @ K.T
    _, lam, _ = sig.lsim(sig.StateSpace(A, B, C[:2], D[:2]), c, t)
    r = mimo_response(t, theta, np.hstack([c, lam]), w_min=0.5, w_max=20.0,
                      input_names=["th1", "th2"], output_names=["c1", "c2", "l1", "l2"])
    lam_c = joint_input_output(r.select(["l1", "l2"]), r.select(["c1", "c2"]))
    truth = _truth(lam_c.omega, c=C[:2])
    err = np.abs(lam_c.frdata - truth) / np.abs(truth).max(axis=2, keepdims=True)
    assert err.max() < 0.12          # the leakage bound of the 3x2 test
    assert np.median(lam_c.coherence) > 0.95


# --- harmonic_response (direct multisine estimate) ------------------------------------------

def test_harmonic_response_is_exact_at_the_harmonics_of_a_periodic_record():
    ms = orthogonal_multisine(2, 20.0, DT, 0.5, 20.0, 1.0, n_periods=4, seed=1)
    t, U, harmonics = ms
    _, y, _ = sig.lsim(sig.StateSpace(A, B, C, D), U, t)
    omega = np.geomspace(1.0, 19.0, 30)
    r = harmonic_response(t, U, y, harmonics, ms.period, omega=omega, skip=ms.period)
    # reference: the analytic response at each input's own harmonics, interpolated the same way
    ref = np.empty_like(r.frdata)
    for j, k in enumerate(harmonics):
        wk = 2 * np.pi * k / ms.period
        hk = _truth(wk)[:, j, :]
        ref[:, j, :] = [np.interp(omega, wk, h.real) + 1j * np.interp(omega, wk, h.imag) for h in hk]
    # after one period the poles' transient (time constant 0.5 s) has decayed by exp(-40):
    # the discrete-time (first-order hold) simulation is the only error, O((w dt)^2) ~ 1e-3 relative
    np.testing.assert_allclose(r.frdata, ref, atol=3e-3 * np.abs(ref).max())
    np.testing.assert_allclose(r.coherence, 1.0, atol=1e-6)


def test_harmonic_response_coherence_drops_with_noise_and_needs_two_periods():
    ms = orthogonal_multisine(2, 20.0, DT, 0.5, 20.0, 1.0, n_periods=3, seed=1)
    t, U, harmonics = ms
    _, y, _ = sig.lsim(sig.StateSpace(A, B, C, D), U, t)
    noisy = y + 0.2 * y.std(axis=0) * np.random.default_rng(2).standard_normal(y.shape)
    r = harmonic_response(t, U, noisy, harmonics, ms.period, skip=ms.period)
    assert np.median(r.coherence) < 0.999
    with pytest.raises(DataError, match="at least 2"):
        harmonic_response(t, U, y, harmonics, ms.period, skip=2 * ms.period)
    with pytest.raises(DataError, match="overlap"):
        harmonic_response(t, U, y, [harmonics[0], harmonics[0]], ms.period)
    with pytest.raises(DataError, match="whole number"):
        harmonic_response(t, U, y, harmonics, ms.period + 0.3 * DT)
    with pytest.raises(InputValueError, match="within"):
        harmonic_response(t, U, y, harmonics, ms.period, omega=[0.01, 1.0])
