"""Why the Eq. 5.3 6-state cannot be trusted on our wake: coordinates, feedthrough, scale, symmetry.

The 6-state fitted to our coaxial hover wake (J_ave ~108) has Cramer-Rao bounds
of 37-64 % on every apparent mass and gain, a collective M of 6-11 where
Pitt-Peters and Eq. 5.3 give ~0.85, and a collective inflow mode that is a
complex pair. :func:`six_state_diagnostics` puts numbers on four explanations,
each with the same data:

1. **Coordinates.** The collective lambda/C_T block is nearly rank one in the
   data (sigma_min/sigma_max ~ 0.06), so the element-wise cost cannot see its
   small singular direction. Fitting the same structure to the rotors' sum and
   difference responses (:func:`flightid.transformed.sum_difference_transform`;
   orthonormal, so no data are added or counted twice) makes that direction an
   element of its own.
2. **A quasi-static part.** The same structure with a direct feedthrough ``D``
   per element (:class:`Coaxial6StateFeedthrough`, ties as Eq. 5.3's): if the
   data want an instantaneous share of the inflow, Eq. 5.3 can only emulate it
   with a near-singular M, which is a flat valley.
3. **The scale pinned.** The same structure with the apparent-mass diagonal
   held at Pitt-Peters' values (an a priori value, as CIFER practice allows for
   a parameter the data cannot fix): the collective block's flat scale is gone,
   and the rows left with a high cost are the ones Eq. 5.3's form cannot fit.
4. **What Eq. 5.3 leaves out.** Hover's axisymmetry allows each cyclic block a
   second term (a rotor's ``lam1s`` from a ``C_M``, :mod:`.axisymmetric`), and our
   wake's measured lambda/C has it, coherent and with the predicted signs. The
   structure with it, fitted on the 20 pairs it produces, over the whole band and
   above the band where our lower rotor's cyclic inflow stops being first order.

The rows report the cost on the rotors' own 12 lambda/C pairs (the pairs of
Table 5.1) whatever coordinates the fit used, so that they compare. Note that
the Cramer-Rao bound of the CIFER convention is a curvature of *the cost*, not
a calibrated standard deviation: an orthonormal change of coordinates of the
same data changes it (``tests/flightid/test_flightid_transformed.py`` shows a factor
~1.8 on synthetic data at an unchanged true error). A bound below 20 % in one
set of coordinates is therefore not, alone, a trusted model.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from aircraft.identification.structures.axisymmetric import Coaxial6StateAxisymmetric
from aircraft.identification.structures.base import PITT_PETERS_M11
from aircraft.identification.structures.hover import Coaxial6State, _COAX6_FREE

__all__ = ["Coaxial6StateFeedthrough", "coaxial_sum_difference", "six_state_diagnostics"]

_GROUPS = ((("lam0_U", "lam0_L"), ("CT_U", "CT_L"), "lam0"),
           (("lam1s_U", "lam1s_L"), ("CL_U", "CL_L"), "lam1s"),
           (("lam1c_U", "lam1c_L"), ("CM_U", "CM_L"), "lam1c"))


def _entries(pattern, prefix=None):
    """A flightid pattern back as entries (names with their sign), renamed to ``prefix``."""
    out = pattern.const.astype(object)
    for i, j, name, sign in pattern.refs:
        out[i, j] = ("-" if sign < 0 else "") + (prefix + name[1:] if prefix else name)
    return out.tolist()


class Coaxial6StateFeedthrough(Coaxial6State):
    """Eq. 5.3's 6-state plus a direct feedthrough ``D`` with the same pattern and ties.

    ``lambda = (M s + Lbar)^-1 C + D C`` (delays on both parts): 8 more parameters
    ``d11 ... d55`` [inflow per load coefficient]. Not a printed structure: a
    diagnostic of what Eq. 5.3 lacks on our wake (module docstring).

    Parameters
    ----------
    frame : {"rotor", "printed"}
        As in :class:`Coaxial6State`: our per-rotor frames (default) or the
        dissertation's common frame; ``D`` takes the frame's signs from ``M``.
    """

    key = "coaxial_6state_feedthrough"

    def build(self, initial, omega, fixed=()):
        from flightid.feedthrough import MLTauFeedthroughStructure
        # Eq. 5.3's own patterns (ties and frame signs included), D tied as M is
        base = super().build({k: v for k, v in initial.items() if not k.startswith("d")}, omega)
        m, lb, tau = (_entries(base._patterns[k]) for k in ("M", "Lbar", "tau"))
        return MLTauFeedthroughStructure(m, lb, tau, _entries(base._patterns["M"], "d"), inputs=self.inputs,
                                         outputs=self.outputs, initial=dict(initial), fixed=fixed, omega=omega)

    def initial_values(self, lam_over_c, n_points=3, coherence_min=None):
        """Eq. 5.3's start (:meth:`Coaxial6State.initial_values`) with ``D = 0``."""
        init = super().initial_values(lam_over_c, n_points, coherence_min)
        init.update({f"d{i}{j}": 0.0 for i, j in _COAX6_FREE})
        return init


def coaxial_sum_difference(responses, structure=None, w_ref=1.0):
    """Sum and difference coordinates of a coaxial pair, signs from the data.

    Parameters
    ----------
    responses : flightid.MeasuredResponse
        The rotors' lambda/C.
    structure : InflowStructure, optional
        Gives the signal order (default :class:`Coaxial6State`).
    w_ref : float
        The sign of each harmonic's sum is that of the cross-rotor response
        relative to the own-rotor one over the three points from ``w_ref`` [rad/s]
        (in our mirrored frames the lateral pair sums with -1).

    Returns
    -------
    T, Sinv, outputs, inputs, signs
        For :func:`flightid.transformed.transform_response` and
        :class:`flightid.transformed.TransformedStructure`.
    """
    from flightid.transformed import sum_difference_transform
    structure = structure or Coaxial6State()
    k0 = int(np.searchsorted(responses.omega, w_ref))
    sl = slice(k0, k0 + 3)
    signs = []
    for (oa, ob), (ia, _), _ in _GROUPS:
        cross = responses.element(ob, ia)[0][sl].mean()
        own = responses.element(oa, ia)[0][sl].mean()
        signs.append(1.0 if np.real(cross / own) >= 0 else -1.0)
    t, s_inv, outs, ins = sum_difference_transform(list(_GROUPS), structure.outputs, structure.inputs, signs)
    return t, s_inv, outs, ins, signs


def _row(label, coordinates, res, inner, responses, rotor_pairs, fit_range, n_omega, row_fit_range=None,
         off_harmonic_pairs=()):
    from flightid.transformed import pair_costs
    params = res.parameters[res.parameters.status == "free"]
    ml = params[params.parameter.str[0].isin(["m", "l"])]
    rotor = pair_costs(inner, responses, rotor_pairs, fit_range, n_omega)
    vals = inner.values
    row_fit_range = tuple(row_fit_range or fit_range)
    row = {"fit": label, "coordinates": coordinates, "fit_range_rad_s": f"{row_fit_range[0]:g}-{row_fit_range[1]:g}",
           "pairs_fitted": len(res.cost_table),
           "J_ave_fitted_pairs": float(res.J_ave), "J_ave_rotor_pairs": rotor.attrs["J_ave"],
           "J_max_rotor_pair": float(rotor.J.max()), "free_parameters": len(params),
           "max_CR_M_L_pct": float(ml.cramer_rao_pct.max()),
           "n_CR_over_20_pct": int((params.cramer_rao_pct > 20).sum()),
           "n_insensitivity_over_10_pct": int((params.insensitivity_pct > 10).sum()),
           "n_flat_directions": int(len(res.flat_directions)), "condition_number": float(res.condition_number)}
    row.update({k: float(vals[k]) for k in ("m11", "m14", "m41", "m44", "l11", "l14", "l41", "l44",
                                            "m22", "l22")})
    cyclic = ml[~ml.parameter.str[1:].isin(["11", "14", "41", "44"])]
    row["max_CR_cyclic_M_L_pct"] = float(cyclic.cramer_rao_pct.max())
    poles = inner.poles()
    row["collective_poles_complex"] = bool(np.any(np.abs(poles.imag) > 1e-6))
    row["slowest_pole_1_s"] = float(-np.max(poles.real))
    if off_harmonic_pairs:
        # the pairs Eq. 5.3 cannot produce, on the common band: the rows compare on them too
        off = pair_costs(inner, responses, list(off_harmonic_pairs), fit_range, n_omega)
        row["J_ave_off_harmonic_pairs"] = off.attrs["J_ave"]
        rotor = pd.concat([rotor, off], ignore_index=True)
    return row, rotor.assign(fit=label)


def six_state_diagnostics(responses, omega, *, fit_range=(1.0, 25.0), n_omega=20, coherence_min=0.6,
                          start=None, feedthrough_max_nfev=3000, axi_high_band=(4.0, 25.0)):
    """Fit Eq. 5.3's 6-state four ways and its axisymmetric extension two ways, on the same data.

    Parameters
    ----------
    responses : flightid.MeasuredResponse
        Joint input-output lambda/C of the coaxial in hover (the pipeline's).
    omega : float
        Rotor speed [rad/s].
    fit_range : (float, float)
        Fit band [rad/s] (the pipeline's).
    n_omega : int
        Log-spaced frequency points per response in the cost (CIFER uses 20).
    coherence_min : float
        Coherence threshold for the fit's default pairs and ranges (:func:`flightid.fit`).
    start : dict, optional
        Start of the Eq. 5.3 fits (default :meth:`Coaxial6State.initial_values`); the
        feedthrough fit starts from the rotor-frame optimum with ``D = 0``; the fourth
        fit holds ``m11, m22, m44, m55`` at their start values (by default Pitt-Peters'
        hover apparent masses, 8/(3 pi) and, with our frames' sign, -16/(45 pi)).
    feedthrough_max_nfev : int
        Evaluation budget of the feedthrough fit (32 parameters).
    axi_high_band : (float, float)
        Band [rad/s] of the sixth fit (its lower edge; the upper is ``fit_range``'s).

    Returns
    -------
    summary : pandas.DataFrame
        One row per fit: rotor frame, sum/difference coordinates, rotor frame with
        feedthrough, rotor frame with the apparent-mass diagonal fixed, then
        :class:`~aircraft.identification.structures.axisymmetric.Coaxial6StateAxisymmetric` on
        ``fit_range`` from each of its equation-error starts, and on ``axi_high_band``
        with ``m11, m44`` fixed at Pitt-Peters' and reduced (:func:`flightid.reduce`);
        the axisymmetric rows only where the data hold the off-harmonic pairs; the cost on the 12
        rotor pairs over ``fit_range`` (and, for the axisymmetric rows, on the 8
        off-harmonic pairs ``lam1s/C_M``, ``lam1c/C_L``), the bounds (``max_CR_cyclic_M_L_pct``:
        the cyclic blocks alone), flat directions, condition number and the collective
        M and Lbar.
    pair_costs : pandas.DataFrame
        Every fit's cost per rotor pair (and per off-harmonic pair for the
        axisymmetric rows), over ``fit_range``.
    """
    from flightid import fit, reduce
    from flightid.transformed import TransformedStructure, transform_response
    st = Coaxial6State()
    start = dict(start or st.initial_values(responses, 3))
    kw = dict(frequency_ranges=tuple(fit_range), n_omega=n_omega, coherence_min=coherence_min)
    rotor_pairs = [(o, u) for o in st.outputs for u in st.inputs
                   if o.split("_")[0] == {"CT": "lam0", "CL": "lam1s", "CM": "lam1c"}[u.split("_")[0]]]
    rows, costs = [], []

    plain = fit(st.build(start, omega), responses, pairs=rotor_pairs, **kw)
    r, c = _row("Eq. 5.3, rotor frame", "rotor", plain, plain.structure, responses, rotor_pairs, fit_range,
                n_omega)
    rows.append(r)
    costs.append(c)

    t, s_inv, outs, ins, signs = coaxial_sum_difference(responses, st)
    transformed = transform_response(responses, t, s_inv, outs, ins)
    sd_pairs = [(f"{g}_{a}", f"{g}_{b}") for g in ("lam0", "lam1s", "lam1c") for a in ("sum", "diff")
                for b in ("sum", "diff")]
    sd = fit(TransformedStructure(st.build(start, omega), t, s_inv, outs, ins), transformed, pairs=sd_pairs, **kw)
    r, c = _row("Eq. 5.3, sum/difference", f"sum/difference (signs {signs})", sd, sd.structure.inner,
                responses, rotor_pairs, fit_range, n_omega)
    rows.append(r)
    costs.append(c)

    ft = Coaxial6StateFeedthrough()
    # from the rotor-frame optimum with D = 0: the feedthrough fit then starts where
    # Eq. 5.3 stopped and can only lower its cost (from the data-driven start it
    # stopped at a worse optimum with a near-integrator, J_ave 230)
    init = ft.initial_values(responses, 3)
    init.update(plain.structure.values)
    # delays start inside their bound (a delay at 0 has no gradient into negative values)
    init.update({k: max(v, 0.01) for k, v in init.items() if k.startswith("t")})
    fed = fit(ft.build(init, omega), responses, pairs=rotor_pairs, max_nfev=feedthrough_max_nfev, **kw)
    r, c = _row("Eq. 5.3 + feedthrough D, rotor frame", "rotor", fed, fed.structure, responses, rotor_pairs,
                fit_range, n_omega)
    d = fed.structure.matrices()["D"]
    r["max_abs_D"] = float(np.abs(d).max())
    rows.append(r)
    costs.append(c)

    # the apparent-mass diagonal held at the start's values (Pitt-Peters' 8/(3 pi)
    # and 16/(45 pi) in our frames by default): an a priori value of the scale that
    # the nearly rank-one collective block cannot fix, so what is left shows which
    # blocks Eq. 5.3's form fits once that scale is pinned
    pinned = fit(st.build(start, omega, fixed=st.protected), responses, pairs=rotor_pairs, **kw)
    r, c = _row("Eq. 5.3, M diagonal fixed at the start (a priori)", "rotor", pinned, pinned.structure,
                responses, rotor_pairs, fit_range, n_omega)
    rows.append(r)
    costs.append(c)

    # every coupling hover's axisymmetry allows (the 1s/1c terms Eq. 5.3 sets to zero),
    # fitted on every pair it produces (the 12 rotor pairs and 8 off-harmonic ones), one
    # row per equation-error start: on our wake the two land at nearly the same cost with
    # different parameters (a flat valley), which one row of the lower cost would hide.
    # (From the low-frequency start the fit stops at J_ave 922 after ~6 min: not tried.)
    axi = Coaxial6StateAxisymmetric()
    # only pairs the data hold (exact data of Eq. 5.3 itself have zeros there; the
    # cost's log of a zero is not a number): with none, the extra terms say nothing
    off_pairs = [(f"{h}_{a}", f"{u}_{b}") for h, u in (("lam1s", "CM"), ("lam1c", "CL"))
                 for a in axi.rotors for b in axi.rotors]
    off_pairs = [p for p in off_pairs if np.all(np.abs(responses.element(*p)[0]) > 0)]
    if not off_pairs:
        return pd.DataFrame(rows), pd.concat(costs, ignore_index=True)
    starts = axi.extra_starts(responses, omega) or [("low-frequency start",
                                                     axi.initial_values(responses, 3, coherence_min))]
    for label, values in starts:
        res = fit(axi.build(values, omega), responses, pairs=rotor_pairs + off_pairs, **kw)
        r, c = _row(f"axisymmetric (Eq. 5.3 + 1s/1c couplings), from the {label}", "rotor", res, res.structure,
                    responses, rotor_pairs, fit_range, n_omega, off_harmonic_pairs=off_pairs)
        rows.append(r)
        costs.append(c)

    # the same above the band where our wake's cyclic response stops being first order,
    # with the collective apparent-mass diagonal held at Pitt-Peters' (the collective
    # block stays nearly rank one there), from the highest band's start; reported on
    # the common band as well
    high = (max(axi_high_band[0], fit_range[0]), fit_range[1])
    values = dict(starts[-1][1], m11=PITT_PETERS_M11, m44=PITT_PETERS_M11)
    # reduced as the pipeline does (guideline thresholds; a few seconds here)
    upper = reduce(axi.build(values, omega, fixed=("m11", "m44")), responses, protected=axi.protected,
                   pairs=rotor_pairs + off_pairs, **dict(kw, frequency_ranges=high)).result
    r, c = _row(f"axisymmetric, {high[0]:g}-{high[1]:g} rad/s, collective M diagonal fixed (a priori), reduced",
                "rotor", upper, upper.structure, responses, rotor_pairs, fit_range, n_omega, row_fit_range=high,
                off_harmonic_pairs=off_pairs)
    rows.append(r)
    costs.append(c)
    return pd.DataFrame(rows), pd.concat(costs, ignore_index=True)
