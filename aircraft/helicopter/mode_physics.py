"""Modes named by their physics (eigenvector participation), not by rank.

::

    classify_modes(sys)             modes table + ``physics`` label + participation per state group
    pair_modes(ours, reference)     ours beside a printed table, matched label by label
    flap_mode_damping(sys, ...)     where the regressive flap (flap-body) modes sit; closed loops too

The participation factor of state i in mode k is ``|v_ik w_ik|`` (right and
left eigenvectors, normalised to sum 1 over the states), which is
scale-invariant, unlike the eigenvector itself. States are grouped by name
(:data:`STATE_GROUPS`): body translation/rotation, flap coning, reactionless
and cyclic flap, inflow. A mode's label follows from its dominant group and,
for the cyclic flap modes, the sense in which the tip-path plane whirls: in the
fixed frame a rotor with flap frequency nu > 1 has a regressive mode whirling
at (1 - nu) Omega, against the rotation, and a progressive one at (1 + nu) Omega,
with it. (The frequency is no test: with a light fuselage the regressive
flap-body mode rises above Omega.)
"""
from __future__ import annotations

import re

import numpy as np
import pandas as pd

__all__ = ["STATE_GROUPS", "state_group", "classify_modes", "pair_modes", "flap_mode_damping",
           "flap_mode_sensitivity"]

#: state-name pattern (regular expression on the name without rotor suffix) -> group
STATE_GROUPS = {
    "heading": r"^psi$", "yaw": r"^r$", "heave": r"^w$",
    "pitch": r"^(q)$", "roll": r"^(p)$",
    "longitudinal": r"^(u|theta)$", "lateral": r"^(v|phi)$",
    "coning": r"^beta0(_dot)?$", "reactionless": r"^betad(_dot)?$",
    "cyclic_flap": r"^beta1[sc](_dot)?$",
    "inflow_mean": r"^lam0", "inflow_cyclic": r"^lam1[sc]", "inflow": r"^inflow_",
}
_BODY = ("heading", "yaw", "heave", "pitch", "roll", "longitudinal", "lateral")
_ROTOR = ("coning", "reactionless", "cyclic_flap")
_INFLOW = ("inflow_mean", "inflow_cyclic", "inflow")


#: Rotor names whose suffix :func:`state_group` ignores unless told others (coaxial_compound's).
_DEFAULT_ROTORS = ("U", "L")


def _suffix_pattern(rotors):
    """``_(U|L)$`` for the rotor names ``rotors`` (empty names carry no suffix)."""
    names = [re.escape(r) for r in rotors if r]
    return f"_({'|'.join(names)})$" if names else r"(?!)$"


def state_group(name, rotors=_DEFAULT_ROTORS):
    """Group of a state name (rotor suffix ``_U``/``_L`` ignored); ``"other"`` if none.

    Parameters
    ----------
    name : str
    rotors : sequence of str
        Rotor names whose suffix is ignored (default ``("U", "L")``; an aircraft's
        are ``[r.name for r in config.rotors]``).

    Returns
    -------
    str
        A key of :data:`STATE_GROUPS` or ``"other"`` (e.g. controller or Padé states).
    """
    base = re.sub(_suffix_pattern(rotors), "", name.strip())
    for group, pattern in STATE_GROUPS.items():
        if re.search(pattern, base):
            return group
    return "other"


def _participation(a):
    lam, right = np.linalg.eig(a)
    left = np.linalg.inv(right).T
    part = np.abs(right * left)
    part = part / np.where(part.sum(axis=0) > 0, part.sum(axis=0), 1.0)
    return lam, part, right


def _whirl(labels, vec, rotors=_DEFAULT_ROTORS):
    """Sense of the tip-path-plane whirl of a mode (eigenvector ``vec``, Im(lambda) > 0).

    With beta1c ~ Re(c e^{i w t}), beta1s ~ Re(s e^{i w t}) the high point of the
    disk moves in the rotor's own direction of rotation when Im(conj(c) s) < 0.
    Returns a number in [-1, 1]: > 0 against the rotation (regressive: for
    nu > 1 the fixed-frame whirl (1 - nu) Omega is negative), < 0 with it
    (progressive, (1 + nu) Omega); each rotor in its own frame.
    """
    num = den = 0.0
    for i, name in enumerate(labels):
        m = re.match(rf"^beta1c({_suffix_pattern(rotors)[:-1]})?$", name.strip())
        if not m:
            continue
        sfx = m.group(1) or ""
        if f"beta1s{sfx}" not in labels:
            continue
        c, s = vec[i], vec[labels.index(f"beta1s{sfx}")]
        num += float(np.imag(np.conj(c) * s))
        den += abs(c) ** 2 + abs(s) ** 2
    return num / den if den > 0 else 0.0


def _label(lam, share, omega, whirl=0.0):
    wn = abs(lam)
    osc = abs(lam.imag) > 1e-6
    rotor = {g: share[g] for g in _ROTOR}
    body = {g: share[g] for g in _BODY}
    inflow = sum(share[g] for g in _INFLOW)
    if wn < 1e-9:
        return "heading"
    top_rotor = max(rotor, key=rotor.get)
    if osc and rotor[top_rotor] >= 0.3:
        if top_rotor == "coning":
            return "coning flap"
        if top_rotor == "reactionless":
            return "reactionless flap"
        # regressive/progressive by the whirl sense (the flap-body mode of a light
        # fuselage can sit above Omega); by frequency only if the sense is unclear
        if whirl < -0.05 or (abs(whirl) <= 0.05 and omega and wn > omega):
            return "progressive flap"
        return "regressive flap (" + ("roll" if share["roll"] + share["lateral"] >= share["pitch"]
                                      + share["longitudinal"] else "pitch") + ")"
    top_body = max(body, key=body.get)
    if inflow > max(sum(body.values()), rotor[top_rotor]) and body[top_body] < 0.35:
        if share["inflow_mean"] >= share["inflow_cyclic"] and share["inflow_mean"] > 0:
            return "inflow (mean)"
        return "inflow (cyclic)" if share["inflow_cyclic"] > 0 else "inflow"
    # (without the rotor speed: above 5 rad/s, faster than any body mode of a hovering aircraft)
    if osc and wn > (0.3 * omega if omega else 5.0) and rotor[top_rotor] > 0.15:
        # a flap-body oscillation in which the body rates dominate the participation
        return "regressive flap (" + ("roll" if share["roll"] >= share["pitch"] else "pitch") + ")"
    if osc:
        lon = share["longitudinal"] + share["pitch"]
        lat = share["lateral"] + share["roll"]
        return "phugoid (longitudinal)" if lon >= lat else "phugoid (lateral)"
    if top_body in ("longitudinal", "lateral"):
        return "subsidence (" + top_body + ")"
    return {"heave": "heave", "yaw": "yaw", "pitch": "pitch subsidence", "roll": "roll subsidence",
            "heading": "heading"}[top_body]


def classify_modes(sys, omega=None):
    """Pole table with a physics label per mode from its participation factors.

    Parameters
    ----------
    sys : control.StateSpace
        Named states (e.g. from :func:`aircraft.helicopter.linearize`).
    omega : float, optional
        Rotor speed [rad/s]; only a fallback where the whirl sense of a flap
        mode is unclear. Default: ``sys.trim.helicopter.config.rotors[0].omega``
        when present, else the whirl sense alone decides.

    Returns
    -------
    pandas.DataFrame
        One row per real pole or complex pair (positive imaginary part), sorted by
        frequency: ``real, imag, frequency`` [rad/s], ``damping``, ``physics``,
        ``dominant_states`` (top three) and one ``share_<group>`` column per state group.
    """
    if omega is None and hasattr(sys, "trim"):
        omega = sys.trim.helicopter.config.rotors[0].omega
    # the aircraft's rotor names where the model carries its trim (coaxial_compound's otherwise)
    rotors = tuple(r.name for r in sys.trim.helicopter.config.rotors) if hasattr(sys, "trim") else _DEFAULT_ROTORS
    a = np.asarray(sys.A, float)
    labels = list(sys.state_labels)
    groups = [state_group(s, rotors) for s in labels]
    lam, part, right = _participation(a)
    rows = []
    for k, l in enumerate(lam):
        if l.imag < -1e-9:
            continue
        share = {g: 0.0 for g in list(STATE_GROUPS) + ["other"]}
        for i, g in enumerate(groups):
            share[g] += part[i, k]
        top = np.argsort(-part[:, k])[:3]
        wn = abs(l)
        rows.append({"real": l.real, "imag": abs(l.imag), "frequency": wn,
                     "damping": -l.real / wn if wn > 0 else np.nan,
                     "physics": _label(l, share, omega, _whirl(labels, right[:, k], rotors)),
                     "dominant_states": ", ".join(f"{labels[i]} ({part[i, k]:.2f})" for i in top),
                     **{f"share_{g}": v for g, v in share.items()}})
    return pd.DataFrame(rows).sort_values("frequency").reset_index(drop=True)


def pair_modes(ours, reference):
    """Put our modes beside a reference table, matched by physics label.

    Within a label, modes are matched in order of frequency (the reference
    gives no eigenvectors to do better); a label present on one side only gets
    an unmatched row. A reference label without an axis (``"phugoid"``,
    ``"regressive flap"``) matches ours of either axis (``"phugoid (lateral)"``).

    Parameters
    ----------
    ours : pandas.DataFrame
        From :func:`classify_modes`.
    reference : pandas.DataFrame
        Columns ``physics``, ``frequency`` [rad/s], ``real`` [1/s] and optionally
        ``description`` (the reference's own wording).

    Returns
    -------
    pandas.DataFrame
        ``physics, ours_frequency, ours_real, ours_damping, ref_frequency,
        ref_real, ref_damping, ref_description, rel_diff_frequency``.
    """
    rows = []
    ref_labels = list(dict.fromkeys(reference.physics))

    def key(label):
        # a reference label without the axis ("phugoid") takes ours of either axis
        for r in ref_labels:
            if label == r or label.startswith(r + " ("):
                return r
        return label
    ours = ours.assign(_key=[key(lab) for lab in ours.physics])
    labels = list(dict.fromkeys(ref_labels + list(ours._key)))
    for lab in labels:
        a = ours[ours._key == lab].sort_values("frequency")
        b = reference[reference.physics == lab].sort_values("frequency")
        for i in range(max(len(a), len(b))):
            ra = a.iloc[i] if i < len(a) else None
            rb = b.iloc[i] if i < len(b) else None
            row = {"physics": ra.physics if ra is not None else lab,
                   "ours_frequency": ra.frequency if ra is not None else np.nan,
                   "ours_real": ra.real if ra is not None else np.nan,
                   "ours_damping": ra.damping if ra is not None else np.nan,
                   "ref_frequency": rb.frequency if rb is not None else np.nan,
                   "ref_real": rb.real if rb is not None else np.nan,
                   "ref_damping": (-rb.real / rb.frequency if rb is not None and rb.frequency > 0
                                   else np.nan),
                   "ref_description": rb.get("description", "") if rb is not None else ""}
            row["rel_diff_frequency"] = (row["ours_frequency"] - row["ref_frequency"]) / row["ref_frequency"] \
                if rb is not None and rb.frequency > 0 else np.nan
            rows.append(row)
    return pd.DataFrame(rows)


def flap_mode_damping(sys, band=(4.0, 20.0), reference=None, max_shift=0.25):
    """Where the regressive flap (flap-body) modes sit and how damped they are.

    Two ways to find them:

    * ``reference=None``: ``sys`` has named states (a bare-airframe model from
      :func:`~aircraft.helicopter.linearize`); the modes labelled regressive
      flap by :func:`classify_modes` are returned.
    * ``reference`` = such a bare-airframe model (or a table from this function):
      ``sys`` may be any system built on it whose states carry no names (a
      coupling numerator, a closed loop with actuator and controller); each
      reference flap mode is tracked to the pole of ``sys`` nearest to it in
      the complex plane (``distance`` says how far it moved).

    Parameters
    ----------
    sys : control.StateSpace or array_like
        The system (or its A matrix) whose flap-mode damping is wanted.
    band : (float, float)
        Frequency band [rad/s] of the ``min_damping_in_band`` column (the
        dissertation's "min zeta 4-20 rad/s", Table 7.5).
    reference : control.StateSpace or pandas.DataFrame, optional
    max_shift : float
        With ``reference``: a mode counts as tracked when the nearest pole lies
        within ``max_shift * |reference pole|``; otherwise (e.g. the pitch flap
        mode of a plant that holds q) its row has NaN frequency and damping and
        ``tracked`` False.

    Returns
    -------
    pandas.DataFrame
        One row per regressive flap mode: ``physics``, ``frequency`` [rad/s],
        ``damping``, ``real`` [1/s], ``in_band`` (frequency inside ``band``),
        ``distance`` (to the reference pole, [rad/s]; 0 without reference),
        ``tracked`` and ``min_damping_in_band`` (the least damped pole of ``sys`` in ``band``,
        whatever its physics, for comparison).
    """
    a = np.asarray(sys.A if hasattr(sys, "A") else sys, float)
    poles = np.linalg.eigvals(a)
    poles = poles[poles.imag >= -1e-9]
    wn = np.abs(poles)
    inband = (wn >= band[0]) & (wn <= band[1])
    zeta = np.where(wn > 0, -poles.real / np.where(wn > 0, wn, 1.0), np.nan)
    min_in_band = float(np.min(zeta[inband])) if inband.any() else np.nan
    if reference is None:
        table = classify_modes(sys)
        flap = table[table.physics.str.startswith("regressive flap")]
        out = flap[["physics", "frequency", "damping", "real"]].copy()
        out["distance"] = 0.0
        out["tracked"] = True
    else:
        ref = reference if isinstance(reference, pd.DataFrame) else flap_mode_damping(reference, band)
        rows = []
        for r in ref.itertuples():
            p_ref = complex(r.real, np.sqrt(max(r.frequency ** 2 - r.real ** 2, 0.0)))
            k = int(np.argmin(np.abs(poles - p_ref)))
            dist = float(abs(poles[k] - p_ref))
            ok = dist <= max_shift * abs(p_ref)
            rows.append({"physics": r.physics, "frequency": wn[k] if ok else np.nan,
                         "damping": zeta[k] if ok else np.nan, "real": poles[k].real if ok else np.nan,
                         "distance": dist, "tracked": ok})
        out = pd.DataFrame(rows)
    if out.empty:
        raise ValueError("no regressive flap mode found: the system has no named cyclic flap states "
                         "(give reference= a bare-airframe model with named states)")
    out["in_band"] = (out.frequency >= band[0]) & (out.frequency <= band[1])
    out["min_damping_in_band"] = min_in_band
    return out.reset_index(drop=True)


def _vary(config, parameter, value):
    from dataclasses import replace
    if parameter in ("Ixx", "Iyy", "Izz"):
        return replace(config, **{parameter: float(value)})
    if parameter == "flap_inertia":
        return replace(config, rotors=tuple(replace(r, flap_inertia=float(value)) for r in config.rotors))
    if parameter == "lock_number":
        # at fixed blade inertia (and so fixed hub stiffness): scale the lift-curve slope,
        # gamma = rho a c R^4 / I_b; the trim re-finds the collective for the same thrust
        return replace(config, rotors=tuple(
            replace(r, lift_slope=r.lift_slope * float(value) / r.lock_number(config.rho))
            for r in config.rotors))
    raise ValueError(f"parameter must be 'Ixx', 'Iyy', 'Izz', 'flap_inertia' or 'lock_number', "
                     f"got {parameter!r}")


def flap_mode_sensitivity(config, inflow_factory, parameter, values, settings=None):
    """Regressive flap (flap-body) modes against one assumption, re-trimmed per value.

    Parameters
    ----------
    config : AircraftConfig
    inflow_factory : callable
        ``inflow_factory()`` returns a fresh inflow model per point.
    parameter : {"Ixx", "Iyy", "Izz", "flap_inertia", "lock_number"}
        ``Ixx``... [kg m^2] of the airframe; ``flap_inertia`` [kg m^2] of every
        blade (changes the Lock number *and* the hub stiffness (nu^2 - 1) I_b
        Omega^2); ``lock_number`` [-] at fixed blade inertia, set through the
        lift-curve slope.
    values : array_like
    settings : HelicopterSettings, optional
        Default: 8 span points, 1 azimuth (exact in hover).

    Returns
    -------
    pandas.DataFrame
        ``parameter, value, physics, frequency`` [rad/s], ``damping``, ``real`` [1/s],
        ``lock_number`` of the first rotor; one row per regressive flap mode and value.
    """
    from .linearize import linearize
    from .model import Helicopter, HelicopterSettings
    from .trim import trim
    settings = settings or HelicopterSettings(n_span=8, n_average=1)
    rows = []
    for v in values:
        cfg = _vary(config, parameter, v)
        sys = linearize(trim(Helicopter(cfg, inflow_factory(), settings)))
        for r in flap_mode_damping(sys).itertuples():
            rows.append({"parameter": parameter, "value": float(v), "physics": r.physics,
                         "frequency": r.frequency, "damping": r.damping, "real": r.real,
                         "lock_number": cfg.rotors[0].lock_number(cfg.rho)})
    return pd.DataFrame(rows)
