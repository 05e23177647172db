"""The one interface every inflow model implements.

Conventions (shared with :mod:`aircraft.wake` and :mod:`aircraft.helicopter`)
-----------------------------------------------------------------------------
Every rotor is described in its *own* frame, so the equations of a counter-rotating
lower rotor are the same as those of the upper one:

* blade azimuth psi: zero pointing aft, increasing in the rotor's direction of
  rotation (``RotorConfig.direction``: +1 counter-clockwise from above, -1 clockwise);
* induced inflow ``lambda(r, psi) = lam0 + lam1s r sin(psi) + lam1c r cos(psi)``,
  positive *down* through the disk, non-dimensional on that rotor's Omega R;
* loads ``C_T = T / (rho pi R^2 (Omega R)^2)`` positive up;
  ``C_L = -sum_b int dL r sin(psi_b) / (rho pi R^2 (Omega R)^2 R)`` and
  ``C_M = -sum_b int dL r cos(psi_b) / (...)``, i.e. for a counter-clockwise
  rotor the body-axis roll (right side down) and pitch (nose up) moments.  For a
  clockwise rotor the body roll moment is ``direction * C_L``; C_M is unchanged.
  With this sign choice the hover Pitt-Peters gains ``lam1s/C_L`` and ``lam1c/C_M``
  are negative, as in the dissertation's Tables 4.1-4.2 (M22 = -16/(45 pi),
  Lbar22 = -lambda_h);
* flap ``beta(psi) = beta0 + beta1c cos(psi) + beta1s sin(psi)`` positive up; flap
  rates ``beta1s_dot``, ``beta1c_dot`` in rad/s.
* flap-rate (wake-distortion) inputs of an inflow model are the **full**
  tip-path-plane rates relative to space, body rates included, in the rotor's
  own frame: ``beta1s_dot = d(beta1s)/dt - p_r``, ``beta1c_dot = d(beta1c)/dt - q_r``
  with ``p_r = direction * p`` (body roll rate, right side down, mirrored for a
  clockwise rotor) and ``q_r = q`` (pitch rate, nose up), flap positive up and
  measured from the shaft. Divided by Omega they are minus the bracket of
  Eq. 2.29, ``-(Delta p / Omega - Delta beta1s*)``. The aircraft
  (:meth:`aircraft.helicopter.rotor.RotorModel.tpp_rates`) gives every model
  that sets ``uses_flap_rates`` these rates; with the shaft fixed (the
  wind-tunnel wake runs an identified model comes from) they equal the
  shaft-relative rates, so identified models need no change.

Signals use the project's canonical names (:doc:`/architecture`): loads ``CT_U, CL_U, CM_U, CT_L, …``
(no suffix for a single rotor), inflow ``lam0_U, lam1s_U, lam1c_U, …``, flap-rate
(wake-distortion) inputs ``beta1s_dot_U, beta1c_dot_U, …``.

Time is in seconds in this interface.  Models written in rotor-azimuth time
(d/dpsi) convert with Omega in exactly one place: :meth:`InflowModel.derivatives`.
"""
from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass

import numpy as np

__all__ = ["RotorOperatingPoint", "InflowModel", "rotor_suffix", "load_names",
           "inflow_names", "flap_rate_names", "check_rotor_names", "config_rotor_names"]


def rotor_suffix(name: str) -> str:
    """Signal suffix for a rotor name: ``"U" -> "_U"``, ``"" -> ""``."""
    return f"_{name}" if name else ""


def check_rotor_names(rotors, n_rotors=None, *, argument="rotors", error=ValueError) -> tuple:
    """Rotor names validated as signal suffixes: a tuple of distinct strings.

    Parameters
    ----------
    rotors : sequence of str
        Rotor names, the upper (first) rotor first, e.g. ``("U", "L")``; a single
        rotor may be unnamed, ``("",)``.
    n_rotors : int, optional
        Number of rotors the caller's model is built for.
    argument : str
        Name of the argument, for the error message.
    error : type
        Exception class raised (a subclass of ValueError).

    Returns
    -------
    tuple of str

    Raises
    ------
    ValueError
        (``error``) A bare string, a name that is not a string, an empty name
        beside others, a name with ``_`` or whitespace (the suffix would not be
        recognisable in a signal name such as ``lam1s_<name>``), repeated names,
        or the wrong number of names.

    Examples
    --------
    >>> check_rotor_names(["upper", "lower"], 2)
    ('upper', 'lower')
    >>> check_rotor_names(("U", "U"), 2)
    Traceback (most recent call last):
    ...
    ValueError: rotors must be distinct rotor names, got ('U', 'U')
    """
    if isinstance(rotors, str):
        raise error(f"{argument} must be a sequence of rotor names, e.g. ('U', 'L'), not the string {rotors!r}")
    try:
        names = tuple(rotors)
    except TypeError:
        raise error(f"{argument} must be a sequence of rotor names, got {rotors!r}") from None
    if not names:
        raise error(f"{argument} must name at least one rotor")
    for r in names:
        if not isinstance(r, str):
            raise error(f"{argument} must hold strings, got {r!r} in {names}")
        if (r == "" and len(names) > 1) or "_" in r or any(c.isspace() for c in r):
            raise error(f"{argument}: rotor name {r!r} cannot be a signal suffix (empty beside other rotors, "
                        f"or containing '_' or whitespace), got {names}")
    if len(set(names)) != len(names):
        raise error(f"{argument} must be distinct rotor names, got {names}")
    if n_rotors is not None and len(names) != n_rotors:
        raise error(f"{argument} must name {n_rotors} rotor(s) for this model, got {len(names)}: {names}")
    return names


def config_rotor_names(config) -> tuple:
    """Rotor names of an aircraft configuration, the upper (first) rotor first.

    Parameters
    ----------
    config : aircraft.AircraftConfig
        Its ``rotors[i].name``.

    Returns
    -------
    tuple of str

    Raises
    ------
    ValueError
        If ``config`` has no rotors or its names are not valid signal suffixes
        (:func:`check_rotor_names`).

    Examples
    --------
    >>> from aircraft.configs import coaxial_compound
    >>> config_rotor_names(coaxial_compound())
    ('U', 'L')
    """
    rotors = getattr(config, "rotors", None)
    if not rotors:
        raise ValueError(f"config must be an aircraft configuration with rotors, got {type(config).__name__}")
    return check_rotor_names([getattr(r, "name", None) for r in rotors], argument="config rotor names")


def load_names(rotors) -> list[str]:
    """``["CT_U", "CL_U", "CM_U", "CT_L", …]`` for rotor names ``rotors``."""
    return [f"{c}{rotor_suffix(r)}" for r in rotors for c in ("CT", "CL", "CM")]


def inflow_names(rotors) -> list[str]:
    """``["lam0_U", "lam1s_U", "lam1c_U", …]`` for rotor names ``rotors``."""
    return [f"{c}{rotor_suffix(r)}" for r in rotors for c in ("lam0", "lam1s", "lam1c")]


def flap_rate_names(rotors) -> list[str]:
    """``["beta1s_dot_U", "beta1c_dot_U", …]`` for rotor names ``rotors``."""
    return [f"{c}{rotor_suffix(r)}" for r in rotors for c in ("beta1s_dot", "beta1c_dot")]


@dataclass(frozen=True)
class RotorOperatingPoint:
    """What an inflow model needs to know of one rotor's flight condition.

    Parameters
    ----------
    omega : float
        Rotor speed [rad/s].
    mu : float
        In-plane advance ratio (free-stream component in the disk plane / Omega R), >= 0.
    mu_z : float
        Axial (climb) ratio: the rotor hub's velocity along the shaft, positive
        *up* (climb), divided by Omega R.  In a climb the free stream then flows
        *down* through the disk, adding to the induced inflow: the total flow
        through the disk is ``lambda_tot = mu_z + lam0`` (positive down, as
        lambda).  The induced inflow is not included in ``mu_z``.  (The
        helicopter sets ``mu_z = -w_hub / (Omega R)`` with body z down.  Note that
        a disk tilted *back* in forward flight has the free stream flowing *up*
        through it, i.e. a *negative* ``mu_z`` here.)
    """

    omega: float
    mu: float = 0.0
    mu_z: float = 0.0

    def __post_init__(self):
        if not self.omega > 0:
            raise ValueError(f"RotorOperatingPoint.omega must be positive [rad/s], got {self.omega!r}")
        if self.mu < 0:
            raise ValueError(f"RotorOperatingPoint.mu must be >= 0, got {self.mu!r}")


class InflowModel(ABC):
    """A dynamic inflow model for one or more rotors.

    The full (possibly nonlinear) model is an ODE ``x' = f(x, loads, op, rates)``
    with outputs ``lambda = g(x, loads, op)``; ``linear`` gives its perturbation
    form about an operating point as a :class:`control.StateSpace` in seconds.

    Subclasses set ``rotors`` (tuple of rotor names, e.g. ``("U", "L")`` or
    ``("",)``) and implement the abstract methods.
    """

    rotors: tuple = ("",)
    #: True if the model takes flap/body-rate (wake-distortion) inputs.
    uses_flap_rates: bool = False

    # -- signal names ---------------------------------------------------------
    @property
    @abstractmethod
    def state_names(self) -> list[str]:
        """Names of the model's states (len == n_states)."""

    @property
    def n_states(self) -> int:
        return len(self.state_names)

    @property
    def load_names(self) -> list[str]:
        return load_names(self.rotors)

    @property
    def rate_names(self) -> list[str]:
        return flap_rate_names(self.rotors) if self.uses_flap_rates else []

    @property
    def input_names(self) -> list[str]:
        """Loads first, then flap rates (if used)."""
        return self.load_names + self.rate_names

    @property
    def output_names(self) -> list[str]:
        return inflow_names(self.rotors)

    # -- dynamics -------------------------------------------------------------
    @abstractmethod
    def steady_state(self, loads: np.ndarray, ops: tuple) -> np.ndarray:
        """States in equilibrium with the total ``loads`` (len 3 * n_rotors).

        ``ops`` is a tuple of :class:`RotorOperatingPoint`, one per rotor.
        """

    @abstractmethod
    def derivatives(self, x: np.ndarray, loads: np.ndarray, ops: tuple,
                    rates: np.ndarray | None = None) -> np.ndarray:
        """State derivative dx/dt [1/s] for total loads and (optional) flap rates.

        ``rates`` (len 2 * n_rotors, order :attr:`rate_names`, rad/s) are the full
        tip-path-plane rates of the module docstring (body rates included)."""

    @abstractmethod
    def inflow(self, x: np.ndarray, loads: np.ndarray, ops: tuple) -> np.ndarray:
        """Total induced inflow harmonics ``[lam0, lam1s, lam1c]`` per rotor.

        ``loads`` may be None: the models of this package have no load-to-inflow
        feedthrough (which would make an algebraic loop with the blade loads).

        This is what a blade-element model uses: it includes interference
        (for example the climb the upper rotor imposes on the lower one), so
        the blade sees ``lambda(r, psi) = lam0 + lam1s r sin psi + lam1c r cos psi``.
        """

    def set_trim(self, x: np.ndarray, loads: np.ndarray, ops: tuple) -> None:
        """Called once the aircraft is trimmed (x: inflow states at trim).

        Models with quantities frozen at trim (e.g. the climbing lower rotor's
        climb, §2.2.2.3) store them here; the default does nothing.
        """

    def release_trim(self) -> None:
        """Undo :meth:`set_trim` (call before trimming again at another condition).

        The default does nothing."""

    def linear(self, loads: np.ndarray, ops: tuple):
        """Perturbation model about the equilibrium with ``loads``: a named
        :class:`control.StateSpace` (inputs ``input_names``, outputs
        ``output_names``, time in seconds).  The default linearises
        :meth:`derivatives`/:meth:`inflow` by central differences; models with
        exact matrices override it."""
        import control

        loads = np.asarray(loads, dtype=float)
        x0 = self.steady_state(loads, ops)
        n_rates = len(self.rate_names)
        u0 = np.concatenate([loads, np.zeros(n_rates)])

        def f(x, u):
            rates = u[len(loads):] if n_rates else None
            return self.derivatives(x, u[:len(loads)], ops, rates)

        def g(x, u):
            return self.inflow(x, u[:len(loads)], ops)

        A, B = _jacobians(f, x0, u0)
        C, D = _jacobians(g, x0, u0)
        sys = control.ss(A, B, C, D, states=self.state_names,
                         inputs=self.input_names, outputs=self.output_names,
                         name=type(self).__name__)
        sys.trim_states = x0
        sys.trim_inputs = u0
        sys.trim_outputs = g(x0, u0)
        return sys


def _jacobians(fun, x0, u0, rel_step=1e-6):
    """Central-difference Jacobians of ``fun(x, u)`` about (x0, u0)."""
    f0 = np.asarray(fun(x0, u0), dtype=float)
    jx = np.zeros((f0.size, x0.size))
    ju = np.zeros((f0.size, u0.size))
    for j in range(x0.size):
        h = rel_step * max(1.0, abs(x0[j]))
        e = np.zeros_like(x0)
        e[j] = h
        jx[:, j] = (np.asarray(fun(x0 + e, u0)) - np.asarray(fun(x0 - e, u0))) / (2 * h)
    for j in range(u0.size):
        h = rel_step * max(1e-3, abs(u0[j]))
        e = np.zeros_like(u0)
        e[j] = h
        ju[:, j] = (np.asarray(fun(x0, u0 + e)) - np.asarray(fun(x0, u0 - e))) / (2 * h)
    return jx, ju
