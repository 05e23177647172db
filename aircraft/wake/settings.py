"""Settings of the free-vortex wake (a dataclass, SI units and radians)."""
from __future__ import annotations

from dataclasses import dataclass, asdict, field
import math

from .._validation import integer as _integer, real as _real
from ..provenance import HASHED_IF_SET

__all__ = ["WakeSettings", "FlightCondition", "WakeSettingsError"]


class WakeSettingsError(ValueError):
    """Raised for inconsistent wake settings or flight conditions."""


@dataclass(frozen=True)
class WakeSettings:
    """Resolution and physical parameters of :class:`~aircraft.wake.FreeVortexWake`.

    Parameters
    ----------
    azimuth_step : float
        Time step as a rotor azimuth increment d psi = d zeta [rad] (default 10 deg).
    wake_revolutions : float
        Length of the free tip vortex, in rotor revolutions of wake age [-].
    buffer_revolutions : float
        Length of the frozen far-wake buffer behind the free wake [rev].  Its markers
        keep the convection velocity they had when they left the free wake (as
        OpenFAST/OLAF does), so the wake end neither rolls up nor is cut abruptly.
    near_wake_extent : float
        Azimuthal extent of the rigid trailed near wake in hover [rad] (default
        60 deg); the free tip vortex starts at its end. In hover the young tip
        vortex lingers within a chord or two of the blade's bound and trailed
        vorticity; marched freely from 30 deg it made the trimmed inflow depend
        on the resolution (kappa 1.05-1.30), the lam0/C_T gain 0.3-1.5x
        1/(4 lambda_h) and trims fail at 10 deg steps. Rigid to 60 deg, kappa is
        1.14-1.16 and the gain 1.03-1.28x at 10-15 deg steps and 2-4 revolutions
        of wake (measured when the rigid near wake was introduced).
    near_wake_extent_forward : float
        The same in forward flight (advance ratio >= 0.05) [rad] (default 30 deg):
        there the young vortex is swept clear of the blades, and the 60 deg near
        wake put the inflow 26-33 % above Glauert's momentum value at mu = 0.3 and
        0.54, against 0-15 % with 30 deg.
    near_wake_contraction : bool
        Contract the rigid near wake by Landgrebe's law. Without it the tip
        vortex leaves the near wake at r = R and the hover wake contracts only to
        ~0.86 R; with it to ~0.78 R as measured by Landgrebe, but the blade-sum
        inflow drops to kappa ~0.92-0.99 (the contracted tip vortex induces
        upwash over the blade tips) with the gain still 0.87-1.06x. Off by default
        because the inflow, not the geometry, is what the identification uses.
    n_elements : int
        Blade elements (lifting-line panels) per blade.
    core_radius : float
        Initial tip-vortex core radius as a fraction of the blade chord [-].
    near_wake_core : float
        Core radius of bound and near-wake trailed filaments, fraction of chord [-].
    core_delta : float
        Squire's eddy-viscosity coefficient delta [-] in the core growth law.
    kinematic_viscosity : float
        nu [m^2/s].
    free_flapping : bool
        If True integrate each blade's flap equation with the wake; if False hold
        the flapping at the prescribed (trim) harmonics.
    initial_wake_kappa : float
        Induced-power factor used for the prescribed (Landgrebe) initial wake.
    tip_vortex_strength : {"thrust_equivalent", "peak"}
        Circulation the rolled-up tip vortex takes from the blade.  The inboard
        trailed sheet is not followed beyond the near wake, so the default gives the
        tip vortex the thrust-weighted blade circulation ``int G r dr / int r dr``
        (the uniform-loading circulation with the same thrust), which keeps the far
        wake's momentum flux consistent with the rotor thrust; ``"peak"`` uses the
        peak bound circulation (classical roll-up of everything outboard of it),
        which over-predicts the inflow when the inboard sheet is omitted.
    kernel_precision : {"single", "double"}
        Arithmetic of the Biot-Savart pair loop (see
        :func:`~aircraft.wake.segment_velocity`). Single precision is about 4x
        faster with ~1e-6 relative round-off, orders of magnitude below the
        model's own error (trimmed hover inflow agrees with double to < 0.5 %,
        tests); use "double" for kernel-level verification.
    far_wake_revolutions : float
        Length of the prescribed helical continuation of every tip vortex past
        the buffer [rev] (0: the wake ends at the buffer). It keeps the end of
        the free wake from rolling up and makes the trimmed inflow independent
        of ``wake_revolutions`` (tests); a source only, no markers.
    far_wake_step : float
        Azimuthal chord of the far-wake helix segments [rad] (default 30 deg).
    far_wake_convected : bool
        True (default): the far wake is the buffer continued at the far-wake chord
        -- points released from the buffer's end keep the circulation they left
        with and move with the buffer's velocity, so it carries the wake's
        history; past the points released so far (the first
        ``far_wake_revolutions`` of marching) it is the prescribed helix of the
        current wake end. False: the prescribed helix everywhere, rebuilt every
        step (the earlier model; with it the trimmed coaxial lambda0 fluctuated
        by 0.8 % instead of 0.1 %, test resolution). See
        :mod:`aircraft.wake.far_wake`.
    buffer_velocity_revolutions : float
        Time constant [rev] of the low-pass filter on the buffer's (and convected
        far wake's) convection velocity, the mean axial velocity of the last free
        revolution (0: the instantaneous value, the earlier model). The
        instantaneous value closed a loop through the free wake: held constant,
        the trimmed coaxial hover lambda0 fluctuation (relative rms of revolution
        averages) fell from 1.2-1.7 % to 0.15-0.2 % and its spectral peak (10
        rad/s at 2 free revolutions, 6 rad/s at 4) went; with this filter, one
        velocity for both rotors and the convected far wake it is 0.1-0.15 %.
    initial_perturbation : float
        Size of a seeded random displacement of every starting tip-vortex marker,
        as a fraction of the rotor radius [-] (0, the default: none). A wake
        marched from a starting geometry that differs at the level of the
        kernel's single-precision rounding (about 1e-7) is the second data set of
        an identification's reproduction check: what another machine would have
        computed. At most 1e-3 (a perturbation, not another wake).
    """

    azimuth_step: float = math.radians(10.0)
    wake_revolutions: float = 4.0
    buffer_revolutions: float = 1.0
    near_wake_extent: float = math.radians(60.0)
    near_wake_extent_forward: float = math.radians(30.0)
    near_wake_contraction: bool = False
    n_elements: int = 10
    core_radius: float = 0.10
    near_wake_core: float = 0.25
    core_delta: float = 1000.0
    kinematic_viscosity: float = 1.5e-5
    free_flapping: bool = False
    initial_wake_kappa: float = 1.15
    tip_vortex_strength: str = "thrust_equivalent"
    kernel_precision: str = "single"
    far_wake_revolutions: float = 10.0
    far_wake_step: float = math.radians(30.0)
    far_wake_convected: bool = True
    buffer_velocity_revolutions: float = 2.0
    initial_perturbation: float = field(default=0.0, metadata=HASHED_IF_SET)

    def __post_init__(self):
        e = WakeSettingsError
        for name in ("azimuth_step", "wake_revolutions", "near_wake_extent",
                     "near_wake_extent_forward", "core_radius", "near_wake_core",
                     "kinematic_viscosity", "initial_wake_kappa", "far_wake_step"):
            _real(e, f"WakeSettings.{name}", getattr(self, name), positive=True)
        for name in ("buffer_revolutions", "core_delta", "far_wake_revolutions"):
            _real(e, f"WakeSettings.{name}", getattr(self, name), nonnegative=True)
        for name in ("near_wake_contraction", "free_flapping"):
            if not isinstance(getattr(self, name), bool):
                raise e(f"WakeSettings.{name} must be True or False, got {getattr(self, name)!r}")
        _integer(e, "WakeSettings.n_elements", self.n_elements, minimum=2)
        # kappa is an induced-power factor: 1 is ideal, real rotors 1.05-1.3
        _real(e, "WakeSettings.initial_wake_kappa", self.initial_wake_kappa, lo=1.0, hi=3.0)
        # a wake of hundreds of revolutions is a typo, and would not fit in memory
        _real(e, "WakeSettings.wake_revolutions", self.wake_revolutions, hi=100.0)
        _real(e, "WakeSettings.buffer_revolutions", self.buffer_revolutions, hi=100.0)
        _real(e, "WakeSettings.far_wake_revolutions", self.far_wake_revolutions, hi=1000.0)
        for name in ("near_wake_extent", "near_wake_extent_forward"):
            _real(e, f"WakeSettings.{name}", getattr(self, name), hi=2 * math.pi)
        if not 0.0 < self.azimuth_step <= math.radians(30.0):
            raise WakeSettingsError(
                f"azimuth_step must be in (0, 30 deg] [rad], got {self.azimuth_step!r}")
        if abs(round(2 * math.pi / self.azimuth_step) * self.azimuth_step - 2 * math.pi) > 1e-9:
            raise WakeSettingsError("azimuth_step must divide 360 deg exactly")
        for name in ("near_wake_extent", "near_wake_extent_forward"):
            if getattr(self, name) < self.azimuth_step - 1e-12:
                raise WakeSettingsError(f"{name} must be at least one azimuth_step [rad]")
        if not self.wake_revolutions > 0 or self.buffer_revolutions < 0:
            raise WakeSettingsError("wake_revolutions must be > 0 and buffer_revolutions >= 0")
        if not (isinstance(self.n_elements, int) and self.n_elements >= 2):
            raise WakeSettingsError(f"n_elements must be an integer >= 2, got {self.n_elements!r}")
        for name in ("core_radius", "near_wake_core", "kinematic_viscosity"):
            if not getattr(self, name) > 0:
                raise WakeSettingsError(f"{name} must be positive, got {getattr(self, name)!r}")
        if self.tip_vortex_strength not in ("thrust_equivalent", "peak"):
            raise WakeSettingsError("tip_vortex_strength must be 'thrust_equivalent' or 'peak', "
                                    f"got {self.tip_vortex_strength!r}")
        if self.kernel_precision not in ("single", "double"):
            raise WakeSettingsError("kernel_precision must be 'single' or 'double', "
                                    f"got {self.kernel_precision!r}")
        if self.far_wake_revolutions < 0 or not 0 < self.far_wake_step <= math.pi / 2:
            raise WakeSettingsError("far_wake_revolutions must be >= 0 and far_wake_step in "
                                    "(0, 90 deg] [rad]")
        if not (self.buffer_velocity_revolutions >= 0 and math.isfinite(self.buffer_velocity_revolutions)):
            raise WakeSettingsError("buffer_velocity_revolutions must be a finite value >= 0 [rev]")
        if self.core_delta < 0:
            raise WakeSettingsError("core_delta must be >= 0")
        _real(e, "WakeSettings.initial_perturbation", self.initial_perturbation, lo=0.0, hi=1e-3)

    @property
    def steps_per_rev(self) -> int:
        return int(round(2 * math.pi / self.azimuth_step))

    def n_near(self, mu=0.0) -> int:
        """Near-wake segments per trailer at advance ratio ``mu``."""
        extent = self.near_wake_extent if mu < 0.05 else self.near_wake_extent_forward
        return max(1, int(round(extent / self.azimuth_step)))

    @property
    def n_free(self) -> int:
        """Free tip-vortex markers per blade (after the first, attached one)."""
        return max(2, int(round(self.wake_revolutions * self.steps_per_rev)))

    @property
    def n_buffer(self) -> int:
        return int(round(self.buffer_revolutions * self.steps_per_rev))

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass(frozen=True)
class FlightCondition:
    """Wind-tunnel flight condition (shaft fixed).

    Parameters
    ----------
    speed : float
        Free-stream speed [m/s] (0 for hover).
    alpha : float
        Rotor (shaft) angle of attack [rad]; positive tilts the disk back, so that
        the free stream has a component *up* through the disk (mu_z > 0).
    """

    speed: float = 0.0
    alpha: float = 0.0

    def __post_init__(self):
        _real(WakeSettingsError, "FlightCondition.speed", self.speed, nonnegative=True, unit="m/s")
        _real(WakeSettingsError, "FlightCondition.alpha", self.alpha, unit="rad")
        if abs(self.alpha) > math.radians(30.0):
            raise WakeSettingsError(f"FlightCondition.alpha must be within +-30 deg (+-0.5236 rad) "
                                    f"[rad], got {self.alpha!r}")

    def to_dict(self) -> dict:
        return asdict(self)
