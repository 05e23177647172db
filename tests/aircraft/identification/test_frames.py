"""Frame conversion between the dissertation's common frame and our rotor frames.

The checks are independent of :mod:`aircraft.inflow.frames`: the
harmonics of one physical field (and of a rotated one) are computed with the
wake's own blade geometry (``FreeVortexWake._blade_frames``) and blade-sum
harmonic code (:mod:`aircraft.wake.outputs`) for a counter-clockwise and a
clockwise rotor.
"""
import types

import numpy as np
import pytest

from aircraft.identification.structures import Coaxial6State, Coaxial12State
from aircraft.inflow.frames import FrameError, convert_frames, frame_signs
from aircraft.inflow import IdentifiedInflow, inflow_names, load_names
from aircraft.inflow.published import (COAXIAL_HOVER_6STATE, COAXIAL_HOVER_12STATE, UH60_HOVER_MFW,
                                       fgc_state_names, in_rotor_frames)
from aircraft.wake.outputs import blade_sum_inflow, blade_sum_loads
from aircraft.wake.wake import FreeVortexWake

NB, PSI0 = 4, 0.3           # 4 blades, an arbitrary reference azimuth
R_EL = np.linspace(0.2, 0.95, 12)
DR = np.full(R_EL.size, R_EL[1] - R_EL[0])


def _body_xy(d, psi):
    """Body (forward, right) positions on R of every element of every blade, from the wake's geometry."""
    er, *_ = FreeVortexWake._blade_frames(None, types.SimpleNamespace(d=d), psi, np.zeros_like(psi))
    # wake body axes: x forward, y left, z up
    return er[:, 0:1] * R_EL[None, :], -er[:, 1:2] * R_EL[None, :]


def _harmonics(d, field):
    """(lam0, lam1s, lam1c) of ``field(x_fwd, y_right)`` seen by a rotor turning ``d``."""
    psi = PSI0 + 2 * np.pi * np.arange(NB) / NB
    x, y = _body_xy(d, psi)
    return np.array(blade_sum_inflow(field(x, y), R_EL, DR, psi))


def _loads(d, field):
    """(CT, CL, CM) of a thrust distribution ``field(x, y)`` [N per element] for direction d."""
    psi = PSI0 + 2 * np.pi * np.arange(NB) / NB
    x, y = _body_xy(d, psi)
    return np.array(blade_sum_loads(field(x, y), np.zeros((NB, R_EL.size)), R_EL, psi, 1.0)[:3])


def _rotor_map(d, phi, fn=_harmonics):
    """3x3 map of (0, 1s, 1c) harmonics under a physical rotation by phi (CCW from above)."""
    c, s = np.cos(phi), np.sin(phi)
    basis = [lambda x, y: 1.0 + 0 * x, lambda x, y: y, lambda x, y: x]
    cols_before = np.array([fn(d, f) for f in basis]).T
    rotated = [lambda x, y, f=f: f(c * x + s * y, -s * x + c * y) for f in basis]
    cols_after = np.array([fn(d, f) for f in rotated]).T
    return cols_after @ np.linalg.inv(cols_before)


def test_one_physical_field_in_both_rotor_frames_differs_by_frame_signs():
    # a lateral + longitudinal inflow gradient seen by a CCW (upper) and a CW (lower) rotor
    field = lambda x, y: 0.05 + 0.02 * y - 0.013 * x       # noqa: E731
    upper, lower = _harmonics(1, field), _harmonics(-1, field)
    signs = frame_signs(["lam0_L", "lam1s_L", "lam1c_L"], {"U": 1, "L": -1})
    # the blade sums recover a linear field exactly with 4 blades (round-off only)
    np.testing.assert_allclose(lower, signs * upper, atol=1e-12)
    assert signs.tolist() == [1, -1, 1]
    # loads: the same physical thrust distribution
    dT = lambda x, y: 3.0 + 1.5 * y + 0.7 * x               # noqa: E731
    lu, ll = _loads(1, dT), _loads(-1, dT)
    np.testing.assert_allclose(ll, frame_signs(["CT_L", "CL_L", "CM_L"], {"U": 1, "L": -1}) * lu, atol=1e-12)


def _q(phi, mirrored):
    """6x6 map of (lam0, lam1s, lam1c) per rotor under a physical rotation, in rotor frames
    (lower rotor clockwise) or, with ``mirrored=False``, both rotors in the upper's frame."""
    qu = _rotor_map(1, phi)
    ql = _rotor_map(-1, phi) if mirrored else qu
    q = np.zeros((6, 6))
    q[:3, :3], q[3:, 3:] = qu, ql
    return q


def _dc(model):
    return np.linalg.inv(model.Lbar)


def test_loads_rotate_like_inflow_harmonics():
    for d in (1, -1):
        np.testing.assert_allclose(_rotor_map(d, 0.7, _loads), _rotor_map(d, 0.7), atol=1e-12)


@pytest.mark.parametrize("phi", [np.pi / 2, 0.61])
def test_hover_symmetry_holds_for_eq53_in_our_frames_only_after_conversion(phi):
    # hover is axisymmetric: rotating the whole coaxial about the shaft must leave
    # lambda/C unchanged, H = Q H Q^-1, in whatever frames H is written
    printed = _dc(COAXIAL_HOVER_6STATE)
    ours = _dc(in_rotor_frames(COAXIAL_HOVER_6STATE))
    q_rotor, q_common = _q(phi, True), _q(phi, False)
    sym = lambda h, q: np.abs(q @ h @ np.linalg.inv(q) - h).max() / np.abs(h).max()   # noqa: E731
    assert sym(ours, q_rotor) < 1e-9            # converted: symmetric in our frames
    assert sym(printed, q_common) < 1e-9        # printed: symmetric in a common frame
    assert sym(printed, q_rotor) > 0.1          # printed, read in our frames: broken


def test_converted_eq53_flips_only_the_cross_rotor_lateral_couplings():
    m = COAXIAL_HOVER_6STATE
    c = in_rotor_frames(m)
    flipped = np.argwhere(np.sign(c.M) != np.sign(m.M))
    assert sorted(map(tuple, flipped)) == [(1, 4), (4, 1)]       # m25, m52
    assert sorted(map(tuple, np.argwhere(np.sign(c.Lbar) != np.sign(m.Lbar)))) == [(1, 4), (4, 1)]
    np.testing.assert_array_equal(c.tau, m.tau)
    # lam1s_L/CL_U quasi-steady: negative as printed, positive in our frames (our wake
    # measured +12.3 at 1 rad/s); lam1c_L/CM_U keeps its sign
    assert _dc(m)[4, 1] < 0 < _dc(c)[4, 1]
    assert _dc(m)[5, 2] < 0 and _dc(c)[5, 2] < 0
    # the conversion is its own inverse; a single rotor is unchanged
    back = convert_frames(c.M, load_names(("U", "L")), inflow_names(("U", "L")), {"U": 1, "L": -1})
    np.testing.assert_array_equal(back, m.M)
    np.testing.assert_array_equal(in_rotor_frames(UH60_HOVER_MFW).M, UH60_HOVER_MFW.M)
    with pytest.raises(FrameError):
        in_rotor_frames(c)


def test_library_structures_obey_hover_symmetry_in_our_frames():
    rng = np.random.default_rng(4)
    s6 = Coaxial6State("rotor")
    vals = {k: rng.uniform(-1, 1) + (2.0 if k in ("m11", "m44", "l11", "l44") else 0.0)
            for k in s6.published_values(COAXIAL_HOVER_6STATE)}
    st = s6.build({k: (abs(v) if k.startswith("t") else v) for k, v in vals.items()}, 23.7)
    h = st.frequency_response([0.0])[:, :, 0]
    q = _q(0.9, True)
    np.testing.assert_allclose(q @ h @ np.linalg.inv(q), h, atol=1e-10 * np.abs(h).max())
    # the printed-frame structure is symmetric in a common frame instead
    hp = Coaxial6State("printed").build(st.values, 23.7).frequency_response([0.0])[:, :, 0]
    qc = _q(0.9, False)
    np.testing.assert_allclose(qc @ hp @ np.linalg.inv(qc), hp, atol=1e-10 * np.abs(hp).max())


def test_tied_12state_structure_obeys_hover_symmetry_with_flap_rate_inputs():
    s12 = Coaxial12State("rotor", tied=True)
    rng = np.random.default_rng(7)
    init = {n: rng.uniform(-1, 1) for n in s12.parameter_names()}
    for k in (1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12):      # stable diagonal
        init[f"f{k}_{k}"] = -3.0 - rng.uniform()
        init[f"f{k}_{k}"] = init.get(f"f{k}_{k}")
    st = s12.build(init, 23.7)
    h = st.frequency_response([0.0, 2.0])                   # (6, 10, 2): inflow / (loads, flap rates)
    q = _q(0.4, True)
    # flap rates (b1s_dot, b1c_dot) per rotor rotate like the (1s, 1c) harmonics
    qr = np.zeros((4, 4))
    qr[:2, :2], qr[2:, 2:] = _q(0.4, True)[1:3, 1:3], _q(0.4, True)[4:, 4:]
    qin = np.zeros((10, 10))
    qin[:6, :6], qin[6:, 6:] = q, qr
    for k in range(2):
        np.testing.assert_allclose(q @ h[:, :, k] @ np.linalg.inv(qin), h[:, :, k], atol=1e-10)


def test_12state_structure_represents_eq69_after_conversion():
    s12 = Coaxial12State("rotor", tied=False)
    st = s12.build(s12.published_values(COAXIAL_HOVER_12STATE), COAXIAL_HOVER_12STATE.omega)
    conv = in_rotor_frames(COAXIAL_HOVER_12STATE)
    ref = IdentifiedInflow.from_fgc(conv.F, conv.G, conv.C, input_order=conv.input_order)
    w = np.array([0.3, 3.0, 20.0])
    h_ref = np.stack([ref.system(1j * x) for x in w], axis=2)
    np.testing.assert_allclose(st.frequency_response(w), h_ref, rtol=1e-10, atol=1e-12 * np.abs(h_ref).max())
    # a similarity transform: same poles as printed
    np.testing.assert_allclose(np.sort_complex(np.linalg.eigvals(conv.F)),
                               np.sort_complex(np.linalg.eigvals(COAXIAL_HOVER_12STATE.F)), rtol=1e-10)
    assert fgc_state_names(("U", "L"))[2] == "lam1sN_U"


def test_frame_signs_reject_unknown_rotors_and_directions():
    with pytest.raises(FrameError):
        frame_signs(["lam1s_X"], {"U": 1, "L": -1})
    with pytest.raises(FrameError):
        frame_signs(["lam1s_U"], {"U": 2})
    with pytest.raises(FrameError):
        convert_frames(np.eye(2), ["CT_U"], ["CT_U", "CL_U"], {"U": 1})
