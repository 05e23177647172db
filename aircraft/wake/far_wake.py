"""Far-wake continuation of the free tip vortices past the buffer.

Two models (``WakeSettings.far_wake_convected``):

* convected (default): the far wake is the frozen buffer continued at a coarser
  chord. Every ``far_wake_step`` the buffer's end marker of each blade is released
  as a far-wake point carrying the circulation it had; the points then move
  rigidly with the buffer's convection velocity. The far wake thus holds the
  history of what left the buffer (strength, radius, height), as the real wake
  does, and nothing in it jumps when the rotor's state changes. Until
  ``far_wake_revolutions`` have been released, the rest is the prescribed helix
  below (a starting helix convected from the initial prescribed wake, which
  descends faster than the free wake, hung detached below the buffer and made the
  tip vortex bulge to 1.15 R).
* prescribed: an ideal helix rebuilt every step from the
  current state -- the last free revolution's mean radius, the last buffer turn's
  mean strength for its whole length, a descent at the rotor's current mean
  inflow -- so the whole far wake follows the wake's end instantly.

Diagnosis of the ~1 % lambda0 oscillation of trimmed coaxial hover (period ~0.77
x the wake age at the buffer's end: 4 rev at 4 + 1 free + buffer revolutions,
2.4-2.5 rev at 2 + 1, i.e. set by the truncation, hence numerical): freezing this
prescribed far wake left it (1.4 -> 1.1 % rms of the revolution averages, coarse
wake); holding the buffer's convection velocity constant removed it (0.15-0.2 %).
The cure is therefore in the buffer velocity (one for all rotors, low-passed; see
``FreeVortexWake._buffer_velocity`` and ``WakeSettings.buffer_velocity_revolutions``);
the convected far wake follows that velocity and the history, not the moment.
"""
from __future__ import annotations

import numpy as np

__all__ = ["far_wake_segments", "far_wake_release_steps", "initial_far_wake", "convect_far_wake"]


def far_wake_release_steps(settings) -> int:
    """Steps between two far-wake points (the far-wake chord over the step) [-].

    Parameters
    ----------
    settings : WakeSettings
        Uses ``far_wake_step`` over ``azimuth_step`` (rounded, at least 1).

    Returns
    -------
    int
    """
    return max(1, int(round(settings.far_wake_step / settings.azimuth_step)))


def _n_far_points(settings) -> int:
    m = far_wake_release_steps(settings)
    return max(1, int(round(settings.far_wake_revolutions * settings.steps_per_rev / m)))


def _helix(wake, ir, X, n_points, start):
    """Prescribed helix past the buffer end: points (Nb, n_points, 3) at wake ages
    ``ages[-1] + (start + k) * step`` and the last buffer turn's strength (Nb,)."""
    s = wake.settings
    rot = wake.rotors[ir]
    nrev = s.steps_per_rev
    nf = s.n_free
    drift = wake.v_inf - np.array([0.0, 0.0, wake._lam0[ir] * wake.omega * rot.R])
    # helix axis: through the hub, carried downstream by the in-plane free stream
    # over the wake age (in forward flight the wake's end lies ~mu zeta R behind
    # the hub; an axis fixed at the hub put the whole far wake under the disk)
    k0 = max(nf + 1 - nrev, 1)
    last = X[:, k0:nf + 1, :]                                  # last free revolution
    t_last = wake._ages[k0:nf + 1] / wake.omega
    radius = np.hypot(last[..., 0] - rot.hub[0] - drift[0] * t_last,
                      last[..., 1] - rot.hub[1] - drift[1] * t_last).mean()
    radius = float(np.clip(radius, 0.6 * rot.R, 1.0 * rot.R))
    step = (far_wake_release_steps(s) * s.azimuth_step if s.far_wake_convected
            else s.far_wake_step)
    zeta = wake._ages[-1] + (start + np.arange(n_points)) * step   # wake age [rad]
    t_rel = (zeta - wake._ages[-1]) / wake.omega
    t_abs = zeta / wake.omega
    z0 = X[:, -1, 2].mean()
    psib = wake._psi_blades(rot, wake.psi)
    g_far = wake.G_tip[ir][:, -nrev:].mean(axis=1)             # strength of the last turn
    if not getattr(wake, "_compiled", True):
        return _helix_reference(wake, ir, X, n_points, start)
    # all blades at once; element by element the same operations as the loop of
    # _helix_reference, so the same numbers
    ang = psib[:, None] - zeta[None, :]
    pts = np.empty((rot.nb, n_points, 3))
    pts[..., 0] = rot.hub[0] - radius * np.cos(ang) + drift[0] * t_abs
    pts[..., 1] = rot.hub[1] - rot.d * radius * np.sin(ang) + drift[1] * t_abs
    pts[..., 2] = z0 + drift[2] * t_rel
    return pts, g_far


def _helix_reference(wake, ir, X, n_points, start):
    """:func:`_helix` as a loop over the blades (the reference march, ``wake._compiled``
    False); the same numbers."""
    s = wake.settings
    rot = wake.rotors[ir]
    nrev = s.steps_per_rev
    nf = s.n_free
    drift = wake.v_inf - np.array([0.0, 0.0, wake._lam0[ir] * wake.omega * rot.R])
    # helix axis: through the hub, carried downstream by the in-plane free stream
    # over the wake age (in forward flight the wake's end lies ~mu zeta R behind
    # the hub; an axis fixed at the hub put the whole far wake under the disk)
    k0 = max(nf + 1 - nrev, 1)
    last = X[:, k0:nf + 1, :]                                  # last free revolution
    t_last = wake._ages[k0:nf + 1] / wake.omega
    radius = np.hypot(last[..., 0] - rot.hub[0] - drift[0] * t_last,
                      last[..., 1] - rot.hub[1] - drift[1] * t_last).mean()
    radius = float(np.clip(radius, 0.6 * rot.R, 1.0 * rot.R))
    step = (far_wake_release_steps(s) * s.azimuth_step if s.far_wake_convected
            else s.far_wake_step)
    zeta = wake._ages[-1] + (start + np.arange(n_points)) * step   # wake age [rad]
    t_rel = (zeta - wake._ages[-1]) / wake.omega
    t_abs = zeta / wake.omega
    z0 = X[:, -1, 2].mean()
    psib = wake._psi_blades(rot, wake.psi)
    g_far = wake.G_tip[ir][:, -nrev:].mean(axis=1)             # strength of the last turn
    pts = np.empty((rot.nb, n_points, 3))
    for b in range(rot.nb):
        ang = psib[b] - zeta
        pts[b] = np.stack([rot.hub[0] - radius * np.cos(ang) + drift[0] * t_abs,
                           rot.hub[1] - rot.d * radius * np.sin(ang) + drift[1] * t_abs,
                           z0 + drift[2] * t_rel], axis=1)
    return pts, g_far


def initial_far_wake(wake, ir, X):
    """Far-wake points and strengths of the starting wake (a prescribed helix).

    Parameters
    ----------
    wake : FreeVortexWake
        The wake (settings, rotors, rotor speed, inflow).
    ir : int
        Rotor index.
    X : ndarray, shape (Nb, n_markers, 3)
        Tip-vortex marker positions of rotor ``ir`` [m].

    Returns
    -------
    points : ndarray, shape (Nb, n_far, 3)
        Far-wake points, youngest first [m].
    gamma : ndarray, shape (Nb, n_far)
        Circulation of the segment starting at each point [m^2/s] (unsigned).
    """
    n = _n_far_points(wake.settings)
    pts, g = _helix(wake, ir, X, n, 1)
    return pts, np.repeat(g[:, None], n, axis=1)


def convect_far_wake(wake, ir, v, X_end, g_end):
    """Advance the convected far wake of rotor ``ir`` by one step (in place).

    Parameters
    ----------
    wake : FreeVortexWake
        The wake (its far-wake buffers ``far_points``, ``far_gamma``,
        ``far_phase``, ``far_released`` are updated).
    ir : int
        Rotor index.
    v : ndarray, shape (3,)
        Convection velocity of the far wake (the buffer's) [m/s].
    X_end : ndarray, shape (Nb, 3)
        The buffer's end markers after the step [m].
    g_end : ndarray, shape (Nb,)
        Their circulation [m^2/s].
    """
    pts, g = wake.far_points[ir], wake.far_gamma[ir]
    pts += wake.dt * v
    wake.far_phase[ir] += 1
    if wake.far_phase[ir] >= far_wake_release_steps(wake.settings):
        # release: the buffer's end becomes the youngest far-wake point
        pts[:, 1:] = pts[:, :-1].copy()
        pts[:, 0] = X_end
        g[:, 1:] = g[:, :-1].copy()
        g[:, 0] = g_end
        wake.far_phase[ir] = 0
        wake.far_released[ir] = min(wake.far_released[ir] + 1, g.shape[1])


def far_wake_segments(wake, ir, X, rc_end):
    """Far-wake source segments of rotor ``ir``: (a, b, gamma, rc).

    The first segment of each blade joins the buffer's end marker to the far wake.
    Without a far wake the wake simply ends: the last free turns then see roughly
    half the induced velocity of an infinite wake, slow down, bunch up and roll up
    into a ring (the tip vortex radius was measured growing past 1.1 R after 3-4
    revolutions), and the rotor inflow and its low-frequency gain depend on the
    wake length. Sources only: the far wake is not convected by its own velocity.
    """
    s = wake.settings
    rot = wake.rotors[ir]
    if s.far_wake_convected:
        far, g_far = wake.far_points[ir], wake.far_gamma[ir]
        n_rel = wake.far_released[ir]
        if n_rel < far.shape[1]:
            # not yet flushed: past the points released so far, the prescribed helix
            # of the current wake end (the starting helix, placed from the initial
            # prescribed wake, would hang detached below the buffer)
            tail, g_tail = _helix(wake, ir, X, far.shape[1] - n_rel, n_rel + 1)
            far = np.concatenate([far[:, :n_rel], tail], axis=1)
            g_far = np.concatenate([g_far[:, :n_rel],
                                    np.repeat(g_tail[:, None], far.shape[1] - n_rel, axis=1)],
                                   axis=1)
        # the junction carries the buffer end's own circulation
        g = np.concatenate([wake.G_tip[ir][:, -1:], g_far[:, :-1]], axis=1)
    else:
        n_seg = max(1, int(round(s.far_wake_revolutions * 2 * np.pi / s.far_wake_step)))
        far, g_far = _helix(wake, ir, X, n_seg + 1, 0)
        g = np.repeat(g_far[:, None], n_seg + 1, axis=1)
    pts = np.concatenate([X[:, -1:, :], far], axis=1)
    A = pts[:, :-1].reshape(-1, 3)
    B = pts[:, 1:].reshape(-1, 3)
    G = rot.d * g.ravel()
    return A, B, G, np.full(A.shape[0], rc_end)
