"""Identified inflow models printed in the reference dissertation, as data.

These are *reference data* (for comparison and for users who want them), never
outputs of our code. Matrices are in the dissertation's convention: inputs
(dC_T, dC_L, dC_M) per rotor, states/outputs (lam0, lam1s, lam1c) per rotor,
derivatives with respect to rotor azimuth psi (so time in seconds needs Omega),
delays in seconds.

Transcription notes
-------------------
* Eq. 5.3 (coaxial hover, 6 states): §5.3 lists the ties "m44 = m55" and
  "l44 = l55", which contradict its own list of 24 free parameters (m44 and m55
  both free) and the printed matrices (M55 = M66 = -0.27, M44 = 1.0563): the
  intended ties are m55 = m66 and l55 = l66. The printed tau41 and tau55 are 0
  although they are listed among the identified parameters.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["PublishedInflowModel", "COAXIAL_HOVER_6STATE"]


@dataclass(frozen=True)
class PublishedInflowModel:
    """One printed model: M, Lbar, tau with its flight condition and source."""

    name: str
    source: str
    rotors: tuple
    omega: float          #: rotor speed [rad/s] of the azimuth-time derivative
    M: np.ndarray
    L: np.ndarray         #: the dissertation's Lbar = [L]^-1
    tau: np.ndarray       #: delays [s], row-wise (Eq. 2.16)
    condition: dict = field(default_factory=dict)

    @property
    def input_names(self):
        from .base import load_names
        return load_names(self.rotors)

    @property
    def output_names(self):
        from .base import inflow_names
        return inflow_names(self.rotors)


COAXIAL_HOVER_6STATE = PublishedInflowModel(
    name="coaxial hover 6-state (Eq. 5.3)",
    source="dissertation Eq. (5.3), §5.4",
    rotors=("U", "L"),
    omega=23.7,
    M=np.array([
        [0.851, 0, 0, -0.4664, 0, 0],
        [0, -0.243, 0, 0, 0.06601, 0],
        [0, 0, -0.243, 0, 0, 0.06601],
        [0.674, 0, 0, 1.0563, 0, 0],
        [0, 0.3349, 0, 0, -0.27, 0],
        [0, 0, 0.3349, 0, 0, -0.27]]),
    L=np.array([
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
    condition={"flight": "hover", "CT_U": 0.0053, "CT_L": 0.0043, "omega_rad_s": 23.7},
)
