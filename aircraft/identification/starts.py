"""Equation-error starts for the M/Lbar/tau inflow structures.

For ``lambda/C = H(s) = (M s/Omega + Lbar)^-1`` (no delays) the inverted measured
block is linear in the parameters::

    H(j omega)^-1 = Lbar + j (omega/Omega) M

so its imaginary part over a band of frequencies gives ``M`` by linear least squares (the
*equation error*), without the nonlinear CIFER cost and its local optima. The
delays bias the estimate (``H^-1`` carries ``exp(+j omega tau)``), by a few
hundredths here; the CIFER fit started from it removes the bias.

Why this exists: on exact data of a physically sized coaxial 6-state model the
fit from :meth:`Coaxial6State.initial_values` (Pitt-Peters ``M``, zero cross
masses) stops at J_ave ~690 with the collective cross masses of the wrong sign,
and eight scattered starts reach only 643; from :func:`equation_error_start` it
recovers every parameter (``tests/aircraft/identification/test_coaxial_6state_start.py``).

A start of :func:`identify_inflow` through :meth:`Coaxial6State.extra_starts`
(since ``pipeline-4``), offered only when stable. On our default coaxial hover
wake it is unstable (the lower rotor's collective apparent mass comes out
negative, -0.18, a pole at +185 rad/s), so there it is not offered.
"""
from __future__ import annotations

import numpy as np

__all__ = ["equation_error_start", "equation_error_masses"]


def equation_error_masses(lam_over_c, omega, outputs, inputs, fit_range=(1.0, 10.0)):
    """The equation-error apparent-mass matrix of a square measured block.

    Parameters
    ----------
    lam_over_c : flightid.MeasuredResponse
        Measured lambda/C (e.g. from :func:`flightid.joint_input_output`).
    omega : float
        Rotor speed [rad/s] (``M`` multiplies d/dpsi, azimuth time).
    outputs, inputs : list of str
        The square block (inflow states and their loads, in model order).
    fit_range : (float, float)
        Frequencies used [rad/s]; every response frequency inside it.

    Returns
    -------
    numpy.ndarray
        ``M_eff``, shape (n, n): least-squares slope of ``Im(H^-1)`` against
        ``omega/Omega`` (dimensionless, azimuth time).

    Raises
    ------
    ValueError
        Bad ``omega``, a block that is not square, or a fit_range with fewer than two
        response frequencies.
    numpy.linalg.LinAlgError
        The measured block is singular at a frequency of the fit_range.
    """
    if not (np.isfinite(omega) and omega > 0):
        raise ValueError(f"omega must be a positive rotor speed [rad/s], got {omega!r}")
    if len(outputs) != len(inputs):
        raise ValueError(f"the block must be square, got {len(outputs)} outputs and {len(inputs)} inputs")
    oi = [lam_over_c.output_labels.index(o) for o in outputs]
    ii = [lam_over_c.input_labels.index(i) for i in inputs]
    w = np.asarray(lam_over_c.omega, dtype=float)
    sel = np.flatnonzero((w >= fit_range[0]) & (w <= fit_range[1]))
    if sel.size < 2:
        raise ValueError(f"equation-error band {tuple(fit_range)} rad/s holds {sel.size} frequencies of the "
                         f"response ({w.min():.3g}-{w.max():.3g} rad/s); need at least 2")
    h = np.moveaxis(lam_over_c.frdata[np.ix_(oi, ii)][:, :, sel], -1, 0)      # (n_w, n, n)
    try:
        h_inv = np.linalg.inv(h)
    except np.linalg.LinAlgError as err:
        raise np.linalg.LinAlgError("measured lambda/C is singular in the equation-error fit_range") from err
    x = w[sel] / omega
    return np.tensordot(x, h_inv.imag, axes=(0, 0)) / float(x @ x)


def equation_error_start(structure, lam_over_c, omega, fit_range=(1.0, 10.0), n_points=3, coherence_min=None):
    """A start of an M/Lbar/tau structure with ``M`` from the equation error.

    ``Lbar`` and the delays are those of ``structure.initial_values`` (the inverted
    low-frequency lambda/C); every ``M`` parameter is the mean of the
    equation-error masses (:func:`equation_error_masses`) at the entries the
    structure ties it to, with their signs (so the 6-state's 1c rows and our
    frames' cross-rotor sign flips are averaged in correctly).

    Parameters
    ----------
    structure : InflowStructure
        An ``"mltau"`` structure (:class:`SingleRotor3State`, :class:`Coaxial6State`).
    lam_over_c : flightid.MeasuredResponse
    omega : float
        Rotor speed [rad/s].
    fit_range : (float, float)
        Equation-error fit_range [rad/s].
    n_points, coherence_min
        Passed to ``structure.initial_values``.

    Returns
    -------
    dict
        Parameter values. The start may be unstable (check
        ``structure.build(values, omega).is_stable()``): the fit refuses such a start.

    Raises
    ------
    ValueError
        A structure that is not of the M/Lbar/tau form, or a fit_range without data.
    """
    if getattr(structure, "form", None) != "mltau":
        raise ValueError(f"equation_error_start needs an M/Lbar/tau structure, got {structure!r}")
    values = dict(structure.initial_values(lam_over_c, n_points, coherence_min))
    m_eff = equation_error_masses(lam_over_c, omega, structure.outputs, structure.inputs, fit_range)
    # the pattern's references (row, column, name, sign) say where each M parameter sits
    refs = structure.build(values, omega)._patterns["M"].refs
    sums, counts = {}, {}
    for i, j, name, sign in refs:
        sums[name] = sums.get(name, 0.0) + sign * m_eff[i, j]
        counts[name] = counts.get(name, 0) + 1
    values.update({name: float(sums[name] / counts[name]) for name in sums})
    return values
