"""Which cyclic acts on which axis: steady hub moments of the rotor controls and sticks.

A rotor's hub moment follows its cyclic pitch with a lag that depends on the blade's
flap frequency and Lock number: about 90 deg for an articulated rotor, far less for a
stiff hingeless one. The pilot mixing (:mod:`aircraft.helicopter.mixing`) carries the
lag as the aircraft's control phase angle. This module measures it on the aircraft
itself, from a linear model with the rotor controls as inputs:

* :func:`quasi_steady_moments`: the body-axis roll and pitch moments [N m/rad] each rotor
  control produces once flapping and inflow have settled, the body held still
  (body states frozen at trim, rotor and inflow states at their steady response);
* :func:`cyclic_moment_shares`: for each cyclic stick and rotor, the share of the moment
  on the stick's own axis (the cosine of the angle between moment and axis, signed:
  positive when the stick moves the aircraft the conventional way);
* :func:`derive_control_phase`: the control phase that maximises the smallest of those
  shares.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from .mixing import MixingError, mixing_matrix

__all__ = ["quasi_steady_moments", "cyclic_moment_shares", "derive_control_phase"]

_N_BODY = 9   # u v w p q r phi theta psi lead every Helicopter state vector


def _rotor_input_model(sys, config):
    names = list(sys.input_labels)
    if any(n.startswith("delta_") for n in names):
        raise MixingError("quasi_steady_moments needs the rotor controls as inputs: "
                          "linearize(trim_result, inputs='rotor')")
    n_controls = 3 * len(config.rotors) + 1
    if len(names) != n_controls:
        raise MixingError(f"the linear model has {len(names)} inputs; the aircraft has {n_controls} "
                          "rotor controls")
    return np.asarray(sys.A, float), np.asarray(sys.B, float), names


def quasi_steady_moments(sys, config):
    """Steady roll and pitch moments of each rotor control, the body held still.

    Parameters
    ----------
    sys : control.StateSpace
        ``linearize(trim_result, inputs="rotor")`` of a :class:`Helicopter`.
    config : AircraftConfig
        The same aircraft (its inertias turn accelerations into moments).

    Returns
    -------
    pandas.DataFrame
        Index: the rotor controls; columns ``roll_N_m_per_rad`` (L, right side down),
        ``pitch_N_m_per_rad`` (M, nose up), ``roll_share`` (|L| / |(L, M)|).

    Examples
    --------
    >>> from aircraft import coaxial_compound
    >>> from aircraft.helicopter import Helicopter, HelicopterSettings, linearize, trim
    >>> from aircraft.inflow import DynamicClimb
    >>> cfg = coaxial_compound()
    >>> sys = linearize(trim(Helicopter(cfg, DynamicClimb(), HelicopterSettings(n_average=1))),
    ...                 inputs="rotor")
    >>> bool(quasi_steady_moments(sys, cfg).loc["theta1s_U", "roll_share"] > 0.8)
    True
    """
    a, b, names = _rotor_input_model(sys, config)
    body = np.arange(_N_BODY)
    rest = np.arange(_N_BODY, a.shape[0])
    try:
        settled = -np.linalg.solve(a[np.ix_(rest, rest)], b[rest])
    except np.linalg.LinAlgError as err:
        raise MixingError("the rotor and inflow states have no steady response with the body held "
                          f"(singular block: {err})") from err
    accel = a[np.ix_(body, rest)] @ settled + b[body]
    inertia = np.array([[config.Ixx, 0.0, -config.Ixz], [0.0, config.Iyy, 0.0], [-config.Ixz, 0.0, config.Izz]])
    moments = inertia @ accel[3:6]
    roll, pitch = moments[0], moments[1]
    size = np.hypot(roll, pitch)
    share = np.divide(np.abs(roll), size, out=np.zeros_like(size), where=size > 0)
    return pd.DataFrame({"roll_N_m_per_rad": roll, "pitch_N_m_per_rad": pitch, "roll_share": share},
                        index=pd.Index(names, name="control"))


def _stick_moments(moments, config, control_phase):
    """Per rotor, the (roll, pitch) moment of its own controls under each cyclic stick.

    Returns an array ``(n_rotors, 2 sticks [lon, lat], 2 axes [roll, pitch])``: on a
    coaxial the two rotors' cross-axis parts cancel in the sum, so the pairing shows
    only rotor by rotor.
    """
    t = mixing_matrix(config, control_phase=control_phase)
    m = moments[["roll_N_m_per_rad", "pitch_N_m_per_rad"]].to_numpy()
    out = []
    for i in range(len(config.rotors)):
        rows = slice(3 * i, 3 * i + 3)
        out.append((m[rows].T @ t[rows][:, 1:3]).T)      # (2 sticks, 2 axes)
    return np.array(out)


def _shares(stick_moments):
    # signed cosine to each stick's own axis: lateral stick right -> roll right (+L),
    # longitudinal stick forward -> nose down (-M)
    lon, lat = stick_moments[..., 0, :], stick_moments[..., 1, :]
    return (-lon[..., 1] / np.hypot(lon[..., 0], lon[..., 1]),
            lat[..., 0] / np.hypot(lat[..., 0], lat[..., 1]))


def cyclic_moment_shares(sys, config, control_phase=None):
    """Share of each cyclic stick's steady hub moment on its own axis, rotor by rotor.

    Parameters
    ----------
    sys : control.StateSpace
        ``linearize(trim_result, inputs="rotor")``.
    config : AircraftConfig
    control_phase : float, optional
        Control phase angle [rad] of the mixing; default the configuration's.

    Returns
    -------
    pandas.DataFrame
        One row per cyclic stick and rotor: ``stick``, ``rotor``, ``roll_N_m`` and
        ``pitch_N_m`` (the moment of that rotor's swashplate per unit stick), ``axis`` and
        ``on_axis_share`` (signed cosine of the angle between the moment and the stick's
        own axis: 1 is a pure, correctly signed moment, 0 a moment on the other axis only).
        Rotor by rotor, because a coaxial's mirrored rotors cancel each other's cross-axis
        moments: the sum would look pure whatever the pairing.

    See Also
    --------
    derive_control_phase, aircraft.helicopter.mixing.mixing_matrix
    """
    moments = quasi_steady_moments(sys, config)
    per_rotor = _stick_moments(moments, config, control_phase)
    s_lon, s_lat = _shares(per_rotor)
    rows = []
    for i, rotor in enumerate(config.rotors):
        for j, (stick, axis, share) in enumerate((("delta_lon", "pitch", s_lon[i]), ("delta_lat", "roll", s_lat[i]))):
            rows.append({"stick": stick, "rotor": rotor.name, "roll_N_m": per_rotor[i, j, 0],
                         "pitch_N_m": per_rotor[i, j, 1], "axis": axis, "on_axis_share": float(share)})
    return pd.DataFrame(rows)


def derive_control_phase(sys, config, resolution=np.radians(0.1)):
    """The control phase angle that puts both cyclic sticks' moments on their own axes.

    Scans the phase over (-180, 180] deg and returns the one that maximises the smallest
    signed on-axis share of both sticks on every rotor (:func:`cyclic_moment_shares`): one
    phase for both sticks, as a swashplate has.

    Parameters
    ----------
    sys : control.StateSpace
        ``linearize(trim_result, inputs="rotor")``.
    config : AircraftConfig
    resolution : float
        Scan step [rad] (default 0.1 deg).

    Returns
    -------
    float
        Control phase angle [rad].
    """
    moments = quasi_steady_moments(sys, config)
    step = float(resolution)
    if not np.isfinite(step) or not 0 < step <= np.radians(10):
        raise MixingError(f"resolution must be in (0, 10 deg] [rad], got {resolution!r}")
    phases = np.arange(-np.pi + step, np.pi + step / 2, step)
    # the sticks' moments are linear in (cos gamma, sin gamma): two evaluations give all
    m0 = _stick_moments(moments, config, 0.0)
    m90 = _stick_moments(moments, config, np.pi / 2)
    c, s = np.cos(phases), np.sin(phases)
    scan = m0[None] * c[:, None, None, None] + m90[None] * s[:, None, None, None]
    s_lon, s_lat = _shares(scan)                      # (n_phases, n_rotors)
    worst = np.minimum(s_lon.min(axis=1), s_lat.min(axis=1))
    return float(phases[int(np.argmax(worst))])
