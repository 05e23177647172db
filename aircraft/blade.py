"""Real blades: chord and twist against radius, aerofoil polars, tip loss.

A :class:`~aircraft.configs.RotorConfig` without a :class:`BladeModel` is the
classical blade: one chord, one linear twist, lift slope ``a`` up to the stall
angle and one profile drag ``cd0``.  With a ``BladeModel`` the blade carries

* a planform: chord [m] and built-in pitch [rad] tabulated against r/R (linear
  interpolation, held constant beyond the first and last station);
* a section polar: either one tabulated :class:`Polar` (c_l, c_d against alpha)
  for the whole blade, or the thickness-based default for symmetric NACA
  4-digit sections (:func:`naca4_symmetric_drag`) with the thickness ratio
  tabulated against r/R and the Reynolds number of each section from its chord
  and rotational speed;
* optionally the Prandtl-Glauert factor on the lift slope (section Mach number
  from the rotational speed);
* optionally a tip-loss factor B: the blade carries no lift outboard of r = B
  (the classical effective-tip model; a lifting line with a free tip vortex
  already has its own tip loss, so it is off by default).

:meth:`BladeModel.sections` evaluates all of this at the elements of a rotor
once, into a :class:`BladeSections` that the wake's blade solve uses.

Units: SI, angles in radians, radii on R.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Polar", "BladeModel", "BladeSections", "naca4_symmetric_drag", "turbulent_skin_friction",
           "SPEED_OF_SOUND", "KINEMATIC_VISCOSITY", "BAILEY_DRAG_SLOPES"]

#: ISA sea-level speed of sound [m/s]
SPEED_OF_SOUND = 340.3
#: ISA sea-level kinematic viscosity [m^2/s]
KINEMATIC_VISCOSITY = 1.46e-5
#: (delta1 [1/rad], delta2 [1/rad^2]) of Bailey's rotor-blade polar of the NACA 0012
#: in "practical construction", c_d = 0.0087 - 0.0216 alpha + 0.400 alpha^2
#: (Bailey, NACA Report 716, 1941; quoted by Gessow & Myers, Aerodynamics of the
#: Helicopter, 1952, ch. 4).
BAILEY_DRAG_SLOPES = (-0.0216, 0.400)


def _table(name, values, n=None, positive=False):
    """A finite 1-D float tuple, checked (ValueError naming ``name``)."""
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a sequence of numbers, got {values!r}") from None
    if arr.ndim != 1 or arr.size < 1 or not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be a non-empty 1-D sequence of finite numbers, got {values!r}")
    if n is not None and arr.size != n:
        raise ValueError(f"{name} needs {n} values (one per station), got {arr.size}")
    if positive and np.any(arr <= 0):
        raise ValueError(f"{name} must be positive, got {values!r}")
    return tuple(float(v) for v in arr)


def turbulent_skin_friction(reynolds):
    """Fully turbulent flat-plate skin friction, Prandtl-Schlichting.

    ``C_f = 0.455 / (log10 Re)^2.58`` (Schlichting, Boundary-Layer Theory).

    Parameters
    ----------
    reynolds : float or ndarray
        Reynolds number on the chord [-], > 1e4.

    Returns
    -------
    float or ndarray
        Skin-friction coefficient of one side [-].

    Examples
    --------
    >>> round(float(turbulent_skin_friction(3e6)), 5)
    0.00367
    """
    re = np.asarray(reynolds, dtype=float)
    if np.any(~np.isfinite(re)) or np.any(re <= 1e4):
        raise ValueError(f"reynolds must be finite and > 1e4, got {reynolds!r}")
    return 0.455 / np.log10(re) ** 2.58


def naca4_symmetric_drag(alpha, thickness, reynolds):
    """Section drag of a symmetric NACA 4-digit aerofoil of a full-scale blade.

    ``c_d = delta0(t/c, Re) + delta1 |alpha| + delta2 alpha^2`` with

    * ``delta0 = 2 C_f(Re) (1 + 2 t/c + 60 (t/c)^4)``: fully turbulent skin friction
      (:func:`turbulent_skin_friction`) on both sides times Hoerner's thickness form
      factor for aerofoils (Hoerner, Fluid-Dynamic Drag, 1965, ch. 6, Eq. 27);
    * ``delta1, delta2`` from Bailey's NACA 0012 rotor-blade polar
      (:data:`BAILEY_DRAG_SLOPES`), held for every thickness.

    Fully turbulent flow stands for a real (not laboratory-smooth) blade: at
    t/c = 0.12 and Re = 3-5 million ``delta0`` is 0.0092-0.0084, bracketing Bailey's
    "practical construction" 0.0087; smooth sections (laminar runs) have about 0.006.  ``|alpha|`` makes the
    polar symmetric, as the section is.

    Parameters
    ----------
    alpha : float or ndarray
        Angle of attack [rad].
    thickness : float or ndarray
        Thickness ratio t/c [-], in (0, 0.5].
    reynolds : float or ndarray
        Reynolds number on the chord [-].

    Returns
    -------
    float or ndarray
        Section drag coefficient [-].

    Examples
    --------
    >>> round(float(naca4_symmetric_drag(0.0, 0.12, 4e6)), 5)
    0.00875
    """
    t = np.asarray(thickness, dtype=float)
    if np.any(~np.isfinite(t)) or np.any(t <= 0) or np.any(t > 0.5):
        raise ValueError(f"thickness must be a ratio t/c in (0, 0.5], got {thickness!r}")
    d0 = 2.0 * turbulent_skin_friction(reynolds) * (1.0 + 2.0 * t + 60.0 * t ** 4)
    a = np.abs(np.asarray(alpha, dtype=float))
    d1, d2 = BAILEY_DRAG_SLOPES
    return d0 + d1 * a + d2 * a ** 2


@dataclass(frozen=True)
class Polar:
    """A tabulated section polar: c_l and c_d against the angle of attack.

    Linear interpolation; beyond the table the end values are held.

    Parameters
    ----------
    alpha : sequence of float
        Angles of attack [rad], strictly increasing, at least two.
    cl, cd : sequence of float
        Lift and drag coefficients [-] at ``alpha``.

    Examples
    --------
    >>> p = Polar(alpha=(-0.2, 0.0, 0.2), cl=(-1.0, 0.0, 1.0), cd=(0.02, 0.01, 0.02))
    >>> float(p.lift(0.1)), float(p.drag(0.1)), p.lift_slope
    (0.5, 0.015, 5.0)
    """

    alpha: tuple
    cl: tuple
    cd: tuple

    def __post_init__(self):
        a = _table("Polar.alpha", self.alpha)
        if len(a) < 2 or np.any(np.diff(a) <= 0):
            raise ValueError(f"Polar.alpha must be strictly increasing with at least two values, got {self.alpha!r}")
        object.__setattr__(self, "alpha", a)
        object.__setattr__(self, "cl", _table("Polar.cl", self.cl, len(a)))
        object.__setattr__(self, "cd", _table("Polar.cd", self.cd, len(a)))
        if min(self.cd) < 0:
            raise ValueError(f"Polar.cd must be >= 0, got {self.cd!r}")

    def lift(self, alpha):
        """Lift coefficient at ``alpha`` [rad] [-]."""
        return np.interp(alpha, self.alpha, self.cl)

    def drag(self, alpha):
        """Drag coefficient at ``alpha`` [rad] [-]."""
        return np.interp(alpha, self.alpha, self.cd)

    @property
    def lift_slope(self):
        """dc_l/dalpha [1/rad] of the table segment at alpha = 0 (the one to its right)."""
        a = np.asarray(self.alpha)
        k = int(np.clip(np.searchsorted(a, 0.0, side="right") - 1, 0, a.size - 2))
        return float((self.cl[k + 1] - self.cl[k]) / (a[k + 1] - a[k]))


@dataclass(frozen=True)
class BladeSections:
    """A blade model evaluated at one rotor's elements (used by the wake's blade solve).

    Attributes
    ----------
    chord : ndarray
        Element chord [m].
    pitch : ndarray
        Built-in pitch relative to the pitch at 0.75 R [rad].
    lift_slope : ndarray
        Lift slope of the linear solve [1/rad] (compressibility included).
    lift_fraction : ndarray
        Fraction of each element that carries lift (tip loss; 1 inboard) [-].
    """

    chord: np.ndarray
    pitch: np.ndarray
    lift_slope: np.ndarray
    lift_fraction: np.ndarray
    stall_angle: float
    polar: Polar | None
    thickness: np.ndarray | None
    reynolds: np.ndarray | None
    mach_factor: np.ndarray

    def lift(self, alpha):
        """Section c_l at ``alpha`` [rad], shape (..., Ne) [-] (before tip loss)."""
        if self.polar is not None:
            return self.polar.lift(alpha) * self.mach_factor
        return self.lift_slope * np.clip(alpha, -self.stall_angle, self.stall_angle)

    def drag(self, alpha, cd0):
        """Section c_d at ``alpha`` [rad], shape (..., Ne) [-]; ``cd0`` when no polar is set."""
        if self.polar is not None:
            return self.polar.drag(alpha)
        if self.thickness is not None:
            return naca4_symmetric_drag(alpha, self.thickness, self.reynolds)
        return np.full(np.shape(alpha), float(cd0))


@dataclass(frozen=True)
class BladeModel:
    """Planform, section polar and tip loss of a blade (all optional).

    Parameters
    ----------
    stations : sequence of float, optional
        Radial stations r/R [-], strictly increasing, of the tables below.
    chord : sequence of float, optional
        Chord at the stations [m]; None: the rotor's constant ``chord``.
    twist : sequence of float, optional
        Built-in pitch at the stations [rad]; the collective is the pitch at
        0.75 R, so only differences matter.  None: the rotor's linear ``twist``.
    thickness : sequence of float, optional
        Thickness ratio t/c at the stations [-]: symmetric NACA 4-digit sections
        with the drag of :func:`naca4_symmetric_drag` (lift: the rotor's
        ``lift_slope`` up to its ``stall_angle``).
    polar : Polar, optional
        One tabulated polar for the whole blade (excludes ``thickness``).
    compressibility : bool
        Prandtl-Glauert factor ``1/sqrt(1 - M^2)`` on the lift, M from the
        rotational speed at each element (default False).
    tip_loss : float, optional
        Tip-loss factor B in (0.8, 1]: no lift outboard of r = B (default None).

    Examples
    --------
    >>> b = BladeModel(stations=(0.2, 1.0), chord=(0.6, 0.3), thickness=(0.30, 0.15))
    >>> s = b.sections(np.array([0.4, 0.8]), chord=0.45, twist=0.0, lift_slope=5.73,
    ...                stall_angle=0.2, omega=20.0, radius=7.0)
    >>> s.chord.round(3).tolist(), s.thickness.round(4).tolist()
    ([0.525, 0.375], [0.2625, 0.1875])
    """

    stations: tuple | None = None
    chord: tuple | None = None
    twist: tuple | None = None
    thickness: tuple | None = None
    polar: Polar | None = None
    compressibility: bool = False
    tip_loss: float | None = None

    def __post_init__(self):
        tables = [k for k in ("chord", "twist", "thickness") if getattr(self, k) is not None]
        if tables and self.stations is None:
            raise ValueError(f"BladeModel.{tables[0]} needs BladeModel.stations (r/R of the table)")
        if self.stations is not None:
            st = _table("BladeModel.stations", self.stations)
            if np.any(np.diff(st) <= 0) or st[0] < 0 or st[-1] > 1.0:
                raise ValueError(f"BladeModel.stations must increase strictly within [0, 1], got {self.stations!r}")
            object.__setattr__(self, "stations", st)
            for k in tables:
                object.__setattr__(self, k, _table(f"BladeModel.{k}", getattr(self, k), len(st),
                                                   positive=(k == "chord")))
        if self.thickness is not None and (min(self.thickness) <= 0 or max(self.thickness) > 0.5):
            raise ValueError(f"BladeModel.thickness must be ratios t/c in (0, 0.5], got {self.thickness!r}")
        if self.polar is not None and not isinstance(self.polar, Polar):
            raise ValueError(f"BladeModel.polar must be an aircraft.blade.Polar, got {self.polar!r}")
        if self.polar is not None and self.thickness is not None:
            raise ValueError("BladeModel: give either polar (a table) or thickness (the NACA default), not both")
        if not isinstance(self.compressibility, bool):
            raise ValueError(f"BladeModel.compressibility must be True or False, got {self.compressibility!r}")
        if self.tip_loss is not None:
            b = self.tip_loss
            if isinstance(b, bool) or not isinstance(b, (int, float)) or not 0.8 < b <= 1.0:
                raise ValueError(f"BladeModel.tip_loss must be a factor B in (0.8, 1], got {b!r}")
            object.__setattr__(self, "tip_loss", float(b))

    def _at(self, name, r):
        return np.interp(r, self.stations, getattr(self, name))

    def sections(self, r, *, chord, twist, lift_slope, stall_angle, omega, radius, r_edge=None,
                 nu=KINEMATIC_VISCOSITY, sound=SPEED_OF_SOUND):
        """Evaluate the blade at element radii ``r`` (r/R).

        Parameters
        ----------
        r : ndarray
            Element centres r/R [-].
        chord, twist, lift_slope, stall_angle : float
            The rotor's constant chord [m], linear twist [rad], lift slope [1/rad]
            and stall angle [rad], used where the blade model sets nothing.
        omega, radius : float
            Rotor speed [rad/s] and radius [m] (Reynolds and Mach numbers).
        r_edge : ndarray, optional
            Element edges r/R (Ne + 1), for the lifting fraction under tip loss;
            None: an element lifts wholly if its centre is inboard of B.
        nu, sound : float
            Kinematic viscosity [m^2/s] and speed of sound [m/s].

        Returns
        -------
        BladeSections
        """
        r = np.asarray(r, dtype=float)
        c = self._at("chord", r) if self.chord is not None else np.full(r.shape, float(chord))
        if self.twist is not None:
            pitch = self._at("twist", r) - float(self._at("twist", 0.75))
        else:
            pitch = twist * (r - 0.75)
        speed = omega * radius * r
        mach = speed / sound
        if self.compressibility:
            if np.any(mach >= 0.95):
                raise ValueError(f"compressibility: section Mach number {mach.max():.2f} is beyond "
                                 "the Prandtl-Glauert factor's range (< 0.95)")
            factor = 1.0 / np.sqrt(1.0 - mach ** 2)
        else:
            factor = np.ones_like(r)
        a0 = self.polar.lift_slope if self.polar is not None else float(lift_slope)
        frac = np.ones_like(r)
        if self.tip_loss is not None:
            if r_edge is None:
                frac = (r <= self.tip_loss).astype(float)
            else:
                e = np.asarray(r_edge, dtype=float)
                frac = np.clip((self.tip_loss - e[:-1]) / (e[1:] - e[:-1]), 0.0, 1.0)
        th = self._at("thickness", r) if self.thickness is not None else None
        re = speed * c / nu if self.thickness is not None else None
        return BladeSections(chord=c, pitch=pitch, lift_slope=a0 * factor, lift_fraction=frac,
                             stall_angle=float(stall_angle), polar=self.polar, thickness=th,
                             reynolds=re, mach_factor=factor)

    # --- file form ---------------------------------------------------------------
    def to_dict(self):
        """The fields that are set, as plain numbers and lists (the TOML table form).

        Examples
        --------
        >>> BladeModel(tip_loss=0.97).to_dict()
        {'compressibility': False, 'tip_loss': 0.97}
        """
        out = {}
        for k in ("stations", "chord", "twist", "thickness"):
            if getattr(self, k) is not None:
                out[k] = list(getattr(self, k))
        if self.polar is not None:
            out["polar"] = {"alpha": list(self.polar.alpha), "cl": list(self.polar.cl),
                            "cd": list(self.polar.cd)}
        out["compressibility"] = self.compressibility
        if self.tip_loss is not None:
            out["tip_loss"] = self.tip_loss
        return out

    @classmethod
    def from_dict(cls, data):
        """Inverse of :meth:`to_dict` (ValueError naming an unknown or bad key).

        Examples
        --------
        >>> b = BladeModel(stations=(0.2, 1.0), thickness=(0.3, 0.15))
        >>> BladeModel.from_dict(b.to_dict()) == b
        True
        """
        if not isinstance(data, dict):
            raise ValueError(f"a blade table must be a table of fields, got {data!r}")
        known = {"stations", "chord", "twist", "thickness", "polar", "compressibility", "tip_loss"}
        bad = sorted(set(data) - known)
        if bad:
            raise ValueError(f"unknown blade field(s) {bad}; the valid ones are {sorted(known)}")
        kw = dict(data)
        if "polar" in kw:
            p = kw["polar"]
            if not isinstance(p, dict) or set(p) != {"alpha", "cl", "cd"}:
                raise ValueError(f"blade polar must be a table with alpha, cl and cd, got {p!r}")
            kw["polar"] = Polar(**p)
        return cls(**kw)
