"""Lifting-line solve of the blades: bound circulation, loads and inflow per step.

Each blade is Ne lifting-line panels with linear lift up to a stall limit and
Kutta-Joukowski loads. The velocity of the bound and near-wake segments, whose
strengths follow from the unknown panel circulations, enters as a small linear
system; the tip vortices' (and far wake's) velocity is explicit. Panels in
(near-)reverse flow carry no lift.
"""
from __future__ import annotations

import numpy as np

from .biot_savart import segment_velocity, segment_influence
from ..inflow.base import rotor_suffix
from .errors import WakeDivergedError
from .outputs import blade_sum_loads, blade_sum_inflow, flap_rate_mbc, flap_mbc

__all__ = ["solve_blades", "advance_blades"]


def solve_blades(wake):
    """Bound circulation, loads and inflow of every blade at the current step.

    Parameters
    ----------
    wake : FreeVortexWake
        The wake; its ``gamma`` (panel circulation [m^2/s]), ``_lam0`` and
        ``_last`` are updated.

    Returns
    -------
    dict
        Per rotor name: ``CT, CL, CM, CQ`` [-], ``lam0, lam1s, lam1c`` [-],
        multiblade flap angles [rad] and rates [rad/s], the flap moment of each
        blade ``mflap`` [N m], and its peak and equivalent circulation
        ``gamma_max``, ``gamma_eq`` [m^2/s].
    """
    s = wake.settings
    ne = s.n_elements
    cols, nrm, tan, ut_ext, up_ext, kcoef, theta, psis = [], [], [], [], [], [], [], []
    for ir, rot in enumerate(wake.rotors):
        psib = wake._psi_blades(rot, wake.psi)
        er, et, span, normal = wake._blade_frames(rot, psib, wake.beta[ir])
        pts = wake._blade_points(rot, psib, wake.beta[ir], rot.r)
        rad_h = rot.R * rot.e + rot.R * (rot.r[None, :] - rot.e) * np.cos(wake.beta[ir])[:, None]
        vblade = (wake.omega * rad_h[:, :, None] * et[:, None, :]
                  + (wake.beta_dot[ir][:, None] * rot.R * (rot.r[None, :] - rot.e))[:, :, None]
                  * normal[:, None, :])
        cols.append(pts.reshape(-1, 3))
        nrm.append(np.repeat(normal, ne, axis=0))
        tan.append(np.repeat(et, ne, axis=0))
        vrel = wake.v_inf[None, None, :] - vblade
        ut_ext.append(-(vrel * et[:, None, :]).sum(-1).ravel())
        up_ext.append(-(vrel * normal[:, None, :]).sum(-1).ravel())
        if rot.sections is None:
            kcoef.append(np.full(rot.nb * ne, 0.5 * rot.chord * rot.a))
            th = wake._controls_at(rot, psib)[:, None] + rot.twist * (rot.r[None, :] - 0.75)
        else:   # real blade: chord, pitch, lift slope and tip loss per element
            sec = rot.sections
            kcoef.append(np.tile(0.5 * sec.chord * sec.lift_slope * sec.lift_fraction, rot.nb))
            th = wake._controls_at(rot, psib)[:, None] + sec.pitch[None, :]
        theta.append(th.ravel())
        psis.append(psib)
    P = np.concatenate(cols)
    n = np.concatenate(nrm)
    et = np.concatenate(tan)
    a, b, g, rc = wake._tip_sources()
    v_far = segment_velocity(P, a, b, g, rc, s.kernel_precision, chained=wake._compiled)
    aa, bb, rcc, gmap = wake._attached_segments()
    infl = segment_influence(P, aa, bb, rcc, chained=wake._compiled)   # (P, S, 3)
    infl_n = np.einsum("psk,pk->ps", infl, n) @ gmap        # normal velocity per unit gamma
    ut = np.concatenate(ut_ext) - np.einsum("pk,pk->p", v_far, et)
    up = np.concatenate(up_ext) - np.einsum("pk,pk->p", v_far, n)
    k = np.concatenate(kcoef)
    th = np.concatenate(theta)
    ut_min = 0.05 * wake.omega * wake.rotors[0].R
    active = ut > ut_min          # reverse flow and near-reverse: no lift
    rhs = np.where(active, k * (th * ut - up), 0.0)
    mat = np.eye(P.shape[0]) - np.where(active[:, None], k[:, None] * infl_n, 0.0)
    gam = np.linalg.solve(mat, rhs)
    up_tot = up - infl_n @ gam
    alpha = th - up_tot / np.where(active, ut, 1.0)
    if all(rot.sections is None for rot in wake.rotors):
        alpha_c = np.clip(alpha, -wake.rotors[0].stall, wake.rotors[0].stall)
        gam = np.where(active, k * alpha_c * ut, 0.0)
    else:
        gam = _section_circulation(wake, alpha, ut, k, active)
    if not np.all(np.isfinite(gam)):
        raise WakeDivergedError(f"non-finite bound circulation at t = {wake.t:.3f} s")
    v_att = np.einsum("psk,s->pk", infl, gmap @ gam)
    v_ind = v_far + v_att
    out = {}
    p0 = 0
    for ir, rot in enumerate(wake.rotors):
        sl = slice(p0, p0 + rot.nb * ne)
        p0 += rot.nb * ne
        G = gam[sl].reshape(rot.nb, ne)
        wake.gamma[ir] = G
        UT = ut[sl].reshape(rot.nb, ne)
        UP = up_tot[sl].reshape(rot.nb, ne)
        dL = wake.rho * G * UT * rot.dr[None, :] * rot.R          # along n
        if rot.sections is None:   # the classical blade (kept as written: same rounding)
            drag = (wake.rho * G * UP + 0.5 * wake.rho * (UT ** 2 + UP ** 2) * rot.chord * rot.cd0
                    * active[sl].reshape(rot.nb, ne)) * rot.dr[None, :] * rot.R
        else:
            sec = rot.sections
            cd = sec.drag(alpha[sl].reshape(rot.nb, ne), rot.cd0)
            drag = (wake.rho * G * UP + 0.5 * wake.rho * (UT ** 2 + UP ** 2) * sec.chord * cd
                    * active[sl].reshape(rot.nb, ne)) * rot.dr[None, :] * rot.R
        cb = np.cos(wake.beta[ir])[:, None]
        dT = dL * cb
        ct, cl, cm, cq = blade_sum_loads(dT, drag, rot.r, psis[ir], rot.scale)
        lam = -v_ind[sl, 2].reshape(rot.nb, ne) / (wake.omega * rot.R)
        l0, l1s, l1c = blade_sum_inflow(lam, rot.r, rot.dr, psis[ir])
        wake._lam0[ir] = max(l0, 0.0)
        b1s_dot, b1c_dot = flap_rate_mbc(wake.beta[ir], wake.beta_dot[ir], psis[ir], wake.omega)
        b0, b1s, b1c = flap_mbc(wake.beta[ir], psis[ir])
        # flap moment about the (equivalent) hinge
        mflap = (dL * rot.R * (rot.r[None, :] - rot.e)).sum(axis=1)
        out[rot.name] = dict(CT=ct, CL=cl, CM=cm, CQ=cq, lam0=l0, lam1s=l1s, lam1c=l1c,
                             beta1s_dot=b1s_dot, beta1c_dot=b1c_dot, beta0=b0,
                             beta1s=b1s, beta1c=b1c, mflap=mflap,
                             gamma_max=G.max(axis=1),
                             gamma_eq=(G * (rot.r * rot.dr)[None, :]).sum(axis=1)
                             / (rot.r * rot.dr).sum())
    wake._last = out
    return out


def _section_circulation(wake, alpha, ut, k, active):
    """Bound circulation Gamma = c c_l(alpha) U_T / 2 per panel [m^2/s], rotor by rotor.

    A classical rotor keeps its linear lift clipped at the stall angle; a real
    blade takes c_l from its section polar (and lifts only inboard of its tip loss).
    """
    ne = wake.settings.n_elements
    gam = np.zeros_like(alpha)
    p0 = 0
    for rot in wake.rotors:
        sl = slice(p0, p0 + rot.nb * ne)
        p0 += rot.nb * ne
        if rot.sections is None:
            gam[sl] = k[sl] * np.clip(alpha[sl], -wake.rotors[0].stall, wake.rotors[0].stall) * ut[sl]
        else:
            sec = rot.sections
            cl = sec.lift(alpha[sl].reshape(rot.nb, ne)) * sec.lift_fraction
            gam[sl] = (0.5 * sec.chord * cl).ravel() * ut[sl]
    return np.where(active, gam, 0.0)


def advance_blades(wake):
    """Advance the azimuth, time and flapping of every blade by one step (in place).

    Free flapping: symplectic Euler of the blade's flap equation (natural
    frequency ``nu`` per rev, aerodynamic flap moment of the last solve) over
    ``wake.dt`` [s]. Otherwise the prescribed tip-path plane (trim plus
    :meth:`~aircraft.wake.wake.FreeVortexWake.set_flap_inputs`) and its exact
    rate.

    Parameters
    ----------
    wake : FreeVortexWake
        The wake; ``t`` [s], ``psi`` [rad], ``beta`` [rad] and ``beta_dot``
        [rad/s] are updated.
    """
    s = wake.settings
    wake.t += wake.dt
    wake.psi += s.azimuth_step
    for ir, rot in enumerate(wake.rotors):
        psib = wake._psi_blades(rot, wake.psi)
        if s.free_flapping:
            m = wake._last[rot.name]["mflap"]
            acc = -wake.omega ** 2 * rot.nu2 * wake.beta[ir] + m / rot.inertia
            wake.beta_dot[ir] = wake.beta_dot[ir] + wake.dt * acc
            wake.beta[ir] = wake.beta[ir] + wake.dt * wake.beta_dot[ir]
        else:
            suf = rotor_suffix(rot.name)
            b0, b1c, b1s = wake.beta_trim[rot.name]
            b1c = b1c + wake.flap_inputs[f"beta1c{suf}"]
            b1s = b1s + wake.flap_inputs[f"beta1s{suf}"]
            db1c = wake.flap_input_rates[f"beta1c{suf}"]
            db1s = wake.flap_input_rates[f"beta1s{suf}"]
            wake.beta[ir] = b0 + b1c * np.cos(psib) + b1s * np.sin(psib)
            wake.beta_dot[ir] = (db1c * np.cos(psib) + db1s * np.sin(psib)
                                 + wake.omega * (-b1c * np.sin(psib) + b1s * np.cos(psib)))
