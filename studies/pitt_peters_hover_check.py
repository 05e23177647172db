"""Pitt-Peters hover matrices of the UH-60-like rotor at C_T = 0.0061.

Our nonlinear Pitt-Peters model (aircraft.inflow.PittPeters), linearised
numerically, against the closed-form hover expressions (M11 = 8/(3 pi),
M22 = M33 = -16/(45 pi), Lbar11 = 4 lambda_h, Lbar22 = Lbar33 = -lambda_h) and,
in a separate column, the Pitt-Peters rows printed in Tables 4.1-4.2 (M/Omega_0).
Writes ``results/pitt_peters_hover_check/matrices.csv``.

Run: ``python -m studies.pitt_peters_hover_check``
"""
from pathlib import Path

import numpy as np
import pandas as pd

from aircraft import uh60_single_rotor
from aircraft.inflow import PittPeters, RotorOperatingPoint, mlbar_from_statespace

PRINTED = {"M11/Omega": 0.0314, "Lbar11": 0.214, "M22/Omega": -0.0042, "Lbar22": -0.0534}


def main(out_dir="results/pitt_peters_hover_check", ct=0.0061):
    omega = uh60_single_rotor().rotors[0].omega
    sys = PittPeters().linear(np.array([ct, 0.0, 0.0]), (RotorOperatingPoint(omega),))
    m, lbar = mlbar_from_statespace(sys, omega)
    lam_h = np.sqrt(ct / 2)
    rows = [("M11/Omega", m[0, 0] / omega, 8 / (3 * np.pi) / omega),
            ("M22/Omega", m[1, 1] / omega, -16 / (45 * np.pi) / omega),
            ("M33/Omega", m[2, 2] / omega, -16 / (45 * np.pi) / omega),
            ("Lbar11", lbar[0, 0], 4 * lam_h), ("Lbar22", lbar[1, 1], -lam_h), ("Lbar33", lbar[2, 2], -lam_h)]
    table = pd.DataFrame(rows, columns=["coefficient", "ours (linearised)", "closed form"])
    table["dissertation Tables 4.1-4.2"] = table.coefficient.map(PRINTED)
    table["off-diagonal max |.|"] = [np.max(np.abs(m - np.diag(np.diag(m)))) / omega] * 3 + \
                                    [np.max(np.abs(lbar - np.diag(np.diag(lbar))))] * 3
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    table.to_csv(out / "matrices.csv", index=False)
    print(f"Pitt-Peters hover, C_T = {ct}, Omega = {omega} rad/s, lambda_h = {lam_h:.5f}")
    print(table.to_string(index=False, float_format=lambda v: f"{v:.5g}"))
    return table


if __name__ == "__main__":
    main()
