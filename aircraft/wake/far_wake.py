"""Prescribed helical continuation of the free tip vortices past the buffer."""
from __future__ import annotations

import numpy as np

__all__ = ["far_wake_segments"]


def far_wake_segments(wake, ir, X, rc_end):
    """Prescribed helical continuation of each tip vortex past the buffer.

    Without it the wake simply ends: the last free turns then see roughly half
    the induced velocity of an infinite wake, slow down, bunch up and roll up
    into a ring (the tip vortex radius was measured growing past 1.1 R after
    3-4 revolutions), and the rotor inflow and its low-frequency gain depend on
    the wake length. The continuation is a source only (no markers are
    convected): per blade, an ideal helix about the rotor axis that drifts with
    the free stream plus the rotor's mean induced velocity (momentum theory's
    far-wake vortex descent), with the mean radius of the last free revolution
    and the strength of the last shed turn, ``far_wake_revolutions`` long in
    ``far_wake_step`` chords (coarse is enough that far from the disk). It
    starts at the mean height of the wake's end, joined to each blade's
    actual last marker by one segment.
    """
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
    n_seg = max(1, int(round(s.far_wake_revolutions * 2 * np.pi / s.far_wake_step)))
    zeta = wake._ages[-1] + np.arange(n_seg + 1) * s.far_wake_step   # wake age [rad]
    t_rel = (zeta - zeta[0]) / wake.omega
    t_abs = zeta / wake.omega
    z0 = X[:, -1, 2].mean()
    psib = wake._psi_blades(rot, wake.psi)
    g_far = wake.G_tip[ir][:, -nrev:].mean(axis=1)             # strength of the last turn
    A, B, G = [], [], []
    for b in range(rot.nb):
        ang = psib[b] - zeta
        pts = np.stack([rot.hub[0] - radius * np.cos(ang) + drift[0] * t_abs,
                        rot.hub[1] - rot.d * radius * np.sin(ang) + drift[1] * t_abs,
                        z0 + drift[2] * t_rel], axis=1)
        pts = np.vstack([X[b, -1][None, :], pts])
        A.append(pts[:-1])
        B.append(pts[1:])
        G.append(np.full(n_seg + 1, rot.d * g_far[b]))
    rc = np.full(rot.nb * (n_seg + 1), rc_end)
    return np.concatenate(A), np.concatenate(B), np.concatenate(G), rc
