"""Smooth (grid) forms of spec boundaries: what a spec gives the DMO's NLP.

A :class:`~controllers.specs.Spec` that can steer the design-margin optimiser
carries a :class:`SmoothConstraint` in its ``smooth`` field.  The NLP
(:mod:`controllers.nlp`) is assembled from the spec list it is given: every
spec with a smooth constraint adds that constraint, with the boundary read from
the spec itself (``level1``, or the constraint's own shape data) at every solve.
Adding a spec to the list is therefore enough for the optimiser to honour it;
specs without a smooth form (damping, bandwidth, OLOP, ...) are honoured by the
true-spec scoring of every candidate.

The loop broken at the mixer input, L(jw) = C(jw) Q(jw), is known to a
constraint on the optimiser's frequency grid as CasADi expressions (real and
imaginary parts, |L|^2, |1+L|^2, the angle from the critical point, the gain in
dB and the unwrapped phase); see :class:`LoopGrid`.  Each constraint returns
expressions that are >= 0 where the boundary is met; the NLP adds its slack.
Every boundary is backed off by ``backoff`` (relative), so that a design meeting
the constraints on the optimiser's grid also meets the spec on the dense
evaluation grid.

Angles in the expressions are in radians, gains in dB, frequencies in rad/s.
"""
from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

__all__ = ["SmoothConstraint", "LoopGrid", "SolvePoint", "NicholsEllipse", "GainMarginPastCritical",
           "PhaseMarginBand", "DisturbancePeakLimit", "DisturbanceBandwidthFloor", "CrossoverMinimum",
           "SmoothConstraintError", "spec_with_constraint"]


class SmoothConstraintError(ValueError):
    """A spec's boundary cannot be turned into its smooth constraint (e.g. not finite)."""


@dataclass
class LoopGrid:
    """One plant's broken loop on the optimiser's grid (CasADi column vectors).

    Attributes
    ----------
    omega : numpy.ndarray
        Grid [rad/s] (numbers).
    backoff : float
        Relative back-off of every boundary [-].
    re, im : casadi.SX
        Real and imaginary parts of L(jw).
    mag2 : casadi.SX
        |L|^2.
    dist2 : casadi.SX
        |1 + L|^2 (the disturbance response is 1/(1+L)).
    angle : casadi.SX
        Angle of -L [rad]: the phase distance of L from -180 deg, in (-pi, pi].
    gain_db : casadi.SX
        20 log10 |L| [dB].
    phase : casadi.SX
        Unwrapped phase of L [rad] (branch anchored at the crossover boundary).
    """

    omega: np.ndarray
    backoff: float
    re: object
    im: object
    mag2: object
    dist2: object
    angle: object
    gain_db: object
    phase: object


@dataclass(frozen=True)
class SolvePoint:
    """Where one NLP solve stands: grid, back-off and the DMO's current crossover boundary.

    Attributes
    ----------
    omega : numpy.ndarray
        Optimiser grid [rad/s].
    backoff : float
        Relative back-off of the boundaries [-].
    crossover_min : float
        Crossover boundary of this solve [rad/s] (sets where the gain-margin
        constraint starts).
    phase_from : float
        The gain-margin constraint applies above ``phase_from * crossover_min``.
    unstable_plant : bool
        Whether a plant of the solve has a pole in the right half plane: its loop
        can only be stable conditionally, so the gain-margin constraint accepts a
        gain margin on either side of the critical point.
    """

    omega: np.ndarray
    backoff: float
    crossover_min: float
    phase_from: float
    unstable_plant: bool = False


class SmoothConstraint:
    """Base class: the smooth NLP form of one spec's Level 1 boundary.

    Subclasses define :meth:`n_parameters`, :meth:`expressions` and
    :meth:`parameters`.  The expressions are built once per NLP with the
    boundary as an NLP parameter; :meth:`parameters` reads its value from the
    spec at every solve, so the same NLP serves every boundary the DMO tries.
    """

    def n_parameters(self, n_grid):
        """Number of NLP parameters of this constraint.

        Parameters
        ----------
        n_grid : int
            Points of the optimiser's grid.

        Returns
        -------
        int
        """
        return 1

    def expressions(self, loop, p):
        """CasADi expressions, each >= 0 where the boundary is met.

        Parameters
        ----------
        loop : LoopGrid
            The broken loop of one plant on the grid.
        p : casadi.SX
            This constraint's parameters (column of :meth:`n_parameters`).

        Returns
        -------
        list of casadi.SX
        """
        raise NotImplementedError

    def parameters(self, spec, point):
        """Parameter values for one solve, read from ``spec``'s boundary.

        Parameters
        ----------
        spec : Spec
            The spec that carries this constraint.
        point : SolvePoint
            Grid, back-off and crossover boundary of the solve.

        Returns
        -------
        numpy.ndarray
        """
        raise NotImplementedError

    def implied_by(self, spec, other, other_spec):
        """Whether ``other`` (carried by ``other_spec``) already enforces this constraint.

        The NLP leaves out a constraint implied by another one in the same
        problem: the feasible set is the same and IPOPT sees fewer rows.

        Parameters
        ----------
        spec : Spec
            The spec carrying this constraint.
        other : SmoothConstraint
            Another constraint of the same problem.
        other_spec : Spec
            The spec carrying ``other``.

        Returns
        -------
        bool
        """
        return False

    def __repr__(self):
        return type(self).__name__ + "()"


def _level1(spec):
    v = float(spec.level1)
    if not np.isfinite(v):
        raise SmoothConstraintError(f"spec {spec.name!r}: a smooth constraint needs a finite Level 1 boundary, "
                                    f"got {spec.level1}")
    return v


def _onehot(n, k):
    return np.eye(1, n, min(k, n - 1)).ravel()


@dataclass(frozen=True, repr=True)
class NicholsEllipse(SmoothConstraint):
    """Nichols exclusion ellipse about (-180 deg, 0 dB): the NicMgG1 boundary.

    The spec's value is the normalised distance of the curve from the ellipse
    (:func:`controllers.metrics.nichols_margin` with the same semi-axes), so
    ``value >= level1`` at every grid point reads
    ``(angle/phase_axis)^2 + (gain/gain_axis)^2 >= (1 + level1)^2``.

    Attributes
    ----------
    phase_axis : float
        Phase semi-axis [deg].
    gain_axis : float
        Gain semi-axis [dB].
    """

    phase_axis: float = 45.0
    gain_axis: float = 6.0

    def __post_init__(self):
        if not (np.isfinite(self.phase_axis) and np.isfinite(self.gain_axis)
                and self.phase_axis > 0 and self.gain_axis > 0):
            raise SmoothConstraintError(f"NicholsEllipse semi-axes must be finite and > 0, got "
                                        f"{self.phase_axis}, {self.gain_axis}")

    def expressions(self, loop, p):
        bo = loop.backoff
        ellipse = ((loop.angle / np.radians(self.phase_axis * (1 + bo))) ** 2
                   + (loop.gain_db / (self.gain_axis * (1 + bo))) ** 2)
        return [ellipse - p[0]]

    def parameters(self, spec, point):
        return np.array([(1.0 + _level1(spec)) ** 2])


@dataclass(frozen=True, repr=True)
class GainMarginPastCritical(SmoothConstraint):
    """Gain margin: the loop gain stays GM away from 0 dB where the phase is past -180 deg (StbMgG1.GM).

    Applied above ``phase_from`` times the crossover boundary (below it, the
    integrator's -180 deg region is allowed). For a stable plant the gain must lie
    below -GM there, which also rules out conditionally stable loops. For an
    unstable plant (:attr:`SolvePoint.unstable_plant`) a stable loop is
    conditionally stable (Nyquist: it must encircle the critical point), so the
    gain may lie below -GM or above +GM, the smooth form of ``|gain| >= GM``
    (``(gain^2 - GM^2) / (2 GM) >= 0``, equal to the stable plant's form to first
    order at gain = -GM); which side is stable is left to the eigenvalue check.
    The spec's ``level1`` is the margin [dB].

    Attributes
    ----------
    transition_deg : float
        Width of the smooth step that marks "phase past -180 deg" [deg].
    """

    transition_deg: float = 3.0

    def n_parameters(self, n_grid):
        return n_grid + 2

    def expressions(self, loop, p):
        mask, gm, two_sided = p[:-2], p[-2], p[-1]
        beyond = 1.0 / (1.0 + ca.exp((loop.phase + np.pi) / np.radians(self.transition_deg)))
        below = -(loop.gain_db + gm)
        either = (loop.gain_db ** 2 - gm ** 2) / (2.0 * gm)
        return [mask * ((1.0 - two_sided) * below + two_sided * either) * beyond]

    def parameters(self, spec, point):
        mask = (point.omega >= point.phase_from * point.crossover_min).astype(float)
        return np.r_[mask, _level1(spec), float(point.unstable_plant)]


@dataclass(frozen=True, repr=True)
class PhaseMarginBand(SmoothConstraint):
    """Phase margin: near 0 dB the loop stays ``level1`` [deg] away from -180 deg (StbMgG1.PM).

    A thin exclusion ellipse about (-180 deg, 0 dB) with phase semi-axis the
    spec's ``level1`` and gain semi-axis ``band_db``: every grid point inside
    +-band_db of 0 dB must be at least the margin away from -180 deg, which is
    the phase margin at the crossover.  On the default grid a loop falling at
    20-40 dB/decade moves 0.1-0.2 dB per grid point, so the band always holds
    grid points.

    Attributes
    ----------
    band_db : float
        Gain semi-axis of the ellipse [dB].
    """

    band_db: float = 1.0

    def __post_init__(self):
        if not np.isfinite(self.band_db) or self.band_db <= 0:
            raise SmoothConstraintError(f"PhaseMarginBand.band_db must be finite and > 0 dB, got {self.band_db}")

    def expressions(self, loop, p):
        bo = loop.backoff
        return [(loop.angle / (p[0] * (np.pi / 180.0) * (1 + bo))) ** 2 + (loop.gain_db / self.band_db) ** 4 - 1.0]

    def implied_by(self, spec, other, other_spec):
        # both exclusion zones are axis-aligned ellipses about the critical point (the
        # same back-off on the phase axis): the band lies inside the other ellipse when
        # both its semi-axes are smaller
        if not isinstance(other, NicholsEllipse) or not np.isfinite(other_spec.level1):
            return False
        grow = 1.0 + float(other_spec.level1)
        return bool(grow > 0 and _level1(spec) <= other.phase_axis * grow and self.band_db <= other.gain_axis * grow)

    def parameters(self, spec, point):
        pm = _level1(spec)
        if pm <= 0:
            raise SmoothConstraintError(f"spec {spec.name!r}: phase margin boundary must be > 0 deg, got {pm}")
        return np.array([pm])


@dataclass(frozen=True, repr=True)
class DisturbancePeakLimit(SmoothConstraint):
    """Disturbance-rejection peak: |1/(1+L)| at most ``level1`` [dB] (DrpAvH1).

    Reads ``|1+L|^2 >= 10^(-level1/10)`` at every grid point.
    """

    def expressions(self, loop, p):
        return [loop.dist2 - p[0]]

    def parameters(self, spec, point):
        return np.array([10 ** (-_level1(spec) * (1 - point.backoff) / 10)])


@dataclass(frozen=True, repr=True)
class DisturbanceBandwidthFloor(SmoothConstraint):
    """Disturbance-rejection bandwidth of at least ``level1`` [rad/s] (DrbRoH1).

    The disturbance response 1/(1+L) stays below -3 dB (``|1+L|^2 >= 2``) at
    every grid frequency up to the boundary.  The DMO raises this boundary.
    """

    def n_parameters(self, n_grid):
        return n_grid

    def expressions(self, loop, p):
        return [p * (loop.dist2 - 2.0 * (1 + loop.backoff))]

    def parameters(self, spec, point):
        return (point.omega <= _level1(spec) * (1 + point.backoff)).astype(float)


@dataclass(frozen=True, repr=True)
class CrossoverMinimum(SmoothConstraint):
    """Crossover frequency of at least ``level1`` [rad/s] (CrsMnG2): |L| >= 1 there.

    The DMO drives its design onto this boundary and raises it.
    """

    def n_parameters(self, n_grid):
        return n_grid

    def expressions(self, loop, p):
        return [ca.dot(p, loop.mag2) - 1.0]

    def parameters(self, spec, point):
        w = point.omega
        return _onehot(w.size, int(np.searchsorted(w, _level1(spec) * (1 + point.backoff))))


def spec_with_constraint(specs, kind, required=True):
    """The first spec of ``specs`` whose smooth constraint is a ``kind``.

    Parameters
    ----------
    specs : list of Spec
    kind : type
        A :class:`SmoothConstraint` subclass (e.g. :class:`CrossoverMinimum`).
    required : bool
        Raise when there is none (otherwise return None).

    Returns
    -------
    Spec or None

    Raises
    ------
    SmoothConstraintError
        No spec carries such a constraint and ``required`` is set.
    """
    for s in specs:
        if isinstance(getattr(s, "smooth", None), kind):
            return s
    if required:
        raise SmoothConstraintError(f"no spec in the list carries a {kind.__name__} smooth constraint; "
                                    f"specs: {[s.name for s in specs]}")
    return None
