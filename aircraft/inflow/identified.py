"""Identified (perturbation) inflow models inside the aircraft: :class:`IdentifiedInflow`.

An identified model is a perturbation about the trim it was identified at::

    x' = A x + B (u - u_ref)                     [1/s]
    lambda = lambda_ref + C x                    (D = 0: no algebraic loop with the loads)

with u the loads ``(C_T, C_L, C_M)`` per rotor (followed by the flap rates
``beta1s_dot, beta1c_dot`` [rad/s] per rotor for models with wake distortion).
The reference trim (loads ``u_ref`` and total inflow ``lambda_ref``) travels with the
model. For printed models that give no trim inflow,
:meth:`IdentifiedInflow.from_published` takes the reference inflow from a
momentum-based model's steady state at the model's trim loads (documented there).

Three ways in: a ready :class:`control.StateSpace` with canonical names, the
``M, Lbar, tau`` form of Eqs. 2.11-2.16/2.30 (:meth:`IdentifiedInflow.from_matrices`,
delays by Padé, then a minimal realisation), or the ``F, G, C`` near/far-wake form of
Eqs. 6.2-6.5 (:meth:`IdentifiedInflow.from_fgc`). This module does not depend on
:mod:`flightid`: identified models come in as arrays or python-control objects.
"""
from __future__ import annotations

import control
import numpy as np

from .base import (InflowModel, RotorOperatingPoint, check_rotor_names, flap_rate_names, inflow_names,
                   load_names, rotor_suffix)
from .pitt_peters import InflowError

__all__ = ["IdentifiedInflow", "mltau_statespace"]


def _rotors_of(outputs):
    """Rotor names of inflow outputs ``lam0_<r>, lam1s_<r>, lam1c_<r>, ...`` (``("",)`` for
    ``lam0, lam1s, lam1c``), or None when they are not in that form."""
    if not outputs or len(outputs) % 3:
        return None
    rotors = []
    for k in range(0, len(outputs), 3):
        first = str(outputs[k])
        if first == "lam0":
            r = ""
        elif first.startswith("lam0_"):
            r = first[len("lam0_"):]
        else:
            return None
        rotors.append(r)
    try:
        rotors = check_rotor_names(rotors)
    except ValueError:
        return None
    return rotors if list(outputs) == inflow_names(rotors) else None


def _sysname(name):
    """python-control forbids '.' in system names ("Eq. 5.3" -> "Eq- 5-3")."""
    return str(name).replace(".", "-")


def _pade_ss(tau, order):
    """Padé approximant of exp(-tau s) [tau in s] as a SISO StateSpace."""
    num, den = control.pade(tau, order)
    return control.ss(control.tf(num, den))


#: Delays below this [s] are realised as none: the automatic reduction leaves removed
#: delays at round-off values (1e-36 s), whose Padé poles (-6/tau) would be ~1e36 1/s.
NEGLIGIBLE_DELAY = 1e-6


def mltau_statespace(M, Lbar, tau=None, *, omega, time="azimuth", pade_order=2,
                     inputs=None, outputs=None, name="M/Lbar/tau", delays="rowwise"):
    """Realise ``M lam' + Lbar lam = u(t - tau)`` (row-wise delays, Eq. 2.16) in seconds.

    Parameters
    ----------
    M, Lbar : (n, n) array_like
        Apparent-mass and ``Lbar = [L]^-1`` matrices (dimensionless loads and inflow).
    tau : (n, n) array_like, optional
        Delays [s]. Following Eq. 2.16, output ``i`` responds to input ``j`` delayed
        by ``tau[i, j]``: the transfer matrix is ``H_ij(s) exp(-tau_ij s)`` with
        ``H(s) = (M s + Lbar)^-1``.
    omega : float
        Rotor speed [rad/s].
    time : {"azimuth", "seconds"}
        Whether ``M`` multiplies ``d/dpsi`` (dimensionless, e.g. Eq. 5.3) or ``d/dt``
        (``M/Omega`` [s], e.g. Tables 4.1-4.2 and Eqs. 4.7-4.8).
    pade_order : int
        Order of the Padé approximant of each non-zero delay.
    delays : {"rowwise", "input"}
        ``"rowwise"`` (default): Eq. 2.16, one delay per (output, input) pair as
        above. ``"input"``: Eq. 2.15, input ``j`` delayed by ``tau[j, j]`` before the
        whole system, ``H(s) diag(exp(-tau_jj s))`` (``tau`` must then be
        diagonal). The two agree when ``H`` is diagonal (hover single rotor).

    Returns
    -------
    control.StateSpace
        Minimal realisation, time in seconds, strictly proper (D = 0).
    """
    M = np.atleast_2d(np.asarray(M, float))
    Lbar = np.atleast_2d(np.asarray(Lbar, float))
    n = M.shape[0]
    if M.shape != (n, n) or Lbar.shape != (n, n):
        raise InflowError(f"M and Lbar must be square and alike, got {M.shape} and {Lbar.shape}")
    tau = np.zeros((n, n)) if tau is None else np.asarray(tau, float)
    if tau.shape != (n, n) or np.any(tau < 0) or not np.all(np.isfinite(tau)):
        raise InflowError(f"tau must be a ({n}, {n}) array of non-negative delays [s]")
    tau = np.where(tau < NEGLIGIBLE_DELAY, 0.0, tau)
    if time not in ("azimuth", "seconds"):
        raise InflowError(f"time must be 'azimuth' or 'seconds', got {time!r}")
    if not omega > 0:
        raise InflowError(f"omega must be positive [rad/s], got {omega!r}")
    if abs(np.linalg.det(M)) < 1e-300:
        raise InflowError("M is singular: not a first-order inflow model")
    m_s = M / omega if time == "azimuth" else M      # seconds: (M/Omega) d/dt
    minv = np.linalg.inv(m_s)
    h = control.ss(-minv @ Lbar, minv, np.eye(n), np.zeros((n, n)))
    inputs = inputs or [f"u{j}" for j in range(n)]
    outputs = outputs or [f"y{i}" for i in range(n)]
    if delays not in ("rowwise", "input"):
        raise InflowError(f"delays must be 'rowwise' (Eq. 2.16) or 'input' (Eq. 2.15), got {delays!r}")
    if delays == "input" and np.any(tau - np.diag(np.diag(tau))):
        raise InflowError("delays='input' (Eq. 2.15) needs a diagonal tau; use 'rowwise' (Eq. 2.16)")
    if not np.any(tau > 0):
        sys = h
    elif delays == "input":
        pades = [_pade_ss(tau[j, j], pade_order) if tau[j, j] > 0 else control.ss([], [], [], [[1.0]])
                 for j in range(n)]
        sys = control.minreal(control.series(control.append(*pades), h), tol=1e-9, verbose=False)
    else:
        sys = _pairwise_delays(h, tau, pade_order)
    return control.ss(sys.A, sys.B, sys.C, np.zeros((n, n)), inputs=inputs, outputs=outputs,
                      states=[f"inflow_x{k}" for k in range(sys.nstates)], name=_sysname(name))


def _pairwise_delays(h, tau, pade_order):
    """``H_ij(s) exp(-s tau_ij)`` realised: column by column, ``H[:, j]`` then each
    output through its own Padé delay, outputs summed, then a minimal realisation."""
    n_out, n_in = h.noutputs, h.ninputs
    cols = []
    for j in range(n_in):
        hj = control.ss(h.A, h.B[:, [j]], h.C, h.D[:, [j]])
        delays = [_pade_ss(tau[i, j], pade_order) if tau[i, j] > 0 else control.ss([], [], [], [[1.0]])
                  for i in range(n_out)]
        cols.append(control.series(hj, control.append(*delays)))
    sys = cols[0]
    for c in cols[1:]:
        sys = control.append(sys, c)
    # sum the per-column outputs: y = sum_j y^(j)
    summer = np.hstack([np.eye(n_out)] * n_in)
    sys = control.ss(sys.A, sys.B, summer @ sys.C, summer @ sys.D)
    return control.minreal(sys, tol=1e-9, verbose=False)


def _delayed_columns(h, tau, pade_order):
    """``H_ij(s) exp(-s tau_ij)`` realised without a minimal realisation: the columns
    without delays share one copy of ``h``; each column with a delay gets its own copy
    followed by a Padé delay per delayed output. Every block is stable when ``h`` is,
    so the (non-minimal) realisation is too. ``control.minreal`` on the fully
    duplicated system (12 states x 10 columns, poles from -0.02 to -4700 1/s for our
    wake's 12-state model) returned a spurious unstable pole."""
    n_out, n_in = h.noutputs, h.ninputs
    delayed = [j for j in range(n_in) if np.any(tau[:, j] > 0)]
    plain = [j for j in range(n_in) if j not in delayed]
    blocks, columns = [], []
    if plain:
        blocks.append(control.ss(h.A, h.B[:, plain], h.C, h.D[:, plain]))
        columns += plain
    for j in delayed:
        hj = control.ss(h.A, h.B[:, [j]], h.C, h.D[:, [j]])
        delays = [_pade_ss(tau[i, j], pade_order) if tau[i, j] > 0 else control.ss([], [], [], [[1.0]])
                  for i in range(n_out)]
        blocks.append(control.series(hj, control.append(*delays)))
        columns.append(j)
    sys = blocks[0]
    for b in blocks[1:]:
        sys = control.append(sys, b)
    summer = np.hstack([np.eye(n_out)] * len(blocks))       # y = sum of the blocks' outputs
    order = np.argsort(columns)                              # back to the input order
    return control.ss(sys.A, sys.B[:, order], summer @ sys.C, (summer @ sys.D)[:, order])


class IdentifiedInflow(InflowModel):
    """Wrap an identified inflow model (any order, delays as Padé states).

    Parameters
    ----------
    system : control.StateSpace
        Inputs named with the canonical load names (optionally followed by the
        flap-rate names ``beta1s_dot_U, beta1c_dot_U, …`` [rad/s]), outputs the
        inflow names, time in seconds, strictly proper, stable.
    rotors : tuple of str, optional
        Rotor names, upper first, e.g. ``("U", "L")`` (coaxial) or ``("",)`` (single
        rotor). Default: inferred from the output names ``lam0_<r>, lam1s_<r>,
        lam1c_<r>`` (``("U", "L")`` if they are not recognised, which then raises a
        naming error).
    loads_ref : array_like, optional
        Loads (C_T, C_L, C_M per rotor) at the identification trim (default zeros).
    inflow_ref : array_like, optional
        Total inflow harmonics at that trim (what the blade sees, interference
        included); :meth:`inflow` returns ``inflow_ref + C x``.
    name : str

    Examples
    --------
    Pitt-Peters' linearised hover model in our rotor frame as an identified model
    (``M`` per d/dpsi; momentum theory ``C_T = 2 lam^2`` gives ``Lbar11 = 4 lam``):

    >>> import numpy as np
    >>> lam = np.sqrt(0.0061 / 2)
    >>> M = np.diag([8 / (3 * np.pi), -16 / (45 * np.pi), -16 / (45 * np.pi)])
    >>> inflow = IdentifiedInflow.from_matrices(M, np.diag([4 * lam, -lam, -lam]), omega=27.0, rotors=("",))
    >>> inflow.system.input_labels, inflow.system.output_labels
    (['CT', 'CL', 'CM'], ['lam0', 'lam1s', 'lam1c'])
    """

    def __init__(self, system, rotors=None, loads_ref=None, inflow_ref=None, name="identified"):
        sys = control.ss(system)
        if rotors is None:
            # infer from the output names: ("",) for lam0, lam1s, lam1c; the suffixes
            # of lam0_<r>, lam1s_<r>, lam1c_<r> otherwise; unrecognised: ("U", "L"),
            # which the checks below then report as a naming error
            rotors = _rotors_of(list(sys.output_labels)) or ("U", "L")
        self.rotors = check_rotor_names(rotors, error=InflowError)
        loads = load_names(self.rotors)
        rates = flap_rate_names(self.rotors)
        inputs = list(sys.input_labels)
        if inputs == loads:
            self.uses_flap_rates = False
        elif inputs == loads + rates:
            self.uses_flap_rates = True
        else:
            raise InflowError(f"identified model inputs {inputs} must be {loads} (+ {rates})")
        if list(sys.output_labels) != inflow_names(self.rotors):
            raise InflowError(f"identified model outputs {sys.output_labels} must be {inflow_names(self.rotors)}")
        if np.any(np.abs(np.asarray(sys.D)) > 1e-12):
            # a direct load -> inflow feedthrough would close an algebraic loop with
            # the blade-element loads; identified inflow models are strictly proper
            raise InflowError("identified inflow model has a feedthrough (D != 0): not supported")
        if sys.nstates == 0:
            raise InflowError("identified inflow model has no states")
        if np.max(np.linalg.eigvals(sys.A).real) >= 0:
            raise InflowError(f"the identified inflow model {name!r} is unstable "
                              f"(max Re(pole) = {np.max(np.linalg.eigvals(sys.A).real):.3g} 1/s): "
                              "refusing to use it in the aircraft")
        self.system = sys
        self.name = name
        n = len(self.rotors)
        self.loads_ref = np.zeros(3 * n) if loads_ref is None else np.asarray(loads_ref, float)
        self.inflow_ref = np.zeros(3 * n) if inflow_ref is None else np.asarray(inflow_ref, float)
        if self.loads_ref.shape != (3 * n,) or self.inflow_ref.shape != (3 * n,):
            raise InflowError(f"loads_ref and inflow_ref need {3 * n} entries")

    @property
    def state_names(self):
        return list(self.system.state_labels)

    def _u(self, loads, rates):
        loads = np.asarray(loads, float)
        if loads.shape != self.loads_ref.shape:
            raise InflowError(f"loads must have {self.loads_ref.size} entries {self.load_names}, "
                              f"got shape {loads.shape}")
        du = loads - self.loads_ref
        if self.uses_flap_rates:
            r = np.zeros(2 * len(self.rotors)) if rates is None else np.asarray(rates, float)
            if r.shape != (2 * len(self.rotors),):
                raise InflowError(f"rates must have {2 * len(self.rotors)} entries {self.rate_names}")
            du = np.concatenate([du, r])
        return du

    def _x(self, x):
        x = np.asarray(x, float)
        if x.shape != (self.n_states,):
            raise InflowError(f"x must have {self.n_states} entries {self.state_names}, got shape {x.shape}")
        return x

    def derivatives(self, x, loads, ops, rates=None):
        return self.system.A @ self._x(x) + self.system.B @ self._u(loads, rates)

    def inflow(self, x, loads, ops):
        """``inflow_ref + C x`` (``loads`` unused: D == 0, checked; may be None)."""
        return self.inflow_ref + self.system.C @ self._x(x)

    def steady_state(self, loads, ops):
        """States at equilibrium with ``loads`` (DC gain; flap rates zero)."""
        return -np.linalg.solve(self.system.A, self.system.B @ self._u(loads, None))

    def linear(self, loads, ops):
        sys = control.ss(self.system.A, self.system.B, self.system.C, self.system.D,
                         inputs=self.input_names, outputs=self.output_names, states=self.state_names,
                         name=_sysname(self.name))
        x0 = self.steady_state(loads, ops)
        sys.trim_states = x0
        sys.trim_inputs = np.concatenate([np.asarray(loads, float), np.zeros(len(self.rate_names))])
        sys.trim_outputs = self.inflow(x0, loads, ops)
        return sys

    def with_rotors(self, rotors):
        """The same model with its rotors renamed (same matrices, new signal names).

        Flies a model identified on (or printed for) rotors ``U, L`` on an aircraft
        whose rotors carry other names, in the same order (upper first).

        Parameters
        ----------
        rotors : sequence of str
            New rotor names, as many as :attr:`rotors`, e.g.
            :func:`~aircraft.inflow.base.config_rotor_names` of the aircraft.

        Returns
        -------
        IdentifiedInflow

        Raises
        ------
        InflowError
            Wrong number of names, repeated or unusable names; or a subclass with
            further rotor-named signals (e.g. tilt inputs), which this does not rename.

        Examples
        --------
        >>> import numpy as np
        >>> m = IdentifiedInflow.from_matrices(np.eye(6), 0.1 * np.eye(6), omega=40.0)
        >>> m.with_rotors(("upper", "lower")).system.output_labels[3]
        'lam0_lower'
        """
        if type(self) is not IdentifiedInflow:
            raise InflowError(f"with_rotors renames the signals of an IdentifiedInflow; a {type(self).__name__} "
                              "has further rotor-named signals: rebuild it with the new rotors")
        new = check_rotor_names(rotors, len(self.rotors), error=InflowError)
        old_sfx = [rotor_suffix(r) for r in self.rotors]

        def rename(label):
            for o, n in zip(old_sfx, new):
                if o and label.endswith(o):
                    return label[:-len(o)] + rotor_suffix(n)
            return label
        sys = self.system
        inputs = load_names(new) + (flap_rate_names(new) if self.uses_flap_rates else [])
        renamed = control.ss(sys.A, sys.B, sys.C, sys.D, inputs=inputs, outputs=inflow_names(new),
                             states=[rename(s) for s in sys.state_labels], name=sys.name)
        return IdentifiedInflow(renamed, new, self.loads_ref.copy(), self.inflow_ref.copy(), self.name)

    # -- constructors -----------------------------------------------------------
    @classmethod
    def from_matrices(cls, M, Lbar, tau=None, *, omega, rotors=("U", "L"), time="azimuth", loads_ref=None,
                      inflow_ref=None, pade_order=2, name="identified M/Lbar/tau", delays="rowwise"):
        """From the ``M, Lbar, tau`` form (see :func:`mltau_statespace`), delays by Padé."""
        rotors = tuple(rotors)
        sys = mltau_statespace(M, Lbar, tau, omega=omega, time=time, pade_order=pade_order,
                               inputs=load_names(rotors), outputs=inflow_names(rotors), name=name,
                               delays=delays)
        return cls(sys, rotors, loads_ref, inflow_ref, name)

    @classmethod
    def from_fgc(cls, F, G, C=None, *, rotors=("U", "L"), input_order=None, loads_ref=None,
                 inflow_ref=None, name="identified F/G/C", tau=None, pade_order=2):
        """From the near/far-wake form ``x' = F x + G u``, ``lambda = C x`` (Eqs. 6.2-6.5).

        Parameters
        ----------
        F : (n, n) array_like  [1/s]
        G : (n, m) array_like
        C : (3 * n_rotors, n) array_like, optional
            Default: ``lambda = lambda_N + lambda_F`` with states ordered
            ``(lam0N, lam0F, lam1sN, lam1sF, lam1cN, lam1cF)`` per rotor (Eq. 6.2).
        input_order : list of str, optional
            Names of G's columns, in any order (e.g. Eq. 6.2's
            ``CT_U, CL_U, beta1s_dot_U, CM_U, beta1c_dot_U, …``); they are
            permuted to the canonical order. Default: the canonical load names.
        loads_ref, inflow_ref : array_like, optional
            Trim loads and inflow (see the class).
        name : str
        tau : (3 * n_rotors, m) array_like, optional
            Delay [s] of input column j on inflow output i (columns in ``input_order``):
            ``lambda_i = sum_j [C (sI - F)^-1 G]_ij exp(-s tau_ij) u_j``, realised by
            Padé approximants of ``pade_order``.
        pade_order : int
            Order of each delay's Padé approximant.
        """
        rotors = tuple(rotors)
        F, G = np.asarray(F, float), np.asarray(G, float)
        n = F.shape[0]
        if F.shape != (n, n) or G.shape[0] != n:
            raise InflowError(f"F must be square and G have as many rows, got {F.shape}, {G.shape}")
        if C is None:
            if n != 6 * len(rotors):
                raise InflowError("default C (near + far) needs 6 states per rotor")
            C = np.zeros((3 * len(rotors), n))
            for i in range(3 * len(rotors)):
                C[i, 2 * i] = C[i, 2 * i + 1] = 1.0
            states = [f"{h}{w}{'_' + r if r else ''}" for r in rotors
                      for h in ("lam0", "lam1s", "lam1c") for w in ("N", "F")]
        else:
            C = np.asarray(C, float)
            states = [f"inflow_x{k}" for k in range(n)]
        order = list(input_order) if input_order is not None else load_names(rotors)
        if len(order) != G.shape[1]:
            raise InflowError(f"input_order has {len(order)} names for {G.shape[1]} columns of G")
        canonical = load_names(rotors) + (flap_rate_names(rotors) if len(order) > 3 * len(rotors) else [])
        if sorted(order) != sorted(canonical):
            raise InflowError(f"input_order {order} must be a permutation of {canonical}")
        Gc = G[:, [order.index(c) for c in canonical]]
        sys = control.ss(F, Gc, C, np.zeros((C.shape[0], Gc.shape[1])), inputs=canonical,
                         outputs=inflow_names(rotors), states=states, name=_sysname(name))
        if tau is not None:
            tau = np.asarray(tau, float)
            if tau.shape != (C.shape[0], G.shape[1]) or not np.all(np.isfinite(tau)) or np.any(tau < 0):
                raise InflowError(f"tau must be a ({C.shape[0]}, {G.shape[1]}) array of finite non-negative "
                                  f"delays [s], got shape {tau.shape}")
            tau = np.where(tau < NEGLIGIBLE_DELAY, 0.0, tau[:, [order.index(c) for c in canonical]])
            if np.any(tau > 0):
                sys = _delayed_columns(sys, tau, pade_order)
                sys = control.ss(sys.A, sys.B, sys.C, np.zeros((C.shape[0], Gc.shape[1])), inputs=canonical,
                                 outputs=inflow_names(rotors), states=[f"inflow_x{k}" for k in range(sys.nstates)],
                                 name=_sysname(name))
        return cls(sys, rotors, loads_ref, inflow_ref, name)

    @classmethod
    def from_file(cls, path_or_name, pade_order=None):
        """Load a versioned model file (:mod:`aircraft.inflow.model_files`).

        Parameters
        ----------
        path_or_name : str or Path
            A ``.json`` file, or the name of a model shipped in
            ``aircraft/data/models`` (e.g. ``"uh60_hover_3state"``,
            ``"coaxial_hover_6state"``, ``"published_eq5_3"``; list them with
            :func:`aircraft.identification.shipped_models`).
        pade_order : int, optional
            Padé order of the delays (default: the one stored in the file).

        Returns
        -------
        IdentifiedInflow
            About the file's trim (``loads_ref``, ``inflow_ref``), in our rotor frames.
        """
        from .model_files import load_record
        return cls.from_record(load_record(path_or_name), pade_order=pade_order)

    @classmethod
    def from_record(cls, record, pade_order=None):
        """The model of a :class:`aircraft.inflow.model_files.ModelRecord`, about its trim.

        Parameters
        ----------
        record : ModelRecord
            In ``mltau``, ``fgc`` or ``statespace`` form.
        pade_order : int, optional
            Padé order of the delays (default: the record's).

        Returns
        -------
        IdentifiedInflow

        Examples
        --------
        >>> from aircraft.inflow.model_files import load_record
        >>> IdentifiedInflow.from_record(load_record("uh60_hover_3state")).rotors
        ('',)
        """
        m = record.matrices
        kw = dict(loads_ref=record.loads_ref, inflow_ref=record.inflow_ref, name=record.name)
        if record.form == "mltau":
            return cls.from_matrices(m["M"], m["Lbar"], m["tau"], omega=record.omega, rotors=record.rotors,
                                     time=record.time, pade_order=pade_order or record.pade_order, **kw)
        if record.form == "fgc":
            return cls.from_fgc(m["F"], m["G"], m["C"], rotors=record.rotors, input_order=record.inputs,
                                tau=m.get("tau"), pade_order=pade_order or record.pade_order, **kw)
        sys = control.ss(m["A"], m["B"], m["C"], np.zeros((m["C"].shape[0], m["B"].shape[1])),
                         inputs=record.inputs, outputs=record.outputs)
        return cls(sys, record.rotors, **kw)

    def to_file(self, path, *, omega, description="", provenance=None):
        """Write this model (its state-space matrices and trim) as a versioned model file.

        Identified models from :func:`aircraft.identification.identify_inflow` are
        better saved with :meth:`IdentifiedModel.save`, which also stores their
        structured matrices, cost table and bounds; this writes what an
        :class:`IdentifiedInflow` knows (``A, B, C``, names, trim).

        Parameters
        ----------
        path : str or Path
        omega : float
            Rotor speed [rad/s] the model belongs to.
        description : str
        provenance : dict, optional

        Returns
        -------
        Path
        """
        from .model_files import ModelRecord
        from aircraft.provenance import settings_hash
        mats = {"A": self.system.A, "B": self.system.B, "C": self.system.C}
        rec = ModelRecord(name=self.name, form="statespace", rotors=self.rotors, omega=float(omega),
                          matrices=mats, inputs=self.input_names, outputs=self.output_names,
                          loads_ref=self.loads_ref, inflow_ref=self.inflow_ref, description=description,
                          settings_hash=settings_hash(mats, digits=16), provenance=dict(provenance or {}))
        return rec.save(path)

    @classmethod
    def from_published(cls, model, reference=None, pade_order=2, loads_ref=None):
        """A printed model of :mod:`aircraft.inflow.published` as an aircraft inflow model.

        The dissertation prints no trim inflow for its identified models; the
        reference inflow is the steady state of ``reference`` at the model's trim
        thrusts with zero hub moments, at the model's ``omega`` and advance ratio
        ``condition["mu"]`` (default 0). Default ``reference``:
        :class:`~aircraft.inflow.coaxial.DynamicClimb` for coaxial hover models,
        :class:`~aircraft.inflow.pitt_peters.IsolatedRotors` for coaxial forward
        flight (§2.2.2.2), :class:`~aircraft.inflow.pitt_peters.PittPeters` for a
        single rotor. ``loads_ref`` (C_T, C_L, C_M per rotor) overrides the
        model's trim loads.
        """
        from .coaxial import DynamicClimb
        from .pitt_peters import IsolatedRotors, PittPeters
        rotors = tuple(model.rotors)
        if loads_ref is None:
            cts = [model.condition.get(f"CT_{r}" if r else "CT") for r in rotors]
            if any(c is None for c in cts):
                raise InflowError(f"{model.name}: no trim thrust in its condition {model.condition}; "
                                  "give loads_ref")
            loads_ref = np.concatenate([[c, 0.0, 0.0] for c in cts])
        loads_ref = np.asarray(loads_ref, float)
        if loads_ref.shape != (3 * len(rotors),):
            raise InflowError(f"loads_ref must have {3 * len(rotors)} entries, got shape {loads_ref.shape}")
        mu = float(model.condition.get("mu", 0.0))
        if reference is None:
            if len(rotors) == 1:
                reference = PittPeters(rotors)
            else:
                reference = DynamicClimb() if mu == 0.0 else IsolatedRotors()
        ops = tuple(RotorOperatingPoint(omega=model.omega, mu=mu) for _ in rotors)
        x = reference.steady_state(loads_ref, ops)
        inflow_ref = reference.inflow(x, loads_ref, ops)
        if hasattr(model, "F"):
            return cls.from_fgc(model.F, model.G, model.C, rotors=rotors, input_order=model.input_order,
                                loads_ref=loads_ref, inflow_ref=inflow_ref, name=model.name)
        return cls.from_matrices(model.M, model.Lbar, model.tau, omega=model.omega, rotors=rotors,
                                 time=model.time, loads_ref=loads_ref, inflow_ref=inflow_ref,
                                 pade_order=pade_order, name=model.name)
