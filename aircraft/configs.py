"""Rotorcraft configurations: the coaxial compound and the UH-60-like single rotor.

Every number the reference dissertation gives (Appendix B, Table B.1) is used as
given; every number it does not give is an *assumption*, collected in
:data:`ASSUMPTIONS` with its reason, so a user can see and change them in one place.

Units are SI (m, kg, s, rad) throughout. Non-dimensional rotor coefficients follow
the dissertation's nomenclature (C_T = T / (rho A (Omega R)^2), etc.).

Axes
----
Body axes: x forward, y starboard, z down, origin at the centre of gravity.
Rotor ``direction`` is +1 for a rotor turning counter-clockwise seen from above
(the usual US single rotor) and -1 for clockwise.  In a coaxial the upper rotor
is counter-clockwise, the lower clockwise.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
import math

from ._validation import integer as _integer, real as _real, vector as _vector
from .blade import BladeModel
from .provenance import HASHED_IF_SET

__all__ = [
    "ConfigError", "FT", "LB", "RHO_SEA_LEVEL", "GRAVITY",
    "RotorConfig", "PropellerConfig", "TailRotorConfig", "AircraftConfig",
    "coaxial_compound", "uh60_single_rotor", "ASSUMPTIONS",
]

FT = 0.3048            #: metres per foot
LB = 0.45359237        #: kilograms per pound (mass)
RHO_SEA_LEVEL = 1.225  #: ISA sea-level density, kg/m^3
GRAVITY = 9.80665      #: m/s^2


class ConfigError(ValueError):
    """A configuration field is NaN, infinite, complex, of the wrong type or out of range.

    The message names the field (``RotorConfig.twist``) and what is allowed.
    """


@dataclass(frozen=True)
class RotorConfig:
    """Geometry, blade and aerodynamic properties of one rotor.

    Parameters
    ----------
    name : str
        Label used as the signal suffix (``"U"``, ``"L"``, or ``""`` for a
        single rotor).
    radius : float
        Rotor radius R [m].
    omega : float
        Nominal rotor speed Omega [rad/s].
    n_blades : int
        Number of blades.
    chord : float
        Constant blade chord c [m].
    twist : float
        Total linear twist from rotation axis to tip [rad] (negative: washout).
    root_cutout : float
        Non-dimensional radius r/R where the lifting blade starts.
    lift_slope : float
        Section lift-curve slope a [1/rad].
    cd0 : float
        Section profile drag coefficient (constant).
    stall_angle : float
        Angle of attack [rad] above which the section lift is held constant.
    flap_frequency : float
        Non-dimensional rotating first flap frequency nu_beta [per rev].
    lag_frequency : float
        Non-dimensional first lag frequency [per rev] (documentation only).
    hinge_offset : float
        Flap hinge offset e/R (hingeless blades: equivalent hinge).
    blade_mass : float
        Mass of one blade [kg] (uniform distribution assumed).
    direction : int
        +1 counter-clockwise seen from above, -1 clockwise.
    hub_position : tuple of float
        Hub centre in body axes relative to the c.g. [m] (x fwd, y stbd, z down).
    shaft_tilt : float
        Forward shaft tilt [rad] (positive tilts the thrust forward; not yet used
        by the aircraft model, which assumes shafts normal to body x).
    flap_inertia : float or None
        Blade flap inertia about the hinge [kg m^2]; None: uniform blade of
        ``blade_mass`` (m L^2 / 3).
    blade : aircraft.blade.BladeModel or None
        Real blade: chord and twist against radius, section polar, tip loss.
        None (default): the constant ``chord``, linear ``twist``, ``lift_slope``
        and ``cd0`` above.  With a chord table, ``chord`` stays the equivalent
        (thrust-weighted) chord of the solidity and of the trim's first guesses.
    """

    name: str
    radius: float
    omega: float
    n_blades: int
    chord: float
    twist: float
    root_cutout: float
    lift_slope: float = 5.73
    cd0: float = 0.010
    stall_angle: float = math.radians(12.0)
    flap_frequency: float = 1.5
    lag_frequency: float = 1.3
    hinge_offset: float = 0.05
    blade_mass: float = 100.0
    direction: int = 1
    hub_position: tuple = (0.0, 0.0, -2.0)
    shaft_tilt: float = 0.0
    flap_inertia: float | None = None
    # added after the recipe hashes were fixed: hashed only when set (provenance.HASHED_IF_SET)
    blade: BladeModel | None = field(default=None, metadata=HASHED_IF_SET)

    def __post_init__(self):
        c = "RotorConfig."
        if self.blade is not None and not isinstance(self.blade, BladeModel):
            raise ConfigError(f"{c}blade must be an aircraft.blade.BladeModel or None, got {self.blade!r}")
        if not isinstance(self.name, str):
            raise ConfigError(f"{c}name must be a string (\"U\", \"L\" or \"\"), got {self.name!r}")
        if self.flap_inertia is not None:
            _real(ConfigError, c + "flap_inertia", self.flap_inertia, positive=True, unit="kg m^2")
        for attr, unit in (("radius", "m"), ("omega", "rad/s"), ("chord", "m"),
                           ("lift_slope", "1/rad"), ("blade_mass", "kg")):
            _real(ConfigError, c + attr, getattr(self, attr), positive=True, unit=unit)
        _integer(ConfigError, c + "n_blades", self.n_blades, minimum=2)
        if not isinstance(self.n_blades, int):
            raise ConfigError(f"{c}n_blades must be a Python int >= 2, got {self.n_blades!r}")
        # a linear twist beyond +-45 deg from root to tip is no rotor blade
        _real(ConfigError, c + "twist", self.twist, lo=-math.pi / 4, hi=math.pi / 4, unit="rad")
        _real(ConfigError, c + "cd0", self.cd0, nonnegative=True, hi=1.0)
        _real(ConfigError, c + "stall_angle", self.stall_angle, positive=True, hi=math.pi / 2, unit="rad")
        _real(ConfigError, c + "lag_frequency", self.lag_frequency, positive=True, unit="per rev")
        _real(ConfigError, c + "shaft_tilt", self.shaft_tilt, lo=-math.pi / 4, hi=math.pi / 4, unit="rad")
        _vector(ConfigError, c + "hub_position", self.hub_position, 3, unit="m")
        _real(ConfigError, c + "root_cutout", self.root_cutout, lo=0.0)
        if not self.root_cutout < 1.0:
            raise ConfigError(f"{c}root_cutout must be in [0, 1), got {self.root_cutout!r}")
        _real(ConfigError, c + "hinge_offset", self.hinge_offset)
        if not 0.0 <= self.hinge_offset < self.root_cutout + 1e-12 or self.hinge_offset >= 1.0:
            raise ConfigError(f"{c}hinge_offset must lie in [0, root_cutout = {self.root_cutout:g}], "
                              f"got {self.hinge_offset!r}")
        if isinstance(self.direction, bool) or self.direction not in (1, -1):
            raise ConfigError(f"{c}direction must be +1 or -1, got {self.direction!r}")
        _real(ConfigError, c + "flap_frequency", self.flap_frequency, lo=1.0, hi=10.0, unit="per rev")

    # --- derived quantities -------------------------------------------------
    @property
    def solidity(self) -> float:
        """Thrust-weighted solidity sigma = N_b c / (pi R)."""
        return self.n_blades * self.chord / (math.pi * self.radius)

    @property
    def disk_area(self) -> float:
        """Disk area pi R^2 [m^2]."""
        return math.pi * self.radius ** 2

    @property
    def tip_speed(self) -> float:
        """Omega R [m/s]."""
        return self.omega * self.radius

    @property
    def blade_flap_inertia(self) -> float:
        """Flap inertia of one blade about the (equivalent) hinge [kg m^2]."""
        if self.flap_inertia is not None:
            return self.flap_inertia
        length = self.radius * (1.0 - self.hinge_offset)
        return self.blade_mass * length ** 2 / 3.0

    def lock_number(self, rho: float = RHO_SEA_LEVEL) -> float:
        """Lock number gamma = rho a c R^4 / I_b [-]."""
        return rho * self.lift_slope * self.chord * self.radius ** 4 / self.blade_flap_inertia

    def flap_phase_lag(self, rho: float = RHO_SEA_LEVEL) -> float:
        """Hover phase lag of the cyclic flap response behind the cyclic pitch [rad].

        The classical closed form of a centre-spring blade (Johnson, *Helicopter
        Theory*, ch. 9; Padfield, *Helicopter Flight Dynamics*, §3.2):
        ``tan(lag) = (gamma / 8) / (nu_beta^2 - 1)``, 90 deg for a blade hinged at the
        shaft. ``pi / 2 - lag`` is then the control phase angle of an aircraft that
        follows this rotor's flap response (:attr:`AircraftConfig.control_phase`).
        """
        return math.atan2(self.lock_number(rho) / 8.0, self.flap_frequency ** 2 - 1.0)

    def thrust_scale(self, rho: float = RHO_SEA_LEVEL) -> float:
        """rho A (Omega R)^2 [N]: divides a thrust to give C_T."""
        return rho * self.disk_area * self.tip_speed ** 2

    def with_omega(self, omega: float) -> "RotorConfig":
        """Copy with another rotor speed (e.g. the cruise Omega)."""
        return replace(self, omega=omega)


@dataclass(frozen=True)
class PropellerConfig:
    """Pusher propeller modelled by momentum theory (Bailey-type rotor).

    radius [m], omega [rad/s], position [m] in body axes, solidity, lift_slope
    [1/rad], cd0, twist [rad].  Thrust acts along body +x only (Appendix B.2).
    """

    radius: float = 6.6 * FT
    omega: float = 136.0
    position: tuple = (-9.0, 0.0, 0.0)
    solidity: float = 0.12
    lift_slope: float = 5.73
    cd0: float = 0.010
    twist: float = math.radians(-30.0)

    def __post_init__(self):
        c = "PropellerConfig."
        for attr, unit in (("radius", "m"), ("omega", "rad/s"), ("lift_slope", "1/rad")):
            _real(ConfigError, c + attr, getattr(self, attr), positive=True, unit=unit)
        _real(ConfigError, c + "solidity", self.solidity, positive=True, hi=1.0)
        _real(ConfigError, c + "cd0", self.cd0, nonnegative=True, hi=1.0)
        _real(ConfigError, c + "twist", self.twist, lo=-math.pi / 2, hi=math.pi / 2, unit="rad")
        _vector(ConfigError, c + "position", self.position, 3, unit="m")


@dataclass(frozen=True)
class TailRotorConfig:
    """Tail rotor modelled by blade-element momentum theory with uniform inflow.

    Its thrust acts along body ``thrust_sign * y`` at ``position``; the rotor's
    own shaft torque is not fed back to the body (it is small, and about the
    pitch axis); its power is reported.

    Parameters
    ----------
    radius : float
        Radius [m].
    omega : float
        Rotor speed [rad/s].
    solidity : float
        Thrust-weighted solidity [-].
    lift_slope : float
        Section lift-curve slope [1/rad].
    cd0 : float
        Section profile drag coefficient [-].
    twist : float
        Linear twist from rotation axis to tip [rad].
    position : tuple of float
        Hub in body axes from the c.g. [m].
    thrust_sign : int
        +1: a positive collective thrusts towards body +y (starboard), -1 to port.
    """

    radius: float = 5.5 * FT
    omega: float = 124.62
    solidity: float = 0.1875
    lift_slope: float = 5.73
    cd0: float = 0.010
    twist: float = math.radians(-18.0)
    position: tuple = (-9.5, 0.0, -1.9)
    thrust_sign: int = 1

    def __post_init__(self):
        c = "TailRotorConfig."
        for attr, unit in (("radius", "m"), ("omega", "rad/s"), ("lift_slope", "1/rad")):
            _real(ConfigError, c + attr, getattr(self, attr), positive=True, unit=unit)
        _real(ConfigError, c + "solidity", self.solidity, positive=True, hi=1.0)
        _real(ConfigError, c + "cd0", self.cd0, nonnegative=True, hi=1.0)
        _real(ConfigError, c + "twist", self.twist, lo=-math.pi / 4, hi=math.pi / 4, unit="rad")
        _vector(ConfigError, c + "position", self.position, 3, unit="m")
        if isinstance(self.thrust_sign, bool) or self.thrust_sign not in (1, -1):
            raise ConfigError(f"{c}thrust_sign must be +1 or -1, got {self.thrust_sign!r}")
        if self.position[0] == 0.0:
            raise ConfigError(f"{c}position: a tail rotor at x = 0 has no yaw moment arm, got {self.position!r}")

    @property
    def tip_speed(self) -> float:
        """Omega R [m/s]."""
        return self.omega * self.radius

    @property
    def disk_area(self) -> float:
        """Disk area pi R^2 [m^2]."""
        return math.pi * self.radius ** 2


@dataclass(frozen=True)
class AircraftConfig:
    """A whole aircraft: rotors, mass properties, fuselage/empennage, propeller.

    mass [kg]; inertias Ixx, Iyy, Izz, Ixz [kg m^2]; fuselage equivalent flat-plate
    drag areas f_x (forward), f_z (vertical) [m^2]; horizontal tail area [m^2],
    position [m] and lift slope [1/rad]; vertical tail likewise; ``rho`` [kg/m^3];
    ``trim_ct``: per-rotor thrust coefficients the wind-tunnel trims aim for in
    hover (from the dissertation where it gives them); ``control_phase`` [rad]:
    the swashplate control phase angle of the pilot mixing
    (:mod:`aircraft.helicopter.mixing`): 0 is the articulated rule (lateral stick on
    the cos-term cyclic), pi/2 pairs the lateral stick with theta1s, as Eq. 7.19 does
    for a stiff hingeless rotor whose hub moment follows the blade lift directly.
    ``fuselage_fx`` is the drag area along body x (drag ``1/2 rho f_x |V| u``);
    ``fuselage_fz`` the cross-flow area (drag ``1/2 rho f_z |v_c| (v, w)`` with the
    cross-flow speed ``|v_c| = sqrt(v^2 + w^2)``); ``fuselage_lift_area`` [m^2/rad]
    the fuselage lift per angle of attack (``L = 1/2 rho (u^2 + w^2) S_L alpha``).
    ``tail_rotor``: a single-rotor aircraft's anti-torque rotor (None: an idealised
    yaw moment, ``HelicopterSettings.tail_rotor_yaw_per_rad``).
    """

    name: str
    rotors: tuple
    mass: float
    Ixx: float
    Iyy: float
    Izz: float
    Ixz: float = 0.0
    rho: float = RHO_SEA_LEVEL
    fuselage_fx: float = 2.0
    fuselage_fz: float = 15.0
    htail_area: float = 3.0
    htail_position: tuple = (-8.0, 0.0, 0.0)
    htail_lift_slope: float = 3.5
    vtail_area: float = 2.5
    vtail_position: tuple = (-8.5, 0.0, -1.0)
    vtail_lift_slope: float = 3.0
    propeller: PropellerConfig | None = None
    trim_ct: tuple = ()
    omega_cruise: float | None = None
    control_phase: float = 0.0
    fuselage_lift_area: float = 0.0
    tail_rotor: TailRotorConfig | None = None

    def __post_init__(self):
        c = "AircraftConfig."
        if isinstance(self.rotors, RotorConfig):
            raise ConfigError(f"{c}rotors must be a tuple of RotorConfig, got a single RotorConfig "
                              "(write rotors=(rotor,))")
        if not isinstance(self.rotors, (tuple, list)) or not self.rotors:
            raise ConfigError(f"{c}rotors must be a non-empty tuple of RotorConfig (one or two), "
                              f"got {self.rotors!r}")
        for k, r in enumerate(self.rotors):
            if not isinstance(r, RotorConfig):
                raise ConfigError(f"{c}rotors[{k}] must be a RotorConfig, got {type(r).__name__}")
        if len(self.rotors) > 2:
            raise ConfigError(f"{c}rotors: one (single rotor) or two (coaxial) rotors are modelled, "
                              f"got {len(self.rotors)}")
        names = [r.name for r in self.rotors]
        if len(set(names)) != len(names):
            raise ConfigError(f"{c}rotors: rotor names must be unique, got {names}")
        _real(ConfigError, c + "mass", self.mass, positive=True, unit="kg")
        for attr in ("Ixx", "Iyy", "Izz"):
            _real(ConfigError, c + attr, getattr(self, attr), positive=True, unit="kg m^2")
        _real(ConfigError, c + "Ixz", self.Ixz, unit="kg m^2")
        if not self.Ixx * self.Izz > self.Ixz ** 2:
            raise ConfigError(f"{c}Ixz: the inertia tensor must be positive definite "
                              f"(Ixz^2 < Ixx Izz), got Ixz = {self.Ixz!r}")
        _real(ConfigError, c + "rho", self.rho, positive=True, hi=2.0, unit="kg/m^3")
        for attr in ("fuselage_fx", "fuselage_fz", "htail_area", "vtail_area"):
            _real(ConfigError, c + attr, getattr(self, attr), nonnegative=True, unit="m^2")
        for attr in ("htail_lift_slope", "vtail_lift_slope"):
            _real(ConfigError, c + attr, getattr(self, attr), nonnegative=True, unit="1/rad")
        for attr in ("htail_position", "vtail_position"):
            _vector(ConfigError, c + attr, getattr(self, attr), 3, unit="m")
        if self.propeller is not None and not isinstance(self.propeller, PropellerConfig):
            raise ConfigError(f"{c}propeller must be a PropellerConfig or None, got "
                              f"{type(self.propeller).__name__}")
        try:
            n_ct = len(self.trim_ct)
        except TypeError:
            raise ConfigError(f"{c}trim_ct must be a tuple of thrust coefficients, got "
                              f"{self.trim_ct!r}") from None
        if n_ct not in (0, len(self.rotors)):
            raise ConfigError(f"{c}trim_ct needs one thrust coefficient per rotor "
                              f"({len(self.rotors)}) or none, got {n_ct}")
        for k, ct in enumerate(self.trim_ct):
            _real(ConfigError, f"{c}trim_ct[{k}]", ct, positive=True, hi=0.1)
        if self.omega_cruise is not None:
            _real(ConfigError, c + "omega_cruise", self.omega_cruise, positive=True, unit="rad/s")
        _real(ConfigError, c + "control_phase", self.control_phase, lo=-math.pi, hi=math.pi, unit="rad")
        _real(ConfigError, c + "fuselage_lift_area", self.fuselage_lift_area, nonnegative=True, unit="m^2/rad")
        if self.tail_rotor is not None:
            if not isinstance(self.tail_rotor, TailRotorConfig):
                raise ConfigError(f"{c}tail_rotor must be a TailRotorConfig or None, got "
                                  f"{type(self.tail_rotor).__name__}")
            if len(self.rotors) != 1:
                raise ConfigError(f"{c}tail_rotor: only a single-rotor aircraft has a tail rotor, "
                                  f"this one has {len(self.rotors)} rotors")

    @property
    def weight(self) -> float:
        """Weight m g [N]."""
        return self.mass * GRAVITY

    @property
    def is_coaxial(self) -> bool:
        return len(self.rotors) == 2

    def rotor(self, name: str) -> RotorConfig:
        """The rotor called ``name`` (``"U"``, ``"L"`` or ``""``)."""
        for r in self.rotors:
            if r.name == name:
                return r
        raise KeyError(f"no rotor named {name!r}; have {[r.name for r in self.rotors]}")


#: Every value not printed in the dissertation, with the reason it was chosen.
ASSUMPTIONS = {
    "coaxial.chord": "0.475 m: per-rotor solidity 0.065 so that C_T/sigma ~ 0.08/0.066 "
                     "at the hover trim C_T (0.0053 upper, 0.0043 lower); XH-59A-like.",
    "coaxial.flap_inertia": "3,610 kg m^2 per blade (Lock number ~6.9), an *equivalent* rigid-blade "
                            "inertia calibrated to the one printed mode that neither the body nor the "
                            "3-state inflow can move: the reactionless (differential) flap mode, whose "
                            "real part is pure blade aerodynamic damping / (2 I_b); Tables 7.1/7.2 print "
                            "-7.975, -7.34, -7.804, -7.576 (mean -7.67 1/s), we had -5.89 with 4,700 kg m^2, "
                            "so I_b = 4,700 x 5.89 / 7.67. (The earlier 4,700 came from gamma ~ 16 zeta nu on "
                            "the coning mode, which ignores the inflow feedback that the coning mode has.) A "
                            "uniform 513 kg blade would give 11,900 kg m^2 (gamma 2.1): the ABC-derived blade "
                            "carries its mass inboard. The reactionless rows are therefore a calibration, "
                            "the coning and progressive rows an independent check.",
    "coaxial.twist": "-10 deg linear: typical of ABC/X2 hingeless rotors (not printed).",
    "coaxial.root_cutout": "0.15 R.",
    "coaxial.hinge_offset": "0.10 R equivalent hinge for a stiff hingeless blade; the "
                            "flap frequency 1.5/rev of Table B.1 is set by an equivalent spring.",
    "coaxial.hub_height": "upper hub 2.4 m above the c.g., lower 0.14 R below it (Table B.1 spacing).",
    "coaxial.inertias": "Ixx 26,800, Iyy 117,400, Izz 127,400 kg m^2, built up by hand (the earlier "
                        "12,000 / 60,000 / 55,000 were below what the blades alone contribute): "
                        "(1) the 8 blades (513.9 kg each, Table B.1) translate with the hubs, 2.40 m and "
                        "1.10 m above the c.g.: 2,055.7 kg x (2.40^2 + 1.10^2) = 14,300 to Ixx and Iyy; "
                        "their own flap inertia is carried by the flap degrees of freedom (the hub spring "
                        "moment), not by the body; (2) the rest, 11,850 kg, with the UH-60 radii of "
                        "gyration (GenHel 6,317 / 52,216 / 49,889 kg m^2 at 7,780 kg: 0.90, 2.59, 2.53 m) "
                        "scaled by the rotor-radius ratio 30.55/26.83: 12,500 / 103,100 / 98,500; "
                        "(3) Izz also carries the two rotors' polar inertia, 8 I_b = 28,900, because the "
                        "rotor speed is held relative to the shaft (no rotor-speed state). "
                        "Sensitivity of the flap-body modes to Ixx: results/coaxial_hover_poles/.",
    "coaxial.fuselage": "f_x 2.5 m^2 drag area along x, f_z 20 m^2 cross-flow (vertical and lateral) drag "
                        "area (regression-model class); no fuselage lift (fuselage_lift_area 0).",
    "coaxial.tails": "horizontal tail 4.0 m^2 at 7.5 m aft; vertical tail 3.0 m^2 at 8.0 m aft.",
    "coaxial.propeller": "solidity 0.12, twist -30 deg, 9.5 m aft of the c.g.",
    "all.lift_slope": "5.73 /rad (2 pi corrected for thickness); stall at 12 deg.",
    "all.cd0": "0.010 constant profile drag.",
    "uh60.hinge_offset": "1.25 ft / 26.83 ft = 0.0466 (Appendix B.1 hinge).",
    "uh60.root_cutout": "(1.25 + 3.83) ft / 26.83 ft = 0.189 (Appendix B.1 spar).",
    "uh60.blade_mass": "116 kg (UH-60A blade ~256 lb).",
    "uh60.flap_frequency": "1.035/rev: articulated rotor with 4.66 % hinge offset.",
    "uh60.control_phase": "pi/2 minus the rotor's classical flap lag (RotorConfig.flap_phase_lag): "
                          "4.6 deg, nearly the articulated rule (the Appendix does not give one).",
    "coaxial.control_phase": "90 deg: Eq. 7.19 pairs the lateral stick with theta1s for this hingeless rotor.",
    "uh60.tail_rotor": "UH-60A-like: R 5.5 ft, 124.62 rad/s, solidity 0.1875, twist -18 deg, hub 9.5 m aft "
                       "and 1.9 m above the c.g., thrust to starboard; no cant, no fin blockage.",
    "uh60.inertias": "UH-60A: Ixx 6,317, Iyy 52,216, Izz 49,889, Ixz 2,551 kg m^2 (GenHel values).",
}


def coaxial_compound(cruise: bool = False) -> AircraftConfig:
    """The coaxial compound aircraft of Appendix B.2 / Table B.1.

    Parameters
    ----------
    cruise : bool
        If True use the forward-flight rotor speed (20.3 rad/s) instead of the
        hover rotor speed (23.7 rad/s).

    Examples
    --------
    >>> cfg = coaxial_compound()
    >>> len(cfg.rotors), cfg.rotors[0].name, cfg.propeller is not None
    (2, 'U', True)
    """
    radius = 30.55 * FT
    omega = 20.3 if cruise else 23.7
    spacing = 0.14 * radius
    blade_mass = 1133.0 * LB
    common = dict(radius=radius, omega=omega, n_blades=4, chord=0.475,
                  twist=math.radians(-10.0), root_cutout=0.15, hinge_offset=0.10,
                  flap_frequency=1.5, lag_frequency=1.3, blade_mass=blade_mass,
                  # equivalent flap inertia calibrated to the reactionless-mode damping (ASSUMPTIONS)
                  flap_inertia=3610.0)
    upper = RotorConfig(name="U", direction=1, hub_position=(0.0, 0.0, -2.4), **common)
    lower = RotorConfig(name="L", direction=-1, hub_position=(0.0, 0.0, -2.4 + spacing), **common)
    return AircraftConfig(
        name="coaxial compound (Table B.1)",
        rotors=(upper, lower),
        mass=35185.0 * LB,
        # hand build-up (ASSUMPTIONS['coaxial.inertias']); was 12,000 / 60,000 / 55,000,
        # below the blades' own parallel-axis contribution (14,300) to Ixx
        Ixx=26800.0, Iyy=117400.0, Izz=127400.0, Ixz=0.0,
        fuselage_fx=2.5, fuselage_fz=20.0,
        htail_area=4.0, htail_position=(-7.5, 0.0, 0.0),
        vtail_area=3.0, vtail_position=(-8.0, 0.0, -1.0),
        propeller=PropellerConfig(position=(-9.5, 0.0, 0.0)),
        trim_ct=(0.0053, 0.0043),
        omega_cruise=20.3,
        # Eq. 7.19: lateral stick on theta1s for this hingeless rotor (§7.2.2)
        control_phase=math.pi / 2,
    )


def uh60_single_rotor() -> AircraftConfig:
    """The UH-60-like single main rotor helicopter of Appendix B.1 (C_T = 0.0061)."""
    radius = 26.83 * FT
    rotor = RotorConfig(
        name="", radius=radius, omega=27.0, n_blades=4, chord=1.73 * FT,
        twist=math.radians(-17.0), root_cutout=(1.25 + 3.83) / 26.83,
        hinge_offset=1.25 / 26.83, flap_frequency=1.035, lag_frequency=0.27,
        blade_mass=116.0, direction=1, hub_position=(0.0, 0.0, -1.9),
    )
    return AircraftConfig(
        name="UH-60-like single rotor (Appendix B.1)",
        rotors=(rotor,),
        mass=17150.0 * LB,
        Ixx=6317.0, Iyy=52216.0, Izz=49889.0, Ixz=2551.0,
        trim_ct=(0.0061,),
        tail_rotor=TailRotorConfig(),
        # ASSUMPTIONS['uh60.control_phase']: follows the rotor's own flap lag
        control_phase=math.pi / 2 - rotor.flap_phase_lag(),
    )
