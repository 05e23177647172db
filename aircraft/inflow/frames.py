"""Rotor frames: converting inflow models between the dissertation's and ours.

Our frames (:mod:`aircraft.inflow.base`, used by the wake and the aircraft)
-----------------------------------------------------------------------------
Every rotor is described in its *own* frame: azimuth psi from aft, increasing in
that rotor's direction of rotation ``d`` (+1 counter-clockwise seen from above,
-1 clockwise). A blade at azimuth psi lies at body position
``x = -r cos psi`` (aft), ``y = d r sin psi`` (right), as in
:meth:`aircraft.wake.FreeVortexWake._blade_frames`. The harmonics are then

* ``lam1s`` (coefficient of ``r sin psi``) = d * (lateral inflow gradient, right-positive),
* ``lam1c`` (coefficient of ``r cos psi``) = -(longitudinal gradient, forward-positive),
* ``C_L = -sum dT r sin psi`` = d * (body roll moment), ``C_M`` = body pitch moment,
* ``beta1s`` (coefficient of ``sin psi``) = d * (lateral tip-path-plane tilt),

so only the *sine* (lateral) signals of a clockwise rotor change sign against a
counter-clockwise one; collective and cosine (longitudinal) signals do not.

The dissertation's printed coaxial models (Eq. 5.3, Eqs. 6.8-6.9)
----------------------------------------------------------------
are written in one common frame for both rotors, the upper rotor's sense of
rotation (its pitch/roll symmetry ties ``m25 = m36``, ``m52 = m63`` hold only in a
common frame, see ``tests/aircraft/identification/test_frames.py``; our own wake measures
``lam1s_L/CL_U = +12.3`` and ``lam1c_L/CM_U = -11.9`` at 1 rad/s where the printed
Eq. 5.3 gives ``-11.3`` and ``-11.3``). Between the common frame (subscript d) and
our frames (subscript o) every signal is multiplied by a sign ``s = +-1``:
``s = d_rotor * d_reference`` for the lateral signals (``lam1s``, ``CL``,
``beta1s_dot`` and the near/far states ``lam1sN``, ``lam1sF``), ``+1`` otherwise. With
``T = diag(s)`` (so ``T^-1 = T``):

* ``M lam' + Lbar lam = C(t - tau)``:  ``M_o = T_C M_d T_lam``, ``Lbar_o = T_C Lbar_d T_lam``,
  ``tau_o = tau_d`` (a delay is a duration: the transfer element ``H_ij`` only changes
  sign, ``H_o = T_lam H_d T_C``);
* ``x' = F x + G u``, ``lam = C x``:  ``F_o = T_x F_d T_x``, ``G_o = T_x G_d T_u``,
  ``C_o = T_lam C_d T_x``.

For the coaxial (upper +1, lower -1) this flips exactly the cross-rotor lateral
couplings (``m25, m52, l25, l52`` of Eq. 5.3 and their F/G counterparts); every
on-rotor term and every longitudinal and collective term is unchanged. The
conversion is its own inverse. Single-rotor models are unchanged.
"""
from __future__ import annotations

import numpy as np

__all__ = ["FrameError", "LATERAL_SIGNALS", "frame_signs", "convert_frames", "COAXIAL_DIRECTIONS",
           "rotor_directions"]

#: Signal-name stems that change sign with the sense of rotation (sine / roll axis).
LATERAL_SIGNALS = ("lam1s", "lam1sN", "lam1sF", "CL", "beta1s_dot", "beta1s", "theta1s")

#: Senses of rotation of :func:`aircraft.configs.coaxial_compound` (upper CCW, lower CW);
#: another aircraft's are :func:`rotor_directions` of its configuration.
COAXIAL_DIRECTIONS = {"U": 1, "L": -1}


def rotor_directions(config):
    """Sense of rotation per rotor name of an aircraft, upper (first) rotor first.

    Parameters
    ----------
    config : aircraft.AircraftConfig
        Its rotors' ``name`` and ``direction`` (+1 counter-clockwise seen from above).

    Returns
    -------
    dict
        ``{name: direction}`` in the configuration's rotor order, as
        :func:`frame_signs` takes it (the first rotor sets the default reference).

    Raises
    ------
    FrameError
        Rotor names that are not distinct signal suffixes, or a direction other than +-1.

    Examples
    --------
    >>> from aircraft.configs import coaxial_compound
    >>> rotor_directions(coaxial_compound()) == COAXIAL_DIRECTIONS
    True
    """
    from .base import check_rotor_names
    rotors = getattr(config, "rotors", None) or ()
    names = check_rotor_names([getattr(r, "name", None) for r in rotors], argument="config rotor names",
                              error=FrameError)
    out = {}
    for name, r in zip(names, rotors):
        d = getattr(r, "direction", None)
        if d not in (1, -1):
            raise FrameError(f"direction of rotor {name!r} must be +1 or -1, got {d!r}")
        out[name] = int(d)
    return out


class FrameError(ValueError):
    """Raised for signal names or rotor directions the frame conversion cannot place."""


def _split(name):
    """``"beta1s_dot_L" -> ("beta1s_dot", "L")``; ``"lam0" -> ("lam0", "")``."""
    if name.endswith("_dot"):     # single-rotor flap rate: no rotor suffix
        return name, ""
    if "_" in name:
        stem, rotor = name.rsplit("_", 1)
        return stem, rotor
    return name, ""


def frame_signs(names, directions, reference=None):
    """Signs taking each named signal from a common frame to the rotor's own frame.

    Parameters
    ----------
    names : sequence of str
        Canonical signal names (``"CL_L"``, ``"lam1sN_U"``, ``"beta1s_dot_L"``, ...).
    directions : dict
        Sense of rotation per rotor name, ``{"U": 1, "L": -1}`` (+1 counter-clockwise
        seen from above); a single rotor is ``{"": 1}``.
    reference : int, optional
        Sense of rotation of the common frame (default: that of the first rotor in
        ``directions``, the upper rotor for the dissertation's models).

    Returns
    -------
    ndarray of float
        ``+1`` or ``-1`` per name (``-1`` for the lateral signals of a rotor turning
        against the reference).
    """
    directions = dict(directions)
    if not directions:
        raise FrameError("directions must name at least one rotor")
    for r, d in directions.items():
        if d not in (1, -1):
            raise FrameError(f"direction of rotor {r!r} must be +1 or -1, got {d!r}")
    ref = next(iter(directions.values())) if reference is None else reference
    if ref not in (1, -1):
        raise FrameError(f"reference direction must be +1 or -1, got {ref!r}")
    out = []
    for name in names:
        stem, rotor = _split(str(name))
        if rotor not in directions:
            raise FrameError(f"signal {name!r}: rotor {rotor!r} not in directions {sorted(directions)}")
        out.append(float(directions[rotor] * ref) if stem in LATERAL_SIGNALS else 1.0)
    return np.array(out)


def convert_frames(matrix, row_names, col_names, directions, reference=None):
    """``diag(s_rows) @ matrix @ diag(s_cols)``: a model matrix between common and rotor frames.

    The same call converts either way (``T^-1 = T``). Use it for ``M``, ``Lbar``
    (rows: the load equations, columns: the inflow states), ``F`` (states, states),
    ``G`` (states, inputs), ``C`` (outputs, states) and any transfer or gain matrix
    (outputs, inputs). Delays are durations and are never converted.

    Parameters
    ----------
    matrix : (n, m) array_like
    row_names, col_names : sequence of str
        Signal names of the rows and the columns (see :func:`frame_signs`).
    directions, reference :
        As for :func:`frame_signs`.

    Returns
    -------
    ndarray (n, m)
    """
    a = np.asarray(matrix, float)
    if a.shape != (len(row_names), len(col_names)):
        raise FrameError(f"matrix shape {a.shape} does not match {len(row_names)} row and "
                         f"{len(col_names)} column names")
    sr = frame_signs(row_names, directions, reference)
    sc = frame_signs(col_names, directions, reference)
    return sr[:, None] * a * sc[None, :]
