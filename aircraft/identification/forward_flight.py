"""Single-rotor inflow identification in forward flight (§4.4) and its Pitt-Peters reference.

::

    identify_forward_flight   identify_inflow at advance ratio mu (wake trim C_T, zero hub moments)
    pitt_peters_forward       the linearised Pitt-Peters (Peters & HaQuang) M, Lbar at the trim

Units: ``M`` multiplies d/dpsi (azimuth time); ``Lbar`` is dimensionless; delays in seconds.
"""
from __future__ import annotations

import math

import numpy as np

from .conditions import flight_condition
from .structures.forward import FORWARD_FIT_PAIRS, SingleRotorForward, pitt_peters_start

__all__ = ["identify_forward_flight", "pitt_peters_forward"]


def identify_forward_flight(config, mu, *, alpha=0.0, ct=0.0061, pattern="eq4_3", settings=None,
                            name=None, n_jobs=2, cache_dir="default", progress=True, start="pitt_peters",
                            pairs=FORWARD_FIT_PAIRS, reproduce=False):
    """Identify the forward-flight model of one rotor at advance ratio ``mu`` from the free wake.

    The wake is trimmed in the wind tunnel to ``ct`` and zero hub moments (shaft
    fixed at ``alpha``, flapping held), then :func:`identify_inflow` runs with
    :class:`SingleRotorForward`: one sweep per swashplate control, joint
    input-output lambda/C, fit, automatic reduction (M diagonal protected), doublet
    verification beside the noise floor.

    Beside the data-driven starts the fit starts from the linearised Pitt-Peters at
    the condition (``start="pitt_peters"``), whose nonzero ``Lbar13``, ``Lbar31``
    bring the coupling responses into the cost; the lowest cost wins. The fitted
    responses are ``pairs``: by default :data:`FORWARD_FIT_PAIRS`, the key responses
    without ``lam0/CM``, whose quasi-steady gain in the wake can have a sign no
    stable model of this structure reaches.

    Parameters
    ----------
    config : aircraft.AircraftConfig
        A single-rotor configuration.
    mu : float
        Advance ratio, > 0.
    alpha : float
        Shaft angle of attack [rad] (positive tilts the disk back).
    ct : float
        Trim thrust coefficient.
    pattern : {"eq4_3", "full"}
        Structure pattern (:class:`SingleRotorForward`).
    settings : IdentificationSettings, optional
    name : str, optional
    n_jobs : int
        Wake worker processes.
    cache_dir : str or None
        Wake run cache (see :func:`aircraft.wake.run_sweeps`).
    progress : bool
    start : {"pitt_peters", None}
        Add the linearised Pitt-Peters start (at ``ct``), or only the data-driven ones.
    pairs : sequence of (output, input) or None
        Responses fitted; None: every coherent response the structure can produce
        at the start (with a zero-coupling start, only the on-axis ones).
    reproduce : bool or "if_trusted"
        Also identify on a second, round-off-different wake data set (see
        :func:`identify_inflow`); part of the trust verdict.

    Returns
    -------
    IdentifiedModel

    Raises
    ------
    ValueError
        Bad ``mu``, ``alpha``, ``pattern``, ``start`` or ``pairs``, or a configuration
        with more than one rotor.
    PipelineError
        The wake trim fails.
    """
    from .pipeline import identify_inflow
    if len(config.rotors) != 1:
        raise ValueError(f"identify_forward_flight is for a single rotor, got {len(config.rotors)} rotors")
    if isinstance(mu, bool) or not isinstance(mu, (int, float, np.integer, np.floating)) or not mu > 0:
        raise ValueError(f"forward flight needs an advance ratio mu > 0, got {mu!r} (hover: identify_inflow)")
    if start not in ("pitt_peters", None):
        raise ValueError(f"start must be 'pitt_peters' or None, got {start!r}")
    condition = flight_condition(config, mu, alpha)
    given = None
    if start == "pitt_peters":
        given = pitt_peters_start(*pitt_peters_forward(ct, mu, alpha, float(config.rotors[0].omega)), pattern=pattern)
    structure = SingleRotorForward(pattern=pattern, start=given, pairs=pairs)
    return identify_inflow(config, condition, structure, trim={"ct": float(ct)}, settings=settings,
                           name=name or f"single rotor mu = {mu:g} ({structure.key}, {pattern})", n_jobs=n_jobs,
                           cache_dir=cache_dir, progress=progress, reproduce=reproduce)


def pitt_peters_forward(ct, mu, alpha=0.0, omega=27.0):
    """Linearised Pitt-Peters (Peters & HaQuang mass flow) at thrust ``ct`` and advance ratio ``mu``.

    The nonlinear :class:`aircraft.inflow.PittPeters` is linearised numerically about
    its steady state (so the mass-flow perturbation is included, as in the
    aircraft), and ``M``, ``Lbar`` are recovered with
    :func:`aircraft.inflow.mlbar_from_statespace`.

    Parameters
    ----------
    ct : float
        Thrust coefficient.
    mu : float
        Advance ratio, >= 0.
    alpha : float
        Shaft angle of attack [rad] (positive tilts the disk back: the free stream
        flows up through it, ``mu_z = -mu tan(alpha)``).
    omega : float
        Rotor speed [rad/s] (``M`` is returned per d/dpsi, so it only sets the time scale).

    Returns
    -------
    M, Lbar : ndarray (3, 3)
        Azimuth-time ``M`` [-] and ``Lbar`` [-] of ``M lam' + Lbar lam = dC``.
    """
    from aircraft.inflow import PittPeters, RotorOperatingPoint, mlbar_from_statespace
    op = RotorOperatingPoint(omega=float(omega), mu=float(mu), mu_z=-float(mu) * math.tan(alpha))
    sys = PittPeters().linear(np.array([float(ct), 0.0, 0.0]), (op,))
    return mlbar_from_statespace(sys, float(omega))
