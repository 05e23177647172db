"""Parametric model structures with free, fixed and tied parameters.

A structure is written with *pattern matrices*: each entry is a number (fixed)
or a parameter name (free), optionally prefixed by ``-`` (tied with opposite
sign). A name used in several entries ties them together. Example, the
single-rotor hover M/Lbar/tau form (Eq. 2.11 with Eq. 2.15 delays)::

    MLTauStructure(
        M=[["M11", 0, 0], [0, "M22", 0], [0, 0, "M22"]],      # M33 tied to M22
        Lbar=[["L11", 0, 0], [0, "L22", 0], [0, 0, "L22"]],
        tau=[["t1", 0, 0], [0, "t2", 0], [0, 0, "t2"]],
        inputs=["CT", "CL", "CM"], outputs=["lam0", "lam1s", "lam1c"],
        initial={"M11": 0.8, ...}, omega=27.0)

Structures
----------
:class:`MLTauStructure`   ``M x' + Lbar x = u(t - tau)``, ``y = C x`` (Eqs. 2.11-2.16, 3.10)
:class:`FGCStructure`     ``x' = F x + G u(t - tau)``, ``y = C x`` (Eqs. 2.33-2.36, 6.2-6.7)
:class:`GainDelayStructure` ``y_i = sum_j K_ij u_j(t - tau_ij)`` (Eqs. 2.39-2.40)

Time: ``omega=None`` means the derivative is d/dt [1/s]. With ``omega`` (rotor
speed, rad/s) the derivative is d/dpsi (rotor-azimuth time, as in the
dissertation's inflow models): the one conversion ``s_model = s / omega`` is
made in :meth:`ModelStructure._s_model`. Delays are always in seconds.
"""
from __future__ import annotations

import copy
import numbers

import numpy as np
import pandas as pd
import control

from .errors import IdentificationError

__all__ = ["ModelStructure", "MLTauStructure", "FGCStructure", "GainDelayStructure"]


class _Pattern:
    """A matrix of constants and (signed) parameter references."""

    def __init__(self, entries, label):
        arr = np.array(entries, dtype=object)
        if arr.ndim != 2:
            raise IdentificationError(f"pattern {label} must be a 2-D matrix")
        self.shape = arr.shape
        self.label = label
        self.const = np.zeros(arr.shape)
        self.refs = []  # (i, j, name, sign)
        for (i, j), e in np.ndenumerate(arr):
            if isinstance(e, str):
                name = e.strip()
                sign = 1.0
                if name.startswith("-"):
                    sign, name = -1.0, name[1:].strip()
                if not name.isidentifier():
                    raise IdentificationError(f"{label}[{i},{j}]: {e!r} is not a valid parameter name")
                self.refs.append((i, j, name, sign))
            elif isinstance(e, numbers.Real):
                self.const[i, j] = float(e)
            else:
                raise IdentificationError(f"{label}[{i},{j}] must be a number or a parameter name, got {e!r}")

    def names(self):
        return [r[2] for r in self.refs]

    def build(self, values):
        out = self.const.copy()
        for i, j, name, sign in self.refs:
            out[i, j] = sign * values[name]
        return out


class ModelStructure:
    """Base class: parameter bookkeeping, frequency response with exact delays,
    conversion to a python-control StateSpace with Padé delays.

    Subclasses define ``_patterns`` (dict label -> pattern), ``_delay_label``,
    :meth:`_undelayed` (complex response without delays) and :meth:`_abcd`.
    """

    _delay_label = "tau"

    def _init_parameters(self, patterns, inputs, outputs, initial, fixed, omega):
        self._patterns = {k: _Pattern(v, k) for k, v in patterns.items() if v is not None}
        names = []
        for p in self._patterns.values():
            for n in p.names():
                if n not in names:
                    names.append(n)
        self.names = names
        initial = dict(initial or {})
        unknown = set(initial) - set(names)
        if unknown:
            raise IdentificationError(f"initial values given for unknown parameters {sorted(unknown)}")
        missing = [n for n in names if n not in initial]
        if missing:
            raise IdentificationError(f"no initial value for parameters {missing}")
        self.values = {n: float(initial[n]) for n in names}
        fixed = set(fixed or ())
        bad = fixed - set(names)
        if bad:
            raise IdentificationError(f"cannot fix unknown parameters {sorted(bad)}")
        self.fixed = fixed
        self.inputs = list(inputs)
        self.outputs = list(outputs)
        if omega is not None and not omega > 0:
            raise IdentificationError(f"omega must be a positive rotor speed [rad/s], got {omega!r}")
        self.omega = omega
        dl = self._patterns.get(self._delay_label)
        self.delay_names = sorted(set(dl.names())) if dl is not None else []
        for n in self.delay_names:
            if self.values[n] < 0:
                raise IdentificationError(f"delay {n} must be >= 0 s, got {self.values[n]}")

    # -- parameters -----------------------------------------------------------
    @property
    def free_names(self):
        """Names of the parameters a fit adjusts."""
        return [n for n in self.names if n not in self.fixed]

    def copy(self):
        return copy.deepcopy(self)

    def with_values(self, values):
        """Copy with some parameter values replaced."""
        new = self.copy()
        for k, v in dict(values).items():
            if k not in new.values:
                raise KeyError(f"no parameter {k!r}")
            new.values[k] = float(v)
        return new

    def fix(self, names, value=None):
        """Copy with ``names`` fixed (at ``value`` if given, else at their current value).
        Fixing to 0 removes a parameter from the model (§6.4.4)."""
        names = [names] if isinstance(names, str) else list(names)
        new = self.copy()
        for n in names:
            if n not in new.values:
                raise KeyError(f"no parameter {n!r}")
            new.fixed.add(n)
            if value is not None:
                new.values[n] = float(value)
        return new

    def free(self, names):
        """Copy with ``names`` released for fitting."""
        names = [names] if isinstance(names, str) else list(names)
        new = self.copy()
        for n in names:
            if n not in new.values:
                raise KeyError(f"no parameter {n!r}")
            new.fixed.discard(n)
        return new

    def parameter_table(self) -> pd.DataFrame:
        """Name, value and status (free/fixed) of every parameter."""
        return pd.DataFrame({"parameter": self.names,
                             "value": [self.values[n] for n in self.names],
                             "status": ["fixed" if n in self.fixed else "free" for n in self.names]})

    def matrices(self, values=None):
        """Numeric matrices (dict label -> ndarray) at ``values`` (default: current)."""
        vals = self.values if values is None else {**self.values, **values}
        return {k: p.build(vals) for k, p in self._patterns.items()}

    # -- derivatives (the analytic Jacobian of :func:`flightid.fit`) ------------
    def _entry_sensitivities(self, mats, s, i, j):
        """The undelayed response's element (i, j) at the Laplace variables ``s``
        (seconds), (n_w,), and its derivatives with respect to the entries of every
        non-delay pattern, ``{label: (n_w, rows, cols) complex}``. None where a
        structure does not give them."""
        return None

    def _has_sensitivities(self):
        """True when :meth:`_entry_sensitivities` describes this class's response: it is
        defined below every method that shapes the response (a subclass that adds a
        term to ``_undelayed`` without its derivatives falls back to differences)."""
        mro = type(self).__mro__

        def owner(name):
            return next(k for k in mro if name in vars(k))
        sens = owner("_entry_sensitivities")
        if sens is ModelStructure:
            return False
        return all(mro.index(sens) <= mro.index(owner(n))
                   for n in ("_undelayed", "frequency_response", "matrices", "_s_model", "_delays"))

    def _reference_maps(self, free):
        """{label: (rows, cols, P)} of the pattern entries that are free parameters, with
        P (n_refs, n_free) the signed map from entries to parameters (ties add up)."""
        col = {n: k for k, n in enumerate(free)}
        maps = {}
        for label, pat in self._patterns.items():
            refs = [(a, b, col[n], sg) for a, b, n, sg in pat.refs if n in col]
            if not refs:
                continue
            a, b, k, sg = (np.array(v) for v in zip(*refs))
            proj = np.zeros((len(refs), len(free)))
            proj[np.arange(len(refs)), k] = sg
            # untied entries (one per parameter) are scattered, ties summed through proj
            unique = np.unique(k).size == k.size
            maps[label] = (a.astype(int), b.astype(int), proj, k.astype(int), sg.astype(float), unique)
        return maps

    def _pair_derivatives(self, mats, s, i, j, maps):
        """(H_ij, dH_ij/dp) at ``s``: the delayed response (n_w,) and its derivatives
        (n_w, n_free) with respect to the free parameters of ``maps``."""
        u, sens = self._entry_sensitivities(mats, s, i, j)
        e = np.exp(-self._delays(mats)[i, j] * s)
        n_free = next(iter(maps.values()))[2].shape[1] if maps else 0
        dh = np.zeros((s.size, n_free), dtype=complex)
        for label, (a, b, proj, k, sg, unique) in maps.items():
            if label == self._delay_label:
                hit = (a == i) & (b == j)
                if np.any(hit):
                    # d/dtau of exp(-tau s) is -s exp(-tau s)
                    dh += np.outer(-s * u * e, proj[hit].sum(axis=0))
            elif unique:
                dh[:, k] += sens[label][:, a, b] * (sg[None, :] * e[:, None])
            else:
                dh += (sens[label][:, a, b] * e[:, None]) @ proj
        return u * e, dh

    # -- responses ------------------------------------------------------------
    def _s_model(self, s):
        """The single place where azimuth time is converted: d/dpsi = (1/Omega) d/dt."""
        return s if self.omega is None else s / self.omega

    def _delays(self, mats):
        d = mats.get(self._delay_label)
        return np.zeros((len(self.outputs), len(self.inputs))) if d is None else d

    def frequency_response(self, omega, values=None):
        """Complex response (n_outputs, n_inputs, n_freq) at ``omega`` [rad/s], exact delays."""
        omega = np.atleast_1d(np.asarray(omega, dtype=float))
        mats = self.matrices(values)
        s = 1j * omega
        h = self._undelayed(mats, s)
        tau = self._delays(mats)
        return h * np.exp(-tau[:, :, None] * s[None, None, :])

    def to_frd(self, omega, values=None, name=None):
        """The model's response as a named :class:`control.FrequencyResponseData`."""
        return control.FRD(self.frequency_response(omega, values), np.asarray(omega, float),
                           inputs=self.inputs, outputs=self.outputs, name=name)

    def poles(self, values=None):
        """Eigenvalues [1/s] of the undelayed dynamics (empty for static structures)."""
        a, _, _, _ = self._abcd(self.matrices(values))
        return np.linalg.eigvals(a) if a.size else np.zeros(0, dtype=complex)

    def is_stable(self, values=None, margin=0.0):
        p = self.poles(values)
        return bool(np.all(p.real < -margin)) if p.size else True

    def to_statespace(self, values=None, pade_order=None, minimal=True, name=None):
        """python-control StateSpace with named signals, delays absorbed by Padé.

        Parameters
        ----------
        pade_order : int or None
            Order of the Padé approximants (Eq. 2.18); ``None`` chooses 1 for
            delays shorter than 0.05 s and 2 otherwise, as the dissertation does.
        minimal : bool
            Reduce the assembled system to a minimal realisation (Eq. 2.19).
        """
        mats = self.matrices(values)
        a, b, c, d = self._abcd(mats)
        tau = self._delays(mats)
        base = control.ss(a, b, c, d) if a.size else control.ss([], [], [], d)
        n_out, n_in = tau.shape
        if not np.any(tau >= 1e-6):
            sys = base
        else:
            rows = []
            for i in range(n_out):
                # row-wise delays (Eq. 2.16): output i sees input j delayed by tau_ij
                delays = [self._pade(tau[i, j], pade_order) for j in range(n_in)]
                delay_block = control.append(*delays) if n_in > 1 else delays[0]
                row = base[i, :] * delay_block
                rows.append(row)
            sys = rows[0]
            for r in rows[1:]:
                sys = control.append(sys, r)
            # append stacked inputs n_in times; sum them back onto the shared inputs
            stack = np.vstack([np.eye(n_in)] * n_out)
            sys = sys * control.ss([], [], [], stack)
            if minimal:
                sys = control.minreal(sys, tol=1e-9, verbose=False)
        n_states = sys.nstates
        states = self._state_names(a.shape[0]) if n_states == a.shape[0] else [f"x{k}" for k in range(n_states)]
        return control.ss(sys.A, sys.B, sys.C, sys.D, inputs=self.inputs, outputs=self.outputs,
                          states=states, name=name or type(self).__name__)

    def _state_names(self, n):
        return [f"x{k}" for k in range(n)]

    @staticmethod
    def _pade(tau, order):
        # below a microsecond a delay is numerically zero: its Padé pole (2/tau)
        # would be ~1e6 rad/s or more and only make the realisation stiff
        if tau < 1e-6:
            return control.ss([], [], [], [[1.0]])
        n = order if order is not None else (1 if tau < 0.05 else 2)
        num, den = control.pade(tau, n)
        return control.ss(control.tf(num, den))


class MLTauStructure(ModelStructure):
    """``M x' + Lbar x = u(t - tau)`` (row-wise delays, Eq. 2.16), ``y = C x``.

    Parameters
    ----------
    M, Lbar : pattern matrices (n_states x n_states)
        Apparent-mass and inverse-gain matrices (``Lbar = [L]^-1`` of the
        dissertation's notation).
    tau : pattern matrix (n_states x n_inputs), optional
        Delays [s]; entry (i, j) delays input j in the equation solved for state i.
        With ``C`` not the identity the delays are applied per *output* row.
    C : array_like (n_outputs x n_states), optional
        Output matrix (identity by default; fixed, not identified).
    inputs, outputs : list of str
    initial : dict
        Initial value of every parameter.
    fixed : iterable of str
        Parameters held at their value.
    omega : float, optional
        Rotor speed [rad/s]: if given, ``x'`` is d/dpsi (azimuth time).
    states : list of str, optional
    """

    def __init__(self, M, Lbar, tau=None, *, inputs, outputs, initial, fixed=(), C=None,
                 omega=None, states=None):
        self._init_parameters({"M": M, "Lbar": Lbar, "tau": tau}, inputs, outputs, initial, fixed, omega)
        n = self._patterns["M"].shape[0]
        if self._patterns["M"].shape != (n, n) or self._patterns["Lbar"].shape != (n, n):
            raise IdentificationError("M and Lbar must be square and of the same size")
        if n != len(self.inputs):
            raise IdentificationError(f"M/Lbar form needs as many inputs as states ({n}), got {len(self.inputs)}")
        self.C = np.eye(n) if C is None else np.asarray(C, dtype=float)
        if self.C.shape != (len(self.outputs), n):
            raise IdentificationError(f"C must be {len(self.outputs)} x {n}, got {self.C.shape}")
        if tau is not None and self._patterns["tau"].shape != (len(self.outputs), len(self.inputs)):
            raise IdentificationError("tau must be n_outputs x n_inputs")
        self.states = list(states) if states is not None else list(self.outputs) if C is None else None

    def _state_names(self, n):
        return self.states if self.states and len(self.states) == n else super()._state_names(n)

    def _undelayed(self, mats, s):
        m, lb = mats["M"], mats["Lbar"]
        sm = self._s_model(s)
        inv = np.linalg.inv(m[None, :, :] * sm[:, None, None] + lb[None, :, :])
        return np.moveaxis(self.C @ inv, 0, -1)

    def _abcd(self, mats):
        m, lb = mats["M"], mats["Lbar"]
        try:
            minv = np.linalg.inv(m)
        except np.linalg.LinAlgError as err:
            raise IdentificationError("M is singular: the model has no state-space form") from err
        scale = 1.0 if self.omega is None else self.omega
        a = -scale * minv @ lb
        b = scale * minv
        return a, b, self.C, np.zeros((len(self.outputs), len(self.inputs)))

    def _entry_sensitivities(self, mats, s, i, j):
        # U = C X^-1 with X = M sm + Lbar: dU = -C X^-1 dX X^-1
        m, lb = mats["M"], mats["Lbar"]
        sm = self._s_model(s)
        row, col = _ml_factors(m, lb, self.C, sm, i, j)
        d_l = -row[:, :, None] * col[:, None, :]
        return row[:, j], {"M": sm[:, None, None] * d_l, "Lbar": d_l}


def _fgc_response(f, g, c, d, sm):
    """C (sm I - F)^-1 G (+ D) at the model-time Laplace variables ``sm``: (n_out, n_in, n_w)."""
    n = f.shape[0]
    # modal form C V diag(1/(s - lambda)) V^-1 G: one eigendecomposition instead
    # of a linear solve per frequency (the fit evaluates this thousands of
    # times). Its rounding error grows with cond(V); near-defective F (cond(V)
    # > 1e6, error > ~1e-10) falls back to the direct solve.
    lam, v = np.linalg.eig(f)
    if np.isfinite(lam).all() and np.linalg.cond(v) < 1e6:
        cv = c @ v
        vg = np.linalg.solve(v, g)
        residues = (cv.T[:, :, None] * vg[:, None, :]).reshape(n, -1)      # (n, o * j)
        res = (1.0 / (sm[:, None] - lam[None, :])) @ residues                # (w, o * j)
        out = np.moveaxis(res.reshape(sm.size, cv.shape[0], g.shape[1]), 0, -1)
    else:
        res = np.linalg.solve(sm[:, None, None] * np.eye(n)[None] - f[None],
                              np.broadcast_to(g, (sm.size,) + g.shape))
        out = np.moveaxis(c @ res, 0, -1)
    return out + d[:, :, None] if d is not None else out



def _fgc_factors(f, g, c, sm, i, j):
    """Row i of C (sm I - F)^-1 and column j of (sm I - F)^-1 G at each ``sm``: (n_w, n) each.
    dU_ij/dF_ab is their product row[a] col[b] (d R = R dF R)."""
    x = sm[:, None, None] * np.eye(f.shape[0])[None] - f[None]
    row = np.linalg.solve(np.swapaxes(x, 1, 2), np.broadcast_to(c[i], (sm.size, c.shape[1]))[..., None])[..., 0]
    col = np.linalg.solve(x, np.broadcast_to(g[:, j], (sm.size, g.shape[0]))[..., None])[..., 0]
    return row, col


def _unit_sensitivity(shape, n_w, i, j):
    out = np.zeros((n_w,) + shape, dtype=complex)
    out[:, i, j] = 1.0
    return out



def _ml_factors(m, lb, c, sm, i, j):
    """Row i of C X^-1 and column j of X^-1, X = M sm + Lbar, at each ``sm``: (n_w, n) each."""
    x = sm[:, None, None] * m[None] + lb[None]
    n_w, n = sm.size, m.shape[0]
    row = np.linalg.solve(np.swapaxes(x, 1, 2), np.broadcast_to(c[i], (n_w, n))[..., None])[..., 0]
    unit = np.zeros(n)
    unit[j] = 1.0
    col = np.linalg.solve(x, np.broadcast_to(unit, (n_w, n))[..., None])[..., 0]
    return row, col


class FGCStructure(ModelStructure):
    """``x' = F x + G u(t - tau)``, ``y = C x`` (Eqs. 2.33-2.36, 6.2-6.7).

    ``F`` (n x n) and ``G`` (n x n_inputs) are pattern matrices; ``C`` is a fixed
    numeric matrix (e.g. the 6 x 12 summing matrix of Eq. 2.32); ``tau``
    (n_outputs x n_inputs) delays input j on output i.  ``omega`` as in
    :class:`MLTauStructure`. ``D`` (n_outputs x n_inputs pattern, optional) adds a
    direct feedthrough ``y = C x + D u(t - tau)``. Flap-rate inputs (Eq. 6.2) are
    just further named inputs (columns of ``G``); ties across axes are names
    shared between entries, with ``-`` for the opposite sign.
    """

    def __init__(self, F, G, C, tau=None, *, inputs, outputs, initial, fixed=(), omega=None,
                 states=None, D=None):
        self._init_parameters({"F": F, "G": G, "tau": tau, "D": D}, inputs, outputs, initial, fixed, omega)
        if D is not None and self._patterns["D"].shape != (len(self.outputs), len(self.inputs)):
            raise IdentificationError(f"D must be {len(self.outputs)} x {len(self.inputs)}")
        n = self._patterns["F"].shape[0]
        if self._patterns["F"].shape != (n, n):
            raise IdentificationError("F must be square")
        if self._patterns["G"].shape != (n, len(self.inputs)):
            raise IdentificationError(f"G must be {n} x {len(self.inputs)}")
        self.C = np.asarray(C, dtype=float)
        if self.C.shape != (len(self.outputs), n):
            raise IdentificationError(f"C must be {len(self.outputs)} x {n}, got {self.C.shape}")
        if tau is not None and self._patterns["tau"].shape != (len(self.outputs), len(self.inputs)):
            raise IdentificationError("tau must be n_outputs x n_inputs")
        self.states = list(states) if states is not None else None

    def _state_names(self, n):
        return self.states if self.states and len(self.states) == n else super()._state_names(n)

    def _undelayed(self, mats, s):
        f, g = mats["F"], mats["G"]
        sm = self._s_model(s)
        return _fgc_response(f, g, self.C, mats.get("D"), sm)

    def _abcd(self, mats):
        scale = 1.0 if self.omega is None else self.omega
        d = mats.get("D", np.zeros((len(self.outputs), len(self.inputs))))
        return scale * mats["F"], scale * mats["G"], self.C, d

    def _entry_sensitivities(self, mats, s, i, j):
        f, g = mats["F"], mats["G"]
        row, col = _fgc_factors(f, g, self.C, self._s_model(s), i, j)
        out = {"F": row[:, :, None] * col[:, None, :], "G": np.zeros((s.size,) + g.shape, dtype=complex)}
        out["G"][:, :, j] = row
        u = row @ g[:, j]
        if "D" in mats:
            out["D"] = _unit_sensitivity(mats["D"].shape, s.size, i, j)
            u = u + mats["D"][i, j]
        return u, out


class GainDelayStructure(ModelStructure):
    """Static output equation ``y_i(t) = sum_j K_ij u_j(t - tau_ij)`` (Eqs. 2.39-2.40).

    Used for off-rotor induced velocity (tail, wing under the hub) as a
    function of the rotor inflow harmonics.
    """

    def __init__(self, K, tau=None, *, inputs, outputs, initial, fixed=()):
        self._init_parameters({"K": K, "tau": tau}, inputs, outputs, initial, fixed, None)
        shape = (len(self.outputs), len(self.inputs))
        if self._patterns["K"].shape != shape:
            raise IdentificationError(f"K must be {shape[0]} x {shape[1]}")
        if tau is not None and self._patterns["tau"].shape != shape:
            raise IdentificationError(f"tau must be {shape[0]} x {shape[1]}")

    def _undelayed(self, mats, s):
        return np.broadcast_to(mats["K"][:, :, None], mats["K"].shape + (s.size,)).astype(complex)

    def _abcd(self, mats):
        return np.zeros((0, 0)), np.zeros((0, len(self.inputs))), np.zeros((len(self.outputs), 0)), mats["K"]

    def _entry_sensitivities(self, mats, s, i, j):
        u = np.full(s.size, mats["K"][i, j], dtype=complex)
        return u, {"K": _unit_sensitivity(mats["K"].shape, s.size, i, j)}
