"""Time-marching free-vortex wake of one rotor or a coaxial pair (wind-tunnel mode).

Computational frame: origin at the first (upper/main) hub, X forward, Y to port,
Z up along the shaft (the shaft is fixed; the free stream carries the rotor angle
of attack).  Rotor quantities are reported in each rotor's own frame
(:mod:`aircraft.inflow.base`); off-rotor velocities in body axes.

Per step (d t = d psi / Omega, equal to the wake-age step d zeta):

1. velocities V^n at the free tip-vortex markers (Biot-Savart of every tip-vortex,
   near-wake and bound segment of every rotor, plus the free stream);
2. predictor (explicit, second-order Adams-Bashforth along the marker path);
3. blades advance (azimuth, controls, flapping); new rigid near wake;
4. corrector: second-order backward difference (BDF2) with the velocity at the
   predicted geometry -- the PC2B idea of Bhagwat & Leishman (2001);
5. bound circulation: lifting-line panels, linear lift with a stall limit,
   Kutta-Joukowski; the near-wake/bound influence is solved as a small linear
   system, the tip vortices' influence is explicit;
6. the newest tip-vortex marker takes the blade's peak bound circulation
   (roll-up); the oldest free marker enters the frozen far-wake buffer.
"""
from __future__ import annotations

import copy
import math
from dataclasses import dataclass

import numpy as np

from ..configs import AircraftConfig
from ..inflow.base import rotor_suffix
from .biot_savart import segment_velocity, core_radius
from .far_wake import far_wake_segments, initial_far_wake, convect_far_wake
from .errors import WakeDivergedError
from .settings import WakeSettings, FlightCondition, WakeSettingsError
from .blades import advance_blades, solve_blades
from .initial_wake import initial_tip_vortices
from .kinematics import near_wake_points
from .reference import near_wake_points_reference, attached_segments_reference
from .threads import single_threaded_blas

__all__ = ["FreeVortexWake", "WakeDivergedError"]

_CONTROL_KEYS = ("theta0", "theta1s", "theta1c")
#: prescribed tip-path-plane (multiblade flap) inputs, rigid-flap mode only
_FLAP_KEYS = ("beta1s", "beta1c")


@dataclass
class _Rotor:
    """Geometry constants of one rotor in the computational frame."""
    name: str
    R: float
    omega: float
    d: int
    nb: int
    chord: float
    e: float
    twist: float
    a: float
    cd0: float
    stall: float
    nu2: float
    inertia: float
    hub: np.ndarray
    r_edge: np.ndarray
    r: np.ndarray
    dr: np.ndarray
    scale: float
    #: the real blade evaluated at the elements (aircraft.blade.BladeSections), or
    #: None for the classical blade (constant chord, linear twist, constant cd0)
    sections: object = None


class FreeVortexWake:
    """Lightweight free-vortex wake of the rotor(s) of an aircraft configuration.

    Parameters
    ----------
    config : AircraftConfig
        One rotor or a coaxial pair (same rotor speed).
    settings : WakeSettings
        Resolution and wake parameters.
    flight : FlightCondition
        Free-stream speed [m/s] and rotor angle of attack [rad] (shaft fixed).

    Notes
    -----
    The wake starts as a prescribed helix (Landgrebe's contraction and descent in
    hover, a momentum-inflow skewed helix in forward flight) and is marched in time.
    Use :meth:`trim` to reach a periodic, trimmed wake, then :meth:`run`.
    """

    #: March with the compiled/vectorised helpers (True) or the former numpy
    #: reference (False, :mod:`aircraft.wake.reference`; same numbers, slower).
    #: :meth:`_reference_march` sets it before ``__init__``, so that the starting
    #: wake is built the same way too.
    _compiled = True

    @classmethod
    def _reference_march(cls, config, settings=None, flight=None):
        """A wake that marches with the former numpy helpers (benchmark baseline, tests).

        Same arguments as the class; the numbers equal those of the compiled march.
        """
        wake = cls.__new__(cls)
        wake._compiled = False
        wake.__init__(config, settings, flight)
        return wake

    def __init__(self, config: AircraftConfig, settings: WakeSettings | None = None,
                 flight: FlightCondition | None = None):
        if not isinstance(config, AircraftConfig):
            raise TypeError("config must be an aircraft.configs.AircraftConfig")
        self.config = config
        self.settings = settings if settings is not None else WakeSettings()
        self.flight = flight if flight is not None else FlightCondition()
        omegas = {rc.omega for rc in config.rotors}
        if len(omegas) != 1:
            raise WakeSettingsError("all rotors must turn at the same speed (coaxial); got "
                                    f"{sorted(omegas)} rad/s")
        self.omega = omegas.pop()
        s = self.settings
        self.dt = s.azimuth_step / self.omega
        hub0 = np.array(config.rotors[0].hub_position, dtype=float)
        self._hub0_body = hub0
        self.rotors = []
        for rc in config.rotors:
            # half-cosine spacing: panels cluster at the tip where the load drops
            sgrid = np.linspace(0.0, 1.0, s.n_elements + 1)
            r_edge = rc.root_cutout + (1.0 - rc.root_cutout) * sgrid
            hub_body = np.array(rc.hub_position, dtype=float)
            hub = self._body_to_comp(hub_body, absolute=True)
            nu2 = rc.flap_frequency ** 2
            self.rotors.append(_Rotor(
                name=rc.name, R=rc.radius, omega=rc.omega, d=rc.direction, nb=rc.n_blades,
                chord=rc.chord, e=rc.hinge_offset, twist=rc.twist, a=rc.lift_slope,
                cd0=rc.cd0, stall=rc.stall_angle, nu2=nu2, inertia=rc.blade_flap_inertia,
                hub=hub, r_edge=r_edge, r=0.5 * (r_edge[1:] + r_edge[:-1]),
                dr=np.diff(r_edge), scale=rc.thrust_scale(config.rho)))
            if rc.blade is not None:
                rot = self.rotors[-1]
                rot.sections = rc.blade.sections(
                    rot.r, chord=rc.chord, twist=rc.twist, lift_slope=rc.lift_slope,
                    stall_angle=rc.stall_angle, omega=rc.omega, radius=rc.radius, r_edge=r_edge,
                    nu=s.kinematic_viscosity)
        self.rho = config.rho
        v = self.flight.speed
        self.v_inf = np.array([-v * math.cos(self.flight.alpha), 0.0, v * math.sin(self.flight.alpha)])
        #: near-wake segments per trailer (hover and forward flight differ, see WakeSettings)
        self.n_near = s.n_near(math.hypot(self.v_inf[0], self.v_inf[1]) / (self.omega * self.rotors[0].R))
        self.controls = {self._cname(k, r.name): 0.0 for r in self.rotors for k in _CONTROL_KEYS}
        self.beta_trim = {r.name: np.zeros(3) for r in self.rotors}  # beta0, beta1c, beta1s
        #: prescribed tip-path-plane perturbations [rad] and their rates [rad/s]
        #: (added to ``beta_trim`` when ``free_flapping`` is off; see :meth:`set_flap_inputs`)
        self.flap_inputs = {self._cname(k, r.name): 0.0 for r in self.rotors for k in _FLAP_KEYS}
        self.flap_input_rates = dict(self.flap_inputs)
        self.points = {}
        self._trim_state = None
        self.trim_result = None
        ct0 = config.trim_ct if len(config.trim_ct) == len(self.rotors) else (0.006,) * len(self.rotors)
        self._initialise(ct0)

    # ------------------------------------------------------------------ frames
    def _body_to_comp(self, p, absolute=False):
        p = np.asarray(p, dtype=float)
        q = p - self._hub0_body if not absolute else p - self._hub0_body
        return np.stack([q[..., 0], -q[..., 1], -q[..., 2]], axis=-1)

    @staticmethod
    def _cname(key, rotor):
        return f"{key}{rotor_suffix(rotor)}"

    @property
    def control_names(self):
        return [self._cname(k, r.name) for r in self.rotors for k in _CONTROL_KEYS]

    @property
    def flap_input_names(self):
        """Names of the prescribed tip-path-plane inputs (``beta1s_U``, ``beta1c_U``, ...)."""
        return [self._cname(k, r.name) for r in self.rotors for k in _FLAP_KEYS]

    def set_flap_inputs(self, values, rates):
        """Prescribe tip-path-plane perturbations for the next step.

        The blades then flap as ``beta_n = b0 + b1c cos psi_n + b1s sin psi_n`` with
        ``(b0, b1c, b1s) = beta_trim + inputs`` and the exact rate

        ``d beta_n / dt = db1c/dt cos psi_n + db1s/dt sin psi_n + Omega (b1s cos psi_n - b1c sin psi_n)``,

        so the multiblade flap rates ``beta1s_dot``/``beta1c_dot``
        of :meth:`current_outputs` equal the prescribed ``rates``.  This is the
        flap-rate excitation of Sec. 6.3 (Eq. 4.11) that separates lambda/C from
        lambda/beta_dot; it needs ``settings.free_flapping = False``.

        Parameters
        ----------
        values : dict
            ``{name: perturbation}`` [rad] for names in :attr:`flap_input_names`.
        rates : dict
            ``{name: time derivative}`` [rad/s], same names.
        """
        unknown = (set(values) | set(rates)) - set(self.flap_input_names)
        if unknown:
            raise ValueError(f"unknown flap input names {sorted(unknown)}; have {self.flap_input_names}")
        if self.settings.free_flapping:
            raise WakeSettingsError("prescribed tip-path-plane inputs need free_flapping=False "
                                    "(free blades flap with their own dynamics)")
        for n, v in values.items():
            self.flap_inputs[n] = float(v)
        for n, v in rates.items():
            self.flap_input_rates[n] = float(v)

    # ------------------------------------------------------------- kinematics
    def _blade_frames(self, rot, psi, beta):
        """Unit vectors of each blade: radial e_r, tangential e_t (direction of
        motion), flapped span direction s, normal n; shapes (Nb, 3)."""
        z = np.array([0.0, 0.0, 1.0])
        er = np.stack([-np.cos(psi), -rot.d * np.sin(psi), np.zeros_like(psi)], axis=1)
        et = np.stack([np.sin(psi), -rot.d * np.cos(psi), np.zeros_like(psi)], axis=1)
        cb, sb = np.cos(beta)[:, None], np.sin(beta)[:, None]
        span = cb * er + sb * z
        normal = cb * z - sb * er
        return er, et, span, normal

    def _blade_points(self, rot, psi, beta, rr):
        """Points at radius ``rr`` (on R) of every blade, shape (Nb, len(rr), 3)."""
        er, _, span, _ = self._blade_frames(rot, psi, beta)
        return (rot.hub[None, None, :] + rot.R * rot.e * er[:, None, :]
                + rot.R * (rr[None, :, None] - rot.e) * span[:, None, :])

    def _psi_blades(self, rot, psi):
        return psi + 2.0 * np.pi * np.arange(rot.nb) / rot.nb

    def _near_wake_points(self, ir, psi, beta):
        """Rigid near-wake trailer points, shape (Nb, Ne+1, n_near+1, 3), age 0 first.

        The march asks for the same near wake several times per step (the first
        markers, the corrector's velocities, the blade solve); the last result per
        rotor is kept with the state it depends on and returned while that state
        is unchanged (do not modify the returned array).
        """
        if not self._compiled:
            return near_wake_points_reference(self, ir, psi, beta)
        rot = self.rotors[ir]
        ct = self._last[rot.name]["CT"] if self._last is not None else self._ct0[ir]
        key = (float(psi), beta.tobytes(), float(self._lam0[ir]), float(ct))
        hit = self._nw_cache.get(ir)
        if hit is not None and hit[0] == key:
            return hit[1]
        s = self.settings
        ages = np.arange(self.n_near + 1) * s.azimuth_step
        # the near wake drifts with the free stream and half the rotor's mean
        # induced velocity (the tip vortex's initial descent is about that)
        drift = self.v_inf - np.array([0.0, 0.0, 0.5 * self._lam0[ir] * self.omega * rot.R])
        pts = near_wake_points(rot.hub, rot.R, rot.e, rot.d, rot.r_edge,
                               self._psi_blades(rot, psi), beta, ages,
                               self._near_wake_contraction(ir, ages), drift, self.omega)
        self._nw_cache[ir] = (key, pts)
        return pts

    def _near_wake_contraction(self, ir, ages):
        """Radial scale of the rigid near wake versus age [-].

        1 (no contraction) unless ``settings.near_wake_contraction``: then
        Landgrebe's hover law r = 0.78 + 0.22 exp(-(0.145 + 27 C_T) zeta)
        (Leishman, Principles, Sec. 10.7), blended out with advance ratio (none
        above mu = 0.1, where the wake is swept back before it can contract).
        """
        if not self.settings.near_wake_contraction:
            return np.ones_like(ages)
        rot = self.rotors[ir]
        mu = math.hypot(self.v_inf[0], self.v_inf[1]) / (self.omega * rot.R)
        weight = max(0.0, 1.0 - mu / 0.1)
        ct = max(self._last[rot.name]["CT"] if self._last is not None else self._ct0[ir], 0.0)
        landgrebe = 0.78 + 0.22 * np.exp(-(0.145 + 27.0 * ct) * ages)
        return 1.0 - weight * (1.0 - landgrebe)

    # ---------------------------------------------------------- initial wake
    def _initialise(self, cts):
        s = self.settings
        nk = 1 + s.n_free + s.n_buffer
        self.t = 0.0
        self.psi = 0.0
        self.step_count = 0
        self._lam0 = np.array([s.initial_wake_kappa * math.sqrt(ct / 2.0) for ct in cts])
        self._ct0 = list(cts)
        self.X, self.Xold, self.Vold, self.Vbuf, self.G_tip, self.G_shed = [], [], [], [], [], []
        self.gamma, self.beta, self.beta_dot = [], [], []
        ages = self.n_near * s.azimuth_step + np.arange(nk) * s.azimuth_step
        self._ages = ages
        mu = np.hypot(self.v_inf[0], self.v_inf[1]) / (self.omega * self.rotors[0].R)
        for ir, rot in enumerate(self.rotors):
            ct = cts[ir]
            X = initial_tip_vortices(self, ir, ct, ages, mu)
            if s.initial_perturbation > 0:
                # the reproduction check's second data set: a start differing at round-off level
                rng = np.random.default_rng(ir)
                X = X + s.initial_perturbation * rot.R * rng.standard_normal(X.shape)
            self.X.append(X)
            self.Xold.append(X.copy())
            self.Vold.append(np.zeros((rot.nb, s.n_free + 1, 3)))
            self.Vbuf.append(np.zeros((rot.nb, nk, 3)))
            g0 = 2.0 * math.pi * ct * self.omega * rot.R ** 2 / rot.nb
            self.G_tip.append(np.full((rot.nb, nk), 1.2 * g0))
            self.G_shed.append(np.full((rot.nb, self.n_near + 1), 1.2 * g0))
            self.gamma.append(np.full((rot.nb, s.n_elements), g0))
            self.beta.append(np.zeros(rot.nb))
            self.beta_dot.append(np.zeros(rot.nb))
        self.far_points, self.far_gamma, self.far_phase, self.far_released = [], [], [], []
        if s.far_wake_revolutions > 0 and s.far_wake_convected:
            for ir in range(len(self.rotors)):
                pts, g = initial_far_wake(self, ir, self.X[ir])
                self.far_points.append(pts)
                self.far_gamma.append(g)
                self.far_phase.append(0)
                self.far_released.append(0)
        self._first_step = True
        self._last = None
        self._nw_cache = {}        # rotor -> (state key, near-wake points)
        self._att_layout = None    # (core radii, gmap) of the attached segments
        self._tip_rc = {}          # rotor -> core radii of its tip-vortex segments
        self._vbuf_mean = None
        self._solve_blades()

    # --------------------------------------------------------------- sources
    def _tip_sources(self, X=None):
        """Tip-vortex segments of all rotors: (a, b, gamma, rc)."""
        s = self.settings
        X = self.X if X is None else X
        A, B, G, RC = [], [], [], []
        for ir, rot in enumerate(self.rotors):
            A.append(X[ir][:, :-1, :].reshape(-1, 3))
            B.append(X[ir][:, 1:, :].reshape(-1, 3))
            G.append(rot.d * 0.5 * (self.G_tip[ir][:, :-1] + self.G_tip[ir][:, 1:]).ravel())
            if not self._compiled or ir not in self._tip_rc:
                # the core growth depends on the wake age only: computed once
                mid = 0.5 * (self._ages[:-1] + self._ages[1:])
                rc = core_radius(mid, self.omega, s.core_radius * rot.chord, s.core_delta,
                                 s.kinematic_viscosity)
                self._tip_rc[ir] = (rc, np.tile(rc, rot.nb))
            rc, rc_tiled = self._tip_rc[ir]
            RC.append(rc_tiled)
            if s.far_wake_revolutions > 0:
                fa, fb, fg, frc = far_wake_segments(self, ir, X[ir], rc[-1])
                A.append(fa)
                B.append(fb)
                G.append(fg)
                RC.append(frc)
        return np.concatenate(A), np.concatenate(B), np.concatenate(G), np.concatenate(RC)

    def _attached_segments(self):
        """Bound and near-wake segments of all blades with the map to panel circulation.

        Returns (a, b, rc, gmap) with ``gmap`` (S, P): segment strength = gmap @ gamma,
        gamma stacked over rotors, blades, panels (P = sum Nb Ne). Per blade: its
        Ne bound segments (root to tip), then for each panel edge its n_near
        trailer segments (younger to older). ``gmap`` and the core radii depend
        on the layout only: built once by the reference, then reused.
        """
        if not self._compiled:
            return attached_segments_reference(self)
        if self._att_layout is None:
            _, _, rc, gmap = attached_segments_reference(self)
            self._att_layout = (rc, gmap)
        rc, gmap = self._att_layout
        A, B = [], []
        for ir, rot in enumerate(self.rotors):
            nw = self._near_wake_points(ir, self.psi, self.beta[ir])
            nb = rot.nb
            A.append(np.concatenate([nw[:, :-1, 0, :], nw[:, :, :-1, :].reshape(nb, -1, 3)],
                                    axis=1).reshape(-1, 3))
            B.append(np.concatenate([nw[:, 1:, 0, :], nw[:, :, 1:, :].reshape(nb, -1, 3)],
                                    axis=1).reshape(-1, 3))
        return np.concatenate(A), np.concatenate(B), rc, gmap

    def _all_sources(self, X=None):
        a1, b1, g1, rc1 = self._tip_sources(X)
        a2, b2, rc2, gmap = self._attached_segments()
        g2 = gmap @ np.concatenate([g.ravel() for g in self.gamma])
        return (np.concatenate([a1, a2]), np.concatenate([b1, b2]),
                np.concatenate([g1, g2]), np.concatenate([rc1, rc2]))

    # ----------------------------------------------------------- blade solve
    def _controls_at(self, rot, psib):
        c = self.controls
        suf = rotor_suffix(rot.name)
        return (c[f"theta0{suf}"] + c[f"theta1s{suf}"] * np.sin(psib)
                + c[f"theta1c{suf}"] * np.cos(psib))

    def _solve_blades(self):
        """Bound circulation, loads and inflow of every blade at the current step
        (see :func:`aircraft.wake.blades.solve_blades`)."""
        return solve_blades(self)

    # ------------------------------------------------------------- marching
    def _free_velocity(self, X, n_eval):
        """Velocity [m/s] at the first ``n_eval`` markers of every blade (all rotors)."""
        a, b, g, rc = self._all_sources(X)
        tg = np.concatenate([X[ir][:, :n_eval, :].reshape(-1, 3) for ir in range(len(self.rotors))])
        v = segment_velocity(tg, a, b, g, rc, self.settings.kernel_precision,
                             chained=self._compiled) + self.v_inf
        out, p0 = [], 0
        for rot in self.rotors:
            n = rot.nb * n_eval
            out.append(v[p0:p0 + n].reshape(rot.nb, n_eval, 3))
            p0 += n
        return out

    def _buffer_velocity(self, V):
        """Convection velocity [m/s] of the frozen buffers (and the convected far wake).

        Markers past the free wake move rigidly with the free stream plus the mean
        axial velocity of the last free revolution (no self-induced roll-up of the
        truncated end, no hard cut). One velocity for all rotors: a coaxial's two
        tip-vortex systems end in one slipstream. Each rotor's own mean (the
        earlier model) differed by 1.8x in trimmed coaxial hover (15 and 27 m/s at
        2 free revolutions: whichever system is inside the other at the end of the
        free wake descends at nearly the full slipstream velocity), so the two
        buffers drifted apart and the inflow oscillated with the leapfrogging of
        the two systems through the wake's end.

        Parameters
        ----------
        V : list of ndarray
            Velocities at the free markers of every rotor, each (Nb, n, 3) [m/s].
        """
        s = self.settings
        nf, nrev = s.n_free, s.steps_per_rev
        k0 = max(nf + 1 - nrev, 0)
        v_ax = np.mean([(v[:, k0:nf + 1, 2] - self.v_inf[2]).mean() for v in V])
        return self.v_inf + np.array([0.0, 0.0, min(v_ax, 0.0)])

    def _advance_blades(self):
        """Advance azimuth and flapping by one step (:func:`aircraft.wake.blades.advance_blades`)."""
        advance_blades(self)

    def _new_first_markers(self):
        """Position of the k = 0 marker (end of each blade's tip trailer)."""
        out = []
        for ir, rot in enumerate(self.rotors):
            nw = self._near_wake_points(ir, self.psi, self.beta[ir])
            out.append(nw[:, -1, -1, :])
        return out

    def step(self):
        """Advance the wake and the blades by one azimuth step."""
        s = self.settings
        nf = s.n_free
        dt = self.dt
        V = self._free_velocity(self.X, nf + 1)
        v_now = self._buffer_velocity(V)
        tau = s.buffer_velocity_revolutions * 2.0 * math.pi / self.omega
        if self._vbuf_mean is None or tau <= 0.0:
            self._vbuf_mean = v_now
        else:
            # first-order low pass: the buffer follows the slipstream's slow changes
            # (quasi-steady inflow), not the end of the free wake's fluctuation
            self._vbuf_mean = self._vbuf_mean + min(dt / tau, 1.0) * (v_now - self._vbuf_mean)
        vbuf = self._vbuf_mean
        Xp, vbufs = [], []
        for ir in range(len(self.rotors)):
            X, Vo = self.X[ir], self.Vold[ir]
            P = np.empty_like(X)
            if self._first_step:
                P[:, 1:nf + 1] = X[:, :nf] + dt * V[ir][:, :nf]
            else:
                P[:, 1] = X[:, 0] + dt * V[ir][:, 0]
                P[:, 2:nf + 1] = X[:, 1:nf] + dt * (1.5 * V[ir][:, 1:nf] - 0.5 * Vo[:, :nf - 1])
            P[:, nf + 1:] = X[:, nf:-1] + dt * vbuf
            Xp.append(P)
            vbufs.append(vbuf)
        self._advance_blades()
        first = self._new_first_markers()
        for ir in range(len(self.rotors)):
            Xp[ir][:, 0] = first[ir]
        Vc = self._free_velocity(Xp, nf + 1)
        for ir, rot in enumerate(self.rotors):
            X, Xo = self.X[ir], self.Xold[ir]
            Xn = Xp[ir].copy()
            Xn[:, 1] = X[:, 0] + 0.5 * dt * (V[ir][:, 0] + Vc[ir][:, 1])
            if self._first_step:
                Xn[:, 2:nf + 1] = X[:, 1:nf] + 0.5 * dt * (V[ir][:, 1:nf] + Vc[ir][:, 2:nf + 1])
            else:
                Xn[:, 2:nf + 1] = ((4.0 * X[:, 1:nf] - Xo[:, :nf - 1]) / 3.0
                                   + (2.0 / 3.0) * dt * Vc[ir][:, 2:nf + 1])
            if not np.all(np.isfinite(Xn)):
                raise WakeDivergedError(f"wake geometry became non-finite at t = {self.t:.3f} s")
            self.Xold[ir] = X
            self.X[ir] = Xn
            self.Vold[ir] = V[ir]
            G = self.G_tip[ir]
            if self.far_points:
                # the marker leaving the buffer (convected like it, one step older
                # than the new end, so the junction never has zero length) and its
                # circulation feed the far wake
                convect_far_wake(self, ir, vbufs[ir], X[:, -1] + dt * vbufs[ir], G[:, -1])
            G[:, 1:] = G[:, :-1].copy()
        self._first_step = False
        out = self._solve_blades()
        key = "gamma_max" if self.settings.tip_vortex_strength == "peak" else "gamma_eq"
        for ir, rot in enumerate(self.rotors):
            # The newest free marker sits at the end of the rigid near wake, n_near
            # steps of age behind the blade: it carries the circulation the blade
            # shed n_near steps ago, not the current one (which would rotate the
            # free wake's cyclic circulation pattern by the near-wake extent in
            # azimuth and advance its collective response by as much in time)
            hist = self.G_shed[ir]
            hist[:, 1:] = hist[:, :-1].copy()
            hist[:, 0] = np.maximum(out[rot.name][key], 0.0)
            self.G_tip[ir][:, 0] = hist[:, -1]
        self.step_count += 1
        return out

    # ------------------------------------------------------------- outputs
    def induced_velocity(self, points):
        """Induced velocity of the whole wake at points given in body axes.

        Parameters
        ----------
        points : array_like, shape (M, 3)
            Positions relative to the c.g. in body axes (x fwd, y stbd, z down) [m].

        Returns
        -------
        ndarray, shape (M, 3)
            Induced velocity (free stream excluded) in body axes [m/s].
        """
        pts = np.atleast_2d(np.asarray(points, dtype=float))
        if pts.shape[1] != 3 or not np.all(np.isfinite(pts)):
            raise ValueError("points must be finite with shape (M, 3) [m]")
        a, b, g, rc = self._all_sources()
        v = segment_velocity(self._body_to_comp(pts), a, b, g, rc, self.settings.kernel_precision)
        return np.stack([v[:, 0], -v[:, 1], -v[:, 2]], axis=1)

    def tip_vortex_radius(self):
        """Mean radial position r/R of the tip-vortex markers versus wake age.

        Returns
        -------
        ages : ndarray [rad]; radius : ndarray, shape (n_rotors, n_ages) [-]
        """
        rad = []
        for ir, rot in enumerate(self.rotors):
            d = self.X[ir] - rot.hub
            rad.append(np.hypot(d[..., 0], d[..., 1]).mean(axis=0) / rot.R)
        return self._ages.copy(), np.array(rad)

    def tip_vortex_height(self):
        """Mean axial position z/R (up positive, from each hub) versus wake age."""
        return self._ages.copy(), np.array([(self.X[ir][..., 2] - rot.hub[2]).mean(axis=0) / rot.R
                                            for ir, rot in enumerate(self.rotors)])

    def current_outputs(self):
        """Dict of the latest rotor outputs keyed by canonical signal name."""
        row = {}
        for rot in self.rotors:
            suf = rotor_suffix(rot.name)
            o = self._last[rot.name]
            for key in ("CT", "CL", "CM", "CQ", "lam0", "lam1s", "lam1c",
                        "beta1s_dot", "beta1c_dot", "beta0", "beta1s", "beta1c"):
                row[f"{key}{suf}"] = float(o[key])
        return row

    def march(self, n_steps, callback=None):
        """March ``n_steps`` with the current controls; mean outputs over them.

        Parameters
        ----------
        n_steps : int
            Number of wake time steps (>= 1) of ``dt`` [s] each.
        callback : callable, optional
            Called with the wake after every step.

        Returns
        -------
        dict
            Output name -> mean over the steps.
        """
        if isinstance(n_steps, bool) or not float(n_steps).is_integer() or int(n_steps) < 1:
            raise ValueError(f"march: n_steps must be an integer >= 1 (wake time steps), got {n_steps!r}")
        acc = None
        with single_threaded_blas():
            for _ in range(int(n_steps)):
                self.step()
                row = self.current_outputs()
                if callback is not None:
                    callback(self)
                acc = dict(row) if acc is None else {k: acc[k] + row[k] for k in acc}
        return {k: v / int(n_steps) for k, v in acc.items()}

    # ----------------------------------------------------------- snapshots
    def snapshot(self):
        """A deep copy of the marching state (wake, blades, controls, time)."""
        keys = ("t", "psi", "step_count", "X", "Xold", "Vold", "Vbuf", "G_tip", "G_shed", "gamma",
                "beta", "beta_dot", "_first_step", "_last", "_lam0", "controls", "beta_trim",
                "flap_inputs", "flap_input_rates", "far_points", "far_gamma", "far_phase",
                "far_released",
                "_vbuf_mean")
        return {k: copy.deepcopy(getattr(self, k)) for k in keys}

    def restore(self, snap):
        """Return to a state saved by :meth:`snapshot`."""
        for k, v in snap.items():
            setattr(self, k, copy.deepcopy(v))

    # ------------------------------------------------------------ trim/run
    def trim(self, *args, **kwargs):
        """Trim the wake; see :func:`aircraft.wake.trim.trim_wake`."""
        from .trim import trim_wake
        return trim_wake(self, *args, **kwargs)

    def run(self, controls=None, duration=1.0, *, points=None, about_trim=True,
            from_trim=True):
        """March with prescribed swashplate time histories; see :func:`aircraft.wake.trim.run_wake`."""
        from .trim import run_wake
        return run_wake(self, controls, duration, points=points, about_trim=about_trim,
                        from_trim=from_trim)
