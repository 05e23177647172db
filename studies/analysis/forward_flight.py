"""Single-rotor forward-flight models beside Pitt-Peters and the dissertation's Eqs. 4.7-4.8.

::

    forward_comparison_table  ours / linearised Pitt-Peters / the dissertation's Eqs. 4.7-4.8
    forward_bode_overlay      the key responses: data, ours, Pitt-Peters, Eq. 4.7 or 4.8

The tables print ``M/Omega`` [s] as Eqs. 4.7-4.8 do (that reading of the printed M is
argued in :mod:`aircraft.inflow.published`).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from aircraft.identification.forward_flight import pitt_peters_forward
from aircraft.identification.structures.forward import KEY_RESPONSES

__all__ = ["forward_comparison_table", "forward_bode_overlay", "sign_note", "SIGN_REASONS", "reproduction_table"]

#: Why each entry has the sign it has (our frames: :mod:`aircraft.inflow.base`,
#: :mod:`aircraft.inflow.pitt_peters`).
SIGN_REASONS = {
    "M11": "+: apparent mass of the uniform inflow (8/(3 pi) in Pitt-Peters)",
    "M22": "-: the moment rows carry the Eq. 2.11 moment signs (Pitt-Peters rows 2-3 times -1)",
    "M33": "-: tied to M22 (Pitt-Peters keeps the cyclic apparent masses equal)",
    "Lbar11": "+: more thrust, more mean inflow (momentum theory: dC_T/dlam0 > 0)",
    "Lbar22": "-: a positive C_L gives a negative lam1s in the Eq. 2.11 moment-sign convention",
    "Lbar33": "-: a positive C_M gives a negative lam1c in the Eq. 2.11 moment-sign convention",
    "Lbar13": "+: wake skew (Pitt-Peters X = 15 pi/64 tan(chi/2) > 0); 0 in hover",
    "Lbar31": "+: wake skew: thrust raises the inflow at the rear of the disk (lam1c > 0); 0 in hover",
    "tau": "delay >= 0 by construction",
}


def sign_note(coefficient, ours, pitt_peters):
    """One line on the sign of an identified entry: the physical reason and whether it
    agrees with Pitt-Peters.

    Parameters
    ----------
    coefficient : str
        Row label of :func:`forward_comparison_table` (e.g. ``"Lbar13"``, ``"M22/Omega [s]"``).
    ours, pitt_peters : float
        Identified and Pitt-Peters values.

    Returns
    -------
    str

    Examples
    --------
    >>> sign_note("Lbar11", 0.2, 0.16)
    '+: more thrust, more mean inflow (momentum theory: dC_T/dlam0 > 0); same sign as Pitt-Peters'
    """
    key = coefficient.split("/")[0].split(" ")[0]
    reason = SIGN_REASONS.get("tau" if key.startswith("tau") else key, "")
    if key.startswith("tau"):
        return reason
    if not np.isfinite(ours) or ours == 0:
        return f"{reason}; not identified (zero)"
    if pitt_peters == 0:
        return f"{reason}; Pitt-Peters has none here"
    agree = np.sign(ours) == np.sign(pitt_peters)
    return f"{reason}; {'same sign as' if agree else 'OPPOSITE sign to'} Pitt-Peters"


def _published_for(mu):
    from aircraft.inflow.published import UH60_MU01_MFW, UH60_MU02_MFW
    return {0.1: UH60_MU01_MFW, 0.2: UH60_MU02_MFW}.get(round(float(mu), 6))


_ROWS = (("M11/Omega [s]", "M", (0, 0)), ("M22/Omega [s]", "M", (1, 1)), ("M33/Omega [s]", "M", (2, 2)),
         ("Lbar11", "Lbar", (0, 0)), ("Lbar13", "Lbar", (0, 2)), ("Lbar22", "Lbar", (1, 1)), ("Lbar31", "Lbar", (2, 0)),
         ("Lbar33", "Lbar", (2, 2)), ("tau11 [s]", "tau", (0, 0)), ("tau13 [s]", "tau", (0, 2)),
         ("tau22 [s]", "tau", (1, 1)), ("tau31 [s]", "tau", (2, 0)), ("tau33 [s]", "tau", (2, 2)))


def forward_comparison_table(models, *, alpha=0.0):
    """Identified coefficients beside linearised Pitt-Peters and the dissertation's Eqs. 4.7-4.8.

    Parameters
    ----------
    models : dict
        ``{mu: IdentifiedModel}`` (from :func:`identify_forward_flight`).
    alpha : float
        Shaft angle [rad] of the Pitt-Peters linearisation (that of the wake runs).

    Returns
    -------
    pandas.DataFrame
        One row per (mu, coefficient): ``ours``, ``cramer_rao_pct``,
        ``insensitivity_pct``, ``status`` (free / removed by the reduction / tied),
        ``pitt_peters`` (at the wake's trimmed C_T), ``dissertation`` (printed
        Eq. 4.7 for mu = 0.1, Eq. 4.8 for mu = 0.2, else NaN; reference data, never an
        output) and ``sign_note`` (:func:`sign_note`). ``M`` rows are ``M/Omega`` [s],
        delays [s].

    Raises
    ------
    ValueError
        Empty ``models``.
    """
    if not models:
        raise ValueError("forward_comparison_table needs at least one {mu: IdentifiedModel}")
    rows = []
    for mu, model in sorted(models.items()):
        omega = model.omega
        mats = model.fit.structure.matrices()
        p = model.parameters.set_index("parameter")
        pp_m, pp_l = pitt_peters_forward(model.trim.outputs["CT"], mu, alpha, omega)
        pub = _published_for(mu)
        for label, mat, (i, j) in _ROWS:
            scale = 1.0 / omega if mat == "M" else 1.0
            pname = f"{ {'M': 'm', 'Lbar': 'l', 'tau': 't'}[mat]}{i + 1}{j + 1}".replace(" ", "")
            if pname in p.index:
                cr, ins, status = (p.loc[pname, "cramer_rao_pct"], p.loc[pname, "insensitivity_pct"],
                                   p.loc[pname, "status"])
            else:
                cr, ins, status = np.nan, np.nan, "tied" if np.ravel(mats[mat])[3 * i + j] != 0 else "not in model"
            pp = {"M": pp_m[i, j] / omega, "Lbar": pp_l[i, j], "tau": 0.0}[mat]
            ref = np.nan
            if pub is not None:
                ref = {"M": pub.M_seconds, "Lbar": pub.Lbar, "tau": pub.tau}[mat][i, j]
            ours = float(mats[mat][i, j]) * scale
            rows.append({"mu": mu, "coefficient": label, "ours": ours,
                         "cramer_rao_pct": cr, "insensitivity_pct": ins, "status": status,
                         "pitt_peters": float(pp), "dissertation": float(ref),
                         "sign_note": (SIGN_REASONS.get(label.split(" ")[0].split("/")[0], "") + "; not in this structure"
                                       if status == "not in model" and not label.startswith("tau")
                                       else sign_note(label, ours, float(pp)))})
    return pd.DataFrame(rows)


def forward_bode_overlay(model, mu, *, alpha=0.0, pairs=KEY_RESPONSES, fig=None):
    """Bode overlay of the key forward-flight responses: wake data, ours, Pitt-Peters, Eq. 4.7/4.8.

    Parameters
    ----------
    model : IdentifiedModel
        From :func:`identify_forward_flight`.
    mu : float
        Advance ratio (selects the printed Eq. 4.7 or 4.8 and the Pitt-Peters point).
    alpha : float
        Shaft angle [rad] of the Pitt-Peters linearisation.
    pairs : sequence of (output, input)
        Responses shown (default :data:`KEY_RESPONSES`).
    fig : matplotlib.figure.Figure, optional

    Returns
    -------
    matplotlib.figure.Figure
        Magnitude [dB], phase [deg] and coherence per response.
    """
    from flightid import MLTauStructure
    from flightid.plotting import bode_with_coherence
    omega = model.omega
    w = model.responses.omega
    lo, hi = model.settings.fit_range
    w = w[(w >= lo) & (w <= hi)]
    sources = [(model.responses, "free wake (joint input-output)"),
               (model.fit.structure.to_frd(w, name="ours"), "ours")]
    names = model.structure.inputs, model.structure.outputs
    pp_m, pp_l = pitt_peters_forward(model.trim.outputs["CT"], mu, alpha, omega)
    pp = MLTauStructure(pp_m, pp_l, inputs=names[0], outputs=names[1], initial={}, omega=omega)
    sources.append((pp.to_frd(w), "linearised Pitt-Peters"))
    pub = _published_for(mu)
    if pub is not None:
        ref = MLTauStructure(pub.M * pub.omega if pub.time == "seconds" else pub.M, pub.Lbar, pub.tau,
                             inputs=names[0], outputs=names[1], initial={}, omega=pub.omega)
        sources.append((ref.to_frd(w), f"dissertation Eq. {'4.7' if round(mu, 6) == 0.1 else '4.8'} (printed)"))
    return bode_with_coherence(sources, list(pairs), fig=fig)


def reproduction_table(config, models, settings, *, alpha=0.0, ct=0.0061, n_jobs=2, cache_dir="default",
                       progress=True):
    """The trust rule's reproduction part for each advance ratio's model: one row per mu.

    Each model of ``models`` (``{mu: IdentifiedModel}`` from
    :func:`aircraft.identification.identify_over_advance_ratio`) is identified again
    with the same call and ``reproduce=True``: the first data set comes from the wake
    cache and its fit is deterministic (the row's ``same_first_fit`` checks that the
    model is the one tabulated), then the second data set, started 1e-7 R away, is run
    and the first model's final structure refitted on it.

    Parameters
    ----------
    config : aircraft.AircraftConfig
        The single rotor the models were identified on.
    models : dict
        ``{mu: IdentifiedModel}``.
    settings : dict
        ``{mu: IdentificationSettings}``, as given to the sweep.
    alpha, ct : float
        Shaft angle [rad] and trim thrust coefficient [-] of the sweep.

    Returns
    -------
    pandas.DataFrame
        mu, J_ave, J_ave_refit (the first structure on the second data set),
        same_first_fit, parameters (free), largest_shift_in_bounds (shift over the
        first fit's bound, the largest over the parameters), parameter_of_largest,
        reproduces (every parameter within its bound), same_structure (the whole
        identification again keeps the same free parameters), trusted (the whole rule,
        reproduction included) and trust_failures.
    """
    from aircraft.identification import identify_forward_flight, identify_inflow
    from aircraft.identification.conditions import flight_condition
    from aircraft.identification.structures.hover import SingleRotor3State

    from .reproduction import reproduction_row

    rows = []
    for mu, first in sorted(models.items()):
        kw = dict(settings=settings[mu], n_jobs=n_jobs, cache_dir=cache_dir, progress=progress, reproduce=True)
        if mu == 0.0:
            model = identify_inflow(config, flight_condition(config, 0.0, alpha), SingleRotor3State(), ct=float(ct),
                                    name="single rotor mu = 0 (hover)", **kw)
        else:
            model = identify_forward_flight(config, mu, alpha=alpha, ct=ct, **kw)
        rows.append({"mu": mu, **reproduction_row(model, first)})
    return pd.DataFrame(rows)
