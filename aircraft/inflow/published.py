"""Identified inflow models printed in the reference dissertation, as data.

These are *reference data* (for comparison and for users who want them), never
outputs of our code. Every model is usable as an aircraft inflow model through
:meth:`aircraft.inflow.IdentifiedInflow.from_published`.

Conventions: inputs (dC_T, dC_L, dC_M) per rotor, outputs (lam0, lam1s, lam1c) per
rotor, in the dissertation's (= our, :mod:`aircraft.inflow.base`) perturbation form
``M lam' + Lbar lam = dC(t - tau)`` with ``Lbar = [L]^-1``; delays in seconds,
row-wise (Eq. 2.16). The coaxial models are printed in one common frame for both
rotors; ours mirrors the lower rotor's, so their cross-rotor lateral couplings
change sign in our frames: :func:`in_rotor_frames` converts (derivation in
:mod:`aircraft.inflow.frames`; :meth:`IdentifiedInflow.from_published` keeps
the printed frame, ``IdentifiedInflow.from_file("eq5_3")`` loads the converted model).
``time`` says what ``M`` multiplies:

* ``"azimuth"``: ``d/dpsi`` (dimensionless ``M``; Eq. 5.3, where M11 = 0.851 ~ 8/(3 pi));
* ``"seconds"``: ``d/dt``, i.e. the printed numbers are ``M/Omega`` [s] (Tables
  4.1-4.2 say so; for Eqs. 4.7-4.8 it is our reading: 0.0394 and 0.0254 are close
  to the hover M11/Omega = 0.0379 of Table 4.1 and far from 8/(3 pi) = 0.85, and
  §4.5's "average of the identified M22 and M33 values is -0.0052" is the mean of
  -0.0063, -0.00603, -0.00323 in these units; its M11 average, 0.0354, is 3 %
  above the mean 0.0342 of 0.0379, 0.0394, 0.0254).

The F/G/C models (Eqs. 6.8-6.9, 6.12-6.13) are ``x' = F x + G u`` [1/s] with six
near/far-wake states per rotor and ``lambda = lambda_N + lambda_F`` (Eqs. 6.2-6.5);
the flap-rate inputs of Eq. 6.9 are taken as rad/s (the dissertation gives no unit;
with rad/s the printed gains, about 0.2-0.3, match an analytical K_R ~ 1 through
(Omega/M22) Lbar22 K_R / Omega ~ 0.28 K_R, whereas reading them per d/dpsi would
imply K_R ~ 0.04).

Suspected transcription errors and oddities (values are kept exactly as printed)
------------------------------------------------------------------------------
* Tables 4.1-4.2, Pitt-Peters rows: Lbar11 = 0.214 and Lbar22 = -0.0534 are
  mutually consistent (ratio -4.0) but imply lambda_h = 0.0534, i.e. C_T = 0.0057,
  not the nominal C_T = 0.0061 of Appendix B (which gives 4 lambda_h = 0.221,
  -lambda_h = -0.0552). The M rows match 8/(3 pi)/27 and -16/(45 pi)/27.
* Eqs. 4.7-4.8: the delay matrices are printed garbled as ``t - [t - tau]`` (Eq.
  4.7) and as a matrix of ``t - tau`` multiplying the loads (Eq. 4.8); we read the
  numbers as tau. Eq. 4.8 prints tau13 = 0.00 although tau13 is listed among the 12
  identified parameters.
* Eq. 5.3: §5.3 lists the ties "m44 = m55" and "l44 = l55", which contradict its own
  list of free parameters and the printed matrices (M55 = M66 = -0.27, M44 = 1.0563):
  the intended ties are m55 = m66 and l55 = l66. The printed tau41 and tau55 are 0
  although they are listed among the identified parameters.
* Eq. 6.9: hover axisymmetry makes the lateral and longitudinal axes identical in
  one sign convention, but the printed G has G[lam1sN_U, CL_U] = +94.12 and
  G[lam1cN_U, CM_U] = -94.12 (likewise 43.13, 90.0, 0.586, 0.330): the 1s and 1c
  axes use opposite moment signs (the 1c axis is in our convention: steady
  lam1c/CM < 0 as in Eq. 5.3; the 1s axis then has the opposite sign of
  Eq. 5.3's lam1s/CL). Also |G[lam1sF_U, b1s_dot_L]| = 0.254 vs
  |G[lam1cF_U, b1c_dot_L]| = 0.255 (rounding or typo), and the far-wake heave rows
  lam0F_U and lam0F_L carry the same value -39.59 from C_T^L only (tied, or copied).
  F11 = +9.03 is a positive diagonal entry, yet the heave block is stable.
* Eqs. 6.12-6.13 (200 kt): F_UU has positive diagonal entries (+2.76, +15.64) and
  lam0F_L has neither self-damping (F_LL[1, 1] = 0) nor load input (G row 8 all
  zero); the coupled 12x12 F is nevertheless stable as printed (slowest pole
  -1.19 1/s, checked in ``tests/aircraft/inflow/test_inflow_identified.py``).
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from .base import flap_rate_names, inflow_names, load_names

__all__ = ["PublishedInflowModel", "PublishedFGCModel", "TABLE_4_1", "TABLE_4_2", "tables_4_1_4_2",
           "UH60_HOVER_MFW", "UH60_HOVER_PITT_PETERS", "UH60_HOVER_RFW", "UH60_MU01_MFW", "UH60_MU02_MFW",
           "COAXIAL_HOVER_6STATE", "COAXIAL_HOVER_12STATE", "COAXIAL_200KT_12STATE",
           "COAXIAL_FORWARD_12STATE", "TABLE_6_3", "PUBLISHED_MODELS", "ALL_MODELS", "in_rotor_frames",
           "fgc_state_names"]

#: UH-60-like rotor speed Omega_0 [rad/s] (Appendix B) and nominal trim C_T.
_UH60_OMEGA, _UH60_CT = 27.0, 0.0061
#: Coaxial rotor speeds [rad/s] (Table B.1).
_COAX_HOVER_OMEGA, _COAX_FF_OMEGA = 23.7, 20.3


@dataclass(frozen=True)
class PublishedInflowModel:
    """One printed ``M, Lbar, tau`` model with its flight condition and source.

    Attributes
    ----------
    M, Lbar : ndarray
        Apparent mass and ``Lbar = [L]^-1`` (``M`` dimensionless if ``time`` is
        "azimuth", [s] if "seconds").
    tau : ndarray
        Delays [s], row-wise (Eq. 2.16).
    omega : float
        Rotor speed [rad/s].
    condition : dict
        Flight condition: ``flight``, trim ``CT``/``CT_U``/``CT_L``, ``mu``.
    """

    name: str
    source: str
    rotors: tuple
    omega: float
    M: np.ndarray
    Lbar: np.ndarray
    tau: np.ndarray
    condition: dict = field(default_factory=dict)
    time: str = "azimuth"
    notes: str = ""
    #: ``"printed"`` (the dissertation's common frame) or ``"rotor"`` (ours, see
    #: :func:`in_rotor_frames`).
    frame: str = "printed"

    @property
    def input_names(self):
        return load_names(self.rotors)

    @property
    def output_names(self):
        return inflow_names(self.rotors)

    @property
    def M_seconds(self):
        """``M`` multiplying d/dt [s]."""
        return self.M / self.omega if self.time == "azimuth" else self.M


@dataclass(frozen=True)
class PublishedFGCModel:
    """One printed near/far-wake model ``x' = F x + G u``, ``lambda = C x`` (seconds).

    ``input_order`` names G's columns as printed; ``C`` None means
    ``lambda = lambda_N + lambda_F`` (Eqs. 6.2-6.5).
    """

    name: str
    source: str
    rotors: tuple
    omega: float
    F: np.ndarray
    G: np.ndarray
    input_order: tuple
    condition: dict = field(default_factory=dict)
    C: np.ndarray | None = None
    notes: str = ""
    #: ``"printed"`` (the dissertation's common frame) or ``"rotor"`` (ours).
    frame: str = "printed"

    def __post_init__(self):
        if self.C is None:     # lambda = lambda_N + lambda_F, states (0N, 0F, 1sN, 1sF, 1cN, 1cF) per rotor
            c = np.zeros((3 * len(self.rotors), self.F.shape[0]))
            for i in range(c.shape[0]):
                c[i, 2 * i] = c[i, 2 * i + 1] = 1.0
            object.__setattr__(self, "C", c)

    @property
    def inputs(self):
        """Names of G's columns, as printed (alias of ``input_order``)."""
        return self.input_order

    @property
    def input_names(self):
        extra = flap_rate_names(self.rotors) if len(self.input_order) > 3 * len(self.rotors) else []
        return load_names(self.rotors) + extra

    @property
    def output_names(self):
        return inflow_names(self.rotors)


def fgc_state_names(rotors):
    """States of Eq. 6.2: ``lam0N, lam0F, lam1sN, lam1sF, lam1cN, lam1cF`` per rotor.

    Parameters
    ----------
    rotors : sequence of str
        Rotor suffixes (``""`` for none), e.g. ``("U", "L")``.

    Returns
    -------
    list of str
        Names with ``_<rotor>`` appended where the suffix is not empty.
    """
    return [f"{h}{w}{'_' + r if r else ''}" for r in rotors
            for h in ("lam0", "lam1s", "lam1c") for w in ("N", "F")]


def in_rotor_frames(model, directions=None):
    """A printed model converted into our per-rotor frames (the printed data stay as printed).

    The dissertation writes both coaxial rotors in one common frame; ours gives
    each rotor its own (mirrored for the clockwise lower rotor). The conversion
    flips the signs of the cross-rotor lateral couplings only; it is derived and
    documented in :mod:`aircraft.inflow.frames`. Single-rotor models come
    back unchanged (apart from ``frame``).

    Parameters
    ----------
    model : PublishedInflowModel or PublishedFGCModel
        A model with ``frame == "printed"``.
    directions : dict, optional
        Sense of rotation per rotor (default ``{"U": 1, "L": -1}`` for the coaxial,
        ``{"": 1}`` for a single rotor).

    Returns
    -------
    PublishedInflowModel or PublishedFGCModel
        Same type, ``frame="rotor"``; delays unchanged.
    """
    from aircraft.inflow.frames import COAXIAL_DIRECTIONS, FrameError, convert_frames
    if model.frame != "printed":
        raise FrameError(f"{model.name} is already in frame {model.frame!r}")
    rotors = tuple(model.rotors)
    if directions is None:
        directions = {"": 1} if rotors == ("",) else COAXIAL_DIRECTIONS
    loads, lam = load_names(rotors), inflow_names(rotors)
    note = (model.notes + " Converted to our rotor frames (aircraft.inflow.frames: "
            "cross-rotor lateral couplings change sign).").strip()
    if isinstance(model, PublishedFGCModel):
        states = fgc_state_names(rotors)
        cols = [c for c in model.input_order]
        return replace(model, F=convert_frames(model.F, states, states, directions),
                       G=convert_frames(model.G, states, cols, directions),
                       C=convert_frames(model.C, lam, states, directions), notes=note, frame="rotor")
    return replace(model, M=convert_frames(model.M, loads, lam, directions),
                   Lbar=convert_frames(model.Lbar, loads, lam, directions), notes=note, frame="rotor")


# --- Tables 4.1-4.2: UH-60-like single rotor in hover (M/Omega_0 [s], Lbar, tau [s]) ----------
#: Table 4.1 (vertical axis), by row: ``{"M11/Omega": [s], "Lbar11": [-], "tau11": [s] or None}``.
TABLE_4_1 = {
    "identified from MFW": {"M11/Omega": 0.0379, "Lbar11": 0.187, "tau11": 0.0408},
    "Pitt-Peters (Ref. 25)": {"M11/Omega": 0.0314, "Lbar11": 0.214, "tau11": None},
    "Pitt-Peters identified (including blade flapping)": {"M11/Omega": 0.0321, "Lbar11": 0.211, "tau11": None},
    "identified from RFW": {"M11/Omega": 0.0360, "Lbar11": 0.148, "tau11": None},   # printed "n/a"
}
#: Table 4.2 (cyclic, diagonal terms), by row: ``{"M22/Omega": [s], "Lbar22": [-], "tau22": [s] or None}``.
TABLE_4_2 = {
    "Pitt-Peters (Ref. 25)": {"M22/Omega": -0.0042, "Lbar22": -0.0534, "tau22": None},
    "HeliUM: 10 state Peters-He": {"M22/Omega": -0.0038, "Lbar22": -0.0405, "tau22": None},
    "MFW": {"M22/Omega": -0.0063, "Lbar22": -0.0636, "tau22": 0.0369},
    "RFW (Rigid)": {"M22/Omega": -0.0043, "Lbar22": -0.0651, "tau22": None},        # printed "n/a"
}


def tables_4_1_4_2():
    """Tables 4.1 and 4.2 as two :class:`pandas.DataFrame` (M/Omega and tau in seconds)."""
    import pandas as pd
    return (pd.DataFrame.from_dict(TABLE_4_1, orient="index").rename_axis("model"),
            pd.DataFrame.from_dict(TABLE_4_2, orient="index").rename_axis("model"))


def _hover_single(name, m11, l11, t11, m22, l22, t22, notes=""):
    return PublishedInflowModel(
        name=name, source="dissertation Tables 4.1-4.2 (§4.3)", rotors=("",), omega=_UH60_OMEGA,
        M=np.diag([m11, m22, m22]), Lbar=np.diag([l11, l22, l22]), tau=np.diag([t11, t22, t22]),
        condition={"flight": "hover", "CT": _UH60_CT, "mu": 0.0, "omega_rad_s": _UH60_OMEGA},
        time="seconds", notes=notes + " M22 = M33, Lbar22 = Lbar33, tau22 = tau33 by symmetry (§4.3.1.2).")


UH60_HOVER_MFW = _hover_single("UH-60 hover, identified from MFW (Tables 4.1-4.2)",
                               0.0379, 0.187, 0.0408, -0.0063, -0.0636, 0.0369)
UH60_HOVER_PITT_PETERS = _hover_single("UH-60 hover, Pitt-Peters (Tables 4.1-4.2)",
                                       0.0314, 0.214, 0.0, -0.0042, -0.0534, 0.0,
                                       "Lbar implies lambda_h = 0.0534 (C_T = 0.0057), see module notes.")
UH60_HOVER_RFW = _hover_single("UH-60 hover, identified from RFW (Tables 4.1-4.2)",
                               0.0360, 0.148, 0.0, -0.0043, -0.0651, 0.0, "Delays printed 'n/a': taken as 0.")

UH60_MU01_MFW = PublishedInflowModel(
    name="UH-60 mu = 0.1, identified from MFW (Eq. 4.7)", source="dissertation Eq. (4.7), §4.4.1.1",
    rotors=("",), omega=_UH60_OMEGA,
    M=np.diag([0.0394, -0.00603, -0.00603]),
    Lbar=np.array([[0.234, 0, 0.038], [0, -0.0685, 0], [0.0521, 0, -0.0873]]),
    tau=np.array([[0.047, 0, 0.071], [0, 0.043, 0], [0.20, 0, 0.039]]),
    condition={"flight": "forward", "mu": 0.1, "CT": _UH60_CT, "omega_rad_s": _UH60_OMEGA},
    time="seconds", notes="M read as M/Omega [s]; delay matrix printed garbled; C_T nominal (not printed).")

UH60_MU02_MFW = PublishedInflowModel(
    name="UH-60 mu = 0.2, identified from MFW (Eq. 4.8)", source="dissertation Eq. (4.8), §4.4.1.2",
    rotors=("",), omega=_UH60_OMEGA,
    M=np.diag([0.0254, -0.00323, -0.00323]),
    Lbar=np.array([[0.345, 0, 0.047], [0, -0.09, 0], [0.121, 0, -0.129]]),
    tau=np.array([[0.062, 0, 0.00], [0, 0.057, 0], [0.15, 0, 0.05]]),
    condition={"flight": "forward", "mu": 0.2, "CT": _UH60_CT, "omega_rad_s": _UH60_OMEGA},
    time="seconds", notes="M read as M/Omega [s]; tau13 printed 0.00; C_T nominal (not printed).")

COAXIAL_HOVER_6STATE = PublishedInflowModel(
    name="coaxial hover 6-state (Eq. 5.3)",
    source="dissertation Eq. (5.3), §5.4",
    rotors=("U", "L"),
    omega=_COAX_HOVER_OMEGA,
    M=np.array([
        [0.851, 0, 0, -0.4664, 0, 0],
        [0, -0.243, 0, 0, 0.06601, 0],
        [0, 0, -0.243, 0, 0, 0.06601],
        [0.674, 0, 0, 1.0563, 0, 0],
        [0, 0.3349, 0, 0, -0.27, 0],
        [0, 0, 0.3349, 0, 0, -0.27]]),
    Lbar=np.array([
        [0.4418, 0, 0, -0.182, 0, 0],
        [0, -0.0453, 0, 0, -0.01089, 0],
        [0, 0, -0.0453, 0, 0, -0.01089],
        [-0.7262, 0, 0, 0.6748, 0, 0],
        [0, 0.03581, 0, 0, -0.06139, 0],
        [0, 0, 0.03581, 0, 0, -0.06139]]),
    tau=np.array([
        [0.03373, 0, 0, 0.09985, 0, 0],
        [0, 0.02264, 0, 0, 0.1265, 0],
        [0, 0, 0.02264, 0, 0, 0.1265],
        [0, 0, 0, 0.02631, 0, 0],
        [0, 0.08218, 0, 0, 0, 0],
        [0, 0, 0.08218, 0, 0, 0]]),
    condition={"flight": "hover", "CT_U": 0.0053, "CT_L": 0.0043, "mu": 0.0, "omega_rad_s": _COAX_HOVER_OMEGA},
    time="azimuth",
    notes="Ties printed as m44 = m55, l44 = l55 (read m55 = m66, l55 = l66); tau41, tau55 printed 0.",
)

#: Eq. 6.2 input order (flap rates next to the moment they resemble).
_EQ62_INPUTS = ("CT_U", "CL_U", "beta1s_dot_U", "CM_U", "beta1c_dot_U",
                "CT_L", "CL_L", "beta1s_dot_L", "CM_L", "beta1c_dot_L")

COAXIAL_HOVER_12STATE = PublishedFGCModel(
    name="coaxial hover 12-state with flap rates (Eqs. 6.8-6.9)",
    source="dissertation Eqs. (6.8)-(6.9), §6.5",
    rotors=("U", "L"), omega=_COAX_HOVER_OMEGA,
    F=np.array([
        [9.03, 0, 0, 0, 0, 0, -10.26, 0, 0, 0, 0, 0],
        [0, -6.85, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0],
        [0, 0, -9.73, 0, 0, 0, 0, 0, 4.39, 0, 0, 0],
        [0, 0, 0, -4.83, 0, 0, 0, 0, -2.40, 0.394, 0, 0],
        [0, 0, 0, 0, -9.73, 0, 0, 0, 0, 0, 4.39, 0],
        [0, 0, 0, 0, 0, -4.83, 0, 0, 0, 0, -2.40, 0.394],
        [19.26, 0, 0, 0, 0, 0, -18.37, 0, 0, 0, 0, 0],
        [0, 0, 0, 0, 0, 0, 0, -5.27, 0, 0, 0, 0],
        [0, 0, 12.11, 0, 0, 0, 0, 0, -9.39, 0, 0, 0],
        [0, 0, 0, -5.60, 0, 0, 0, 0, -3.27, 0, 0, 0],
        [0, 0, 0, 0, 12.11, 0, 0, 0, 0, 0, -9.39, 0],
        [0, 0, 0, 0, 0, -5.60, 0, 0, 0, 0, -3.27, 0]]),
    G=np.array([
        [7.08, 0, 0, 0, 0, 36.12, 0, 0, 0, 0],
        [0, 0, 0, 0, 0, -39.59, 0, 0, 0, 0],
        [0, 94.12, -0.165, 0, 0, 0, 0, 0.287, 0, 0],
        [0, 0, -0.0840, 0, 0, 0, 0, -0.254, 0, 0],
        [0, 0, 0, -94.12, -0.165, 0, 0, 0, 0, -0.287],
        [0, 0, 0, 0, -0.0840, 0, 0, 0, 0, 0.255],
        [0, 0, 0, 0, 0, 44.43, 0, 0, 0, 0],
        [0, 0, 0, 0, 0, -39.59, 0, 0, 0, 0],
        [0, -43.13, 0, 0, 0, 0, 90.0, 0.586, 0, 0],
        [0, 0, 0, 0, 0, 0, 0, -0.330, 0, 0],
        [0, 0, 0, 43.13, 0, 0, 0, 0, -90.0, -0.586],
        [0, 0, 0, 0, 0, 0, 0, 0, 0, 0.330]]),
    input_order=_EQ62_INPUTS,
    condition={"flight": "hover", "CT_U": 0.0053, "CT_L": 0.0043, "mu": 0.0, "omega_rad_s": _COAX_HOVER_OMEGA},
    notes="1s/1c axes with opposite signs (see module notes); flap rates taken as rad/s; "
          "Fig. 6.2 caption gives CT_U = 0.0052, the text 0.0053.",
)

_F_UU = [[-4.85, 0, 0.95, 0, 0.99, 0],
         [0, 2.76, 0, 1756.4, -0.91, 0],
         [-0.41, 0, -5.26, 0, 5.31, 0],
         [-0.054, -0.11, 0, -59.32, 0.036, -4.71],
         [0, 0, -2.56, 0, -6.39, 0],
         [0, 0.32, 0, 243.79, -0.12, 15.64]]
_F_UL = [[0, 0, 0.69, 0, -2.06, 0],
         [3.68, -82.89, 1.12, -3.15, 0, 31.53],
         [2.95, 0, 1.17, 0, 0.64, 0],
         [0, 2.46, 0, 0.081, 0, -1.00],
         [-3.03, 0, -1.23, 0, -0.31, 0],
         [0.46, -10.44, 0, -0.40, 0, 4.19]]
_F_LU = [[1.75, 0, 0, 0, 0, 0],
         [0, -2.45, 0, 0, 0, -148.75],
         [-7.75, 0, 3.08, 0, 1.88, 0],
         [14.72, 194.98, 0, 0, -2.96, -1072.7],
         [0, 0, -1.79, 0, 0, 0],
         [2.34, 0, 0, 0, -0.63, -425.11]]
_F_LL = [[-5.80, 0, 0, 0, -1.65, 0],
         [0, 0, 2.01, 0, -0.057, 0],
         [0, 0, -5.30, 0, 0, 0],
         [0, -315.92, 0, -12.19, 0, 59.07],
         [10.44, 0, 1.55, 0, -3.08, 0],
         [-3.47, 0, 5.84, 0, 0, 0]]

COAXIAL_200KT_12STATE = PublishedFGCModel(
    name="coaxial 200 kt 12-state (Eqs. 6.12-6.13)",
    source="dissertation Eqs. (6.12)-(6.13), §6.6",
    rotors=("U", "L"), omega=_COAX_FF_OMEGA,
    F=np.block([[np.array(_F_UU), np.array(_F_UL)], [np.array(_F_LU), np.array(_F_LL)]]),
    G=np.array([
        [17.13, -14.09, 6.13, 4.99, 5.99, -2.26],
        [0, 0, 0, -1.82, 0, 16.80],
        [-45.82, 107.77, -22.32, 0, 0, 0],
        [0, 0, 0, 0, 0, -0.55],
        [18.65, -39.79, -54.23, 0, 0, 0],
        [0, 0, 0, -0.41, 0, 2.28],
        [3.72, 0, -2.48, 13.24, 17.86, 7.13],
        [0, 0, 0, 0, 0, 0],
        [0, -28.97, 0, 11.26, 59.26, 6.82],
        [0, 33.85, 0, 0, 0, 0],
        [0, 12.22, 0, 0, 11.91, 0],
        [0, 0, -1.88, 0, 0, 0]]),
    input_order=("CT_U", "CL_U", "CM_U", "CT_L", "CL_L", "CM_L"),
    condition={"flight": "forward", "speed_kt": 200.0, "mu": 0.54, "alpha_deg": 2.0,
               "CT_U": 0.0073, "CT_L": 0.0065, "omega_rad_s": _COAX_FF_OMEGA},
    notes="Positive F diagonals and lam0F_L without damping or input, yet stable as printed; "
          "C_T 'around' 0.0073/0.0065 (time-averaged).",
)

#: Alias (the 200 kt model is the only forward-flight coaxial model printed).
COAXIAL_FORWARD_12STATE = COAXIAL_200KT_12STATE

#: Table 6.3: cost J of the dissertation's 200 kt fit (Eqs. 6.12-6.13) per response,
#: ``{(output, input): J}`` with our signal names (reference data). The printed "Average
#: Cost 77.0" is not the mean of the printed entries (34.7); both are kept as printed.
TABLE_6_3 = {
    (out, inp): j
    for out, row in (("lam0_U", (15.6, 15.3, 14.1, 32.2, 17.1, 44.8)),
                     ("lam1s_U", (9.5, 11.1, 8.3, 6.5, 10.3, 8.7)),
                     ("lam1c_U", (10.2, 9.6, 6.1, 8.8, 10.1, 25.6)),
                     ("lam0_L", (32.4, 337.4, 20.1, 17.7, 42.0, 217.2)),
                     ("lam1s_L", (3.4, 6.2, 4.3, 64.4, 12.0, 15.6)),
                     ("lam1c_L", (14.8, 27.9, 20.2, 20.4, 49.2, 79.4)))
    for inp, j in zip(("CT_U", "CL_U", "CM_U", "CT_L", "CL_L", "CM_L"), row)
}

#: Every printed model, by a short key.
PUBLISHED_MODELS = {
    "table4_mfw": UH60_HOVER_MFW,
    "table4_pitt_peters": UH60_HOVER_PITT_PETERS,
    "table4_rfw": UH60_HOVER_RFW,
    "eq4_7": UH60_MU01_MFW,
    "eq4_8": UH60_MU02_MFW,
    "eq5_3": COAXIAL_HOVER_6STATE,
    "eq6_8_6_9": COAXIAL_HOVER_12STATE,
    "eq6_12_6_13": COAXIAL_200KT_12STATE,
}

#: Every printed model (same objects as :data:`PUBLISHED_MODELS`).
ALL_MODELS = tuple(PUBLISHED_MODELS.values())
