"""Pitt-Peters hover matrices of the UH-60-like rotor at C_T = 0.0061.

Our nonlinear Pitt-Peters model (aircraft.inflow.PittPeters), linearised
numerically, against the closed-form hover expressions (M11 = 8/(3 pi),
M22 = M33 = -16/(45 pi), Lbar11 = 4 lambda_h, Lbar22 = Lbar33 = -lambda_h) and,
in a separate column, the Pitt-Peters rows printed in Tables 4.1-4.2 (M/Omega_0 [s];
the tables print the 22 terms only, 33 = 22 by symmetry, §4.3.1.2).
Writes ``results/pitt_peters_hover_check/matrices.csv``.

For context it also writes ``forward_flight.csv``: our forward-flight
linearisation (mu = 0.1, 0.2, shaft normal to the free stream, same C_T) beside
the free-wake identifications of Eqs. 4.7-4.8. The dissertation prints no
Pitt-Peters forward-flight matrices (only Figs. 4.35-4.36, quoted in words:
"Lbar13 ... increases to about 0.17 at mu = 0.2 for the Pitt-Peters model"), so
that table is a comparison with a different model, not a check.

Run: ``python -m studies.pitt_peters_hover_check``
"""
from pathlib import Path

import numpy as np
import pandas as pd

from aircraft import uh60_single_rotor
from aircraft.inflow import PittPeters, RotorOperatingPoint, mlbar_from_statespace
from aircraft.inflow.published import TABLE_4_1, TABLE_4_2, UH60_MU01_MFW, UH60_MU02_MFW

_PP_ROW = "Pitt-Peters (Ref. 25)"


def main(out_dir="results/pitt_peters_hover_check", ct=0.0061):
    omega = uh60_single_rotor().rotors[0].omega
    sys = PittPeters().linear(np.array([ct, 0.0, 0.0]), (RotorOperatingPoint(omega),))
    m, lbar = mlbar_from_statespace(sys, omega)
    lam_h = np.sqrt(ct / 2)
    t1, t2 = TABLE_4_1[_PP_ROW], TABLE_4_2[_PP_ROW]
    rows = [  # coefficient, ours, closed form, printed
        ("M11/Omega [s]", m[0, 0] / omega, 8 / (3 * np.pi) / omega, t1["M11/Omega"]),
        ("M22/Omega [s]", m[1, 1] / omega, -16 / (45 * np.pi) / omega, t2["M22/Omega"]),
        ("M33/Omega [s]", m[2, 2] / omega, -16 / (45 * np.pi) / omega, t2["M22/Omega"]),
        ("Lbar11", lbar[0, 0], 4 * lam_h, t1["Lbar11"]),
        ("Lbar22", lbar[1, 1], -lam_h, t2["Lbar22"]),
        ("Lbar33", lbar[2, 2], -lam_h, t2["Lbar22"]),
    ]
    table = pd.DataFrame(rows, columns=["coefficient", "ours (linearised)", "closed form",
                                        "dissertation Tables 4.1-4.2"])
    table["ours/closed - 1"] = table["ours (linearised)"] / table["closed form"] - 1
    table["printed/closed - 1"] = table["dissertation Tables 4.1-4.2"] / table["closed form"] - 1
    off_m = np.max(np.abs(m - np.diag(np.diag(m)))) / omega
    off_l = np.max(np.abs(lbar - np.diag(np.diag(lbar))))
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    table.to_csv(out / "matrices.csv", index=False)
    print(f"Pitt-Peters hover, C_T = {ct}, Omega = {omega} rad/s, lambda_h = sqrt(C_T/2) = {lam_h:.5f}")
    print(f"azimuth-time M = diag({m[0, 0]:.5f}, {m[1, 1]:.5f}, {m[2, 2]:.5f}) "
          f"(8/(3 pi) = {8 / (3 * np.pi):.5f}, -16/(45 pi) = {-16 / (45 * np.pi):.5f})")
    print(table.to_string(index=False, float_format=lambda v: f"{v:.5g}"))
    print(f"largest off-diagonal |M/Omega| = {off_m:.2g} s, |Lbar| = {off_l:.2g}")
    print(f"printed Lbar11/4 = {t1['Lbar11'] / 4:.4f} and -Lbar22 = {-t2['Lbar22']:.4f}: the printed rows "
          f"imply lambda_h ~ 0.0534 (C_T ~ {2 * 0.0534 ** 2:.4f}), not {lam_h:.4f}")
    forward_flight(out, ct, omega)
    return table


def forward_flight(out, ct, omega):
    """Our forward-flight (M/Omega, Lbar) beside Eqs. 4.7-4.8 (a different model)."""
    rows = []
    for mu, ident in ((0.1, UH60_MU01_MFW), (0.2, UH60_MU02_MFW)):
        sys = PittPeters().linear(np.array([ct, 0.0, 0.0]), (RotorOperatingPoint(omega, mu=mu),))
        m, lbar = mlbar_from_statespace(sys, omega)
        for name, (i, j) in (("11", (0, 0)), ("22", (1, 1)), ("33", (2, 2)), ("13", (0, 2)), ("31", (2, 0))):
            rows.append((mu, f"Lbar{name}", lbar[i, j], ident.Lbar[i, j]))
        rows.append((mu, "M11/Omega [s]", m[0, 0] / omega, ident.M[0, 0]))
        rows.append((mu, "M22/Omega [s]", m[1, 1] / omega, ident.M[1, 1]))
    table = pd.DataFrame(rows, columns=["mu", "coefficient", "ours (Pitt-Peters, linearised)",
                                        "identified from MFW (Eqs. 4.7-4.8)"])
    table.to_csv(out / "forward_flight.csv", index=False)
    print("\nforward flight (context only: the identified models are a different model)")
    print(table.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    return table


if __name__ == "__main__":
    main()
