"""The inflow-structure base class and the low-frequency helpers every structure uses.

An :class:`InflowStructure` knows its signals (swashplate controls swept, load and flap-rate
inputs, inflow outputs), builds the :mod:`flightid` parametric structure
(:class:`flightid.MLTauStructure` / :class:`flightid.FGCStructure`) from initial
values, proposes a data-driven start from measured lambda/C responses, maps a
printed model onto its parameters, and turns fitted values into an
:class:`aircraft.inflow.IdentifiedInflow`.
"""
from __future__ import annotations

import math

import numpy as np

from aircraft.inflow.base import check_rotor_names, flap_rate_names, inflow_names, load_names

__all__ = ["InflowStructure", "low_frequency_gain", "low_frequency_points", "PITT_PETERS_M11",
           "PITT_PETERS_M22"]

PITT_PETERS_M11 = 8.0 / (3.0 * math.pi)          # Pitt-Peters hover apparent mass (azimuth time)
PITT_PETERS_M22 = -16.0 / (45.0 * math.pi)


def low_frequency_points(response, n_points, coherence_min=None, outputs=None, inputs=None):
    """Indices of the ``n_points`` lowest frequencies, or lowest coherent ones.

    With ``coherence_min`` None: the ``n_points`` lowest frequencies. Otherwise a point
    qualifies when every element of the (``outputs`` x ``inputs``) block has coherence
    >= ``coherence_min``. A sweep's lowest points usually do; a multisine's lowest
    harmonics often do not, and a start taken there is noise (the default-wake
    multisine started from its three lowest points, coherence 0.15-0.5 in the cyclic
    cross pairs, and ended at J_ave 1553). Where fewer than ``n_points`` points
    qualify, the ``n_points`` points of highest worst-element coherence in the lower
    half of the band are used instead, so a start always exists.

    Parameters
    ----------
    response : flightid.MeasuredResponse
        Measured response with coherence (frequencies ascending).
    n_points : int
        Number of points wanted (>= 1).
    coherence_min : float or None
        Coherence threshold in [0, 1), or None for the lowest points whatever their
        coherence.
    outputs, inputs : list of str, optional
        The block to check; default every element.

    Returns
    -------
    numpy.ndarray of int
        Ascending frequency indices, ``n_points`` of them (fewer only when the
        response has fewer points).
    """
    if isinstance(n_points, bool) or not isinstance(n_points, (int, np.integer)) or n_points < 1:
        raise ValueError(f"n_points must be an integer >= 1, got {n_points!r}")
    n_omega = response.frdata.shape[-1]
    if coherence_min is None:
        return np.arange(min(n_points, n_omega))
    if not 0.0 <= float(coherence_min) < 1.0:
        raise ValueError(f"coherence_min must lie in [0, 1) or be None, got {coherence_min!r}")
    coh = response.coherence
    if outputs is not None or inputs is not None:
        oi = [response.output_labels.index(o) for o in (outputs or response.output_labels)]
        ii = [response.input_labels.index(i) for i in (inputs or response.input_labels)]
        coh = coh[np.ix_(oi, ii)]
    worst = coh.reshape(-1, coh.shape[-1]).min(axis=0)
    good = np.flatnonzero(worst >= coherence_min)
    if good.size >= n_points:
        return good[:n_points]
    half = max(n_points, worst.size // 2)
    return np.sort(np.argsort(-worst[:half], kind="stable")[:n_points])


def low_frequency_gain(response, n_points, coherence_min=None, outputs=None, inputs=None):
    """Real part of the measured response averaged over its lowest coherent points.

    The quasi-steady gain of a block (``lambda = G0 C`` as s -> 0), from the points of
    :func:`low_frequency_points`; the mean over several of them averages the record's
    low-frequency noise.

    Parameters
    ----------
    response : flightid.MeasuredResponse
        Measured response with coherence.
    n_points : int
        Points averaged.
    coherence_min : float or None
        As for :func:`low_frequency_points` (None: the lowest points).
    outputs, inputs : list of str, optional
        The block; default the whole response.

    Returns
    -------
    numpy.ndarray
        ``G0``, shape (n_outputs, n_inputs) of the block, in the response's units.
    """
    idx = low_frequency_points(response, n_points, coherence_min, outputs, inputs)
    data = response.frdata
    if outputs is not None or inputs is not None:
        oi = [response.output_labels.index(o) for o in (outputs or response.output_labels)]
        ii = [response.input_labels.index(i) for i in (inputs or response.input_labels)]
        data = data[np.ix_(oi, ii)]
    return np.real(data[:, :, idx].mean(axis=2))


def _low_frequency_inverse(lam_over_c, n_points, outputs=None, inputs=None, coherence_min=None):
    """Inverse of :func:`low_frequency_gain`: the quasi-steady Lbar (``lambda = Lbar^-1 C``)."""
    g0 = low_frequency_gain(lam_over_c, n_points, coherence_min, outputs=outputs, inputs=inputs)
    try:
        return np.linalg.inv(g0)
    except np.linalg.LinAlgError as err:
        raise np.linalg.LinAlgError("measured low-frequency lambda/C is singular: "
                                    "no data-driven start") from err


class InflowStructure:
    """Base class of the structures (see the module table).

    Parameters
    ----------
    frame : {"rotor", "printed"}
        Frame of the parameters: ``"rotor"`` (default) or ``"printed"``.
    rotors : sequence of str, optional
        Rotor names of the signals, upper (first) rotor first, as many as the
        structure has rotors (default: the class's, ``("U", "L")`` for the coaxial
        structures); e.g. the aircraft's
        (:func:`~aircraft.inflow.base.config_rotor_names`). Parameter names do
        not change: they number rows and columns.

    Raises
    ------
    ValueError
        An unknown ``frame``; ``rotors`` of the wrong count, repeated, or not
        usable as signal suffixes.

    Attributes
    ----------
    key : str
        Short name (``"single_rotor_3state"``, ...), used in files and hashes.
    rotors : tuple of str
    controls : list of str
        Swashplate controls swept by the pipeline (one sweep each).
    frame : {"rotor", "printed"}
        ``"rotor"``: our per-rotor frames (default); ``"printed"``: the
        dissertation's common frame (for comparisons only).
    """

    key = ""
    rotors = ("",)
    form = "mltau"
    uses_flap_rates = False

    def __init__(self, frame="rotor", *, rotors=None):
        if frame not in ("rotor", "printed"):
            raise ValueError(f"frame must be 'rotor' or 'printed', got {frame!r}")
        self.frame = frame
        if rotors is not None:
            # an instance attribute shadows the class default only when names are given
            self.rotors = check_rotor_names(rotors, len(type(self).rotors))

    def with_rotors(self, rotors):
        """A copy of this structure whose signals carry other rotor names.

        Parameters
        ----------
        rotors : sequence of str
            As many names as :attr:`rotors`, upper first.

        Returns
        -------
        InflowStructure
            Same parameters and matrices; renamed controls, inputs and outputs.

        Raises
        ------
        ValueError
            As for the ``rotors`` argument of the class.

        Examples
        --------
        >>> from aircraft.identification.structures import Coaxial6State
        >>> Coaxial6State().with_rotors(("upper", "lower")).outputs[3]
        'lam0_lower'
        """
        import copy
        new = copy.copy(self)
        new.rotors = check_rotor_names(rotors, len(type(self).rotors))
        return new

    def for_rotors(self, rotors):
        """This structure with an aircraft's rotor names (the pipeline's adaptation).

        Parameters
        ----------
        rotors : sequence of str
            The configuration's rotor names, upper first.

        Returns
        -------
        InflowStructure
            ``self`` when the names are already these; a renamed copy
            (:meth:`with_rotors`) when the structure has its class's default names.

        Raises
        ------
        ValueError
            Names given explicitly to the structure that differ from ``rotors``, or
            ``rotors`` unusable for it (count, repeats).

        Examples
        --------
        >>> from aircraft.identification.structures import Coaxial6State
        >>> Coaxial6State().for_rotors(("A", "B")).rotors
        ('A', 'B')
        """
        names = check_rotor_names(rotors, len(type(self).rotors))
        if names == tuple(self.rotors):
            return self
        if tuple(self.rotors) != tuple(type(self).rotors):
            raise ValueError(f"structure {self.key} has rotors {tuple(self.rotors)}, the configuration {names}")
        return self.with_rotors(names)

    # -- signals ---------------------------------------------------------------
    @property
    def controls(self):
        return [f"{c}{'_' + r if r else ''}" for r in self.rotors for c in ("theta0", "theta1s", "theta1c")]

    @property
    def excitations(self):
        """Controls the pipeline sweeps, one record each: the swashplate controls and,
        for a structure with flap-rate inputs, every rotor's prescribed tip-path-plane
        inputs ``beta1s``, ``beta1c`` (§6.3), so that the block joint input-output
        (Eq. 4.11) has one independent excitation per load and flap-rate input."""
        if not self.uses_flap_rates:
            return list(self.controls)
        return list(self.controls) + [f"{c}{'_' + r if r else ''}" for r in self.rotors
                                      for c in ("beta1s", "beta1c")]

    def staged_plan(self):
        """The :class:`flightid.staging.Stage` plan of the fit (§6.4.3), or None for one fit of
        every parameter (the small structures)."""
        return None

    #: Extra keyword arguments of every :func:`flightid.fit` of this structure.
    fit_options: dict = {}

    def extra_starts(self, lam_over_c, omega):
        """Further data-driven starts the pipeline fits beside :meth:`initial_values`.

        Parameters
        ----------
        lam_over_c : flightid.MeasuredResponse
        omega : float
            Rotor speed [rad/s].

        Returns
        -------
        list of (str, dict)
            ``(label, parameter values)``; none by default.
        """
        return []

    @property
    def loads(self):
        return load_names(self.rotors)

    @property
    def rates(self):
        return flap_rate_names(self.rotors) if self.uses_flap_rates else []

    @property
    def inputs(self):
        """Model inputs: loads, then flap rates (canonical order of :class:`IdentifiedInflow`)."""
        return self.loads + self.rates

    @property
    def outputs(self):
        return inflow_names(self.rotors)

    #: Parameters the automatic reduction never removes: the diagonal apparent
    #: masses (or near-wake poles). Without one a state has no dynamics of its own;
    #: on the coarse coaxial wake removing m22 left the cyclic M with det 5e-5 and
    #: a 7600 1/s pole.
    protected = ()

    def spec(self):
        """What identifies this structure in a settings hash (dict of str)."""
        out = {"key": self.key, "frame": self.frame, "form": self.form, "protected": list(self.protected)}
        if tuple(self.rotors) != tuple(type(self).rotors):   # absent by default: the hashes stay
            out["rotors"] = list(self.rotors)
        return out

    def _rotors_repr(self):
        """``", rotors=(...)"`` when the names are not the class's, else empty."""
        return "" if tuple(self.rotors) == tuple(type(self).rotors) else f", rotors={tuple(self.rotors)!r}"

    def __repr__(self):
        return f"{type(self).__name__}(frame={self.frame!r}{self._rotors_repr()})"

    # -- to implement ----------------------------------------------------------
    def build(self, initial, omega, fixed=()):
        """The :mod:`flightid` structure with ``initial`` values, ``omega`` [rad/s]."""
        raise NotImplementedError

    def initial_values(self, lam_over_c, n_points=3, coherence_min=None):
        """Data-driven start from measured lambda/C (a :class:`flightid.MeasuredResponse`)."""
        raise NotImplementedError

    def published_values(self, model):
        """Parameter values of a printed model (converted to ``self.frame``)."""
        raise NotImplementedError

    def to_inflow(self, values, omega, *, loads_ref=None, inflow_ref=None, pade_order=2, name=None):
        """An :class:`aircraft.inflow.IdentifiedInflow` at parameter ``values``."""
        from aircraft.inflow import IdentifiedInflow
        mats = self.build(values, omega).matrices()
        name = name or f"identified {self.key}"
        if self.form == "mltau":
            return IdentifiedInflow.from_matrices(mats["M"], mats["Lbar"], mats["tau"], omega=omega,
                                                  rotors=self.rotors, time="azimuth", loads_ref=loads_ref,
                                                  inflow_ref=inflow_ref, pade_order=pade_order, name=name)
        c = self.build(values, omega).C
        # FGCStructure with omega: x' = F x + G u in d/dpsi; seconds: Omega F, Omega G
        return IdentifiedInflow.from_fgc(omega * mats["F"], omega * mats["G"], c, rotors=self.rotors,
                                         input_order=self.inputs, loads_ref=loads_ref,
                                         inflow_ref=inflow_ref, name=name, tau=mats.get("tau"),
                                         pade_order=pade_order)


