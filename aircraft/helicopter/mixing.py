"""Pilot mixing (Eq. 7.19) between pilot inputs and rotor controls, with the swashplate
control phase angle.

The dissertation mixes sums and differences of the upper and lower swashplate
angles with K = 0.5: collective = K (theta0^U + theta0^L), pedal =
K (theta0^U - theta0^L), cyclic sticks = K x (sum of the rotors' cyclic),
propeller = K theta_PR. Which cyclic each stick drives is set by the rotor's
physics, through the **control phase angle** ``gamma`` of the aircraft
(:attr:`aircraft.configs.AircraftConfig.control_phase`).

Derivation, in each rotor's own frame (azimuth psi from aft in the direction of
rotation, :mod:`aircraft.inflow.base`). A cyclic ``theta1c cos psi + theta1s sin psi``
has its maximum pitch at the azimuth ``psi_max`` with ``(theta1c, theta1s) =
A (cos psi_max, sin psi_max)``. A rotor loads the disc, and so moves the hub, some
azimuth ``Delta`` after the pitch maximum: about 90 deg for an articulated rotor
(flap frequency near 1/rev), much less for a stiff hingeless rotor, whose hub
moment comes mostly straight from the blade lift. Roll right (right side down)
needs the extra lift on the port side: psi = 270 deg for a counter-clockwise rotor
(direction +1), 90 deg for a clockwise one. Nose down needs it aft (psi = 0).

* ``gamma = 0`` is the articulated rule (``Delta = 90`` deg): the pitch maximum
  90 deg ahead of the lift wanted, i.e. lateral stick on ``-direction * theta1c``
  and longitudinal stick on ``-theta1s``.
* A control phase ``gamma`` applies the same cyclic ``gamma`` later in the
  rotation (the pitch maximum moves from ``psi_max`` to ``psi_max + gamma``), for a
  rotor whose response lags by ``Delta = 90 deg - gamma``::

      theta1c' = cos(gamma) theta1c - sin(gamma) theta1s
      theta1s' = sin(gamma) theta1c + cos(gamma) theta1s

* ``gamma = 90`` deg is Eq. 7.19's pairing for the coaxial's hingeless rotor
  (§7.2.2: "theta1s produces primarily roll response and theta1c produces
  primarily pitch"): per rotor of direction ``d``::

      theta1s = -d delta_lat / (n K)        theta1c = +delta_lon / (n K)

  i.e. ``delta_lat = K (theta1s_L - theta1s_U)`` and
  ``delta_lon = K (theta1c_U + theta1c_L)`` on the coaxial (n = 2 rotors).

Sign convention of the sticks: positive = more collective, stick forward (nose
down), stick right (roll right), right pedal (nose right), more propeller pitch.
:func:`aircraft.helicopter.control_phase.cyclic_moment_shares` measures, on a
linearised aircraft, how much of each cyclic stick's steady hub moment lies on its
own axis, and :func:`~aircraft.helicopter.control_phase.derive_control_phase` the
phase that puts it there.

The **differential lateral cyclic** (lift-offset control,
``TrimCondition.lateral_cyclic_difference``) pairs the same way: a positive
difference moves each rotor's lift towards its own advancing side
(own-frame psi = 90 deg), so the roll moments of the two rotors cancel and the lift
offset grows; at ``gamma = 90`` deg it is ``theta1s_U = theta1s_L = +difference / 2``
(the dissertation's ``delta_Delta_lat = theta1s^U - theta1s^L`` in its frames,
where the lower rotor's azimuth runs the other way).
"""
from __future__ import annotations

import math

import numpy as np

from .._validation import real as _real

__all__ = ["MixingError", "PILOT_INPUTS", "ROTOR_CONTROLS", "pilot_inputs", "cyclic_rotation", "mixing_matrix",
           "lateral_cyclic_difference_controls"]

#: pilot inputs of the coaxial compound (a single-rotor aircraft has no ``delta_prop``)
PILOT_INPUTS = ["delta_col", "delta_lon", "delta_lat", "delta_ped", "delta_prop"]
#: rotor controls of the coaxial compound, in the order of ``Helicopter.input_names``
ROTOR_CONTROLS = ["theta0_U", "theta1s_U", "theta1c_U", "theta0_L", "theta1s_L", "theta1c_L", "theta_prop"]


class MixingError(ValueError):
    """A mixing argument (configuration, gain, control phase) is invalid."""


def pilot_inputs(config=None):
    """Pilot input names of an aircraft: the coaxial's five, or four for a single rotor.

    Parameters
    ----------
    config : AircraftConfig, optional
        Default: the coaxial layout.

    Returns
    -------
    list of str
    """
    if config is None or config.is_coaxial:
        return list(PILOT_INPUTS)
    return PILOT_INPUTS[:4]


def cyclic_rotation(control_phase):
    """2 x 2 rotation of an own-frame cyclic ``(theta1s, theta1c)`` by a control phase.

    Parameters
    ----------
    control_phase : float
        Swashplate control phase angle gamma [rad]: the cyclic is applied gamma later
        in the rotor's rotation than the articulated (90 deg lag) rule.

    Returns
    -------
    numpy.ndarray
        ``R`` with ``(theta1s', theta1c') = R @ (theta1s, theta1c)``.

    Examples
    --------
    >>> import numpy as np
    >>> np.round(cyclic_rotation(np.pi / 2) @ [0.0, -1.0], 12) + 0.0   # -theta1c -> -theta1s
    array([-1.,  0.])
    """
    g = _real(MixingError, "control_phase", control_phase, lo=-math.pi, hi=math.pi, unit="rad")
    c, s = math.cos(g), math.sin(g)
    # (theta1s', theta1c') = (s theta1c + c theta1s, c theta1c - s theta1s)
    return np.array([[c, s], [-s, c]])


def _layout(config):
    """(rotor directions, has propeller, control phase) of an aircraft (default: the coaxial's)."""
    if config is None:
        return (1, -1), True, math.pi / 2
    return tuple(r.direction for r in config.rotors), config.propeller is not None, config.control_phase


def _pedal_sign(config):
    """Sign of the tail-rotor control per right pedal (nose right).

    A tail rotor thrusting along ``thrust_sign * y`` at ``x`` gives the yaw moment
    ``x * thrust_sign * T``; right pedal must raise it. Without a tail rotor the
    idealised yaw control is positive nose right.
    """
    tail = getattr(config, "tail_rotor", None)
    if tail is None:
        return 1.0
    return float(np.sign(tail.position[0] * tail.thrust_sign))


def mixing_matrix(config=None, k=None, control_phase=None):
    """``T`` with ``theta = T @ delta + offsets``: the inverse of Eq. 7.19's mixing.

    Parameters
    ----------
    config : AircraftConfig, optional
        The aircraft (its rotors' directions, propeller and ``control_phase``).
        Default: the coaxial compound's layout with Eq. 7.19's 90 deg phase.
    k : float, optional
        Mixing gain K (delta = K x sum of the rotors' angles); default
        ``1 / n_rotors``: Eq. 7.19's 0.5 on the coaxial, 1 on a single rotor
        (each stick then moves each rotor's angle one for one).
    control_phase : float, optional
        Overrides the configuration's control phase angle [rad].

    Returns
    -------
    numpy.ndarray
        ``(n_controls, n_pilot)``: rows in ``Helicopter.input_names`` order (per
        rotor ``theta0, theta1s, theta1c``, then ``theta_prop`` or the single
        rotor's ``theta_tr``), columns in :func:`pilot_inputs` order. Right pedal
        (nose right) lowers the collective of a tail rotor aft of the c.g. that
        thrusts to starboard.

    Examples
    --------
    >>> import numpy as np
    >>> t = mixing_matrix()                       # coaxial, control phase 90 deg
    >>> t[[1, 4], 2]                              # delta_lat -> theta1s_U, theta1s_L
    array([-1.,  1.])
    >>> t[[2, 5], 1]                              # delta_lon -> theta1c_U, theta1c_L
    array([1., 1.])
    """
    directions, propeller, gamma = _layout(config)
    if control_phase is not None:
        gamma = control_phase
    n = len(directions)
    k = 1.0 / n if k is None else _real(MixingError, "k", k, positive=True)
    rot = cyclic_rotation(gamma)
    g = 1.0 / (n * k)
    single = n == 1
    n_pilot = 4 if single else 5
    t = np.zeros((3 * n + 1, n_pilot))
    for i, d in enumerate(directions):
        r0 = 3 * i
        t[r0, 0] = g                                     # collective
        if not single:
            t[r0, 3] = g * (1 if i == 0 else -1)          # pedal: differential collective
        # articulated rule (gamma = 0), own frame (theta1s, theta1c), then rotated
        t[r0 + 1:r0 + 3, 1] = rot @ np.array([-g, 0.0])            # longitudinal
        t[r0 + 1:r0 + 3, 2] = rot @ np.array([0.0, -d * g])        # lateral
    if single:
        t[3, 3] = _pedal_sign(config) / k          # pedal -> tail-rotor control
    elif propeller:
        t[3 * n, 4] = 1.0 / k
    return t


def lateral_cyclic_difference_controls(config, difference):
    """Rotor-control increment of a differential lateral cyclic (lift-offset control).

    Parameters
    ----------
    config : AircraftConfig
        A coaxial aircraft (its ``control_phase`` pairs the input).
    difference : float
        Differential lateral cyclic [rad]; positive moves each rotor's lift towards
        its own advancing side.

    Returns
    -------
    numpy.ndarray
        Increment of the rotor controls (``Helicopter.input_names`` order):
        ``+difference / 2`` on each rotor's own-frame cyclic at the advancing side,
        rotated back by the control phase (``theta1s`` on both rotors at 90 deg).

    Examples
    --------
    >>> from aircraft import coaxial_compound
    >>> lateral_cyclic_difference_controls(coaxial_compound(), 0.02)[[1, 2, 4, 5]].round(12)
    array([0.01, 0.  , 0.01, 0.  ])
    """
    directions, _, gamma = _layout(config)
    if len(directions) != 2:
        raise MixingError("a differential lateral cyclic needs a coaxial aircraft (two rotors)")
    difference = _real(MixingError, "difference", difference, lo=-math.pi / 6, hi=math.pi / 6, unit="rad")
    rot = cyclic_rotation(gamma)
    u = np.zeros(3 * len(directions) + 1)
    for i in range(len(directions)):
        # articulated rule: pitch maximum 90 deg before the advancing side (psi = 0)
        u[3 * i + 1:3 * i + 3] = rot @ np.array([0.0, difference / 2])
    return u
